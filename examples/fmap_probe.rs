//! Diagnostic: how good is the orientation-reversing functional map hypothesis alone on a shape
//! with ground truth (`NAME.off` + `NAME.sym.txt`)? Prints acc@0.05 of its point map, read
//! both ways (`spectral_init::Conversion`), before and after a full ZoomOut, with the judge's
//! verdict.
//!
//! ```text
//! cargo run --release --example fmap_probe -- ../shared/data/tosca/cat3.off [...]
//! ```
use intrinsym::descriptors::{wks, WksParams};
use intrinsym::judge::{vertex_normals, Judge, JudgeParams};
use intrinsym::maps::{orientation, spectral_init, zoomout};
use intrinsym::mesh::read_mesh;
use intrinsym::{eval, Eigenbasis, EigenParams, Mesh, MeshParams};

fn main() {
    for path in std::env::args().skip(1) {
        let raw = read_mesh(std::path::Path::new(&path)).expect("mesh");
        let mut mp = MeshParams::default();
        mp.allow_non_manifold = true;
        let mesh = Mesh::new(raw.vertices, raw.triangles, &mp).expect("valid mesh");
        let truth: Vec<(usize, Vec<usize>)> = std::fs::read_to_string(path.replace(".off", ".sym.txt"))
            .expect("truth")
            .lines()
            .filter_map(|l| {
                let mut it = l.split_whitespace().map(|x| x.parse::<usize>().ok());
                Some((it.next()??, vec![it.next()??]))
            })
            .filter(|(a, b)| *a < mesh.num_vertices() && b[0] < mesh.num_vertices())
            .collect();
        let basis = Eigenbasis::compute(&mesh, &EigenParams::default()).expect("basis");
        let desc = wks(&basis, &WksParams::default());
        let t = std::time::Instant::now();
        let c = orientation::reversing_fmap(&mesh, &mesh.oriented_triangles(), &basis, &desc, &orientation::OrientationParams::default()).expect("fmap");
        let secs = t.elapsed().as_secs_f64();
        let adj = mesh.adjacency();
        let search: Vec<usize> = (0..mesh.num_vertices()).step_by(5).collect();
        let judge = Judge::new(&mesh.vertices, vertex_normals(&mesh), &adj, mesh.area().sqrt(), &JudgeParams::default());
        let as_map = |im: &[usize]| im.iter().map(|&w| w as i64).collect::<Vec<i64>>();
        println!("{path}: fmap {secs:.2} s");
        for conversion in [spectral_init::Conversion::Adjoint, spectral_init::Conversion::Transported] {
            let mut image = spectral_init::point_map(&basis, &adj, &c, &search, conversion);
            let a0 = eval::accuracy(&mesh, &as_map(&image), &truth, &[0.05])[0];
            let v0 = judge.judge(&as_map(&image), 0.0, 0.04);
            zoomout::zoomout(&basis, &adj, &mut image, c.nrows(), 100, 5);
            let a1 = eval::accuracy(&mesh, &as_map(&image), &truth, &[0.05])[0];
            let v1 = judge.judge(&as_map(&image), 0.0, 0.04);
            println!("  {conversion:?}: point map acc {a0:.3} rev {:.2} fixed {:.2}; zoomout acc {a1:.3} rev {:.2} fixed {:.2}", v0.reversal, v0.fixed, v1.reversal, v1.fixed);
        }
    }
}
