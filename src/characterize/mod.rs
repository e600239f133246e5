//! Symmetry characterization (paper §6): where a symmetry sits on the 1-D symmetry space, and
//! what kind of transformation it is.
//!
//! **Complexity** (the paper's inner product `⟨W, C⟩`, normalized so it does not depend on the
//! region's size): with the inverted Gaussian weight `W_ij = 1 − exp(−(i−j)²/(2s²))`, zero on the
//! diagonal (Pokrass et al. 2013),
//! $$\mathrm{complexity}(C) = \frac{\sum_{ij} W_{ij}\,|C_{ij}|}{\lVert C\rVert_F}.$$
//! A perfect isometry with a simple spectrum has a diagonal `C` and complexity 0; mixing of
//! eigenfunctions by pose changes, repeated eigenvalues or partiality moves a symmetry along the
//! line. The paper calls the induced distance a semi-metric (no triangle inequality).
//!
//! **Order**: the smallest `m ≤ max_order` with `T^m ≈ id` on the region (2 for a reflection-like
//! involution, n for a rotation of an n-fold shape), the tolerance of an orbit of `m` steps
//! `min(m, 2)` times a step's. **Distortion**: mean `|d(x,y) − d(Tx,Ty)|`
//! over anchor pairs, divided by the diameter. **Displacement**: mean `d(v, Tv)` over the region
//! divided by the diameter (near 0 for the identity, which always fits and is rejected).

use faer::Mat;

pub mod continuous;
pub use continuous::{continuous_symmetry, Continuous, ContinuousParams};

use crate::distance::BiharmonicEmbedding;

/// `Σ W_ij |C_ij| / ‖C‖_F` with `W_ij = 1 − exp(−(i−j)²/(2 width²))`.
pub fn complexity(c: &Mat<f64>, width: f64) -> f64 {
    let mut num = 0.0;
    let mut fro = 0.0;
    for j in 0..c.ncols() {
        for i in 0..c.nrows() {
            let d = i as f64 - j as f64;
            num += (1.0 - (-d * d / (2.0 * width * width)).exp()) * c[(i, j)].abs();
            fro += c[(i, j)] * c[(i, j)];
        }
    }
    if fro > 0.0 {
        num / fro.sqrt()
    } else {
        0.0
    }
}

/// Smallest `m` in `1..=max_order` with `T^m(v)` within `min(m, 2) · tol` of `v` for at least
/// 80% of the probe vertices whose orbit stays in the region; 0 if none. (Until session 34 the
/// tolerance grew as `m · tol`: at `m = 8` it reached 0.48 of the biharmonic diameter with the
/// default `accept`, and sloppy front↔back maps of the round-legged directed quadruped, whose
/// square is not near the identity, were reported as rotations of order 8. Growing it as
/// `√m · tol` instead turned 27 maps of order 2 on shared/data into orders 0 to 12.)
pub fn order(map: &[i64], probes: &[usize], emb: &BiharmonicEmbedding, tol: f64, max_order: usize) -> usize {
    for m in 1..=max_order {
        let mut ok = 0;
        let mut total = 0;
        for &v in probes {
            let mut w = v as i64;
            for _ in 0..m {
                if w < 0 {
                    break;
                }
                w = map[w as usize];
            }
            if w < 0 {
                continue;
            }
            total += 1;
            // Errors accumulate along the orbit: allow `tol` per step, up to two.
            if emb.dist(v, w as usize) <= tol * m.min(2) as f64 {
                ok += 1;
            }
        }
        if total > 0 && ok * 5 >= total * 4 {
            return m;
        }
    }
    0
}

/// Mean `|d(x,y) − d(Tx,Ty)|` over pairs of anchors, divided by `diameter`.
pub fn distortion(anchors: &[(usize, usize)], emb: &BiharmonicEmbedding, diameter: f64) -> f64 {
    distortion_between(anchors, emb, emb, diameter)
}

/// [`distortion`] of a map between two shapes: `d` of the sources in `src_emb`, of the
/// targets in `dst_emb` (the same embedding for a self-map).
pub fn distortion_between(anchors: &[(usize, usize)], src_emb: &BiharmonicEmbedding, dst_emb: &BiharmonicEmbedding, diameter: f64) -> f64 {
    let src: Vec<usize> = anchors.iter().map(|a| a.0).collect();
    let dst: Vec<usize> = anchors.iter().map(|a| a.1).collect();
    let ds = src_emb.between(&src, &src);
    let dt = dst_emb.between(&dst, &dst);
    let mut sum = 0.0;
    let mut count = 0;
    for i in 0..src.len() {
        for j in 0..i {
            sum += (ds[(i, j)] - dt[(i, j)]).abs();
            count += 1;
        }
    }
    if count == 0 {
        0.0
    } else {
        sum / count as f64 / diameter
    }
}

/// Mean `|d(x,y) − d(Tx,Ty)|` over pairs of probe vertices both in the region, divided by
/// `diameter`: an unbiased isometry error (anchors were selected for fitting well).
pub fn sample_distortion(map: &[i64], probes: &[usize], emb: &BiharmonicEmbedding, diameter: f64) -> f64 {
    let src: Vec<usize> = probes.iter().copied().filter(|&v| map[v] >= 0).collect();
    if src.len() < 2 {
        return f64::INFINITY;
    }
    let dst: Vec<usize> = src.iter().map(|&v| map[v] as usize).collect();
    distortion(&src.iter().copied().zip(dst).collect::<Vec<_>>(), emb, diameter)
}

/// Mean `d(v, T v)` over the mapped probe vertices, divided by `diameter`.
pub fn displacement(map: &[i64], probes: &[usize], emb: &BiharmonicEmbedding, diameter: f64) -> f64 {
    let moved: Vec<f64> = probes.iter().filter(|&&v| map[v] >= 0).map(|&v| emb.dist(v, map[v] as usize)).collect();
    if moved.is_empty() {
        0.0
    } else {
        moved.iter().sum::<f64>() / moved.len() as f64 / diameter
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complexity_is_zero_for_diagonal_and_grows_off_diagonal() {
        let diag = Mat::<f64>::from_fn(10, 10, |i, j| if i == j { if i % 2 == 0 { 1.0 } else { -1.0 } } else { 0.0 });
        assert_eq!(complexity(&diag, 1.0), 0.0);
        let near = Mat::<f64>::from_fn(10, 10, |i, j| if i == j { 1.0 } else if i + 1 == j { 0.3 } else { 0.0 });
        let far = Mat::<f64>::from_fn(10, 10, |i, j| if i == j { 1.0 } else if i + 5 == j { 0.3 } else { 0.0 });
        let (a, b) = (complexity(&near, 1.0), complexity(&far, 1.0));
        assert!(a > 0.0 && b > a, "{a} {b}");
        // Scale-free.
        let scaled = Mat::<f64>::from_fn(10, 10, |i, j| 3.0 * near[(i, j)]);
        assert!((complexity(&scaled, 1.0) - a).abs() < 1e-12);
    }
}
