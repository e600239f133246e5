//! Memory-bound kernels of the Lanczos iteration on interleaved blocks.
//!
//! A Lanczos block of [`LANES`] vectors is stored *interleaved*: row `r` is one `[f64; 8]`
//! holding entry `r` of every vector. The products with the tall basis `V` (`n × m`,
//! column-major) are then broadcast-multiply-adds on whole rows, with no packing: `V` streams
//! from memory once per product while a band of the block stays in L1. faer's gemm on these
//! shapes (`m × 8 × n` with `n ≫ m`) packs a copy of every band of `V` first; that copy was a
//! third of the orthogonalisation time.
//!
//! The kernels run inside [`dispatch`], which compiles them for the best instruction set the
//! CPU has (pulp: AVX2 with FMA on x86-64; pulp's AVX-512 path was measured slower on this
//! AMD EPYC) with explicit SIMD on the 8-wide rows: left to itself, LLVM vectorised the update
//! over rows instead and gathered the interleaved entries (2× slower). Products use fused
//! multiply-adds, so results differ at rounding level between instruction sets, never more.

use faer::MatRef;

/// Vectors per interleaved block (the Lanczos block size).
pub const LANES: usize = 8;

/// One row of an interleaved block.
pub type Lanes = [f64; LANES];

/// Rows per band: a band of the block (band × 64 bytes) stays in L1.
const BAND: usize = 1024;

/// A kernel body to compile for the best SIMD instruction set (see [`dispatch`]). Implementations
/// must mark `run` `#[inline(always)]`, so that it is compiled inside pulp's target-feature
/// function; a closure is not enough (it stays a separate function compiled for baseline SSE2,
/// measured 2× slower).
pub trait Kernel {
    type Output;
    fn run<S: pulp::Simd>(self, simd: S) -> Self::Output;
}

struct Simd<K>(K);

impl<K: Kernel> pulp::WithSimd for Simd<K> {
    type Output = K::Output;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) -> K::Output {
        self.0.run(simd)
    }
}

/// Runs `kernel` compiled for the best SIMD instruction set of this CPU (detected once: some
/// kernels, like a descent's squared distance, are called millions of times).
pub fn dispatch<K: Kernel>(kernel: K) -> K::Output {
    static ARCH: std::sync::OnceLock<pulp::Arch> = std::sync::OnceLock::new();
    ARCH.get_or_init(pulp::Arch::new).dispatch(Simd(kernel))
}

/// A row as SIMD vectors of `S` (two `f64x4` with AVX2).
#[inline(always)]
pub fn vecs<S: pulp::Simd>(x: &Lanes) -> &[S::f64s] {
    S::as_simd_f64s(x).0
}

/// A row as mutable SIMD vectors of `S`.
#[inline(always)]
pub fn vecs_mut<S: pulp::Simd>(x: &mut Lanes) -> &mut [S::f64s] {
    S::as_mut_simd_f64s(x).0
}

/// Column `j` of a column-major matrix as a slice.
fn column<'a>(v: MatRef<'a, f64>, j: usize) -> &'a [f64] {
    v.col(j).try_as_col_major().expect("column-major basis").as_slice()
}

/// `c[i] += Σ_r v[r, i] · w[r]` for every column `i` of `v` (`c` has `v.ncols()` rows).
pub fn gram(v: MatRef<'_, f64>, w: &[Lanes], c: &mut [Lanes]) {
    let (n, m) = (v.nrows(), v.ncols());
    assert!(w.len() == n && c.len() == m);
    let cols: Vec<&[f64]> = (0..m).map(|j| column(v, j)).collect();
    dispatch(Gram { cols: &cols, w, c })
}

struct Gram<'a> {
    cols: &'a [&'a [f64]],
    w: &'a [Lanes],
    c: &'a mut [Lanes],
}

impl Kernel for Gram<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) {
        let Gram { cols, w, c } = self;
        let (n, m) = (w.len(), cols.len());
        let mut r0 = 0;
        while r0 < n {
            let r1 = (r0 + BAND).min(n);
            let wb = &w[r0..r1];
            let mut i = 0;
            while i + 4 <= m {
                let (a, b, cc, d) = (&cols[i][r0..r1], &cols[i + 1][r0..r1], &cols[i + 2][r0..r1], &cols[i + 3][r0..r1]);
                let (mut acc0, mut acc1, mut acc2, mut acc3) = ([0.0; LANES], [0.0; LANES], [0.0; LANES], [0.0; LANES]);
                {
                    let (v0, v1, v2, v3) = (vecs_mut::<S>(&mut acc0), vecs_mut::<S>(&mut acc1), vecs_mut::<S>(&mut acc2), vecs_mut::<S>(&mut acc3));
                    for r in 0..wb.len() {
                        let x = vecs::<S>(&wb[r]);
                        let (sa, sb, sc, sd) = (simd.splat_f64s(a[r]), simd.splat_f64s(b[r]), simd.splat_f64s(cc[r]), simd.splat_f64s(d[r]));
                        for q in 0..x.len() {
                            v0[q] = simd.mul_add_f64s(sa, x[q], v0[q]);
                            v1[q] = simd.mul_add_f64s(sb, x[q], v1[q]);
                            v2[q] = simd.mul_add_f64s(sc, x[q], v2[q]);
                            v3[q] = simd.mul_add_f64s(sd, x[q], v3[q]);
                        }
                    }
                }
                add(&mut c[i], &acc0);
                add(&mut c[i + 1], &acc1);
                add(&mut c[i + 2], &acc2);
                add(&mut c[i + 3], &acc3);
                i += 4;
            }
            while i < m {
                let a = &cols[i][r0..r1];
                let mut acc = [0.0; LANES];
                {
                    let v = vecs_mut::<S>(&mut acc);
                    for (x, &s) in wb.iter().zip(a) {
                        let (x, s) = (vecs::<S>(x), simd.splat_f64s(s));
                        for q in 0..x.len() {
                            v[q] = simd.mul_add_f64s(s, x[q], v[q]);
                        }
                    }
                }
                add(&mut c[i], &acc);
                i += 1;
            }
            r0 = r1;
        }
    }
}

/// `w[r] −= Σ_i v[r, i] · c[i]`.
pub fn update(v: MatRef<'_, f64>, w: &mut [Lanes], c: &[Lanes]) {
    let (n, m) = (v.nrows(), v.ncols());
    assert!(w.len() == n && c.len() == m);
    let cols: Vec<&[f64]> = (0..m).map(|j| column(v, j)).collect();
    dispatch(Update { cols: &cols, w, c })
}

struct Update<'a> {
    cols: &'a [&'a [f64]],
    w: &'a mut [Lanes],
    c: &'a [Lanes],
}

impl Kernel for Update<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) {
        let Update { cols, w, c } = self;
        let (n, m) = (w.len(), cols.len());
        let mut r0 = 0;
        while r0 < n {
            let r1 = (r0 + BAND).min(n);
            let wb = &mut w[r0..r1];
            let mut i = 0;
            while i + 4 <= m {
                let (a, b, cc, d) = (&cols[i][r0..r1], &cols[i + 1][r0..r1], &cols[i + 2][r0..r1], &cols[i + 3][r0..r1]);
                let (c0, c1, c2, c3) = (vecs::<S>(&c[i]), vecs::<S>(&c[i + 1]), vecs::<S>(&c[i + 2]), vecs::<S>(&c[i + 3]));
                for r in 0..wb.len() {
                    let y = vecs_mut::<S>(&mut wb[r]);
                    let (sa, sb, sc, sd) = (simd.splat_f64s(-a[r]), simd.splat_f64s(-b[r]), simd.splat_f64s(-cc[r]), simd.splat_f64s(-d[r]));
                    for q in 0..y.len() {
                        let u = simd.mul_add_f64s(sa, c0[q], y[q]);
                        let v = simd.mul_f64s(sb, c1[q]);
                        let u = simd.mul_add_f64s(sc, c2[q], u);
                        let v = simd.mul_add_f64s(sd, c3[q], v);
                        y[q] = simd.add_f64s(u, v);
                    }
                }
                i += 4;
            }
            while i < m {
                let a = &cols[i][r0..r1];
                let ci = vecs::<S>(&c[i]);
                for (y, &s) in wb.iter_mut().zip(a) {
                    let (y, s) = (vecs_mut::<S>(y), simd.splat_f64s(-s));
                    for q in 0..y.len() {
                        y[q] = simd.mul_add_f64s(s, ci[q], y[q]);
                    }
                }
                i += 1;
            }
            r0 = r1;
        }
    }
}

/// `y += x`, lane-wise.
#[inline(always)]
fn add(y: &mut Lanes, x: &Lanes) {
    for t in 0..LANES {
        y[t] += x[t];
    }
}

/// `out[r] = mass[r] · w[r]`.
pub fn scale_rows(w: &[Lanes], mass: &[f64], out: &mut Vec<Lanes>) {
    out.clear();
    out.extend(w.iter().zip(mass).map(|(x, &m)| x.map(|v| m * v)));
}

/// `out = L x` for a symmetric CSC `L` and an interleaved block `x` (row `i` of `L` is its
/// column `i`, so each entry is one gathered row and one multiply-add).
pub fn sparse_mul(lap: &sprs::CsMat<f64>, x: &[Lanes], out: &mut Vec<Lanes>) {
    out.clear();
    out.resize(x.len(), [0.0; LANES]);
    dispatch(SparseMul { lap, x, out })
}

struct SparseMul<'a> {
    lap: &'a sprs::CsMat<f64>,
    x: &'a [Lanes],
    out: &'a mut [Lanes],
}

impl Kernel for SparseMul<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) {
        for (o, col) in self.out.iter_mut().zip(self.lap.outer_iterator()) {
            let o = vecs_mut::<S>(o);
            for (j, &a) in col.iter() {
                let (xj, a) = (vecs::<S>(&self.x[j]), simd.splat_f64s(a));
                for q in 0..o.len() {
                    o[q] = simd.mul_add_f64s(a, xj[q], o[q]);
                }
            }
        }
    }
}

/// `Σ_r mass[r] · x[r] · y[r]`, lane-wise.
pub fn m_dots(x: &[Lanes], y: &[Lanes], mass: &[f64]) -> Lanes {
    dispatch(MDots { x, y, mass })
}

struct MDots<'a> {
    x: &'a [Lanes],
    y: &'a [Lanes],
    mass: &'a [f64],
}

impl Kernel for MDots<'_> {
    type Output = Lanes;
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) -> Lanes {
        let mut acc = [0.0; LANES];
        {
            let v = vecs_mut::<S>(&mut acc);
            for ((a, b), &m) in self.x.iter().zip(self.y).zip(self.mass) {
                let (a, b, m) = (vecs::<S>(a), vecs::<S>(b), simd.splat_f64s(m));
                for q in 0..v.len() {
                    v[q] = simd.mul_add_f64s(simd.mul_f64s(m, a[q]), b[q], v[q]);
                }
            }
        }
        acc
    }
}

/// The M-Gram matrix of an interleaved block: `g[s][t] = Σ_r mass[r] · w[r][s] · w[r][t]`.
pub fn m_gram(w: &[Lanes], mass: &[f64]) -> [Lanes; LANES] {
    dispatch(MGram { w, mass })
}

struct MGram<'a> {
    w: &'a [Lanes],
    mass: &'a [f64],
}

impl Kernel for MGram<'_> {
    type Output = [Lanes; LANES];
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) -> [Lanes; LANES] {
        let mut g = [[0.0; LANES]; LANES];
        for (row, &m) in self.w.iter().zip(self.mass) {
            let x = vecs::<S>(row);
            for (s, gs) in g.iter_mut().enumerate() {
                let (gs, a) = (vecs_mut::<S>(gs), simd.splat_f64s(m * row[s]));
                for q in 0..gs.len() {
                    gs[q] = simd.mul_add_f64s(a, x[q], gs[q]);
                }
            }
        }
        g
    }
}

/// Every row `w[r] ← Σ_s w[r][s] · cols[s]` (a small matrix applied to each row).
pub fn mul_rows(w: &mut [Lanes], cols: &[Lanes]) {
    assert_eq!(cols.len(), LANES);
    dispatch(MulRows { w, cols })
}

struct MulRows<'a> {
    w: &'a mut [Lanes],
    cols: &'a [Lanes],
}

impl Kernel for MulRows<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: pulp::Simd>(self, simd: S) {
        for row in self.w.iter_mut() {
            let mut out = [0.0; LANES];
            {
                let o = vecs_mut::<S>(&mut out);
                for (s, col) in self.cols.iter().enumerate() {
                    let (c, a) = (vecs::<S>(col), simd.splat_f64s(row[s]));
                    for q in 0..o.len() {
                        o[q] = simd.mul_add_f64s(a, c[q], o[q]);
                    }
                }
            }
            *row = out;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    #[test]
    fn gram_and_update_match_dense_products() {
        let (n, m) = (1000, 11);
        let v = Mat::<f64>::from_fn(n, m, |i, j| ((i * 31 + j * 17) % 23) as f64 / 23.0 - 0.5);
        let w: Vec<Lanes> = (0..n).map(|i| std::array::from_fn(|t| ((i * 7 + t * 5) % 13) as f64 / 13.0 - 0.5)).collect();
        let mut c = vec![[0.0; LANES]; m];
        gram(v.as_ref(), &w, &mut c);
        for j in 0..m {
            for t in 0..LANES {
                let want: f64 = (0..n).map(|i| v[(i, j)] * w[i][t]).sum();
                assert!((c[j][t] - want).abs() < 1e-10 * n as f64, "gram ({j}, {t})");
            }
        }
        let mut u = w.clone();
        update(v.as_ref(), &mut u, &c);
        for i in (0..n).step_by(37) {
            for t in 0..LANES {
                let want = w[i][t] - (0..m).map(|j| v[(i, j)] * c[j][t]).sum::<f64>();
                assert!((u[i][t] - want).abs() < 1e-9, "update ({i}, {t})");
            }
        }
    }
}

