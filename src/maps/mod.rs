//! Transformation space mapping (paper §5): from a candidate's sample correspondences to a dense
//! vertex map, its region, a per-vertex confidence and a functional map `C`.
//!
//! **Distance-profile matching.** An intrinsic symmetry `T` preserves distances, so for anchors
//! `a_i → b_i = T(a_i)` every vertex satisfies `d(v, a_i) = d(T v, b_i)`. The image of `v` is
//! the vertex whose biharmonic distance profile to the targets best matches `v`'s profile to the
//! sources, over the `K` anchors nearest to `v` (`A_v`, default 16):
//! $$T(v) = \arg\min_w \frac1{K}\sum_{i \in A_v} \big|d(v, a_i) - d(w, b_i)\big| =: \arg\min_w c_v(w).$$
//! This is the paper's voting criterion turned into a map, and it needs no sign or eigenspace
//! disambiguation (the trap of sign-only functional maps on posed shapes). It runs in two steps:
//!
//! 1. *Anchor refinement*: every sample is matched (coarse search over a strided vertex subset,
//!    then greedy descents on the mesh graph from its best 8 vertices), samples with
//!    `c ≤ accept·diameter` become anchors at vertex precision, and this repeats: a partial
//!    candidate grows to its whole region.
//! 2. *Dense map*: each vertex descends `c_v` on the mesh graph from the images of its nearest
//!    anchor and of already-mapped neighbours.
//!
//! The **region** is `{v : c_v(T v) ≤ accept·diameter and δ_WKS(v, T v) ≤ wks_accept}` (the
//! paper's two criteria, global distances and local geometry): the whole shape for a global symmetry,
//! the symmetric parts for a partial one (`map = −1` elsewhere). **Confidence** is
//! `1 − c_v(T v)/(accept·diameter)` clamped to [0, 1]: how well `T` preserves the distances from
//! `v` to the anchors. The **functional map** (Ovsjanikov et al. 2012) of the pull-back
//! `f ↦ f∘T` in the first `k_f` eigenfunctions is `C_ij = Σ_{v∈region} m_v φ_i(v) φ_j(T v)`,
//! so `Φ(T v) ≈ Φ(v) C`; for a reflection it is near `diag(±1)`.

use faer::Mat;

pub mod congruent;
pub mod geodesic;
pub mod orientation;
pub mod parity;
pub mod proxy;
pub mod spectral_init;
pub mod zoomout;

pub use zoomout::zoomout;

use crate::distance::BiharmonicEmbedding;
use crate::mesh::vec3::{dot, sub};
use crate::mesh::Mesh;
use crate::spectral::Eigenbasis;

/// Parameters of the dense maps ([`profile_map`], [`refine`], [`geodesic::polish`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct MapParams {
    /// A vertex is in the region when its mean distance mismatch is below `accept · diameter`
    /// (default 0.03: the true mirror of a posed animal mismatches by up to 0.025 on bent legs).
    pub accept: f64,
    /// Anchor refinement rounds (default 3).
    pub refine: usize,
    /// Size `k_f` of the reported functional map (default 20).
    pub fmap_size: usize,
    /// Vertices in the coarse search of anchor refinement (default 1000), of which the best 8 are
    /// descended (a single descent from the best of 1000 lost the true mirror of TOSCA's david:
    /// the robust mismatch has narrow basins; 3000 with one descent was 4× slower).
    pub search_vertices: usize,
    /// Each vertex is matched on its distances to this many nearest anchors (default 16): near
    /// anchors pin it precisely, and bending far away (a posed limb) does not disturb it.
    pub local_anchors: usize,
    /// A vertex is in the region only if the WKS distance ([`crate::voting::wks_distance`]) to
    /// its image is below this (default 0.2; mirror pairs of a posed, noisy animal stay below
    /// 0.18 in 99% of vertices, head and tail are 0.18–0.43 apart).
    pub wks_accept: f64,
    /// Maps whose region covers this fraction of the vertices are refined by ZoomOut (default 0.6).
    pub zoomout_fraction: f64,
    /// ZoomOut grows the functional map up to this size (default 100, capped at the eigenpairs
    /// computed; 0 disables ZoomOut). On TOSCA 40 → 60 → 100 gave 88 → 90 → 92–94% acc@0.05.
    pub zoomout_k: usize,
    /// Size `k0` of the block-diagonal functional map fitted to the anchors as a second ZoomOut
    /// start (default 12; 0 disables it).
    pub spectral_start: usize,
    /// ZoomOut step in eigenfunctions per iteration (default 5).
    pub zoomout_step: usize,
    /// A map whose region covers this fraction after refinement is global and defined on
    /// every vertex, with confidence telling where it is reliable (default 0.75: bent limbs push
    /// up to a quarter of a posed shape past the region tolerance; with 0.9 the posed quadruped's
    /// front↔back near-symmetry and TOSCA's posed david stayed "partial" and unmapped there).
    pub global_fraction: f64,
    /// Passes of the geodesic polish ([`geodesic::polish`]) given to every map (default 4; 0
    /// disables it; passes stop at a fixed point or a cycle of two, with the result every pass
    /// would give: [`geodesic::polish_passes`]); each pass ends, on a global map, with
    /// one ZoomOut step at `zoomout_k`. Session 22, all of shared/data, seeds 0–3, mean acc@0.05
    /// best / first: two passes 87.2 / 85.0%, three 87.8 / 85.9, four 87.9 / 86.4 (every
    /// dataset up on both against two), five 88.2 / 86.1, six 88.4 / 86.0 (SHREC'16 first
    /// −2.7 and −3.4 against four: a wrong reflection of kid05 gains more from the extra passes
    /// than its mirror). Time: ×1.12 on TOSCA, ×1.1–1.3 on the 60k KIDS poses against two.
    pub polish: usize,
    /// Further passes of the polish given to each search's strongest symmetries
    /// (`final_polish_maps` of them) once the search has ranked its maps (default 8; the
    /// `polish` passes of every map come first, and with `polish` = 0 there are none of either).
    /// See [`mod@crate::detect`], "Further polish of the strongest symmetries".
    pub final_polish: usize,
    /// How many of the search's strongest global symmetries get the `final_polish` passes
    /// (default 2, polished concurrently). Where the strongest map is wrong, the right one is
    /// often second and imprecise: over all of shared/data at seeds 0, 10, 20, 30 (best / first
    /// acc@0.05, docs/accuracy.md "Session 33") two against one gave all 89.0 / 88.0 → 89.3 /
    /// 88.2% (FAUST 92.9 / 92.7 → 93.0 / 93.0, SHREC'16 71.0 / 65.9 → 71.8 / 66.9, TOSCA
    /// 89.7 / 88.7 → 89.9 / 88.8, KIDS unchanged); three maps gained nothing more (every
    /// dataset within ±0.1 of two).
    pub final_polish_maps: usize,
    /// Further passes of the polish for the strongest global symmetry over all searches, once
    /// their symmetries are pooled (default 8; 0: none; none either with `polish` = 0). See
    /// [`mod@crate::detect`], "Further polish of the strongest symmetries": over shared/data at
    /// four seeds, best / first acc@0.05 89.4 / 89.1 → 89.7 / 89.4% (every dataset up), ×1.14
    /// the time on TOSCA; sixteen passes gained nothing more (over all +0.0 / +0.0 at seeds 0
    /// and 10). Not on a hierarchy's coarse mesh ([`crate::hierarchy`]): there they
    /// gained 0.1 point on the 60k KIDS poses for ×1.07–1.18 the time, against issue 17's
    /// budget. Since session 42 these are settling passes ([`geodesic::Pass::Settle`]): over
    /// the same four seeds 89.7 / 89.4 → 90.3 / 90.0% (TOSCA +1.2 / +1.1, SHREC'16 +1.0 /
    /// +1.2).
    pub winner_polish: usize,
    /// Anchor candidates of the polish: voting's samples continued by farthest-point sampling
    /// to this many (default 192, three times voting's), in geodesic distance on the mesh's
    /// edge graph when `polish_geodesic` (the default), else in the biharmonic embedding as
    /// voting's. With biharmonic samples, on posed TOSCA 64 → 128 gave 85.0 → 86.4% mean
    /// acc@0.05 and 192 86.5% (and 192 gained nothing over shared/data in session 22); see
    /// `polish_geodesic` for the geodesic ones.
    pub polish_samples: usize,
    /// Continue the polish's anchors in geodesic distance (default true) rather than in the
    /// biharmonic embedding. The polish matches geodesic distance profiles, and a map slides
    /// along a limb where anchors are sparse; biharmonic distance shrinks the limbs and
    /// extremities (it is a global distance), so its farthest points leave them thinly
    /// anchored, while geodesic farthest points spread evenly over the surface. Over all of
    /// shared/data at seeds 0, 10, 20, 30 (best / first acc@0.05, docs/accuracy.md "Session
    /// 32"): 192 geodesic anchors against 128 biharmonic ones, all 88.5 / 87.5 → 89.0 / 88.0%
    /// (TOSCA 88.6 / 87.9 → 89.7 / 88.7, FAUST 92.6 / 92.6 → 92.9 / 92.7, SHREC'16 70.9 / 65.5
    /// → 71.0 / 65.9, KIDS 95.2 → 95.2); 128 geodesic anchors gained on TOSCA (+1.0 / +0.6)
    /// but lost the KIDS poses 1.8 points (their hands' extremities took a share of the
    /// anchors the body then lacked).
    pub polish_geodesic: bool,
    /// Weight `μ` of the curvature term `μ |h_s(v) − h_s(w)|` in the polish's matching cost
    /// (`h_s` the band-limited mean curvature over its median magnitude,
    /// [`crate::descriptors::curvature`]; the profile term is in units of √area). Default
    /// 0.03; 0 disables it.
    pub curvature_weight: f64,
    /// Heat time `τ` of the curvature's low-pass filter on the unit-area mesh (default 1e-3).
    pub curvature_time: f64,
    /// On a mesh of more than 1.5 times this many vertices, the maps are made
    /// on a proxy of this many vertices and lifted to every vertex ([`proxy`]; default 6000,
    /// 0 disables it).
    pub proxy_vertices: usize,
    /// Passes of the geodesic polish on the mesh itself for each search's strongest map
    /// lifted from a proxy, before the searches' versions are compared ([`proxy`], step 5;
    /// default 4, 0: none).
    pub lift_polish: usize,
    /// The orientation-reversing functional map hypothesis ([`orientation`]).
    pub orientation: orientation::OrientationParams,
    /// Parity variants of each search's strongest map ([`parity`]): the lowest non-constant
    /// eigenfunctions whose sign a variant may flip (default 6; 0: none).
    pub parity_flips: usize,
    /// How many parity variants, the judge's strongest, are read in full and polished
    /// (default 2; 0: none).
    pub parity_variants: usize,
}

impl Default for MapParams {
    fn default() -> Self {
        MapParams { accept: 0.03, refine: 3, fmap_size: 20, search_vertices: 1000, local_anchors: 16, wks_accept: 0.2, zoomout_fraction: 0.6, zoomout_k: 100, spectral_start: 12, zoomout_step: 5, global_fraction: 0.75, polish: 4, final_polish: 8, final_polish_maps: 2, winner_polish: 8, polish_samples: 192, polish_geodesic: true, curvature_weight: 0.03, curvature_time: 1e-3, proxy_vertices: 6000, lift_polish: 4, orientation: Default::default(), parity_flips: 6, parity_variants: 2 }
    }
}

/// A dense symmetry map.
#[derive(Clone, Debug)]
pub struct DenseMap {
    /// `(n,)` image vertex of each vertex, `-1` outside the region.
    pub map: Vec<i64>,
    /// `(n,)` confidence in [0, 1] (0 outside the region).
    pub confidence: Vec<f64>,
    /// `(n,)` mean distance mismatch `c_v(T v)` of the best image (also outside the region).
    pub mismatch: Vec<f64>,
    /// Vertex-level anchors `(source, target)` after refinement.
    pub anchors: Vec<(usize, usize)>,
    /// Number of vertices in the region.
    pub region_size: usize,
    /// Whether the map is global (then defined on every vertex).
    pub global: bool,
    /// Whether ZoomOut refined it.
    pub refined: bool,
    /// `(n,)` best image of every vertex, also outside the region.
    pub image: Vec<usize>,
}

impl DenseMap {
    /// A global map defined by every vertex's image, with full confidence and no anchors (for
    /// starting the refinements from a known map).
    pub fn from_image(image: Vec<usize>) -> DenseMap {
        let n = image.len();
        DenseMap {
            map: image.iter().map(|&w| w as i64).collect(),
            confidence: vec![1.0; n],
            mismatch: vec![0.0; n],
            anchors: Vec::new(),
            region_size: n,
            global: true,
            refined: true,
            image,
        }
    }
}

/// Precomputed geometry shared by every candidate's extraction.
pub struct Context<'a> {
    /// Vertex positions (the lengths of the edge graph's edges).
    pub positions: &'a [[f64; 3]],
    /// Biharmonic embedding.
    pub emb: &'a BiharmonicEmbedding,
    /// CSR adjacency.
    pub adjacency: (Vec<usize>, Vec<u32>),
    /// Per entry of `adjacency`, how much longer the edge is along the surface than its
    /// chord (a hierarchy's coarse mesh: [`crate::hierarchy::Hierarchy::stretch`]); `None`:
    /// edges as long as their chords. The polish's geodesics run on these lengths.
    pub stretch: Option<&'a [f64]>,
    /// Biharmonic diameter.
    pub diameter: f64,
    /// Strided vertex subset for coarse searches.
    pub search: Vec<usize>,
    /// `(n · E)` row-major wave kernel signatures.
    pub wks: Vec<f64>,
    /// Number of energies `E`.
    pub energies: usize,
    /// The eigenbasis, for ZoomOut refinement (`None` disables it).
    pub basis: Option<&'a Eigenbasis>,
    /// The judge on this graph ([`crate::judge`]) with the probe vertices distortion is
    /// measured on and the largest distortion accepted; `None` ranks global maps by complexity.
    pub judge: Option<(crate::judge::Judge, Vec<usize>, f64)>,
    /// The band-limited mean curvature of each vertex ([`crate::descriptors::curvature`]) for
    /// the polish's curvature term; `None` disables the term.
    pub curvature: Option<Vec<f64>>,
    /// ZoomOut's data on `basis` up to `zoom_size` eigenfunctions, built on first use.
    zoom: std::sync::OnceLock<zoomout::ZoomBasis>,
    /// Every vertex's profile among the samples (the anchors of every refined map's own
    /// judgement), built on first use.
    samples: std::sync::OnceLock<(Vec<usize>, Profiles)>,
    zoom_size: usize,
}

impl<'a> Context<'a> {
    /// Builds the shared context.
    pub fn new(mesh: &'a Mesh, emb: &'a BiharmonicEmbedding, wks: &Mat<f64>, diameter: f64, params: &MapParams) -> Self {
        Self::on_graph(&mesh.vertices, mesh.adjacency(), emb, wks, diameter, params)
    }

    /// The context of a vertex graph (a mesh's, or a [`proxy::Proxy`]'s): positions, CSR
    /// adjacency, and the embedding and signatures of its vertices.
    pub fn on_graph(
        positions: &'a [[f64; 3]],
        adjacency: (Vec<usize>, Vec<u32>),
        emb: &'a BiharmonicEmbedding,
        wks: &Mat<f64>,
        diameter: f64,
        params: &MapParams,
    ) -> Self {
        let energies = wks.ncols();
        let rows = row_major(wks.as_ref(), energies);
        Context { positions, emb, adjacency, stretch: None, diameter, search: search_subset(positions.len(), params), wks: rows, energies, basis: None, judge: None, curvature: None, zoom: Default::default(), samples: Default::default(), zoom_size: params.zoomout_k }
    }

    /// `μ |h_s(v) − h_s(w)|`, the polish's curvature term for `v ↦ w` (0 without curvature).
    pub(crate) fn curvature_cost(&self, v: usize, w: usize, weight: f64) -> f64 {
        match &self.curvature {
            Some(h) if weight > 0.0 => weight * (h[v] - h[w]).abs(),
            _ => 0.0,
        }
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Every vertex's profile among the anchors `samples` (a refined map's own anchors are the
    /// samples and their images: the sources, hence the profiles, are the same every time).
    /// The first list asked for is kept (the maps stage has one); `None` for another.
    fn sample_profiles(&self, samples: &[usize], params: &MapParams) -> Option<&Profiles> {
        // Serial inside the initialiser: a parallel loop there could take, on a waiting core,
        // another task that waits for this same initialisation (a deadlock).
        let (list, profiles) = self.samples.get_or_init(|| (samples.to_vec(), Profiles::with_threads(self.num_vertices(), &self.emb.from_sources(samples), samples.len(), params.local_anchors, false)));
        (list.as_slice() == samples).then_some(profiles)
    }

    /// ZoomOut's shared data on the basis (up to `zoomout_k` eigenfunctions), `None` without a
    /// basis.
    pub fn zoom(&self) -> Option<&zoomout::ZoomBasis> {
        let basis = self.basis?;
        Some(self.zoom.get_or_init(|| zoomout::ZoomBasis::new(basis, self.zoom_size.max(1))))
    }

    /// The judge's verdict on `map`, when the context has a judge.
    pub fn verdict(&self, map: &[i64]) -> Option<crate::judge::Verdict> {
        let (judge, probes, max_distortion) = self.judge.as_ref()?;
        let distortion = crate::characterize::sample_distortion(map, probes, self.emb, self.diameter);
        Some(judge.judge(map, distortion, *max_distortion))
    }

    /// Whether each of `vertices` lies where `map` is locally the identity: the judge's
    /// stencil nearest to it (in space) has its centre fixed and its orientation kept
    /// ([`crate::judge::Judge::identity_flags`]). All `false` without a judge.
    pub fn in_identity_part(&self, map: &[i64], vertices: &[usize]) -> Vec<bool> {
        let Some((judge, _, _)) = &self.judge else { return vec![false; vertices.len()] };
        let flags = judge.identity_flags(map);
        if !flags.iter().any(|&(_, fixed)| fixed) {
            return vec![false; vertices.len()];
        }
        let p = self.positions;
        let d2 = |a: usize, b: usize| {
            let d = sub(p[a], p[b]);
            dot(d, d)
        };
        vertices.iter().map(|&v| flags.iter().min_by(|x, y| d2(x.0, v).total_cmp(&d2(y.0, v))).is_some_and(|&(_, fixed)| fixed)).collect()
    }

    /// WKS distance between two vertices.
    pub fn wks_distance(&self, a: usize, b: usize) -> f64 {
        let e = self.energies;
        crate::voting::wks_distance(&self.wks[a * e..(a + 1) * e], &self.wks[b * e..(b + 1) * e])
    }

    fn neighbours(&self, v: usize) -> &[u32] {
        &self.adjacency.1[self.adjacency.0[v]..self.adjacency.0[v + 1]]
    }
}

/// Mean absolute mismatch between a source profile `(anchor, distance)` and the target
/// distances at vertex `w`.
fn mismatch(profile: &[(usize, f64)], dst: &Mat<f64>, w: usize) -> f64 {
    let mut s = 0.0;
    for &(i, p) in profile {
        s += (p - dst[(w, i)]).abs();
    }
    s / profile.len() as f64
}

/// Trimmed mismatch: the mean of the smallest `TRIM` fraction of `|d(v,a_i) − d(w,b_i)|`, robust
/// to the wrong correspondences a voting candidate still contains (up to a third of them).
fn robust_mismatch(profile: &[(usize, f64)], dst: &Mat<f64>, w: usize, scratch: &mut Vec<u64>) -> f64 {
    scratch.clear();
    scratch.extend(profile.iter().map(|&(i, p)| (p - dst[(w, i)]).abs().to_bits()));
    trimmed_mean(scratch)
}

/// Fraction of the differences the trimmed mismatch keeps ([`robust_mismatch`]).
const TRIM: f64 = 0.6;

/// Number of the `p` differences the trimmed mismatch keeps.
fn trimmed_count(p: usize) -> usize {
    ((TRIM * p as f64).ceil() as usize).clamp(1, p)
}

/// Mean of the smallest [`trimmed_count`] of non-negative floats given as bit patterns
/// (they order like the floats: the selection is on integers); reorders `bits`.
fn trimmed_mean(bits: &mut [u64]) -> f64 {
    let keep = trimmed_count(bits.len());
    bits.select_nth_unstable(keep - 1);
    bits[..keep].iter().map(|&b| f64::from_bits(b)).sum::<f64>() / keep as f64
}

/// The `k` anchors nearest to a vertex among `candidates`, `(anchor, the vertex's distance to
/// it)` pairs: those pairs in `out`.
fn nearest_profile(candidates: impl IntoIterator<Item = (usize, f64)>, k: usize, out: &mut Vec<(usize, f64)>) {
    out.clear();
    out.extend(candidates);
    if out.len() > k {
        // Distances are non-negative: their bit patterns order like them (and like
        // `total_cmp`, so the selection is the same), compared as integers.
        out.select_nth_unstable_by_key(k - 1, |a| a.1.to_bits());
        out.truncate(k);
    }
}

/// The coarse search's vertices: about `search_vertices` of `n`, evenly strided.
pub(crate) fn search_subset(n: usize, params: &MapParams) -> Vec<usize> {
    let stride = (n / params.search_vertices.max(1)).max(1);
    (0..n).step_by(stride).collect()
}

/// The first `cols` columns of `m` `(n, ≥ cols)` in row-major order (a row's entries
/// contiguous), for the per-vertex distance evaluations of the descents.
pub(crate) fn row_major(m: faer::MatRef<'_, f64>, cols: usize) -> Vec<f64> {
    let n = m.nrows();
    let mut r = vec![0.0; n * cols];
    for i in 0..cols {
        let col = m.col(i);
        for v in 0..n {
            r[v * cols + i] = col[v];
        }
    }
    r
}

/// `‖a − b‖²`, with eight independent partial sums: a single running sum is a chain of
/// dependent additions (4 cycles each), and this is the inner loop of every spectral descent.
/// The partial sums run in explicit SIMD ([`SquaredDistance`]; left to LLVM they stay
/// baseline SSE2), each lane doing what the scalar sum `t` does, so results are the same bits.
#[inline]
pub(crate) fn squared_distance(a: &[f64], b: &[f64]) -> f64 {
    crate::spectral::kernels::dispatch(SquaredDistance { a, b })
}

/// See [`squared_distance`].
struct SquaredDistance<'a> {
    a: &'a [f64],
    b: &'a [f64],
}

impl crate::spectral::kernels::Kernel for SquaredDistance<'_> {
    type Output = f64;
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) -> f64 {
        squared_distance_in(simd, self.a, self.b)
    }
}

/// [`squared_distance`] inside a kernel already dispatched to `simd`: a loop of many
/// distances, like a batch of ZoomOut's descents, dispatches once instead of once per distance
/// (refinement 4% faster at 5k).
#[inline(always)]
pub(crate) fn squared_distance_in<S: pulp::Simd>(simd: S, a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    {
        // Partial sum t is lane t of the accumulators viewed as vectors.
        let (av, _) = S::as_mut_simd_f64s(&mut acc);
        for (x, y) in ca.zip(cb) {
            // Vectors of 1, 2, 4 or 8 lanes split a chunk of 8 exactly.
            let ((xv, xt), (yv, _)) = (S::as_simd_f64s(x), S::as_simd_f64s(y));
            debug_assert!(xt.is_empty());
            for ((a, &x), &y) in av.iter_mut().zip(xv).zip(yv) {
                let d = simd.sub_f64s(x, y);
                *a = simd.add_f64s(*a, simd.mul_f64s(d, d));
            }
        }
    }
    let mut s = ra.iter().zip(rb).map(|(x, y)| (x - y) * (x - y)).sum::<f64>();
    for t in acc {
        s += t;
    }
    s
}

/// Visits every vertex reachable from `roots` (CSR `adjacency`) breadth-first, calling
/// `visit(v, u)` when `u` is first reached, from `v` (the roots themselves are not visited).
pub(crate) fn breadth_first(adjacency: &(Vec<usize>, Vec<u32>), roots: &[usize], mut visit: impl FnMut(usize, usize)) {
    let n = adjacency.0.len() - 1;
    let mut done = vec![false; n];
    let mut queue = std::collections::VecDeque::with_capacity(n);
    for &r in roots {
        if !std::mem::replace(&mut done[r], true) {
            queue.push_back(r);
        }
    }
    while let Some(v) = queue.pop_front() {
        for &u in &adjacency.1[adjacency.0[v]..adjacency.0[v + 1]] {
            let u = u as usize;
            if !std::mem::replace(&mut done[u], true) {
                visit(v, u);
                queue.push_back(u);
            }
        }
    }
}

/// Greedy descent of `cost` on the mesh graph (CSR `adjacency`) from `start`: moves to the best
/// neighbour while it improves. Returns the vertex and its cost.
pub(crate) fn greedy_descent(adjacency: &(Vec<usize>, Vec<u32>), start: usize, mut cost: impl FnMut(usize) -> f64) -> (usize, f64) {
    let c = cost(start);
    greedy_descent_from(adjacency, (start, c), cost)
}

/// [`greedy_descent`] from a start whose cost `cost(start.0) = start.1` is known already.
pub(crate) fn greedy_descent_from(adjacency: &(Vec<usize>, Vec<u32>), start: (usize, f64), mut cost: impl FnMut(usize) -> f64) -> (usize, f64) {
    let (mut w, mut c) = start;
    loop {
        let mut best = (w, c);
        for &u in &adjacency.1[adjacency.0[w]..adjacency.0[w + 1]] {
            let cu = cost(u as usize);
            if cu < best.1 {
                best = (u as usize, cu);
            }
        }
        if best.0 == w {
            return (w, c);
        }
        (w, c) = best;
    }
}

/// [`greedy_descent`] on `ctx`'s mesh graph from a start of known cost.
fn descend_from(ctx: &Context<'_>, start: (usize, f64), cost: impl FnMut(usize) -> f64) -> (usize, f64) {
    greedy_descent_from(&ctx.adjacency, start, cost)
}

/// Descents started from the [`STARTS`] best vertices of the coarse subset `ctx.search`; the
/// best end and its cost (a local minimum: descending from it again stays there). Several
/// starts keep narrow basins (the robust mismatch has them) reachable from a sparse subset.
fn multi_start(ctx: &Context<'_>, mut cost: impl FnMut(usize) -> f64) -> (usize, f64) {
    let mut scored: Vec<(f64, usize)> = ctx.search.iter().map(|&w| (cost(w), w)).collect();
    let keep = STARTS.min(scored.len());
    if keep == 0 {
        return (0, cost(0));
    }
    scored.select_nth_unstable_by(keep - 1, |a, b| a.0.total_cmp(&b.0));
    scored[..keep]
        .iter()
        .map(|&(c, w)| descend_from(ctx, (w, c), &mut cost))
        .fold((0, f64::INFINITY), |b, c| if c.1 < b.1 { c } else { b })
}

/// Descents per coarse search ([`multi_start`]).
const STARTS: usize = 8;

/// The target distances of the coarse subset `ctx.search`, row-major (`rows[r·p + i] =
/// dst(search[r], i)`, a vertex's `p` distances contiguous), for [`robust_multi_start`].
fn search_rows(ctx: &Context<'_>, dst: &Mat<f64>) -> Vec<f64> {
    let p = dst.ncols();
    ctx.search.iter().flat_map(|&w| (0..p).map(move |i| dst[(w, i)])).collect()
}

/// [`multi_start`] of the trimmed mismatch ([`robust_mismatch`]) of `profile` (the
/// anchors `0..p` in order, as the first round of anchor refinement has them), with the same
/// result: `rows` holds the target distances of the coarse subset row-major (`rows[r·p + i]
/// = d(search[r], b_i)`, contiguous), and a vertex is only ranked exactly when a lower bound
/// of its mismatch does not already exclude it from the best [`STARTS`].
///
/// The bound: the sum `S` of the smallest `q` of `p` differences `x_i ≥ 0` is the maximum
/// over `t` of the concave `Σ_i min(x_i, t) − (p − q)·t` (attained at the `q`-th smallest),
/// so every `t` bounds it from below, without a selection; `t = 2τ` and `4τ` (`τ` the current
/// `STARTS`-th best mismatch) exclude nearly every vertex of the coarse subset. The selection
/// this skips was the largest single cost of anchor refinement.
fn robust_multi_start(ctx: &Context<'_>, profile: &[(usize, f64)], rows: &[f64], scratch: &mut Vec<u64>, mut cost: impl FnMut(usize) -> f64) -> (usize, f64) {
    let p = profile.len();
    debug_assert!(profile.iter().enumerate().all(|(i, a)| a.0 == i) && rows.len() == ctx.search.len() * p);
    if p == 0 || ctx.search.is_empty() {
        return (0, cost(0));
    }
    let source: Vec<f64> = profile.iter().map(|a| a.1).collect();
    let mut best = Vec::with_capacity(STARTS + 1);
    crate::spectral::kernels::dispatch(RobustScan { source: &source, rows, search: &ctx.search, best: &mut best, scratch });
    // The scan's mismatch is the cost's own (the same differences, the same trimmed mean).
    best.iter().map(|&(c, w)| descend_from(ctx, (w, c), &mut cost)).fold((0, f64::INFINITY), |b, c| if c.1 < b.1 { c } else { b })
}

/// The scan of [`robust_multi_start`]: the best [`STARTS`] `(mismatch, vertex)` of the coarse
/// subset into `best`, in increasing order. The bound's sums run in explicit SIMD (eight
/// partial sums: their rounding only moves the bound, which has a margin); the exact mismatch
/// is [`trimmed_mean`] of the same differences as [`robust_mismatch`].
struct RobustScan<'a> {
    source: &'a [f64],
    rows: &'a [f64],
    search: &'a [usize],
    best: &'a mut Vec<(f64, usize)>,
    scratch: &'a mut Vec<u64>,
}

impl crate::spectral::kernels::Kernel for RobustScan<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) {
        let RobustScan { source, rows, search, best, scratch } = self;
        let p = source.len();
        let q = trimmed_count(p);
        let (sv, stail) = (source.chunks_exact(8), source.chunks_exact(8).remainder());
        for (row, &w) in rows.chunks_exact(p).zip(search) {
            if best.len() == STARTS {
                let tau = best[STARTS - 1].0;
                let (t1, t2) = (2.0 * tau, 4.0 * tau);
                let (mut a1, mut a2) = ([0.0f64; 8], [0.0f64; 8]);
                {
                    let (v1, _) = S::as_mut_simd_f64s(&mut a1);
                    let (v2, _) = S::as_mut_simd_f64s(&mut a2);
                    let (t1v, t2v) = (simd.splat_f64s(t1), simd.splat_f64s(t2));
                    for (x, y) in sv.clone().zip(row.chunks_exact(8)) {
                        // Vectors of 1, 2, 4 or 8 lanes split a chunk of 8 exactly.
                        let ((xv, _), (yv, _)) = (S::as_simd_f64s(x), S::as_simd_f64s(y));
                        for (((a1, a2), &x), &y) in v1.iter_mut().zip(v2.iter_mut()).zip(xv).zip(yv) {
                            let d = simd.abs_f64s(simd.sub_f64s(x, y));
                            *a1 = simd.add_f64s(*a1, simd.min_f64s(d, t1v));
                            *a2 = simd.add_f64s(*a2, simd.min_f64s(d, t2v));
                        }
                    }
                }
                let (mut s1, mut s2) = (a1.iter().sum::<f64>(), a2.iter().sum::<f64>());
                for (x, y) in stail.iter().zip(&row[p - stail.len()..]) {
                    let d = (x - y).abs();
                    s1 += d.min(t1);
                    s2 += d.min(t2);
                }
                // `S ≥ q·τ` means a mismatch ≥ τ: not among the best (with a margin for rounding).
                let lower = (s1 - (p - q) as f64 * t1).max(s2 - (p - q) as f64 * t2);
                if lower >= q as f64 * tau * (1.0 + 1e-9) {
                    continue;
                }
            }
            scratch.clear();
            scratch.extend(source.iter().zip(row).map(|(x, y)| (x - y).abs().to_bits()));
            let c = trimmed_mean(scratch);
            if best.len() < STARTS || c < best[STARTS - 1].0 {
                let at = best.partition_point(|b| b.0 <= c);
                best.insert(at, (c, w));
                best.truncate(STARTS);
            }
        }
    }
}

/// Greedy descent of the mismatch on the mesh graph from `start` (a vertex and its mismatch).
fn descend(ctx: &Context<'_>, profile: &[(usize, f64)], dst: &Mat<f64>, start: (usize, f64)) -> (usize, f64) {
    descend_from(ctx, start, |w| mismatch(profile, dst, w))
}

/// Profile-matches a candidate given as vertex-level anchors `(source, target)` (see the module
/// docs); `samples` are the vertices that may become anchors and `initial_tol` the precision of
/// the given anchors (voting's ε): refinement starts there and halves the tolerance each round
/// down to `accept · diameter`. `None` if fewer than 3 anchors survive.
pub fn profile_map(
    ctx: &Context<'_>,
    anchors: &[(usize, usize)],
    samples: &[usize],
    initial_tol: f64,
    params: &MapParams,
) -> Option<DenseMap> {
    let (anchors, image, profiles) = profile_images(ctx, anchors, samples, initial_tol, params)?;
    Some(finish(ctx, anchors, image, params, false, Some(&profiles)))
}

/// The hypothesis of a functional map `c` solved from an energy (`Φ(T v) ≈ Φ(v) C`, on the
/// context's basis): its point map (read with the candidates transported by `C`,
/// [`spectral_init::Conversion::Transported`]: such a `C` shrinks weakly pinned directions),
/// judged against its own images of the samples like a refined map, but not yet refined
/// ([`refine`] refines it as it does a profile map). A point map too coarse for [`refine`]
/// (its region under `zoomout_fraction`: read in `K = 30` eigenfunctions, a posed shape's
/// map preserves distances on few vertices) is first refined by ZoomOut from `K` to
/// `zoomout_k`, as pyFM refines its maps, so that the hypothesis competes at all. Always
/// refining it that way instead cost the FAUST and KIDS figures their gain (the map drifts
/// from the mirror when it was refinable already); see docs/accuracy.md, session 14. `None`
/// without a basis.
pub fn from_functional_map(ctx: &Context<'_>, c: &Mat<f64>, samples: &[usize], params: &MapParams) -> Option<DenseMap> {
    let basis = ctx.basis?;
    if c.nrows() > basis.k() {
        return None;
    }
    let image = spectral_init::point_map(basis, &ctx.adjacency, c, &ctx.search, spectral_init::Conversion::Transported);
    let mut m = own_map(ctx, image, samples, params);
    if let (false, Some(zb)) = (refinable(ctx, &m, params), ctx.zoom()) {
        let k1 = params.zoomout_k.min(zb.size());
        if c.nrows() < k1 {
            // The point map read from `c` (the map keeps it as its `image`).
            let mut image = m.image.clone();
            zoomout::zoomout_with(zb, &ctx.adjacency, &mut image, c.nrows(), k1, params.zoomout_step);
            m = own_map(ctx, image, samples, params);
        }
    }
    m.refined = false;
    Some(m)
}

/// Whether a profile map is global enough for [`refine`].
pub fn refinable(ctx: &Context<'_>, m: &DenseMap, params: &MapParams) -> bool {
    ctx.basis.is_some() && params.zoomout_k > 0 && m.region_size as f64 >= params.zoomout_fraction * ctx.num_vertices() as f64
}

/// ZoomOut refinement of a (nearly) global profile map, then a second pass: the refined map's
/// images of the samples become the anchors of a fresh profile match, refined again (ZoomOut
/// fixes anchors the candidate had wrong; on TOSCA's michael this turned a 72% map into a 92%
/// global one). The better of the two (by `quality`) is returned: `refine_second` of
/// `refine_first`; a candidate the first pass cannot refine is returned unrefined.
pub fn refine(ctx: &Context<'_>, m: &DenseMap, samples: &[usize], params: &MapParams) -> DenseMap {
    match refine_first(ctx, m, samples, params) {
        Some(first) => refine_second(ctx, m, first, samples, params),
        None => m.clone(),
    }
}

/// The first pass of [`refine`]: two ZoomOut starts (the profile map, and a low-frequency
/// functional map fitted to the anchors) to a middle size, the better one to `zoomout_k`.
/// `None` (the candidate stays unrefined) when no result stays with the candidate.
fn refine_first(ctx: &Context<'_>, m: &DenseMap, samples: &[usize], params: &MapParams) -> Option<DenseMap> {
    let (Some(basis), Some(zb)) = (ctx.basis, ctx.zoom()) else { return None };
    let own = |image: Vec<usize>| own_map(ctx, image, samples, params);
    let better = |a: &DenseMap, b: &DenseMap| quality(ctx, basis, a, params) < quality(ctx, basis, b, params);
    let stays = |r: &DenseMap| stays_with(ctx, m, r, samples, params);
    // Two starts, both zoomed out to a middle size; the better one (by `quality`) continues.
    let mid = (params.zoomout_k / 3).max(params.spectral_start).min(params.zoomout_k);
    // The first start: the profile map itself.
    let first_start = || {
        let mut image = m.image.clone();
        zoomout::zoomout_with(zb, &ctx.adjacency, &mut image, 10, mid, params.zoomout_step);
        own(image)
    };
    // The second start: the low-frequency functional map fitted to the anchors (robust where a
    // pose distorts distance profiles). The two starts are independent: a thread each.
    let second_start = || {
        let c0 = spectral_init::robust_fit(basis, &m.anchors, params.spectral_start);
        let mut image = spectral_init::point_map(basis, &ctx.adjacency, &c0, &ctx.search, spectral_init::Conversion::Adjoint);
        zoomout::zoomout_with(zb, &ctx.adjacency, &mut image, params.spectral_start, mid, params.zoomout_step);
        own(image)
    };
    let (mut start, other) = if params.spectral_start > 0 {
        let (other, start) = crate::parallel::join(second_start, first_start);
        (start, Some(other))
    } else {
        (first_start(), None)
    };
    if let Some(other) = other {
        if stays(&other) && (better(&other, &start) || !stays(&start)) {
            start = other;
        }
    }
    if !stays(&start) {
        return None;
    }
    let mut image = start.image;
    zoomout::zoomout_with(zb, &ctx.adjacency, &mut image, mid, params.zoomout_k, params.zoomout_step);
    let best = own(image);
    if !stays(&best) {
        return None;
    }
    Some(best)
}

/// The second pass of [`refine`] on the first pass's result `first` for the candidate `m`: a
/// fresh profile match from `first`'s sample images, refined again; the better of the two.
fn refine_second(ctx: &Context<'_>, m: &DenseMap, first: DenseMap, samples: &[usize], params: &MapParams) -> DenseMap {
    let (Some(basis), Some(zb)) = (ctx.basis, ctx.zoom()) else { return first };
    let mut best = first;
    let again: Vec<(usize, usize)> = samples.iter().filter(|&&s| best.map[s] >= 0).map(|&s| (s, best.image[s])).collect();
    if let Some((_, mut image, _)) = profile_images(ctx, &again, samples, params.accept * ctx.diameter * 2.0, params) {
        zoomout::zoomout_with(zb, &ctx.adjacency, &mut image, 10, params.zoomout_k, params.zoomout_step);
        let second = own_map(ctx, image, samples, params);
        if stays_with(ctx, m, &second, samples, params) && quality(ctx, basis, &second, params) < quality(ctx, basis, &best, params) {
            best = second;
        }
    }
    best
}

/// A refined map judged against its own images of the samples (the candidate's anchors may be
/// partly wrong, and would shrink the region of a right map).
fn own_map(ctx: &Context<'_>, image: Vec<usize>, samples: &[usize], params: &MapParams) -> DenseMap {
    let anchors: Vec<(usize, usize)> = samples.iter().map(|&s| (s, image[s])).collect();
    finish(ctx, anchors, image, params, true, ctx.sample_profiles(samples, params))
}

/// Refinement must improve the candidate's map `m`, not replace it by another symmetry (seen
/// on the noisy quadruped: a start drifting from left–right to front–back): a result must agree
/// with the profile map on at least half of the samples.
fn stays_with(ctx: &Context<'_>, m: &DenseMap, r: &DenseMap, samples: &[usize], params: &MapParams) -> bool {
    let agree_tol = 2.0 * params.accept * ctx.diameter;
    let same = samples.iter().filter(|&&s| ctx.emb.dist(m.image[s], r.image[s]) <= agree_tol).count();
    2 * same >= samples.len()
}

/// Lower is better: global maps first, by the judge's score ([`crate::judge`]; without a
/// judge, by the complexity of their functional map); then partial maps by region size.
fn quality(ctx: &Context<'_>, basis: &Eigenbasis, m: &DenseMap, params: &MapParams) -> f64 {
    if m.global {
        match ctx.verdict(&m.map) {
            Some(v) => 1.0 - v.score,
            None => crate::characterize::complexity(&functional_map(basis, &m.map, params.fmap_size), 1.0),
        }
    } else {
        1e6 - m.region_size as f64
    }
}

/// A profile match: refined anchors, every vertex's image, and the vertices' profiles.
type ProfileMatch = (Vec<(usize, usize)>, Vec<usize>, Profiles);

/// Anchor refinement and the dense profile match: refined anchors and every vertex's image.
fn profile_images(
    ctx: &Context<'_>,
    anchors: &[(usize, usize)],
    samples: &[usize],
    initial_tol: f64,
    params: &MapParams,
) -> Option<ProfileMatch> {
    // No anchor, no profile (the trimmed mismatch needs at least one difference).
    if anchors.is_empty() {
        return None;
    }
    let n = ctx.num_vertices();
    let tol = params.accept * ctx.diameter;
    let mut anchors: Vec<(usize, usize)> = anchors.to_vec();
    // Image of every sample from the previous round (also of those not accepted as anchors):
    // later rounds descend from it instead of searching again.
    let mut previous: Vec<Option<usize>> = vec![None; samples.len()];
    for round in 0..params.refine {
        let round_tol = (initial_tol * 0.5f64.powi(round as i32)).max(tol);
        let src: Vec<usize> = anchors.iter().map(|a| a.0).collect();
        let dst_v: Vec<usize> = anchors.iter().map(|a| a.1).collect();
        let dst = ctx.emb.from_sources(&dst_v);
        let sd = ctx.emb.between(samples, &src);
        // The first round's coarse searches read the target distances of the coarse subset,
        // contiguous per vertex (see `robust_multi_start`).
        let search_rows = if round == 0 { search_rows(ctx, &dst) } else { Vec::new() };
        // Each sample's match is independent (on all cores); the anchors are then taken in
        // sample order, each image used once.
        let indices: Vec<usize> = (0..samples.len()).collect();
        let matched: Vec<(usize, f64)> = crate::parallel::map(&indices, |&si| {
            let x = samples[si];
            let (mut profile, mut scratch, mut search_scratch) = (Vec::new(), Vec::new(), Vec::new());
            // The first round matches on all anchors with a trimmed mean (the candidate's pairs
            // are coarse and partly wrong); later rounds on the nearest anchors.
            let robust = round == 0;
            let k = if robust { src.len() } else { params.local_anchors };
            nearest_profile((0..src.len()).map(|i| (i, sd[(si, i)])), k, &mut profile);
            let mut cost = |w: usize| if robust { robust_mismatch(&profile, &dst, w, &mut scratch) } else { mismatch(&profile, &dst, w) };
            // Start: the previous round's image, else the best strided vertex (coarse search),
            // or the candidate's own target if x is an anchor and that fits better.
            let mut start = match previous[si] {
                Some(w) => (w, cost(w)),
                None if robust => robust_multi_start(ctx, &profile, &search_rows, &mut search_scratch, &mut cost),
                None => multi_start(ctx, &mut cost),
            };
            if let Some(&(_, t)) = anchors.iter().find(|a| a.0 == x) {
                let ct = cost(t);
                if ct < start.1 {
                    start = (t, ct);
                }
            }
            descend_from(ctx, start, &mut cost)
        });
        let mut next = Vec::new();
        let mut used = std::collections::HashSet::new();
        for ((si, &x), (w, c)) in samples.iter().enumerate().zip(matched) {
            previous[si] = Some(w);
            if c <= round_tol && ctx.wks_distance(x, w) <= params.wks_accept && used.insert(w) {
                next.push((x, w));
            }
        }
        if next.len() < 3 {
            return None;
        }
        anchors = next;
    }

    // Dense map.
    let src: Vec<usize> = anchors.iter().map(|a| a.0).collect();
    let dst_v: Vec<usize> = anchors.iter().map(|a| a.1).collect();
    let (dsrc, ddst) = crate::parallel::join(|| ctx.emb.from_sources(&src), || ctx.emb.from_sources(&dst_v));
    // Every vertex's profile (its nearest anchors), on all cores; the descents below are
    // sequential (each starts from its mapped neighbours' images).
    let vertex_profiles = Profiles::new(n, &dsrc, src.len(), params.local_anchors);
    let mut best = vec![usize::MAX; n];
    // Breadth-first from the anchor sources so that neighbours' images are good starts.
    let mut queue = std::collections::VecDeque::new();
    let mut seen = vec![false; n];
    for &a in &src {
        if !seen[a] {
            seen[a] = true;
            queue.push_back(a);
        }
    }
    while let Some(v) = queue.pop_front() {
        let profile = vertex_profiles.of(v);
        let nearest = profile.iter().fold(profile[0], |b, &p| if p.1 < b.1 { p } else { b }).0;
        let mut start = dst_v[nearest];
        let mut start_c = mismatch(profile, &ddst, start);
        for &u in ctx.neighbours(v) {
            let b = best[u as usize];
            if b != usize::MAX {
                let c = mismatch(profile, &ddst, b);
                if c < start_c {
                    (start, start_c) = (b, c);
                }
            }
        }
        best[v] = descend(ctx, profile, &ddst, (start, start_c)).0;
        for &u in ctx.neighbours(v) {
            if !seen[u as usize] {
                seen[u as usize] = true;
                queue.push_back(u as usize);
            }
        }
    }
    Some((anchors, best, vertex_profiles.with_targets(ddst)))
}

/// Every vertex's profile, its `k` nearest anchors `(anchor, distance)` (row `v` at
/// `entries[v·k..]`, as [`nearest_profile`] gives them), and the distances from the anchors'
/// targets (`(n, anchors)`, once known): what [`finish`] would compute again for the same
/// anchors.
struct Profiles {
    k: usize,
    entries: Vec<(usize, f64)>,
    targets: Option<Mat<f64>>,
}

impl Profiles {
    /// The profiles of `n` vertices among `anchors` anchors with distances `dsrc` `(n, anchors)`,
    /// on all cores.
    fn new(n: usize, dsrc: &Mat<f64>, anchors: usize, local: usize) -> Profiles {
        Self::with_threads(n, dsrc, anchors, local, true)
    }

    /// [`Profiles::new`], on one thread unless `parallel`.
    fn with_threads(n: usize, dsrc: &Mat<f64>, anchors: usize, local: usize, parallel: bool) -> Profiles {
        let k = local.min(anchors);
        let rows = |range: std::ops::Range<usize>| {
            let mut profile = Vec::new();
            let mut out = Vec::with_capacity(range.len() * k);
            for v in range {
                nearest_profile((0..anchors).map(|i| (i, dsrc[(v, i)])), local, &mut profile);
                debug_assert_eq!(profile.len(), k);
                out.extend_from_slice(&profile);
            }
            out
        };
        let entries = if parallel { crate::parallel::chunks(n, rows).concat() } else { rows(0..n) };
        Profiles { k, entries, targets: None }
    }

    fn with_targets(self, targets: Mat<f64>) -> Profiles {
        Profiles { targets: Some(targets), ..self }
    }

    fn of(&self, v: usize) -> &[(usize, f64)] {
        &self.entries[v * self.k..(v + 1) * self.k]
    }
}

/// Mismatch, region and confidence of `image` under `anchors`. A map whose region covers
/// `global_fraction` of the vertices is global and defined everywhere.
/// `known`: the vertices' profiles among these anchors (and, when known, the distances from
/// their targets), computed already.
fn finish(ctx: &Context<'_>, anchors: Vec<(usize, usize)>, image: Vec<usize>, params: &MapParams, refined: bool, known: Option<&Profiles>) -> DenseMap {
    let n = ctx.num_vertices();
    let tol = params.accept * ctx.diameter;
    let src: Vec<usize> = anchors.iter().map(|a| a.0).collect();
    let dst_v: Vec<usize> = anchors.iter().map(|a| a.1).collect();
    let computed;
    let profiles = match known {
        Some(p) => p,
        None => {
            computed = Profiles::new(n, &ctx.emb.from_sources(&src), src.len(), params.local_anchors);
            &computed
        }
    };
    let fresh;
    let ddst = match &profiles.targets {
        Some(t) => t,
        None => {
            fresh = ctx.emb.from_sources(&dst_v);
            &fresh
        }
    };
    let mismatch_of: Vec<f64> = crate::parallel::chunks(n, |range| range.map(|v| mismatch(profiles.of(v), ddst, image[v])).collect::<Vec<f64>>()).concat();
    let in_region = |v: usize| mismatch_of[v] <= tol && ctx.wks_distance(v, image[v]) <= params.wks_accept;
    let inside: Vec<bool> = (0..n).map(in_region).collect();
    let global = inside.iter().filter(|&&x| x).count() as f64 >= params.global_fraction * n as f64;
    let mut map = vec![-1i64; n];
    let mut confidence = vec![0.0; n];
    let mut region_size = 0;
    for v in 0..n {
        if global || inside[v] {
            map[v] = image[v] as i64;
            confidence[v] = (1.0 - mismatch_of[v] / tol).clamp(0.0, 1.0);
            region_size += 1;
        }
    }
    DenseMap { map, confidence, mismatch: mismatch_of, anchors, region_size, global, refined, image }
}

/// The composition `v ↦ second(first(v))` of two global maps: global, with the smaller of the
/// two confidences and the larger mismatch along the way, and the samples with their images as
/// anchors.
pub fn compose(second: &DenseMap, first: &DenseMap, samples: &[usize]) -> DenseMap {
    let image: Vec<usize> = first.image.iter().map(|&w| second.image[w]).collect();
    let confidence = first.image.iter().zip(&first.confidence).map(|(&w, &c)| c.min(second.confidence[w])).collect();
    let mismatch = first.image.iter().zip(&first.mismatch).map(|(&w, &m)| m.max(second.mismatch[w])).collect();
    DenseMap {
        map: image.iter().map(|&w| w as i64).collect(),
        confidence,
        mismatch,
        anchors: samples.iter().map(|&s| (s, image[s])).collect(),
        region_size: image.len(),
        global: true,
        refined: first.refined && second.refined,
        image,
    }
}

/// `(k_f, k_f)` functional map of the pull-back by `map` over its region:
/// `C_ij = Σ_{v: map[v] ≥ 0} m_v φ_i(v) φ_j(map[v])`.
pub fn functional_map(basis: &Eigenbasis, map: &[i64], k_f: usize) -> Mat<f64> {
    let k_f = k_f.min(basis.k());
    let region: Vec<(usize, usize)> = map.iter().enumerate().filter(|&(_, &t)| t >= 0).map(|(v, &t)| (v, t as usize)).collect();
    // C = (M Φ)ᵀ Φ[T] over the region, one gemm.
    let a = Mat::<f64>::from_fn(region.len(), k_f, |r, i| basis.mass[region[r].0] * basis.evecs[(region[r].0, i)]);
    let b = Mat::<f64>::from_fn(region.len(), k_f, |r, j| basis.evecs[(region[r].1, j)]);
    let mut c = Mat::<f64>::zeros(k_f, k_f);
    faer::linalg::matmul::matmul(c.as_mut(), faer::Accum::Replace, a.transpose(), b.as_ref(), 1.0, faer::Par::Seq);
    c
}

/// The spectral data the maps' tests start from: a mesh's eigenbasis (`k` pairs), biharmonic
/// embedding and WKS (default parameters).
#[cfg(test)]
pub(crate) fn test_spectra(mesh: &Mesh, k: usize) -> (Eigenbasis, BiharmonicEmbedding, Mat<f64>) {
    let basis = Eigenbasis::compute(mesh, &crate::spectral::EigenParams { k, ..Default::default() }).expect("a generated mesh has an eigenbasis");
    let emb = crate::distance::biharmonic(&basis);
    let desc = crate::descriptors::wks(&basis, &crate::descriptors::WksParams::default());
    (basis, emb, desc)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{self, Pose};

    /// The pruned coarse search of the trimmed mismatch ranks exactly as the exhaustive one:
    /// on a posed quadruped, for true mirror anchors with a third of them scrambled (as a
    /// voting candidate's), both return the same vertex for every sample; and the bound is
    /// below the trimmed sum for every `t`, equal to it at the `q`-th smallest difference.
    #[test]
    fn pruned_robust_search_is_the_exhaustive_one() {
        let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
        let (_basis, emb, desc) = test_spectra(&c.mesh, 30);
        let diameter = (0..c.mesh.num_vertices()).step_by(7).map(|v| emb.dist(0, v)).fold(0.0, f64::max);
        let ctx = Context::new(&c.mesh, &emb, &desc, diameter, &MapParams::default());
        let n = c.mesh.num_vertices();
        let samples: Vec<usize> = (0..n).step_by(n / 40).collect();
        let anchors: Vec<(usize, usize)> = samples.iter().enumerate().map(|(i, &s)| (s, if i % 3 == 0 { samples[(i * 7) % samples.len()] } else { c.mirror[s] as usize })).collect();
        let dst_v: Vec<usize> = anchors.iter().map(|a| a.1).collect();
        let src: Vec<usize> = anchors.iter().map(|a| a.0).collect();
        let dst = emb.from_sources(&dst_v);
        let sd = emb.between(&samples, &src);
        let rows = search_rows(&ctx, &dst);
        let (mut scratch, mut scratch2, mut profile) = (Vec::new(), Vec::new(), Vec::new());
        for si in 0..samples.len() {
            nearest_profile((0..src.len()).map(|i| (i, sd[(si, i)])), src.len(), &mut profile);
            let exhaustive = multi_start(&ctx, |w| robust_mismatch(&profile, &dst, w, &mut scratch));
            let pruned = robust_multi_start(&ctx, &profile, &rows, &mut scratch2, |w| robust_mismatch(&profile, &dst, w, &mut scratch));
            assert_eq!(pruned, exhaustive, "sample {si}");
        }
        // The bound is a lower bound of the trimmed mismatch for any t, tight at the q-th value.
        let x = [0.3, 0.1, 0.7, 0.2, 0.9, 0.05];
        let q = trimmed_count(x.len());
        let mut bits: Vec<u64> = x.iter().map(|v: &f64| v.to_bits()).collect();
        let exact = trimmed_mean(&mut bits) * q as f64;
        for t in [0.0, 0.1, 0.25, 0.3, 0.5, 2.0] {
            let bound = x.iter().map(|v: &f64| v.min(t)).sum::<f64>() - (x.len() - q) as f64 * t;
            assert!(bound <= exact + 1e-15, "t = {t}");
        }
        let tight = x.iter().map(|v: &f64| v.min(0.3)).sum::<f64>() - (x.len() - q) as f64 * 0.3;
        assert!((tight - exact).abs() < 1e-15);
    }

    /// A candidate without anchors has no profile map (it used to panic in the trimmed
    /// mismatch, which needs one difference at least).
    #[test]
    fn no_anchors_no_profile_map() {
        let mesh = shapes::icosphere(3);
        let (_basis, emb, desc) = test_spectra(&mesh, 20);
        let ctx = Context::new(&mesh, &emb, &desc, 1.0, &MapParams::default());
        let samples: Vec<usize> = (0..mesh.num_vertices()).step_by(10).collect();
        assert!(profile_map(&ctx, &[], &samples, 0.1, &MapParams::default()).is_none());
    }
}
