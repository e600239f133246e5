//! Time of reading mesh files and of validating them ([`intrinsym::Mesh::new`], default
//! parameters), and a hash of what was read (to check that a faster reader reads the same):
//! `cargo run --release --example bench_read -- FILE...`.
//!
//! Session 37 (docs/hierarchy-benchmark.md): the text readers lend each line from one buffer
//! instead of copying every line and token; the 955k-vertex scan-like KIDS mesh as OFF 0.65 →
//! 0.34 s, as OBJ 1.19 → 0.63 s, a 60k KIDS pose 0.042 → 0.020 s; the same meshes, and the
//! same errors, from 144 files (shared/data, tests/data, the 955k mesh as OFF, OBJ and PLY,
//! 18 malformed ones), but one message: an OBJ index written `007` is now quoted `7`.
use std::hash::{Hash, Hasher};
fn main() {
    for path in std::env::args().skip(1) {
        let t = std::time::Instant::now();
        match intrinsym::mesh::read_mesh(std::path::Path::new(&path)) {
            Ok(raw) => {
                let dt = t.elapsed().as_secs_f64();
                let mut h = std::collections::hash_map::DefaultHasher::new();
                for p in &raw.vertices { for x in p { x.to_bits().hash(&mut h); } }
                raw.triangles.hash(&mut h);
                let t = std::time::Instant::now();
                let checked = intrinsym::Mesh::new(raw.vertices.clone(), raw.triangles.clone(), &intrinsym::MeshParams::default()).map(|_| ());
                let dv = t.elapsed().as_secs_f64();
                println!("{path}: {} vertices {} triangles hash {:x}, read {dt:.3} s, validated {dv:.3} s ({})", raw.vertices.len(), raw.triangles.len(), h.finish(), if checked.is_ok() { "valid" } else { "invalid" });
            }
            Err(e) => println!("{path}: error {e}"),
        }
    }
}
