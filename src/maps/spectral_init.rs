//! A low-frequency functional map fitted to correspondences, as the start of ZoomOut.
//!
//! For an intrinsic isometry `T` and eigenfunctions with simple eigenvalues, `φ_i∘T = ±φ_i`
//! (Ovsjanikov, Sun & Guibas 2008); inside a cluster of (nearly) repeated eigenvalues `T` acts
//! by an orthogonal block. So the pull-back's functional map in the first `k0` eigenfunctions is
//! block-diagonal by eigenvalue cluster, `C₀ = diag(B_1, …)`, and each block is the orthogonal
//! Procrustes solution on the correspondences `a_j → b_j`:
//! $$B = \arg\min_{B^\top B = I} \sum_j \lVert \Phi_{blk}(b_j) - \Phi_{blk}(a_j)\,B\rVert^2 = UV^\top,\quad U\Sigma V^\top = \Phi_{blk}(A)^\top \Phi_{blk}(B).$$
//! (A 1 × 1 block is the sign of `Σ_j φ_i(a_j) φ_i(b_j)`.) Correspondences from voting are
//! partly wrong, so the fit is repeated on the 70% of pairs it explains best. The point map of
//! `C₀` — nearest neighbour of `Φ_k0(v) C₀` among `Φ_k0(w)`, coarse over a vertex subset then by
//! descent on the mesh — starts ZoomOut. Low frequencies are the ones a pose changes least,
//! which makes this start robust on posed shapes where distance profiles are not.
//!
//! **Reading a point map from `C`** ([`Conversion`]). For an orthogonal `C` (this module's
//! `C₀`, ZoomOut's maps) the two ways agree: `‖Φ(w)Cᵀ − Φ(v)‖ = ‖Φ(w) − Φ(v)C‖`. A functional
//! map solved from an energy ([`super::orientation`]) is not orthogonal: on posed shapes it
//! shrinks the directions its terms pin only weakly (on FAUST's posed people the
//! orientation-reversing map's diagonal holds −0.25…0.08 where a mirror has −1, `‖C‖_F ≈ 3`
//! against `√30`). Then `Φ(v)C` has (almost) no component in those directions, and its
//! nearest `Φ(w)` is a vertex where they vanish: 36–318 distinct images for 5,000 vertices
//! on the FAUST shapes looked at. Transporting the candidates instead (`Φ(w)Cᵀ`, pyFM's
//! default conversion) shrinks the candidates alike, so the weak directions stop deciding:
//! the same `C` on FAUST's tr_reg_004 gave 0.57 acc@0.05 (0.02 read the other way).

use faer::Mat;

use crate::spectral::Eigenbasis;

/// Relative eigenvalue gap below which eigenpairs form one cluster (block).
const CLUSTER_GAP: f64 = 0.05;

/// `(k0, k0)` block-diagonal orthogonal `C₀` fitted to `pairs` (vertex indices).
pub fn fit_blocks(basis: &Eigenbasis, pairs: &[(usize, usize)], k0: usize) -> Mat<f64> {
    let k0 = k0.min(basis.k());
    let mut c = Mat::<f64>::zeros(k0, k0);
    c[(0, 0)] = 1.0; // the constant function maps to itself
    let mut i = 1;
    while i < k0 {
        let mut j = i + 1;
        while j < k0 && (basis.evals[j] - basis.evals[j - 1]) < CLUSTER_GAP * basis.evals[j] {
            j += 1;
        }
        let d = j - i;
        // M = Φ_blk(A)ᵀ Φ_blk(B).
        let m = Mat::<f64>::from_fn(d, d, |r, s| pairs.iter().map(|&(a, b)| basis.evecs[(a, i + r)] * basis.evecs[(b, i + s)]).sum());
        if d == 1 {
            c[(i, i)] = if m[(0, 0)] >= 0.0 { 1.0 } else { -1.0 };
        } else if let Ok(svd) = m.svd() {
            let r = svd.U() * svd.V().transpose();
            for p in 0..d {
                for q in 0..d {
                    c[(i + p, i + q)] = r[(p, q)];
                }
            }
        } else {
            for p in 0..d {
                c[(i + p, i + p)] = 1.0;
            }
        }
        i = j;
    }
    c
}

/// `C₀` fitted twice: on all pairs, then on the 70% with the smallest residual
/// `‖Φ(b) − Φ(a) C₀‖`.
pub fn robust_fit(basis: &Eigenbasis, pairs: &[(usize, usize)], k0: usize) -> Mat<f64> {
    let c = fit_blocks(basis, pairs, k0);
    let k0 = c.nrows();
    let mut scored: Vec<(f64, (usize, usize))> = pairs
        .iter()
        .map(|&(a, b)| {
            let mut r = 0.0;
            for q in 0..k0 {
                let mut pred = 0.0;
                for p in 0..k0 {
                    pred += basis.evecs[(a, p)] * c[(p, q)];
                }
                r += (basis.evecs[(b, q)] - pred).powi(2);
            }
            (r, (a, b))
        })
        .collect();
    scored.sort_by(|x, y| x.0.total_cmp(&y.0));
    let keep: Vec<(usize, usize)> = scored[..((0.7 * scored.len() as f64).ceil() as usize).max(1)].iter().map(|x| x.1).collect();
    fit_blocks(basis, &keep, k0)
}

/// How a point map is read from a functional map `C` with `Φ_dst(T v) ≈ Φ_src(v) C` (see the
/// module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conversion {
    /// `T(v)` is the vertex `w` whose `Φ_dst(w)` is nearest to `Φ_src(v) C` (the adjoint):
    /// for an orthogonal `C`.
    Adjoint,
    /// `T(v)` is the vertex `w` whose `Φ_dst(w) Cᵀ` is nearest to `Φ_src(v)` (pyFM's default):
    /// for a `C` solved from an energy, which shrinks weakly pinned directions.
    Transported,
}

/// Point map of `C₀` (read as `conversion` says: for every vertex, the vertex nearest to it
/// in the spectral embedding). Vertices are visited breadth-first; each starts from the best
/// image among its mapped neighbours (or, for the first of each component of the visit, a
/// coarse search over `search`) and descends on the mesh graph.
pub fn point_map(basis: &Eigenbasis, adjacency: &(Vec<usize>, Vec<u32>), c: &Mat<f64>, search: &[usize], conversion: Conversion) -> Vec<usize> {
    point_map_between(basis, adjacency, basis, adjacency, c, search, conversion)
}

/// [`point_map`] from one shape (`src`, visited breadth-first on its graph) to another (`dst`,
/// `Φ_dst(T v) ≈ Φ_src(v) C₀`; the descents on its graph, the coarse search over its vertices
/// `search`).
pub fn point_map_between(
    src: &Eigenbasis,
    src_adjacency: &(Vec<usize>, Vec<u32>),
    dst: &Eigenbasis,
    dst_adjacency: &(Vec<usize>, Vec<u32>),
    c: &Mat<f64>,
    search: &[usize],
    conversion: Conversion,
) -> Vec<usize> {
    let n = src.num_vertices();
    let k0 = c.nrows();
    let from = super::row_major(src.evecs.as_ref(), k0);
    // The candidates' embedding: `Φ_dst` (shared with the source's on one shape), or
    // `Φ_dst Cᵀ`; both row-major.
    let rows = match conversion {
        Conversion::Adjoint if std::ptr::eq(src, dst) => None,
        Conversion::Adjoint => Some(super::row_major(dst.evecs.as_ref(), k0)),
        Conversion::Transported => {
            let plain = super::row_major(dst.evecs.as_ref(), k0);
            let mut pushed = vec![0.0; plain.len()];
            for (out, row) in pushed.chunks_exact_mut(k0).zip(plain.chunks_exact(k0)) {
                for (p, o) in out.iter_mut().enumerate() {
                    *o = (0..k0).map(|q| row[q] * c[(p, q)]).sum();
                }
            }
            Some(pushed)
        }
    };
    let rows = rows.as_deref().unwrap_or(&from);
    let dist = |w: usize, t: &[f64]| -> f64 { super::squared_distance(&rows[w * k0..(w + 1) * k0], t) };
    let nbrs = |w: usize| &src_adjacency.1[src_adjacency.0[w]..src_adjacency.0[w + 1]];
    let mut target = vec![0.0; k0];
    let mut map = vec![usize::MAX; n];
    let mut queued = vec![false; n];
    let mut queue = std::collections::VecDeque::new();
    for root in 0..n {
        if queued[root] {
            continue;
        }
        queued[root] = true;
        queue.push_back(root);
        while let Some(v) = queue.pop_front() {
            match conversion {
                Conversion::Adjoint => {
                    for (q, t) in target.iter_mut().enumerate() {
                        *t = (0..k0).map(|p| from[v * k0 + p] * c[(p, q)]).sum();
                    }
                }
                Conversion::Transported => target.copy_from_slice(&from[v * k0..(v + 1) * k0]),
            }
            let mut w = usize::MAX;
            let mut best = f64::INFINITY;
            // Start from the best image among the already mapped neighbours.
            for &u in nbrs(v) {
                let m = map[u as usize];
                if m != usize::MAX {
                    let d = dist(m, &target);
                    if d < best {
                        (w, best) = (m, d);
                    }
                }
            }
            if w == usize::MAX {
                w = search.iter().copied().min_by(|&a, &b| dist(a, &target).total_cmp(&dist(b, &target))).unwrap_or(if v < dst.num_vertices() { v } else { 0 });
            }
            let w = super::greedy_descent(dst_adjacency, w, |u| dist(u, &target)).0;
            map[v] = w;
            for &u in nbrs(v) {
                if !queued[u as usize] {
                    queued[u as usize] = true;
                    queue.push_back(u as usize);
                }
            }
        }
    }
    map
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::vec3::{norm, sub};
    use crate::shapes;
    use crate::spectral::EigenParams;

    /// A mirror's functional map with its antisymmetric directions shrunk tenfold (what an
    /// energy's solution does on a posed shape, see the module docs): read by the adjoint, the
    /// map collapses towards the vertices where those directions vanish (measured: 77% of the
    /// vertices within 0.05·√area of their mirror, half as many distinct images); with the
    /// candidates transported, it is still the mirror (100%, 95% distinct).
    #[test]
    fn a_shrunk_functional_map_is_read_with_the_candidates_transported() {
        let c = shapes::quadruped(4, shapes::Pose::Rest, 0.0, 0);
        let mesh = &c.mesh;
        let k = 30;
        let basis = Eigenbasis::compute(mesh, &EigenParams { k, ..Default::default() }).unwrap();
        let mirror: Vec<i64> = c.mirror.iter().map(|&w| w as i64).collect();
        let exact = crate::maps::functional_map(&basis, &mirror, k);
        // Shrink every column whose diagonal entry is negative (an antisymmetric eigenfunction).
        let shrunk = Mat::<f64>::from_fn(k, k, |i, j| if exact[(j, j)] < 0.0 { 0.1 * exact[(i, j)] } else { exact[(i, j)] });
        assert!((0..k).filter(|&j| exact[(j, j)] < -0.5).count() >= 5, "the mirror has antisymmetric eigenfunctions");
        let n = mesh.num_vertices();
        let search: Vec<usize> = (0..n).step_by(5).collect();
        let scale = mesh.area().sqrt();
        let dist = |a: usize, b: usize| norm(sub(mesh.vertices[a], mesh.vertices[b])) / scale;
        let judge = |conversion: Conversion| {
            let image = point_map(&basis, &mesh.adjacency(), &shrunk, &search, conversion);
            let near = (0..n).filter(|&v| dist(image[v], c.mirror[v] as usize) < 0.05).count() as f64 / n as f64;
            let mut distinct = image.clone();
            distinct.sort_unstable();
            distinct.dedup();
            (near, distinct.len() as f64 / n as f64)
        };
        let (adjoint, adjoint_images) = judge(Conversion::Adjoint);
        let (transported, transported_images) = judge(Conversion::Transported);
        // Both readings agree on the exact (orthogonal) map.
        let exact_image = point_map(&basis, &mesh.adjacency(), &exact, &search, Conversion::Transported);
        let exact_near = (0..n).filter(|&v| dist(exact_image[v], c.mirror[v] as usize) < 0.1).count() as f64 / n as f64;
        assert!(exact_near > 0.9, "exact map read transported: {exact_near}");
        assert!(transported > 0.95, "transported: {transported} near the mirror");
        assert!(adjoint < 0.85 && adjoint_images < 0.7 * transported_images, "adjoint: {adjoint} near the mirror, {adjoint_images} distinct images (transported {transported_images})");
    }
}
