//! Properties of the Laplace–Beltrami eigenbasis on generated meshes.

use intrinsym::spectral::{eigen, Solver, SpectralError};
use intrinsym::{shapes, Eigenbasis, EigenParams};

fn params(k: usize, solver: Solver) -> EigenParams {
    let mut p = EigenParams::default();
    p.k = k;
    p.solver = solver;
    p
}

/// Sphere eigenvalues l(l+1), multiplicity 2l+1, for l = 0..=3 (16 values).
fn sphere_spectrum() -> Vec<(f64, usize)> {
    (0..=3).map(|l| ((l * (l + 1)) as f64, 2 * l + 1)).collect()
}

#[test]
fn icosphere_eigenvalues_converge_to_l_l_plus_1_with_multiplicities() {
    let mut previous_error = f64::INFINITY;
    for level in 2..=5 {
        let mesh = shapes::icosphere(level);
        let basis = Eigenbasis::compute(&mesh, &params(16, Solver::Auto)).unwrap();
        let mut i = 0;
        let mut worst = 0.0f64;
        for (exact, mult) in sphere_spectrum() {
            let group = &basis.evals[i..i + mult];
            for &x in group {
                let err = if exact == 0.0 { x.abs() } else { (x - exact).abs() / exact };
                worst = worst.max(err);
            }
            i += mult;
        }
        // The multiplicities are right: each group is closer to its own l(l+1) than to the next.
        let mut i = 0;
        for (l, (exact, mult)) in sphere_spectrum().into_iter().enumerate() {
            let next = ((l + 1) * (l + 2)) as f64;
            for &x in &basis.evals[i..i + mult] {
                assert!((x - exact).abs() < (x - next).abs(), "level {level}: λ={x} not in the l={l} group");
            }
            i += mult;
        }
        // O(h²): the error falls by about 4 per refinement; demand at least 3.
        assert!(worst < previous_error / 3.0, "level {level}: error {worst} vs {previous_error}");
        previous_error = worst;
        if level == 5 {
            assert!(worst < 2e-3, "level 5 relative error {worst}");
            assert!(!basis.info.dense, "level 5 (10k vertices) exercises Lanczos");
        }
    }
}

#[test]
fn lanczos_is_m_orthonormal_with_small_residuals() {
    for (mesh, k) in [(shapes::icosphere(5), 100), (shapes::bumpy_torus(40), 120), (shapes::bumpy_torus(24), 30)] {
        let basis = Eigenbasis::compute(&mesh, &params(k, Solver::Lanczos)).unwrap();
        assert!(!basis.info.dense);
        assert_eq!(basis.evals.len(), k);
        assert_eq!(basis.evecs.ncols(), k);
        // Measure independently of the solver's own report.
        let (res, orth) = eigen::check(&basis.laplacian, &basis.mass, &basis.evals, basis.evecs.as_ref());
        assert!(orth < 1e-10, "ΦᵀMΦ − I = {orth}");
        assert!(res < 1e-8, "residual {res}");
        assert_eq!(basis.evals[0], 0.0);
        assert!(basis.evals.windows(2).all(|w| w[0] <= w[1]), "ascending");
        assert!(basis.evals[1] > 0.0);
    }
}

/// The fewest pairs the solver accepts: k = 1 is the constant mode alone (it panicked on an
/// index below zero before, `intrinsym spectrum -k 1`), k = 2 adds the Fiedler pair; both on
/// the Lanczos path agree with the dense solver.
#[test]
fn one_or_two_eigenpairs() {
    let mesh = shapes::icosphere(4);
    for k in [1, 2] {
        let basis = Eigenbasis::compute(&mesh, &params(k, Solver::Lanczos)).unwrap();
        let dense = Eigenbasis::compute(&mesh, &params(k, Solver::Dense)).unwrap();
        assert_eq!(basis.evals.len(), k);
        assert_eq!(basis.evals[0], 0.0);
        let (res, orth) = eigen::check(&basis.laplacian, &basis.mass, &basis.evals, basis.evecs.as_ref());
        assert!(res < 1e-8 && orth < 1e-10, "k = {k}: residual {res}, orthogonality {orth}");
        for (a, b) in basis.evals.iter().zip(&dense.evals) {
            assert!((a - b).abs() <= 1e-8 * b.abs().max(1.0), "k = {k}: {a} against dense {b}");
        }
    }
}

#[test]
fn lanczos_agrees_with_dense() {
    for mesh in [shapes::bumpy_torus(16), shapes::icosphere(3), shapes::bumpy_torus(21)] {
        let n = mesh.num_vertices();
        let k = 60.min(n / 4);
        let lanczos = Eigenbasis::compute(&mesh, &params(k, Solver::Lanczos)).unwrap();
        let dense = Eigenbasis::compute(&mesh, &params(k, Solver::Dense)).unwrap();
        assert!(!lanczos.info.dense && dense.info.dense);
        let scale = dense.evals[k - 1];
        for (a, b) in lanczos.evals.iter().zip(&dense.evals) {
            assert!((a - b).abs() <= 1e-10 * scale, "n={n}: {a} vs {b}");
        }
        // Eigenvectors span the same spaces: for every Lanczos vector, its M-projection onto
        // the dense vectors of (numerically) the same eigenvalue has norm 1.
        for j in 0..k - 1 {
            let lam = lanczos.evals[j];
            let mut norm2 = 0.0;
            for (i, &mu) in dense.evals.iter().enumerate() {
                if (mu - lam).abs() <= 1e-6 * scale {
                    let dot: f64 = (0..n).map(|v| lanczos.evecs[(v, j)] * dense.mass[v] * dense.evecs[(v, i)]).sum();
                    norm2 += dot * dot;
                }
            }
            // Clusters cut by the k boundary are skipped.
            if (lanczos.evals[k - 1] - lam).abs() > 1e-6 * scale {
                assert!((norm2 - 1.0).abs() < 1e-7, "n={n}, pair {j}: projection {norm2}");
            }
        }
    }
}

#[test]
fn needle_and_zero_area_triangles_give_finite_results() {
    for level in [2, 3, 5] {
        let mesh = shapes::needle_sphere(level);
        assert!(mesh.info.degenerate_triangles > 0);
        let basis = Eigenbasis::compute(&mesh, &params(40, Solver::Auto)).unwrap();
        assert!(basis.evals.iter().all(|x| x.is_finite() && *x >= 0.0));
        assert!((0..basis.evecs.ncols()).all(|j| basis.evecs.col(j).iter().all(|x| x.is_finite())));
        // Slivers get cotangents up to ~1/MOLLIFY_REL = 1e6, so ‖L‖ is ~1e6 and rounding alone
        // leaves residuals of ~1e-6..1e-4 (the solver floors its tolerance there; see eigen.rs).
        assert!(basis.info.max_residual < 1e-3, "residual {}", basis.info.max_residual);
        assert!(basis.info.orthogonality < 1e-10);
    }
}

#[test]
fn a_surface_flattened_onto_a_segment_is_refused_with_advice_that_works() {
    // A sphere squashed onto a line (x = 0, z ×1e-9): every triangle a sliver. Lanczos cannot
    // resolve 100 pairs of such a Laplacian; the refusal must name what a user can change (k),
    // and fewer pairs must then work.
    let sphere = shapes::icosphere(3);
    let squashed: Vec<[f64; 3]> = sphere.vertices.iter().map(|p| [0.0, p[1], p[2] * 1e-9]).collect();
    let mesh = intrinsym::Mesh::new(squashed, sphere.triangles.clone(), &Default::default()).unwrap();
    let e = Eigenbasis::compute(&mesh, &params(100, Solver::Lanczos)).unwrap_err();
    assert!(matches!(e, SpectralError::NotConverged { wanted: 100, .. }), "{e:?}");
    let message = e.to_string();
    assert!(message.contains("fewer eigenpairs") && message.contains("-k") && !message.contains("max_restarts"), "{message}");
    let basis = Eigenbasis::compute(&mesh, &params(30, Solver::Lanczos)).unwrap();
    assert!(basis.evals.iter().all(|x| x.is_finite() && *x >= 0.0));
}

#[test]
fn eigenpair_count_limits() {
    let mesh = shapes::icosphere(1); // 42 vertices
    let all = Eigenbasis::compute(&mesh, &params(42, Solver::Auto)).unwrap();
    assert_eq!(all.evals.len(), 42);
    for k in [0, 43, usize::MAX] {
        let e = Eigenbasis::compute(&mesh, &params(k, Solver::Auto)).unwrap_err();
        assert_eq!(e, SpectralError::TooManyEigenpairs { k, n: 42 });
    }
}

#[test]
fn progress_is_reported_and_can_cancel() {
    let mesh = shapes::bumpy_torus(30);
    let mut seen = Vec::new();
    let basis = Eigenbasis::compute_with_progress(&mesh, &params(30, Solver::Lanczos), &mut |f| {
        seen.push(f);
        true
    })
    .unwrap();
    assert_eq!(basis.evals.len(), 30);
    assert!(!seen.is_empty() && seen.iter().all(|f| (0.0..=1.0).contains(f)));
    // It moves steadily (issue 16, item 20: with 100 pairs it sat at 0.01 through the first
    // Lanczos basis, most of the work): never backwards, and past a quarter by the middle call
    // (it was 0.01 there).
    let mesh = shapes::bumpy_torus(60);
    let mut seen = Vec::new();
    Eigenbasis::compute_with_progress(&mesh, &params(100, Solver::Lanczos), &mut |f| {
        seen.push(f);
        true
    })
    .unwrap();
    assert!(seen.windows(2).all(|w| w[1] >= w[0]), "{seen:?}");
    assert!(seen[seen.len() / 2] > 0.25, "{seen:?}");
    let mut calls = 0;
    let e = Eigenbasis::compute_with_progress(&mesh, &params(30, Solver::Lanczos), &mut |_| {
        calls += 1;
        calls < 3
    })
    .unwrap_err();
    assert_eq!(e, SpectralError::Cancelled);
    assert_eq!(calls, 3);
}

#[test]
fn deterministic_for_a_seed() {
    let mesh = shapes::bumpy_torus(30);
    let a = Eigenbasis::compute(&mesh, &params(20, Solver::Lanczos)).unwrap();
    let b = Eigenbasis::compute(&mesh, &params(20, Solver::Lanczos)).unwrap();
    assert_eq!(a.evals, b.evals);
    assert!((0..20).all(|j| a.evecs.col(j) == b.evecs.col(j)));
}

/// The reorthogonalisation split over two threads computes every coefficient and row exactly
/// as one thread does: the same eigenpairs to the last bit. (k = 60 makes the basis wide
/// enough for the split, which starts at 32 columns.)
#[test]
fn two_threads_give_the_single_thread_result() {
    let mesh = shapes::bumpy_torus(30);
    let mut single = params(60, Solver::Lanczos);
    single.parallel = false;
    let a = Eigenbasis::compute(&mesh, &single).unwrap();
    let b = Eigenbasis::compute(&mesh, &params(60, Solver::Lanczos)).unwrap();
    assert_eq!(a.info.solves, b.info.solves);
    assert_eq!(a.evals, b.evals);
    assert!((0..60).all(|j| a.evecs.col(j) == b.evecs.col(j)));
}

/// The basis is returned in the input's units whatever they are (issue 16, item 1: Lanczos
/// failed to converge at ×1000 and ×1e-6): `λ·s²` does not depend on the scale `s`.
#[test]
fn eigenvalues_scale_as_the_inverse_square_of_the_units() {
    let mesh = shapes::quadruped(3, shapes::Pose::Walking, 0.0, 0).mesh;
    let base = Eigenbasis::compute(&mesh, &params(30, Solver::Lanczos)).unwrap();
    for scale in [1e-9, 1e-6, 1e3, 1e6, 1e9] {
        let v: Vec<[f64; 3]> = mesh.vertices.iter().map(|p| p.map(|x| x * scale + 1e6 * scale)).collect();
        let scaled = intrinsym::Mesh::new(v, mesh.triangles.clone(), &intrinsym::MeshParams::default()).unwrap();
        let b = Eigenbasis::compute(&scaled, &params(30, Solver::Lanczos)).unwrap();
        for (i, (l, l0)) in b.evals.iter().zip(&base.evals).enumerate().skip(1) {
            assert!((l * scale * scale / l0 - 1.0).abs() < 1e-6, "scale {scale:e}, λ{i}: {l:e} vs {l0:e}");
        }
        assert!((b.area / (scale * scale * base.area) - 1.0).abs() < 1e-9);
    }
}
