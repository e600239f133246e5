//! Diagnostic: the longest stretches between progress calls of a whole detection, and how soon
//! a cancellation takes effect (`progress_gaps MESH [CANCEL_AFTER_S]`).
use intrinsym::mesh::{read_mesh, MeshParams};
use intrinsym::{detect, Mesh, Params};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let raw = read_mesh(&a[1]).unwrap();
    let mesh = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default()).unwrap();
    let cancel_after: Option<f64> = a.get(2).map(|s| s.parse().unwrap());
    let t = std::time::Instant::now();
    let mut seen: Vec<(f64, f64)> = Vec::new();
    let mut cancelled_at = None;
    let result = detect(&mesh, &Params::default(), &mut |f| {
        let now = t.elapsed().as_secs_f64();
        seen.push((now, f));
        match cancel_after {
            Some(c) if now >= c => {
                cancelled_at.get_or_insert(now);
                false
            }
            _ => true,
        }
    });
    let end = t.elapsed().as_secs_f64();
    let mut gaps: Vec<(f64, f64, f64)> = seen.windows(2).map(|w| (w[1].0 - w[0].0, w[0].1, w[1].1)).collect();
    gaps.push((seen.first().map_or(end, |s| s.0), 0.0, seen.first().map_or(1.0, |s| s.1)));
    gaps.sort_by(|x, y| y.0.total_cmp(&x.0));
    println!("{} calls in {end:.2} s; longest gaps:", seen.len());
    for (g, from, to) in gaps.iter().take(6) {
        println!("  {g:.3} s between {from:.3} and {to:.3}");
    }
    if let Some(c) = cancelled_at {
        println!("cancelled at {c:.2} s, returned {:.3} s later ({})", end - c, if result.is_err() { "an error" } else { "a result" });
    }
}
