//! Wave kernel signature (Aubry, Schlickewei & Cremers 2011), as used by the paper (§4.2) to
//! find *good voters*: point pairs with similar local intrinsic geometry.
//!
//! For log-energies `e_1 < … < e_E`, evenly spaced between `log λ_1` and `log λ_{k−1}` and shrunk
//! by `2σ` at both ends, with `σ = WKS_VARIANCE · (e_2 − e_1)`:
//! $$\mathrm{WKS}(x, e) = \frac{\sum_{i\ge1} \varphi_i(x)^2\, \exp\!\big(-\tfrac{(e-\log\lambda_i)^2}{2\sigma^2}\big)}{\sum_{i\ge1}\exp\!\big(-\tfrac{(e-\log\lambda_i)^2}{2\sigma^2}\big)} \cdot \text{area}$$
//! The constant eigenvector is skipped. With M-orthonormal `φ_i` each energy's signature has
//! area-weighted mean 1 (`Σ_x m_x WKS(x, e) = area`), so signatures are scale- and
//! resolution-free and comparable across energies.

use faer::Mat;

use crate::spectral::Eigenbasis;

/// Parameters of [`wks`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct WksParams {
    /// Number of energies `E` (default 100).
    pub energies: usize,
    /// `σ` in units of the energy step (default 7, Aubry et al.).
    pub variance: f64,
}

impl Default for WksParams {
    fn default() -> Self {
        WksParams { energies: 100, variance: 7.0 }
    }
}

/// `(n, E)` wave kernel signatures of every vertex.
pub fn wks(basis: &Eigenbasis, params: &WksParams) -> Mat<f64> {
    let n = basis.num_vertices();
    let k = basis.k();
    let ne = params.energies.max(2);
    assert!(k >= 3, "WKS needs at least 3 eigenpairs");
    // Clamp tiny eigenvalues (numerically zero modes) away from log(0).
    let loglam: Vec<f64> = basis.evals[1..].iter().map(|&l| l.max(1e-12 * basis.evals[k - 1]).ln()).collect();
    let (lo, hi) = (loglam[0], loglam[loglam.len() - 1]);
    let step0 = (hi - lo) / ne as f64;
    let sigma = params.variance * step0;
    let (lo, hi) = (lo + 2.0 * sigma, hi - 2.0 * sigma);
    let (lo, hi) = if lo < hi { (lo, hi) } else { (loglam[0], loglam[loglam.len() - 1]) };
    let energies: Vec<f64> = (0..ne).map(|j| lo + (hi - lo) * j as f64 / (ne - 1) as f64).collect();
    // Filter weights (k−1, E), normalized per energy.
    let mut weights = Mat::<f64>::zeros(k - 1, ne);
    for (j, &e) in energies.iter().enumerate() {
        let mut total = 0.0;
        for (i, &l) in loglam.iter().enumerate() {
            let w = (-(e - l).powi(2) / (2.0 * sigma * sigma)).exp();
            weights[(i, j)] = w;
            total += w;
        }
        for i in 0..k - 1 {
            weights[(i, j)] *= basis.area / total.max(f64::MIN_POSITIVE);
        }
    }
    let sq = Mat::<f64>::from_fn(n, k - 1, |v, i| basis.evecs[(v, i + 1)].powi(2));
    let mut out = Mat::<f64>::zeros(n, ne);
    faer::linalg::matmul::matmul(out.as_mut(), faer::Accum::Replace, sq.as_ref(), weights.as_ref(), 1.0, faer::Par::Seq);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{shapes, EigenParams};

    #[test]
    fn wks_has_unit_mean_per_energy_and_is_positive() {
        let mesh = shapes::bumpy_torus(14);
        let p = EigenParams { k: 30, ..Default::default() };
        let basis = Eigenbasis::compute(&mesh, &p).unwrap();
        let d = wks(&basis, &WksParams::default());
        assert_eq!(d.ncols(), 100);
        for j in 0..d.ncols() {
            let mean: f64 = (0..d.nrows()).map(|v| basis.mass[v] * d[(v, j)]).sum::<f64>() / basis.area;
            assert!((mean - 1.0).abs() < 1e-9, "energy {j}: mean {mean}");
            assert!((0..d.nrows()).all(|v| d[(v, j)] >= 0.0));
        }
    }

    #[test]
    fn wks_is_invariant_under_the_mirror_of_the_icosphere() {
        // The icosphere is symmetric under x -> -x with exact vertex correspondence, but its
        // eigenvectors in a degenerate eigenspace are arbitrary: WKS, a sum over whole
        // eigenspaces when σ spans them, must still agree at mirror vertices.
        let mesh = shapes::icosphere(3);
        let p = EigenParams { k: 36, ..Default::default() };
        let basis = Eigenbasis::compute(&mesh, &p).unwrap();
        let d = wks(&basis, &WksParams::default());
        let mirror = shapes::mirror_map(&mesh, 0);
        for v in 0..mesh.num_vertices() {
            for j in 0..d.ncols() {
                let (a, b) = (d[(v, j)], d[(mirror[v] as usize, j)]);
                assert!((a - b).abs() < 1e-6 * (1.0 + a.abs()), "v {v} e {j}: {a} vs {b}");
            }
        }
    }
}
