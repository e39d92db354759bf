//! The sparsity pattern of the transport's Hessian as sorted edge keys (ours): the keys of a
//! regular triangulation's interior edges, how many of them a pattern lacks, and the union
//! of two patterns, for [`super::newton`]'s reuse of one symbolic factorization across Newton
//! steps whose triangulations differ by a few flips (see `OtSolver::update_pattern`).

/// The keys `(i << 32) | j` of the edges `(i, j, _)` (`i < j`) with `i > 0`, sorted without
/// repeats: bucketed by `i` (a counting sort), each bucket's few `j` sorted in place, which
/// is much cheaper than a general sort of every Newton step's keys.
pub(super) fn interior_edge_keys(n: usize, edges: &[(u32, u32, f64)]) -> Vec<u64> {
    let mut start = vec![0usize; n + 1];
    for &(i, _, _) in edges.iter().filter(|e| e.0 > 0) {
        start[i as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut next = start.clone();
    let mut keys = vec![0u64; start[n]];
    for &(i, j, _) in edges.iter().filter(|e| e.0 > 0) {
        keys[next[i as usize]] = ((i as u64) << 32) | j as u64;
        next[i as usize] += 1;
    }
    for bucket in start.windows(2) {
        keys[bucket[0]..bucket[1]].sort_unstable();
    }
    keys.dedup();
    keys
}

/// How many of the sorted `keys` are not in the sorted `pattern`.
pub(super) fn count_missing(keys: &[u64], pattern: &[u64]) -> usize {
    let (mut missing, mut p) = (0, 0);
    for &k in keys {
        while p < pattern.len() && pattern[p] < k {
            p += 1;
        }
        if p == pattern.len() || pattern[p] != k {
            missing += 1;
        }
    }
    missing
}

/// The sorted union of two sorted lists without repeats.
pub(super) fn sorted_union(a: &[u64], b: &[u64]) -> Vec<u64> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let (x, y) = (a[i], b[j]);
        out.push(x.min(y));
        i += usize::from(x <= y);
        j += usize::from(y <= x);
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pseudo-random edges `(i, j, c)`, `i < j < n`, with repeats, in no order.
    fn edges(n: u32, count: usize, seed: u64) -> Vec<(u32, u32, f64)> {
        let mut s = seed;
        (0..count)
            .filter_map(|_| {
                s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                let (a, b) = ((s >> 33) as u32 % n, (s >> 11) as u32 % n);
                (a != b).then(|| (a.min(b), a.max(b), 1.0))
            })
            .collect()
    }

    fn sorted_keys(edges: &[(u32, u32, f64)]) -> Vec<u64> {
        let mut keys: Vec<u64> = edges.iter().filter(|e| e.0 > 0).map(|&(i, j, _)| ((i as u64) << 32) | j as u64).collect();
        keys.sort_unstable();
        keys.dedup();
        keys
    }

    #[test]
    fn pattern_keys_missing_and_union_match_a_sort() {
        let (a, b) = (edges(300, 2000, 3), edges(300, 2000, 4));
        let (ka, kb) = (interior_edge_keys(300, &a), interior_edge_keys(300, &b));
        assert_eq!(ka, sorted_keys(&a));
        assert!(ka.len() > 1000 && ka.iter().all(|k| k >> 32 > 0));
        let missing = kb.iter().filter(|k| ka.binary_search(k).is_err()).count();
        assert!(missing > 0 && missing < kb.len());
        assert_eq!(count_missing(&kb, &ka), missing);
        assert_eq!(count_missing(&kb, &kb), 0);
        assert_eq!(count_missing(&kb, &[]), kb.len());
        let mut union = [a.clone(), b.clone()].concat();
        union.sort_unstable_by_key(|e| (e.0, e.1));
        assert_eq!(sorted_union(&ka, &kb), sorted_keys(&union));
        assert_eq!(sorted_union(&ka, &[]), ka);
    }
}
