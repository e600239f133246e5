use intrinsym::mesh::read_mesh;
use intrinsym::{detect, eval, Mesh, MeshParams, Params};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let raw = read_mesh(&path).unwrap();
    let mesh = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default()).unwrap();
    let truth: Vec<(usize, Vec<usize>)> = std::fs::read_to_string(path.replace(".off", ".sym.txt")).unwrap().lines().filter_map(|l| { let v: Vec<usize> = l.split_whitespace().filter_map(|x| x.parse().ok()).collect(); if v.len() == 2 { Some((v[0], vec![v[1]])) } else { None } }).collect();
    let mut p = Params::default();
    if let Ok(v) = std::env::var("SAMPLES") { p.samples = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("EPS") { p.voting.eps = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("ACCEPT") { p.maps.accept = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("DIST") { p.max_distortion = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("ZK") { p.maps.zoomout_k = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("ZSTEP") { p.maps.zoomout_step = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("SEARCH") { p.maps.search_vertices = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("REFINE") { p.maps.refine = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("K0") { p.maps.spectral_start = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("MAXC") { p.max_candidates = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("MAXR") { p.max_refinements = v.parse().unwrap(); }
    let d = detect(&mesh, &p, &mut |_| true).unwrap();
    let t = &d.timings;
    println!("n={} candidates={} found={} total {:.2}s (spectral {:.2} voting {:.2} maps {:.2})", mesh.num_vertices(), d.candidates, d.symmetries.len(), t.total, t.spectral, t.voting, t.maps);
    for (i, s) in d.symmetries.iter().enumerate() {
        let acc = eval::accuracy(&mesh, &s.map, &truth, &[0.05, 0.1]);
        println!("#{i} {} order {} region {} distortion {:.4} complexity {:.3} acc@.05 {:.3} @.1 {:.3} anchors {}", s.kind.as_str(), s.order, s.region_size, s.distortion, s.complexity, acc[0], acc[1], s.support_pairs.len());
    }
}
