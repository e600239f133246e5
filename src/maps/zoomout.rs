//! ZoomOut refinement (Melzi, Ren, Rodolà, Sharma, Wonka & Ovsjanikov 2019) of a self-map.
//!
//! Alternates between the functional map of the pull-back in the first `k` eigenfunctions,
//! $$C_k = \Phi_k^\top M\, \Phi_k \circ T \quad(\Phi_k(Tv) \approx \Phi_k(v)\, C_k),$$
//! and the point map it induces, `T(v) = argmin_w ‖Φ_k(w) − Φ_k(v) C_k‖`, while `k` grows from
//! `k0` to `k1`. Spectral upsampling turns an approximately right map into a smooth,
//! vertex-accurate one. The nearest neighbour is found by greedy descent on the mesh graph from
//! the current image (the map moves little per step), so an iteration costs O(n·k) instead of
//! the O(n²·k) of an exhaustive search. On meshes above 2 × [`SUBSAMPLE`] vertices the intermediate
//! iterations estimate `C_k` from, and move, an evenly strided subset of that many vertices only
//! (the functional map is a low-dimensional object); the last iteration maps every vertex,
//! breadth-first from the subset so each vertex starts from its neighbours' images.
//!
//! **Involutions keep their type (beyond the paper and plain ZoomOut).** A reflection or a
//! half-turn `T` is its own inverse, and the functional map of an isometry is orthogonal, so
//! `C² = I` and `C = Cᵀ`. Plain ZoomOut fits `T` alone and lets `C` drift from that (towards
//! the map that fits best locally, ultimately the identity). The geodesic polish's smoothing
//! step ([`smooth_with`]), when its map is an involution ([`is_involution`]), replaces `C` by
//! its involution part: `(C + Cᵀ)/2 = Q Λ Qᵀ`, then every eigenvalue of magnitude ≥ ½ becomes
//! ±1 ([`involution_part`]; with all of them, `Q sign(Λ) Qᵀ` is the nearest orthogonal
//! involution). `T` and `T⁻¹` are fitted together (the bijectivity coupling of Ren et al. 2018,
//! BCICP, for a self-map) and `C² = I` holds on every direction the map matches, at the cost
//! of one `k × k` eigendecomposition. Measured over shared/data (116 shapes, best / first
//! acc@0.05, `bench/compare_eval.py`, session 13, with the order-1 filter of
//! [`mod@crate::detect`]), against plain ZoomOut: TOSCA 83.2 → 84.1 / 83.2 → 84.1, FAUST
//! 87.7 → 88.7 / 87.0 → 87.8, SHREC'16 54.6 → 54.6 / 42.3 → 42.6, KIDS 60k 87.4 → 90.1 /
//! 87.4 → 90.1%. Variants measured the same way (`docs/accuracy.md`): every eigenvalue to ±1
//! (the nearest orthogonal involution) gave 83.2 / 81.5% over all against 82.8 / 80.9%, but a
//! sign taken on an eigenvalue near 0 is a coin toss: the maps of a 642-vertex quadruped changed
//! on 7.5% of the vertices when its coordinates were scaled by 10⁻⁹; also symmetrising
//! `C ← (C + Cᵀ)/2` in every iteration of the refinements' ZoomOuts turned wrong maps into
//! coherent-looking reflections (a generated shape with no symmetry got a global one; thin
//! legs on the hierarchy lost their mirror, 0.9 → 0.72 acc@0.05); projecting in every iteration lowered TOSCA's first by 0.9 point. Session 10's
//! symmetrised smoothing step without the projection and the order-1 filter lowered the first
//! reported symmetry.

use faer::{Accum, Mat, MatRef, Par};

use crate::spectral::Eigenbasis;

/// Vertices used by the intermediate ZoomOut iterations on meshes of more than twice as many
/// (on the 10k-vertex quadrupeds a 5k subset cost about one point of acc@0.05, so meshes of
/// up to 12k vertices are refined whole).
pub const SUBSAMPLE: usize = 6000;

/// What every ZoomOut on one basis shares: Φ row-major (a vertex's coefficients contiguous,
/// for the descents), the vertex subset of the intermediate iterations, and `M Φ` on it
/// (scaled to the whole surface). Built once per maps stage ([`super::Context::zoom`]) instead
/// of once per call (the copies were a third of a single polishing step).
pub struct ZoomBasis {
    /// `(n · stride)` row-major Φ, the first `stride` eigenfunctions.
    rows: Vec<f64>,
    stride: usize,
    /// The subset (all vertices on small meshes).
    sub: Vec<usize>,
    /// `(|sub|, stride)` `scale · m_v Φ(v)`.
    mphi: Mat<f64>,
}

impl ZoomBasis {
    /// The shared data for ZoomOuts up to `kmax` eigenfunctions (capped at the basis size).
    pub fn new(basis: &Eigenbasis, kmax: usize) -> Self {
        let n = basis.num_vertices();
        let stride = kmax.min(basis.k()).max(1);
        let rows = super::row_major(basis.evecs.as_ref(), stride);
        let step = if n > 2 * SUBSAMPLE { n.div_ceil(SUBSAMPLE) } else { 1 };
        let sub: Vec<usize> = (0..n).step_by(step).collect();
        let scale = basis.mass.iter().sum::<f64>() / sub.iter().map(|&v| basis.mass[v]).sum::<f64>();
        let mut mphi = Mat::<f64>::zeros(sub.len(), stride);
        for i in 0..stride {
            let col = basis.evecs.col(i);
            for (r, x) in mphi.col_as_slice_mut(i).iter_mut().enumerate() {
                let v = sub[r];
                *x = scale * basis.mass[v] * col[v];
            }
        }
        ZoomBasis { rows, stride, sub, mphi }
    }

    /// Largest ZoomOut size this serves.
    pub fn size(&self) -> usize {
        self.stride
    }
}

/// Refines `map` (every entry ≥ 0) in place over `k0 < … < k1` eigenfunctions, growing by
/// `max(step, 15%)` per iteration.
pub fn zoomout(basis: &Eigenbasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k0: usize, k1: usize, step: usize) {
    zoomout_with(&ZoomBasis::new(basis, k1), adjacency, map, k0, k1, step)
}

/// [`zoomout`] with the shared data of a basis (`k1` is capped at its size).
pub fn zoomout_with(zb: &ZoomBasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k0: usize, k1: usize, step: usize) {
    zoomout_between(zb, adjacency, zb, adjacency, map, k0, k1, step, Involution::Off)
}

/// One ZoomOut step at `k` eigenfunctions (the spectral smoothing of the geodesic polish): an
/// involution's functional map is replaced by its involution part ([`Involution::Project`]).
pub fn smooth_with(zb: &ZoomBasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k: usize) {
    zoomout_between(zb, adjacency, zb, adjacency, map, k, k, 1, Involution::Project)
}

/// What a self-map's ZoomOut does with the functional map of an involution (a map with
/// `T(T(v))` within two rings of `v` on at least half of the vertices: a reflection, a
/// half-turn). An isometric involution `T` has an orthogonal `C` with `C² = I`, hence `C = Cᵀ`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Involution {
    /// Nothing (a map between two shapes).
    Off,
    /// `C ←` its involution part ([`involution_part`]).
    Project,
}

/// ZoomOut of a map from one shape (`src`: its subset, `M Φ` and graph) to another (`dst`:
/// the nearest neighbours among its vertices, descents on its graph), `Φ_dst(T v) ≈ Φ_src(v)
/// C_k` with `C_k = (M Φ_src,k)ᵀ Φ_dst,k[T]`; the two are one for a self-map. `k1` is capped at
/// the smaller basis.
#[allow(clippy::too_many_arguments)]
pub fn zoomout_between(
    src: &ZoomBasis,
    src_adjacency: &(Vec<usize>, Vec<u32>),
    dst: &ZoomBasis,
    adjacency: &(Vec<usize>, Vec<u32>),
    map: &mut [usize],
    k0: usize,
    k1: usize,
    step: usize,
    involution: Involution,
) {
    let zb = src;
    let n = zb.rows.len() / zb.stride;
    let kmax = k1.min(zb.stride).min(dst.stride);
    let mut k = k0.min(kmax).max(1);
    let (from, stride, sub, mphi) = (&zb.rows, zb.stride, &zb.sub, &zb.mphi);
    let (rows, dst_stride) = (&dst.rows, dst.stride);
    let dist = |w: usize, target: &[f64]| -> f64 { super::squared_distance(&rows[w * dst_stride..w * dst_stride + target.len()], target) };
    // Targets Φ_k(v) C_k of the vertices `vs`, one gemm: column r of `(C_kᵀ Φ_k(vs)ᵀ)` is the
    // target of vs[r], contiguous for the descent. Column v of the row-major Φ read as a
    // `(stride, n)` column-major matrix is Φ(v): all vertices need no copy.
    let all_phi = MatRef::from_column_major_slice_with_stride(from, stride, n, stride);
    let product = |c: &Mat<f64>, phi: MatRef<'_, f64>| -> Mat<f64> {
        let mut t = Mat::<f64>::zeros(c.nrows(), phi.ncols());
        faer::linalg::matmul::matmul(t.as_mut(), Accum::Replace, c.transpose(), phi, 1.0, Par::Seq);
        t
    };
    // The targets of the vertices `range` (no copy), or of the vertices `vs` (gathered).
    let targets_in = |range: std::ops::Range<usize>, c: &Mat<f64>| product(c, all_phi.subrows(0, c.nrows()).subcols(range.start, range.len()));
    let targets_of = |vs: &[usize], c: &Mat<f64>| product(c, Mat::<f64>::from_fn(c.nrows(), vs.len(), |p, r| from[vs[r] * stride + p]).as_ref());
    let whole = sub.len() == n;
    // C is summed over two fixed halves of the subset, one per core (the same sums on one
    // core: the result does not depend on the number of cores); it was a third of a ZoomOut.
    let half = sub.len() / 2;
    let (mut gather_a, mut gather_b) = (vec![0.0; half * kmax], vec![0.0; (sub.len() - half) * kmax]);
    // Decided once, on the starting map (the refinement keeps the type).
    let involution = if involution != Involution::Off && std::ptr::eq(src, dst) && is_involution(adjacency, map, sub) { involution } else { Involution::Off };
    loop {
        // C_k = (M Φ_k)ᵀ Φ_k[T] over the subset; Φ_k[T] gathered a row (one vertex's
        // coefficients, contiguous) at a time.
        let part = |r0: usize, part: &[usize], gather: &mut [f64]| -> Mat<f64> {
            for (r, &v) in part.iter().enumerate() {
                let w = map[v];
                gather[r * k..(r + 1) * k].copy_from_slice(&rows[w * dst_stride..w * dst_stride + k]);
            }
            let phit = MatRef::from_row_major_slice(&gather[..part.len() * k], part.len(), k);
            let mut c = Mat::<f64>::zeros(k, k);
            faer::linalg::matmul::matmul(c.as_mut(), Accum::Replace, mphi.as_ref().subrows(r0, part.len()).subcols(0, k).transpose(), phit, 1.0, Par::Seq);
            c
        };
        let (ca, cb) = crate::parallel::join(|| part(0, &sub[..half], &mut gather_a), || part(half, &sub[half..], &mut gather_b));
        let mut c = ca + cb;
        if involution == Involution::Project {
            c = involution_part(&c);
        }
        // The subset's vertices move independently: a range of them per core, each with its
        // own targets (a column of the product is the same alone or among others).
        let moved = crate::parallel::chunks(sub.len(), |range| {
            let t = if whole { targets_in(range.clone(), &c) } else { targets_of(&sub[range.clone()], &c) };
            let starts: Vec<usize> = range.map(|r| map[sub[r]]).collect();
            crate::spectral::kernels::dispatch(Descents { adjacency, rows, stride: dst_stride, targets: &t, starts: &starts })
        });
        for (&v, w) in sub.iter().zip(moved.into_iter().flatten()) {
            map[v] = w;
        }
        if k >= kmax && sub.len() < n {
            // Last iteration on a large mesh: every other vertex, breadth-first from the subset.
            let t = targets_in(0..n, &c);
            super::breadth_first(src_adjacency, sub, |v, u| {
                let target = t.col_as_slice(u);
                let start = if dist(map[v], target) < dist(map[u], target) { map[v] } else { map[u] };
                map[u] = super::greedy_descent(adjacency, start, |w| dist(w, target)).0;
            });
        }
        if k >= kmax {
            break;
        }
        // Grow by `step` or 15%, whichever is more: the cost per step is O(n·k²).
        k = (k + step).max(k * 23 / 20).min(kmax);
    }
}

/// Greedy descents of the point map, one per column of `targets` (`Φ_k(v) C_k`, `k` its rows)
/// from `starts`, in one SIMD dispatch (see [`super::squared_distance_in`]); the same
/// results as [`super::greedy_descent`] on [`super::squared_distance`].
struct Descents<'a> {
    adjacency: &'a (Vec<usize>, Vec<u32>),
    rows: &'a [f64],
    stride: usize,
    targets: &'a Mat<f64>,
    starts: &'a [usize],
}

impl crate::spectral::kernels::Kernel for Descents<'_> {
    type Output = Vec<usize>;
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) -> Vec<usize> {
        // The descent of `super::greedy_descent` written out: a closure would not be compiled
        // with the kernel's instruction set.
        let (rows, stride) = (self.rows, self.stride);
        let (off, nbr) = (&self.adjacency.0, &self.adjacency.1);
        let k = self.targets.nrows();
        let mut out = Vec::with_capacity(self.starts.len());
        for (i, &start) in self.starts.iter().enumerate() {
            let target = self.targets.col_as_slice(i);
            let mut w = start;
            let mut c = super::squared_distance_in(simd, &rows[w * stride..w * stride + k], target);
            loop {
                let mut best = (w, c);
                for &u in &nbr[off[w]..off[w + 1]] {
                    let u = u as usize;
                    let cu = super::squared_distance_in(simd, &rows[u * stride..u * stride + k], target);
                    if cu < best.1 {
                        best = (u, cu);
                    }
                }
                if best.0 == w {
                    break;
                }
                (w, c) = best;
            }
            out.push(w);
        }
        out
    }
}

/// The involution part of `C`: `Q f(Λ) Qᵀ` for the eigendecomposition `Q Λ Qᵀ` of
/// `(C + Cᵀ)/2`, with `f(λ) = sign(λ)` where `|λ| ≥ ½` and `f(λ) = λ` elsewhere: the
/// directions the map carries onto ± themselves more than half-way become exact (±1), as in
/// the nearest orthogonal involution, and the others are left alone (½ is the midpoint between
/// no correlation and a match; forcing an eigenvalue near 0 to ±1 is a coin toss: with
/// `f = sign` everywhere, the maps of a 642-vertex quadruped changed on 7.5% of the vertices
/// when its coordinates were scaled by 10⁻⁹, `tests/detect.rs`,
/// `units_and_position_do_not_change_the_result`). `C` symmetrised if the eigensolver fails.
pub(crate) fn involution_part(c: &Mat<f64>) -> Mat<f64> {
    let sym = (c + c.transpose()) * 0.5;
    let Ok(evd) = sym.self_adjoint_eigen(faer::Side::Lower) else { return sym };
    let q = evd.U();
    let k = sym.nrows();
    let signs = Mat::<f64>::from_fn(k, k, |i, j| {
        let l = evd.S()[i];
        if i != j {
            0.0
        } else if l.abs() < 0.5 {
            l
        } else {
            l.signum()
        }
    });
    q * signs * q.transpose()
}

/// Whether `map` is (roughly) an involution: on at least half of `sub`, `T(T(v))` is within two
/// rings of `v` (a ZoomOut start is about right: a reflection's or a half-turn's passes
/// easily, a rotation of order ≥ 3 sends `T(T(v))` far).
pub(crate) fn is_involution(adjacency: &(Vec<usize>, Vec<u32>), map: &[usize], sub: &[usize]) -> bool {
    let (off, nbr) = adjacency;
    let near = |a: usize, b: usize| -> bool {
        if a == b {
            return true;
        }
        nbr[off[a]..off[a + 1]].iter().any(|&u| {
            let u = u as usize;
            u == b || nbr[off[u]..off[u + 1]].iter().any(|&x| x as usize == b)
        })
    };
    let back = sub.iter().filter(|&&v| near(v, map[map[v]])).count();
    2 * back >= sub.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// `C = Q Λ Qᵀ + (antisymmetric)`: the antisymmetric part goes, eigenvalues of magnitude
    /// ≥ ½ become ±1, the others stay; an orthogonal involution is left as it is.
    #[test]
    fn the_involution_part_keeps_matched_directions_only() {
        let mut rng = crate::random::SplitMix::new(7);
        let mut rand = || rng.unit() - 0.5;
        let k = 8;
        // Q: a Householder reflection, orthogonal and symmetric.
        let u: Vec<f64> = (0..k).map(|_| rand()).collect();
        let uu: f64 = u.iter().map(|x| x * x).sum();
        let q = Mat::<f64>::from_fn(k, k, |i, j| if i == j { 1.0 } else { 0.0 } - 2.0 * u[i] * u[j] / uu);
        let diag = |d: &[f64]| Mat::<f64>::from_fn(k, k, |i, j| if i == j { d[i] } else { 0.0 });
        let lambda = [0.93, -0.81, 0.62, -0.55, 0.3, -0.2, 0.05, -0.45];
        let want = [1.0, -1.0, 1.0, -1.0, 0.3, -0.2, 0.05, -0.45];
        let skew = Mat::<f64>::from_fn(k, k, |i, j| if i < j { 0.1 * (i + 2 * j) as f64 / k as f64 } else if i > j { -0.1 * (j + 2 * i) as f64 / k as f64 } else { 0.0 });
        let c = &q * diag(&lambda) * q.transpose() + &skew;
        let r = involution_part(&c);
        assert!((&r - &q * diag(&want) * q.transpose()).norm_l2() < 1e-10);
        // An exact involution: a permutation swapping pairs, with signs.
        let eye = Mat::<f64>::identity(12, 12);
        let p = Mat::<f64>::from_fn(12, 12, |i, j| if j == (i ^ 1) { 1.0 } else { 0.0 });
        let s = Mat::<f64>::from_fn(12, 12, |i, j| if i == j { if i % 3 == 0 { -1.0 } else { 1.0 } } else { 0.0 });
        let inv = &s * &p * &s;
        assert!((&inv * &inv - &eye).norm_l2() < 1e-12);
        assert!((involution_part(&inv) - &inv).norm_l2() < 1e-10);
    }

    /// A mirror and a half-turn are involutions, the identity too; a rotation by a third of a
    /// turn is not (`T(T(v))` is the rotation by two thirds).
    #[test]
    fn involutions_are_told_from_rotations() {
        let c = shapes::star(3, 3);
        let n = c.mesh.num_vertices();
        let all: Vec<usize> = (0..n).collect();
        let adjacency = c.mesh.adjacency();
        let maps = shapes::star_symmetries(&c, 3);
        let get = |name: &str| -> Vec<usize> { maps.iter().find(|(m, _)| m == name).expect(name).1.iter().map(|&w| w as usize).collect() };
        assert!(is_involution(&adjacency, &get("mirror 0"), &all));
        assert!(is_involution(&adjacency, &get("half-turn about arm 1"), &all));
        assert!(is_involution(&adjacency, &all, &all));
        assert!(!is_involution(&adjacency, &get("rotation 120°"), &all));
    }

    /// The smoothing step of a scrambled mirror (every vertex sent to a vertex two rings from
    /// its image) on a posed, noisy quadruped: with the involution part, the map comes back
    /// to the mirror better than with plain ZoomOut's step, and T∘T is nearer the identity.
    #[test]
    fn smoothing_a_scrambled_mirror_gives_an_involution() {
        let c = shapes::quadruped(4, shapes::Pose::Walking, 0.005, 1);
        let n = c.mesh.num_vertices();
        let adjacency = c.mesh.adjacency();
        let (off, nbr) = &adjacency;
        let truth: Vec<usize> = c.mirror.iter().map(|&w| w as usize).collect();
        let step = |w: usize, i: usize| nbr[off[w] + i % (off[w + 1] - off[w])] as usize;
        let start: Vec<usize> = (0..n).map(|v| step(step(truth[v], v * 7), v * 3 + 1)).collect();
        let (basis, _, _) = crate::maps::test_spectra(&c.mesh, 60);
        let zb = ZoomBasis::new(&basis, 60);
        let near = |a: usize, b: usize| a == b || nbr[off[a]..off[a + 1]].iter().any(|&u| u as usize == b);
        let score = |involution: Involution| {
            let mut map = start.clone();
            zoomout_between(&zb, &adjacency, &zb, &adjacency, &mut map, 60, 60, 1, involution);
            let right = (0..n).filter(|&v| near(map[v], truth[v])).count() as f64 / n as f64;
            let back = (0..n).filter(|&v| near(map[map[v]], v)).count() as f64 / n as f64;
            (right, back)
        };
        let (plain, projected) = (score(Involution::Off), score(Involution::Project));
        // Measured: plain (0.963, 0.931), projected (0.987, 0.984).
        assert!(projected.0 >= 0.95 && projected.0 > plain.0, "within a ring of the mirror: plain {plain:?}, projected {projected:?}");
        assert!(projected.1 >= plain.1 + 0.02, "come back within a ring: plain {plain:?}, projected {projected:?}");
    }
}
