//! Lumped (barycentric) mass matrix.
//!
//! $$M_{ii} = \tfrac13 \sum_{t \ni i} \operatorname{area}(t)$$
//! Always positive (unlike the mixed-Voronoi mass, which needs care on obtuse triangles), and
//! consistent with the mollified lengths the Laplacian uses ([`super::cotan`]). With it, the
//! discrete eigenvalues of the unit sphere converge to l(l+1) at O(h²).

use super::cotan::heron_area;
use crate::mesh::Mesh;

/// `(n,)` diagonal of the lumped mass matrix from mollified `lengths`.
pub fn lumped_mass(mesh: &Mesh, lengths: &[[f64; 3]]) -> Vec<f64> {
    let mut mass = vec![0.0; mesh.num_vertices()];
    for (t, l) in mesh.triangles.iter().zip(lengths) {
        let a = heron_area(l) / 3.0;
        for &i in t {
            mass[i as usize] += a;
        }
    }
    mass
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;
    use crate::spectral::cotan::mollified_edge_lengths;

    #[test]
    fn mass_sums_to_area_and_is_positive() {
        for level in 0..4 {
            let mesh = shapes::icosphere(level);
            let m = lumped_mass(&mesh, &mollified_edge_lengths(&mesh));
            assert!(m.iter().all(|&x| x > 0.0));
            let total: f64 = m.iter().sum();
            assert!((total - mesh.area()).abs() < 1e-12 * total);
        }
    }
}
