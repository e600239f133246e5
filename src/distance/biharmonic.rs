//! Biharmonic distance (Lipman, Rustamov & Funkhouser 2010), the paper's eq. (3):
//! $$d(x,y)^2 = \sum_{i\ge1} \frac{(\varphi_i(x) - \varphi_i(y))^2}{\lambda_i^2}$$
//! over the computed eigenpairs, skipping the constant one. It is the Euclidean distance between
//! rows of the embedding `B = [φ_i / λ_i]`, so distances from a few sources to every vertex are
//! one matrix product (`‖B_x‖² + ‖B_s‖² − 2 B_x·B_s`), never an n × n matrix.

use faer::{Accum, Mat, MatRef, Par};

use crate::spectral::kernels::{dispatch, Kernel};
use crate::spectral::Eigenbasis;

/// The biharmonic embedding of every vertex.
#[derive(Clone, Debug)]
pub struct BiharmonicEmbedding {
    /// `(n, k−1)` rows `B_x = (φ_i(x)/λ_i)_{i≥1}`.
    pub coords: Mat<f64>,
    /// `(n,)` squared row norms.
    pub norms2: Vec<f64>,
}

/// Builds the embedding from an eigenbasis.
pub fn biharmonic(basis: &Eigenbasis) -> BiharmonicEmbedding {
    let n = basis.num_vertices();
    let k = basis.k();
    let coords = Mat::<f64>::from_fn(n, k - 1, |v, i| basis.evecs[(v, i + 1)] / basis.evals[i + 1].max(f64::MIN_POSITIVE));
    let norms2 = (0..n).map(|v| (0..k - 1).map(|i| coords[(v, i)].powi(2)).sum()).collect();
    BiharmonicEmbedding { coords, norms2 }
}

/// `d ← √max(0, ‖B_v‖² + ‖B_x‖² − 2 d)` over a column of dot products `d = B_v · B_x`: the same
/// operations in the same order in every lane (no fused multiply-add), so the result is the
/// scalar one bit for bit.
struct ToDistance<'a> {
    col: &'a mut [f64],
    norms2: &'a [f64],
    nx: f64,
}

impl Kernel for ToDistance<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) {
        let (head, tail) = S::as_mut_simd_f64s(self.col);
        let (norms, norms_tail) = S::as_simd_f64s(self.norms2);
        let (nx, two, zero) = (simd.splat_f64s(self.nx), simd.splat_f64s(2.0), simd.splat_f64s(0.0));
        for (d, &nv) in head.iter_mut().zip(norms) {
            *d = simd.sqrt_f64s(simd.max_f64s(simd.sub_f64s(simd.add_f64s(nv, nx), simd.mul_f64s(two, *d)), zero));
        }
        for (d, &nv) in tail.iter_mut().zip(norms_tail) {
            *d = (nv + self.nx - 2.0 * *d).max(0.0).sqrt();
        }
    }
}

impl BiharmonicEmbedding {
    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.norms2.len()
    }

    /// Whether there are no vertices.
    pub fn is_empty(&self) -> bool {
        self.norms2.is_empty()
    }

    /// The largest distance between two of `vertices` (0 for fewer than two): the scale
    /// sample distortions are measured in (voting's diameter, over its samples).
    pub fn diameter_of(&self, vertices: &[usize]) -> f64 {
        vertices.iter().flat_map(|&a| vertices.iter().map(move |&b| (a, b))).map(|(a, b)| self.dist(a, b)).fold(0.0, f64::max)
    }

    /// Distance between two vertices.
    pub fn dist(&self, x: usize, y: usize) -> f64 {
        let (a, b) = (self.coords.row(x), self.coords.row(y));
        let mut s = 0.0;
        for i in 0..self.coords.ncols() {
            s += (a[i] - b[i]).powi(2);
        }
        s.sqrt()
    }

    /// `(n, |sources|)` distances from each source to every vertex.
    pub fn from_sources(&self, sources: &[usize]) -> Mat<f64> {
        let n = self.len();
        let src = Mat::<f64>::from_fn(sources.len(), self.coords.ncols(), |s, i| self.coords[(sources[s], i)]);
        let mut g = Mat::<f64>::zeros(n, sources.len());
        faer::linalg::matmul::matmul(g.as_mut(), Accum::Replace, self.coords.as_ref(), src.transpose(), 1.0, Par::Seq);
        // In place, a column at a time (element-wise `from_fn` indexing was 10% of a detection),
        // with explicit SIMD: left to LLVM the square roots stay baseline SSE2, 8% of a
        // detection's time.
        for (s, &x) in sources.iter().enumerate() {
            dispatch(ToDistance { col: g.col_as_slice_mut(s), norms2: &self.norms2, nx: self.norms2[x] });
        }
        g
    }

    /// `(|a|, |b|)` distances between two vertex sets.
    pub fn between(&self, a: &[usize], b: &[usize]) -> Mat<f64> {
        let ca = Mat::<f64>::from_fn(a.len(), self.coords.ncols(), |s, i| self.coords[(a[s], i)]);
        let cb = Mat::<f64>::from_fn(b.len(), self.coords.ncols(), |s, i| self.coords[(b[s], i)]);
        let mut g = Mat::<f64>::zeros(a.len(), b.len());
        faer::linalg::matmul::matmul(g.as_mut(), Accum::Replace, ca.as_ref(), cb.transpose(), 1.0, Par::Seq);
        Mat::<f64>::from_fn(a.len(), b.len(), |i, j| (self.norms2[a[i]] + self.norms2[b[j]] - 2.0 * g[(i, j)]).max(0.0).sqrt())
    }

    /// Coordinates as a matrix view.
    pub fn as_ref(&self) -> MatRef<'_, f64> {
        self.coords.as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{shapes, EigenParams};

    #[test]
    fn is_a_metric_and_matches_pairwise_formula() {
        let mesh = shapes::bumpy_torus(12);
        let p = EigenParams { k: 40, ..Default::default() };
        let basis = Eigenbasis::compute(&mesh, &p).unwrap();
        let emb = biharmonic(&basis);
        let src = [0usize, 17, 100, 250];
        let d = emb.from_sources(&src);
        for (s, &x) in src.iter().enumerate() {
            assert!(d[(x, s)] < 1e-7 * d[(0, 3)].max(1e-12));
            for y in [1usize, 50, 300, 431] {
                let direct: f64 = (1..40).map(|i| ((basis.evecs[(x, i)] - basis.evecs[(y, i)]) / basis.evals[i]).powi(2)).sum::<f64>().sqrt();
                assert!((d[(y, s)] - direct).abs() < 1e-9 * direct.max(1e-9));
                assert!((emb.dist(x, y) - direct).abs() < 1e-9 * direct.max(1e-9));
            }
        }
        // Triangle inequality on a few triples.
        for (a, b, c) in [(0, 17, 100), (250, 3, 77), (5, 6, 400)] {
            assert!(emb.dist(a, c) <= emb.dist(a, b) + emb.dist(b, c) + 1e-12);
        }
        let between = emb.between(&[0, 17], &[100, 250]);
        assert!((between[(1, 0)] - emb.dist(17, 100)).abs() < 1e-9 * emb.dist(17, 100));
    }
}
