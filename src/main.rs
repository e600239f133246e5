//! `intrinsym`: the command-line front end.
//!
//! ```text
//! intrinsym spectrum INPUT [-k 100] [--json]   Laplace–Beltrami eigenvalues, timing, checks
//! intrinsym generate SHAPE OUTPUT.off [--size S] generated test shapes
//! ```

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand, ValueEnum};
use intrinsym::mesh::{read_mesh, write_off, ComponentPolicy};
use intrinsym::{shapes, Eigenbasis, EigenParams, Mesh, MeshParams};

#[derive(Parser)]
#[command(name = "intrinsym", version, about = "Detect and characterize intrinsic symmetries of triangle meshes")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Compute the k lowest Laplace–Beltrami eigenpairs of a mesh (OFF, PLY or OBJ).
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
        /// Size: subdivision level (icosphere, needle-sphere) or grid size (torus: 3·size² vertices).
        #[arg(long, default_value_t = 34)]
        size: usize,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum Shape {
    Icosphere,
    Torus,
    NeedleSphere,
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("intrinsym: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<(), intrinsym::Error> {
    match cli.command {
        Command::Spectrum { input, k, reject_disconnected, json } => {
            let t = Instant::now();
            let raw = read_mesh(&input)?;
            let mut mp = MeshParams::default();
            if reject_disconnected {
                mp.components = ComponentPolicy::Reject;
            }
            let mesh = Mesh::new(raw.vertices, raw.triangles, &mp)?;
            let read_seconds = t.elapsed().as_secs_f64();
            let mut params = EigenParams::default();
            params.k = k;
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
        Command::Generate { shape, output, size } => {
            let mesh = match shape {
                Shape::Icosphere => shapes::icosphere(size as u32),
                Shape::Torus => shapes::bumpy_torus(size),
                Shape::NeedleSphere => shapes::needle_sphere(size as u32),
            };
            write_off(&output, &mesh.vertices, &mesh.triangles)?;
            println!("wrote {} ({} vertices)", output.display(), mesh.num_vertices());
        }
    }
    Ok(())
}
