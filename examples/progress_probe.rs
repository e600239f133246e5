//! Diagnostic: the eigensolver's progress calls on a bumpy torus (`progress_probe S K`).
use intrinsym::spectral::{EigenParams, Solver};
use intrinsym::{shapes, Eigenbasis};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let mesh = shapes::bumpy_torus(a[1].parse().unwrap());
    let mut p = EigenParams::default();
    p.k = a[2].parse().unwrap();
    p.solver = Solver::Lanczos;
    let t = std::time::Instant::now();
    let mut seen = Vec::new();
    Eigenbasis::compute_with_progress(&mesh, &p, &mut |f| {
        seen.push((t.elapsed().as_secs_f64(), f));
        true
    })
    .unwrap();
    for (s, f) in seen.iter().step_by((seen.len() / 12).max(1)) {
        print!("{s:.2}s:{f:.2} ");
    }
    println!("({} calls, {:.2} s)", seen.len(), t.elapsed().as_secs_f64());
}
