//! One spectral benchmark case: `bench_spectral S K [DUMP_DIR]` on `shapes::bumpy_torus(S)`.
//!
//! Prints one JSON line: vertices, k, assembly/factor/eigensolve seconds, peak RSS (MiB),
//! residual, orthogonality, and the eigenvalues. With DUMP_DIR it also writes the raw CSC
//! arrays of L and the mass (little-endian) for the scipy peer in `bench/spectral.py`.
//! Run `python3 bench/spectral.py` for the full table.

use std::io::Write;

use intrinsym::spectral::{cotan, mass};
use intrinsym::{shapes, Eigenbasis, EigenParams};

fn peak_rss_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|kb| kb.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let s: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(129);
    let k: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(100);
    let mesh = shapes::bumpy_torus(s);
    if let Some(dir) = args.get(3) {
        let lengths = cotan::mollified_edge_lengths(&mesh);
        let l = cotan::cotan_laplacian(&mesh, &lengths);
        let m = mass::lumped_mass(&mesh, &lengths);
        let write = |name: &str, bytes: Vec<u8>| std::fs::write(format!("{dir}/{name}"), bytes).unwrap();
        write("indptr.bin", l.indptr().raw_storage().iter().flat_map(|&x| (x as u64).to_le_bytes()).collect());
        write("indices.bin", l.indices().iter().flat_map(|&x| (x as u64).to_le_bytes()).collect());
        write("data.bin", l.data().iter().flat_map(|x| x.to_le_bytes()).collect());
        write("mass.bin", m.iter().flat_map(|x| x.to_le_bytes()).collect());
    }
    let mut params = EigenParams::default();
    params.k = k;
    if let Some(f) = std::env::var("BASIS").ok().and_then(|b| b.parse().ok()) {
        params.basis_factor = f;
    }
    if let Some(t) = std::env::var("TOL").ok().and_then(|b| b.parse().ok()) {
        params.tol = t;
    }
    // SINGLE=1: the whole eigensolve on one thread (EigenParams::parallel off).
    if std::env::var("SINGLE").is_ok_and(|v| v == "1") {
        params.parallel = false;
    }
    let t = std::time::Instant::now();
    let basis = Eigenbasis::compute(&mesh, &params).expect("eigensolve");
    let total = t.elapsed().as_secs_f64();
    let i = &basis.info;
    let evals: Vec<String> = basis.evals.iter().map(|x| format!("{x:.17e}")).collect();
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{{\"vertices\": {}, \"k\": {}, \"assembly\": {:.4}, \"factor\": {:.4}, \"eigensolve\": {:.4}, \"total\": {:.4}, \
         \"peak_mib\": {:.1}, \"residual\": {:.3e}, \"orthogonality\": {:.3e}, \"solves\": {}, \"restarts\": {}, \
         \"tri\": {:.3}, \"orth\": {:.3}, \"restart\": {:.3}, \"check\": {:.3}, \"shift\": {:.17e}, \"evals\": [{}]}}",
        mesh.num_vertices(),
        k,
        basis.assembly_seconds,
        i.factor_seconds,
        i.solve_seconds,
        total,
        peak_rss_mib(),
        i.max_residual,
        i.orthogonality,
        i.solves,
        i.restarts,
        i.triangular_seconds,
        i.orthogonalize_seconds,
        i.restart_seconds,
        i.check_seconds,
        i.shift,
        evals.join(", ")
    )
    .unwrap();
}
