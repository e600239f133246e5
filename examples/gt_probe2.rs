use intrinsym::descriptors::{wks, WksParams};
use intrinsym::distance::biharmonic;
use intrinsym::mesh::read_mesh;
use intrinsym::sampling::farthest_point;
use intrinsym::voting::wks_distance;
use intrinsym::{Eigenbasis, EigenParams, Mesh, MeshParams};
fn q(mut v: Vec<f64>) -> String { v.sort_by(|a,b| a.total_cmp(b)); let n=v.len(); format!("p50 {:.4} p80 {:.4} p90 {:.4} p99 {:.4}", v[n/2], v[n*8/10], v[n*9/10], v[n*99/100]) }
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
    let s = farthest_point(&emb, 64, 0);
    let sv: Vec<usize> = s.vertices.iter().copied().filter(|&v| gt[v] != usize::MAX).collect();
    let diam = sv.iter().flat_map(|&i| sv.iter().map(move |&j| (i,j))).map(|(i,j)| emb.dist(i, j)).fold(0.0, f64::max);
    let dst: Vec<usize> = sv.iter().map(|&v| gt[v]).collect();
    let ds = emb.from_sources(&sv);
    let dd = emb.from_sources(&dst);
    let row = |v: usize| (0..d.ncols()).map(|e| d[(v, e)]).collect::<Vec<f64>>();
    let vs: Vec<usize> = (0..n).filter(|&v| gt[v] != usize::MAX).collect();
    let mis: Vec<f64> = vs.iter().map(|&v| { let m = gt[v]; let mut idx: Vec<usize> = (0..sv.len()).collect(); idx.sort_by(|&a,&bb| ds[(v,a)].total_cmp(&ds[(v,bb)])); idx[..16].iter().map(|&i| (ds[(v,i)] - dd[(m,i)]).abs()).sum::<f64>() / 16.0 / diam }).collect();
    let w: Vec<f64> = vs.iter().map(|&v| wks_distance(&row(v), &row(gt[v]))).collect();
    println!("{path}: GT local16 mismatch/diam {}\n   wks {}", q(mis), q(w));
}
