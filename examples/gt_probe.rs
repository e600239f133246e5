use intrinsym::descriptors::{wks, WksParams};
use intrinsym::distance::biharmonic;
use intrinsym::sampling::farthest_point;
use intrinsym::shapes::{self, Pose};
use intrinsym::voting::wks_distance;
use intrinsym::{Eigenbasis, EigenParams};
fn q(mut v: Vec<f64>) -> String { v.sort_by(|a,b| a.total_cmp(b)); let n=v.len(); format!("p50 {:.4} p90 {:.4} p99 {:.4} max {:.4}", v[n/2], v[n*9/10], v[n*99/100], v[n-1]) }
fn main() {
    let noise: f64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(0.0);
    let c = shapes::quadruped(5, Pose::Walking, noise, 3);
    let b = Eigenbasis::compute(&c.mesh, &EigenParams::default()).unwrap();
    let d = wks(&b, &WksParams::default());
    let emb = biharmonic(&b);
    let s = farthest_point(&emb, 64, 0);
    let n = c.mesh.num_vertices();
    let diam = (0..64).flat_map(|i| (0..64).map(move |j| (i,j))).map(|(i,j)| emb.dist(s.vertices[i], s.vertices[j])).fold(0.0, f64::max);
    let src = s.vertices.clone();
    let dst: Vec<usize> = src.iter().map(|&v| c.mirror[v] as usize).collect();
    let ds = emb.from_sources(&src);
    let dd = emb.from_sources(&dst);
    let row = |v: usize| (0..d.ncols()).map(|e| d[(v, e)]).collect::<Vec<f64>>();
    for (name, sel) in [("body", usize::MAX), ("leg0", 0), ("leg1", 1), ("head", 4), ("tail", 5)] {
        let vs: Vec<usize> = (0..n).filter(|&v| c.limb[v] == sel).collect();
        let mis: Vec<f64> = vs.iter().map(|&v| { let m = c.mirror[v] as usize; (0..64).map(|i| (ds[(v,i)] - dd[(m,i)]).abs()).sum::<f64>() / 64.0 / diam }).collect();
        // K nearest anchors only
        let mis8: Vec<f64> = vs.iter().map(|&v| { let m = c.mirror[v] as usize; let mut idx: Vec<usize> = (0..64).collect(); idx.sort_by(|&a,&bb| ds[(v,a)].total_cmp(&ds[(v,bb)])); idx[..12].iter().map(|&i| (ds[(v,i)] - dd[(m,i)]).abs()).sum::<f64>() / 12.0 / diam }).collect();
        let w: Vec<f64> = vs.iter().map(|&v| wks_distance(&row(v), &row(c.mirror[v] as usize))).collect();
        println!("{name:5} n={:5} mismatch/diam {}\n      near12 {}\n      wks {}", vs.len(), q(mis), q(mis8), q(w));
    }
    println!("sampling radius/diam {:.4}", s.radius.iter().cloned().fold(0.0, f64::max) / diam);
}
