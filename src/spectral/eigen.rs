//! The smallest generalized eigenpairs `L φ = λ M φ` by shift-invert block Lanczos.
//!
//! With `M` the lumped (diagonal, positive) mass and `σ > 0`, the operator
//! $$\mathrm{Op} = (L + \sigma M)^{-1} M$$
//! is self-adjoint in the `M` inner product `⟨x, y⟩_M = xᵀ M y`, with eigenvalues
//! `θ = 1 / (λ + σ)`: the smallest λ become the largest, well separated θ. We run a block Lanczos
//! process on `Op` (Golub & Underwood 1977) with
//!
//! - one sparse Cholesky factorization of `L + σM` (faer, supernodal, AMD ordering); each Lanczos
//!   step is one block solve with `b = 8` interleaved right-hand sides ([`super::factor`]), where
//!   single-vector solves would be memory bound;
//! - the block lives interleaved (row `r` = entry `r` of the 8 vectors) while it is built, so the
//!   products with the tall basis stream it once without packing ([`super::kernels`]);
//! - **full M-reorthogonalisation**: after the Lanczos recurrence (projection on the previous
//!   and current block), one block classical Gram–Schmidt pass against the whole basis, repeated
//!   while it removes a large part of a column (the Daniel–Gragg–Kaufman–Stewart criterion;
//!   "twice is enough", Giraud et al. 2005), so the basis stays M-orthonormal to machine
//!   precision and the projected matrix `H = Vᵀ M Op V` is computed, not assumed; each new block
//!   is orthonormalised by Cholesky QR twice (MGS with random replacement on breakdown); the
//!   passes over the tall basis are memory-bound, so on two cores each runs as two
//!   independent halves (coefficients by columns, updates by rows), bit-identical to one
//!   thread ([`EigenParams::parallel`]);
//! - **explicit deflation** of the constant mode `u₀ = 1/√area` (λ₀ = 0), projected out of every
//!   vector, so no Krylov dimension is spent on it and λ₀ is exactly 0;
//! - **thick restarts** (Wu & Simon 2000; Stewart's Krylov–Schur): when the basis is full, the
//!   best `p` Ritz vectors and the residual block are kept, with the arrowhead coupling
//!   `R·S_last` in `H`, and the process continues;
//! - convergence on the *original* problem's residual, estimated cheaply from the Ritz residual
//!   `Op y − θ y = Q R s`: `Lφ − λMφ = −(L + σM) Q R s / θ`, one sparse product with the residual
//!   block per restart; the tolerance is floored at the attainable `10³ ε ‖L‖∞ n / area`;
//! - a measured check of every returned pair, `‖Lφ − λMφ‖ / ‖Mφ‖` and `ΦᵀMΦ − I`, reported in
//!   [`EigenInfo`]; if it misses the tolerance the iteration continues with a 10× tighter
//!   estimate. We never trust an eigensolver blindly.
//!
//! Blocks (size ≥ the largest multiplicity, 7 on a sphere at l = 3) find every copy of a repeated
//! eigenvalue; a single-vector Lanczos finds later copies only through rounding noise.
//!
//! Small problems (n ≤ [`DENSE_LIMIT`] or a Krylov space that would not fit) use a dense
//! symmetric eigensolver on `M^{-1/2} L M^{-1/2}` instead, which is exact and faster there.

use faer::linalg::matmul::matmul;
use faer::reborrow::ReborrowMut;
use faer::{Accum, Mat, MatMut, MatRef, Par, Side};
use sprs::CsMat;
use std::time::Instant;

use super::factor::ShiftedCholesky;
use super::kernels::{self, Lanes, LANES};
use super::SpectralError;
use crate::random::SplitMix;

/// Below this many vertices the dense solver is used (Lanczos is faster above ~300 vertices, and
/// more accurate on badly conditioned meshes: the dense path loses ε‖M^{-1/2}LM^{-1/2}‖).
pub const DENSE_LIMIT: usize = 400;

/// Parameters of [`eigen`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct EigenParams {
    /// Number of eigenpairs, including the constant one (default 100).
    pub k: usize,
    /// Shift σ, in units of `4π / area` (the first nonzero eigenvalue of a sphere is 2 in those
    /// units). Default 0.01: small enough to separate the low spectrum, far from singular.
    pub shift: f64,
    /// Krylov basis size as a multiple of the number of wanted pairs (default 2.5, at least k + 3 blocks).
    pub basis_factor: f64,
    /// Residual tolerance: stop when every pair's estimated `‖Lφ − λMφ‖ / ‖Mφ‖` is below
    /// `tol · λ_{k−1}` (default 1e-10); the returned pairs are checked against `10·tol·λ_{k−1}`.
    pub tol: f64,
    /// Maximum number of restarts before [`SpectralError::NotConverged`] (default 200).
    pub max_restarts: usize,
    /// Seed of the random start block.
    pub seed: u64,
    /// Which solver (default [`Solver::Auto`]).
    pub solver: Solver,
    /// Run the reorthogonalisation's projections against the basis on two threads when more
    /// than one core is available (default true; results are bit-identical to one thread).
    /// They stream the tall basis from memory, and two cores stream it faster: at 50k
    /// vertices, k = 100, 0.75 → 0.47 s. (faer's multi-threaded dense kernels were measured
    /// slower than one thread on the 2-core target machines; these projections are not dense
    /// compute-bound kernels but independent halves of a memory-bound pass.)
    pub parallel: bool,
}

/// Eigensolver choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Solver {
    /// Dense for small meshes (n ≤ [`DENSE_LIMIT`]), Lanczos otherwise.
    #[default]
    Auto,
    /// Always shift-invert block Lanczos (falls back to dense only when the Krylov basis would
    /// not fit in the mesh).
    Lanczos,
    /// Always dense (O(n³): small meshes only).
    Dense,
}

impl Default for EigenParams {
    fn default() -> Self {
        EigenParams { k: 100, shift: 0.01, basis_factor: 2.5, tol: 1e-10, max_restarts: 200, seed: 0, solver: Solver::Auto, parallel: true }
    }
}

/// What the eigensolver did.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct EigenInfo {
    /// The absolute shift σ used.
    pub shift: f64,
    /// Columns pushed through `(L + σM)⁻¹` (block solves × block size).
    pub solves: usize,
    /// Thick restarts.
    pub restarts: usize,
    /// Krylov basis size used.
    pub basis: usize,
    /// Largest `‖Lφ − λMφ‖₂ / ‖Mφ‖₂` over the returned pairs.
    pub max_residual: f64,
    /// Largest `|ΦᵀMΦ − I|` entry.
    pub orthogonality: f64,
    /// Whether the dense solver was used.
    pub dense: bool,
    /// Seconds in the sparse factorization.
    pub factor_seconds: f64,
    /// Seconds in the Lanczos iteration and post-processing (all of the below).
    pub solve_seconds: f64,
    /// Of which: triangular solves with the factor.
    pub triangular_seconds: f64,
    /// Of which: reorthogonalisation.
    pub orthogonalize_seconds: f64,
    /// Of which: Rayleigh–Ritz, convergence tests and restarts.
    pub restart_seconds: f64,
    /// Of which: the final residual and orthogonality check.
    pub check_seconds: f64,
}

/// `k` smallest eigenpairs of `L φ = λ M φ` for a connected surface.
///
/// `lap`: `(n, n)` symmetric positive semi-definite with kernel `span(1)`; `mass`: `(n,)`
/// positive lumped mass; `area = Σ mass`. Returns `evals` `(k,)` ascending, `evals[0] = 0`, and
/// `evecs` `(n, k)` M-orthonormal. `progress(fraction)` returning `false` cancels.
#[allow(non_snake_case)]
pub fn eigen(
    lap: &CsMat<f64>,
    mass: &[f64],
    params: &EigenParams,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(Vec<f64>, Mat<f64>, EigenInfo), SpectralError> {
    let n = mass.len();
    let k = params.k;
    if k == 0 || k > n {
        return Err(SpectralError::TooManyEigenpairs { k, n });
    }
    assert!(lap.rows() == n && lap.cols() == n && lap.is_csc());
    let area: f64 = mass.iter().sum();
    if k == 1 {
        // The constant mode alone: nothing to iterate for.
        let evecs = Mat::<f64>::from_fn(n, 1, |_, _| 1.0 / area.sqrt());
        let (max_residual, orthogonality) = check(lap, mass, &[0.0], evecs.as_ref());
        return Ok((vec![0.0], evecs, EigenInfo { max_residual, orthogonality, ..Default::default() }));
    }
    let sigma = params.shift * 4.0 * std::f64::consts::PI / area;
    let nev = k - 1; // non-constant pairs
    let b = LANES;
    let ncv = ((params.basis_factor * nev as f64).ceil() as usize).max(nev + 3 * b);
    let ncv = ncv.div_ceil(b) * b;
    let small = n <= DENSE_LIMIT && params.solver == Solver::Auto;
    if small || params.solver == Solver::Dense || ncv + 2 * b >= n {
        return dense_eigen(lap, mass, k);
    }

    // Factorize L + σM.
    let t0 = Instant::now();
    if !progress(0.0) {
        return Err(SpectralError::Cancelled);
    }
    let factor = ShiftedCholesky::new(lap, mass, sigma)?;
    let factor_seconds = t0.elapsed().as_secs_f64();
    // Progress never goes back (see `progress_estimate`).
    let mut reported = FACTOR_SHARE;
    if !progress(reported) {
        return Err(SpectralError::Cancelled);
    }
    let t1 = Instant::now();

    let u0 = 1.0 / area.sqrt(); // constant mode value, ‖u0‖_M = 1
    let ws = Workspace { mass, u0 };
    // ‖Mφ‖₂ of an M-unit vector is about √(Σm²/Σm); used only in the convergence *estimate*,
    // the final check measures it exactly.
    let m_scale = (mass.iter().map(|m| m * m).sum::<f64>() / area).sqrt();
    // Attainable accuracy: rounding in L alone leaves a residual of about ε‖L‖∞‖φ‖₂/‖Mφ‖₂,
    // with ‖φ‖₂/‖Mφ‖₂ ≈ n/area for an M-unit φ. Needle triangles make ‖L‖ huge (cotangents
    // up to 1/MOLLIFY_REL): their tolerance is floored there instead of never converging.
    let l_norm = lap.outer_iterator().map(|c| c.iter().map(|(_, x)| x.abs()).sum::<f64>()).fold(0.0, f64::max);
    let floor = 1e3 * f64::EPSILON * l_norm * n as f64 / area;

    // The basis grows in blocks until at least ncv columns are closed (Op applied), so it can
    // hold up to ncv + b - 1 closed columns plus the open block.
    let cap = ncv + 2 * b;
    let mut V = Mat::<f64>::zeros(n, cap);
    let mut H = Mat::<f64>::zeros(cap, cap);
    let mut rng = SplitMix::new(params.seed ^ 0x9E37_79B9_7F4A_7C15);
    for j in 0..b {
        for x in V.col_as_slice_mut(j) {
            *x = rng.normal();
        }
    }
    ws.deflate(V.as_mut().subcols_mut(0, b));
    ws.orthonormalize_block(&mut V, 0, b, &mut rng);

    let mut info = EigenInfo { shift: sigma, basis: ncv, factor_seconds, ..Default::default() };
    let mut nv = b; // columns in the basis; the last block is "open" (Op not yet applied)
    let mut restart_start = 0; // first open block after a (re)start
    // The block being built, interleaved (row r holds entry r of the b vectors), and scratch.
    let mut W: Vec<Lanes> = vec![[0.0; LANES]; n];
    let mut coeff: Vec<Lanes> = vec![[0.0; LANES]; cap];
    let mut scratch = Scratch { parallel: params.parallel && crate::parallel::available(), ..Default::default() };
    let mut R_last = Mat::<f64>::zeros(b, b);
    let mut converged_best = 0;
    let mut tol = params.tol;

    loop {
        // Expand the basis until at least ncv columns are closed.
        while nv - b < ncv {
            let j0 = nv - b;
            // W = Op V_j = (L + σM)⁻¹ M V_j, deflated.
            gather(V.as_ref(), j0, b, &mut W);
            for (w, &m) in W.iter_mut().zip(mass) {
                *w = w.map(|x| m * x);
            }
            let ts = Instant::now();
            factor.solve(&mut W, &mut scratch.solve);
            info.solves += b;
            info.triangular_seconds += ts.elapsed().as_secs_f64();
            let ts = Instant::now();
            ws.deflate_lanes(&mut W);
            // Orthogonalisation: first the Lanczos recurrence (the previous and current block;
            // after a restart, everything kept), then a full block classical Gram–Schmidt pass
            // against the whole basis, repeated when it removed a large part of a column
            // (Daniel–Gragg–Kaufman–Stewart criterion): full reorthogonalisation at the price of
            // about one pass.
            let coeff = &mut coeff[..nv];
            coeff.fill([0.0; LANES]);
            let lo = if j0 == restart_start { 0 } else { j0 - b };
            project_out(V.as_ref().subcols(lo, nv - lo), &mut W, mass, &mut coeff[lo..], &mut scratch);
            for _pass in 0..3 {
                let before = kernels::m_dots(&W, &W, mass);
                project_out(V.as_ref().subcols(0, nv), &mut W, mass, coeff, &mut scratch);
                let after = kernels::m_dots(&W, &W, mass);
                // Squared norms: ‖after‖ > 0.7 ‖before‖.
                if before.iter().zip(&after).all(|(b, a)| *a > 0.49 * b) {
                    break;
                }
            }
            for (i, c) in coeff.iter().enumerate() {
                for t in 0..b {
                    H[(i, j0 + t)] = c[t];
                }
            }
            // W = Q R: Cholesky QR twice on the interleaved block; the column-wise path
            // (with breakdown handling) when the block is nearly rank deficient.
            let R = match ws.cholqr2_lanes(&mut W) {
                Some(R) => {
                    scatter(&W, &mut V, nv);
                    R
                }
                None => {
                    scatter(&W, &mut V, nv);
                    ws.orthonormalize_block(&mut V, nv, b, &mut rng)
                }
            };
            H.as_mut().submatrix_mut(nv, j0, b, b).copy_from(R.as_ref());
            R_last.copy_from(R.as_ref());
            info.orthogonalize_seconds += ts.elapsed().as_secs_f64();
            nv += b;
            reported = reported.max(progress_estimate(converged_best, nev, info.solves, ncv));
            if !progress(reported) {
                return Err(SpectralError::Cancelled);
            }
        }

        // Rayleigh–Ritz on the symmetrised projected matrix of the m closed columns.
        let m = nv - b;
        let ts = Instant::now();
        let Hs = Mat::<f64>::from_fn(m, m, |i, j| 0.5 * (H[(i, j)] + H[(j, i)]));
        let evd = Hs.self_adjoint_eigen(Side::Lower).map_err(|e| SpectralError::Factorization(format!("{e:?}")))?;
        // Descending θ.
        let theta: Vec<f64> = (0..m).rev().map(|i| evd.S()[i]).collect();
        let S = Mat::<f64>::from_fn(m, m, |i, j| evd.U()[(i, m - 1 - j)]);
        // Ritz residual in the shift-inverted problem: Op y − θ y = Q (R S_last s) = Q c.
        let mut coupling = Mat::<f64>::zeros(b, m);
        matmul(coupling.as_mut(), Accum::Replace, R_last.as_ref(), S.as_ref().subrows(m - b, b), 1.0, Par::Seq);
        // In the original problem, Lφ − λMφ = −(L + σM) Q c / θ: with Z = (L + σM) Q and
        // G = ZᵀZ, ‖Lφ − λMφ‖ = √(cᵀGc)/θ, at the cost of one sparse product per restart.
        gather(V.as_ref(), m, b, &mut scratch.mw);
        kernels::sparse_mul(lap, &scratch.mw, &mut scratch.solve);
        let mut G = Mat::<f64>::zeros(b, b);
        for ((z, q), &w) in scratch.solve.iter().zip(&scratch.mw).zip(mass) {
            let z: Lanes = std::array::from_fn(|t| z[t] + sigma * w * q[t]);
            for r in 0..b {
                for s in 0..b {
                    G[(r, s)] += z[r] * z[s];
                }
            }
        }
        let lambda_max = 1.0 / theta[nev - 1] - sigma;
        let estimate = |i: usize| {
            let c = coupling.col(i);
            let mut q = 0.0;
            for r in 0..b {
                for s in 0..b {
                    q += c[r] * G[(r, s)] * c[s];
                }
            }
            q.max(0.0).sqrt() / theta[i] / m_scale
        };
        let threshold = (tol * lambda_max).max(floor);
        let converged = (0..nev).take_while(|&i| estimate(i) <= threshold).count();
        converged_best = converged_best.max(converged);
        if converged == nev || info.restarts >= params.max_restarts {
            if converged < nev {
                return Err(SpectralError::NotConverged { converged: converged + 1, wanted: k });
            }
            // Ritz vectors Y = V S[:, :nev] after the constant mode.
            let mut Y = Mat::<f64>::zeros(n, k);
            Y.col_as_slice_mut(0).fill(u0);
            {
                // Two halves of the rows on two threads when allowed (each row as on one).
                let (vq, sq) = (V.as_ref().subcols(0, m), S.as_ref().subcols(0, nev));
                if scratch.parallel {
                    let (top, bottom) = Y.as_mut().subcols_mut(1, nev).split_at_row_mut(n / 2);
                    let (vt, vb) = vq.split_at_row(n / 2);
                    crate::parallel::join(
                        || matmul(bottom, Accum::Replace, vb, sq, 1.0, Par::Seq),
                        || matmul(top, Accum::Replace, vt, sq, 1.0, Par::Seq),
                    );
                } else {
                    matmul(Y.as_mut().subcols_mut(1, nev), Accum::Replace, vq, sq, 1.0, Par::Seq);
                }
            }
            let mut evals: Vec<f64> = std::iter::once(0.0).chain(theta[..nev].iter().map(|t| 1.0 / t - sigma)).collect();
            for j in 1..k {
                normalize_sign(Y.col_as_slice_mut(j));
            }
            let tc = Instant::now();
            let (res, orth) = check(lap, mass, &evals, Y.as_ref());
            info.check_seconds += tc.elapsed().as_secs_f64();
            // The estimate uses an average ‖Mφ‖; trust only the measured residual.
            if res <= 10.0 * (params.tol * lambda_max).max(floor) || tol < params.tol * 1e-4 {
                info.solve_seconds = t1.elapsed().as_secs_f64();
                info.max_residual = res;
                info.orthogonality = orth;
                for e in &mut evals[1..] {
                    *e = e.max(0.0);
                }
                return Ok((evals, Y, info));
            }
            tol *= 0.1;
        }

        // Thick restart: keep p Ritz vectors and the residual block.
        let p = (nev + (ncv - nev) / 2).min(ncv - b);
        rotate_in_place(&mut V, m, S.as_ref().subcols(0, p), scratch.parallel);
        let resid_block = V.as_ref().subcols(m, b).to_owned();
        V.as_mut().subcols_mut(p, b).copy_from(resid_block.as_ref());
        H.fill(0.0);
        for i in 0..p {
            H[(i, i)] = theta[i];
        }
        H.as_mut().submatrix_mut(p, 0, b, p).copy_from(coupling.as_ref().subcols(0, p));
        nv = p + b;
        restart_start = p;
        info.restarts += 1;
        info.restart_seconds += ts.elapsed().as_secs_f64();
    }
}

/// Share of the eigensolve's progress given to the factorization.
const FACTOR_SHARE: f64 = 0.05;

/// Progress fraction: the larger of the work done (operator applications against the usual
/// total, one full basis plus half as many again for restarts) and the pairs converged. It
/// used to count converged pairs alone, which stay 0 through the first basis, most of the
/// work: a 60k-vertex mesh sat at 0% for 9 s in MeshLab (issue 16, item 20).
fn progress_estimate(converged: usize, nev: usize, solves: usize, ncv: usize) -> f64 {
    let work = solves as f64 / (1.5 * ncv as f64).max(1.0);
    let done = converged as f64 / (nev as f64).max(1.0);
    (FACTOR_SHARE + (1.0 - FACTOR_SHARE) * work.max(done)).clamp(0.0, 0.99)
}

struct Workspace<'a> {
    mass: &'a [f64],
    u0: f64,
}

impl Workspace<'_> {
    /// Removes the constant mode from every column: x ← x − u₀ ⟨u₀, x⟩_M.
    fn deflate(&self, mut x: MatMut<'_, f64>) {
        for j in 0..x.ncols() {
            let mut col = x.rb_mut().col_mut(j);
            let mut dot = 0.0;
            for i in 0..col.nrows() {
                dot += self.mass[i] * col[i];
            }
            let c = dot * self.u0 * self.u0;
            for i in 0..col.nrows() {
                col[i] -= c;
            }
        }
    }

    /// The same for an interleaved block.
    fn deflate_lanes(&self, x: &mut [Lanes]) {
        let mut dot = [0.0; LANES];
        for (row, &m) in x.iter().zip(self.mass) {
            for t in 0..LANES {
                dot[t] += m * row[t];
            }
        }
        let c = dot.map(|d| d * self.u0 * self.u0);
        for row in x.iter_mut() {
            for t in 0..LANES {
                row[t] -= c[t];
            }
        }
    }

    /// Cholesky QR twice on an interleaved block (see [`Self::orthonormalize_block`]):
    /// `W ← Q` with `W = Q R`, `R` returned; `None` (and `W` unchanged) when the Gram matrix is
    /// too ill-conditioned for it.
    fn cholqr2_lanes(&self, w: &mut [Lanes]) -> Option<Mat<f64>> {
        let b = LANES;
        let original = w.to_vec();
        let mut r_total = Mat::<f64>::identity(b, b);
        for _pass in 0..2 {
            let gram = kernels::m_gram(w, self.mass);
            let g = Mat::<f64>::from_fn(b, b, |i, j| gram[i][j]);
            let diag_max = (0..b).map(|i| g[(i, i)]).fold(0.0f64, f64::max);
            let l = match g.llt(Side::Lower) {
                Ok(c) => c.L().to_owned(),
                Err(_) => {
                    w.copy_from_slice(&original);
                    return None;
                }
            };
            let (lo, hi) = (0..b).fold((f64::INFINITY, 0.0f64), |(lo, hi), i| (lo.min(l[(i, i)]), hi.max(l[(i, i)])));
            if !(diag_max > 0.0 && lo > 1e-6 * hi) {
                w.copy_from_slice(&original);
                return None;
            }
            // Q = W L⁻ᵀ: each row q = L⁻¹ w, i.e. q = Σ_s w[s] · (column s of L⁻¹).
            let mut inv = Mat::<f64>::identity(b, b);
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(l.as_ref(), inv.as_mut(), Par::Seq);
            let cols: Vec<Lanes> = (0..b).map(|s| std::array::from_fn(|t| inv[(t, s)])).collect();
            kernels::mul_rows(w, &cols);
            let mut next = Mat::<f64>::zeros(b, b);
            matmul(next.as_mut(), Accum::Replace, l.transpose(), r_total.as_ref(), 1.0, Par::Seq);
            r_total = next;
        }
        Some(r_total)
    }

    /// M-orthonormalizes columns `j0..j0+b` of `v` in place and returns the `(b, b)`
    /// upper-triangular `R` with `W = Q R`.
    ///
    /// Cholesky QR twice (CholQR2, Yamamoto et al. 2015: orthogonal to machine precision when
    /// the block's condition number is below ~1e7, and gemm-fast); when the block is nearly
    /// rank deficient (the Krylov space became invariant) it falls back to modified
    /// Gram–Schmidt, replacing a vanishing column by a random vector orthogonal to everything,
    /// with a zero column in `R`.
    fn orthonormalize_block(&self, v: &mut Mat<f64>, j0: usize, b: usize, rng: &mut SplitMix) -> Mat<f64> {
        let mut r_total = Mat::<f64>::identity(b, b);
        for _pass in 0..2 {
            let block = v.as_ref().subcols(j0, b);
            let mw = Mat::<f64>::from_fn(block.nrows(), b, |i, j| self.mass[i] * block[(i, j)]);
            let mut g = Mat::<f64>::zeros(b, b);
            matmul(g.as_mut(), Accum::Replace, block.transpose(), mw.as_ref(), 1.0, Par::Seq);
            let diag_max = (0..b).map(|i| g[(i, i)]).fold(0.0f64, f64::max);
            let chol = g.llt(Side::Lower);
            let ok = match &chol {
                Ok(c) => {
                    let l = c.L();
                    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
                    for i in 0..b {
                        lo = lo.min(l[(i, i)]);
                        hi = hi.max(l[(i, i)]);
                    }
                    diag_max > 0.0 && lo > 1e-6 * hi
                }
                Err(_) => false,
            };
            if !ok {
                let r = self.orthonormalize_block_mgs(v, j0, b, rng);
                let mut out = Mat::<f64>::zeros(b, b);
                matmul(out.as_mut(), Accum::Replace, r.as_ref(), r_total.as_ref(), 1.0, Par::Seq);
                return out;
            }
            let l = chol.unwrap().L().to_owned();
            // Q = W L⁻ᵀ: solve Q Lᵀ = W, i.e. L Qᵀ = Wᵀ, column by column of Qᵀ.
            let mut wt = v.as_ref().subcols(j0, b).transpose().to_owned();
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(l.as_ref(), wt.as_mut(), Par::Seq);
            v.as_mut().subcols_mut(j0, b).copy_from(wt.transpose());
            // R accumulates as R = Lᵀ_2 Lᵀ_1.
            let mut next = Mat::<f64>::zeros(b, b);
            matmul(next.as_mut(), Accum::Replace, l.transpose(), r_total.as_ref(), 1.0, Par::Seq);
            r_total = next;
        }
        r_total
    }

    // `!(x > y)` on purpose: also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn orthonormalize_block_mgs(&self, v: &mut Mat<f64>, j0: usize, b: usize, rng: &mut SplitMix) -> Mat<f64> {
        let mass = self.mass;
        let mut r = Mat::<f64>::zeros(b, b);
        for c in 0..b {
            let j = j0 + c;
            let before = m_norm(v.col_as_slice(j), mass);
            for _pass in 0..2 {
                for q in 0..c {
                    let d = m_dot(v.col_as_slice(j0 + q), v.col_as_slice(j), mass);
                    r[(q, c)] += d;
                    axpy_cols(v, j, j0 + q, -d);
                }
            }
            let mut nrm = m_norm(v.col_as_slice(j), mass);
            if !(nrm > 1e-10 * before) || nrm == 0.0 {
                // Breakdown: replace by a fresh random direction orthogonal to the basis.
                for q in 0..c {
                    r[(q, c)] = 0.0;
                }
                for x in v.col_as_slice_mut(j) {
                    *x = rng.normal();
                }
                for _pass in 0..2 {
                    self.deflate(v.as_mut().subcols_mut(j, 1));
                    for q in 0..j {
                        let d = m_dot(v.col_as_slice(q), v.col_as_slice(j), mass);
                        axpy_cols(v, j, q, -d);
                    }
                }
                nrm = m_norm(v.col_as_slice(j), mass);
                for x in v.col_as_slice_mut(j) {
                    *x /= nrm;
                }
                continue;
            }
            r[(c, c)] = nrm;
            for x in v.col_as_slice_mut(j) {
                *x /= nrm;
            }
        }
        r
    }
}

/// The interleaved block of columns `j0 .. j0 + width` of `v` (`width ≤ LANES`; the other lanes
/// are zero).
fn gather(v: MatRef<'_, f64>, j0: usize, width: usize, w: &mut Vec<Lanes>) {
    w.clear();
    w.resize(v.nrows(), [0.0; LANES]);
    for t in 0..width {
        for (row, &x) in w.iter_mut().zip(v.col(j0 + t).try_as_col_major().expect("column-major").as_slice()) {
            row[t] = x;
        }
    }
}

/// Columns `j0 .. j0 + LANES` of `v` ← the interleaved block `w`.
fn scatter(w: &[Lanes], v: &mut Mat<f64>, j0: usize) {
    for t in 0..LANES {
        for (x, row) in v.col_as_slice_mut(j0 + t).iter_mut().zip(w) {
            *x = row[t];
        }
    }
}

/// Reused buffers of the iteration.
#[derive(Default)]
struct Scratch {
    solve: Vec<Lanes>,
    mw: Vec<Lanes>,
    c: Vec<Lanes>,
    /// Whether the projections run on two threads ([`EigenParams::parallel`]).
    parallel: bool,
}

/// W ← W − V (Vᵀ M W) for an interleaved block `w`, accumulating the coefficients into `coeff`
/// (`V.ncols()` rows). Two streaming passes over `V` ([`kernels::gram`], [`kernels::update`]).
fn project_out(v: MatRef<'_, f64>, w: &mut [Lanes], mass: &[f64], coeff: &mut [Lanes], scratch: &mut Scratch) {
    if v.ncols() == 0 {
        return;
    }
    kernels::scale_rows(w, mass, &mut scratch.mw);
    scratch.c.clear();
    scratch.c.resize(v.ncols(), [0.0; LANES]);
    // Two cores stream the tall basis faster than one (these are memory-bound passes): the
    // coefficients over two halves of its columns, the update over two halves of its rows.
    // Every coefficient and every row is computed exactly as on one thread.
    if scratch.parallel && v.ncols() >= 32 {
        let h = v.ncols() / 2;
        let (c1, c2) = scratch.c.split_at_mut(h);
        let mw = &scratch.mw;
        crate::parallel::join(|| kernels::gram(v.subcols(0, h), mw, c1), || kernels::gram(v.subcols(h, v.ncols() - h), mw, c2));
        let r = v.nrows() / 2;
        let (w1, w2) = w.split_at_mut(r);
        let c = &scratch.c;
        crate::parallel::join(|| kernels::update(v.subrows(0, r), w1, c), || kernels::update(v.subrows(r, v.nrows() - r), w2, c));
    } else {
        kernels::gram(v, &scratch.mw, &mut scratch.c);
        kernels::update(v, w, &scratch.c);
    }
    for (acc, c) in coeff.iter_mut().zip(&scratch.c) {
        for t in 0..LANES {
            acc[t] += c[t];
        }
    }
}



/// `V[:, 0..p] ← V[:, 0..m] S` `(m, p)`, in place, a band of rows at a time (the two halves
/// of the rows on two threads when `parallel`; each band as on one).
fn rotate_in_place(v: &mut Mat<f64>, m: usize, s: MatRef<'_, f64>, parallel: bool) {
    fn bands(mut v: MatMut<'_, f64>, m: usize, s: MatRef<'_, f64>) {
        let (n, p) = (v.nrows(), s.ncols());
        const ROWS: usize = 256;
        let mut buf = Mat::<f64>::zeros(ROWS, p);
        let mut r0 = 0;
        while r0 < n {
            let h = ROWS.min(n - r0);
            matmul(buf.as_mut().subrows_mut(0, h), Accum::Replace, v.as_ref().submatrix(r0, 0, h, m), s, 1.0, Par::Seq);
            v.rb_mut().submatrix_mut(r0, 0, h, p).copy_from(buf.as_ref().subrows(0, h));
            r0 += h;
        }
    }
    if !parallel {
        return bands(v.as_mut(), m, s);
    }
    // Split on a band boundary, so that every band is the one a single thread computes.
    let h = ((v.nrows() / 2).div_ceil(256) * 256).min(v.nrows());
    let (top, bottom) = v.as_mut().split_at_row_mut(h);
    crate::parallel::join(|| bands(bottom, m, s), || bands(top, m, s));
}

fn m_dot(x: &[f64], y: &[f64], mass: &[f64]) -> f64 {
    x.iter().zip(y).zip(mass).map(|((a, b), m)| a * b * m).sum()
}

fn m_norm(x: &[f64], mass: &[f64]) -> f64 {
    m_dot(x, x, mass).sqrt()
}

/// Column `dst` += a · column `src` (`src < dst`).
fn axpy_cols(v: &mut Mat<f64>, dst: usize, src: usize, a: f64) {
    debug_assert!(src < dst);
    let (left, mut right) = v.as_mut().split_at_col_mut(dst);
    let s = left.col(src).try_as_col_major().unwrap().as_slice();
    let d = right.rb_mut().col_mut(0).try_as_col_major_mut().unwrap().as_slice_mut();
    for (x, y) in d.iter_mut().zip(s) {
        *x += a * y;
    }
}

/// Flips `x` so that its entry of largest magnitude is positive (deterministic signs).
fn normalize_sign(x: &mut [f64]) {
    let mut best = 0.0f64;
    let mut sign = 1.0;
    for &v in x.iter() {
        if v.abs() > best * (1.0 + 1e-9) {
            best = v.abs();
            sign = v.signum();
        }
    }
    if sign < 0.0 {
        for v in x {
            *v = -*v;
        }
    }
}

/// Max residual `‖Lφ − λMφ‖₂ / ‖Mφ‖₂` and max `|ΦᵀMΦ − I|` entry.
#[allow(non_snake_case)]
pub fn check(lap: &CsMat<f64>, mass: &[f64], evals: &[f64], evecs: MatRef<'_, f64>) -> (f64, f64) {
    let k = evecs.ncols();
    // Eight columns at a time, interleaved: no n × k temporaries.
    let mut x: Vec<Lanes> = Vec::new();
    let (mut lx, mut mx) = (Vec::new(), Vec::new());
    let mut G = vec![[0.0; LANES]; k * k.div_ceil(LANES)];
    let mut worst = 0.0f64;
    for (chunk, g) in (0..k).step_by(LANES).zip(G.chunks_mut(k)) {
        let width = LANES.min(k - chunk);
        gather(evecs, chunk, width, &mut x);
        kernels::sparse_mul(lap, &x, &mut lx);
        kernels::scale_rows(&x, mass, &mut mx);
        for t in 0..width {
            let (mut r2, mut m2) = (0.0, 0.0);
            for (l, m) in lx.iter().zip(&mx) {
                r2 += (l[t] - evals[chunk + t] * m[t]).powi(2);
                m2 += m[t] * m[t];
            }
            worst = worst.max((r2 / m2).sqrt());
        }
        kernels::gram(evecs, &mx, g);
    }
    let mut orth = 0.0f64;
    for j in 0..k {
        for i in 0..k {
            let target = if i == j { 1.0 } else { 0.0 };
            orth = orth.max((G[(j / LANES) * k + i][j % LANES] - target).abs());
        }
    }
    (worst, orth)
}

/// Dense reference: eigen-decomposition of `M^{-1/2} L M^{-1/2}`.
#[allow(non_snake_case)]
pub fn dense_eigen(lap: &CsMat<f64>, mass: &[f64], k: usize) -> Result<(Vec<f64>, Mat<f64>, EigenInfo), SpectralError> {
    let t = std::time::Instant::now();
    let n = mass.len();
    if k == 0 || k > n {
        return Err(SpectralError::TooManyEigenpairs { k, n });
    }
    let isq: Vec<f64> = mass.iter().map(|m| 1.0 / m.sqrt()).collect();
    let mut A = Mat::<f64>::zeros(n, n);
    for (j, col) in lap.outer_iterator().enumerate() {
        for (i, &x) in col.iter() {
            A[(i, j)] += 0.5 * x * isq[i] * isq[j];
            A[(j, i)] += 0.5 * x * isq[i] * isq[j];
        }
    }
    let evd = A.self_adjoint_eigen(Side::Lower).map_err(|e| SpectralError::Factorization(format!("{e:?}")))?;
    let mut evals: Vec<f64> = (0..k).map(|i| evd.S()[i]).collect();
    evals[0] = 0.0;
    let mut X = Mat::<f64>::from_fn(n, k, |i, j| isq[i] * evd.U()[(i, j)]);
    // Exact constant mode (the dense solver returns it to rounding).
    let u0 = 1.0 / mass.iter().sum::<f64>().sqrt();
    for i in 0..n {
        X[(i, 0)] = u0;
    }
    // On badly conditioned meshes the dense solver's vectors drift from M-orthonormality by
    // ~ε‖A‖ (1e-8 with needle triangles): restore it with two passes of modified Gram–Schmidt.
    for _pass in 0..2 {
        for j in 0..k {
            for q in 0..j {
                let d = m_dot(X.col_as_slice(q), X.col_as_slice(j), mass);
                axpy_cols(&mut X, j, q, -d);
            }
            let nrm = m_norm(X.col_as_slice(j), mass);
            for x in X.col_as_slice_mut(j) {
                *x /= nrm;
            }
        }
    }
    for j in 0..k {
        normalize_sign(X.as_mut().col_mut(j).try_as_col_major_mut().unwrap().as_slice_mut());
    }
    let (res, orth) = check(lap, mass, &evals, X.as_ref());
    let info = EigenInfo {
        dense: true,
        max_residual: res,
        orthogonality: orth,
        solve_seconds: t.elapsed().as_secs_f64(),
        ..Default::default()
    };
    Ok((evals, X, info))
}

