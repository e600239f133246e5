//! Quadric-error edge collapse (Garland & Heckbert 1997) with subset placement: the coarse
//! mesh's vertices are vertices of the fine mesh.
//!
//! Every vertex carries the quadric `Q_v = Σ_f A_f p_f p_fᵀ` of the planes `p_f` of its faces
//! (area-weighted), plus planes perpendicular to its boundary edges so that boundaries keep
//! their shape. Collapsing `u` into `v` costs `(Q_u + Q_v)(x_v)` — the squared distance of
//! `x_v` from the planes of both neighbourhoods — plus `β |x_u − x_v|⁴` (an even density, see
//! [`LENGTH_WEIGHT`]), and `v` inherits `Q_u + Q_v`. Edges are collapsed cheapest first, in
//! rounds of collapses whose neighbourhoods do not overlap, until the target count.
//! A collapse is refused when it would change the topology (the link condition: the common
//! neighbours of `u` and `v` are exactly the apexes of the faces on the edge), move a boundary
//! off itself, fold a face over (its normal turning by more than 90°) or touch a non-manifold
//! edge's vertices. Thin parts survive: shortening a finger costs its length squared in the
//! quadrics of its sides, so it keeps vertices while flat regions lose them. Keeping fine
//! vertices (instead of the optimal position) costs a little quadric error and makes the
//! coarse mesh's vertices exact seeds for lifting maps back (`super`).
//!
//! **Known limit: folds and near-contacts.** Where the surface folds onto itself or two parts
//! nearly touch (a foot against the other foot), collapsing the vertex at the bottom of the
//! fold joins the two sheets with an edge whose chord is far shorter than the way along the
//! surface, and the quadric error barely sees it; the coarse mesh's geodesics and Laplacian
//! then take the fold for a bridge. On the 60k KIDS pose 4 such edges (chord under 0.6 of the
//! fine geodesic) are 0.9% of all, but 6–8% where its lifted maps fail
//! (`bench/coarse_shortcuts.py`). Refusing the collapses that create them (a test on the
//! normals, or on the chord against the length across the collapsed vertex's fan) made the
//! right maps more precise but moved the failures about and broke the noisy scans:
//! docs/hierarchy-benchmark.md, "Session 49".
//!
//! **Known limit: detail where the fine mesh is dense.** The length term makes the coarse
//! mesh even, so a region the scan samples densely because it has detail (the KIDS poses'
//! hands: 46 fine vertices per coarse one, 10 on average) keeps as few coarse vertices as a
//! smooth one; the hands become mittens, and the maps place their points a few units off on every
//! pose (most of the 1.9 points between the coarse mesh and full resolution there). Weighting
//! the length term by the fine density closes the gap on the scans but thins out the sparse
//! legs of generated shapes: measured and not kept, docs/hierarchy-benchmark.md, "Session 51".
//! Weighting only the denser side, with the target grown by what the weights add, gains
//! within the benchmark's noise and fails the thin-legs test in one of two builds of the
//! same weights ("Session 52").

use crate::mesh::sorted_edge_keys;
use crate::mesh::vec3::{cross, dot, sub};
use crate::mesh::Mesh;

/// Weight of the edge-length term `β |e|⁴` added to the quadric cost of a collapse (on the
/// unit-area mesh the detection works on). The quadric alone removes flat regions first and
/// leaves their triangles long and thin, the coarse mesh's density following curvature; the
/// term makes the coarse mesh more even, which the sampling and maps expect. Measured with a
/// first version of this simplification (one global heap, strictly cheapest first) on the 5
/// KIDS poses at 60k and the 13 SHREC'16 kids at 11–12k vertices, best acc@0.05: β = 0 gave
/// KIDS 78.7%; 0.1: 91.6 / SHREC'16 45.6%; 1: 90.5 / 50.8%; 3: 87.8 / 45.5%; 10: 90.3 /
/// 58.1%; 100: 85.0% KIDS (full resolution: 85.2 / 54.6%). The SHREC'16 figures swing by
/// several points between neighbouring values (on those glued, self-touching scans the result
/// is fragile whatever the coarse mesh), which is why meshes of their size are not simplified
/// ([`super::MARGIN`]). With the rounds below, β = 10: KIDS 87.5%. Measured again with the
/// pipeline of 0.7.13 (docs/hierarchy-benchmark.md, "Session 52"; 12 seeds): β = 3 gains on
/// the noisy KIDS copies (94.07 → 97.32%) and the clean poses (96.17 → 97.29%) but loses the
/// first map of the SHREC'16 copies (−1.4 and −3.0 points: a front↔back flip ranked above the
/// mirror); β = 1 and 30 are within noise. Kept in session 53 (0.7.14) with the judge's band
/// factor squared, which ranks the mirror first again ([`crate::judge`]): 12 seeds, KIDS
/// 96.17 → 97.30%, noisy copies 94.07 / 93.86 → 97.32 / 97.03%; SHREC'16 subdivided (seeds 0,
/// 10) 70.67 / 69.27 → 73.57 / 72.62% (docs/hierarchy-benchmark.md, "Session 53").
const LENGTH_WEIGHT: f64 = 3.0;

/// The live faces around a vertex, inline (one cache line, no pointer to chase: the costing
/// touches every neighbour's list).
type Faces = smallvec::SmallVec<[u32; 10]>;

/// Vertices per block of the first costing (between progress calls).
const BLOCK: usize = 1 << 17;

/// A symmetric 4 × 4 quadric, upper triangle: `a b c d / e f g / h i / j`.
#[derive(Clone, Copy, Default)]
struct Quadric([f64; 10]);

impl Quadric {
    /// `w · p pᵀ` for the plane `n·x + d = 0`.
    fn plane(n: [f64; 3], d: f64, w: f64) -> Quadric {
        let [a, b, c] = n;
        Quadric([a * a * w, a * b * w, a * c * w, a * d * w, b * b * w, b * c * w, b * d * w, c * c * w, c * d * w, d * d * w])
    }
    fn add(&mut self, o: &Quadric) {
        for (x, y) in self.0.iter_mut().zip(&o.0) {
            *x += y;
        }
    }
    /// `[x 1] Q [x 1]ᵀ`.
    fn eval(&self, p: [f64; 3]) -> f64 {
        let q = &self.0;
        let [x, y, z] = p;
        q[0] * x * x + 2.0 * q[1] * x * y + 2.0 * q[2] * x * z + 2.0 * q[3] * x + q[4] * y * y + 2.0 * q[5] * y * z + 2.0 * q[6] * y + q[7] * z * z + 2.0 * q[8] * z + q[9]
    }
}

/// The sorted neighbours of `v` through its live faces.
fn neighbours(v: usize, around: &[Faces], faces: &[[u32; 3]], out: &mut Vec<u32>) {
    out.clear();
    for &f in &around[v] {
        for &w in &faces[f as usize] {
            if w as usize != v {
                out.push(w);
            }
        }
    }
    out.sort_unstable();
    out.dedup();
}

/// The faces on an edge (at most two: edges at an unlocked vertex are manifold) and their
/// apexes.
#[derive(Clone, Copy)]
struct Edge {
    faces: [u32; 2],
    apexes: [u32; 2],
    count: usize,
}

impl Edge {
    fn faces(&self) -> &[u32] {
        &self.faces[..self.count]
    }
    fn apexes(&self) -> &[u32] {
        &self.apexes[..self.count]
    }
}

/// Whether `u` (unlocked) can collapse into `v` (see the module docs): the faces on the edge
/// and their apexes if so. `nu` and `nv` are the sorted neighbours of `u` and `v`
/// ([`neighbours`]).
#[allow(clippy::too_many_arguments)]
fn collapsible(u: usize, v: usize, p: &[[f64; 3]], around: &[Faces], faces: &[[u32; 3]], boundary: &[bool], nu: &[u32], nv: &[u32]) -> Option<Edge> {
    let mut e = Edge { faces: [0; 2], apexes: [0; 2], count: 0 };
    for &f in &around[u] {
        let t = faces[f as usize];
        if t.contains(&(v as u32)) {
            if e.count == 2 {
                return None;
            }
            e.faces[e.count] = f;
            e.apexes[e.count] = t.iter().copied().find(|&w| w as usize != u && w as usize != v).expect("a triangle has three vertices");
            e.count += 1;
        }
    }
    if e.count == 0 || (boundary[u] && !(e.count == 1 && boundary[v])) {
        return None;
    }
    // Link condition.
    let common = nu.iter().filter(|w| nv.binary_search(w).is_ok()).count();
    if common != e.count {
        return None;
    }
    // No face folds over or collapses.
    let folds = around[u].iter().filter(|f| !e.faces().contains(f)).any(|&f| {
        let t = faces[f as usize];
        let at = |w: u32| if w as usize == u { p[v] } else { p[w as usize] };
        let old = cross(sub(p[t[1] as usize], p[t[0] as usize]), sub(p[t[2] as usize], p[t[0] as usize]));
        let new = cross(sub(at(t[1]), at(t[0])), sub(at(t[2]), at(t[0])));
        let (lo, ln) = (dot(old, old).sqrt(), dot(new, new).sqrt());
        ln <= 1e-12 * lo.max(f64::MIN_POSITIVE) || dot(old, new) <= 0.0
    });
    (!folds).then_some(e)
}

/// The sorted neighbours of a vertex, inline (most have 5–8; a coarse vertex up to a dozen).
type Neighbours = smallvec::SmallVec<[u32; 12]>;

/// The simplified mesh: `kept[i]` is the fine vertex of coarse vertex `i`; `triangles` index
/// the coarse vertices.
pub struct Simplified {
    /// Fine vertex of each coarse vertex, ascending.
    pub kept: Vec<usize>,
    /// Coarse triangles.
    pub triangles: Vec<[u32; 3]>,
}

/// Collapses edges of `mesh` until at most `target` vertices remain or no collapse is allowed.
pub fn simplify(mesh: &Mesh, target: usize) -> Simplified {
    simplify_with_progress(mesh, target, &mut |_| true).expect("never cancelled")
}

/// [`simplify`], calling `progress(fraction of the collapses done)` after every round;
/// `None` when it returns `false` (cancelled).
pub fn simplify_with_progress(mesh: &Mesh, target: usize, progress: &mut dyn FnMut(f64) -> bool) -> Option<Simplified> {
    let n = mesh.num_vertices();
    let p = &mesh.vertices;
    let mut faces: Vec<[u32; 3]> = mesh.triangles.clone();
    let mut face_alive = vec![true; faces.len()];
    let mut around: Vec<Faces> = vec![Faces::new(); n];
    for (f, t) in faces.iter().enumerate() {
        for &v in t {
            around[v as usize].push(f as u32);
        }
    }
    if !progress(0.0) {
        return None;
    }
    // Edge use counts: boundary (1) and non-manifold (> 2) edges.
    let edges = sorted_edge_keys(&faces);
    let mut boundary = vec![false; n];
    let mut locked = vec![false; n];
    let mut quadric = vec![Quadric::default(); n];
    for t in &faces {
        let nv = cross(sub(p[t[1] as usize], p[t[0] as usize]), sub(p[t[2] as usize], p[t[0] as usize]));
        let twice = dot(nv, nv).sqrt();
        if twice <= 0.0 {
            continue;
        }
        let nn = nv.map(|x| x / twice);
        let q = Quadric::plane(nn, -dot(nn, p[t[0] as usize]), 0.5 * twice);
        for &v in t {
            quadric[v as usize].add(&q);
        }
    }
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j] == edges[i] {
            j += 1;
        }
        let (a, b) = ((edges[i] >> 32) as usize, (edges[i] & 0xffff_ffff) as usize);
        match j - i {
            1 => {
                boundary[a] = true;
                boundary[b] = true;
                // A plane through the edge, perpendicular to its face, keeps the boundary.
                if let Some(&f) = around[a].iter().find(|&&f| faces[f as usize].contains(&(b as u32))) {
                    let t = faces[f as usize];
                    let nf = cross(sub(p[t[1] as usize], p[t[0] as usize]), sub(p[t[2] as usize], p[t[0] as usize]));
                    let e = sub(p[b], p[a]);
                    let m = cross(e, nf);
                    let len = dot(m, m).sqrt();
                    if len > 0.0 {
                        let m = m.map(|x| x / len);
                        let q = Quadric::plane(m, -dot(m, p[a]), 10.0 * dot(e, e));
                        quadric[a].add(&q);
                        quadric[b].add(&q);
                    }
                }
            }
            2 => {}
            _ => {
                locked[a] = true;
                locked[b] = true;
            }
        }
        i = j;
    }

    let mut alive = n;
    let mut vertex_alive = vec![true; n];
    let beta = LENGTH_WEIGHT;
    let cost = |u: usize, v: usize, quadric: &[Quadric]| {
        let mut q = quadric[u];
        q.add(&quadric[v]);
        let e = sub(p[u], p[v]);
        q.eval(p[v]).max(0.0) + beta * dot(e, e) * dot(e, e)
    };
    let mut nv = Vec::new();
    let mut touched = vec![false; n];
    let mut marked: Vec<usize> = Vec::new();
    // Rounds of independent collapses: every vertex's cheapest allowed collapse, and the
    // cheapest quarter of them applied where no earlier collapse of the round touched the
    // neighbourhood (their costs are then current). A global heap gives the strict order one
    // collapse at a time, but its stale entries and cache misses made it superlinear (4.8 s
    // at 239k vertices against 0.44 s at 60k); rounds cost a pass and a selection each. A
    // vertex's best is its cheapest *allowed* collapse: with only the cheapest, a vertex whose
    // cheapest was refused stayed stuck (KIDS 60k 68.8% against 87.5%).
    // Each vertex's cheapest allowed collapse (as a heap of every edge would pop it), recomputed
    // only where a collapse changed the neighbourhood (`dirty`).
    let best_of = |u: usize, around: &[Faces], faces: &[[u32; 3]], nbrs: &[Neighbours], quadric: &[Quadric], boundary: &[bool], options: &mut Vec<(u64, u32)>| -> (u64, u32) {
        let nb = &nbrs[u];
        options.clear();
        options.extend(nb.iter().map(|&v| (cost(u, v as usize, quadric).to_bits(), v)));
        options.sort_unstable();
        options.iter().copied().find(|&(_, v)| collapsible(u, v as usize, p, around, faces, boundary, nb, &nbrs[v as usize]).is_some()).unwrap_or((u64::MAX, u as u32))
    };
    // In blocks, with a progress call after each (a second or two on 10⁶ vertices in all).
    if !progress(0.0) {
        return None;
    }
    // Every vertex's sorted neighbours, kept current through the collapses (the costing reads
    // them for every vertex it visits: walking the faces each time took a fifth of the time).
    let lists = crate::parallel::chunks(n, |range| {
        let mut out = Vec::new();
        range
            .map(|v| {
                neighbours(v, &around, &faces, &mut out);
                Neighbours::from_slice(&out)
            })
            .collect::<Vec<_>>()
    });
    let mut nbrs: Vec<Neighbours> = lists.into_iter().flatten().collect();
    if !progress(0.0) {
        return None;
    }
    let mut best: Vec<(u64, u32)> = Vec::with_capacity(n);
    for block in (0..n).step_by(BLOCK) {
        let block = block..(block + BLOCK).min(n);
        let found = crate::parallel::chunks(block.len(), |range| {
            let mut options = Vec::new();
            range.map(|i| best_of(block.start + i, &around, &faces, &nbrs, &quadric, &boundary, &mut options)).collect::<Vec<_>>()
        });
        best.extend(found.into_iter().flatten());
        if !progress(0.0) {
            return None;
        }
    }
    let mut live: Vec<u32> = (0..n as u32).filter(|&u| !locked[u as usize]).collect();
    let mut dirty: Vec<usize> = Vec::new();
    while alive > target {
        // Independent per vertex: on all cores.
        let fresh = crate::parallel::chunks(dirty.len(), |range| {
            let mut options = Vec::new();
            range.filter(|&i| vertex_alive[dirty[i]]).map(|i| (dirty[i], best_of(dirty[i], &around, &faces, &nbrs, &quadric, &boundary, &mut options))).collect::<Vec<_>>()
        });
        for (u, b) in fresh.into_iter().flatten() {
            best[u] = b;
        }
        dirty.clear();
        live.retain(|&u| vertex_alive[u as usize] && !locked[u as usize]);
        let mut candidates: Vec<(u64, u32, u32)> = live.iter().map(|&u| (best[u as usize].0, u, best[u as usize].1)).filter(|c| c.0 != u64::MAX).collect();
        let quarter = candidates.len().div_ceil(4);
        if quarter == 0 {
            break;
        }
        candidates.select_nth_unstable(quarter - 1);
        candidates.truncate(quarter);
        // The round's collapses in vertex order (memory order: on a million vertices the cost
        // order's random access made a collapse three times as slow). Not a spatial order:
        // renumbering the vertices along a Morton curve and collapsing in that order made the
        // sweep's conflicts lose systematically on one side, and the coarse meshes of the noisy
        // 41k quadrupeds lost their left–right mirror (first in 2 of 4 seeds against 4 of 4,
        // missing in one). The Morton numbering for memory alone, collapses still in input
        // order, gained nothing measurable at 10⁶ vertices (3 interleaved runs each).
        candidates.sort_unstable_by_key(|c| c.1);
        let mut removed = 0;
        for &(_, u, v) in &candidates[..quarter] {
            if alive == target {
                break;
            }
            let (u, v) = (u as usize, v as usize);
            if touched[u] || touched[v] {
                continue;
            }
            let Some(edge) = collapsible(u, v, p, &around, &faces, &boundary, &nbrs[u], &nbrs[v]) else { continue };
            let (shared, apexes) = (edge.faces(), edge.apexes());
            // Collapse u into v.
            for &f in shared {
                face_alive[f as usize] = false;
            }
            let moved: Vec<u32> = around[u].iter().copied().filter(|&f| face_alive[f as usize]).collect();
            for &f in &moved {
                for w in faces[f as usize].iter_mut() {
                    if *w as usize == u {
                        *w = v as u32;
                    }
                }
            }
            around[u].clear();
            around[v].retain(|f| face_alive[*f as usize]);
            around[v].extend(moved);
            for &a in apexes {
                around[a as usize].retain(|f| face_alive[*f as usize]);
            }
            vertex_alive[u] = false;
            alive -= 1;
            removed += 1;
            let q = quadric[u];
            quadric[v].add(&q);
            locked[v] |= locked[u];
            boundary[v] |= boundary[u];
            // The neighbour lists, without walking faces: `v` has both lists' vertices but
            // `u` and `v`; every other neighbour of `u` sees `v` instead of `u`. An apex keeps
            // `v` unless the collapse folded away an ear of the boundary (the apex's edges to
            // `u` and `v` both boundary edges: no live face of `v` holds it any more).
            let nu = std::mem::take(&mut nbrs[u]);
            nv.clear();
            let (mut i, mut j) = (0, 0);
            let old = &nbrs[v];
            while i < nu.len() || j < old.len() {
                let x = match (nu.get(i), old.get(j)) {
                    (Some(&a), Some(&b)) if a == b => {
                        i += 1;
                        j += 1;
                        a
                    }
                    (Some(&a), Some(&b)) if a < b => {
                        i += 1;
                        a
                    }
                    (Some(&a), None) => {
                        i += 1;
                        a
                    }
                    (_, Some(&b)) => {
                        j += 1;
                        b
                    }
                    (None, None) => unreachable!("the loop ends first"),
                };
                if x as usize != u && x as usize != v {
                    nv.push(x);
                }
            }
            for &x in apexes {
                let x = x as usize;
                nbrs[x].retain(|w| *w as usize != u);
                if boundary[x] && !around[v].iter().any(|&f| faces[f as usize].contains(&(x as u32))) {
                    nbrs[x].retain(|w| *w as usize != v);
                    nv.retain(|w| *w as usize != x);
                }
            }
            for &w in &nu {
                let w = w as usize;
                if w == v || apexes.contains(&(w as u32)) {
                    continue;
                }
                let list = &mut nbrs[w];
                list.retain(|x| *x as usize != u);
                if let Err(at) = list.binary_search(&(v as u32)) {
                    list.insert(at, v as u32);
                }
            }
            nbrs[v] = Neighbours::from_slice(&nv);
            // The changed neighbourhood waits for the next round.
            for &w in nv.iter().chain(std::iter::once(&(v as u32))).chain(std::iter::once(&(u as u32))) {
                if !std::mem::replace(&mut touched[w as usize], true) {
                    marked.push(w as usize);
                }
            }
        }
        for w in marked.drain(..) {
            touched[w] = false;
            dirty.push(w);
        }
        // In memory order: the next round's costing reads each vertex's neighbourhood.
        dirty.sort_unstable();
        if removed == 0 {
            break;
        }
        if !progress((n - alive) as f64 / (n - target.min(n)).max(1) as f64) {
            return None;
        }
    }
    let kept: Vec<usize> = (0..n).filter(|&v| vertex_alive[v]).collect();
    let mut index = vec![u32::MAX; n];
    for (i, &v) in kept.iter().enumerate() {
        index[v] = i as u32;
    }
    let triangles = faces.iter().zip(&face_alive).filter(|(_, &a)| a).map(|(t, _)| t.map(|v| index[v as usize])).collect();
    Some(Simplified { kept, triangles })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{self, Pose};

    /// A closed surface stays closed and keeps its genus (Euler characteristic), reaches the
    /// target, and every coarse triangle uses coarse vertices.
    #[test]
    fn a_closed_surface_keeps_its_topology() {
        for mesh in [shapes::quadruped(5, Pose::Walking, 0.0, 0).mesh, shapes::torus_of_revolution(120, 60, 0.3)] {
            let chi = |v: usize, t: &[[u32; 3]]| {
                let mut e = sorted_edge_keys(t);
                e.dedup();
                v as i64 - e.len() as i64 + t.len() as i64
            };
            let before = chi(mesh.num_vertices(), &mesh.triangles);
            let s = simplify(&mesh, 1500);
            assert_eq!(s.kept.len(), 1500);
            assert!(s.triangles.iter().flatten().all(|&i| (i as usize) < s.kept.len()));
            assert_eq!(chi(s.kept.len(), &s.triangles), before);
            // Every edge still has two faces (closed, manifold).
            let e = sorted_edge_keys(&s.triangles);
            assert!(e.chunks(2).all(|c| c.len() == 2 && c[0] == c[1]) && e.windows(3).all(|w| !(w[0] == w[1] && w[1] == w[2])));
        }
    }
}
