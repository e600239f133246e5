//! Cotangent Laplacian on intrinsically mollified edge lengths.
//!
//! $$L_{ij} = -\tfrac12(\cot\alpha_{ij} + \cot\beta_{ij}),\qquad L_{ii} = -\sum_{j\ne i} L_{ij}$$
//! (Pinkall & Polthier 1993), the positive semi-definite sign convention: `L·1 = 0`, `xᵀLx ≥ 0`.
//!
//! Cotangents are computed from edge lengths, `cot A = (b² + c² − a²) / (4·area)`, with the area
//! from Heron's formula. Before that the edge lengths are **intrinsically mollified** (Sharp & Crane
//! 2020, "A Laplacian for Nonmanifold Triangle Meshes", §4.5): every length grows by the smallest
//! `ε ≥ 0` for which each triangle satisfies the strict triangle inequality with margin
//! `δ = MOLLIFY_REL · (mean edge length)`. A zero-area or needle triangle therefore keeps a small
//! positive area and finite cotangents, and every triangle's element matrix stays positive
//! semi-definite — unlike clamping cotangents, which can make a sliver's element matrix indefinite.
//! On a mesh without near-degenerate triangles ε = 0 and this is the textbook cotangent Laplacian.

use sprs::CsMat;

use crate::mesh::vec3::dist2;
use crate::mesh::Mesh;

/// Mollification margin relative to the mean edge length (the value of Sharp & Crane's code).
pub const MOLLIFY_REL: f64 = 1e-6;

/// `(m, 3)` edge lengths per triangle, `l[t][k]` opposite corner `k`, after mollification.
pub fn mollified_edge_lengths(mesh: &Mesh) -> Vec<[f64; 3]> {
    let v = &mesh.vertices;
    let mut lengths = triangle_lengths(mesh, |a, b| dist2(v[a as usize], v[b as usize]).sqrt());
    let delta = margin(&lengths);
    let eps = lengths.iter().map(|l| shortfall(l, delta)).fold(0.0f64, f64::max);
    if eps > 0.0 {
        for l in &mut lengths {
            for x in l.iter_mut() {
                *x += eps;
            }
        }
    }
    lengths
}

/// `(m, 3)` edge lengths per triangle as [`mollified_edge_lengths`], each chord multiplied by
/// its edge's factor in `stretch` (one per entry of the CSR `adjacency` of `mesh`,
/// [`Mesh::adjacency`]): the intrinsic lengths of a coarse mesh measured along its fine mesh
/// ([`crate::hierarchy`], step 3). A stretched edge can break its triangle's inequality, so
/// the mollification is per triangle here: a triangle's three lengths grow by the least `ε`
/// that restores it with the margin `δ` (Sharp & Crane's local variant), the others keep
/// theirs.
pub fn stretched_edge_lengths(mesh: &Mesh, adjacency: &(Vec<usize>, Vec<u32>), stretch: &[f64]) -> Vec<[f64; 3]> {
    let (off, nbr) = adjacency;
    let factor = |a: u32, b: u32| {
        let row = &nbr[off[a as usize]..off[a as usize + 1]];
        row.binary_search(&b).map_or(1.0, |i| stretch[off[a as usize] + i])
    };
    let v = &mesh.vertices;
    let mut lengths = triangle_lengths(mesh, |a, b| dist2(v[a as usize], v[b as usize]).sqrt() * factor(a, b));
    let delta = margin(&lengths);
    for l in &mut lengths {
        let eps = shortfall(l, delta);
        if eps > 0.0 {
            l.iter_mut().for_each(|x| *x += eps);
        }
    }
    lengths
}

/// Each triangle's three lengths `length(a, b)`, `l[t][k]` opposite corner `k`.
fn triangle_lengths(mesh: &Mesh, length: impl Fn(u32, u32) -> f64) -> Vec<[f64; 3]> {
    mesh.triangles.iter().map(|t| [length(t[1], t[2]), length(t[2], t[0]), length(t[0], t[1])]).collect()
}

/// The mollification margin `δ = MOLLIFY_REL · (mean length)`.
fn margin(lengths: &[[f64; 3]]) -> f64 {
    MOLLIFY_REL * (lengths.iter().flatten().sum::<f64>() / (3 * lengths.len()).max(1) as f64)
}

/// The least `ε ≥ 0` by which a triangle's three lengths must all grow to satisfy the triangle
/// inequality with margin `δ` (`l_j + l_k − l_i ≥ δ` for every side `i`).
fn shortfall(l: &[f64; 3], delta: f64) -> f64 {
    (0..3).map(|k| delta - (l[(k + 1) % 3] + l[(k + 2) % 3] - l[k])).fold(0.0f64, f64::max)
}

/// Area of a triangle with side lengths `l` (Heron, in the numerically stable ordering).
pub fn heron_area(l: &[f64; 3]) -> f64 {
    let mut s = *l;
    s.sort_by(|a, b| b.total_cmp(a)); // a ≥ b ≥ c
    let [a, b, c] = s;
    let p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    0.25 * p.max(0.0).sqrt()
}

/// The three cotangents of a triangle with side lengths `l` (`cot[k]` at corner `k`).
pub fn cotangents(l: &[f64; 3]) -> [f64; 3] {
    let area = heron_area(l);
    let sq = l.map(|x| x * x);
    std::array::from_fn(|k| (sq[(k + 1) % 3] + sq[(k + 2) % 3] - sq[k]) / (4.0 * area))
}

/// `(n, n)` cotangent Laplacian (CSC, symmetric, both triangles stored) from mollified `lengths`.
pub fn cotan_laplacian(mesh: &Mesh, lengths: &[[f64; 3]]) -> CsMat<f64> {
    let n = mesh.num_vertices();
    // The pattern (each vertex's neighbours and itself, sorted; symmetric, so CSC = CSR) by
    // bucketing half-edges per vertex: a general triplet sort (sprs `TriMat`) took half of the
    // assembly time.
    let mut start = vec![0usize; n + 1];
    for t in &mesh.triangles {
        for &v in t {
            start[v as usize + 1] += 3; // two neighbours and the vertex itself
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut raw = vec![0u32; start[n]];
    for t in &mesh.triangles {
        for k in 0..3 {
            let v = t[k] as usize;
            raw[fill[v]..fill[v] + 3].copy_from_slice(&[t[k], t[(k + 1) % 3], t[(k + 2) % 3]]);
            fill[v] += 3;
        }
    }
    let mut indptr = Vec::with_capacity(n + 1);
    let mut indices: Vec<usize> = Vec::with_capacity(start[n] / 2 + n);
    indptr.push(0);
    for v in 0..n {
        let bucket = &mut raw[start[v]..start[v + 1]];
        bucket.sort_unstable();
        let first = indices.len();
        for &u in bucket.iter() {
            if indices.len() == first || indices[indices.len() - 1] != u as usize {
                indices.push(u as usize);
            }
        }
        if indices.len() == first {
            indices.push(v); // an isolated vertex keeps its (zero) diagonal
        }
        indptr.push(indices.len());
    }
    let mut data = vec![0.0; indices.len()];
    let mut add = |i: usize, j: usize, w: f64| {
        let col = &indices[indptr[i]..indptr[i + 1]];
        let at = col.binary_search(&j).expect("entry in the pattern");
        data[indptr[i] + at] += w;
    };
    for (t, l) in mesh.triangles.iter().zip(lengths) {
        let cot = cotangents(l);
        for k in 0..3 {
            let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
            let w = 0.5 * cot[k];
            add(i, j, -w);
            add(j, i, -w);
            add(i, i, w);
            add(j, j, w);
        }
    }
    CsMat::new_csc((n, n), indptr, indices, data)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn cotangents_of_known_triangles() {
        // Equilateral: cot 60° = 1/√3.
        for c in cotangents(&[1.0, 1.0, 1.0]) {
            assert!((c - 1.0 / 3f64.sqrt()).abs() < 1e-14);
        }
        // 3-4-5: right angle opposite the side 5.
        let c = cotangents(&[3.0, 4.0, 5.0]);
        assert!((c[0] - 4.0 / 3.0).abs() < 1e-14 && (c[1] - 3.0 / 4.0).abs() < 1e-14 && c[2].abs() < 1e-14);
        assert!((heron_area(&[3.0, 4.0, 5.0]) - 6.0).abs() < 1e-14);
    }

    #[test]
    fn laplacian_is_symmetric_with_constant_kernel() {
        for level in 0..4 {
            let mesh = shapes::icosphere(level);
            let l = cotan_laplacian(&mesh, &mollified_edge_lengths(&mesh));
            let n = mesh.num_vertices();
            let scale = l.data().iter().fold(0.0f64, |a, &x| a.max(x.abs()));
            let mut row_sum = vec![0.0; n];
            for (&x, (i, j)) in l.iter() {
                row_sum[i] += x;
                let xt = *l.get(j, i).expect("symmetric pattern");
                assert!((x - xt).abs() <= 1e-14 * scale);
                if i != j {
                    assert!(x <= 0.0, "icosphere is Delaunay: off-diagonals are ≤ 0");
                } else {
                    assert!(x > 0.0);
                }
            }
            for s in row_sum {
                assert!(s.abs() <= 1e-13 * scale * n as f64);
            }
        }
    }

    #[test]
    fn mollification_makes_slivers_finite() {
        let mesh = shapes::needle_sphere(2);
        let lengths = mollified_edge_lengths(&mesh);
        assert!(mesh.info.degenerate_triangles > 0);
        for l in &lengths {
            let c = cotangents(l);
            assert!(c.iter().all(|x| x.is_finite()), "{l:?} -> {c:?}");
            assert!(heron_area(l) > 0.0);
        }
        let lap = cotan_laplacian(&mesh, &lengths);
        assert!(lap.data().iter().all(|x| x.is_finite()));
    }
}
