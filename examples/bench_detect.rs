//! Detection benchmark: the whole pipeline at 2.5k–80k vertices, with per-stage times and the
//! accuracy of the best symmetry, as a Markdown table.
//!
//! `cargo run --release --example bench_detect [DATA_DIR] [RUNS] [tosca]` (default
//! `../shared/data`, 3 runs; the table shows the median run by total time; `tosca`: only the
//! TOSCA row). Shapes: the generated posed
//! quadruped at icosphere levels 4–6 (2.5k, 10k, 41k vertices) with its exact mirror; every
//! TOSCA shape of DATA_DIR (≈5k) as one summary row; and, scaled up by flat midpoint
//! subdivision ([`shapes::subdivide`], the same surface), TOSCA david0 ×1 and ×2 (20k, 80k) and
//! SHREC'16 kid00 ×1 (48k), scored on their original vertices' ground truth. acc@0.05 as in
//! `intrinsym-eval`. Times: wall-clock seconds of `detect` (mesh loading excluded).

use std::path::{Path, PathBuf};

use intrinsym::mesh::read_mesh;
use intrinsym::shapes::{self, Pose};
use intrinsym::{detect, eval, Detection, Mesh, MeshParams, Params};

type Truth = Vec<(usize, Vec<usize>)>;

/// A mesh file with its `.sym.txt` ground truth (input indices → processed indices).
fn load(path: &Path) -> Option<(Mesh, Truth)> {
    let raw = read_mesh(path).ok()?;
    let mut mp = MeshParams::default();
    mp.allow_non_manifold = true;
    let mesh = Mesh::new(raw.vertices, raw.triangles, &mp).ok()?;
    let mut to_mesh = vec![usize::MAX; mesh.info.input_vertices];
    for (i, &v) in mesh.input_index.iter().enumerate() {
        to_mesh[v as usize] = i;
    }
    let text = std::fs::read_to_string(path.with_extension("sym.txt")).ok()?;
    let truth = text
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace().map(|x| x.parse::<usize>());
            match (it.next(), it.next()) {
                (Some(Ok(a)), Some(Ok(b))) if a < to_mesh.len() && b < to_mesh.len() && to_mesh[a] != usize::MAX && to_mesh[b] != usize::MAX => Some((to_mesh[a], vec![to_mesh[b]])),
                _ => None,
            }
        })
        .collect();
    Some((mesh, truth))
}

fn subdivided(mesh: &Mesh, times: usize) -> Mesh {
    let mut mp = MeshParams::default();
    mp.allow_non_manifold = true;
    let mut m = mesh.clone();
    for _ in 0..times {
        m = shapes::subdivide(&m, &mp).expect("a subdivided valid mesh is valid");
    }
    m
}

struct Run {
    det: Detection,
    acc: f64,
}

/// `runs` detections; the median by total time.
fn bench(mesh: &Mesh, truth: &Truth, runs: usize) -> Run {
    let mut all: Vec<Run> = (0..runs.max(1))
        .map(|_| {
            let det = detect(mesh, &Params::default(), &mut |_| true).expect("detect");
            let acc = det.symmetries.iter().map(|s| eval::accuracy(mesh, &s.map, truth, &[0.05])[0]).fold(0.0, f64::max);
            Run { det, acc }
        })
        .collect();
    all.sort_by(|a, b| a.det.timings.total.total_cmp(&b.det.timings.total));
    let mid = all.len() / 2;
    all.swap_remove(mid)
}

fn row(name: &str, vertices: usize, r: &Run) {
    let t = &r.det.timings;
    println!(
        "| {name} | {vertices} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | **{:.2}** | {:.1}% |",
        t.spectral,
        t.descriptors + t.distance + t.sampling,
        t.voting,
        t.maps_proxy,
        t.maps_profile,
        t.maps_refine,
        t.maps_polish,
        t.maps_compose + t.maps_lift,
        t.characterize + t.cluster,
        t.total,
        100.0 * r.acc
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let data = PathBuf::from(args.get(1).map_or("../shared/data", String::as_str));
    let runs: usize = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(3);
    // `tosca` as a third argument: the TOSCA row only (quick comparisons at 5k).
    let only_tosca = args.get(3).is_some_and(|a| a == "tosca");
    println!("| shape | vertices | eigenbasis | WKS + distance + sampling | voting | proxy | profile | refine | polish | compose + lift | characterize | **total** | acc@0.05 |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let creature = |level: u32| {
        let c = shapes::quadruped(level, Pose::Walking, 0.0, 0);
        let truth: Truth = (0..c.mesh.num_vertices()).map(|v| (v, vec![c.mirror[v] as usize])).collect();
        (c.mesh, truth)
    };
    if !only_tosca {
        let (m, t) = creature(4);
        row("quadruped, posed (level 4)", m.num_vertices(), &bench(&m, &t, runs));
    }

    // TOSCA: one summary row (mean and range of the medians).
    let mut tosca: Vec<(String, usize, Run)> = Vec::new();
    if let Ok(entries) = std::fs::read_dir(data.join("tosca")) {
        let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).filter(|p| p.extension().is_some_and(|x| x == "off")).collect();
        paths.sort();
        for p in paths {
            if let Some((m, t)) = load(&p) {
                let name = p.file_stem().unwrap().to_string_lossy().to_string();
                tosca.push((name, m.num_vertices(), bench(&m, &t, runs)));
            }
        }
    }
    if !tosca.is_empty() {
        let totals: Vec<f64> = tosca.iter().map(|x| x.2.det.timings.total).collect();
        let mean = totals.iter().sum::<f64>() / totals.len() as f64;
        let (lo, hi) = totals.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        let acc = tosca.iter().map(|x| x.2.acc).sum::<f64>() / tosca.len() as f64;
        let avg = |f: &dyn Fn(&intrinsym::detect::Timings) -> f64| tosca.iter().map(|x| f(&x.2.det.timings)).sum::<f64>() / tosca.len() as f64;
        println!(
            "| TOSCA, {} shapes (mean; total {:.2}–{:.2}) | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | **{:.2}** | {:.1}% |",
            tosca.len(),
            lo,
            hi,
            tosca[0].1,
            avg(&|t| t.spectral),
            avg(&|t| t.descriptors + t.distance + t.sampling),
            avg(&|t| t.voting),
            avg(&|t| t.maps_proxy),
            avg(&|t| t.maps_profile),
            avg(&|t| t.maps_refine),
            avg(&|t| t.maps_polish),
            avg(&|t| t.maps_compose + t.maps_lift),
            avg(&|t| t.characterize + t.cluster),
            mean,
            100.0 * acc
        );
    }
    if only_tosca {
        return;
    }
    let (m, t) = creature(5);
    row("quadruped, posed (level 5)", m.num_vertices(), &bench(&m, &t, runs));
    if let Some((m, t)) = load(&data.join("tosca/david0.off")) {
        let s = subdivided(&m, 1);
        row("TOSCA david0, subdivided ×1", s.num_vertices(), &bench(&s, &t, runs));
    }
    let (m, t) = creature(6);
    row("quadruped, posed (level 6)", m.num_vertices(), &bench(&m, &t, runs));
    if let Some((m, t)) = load(&data.join("shrec16_kids/kid00.off")) {
        let s = subdivided(&m, 1);
        row("SHREC'16 kid00, subdivided ×1", s.num_vertices(), &bench(&s, &t, runs));
    }
    if let Some((m, t)) = load(&data.join("tosca/david0.off")) {
        let s = subdivided(&m, 2);
        row("TOSCA david0, subdivided ×2", s.num_vertices(), &bench(&s, &t, runs));
    }
}
