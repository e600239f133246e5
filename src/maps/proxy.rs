//! A coarse proxy of a large mesh for the dense-map stage, and the lift of its maps back to
//! every vertex.
//!
//! The dense maps (profile matching, ZoomOut, the geodesic polish) cost O(n) per step with
//! large constants, and a symmetry map is a smooth, low-dimensional object: a few thousand
//! well spread vertices determine it. So on a mesh of more than `1.5 m` vertices the maps
//! stage runs on a proxy of `m` vertices (default 6000, [`super::MapParams::proxy_vertices`];
//! the 41k posed quadruped: maps 6.1 → 1.1 s, mirror 95.6 → 95.3% acc@0.05, all 12 leg maps
//! 0.94–1.00 acc@0.1):
//!
//! 1. **Seeds**: the farthest-point samples already used (voting's and the polish's, so they
//!    keep their indices `0, 1, …`), extended by farthest-point sampling in the edge-graph
//!    geodesic distance (incremental Dijkstra, each new seed re-labelling only the vertices it
//!    is nearer to) up to `m`. Geodesic spacing is even on the surface, whatever the vertex
//!    density.
//! 2. **Cells**: every vertex belongs to its nearest seed (the geodesic Voronoi cell, a
//!    by-product of the sampling). Two seeds are neighbours when an edge of the mesh joins their
//!    cells: the proxy's graph is the dual of the Voronoi partition, a coarse triangulation.
//! 3. **Restriction**: the proxy's eigenbasis is the mesh's, sampled at the seeds
//!    (`Φ_proxy = Φ[seeds]`, same eigenvalues), with the mass of each cell
//!    (`m_c = Σ_{v∈cell c} m_v`), so `C = (M Φ)ᵀ Φ[T]` is the same integral at a coarser
//!    quadrature; the biharmonic embedding and the wave kernel signatures are the mesh's rows
//!    at the seeds. Nothing is recomputed on a coarse mesh: the spectral quantities are exact.
//! 4. **Lift** ([`Proxy::lift`]): vertex `v` in the cell of seed `c` is placed relative to
//!    `c`'s proxy image by local trilateration: its image is the vertex `w` minimising
//!    `Σ_{c'} | |x_v − x_{c'}| − |x_w − x_{T c'}| |` over `c` and its neighbour seeds `c'`
//!    (greedy descent on the mesh from the image of `c`, or of an already placed neighbour
//!    of `v` in its cell: each cell is placed breadth-first from its seed, cells in parallel;
//!    on 10⁶ vertices a map's lift takes about half a second on two cores).
//!    At the scale of a cell (radius ≈ √(area / (π m)), 0.7% of √area at m = 6000) an
//!    intrinsic isometry preserves straight distances to first order, so this only interpolates
//!    within the proxy's precision; it does not decide anything the proxy map did not. The
//!    region, confidence and mismatch of `v` are its cell's.
//! 5. **Polish on the mesh** (session 38, [`super::MapParams::lift_polish`], 4 passes): each
//!    search's strongest lifted map gets the geodesic polish again on the mesh's own edge
//!    graph, from the same anchors (in mesh indices), before the searches' versions of a
//!    symmetry are compared. The proxy's graph joins seeds about `√(area/m)` apart, and its
//!    Dijkstra distances are coarser than the mesh's: on SHREC'16 kid03 (9,204 vertices,
//!    one search) the proxy's map is within 0.05·√area of the truth at 88.2% of the vertices
//!    (its seeds 88.6%, the lifted vertices 87.3%), 89.4% after the polish on the mesh. Most of
//!    the gain is in the choice between versions: kid03's restarts found its mirror twice,
//!    and unpolished the worse version (57%) scored 0.354 against 0.353; polished, the better
//!    one wins (89%). SHREC'16's 14 kids (8.6–12k vertices, the only shapes of shared/data on
//!    a proxy), seeds 0, 10, 20, 30, best / first acc@0.05: 71.8 / 70.8 → 72.6 / 72.0%
//!    (kid03 0.69 → 0.79, kid13's first 0.66 → 0.69; kid02, kid08 and kid11 −0.01). Two maps
//!    instead of one: 72.7 / 72.1 at twice the cost; eight passes for two maps 73.0 / 72.2;
//!    two passes for one 72.5 / 71.8. Cost, quiet machine: about 0.5 s per search at 10k
//!    vertices, 1 s at 20k (×1.2–1.5 the detection); not applied on the hierarchy's coarse
//!    mesh (`crate::hierarchy`), whose lift to 24k–10⁶ vertices it would outweigh.

use faer::Mat;
use sprs::CsMat;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

use super::geodesic::EdgeGraph;
use super::DenseMap;
use crate::distance::BiharmonicEmbedding;
use crate::mesh::Mesh;
use crate::mesh::vec3::dist2;
use crate::spectral::Eigenbasis;

/// A mesh needs a proxy when it has more than this many times `proxy_vertices` vertices.
pub(crate) const PROXY_MARGIN: f64 = 1.5;

/// Whether the maps of a mesh of `n` vertices are made on a proxy.
pub fn wanted(n: usize, params: &super::MapParams) -> bool {
    params.proxy_vertices > 0 && n as f64 > PROXY_MARGIN * params.proxy_vertices as f64
}

/// The coarse proxy of a mesh (see the module docs). Proxy vertex `c` is mesh vertex
/// `seeds[c]`.
pub struct Proxy {
    /// `(m,)` the mesh vertex of each proxy vertex.
    pub seeds: Vec<usize>,
    /// `(n,)` the proxy vertex (cell) of each mesh vertex.
    pub owner: Vec<u32>,
    /// `(m,)` positions of the seeds.
    pub positions: Vec<[f64; 3]>,
    /// CSR adjacency of the proxy graph (cells sharing a mesh edge).
    pub adjacency: (Vec<usize>, Vec<u32>),
    /// CSR adjacency of the mesh (the lift descends on it).
    pub mesh_adjacency: (Vec<usize>, Vec<u32>),
    /// The mesh's biharmonic embedding at the seeds.
    pub emb: BiharmonicEmbedding,
    /// `(m, E)` the mesh's wave kernel signatures at the seeds.
    pub wks: Mat<f64>,
    /// The mesh's eigenbasis at the seeds, with cell masses (no Laplacian: an empty matrix).
    pub basis: Eigenbasis,
}

impl Proxy {
    /// A proxy of `size` vertices whose first seeds are `first` (distinct mesh vertices, in
    /// order): proxy vertex `i < first.len()` is `first[i]`. `graph` is the mesh's
    /// ([`EdgeGraph::new`] of its vertices and adjacency).
    pub fn new(mesh: &Mesh, graph: &EdgeGraph, basis: &Eigenbasis, emb: &BiharmonicEmbedding, wks: &Mat<f64>, first: &[usize], size: usize) -> Proxy {
        let n = mesh.num_vertices();
        let adjacency = mesh.adjacency();
        let (seeds, owner) = geodesic_farthest_points(graph, first, size.clamp(first.len().max(1), n));
        let m = seeds.len();
        // Cells sharing a mesh edge are neighbours.
        let mut rows: Vec<Vec<u32>> = vec![Vec::new(); m];
        let (off, nbr) = &adjacency;
        for v in 0..n {
            for &u in &nbr[off[v]..off[v + 1]] {
                let (a, b) = (owner[v], owner[u as usize]);
                if a != b {
                    rows[a as usize].push(b);
                }
            }
        }
        let mut coff = Vec::with_capacity(m + 1);
        let mut cnbr = Vec::new();
        coff.push(0);
        for r in &mut rows {
            r.sort_unstable();
            r.dedup();
            cnbr.extend_from_slice(r);
            coff.push(cnbr.len());
        }
        let positions = seeds.iter().map(|&s| mesh.vertices[s]).collect();
        let sub_emb = BiharmonicEmbedding {
            coords: Mat::from_fn(m, emb.coords.ncols(), |c, i| emb.coords[(seeds[c], i)]),
            norms2: seeds.iter().map(|&s| emb.norms2[s]).collect(),
        };
        let sub_wks = Mat::from_fn(m, wks.ncols(), |c, e| wks[(seeds[c], e)]);
        let mass = cell_sums(&owner, &basis.mass, m);
        let sub_basis = Eigenbasis {
            evals: basis.evals.clone(),
            evecs: Mat::from_fn(m, basis.k(), |c, i| basis.evecs[(seeds[c], i)]),
            mass,
            laplacian: CsMat::zero((m, m)),
            area: basis.area,
            info: basis.info.clone(),
            assembly_seconds: 0.0,
        };
        Proxy { seeds, owner, positions, adjacency: (coff, cnbr), mesh_adjacency: adjacency, emb: sub_emb, wks: sub_wks, basis: sub_basis }
    }

    /// Number of proxy vertices.
    pub fn len(&self) -> usize {
        self.seeds.len()
    }

    /// Whether the proxy has no vertices.
    pub fn is_empty(&self) -> bool {
        self.seeds.is_empty()
    }

    /// The map `m` of the proxy lifted to every mesh vertex (see the module docs): `positions`
    /// are the mesh's.
    pub fn lift(&self, positions: &[[f64; 3]], m: &DenseMap) -> DenseMap {
        lift(&self.seeds, &self.owner, &self.positions, &self.adjacency, &self.mesh_adjacency, positions, m)
    }
}

/// `values` (one per mesh vertex) summed over each of the `cells` cells (`owner[v]` the cell of
/// vertex `v`), in vertex order: a cell's mass from the mesh's lumped mass, here and on the
/// hierarchy's coarse mesh ([`crate::hierarchy::Hierarchy::cell_mass`]).
pub(crate) fn cell_sums(owner: &[u32], values: &[f64], cells: usize) -> Vec<f64> {
    let mut sums = vec![0.0f64; cells];
    for (&c, &x) in owner.iter().zip(values) {
        sums[c as usize] += x;
    }
    sums
}

/// The map `m` of a proxy (vertex `c` at mesh vertex `seeds[c]`, at `seed_positions[c]`, with
/// the graph `seed_adjacency`) lifted to every vertex of the mesh (`positions`, graph
/// `mesh_adjacency`, `owner[v]` the proxy vertex whose cell holds `v`), by the local
/// trilateration of the module docs.
pub(crate) fn lift(
    seeds: &[usize],
    owner: &[u32],
    seed_positions: &[[f64; 3]],
    seed_adjacency: &(Vec<usize>, Vec<u32>),
    mesh_adjacency: &(Vec<usize>, Vec<u32>),
    positions: &[[f64; 3]],
    m: &DenseMap,
) -> DenseMap {
    let n = owner.len();
    let adjacency = mesh_adjacency;
    let (coff, cnbr) = seed_adjacency;
    let d = |a: &[f64; 3], b: &[f64; 3]| dist2(*a, *b).sqrt();
    // The cells' vertices (counting sort by owner).
    let cells = seeds.len();
    let mut off = vec![0usize; cells + 1];
    for &c in owner {
        off[c as usize + 1] += 1;
    }
    for c in 0..cells {
        off[c + 1] += off[c];
    }
    let mut fill = off.clone();
    let mut members = vec![0u32; n];
    for (v, &c) in owner.iter().enumerate() {
        members[fill[c as usize]] = v as u32;
        fill[c as usize] += 1;
    }
    // Each cell on its own (cells in parallel): its seed maps to its proxy image, the other
    // vertices are placed breadth-first from the seed within the cell (a geodesic Voronoi cell
    // is connected), so that a vertex's neighbour is placed before it and gives it a start.
    let placed = crate::parallel::chunks(cells, |range| {
        let mut out: Vec<(u32, u32)> = Vec::with_capacity(off[range.end] - off[range.start]);
        let mut local = vec![usize::MAX; n];
        // (distance from v to seed c', image position of c') for c and its neighbours.
        let mut frame: Vec<(f64, [f64; 3])> = Vec::new();
        let mut queue = std::collections::VecDeque::new();
        for c in range {
            let own = seeds[m.image[c]];
            local[seeds[c]] = own;
            out.push((seeds[c] as u32, own as u32));
            queue.push_back(seeds[c]);
            let place = |u: usize, from: usize, frame: &mut Vec<(f64, [f64; 3])>| {
                frame.clear();
                for &c2 in std::iter::once(&(c as u32)).chain(&cnbr[coff[c]..coff[c + 1]]) {
                    let c2 = c2 as usize;
                    frame.push((d(&positions[u], &seed_positions[c2]), positions[seeds[m.image[c2]]]));
                }
                let cost = |w: usize| frame.iter().map(|(dv, t)| (dv - d(&positions[w], t)).abs()).sum::<f64>();
                let start = if from != usize::MAX && cost(from) < cost(own) { from } else { own };
                super::greedy_descent(adjacency, start, cost).0
            };
            while let Some(v) = queue.pop_front() {
                for &u in &adjacency.1[adjacency.0[v]..adjacency.0[v + 1]] {
                    let u = u as usize;
                    if owner[u] as usize == c && local[u] == usize::MAX {
                        local[u] = place(u, local[v], &mut frame);
                        out.push((u as u32, local[u] as u32));
                        queue.push_back(u);
                    }
                }
            }
            // A cell not connected through its own vertices (not from the Voronoi cells of
            // `geodesic_farthest_points` or `EdgeGraph::nearest_sources`, which are; a vertex that
            // joined cell 0 from an unreached part is one): the rest from the seed's image.
            for &u in &members[off[c]..off[c + 1]] {
                let u = u as usize;
                if local[u] == usize::MAX {
                    local[u] = place(u, usize::MAX, &mut frame);
                    out.push((u as u32, local[u] as u32));
                }
            }
        }
        out
    });
    let mut image = vec![usize::MAX; n];
    for (u, w) in placed.into_iter().flatten() {
        image[u as usize] = w as usize;
    }
    // Every vertex is in a cell: a component without a seed is a cell of its own
    // (`geodesic_farthest_points`) or joins cell 0 (`Hierarchy`'s `nearest_sources` cells).
    debug_assert!(image.iter().all(|&w| w != usize::MAX));
    let mut map = vec![-1i64; n];
    let mut confidence = vec![0.0; n];
    let mut mismatch = vec![0.0; n];
    let mut region_size = 0;
    for v in 0..n {
        let c = owner[v] as usize;
        mismatch[v] = m.mismatch[c];
        if m.map[c] >= 0 {
            map[v] = image[v] as i64;
            confidence[v] = m.confidence[c];
            region_size += 1;
        }
    }
    DenseMap {
        map,
        confidence,
        mismatch,
        anchors: m.anchors.iter().map(|&(a, b)| (seeds[a], seeds[b])).collect(),
        region_size,
        global: m.global,
        refined: m.refined,
        image,
    }
}

/// Farthest-point sampling in edge-graph distance, starting from the seeds `first`, up to
/// `size` seeds; returns the seeds and the nearest seed (Voronoi cell) of every vertex. A
/// component of the graph without a seed is infinitely far, so every component gets one.
pub(crate) fn geodesic_farthest_points(graph: &EdgeGraph, first: &[usize], size: usize) -> (Vec<usize>, Vec<u32>) {
    let n = graph.off.len() - 1;
    let mut dist = vec![f64::INFINITY; n];
    let mut owner = vec![u32::MAX; n];
    let mut seeds: Vec<usize> = Vec::with_capacity(size);
    // Candidates for the farthest vertex, lazily invalidated: an entry is current when its
    // distance is the vertex's distance now (distances only decrease).
    let mut far: BinaryHeap<(u64, u32)> = BinaryHeap::new();
    let mut near: BinaryHeap<Reverse<(u64, u32)>> = BinaryHeap::new();
    let mut grow = |sources: &[usize], seeds: &mut Vec<usize>, dist: &mut Vec<f64>, owner: &mut Vec<u32>, far: &mut BinaryHeap<(u64, u32)>| {
        for &s in sources {
            let c = seeds.len() as u32;
            seeds.push(s);
            dist[s] = 0.0;
            owner[s] = c;
            near.push(Reverse((0, s as u32)));
        }
        graph.relax_owners(dist, owner, &mut near, &mut |v, key| {
            far.push((key, v as u32));
            true
        });
    };
    grow(first, &mut seeds, &mut dist, &mut owner, &mut far);
    // Unreached vertices (other components) are candidates at infinite distance.
    for (v, &d) in dist.iter().enumerate() {
        if d == f64::INFINITY {
            far.push((f64::INFINITY.to_bits(), v as u32));
        }
    }
    while seeds.len() < size {
        let Some((key, v)) = far.pop() else { break };
        let v = v as usize;
        if key != dist[v].to_bits() || dist[v] == 0.0 {
            continue;
        }
        grow(&[v], &mut seeds, &mut dist, &mut owner, &mut far);
    }
    // Components still without a seed (only if `size` was too small for them all): their own.
    for v in 0..n {
        if owner[v] == u32::MAX {
            let c = seeds.len() as u32;
            seeds.push(v);
            owner[v] = c;
            let mut queue = VecDeque::from([v]);
            while let Some(x) = queue.pop_front() {
                for &u in &graph.nbr[graph.off[x]..graph.off[x + 1]] {
                    if owner[u as usize] == u32::MAX {
                        owner[u as usize] = c;
                        queue.push_back(u as usize);
                    }
                }
            }
        }
    }
    (seeds, owner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{self, Pose};

    /// A quadruped, its basis (k = 20) and the proxy of `size` vertices starting at `first`.
    fn proxy_of(level: u32, pose: Pose, first: &[usize], size: usize) -> (shapes::Creature, Eigenbasis, Proxy) {
        let c = shapes::quadruped(level, pose, 0.0, 0);
        let (basis, emb, desc) = crate::maps::test_spectra(&c.mesh, 20);
        let p = Proxy::new(&c.mesh, &EdgeGraph::new(&c.mesh.vertices, c.mesh.adjacency()), &basis, &emb, &desc, first, size);
        (c, basis, p)
    }

    /// The proxy keeps the given seeds first, covers the mesh with connected cells of even
    /// size, and conserves the area.
    #[test]
    fn cells_partition_the_mesh() {
        let first = [7usize, 100, 2000];
        let (c, basis, p) = proxy_of(4, Pose::Walking, &first, 500);
        let n = c.mesh.num_vertices();
        assert_eq!(p.len(), 500);
        assert_eq!(&p.seeds[..3], &first);
        let mut sizes = vec![0usize; p.len()];
        for v in 0..n {
            sizes[p.owner[v] as usize] += 1;
        }
        for (c2, &s) in p.seeds.iter().enumerate() {
            assert_eq!(p.owner[s] as usize, c2, "a seed is in its own cell");
        }
        // Farthest-point cells are even: none more than 4× the mean (n / 500 ≈ 5).
        assert!(sizes.iter().all(|&s| s >= 1 && s <= 4 * n / 500), "cell sizes {:?}", sizes.iter().max());
        let area: f64 = p.basis.mass.iter().sum();
        assert!((area - basis.area).abs() < 1e-9 * basis.area);
        // The proxy graph is connected (the mesh is) and symmetric.
        let (off, nbr) = &p.adjacency;
        for a in 0..p.len() {
            for &b in &nbr[off[a]..off[a + 1]] {
                assert!(nbr[off[b as usize]..off[b as usize + 1]].contains(&(a as u32)));
            }
        }
        let mut seen = vec![false; p.len()];
        let mut stack = vec![0usize];
        seen[0] = true;
        while let Some(a) = stack.pop() {
            for &b in &nbr[off[a]..off[a + 1]] {
                if !std::mem::replace(&mut seen[b as usize], true) {
                    stack.push(b as usize);
                }
            }
        }
        assert!(seen.iter().all(|&s| s));
    }

    /// Lifting the proxy's restriction of the exact mirror gives back the mirror at nearly
    /// every vertex (trilateration inside the cells), with the cells' region.
    #[test]
    fn lift_recovers_the_mirror_between_seeds() {
        let (c, basis, p) = proxy_of(5, Pose::Rest, &[0], 1500);
        let n = c.mesh.num_vertices();
        // The proxy map: each seed to the seed whose cell holds its mirror image.
        let image: Vec<usize> = p.seeds.iter().map(|&s| p.owner[c.mirror[s] as usize] as usize).collect();
        let image_of = |v: usize| image[p.owner[v] as usize];
        let mut coarse = DenseMap::from_image(image.clone());
        // One cell outside the region.
        coarse.map[5] = -1;
        let lifted = p.lift(&c.mesh.vertices, &coarse);
        // The proxy map is right to a cell; the lift must stay within that and beat the
        // piecewise-constant lift (every vertex to its cell's image seed).
        let x = &c.mesh.vertices;
        let d = |a: usize, b: usize| dist2(x[a], x[b]).sqrt();
        let radius = (basis.area / (std::f64::consts::PI * p.len() as f64)).sqrt();
        let err: Vec<f64> = (0..n).map(|v| d(lifted.image[v], c.mirror[v] as usize)).collect();
        let constant: f64 = (0..n).map(|v| d(p.seeds[image_of(v)], c.mirror[v] as usize)).sum::<f64>() / n as f64;
        let mean = err.iter().sum::<f64>() / n as f64;
        let within = err.iter().filter(|&&e| e <= 2.0 * radius).count();
        assert!(within as f64 >= 0.97 * n as f64, "{within} of {n} within two cell radii");
        assert!(mean < 0.7 * constant, "mean error {mean:.4} against {constant:.4} piecewise constant (cell radius {radius:.4})");
        let outside = (0..n).filter(|&v| p.owner[v] == 5).count();
        assert_eq!(lifted.region_size, n - outside);
        assert!((0..n).all(|v| (lifted.map[v] < 0) == (p.owner[v] == 5)));
    }
}
