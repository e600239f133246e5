//! Diagnostic: the continuous-symmetry test (`characterize::continuous`) on meshes given as
//! files (`continuous_probe K FILE...`): cluster sizes, the smallest relative residuals, dimension.
use intrinsym::characterize::{continuous_symmetry, ContinuousParams};
use intrinsym::mesh::{read_mesh, Mesh, MeshParams};
use intrinsym::spectral::{EigenParams, Eigenbasis};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let k: usize = a[1].parse().unwrap();
    for f in &a[2..] {
        let raw = read_mesh(f).unwrap();
        let mesh = Mesh::new(raw.vertices, raw.triangles, &MeshParams::default()).unwrap();
        let basis = Eigenbasis::compute(&mesh, &{
            let mut e = EigenParams::default();
            e.k = 40;
            e
        })
        .unwrap();
        let t = std::time::Instant::now();
        let c = continuous_symmetry(&basis, &{
            let mut p = ContinuousParams::default();
            p.k = k;
            p
        });
        let ev: Vec<String> = basis.evals[..k.min(basis.k())]
            .iter()
            .map(|x| format!("{:.3}", x / basis.evals[1]))
            .collect();
        println!(
            "{f}: dim {} residuals {:?} ({:.3} s)\n   evals/λ1 {}",
            c.dimension,
            c.residuals
                .iter()
                .map(|x| format!("{x:.4}"))
                .collect::<Vec<_>>(),
            t.elapsed().as_secs_f64(),
            ev.join(" ")
        );
    }
}
