//! Generated shapes with known geometry, for tests, benchmarks and the bundled example.
//!
//! - [`icosphere`]: the unit sphere, whose Laplace–Beltrami eigenvalues are l(l+1) with
//!   multiplicity 2l+1;
//! - [`bumpy_torus`]: a torus with a smooth, symmetry-breaking radial bump, sized for the
//!   spectral benchmarks (3·s² vertices);
//! - [`needle_sphere`]: an icosphere with collapsed (zero-area) and needle triangles;
//! - [`creature`]: mirror-symmetric animals built on the icosphere (whose vertex set is exactly
//!   symmetric under x → −x, so every vertex's true mirror image is known), optionally posed
//!   (limbs rotated with smooth skinning) and noised (normal displacement), with ground truth:
//!   [`quadruped`] (4 legs, head, tail) and [`star`] (n arms in a plane), and, with directed
//!   limbs ([`creature_with`]), [`directed_quadruped`] and [`spiked`], whose repeated parts map
//!   onto each other by translations no global symmetry carries;
//! - [`subdivide`]: a mesh with every triangle split in four at its edge midpoints (the same
//!   surface at 4× the triangles), for scaling a shape with ground truth to benchmark sizes.
//!
//! Every function returns a validated [`Mesh`].

use crate::mesh::vec3::{cross, dist2, dot, norm};
use crate::mesh::{Mesh, MeshParams};

fn build(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
    Mesh::new(vertices, triangles, &MeshParams::default()).expect("generated meshes are valid")
}

/// The unit icosphere after `level` 4-to-1 subdivisions: 10·4^level + 2 vertices.
pub fn icosphere(level: u32) -> Mesh {
    let (v, t) = icosphere_arrays(level);
    build(v, t)
}

/// The icosphere of `level` scaled by `axes`: an ellipsoid (three distinct axes: 7 symmetries,
/// the three mirrors, the three half-turns and the antipodal map, each an exact permutation of
/// the vertices, since the icosphere is symmetric under each coordinate's sign flip) or a
/// spheroid (two equal axes: a continuous family).
pub fn ellipsoid(level: u32, axes: [f64; 3]) -> Mesh {
    let (v, t) = icosphere_arrays(level);
    build(v.into_iter().map(|p| [p[0] * axes[0], p[1] * axes[1], p[2] * axes[2]]).collect(), t)
}

/// The map `v ↦ the vertex at (±x, ±y, ±z)` of a mesh symmetric under coordinate sign flips
/// (`flip[i]`: negate coordinate `i`); `None` for a vertex with no such partner.
pub fn sign_flip_map(mesh: &Mesh, flip: [bool; 3]) -> Vec<Option<u32>> {
    let key = |p: [f64; 3]| p.map(|x| (x * 1e6).round() as i64);
    let index: std::collections::HashMap<[i64; 3], u32> = mesh.vertices.iter().enumerate().map(|(i, &p)| (key(p), i as u32)).collect();
    mesh.vertices
        .iter()
        .map(|&p| {
            let q = [0, 1, 2].map(|i| if flip[i] { -p[i] } else { p[i] });
            index.get(&key(q)).copied()
        })
        .collect()
}

/// A torus of revolution (major radius 1, minor `minor`) on an `nu × nv` grid whose odd rings
/// are turned by half a step (so the grid is not itself the only symmetry): a continuous
/// family of rotations about its axis.
pub fn torus_of_revolution(nu: usize, nv: usize, minor: f64) -> Mesh {
    assert!(nu >= 3 && nv >= 3, "torus_of_revolution needs a grid of at least 3 × 3");
    let tau = std::f64::consts::TAU;
    let mut v = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let (th, ph) = (tau * i as f64 / nu as f64, tau * (j as f64 + 0.5 * (i % 2) as f64) / nv as f64);
            let r = 1.0 + minor * ph.cos();
            v.push([r * th.cos(), r * th.sin(), minor * ph.sin()]);
        }
    }
    build(v, torus_grid(nu, nv))
}

fn normalize(p: [f64; 3]) -> [f64; 3] {
    let r = norm(p);
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
    build(v, torus_grid(nu, nv))
}

/// The triangles of an `nu × nv` grid closed in both directions (vertex `(i, j)` at
/// `i·nv + j`), two per cell.
fn torus_grid(nu: usize, nv: usize) -> Vec<[u32; 3]> {
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut t = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    t
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
    // Not welded: the coincident vertices are the point (zero-area triangles kept).
    let unwelded = MeshParams { weld: false, ..Default::default() };
    Mesh::new(v, t, &unwelded).expect("generated meshes are valid")
}

/// For each vertex, the vertex at its mirror position across the plane `x_axis = 0`
/// (`u32::MAX` where there is none). Exact on meshes built symmetric, like the icosphere.
pub fn mirror_map(mesh: &Mesh, axis: usize) -> Vec<u32> {
    let key = |p: [f64; 3]| p.map(|x| (x * 1e9).round() as i64);
    let index: std::collections::HashMap<[i64; 3], u32> =
        mesh.vertices.iter().enumerate().map(|(i, &p)| (key(p), i as u32)).collect();
    mesh.vertices
        .iter()
        .map(|&p| {
            let mut q = p;
            q[axis] = -q[axis];
            *index.get(&key(q)).unwrap_or(&u32::MAX)
        })
        .collect()
}

/// A limb: a protrusion grown from the sphere cap around `direction`.
#[derive(Clone, Debug)]
pub struct Limb {
    /// Centre of the cap on the unit sphere (normalized by the constructor).
    pub direction: [f64; 3],
    /// Direction the limb grows along.
    pub axis: [f64; 3],
    /// Length of the limb.
    pub length: f64,
    /// Half-angle of the cap (radians): the limb's thickness.
    pub cap: f64,
    /// Pose: rotation angle (radians) about `bend_axis` at the limb's base.
    pub bend: f64,
    /// Axis of the pose rotation.
    pub bend_axis: [f64; 3],
}

/// A generated animal and what is known about it.
#[derive(Clone, Debug)]
pub struct Creature {
    /// The mesh.
    pub mesh: Mesh,
    /// `(n,)` the true left–right mirror image of each vertex (the rest shape is symmetric in x).
    pub mirror: Vec<u32>,
    /// `(n,)` limb of each vertex (`usize::MAX` for the body): the vertices of limb j are those
    /// whose weight for j exceeds 1/2.
    pub limb: Vec<usize>,
    /// The limbs as built.
    pub limbs: Vec<Limb>,
    /// `(n, 3)` positions before posing and noise (the symmetric rest shape).
    pub rest: Vec<[f64; 3]>,
}

fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Rotation of `p` about the axis `k` (unit) through `c` by `angle` (Rodrigues).
fn rotate(p: [f64; 3], c: [f64; 3], k: [f64; 3], angle: f64) -> [f64; 3] {
    let v = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
    let (s, co) = angle.sin_cos();
    let kv = dot(k, v);
    let cr = cross(k, v);
    std::array::from_fn(|d| c[d] + v[d] * co + cr[d] * s + k[d] * kv * (1.0 - co))
}

/// Builds a creature on the icosphere of `level`: an ellipsoid body with radii `body` and the
/// given limbs; posed by each limb's `bend`, then displaced along vertex normals by Gaussian
/// noise of standard deviation `noise` × bounding-box diagonal (seeded).
pub fn creature(level: u32, body: [f64; 3], limbs: &[Limb], noise: f64, seed: u64) -> Creature {
    creature_with(level, body, limbs, &[], noise, seed)
}

/// What makes a limb *directed* (not mirror-symmetric front to back, as a real leg is not):
/// in the rest shape its cross-section is round (`round_limb`), the front half of its tip is
/// drawn out forward into a toe, then its lower half is turned about a knee at mid-length so
/// that the foot swings forward. Identical directed limbs are congruent by a translation below
/// the hip (the knee of a front leg and of a hind leg both point backward), which no reflection
/// of the body reproduces.
#[derive(Clone, Debug)]
pub struct Directed {
    /// The forward direction (the toe and the swing point this way).
    pub forward: [f64; 3],
    /// Knee angle (radians) of the lower half.
    pub knee: f64,
    /// Length of the toe, as a fraction of the limb's length.
    pub toe: f64,
}

/// [`creature`] with directed limbs: `directed[j]` (when present and `Some`) shapes limb `j`
/// at rest, before pose and noise.
pub fn creature_with(level: u32, body: [f64; 3], limbs: &[Limb], directed: &[Option<Directed>], noise: f64, seed: u64) -> Creature {
    let (sphere, t) = icosphere_arrays(level);
    let limbs: Vec<Limb> = limbs.iter().map(|l| Limb { direction: normalize(l.direction), axis: normalize(l.axis), bend_axis: normalize(l.bend_axis), ..l.clone() }).collect();
    let n = sphere.len();
    let mut rest = Vec::with_capacity(n);
    let mut limb_of = vec![usize::MAX; n];
    let mut weights = vec![vec![0.0; limbs.len()]; n];
    for (v, &u) in sphere.iter().enumerate() {
        let mut p = [body[0] * u[0], body[1] * u[1], body[2] * u[2]];
        for (j, l) in limbs.iter().enumerate() {
            let theta = dot(u, l.direction).clamp(-1.0, 1.0).acos();
            let t = theta / l.cap;
            if t < 1.0 {
                let grow = l.length * (1.0 - smoothstep(t));
                let directed = directed.get(j).and_then(|d| d.as_ref());
                if let Some(dir) = directed {
                    p = round_limb(p, u, body, l, dir, t);
                }
                for (x, a) in p.iter_mut().zip(l.axis) {
                    *x += grow * a;
                }
                if let Some(dir) = directed {
                    p = direct(p, u, limb_base(body, l), l, dir, grow / l.length);
                }
                // Skinning weight: 1 inside the limb, blending to 0 over its base.
                weights[v][j] = 1.0 - smoothstep((t - 0.55) / 0.45);
                if weights[v][j] > 0.5 {
                    limb_of[v] = j;
                }
            }
        }
        rest.push(p);
    }
    // Pose: rotate each limb about its base point with the blended angle.
    let mut posed = rest.clone();
    for (j, l) in limbs.iter().enumerate() {
        if l.bend == 0.0 {
            continue;
        }
        let base = limb_base(body, l);
        for v in 0..n {
            if weights[v][j] > 0.0 {
                posed[v] = rotate(posed[v], base, l.bend_axis, l.bend * weights[v][j]);
            }
        }
    }
    let mut mesh = build(posed, t);
    if noise > 0.0 {
        let diag = mesh.bbox_diagonal();
        let normals = vertex_normals(&mesh);
        let mut rng = crate::random::SplitMix::new(seed ^ 0xD1B5_4A32_D192_ED03);
        for (p, nrm) in mesh.vertices.iter_mut().zip(&normals) {
            let (a, b) = (rng.unit().max(1e-300), rng.unit());
            let g = (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos();
            for d in 0..3 {
                p[d] += noise * diag * g * nrm[d];
            }
        }
    }
    let rest_mesh = build(rest.clone(), mesh.triangles.clone());
    let mirror = mirror_map(&rest_mesh, 0);
    Creature { mesh, mirror, limb: limb_of, limbs, rest }
}

/// Where limb `l` leaves a body of radii `body`: the centre of its cap on the body.
fn limb_base(body: [f64; 3], l: &Limb) -> [f64; 3] {
    [body[0] * l.direction[0], body[1] * l.direction[1], body[2] * l.direction[2]]
}

/// A directed limb's frame across its axis: forward (`dir.forward` made perpendicular to the
/// axis) and lateral (axis × forward), the same for every limb with the same axis.
fn limb_frame(l: &Limb, dir: &Directed) -> ([f64; 3], [f64; 3]) {
    let f = dir.forward;
    let forward = normalize(std::array::from_fn(|d| f[d] - dot(f, l.axis) * l.axis[d]));
    (forward, normalize(cross(l.axis, forward)))
}

/// A directed limb's cross-section made round: the body point `p` of sphere point `u` at
/// `t` (its angle from the cap's centre over the cap's radius) is moved, below the limb's
/// upper part, onto a disc about the cap's centre whose axes are the same for every limb
/// (forward and lateral), so that identical directed limbs are translates of each other.
/// Without it a limb's cross-section is its cap scaled by the body's radii (an ellipse 2.8
/// times longer front to back than across on the directed quadruped's body): a blade whose
/// front↔back mirror fits it as well as the translation does (session 34).
fn round_limb(p: [f64; 3], u: [f64; 3], body: [f64; 3], l: &Limb, dir: &Directed, t: f64) -> [f64; 3] {
    let (forward, lateral) = limb_frame(l, dir);
    let centre = limb_base(body, l);
    let radial: [f64; 3] = std::array::from_fn(|d| u[d] - dot(u, l.direction) * l.direction[d]);
    let phi = dot(radial, forward).atan2(dot(radial, lateral));
    let radius = l.cap.sin() * body.iter().copied().fold(f64::INFINITY, f64::min);
    let round: [f64; 3] = std::array::from_fn(|d| centre[d] + radius * t * (phi.cos() * lateral[d] + phi.sin() * forward[d]));
    // Round below, the body's own surface at the cap's rim.
    let keep = smoothstep((t - 0.55) / 0.4);
    std::array::from_fn(|d| keep * p[d] + (1.0 - keep) * round[d])
}

/// The rest position `p` of a limb vertex (sphere point `u`, at height `h` ∈ [0, 1] of the
/// limb `l` grown from `base`) with the limb directed by `dir`: the toe, then the knee.
fn direct(mut p: [f64; 3], u: [f64; 3], base: [f64; 3], l: &Limb, dir: &Directed, h: f64) -> [f64; 3] {
    // Forward across the cap: the forward direction in the sphere's tangent plane at the
    // cap's centre, and how far forward `u` lies in the cap.
    let f = dir.forward;
    let along = dot(f, l.direction);
    let tangent = normalize(std::array::from_fn(|d| f[d] - along * l.direction[d]));
    // 1 on the front half of the cap beyond a third of its radius, fading to 0 at its centre.
    let w = (dot(u, tangent) / (l.cap / 3.0).sin()).clamp(-1.0, 1.0);
    let toe = dir.toe * l.length * smoothstep((h - 0.5) / 0.35) * w.max(0.0);
    let (f_perp, lateral) = limb_frame(l, dir);
    for d in 0..3 {
        p[d] += toe * f_perp[d];
    }
    // The knee: the lower half turns about the lateral axis through the limb's midpoint, the
    // foot swinging forward (blended over 0.4..0.6 of the height).
    let knee = std::array::from_fn(|d| base[d] + 0.5 * l.length * l.axis[d]);
    rotate(p, knee, lateral, -dir.knee * smoothstep((h - 0.4) / 0.2))
}

impl Creature {
    /// Ground truth of the partial symmetry "limb `i` → limb `j`" for limbs that are mirror
    /// images of each other across the planes x = 0 and/or z = 0 of the rest shape (the four legs
    /// of [`quadruped`]): for each vertex of limb `i`, the vertex of limb `j` nearest its image
    /// under the reflection(s) `R` that carry limb `i` onto limb `j` (`R = diag(±1, 1, ±1)`,
    /// read off the limbs' centroids), and the image under `R` composed with the limb's own
    /// mirror across the plane x = const through its centroid (a leg is mirror-symmetric, so
    /// either image is correct). For a left↔right pair these are the mirror and the
    /// translation of the limb; for front↔hind and diagonal pairs the reflection in z (and x)
    /// matters: a translation would map the front of a front leg to the front of a hind leg,
    /// which no intrinsic symmetry of the shape does.
    pub fn limb_truth(&self, i: usize, j: usize) -> Vec<(usize, Vec<usize>)> {
        let (vi, ci) = self.limb_vertices(i);
        let (vj, cj) = self.limb_vertices(j);
        let nearest = |q: [f64; 3]| *vj.iter().min_by(|&&a, &&b| dist2(self.rest[a], q).total_cmp(&dist2(self.rest[b], q))).expect("limb j has vertices");
        // The reflection(s) carrying limb i onto limb j: flip x and/or z where the centroids
        // lie on opposite sides.
        let (rx, rz) = (if ci[0] * cj[0] < 0.0 { -1.0 } else { 1.0 }, if ci[2] * cj[2] < 0.0 { -1.0 } else { 1.0 });
        vi.iter()
            .map(|&v| {
                let p = self.rest[v];
                let local = [p[0] - ci[0], p[1] - ci[1], p[2] - ci[2]];
                let image = |fx: f64| nearest([cj[0] + rx * fx * local[0], cj[1] + local[1], cj[2] + rz * local[2]]);
                (v, vec![image(1.0), image(-1.0)])
            })
            .collect()
    }

    /// Ground truth of the partial symmetry "limb `i` → limb `j`" for limbs that are
    /// translates of each other at rest (the directed legs of [`directed_quadruped`], the
    /// spikes of [`spiked`]): for each vertex of limb `i`, the vertex of limb `j` nearest its
    /// translate (by the difference of the limbs' centroids), and the one nearest its translate
    /// mirrored across the plane x = const through limb `j`'s centroid (the limb's own
    /// left–right mirror: either image is correct).
    pub fn translation_truth(&self, i: usize, j: usize) -> Vec<(usize, Vec<usize>)> {
        let (vi, ci) = self.limb_vertices(i);
        let (vj, cj) = self.limb_vertices(j);
        let nearest = |q: [f64; 3]| *vj.iter().min_by(|&&a, &&b| dist2(self.rest[a], q).total_cmp(&dist2(self.rest[b], q))).expect("limb j has vertices");
        vi.iter()
            .map(|&v| {
                let p = self.rest[v];
                let local = [p[0] - ci[0], p[1] - ci[1], p[2] - ci[2]];
                let image = |fx: f64| nearest([cj[0] + fx * local[0], cj[1] + local[1], cj[2] + local[2]]);
                (v, vec![image(1.0), image(-1.0)])
            })
            .collect()
    }

    /// The vertices of limb `l` and their centroid at rest.
    fn limb_vertices(&self, l: usize) -> (Vec<usize>, [f64; 3]) {
        let vs: Vec<usize> = (0..self.rest.len()).filter(|&v| self.limb[v] == l).collect();
        let mut c = [0.0; 3];
        for &v in &vs {
            for (x, r) in c.iter_mut().zip(self.rest[v]) {
                *x += r / vs.len() as f64;
            }
        }
        (vs, c)
    }
}

/// Area-weighted unit vertex normals over the mesh's own triangles ([`Mesh::vertex_normals`]).
pub fn vertex_normals(mesh: &Mesh) -> Vec<[f64; 3]> {
    mesh.vertex_normals(&mesh.triangles)
}

/// Pose of a [`quadruped`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pose {
    /// The symmetric rest pose.
    Rest,
    /// Legs swung asymmetrically, head turned, tail raised.
    Walking,
}

/// A four-legged animal (body along z, legs down, head at +z, tail at −z), mirror-symmetric
/// in x at rest. Limbs 0..4 are the legs (front-left, front-right, hind-left, hind-right),
/// 4 the head, 5 the tail. `level` 5 gives 10,242 vertices.
pub fn quadruped(level: u32, pose: Pose, noise: f64, seed: u64) -> Creature {
    let limbs = quadruped_limbs(pose, 0.55, [0.5, -0.3, -0.4, 0.35]);
    creature(level, [0.5, 0.45, 1.0], &limbs, noise, seed)
}

/// The six limbs of a quadruped: four legs (front-left, front-right, hind-left, hind-right)
/// growing straight down from caps at `±0.55` across and `±along` front to back on the unit
/// sphere, swung by `swings` when walking, then the head and the tail.
fn quadruped_limbs(pose: Pose, along: f64, swings: [f64; 4]) -> [Limb; 6] {
    let walking = pose == Pose::Walking;
    let x = [1.0, 0.0, 0.0];
    let leg = |sx: f64, sz: f64, bend: f64| Limb {
        direction: [0.55 * sx, -0.75, along * sz],
        axis: [0.0, -1.0, 0.0],
        length: 1.1,
        cap: 0.38,
        bend: if walking { bend } else { 0.0 },
        bend_axis: x,
    };
    [
        leg(1.0, 1.0, swings[0]),
        leg(-1.0, 1.0, swings[1]),
        leg(1.0, -1.0, swings[2]),
        leg(-1.0, -1.0, swings[3]),
        Limb { direction: [0.0, 0.45, 1.0], axis: [0.0, 0.35, 1.0], length: 0.6, cap: 0.5, bend: if walking { 0.6 } else { 0.0 }, bend_axis: [0.0, 1.0, 0.0] },
        Limb { direction: [0.0, 0.25, -1.0], axis: [0.0, 0.3, -1.0], length: 0.9, cap: 0.22, bend: if walking { -0.7 } else { 0.0 }, bend_axis: x },
    ]
}

/// A four-legged animal like [`quadruped`] whose four identical legs are *directed* (knee
/// bent, toe forward: [`Directed`]) and grow straight down from caps placed symmetrically front
/// and back, so the only global symmetry is the left–right mirror, and a front leg maps onto a
/// hind leg by a translation of the leg ([`Creature::translation_truth`]), a partial symmetry
/// no map of the whole body carries. Limbs 0..4 are the legs (front-left, front-right,
/// hind-left, hind-right), 4 the head, 5 the tail. `Pose::Walking` swings the legs as in
/// [`quadruped`]. `level` 4 gives 2,562 vertices, 5 gives 10,242.
pub fn directed_quadruped(level: u32, pose: Pose, noise: f64, seed: u64) -> Creature {
    // Legs nearer the middle (a longer body, below): the body around a leg's base is nearly
    // the same front and back.
    let limbs = quadruped_limbs(pose, 0.35, [0.4, -0.3, -0.35, 0.3]);
    let paw = Some(Directed { forward: [0.0, 0.0, 1.0], knee: 0.6, toe: 0.3 });
    creature_with(level, [0.5, 0.45, 1.4], &limbs, &[paw.clone(), paw.clone(), paw.clone(), paw], noise, seed)
}

/// A long body with three identical directed spikes in a row along its back (limbs 0, 1, 2,
/// front to back): each spike maps onto the others by a translation
/// ([`Creature::translation_truth`]), and the only global symmetry is the left–right mirror.
pub fn spiked(level: u32, noise: f64, seed: u64) -> Creature {
    let spike = |z: f64| Limb { direction: [0.0, 1.0, z], axis: [0.0, 1.0, 0.0], length: 0.8, cap: 0.3, bend: 0.0, bend_axis: [1.0, 0.0, 0.0] };
    let limbs = [spike(0.8), spike(0.0), spike(-0.8)];
    let tip = Some(Directed { forward: [0.0, 0.0, 1.0], knee: 0.5, toe: 0.3 });
    creature_with(level, [0.45, 0.4, 1.6], &limbs, &[tip.clone(), tip.clone(), tip], noise, seed)
}

/// The `4·arms − 1` non-trivial symmetries of [`star`] as vertex maps, named. The star is
/// symmetric under the dihedral group of its arms (mirrors in the vertical planes through the
/// y axis and arm j, rotations by `j·360°/arms` about the y axis) times the flip y → −y of its
/// flat body: the flip itself, the half-turns about each arm's axis (mirror j ∘ flip) and the
/// rotoreflections (rotation ∘ flip). The tessellation is exactly symmetric only under x → −x
/// (mirror 0), so each map sends a vertex to the vertex nearest its transformed position.
pub fn star_symmetries(c: &Creature, arms: usize) -> Vec<(String, Vec<u32>)> {
    let p = &c.rest;
    let nearest = |q: [f64; 3]| -> u32 {
        (0..p.len()).min_by(|&i, &j| dist2(p[i], q).total_cmp(&dist2(p[j], q))).unwrap_or(0) as u32
    };
    let mut out = Vec::new();
    for flip in [false, true] {
        let apply = |f: &dyn Fn([f64; 3]) -> [f64; 3]| {
            p.iter()
                .map(|&x| {
                    let y = f(x);
                    nearest(if flip { [y[0], -y[1], y[2]] } else { y })
                })
                .collect::<Vec<u32>>()
        };
        for j in 0..arms {
            let a = 2.0 * std::f64::consts::PI * j as f64 / arms as f64 + 0.5 * std::f64::consts::PI;
            let (dx, dz) = (a.cos(), a.sin());
            let reflect = |x: [f64; 3]| {
                let t = 2.0 * (x[0] * dx + x[2] * dz);
                [t * dx - x[0], x[1], t * dz - x[2]]
            };
            out.push((if flip { format!("half-turn about arm {j}") } else { format!("mirror {j}") }, apply(&reflect)));
        }
        for j in 0..arms {
            if j == 0 && !flip {
                continue; // the identity
            }
            let t = 2.0 * std::f64::consts::PI * j as f64 / arms as f64;
            let (c, s) = (t.cos(), t.sin());
            let rotate = |x: [f64; 3]| [c * x[0] + s * x[2], x[1], -s * x[0] + c * x[2]];
            let angle = 360 * j / arms;
            let name = match (flip, j) {
                (true, 0) => "horizontal mirror (y → −y)".to_string(),
                (true, _) => format!("rotoreflection {angle}°"),
                _ => format!("rotation {angle}°"),
            };
            out.push((name, apply(&rotate)));
        }
    }
    out
}

/// A flat star with `arms` equal arms in the xz-plane (n mirror planes and n−1 rotations).
pub fn star(arms: usize, level: u32) -> Creature {
    let limbs: Vec<Limb> = (0..arms)
        .map(|j| {
            let a = 2.0 * std::f64::consts::PI * j as f64 / arms as f64 + 0.5 * std::f64::consts::PI;
            let d = [a.cos(), 0.0, a.sin()];
            Limb { direction: d, axis: d, length: 1.2, cap: 0.45, bend: 0.0, bend_axis: [0.0, 1.0, 0.0] }
        })
        .collect();
    creature(level, [0.8, 0.35, 0.8], &limbs, 0.0, 0)
}

/// A creature with no symmetry: limbs of different lengths and thicknesses in directions no
/// map exchanges (a "shoe": its only congruent partner is a copy or a mirror image).
pub fn lopsided(level: u32) -> Creature {
    let limb = |direction: [f64; 3], length: f64, cap: f64| Limb { direction, axis: direction, length, cap, bend: 0.0, bend_axis: [1.0, 0.0, 0.0] };
    let limbs = [limb([0.8, -0.5, 0.3], 1.2, 0.35), limb([-0.3, -0.7, 0.65], 0.7, 0.3), limb([0.1, 0.9, -0.4], 0.45, 0.5), limb([-0.9, 0.1, -0.45], 0.9, 0.22)];
    creature(level, [0.45, 0.6, 1.0], &limbs, 0.0, 0)
}

/// Two meshes side by side along x as one mesh of two components: `b` placed `gap` bounding-box
/// widths of `a` to the right of `a`, mirrored in x when `mirrored` (a pair of shoes; its
/// triangles turned to keep the outward orientation). Vertex `v` of `a` is vertex `v` of the
/// result, vertex `v` of `b` is `a.num_vertices() + v`.
pub fn side_by_side(a: &Mesh, b: &Mesh, mirrored: bool, gap: f64) -> Mesh {
    let n = a.num_vertices() as u32;
    let (lo, hi) = crate::mesh::bounding_box(&a.vertices);
    let (blo, bhi) = crate::mesh::bounding_box(&b.vertices);
    // b's left edge at a's right edge plus the gap.
    let left = hi[0] + gap * (hi[0] - lo[0]);
    let mut vertices = a.vertices.clone();
    vertices.extend(b.vertices.iter().map(|&[x, y, z]| if mirrored { [left + (bhi[0] - x), y, z] } else { [left + (x - blo[0]), y, z] }));
    let mut triangles = a.triangles.clone();
    triangles.extend(b.triangles.iter().map(|&[p, q, r]| if mirrored { [p + n, r + n, q + n] } else { [p + n, q + n, r + n] }));
    Mesh::new(vertices, triangles, &MeshParams::default()).expect("generated meshes are valid")
}

/// Two copies of `mesh` ([`side_by_side`]) and the swap's ground truth: `truth[v]` is where
/// `v` is in the other copy.
pub fn pair(mesh: &Mesh, mirrored: bool, gap: f64) -> (Mesh, Vec<u32>) {
    let n = mesh.num_vertices() as u32;
    let truth = (0..2 * n).map(|v| if v < n { v + n } else { v - n }).collect();
    (side_by_side(mesh, mesh, mirrored, gap), truth)
}

/// Flat midpoint subdivision: every triangle split into four at its edge midpoints. The surface
/// is unchanged; vertex `v < n` stays vertex `v` (so a ground truth on the input vertices still
/// holds), and each edge adds one vertex (n + #edges vertices in all). Non-manifold edges
/// are split like the others (`params` decides whether the result is accepted).
pub fn subdivide(mesh: &Mesh, params: &MeshParams) -> Result<Mesh, crate::mesh::MeshError> {
    let mut vertices = mesh.vertices.clone();
    let mut midpoint = std::collections::HashMap::new();
    let mut mid = |a: u32, b: u32, vertices: &mut Vec<[f64; 3]>| -> u32 {
        *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (p, q) = (vertices[a as usize], vertices[b as usize]);
            vertices.push([(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, (p[2] + q[2]) / 2.0]);
            (vertices.len() - 1) as u32
        })
    };
    let mut triangles = Vec::with_capacity(4 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        let (ab, bc, ca) = (mid(a, b, &mut vertices), mid(b, c, &mut vertices), mid(c, a, &mut vertices));
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    Mesh::new(vertices, triangles, params)
}


#[cfg(test)]
mod tests {
    use super::*;

    /// The vertex of the rest shape nearest each vertex's reflection `diag(sx, 1, sz)`.
    fn reflection(c: &Creature, sx: f64, sz: f64) -> Vec<i64> {
        let p = &c.rest;
        (0..p.len())
            .map(|v| {
                let q = [sx * p[v][0], p[v][1], sz * p[v][2]];
                (0..p.len()).min_by(|&a, &b| dist2(p[a], q).total_cmp(&dist2(p[b], q))).unwrap() as i64
            })
            .collect()
    }

    /// The rest shape's reflections carry each leg onto the others, and the leg truth says so:
    /// x → −x maps leg 0 onto leg 1, z → −z onto leg 2 (front ↔ hind), both onto leg 3. (The
    /// first version of `limb_truth` translated a leg instead, which is right only for the
    /// left–right pairs: the z reflection scored 0.4 on front ↔ hind there.)
    #[test]
    fn leg_truth_follows_the_reflections_of_the_rest_shape() {
        let c = quadruped(3, Pose::Rest, 0.0, 0);
        for (j, sx, sz) in [(1, -1.0, 1.0), (2, 1.0, -1.0), (3, -1.0, -1.0)] {
            let map = reflection(&c, sx, sz);
            for (i, jj) in [(0, j), (j, 0)] {
                let truth = c.limb_truth(i, jj);
                let exact = truth.iter().filter(|(v, img)| img.contains(&(map[*v] as usize))).count();
                assert!(exact as f64 >= 0.97 * truth.len() as f64, "leg {i} -> {jj}: {exact} of {}", truth.len());
            }
        }
        // A leg mapped onto the wrong leg is wrong.
        let x = reflection(&c, -1.0, 1.0);
        let truth = c.limb_truth(0, 2);
        assert_eq!(truth.iter().filter(|(v, img)| img.contains(&(x[*v] as usize))).count(), 0);
    }

    /// Subdivision keeps the surface and the input vertices, and adds one vertex per edge.
    #[test]
    fn subdivision_keeps_surface_and_vertices() {
        let c = quadruped(3, Pose::Walking, 0.0, 0);
        let m = &c.mesh;
        let s = subdivide(m, &MeshParams::default()).unwrap();
        let edges = 3 * m.num_triangles() / 2; // closed surface
        assert_eq!(s.num_vertices(), m.num_vertices() + edges);
        assert_eq!(s.num_triangles(), 4 * m.num_triangles());
        assert_eq!(&s.vertices[..m.num_vertices()], &m.vertices[..]);
        assert!((s.area() - m.area()).abs() < 1e-9 * m.area());
    }
}
