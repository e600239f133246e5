//! Grouping symmetries (paper §6–7: clustering points of the symmetry space).
//!
//! Each symmetry becomes a feature vector — complexity, inverse order, region fraction,
//! displacement — standardized per feature; k-means (k-means++ seeding from a fixed seed, Lloyd
//! iterations) groups them. The number of groups is given, or chosen automatically as the `k`
//! in `1..=min(6, count)` with the best mean silhouette, where `k = 1` wins unless some `k ≥ 2`
//! reaches a silhouette of 0.5 (well separated groups). Written here rather than taken from a
//! crate: the candidates (`linfa-clustering`, `kmeans`) bring ndarray/rayon stacks for a
//! 40-line algorithm on at most a few dozen points.

/// Group label (0-based) of each feature vector; deterministic.
pub fn cluster(features: &[Vec<f64>], groups: Option<usize>) -> Vec<usize> {
    let n = features.len();
    if n <= 1 {
        return vec![0; n];
    }
    let dim = features[0].len();
    // Standardize.
    let mut x = features.to_vec();
    for d in 0..dim {
        let mean = x.iter().map(|f| f[d]).sum::<f64>() / n as f64;
        let sd = (x.iter().map(|f| (f[d] - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        for f in &mut x {
            f[d] = if sd > 1e-12 { (f[d] - mean) / sd } else { 0.0 };
        }
    }
    if let Some(k) = groups {
        return kmeans(&x, k.clamp(1, n));
    }
    let mut best = (vec![0; n], 0.5);
    for k in 2..=6.min(n - 1) {
        let labels = kmeans(&x, k);
        let s = silhouette(&x, &labels, k);
        if s > best.1 {
            best = (labels, s);
        }
    }
    best.0
}

fn d2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum()
}

fn kmeans(x: &[Vec<f64>], k: usize) -> Vec<usize> {
    let n = x.len();
    // k-means++ with deterministic choices: the first centre is point 0, then the farthest
    // point by D² (ties by index): deterministic and good for tiny sets.
    let mut centres = vec![x[0].clone()];
    while centres.len() < k {
        let far = (0..n).max_by(|&a, &b| {
            let da = centres.iter().map(|c| d2(&x[a], c)).fold(f64::INFINITY, f64::min);
            let db = centres.iter().map(|c| d2(&x[b], c)).fold(f64::INFINITY, f64::min);
            da.total_cmp(&db).then(b.cmp(&a))
        });
        centres.push(x[far.unwrap()].clone());
    }
    let mut labels = vec![0; n];
    for _ in 0..100 {
        let new: Vec<usize> = x
            .iter()
            .map(|p| (0..k).min_by(|&a, &b| d2(p, &centres[a]).total_cmp(&d2(p, &centres[b]))).unwrap())
            .collect();
        let changed = new != labels;
        labels = new;
        for (c, centre) in centres.iter_mut().enumerate() {
            let members: Vec<&Vec<f64>> = x.iter().zip(&labels).filter(|(_, &l)| l == c).map(|(p, _)| p).collect();
            if !members.is_empty() {
                for d in 0..centre.len() {
                    centre[d] = members.iter().map(|p| p[d]).sum::<f64>() / members.len() as f64;
                }
            }
        }
        if !changed {
            break;
        }
    }
    // Relabel by first appearance so labels are canonical.
    let mut map = vec![usize::MAX; k];
    let mut next = 0;
    labels
        .iter()
        .map(|&l| {
            if map[l] == usize::MAX {
                map[l] = next;
                next += 1;
            }
            map[l]
        })
        .collect()
}

fn silhouette(x: &[Vec<f64>], labels: &[usize], k: usize) -> f64 {
    let n = x.len();
    let mut total = 0.0;
    for i in 0..n {
        let mut sums = vec![0.0; k];
        let mut counts = vec![0usize; k];
        for j in 0..n {
            if i != j {
                sums[labels[j]] += d2(&x[i], &x[j]).sqrt();
                counts[labels[j]] += 1;
            }
        }
        if counts[labels[i]] == 0 {
            continue; // singleton: silhouette 0
        }
        let a = sums[labels[i]] / counts[labels[i]] as f64;
        let b = (0..k).filter(|&c| c != labels[i] && counts[c] > 0).map(|c| sums[c] / counts[c] as f64).fold(f64::INFINITY, f64::min);
        if b.is_finite() {
            total += (b - a) / a.max(b).max(1e-300);
        }
    }
    total / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_separated_groups_and_one_group_for_a_blob() {
        let mut f = Vec::new();
        for i in 0..5 {
            f.push(vec![0.0 + 0.01 * i as f64, 1.0]);
            f.push(vec![5.0 + 0.01 * i as f64, 1.0]);
        }
        let l = cluster(&f, None);
        assert_eq!(l.len(), 10);
        for i in 0..5 {
            assert_eq!(l[2 * i], l[0]);
            assert_eq!(l[2 * i + 1], l[1]);
        }
        assert_ne!(l[0], l[1]);
        let blob: Vec<Vec<f64>> = (0..16).map(|i| vec![(i % 4) as f64, (i / 4) as f64]).collect(); // a uniform grid
        let lb = cluster(&blob, None);
        assert!(lb.iter().all(|&x| x == 0), "{lb:?}");
        assert_eq!(cluster(&f, Some(3)).iter().max(), Some(&2));
        assert_eq!(cluster(&f, None), cluster(&f, None));
    }
}
