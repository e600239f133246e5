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
//! 2. **Detection** on the coarse mesh: the whole pipeline — eigenbasis, descriptors, sampling,
//!    voting, hypotheses, refinement, judge — exactly as on any mesh of `m` vertices.
//! 3. **Cells**: every fine vertex belongs to its geodesically nearest coarse vertex (one
//!    multi-source Dijkstra on the fine edge graph).
//! 4. **Lift** ([`crate::maps::proxy`]'s local trilateration): a fine vertex is placed relative
//!    to the images of its cell's coarse vertex and that vertex's coarse neighbours, preserving
//!    its straight distances to them, by greedy descent on the fine mesh.
//! 5. **Judge** ([`crate::judge`]) of the lifted maps on the fine mesh (its 600 stencils), which
//!    ranks them as a mesh's own maps are ranked.
//!
//! What is computed at full resolution: only the cells, the lift (O(n log n) and O(n)), the
//! judge's stencils, the mean curvature of the polish's curvature term (one pass over the
//! triangles, averaged over each cell: [`crate::descriptors::curvature`]) and the outputs
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
/// (34–48k vertices) stay on it (65.3% against 63.7% at full resolution). Smaller meshes
/// stay off it for the same reason: simplifying the glued SHREC'16 kids (11–12k vertices) to
/// half their vertices gave best acc@0.05 45–58% against 54.6% at full resolution, from
/// neighbouring settings of the simplification.
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
        Ok(Hierarchy { coarse, seeds, owner, coarse_adjacency, fine_adjacency })
    }

    /// A map of the coarse mesh (coarse vertex indices) lifted to every fine vertex
    /// (`positions` the fine mesh's).
    pub fn lift(&self, positions: &[[f64; 3]], m: &DenseMap) -> DenseMap {
        let seed_positions: Vec<[f64; 3]> = self.seeds.iter().map(|&s| positions[s]).collect();
        crate::maps::proxy::lift(&self.seeds, &self.owner, &seed_positions, &self.coarse_adjacency, &self.fine_adjacency, positions, m)
    }

    /// A field on the coarse mesh's vertices carried to every fine vertex: each takes its
    /// cell's value (the counterpart of [`crate::descriptors::curvature::restrict_to_cells`], which
    /// averages a fine field over each cell).
    pub fn on_fine(&self, coarse: &[f64]) -> Vec<f64> {
        self.owner.iter().map(|&c| coarse[c as usize]).collect()
    }
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
}
