//! Diagnostic: the judge's verdicts on every symmetry detected on a generated posed quadruped
//! (`judge_probe LEVEL NOISE SEED [PROXY_VERTICES]`), with each map's acc@0.05 against the left–right mirror.
use intrinsym::shapes::{self, Pose};
use intrinsym::{detect, eval, Params};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let level: u32 = a.get(1).and_then(|x| x.parse().ok()).unwrap_or(5);
    let noise: f64 = a.get(2).and_then(|x| x.parse().ok()).unwrap_or(0.005);
    let seed: u64 = a.get(3).and_then(|x| x.parse().ok()).unwrap_or(0);
    let c = shapes::quadruped(level, Pose::Walking, noise, seed);
    let truth: Vec<(usize, Vec<usize>)> = (0..c.mesh.num_vertices()).map(|v| (v, vec![c.mirror[v] as usize])).collect();
    let mut params = Params::default();
    if let Some(proxy) = a.get(4).and_then(|x| x.parse().ok()) {
        params.maps.proxy_vertices = proxy;
    }
    let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
    for (i, s) in d.symmetries.iter().enumerate() {
        let acc = eval::accuracy(&c.mesh, &s.map, &truth, &[0.05])[0];
        println!("#{i} {} order {} acc {acc:.3} distortion {:.4} complexity {:.2} {:?}", s.kind.as_str(), s.order, s.distortion, s.complexity, s.verdict);
    }
}
