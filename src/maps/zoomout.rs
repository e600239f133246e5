//! ZoomOut refinement (Melzi, Ren, Rodolà, Sharma, Wonka & Ovsjanikov 2019) of a self-map.
//!
//! Alternates between the functional map of the pull-back in the first `k` eigenfunctions,
//! $$C_k = \Phi_k^\top M\, \Phi_k[T] \quad(\Phi_k(Tv) \approx \Phi_k(v)\, C_k),$$
//! and the point map it induces, `T(v) = argmin_w ‖Φ_k(w) − Φ_k(v) C_k‖`, while `k` grows from
//! `k0` to `k1`. Spectral upsampling turns an approximately right map into a smooth,
//! vertex-accurate one. The nearest neighbour is found by greedy descent on the mesh graph from
//! the current image (the map moves little per step), so an iteration costs O(n·k) instead of
//! the O(n²·k) of an exhaustive search.

use faer::{Accum, Mat, Par};

use crate::spectral::Eigenbasis;

/// Refines `map` (every entry ≥ 0) in place over `k0 < … < k1` eigenfunctions, growing by
/// `max(step, 15%)` per iteration.
pub fn zoomout(basis: &Eigenbasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k0: usize, k1: usize, step: usize) {
    let n = basis.num_vertices();
    let kmax = k1.min(basis.k());
    let mut k = k0.min(kmax).max(1);
    // Row-major Φ (one vertex's coefficients contiguous) for the descent, and M Φ for C.
    let rows: Vec<f64> = {
        let mut r = vec![0.0; n * kmax];
        for i in 0..kmax {
            let col = basis.evecs.col(i);
            for v in 0..n {
                r[v * kmax + i] = col[v];
            }
        }
        r
    };
    let mut mphi = Mat::<f64>::zeros(n, kmax);
    for i in 0..kmax {
        let col = basis.evecs.col(i);
        for (v, x) in mphi.col_as_slice_mut(i).iter_mut().enumerate() {
            *x = basis.mass[v] * col[v];
        }
    }
    let phi_t = basis.evecs.as_ref().subcols(0, kmax).transpose();
    loop {
        // C_k = (M Φ_k)ᵀ Φ_k[T].
        let mut phit = Mat::<f64>::zeros(n, k);
        for i in 0..k {
            for (v, x) in phit.col_as_slice_mut(i).iter_mut().enumerate() {
                *x = rows[map[v] * kmax + i];
            }
        }
        let mut c = Mat::<f64>::zeros(k, k);
        faer::linalg::matmul::matmul(c.as_mut(), Accum::Replace, mphi.as_ref().subcols(0, k).transpose(), phit.as_ref(), 1.0, Par::Seq);
        // Targets, one column per vertex: gᵀ = Cᵀ Φ_kᵀ.
        let mut gt = Mat::<f64>::zeros(k, n);
        faer::linalg::matmul::matmul(gt.as_mut(), Accum::Replace, c.transpose(), phi_t.subrows(0, k), 1.0, Par::Seq);
        let dist = |w: usize, target: &[f64]| -> f64 {
            rows[w * kmax..w * kmax + k].iter().zip(target).map(|(a, b)| (a - b) * (a - b)).sum()
        };
        for v in 0..n {
            let target = gt.col_as_slice(v);
            let w = super::greedy_descent(adjacency, map[v], |u| dist(u, target)).0;
            map[v] = w;
        }
        if k >= kmax {
            break;
        }
        // Grow by `step` or 15%, whichever is more: the cost per step is O(n·k²).
        k = (k + step).max(k * 23 / 20).min(kmax);
    }
}
