//! The hierarchy's coarse mesh of a mesh file, for inspection: `coarse_mesh MESH OUT [TARGET]`
//! simplifies the unit-area mesh to `TARGET` vertices (default 6000, the hierarchy's) with
//! `hierarchy::simplify::simplify` and writes `OUT.off` (the coarse mesh in the input file's
//! coordinates) and `OUT.kept.txt` (for each coarse vertex, its vertex index in the input
//! file). `bench/coarse_shortcuts.py` reads both to measure how far the coarse mesh's edges
//! cut across the fine surface (docs/hierarchy-benchmark.md, "Session 49").

use std::io::Write;

use intrinsym::hierarchy::simplify::simplify;
use intrinsym::mesh::{read_mesh, write_off};
use intrinsym::{Mesh, MeshParams};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(path), Some(out)) = (args.get(1), args.get(2)) else {
        return Err("usage: coarse_mesh MESH OUT [TARGET]".into());
    };
    let target: usize = match args.get(3) {
        Some(t) => t.parse().map_err(|_| format!("TARGET must be a vertex count, got {t:?}"))?,
        None => 6000,
    };
    let raw = read_mesh(path)?;
    let input = raw.vertices.clone();
    // As the detection reads it (welded, validated), at unit area.
    let (unit, _) = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default())?.normalized();
    let n = unit.num_vertices();
    let s = simplify(&unit, target);
    let original: Vec<usize> = s.kept.iter().map(|&v| unit.input_index[v] as usize).collect();
    let positions: Vec<[f64; 3]> = original.iter().map(|&v| input[v]).collect();
    write_off(format!("{out}.off"), &positions, &s.triangles)?;
    let mut kept = std::io::BufWriter::new(std::fs::File::create(format!("{out}.kept.txt"))?);
    for &v in &original {
        writeln!(kept, "{v}")?;
    }
    kept.flush()?;
    println!("{n} vertices -> {} ({} triangles): {out}.off, {out}.kept.txt", original.len(), s.triangles.len());
    Ok(())
}
