//! `intrinsym-eval`: the evaluation protocol of DESIGN.md on shapes with known symmetry.
//!
//! ```text
//! intrinsym-eval [--data DIR] [--peer DIR] [--tsv FILE] [--symmetries FILE] [--judge-truth] [--generated] [--only NAME] [--set KEY=VALUE]...
//! ```
//! For every `NAME.off` with a `NAME.sym.txt` (two 0-based columns `x  sym_x`) under DIR
//! (default `../shared/data`, searched recursively one level), runs detection with default
//! parameters and scores the best-matching detected symmetry: accuracy@r = fraction of the
//! ground-truth pairs whose predicted image is within geodesic distance r·√area of the true one
//! (edge-graph Dijkstra; unmapped counts as wrong). `--generated` also scores the generated
//! shapes (posed and noisy quadrupeds, star). Prints a Markdown table. `--set` overrides one
//! parameter for an experiment (keys: see [`set_param`]). `--judge-truth` adds to the
//! `--symmetries` table a line per shape for the ground truth itself (index `truth`): the
//! judge's verdict on it, as [`intrinsym::eval::judge_maps`] gives it, and prints a table of
//! the shapes whose first symmetry is below 0.7 with the cause: search or judge.

use std::path::{Path, PathBuf};
use std::time::Instant;

use intrinsym::mesh::read_mesh;
use intrinsym::shapes::{self, Pose};
use intrinsym::{detect, eval, Mesh, MeshParams, Params};

struct Row {
    dataset: String,
    name: String,
    vertices: usize,
    /// Best of the reported symmetries, at 0.05 and 0.10.
    acc05: f64,
    acc10: f64,
    /// The first reported symmetry (what MeshLab colours by default).
    first05: f64,
    first10: f64,
    /// The peer's map (pyFM), when one is cached.
    peer: Option<(f64, f64)>,
    seconds: f64,
    found: usize,
    rank: usize,
    /// Every reported symmetry with its accuracy and the judge's terms, a TSV line each
    /// (`--symmetries FILE`: the data the judge's design is checked on).
    symmetries: Vec<String>,
    /// Each reported symmetry's acc@0.05 and judge's score, in report order.
    scores: Vec<(f64, f64)>,
    /// The judge's score of the ground truth and the truth's stencil coverage (`--judge-truth`).
    truth: Option<(f64, f64)>,
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
        "restarts" => p.restarts = u()?,
        "restart_below" => p.restart_below = f()?,
        "eps" => p.voting.eps = f()?,
        "wks_quantile" => p.voting.wks_quantile = f()?,
        "max_distortion" => p.max_distortion = f()?,
        "max_candidates" => p.max_candidates = u()?,
        "min_score_ratio" => p.min_score_ratio = f()?,
        "global_preference" => p.global_preference = f()?,
        "max_refinements" => p.max_refinements = u()?,
        "patience" => p.patience = u()?,
        "accept" => p.maps.accept = f()?,
        "zoomout_k" => p.maps.zoomout_k = u()?,
        "zoomout_step" => p.maps.zoomout_step = u()?,
        "spectral_start" => p.maps.spectral_start = u()?,
        "polish" => p.maps.polish = u()?,
        "final_polish" => p.maps.final_polish = u()?,
        "final_polish_maps" => p.maps.final_polish_maps = u()?,
        "winner_polish" => p.maps.winner_polish = u()?,
        "polish_samples" => p.maps.polish_samples = u()?,
        "polish_geodesic" => p.maps.polish_geodesic = u()? != 0,
        "curvature_weight" => p.maps.curvature_weight = f()?,
        "curvature_time" => p.maps.curvature_time = f()?,
        "local_anchors" => p.maps.local_anchors = u()?,
        "search_vertices" => p.maps.search_vertices = u()?,
        "global_fraction" => p.maps.global_fraction = f()?,
        "proxy_vertices" => p.maps.proxy_vertices = u()?,
        "lift_polish" => p.maps.lift_polish = u()?,
        "parity_flips" => p.maps.parity_flips = u()?,
        "parity_variants" => p.maps.parity_variants = u()?,
        "hierarchy_vertices" => p.hierarchy_vertices = u()?,
        "max_hole" => p.max_hole = f()?,
        "min_hole" => p.min_hole = f()?,
        "fixed_radius" => p.judge.fixed_radius = f()?,
        "stencil" => p.judge.stencil = f()?,
        "max_fixed" => p.max_fixed = f()?,
        "max_curvature_change" => p.max_curvature_change = f()?,
        "max_fixed_preserving" => p.max_fixed_preserving = f()?,
        "fmap_k" => p.maps.orientation.k = u()?,
        "fmap_descriptors" => p.maps.orientation.descriptors = u()?,
        "orientation_near" => p.maps.orientation.w_near = f()?,
        "near_reflections" => p.maps.orientation.near_reflections = u()? != 0,
        _ => return Err(format!("unknown parameter {key}")),
    }
    Ok(())
}

/// A named known symmetry: each covered vertex with its acceptable images.
type Truth = (String, Vec<(usize, Vec<usize>)>);

/// One detection, scored against each of several known symmetries (a row each).
fn score_all(mesh: &Mesh, truths: &[Truth], params: &Params) -> Vec<Row> {
    let t = Instant::now();
    let det = detect(mesh, params, &mut |_| true);
    let seconds = t.elapsed().as_secs_f64();
    let found = det.as_ref().map_or(0, |d| d.symmetries.len());
    // Maps are in input indices; the scorer works on the processed mesh (welded, isolated or
    // ignored vertices drop out).
    let mut to_mesh = vec![-1i64; mesh.info.input_vertices];
    for (i, &v) in mesh.input_index.iter().enumerate() {
        to_mesh[v as usize] = i as i64;
    }
    let processed = |map: &[i64]| -> Vec<i64> {
        let mut out = vec![-1i64; mesh.num_vertices()];
        for (i, &v) in mesh.input_index.iter().enumerate() {
            let image = map[v as usize];
            if image >= 0 {
                out[i] = to_mesh[image as usize];
            }
        }
        out
    };
    truths
        .iter()
        .map(|(name, truth)| {
            let mut best = (0.0, 0.0, 0usize);
            let mut first = (0.0, 0.0);
            let mut symmetries = Vec::new();
            let mut scores = Vec::new();
            match &det {
                Ok(d) => {
                    for (i, s) in d.symmetries.iter().enumerate() {
                        let a = eval::accuracy(mesh, &processed(&s.map), truth, &[0.05, 0.10]);
                        let v = &s.verdict;
                        symmetries.push(format!(
                            "{name}\t{i}\t{:.4}\t{:.4}\t{}\t{}\t{:.4}\t{:.4}\t{:.4}\t{:.5}\t{:.4}\t{:.4}\t{:.4}\t{:.4}",
                            a[0], a[1], s.kind.as_str(), s.order, v.reversal, v.fixed, v.coverage, s.distortion, s.complexity, v.score, v.curvature, v.band_trace
                        ));
                        scores.push((a[0], v.score));
                        if i == 0 {
                            first = (a[0], a[1]);
                        }
                        if a[0] > best.0 || (a[0] == best.0 && a[1] > best.1) {
                            best = (a[0], a[1], i + 1);
                        }
                    }
                }
                Err(e) => eprintln!("{name}: {e}"),
            }
            Row {
                dataset: String::new(),
                name: name.clone(),
                vertices: mesh.num_vertices(),
                acc05: best.0,
                acc10: best.1,
                first05: first.0,
                first10: first.1,
                peer: None,
                seconds,
                found,
                rank: best.2,
                symmetries,
                scores,
                truth: None,
            }
        })
        .collect()
}

/// The `--symmetries` line of the ground truth itself (index `truth`): the verdict the judge
/// would give it ([`eval::judge_maps`]), to tell a failed search (the truth outscores what was
/// reported) from a failed judge (a wrong map outscores the truth).
fn truth_line(name: &str, mesh: &Mesh, truth: &[(usize, Vec<usize>)], params: &Params) -> (String, Option<(f64, f64)>) {
    let mut map = vec![-1i64; mesh.num_vertices()];
    for (a, b) in truth {
        map[*a] = b[0] as i64;
    }
    let a = eval::accuracy(mesh, &map, truth, &[0.05, 0.10]);
    match eval::judge_maps(mesh, params, &[map]) {
        Ok(v) => {
            let (v, distortion) = &v[0];
            let line = format!("{name}\ttruth\t{:.4}\t{:.4}\tglobal\t2\t{:.4}\t{:.4}\t{:.4}\t{:.5}\tNaN\t{:.4}\t{:.4}\t{:.4}", a[0], a[1], v.reversal, v.fixed, v.coverage, distortion, v.score, v.curvature, v.band_trace);
            (line, Some((v.score, v.coverage)))
        }
        Err(e) => {
            eprintln!("{name}: the truth's verdict: {e}");
            (format!("{name}\ttruth\t{:.4}\t{:.4}\tglobal\t2\tNaN\tNaN\tNaN\tNaN\tNaN\tNaN\tNaN", a[0], a[1]), None)
        }
    }
}

/// Reads a cached peer map (`NAME.map`, one image vertex per input vertex) and scores it.
fn score_peer(path: &Path, mesh: &Mesh, to_mesh: &[usize], truth: &[(usize, Vec<usize>)]) -> Option<(f64, f64)> {
    let text = std::fs::read_to_string(path).ok()?;
    let input: Vec<i64> = text.lines().map(|l| l.trim().parse::<i64>().unwrap_or(-1)).collect();
    if input.len() != to_mesh.len() {
        eprintln!("{}: {} entries for {} vertices, ignored", path.display(), input.len(), to_mesh.len());
        return None;
    }
    let mut pred = vec![-1i64; mesh.num_vertices()];
    for (v, &w) in input.iter().enumerate() {
        if to_mesh[v] != usize::MAX && w >= 0 && (w as usize) < to_mesh.len() && to_mesh[w as usize] != usize::MAX {
            pred[to_mesh[v]] = to_mesh[w as usize] as i64;
        }
    }
    let a = eval::accuracy(mesh, &pred, truth, &[0.05, 0.10]);
    Some((a[0], a[1]))
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

fn pct(x: f64) -> String {
    format!("{:.1}%", 100.0 * x)
}

fn print_row(r: &Row) {
    let peer = r.peer.map_or("–".to_string(), |p| pct(p.0));
    println!(
        "| {} | {} | {} | {} | {} | {} | {} | {:.2} | {} | {} |",
        r.dataset,
        r.name,
        r.vertices,
        pct(r.acc05),
        pct(r.acc10),
        pct(r.first05),
        peer,
        r.seconds,
        r.found,
        r.rank
    );
}

/// The per-dataset summary: means of best, first and peer, shapes below 0.5, first = best.
fn print_summary(rows: &[Row]) {
    let mut sets: Vec<String> = rows.iter().map(|r| r.dataset.clone()).collect();
    sets.dedup();
    sets.push("all".into());
    println!();
    println!("| dataset | shapes | best @0.05 | first @0.05 | pyFM @0.05 | best @0.10 | first @0.10 | pyFM @0.10 | best < 0.5 | pyFM < 0.5 | first is best | mean time s |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for set in sets {
        let rs: Vec<&Row> = rows.iter().filter(|r| set == "all" || r.dataset == set).collect();
        let n = rs.len() as f64;
        let mean = |f: &dyn Fn(&Row) -> f64| rs.iter().map(|r| f(r)).sum::<f64>() / n;
        let peers: Vec<(f64, f64)> = rs.iter().filter_map(|r| r.peer).collect();
        let peer = |k: usize| {
            if peers.len() == rs.len() {
                pct(peers.iter().map(|p| if k == 0 { p.0 } else { p.1 }).sum::<f64>() / n)
            } else if peers.is_empty() {
                "–".into()
            } else {
                format!("{} ({} of {})", pct(peers.iter().map(|p| if k == 0 { p.0 } else { p.1 }).sum::<f64>() / peers.len() as f64), peers.len(), rs.len())
            }
        };
        // "first is best": the first reported symmetry within half a point of the best one.
        let first_is_best = rs.iter().filter(|r| r.first05 + 0.005 >= r.acc05).count();
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} of {} | {:.2} |",
            set,
            rs.len(),
            pct(mean(&|r| r.acc05)),
            pct(mean(&|r| r.first05)),
            peer(0),
            pct(mean(&|r| r.acc10)),
            pct(mean(&|r| r.first10)),
            peer(1),
            rs.iter().filter(|r| r.acc05 < 0.5).count(),
            if peers.is_empty() { "–".into() } else { peers.iter().filter(|p| p.0 < 0.5).count().to_string() },
            first_is_best,
            rs.len(),
            mean(&|r| r.seconds)
        );
    }
}

/// `--judge-truth`: every shape whose first symmetry is below 0.7 at acc@0.05, with the cause.
/// The truth's score is divided by its stencil coverage (annotations leave vertices out, and
/// the score counts them against it). *search*: that outscores every reported map, so the
/// truth was not found; *judge*: a wrong reported map (acc@0.05 < 0.5) outscores it, so it
/// would lose even if found; otherwise *neither*.
fn print_causes(rows: &[Row]) {
    println!();
    println!("| dataset | shape | first / best @0.05 | truth's score (over coverage) | best reported score | best wrong score | cause |");
    println!("|---|---|---|---|---|---|---|");
    for r in rows.iter().filter(|r| r.first05 < 0.7) {
        let Some((score, coverage)) = r.truth else { continue };
        let truth = if coverage > 0.0 { score / coverage } else { score };
        let top = r.scores.iter().map(|s| s.1).fold(0.0, f64::max);
        let wrong = r.scores.iter().filter(|s| s.0 < 0.5).map(|s| s.1).fold(f64::NAN, f64::max);
        let cause = if truth > top {
            "search"
        } else if wrong > truth {
            "judge"
        } else {
            "neither"
        };
        let wrong = if wrong.is_nan() { "–".to_string() } else { format!("{wrong:.3}") };
        println!("| {} | {} | {:.2} / {:.2} | {:.3} ({:.3}) | {:.3} | {} | {} |", r.dataset, r.name, r.first05, r.acc05, score, truth, top, wrong, cause);
    }
}

/// Writes every row as tab-separated values (for comparing runs: `bench/compare_eval.py`).
fn write_tsv(path: &Path, rows: &[Row]) -> std::io::Result<()> {
    let mut out = String::from("dataset\tshape\tvertices\tbest05\tbest10\tfirst05\tfirst10\tpeer05\tpeer10\tseconds\tfound\trank\n");
    for r in rows {
        let (p5, p10) = r.peer.map_or((f64::NAN, f64::NAN), |p| p);
        out += &format!(
            "{}\t{}\t{}\t{:.4}\t{:.4}\t{:.4}\t{:.4}\t{:.4}\t{:.4}\t{:.3}\t{}\t{}\n",
            r.dataset, r.name, r.vertices, r.acc05, r.acc10, r.first05, r.first10, p5, p10, r.seconds, r.found, r.rank
        );
    }
    std::fs::write(path, out)
}

const USAGE: &str = "usage: intrinsym-eval [--data DIR] [--peer DIR] [--tsv FILE] [--symmetries FILE] [--judge-truth] [--generated] [--only NAME] [--set KEY=VALUE]...";

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut data = PathBuf::from("../shared/data");
    let mut peer_dir: Option<PathBuf> = std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache/intrinsym/pyfm"));
    let mut tsv: Option<PathBuf> = None;
    let mut symmetries_tsv: Option<PathBuf> = None;
    let mut generated = false;
    let mut judge_truth = false;
    let mut only: Option<String> = None;
    let mut params = Params::default();
    let mut i = 1;
    let value = |i: usize| -> String {
        args.get(i).cloned().unwrap_or_else(|| {
            eprintln!("{USAGE} ({} wants a value)", args[i - 1]);
            std::process::exit(2);
        })
    };
    while i < args.len() {
        match args[i].as_str() {
            "--data" => {
                i += 1;
                data = PathBuf::from(value(i));
            }
            "--peer" => {
                i += 1;
                peer_dir = Some(PathBuf::from(value(i)));
            }
            "--tsv" => {
                i += 1;
                tsv = Some(PathBuf::from(value(i)));
            }
            "--symmetries" => {
                i += 1;
                symmetries_tsv = Some(PathBuf::from(value(i)));
            }
            "--generated" => generated = true,
            "--judge-truth" => judge_truth = true,
            "--only" => {
                i += 1;
                only = Some(value(i));
            }
            "--set" => {
                i += 1;
                if let Err(e) = set_param(&mut params, &value(i)) {
                    eprintln!("intrinsym-eval: {e}");
                    std::process::exit(2);
                }
            }
            other => {
                eprintln!("{USAGE} (unknown {other})");
                std::process::exit(2);
            }
        }
        i += 1;
    }
    println!("| dataset | shape | vertices | best @0.05 | best @0.10 | first @0.05 | pyFM @0.05 | time s | symmetries | rank of best |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
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
        let dataset = p.parent().and_then(|d| d.file_name()).map_or(String::new(), |d| d.to_string_lossy().to_string());
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
        let mut r = score(&name, &mesh, &truth, &params);
        r.dataset = dataset;
        if judge_truth {
            let (line, verdict) = truth_line(&name, &mesh, &truth, &params);
            r.symmetries.push(line);
            r.truth = verdict;
        }
        r.peer = peer_dir.as_ref().and_then(|d| score_peer(&d.join(format!("{name}.map")), &mesh, &to_mesh, &truth));
        print_row(&r);
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
            let mut r = score(name, &c.mesh, &truth, &params);
            r.dataset = "generated".into();
            print_row(&r);
            rows.push(r);
        }
        // The star: every one of its 19 symmetries, each scored against the best detected map.
        if only.as_ref().is_none_or(|o| "star".contains(o.as_str())) {
            let c = shapes::star(5, 5);
            let truths: Vec<Truth> = shapes::star_symmetries(&c, 5)
                .into_iter()
                .map(|(name, map)| (format!("star, 5 arms: {name}"), map.iter().enumerate().map(|(v, &w)| (v, vec![w as usize])).collect()))
                .collect();
            for mut r in score_all(&c.mesh, &truths, &params) {
                r.dataset = "star".into();
                print_row(&r);
                rows.push(r);
            }
        }
    }
    if !rows.is_empty() {
        print_summary(&rows);
        if judge_truth {
            print_causes(&rows);
        }
    }
    if let Some(path) = symmetries_tsv {
        let mut out = String::from("shape\tindex\tacc05\tacc10\tkind\torder\treversal\tfixed\tcoverage\tdistortion\tcomplexity\tscore\tcurvature\tband\n");
        for line in rows.iter().flat_map(|r| &r.symmetries) {
            out += line;
            out.push('\n');
        }
        if let Err(e) = std::fs::write(&path, out) {
            eprintln!("intrinsym-eval: {}: {e}", path.display());
            std::process::exit(1);
        }
    }
    if let Some(path) = tsv {
        if let Err(e) = write_tsv(&path, &rows) {
            eprintln!("intrinsym-eval: {}: {e}", path.display());
            std::process::exit(1);
        }
    }
}
