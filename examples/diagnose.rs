//! Where the best detected symmetry of a shape with ground truth goes wrong:
//! `diagnose SHAPE.off` (with `SHAPE.sym.txt` next to it).
//!
//! Prints every reported symmetry's accuracy, then for the best one the connected pieces of
//! wrongly mapped vertices (error > 0.05·√area): size, centroid, and the mean distance
//! mismatch (against the 64 farthest-point samples, 16 nearest) of the detected and of the
//! true map there — a piece where the true map fits better is a search failure, one where it
//! fits worse a model failure. With `EXPERIMENTS=1` it also shows how far each dense-map method
//! gets from the true sample correspondences (the evidence for `maps::geodesic`).

use intrinsym::distance::biharmonic;
use intrinsym::mesh::read_mesh;
use intrinsym::sampling::farthest_point;
use intrinsym::{detect, eval, Eigenbasis, Mesh, MeshParams, Params};

fn main() {
    let path = std::env::args().nth(1).expect("usage: diagnose SHAPE.off");
    let raw = read_mesh(&path).expect("read");
    let mut mp = MeshParams::default();
    mp.allow_non_manifold = true;
    let mesh = Mesh::new(raw.vertices, raw.triangles, &mp).expect("mesh");
    let n = mesh.num_vertices();
    let mut truth = vec![usize::MAX; n];
    let sym = std::fs::read_to_string(path.replace(".off", ".sym.txt")).expect("sym.txt");
    for l in sym.lines() {
        let v: Vec<usize> = l.split_whitespace().filter_map(|x| x.parse().ok()).collect();
        if v.len() == 2 && v[0] < n && v[1] < n {
            truth[v[0]] = v[1];
        }
    }
    let pairs: Vec<(usize, Vec<usize>)> = (0..n).filter(|&v| truth[v] != usize::MAX).map(|v| (v, vec![truth[v]])).collect();
    let params = Params::default();
    let t = std::time::Instant::now();
    let det = detect(&mesh, &params, &mut |_| true).expect("detect");
    println!("detect {:.2} s, timings {:?}", t.elapsed().as_secs_f64(), det.timings);
    let mut best = (0.0, 0);
    for (i, s) in det.symmetries.iter().enumerate() {
        let a = eval::accuracy(&mesh, &s.map, &pairs, &[0.05, 0.10]);
        println!(
            "#{i}: {:?} region {} complexity {:.3} distortion {:.4} acc {:.1}/{:.1} {:?}",
            s.kind,
            s.region_size,
            s.complexity,
            s.distortion,
            100.0 * a[0],
            100.0 * a[1],
            s.verdict
        );
        if a[0] > best.0 {
            best = (a[0], i);
        }
    }
    let s = &det.symmetries[best.1];
    if std::env::var("EXPERIMENTS").is_ok() {
        experiments(&mesh, &pairs);
    }
    let scale = mesh.area().sqrt();
    let mut geo = eval::Geodesics::new(&mesh);
    let wrong: Vec<bool> = (0..n)
        .map(|v| truth[v] != usize::MAX && (s.map[v] < 0 || geo.distance(s.map[v] as usize, truth[v], 0.05 * scale).is_infinite()))
        .collect();
    // Mismatch of a map against the samples.
    let basis = Eigenbasis::compute(&mesh, &params.eigen).expect("basis");
    let emb = biharmonic(&basis);
    let samples = farthest_point(&emb, 64, 0).vertices;
    let diameter = samples.iter().flat_map(|&a| samples.iter().map(move |&b| (a, b))).map(|(a, b)| emb.dist(a, b)).fold(0.0, f64::max);
    let fit = |v: usize, image: &dyn Fn(usize) -> Option<usize>| -> Option<f64> {
        let tv = image(v)?;
        let mut near: Vec<(f64, usize)> = samples.iter().map(|&a| (emb.dist(v, a), a)).collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        let terms: Vec<f64> = near.iter().filter_map(|&(d, a)| image(a).map(|ta| (d - emb.dist(tv, ta)).abs())).take(16).collect();
        Some(terms.iter().sum::<f64>() / terms.len() as f64 / diameter)
    };
    let ours = |v: usize| (s.map[v] >= 0).then_some(s.map[v] as usize);
    let gt = |v: usize| (truth[v] != usize::MAX).then_some(truth[v]);
    let (off, nbr) = mesh.adjacency();
    let mut seen = vec![false; n];
    let mut pieces = Vec::new();
    for v0 in 0..n {
        if !wrong[v0] || seen[v0] {
            continue;
        }
        let mut comp = vec![v0];
        seen[v0] = true;
        let mut i = 0;
        while i < comp.len() {
            let v = comp[i];
            i += 1;
            for &u in &nbr[off[v]..off[v + 1]] {
                let u = u as usize;
                if wrong[u] && !seen[u] {
                    seen[u] = true;
                    comp.push(u);
                }
            }
        }
        pieces.push(comp);
    }
    pieces.sort_by_key(|c| std::cmp::Reverse(c.len()));
    let (lo, hi) = mesh.vertices.iter().fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), p| {
        (std::array::from_fn(|i| lo[i].min(p[i])), std::array::from_fn(|i| hi[i].max(p[i])))
    });
    println!("best #{} acc {}; bbox {lo:.2?} – {hi:.2?}; {} wrong in {} pieces", best.1, 100.0 * best.0, wrong.iter().filter(|&&w| w).count(), pieces.len());
    let mean = |vs: &[usize], f: &dyn Fn(usize) -> Option<f64>| {
        let x: Vec<f64> = vs.iter().filter_map(|&v| f(v)).collect();
        x.iter().sum::<f64>() / x.len().max(1) as f64
    };
    let right: Vec<usize> = (0..n).filter(|&v| truth[v] != usize::MAX && !wrong[v]).collect();
    println!("right vertices: mismatch ours {:.4} truth {:.4}", mean(&right, &|v| fit(v, &ours)), mean(&right, &|v| fit(v, &gt)));
    for c in pieces.iter().take(8) {
        let centroid: [f64; 3] = std::array::from_fn(|i| c.iter().map(|&v| mesh.vertices[v][i]).sum::<f64>() / c.len() as f64);
        let image_centroid: [f64; 3] = std::array::from_fn(|i| c.iter().filter_map(|&v| ours(v)).map(|w| mesh.vertices[w][i]).sum::<f64>() / c.len() as f64);
        println!(
            "piece {} vertices at {centroid:.2?} → ours {image_centroid:.2?}: mismatch ours {:.4} truth {:.4}, confidence {:.2}",
            c.len(),
            mean(c, &|v| fit(v, &ours)),
            mean(c, &|v| fit(v, &gt)),
            c.iter().map(|&v| s.confidence[v]).sum::<f64>() / c.len() as f64
        );
    }
}

/// The experiments behind `maps::geodesic` (run with `EXPERIMENTS=1`): how far each dense-map
/// method gets from the *true* sample correspondences.
pub fn experiments(mesh: &Mesh, pairs: &[(usize, Vec<usize>)]) {
    use intrinsym::maps;
    let params = Params::default();
    let basis = Eigenbasis::compute(mesh, &params.eigen).expect("basis");
    let emb = biharmonic(&basis);
    let desc = intrinsym::descriptors::wks(&basis, &params.wks);
    let samples = farthest_point(&emb, 64, 0).vertices;
    let diameter = samples.iter().flat_map(|&a| samples.iter().map(move |&b| (a, b))).map(|(a, b)| emb.dist(a, b)).fold(0.0, f64::max);
    let mut ctx = maps::Context::new(mesh, &emb, &desc, diameter, &params.maps);
    ctx.basis = Some(&basis);
    let acc = |m: &[usize]| {
        let m: Vec<i64> = m.iter().map(|&w| w as i64).collect();
        let a = eval::accuracy(mesh, &m, pairs, &[0.05, 0.1]);
        format!("{:.1}/{:.1}", 100.0 * a[0], 100.0 * a[1])
    };
    let n = mesh.num_vertices();
    let mut truth = vec![usize::MAX; n];
    for (v, t) in pairs {
        truth[*v] = t[0];
    }
    let true_anchors: Vec<(usize, usize)> = samples.iter().filter(|&&v| truth[v] != usize::MAX).map(|&v| (v, truth[v])).collect();
    if let Some(p) = maps::profile_map(&ctx, &true_anchors, &samples, 0.03 * diameter, &params.maps) {
        println!("biharmonic profile map from the true sample pairs: acc@0.05/0.10 {}", acc(&p.image));
    }
    let start: Vec<usize> = (0..n).map(|v| if truth[v] != usize::MAX { truth[v] } else { v }).collect();
    for k0 in [10, 100] {
        let mut image = start.clone();
        maps::zoomout(&basis, &ctx.adjacency, &mut image, k0, 100, 5);
        println!("ZoomOut {k0} → 100 started from the true map: {}", acc(&image));
    }
    let true_map = maps::DenseMap::from_image(start);
    // One polish pass from the true map: every sample pair is right, so this is the geodesic
    // dense matching alone.
    let geodesics = maps::geodesic::Geodesics::new(&ctx);
    let polished = maps::geodesic::polish(&ctx, &geodesics, &true_map, &samples, &params.maps);
    println!("geodesic profile map from the true sample pairs: {}", acc(&polished.image));
}
