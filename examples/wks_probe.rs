use intrinsym::descriptors::{wks, WksParams};
use intrinsym::shapes::{self, Pose};
use intrinsym::voting::wks_distance;
use intrinsym::{Eigenbasis, EigenParams};
fn q(mut v: Vec<f64>) -> String { v.sort_by(|a,b| a.total_cmp(b)); let n=v.len(); format!("p10 {:.3} p50 {:.3} p90 {:.3} p99 {:.3}", v[n/10], v[n/2], v[n*9/10], v[n*99/100]) }
fn main() {
    for noise in [0.0, 0.005] {
        let c = shapes::quadruped(5, Pose::Walking, noise, 3);
        let b = Eigenbasis::compute(&c.mesh, &EigenParams::default()).unwrap();
        let d = wks(&b, &WksParams::default());
        let row = |v: usize| (0..d.ncols()).map(|e| d[(v, e)]).collect::<Vec<f64>>();
        let n = c.mesh.num_vertices();
        let mirror: Vec<f64> = (0..n).map(|v| wks_distance(&row(v), &row(c.mirror[v] as usize))).collect();
        // random pairs
        let rand: Vec<f64> = (0..n).map(|v| wks_distance(&row(v), &row((v * 7919 + 13) % n))).collect();
        // head (limb 4) vs tail (limb 5): nearest-by-index
        let head: Vec<usize> = (0..n).filter(|&v| c.limb[v] == 4).collect();
        let tail: Vec<usize> = (0..n).filter(|&v| c.limb[v] == 5).collect();
        let ht: Vec<f64> = head.iter().map(|&h| tail.iter().map(|&t| wks_distance(&row(h), &row(t))).fold(f64::INFINITY, f64::min)).collect();
        println!("noise {noise}: mirror {}\n  random {}\n  head->best tail {}", q(mirror), q(rand), q(ht));
    }
}
