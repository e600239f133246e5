//! Diagnostic run on the generated quadruped: every detected symmetry with its accuracy
//! against the left–right mirror, where each leg's vertices go, and the best acc@0.1 of each
//! ordered leg → leg map.
//!
//! `cargo run --release --example quadruped_report [NOISE] [rest]` with `LEVEL` (icosphere level,
//! default 5), `SEED` (noise seed), and overrides `EPS`, `ACCEPT`, `DIST`, `MAXC`, `MAXR`, `PROXY` (proxy vertices).
use intrinsym::shapes::{self, Pose};
use intrinsym::{detect, eval, Params};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let noise: f64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(0.0);
    let pose = if args.get(2).map(|s| s == "rest").unwrap_or(false) { Pose::Rest } else { Pose::Walking };
    let level: u32 = std::env::var("LEVEL").ok().and_then(|l| l.parse().ok()).unwrap_or(5);
    let seed: u64 = std::env::var("SEED").ok().and_then(|l| l.parse().ok()).unwrap_or(3);
    let c = shapes::quadruped(level, pose, noise, seed);
    let mut p = Params::default();
    if let Ok(v) = std::env::var("EPS") { p.voting.eps = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("ACCEPT") { p.maps.accept = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("DIST") { p.max_distortion = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("MAXC") { p.max_candidates = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("MAXR") { p.max_refinements = v.parse().unwrap(); }
    if let Ok(v) = std::env::var("PROXY") { p.maps.proxy_vertices = v.parse().unwrap(); }
    let d = detect(&c.mesh, &p, &mut |_| true).unwrap();
    let t = &d.timings;
    println!("n={} candidates={} found={} total {:.2}s (spectral {:.2} wks {:.2} dist {:.2} sampling {:.2} voting {:.2} maps {:.2} [profile {:.2} refine {:.2} polish {:.2} compose {:.2} proxy {:.2} lift {:.2}] char {:.2})", c.mesh.num_vertices(), d.candidates, d.symmetries.len(), t.total, t.spectral, t.descriptors, t.distance, t.sampling, t.voting, t.maps, t.maps_profile, t.maps_refine, t.maps_polish, t.maps_compose, t.maps_proxy, t.maps_lift, t.characterize);
    let truth: Vec<(usize, Vec<usize>)> = (0..c.mesh.num_vertices()).map(|v| (v, vec![c.mirror[v] as usize])).collect();
    let mut leg_ok = vec![vec![0.0f64; 4]; 4];
    for i in 0..4 { for j in 0..4 { if i != j {
        let truth = c.limb_truth(i, j);
        for s in &d.symmetries { let a = eval::accuracy(&c.mesh, &s.map, &truth, &[0.1])[0]; if a > leg_ok[i][j] { leg_ok[i][j] = a; } }
    }}}
    println!("leg->leg best acc@0.1: {:?}", leg_ok.iter().map(|r| r.iter().map(|x| format!("{x:.2}")).collect::<Vec<_>>()).collect::<Vec<_>>());
    for (i, s) in d.symmetries.iter().enumerate() {
        let acc = eval::accuracy(&c.mesh, &s.map, &truth, &[0.05, 0.1]);
        let legs: Vec<usize> = (0..4).map(|j| {
            // fraction of leg j vertices mapped, and to which leg
            let mut counts = [0usize; 7];
            for v in 0..c.mesh.num_vertices() { if c.limb[v] == j && s.map[v] >= 0 { let l = c.limb[s.map[v] as usize]; counts[if l == usize::MAX { 6 } else { l }] += 1; } }
            (0..7).max_by_key(|&k| counts[k]).unwrap() * 1000 + counts.iter().max().unwrap()
        }).collect();
        println!("#{i} {} order {} region {} distortion {:.4} complexity {:.3} group {} mirror-acc@.05 {:.3} @.1 {:.3} legs->(leg*1000+count) {:?} anchors {}", s.kind.as_str(), s.order, s.region_size, s.distortion, s.complexity, s.group, acc[0], acc[1], legs, s.support_pairs.len());
    }
}
