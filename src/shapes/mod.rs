//! Generated shapes with known geometry, for tests, benchmarks and the bundled example.
//!
//! - [`icosphere`]: the unit sphere, whose Laplace–Beltrami eigenvalues are l(l+1) with
//!   multiplicity 2l+1;
//! - [`bumpy_torus`]: a torus with a smooth, symmetry-breaking radial bump, sized for the
//!   spectral benchmarks (3·s² vertices);
//! - [`needle_sphere`]: an icosphere with collapsed (zero-area) and needle triangles.
//!
//! Every function returns a validated [`Mesh`].

use crate::mesh::{Mesh, MeshParams};

fn build(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
    Mesh::new(vertices, triangles, &MeshParams::default()).expect("generated meshes are valid")
}

/// The unit icosphere after `level` 4-to-1 subdivisions: 10·4^level + 2 vertices.
pub fn icosphere(level: u32) -> Mesh {
    let (v, t) = icosphere_arrays(level);
    build(v, t)
}

fn normalize(p: [f64; 3]) -> [f64; 3] {
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    [p[0] / r, p[1] / r, p[2] / r]
}

fn icosphere_arrays(level: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = [
        [-1., g, 0.], [1., g, 0.], [-1., -g, 0.], [1., -g, 0.],
        [0., -1., g], [0., 1., g], [0., -1., -g], [0., 1., -g],
        [g, 0., -1.], [g, 0., 1.], [-g, 0., -1.], [-g, 0., 1.],
    ]
    .iter()
    .map(|&p| normalize(p))
    .collect();
    let mut t: Vec<[u32; 3]> = vec![
        [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11],
        [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
        [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
        [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
    ];
    for _ in 0..level {
        let mut mid = std::collections::HashMap::new();
        let mut midpoint = |a: u32, b: u32, v: &mut Vec<[f64; 3]>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (v[a as usize], v[b as usize]);
                v.push(normalize([(p[0] + q[0]) / 2., (p[1] + q[1]) / 2., (p[2] + q[2]) / 2.]));
                (v.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(4 * t.len());
        for &[a, b, c] in &t {
            let ab = midpoint(a, b, &mut v);
            let bc = midpoint(b, c, &mut v);
            let ca = midpoint(c, a, &mut v);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        t = next;
    }
    (v, t)
}

/// A torus (major radius 1, minor 0.35) with a smooth bump that breaks its symmetries;
/// a `3s × s` grid, so `3·s²` vertices (s = 34 → 3.5k, 58 → 10k, 129 → 50k, 258 → 200k, 577 → 1M).
pub fn bumpy_torus(s: usize) -> Mesh {
    assert!(s >= 3, "bumpy_torus needs s >= 3");
    let (nu, nv) = (3 * s, s);
    let mut v = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = 2.0 * std::f64::consts::PI * i as f64 / nu as f64;
        for j in 0..nv {
            let w = 2.0 * std::f64::consts::PI * j as f64 / nv as f64;
            let r = 0.35 * (1.0 + 0.15 * (3.0 * u).sin() * (2.0 * w + 0.5).cos() + 0.1 * (u + 0.3).cos());
            let big = 1.0 + 0.1 * (2.0 * u).sin();
            v.push([(big + r * w.cos()) * u.cos(), (big + r * w.cos()) * u.sin() * 1.1, r * w.sin()]);
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut t = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    build(v, t)
}

/// An icosphere with bad triangles: every 7th vertex is moved onto a neighbour (its two shared
/// triangles get zero area) and every 11th almost onto one (needles, relative offset 1e-9).
pub fn needle_sphere(level: u32) -> Mesh {
    let (mut v, t) = icosphere_arrays(level);
    let mut neighbour = vec![u32::MAX; v.len()];
    for f in &t {
        for k in 0..3 {
            neighbour[f[k] as usize] = f[(k + 1) % 3];
        }
    }
    for i in 0..v.len() {
        let q = v[neighbour[i] as usize];
        if i % 7 == 3 {
            v[i] = q;
        } else if i % 11 == 5 {
            v[i] = [q[0] + 1e-9, q[1] - 1e-9, q[2]];
        }
    }
    build(v, t)
}
