//! Dijkstra micro-benchmark: `bench_dijkstra MESH [SEARCHES]`, the mean time of one search of
//! `maps::geodesic::EdgeGraph::distances` (the polish's geodesics) from evenly spread sources,
//! and a checksum of the distances (to compare implementations).

use intrinsym::maps::geodesic::EdgeGraph;
use intrinsym::mesh::read_mesh;
use intrinsym::{Mesh, MeshParams};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("usage: bench_dijkstra MESH [SEARCHES]");
    let searches: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(500);
    let raw = read_mesh(path).expect("mesh");
    let mesh = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default()).expect("mesh");
    let graph = EdgeGraph::new(&mesh.vertices, mesh.adjacency());
    let n = mesh.num_vertices();
    let mut best = f64::INFINITY;
    let mut checksum = 0.0;
    for _round in 0..3 {
        let t = std::time::Instant::now();
        checksum = 0.0;
        for i in 0..searches {
            let d = graph.distances(i * 7919 % n);
            checksum += d.iter().sum::<f64>();
        }
        best = best.min(t.elapsed().as_secs_f64() / searches as f64);
    }
    println!("{n} vertices: {:.1} µs per search (best of 3 rounds of {searches}), checksum {checksum:.17e}", best * 1e6);
}
