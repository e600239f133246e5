//! Band-limited mean curvature: the one *extrinsic* cue of the pipeline (beyond the paper),
//! used by the geodesic polish ([`crate::maps::geodesic`]) to break ties that intrinsic
//! geometry leaves open.
//!
//! **Why.** On posed shapes the map that preserves geodesic distances best is not the ground
//! truth's: joints stretch, and the isometric optimum is a slightly slid version of the true
//! map (docs/accuracy.md, sessions 15 and 16). A posed body bends at its joints and its parts
//! stay nearly rigid, and a rigid part keeps its mean curvature; so the true symmetry
//! preserves the mean curvature of the parts, while a map slid along a limb or a torso does
//! not (a tapered or curved part changes curvature along its length). Measured with session
//! 15's maps (a `python3` probe, heat-smoothed curvature, mean `|h(v) − h(T v)|` over its
//! median magnitude): on seven posed TOSCA shapes the ground truth changes it by 0.34–0.57,
//! our maps by 0.52–0.69; on a 60k KIDS pose 0.08 against 0.73. On two FAUST shapes it is
//! the other way round (0.66 and 0.78 against 0.49: FAUST's truth is its registration
//! template's symmetry, and real bodies are not symmetric), yet the term raises FAUST's
//! figures too (docs/accuracy.md, session 16).
//!
//! **What.** With the cotangent Laplacian `L` (stiffness), lumped mass `M` and unit vertex
//! normals `n` of the unit-area mesh, `h = ((L X) · n) / M` is (twice) the signed mean
//! curvature at each vertex (`X` the positions); it is noisy on a scan, so it is low-passed in
//! the eigenbasis the pipeline has anyway,
//! $$h_s = Φ_k \, \mathrm{diag}\!\left(\frac{1}{1 + τ λ_i}\right) Φ_kᵀ M h,$$
//! (the resolvent of the heat equation at time `τ`, truncated to the `k` eigenpairs), and
//! divided by the median of `|h_s|` so that a weight on it has one meaning on every shape.
//! The sign depends only on the orientation of the triangles, the same at `v` and at `T v`,
//! so orientation-reversing and -preserving maps alike are compared on one field.
//!
//! On a large mesh detected on its coarse version ([`crate::hierarchy`]) `h` is computed on
//! the fine mesh and averaged over each coarse vertex's cell ([`Raw::on_cells`]), then
//! low-passed in the coarse basis: estimated on the coarse mesh's long, irregular triangles
//! instead, the term lowered the 60k KIDS poses 1 and 5 from 99.8 / 97.1% to 96.0 / 91.5%
//! acc@0.05 (at full resolution, without the hierarchy, it raised them: 94.4 / 88.5% to 95.3
//! / 94.6%).
//!
//! **Noise on the hierarchy: two halves of every cell.** The cells' means have already
//! averaged much of a scan's noise away, so the energy test below does not see it there:
//! noisy 60k KIDS poses (σ = 0.002·√area, 47% of their edge) keep 0.21 of the means' energy
//! and the term ran at half weight, which cost them 5.4 points against no term at all (87.6
//! against 93.0% acc@0.05, seeds 0–30), while the same term is worth 5.4 points on the clean
//! poses and 8.7 on scan-like (subdivided) SHREC'16 kids. No energy ratio separates them
//! (docs/hierarchy-benchmark.md, "Session 40": against the *fine* field's energy the noisy
//! poses keep 0.05, but so do the subdivided kids, whose creases the cells integrate
//! faithfully). What does is the error of `h_s` itself: each
//! cell is cut in two by a plane through its seed ([`Raw::on_cells`]), each half's mean is
//! low-passed like the whole's, and the two estimates `a`, `b` compared,
//! $$ρ = ‖a_s − b_s‖_M / ‖a_s + b_s‖_M,$$
//! an estimate of the relative error of `h_s` (the halves' errors are independent where the
//! curvature is noise; their difference is twice the whole's error, their sum twice the
//! field). Measured: clean KIDS poses 0.13–0.17, subdivided SHREC'16 kids 0.29–0.40, the
//! noisy poses 0.81–0.98 (their two halves barely agree). The term keeps its weight up to ρ =
//! [`TRUSTED_ERROR`] and is off from [`NOISE_ERROR`] on (linear between): even at 2.6% of its
//! weight a wrong curvature decides the polish's near-ties (noisy poses 89.5% at that weight).
//! At full resolution there are no cells and the energy test alone decides; there a faded
//! noisy term still helps (noisy SHREC'16 kids, ratio 0.11–0.16: switching it off cost 4.4
//! points).
//!
//! **Noise.** Noise on the positions is mostly high-frequency curvature (it grows as the noise
//! over the squared edge length), so a noisy mesh keeps little of its curvature's energy in
//! the low band; the ratio `‖h_s‖_M / ‖h‖_M` (before normalising) measures it, and below
//! [`RELIABLE_RATIO`] the term fades. At full weight on a generated quadruped with 0.5% noise
//! the curvature of the noise took the mirror from 0.955 to 0.78 acc@0.05
//! (`noisy_quadrupeds_on_the_hierarchy`); faded, 0.98. Milder noise is not caught (session
//! 30, `bench/noisy_copies.py`, σ = 0.002·√area on FAUST's 5k meshes, 14% of an edge): the low
//! band keeps 0.43–0.45 of the energy there (0.65–0.70 clean; clean shapes of shared/data go
//! down to 0.32, so the fraction cannot tell noise from detail), `h_s` is off by 0.16–0.22 of
//! its median, and FAUST scores 88.8% acc@0.05 with the term against 90.4% without it (92.9 /
//! 92.4% clean; TOSCA gains from it clean and noisy). Curvature from Taubin-smoothed positions
//! did not help (noisy 90.0%, clean 92.6%).
//!
//! Tried and dropped: the mean curvature normal of the band-limited *positions*
//! (`Σ_i λ_i/(1 + τλ_i) φ_i φ_iᵀ M X`, robust to noise by construction) — a weaker cue: over
//! the 116 shapes 84.8 / 82.7% best / first against 85.9 / 83.1% (the positions'
//! coefficients times `λ_i` decay slowly, and 100 of them blur the limbs' curvature).
//!
//! A shape that bends without stretching everywhere (a rolled sheet) does not keep its
//! curvature under its intrinsic symmetry: the term's weight is small and it only ranks
//! images that geodesics leave nearly tied.

use crate::mesh::vec3::{cross, dot, norm, sub};
use crate::hierarchy::Hierarchy;
use crate::mesh::Mesh;
use crate::spectral::Eigenbasis;

/// `(h, M)`: the raw mean curvature `h = ((L X) · n) / M` of `mesh` at each vertex (cotangent
/// weights of the positions, vertex `normals` of one consistent orientation) and the lumped
/// mass `M` (a third of the incident triangles' area), triangle by triangle (no matrix: it
/// also runs on the 10⁶-vertex meshes of the hierarchy). Degenerate triangles add nothing; a
/// vertex without area gets 0.
pub fn raw_mean_curvature(mesh: &Mesh, normals: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>) {
    let n = mesh.num_vertices();
    let p = &mesh.vertices;
    let mut lx = vec![[0.0f64; 3]; n];
    let mut mass = vec![0.0f64; n];
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| v as usize);
        let twice = norm(cross(sub(p[b], p[a]), sub(p[c], p[a])));
        // Also skips a NaN area.
        if twice.is_nan() || twice <= 0.0 {
            continue;
        }
        for (i, j, k) in [(a, b, c), (b, c, a), (c, a, b)] {
            mass[i] += twice / 6.0;
            // The angle at `k` weighs the edge `ij` opposite it: `cot / 2`.
            let w = 0.5 * dot(sub(p[i], p[k]), sub(p[j], p[k])) / twice;
            let d = sub(p[i], p[j]);
            for x in 0..3 {
                lx[i][x] += w * d[x];
                lx[j][x] -= w * d[x];
            }
        }
    }
    let h = (0..n).map(|v| if mass[v] > 0.0 { dot(lx[v], normals[v]) / mass[v] } else { 0.0 }).collect();
    (h, mass)
}

/// A raw mean curvature field on a mesh's vertices, as [`band_limited`] takes it.
#[derive(Clone, Debug, PartialEq)]
pub struct Raw {
    /// `h` at each vertex.
    pub values: Vec<f64>,
    /// On a hierarchy's coarse mesh, the means of `h` over two halves of each cell
    /// ([`Raw::on_cells`]): two independent estimates of `values` whose agreement after the
    /// low-pass measures the noise the cells' means still carry. `None` at full resolution.
    pub halves: Option<[Vec<f64>; 2]>,
}

impl Raw {
    /// A field estimated on the mesh itself.
    pub fn on_mesh(values: Vec<f64>) -> Raw {
        Raw { values, halves: None }
    }

    /// A fine per-vertex field carried to the coarse mesh of `hierarchy` (its `owner`
    /// partition of the fine vertices, its `seeds`): `values` the mass-weighted mean of
    /// `fine` over each cell (`mass` the fine lumped mass; the coarse mesh's long, irregular
    /// triangles estimate curvature poorly, the fine mesh's well) and `halves` the means over
    /// two halves of each cell. A fine vertex `v` of the cell of coarse vertex `c` is in the
    /// first half when `(p_v − p_seed) · t ≥ 0`, `t` a fixed direction projected onto the
    /// seed's tangent plane (`positions` and `normals` of the fine vertices), so each half is
    /// a contiguous patch (a crease or a facet is split, not sampled). A cell without a
    /// finite value gets 0, a half without one the whole cell's mean. One pass over the fine
    /// vertices.
    pub fn on_cells(fine: &[f64], mass: &[f64], hierarchy: &Hierarchy, positions: &[[f64; 3]], normals: &[[f64; 3]]) -> Raw {
        let (owner, seeds) = (&hierarchy.owner, &hierarchy.seeds);
        let m = seeds.len();
        // The tangent direction at each seed: a fixed direction without the normal's component
        // (another where the two are nearly parallel).
        let tangents: Vec<[f64; 3]> = seeds
            .iter()
            .map(|&s| {
                let n = normals[s];
                let along = |e: [f64; 3]| sub(e, n.map(|x| dot(e, n) * x));
                let t = along([0.93, 0.31, 0.19]);
                if norm(t) > 0.3 { t } else { along([-0.19, 0.31, 0.93]) }
            })
            .collect();
        // The whole cells' sums are kept apart from the halves' (not added up from them), so
        // the cells' means do not depend on the split, to the last bit.
        let (mut sum, mut weight) = (vec![0.0f64; m], vec![0.0f64; m]);
        let (mut half_sum, mut half_weight) = ([vec![0.0f64; m], vec![0.0f64; m]], [vec![0.0f64; m], vec![0.0f64; m]]);
        for (v, &c) in owner.iter().enumerate() {
            let c = c as usize;
            if c < m && fine[v].is_finite() {
                sum[c] += mass[v] * fine[v];
                weight[c] += mass[v];
                let side = usize::from(dot(sub(positions[v], positions[seeds[c]]), tangents[c]) < 0.0);
                half_sum[side][c] += mass[v] * fine[v];
                half_weight[side][c] += mass[v];
            }
        }
        let mean = |s: &[f64], w: &[f64], c: usize| (w[c] > 0.0).then(|| s[c] / w[c]);
        let values: Vec<f64> = (0..m).map(|c| mean(&sum, &weight, c).unwrap_or(0.0)).collect();
        let halves = [0, 1].map(|side| (0..m).map(|c| mean(&half_sum[side], &half_weight[side], c).unwrap_or(values[c])).collect());
        Raw { values, halves: Some(halves) }
    }
}

/// The relative error `ρ` of the band-limited curvature (module docs) up to which the term
/// keeps its weight on a hierarchy: above every clean or scan-like mesh measured (clean 60k
/// KIDS poses 0.13–0.17, subdivided SHREC'16 kids 0.29–0.40), where an error of half the field
/// is not yet reached.
const TRUSTED_ERROR: f64 = 0.5;

/// From this relative error `ρ` on the term is off: the two halves' low-passed curvatures
/// differ by 70% of their sum, mostly noise (noisy 60k KIDS poses 0.81–0.98).
const NOISE_ERROR: f64 = 0.7;

/// The fraction of the raw curvature's energy (`‖·‖_M`) that the low-passed one keeps, below
/// which the curvature is taken for noise and its term fades (as the square of the fraction's
/// ratio to this). Measured (session 16): 0.32–0.70 over the 116 shapes of `../shared/data`
/// (median 0.61; lowest the glued SHREC'16 kids: kid03 0.32, kid06 0.35), 0.71 on the clean
/// generated 41k quadruped, 0.145 and 0.073 on it with 0.2% and 0.5% noise (where the term at
/// full weight took its mirror from 0.955 to 0.78 acc@0.05). Below every shape of shared/data,
/// so none of them is faded; with 0.4 (six of them faded by up to 37%) the figures moved by
/// 0.1 point on SHREC'16 and not elsewhere.
const RELIABLE_RATIO: f64 = 0.3;

/// `Φ_k diag(1/(1 + τλ_i)) Φ_kᵀ M f`: `f` low-passed in `basis` at heat time `tau`.
fn low_pass(f: &[f64], basis: &Eigenbasis, tau: f64) -> Vec<f64> {
    let n = f.len();
    let k = basis.k();
    let phi = &basis.evecs;
    let mf: Vec<f64> = f.iter().zip(&basis.mass).map(|(h, m)| h * m).collect();
    let coefficients: Vec<f64> = (0..k)
        .map(|i| {
            let c: f64 = (0..n).map(|v| phi[(v, i)] * mf[v]).sum();
            c / (1.0 + tau.max(0.0) * basis.evals[i].max(0.0))
        })
        .collect();
    (0..n).map(|v| (0..k).map(|i| phi[(v, i)] * coefficients[i]).sum()).collect()
}

/// The band-limited, median-normalised mean curvature `h_s` (see the module docs) from the
/// raw curvature `raw` of the vertices of `basis`'s mesh, at heat time `tau` (unit area),
/// scaled down on a noisy mesh ([`RELIABLE_RATIO`]; on a hierarchy's coarse mesh also by the
/// disagreement of the cells' halves, [`TRUSTED_ERROR`]). All zeros on a flat mesh or when any
/// value is not finite; a negative `tau` counts as 0.
pub fn band_limited(raw: &Raw, basis: &Eigenbasis, tau: f64) -> Vec<f64> {
    let n = raw.values.len();
    let mut h = low_pass(&raw.values, basis, tau);
    // How much of the curvature's energy the low band holds: noise spreads over every
    // frequency, so a noisy mesh keeps little of it and its term fades.
    let energy = |f: &[f64]| f.iter().zip(&basis.mass).map(|(x, m)| x * x * m).sum::<f64>().sqrt();
    let ratio = energy(&h) / energy(&raw.values);
    let mut reliability = if ratio.is_finite() { (ratio / RELIABLE_RATIO).min(1.0).powi(2) } else { 0.0 };
    if let Some([a, b]) = &raw.halves {
        let (a, b) = (low_pass(a, basis, tau), low_pass(b, basis, tau));
        let difference: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x - y).collect();
        let sum: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + y).collect();
        let error = energy(&difference) / energy(&sum);
        let trust = if error.is_finite() { ((NOISE_ERROR - error) / (NOISE_ERROR - TRUSTED_ERROR)).clamp(0.0, 1.0) } else { 0.0 };
        reliability *= trust;
    }
    let mut magnitudes: Vec<f64> = h.iter().map(|x| x.abs()).collect();
    let median = if n == 0 { 0.0 } else { *magnitudes.select_nth_unstable_by(n / 2, f64::total_cmp).1 };
    if median > 0.0 && median.is_finite() {
        for x in &mut h {
            *x *= reliability / median;
        }
    }
    // No cue rather than a wrong one: a flat mesh, or a value a near-degenerate triangle's
    // cotangent blew up (the polish's descent compares costs, which NaN would break).
    if !(median > 0.0 && median.is_finite() && h.iter().all(|x| x.is_finite())) {
        h.fill(0.0);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix;
    use crate::spectral::EigenParams;

    /// On a sphere the mean curvature is constant: `h_s` is ±1 everywhere (normalised by its
    /// median); on an elongated ellipsoid it is largest at the tips.
    #[test]
    fn constant_on_a_sphere_largest_at_an_ellipsoids_tips() {
        let sphere = crate::shapes::ellipsoid(3, [1.0, 1.0, 1.0]);
        let (sphere, _) = sphere.normalized();
        let basis = Eigenbasis::compute(&sphere, &EigenParams { k: 20, ..Default::default() }).unwrap();
        let normals = sphere.vertex_normals(&sphere.oriented_triangles());
        let h = band_limited(&Raw::on_mesh(raw_mean_curvature(&sphere, &normals).0), &basis, 1e-3);
        assert!(h.iter().all(|x| (x.abs() - 1.0).abs() < 0.05), "{:?}", h.iter().fold((f64::MAX, f64::MIN), |a, &x| (a.0.min(x), a.1.max(x))));

        let (ellipsoid, _) = crate::shapes::ellipsoid(3, [2.0, 1.0, 1.0]).normalized();
        let basis = Eigenbasis::compute(&ellipsoid, &EigenParams { k: 30, ..Default::default() }).unwrap();
        let normals = ellipsoid.vertex_normals(&ellipsoid.oriented_triangles());
        let h = band_limited(&Raw::on_mesh(raw_mean_curvature(&ellipsoid, &normals).0), &basis, 1e-3);
        let tip = (0..ellipsoid.num_vertices()).max_by(|&a, &b| ellipsoid.vertices[a][0].total_cmp(&ellipsoid.vertices[b][0])).unwrap();
        let waist = (0..ellipsoid.num_vertices()).min_by(|&a, &b| ellipsoid.vertices[a][0].abs().total_cmp(&ellipsoid.vertices[b][0].abs())).unwrap();
        assert!(h[tip].abs() > 1.5 * h[waist].abs(), "tip {} waist {}", h[tip], h[waist]);
    }

    /// The cells of an ellipsoid's hierarchy carry the fine mesh's curvature to the coarse
    /// mesh: each cell's mean is near its seed's value, and band-limited on the coarse basis
    /// it ranks the tips above the waist.
    #[test]
    fn cells_carry_the_fine_curvature_to_the_coarse_mesh() {
        let (fine, _) = crate::shapes::ellipsoid(5, [2.0, 1.0, 1.0]).normalized();
        let h = crate::hierarchy::Hierarchy::new(&fine, 1500).unwrap();
        let (coarse, _) = h.coarse.normalized();
        let normals = fine.vertex_normals(&fine.oriented_triangles());
        let (at_seed, mass) = raw_mean_curvature(&fine, &normals);
        let raw = Raw::on_cells(&at_seed, &mass, &h, &fine.vertices, &normals).values;
        // The curvature varies slowly at the scale of a cell: a cell's mean stays within 10% of
        // its seed's own value.
        let close = h.seeds.iter().zip(&raw).filter(|(&s, &c)| (c - at_seed[s]).abs() <= 0.1 * at_seed[s].abs()).count();
        assert!(close as f64 >= 0.95 * raw.len() as f64, "{close} of {}", raw.len());
        let basis = Eigenbasis::compute(&coarse, &EigenParams { k: 30, ..Default::default() }).unwrap();
        let hs = band_limited(&Raw::on_mesh(raw), &basis, 1e-3);
        let tip = (0..coarse.num_vertices()).max_by(|&a, &b| coarse.vertices[a][0].total_cmp(&coarse.vertices[b][0])).unwrap();
        let waist = (0..coarse.num_vertices()).min_by(|&a, &b| coarse.vertices[a][0].abs().total_cmp(&coarse.vertices[b][0].abs())).unwrap();
        assert!(hs[tip].abs() > 1.5 * hs[waist].abs(), "tip {} waist {}", hs[tip], hs[waist]);
    }

    /// On a hierarchy the two halves of each cell tell noise from curvature: on a clean
    /// ellipsoid they agree (relative error ρ = 0.015) and the term keeps its weight (the same
    /// field as from the cells' means alone); with noise of ±0.5% of √area on every vertex
    /// (about a quarter of an edge) they do not (ρ = 0.90) and the term is off, where the
    /// energy test alone, which sees only the already averaged means, keeps 0.57 of it.
    #[test]
    fn the_halves_of_the_cells_turn_noisy_curvature_off() {
        let coarse_curvature = |noise: f64| {
            let (mut fine, _) = crate::shapes::ellipsoid(5, [2.0, 1.0, 1.0]).normalized();
            let mut random = SplitMix::new(1);
            for p in &mut fine.vertices {
                for x in p.iter_mut() {
                    *x += noise * (2.0 * random.unit() - 1.0);
                }
            }
            let normals = fine.vertex_normals(&fine.oriented_triangles());
            let (raw, mass) = raw_mean_curvature(&fine, &normals);
            let h = crate::hierarchy::Hierarchy::new(&fine, 1500).unwrap();
            let (coarse, _) = h.coarse.normalized();
            let basis = Eigenbasis::compute(&coarse, &EigenParams { k: 30, ..Default::default() }).unwrap();
            let on_cells = Raw::on_cells(&raw, &mass, &h, &fine.vertices, &normals);
            (band_limited(&on_cells, &basis, 1e-3), band_limited(&Raw::on_mesh(on_cells.values.clone()), &basis, 1e-3))
        };
        let (clean, clean_means_only) = coarse_curvature(0.0);
        assert_eq!(clean, clean_means_only);
        assert!(clean.iter().any(|&x| x != 0.0));
        let (noisy, noisy_means_only) = coarse_curvature(0.005);
        assert!(noisy.iter().all(|&x| x == 0.0), "the term is not off on the noisy ellipsoid");
        let mut magnitudes: Vec<f64> = noisy_means_only.iter().map(|x| x.abs()).collect();
        let mid = magnitudes.len() / 2;
        let median = *magnitudes.select_nth_unstable_by(mid, f64::total_cmp).1;
        assert!(median > 0.4, "the means alone fade it to {median}");
    }

    /// Noise on every vertex (a scan's) is mostly high-frequency curvature: the low band
    /// keeps little of it and the term fades; a clean sphere keeps its full weight (|h_s| = 1).
    #[test]
    fn noise_fades_the_curvature() {
        let median_magnitude = |noise: f64| {
            let mut sphere = crate::shapes::icosphere(4);
            let mut random = SplitMix::new(2);
            for p in &mut sphere.vertices {
                let r = 1.0 + noise * (2.0 * random.unit() - 1.0);
                *p = p.map(|x| x * r);
            }
            let (sphere, _) = sphere.normalized();
            let basis = Eigenbasis::compute(&sphere, &EigenParams { k: 30, ..Default::default() }).unwrap();
            let normals = sphere.vertex_normals(&sphere.oriented_triangles());
            let (raw, _) = raw_mean_curvature(&sphere, &normals);
            let mut h: Vec<f64> = band_limited(&Raw::on_mesh(raw), &basis, 1e-3).iter().map(|x| x.abs()).collect();
            let mid = h.len() / 2;
            *h.select_nth_unstable_by(mid, f64::total_cmp).1
        };
        let (clean, light, heavy) = (median_magnitude(0.0), median_magnitude(0.02), median_magnitude(0.05));
        assert!((clean - 1.0).abs() < 1e-9, "clean {clean}");
        assert!(light < 0.8 && heavy < 0.5 * light, "2% noise {light}, 5% {heavy}");
    }
}
