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

/// Refines `map` (every entry ≥ 0) in place over `k0, k0+step, …, k1` eigenfunctions.
pub fn zoomout(basis: &Eigenbasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k0: usize, k1: usize, step: usize) {
    let n = basis.num_vertices();
    let k1 = k1.min(basis.k());
    let mut k = k0.min(k1);
    loop {
        // C_k = (M Φ_k)ᵀ Φ_k[T].
        let mphi = Mat::<f64>::from_fn(n, k, |v, i| basis.mass[v] * basis.evecs[(v, i)]);
        let phit = Mat::<f64>::from_fn(n, k, |v, i| basis.evecs[(map[v], i)]);
        let mut c = Mat::<f64>::zeros(k, k);
        faer::linalg::matmul::matmul(c.as_mut(), Accum::Replace, mphi.transpose(), phit.as_ref(), 1.0, Par::Seq);
        // Targets g_v = Φ_k(v) C_k.
        let phi = basis.evecs.as_ref().subcols(0, k);
        let mut g = Mat::<f64>::zeros(n, k);
        faer::linalg::matmul::matmul(g.as_mut(), Accum::Replace, phi, c.as_ref(), 1.0, Par::Seq);
        // Row-major copy of Φ_k for cache-friendly distance evaluations.
        let rows: Vec<f64> = (0..n).flat_map(|v| (0..k).map(move |i| (v, i))).map(|(v, i)| basis.evecs[(v, i)]).collect();
        let dist = |w: usize, target: &[f64]| -> f64 {
            rows[w * k..(w + 1) * k].iter().zip(target).map(|(a, b)| (a - b) * (a - b)).sum()
        };
        let mut target = vec![0.0; k];
        for v in 0..n {
            for (i, t) in target.iter_mut().enumerate() {
                *t = g[(v, i)];
            }
            let mut w = map[v];
            let mut best = dist(w, &target);
            loop {
                let mut moved = false;
                for &u in &adjacency.1[adjacency.0[w]..adjacency.0[w + 1]] {
                    let d = dist(u as usize, &target);
                    if d < best {
                        best = d;
                        w = u as usize;
                        moved = true;
                    }
                }
                if !moved {
                    break;
                }
            }
            map[v] = w;
        }
        if k >= k1 {
            break;
        }
        k = (k + step).min(k1);
    }
}
