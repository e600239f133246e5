//! Simplification benchmark: `bench_simplify MESH [TARGET]` times
//! `hierarchy::simplify::simplify` of the unit-area mesh down to `TARGET` vertices (default
//! 6000, the hierarchy's), best of 3 runs, and prints a checksum of the coarse mesh (its kept
//! vertices and triangles) so that two implementations can be checked for identical output.

use intrinsym::hierarchy::simplify::simplify;
use intrinsym::mesh::read_mesh;
use intrinsym::{Mesh, MeshParams};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("usage: bench_simplify MESH [TARGET]");
    let target: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(6000);
    let raw = read_mesh(path).expect("mesh");
    let (mesh, _) = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default()).expect("mesh").normalized();
    let mut best = f64::INFINITY;
    let mut checksum = 0u64;
    for _round in 0..3 {
        let t = std::time::Instant::now();
        let s = simplify(&mesh, target);
        best = best.min(t.elapsed().as_secs_f64());
        checksum = s.kept.iter().map(|&v| v as u64).chain(s.triangles.iter().flatten().map(|&i| i as u64)).fold(0xcbf2_9ce4_8422_2325, |h, x| (h ^ x).wrapping_mul(0x0100_0000_01b3));
        println!("{} vertices -> {} ({} triangles)", mesh.num_vertices(), s.kept.len(), s.triangles.len());
    }
    println!("{:.3} s (best of 3), checksum {checksum:016x}", best);
}
