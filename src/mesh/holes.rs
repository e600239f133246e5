//! Holes closed before detection (beyond the paper): each boundary loop of a hole's size is
//! capped, the pipeline runs on the closed surface, and the caps' vertices are reported as the
//! rim vertices nearest them.
//!
//! **Why.** Every stage before the maps reads the Laplace–Beltrami eigenbasis, whose
//! eigenfunctions on a surface with boundary satisfy the Neumann condition on the rim: a hole
//! changes them over the whole surface, not only around it. A scan's holes (occlusions,
//! topological clean-up) are not mirrored on the other side, so where the intact surface would
//! have a symmetric spectrum, the holed one has a lopsided one, and with it the wave kernel
//! signature, the biharmonic distance and the functional maps. Measured on TOSCA's cat0 with
//! three holes of radius 0.08·√area (7% of its vertices removed): profile maps made from the
//! *true* sample correspondences with biharmonic distances score 45% acc@0.05, with geodesic
//! ones 88%; the detection finds no mirror at all (2.5%; intact 98%). Over holed copies of
//! TOSCA and FAUST (`bench/holed_copies.py`: three holes of radius 0.08·√area each, seed 5),
//! best / first acc@0.05 63.9 / 57.8 → 83.6 / 81.5% on TOSCA and 51.4 / 45.5 → 77.6 / 75.6% on
//! FAUST with the holes capped (docs/accuracy.md, "Session 31").
//!
//! **What.** A boundary loop (a cycle of edges with one triangle each, traced on the
//! consistently oriented triangles) from [`MIN_LOOP`] to [`MAX_LOOP`] times √area long is a
//! hole; a longer one is the rim of an open surface (a disk's rim is 3.5·√area long, a
//! hemisphere's 2.5) and stays open, and so does a shorter one: capping the small holes of
//! shared/data cost accuracy (see [`MIN_LOOP`]). A hole of `m` rim vertices, length `L`, mean
//! rim edge `h` is capped by `R = round(L / (2π h))` rings shrinking toward the rim's centroid
//! `c` (ring `j` has `max(3, round(m (R − j) / R))` vertices at `c + (R − j)/R · (γ(t) − c)`,
//! `γ` the rim by arc length) and the centroid itself, consecutive rings zipped by triangles in
//! order of their arc-length parameters: edges about as long as the rim's, a flat cone over the
//! hole. Only its metric matters to the intrinsic stages; the polish's mean curvature, which
//! would see a crease along the rim, takes over each cap and rim the mean of the vertices just
//! outside ([`Closed::calm_curvature`]).
//!
//! The caps' vertices come after the mesh's, so every vertex keeps its index, and take part in
//! everything (eigenbasis, descriptors, sampling, voting, maps, judge). A map is reported on
//! the mesh's vertices; an image that falls in a cap is reported as the cap vertex's anchor,
//! the rim vertex nearest it (the point of the surface nearest to where the image should be).
//! A pinched rim (a vertex with several boundary edges leaving it) is traced one way; a loop
//! that cannot be closed that way is left open.

use super::vec3::{norm, sub};
use super::Mesh;

/// The longest boundary loop that is closed, in units of √area of the mesh: the rims of open
/// surfaces are longer (a hemisphere 2.5, a disk 3.5), a scan's holes shorter (three holes of
/// radius 0.08·√area punched in a generated quadruped leave rims of 0.43–1.05, two of them
/// run together; a tube of length 10 radii has rims of 0.79 at its ends: capped, it stays as
/// symmetric as it was).
pub const MAX_LOOP: f64 = 2.0;

/// The shortest boundary loop that is closed, in units of √area. Capping small holes gains
/// nothing and costs a little: the small loops of shared/data (the SHREC'16 kids' and KIDS
/// poses', 0.02–0.31·√area, most in mirror-image pairs) capped as well (curvature calmed)
/// lowered the kids from 70.9 / 65.5 to 68.6 / 64.5 and the KIDS poses from 95.2 to 93.4%
/// acc@0.05 (best / first, mean over seeds 0, 10, 20, 30); three holes of radius 0.05·√area
/// (rims about 0.31) punched in twelve TOSCA shapes cost 3.5 points, and capping them gained
/// 1.9 (best) and lost 0.5 (first); holes of radius 0.08 (rims about 0.5) cost tens of
/// points, and capping wins them back (docs/accuracy.md, "Session 31"). A one-sided hole
/// below this can still hide a symmetry (a generated quadruped's three holes of radius 0.06).
pub const MIN_LOOP: f64 = 0.4;

/// A mesh with its holes capped.
#[derive(Clone, Debug)]
pub struct Closed {
    /// The mesh and its caps: the first [`Closed::original`] vertices are the mesh's, in its
    /// order, with its input indices; cap vertex `original + j` has input index
    /// `info.input_vertices + j` (past every input vertex), and `info.input_vertices` counts
    /// the caps' vertices too.
    pub mesh: Mesh,
    /// Vertices of the mesh before closing.
    pub original: usize,
    /// For each cap vertex, the rim vertex nearest it (a vertex of the mesh).
    pub anchor: Vec<u32>,
    /// Each hole's rim (vertices of the mesh) and the range of its cap's vertices.
    pub rims: Vec<(Vec<u32>, std::ops::Range<usize>)>,
}

impl Closed {
    /// Takes the caps out of a raw per-vertex mean curvature of the closed mesh (`raw`, as
    /// [`crate::descriptors::curvature::raw_mean_curvature`] gives it): each hole's rim and cap
    /// vertices get the mean of the vertices just outside the rim. A flat cap meets the surface
    /// at a crease, and the crease's curvature is the cap's, not the shape's. Measured with
    /// every loop of shared/data capped (seeds 0, 10, 20, 30, best / first acc@0.05): SHREC'16
    /// 67.2 / 62.3% with the crease, 68.6 / 64.5% calmed; KIDS 93.8 and 93.4%.
    pub fn calm_curvature(&self, raw: &mut [f64]) {
        let (off, nbr) = self.mesh.adjacency();
        for (rim, cap) in &self.rims {
            let on_rim: std::collections::HashSet<u32> = rim.iter().copied().collect();
            let outside: std::collections::BTreeSet<u32> = rim
                .iter()
                .flat_map(|&v| nbr[off[v as usize]..off[v as usize + 1]].iter().copied())
                .filter(|&u| (u as usize) < self.original && !on_rim.contains(&u))
                .collect();
            let values: Vec<f64> = outside.iter().map(|&u| raw[u as usize]).filter(|x| x.is_finite()).collect();
            if values.is_empty() {
                continue;
            }
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            for &v in rim {
                raw[v as usize] = mean;
            }
            raw[cap.clone()].fill(mean);
        }
    }

    /// The vertex of the mesh standing for vertex `v` of the closed mesh: itself, or a cap
    /// vertex's anchor.
    pub fn on_mesh(&self, v: usize) -> usize {
        if v < self.original {
            v
        } else {
            self.anchor[v - self.original] as usize
        }
    }
}

/// `mesh` with every boundary loop from `min_loop` to `max_loop` times √area long capped
/// (module docs); `None` when there is none (a closed mesh, or only short or long rims).
pub fn close(mesh: &Mesh, min_loop: f64, max_loop: f64) -> Option<Closed> {
    let Boundary { loops, oriented: mut triangles } = boundary_loops(mesh)?;
    let scale = mesh.area().sqrt();
    let holes: Vec<Vec<u32>> = loops
        .into_iter()
        .filter(|l| l.len() >= 3 && (min_loop * scale..=max_loop * scale).contains(&loop_length(&mesh.vertices, l)))
        .collect();
    if holes.is_empty() {
        return None;
    }
    let original = mesh.num_vertices();
    let mut vertices = mesh.vertices.clone();
    let mut anchor = Vec::new();
    let mut rims = Vec::with_capacity(holes.len());
    for hole in &holes {
        let start = vertices.len();
        cap(hole, &mut vertices, &mut triangles, &mut anchor);
        rims.push((hole.clone(), start..vertices.len()));
    }
    let input_vertices = mesh.info.input_vertices;
    let mut input_index = mesh.input_index.clone();
    input_index.extend((0..anchor.len()).map(|j| (input_vertices + j) as u32));
    let mut info = mesh.info.clone();
    info.input_vertices += anchor.len();
    let closed = Mesh { vertices, triangles, input_index, welded: mesh.welded.clone(), info };
    Some(Closed { mesh: closed, original, anchor, rims })
}

/// A mesh's boundary loops and the triangles they were traced on.
struct Boundary {
    /// Vertex cycles without the closing repeat, each in the direction the triangles traverse it.
    loops: Vec<Vec<u32>>,
    /// The mesh's triangles, consistently oriented (`Mesh::oriented_triangles`).
    oriented: Vec<[u32; 3]>,
}

/// The boundary loops of `mesh` (edges of one triangle), traced on its consistently oriented
/// triangles; `None` for a mesh without boundary.
fn boundary_loops(mesh: &Mesh) -> Option<Boundary> {
    // Boundary edges: keys that occur once among the sorted edge keys (linear time; a closed
    // mesh, the common case, stops here).
    let keys = super::sorted_edge_keys(&mesh.triangles);
    let boundary: Vec<u64> = keys.chunk_by(|a, b| a == b).filter(|run| run.len() == 1).map(|run| run[0]).collect();
    if boundary.is_empty() {
        return None;
    }
    let on_boundary = |a: u32, b: u32| boundary.binary_search(&super::edge_key(a, b)).is_ok();
    // Each boundary half-edge `a → b` as the consistently oriented triangles traverse it, by
    // `a` (sorted, so the tracing is deterministic).
    let triangles = mesh.oriented_triangles();
    let mut out: Vec<(u32, u32)> = Vec::new();
    for t in &triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on_boundary(a, b) {
                out.push((a, b));
            }
        }
    }
    out.sort_unstable();
    let mut used = vec![false; out.len()];
    let next = |v: u32, used: &[bool]| -> Option<usize> {
        let start = out.partition_point(|e| e.0 < v);
        (start..out.len()).take_while(|&i| out[i].0 == v).find(|&i| !used[i])
    };
    let mut loops = Vec::new();
    for first in 0..out.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let start = out[first].0;
        let mut cycle = vec![start];
        let mut at = out[first].1;
        let closed = loop {
            if at == start {
                break true;
            }
            cycle.push(at);
            match next(at, &used) {
                Some(i) => {
                    used[i] = true;
                    at = out[i].1;
                }
                None => break false,
            }
        };
        if closed {
            loops.push(cycle);
        }
    }
    Some(Boundary { loops, oriented: triangles })
}

fn loop_length(p: &[[f64; 3]], cycle: &[u32]) -> f64 {
    (0..cycle.len()).map(|i| norm(sub(p[cycle[(i + 1) % cycle.len()] as usize], p[cycle[i] as usize]))).sum()
}

/// Caps the hole `rim` (module docs): appends the cap's vertices to `vertices` (with their
/// anchors to `anchor`) and its triangles, oriented against the rim's direction, to
/// `triangles`.
fn cap(rim: &[u32], vertices: &mut Vec<[f64; 3]>, triangles: &mut Vec<[u32; 3]>, anchor: &mut Vec<u32>) {
    let m = rim.len();
    let p: Vec<[f64; 3]> = rim.iter().map(|&v| vertices[v as usize]).collect();
    if m == 3 {
        triangles.push([rim[2], rim[1], rim[0]]);
        return;
    }
    let seg: Vec<f64> = (0..m).map(|i| norm(sub(p[(i + 1) % m], p[i]))).collect();
    let length: f64 = seg.iter().sum();
    // A rim of zero (or NaN) length has nothing to cap.
    if length.is_nan() || length <= 0.0 {
        return;
    }
    // Arc-length parameter of each rim vertex, in [0, 1).
    let mut s = vec![0.0; m];
    for i in 1..m {
        s[i] = s[i - 1] + seg[i - 1] / length;
    }
    let centre = p.iter().fold([0.0; 3], |c, q| [c[0] + q[0] / m as f64, c[1] + q[1] / m as f64, c[2] + q[2] / m as f64]);
    let mean_edge = length / m as f64;
    let rings = ((length / (2.0 * std::f64::consts::PI * mean_edge)).round() as usize).max(1);
    // The rim point at parameter t, and the rim vertex nearest it in parameter.
    let on_rim = |t: f64| -> ([f64; 3], usize) {
        let k = s.partition_point(|&x| x <= t).saturating_sub(1).min(m - 1);
        let end = if k + 1 < m { s[k + 1] } else { 1.0 };
        let a = if end > s[k] { (t - s[k]) / (end - s[k]) } else { 0.0 };
        let (q0, q1) = (p[k], p[(k + 1) % m]);
        let point = [0, 1, 2].map(|d| q0[d] + a * (q1[d] - q0[d]));
        (point, if a < 0.5 { k } else { (k + 1) % m })
    };
    // Rings from the rim inward: (vertex indices, parameters).
    let mut previous: (Vec<u32>, Vec<f64>) = (rim.to_vec(), s.clone());
    for j in 1..=rings {
        let inner: (Vec<u32>, Vec<f64>) = if j == rings {
            // The centre, anchored at the rim vertex nearest it.
            let nearest = (0..m).min_by(|&a, &b| norm(sub(p[a], centre)).total_cmp(&norm(sub(p[b], centre)))).unwrap_or(0);
            anchor.push(rim[nearest]);
            vertices.push(centre);
            (vec![(vertices.len() - 1) as u32], vec![0.0])
        } else {
            let frac = (rings - j) as f64 / rings as f64;
            let count = ((m as f64 * frac).round() as usize).max(3);
            let params: Vec<f64> = (0..count).map(|i| i as f64 / count as f64).collect();
            let mut idx = Vec::with_capacity(count);
            for &t in &params {
                let (q, near) = on_rim(t);
                vertices.push([0, 1, 2].map(|d| centre[d] + frac * (q[d] - centre[d])));
                anchor.push(rim[near]);
                idx.push((vertices.len() - 1) as u32);
            }
            (idx, params)
        };
        zip(&previous, &inner, triangles);
        previous = inner;
    }
}

/// Triangles between two closed rings (`outer` in the rim's direction, `inner` likewise, each
/// with the arc-length parameters of its vertices), oriented against that direction: the
/// next triangle advances on the ring whose next parameter comes first.
fn zip(outer: &(Vec<u32>, Vec<f64>), inner: &(Vec<u32>, Vec<f64>), triangles: &mut Vec<[u32; 3]>) {
    let (a, sa) = outer;
    let (b, sb) = inner;
    let (na, nb) = (a.len(), b.len());
    if nb == 1 {
        for i in 0..na {
            triangles.push([a[(i + 1) % na], a[i], b[0]]);
        }
        return;
    }
    let (mut i, mut j) = (0, 0);
    while i < na || j < nb {
        let ta = if i + 1 < na { sa[i + 1] } else { 1.0 };
        let tb = if j + 1 < nb { sb[j + 1] } else { 1.0 };
        if j >= nb || (i < na && ta <= tb) {
            triangles.push([a[(i + 1) % na], a[i], b[j % nb]]);
            i += 1;
        } else {
            triangles.push([b[(j + 1) % nb], a[i % na], b[j]]);
            j += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MeshParams;

    /// An icosphere with the triangles around its south pole removed: one hole.
    fn holed(level: u32, below: f64) -> Mesh {
        let s = crate::shapes::icosphere(level);
        let t: Vec<[u32; 3]> = s.triangles.iter().filter(|t| t.iter().map(|&i| s.vertices[i as usize][2]).sum::<f64>() / 3.0 > below).copied().collect();
        Mesh::new(s.vertices.clone(), t, &MeshParams::default()).unwrap()
    }

    /// A capped hole leaves a closed surface (every edge in two triangles, consistently
    /// oriented), keeps the mesh's vertices first, anchors every cap vertex on the rim, and
    /// restores about the missing area.
    #[test]
    fn a_hole_is_capped_into_a_closed_surface() {
        let mesh = holed(3, -0.95);
        let loops = boundary_loops(&mesh).expect("a boundary").loops;
        assert_eq!(loops.len(), 1);
        let ratio = loop_length(&mesh.vertices, &loops[0]) / mesh.area().sqrt();
        let closed = close(&mesh, MIN_LOOP, MAX_LOOP).unwrap_or_else(|| panic!("one hole, rim {ratio} √area"));
        assert_eq!((closed.rims.len(), closed.original), (1, mesh.num_vertices()));
        let c = &closed.mesh;
        assert_eq!(&c.vertices[..closed.original], &mesh.vertices[..]);
        assert_eq!(&c.input_index[..closed.original], &mesh.input_index[..]);
        assert_eq!(c.num_vertices(), closed.original + closed.anchor.len());
        assert!(boundary_loops(c).is_none(), "still open");
        assert!(c.consistently_oriented());
        let rim: std::collections::HashSet<u32> = loops[0].iter().copied().collect();
        assert!(closed.anchor.iter().all(|a| rim.contains(a)));
        // The cap covers the spherical cap it replaces within 20% (it is flat).
        let sphere = crate::shapes::icosphere(3);
        let whole = Mesh::new(sphere.vertices.clone(), sphere.triangles.clone(), &MeshParams::default()).unwrap();
        let (missing, capped) = (whole.area() - mesh.area(), c.area() - mesh.area());
        assert!(capped > 0.8 * missing && capped < 1.2 * missing, "cap {capped} for {missing}");
        // Cap edges are about as long as the rim's.
        let rim_edge = loop_length(&mesh.vertices, &loops[0]) / loops[0].len() as f64;
        for t in &c.triangles[mesh.num_triangles()..] {
            for k in 0..3 {
                let e = norm(sub(c.vertices[t[k] as usize], c.vertices[t[(k + 1) % 3] as usize]));
                assert!(e < 2.5 * rim_edge, "cap edge {e} against the rim's {rim_edge}");
            }
        }
    }

    /// A closed mesh and an open surface's long rim are left as they are.
    #[test]
    fn closed_meshes_and_long_rims_stay() {
        let s = crate::shapes::icosphere(2);
        let sphere = Mesh::new(s.vertices.clone(), s.triangles.clone(), &MeshParams::default()).unwrap();
        assert!(close(&sphere, MIN_LOOP, MAX_LOOP).is_none());
        // A hemisphere: its rim is 2.5·√area long.
        assert!(close(&holed(3, 0.0), MIN_LOOP, MAX_LOOP).is_none());
        assert!(close(&holed(3, 0.0), MIN_LOOP, 3.0).is_some());
        // A small hole (rim 0.23·√area).
        let small = holed(3, -0.99);
        assert!(close(&small, MIN_LOOP, MAX_LOOP).is_none());
        assert!(close(&small, 0.0, MAX_LOOP).is_some());
    }
}
