use intrinsym::descriptors::{wks, WksParams};
use intrinsym::distance::biharmonic;
use intrinsym::mesh::read_mesh;
use intrinsym::sampling::farthest_point;
use intrinsym::voting::{vote, VotingParams};
use intrinsym::{Eigenbasis, EigenParams, Mesh, MeshParams};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let raw = read_mesh(&path).unwrap();
    let mesh = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default()).unwrap();
    let n = mesh.num_vertices();
    let mut gt = vec![usize::MAX; n];
    for l in std::fs::read_to_string(path.replace(".off", ".sym.txt")).unwrap().lines() { let v: Vec<usize> = l.split_whitespace().filter_map(|x| x.parse().ok()).collect(); if v.len() == 2 { gt[v[0]] = v[1]; } }
    let b = Eigenbasis::compute(&mesh, &EigenParams::default()).unwrap();
    let d = wks(&b, &WksParams::default());
    let emb = biharmonic(&b);
    let s = farthest_point(&emb, std::env::var("SAMPLES").ok().and_then(|x| x.parse().ok()).unwrap_or(64), 0);
    let mut vp = VotingParams::default();
    if let Ok(v) = std::env::var("EPS") { vp.eps = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("Q") { vp.wks_quantile = v.parse().unwrap(); }
    let (cands, info, _) = vote(&emb, &d, &s, &vp);
    println!("good pairs {} eps/diam {:.3} grown {} candidates {}", info.good_pairs, info.eps / info.diameter, info.grown, cands.len());
    // GT sample pairs: is gt image of each sample near some sample? and is it a good voter?
    let sv = &s.vertices;
    let mut near = 0; 
    for &a in sv { if gt[a] != usize::MAX { let m = sv.iter().map(|&x| emb.dist(x, gt[a])).fold(f64::INFINITY, f64::min); if m < info.eps { near += 1; } } }
    println!("samples whose GT image is within eps of a sample: {near}/{}", sv.len());
    let mut ranked: Vec<_> = cands.iter().collect();
    ranked.sort_by(|a, b| (b.pairs.len() * b.support).cmp(&(a.pairs.len() * a.support)));
    for (i, c) in ranked.iter().take(12).enumerate() {
        let ok = c.pairs.iter().filter(|&&(a, bb)| gt[sv[a]] != usize::MAX && emb.dist(gt[sv[a]], sv[bb]) < info.eps).count();
        let selfp = c.pairs.iter().filter(|p| p.0 == p.1).count();
        println!("cand {i}: pairs {} (self {selfp}) support {} votes {} GT-consistent {}", c.pairs.len(), c.support, c.votes, ok);
    }
}
