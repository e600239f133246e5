//! ZoomOut refinement (Melzi, Ren, Rodolà, Sharma, Wonka & Ovsjanikov 2019) of a self-map.
//!
//! Alternates between the functional map of the pull-back in the first `k` eigenfunctions,
//! $$C_k = \Phi_k^\top M\, \Phi_k \circ T \quad(\Phi_k(Tv) \approx \Phi_k(v)\, C_k),$$
//! and the point map it induces, `T(v) = argmin_w ‖Φ_k(w) − Φ_k(v) C_k‖`, while `k` grows from
//! `k0` to `k1`. Spectral upsampling turns an approximately right map into a smooth,
//! vertex-accurate one. The nearest neighbour is found by greedy descent on the mesh graph from
//! the current image (the map moves little per step), so an iteration costs O(n·k) instead of
//! the O(n²·k) of an exhaustive search. On meshes above 2 × [`SUBSAMPLE`] vertices the intermediate
//! iterations estimate `C_k` from, and move, an evenly strided subset of that many vertices only
//! (the functional map is a low-dimensional object); the last iteration maps every vertex,
//! breadth-first from the subset so each vertex starts from its neighbours' images.

use faer::{Accum, Mat, MatRef, Par};

use crate::spectral::Eigenbasis;

/// Vertices used by the intermediate ZoomOut iterations on meshes of more than twice as many
/// (on the 10k-vertex quadrupeds a 5k subset cost about one point of acc@0.05, so meshes of
/// up to 12k vertices are refined whole).
pub const SUBSAMPLE: usize = 6000;

/// What every ZoomOut on one basis shares: Φ row-major (a vertex's coefficients contiguous,
/// for the descents), the vertex subset of the intermediate iterations, and `M Φ` on it
/// (scaled to the whole surface). Built once per maps stage ([`super::Context::zoom`]) instead
/// of once per call (the copies were a third of a single polishing step).
pub struct ZoomBasis {
    /// `(n · stride)` row-major Φ, the first `stride` eigenfunctions.
    rows: Vec<f64>,
    stride: usize,
    /// The subset (all vertices on small meshes).
    sub: Vec<usize>,
    /// `(|sub|, stride)` `scale · m_v Φ(v)`.
    mphi: Mat<f64>,
}

impl ZoomBasis {
    /// The shared data for ZoomOuts up to `kmax` eigenfunctions (capped at the basis size).
    pub fn new(basis: &Eigenbasis, kmax: usize) -> Self {
        let n = basis.num_vertices();
        let stride = kmax.min(basis.k()).max(1);
        let rows = super::row_major(basis.evecs.as_ref(), stride);
        let step = if n > 2 * SUBSAMPLE { n.div_ceil(SUBSAMPLE) } else { 1 };
        let sub: Vec<usize> = (0..n).step_by(step).collect();
        let scale = basis.mass.iter().sum::<f64>() / sub.iter().map(|&v| basis.mass[v]).sum::<f64>();
        let mut mphi = Mat::<f64>::zeros(sub.len(), stride);
        for i in 0..stride {
            let col = basis.evecs.col(i);
            for (r, x) in mphi.col_as_slice_mut(i).iter_mut().enumerate() {
                let v = sub[r];
                *x = scale * basis.mass[v] * col[v];
            }
        }
        ZoomBasis { rows, stride, sub, mphi }
    }

    /// Largest ZoomOut size this serves.
    pub fn size(&self) -> usize {
        self.stride
    }
}

/// Refines `map` (every entry ≥ 0) in place over `k0 < … < k1` eigenfunctions, growing by
/// `max(step, 15%)` per iteration.
pub fn zoomout(basis: &Eigenbasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k0: usize, k1: usize, step: usize) {
    zoomout_with(&ZoomBasis::new(basis, k1), adjacency, map, k0, k1, step)
}

/// [`zoomout`] with the shared data of a basis (`k1` is capped at its size).
pub fn zoomout_with(zb: &ZoomBasis, adjacency: &(Vec<usize>, Vec<u32>), map: &mut [usize], k0: usize, k1: usize, step: usize) {
    zoomout_between(zb, adjacency, zb, adjacency, map, k0, k1, step)
}

/// ZoomOut of a map from one shape (`src`: its subset, `M Φ` and graph) to another (`dst`:
/// the nearest neighbours among its vertices, descents on its graph), `Φ_dst(T v) ≈ Φ_src(v)
/// C_k` with `C_k = (M Φ_src,k)ᵀ Φ_dst,k[T]`; the two are one for a self-map. `k1` is capped at
/// the smaller basis.
#[allow(clippy::too_many_arguments)]
pub fn zoomout_between(
    src: &ZoomBasis,
    src_adjacency: &(Vec<usize>, Vec<u32>),
    dst: &ZoomBasis,
    adjacency: &(Vec<usize>, Vec<u32>),
    map: &mut [usize],
    k0: usize,
    k1: usize,
    step: usize,
) {
    let zb = src;
    let n = zb.rows.len() / zb.stride;
    let kmax = k1.min(zb.stride).min(dst.stride);
    let mut k = k0.min(kmax).max(1);
    let (from, stride, sub, mphi) = (&zb.rows, zb.stride, &zb.sub, &zb.mphi);
    let (rows, dst_stride) = (&dst.rows, dst.stride);
    let dist = |w: usize, target: &[f64]| -> f64 { super::squared_distance(&rows[w * dst_stride..w * dst_stride + target.len()], target) };
    // Targets Φ_k(v) C_k of the vertices `vs`, one gemm: column r of `(C_kᵀ Φ_k(vs)ᵀ)` is the
    // target of vs[r], contiguous for the descent. Column v of the row-major Φ read as a
    // `(stride, n)` column-major matrix is Φ(v): all vertices need no copy.
    let all_phi = MatRef::from_column_major_slice_with_stride(from, stride, n, stride);
    let product = |c: &Mat<f64>, phi: MatRef<'_, f64>| -> Mat<f64> {
        let mut t = Mat::<f64>::zeros(c.nrows(), phi.ncols());
        faer::linalg::matmul::matmul(t.as_mut(), Accum::Replace, c.transpose(), phi, 1.0, Par::Seq);
        t
    };
    // The targets of the vertices `range` (no copy), or of the vertices `vs` (gathered).
    let targets_in = |range: std::ops::Range<usize>, c: &Mat<f64>| product(c, all_phi.subrows(0, c.nrows()).subcols(range.start, range.len()));
    let targets_of = |vs: &[usize], c: &Mat<f64>| product(c, Mat::<f64>::from_fn(c.nrows(), vs.len(), |p, r| from[vs[r] * stride + p]).as_ref());
    let whole = sub.len() == n;
    // C is summed over two fixed halves of the subset, one per core (the same sums on one
    // core: the result does not depend on the number of cores); it was a third of a ZoomOut.
    let half = sub.len() / 2;
    let (mut gather_a, mut gather_b) = (vec![0.0; half * kmax], vec![0.0; (sub.len() - half) * kmax]);
    loop {
        // C_k = (M Φ_k)ᵀ Φ_k[T] over the subset; Φ_k[T] gathered a row (one vertex's
        // coefficients, contiguous) at a time.
        let part = |r0: usize, part: &[usize], gather: &mut [f64]| -> Mat<f64> {
            for (r, &v) in part.iter().enumerate() {
                let w = map[v];
                gather[r * k..(r + 1) * k].copy_from_slice(&rows[w * dst_stride..w * dst_stride + k]);
            }
            let phit = MatRef::from_row_major_slice(&gather[..part.len() * k], part.len(), k);
            let mut c = Mat::<f64>::zeros(k, k);
            faer::linalg::matmul::matmul(c.as_mut(), Accum::Replace, mphi.as_ref().subrows(r0, part.len()).subcols(0, k).transpose(), phit, 1.0, Par::Seq);
            c
        };
        let (ca, cb) = crate::parallel::join(|| part(0, &sub[..half], &mut gather_a), || part(half, &sub[half..], &mut gather_b));
        let c = ca + cb;
        // The subset's vertices move independently: a range of them per core, each with its
        // own targets (a column of the product is the same alone or among others).
        let moved = crate::parallel::chunks(sub.len(), |range| {
            let t = if whole { targets_in(range.clone(), &c) } else { targets_of(&sub[range.clone()], &c) };
            let starts: Vec<usize> = range.map(|r| map[sub[r]]).collect();
            crate::spectral::kernels::dispatch(Descents { adjacency, rows, stride: dst_stride, targets: &t, starts: &starts })
        });
        for (&v, w) in sub.iter().zip(moved.into_iter().flatten()) {
            map[v] = w;
        }
        if k >= kmax && sub.len() < n {
            // Last iteration on a large mesh: every other vertex, breadth-first from the subset.
            let t = targets_in(0..n, &c);
            super::breadth_first(src_adjacency, sub, |v, u| {
                let target = t.col_as_slice(u);
                let start = if dist(map[v], target) < dist(map[u], target) { map[v] } else { map[u] };
                map[u] = super::greedy_descent(adjacency, start, |w| dist(w, target)).0;
            });
        }
        if k >= kmax {
            break;
        }
        // Grow by `step` or 15%, whichever is more: the cost per step is O(n·k²).
        k = (k + step).max(k * 23 / 20).min(kmax);
    }
}

/// Greedy descents of the point map, one per column of `targets` (`Φ_k(v) C_k`, `k` its rows)
/// from `starts`, in one SIMD dispatch (see [`super::squared_distance_in`]); the same
/// results as [`super::greedy_descent`] on [`super::squared_distance`].
struct Descents<'a> {
    adjacency: &'a (Vec<usize>, Vec<u32>),
    rows: &'a [f64],
    stride: usize,
    targets: &'a Mat<f64>,
    starts: &'a [usize],
}

impl crate::spectral::kernels::Kernel for Descents<'_> {
    type Output = Vec<usize>;
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) -> Vec<usize> {
        // The descent of `super::greedy_descent` written out: a closure would not be compiled
        // with the kernel's instruction set.
        let (rows, stride) = (self.rows, self.stride);
        let (off, nbr) = (&self.adjacency.0, &self.adjacency.1);
        let k = self.targets.nrows();
        let mut out = Vec::with_capacity(self.starts.len());
        for (i, &start) in self.starts.iter().enumerate() {
            let target = self.targets.col_as_slice(i);
            let mut w = start;
            let mut c = super::squared_distance_in(simd, &rows[w * stride..w * stride + k], target);
            loop {
                let mut best = (w, c);
                for &u in &nbr[off[w]..off[w + 1]] {
                    let u = u as usize;
                    let cu = super::squared_distance_in(simd, &rows[u * stride..u * stride + k], target);
                    if cu < best.1 {
                        best = (u, cu);
                    }
                }
                if best.0 == w {
                    break;
                }
                (w, c) = best;
            }
            out.push(w);
        }
        out
    }
}
