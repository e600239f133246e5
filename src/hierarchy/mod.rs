//! Detection on a multiresolution hierarchy (beyond the paper; issue 17): a large mesh is
//! detected on a coarse version of itself, and the maps are lifted back.
//!
//! The symmetries of a shape live at a scale far coarser than its vertices, and every stage of
//! the pipeline costs at least linear time in the vertices, the eigensolve more (it dominated
//! on 60k-vertex scans). So on a mesh of more than `4 m` vertices (`m` =
//! [`crate::detect::Params::hierarchy_vertices`], default 6000):
//!
//! 1. **Coarse mesh** ([`simplify`]): quadric-error edge collapse down to `m` vertices, each a
//!    vertex of the fine mesh, keeping the topology (link condition), boundaries and thin parts
//!    (a finger's vertices carry the quadrics of its sides: shortening it is expensive).
//! 2. **Cells**: every fine vertex belongs to its geodesically nearest coarse vertex (one
//!    multi-source Dijkstra on the fine edge graph).
//! 3. **Detection** on the coarse mesh: the whole pipeline — eigenbasis, descriptors, sampling,
//!    voting, hypotheses, refinement, judge — as on any mesh of `m` vertices, except its metric,
//!    measured on the fine mesh. The mass matrix of its eigenproblem `L_c φ = λ M φ` is `M =
//!    diag(A_c)`, `A_c` the area of the fine mesh's cell of coarse vertex `c`
//!    ([`Hierarchy::cell_mass`]; the proxy of [`crate::maps::proxy`] weighs its seeds the same
//!    way), not the coarse mesh's lumped mass (a third of the area of its triangles around `c`);
//!    the stiffness `L_c` and the edge graph take the edges' lengths along the fine mesh (below).
//!    The simplification leaves triangles of very different shapes side by side, and their lumped
//!    mass is a poor quadrature of the surface: on the 60k KIDS poses the ratio of cell area to
//!    lumped mass spreads from 0.44 to 3.7 (1st and 99th percentiles; coefficient of variation of
//!    the masses 0.48 lumped, 0.35 cells), and every `⟨f, g⟩_M` of the pipeline — the
//!    M-orthonormality of the basis, the functional maps `C = Φᵀ M Φ[T]`, the band-limited
//!    curvature — weighs the surface unevenly. Measured (best / first acc@0.05, mean over seeds
//!    0–3, 10, 20; docs/hierarchy-benchmark.md, "Session 28"): the 60k KIDS poses 93.3 / 93.3% →
//!    95.2 / 95.2% (full resolution: 94.8%), scan-like copies of the SHREC'16 kids (34–48k) 65.1 /
//!    57.7% → 66.2 / 58.5%. A Galerkin operator (`PᵀLP` and `PᵀMP` with a smoothed-aggregation
//!    prolongation of the cells) was far worse: eigenvalues 1.4–3 times the fine mesh's.
//!
//!    **Edge lengths measured along the fine surface** (beyond the paper; session 50). Where the
//!    surface folds onto itself or two parts nearly touch (a foot against the other foot, the
//!    crease of a bent knee), the simplification joins the two sheets with a short edge that its
//!    quadric error barely sees, and the coarse mesh's geodesics, Laplacian and maps take the fold
//!    for a bridge (on the 60k KIDS poses a coarse edge whose chord is under 0.6 of the way between
//!    its ends along the fine mesh is 6–9 times as frequent where the lifted maps failed; session
//!    49). Refusing those collapses broke the noisy scans (their crumpled fans look like folds). So
//!    the coarse mesh keeps its triangles and its vertices, but its *metric* is measured on the
//!    fine mesh: each coarse edge `(c, d)` gets the length `|x_c − x_d| · s_cd` with the stretch
//!    `s_cd = max(1, 0.9·g_cd / |x_c − x_d|)`, `g_cd` the fine edge graph's distance between the
//!    two ends ([`Hierarchy::stretch`]; 0.9 because a path along edges zigzags, by 5–8% on average,
//!    up to 2/√3 on a regular triangulation, so only a way clearly longer than the straight line
//!    counts). The stiffness `L_c` is the cotangent Laplacian of these lengths (Heron's areas and
//!    the cotangents from lengths alone, an intrinsic metric on the coarse triangles, as in
//!    intrinsic triangulations, Sharp, Soliman & Crane 2019; per-triangle mollification where a
//!    stretched edge breaks a triangle's inequality), and the coarse edge graph of the polish's
//!    geodesics and anchors has them as its edges' lengths: an edge across a fold couples its ends
//!    as weakly as the way around does. Measured against the chords (best acc@0.05;
//!    docs/hierarchy-benchmark.md, "Session 50"): the 60k KIDS poses 95.68 → 96.17% over 12 seeds
//!    (pose results at full resolution's precision, ≥ 0.997: 0 → 10 of 60), their noisy copies
//!    92.51 → 94.33% (seeds 0–30), TOSCA's shapes subdivided to 20k on a 4,000-vertex coarse mesh
//!    87.73 → 92.61% (seeds 0, 10; 38 shapes up, 6 down), FAUST's 90.44 → 90.98%, the SHREC'16 kids
//!    subdivided (34–48k) 69.60 / 63.27 → 70.67 / 69.27% (best / first). The folds are not all of
//!    it: stretching only the edges whose factor is at least 2 (0.3–1% of them) lost the gain (KIDS
//!    95.28% over nine of the seeds, where the full stretch has 96.28 and the chords 95.78; noisy
//!    copies 89.46%): the mild stretch of a third of the edges, which makes the coarse graph's
//!    distances follow the fine graph's, matters as much (why is not measured). Nor is it a better
//!    discretisation of the surface's spectrum: a coarse mesh's eigenvalues sit further from a
//!    congruent mesh's with it (5.9% against 1.9% on two shoes), so the congruence of components
//!    compares a coarse mesh through an eigenbasis with chord lengths (`crate::detect`). The graph
//!    distance is a rough geodesic: on the generated quadruped at rest a tenth of the coarse edges
//!    get a stretch above 1.2 without any fold, mostly the graph's zigzag (the fine path shortened
//!    by chords of half the coarse edge's length brings that tenth to 1.13). Computing it: one
//!    truncated search per coarse vertex on the fine graph, stopped once its neighbours are settled
//!    or 8 longest edges away.
//! 4. **Lift** ([`crate::maps::proxy`]'s local trilateration): a fine vertex is placed relative
//!    to the images of its cell's coarse vertex and that vertex's coarse neighbours, preserving
//!    its straight distances to them, by greedy descent on the fine mesh.
//! 5. **Judge** ([`crate::judge`]) of the lifted maps on the fine mesh (its 600 stencils), which
//!    ranks them as a mesh's own maps are ranked.
//!
//! What is computed at full resolution: only the cells, the edges' stretch, the lumped mass
//! (summed into the cell masses; also the judge's band trace), the lift (O(n log n) and O(n)), the
//! judge's stencils, the mean curvature of the polish's curvature term (one pass over the
//! triangles, averaged over each cell and over two halves of each cell, whose disagreement
//! tells a noisy scan: [`crate::descriptors::curvature`]) and the outputs
//! themselves (maps and confidences). No eigenpair, descriptor or dense `n × k`
//! matrix of the fine mesh is ever formed, so memory grows linearly with the vertices. The
//! functional map and complexity reported for a symmetry are those of the coarse mesh's
//! basis. A map's precision is that of the coarse map plus the lift's interpolation (the cell
//! radius at m = 6000 is about 0.7% of √area, a seventh of the evaluation's 0.05 radius).

pub mod simplify;

use crate::maps::geodesic::EdgeGraph;
use crate::maps::DenseMap;
use crate::mesh::{Mesh, MeshError, MeshParams};

/// A mesh needs the hierarchy when it has more than this many times `hierarchy_vertices`
/// vertices (24,000 by default). Below that the full pipeline takes about a second (5k
/// vertices: 0.6 s, 12k: 1 s, 20k: 1.1 s) and is more accurate: on scan-like copies of
/// shared/data's TOSCA and FAUST shapes (`bench/subdivided.py`: midpoint-subdivided to 20k
/// vertices, 0.05% noise; seeds 0–2) the coarse mesh lost 1.6 points of best acc@0.05 on each
/// (TOSCA 88.5 → 86.9%, FAUST 92.3 → 90.7%) for ×0.55–0.7 of the time, so the margin was raised
/// from 3 to 4 (docs/hierarchy-benchmark.md, "Session 27"). The copies of the SHREC'16 kids
/// (34–48k vertices) stay on it (65.3%, 64.2% with the cell masses of step 3, against 63.7% at
/// full resolution; seeds 0–2). Smaller meshes stay off it for the same reason: simplifying
/// the glued SHREC'16 kids (11–12k vertices) to half their vertices gave best acc@0.05 45–58%
/// against 54.6% at full resolution, from neighbouring settings of the simplification.
pub(crate) const MARGIN: f64 = 4.0;

/// The simplification's share of [`Hierarchy::with_progress`]'s progress (the Voronoi cells
/// have the rest; on 10⁶ vertices they take a sixth of the time).
const SIMPLIFY_SHARE: f64 = 0.85;

/// Whether a mesh of `n` vertices is detected on a coarse mesh of `size` vertices.
pub fn wanted(n: usize, size: usize) -> bool {
    size > 0 && n as f64 > MARGIN * size as f64
}

/// A fine mesh's coarse version and what lifting maps back needs.
pub struct Hierarchy {
    /// The coarse mesh; its vertex `c` is fine vertex `seeds[c]` (its `input_index` counts in
    /// the coarse vertices, not the input's).
    pub coarse: Mesh,
    /// `(m,)` fine vertex of each coarse vertex.
    pub seeds: Vec<usize>,
    /// `(n,)` coarse vertex whose cell holds each fine vertex.
    pub owner: Vec<u32>,
    /// CSR adjacency of the coarse mesh.
    coarse_adjacency: (Vec<usize>, Vec<u32>),
    /// CSR adjacency of the fine mesh.
    pub fine_adjacency: (Vec<usize>, Vec<u32>),
    /// Per entry of the coarse mesh's CSR adjacency ([`Mesh::adjacency`]), how much longer the
    /// way between the edge's ends along the fine mesh is than the edge's chord, at least 1
    /// (module docs, step 3; [`stretch`]).
    pub stretch: Vec<f64>,
}

/// Why a hierarchy was not built.
#[derive(Debug)]
pub enum HierarchyError {
    /// The coarse mesh is not a valid mesh.
    Mesh(MeshError),
    /// The progress callback said stop.
    Cancelled,
}

impl Hierarchy {
    /// The coarse mesh of about `size` vertices of `mesh` (one connected component), its cells.
    pub fn new(mesh: &Mesh, size: usize) -> Result<Hierarchy, MeshError> {
        Self::with_progress(mesh, size, &mut |_| true).map_err(|e| match e {
            HierarchyError::Mesh(e) => e,
            HierarchyError::Cancelled => unreachable!("never cancelled"),
        })
    }

    /// [`Hierarchy::new`], reporting the simplification's progress in [0, 1] (cancelled when
    /// `progress` returns `false`).
    pub fn with_progress(mesh: &Mesh, size: usize, progress: &mut dyn FnMut(f64) -> bool) -> Result<Hierarchy, HierarchyError> {
        let s = simplify::simplify_with_progress(mesh, size, &mut |f| progress(SIMPLIFY_SHARE * f)).ok_or(HierarchyError::Cancelled)?;
        let positions: Vec<[f64; 3]> = s.kept.iter().map(|&v| mesh.vertices[v]).collect();
        // Coincident fine vertices are self-contacts here (welding ran on the input): keep them.
        let coarse = Mesh::new(positions, s.triangles, &MeshParams { weld: false, ..Default::default() }).map_err(HierarchyError::Mesh)?;
        let seeds: Vec<usize> = coarse.input_index.iter().map(|&i| s.kept[i as usize]).collect();
        if !progress(SIMPLIFY_SHARE) {
            return Err(HierarchyError::Cancelled);
        }
        let fine_adjacency = mesh.adjacency();
        if !progress(SIMPLIFY_SHARE) {
            return Err(HierarchyError::Cancelled);
        }
        let graph = EdgeGraph::new(&mesh.vertices, fine_adjacency.clone());
        if !progress(SIMPLIFY_SHARE) {
            return Err(HierarchyError::Cancelled);
        }
        let owner = graph.nearest_sources(&seeds, &mut |f| progress(SIMPLIFY_SHARE + (1.0 - SIMPLIFY_SHARE) * f)).ok_or(HierarchyError::Cancelled)?;
        // The mesh is one connected component (`crate::detect` splits them), so every vertex
        // has a cell; were one unreached, its lift would start from cell 0's seed's image.
        let owner = owner.into_iter().map(|c| if c == u32::MAX { 0 } else { c }).collect();
        let coarse_adjacency = coarse.adjacency();
        let stretch = stretch(&coarse.vertices, &seeds, &coarse_adjacency, &graph);
        if !progress(1.0) {
            return Err(HierarchyError::Cancelled);
        }
        Ok(Hierarchy { coarse, seeds, owner, coarse_adjacency, fine_adjacency, stretch })
    }

    /// A map of the coarse mesh (coarse vertex indices) lifted to every fine vertex
    /// (`positions` the fine mesh's).
    pub fn lift(&self, positions: &[[f64; 3]], m: &DenseMap) -> DenseMap {
        let seed_positions: Vec<[f64; 3]> = self.seeds.iter().map(|&s| positions[s]).collect();
        crate::maps::proxy::lift(&self.seeds, &self.owner, &seed_positions, &self.coarse_adjacency, &self.fine_adjacency, positions, m)
    }

    /// The area of each coarse vertex's cell on the fine mesh (`fine_mass` the fine lumped
    /// mass), scaled to sum to `total` (the coarse mesh's area, in its units): the coarse
    /// eigenbasis's mass matrix (module docs, step 3). A cell that holds no area (its seed
    /// shares a position with another seed that took its vertices) gets the smallest cell's,
    /// so every mass stays positive.
    // `!(x > y)` on purpose: also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    pub fn cell_mass(&self, fine_mass: &[f64], total: f64) -> Vec<f64> {
        let mut mass = crate::maps::proxy::cell_sums(&self.owner, fine_mass, self.seeds.len());
        let smallest = mass.iter().copied().filter(|&m| m > 0.0).fold(f64::INFINITY, f64::min);
        if smallest.is_finite() {
            mass.iter_mut().filter(|m| !(**m > 0.0)).for_each(|m| *m = smallest);
        }
        let sum: f64 = mass.iter().sum();
        let scale = if sum > 0.0 { total / sum } else { 1.0 };
        mass.iter_mut().for_each(|m| *m *= scale);
        mass
    }

    /// A field on the coarse mesh's vertices carried to every fine vertex: each takes its
    /// cell's value (the counterpart of [`crate::descriptors::curvature::Raw::on_cells`], which
    /// averages a fine field over each cell).
    pub fn on_fine(&self, coarse: &[f64]) -> Vec<f64> {
        self.owner.iter().map(|&c| coarse[c as usize]).collect()
    }
}

/// The fine edge graph's distances overestimate the surface's geodesics (a path along edges
/// zigzags: by up to 2/√3 on a regular triangulation, 5–8% on average), so an edge is
/// stretched only where this fraction of its graph distance exceeds its chord: where the way
/// along the surface is clearly longer than the straight line (a fold, a near-contact), not
/// the zigzag of a flat patch.
const GRAPH_TO_GEODESIC: f64 = 0.9;

/// The fine searches of [`stretch`] stop this many times a coarse vertex's longest edge away
/// (its neighbours not reached by then get that distance): they stay local.
const STRETCH_REACH: f64 = 8.0;

/// Per entry of the coarse CSR `adjacency` (coarse vertex `c` at fine vertex `seeds[c]`,
/// `positions` the coarse mesh's), the factor `max(1, 0.9·g/|x_c − x_d|)` with `g` the fine
/// edge graph's distance between the two ends (module docs, step 3): one truncated search from
/// each coarse vertex until it has settled its higher-numbered neighbours, on all cores.
fn stretch(positions: &[[f64; 3]], seeds: &[usize], adjacency: &(Vec<usize>, Vec<u32>), graph: &EdgeGraph) -> Vec<f64> {
    let (off, nbr) = adjacency;
    let m = seeds.len();
    let fine = graph.off.len() - 1;
    let mut coarse_of = vec![u32::MAX; fine];
    for (c, &s) in seeds.iter().enumerate() {
        coarse_of[s] = c as u32;
    }
    let chord = |c: usize, d: usize| crate::mesh::vec3::dist2(positions[c], positions[d]).sqrt();
    let found: Vec<(usize, usize, f64)> = crate::parallel::chunks(m, |range| {
        let mut scratch = vec![f64::INFINITY; fine];
        let mut out = Vec::new();
        for c in range {
            // Entries of c's row with a higher neighbour, each with its distance once settled.
            let row = off[c]..off[c + 1];
            let mut want: Vec<(usize, f64)> = row.filter(|&k| nbr[k] as usize > c).map(|k| (k, f64::INFINITY)).collect();
            let reach = STRETCH_REACH * want.iter().map(|&(k, _)| chord(c, nbr[k] as usize)).fold(0.0, f64::max);
            let mut left = want.len();
            if left > 0 {
                graph.search_unordered(seeds[c], reach, &mut scratch, &mut |v, d| {
                    let k = coarse_of[v];
                    if k != u32::MAX {
                        if let Some(w) = want.iter_mut().find(|(e, g)| nbr[*e] == k && g.is_infinite()) {
                            w.1 = d;
                            left -= 1;
                        }
                    }
                    left > 0
                });
            }
            for (k, g) in want {
                let length = chord(c, nbr[k] as usize);
                let factor = if length > 0.0 { (GRAPH_TO_GEODESIC * g.min(reach) / length).max(1.0) } else { 1.0 };
                out.push((c, k, factor));
            }
        }
        out
    })
    .into_iter()
    .flatten()
    .collect();
    let mut stretch = vec![1.0; nbr.len()];
    for (c, k, factor) in found {
        stretch[k] = factor;
        // The same edge seen from its other end.
        let d = nbr[k] as usize;
        if let Ok(i) = nbr[off[d]..off[d + 1]].binary_search(&(c as u32)) {
            stretch[off[d] + i] = factor;
        }
    }
    stretch
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{self, Pose};

    /// The coarse mesh of a posed animal is one closed surface of the requested size, its
    /// vertices are fine vertices, every fine vertex has a cell, and the identity lifts to the
    /// identity (up to the trilateration's tolerance: within one ring).
    #[test]
    fn the_coarse_mesh_is_a_closed_subset_and_lifts_the_identity() {
        let c = shapes::quadruped(5, Pose::Walking, 0.0, 0);
        let h = Hierarchy::new(&c.mesh, 2000).unwrap();
        assert_eq!(h.coarse.num_vertices(), 2000);
        assert_eq!(h.coarse.info.components, 1);
        assert!(h.seeds.iter().enumerate().all(|(i, &s)| h.coarse.vertices[i] == c.mesh.vertices[s]));
        assert!(h.owner.iter().all(|&o| (o as usize) < 2000));
        let m = DenseMap::from_image((0..2000).collect());
        let lifted = h.lift(&c.mesh.vertices, &m);
        let exact = (0..c.mesh.num_vertices()).filter(|&v| lifted.map[v] == v as i64).count();
        assert!(exact as f64 > 0.95 * c.mesh.num_vertices() as f64, "{exact} fixed");
    }

    /// The cell masses are the fine mesh's area, each cell's share of it, and an eigenbasis of
    /// the coarse mesh weighed by them is closer to the fine mesh's spectrum than one weighed
    /// by the coarse mesh's own lumped mass (module docs, step 3).
    #[test]
    fn cell_masses_measure_the_fine_surface() {
        use crate::spectral::{mass, cotan, EigenParams, Eigenbasis};
        let c = shapes::quadruped(5, Pose::Walking, 0.0, 0);
        let (fine, _) = c.mesh.normalized();
        let h = Hierarchy::new(&fine, 2000).unwrap();
        let fine_mass = mass::lumped_mass(&fine, &cotan::mollified_edge_lengths(&fine));
        let cells = h.cell_mass(&fine_mass, h.coarse.area());
        assert!(cells.iter().all(|&m| m > 0.0));
        assert!((cells.iter().sum::<f64>() - h.coarse.area()).abs() < 1e-9);
        let mut direct = vec![0.0; 2000];
        for v in 0..fine.num_vertices() {
            direct[h.owner[v] as usize] += fine_mass[v];
        }
        let scale = h.coarse.area() / fine_mass.iter().sum::<f64>();
        assert!(cells.iter().zip(&direct).all(|(a, b)| (a - b * scale).abs() <= 1e-12 * a.max(1e-9)));
        let params = EigenParams { k: 40, ..Default::default() };
        let exact = Eigenbasis::compute(&fine, &params).unwrap();
        let lumped = Eigenbasis::compute(&h.coarse, &params).unwrap();
        let weighed = Eigenbasis::compute_with_mass(&h.coarse, Some(&cells), None, &params, &mut |_| true).unwrap();
        let error = |b: &Eigenbasis| (1..40).map(|i| (b.evals[i] * b.area / (exact.evals[i] * exact.area) - 1.0).abs()).sum::<f64>() / 39.0;
        let (e_lumped, e_cells) = (error(&lumped), error(&weighed));
        eprintln!("mean relative eigenvalue error: lumped {e_lumped:.4}, cells {e_cells:.4}");
        assert!(e_cells < e_lumped, "lumped {e_lumped}, cells {e_cells}");
    }

    /// A strip folded into a hairpin (two sheets `gap` apart joined by a half-cylinder):
    /// its grid's positions and CSR adjacency, and the grid index of (along, across).
    fn hairpin(gap: f64, spacing: f64) -> (Vec<[f64; 3]>, (Vec<usize>, Vec<u32>), impl Fn(usize, usize) -> usize) {
        let (arm, r) = (1.0, 0.5 * gap);
        let length = 2.0 * arm + std::f64::consts::PI * r;
        let (nu, nw) = ((length / spacing).round() as usize + 1, 6);
        let point = |s: f64| -> [f64; 2] {
            if s < arm {
                [arm - s, r]
            } else if s < arm + std::f64::consts::PI * r {
                let t = (s - arm) / r;
                [-r * t.sin(), r * t.cos()]
            } else {
                [s - arm - std::f64::consts::PI * r, -r]
            }
        };
        let at = move |u: usize, w: usize| u * nw + w;
        let mut positions = Vec::new();
        for u in 0..nu {
            let [x, z] = point(length * u as f64 / (nu - 1) as f64);
            for w in 0..nw {
                positions.push([x, spacing * w as f64, z]);
            }
        }
        let mut triangles = Vec::new();
        for u in 0..nu - 1 {
            for w in 0..nw - 1 {
                triangles.push([at(u, w) as u32, at(u + 1, w) as u32, at(u + 1, w + 1) as u32]);
                triangles.push([at(u, w) as u32, at(u + 1, w + 1) as u32, at(u, w + 1) as u32]);
            }
        }
        let mesh = Mesh::new(positions.clone(), triangles, &MeshParams { weld: false, ..Default::default() }).unwrap();
        (positions, mesh.adjacency(), at)
    }

    /// An edge that cuts across a fold is stretched to the way around it (up to the search's
    /// reach), an edge along one sheet is not; both ends of an edge get the same factor.
    #[test]
    fn an_edge_across_a_fold_is_stretched_and_one_along_a_sheet_is_not() {
        let (gap, spacing) = (0.05, 0.01);
        let (fine, adjacency, at) = hairpin(gap, spacing);
        let graph = EdgeGraph::new(&fine, adjacency);
        let last = (fine.len() / 6) - 1;
        // Coarse vertices: on the upper sheet 0.5 from the fold, the point of the lower sheet
        // below it, and the upper sheet's point 0.04 further along.
        let (top, below, along) = (at(50, 2), at(last - 50, 2), at(46, 2));
        assert!((crate::mesh::vec3::dist2(fine[top], fine[below]).sqrt() - gap).abs() < 1e-9);
        let seeds = vec![top, below, along];
        let positions: Vec<[f64; 3]> = seeds.iter().map(|&s| fine[s]).collect();
        // Coarse edges 0–1 (across the fold) and 0–2 (along the sheet).
        let coarse_adjacency = (vec![0, 2, 3, 4], vec![1, 2, 0, 0]);
        let stretch = stretch(&positions, &seeds, &coarse_adjacency, &graph);
        // Across: the way around is 2·0.5 + π·0.025 ≈ 1.08, beyond the search's reach of
        // 8 times the longer edge (0.4): 0.9 · 0.4 / 0.05 = 7.2.
        let reach = STRETCH_REACH * gap;
        let expected = GRAPH_TO_GEODESIC * reach / gap;
        assert!((stretch[0] - expected).abs() < 1e-9, "{stretch:?}");
        assert_eq!(stretch[0], stretch[2], "the same factor from both ends");
        // Along: the chord is the graph distance, 0.9 of it is shorter: no stretch.
        assert_eq!(stretch[1], 1.0);
        assert_eq!(stretch[3], 1.0);
    }

    /// Every edge of a real coarse mesh gets a factor of at least 1, the same from both ends;
    /// on a smooth animal without contacts most edges keep their chords. Not all: a tenth get
    /// 1.05–1.25, mostly the fine edge graph's zigzag beyond what [`GRAPH_TO_GEODESIC`] allows
    /// for, and the top percent 1.5–2.4, where the surface between the edge's ends bends away
    /// from the chord (module docs, step 3).
    #[test]
    fn a_smooth_shapes_coarse_edges_keep_their_chords() {
        let c = shapes::quadruped(5, Pose::Rest, 0.0, 0);
        let h = Hierarchy::new(&c.mesh, 2000).unwrap();
        let (off, nbr) = &h.coarse_adjacency;
        assert_eq!(h.stretch.len(), nbr.len());
        assert!(h.stretch.iter().all(|&f| f >= 1.0 && f.is_finite()));
        for v in 0..h.coarse.num_vertices() {
            for k in off[v]..off[v + 1] {
                let u = nbr[k] as usize;
                let back = off[u] + nbr[off[u]..off[u + 1]].binary_search(&(v as u32)).unwrap();
                assert_eq!(h.stretch[k], h.stretch[back]);
            }
        }
        let mut q = h.stretch.clone();
        q.sort_by(f64::total_cmp);
        let at = |p: f64| q[((q.len() - 1) as f64 * p) as usize];
        let kept = q.iter().filter(|&&f| f == 1.0).count() as f64 / q.len() as f64;
        eprintln!("chords kept {kept:.3}; stretch at 0.9: {:.3}, 0.99: {:.3}, max {:.3}", at(0.9), at(0.99), at(1.0));
        assert!(kept > 0.6, "{kept}");
        assert!(at(0.9) < 1.3 && at(1.0) < 3.0, "{} {}", at(0.9), at(1.0));
    }

    /// A cell that holds no fine vertex (its seed coincides with another seed that took them)
    /// still gets a positive mass, the smallest cell's, and the masses sum to the total asked.
    #[test]
    fn an_empty_cell_gets_the_smallest_mass() {
        let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
        let mut h = Hierarchy::new(&c.mesh, 300).unwrap();
        let fine_mass = vec![1.0; c.mesh.num_vertices()];
        // Empty cell 7: its vertices go to cell 8.
        for o in &mut h.owner {
            if *o == 7 {
                *o = 8;
            }
        }
        let mass = h.cell_mass(&fine_mass, 2.0);
        let sizes = |k: u32| h.owner.iter().filter(|&&o| o == k).count() as f64;
        let smallest = (0..300u32).map(sizes).filter(|&s| s > 0.0).fold(f64::INFINITY, f64::min);
        let total: f64 = mass.iter().sum();
        assert!(mass.iter().all(|&m| m > 0.0));
        assert!((total - 2.0).abs() < 1e-12, "{total}");
        // Every cell's mass is its share of the total (the empty one counted at the smallest size).
        let unit = 2.0 / (c.mesh.num_vertices() as f64 + smallest);
        assert!((mass[7] - smallest * unit).abs() < 1e-12);
        assert!((mass[8] - sizes(8) * unit).abs() < 1e-12);
    }
}
