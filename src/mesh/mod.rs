//! Triangle meshes: validation, clean-up decisions and file input.
//!
//! A [`Mesh`] is built from row-major arrays, `vertices` (n × 3, `f64`) and `triangles`
//! (m × 3, `u32`), the layout of the C API and of every mesh file. Building it validates the
//! input; what is checked, and what is decided for each problem, is the contract every front
//! end (Rust, C, MeshLab, CLI) inherits:
//!
//! | input problem | decision |
//! |---|---|
//! | array length not a multiple of 3 | error [`MeshError::BadLength`] |
//! | no vertex or no triangle | error [`MeshError::Empty`] |
//! | NaN or ±inf coordinate | error [`MeshError::NonFinite`] |
//! | index ≥ number of vertices | error [`MeshError::IndexOutOfRange`] |
//! | the same vertex twice in one triangle | error [`MeshError::RepeatedIndex`] |
//! | an edge shared by more than two triangles | **accepted** and counted in [`MeshInfo::non_manifold_edges`] (the Laplacian is that of the tufted cover, below); error [`MeshError::NonManifoldEdge`] when [`MeshParams::allow_non_manifold`] is off |
//! | coincident vertices (an STL-style triangle soup, a seam split by duplicated vertices) | **welded** ([`MeshParams::weld`], tolerance [`WELD_REL`] of the bounding-box diagonal), counted in [`MeshInfo::welded_vertices`]; results give a welded vertex the map of the vertex it joined |
//! | zero-area (collinear or collapsed) triangles | **kept** and counted in [`MeshInfo::degenerate_triangles`]: the Laplacian is built on intrinsically mollified edge lengths (Sharp & Crane 2020), so they get a tiny positive area and finite cotangents; dropping them would punch holes |
//! | the same triangle twice (the same three vertices, in either orientation: a double-sided export, a duplicated face) | **dropped** but for the first, counted in [`MeshInfo::duplicate_triangles`]: a repeated face is a second sheet to the Laplacian |
//! | every triangle degenerate (zero total area) | error [`MeshError::Degenerate`] |
//! | vertices used by no triangle | **ignored**, wherever they lie (not part of the computation, nor of the scale, the welding tolerance or the outlier test; results mark them "no image", confidence 0), counted in [`MeshInfo::isolated_vertices`] |
//! | several connected components | by default **every component of at least [`MIN_COMPONENT_SHARE`] of the largest one's area** is kept ([`ComponentPolicy::Each`]; smaller ones are reported as ignored vertices); detection processes each kept component on its own ([`Mesh::split_components`]) and maps congruent components onto each other (`crate::maps::congruent`). [`ComponentPolicy::Largest`] keeps the largest only; [`ComponentPolicy::Reject`] makes it error [`MeshError::Disconnected`]. Intrinsic symmetry is defined per connected surface: the spectrum of a disconnected surface mixes the components' spectra, so no eigenbasis is ever computed on several components at once |
//!
//! Polygon faces in files are fan-triangulated by the readers in [`io`]; vertex indices in
//! every result are those of the input arrays ([`Mesh::input_index`] maps back).

pub mod holes;
pub mod io;
pub(crate) mod vec3;

pub use io::{read_mesh, write_off, IoError, RawMesh};

use std::fmt;

use vec3::{cross, dot, norm, sub};

/// What to do with a mesh that has several connected components.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum ComponentPolicy {
    /// Keep every component of at least [`MIN_COMPONENT_SHARE`] of the largest one's area;
    /// ignore smaller ones (scanning debris, loose fragments).
    #[default]
    Each,
    /// Keep the component with the largest surface area; ignore the others.
    Largest,
    /// Refuse the mesh with [`MeshError::Disconnected`].
    Reject,
}

/// Parameters of mesh validation.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct MeshParams {
    /// Several connected components: keep each of meaningful size (default), the largest, or
    /// reject the mesh.
    pub components: ComponentPolicy,
    /// Accept edges shared by more than two triangles (default: accept; issue 16, item 2). The
    /// Laplacian is assembled triangle by triangle from intrinsic edge lengths, each triangle
    /// adding its own positive semi-definite cotangent element matrix: that is the cotangent
    /// Laplacian of the *tufted cover* of Sharp & Crane 2020 ("A Laplacian for nonmanifold
    /// triangle meshes"), where every triangle keeps its own copy of a non-manifold edge (we do
    /// not perform their intrinsic Delaunay flips, which would also make every weight
    /// positive). Scans with self-contacts glued into non-manifold edges, like SHREC'16's kids,
    /// are processed (a kid00 that MeshLab had to repair first now runs as it is); the count
    /// is reported in [`MeshInfo::non_manifold_edges`].
    pub allow_non_manifold: bool,
    /// Weld coincident vertices (default: yes): boundary vertices closer than [`WELD_REL`] times
    /// the bounding-box diagonal are one vertex, as in a mesh exported from STL (every triangle
    /// with its own three vertices) or split along a seam. Vertices inside closed sheets are
    /// never welded: coincident there is a self-contact, not a seam. Counted in
    /// [`MeshInfo::welded_vertices`]; results give a welded vertex the map of the vertex it
    /// was welded to.
    pub weld: bool,
}

impl Default for MeshParams {
    fn default() -> Self {
        MeshParams { components: ComponentPolicy::default(), allow_non_manifold: true, weld: true }
    }
}

/// Welding tolerance relative to the bounding-box diagonal: far below any mesh's edge length
/// (a 10⁶-vertex scan's edges are about 10⁻³ of its diagonal), far above float32 rounding of
/// a written coordinate (about 10⁻⁷ of the coordinates' magnitude is the largest error).
pub const WELD_REL: f64 = 1e-6;

/// [`ComponentPolicy::Each`] keeps the components of at least this fraction of the largest
/// component's area. A component of 1% of the area has eigenvalues about 100 times the main
/// surface's (λ scales as 1/area): its first eigenpairs lie beyond the main surface's 100, so
/// its descriptors and maps would rest on a handful of modes; such parts are debris of a scan
/// or loose fragments far more often than a part whose symmetry a user wants.
pub const MIN_COMPONENT_SHARE: f64 = 0.01;

/// Facts found while validating a mesh (warnings, not errors).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct MeshInfo {
    /// Number of vertices in the input arrays.
    pub input_vertices: usize,
    /// Number of triangles in the input arrays.
    pub input_triangles: usize,
    /// Triangles with (numerically) zero area that were kept.
    pub degenerate_triangles: usize,
    /// Input vertices referenced by no triangle (ignored).
    pub isolated_vertices: usize,
    /// Number of connected components in the input.
    pub components: usize,
    /// Components kept for processing ([`ComponentPolicy`]).
    pub kept_components: usize,
    /// Vertices of the components that were not processed (ignored).
    pub ignored_component_vertices: usize,
    /// Edges shared by more than two triangles (accepted unless `allow_non_manifold` is off).
    pub non_manifold_edges: usize,
    /// Vertices welded to a coincident one ([`MeshParams::weld`]).
    pub welded_vertices: usize,
    /// Triangles that welding collapsed (two corners became one vertex): dropped.
    pub collapsed_triangles: usize,
    /// Triangles with the same three vertices as an earlier one (in any order, so either
    /// orientation; in the input or after welding): dropped, the earlier one kept.
    pub duplicate_triangles: usize,
    /// Holes (boundary loops from `Params::min_hole` to `Params::max_hole` times √area long)
    /// capped for the detection ([`holes`]); filled in by detection, 0 from validation.
    pub closed_holes: usize,
    /// Vertices of those caps (not reported: an image in a cap is reported on the rim).
    pub cap_vertices: usize,
}

/// Why a mesh was refused.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// An array's length is not a multiple of 3.
    BadLength {
        /// "vertices" or "triangles".
        array: &'static str,
        /// The length given.
        len: usize,
    },
    /// No vertex or no triangle.
    Empty,
    /// More vertices than `u32` indices can address.
    TooLarge {
        /// Number of vertices given.
        vertices: usize,
    },
    /// A coordinate is NaN or infinite.
    NonFinite {
        /// Input index of the vertex.
        vertex: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// Input index of the triangle.
        triangle: usize,
        /// The offending index.
        index: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// A triangle uses the same vertex twice.
    RepeatedIndex {
        /// Input index of the triangle.
        triangle: usize,
    },
    /// An edge is shared by more than two triangles.
    NonManifoldEdge {
        /// First endpoint (input index).
        a: u32,
        /// Second endpoint (input index).
        b: u32,
        /// Number of triangles sharing the edge.
        triangles: usize,
    },
    /// The surface has zero total area.
    Degenerate,
    /// One vertex lies so far from the others that, at its scale, every triangle is a point
    /// (a stray coordinate such as 1e308 in an otherwise ordinary mesh).
    Outlier {
        /// Input index of the farthest vertex.
        vertex: usize,
        /// Its largest coordinate magnitude.
        magnitude: f64,
        /// The median vertex's largest coordinate magnitude.
        typical: f64,
    },
    /// Several connected components and [`ComponentPolicy::Reject`].
    Disconnected {
        /// Number of components.
        components: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::BadLength { array, len } => {
                write!(f, "{array} array has length {len}, not a multiple of 3")
            }
            MeshError::Empty => write!(f, "mesh has no vertices or no triangles"),
            MeshError::TooLarge { vertices } => {
                write!(f, "{vertices} vertices exceed the 32-bit index range")
            }
            MeshError::NonFinite { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite coordinate")
            }
            MeshError::IndexOutOfRange { triangle, index, vertices } => write!(
                f,
                "triangle {triangle} refers to vertex {index}, but there are only {vertices} vertices"
            ),
            MeshError::RepeatedIndex { triangle } => {
                write!(f, "triangle {triangle} uses the same vertex twice")
            }
            MeshError::NonManifoldEdge { a, b, triangles } => write!(
                f,
                "edge ({a}, {b}) is shared by {triangles} triangles (non-manifold; at most 2 allowed)"
            ),
            MeshError::Degenerate => write!(f, "all triangles have zero area"),
            MeshError::Outlier { vertex, magnitude, typical } => write!(
                f,
                "vertex {vertex} has a coordinate of magnitude {magnitude:e}, while a typical vertex's is {typical:e}: at that scale every triangle has zero area; remove or fix the stray vertex"
            ),
            MeshError::Disconnected { components } => write!(
                f,
                "mesh has {components} connected components (process each with ComponentPolicy::Each, or the largest with ComponentPolicy::Largest)"
            ),
        }
    }
}

impl std::error::Error for MeshError {}

/// A validated triangle mesh with finite coordinates: one connected surface, or several
/// ([`ComponentPolicy::Each`]; [`Mesh::split_components`] splits them).
#[derive(Clone, Debug)]
pub struct Mesh {
    /// `(n, 3)` positions of the processed vertices.
    pub vertices: Vec<[f64; 3]>,
    /// `(m, 3)` triangles indexing [`Mesh::vertices`].
    pub triangles: Vec<[u32; 3]>,
    /// `(n,)` input index of each processed vertex.
    pub input_index: Vec<u32>,
    /// Input vertices welded to another, as `(vertex, the input vertex it was welded to)`
    /// ([`MeshParams::weld`]).
    pub welded: Vec<(u32, u32)>,
    /// What validation found.
    pub info: MeshInfo,
}

/// Relative area below which a triangle counts as degenerate: `|e1 × e2| ≤ DEGENERATE_REL · (longest edge)²`.
const DEGENERATE_REL: f64 = 1e-12;

impl Mesh {
    /// Validates row-major arrays: `vertices` (3n values), `triangles` (3m indices).
    pub fn from_slices(vertices: &[f64], triangles: &[u32], params: &MeshParams) -> Result<Mesh, MeshError> {
        if vertices.len() % 3 != 0 {
            return Err(MeshError::BadLength { array: "vertices", len: vertices.len() });
        }
        if triangles.len() % 3 != 0 {
            return Err(MeshError::BadLength { array: "triangles", len: triangles.len() });
        }
        let v: Vec<[f64; 3]> = vertices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let t: Vec<[u32; 3]> = triangles.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        Mesh::new(v, t, params)
    }

    /// Validates a mesh given as vertex and triangle lists.
    // `!(x > y)` on purpose: also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    pub fn new(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>, params: &MeshParams) -> Result<Mesh, MeshError> {
        let n = vertices.len();
        let m = triangles.len();
        if n == 0 || m == 0 {
            return Err(MeshError::Empty);
        }
        if n > u32::MAX as usize {
            return Err(MeshError::TooLarge { vertices: n });
        }
        if let Some(i) = vertices.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
            return Err(MeshError::NonFinite { vertex: i });
        }
        for (ti, t) in triangles.iter().enumerate() {
            for &i in t {
                if i as usize >= n {
                    return Err(MeshError::IndexOutOfRange { triangle: ti, index: i, vertices: n });
                }
            }
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return Err(MeshError::RepeatedIndex { triangle: ti });
            }
        }
        // Vertices used by no triangle are ignored (module docs), so they set neither the
        // scale, nor the welding tolerance, nor the outlier test: one stray point far away
        // made the welding tolerance so large that it welded an open mesh's boundary together,
        // one at another scale made every triangle degenerate (session 31).
        let referenced = referenced_vertices(n, &triangles);
        // Areas, degeneracy and welding are measured on the coordinates divided by their
        // largest magnitude: a triangle's squared-area arithmetic goes to the fourth power of
        // the coordinates, which overflows from 1e77 and underflows below 1e-77 (issue 16,
        // item 1).
        let (unit, unit_vertices) = unit_scaled(&vertices, &referenced);
        // The sorted edge keys serve welding (boundary edges) and the manifold check.
        let keys = sorted_edge_keys(&triangles);
        let (triangles, welded, collapsed_triangles) = if params.weld { weld(&unit_vertices, &referenced, triangles, &keys) } else { (triangles, Vec::new(), 0) };
        if triangles.is_empty() {
            return Err(outlier(&vertices, &referenced).unwrap_or(MeshError::Degenerate));
        }
        let (triangles, duplicate_triangles) = without_duplicates(triangles);
        let (input_triangles, m) = (m, triangles.len());
        let keys = if welded.is_empty() && duplicate_triangles == 0 { keys } else { sorted_edge_keys(&triangles) };
        let non_manifold_edges = match check_edge_manifold(&keys) {
            Ok(()) => 0,
            Err(e) if !params.allow_non_manifold => return Err(e),
            Err(_) => count_non_manifold_edges(&keys),
        };

        if unit == 0.0 {
            return Err(MeshError::Degenerate);
        }
        let areas: Vec<f64> = triangles.iter().map(|t| triangle_area(&unit_vertices, t)).collect();
        let degenerate = triangles
            .iter()
            .zip(&areas)
            .filter(|(t, &a)| 2.0 * a <= DEGENERATE_REL * longest_edge_sq(&unit_vertices, t))
            .count();
        let total_area: f64 = areas.iter().sum();
        if !(total_area > 0.0) || degenerate == m {
            return Err(outlier(&vertices, &referenced).unwrap_or(MeshError::Degenerate));
        }

        // Connected components of the triangles (through shared vertices).
        let mut uf = UnionFind::new(n);
        for t in &triangles {
            uf.union(t[0] as usize, t[1] as usize);
            uf.union(t[0] as usize, t[2] as usize);
        }
        // Welding may have left some vertices unused (dropping repeated triangles leaves
        // every vertex its first triangle).
        let used = if welded.is_empty() { referenced } else { referenced_vertices(n, &triangles) };
        let isolated = used.iter().filter(|&&u| !u).count() - welded.len();
        let mut comp_area = std::collections::HashMap::new();
        for (t, a) in triangles.iter().zip(&areas) {
            *comp_area.entry(uf.find(t[0] as usize)).or_insert(0.0) += a;
        }
        let components = comp_area.len();
        if components > 1 && params.components == ComponentPolicy::Reject {
            return Err(MeshError::Disconnected { components });
        }
        // Largest component by area; ties broken by the smallest root for determinism.
        let keep_root = comp_area
            .iter()
            .map(|(&r, &a)| (r, a))
            .max_by(|x, y| x.1.total_cmp(&y.1).then(y.0.cmp(&x.0)))
            .map(|(r, _)| r)
            .expect("at least one triangle");
        let largest = comp_area[&keep_root];
        let root: Vec<usize> = (0..n).map(|i| uf.find(i)).collect();
        let kept = |r: usize| match params.components {
            ComponentPolicy::Each => comp_area.get(&r).is_some_and(|&a| a >= MIN_COMPONENT_SHARE * largest),
            _ => r == keep_root,
        };
        let kept_components = comp_area.keys().filter(|&&r| kept(r)).count();

        let mut new_index = vec![u32::MAX; n];
        let mut input_index = Vec::new();
        let mut kept_vertices = Vec::new();
        for i in 0..n {
            if used[i] && kept(root[i]) {
                new_index[i] = input_index.len() as u32;
                input_index.push(i as u32);
                kept_vertices.push(vertices[i]);
            }
        }
        let mut kept_triangles = Vec::with_capacity(m);
        let mut kept_degenerate = 0;
        for (t, a) in triangles.iter().zip(&areas) {
            if kept(root[t[0] as usize]) {
                kept_triangles.push([new_index[t[0] as usize], new_index[t[1] as usize], new_index[t[2] as usize]]);
                if 2.0 * a <= DEGENERATE_REL * longest_edge_sq(&unit_vertices, t) {
                    kept_degenerate += 1;
                }
            }
        }
        // A vertex welded into an ignored component is ignored with it.
        let welded: Vec<(u32, u32)> = welded.into_iter().filter(|&(_, r)| new_index[r as usize] != u32::MAX).collect();
        let ignored_component_vertices = n - isolated - input_index.len() - welded.len();
        Ok(Mesh {
            vertices: kept_vertices,
            triangles: kept_triangles,
            input_index,
            welded: welded.clone(),
            info: MeshInfo {
                input_vertices: n,
                input_triangles,
                degenerate_triangles: kept_degenerate,
                isolated_vertices: isolated,
                components,
                kept_components,
                ignored_component_vertices,
                non_manifold_edges,
                welded_vertices: welded.len(),
                collapsed_triangles,
                duplicate_triangles,
                closed_holes: 0,
                cap_vertices: 0,
            },
        })
    }

    /// Number of processed vertices.
    pub fn num_vertices(&self) -> usize {
        self.vertices.len()
    }

    /// Number of processed triangles.
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// The connected components of this mesh as meshes of their own, largest area first (ties
    /// by their first vertex), each with [`Mesh::input_index`] and [`Mesh::welded`] still in the
    /// indices of the input arrays and this mesh's [`MeshInfo`]; `None` when the mesh is one
    /// connected surface (nothing to split, and no copy made).
    pub fn split_components(&self) -> Option<Vec<Mesh>> {
        let n = self.num_vertices();
        let mut uf = UnionFind::new(n);
        for t in &self.triangles {
            uf.union(t[0] as usize, t[1] as usize);
            uf.union(t[0] as usize, t[2] as usize);
        }
        let root: Vec<usize> = (0..n).map(|v| uf.find(v)).collect();
        // Roots in order of first vertex; the area of each.
        let mut label = vec![usize::MAX; n];
        let mut roots = Vec::new();
        for v in 0..n {
            if label[root[v]] == usize::MAX {
                label[root[v]] = roots.len();
                roots.push(root[v]);
            }
        }
        if roots.len() <= 1 {
            return None;
        }
        let mut area = vec![0.0; roots.len()];
        for t in &self.triangles {
            area[label[root[t[0] as usize]]] += triangle_area(&self.vertices, t);
        }
        let mut order: Vec<usize> = (0..roots.len()).collect();
        order.sort_by(|&a, &b| area[b].total_cmp(&area[a]).then(a.cmp(&b)));
        // Where each input vertex went: (component, index in it).
        let mut local = vec![(usize::MAX, u32::MAX); n];
        let mut parts: Vec<Mesh> = order
            .iter()
            .map(|_| Mesh { vertices: Vec::new(), triangles: Vec::new(), input_index: Vec::new(), welded: Vec::new(), info: self.info.clone() })
            .collect();
        let rank: Vec<usize> = {
            let mut r = vec![0; order.len()];
            for (i, &c) in order.iter().enumerate() {
                r[c] = i;
            }
            r
        };
        for v in 0..n {
            let c = rank[label[root[v]]];
            let part = &mut parts[c];
            local[v] = (c, part.vertices.len() as u32);
            part.vertices.push(self.vertices[v]);
            part.input_index.push(self.input_index[v]);
        }
        for t in &self.triangles {
            let c = local[t[0] as usize].0;
            parts[c].triangles.push(t.map(|v| local[v as usize].1));
        }
        let component_of_input: std::collections::HashMap<u32, usize> = (0..n).map(|v| (self.input_index[v], local[v].0)).collect();
        for &(v, kept) in &self.welded {
            if let Some(&c) = component_of_input.get(&kept) {
                parts[c].welded.push((v, kept));
            }
        }
        Some(parts)
    }

    /// This mesh centred on its bounding box's centre and scaled to unit area, and the scale
    /// `s` (input coordinates = `s` · these + centre). Intrinsic symmetry does not depend on
    /// position or units, but floating point does: the pipeline works on this copy, so that a
    /// mesh in millimetres, in kilometres or far from the origin gives the same result (issue
    /// 16, item 1). Computed without overflow for any finite coordinates.
    pub fn normalized(&self) -> (Mesh, f64) {
        // Every vertex of a built mesh is used by a triangle.
        let (unit, mut q) = unit_scaled(&self.vertices, &vec![true; self.vertices.len()]);
        let unit = if unit > 0.0 { unit } else { 1.0 };
        let (lo, hi) = bounding_box(&q);
        let centre = [0, 1, 2].map(|d| 0.5 * (lo[d] + hi[d]));
        for p in &mut q {
            *p = sub(*p, centre);
        }
        let area: f64 = self.triangles.iter().map(|t| triangle_area(&q, t)).sum();
        let s = if area > 0.0 { area.sqrt() } else { 1.0 };
        for p in &mut q {
            *p = p.map(|x| x / s);
        }
        let mesh = Mesh { vertices: q, triangles: self.triangles.clone(), input_index: self.input_index.clone(), welded: self.welded.clone(), info: self.info.clone() };
        (mesh, unit * s)
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        self.triangles.iter().map(|t| triangle_area(&self.vertices, t)).sum()
    }

    /// Vertex adjacency in CSR form: neighbours of `v` are `nbr[off[v]..off[v + 1]]`, sorted.
    ///
    /// Built by a counting sort on the first vertex of each half-edge, then each vertex's short
    /// list sorted and deduplicated: the same table as sorting all `6·F` directed edges, in
    /// linear time (on 10⁶ vertices the global sort took about a third of a second).
    pub fn adjacency(&self) -> (Vec<usize>, Vec<u32>) {
        let n = self.num_vertices();
        // Each triangle gives each of its vertices two neighbours (with repeats across faces).
        let start = bucket_offsets(n, self.triangles.iter().flatten().flat_map(|&a| [a as usize; 2]));
        let mut fill = start.clone();
        let mut all = vec![0u32; start[n]];
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3]);
                let c = t[(k + 2) % 3];
                all[fill[a]] = b;
                all[fill[a] + 1] = c;
                fill[a] += 2;
            }
        }
        // Sorted and deduplicated per vertex, compacted in place.
        let mut off = vec![0usize; n + 1];
        let mut len = 0;
        for v in 0..n {
            let (lo, hi) = (start[v], start[v + 1]);
            all[lo..hi].sort_unstable();
            let mut last = None;
            for i in lo..hi {
                let w = all[i];
                if last != Some(w) {
                    all[len] = w;
                    len += 1;
                    last = Some(w);
                }
            }
            off[v + 1] = len;
        }
        all.truncate(len);
        (off, all)
    }

    /// The triangles with a consistent orientation: each connected patch takes the
    /// orientation of its first triangle, propagated across shared edges (two triangles agree
    /// when they traverse their shared edge in opposite directions). A user's mesh may mix
    /// orientations; the Laplacian does not care, but the judge's normals and the orientation
    /// operators do ([`crate::judge`], [`crate::maps::orientation`]). Across a non-manifold edge
    /// the first neighbour found decides.
    pub fn oriented_triangles(&self) -> Vec<[u32; 3]> {
        if self.consistently_oriented() {
            return self.triangles.clone();
        }
        let m = self.triangles.len();
        // (undirected edge key, triangle), sorted: an edge's triangles in index order.
        let mut by_edge: Vec<(u64, u32)> = Vec::with_capacity(3 * m);
        for (f, t) in self.triangles.iter().enumerate() {
            for k in 0..3 {
                by_edge.push((edge_key(t[k], t[(k + 1) % 3]), f as u32));
            }
        }
        by_edge.sort_unstable();
        let on_edge = |key: u64| {
            let start = by_edge.partition_point(|e| e.0 < key);
            by_edge[start..].iter().take_while(move |e| e.0 == key).map(|e| e.1 as usize)
        };
        let directed = |t: &[u32; 3], a: u32, b: u32| (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b);
        let mut out = self.triangles.clone();
        let mut done = vec![false; m];
        let mut queue = std::collections::VecDeque::new();
        for root in 0..m {
            if done[root] {
                continue;
            }
            done[root] = true;
            queue.push_back(root);
            while let Some(f) = queue.pop_front() {
                let t = out[f];
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    for g in on_edge(edge_key(a, b)) {
                        if done[g] {
                            continue;
                        }
                        done[g] = true;
                        // Agreeing neighbours traverse the edge b → a.
                        if directed(&out[g], a, b) {
                            out[g].swap(1, 2);
                        }
                        queue.push_back(g);
                    }
                }
            }
        }
        out
    }

    /// Whether no directed edge `a → b` is traversed by two triangles: then neighbours across
    /// every edge already agree and [`Mesh::oriented_triangles`] would flip none (the usual
    /// case, checked in linear time: on 10⁶ vertices the propagation took seconds).
    fn consistently_oriented(&self) -> bool {
        let n = self.vertices.len();
        let off = bucket_offsets(n, self.triangles.iter().flatten().map(|&a| a as usize));
        let mut fill = off.clone();
        let mut heads = vec![0u32; off[n]];
        for t in &self.triangles {
            for k in 0..3 {
                let a = t[k] as usize;
                heads[fill[a]] = t[(k + 1) % 3];
                fill[a] += 1;
            }
        }
        (0..n).all(|v| {
            let out = &mut heads[off[v]..off[v + 1]];
            out.sort_unstable();
            out.windows(2).all(|w| w[0] != w[1])
        })
    }

    /// Area-weighted unit vertex normals over `triangles` (the mesh's own, or
    /// [`Mesh::oriented_triangles`]); zero for a vertex whose faces are all degenerate.
    pub fn vertex_normals(&self, triangles: &[[u32; 3]]) -> Vec<[f64; 3]> {
        let mut normals = vec![[0.0f64; 3]; self.num_vertices()];
        for t in triangles {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            let (e1, e2) = (sub(b, a), sub(c, a));
            let cr = cross(e1, e2);
            for &i in t {
                for d in 0..3 {
                    normals[i as usize][d] += cr[d];
                }
            }
        }
        for v in &mut normals {
            let r = norm_sq(*v).sqrt();
            if r > 0.0 {
                *v = v.map(|x| x / r);
            }
        }
        normals
    }

    /// Length of the bounding-box diagonal.
    pub fn bbox_diagonal(&self) -> f64 {
        let (lo, hi) = bounding_box(&self.vertices);
        norm_sq(sub(hi, lo)).sqrt()
    }
}

/// Which of `n` vertices some triangle uses.
fn referenced_vertices(n: usize, triangles: &[[u32; 3]]) -> Vec<bool> {
    let mut used = vec![false; n];
    for t in triangles {
        for &i in t {
            used[i as usize] = true;
        }
    }
    used
}

/// The points divided by the largest coordinate magnitude of the `referenced` ones (so every
/// coordinate of those is in [−1, 1]) and that magnitude; the other points (ignored by
/// everything) are put at the origin. 0 and the points unchanged when every referenced
/// coordinate is 0.
fn unit_scaled(points: &[[f64; 3]], referenced: &[bool]) -> (f64, Vec<[f64; 3]>) {
    let unit = points.iter().zip(referenced).filter(|(_, &r)| r).flat_map(|(p, _)| p.iter()).fold(0.0f64, |m, x| m.max(x.abs()));
    if unit == 0.0 {
        return (0.0, points.to_vec());
    }
    (unit, points.iter().zip(referenced).map(|(p, &r)| if r { p.map(|x| x / unit) } else { [0.0; 3] }).collect())
}

/// The corners `(lo, hi)` of the axis-aligned bounding box of `points`.
pub(crate) fn bounding_box(points: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    (lo, hi)
}

/// Welds the boundary vertices of `q` (the coordinates scaled by [`unit_scaled`]) closer than
/// [`WELD_REL`] times the bounding-box diagonal (a hash grid of that cell size; each vertex
/// joins the first earlier one within reach); `keys` are the triangles' sorted edge keys
/// ([`sorted_edge_keys`]), which tell the boundary. Returns the triangles on the kept vertices
/// without those that collapsed, the `(welded, kept)` pairs and the number of collapsed
/// triangles.
fn weld(q: &[[f64; 3]], referenced: &[bool], triangles: Vec<[u32; 3]>, keys: &[u64]) -> (Vec<[u32; 3]>, Vec<(u32, u32)>, usize) {
    // Only vertices on a boundary edge (an edge of one triangle) are welded: a seam's or a
    // triangle soup's copies lie on boundaries, while two coincident vertices inside closed
    // sheets are a self-contact (FAUST has a few), and gluing them would pinch the surface into
    // non-manifold edges (measured: FAUST tr_reg_004's first symmetry 31% -> 7%).
    let mut on_boundary = vec![false; q.len()];
    for run in keys.chunk_by(|a, b| a == b) {
        if run.len() == 1 {
            on_boundary[(run[0] >> 32) as usize] = true;
            on_boundary[(run[0] & 0xFFFF_FFFF) as usize] = true;
        }
    }
    if !on_boundary.iter().any(|&b| b) {
        return (triangles, Vec::new(), 0);
    }
    let (lo, hi) = bounding_box(&q.iter().zip(referenced).filter(|(_, &r)| r).map(|(p, _)| *p).collect::<Vec<_>>());
    let diagonal = norm_sq(sub(hi, lo)).sqrt();
    let tol = WELD_REL * diagonal;
    if tol <= 0.0 {
        return (triangles, Vec::new(), 0);
    }
    let cell = |p: &[f64; 3]| [0, 1, 2].map(|d| ((p[d] - lo[d]) / tol).floor() as i64);
    // Each cell holds a chain of vertices: the first in `head`, the rest through `next`.
    let mut head: std::collections::HashMap<[i64; 3], u32, CellHash> = std::collections::HashMap::with_capacity_and_hasher(q.len(), CellHash);
    let mut next: Vec<u32> = vec![u32::MAX; q.len()];
    let mut keep: Vec<u32> = (0..q.len() as u32).collect();
    let mut welded = Vec::new();
    for (i, p) in q.iter().enumerate() {
        if !on_boundary[i] {
            continue;
        }
        let c = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let mut j = head.get(&[c[0] + dx, c[1] + dy, c[2] + dz]).copied().unwrap_or(u32::MAX);
                    while j != u32::MAX {
                        if norm_sq(sub(q[j as usize], *p)) <= tol * tol {
                            found = Some(j);
                            break 'search;
                        }
                        j = next[j as usize];
                    }
                }
            }
        }
        match found {
            Some(j) => {
                keep[i] = j;
                welded.push((i as u32, j));
            }
            None => {
                let slot = head.entry(c).or_insert(u32::MAX);
                next[i] = *slot;
                *slot = i as u32;
            }
        }
    }
    if welded.is_empty() {
        return (triangles, welded, 0);
    }
    let before = triangles.len();
    let triangles: Vec<[u32; 3]> = triangles.into_iter().map(|t| t.map(|v| keep[v as usize])).filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).collect();
    let collapsed = before - triangles.len();
    (triangles, welded, collapsed)
}

/// A fast hasher for grid cells (the multiply–rotate of rustc's FxHash): the standard SipHash
/// made welding a 60k-vertex mesh cost 0.1 s, most of validation; cell keys are not
/// attacker-chosen in a way that matters (a collision costs time, never a wrong weld).
#[derive(Clone, Copy, Default)]
struct CellHash;

#[derive(Default)]
struct CellHasher(u64);

impl std::hash::BuildHasher for CellHash {
    type Hasher = CellHasher;
    fn build_hasher(&self) -> CellHasher {
        CellHasher(0)
    }
}

impl std::hash::Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_i64(&mut self, x: i64) {
        self.write_u64(x as u64);
    }
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

/// The stray vertex of a mesh, among the `referenced` ones, whose largest coordinate is more
/// than 10¹² times the median referenced vertex's (issue 16, item 14), if any.
fn outlier(vertices: &[[f64; 3]], referenced: &[bool]) -> Option<MeshError> {
    let magnitude = |p: &[f64; 3]| p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let used: Vec<usize> = (0..vertices.len()).filter(|&v| referenced[v]).collect();
    let mut sizes: Vec<f64> = used.iter().map(|&v| magnitude(&vertices[v])).collect();
    let (at, &largest) = sizes.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1))?;
    let vertex = used[at];
    let middle = sizes.len() / 2;
    let typical = *sizes.select_nth_unstable_by(middle, f64::total_cmp).1;
    (largest > 1e12 * typical).then_some(MeshError::Outlier { vertex, magnitude: largest, typical })
}

fn norm_sq(a: [f64; 3]) -> f64 {
    dot(a, a)
}

/// Area of triangle `t` of `v`.
pub(crate) fn triangle_area(v: &[[f64; 3]], t: &[u32; 3]) -> f64 {
    let p = v[t[0] as usize];
    let a = sub(v[t[1] as usize], p);
    let b = sub(v[t[2] as usize], p);
    0.5 * norm(cross(a, b))
}

fn longest_edge_sq(v: &[[f64; 3]], t: &[u32; 3]) -> f64 {
    let [a, b, c] = t.map(|i| v[i as usize]);
    norm_sq(sub(a, b)).max(norm_sq(sub(b, c))).max(norm_sq(sub(c, a)))
}

/// CSR offsets of a counting sort: one entry per item of `buckets` (each in `0..n`), bucket
/// `v`'s entries at `off[v]..off[v + 1]`.
fn bucket_offsets(n: usize, buckets: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut off = vec![0usize; n + 1];
    for b in buckets {
        off[b + 1] += 1;
    }
    for v in 0..n {
        off[v + 1] += off[v];
    }
    off
}

/// `triangles` without those that repeat an earlier triangle's three vertices (in any order),
/// and how many were dropped. A duplicate face adds a second sheet over the same triangle: the
/// Laplacian takes it for a tufted, doubled surface there (measured on a 10:1 ellipsoid with a
/// third of its faces repeated: no symmetry reported instead of its two; TOSCA shapes with 5%
/// of their faces repeated reversed, as a double-sided export has them: detection twice as
/// slow). Linear time: triangles are grouped by their smallest vertex, and only a group's own
/// triangles are compared.
fn without_duplicates(triangles: Vec<[u32; 3]>) -> (Vec<[u32; 3]>, usize) {
    // Each triangle's vertices in ascending order: equal for the same three vertices.
    let sorted: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect();
    let n = sorted.iter().map(|s| s[2]).max().map_or(0, |v| v as usize + 1);
    let start = bucket_offsets(n, sorted.iter().map(|s| s[0] as usize));
    let mut fill = start[..n].to_vec();
    let mut group = vec![0u32; triangles.len()];
    for (i, s) in sorted.iter().enumerate() {
        let low = s[0] as usize;
        group[fill[low]] = i as u32;
        fill[low] += 1;
    }
    let mut duplicate = vec![false; triangles.len()];
    let mut found = 0;
    for v in 0..n {
        let members = &mut group[start[v]..start[v + 1]];
        if members.len() < 2 {
            continue;
        }
        // By vertices, then by position in the input: the first of equal ones is kept.
        members.sort_unstable_by_key(|&i| (sorted[i as usize], i));
        for pair in members.windows(2) {
            if sorted[pair[0] as usize] == sorted[pair[1] as usize] {
                duplicate[pair[1] as usize] = true;
                found += 1;
            }
        }
    }
    if found == 0 {
        return (triangles, 0);
    }
    (triangles.into_iter().zip(duplicate).filter(|(_, d)| !d).map(|(t, _)| t).collect(), found)
}

/// The key `(min << 32) | max` of the edge `a b`.
fn edge_key(a: u32, b: u32) -> u64 {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    ((a as u64) << 32) | b as u64
}

/// Every triangle's edges as keys `(min << 32) | max`, sorted: an edge appears once per
/// triangle that uses it (once on a boundary, more than twice where it is non-manifold).
///
/// A counting sort on the smaller vertex (the key's high half), then each vertex's few keys
/// sorted: the order of sorting all `3·F` keys, in linear time (on 10⁶ vertices the global sort
/// took about a third of a second, and a mesh's construction and its simplification sort them
/// three times).
pub(crate) fn sorted_edge_keys(triangles: &[[u32; 3]]) -> Vec<u64> {
    let n = triangles.iter().flatten().max().map_or(0, |&v| v as usize + 1);
    let start = bucket_offsets(n, triangles.iter().flat_map(|t| (0..3).map(move |k| t[k].min(t[(k + 1) % 3]) as usize)));
    let mut fill = start[..n].to_vec();
    let mut keys = vec![0u64; 3 * triangles.len()];
    for t in triangles {
        for k in 0..3 {
            let key = edge_key(t[k], t[(k + 1) % 3]);
            let low = (key >> 32) as usize;
            keys[fill[low]] = key;
            fill[low] += 1;
        }
    }
    for v in 0..n {
        keys[start[v]..start[v + 1]].sort_unstable();
    }
    keys
}

/// Edges shared by more than two triangles, from the sorted edge keys ([`sorted_edge_keys`]).
fn count_non_manifold_edges(keys: &[u64]) -> usize {
    keys.chunk_by(|a, b| a == b).filter(|run| run.len() > 2).count()
}

/// Errors on the first edge shared by more than two triangles (reported with input indices),
/// from the sorted edge keys.
fn check_edge_manifold(keys: &[u64]) -> Result<(), MeshError> {
    let mut i = 0;
    while i < keys.len() {
        let mut j = i + 1;
        while j < keys.len() && keys[j] == keys[i] {
            j += 1;
        }
        if j - i > 2 {
            return Err(MeshError::NonManifoldEdge {
                a: (keys[i] >> 32) as u32,
                b: keys[i] as u32,
                triangles: j - i,
            });
        }
        i = j;
    }
    Ok(())
}

struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind { parent: (0..n).collect() }
    }
    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }
    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            // Smaller root wins: roots, and so component choice, do not depend on call order.
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent[hi] = lo;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The adjacency is the table of every directed edge sorted and deduplicated, and the edge
    /// keys every triangle's edges sorted, on a closed mesh and on one with a boundary, a
    /// non-manifold edge, a repeated triangle and an isolated vertex.
    #[test]
    fn adjacency_and_edge_keys_are_every_edge_sorted() {
        let reference = |m: &Mesh| {
            let mut e: Vec<(u32, u32)> = m.triangles.iter().flat_map(|t| (0..3).flat_map(move |k| [(t[k], t[(k + 1) % 3]), (t[(k + 1) % 3], t[k])])).collect();
            e.sort_unstable();
            e.dedup();
            let mut off = vec![0usize; m.num_vertices() + 1];
            for &(a, _) in &e {
                off[a as usize + 1] += 1;
            }
            for v in 0..m.num_vertices() {
                off[v + 1] += off[v];
            }
            (off, e.into_iter().map(|(_, b)| b).collect::<Vec<u32>>())
        };
        let sphere = crate::shapes::icosphere(3);
        // A fan with a boundary, an edge shared by three triangles (0–1) and a repeated triangle.
        let odd = Mesh {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [2.0, 2.0, 2.0]],
            triangles: vec![[0, 1, 2], [1, 0, 3], [0, 1, 4], [0, 1, 4], [2, 4, 0]],
            ..sphere.clone()
        };
        for m in [&sphere, &odd] {
            let (off, nbr) = m.adjacency();
            assert_eq!((off.clone(), nbr.clone()), reference(m));
            assert!((0..m.num_vertices()).all(|v| nbr[off[v]..off[v + 1]].windows(2).all(|w| w[0] < w[1])));
        }
        // The edge keys: every triangle's edges, sorted as a whole.
        for m in [&sphere, &odd] {
            let mut keys: Vec<u64> = m.triangles.iter().flat_map(|t| (0..3).map(move |k| edge_key(t[k], t[(k + 1) % 3]))).collect();
            keys.sort_unstable();
            assert_eq!(sorted_edge_keys(&m.triangles), keys);
        }
        assert!(sorted_edge_keys(&[]).is_empty());
        // The isolated vertex 5 has no neighbours; vertex 0 has 1, 2, 3, 4.
        let (off, nbr) = odd.adjacency();
        assert_eq!(&nbr[off[0]..off[1]], &[1, 2, 3, 4]);
        assert_eq!(off[5], off[6]);
    }

    /// A stray vertex at 1e308 in an ordinary mesh is refused with a message that names it
    /// (issue 16, item 14: it failed in the eigensolver with "NonPositivePivot"), while the
    /// same mesh scaled as a whole to 1e300 or 1e-300 is accepted.
    #[test]
    fn a_stray_vertex_is_named_but_any_uniform_scale_is_accepted() {
        let sphere = crate::shapes::icosphere(2);
        let mut v = sphere.vertices.clone();
        v[7] = [1e308, 0.0, 0.0];
        match Mesh::new(v, sphere.triangles.clone(), &MeshParams::default()) {
            Err(e @ MeshError::Outlier { vertex: 7, .. }) => assert!(e.to_string().contains("vertex 7"), "{e}"),
            other => panic!("expected the outlier to be named: {other:?}"),
        }
        for scale in [1e300, 1e-300] {
            let v: Vec<[f64; 3]> = sphere.vertices.iter().map(|p| p.map(|x| x * scale)).collect();
            let mesh = Mesh::new(v, sphere.triangles.clone(), &MeshParams::default()).expect("a uniformly scaled mesh");
            let (unit, s) = mesh.normalized();
            assert!((unit.area() - 1.0).abs() < 1e-9, "unit area: {}", unit.area());
            assert!((s / (scale * sphere.area().sqrt()) - 1.0).abs() < 1e-9, "scale {s:e}");
        }
    }

    #[test]
    fn mixed_orientations_are_made_consistent() {
        let sphere = crate::shapes::icosphere(2);
        let mut flipped = sphere.triangles.clone();
        for t in flipped.iter_mut().skip(1).step_by(3) {
            t.swap(0, 1);
        }
        let mesh = Mesh::new(sphere.vertices.clone(), flipped, &MeshParams::default()).unwrap();
        assert!(!mesh.consistently_oriented());
        let fixed = mesh.oriented_triangles();
        // Every edge of the closed surface is traversed once in each direction…
        let mut directed: Vec<(u32, u32)> = fixed.iter().flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3]))).collect();
        directed.sort_unstable();
        let before = directed.len();
        directed.dedup();
        assert_eq!(directed.len(), before, "an edge traversed twice in one direction");
        assert!(directed.iter().all(|&(a, b)| directed.binary_search(&(b, a)).is_ok()));
        // …and the orientation is the first triangle's: here the original, outward one.
        let same_cycle = |t: &[u32; 3], u: &[u32; 3]| (0..3).any(|r| (0..3).all(|k| t[k] == u[(k + r) % 3]));
        assert!(fixed.iter().zip(&sphere.triangles).all(|(t, u)| same_cycle(t, u)));
        // A consistent mesh is its own orientation (the linear-time check).
        let consistent = Mesh::new(sphere.vertices.clone(), fixed.clone(), &MeshParams::default()).unwrap();
        assert!(consistent.consistently_oriented());
        assert_eq!(consistent.oriented_triangles(), consistent.triangles);
    }

    fn tet() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        (
            vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        )
    }

    fn err(v: Vec<[f64; 3]>, t: Vec<[u32; 3]>) -> MeshError {
        Mesh::new(v, t, &MeshParams::default()).unwrap_err()
    }

    #[test]
    fn accepts_closed_tetrahedron() {
        let (v, t) = tet();
        let m = Mesh::new(v, t, &MeshParams::default()).unwrap();
        assert_eq!(m.num_vertices(), 4);
        assert_eq!(m.info.components, 1);
        assert!((m.area() - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-12);
    }

    #[test]
    fn bad_lengths() {
        let p = MeshParams::default();
        assert!(matches!(
            Mesh::from_slices(&[0.0; 8], &[0, 1, 2], &p),
            Err(MeshError::BadLength { array: "vertices", len: 8 })
        ));
        assert!(matches!(
            Mesh::from_slices(&[0.0; 9], &[0, 1], &p),
            Err(MeshError::BadLength { array: "triangles", len: 2 })
        ));
    }

    #[test]
    fn empty() {
        assert_eq!(err(vec![], vec![]), MeshError::Empty);
        assert_eq!(err(vec![[0.; 3]; 3], vec![]), MeshError::Empty);
    }

    #[test]
    fn non_finite() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let (mut v, t) = tet();
            v[2][1] = bad;
            assert_eq!(err(v, t), MeshError::NonFinite { vertex: 2 });
        }
    }

    #[test]
    fn index_out_of_range() {
        let (v, mut t) = tet();
        t[3][1] = 4;
        assert_eq!(err(v, t), MeshError::IndexOutOfRange { triangle: 3, index: 4, vertices: 4 });
    }

    #[test]
    fn repeated_index() {
        let (v, mut t) = tet();
        t[1] = [1, 3, 1];
        assert_eq!(err(v, t), MeshError::RepeatedIndex { triangle: 1 });
    }

    #[test]
    fn non_manifold_edge() {
        let (mut v, mut t) = tet();
        v.push([1., 1., 1.]);
        t.push([0, 1, 4]); // third triangle on edge (0,1)
        let strict = MeshParams { allow_non_manifold: false, ..Default::default() };
        assert_eq!(Mesh::new(v.clone(), t.clone(), &strict).unwrap_err(), MeshError::NonManifoldEdge { a: 0, b: 1, triangles: 3 });
        // Accepted by default, and counted.
        assert_eq!(Mesh::new(v, t, &MeshParams::default()).unwrap().info.non_manifold_edges, 1);
        // The same triangle twice is dropped (`duplicate_triangles_are_dropped`), so it makes
        // no non-manifold edge, even for the strict.
        let (v, mut t) = tet();
        t.push(t[0]);
        assert_eq!(Mesh::new(v, t, &strict).unwrap().info.duplicate_triangles, 1);
    }

    #[test]
    fn all_degenerate_is_an_error() {
        let v = vec![[0., 0., 0.], [1., 0., 0.], [2., 0., 0.], [3., 0., 0.]];
        assert_eq!(err(v, vec![[0, 1, 2], [1, 3, 2]]), MeshError::Degenerate);
        assert_eq!(err(vec![[1., 1., 1.]; 3], vec![[0, 1, 2]]), MeshError::Degenerate);
    }

    #[test]
    fn degenerate_triangles_are_kept_and_counted() {
        // The tetrahedron with edge (1,2) split at vertex 4: faces [0,2,1] and [1,2,3] become four.
        let (mut v, _) = tet();
        v.push([0.5, 0.5, 0.0]);
        let t = vec![[0, 2, 4], [0, 4, 1], [0, 1, 3], [1, 4, 3], [4, 2, 3], [0, 3, 2]];
        let m = Mesh::new(v.clone(), t.clone(), &MeshParams::default()).unwrap();
        assert_eq!(m.info.degenerate_triangles, 0);
        // Collapse vertex 4 onto vertex 1: faces [0,4,1] and [1,4,3] get zero area but stay
        // (without welding)…
        v[4] = v[1];
        let unwelded = MeshParams { weld: false, ..Default::default() };
        let m = Mesh::new(v.clone(), t.clone(), &unwelded).unwrap();
        assert_eq!(m.info.degenerate_triangles, 2);
        assert_eq!(m.num_triangles(), 6);
        // …and by default too: the surface is closed, so the coincident vertices 1 and 4 are
        // a contact, not a seam, and are not welded.
        let m = Mesh::new(v, t, &MeshParams::default()).unwrap();
        assert_eq!((m.info.welded_vertices, m.info.degenerate_triangles), (0, 2));
    }

    /// A seam split by duplicated vertices (two triangles of a square that share no vertex
    /// along their diagonal) is welded: one surface, the copies counted and remembered.
    #[test]
    fn a_split_seam_is_welded() {
        let v = vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
        let t = vec![[0, 1, 2], [3, 4, 5]];
        let m = Mesh::new(v.clone(), t.clone(), &MeshParams::default()).unwrap();
        assert_eq!((m.info.welded_vertices, m.info.components, m.num_vertices()), (2, 1, 4));
        assert_eq!(m.welded, vec![(3, 0), (4, 2)]);
        let apart = Mesh::new(v, t, &MeshParams { weld: false, ..Default::default() }).unwrap();
        assert_eq!(apart.info.components, 2);
    }

    #[test]
    fn isolated_vertices_are_ignored() {
        let (mut v, t) = tet();
        v.insert(0, [9., 9., 9.]);
        let t: Vec<[u32; 3]> = t.iter().map(|f| f.map(|i| i + 1)).collect();
        let m = Mesh::new(v, t, &MeshParams::default()).unwrap();
        assert_eq!(m.info.isolated_vertices, 1);
        assert_eq!(m.num_vertices(), 4);
        assert_eq!(m.input_index, vec![1, 2, 3, 4]);
        assert!(m.triangles.iter().flatten().all(|&i| i < 4));
    }

    /// An unreferenced vertex is ignored, wherever it lies: one far away did set the welding
    /// tolerance (relative to the bounding box) and welded 41 boundary vertices of an open
    /// sphere together, one at another scale than the mesh made every triangle degenerate.
    #[test]
    fn a_far_unreferenced_vertex_changes_nothing() {
        let sphere = crate::shapes::icosphere(3);
        let below = |t: &[u32; 3]| t.iter().map(|&i| sphere.vertices[i as usize][2]).sum::<f64>() < -0.9;
        let open: Vec<[u32; 3]> = sphere.triangles.iter().filter(|t| !below(t)).copied().collect();
        let alone = Mesh::new(sphere.vertices.clone(), open.clone(), &MeshParams::default()).unwrap();
        assert_eq!(alone.info.welded_vertices, 0);
        for (scale, stray) in [(1.0, 1e6), (1e-150, 1.0), (1.0, 1e300)] {
            let mut v: Vec<[f64; 3]> = sphere.vertices.iter().map(|p| p.map(|x| x * scale)).collect();
            v.push([stray, 0.0, 0.0]);
            let m = Mesh::new(v, open.clone(), &MeshParams::default()).unwrap_or_else(|e| panic!("scale {scale:e}, stray at {stray:e}: {e}"));
            assert_eq!((m.info.welded_vertices, m.info.collapsed_triangles), (0, 0), "scale {scale:e}, stray at {stray:e}");
            assert_eq!(m.info.isolated_vertices, alone.info.isolated_vertices + 1);
            assert_eq!((&m.triangles, &m.input_index), (&alone.triangles, &alone.input_index));
            assert_eq!(m.info.degenerate_triangles, 0);
        }
    }

    /// A repeated face (either orientation, in the input or made by welding) is dropped and
    /// counted; the mesh is the one without it.
    #[test]
    fn duplicate_triangles_are_dropped() {
        let sphere = crate::shapes::icosphere(2);
        let plain = Mesh::new(sphere.vertices.clone(), sphere.triangles.clone(), &MeshParams::default()).unwrap();
        let mut doubled = sphere.triangles.clone();
        doubled.extend(sphere.triangles.iter().step_by(3).map(|t| [t[2], t[1], t[0]]));
        doubled.extend(sphere.triangles.iter().skip(1).step_by(5).map(|t| [t[1], t[2], t[0]]));
        let extra = doubled.len() - sphere.triangles.len();
        let m = Mesh::new(sphere.vertices.clone(), doubled, &MeshParams::default()).unwrap();
        assert_eq!(m.info.duplicate_triangles, extra);
        assert_eq!((m.info.non_manifold_edges, m.info.input_triangles), (0, sphere.triangles.len() + extra));
        assert_eq!(m.triangles, plain.triangles);
        // A triangle soup with every face twice, reversed: welding makes the copies one.
        let mut v = Vec::new();
        let mut t = Vec::new();
        for face in sphere.triangles.iter().flat_map(|f| [*f, [f[2], f[1], f[0]]]) {
            let i = v.len() as u32;
            v.extend(face.map(|c| sphere.vertices[c as usize]));
            t.push([i, i + 1, i + 2]);
        }
        let soup = Mesh::new(v, t, &MeshParams::default()).unwrap();
        assert_eq!((soup.num_vertices(), soup.num_triangles()), (plain.num_vertices(), plain.num_triangles()));
        assert_eq!((soup.info.duplicate_triangles, soup.info.non_manifold_edges), (sphere.triangles.len(), 0));
    }

    #[test]
    fn components_each_largest_or_reject() {
        let (v, t) = tet();
        // Second tetrahedron, twice as large, offset; its vertices come first in the input.
        let mut v2: Vec<[f64; 3]> = v.iter().map(|p| [2. * p[0] + 5., 2. * p[1], 2. * p[2]]).collect();
        v2.extend(v.iter().copied());
        let mut t2 = t.clone();
        t2.extend(t.iter().map(|f| f.map(|i| i + 4)));
        let m = Mesh::new(v2.clone(), t2.clone(), &MeshParams::default()).unwrap();
        assert_eq!((m.info.components, m.info.kept_components, m.info.ignored_component_vertices), (2, 2, 0));
        let parts = m.split_components().expect("two components");
        assert_eq!(parts.len(), 2);
        // Largest first, input indices kept.
        assert_eq!(parts[0].input_index, vec![0, 1, 2, 3]);
        assert_eq!(parts[1].input_index, vec![4, 5, 6, 7]);
        assert!((parts[0].area() / parts[1].area() - 4.0).abs() < 1e-12);
        assert!(parts.iter().all(|p| p.triangles.iter().flatten().all(|&i| i < 4)));
        let largest = Mesh::new(v2.clone(), t2.clone(), &MeshParams { components: ComponentPolicy::Largest, ..Default::default() }).unwrap();
        assert_eq!((largest.info.kept_components, largest.info.ignored_component_vertices), (1, 4));
        assert_eq!(largest.input_index, vec![0, 1, 2, 3]);
        assert!(largest.split_components().is_none());
        // A component under MIN_COMPONENT_SHARE of the largest one's area is ignored.
        let mut v3 = v2.clone();
        for p in &mut v3[4..] {
            *p = p.map(|x| 0.05 * x);
        }
        let m = Mesh::new(v3, t2.clone(), &MeshParams::default()).unwrap();
        assert_eq!((m.info.kept_components, m.info.ignored_component_vertices, m.num_vertices()), (1, 4, 4));
        let reject = MeshParams { components: ComponentPolicy::Reject, ..Default::default() };
        assert_eq!(Mesh::new(v2, t2, &reject).unwrap_err(), MeshError::Disconnected { components: 2 });
    }
}
