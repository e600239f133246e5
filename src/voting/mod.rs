//! Correspondence space voting (paper §4): from farthest-point samples to candidate symmetries,
//! each a set of *directed* sample correspondences `x → x'` that support one another.
//!
//! 1. **Good voters** (§4.2): sample pairs whose wave kernel signatures are close,
//!    `δ_WKS(x, x′) ≤ T_WKS`, with `T_WKS` the `wks_quantile` quantile of all pair distances
//!    (scale- and resolution-free). `δ_WKS` is the root-mean-square over energies of the relative
//!    difference `(a_e − b_e)/(a_e + b_e)`. Self-pairs `x → x` (the fixed points of a reflection,
//!    on its mirror plane) neither vote nor join candidates: they are consistent with the
//!    identity, which always fits, and with a sampling-sized ε they flood candidates and pull
//!    them towards it (seen on TOSCA's cat: 40 of 64 pairs). Samples on a mirror plane get their
//!    fixed-point images in map extraction instead.
//! 2. **Votes** (§4.3): a directed pair `x → x′` gets a vote from a good voter `y → y′` (both
//!    orientations of `{y, y′}` are tried) when `|d(x,y) − d(x′,y′)| < ε`; for involutions the
//!    paper's second criterion `|d(x,y′) − d(x′,y)| < ε` is also required. `ε = eps · diameter`,
//!    at least the sampling radius (the mirror image of a sample is only near a sample).
//! 3. **Candidates** (beyond the paper, which stops at "symmetric pairs"): pairs that support
//!    each other form one symmetry. For each well-voted seed pair and each of a few far-apart
//!    second pairs consistent with it (two correspondences fix a surface isometry's
//!    orientation), the candidate grows greedily by the pair consistent with the most members
//!    (at least `consistency` of them), keeping the correspondence injective. Candidates that
//!    map most shared samples to within ε of each other are the same symmetry: they are merged
//!    and their support counted.
//!
//! **Rotations** (beyond the paper): the second criterion holds only for involutions; a rotation
//! of an n-fold shape satisfies the first but not the second. Growth therefore uses the first
//! criterion alone, so directed pairs of a rotation (`arm₀ → arm₁ → arm₂ …`) form their own
//! candidate; whether a candidate is an involution is decided later from its map
//! (`characterize`), not assumed here.

use faer::Mat;

use crate::distance::BiharmonicEmbedding;
use crate::sampling::Samples;

/// Parameters of [`vote`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct VotingParams {
    /// Good voters: pairs whose WKS distance is below this quantile of all sample pairs (default 0.2).
    pub wks_quantile: f64,
    /// Distance tolerance ε relative to the biharmonic diameter (default 0.04).
    pub eps: f64,
    /// A pair joins a candidate when consistent with at least this fraction of its members (default 0.85).
    pub consistency: f64,
    /// Candidates smaller than this many correspondences are dropped (default 4).
    pub min_pairs: usize,
    /// Second pairs tried per seed (default 6).
    pub branches: usize,
}

impl Default for VotingParams {
    fn default() -> Self {
        VotingParams { wks_quantile: 0.2, eps: 0.04, consistency: 0.85, min_pairs: 4, branches: 6 }
    }
}

/// A candidate symmetry: directed correspondences between samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// `(source, target)` indices into the sample list, sources distinct, targets distinct.
    pub pairs: Vec<(usize, usize)>,
    /// Votes of the seed pair.
    pub votes: usize,
    /// How many seeds grew into this candidate.
    pub support: usize,
}

/// What voting saw.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct VotingInfo {
    /// Good-voter directed pairs (without self-pairs).
    pub good_pairs: usize,
    /// The absolute ε used.
    pub eps: f64,
    /// The biharmonic diameter of the samples.
    pub diameter: f64,
    /// Candidates before merging.
    pub grown: usize,
}

/// Relative WKS distance between two descriptors (RMS of `(a−b)/(a+b)` over energies), in [0, 1].
pub fn wks_distance(a: &[f64], b: &[f64]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| {
            let d = x.abs() + y.abs();
            if d > 0.0 {
                ((x - y) / d).powi(2)
            } else {
                0.0
            }
        })
        .sum();
    (s / a.len().max(1) as f64).sqrt()
}

/// At most this many good pairs vote (those with the closest signatures): 12,000 pairs cost two
/// relations of 18 MB each and about a second; the defaults (64 samples, quantile 0.2) give
/// about 800.
pub const MAX_GOOD_PAIRS: usize = 12_000;

/// At most this many seeds grow candidates (twice the default 64 samples).
pub const MAX_SEEDS: usize = 128;

/// Runs correspondence space voting on the samples; `wks` is `(n, E)`.
pub fn vote(
    emb: &BiharmonicEmbedding,
    wks: &Mat<f64>,
    samples: &Samples,
    params: &VotingParams,
) -> (Vec<Candidate>, VotingInfo, Mat<f64>) {
    let s = &samples.vertices;
    let ns = s.len();
    let dist = emb.between(s, s);
    let diameter = (0..ns).flat_map(|i| (0..ns).map(move |j| (i, j))).map(|(i, j)| dist[(i, j)]).fold(0.0, f64::max);
    let cover = samples.radius.iter().cloned().fold(0.0, f64::max);
    let eps = (params.eps * diameter).max(cover);
    let desc: Vec<Vec<f64>> = s.iter().map(|&v| (0..wks.ncols()).map(|e| wks[(v, e)]).collect()).collect();
    let mut wd = Mat::<f64>::zeros(ns, ns);
    let mut all = Vec::with_capacity(ns * ns / 2);
    for i in 0..ns {
        for j in 0..i {
            let d = wks_distance(&desc[i], &desc[j]);
            wd[(i, j)] = d;
            wd[(j, i)] = d;
            all.push(d);
        }
    }
    all.sort_by(|a, b| a.total_cmp(b));
    let t_wks = if all.is_empty() { 0.0 } else { all[((params.wks_quantile * all.len() as f64) as usize).min(all.len() - 1)] };
    // Directed good pairs, without self-pairs (see the module docs).
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for i in 0..ns {
        for j in 0..ns {
            if i != j && wd[(i, j)] <= t_wks {
                pairs.push((i, j));
            }
        }
    }
    // A budget on good pairs: the relations below are quadratic in their number, in bits and
    // in time (issue 16, item 13: 1000 samples at quantile 0.2, or a 162-vertex sphere at
    // quantile 1, ran for minutes and tens of gigabytes). Past it the pairs with the closest
    // signatures are kept, as a lower quantile would.
    if pairs.len() > MAX_GOOD_PAIRS {
        let mut by_signature = pairs.clone();
        by_signature.sort_by(|a, b| wd[(a.0, a.1)].total_cmp(&wd[(b.0, b.1)]).then(a.cmp(b)));
        by_signature.truncate(MAX_GOOD_PAIRS);
        by_signature.sort();
        pairs = by_signature;
    }
    let good_pairs = pairs.len();
    let consistent = |p: (usize, usize), q: (usize, usize)| (dist[(p.0, q.0)] - dist[(p.1, q.1)]).abs() < eps;
    // The paper's second criterion: for an involution T (T x = x', T y = y'), d(x, y') = d(x', y).
    let consistent_involution =
        |p: (usize, usize), q: (usize, usize)| consistent(p, q) && (dist[(p.0, q.1)] - dist[(p.1, q.0)]).abs() < eps;
    // Both relations between all good pairs, as bit rows: growth only adds rows.
    let general = BitRows::new(good_pairs, |a, b| consistent(pairs[a], pairs[b]));
    let involutive = BitRows::new(good_pairs, |a, b| consistent_involution(pairs[a], pairs[b]));
    // Votes (paper §4.3): both criteria, both orientations of the voter.
    // A voter's count is independent of the others': ranges of them on all cores.
    let votes: Vec<usize> = crate::parallel::chunks(good_pairs, |range| {
        pairs[range]
            .iter()
            .map(|&(x, xp)| {
                pairs[..good_pairs]
                    .iter()
                    .filter(|&&(y, yp)| (y, yp) != (x, xp) && y != x)
                    .filter(|&&(y, yp)| {
                        let c1 = (dist[(x, y)] - dist[(xp, yp)]).abs() < eps;
                        let c2 = (dist[(x, yp)] - dist[(xp, y)]).abs() < eps;
                        c1 && c2
                    })
                    .count()
            })
            .collect::<Vec<usize>>()
    })
    .concat();
    let mut order: Vec<usize> = (0..good_pairs).collect();
    order.sort_by(|&a, &b| votes[b].cmp(&votes[a]).then(wd[(pairs[a].0, pairs[a].1)].total_cmp(&wd[(pairs[b].0, pairs[b].1)])));

    // The good pairs by source and by target (growth marks out the pairs of a used sample).
    let (mut by_source, mut by_target) = (vec![Vec::new(); ns], vec![Vec::new(); ns]);
    for (r, &(x, y)) in pairs.iter().enumerate() {
        by_source[x].push(r as u32);
        by_target[y].push(r as u32);
    }
    // Each seed grows independently: seeds are grown on all cores, collected in seed order.
    // At most 2 per sample, and at most MAX_SEEDS (the default's 2 × 64): each seed's growth
    // scans every good pair, so more samples must not mean quadratically more growth.
    let max_seeds = (2 * ns).min(MAX_SEEDS);
    let seeds: Vec<usize> = order.iter().copied().take(max_seeds).take_while(|&pi| votes[pi] > 0).collect();
    let grow_seed = |&pi: &usize| -> Vec<Candidate> {
        let mut grown = Vec::new();
        let p = pairs[pi];
        // Second pairs: consistent with p, far from it (orientation), best voted, distinct targets.
        let mut seconds: Vec<usize> = (0..good_pairs)
            .filter(|&qi| {
                let q = pairs[qi];
                q.0 != p.0 && q.1 != p.1 && consistent(p, q) && dist[(p.0, q.0)] > 0.25 * diameter
            })
            .collect();
        seconds.sort_by(|&a, &b| votes[b].cmp(&votes[a]));
        let mut used_targets = Vec::new();
        let mut tried = 0;
        for qi in seconds {
            if tried == params.branches {
                break;
            }
            let q = pairs[qi];
            if used_targets.iter().any(|&(a, b)| a == q.0 && b == q.1) {
                continue;
            }
            used_targets.push(q);
            tried += 1;
            // Grow twice: as an involution (both criteria; mirrors) and as a general isometry
            // (first criterion; rotations). Identical results are merged below.
            for involution in [true, false] {
                let members = if involution {
                    if !involutive.get(pi, qi) {
                        continue;
                    }
                    grow(&pairs, vec![pi, qi], &involutive, params.consistency, &by_source, &by_target)
                } else {
                    grow(&pairs, vec![pi, qi], &general, params.consistency, &by_source, &by_target)
                };
                if members.len() >= params.min_pairs {
                    let mut sorted = members;
                    sorted.sort();
                    grown.push(Candidate { pairs: sorted, votes: votes[pi], support: 1 });
                }
            }
        }
        grown
    };
    let grown: Vec<Candidate> = crate::parallel::map(&seeds, grow_seed).into_iter().flatten().collect();
    let grown_count = grown.len();
    let merged = merge(grown, Some(&dist), eps);
    (merged, VotingInfo { good_pairs, eps, diameter, grown: grown_count }, dist)
}

/// A symmetric relation on `len` items as rows of bits.
struct BitRows {
    words: usize,
    bits: Vec<u64>,
}

impl BitRows {
    fn new(len: usize, related: impl Fn(usize, usize) -> bool) -> BitRows {
        let words = len.div_ceil(64);
        let mut bits = vec![0u64; len * words];
        for a in 0..len {
            for b in 0..=a {
                if related(a, b) {
                    bits[a * words + b / 64] |= 1 << (b % 64);
                    bits[b * words + a / 64] |= 1 << (a % 64);
                }
            }
        }
        BitRows { words, bits }
    }

    fn get(&self, a: usize, b: usize) -> bool {
        self.bits[a * self.words + b / 64] >> (b % 64) & 1 == 1
    }

    /// Adds 1 to `count[b]` for every `b` related to `a`.
    fn add_row(&self, a: usize, count: &mut [i32]) {
        for (w, &word) in self.bits[a * self.words..(a + 1) * self.words].iter().enumerate() {
            let mut x = word;
            while x != 0 {
                count[w * 64 + x.trailing_zeros() as usize] += 1;
                x &= x - 1;
            }
        }
    }
}

/// Greedy growth of an injective set of mutually consistent directed pairs (indices into
/// `pairs`; `consistent` relates them): the pair consistent with the most members (the first
/// such pair on ties) joins while it is consistent with at least `fraction` of them.
/// `by_source[x]` and `by_target[x]` list the pairs with source or target `x`: a member's
/// source and target are used, so those pairs are marked out (their count goes far below zero,
/// where additions cannot bring it back) and the choice is a plain first-maximum scan.
fn grow(pairs: &[(usize, usize)], mut members: Vec<usize>, consistent: &BitRows, fraction: f64, by_source: &[Vec<u32>], by_target: &[Vec<u32>]) -> Vec<(usize, usize)> {
    const OUT: i32 = i32::MIN / 2;
    // count[r] = members consistent with pair r (OUT and below: r is out).
    let mut count = vec![0i32; pairs.len()];
    let join = |m: usize, count: &mut [i32]| {
        consistent.add_row(m, count);
        for &r in by_source[pairs[m].0].iter().chain(&by_target[pairs[m].1]) {
            count[r as usize] = OUT;
        }
    };
    for &m in &members {
        join(m, &mut count);
    }
    loop {
        let need = ((fraction * members.len() as f64).ceil() as i32).max(2);
        let (mut bi, mut bc) = (0usize, OUT);
        for (ri, &c) in count.iter().enumerate() {
            if c > bc {
                (bi, bc) = (ri, c);
            }
        }
        if bc < need {
            break;
        }
        members.push(bi);
        join(bi, &mut count);
    }
    members.into_iter().map(|m| pairs[m]).collect()
}

/// Merges candidates that are the same symmetry: on the sources both map, at least half of
/// the targets lie within `eps` of each other (or, with no distances, are equal). The larger
/// candidate (then the better voted) is kept and counts the other's support.
fn merge(mut grown: Vec<Candidate>, dist: Option<&Mat<f64>>, eps: f64) -> Vec<Candidate> {
    grown.sort_by(|a, b| b.pairs.len().cmp(&a.pairs.len()).then(b.votes.cmp(&a.votes)).then(a.pairs.cmp(&b.pairs)));
    let mut out: Vec<Candidate> = Vec::new();
    'next: for c in grown {
        for o in out.iter_mut() {
            let mut shared = 0;
            let mut agree = 0;
            for &(s, t) in &c.pairs {
                if let Some(&(_, u)) = o.pairs.iter().find(|p| p.0 == s) {
                    shared += 1;
                    let close = match dist {
                        Some(d) => d[(t, u)] < eps,
                        None => t == u,
                    };
                    if close {
                        agree += 1;
                    }
                }
            }
            if shared * 2 >= c.pairs.len() && agree * 2 >= shared {
                o.support += c.support;
                continue 'next;
            }
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Settings at the ends of their ranges (every sample pair a good voter) vote with at
    /// most MAX_GOOD_PAIRS pairs, those with the closest signatures (issue 16, item 13: such
    /// settings ran for minutes), and still find the sphere's symmetries.
    #[test]
    fn the_good_pairs_are_capped_at_the_ends_of_the_ranges() {
        let mesh = crate::shapes::icosphere(2);
        let basis = crate::spectral::Eigenbasis::compute(&mesh, &crate::spectral::EigenParams { k: 40, ..Default::default() }).unwrap();
        let emb = crate::distance::biharmonic(&basis);
        let wks = crate::descriptors::wks(&basis, &Default::default());
        let samples = crate::sampling::farthest_point(&emb, mesh.num_vertices(), 0);
        let params = VotingParams { wks_quantile: 1.0, eps: 0.5, ..Default::default() };
        let (candidates, info, _) = vote(&emb, &wks, &samples, &params);
        let n = mesh.num_vertices();
        assert!(n * (n - 1) > MAX_GOOD_PAIRS, "the case must exceed the budget");
        assert_eq!(info.good_pairs, MAX_GOOD_PAIRS);
        assert!(!candidates.is_empty());
    }

    #[test]
    fn wks_distance_is_relative_and_bounded() {
        let a = [1.0, 2.0, 3.0];
        assert_eq!(wks_distance(&a, &a), 0.0);
        let b = [2.0, 4.0, 6.0];
        let c = [20.0, 40.0, 60.0];
        assert!((wks_distance(&a, &b) - 1.0 / 3.0).abs() < 1e-12);
        assert!((wks_distance(&c, &c.map(|x| 2.0 * x)) - wks_distance(&a, &b)).abs() < 1e-12);
        assert!(wks_distance(&a, &[0.0; 3]) <= 1.0);
    }

    #[test]
    fn merge_keeps_distinct_and_absorbs_contained() {
        let c = |pairs: Vec<(usize, usize)>| Candidate { pairs, votes: 1, support: 1 };
        let big = c(vec![(0, 1), (1, 0), (2, 3), (3, 2), (4, 4), (5, 6), (6, 5), (7, 7), (8, 9), (9, 8)]);
        let sub = c(vec![(0, 1), (1, 0), (2, 3), (3, 2)]);
        let other = c(vec![(0, 2), (2, 4), (4, 0), (1, 3)]);
        let merged = merge(vec![sub, big.clone(), other.clone()], None, 0.0);
        assert_eq!(merged.len(), 2);
        assert_eq!(merged[0].pairs, big.pairs);
        assert_eq!(merged[0].support, 2);
        assert_eq!(merged[1].pairs, other.pairs);
    }
}
