//! `intrinsym`: the command-line front end.
//!
//! ```text
//! intrinsym detect INPUT [--json OUT.json] [--ply OUT.ply] [--report OUT.svg|.html] [params…]
//! intrinsym spectrum INPUT [-k 100] [--json]   Laplace–Beltrami eigenvalues, timing, checks
//! intrinsym generate SHAPE OUTPUT.off [--size S] generated test shapes
//! ```

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{CommandFactory, Parser, Subcommand, ValueEnum};
use intrinsym::mesh::{read_mesh, write_off, ComponentPolicy};
use intrinsym::{detect, shapes, Eigenbasis, EigenParams, Mesh, MeshParams, Params};

#[derive(Parser)]
#[command(name = "intrinsym", version, about = "Detect and characterize intrinsic symmetries of triangle meshes")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Detect the intrinsic symmetries of a mesh (OFF, PLY, OBJ or STL).
    Detect {
        /// Input mesh.
        input: PathBuf,
        /// Write the full result (maps, confidences, functional maps) as JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write the mesh as PLY with per-vertex colour (a vertex and its image under the
        /// first reported symmetry share a colour) and quality (symmetry confidence).
        #[arg(long)]
        ply: Option<PathBuf>,
        /// Write a picture of the symmetry space and of each functional map (.svg or .html).
        #[arg(long, value_parser = report_path)]
        report: Option<PathBuf>,
        /// Eigenpairs of the Laplace–Beltrami operator, 3 to 1000.
        #[arg(short, long, default_value_t = 100, value_parser = eigenpairs)]
        k: usize,
        /// Farthest-point samples, 8 to 1000 (the paper uses 20–100).
        #[arg(long, default_value_t = 64, value_parser = sample_count)]
        samples: usize,
        /// Random seed (first sample, eigensolver start).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Further searches from other first samples (seeds seed+1, seed+2, …) while the strongest symmetry found scores below 0.4; their symmetries are pooled, 0 to 8 (0: one search).
        #[arg(long, default_value_t = 2, value_parser = restart_count)]
        restarts: usize,
        /// Leave out symmetries whose score is below this fraction of the strongest one's, and (above 0) global maps that are weaker versions of a reported one, in [0, 1] (0: report every one found).
        #[arg(long, default_value_t = 0.2, value_parser = fraction)]
        min_score_ratio: f64,
        /// Report a partial symmetry before a global one only if it scores more than this many times higher, ≥ 1 (1: rank by score alone).
        #[arg(long, default_value_t = 3.0, value_parser = at_least_one)]
        global_preference: f64,
        /// Good voters: WKS distance below this quantile of all sample pairs, in (0, 1].
        #[arg(long, default_value_t = 0.2, value_parser = positive_fraction)]
        wks_quantile: f64,
        /// Voting tolerance ε, fraction of the biharmonic diameter, in (0, 0.5].
        #[arg(long, default_value_t = 0.04, value_parser = tolerance)]
        eps: f64,
        /// Region tolerance: mean distance mismatch as a fraction of the diameter, in (0, 0.5].
        #[arg(long, default_value_t = 0.03, value_parser = tolerance)]
        accept: f64,
        /// Passes of the geodesic polish of every map (0 disables it).
        #[arg(long, default_value_t = 4)]
        polish: usize,
        /// Further passes of the polish for each search's two strongest symmetries, after
        /// the others are ranked (0: none; none either with --polish 0).
        #[arg(long, default_value_t = 8)]
        final_polish: usize,
        /// Further passes of the polish for the strongest symmetry over all searches, once they
        /// are pooled (0: none; none either with --polish 0).
        #[arg(long, default_value_t = intrinsym::maps::MapParams::default().winner_polish)]
        winner_polish: usize,
        /// Weight of the polish's extrinsic cue, band-limited mean curvature, which also ranks
        /// the output and drops maps that change it far more than a true symmetry does (≥ 0;
        /// 0: purely intrinsic maps and ranking, e.g. for a shape that bends without stretching
        /// everywhere).
        #[arg(long, default_value_t = 0.03, value_parser = non_negative)]
        curvature_weight: f64,
        /// On meshes of more than 1.5 times this many vertices, make the maps on a proxy of this
        /// many vertices and lift them to every vertex; 0 (always on the whole mesh) or 1000
        /// to 1000000.
        #[arg(long, default_value_t = 6000, value_parser = vertex_budget)]
        proxy_vertices: usize,
        /// Passes of the polish on the mesh itself for each search's strongest map lifted
        /// from the proxy (0: none; none either with --polish 0 or without a proxy).
        #[arg(long, default_value_t = intrinsym::maps::MapParams::default().lift_polish)]
        lift_polish: usize,
        /// On a component of more than 4 times this many vertices, detect on a coarse mesh of
        /// this many vertices and lift the maps to every vertex; 0 (always at full resolution)
        /// or 1000 to 1000000.
        #[arg(long, default_value_t = 6000, value_parser = vertex_budget)]
        hierarchy_vertices: usize,
        /// Cap every hole (boundary loop) from 0.4 to this many times √area long before
        /// detecting; the rims of open surfaces are longer (a hemisphere's 2.5) and stay open
        /// (0: never cap).
        #[arg(long, default_value_t = intrinsym::mesh::holes::MAX_LOOP, value_parser = non_negative)]
        max_hole: f64,
        /// Number of symmetry groups, 1 to 64 (default, or 0: automatic).
        #[arg(long, value_parser = group_count)]
        groups: Option<usize>,
        /// Also look for partial symmetries between repeated parts that no global symmetry
        /// carries (a front paw onto a hind paw; experimental, see `intrinsym::parts`).
        #[arg(long)]
        parts: bool,
        /// Refuse edges shared by more than two triangles (by default they are accepted and
        /// counted).
        #[arg(long)]
        reject_non_manifold: bool,
        /// Accepted for compatibility: non-manifold edges are accepted by default now.
        #[arg(long, hide = true)]
        allow_non_manifold: bool,
        /// Do not weld coincident vertices.
        #[arg(long)]
        no_weld: bool,
        /// Refuse meshes with several connected components instead of processing each.
        #[arg(long, conflicts_with = "largest_component")]
        reject_disconnected: bool,
        /// Process only the largest connected component (by area) instead of each one of at
        /// least 1% of its area.
        #[arg(long)]
        largest_component: bool,
    },
    /// Compute the k lowest Laplace–Beltrami eigenpairs of a mesh (OFF, PLY, OBJ or STL).
    Spectrum {
        /// Input mesh.
        input: PathBuf,
        /// Number of eigenpairs, including the constant one.
        #[arg(short, long, default_value_t = 100)]
        k: usize,
        /// Refuse meshes with several connected components instead of using the largest.
        #[arg(long)]
        reject_disconnected: bool,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write a generated shape as OFF.
    Generate {
        /// Which shape.
        shape: Shape,
        /// Output file (.off).
        output: PathBuf,
        /// Size: the icosphere's subdivision level for every shape but the torus (0–8, default
        /// 5: 10,242 vertices for the sphere, 655,362 at 8), or the torus's grid size (3–1000,
        /// default 34: 3·size² vertices).
        #[arg(long)]
        size: Option<usize>,
        /// For the quadrupeds: also write the true left–right map as `x sym_x` lines.
        #[arg(long)]
        truth: Option<PathBuf>,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum Shape {
    Icosphere,
    Torus,
    NeedleSphere,
    /// A posed four-legged animal (icosphere level `size`, e.g. 4 or 5).
    Quadruped,
    /// The same animal in its mirror-symmetric rest pose (x → −x is an exact symmetry).
    QuadrupedRest,
    /// A flat five-armed star (icosphere level `size`).
    Star,
    /// A posed four-legged animal whose identical legs are directed (knee, toe forward): its
    /// front and hind legs map onto each other by a translation, no global symmetry.
    DirectedQuadruped,
    /// A long body with three identical directed spikes in a row.
    Spiked,
}

fn main() -> ExitCode {
    intrinsym::ffi::process::default_sigpipe();
    let cli = Cli::parse();
    if let Command::Generate { shape, size: Some(size), .. } = &cli.command {
        let (range, what, _) = size_spec(*shape);
        if !range.contains(size) {
            let message = format!("--size {size} is out of range for this shape: {what} from {} to {}", range.start(), range.end());
            Cli::command().error(clap::error::ErrorKind::ValueValidation, message).exit();
        }
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("intrinsym: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), intrinsym::Error> {
    match cli.command {
        Command::Detect {
            input,
            json,
            ply,
            report,
            k,
            samples,
            seed,
            restarts,
            min_score_ratio,
            global_preference,
            wks_quantile,
            eps,
            accept,
            polish,
            final_polish,
            winner_polish,
            curvature_weight,
            proxy_vertices,
            lift_polish,
            hierarchy_vertices,
            max_hole,
            groups,
            parts,
            reject_non_manifold,
            allow_non_manifold: _,
            no_weld,
            reject_disconnected,
            largest_component,
        } => {
            // An output that cannot be written fails now, not after the detection.
            for path in [&json, &ply, &report].into_iter().flatten() {
                let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
                if !dir.is_dir() {
                    let source = std::io::Error::new(std::io::ErrorKind::NotFound, format!("its folder {} does not exist (nothing was detected)", dir.display()));
                    return Err(intrinsym::mesh::IoError::Os { path: path.clone(), source }.into());
                }
            }
            let raw = read_mesh(&input)?;
            let mut mp = MeshParams::default();
            mp.allow_non_manifold = !reject_non_manifold;
            mp.weld = !no_weld;
            if reject_disconnected {
                mp.components = ComponentPolicy::Reject;
            }
            if largest_component {
                mp.components = ComponentPolicy::Largest;
            }
            let mesh = Mesh::new(raw.vertices.clone(), raw.triangles.clone(), &mp)?;
            let mut params = Params::default();
            params.eigen.k = k;
            params.samples = samples;
            params.seed = seed;
            params.restarts = restarts;
            params.min_score_ratio = min_score_ratio;
            params.global_preference = global_preference;
            params.voting.wks_quantile = wks_quantile;
            params.voting.eps = eps;
            params.maps.accept = accept;
            params.maps.polish = polish;
            params.maps.final_polish = final_polish;
            params.maps.winner_polish = winner_polish;
            params.maps.curvature_weight = curvature_weight;
            params.maps.proxy_vertices = proxy_vertices;
            params.maps.lift_polish = lift_polish;
            params.hierarchy_vertices = hierarchy_vertices;
            params.max_hole = max_hole;
            params.groups = groups.filter(|&g| g > 0);
            params.parts.enabled = parts;
            // A progress bar on stderr, hidden when stderr is not a terminal.
            let bar = indicatif::ProgressBar::with_draw_target(Some(1000), indicatif::ProgressDrawTarget::stderr());
            bar.set_style(
                indicatif::ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent:>3}% {elapsed}")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            bar.set_message("detecting symmetries");
            let det = detect(&mesh, &params, &mut |f| {
                bar.set_position((f * 1000.0) as u64);
                true
            })?;
            bar.finish_and_clear();
            let info = &mesh.info;
            println!("{}: {} vertices, {} triangles", input.display(), info.input_vertices, info.input_triangles);
            if info.isolated_vertices + info.ignored_component_vertices + info.degenerate_triangles + info.non_manifold_edges > 0 {
                println!(
                    "  note: {} isolated vertices and {} vertices of {} other components ignored; {} zero-area triangles kept; {} non-manifold edges",
                    info.isolated_vertices,
                    info.ignored_component_vertices,
                    info.components.saturating_sub(info.kept_components),
                    info.degenerate_triangles,
                    info.non_manifold_edges
                );
            }
            if det.mesh.closed_holes > 0 {
                println!(
                    "  note: {} holes capped for the detection ({} cap vertices; an image that falls in a cap is reported on the hole's rim)",
                    det.mesh.closed_holes, det.mesh.cap_vertices
                );
            }
            if info.duplicate_triangles > 0 {
                println!("  note: {} repeated triangles (the same three vertices as an earlier one) dropped", info.duplicate_triangles);
            }
            if info.welded_vertices > 0 {
                println!(
                    "  note: {} coincident vertices welded ({} triangles collapsed and dropped); they get the map of the vertex they were welded to",
                    info.welded_vertices, info.collapsed_triangles
                );
            }
            let t = &det.timings;
            println!(
                "  {} symmetries in {:.2} s (spectral {:.2}, descriptors {:.2}, sampling {:.2}, voting {:.2}, maps {:.2}, characterize {:.2})",
                det.symmetries.len(),
                t.total,
                t.spectral,
                t.descriptors + t.distance,
                t.sampling,
                t.voting,
                t.maps,
                t.characterize + t.cluster
            );
            if t.hierarchy > 0.0 {
                println!("  detected on a coarse mesh of {} vertices ({:.2} s to build it, {:.2} s to lift the maps to every vertex)", params.hierarchy_vertices, t.hierarchy, t.lift);
            }
            if det.components.len() > 1 {
                println!("  {} components processed, each on its own ({:.2} s mapping congruent ones onto each other):", det.components.len(), t.congruence);
                for (i, c) in det.components.iter().enumerate() {
                    let own = det.symmetries.iter().filter(|s| s.components == [i, i]).count();
                    let swaps = det.symmetries.iter().filter(|s| s.components[0] != s.components[1] && s.components.contains(&i)).count();
                    println!("    component {i}: {} vertices, {:.1}% of the area, {own} symmetries of its own, {swaps} maps onto a congruent component", c.vertices, 100.0 * c.area);
                }
            }
            if det.continuous.dimension > 0 {
                println!(
                    "  a continuous symmetry: a {}-parameter family of isometries (Killing-field residual {:.1e}); one map of each orientation type is listed",
                    det.continuous.dimension, det.continuous.residuals[0]
                );
            }
            for (i, s) in det.symmetries.iter().enumerate() {
                // Order 2 is a reflection when it reverses orientation, a half-turn otherwise.
                let order = match (s.order, s.verdict.reverses()) {
                    (0, _) => "order ?".to_string(),
                    (2, true) => "reflection-like (order 2)".to_string(),
                    (2, false) => "half-turn (order 2)".to_string(),
                    (o, _) => format!("order {o}"),
                };
                let orientation = s.verdict.orientation();
                let place = match (det.components.len(), s.components) {
                    (1, _) => String::new(),
                    (_, [a, b]) if a == b => format!("  component {a}"),
                    (_, [a, b]) => format!("  components {a} <-> {b}"),
                };
                println!(
                    "  #{i}: {:<7} group {}  {order:<26} {orientation:<10} score {:.3}  region {:>6} vertices  complexity {:.3}  distortion {:.4}  seed {} -> {}{place}",
                    s.kind.as_str(),
                    s.group,
                    s.verdict.score,
                    s.region_size,
                    s.complexity,
                    s.distortion,
                    s.source,
                    s.target
                );
            }
            if let Some(path) = json {
                let value = intrinsym::output::json::to_json(&det, &params);
                let text = serde_json::to_string(&value).expect("JSON of plain numbers");
                std::fs::write(&path, text).map_err(|source| intrinsym::mesh::IoError::Os { path: path.clone(), source })?;
                println!("  wrote {}", path.display());
            }
            if let Some(path) = ply {
                let empty = vec![-1i64; det.vertices];
                let map = det.symmetries.first().map_or(&empty, |s| &s.map);
                let colours = intrinsym::output::ply::correspondence_colours(&raw.vertices, map);
                intrinsym::output::ply::write_ply(&path, &raw, &colours, &det.vertex_symmetry())?;
                println!("  wrote {}", path.display());
            }
            if let Some(path) = report {
                let title = format!("intrinsym: {}", input.display());
                let text = if path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm")) {
                    intrinsym::output::report::html(&det, &title, Some(&raw.vertices))
                } else {
                    intrinsym::output::report::svg(&det, &title, Some(&raw.vertices))
                };
                std::fs::write(&path, text).map_err(|source| intrinsym::mesh::IoError::Os { path: path.clone(), source })?;
                println!("  wrote {}", path.display());
            }
        }
        Command::Spectrum { input, k, reject_disconnected, json } => {
            let t = Instant::now();
            let raw = read_mesh(&input)?;
            let mut mp = MeshParams::default();
            // The spectrum of one connected surface: the largest component's.
            mp.components = if reject_disconnected { ComponentPolicy::Reject } else { ComponentPolicy::Largest };
            let mesh = Mesh::new(raw.vertices, raw.triangles, &mp)?;
            let read_seconds = t.elapsed().as_secs_f64();
            let mut params = EigenParams::default();
            // As `detect` does: at most one eigenpair per vertex (issue 16, item 6).
            let n = mesh.num_vertices();
            params.k = k.min(n);
            if params.k < k {
                eprintln!("note: k = {k} is more than the mesh's {n} vertices; computing {n} eigenpairs");
            }
            let k = params.k;
            let basis = Eigenbasis::compute(&mesh, &params)?;
            let i = &basis.info;
            if json {
                let evals: Vec<String> = basis.evals.iter().map(|x| format!("{x:e}")).collect();
                println!(
                    "{{\"vertices\": {}, \"triangles\": {}, \"k\": {}, \"read_seconds\": {read_seconds:.4}, \
                     \"assembly_seconds\": {:.4}, \"factor_seconds\": {:.4}, \"eigensolve_seconds\": {:.4}, \
                     \"max_residual\": {:e}, \"orthogonality\": {:e}, \"eigenvalues\": [{}]}}",
                    mesh.num_vertices(),
                    mesh.num_triangles(),
                    k,
                    basis.assembly_seconds,
                    i.factor_seconds,
                    i.solve_seconds,
                    i.max_residual,
                    i.orthogonality,
                    evals.join(", ")
                );
            } else {
                let info = &mesh.info;
                println!("{}: {} vertices, {} triangles", input.display(), mesh.num_vertices(), mesh.num_triangles());
                if info.isolated_vertices + info.ignored_component_vertices + info.degenerate_triangles > 0 {
                    println!(
                        "  note: {} isolated vertices ignored; {} of {} components ignored ({} vertices); {} zero-area triangles kept",
                        info.isolated_vertices,
                        info.components - 1,
                        info.components,
                        info.ignored_component_vertices,
                        info.degenerate_triangles
                    );
                }
                println!(
                    "  {} eigenpairs by {} in {:.3} s (read {:.3}, assembly {:.3}, factorization {:.3}, eigensolve {:.3})",
                    k,
                    if i.dense { "dense solver" } else { "shift-invert block Lanczos" },
                    read_seconds + basis.assembly_seconds + i.factor_seconds + i.solve_seconds,
                    read_seconds,
                    basis.assembly_seconds,
                    i.factor_seconds,
                    i.solve_seconds
                );
                println!("  max ‖Lφ − λMφ‖/‖Mφ‖ = {:.1e}, max |ΦᵀMΦ − I| = {:.1e}", i.max_residual, i.orthogonality);
                println!("  eigenvalues:");
                for (row, chunk) in basis.evals.chunks(5).enumerate() {
                    let cols: Vec<String> = chunk.iter().map(|x| format!("{x:>14.8}")).collect();
                    println!("  {:>4}: {}", row * 5, cols.join(" "));
                }
            }
        }
        Command::Generate { shape, output, size, truth } => {
            // (A size given was checked in `main`.)
            let size = size.unwrap_or(size_spec(shape).2);
            let creature = |pose| shapes::quadruped(size as u32, pose, 0.0, 0);
            let (mesh, mirror) = match shape {
                Shape::Icosphere => (shapes::icosphere(size as u32), None),
                Shape::Torus => (shapes::bumpy_torus(size), None),
                Shape::NeedleSphere => (shapes::needle_sphere(size as u32), None),
                Shape::Quadruped => {
                    let c = creature(shapes::Pose::Walking);
                    (c.mesh, Some(c.mirror))
                }
                Shape::QuadrupedRest => {
                    let c = creature(shapes::Pose::Rest);
                    (c.mesh, Some(c.mirror))
                }
                Shape::Star => (shapes::star(5, size as u32).mesh, None),
                Shape::DirectedQuadruped => {
                    let c = shapes::directed_quadruped(size as u32, shapes::Pose::Walking, 0.0, 0);
                    (c.mesh, Some(c.mirror))
                }
                Shape::Spiked => {
                    let c = shapes::spiked(size as u32, 0.0, 0);
                    (c.mesh, Some(c.mirror))
                }
            };
            if let (Some(path), Some(mirror)) = (truth, mirror) {
                let text: String = mirror.iter().enumerate().map(|(v, m)| format!("{v} {m}\n")).collect();
                std::fs::write(&path, text).map_err(|source| intrinsym::mesh::IoError::Os { path: path.clone(), source })?;
            }
            write_off(&output, &mesh.vertices, &mesh.triangles)?;
            println!("wrote {} ({} vertices)", output.display(), mesh.num_vertices());
        }
    }
    Ok(())
}

/// The sizes `generate` accepts for a shape, what the size is, and its default: the torus's
/// grid (3·size² vertices), the others' icosphere level (each level four times the vertices:
/// 8 gives 655,362, the largest mesh of the benchmarks).
fn size_spec(shape: Shape) -> (std::ops::RangeInclusive<usize>, &'static str, usize) {
    match shape {
        Shape::Torus => (3..=1000, "a grid size", 34),
        _ => (0..=8, "an icosphere level", 5),
    }
}

/// A report file: `.svg`, `.html` or `.htm` (what it holds follows the extension).
fn report_path(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("svg" | "html" | "htm") => Ok(path),
        _ => Err(format!("{text:?} must end in .svg, .html or .htm")),
    }
}

/// `text` as a number `ok` accepts; out of range, the error names `range` (clap adds the
/// option).
fn number(text: &str, ok: impl Fn(f64) -> bool, range: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(x) if ok(x) => Ok(x),
        Ok(x) => Err(format!("{x} is out of range: {range}")),
        Err(e) => Err(format!("{text:?} is not a number: {e}")),
    }
}

/// `text` as a non-negative integer `ok` accepts ([`number`]'s twin for counts).
fn integer(text: &str, ok: impl Fn(usize) -> bool, range: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(x) if ok(x) => Ok(x),
        Ok(x) => Err(format!("{x} is out of range: {range}")),
        Err(e) => Err(format!("{text:?} is not a non-negative integer: {e}")),
    }
}

// The settings' ranges, those of the C API's setters (`sym_params_set_*`).

fn eigenpairs(text: &str) -> Result<usize, String> {
    integer(text, |x| (3..=1000).contains(&x), "an integer from 3 to 1000")
}

fn sample_count(text: &str) -> Result<usize, String> {
    integer(text, |x| (8..=1000).contains(&x), "an integer from 8 to 1000")
}

fn restart_count(text: &str) -> Result<usize, String> {
    integer(text, |x| x <= 8, "an integer from 0 to 8")
}

fn group_count(text: &str) -> Result<usize, String> {
    integer(text, |x| x <= 64, "an integer from 0 to 64")
}

fn vertex_budget(text: &str) -> Result<usize, String> {
    integer(text, |x| x == 0 || (1000..=1_000_000).contains(&x), "0 (off) or an integer from 1000 to 1000000")
}

fn positive_fraction(text: &str) -> Result<f64, String> {
    number(text, |x| x > 0.0 && x <= 1.0, "a number greater than 0, at most 1")
}

fn tolerance(text: &str) -> Result<f64, String> {
    number(text, |x| x > 0.0 && x <= 0.5, "a number greater than 0, at most 0.5")
}

fn fraction(text: &str) -> Result<f64, String> {
    number(text, |x| (0.0..=1.0).contains(&x), "a number from 0 to 1")
}

fn at_least_one(text: &str) -> Result<f64, String> {
    number(text, |x| x.is_finite() && x >= 1.0, "a finite number ≥ 1")
}

fn non_negative(text: &str) -> Result<f64, String> {
    number(text, |x| x.is_finite() && x >= 0.0, "a finite number ≥ 0")
}
