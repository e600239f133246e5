//! Evaluation protocol (DESIGN.md): error of a vertex = geodesic distance between its predicted
//! and true image / √area; accuracy@r = fraction of ground-truth pairs with error ≤ r
//! (unmapped counts as wrong).
//!
//! Geodesics are Dijkstra distances on the edge graph, a slight overestimate of the true
//! surface distance (by a few percent on regular meshes), stopped at the largest radius asked
//! for, so scoring costs a local search per vertex, not an all-pairs matrix.
//!
//! [`judge_maps`] gives the verdict the detection's judge ([`crate::judge`]) would give any
//! map, the ground truth's included: where the truth outscores every reported map and was not
//! found, the search failed; where a wrong map outscores the truth, the judge did.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::maps::geodesic::EdgeGraph;
use crate::mesh::Mesh;
use crate::mesh::vec3::dist2;

#[derive(PartialEq)]
struct Item(f64, u32);
impl Eq for Item {}
impl PartialOrd for Item {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Item {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// Edge-graph geodesic distances, bounded: a reusable Dijkstra workspace.
pub struct Geodesics {
    graph: EdgeGraph,
    dist: Vec<f64>,
    touched: Vec<u32>,
    /// Vertex positions: the straight-line distance bounds an edge path from below.
    points: Vec<[f64; 3]>,
}

impl Geodesics {
    /// Prepares the edge graph of `mesh`.
    pub fn new(mesh: &Mesh) -> Self {
        let n = mesh.num_vertices();
        Geodesics { graph: EdgeGraph::new(&mesh.vertices, mesh.adjacency()), dist: vec![f64::INFINITY; n], touched: Vec::new(), points: mesh.vertices.clone() }
    }

    /// Distance from `a` to `b`, or `f64::INFINITY` when it exceeds `limit`.
    pub fn distance(&mut self, a: usize, b: usize, limit: f64) -> f64 {
        // Every edge path is at least as long as the straight segment: a pair farther apart
        // than `limit` cannot be reached, and needs no search (most pairs of a wrong map).
        let (p, q) = (self.points[a], self.points[b]);
        if dist2(p, q).sqrt() > limit {
            return f64::INFINITY;
        }
        for &t in &self.touched {
            self.dist[t as usize] = f64::INFINITY;
        }
        self.touched.clear();
        let mut heap = BinaryHeap::new();
        self.dist[a] = 0.0;
        self.touched.push(a as u32);
        heap.push(Item(0.0, a as u32));
        while let Some(Item(d, v)) = heap.pop() {
            let v = v as usize;
            if v == b {
                return d;
            }
            if d > self.dist[v] || d > limit {
                continue;
            }
            let g = &self.graph;
            for e in g.off[v]..g.off[v + 1] {
                let u = g.nbr[e] as usize;
                let nd = d + g.len[e];
                if nd < self.dist[u] && nd <= limit {
                    if self.dist[u].is_infinite() {
                        self.touched.push(u as u32);
                    }
                    self.dist[u] = nd;
                    heap.push(Item(nd, u as u32));
                }
            }
        }
        f64::INFINITY
    }
}

/// Accuracy at each radius in `radii` (fractions of √area) of `pred` against the ground-truth
/// pairs `(x, true image of x)`; `alternatives` are further acceptable images per pair (e.g.
/// the in-leg mirror), checked too. Unmapped (`pred[x] < 0`) counts as wrong.
pub fn accuracy(mesh: &Mesh, pred: &[i64], truth: &[(usize, Vec<usize>)], radii: &[f64]) -> Vec<f64> {
    let scale = mesh.area().sqrt();
    let limit = radii.iter().cloned().fold(0.0, f64::max) * scale;
    let mut geo = Geodesics::new(mesh);
    let mut hits = vec![0usize; radii.len()];
    for (x, images) in truth {
        let p = pred[*x];
        if p < 0 {
            continue;
        }
        let err = images.iter().map(|&t| geo.distance(p as usize, t, limit)).fold(f64::INFINITY, f64::min) / scale;
        for (h, r) in hits.iter_mut().zip(radii) {
            if err <= *r {
                *h += 1;
            }
        }
    }
    hits.iter().map(|&h| h as f64 / truth.len().max(1) as f64).collect()
}

/// The report phase's verdict ([`crate::judge::Judge::judge`], with its sample distortion) on
/// each of `maps` (an image per vertex of `mesh`, −1 outside the map; entries out of range
/// count as −1), as a detection of `mesh` with `params` at full resolution would judge its own
/// maps: the same eigenbasis, samples, distortion scale, normals and band-limited curvature.
/// A mesh of several components is judged whole, and a mesh large enough for the hierarchy
/// ([`crate::hierarchy`]) at full resolution, so there the verdicts are not the detection's.
/// Returns each map's verdict and its sample distortion.
pub fn judge_maps(mesh: &Mesh, params: &crate::Params, maps: &[Vec<i64>]) -> Result<Vec<(crate::judge::Verdict, f64)>, crate::Error> {
    let (mesh, _) = mesh.normalized();
    let n = mesh.num_vertices();
    let basis = crate::spectral::Eigenbasis::compute_with_progress(&mesh, &params.eigen_for(n), &mut |_| true)?;
    let emb = crate::distance::biharmonic(&basis);
    let samples = crate::sampling::farthest_point(&emb, params.samples, params.seed).vertices;
    let diameter = emb.diameter_of(&samples);
    let normals = mesh.vertex_normals(&mesh.oriented_triangles());
    let curvature = crate::detect::band_limited_curvature(None, &mesh, &normals, &basis, &params.maps);
    let judge = crate::judge::Judge::new(&mesh.vertices, normals, &mesh.adjacency(), mesh.area().sqrt(), &params.judge).with_curvature(curvature).with_band(Some(crate::judge::LowBand::from_basis(&basis)));
    Ok(maps
        .iter()
        .map(|map| {
            let map: Vec<i64> = (0..n).map(|v| map.get(v).copied().filter(|&w| w >= 0 && (w as usize) < n).unwrap_or(-1)).collect();
            let distortion = crate::characterize::sample_distortion(&map, &samples, &emb, diameter);
            (judge.judge(&map, distortion, params.max_distortion), distortion)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn geodesics_on_the_icosphere_are_close_to_great_circles() {
        let mesh = shapes::icosphere(4);
        let mut g = Geodesics::new(&mesh);
        let mirror = shapes::mirror_map(&mesh, 0);
        // A vertex and its mirror: great-circle distance 2·asin(|x|)... use the angle.
        for v in [5usize, 100, 700, 2000] {
            let p = mesh.vertices[v];
            let q = mesh.vertices[mirror[v] as usize];
            let angle = (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]).clamp(-1.0, 1.0).acos();
            let d = g.distance(v, mirror[v] as usize, 10.0);
            assert!(d >= angle - 1e-9 && d <= angle * 1.15 + 1e-9, "v {v}: {d} vs {angle}");
        }
        assert!(g.distance(0, mirror[0] as usize, 1e-6).is_infinite() || mirror[0] == 0);
    }

    #[test]
    fn accuracy_of_truth_is_one_and_of_nothing_is_zero() {
        let mesh = shapes::icosphere(3);
        let mirror = shapes::mirror_map(&mesh, 0);
        let truth: Vec<(usize, Vec<usize>)> = (0..mesh.num_vertices()).map(|v| (v, vec![mirror[v] as usize])).collect();
        let pred: Vec<i64> = mirror.iter().map(|&m| m as i64).collect();
        assert_eq!(accuracy(&mesh, &pred, &truth, &[0.05, 0.1]), vec![1.0, 1.0]);
        assert_eq!(accuracy(&mesh, &vec![-1; mesh.num_vertices()], &truth, &[0.05]), vec![0.0]);
        let identity: Vec<i64> = (0..mesh.num_vertices() as i64).collect();
        let acc = accuracy(&mesh, &identity, &truth, &[0.05])[0];
        assert!(acc > 0.0 && acc < 0.2, "{acc}");
    }

    /// The judge's verdicts on given maps: on the rest quadruped its exact mirror reverses
    /// orientation, fixes almost nothing and outscores the identity (which fixes everything,
    /// score 0) and a half-identity; the detection's own first map gets the verdict the
    /// detection reported for it.
    #[test]
    fn the_judge_of_given_maps_matches_the_detection() {
        let c = shapes::quadruped(4, shapes::Pose::Rest, 0.0, 0);
        let n = c.mesh.num_vertices();
        let mirror: Vec<i64> = c.mirror.iter().map(|&m| if m == u32::MAX { -1 } else { m as i64 }).collect();
        let identity: Vec<i64> = (0..n as i64).collect();
        let half: Vec<i64> = (0..n).map(|v| if c.mesh.vertices[v][2] > 0.0 { mirror[v] } else { v as i64 }).collect();
        let params = crate::Params::default();
        let d = crate::detect(&c.mesh, &params, &mut |_| true).unwrap();
        let first = d.symmetries[0].map.clone();
        let v = judge_maps(&c.mesh, &params, &[mirror, identity, half, first, vec![3; 2]]).unwrap();
        assert!(v[0].0.reversal > 0.95 && v[0].0.fixed < 0.05 && v[0].1 < 0.01, "mirror: {:?}", v[0]);
        assert!(v[1].0.fixed > 0.95 && v[1].0.score == 0.0, "identity: {:?}", v[1]);
        assert!(v[0].0.score > 0.5 && v[0].0.score > 2.0 * v[2].0.score, "mirror {:?} against half {:?}", v[0], v[2]);
        let reported = &d.symmetries[0];
        assert!((v[3].0.score - reported.verdict.score).abs() < 1e-9 && (v[3].1 - reported.distortion).abs() < 1e-12, "{:?} against {} {}", v[3], reported.verdict.score, reported.distortion);
        // A map too short: its missing entries are unmapped, nothing panics.
        assert!(v[4].0.coverage < 0.01);
    }
}
