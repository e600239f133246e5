//! `intrinsym-eval`: the evaluation protocol of DESIGN.md on shapes with known symmetry.
//!
//! ```text
//! intrinsym-eval [--data DIR] [--generated] [--only NAME] [--set KEY=VALUE]...
//! ```
//! For every `NAME.off` with a `NAME.sym.txt` (two 0-based columns `x  sym_x`) under DIR
//! (default `../shared/data`, searched recursively one level), runs detection with default
//! parameters and scores the best-matching detected symmetry: accuracy@r = fraction of the
//! ground-truth pairs whose predicted image is within geodesic distance r·√area of the true one
//! (edge-graph Dijkstra; unmapped counts as wrong). `--generated` also scores the generated
//! shapes (posed and noisy quadrupeds, star). Prints a Markdown table. `--set` overrides one
//! parameter for an experiment (keys: see [`set_param`]).

use std::path::{Path, PathBuf};
use std::time::Instant;

use intrinsym::mesh::read_mesh;
use intrinsym::shapes::{self, Pose};
use intrinsym::{detect, eval, Mesh, MeshParams, Params};

struct Row {
    name: String,
    vertices: usize,
    acc05: f64,
    acc10: f64,
    seconds: f64,
    found: usize,
    rank: usize,
}

fn score(name: &str, mesh: &Mesh, truth: &[(usize, Vec<usize>)], params: &Params) -> Row {
    score_all(mesh, &[(name.to_string(), truth.to_vec())], params).remove(0)
}

/// Sets one parameter from `key=value`.
fn set_param(p: &mut Params, kv: &str) -> Result<(), String> {
    let (key, value) = kv.split_once('=').ok_or_else(|| format!("--set wants KEY=VALUE, got {kv}"))?;
    let f = || value.parse::<f64>().map_err(|e| format!("{key}: {e}"));
    let u = || value.parse::<usize>().map_err(|e| format!("{key}: {e}"));
    match key {
        "k" => p.eigen.k = u()?,
        "samples" => p.samples = u()?,
        "seed" => p.seed = u()? as u64,
        "eps" => p.voting.eps = f()?,
        "wks_quantile" => p.voting.wks_quantile = f()?,
        "max_distortion" => p.max_distortion = f()?,
        "max_candidates" => p.max_candidates = u()?,
        "max_refinements" => p.max_refinements = u()?,
        "patience" => p.patience = u()?,
        "accept" => p.maps.accept = f()?,
        "zoomout_k" => p.maps.zoomout_k = u()?,
        "zoomout_step" => p.maps.zoomout_step = u()?,
        "spectral_start" => p.maps.spectral_start = u()?,
        "polish" => p.maps.polish = u()?,
        "polish_samples" => p.maps.polish_samples = u()?,
        "local_anchors" => p.maps.local_anchors = u()?,
        "search_vertices" => p.maps.search_vertices = u()?,
        "global_fraction" => p.maps.global_fraction = f()?,
        "proxy_vertices" => p.maps.proxy_vertices = u()?,
        _ => return Err(format!("unknown parameter {key}")),
    }
    Ok(())
}

/// One detection, scored against each of several known symmetries (a row each).
fn score_all(mesh: &Mesh, truths: &[(String, Vec<(usize, Vec<usize>)>)], params: &Params) -> Vec<Row> {
    let t = Instant::now();
    let det = detect(mesh, params, &mut |_| true);
    let seconds = t.elapsed().as_secs_f64();
    let found = det.as_ref().map_or(0, |d| d.symmetries.len());
    truths
        .iter()
        .map(|(name, truth)| {
            let mut best = (0.0, 0.0, 0usize);
            match &det {
                Ok(d) => {
                    for (i, s) in d.symmetries.iter().enumerate() {
                        let a = eval::accuracy(mesh, &s.map, truth, &[0.05, 0.10]);
                        if a[0] > best.0 || (a[0] == best.0 && a[1] > best.1) {
                            best = (a[0], a[1], i + 1);
                        }
                    }
                }
                Err(e) => eprintln!("{name}: {e}"),
            }
            Row { name: name.clone(), vertices: mesh.num_vertices(), acc05: best.0, acc10: best.1, seconds, found, rank: best.2 }
        })
        .collect()
}

fn read_truth(path: &Path) -> Vec<(usize, Vec<usize>)> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace().map(|x| x.parse::<usize>());
            match (it.next(), it.next()) {
                (Some(Ok(a)), Some(Ok(b))) => Some((a, vec![b])),
                _ => None,
            }
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut data = PathBuf::from("../shared/data");
    let mut generated = false;
    let mut only: Option<String> = None;
    let mut params = Params::default();
    let mut i = 1;
    while i < args.len() {
        match args[i].as_str() {
            "--data" => {
                i += 1;
                data = PathBuf::from(&args[i]);
            }
            "--generated" => generated = true,
            "--only" => {
                i += 1;
                only = Some(args[i].clone());
            }
            "--set" => {
                i += 1;
                if let Err(e) = args.get(i).ok_or_else(|| "--set wants KEY=VALUE".to_string()).and_then(|kv| set_param(&mut params, kv)) {
                    eprintln!("intrinsym-eval: {e}");
                    std::process::exit(2);
                }
            }
            other => {
                eprintln!("usage: intrinsym-eval [--data DIR] [--generated] [--only NAME] [--set KEY=VALUE]... (unknown {other})");
                std::process::exit(2);
            }
        }
        i += 1;
    }
    println!("| shape | vertices | acc@0.05 | acc@0.10 | time s | symmetries | rank of best |");
    println!("|---|---|---|---|---|---|---|");
    let print = |r: &Row| {
        println!("| {} | {} | {:.1}% | {:.1}% | {:.2} | {} | {} |", r.name, r.vertices, 100.0 * r.acc05, 100.0 * r.acc10, r.seconds, r.found, r.rank);
    };
    let mut offs: Vec<PathBuf> = Vec::new();
    for dir in std::iter::once(data.clone()).chain(std::fs::read_dir(&data).into_iter().flatten().flatten().map(|e| e.path())) {
        if let Ok(entries) = std::fs::read_dir(&dir) {
            for e in entries.flatten() {
                let p = e.path();
                if p.extension().is_some_and(|x| x == "off") && p.with_extension("sym.txt").exists() {
                    offs.push(p);
                }
            }
        }
    }
    offs.sort();
    let mut rows = Vec::new();
    for p in offs {
        let name = p.file_stem().unwrap().to_string_lossy().to_string();
        if only.as_ref().is_some_and(|o| !name.contains(o.as_str())) {
            continue;
        }
        let raw = match read_mesh(&p) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("{e}");
                continue;
            }
        };
        // SHREC'16 kids have self-contacts glued into non-manifold edges: accept them here.
        let mut mp = MeshParams::default();
        mp.allow_non_manifold = true;
        let mesh = match Mesh::new(raw.vertices, raw.triangles, &mp) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        // Ground truth is in input indices; translate to the processed mesh (ignored vertices drop out).
        let mut to_mesh = vec![usize::MAX; mesh.info.input_vertices];
        for (i, &v) in mesh.input_index.iter().enumerate() {
            to_mesh[v as usize] = i;
        }
        let truth: Vec<(usize, Vec<usize>)> = read_truth(&p.with_extension("sym.txt"))
            .into_iter()
            .filter(|(a, b)| *a < to_mesh.len() && b[0] < to_mesh.len() && to_mesh[*a] != usize::MAX && to_mesh[b[0]] != usize::MAX)
            .map(|(a, b)| (to_mesh[a], vec![to_mesh[b[0]]]))
            .collect();
        let r = score(&name, &mesh, &truth, &params);
        print(&r);
        rows.push(r);
    }
    if generated {
        let cases: Vec<(&str, shapes::Creature)> = vec![
            ("quadruped (rest)", shapes::quadruped(5, Pose::Rest, 0.0, 0)),
            ("quadruped (posed)", shapes::quadruped(5, Pose::Walking, 0.0, 0)),
            ("quadruped (posed, 0.2% noise)", shapes::quadruped(5, Pose::Walking, 0.002, 1)),
            ("quadruped (posed, 0.5% noise)", shapes::quadruped(5, Pose::Walking, 0.005, 2)),
        ];
        for (name, c) in cases {
            if only.as_ref().is_some_and(|o| !name.contains(o.as_str())) {
                continue;
            }
            let truth: Vec<(usize, Vec<usize>)> = (0..c.mesh.num_vertices()).map(|v| (v, vec![c.mirror[v] as usize])).collect();
            let r = score(name, &c.mesh, &truth, &params);
            print(&r);
            rows.push(r);
        }
        // The star: every one of its 9 symmetries, each scored against the best detected map.
        if only.as_ref().is_none_or(|o| "star".contains(o.as_str())) {
            let c = shapes::star(5, 5);
            let truths: Vec<(String, Vec<(usize, Vec<usize>)>)> = shapes::star_symmetries(&c, 5)
                .into_iter()
                .map(|(name, map)| (format!("star, 5 arms: {name}"), map.iter().enumerate().map(|(v, &w)| (v, vec![w as usize])).collect()))
                .collect();
            for r in score_all(&c.mesh, &truths, &params) {
                print(&r);
                rows.push(r);
            }
        }
    }
    if !rows.is_empty() {
        let mean05 = rows.iter().map(|r| r.acc05).sum::<f64>() / rows.len() as f64;
        let mean10 = rows.iter().map(|r| r.acc10).sum::<f64>() / rows.len() as f64;
        let time = rows.iter().map(|r| r.seconds).sum::<f64>() / rows.len() as f64;
        println!("| **mean** | | {:.1}% | {:.1}% | {:.2} | | |", 100.0 * mean05, 100.0 * mean10, time);
    }
}
