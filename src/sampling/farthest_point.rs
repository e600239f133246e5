//! Farthest point sampling (Eldar et al. 1997) in the biharmonic embedding, as the paper does
//! (§4.1): a seeded random first point, then repeatedly the vertex farthest from all chosen
//! ones. Samples gather at shape extremities (paw tips, head, tail), where symmetric
//! counterparts are also sampled. Also returns, for each vertex, its nearest sample (the
//! biharmonic Voronoi cell), used later to seed dense maps.

use crate::distance::BiharmonicEmbedding;

/// Result of [`farthest_point`].
#[derive(Clone, Debug)]
pub struct Samples {
    /// Chosen vertices in selection order.
    pub vertices: Vec<usize>,
    /// `(n,)` index into `vertices` of each vertex's nearest sample.
    pub cell: Vec<usize>,
    /// `(n,)` distance from each vertex to its nearest sample.
    pub radius: Vec<f64>,
}

/// Chooses `count` samples (at most n), deterministically for a given `seed`.
pub fn farthest_point(emb: &BiharmonicEmbedding, count: usize, seed: u64) -> Samples {
    let n = emb.len();
    let count = count.min(n).max(1);
    // The random start: the first output of the seed's generator.
    let first = (crate::random::SplitMix::new(seed).next_u64() % n as u64) as usize;
    let mut samples = Samples { vertices: vec![first], cell: vec![0usize; n], radius: vec![f64::INFINITY; n] };
    samples.absorb(emb, first);
    samples.extend(emb, count);
    samples
}

impl Samples {
    /// Continues the sampling up to `count` samples (at most n): the result is the one
    /// [`farthest_point`] gives for `count` directly, at the cost of the new samples only.
    pub fn extend(&mut self, emb: &BiharmonicEmbedding, count: usize) {
        let count = count.min(emb.len());
        while self.vertices.len() < count {
            let (far, _) = self.radius.iter().enumerate().fold((0, -1.0), |b, (v, &r)| if r > b.1 { (v, r) } else { b });
            self.vertices.push(far);
            self.absorb(emb, far);
        }
    }

    /// Updates the cells and radii with the newest sample `last`.
    fn absorb(&mut self, emb: &BiharmonicEmbedding, last: usize) {
        let d = emb.from_sources(&[last]);
        let s = self.vertices.len() - 1;
        for (v, &dv) in d.col_as_slice(0).iter().enumerate() {
            if dv < self.radius[v] {
                self.radius[v] = dv;
                self.cell[v] = s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::biharmonic;
    use crate::{shapes, Eigenbasis, EigenParams};

    #[test]
    fn samples_are_spread_deterministic_and_cells_are_nearest() {
        let mesh = shapes::bumpy_torus(14);
        let p = EigenParams { k: 30, ..Default::default() };
        let basis = Eigenbasis::compute(&mesh, &p).unwrap();
        let emb = biharmonic(&basis);
        let a = farthest_point(&emb, 20, 7);
        let b = farthest_point(&emb, 20, 7);
        assert_eq!(a.vertices, b.vertices);
        // Extending is sampling further: the same as asking for more at once.
        let mut c = a.clone();
        c.extend(&emb, 30);
        let d = farthest_point(&emb, 30, 7);
        assert_eq!(c.vertices, d.vertices);
        assert_eq!(c.cell, d.cell);
        assert_eq!(&c.vertices[..20], &a.vertices[..]);
        let mut uniq = a.vertices.clone();
        uniq.sort();
        uniq.dedup();
        assert_eq!(uniq.len(), 20);
        // Covering radius is at most the smallest distance between two samples (FPS property).
        let cover = a.radius.iter().cloned().fold(0.0, f64::max);
        for i in 0..20 {
            for j in 0..i {
                assert!(emb.dist(a.vertices[i], a.vertices[j]) >= cover - 1e-12);
            }
        }
        for v in (0..mesh.num_vertices()).step_by(37) {
            let best = a.vertices.iter().map(|&s| emb.dist(v, s)).fold(f64::INFINITY, f64::min);
            assert!((a.radius[v] - best).abs() < 1e-9 * best.max(1e-12));
            assert!((emb.dist(v, a.vertices[a.cell[v]]) - best).abs() < 1e-9 * best.max(1e-12));
        }
    }
}
