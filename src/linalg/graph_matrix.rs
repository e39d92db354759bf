//! Symmetric sparse matrices on the edges of a graph, built straight into compressed sparse
//! columns.
//!
//! The transport's Newton matrix (paper Sec. 2.2, the Hessian of Eq. 9) is a weighted graph
//! Laplacian on the regular triangulation's edges. Built as triplets (an explicit zero per
//! kept pattern entry, two entries per edge, one per diagonal) and assembled by sorting, it
//! took a seventh of each Newton step on the 53k-vertex hand. [`GraphPattern`] lays
//! out the columns once per pattern (rows come out sorted without a sort: see
//! [`GraphPattern::new`]) and each matrix on it is a scatter of its edge values.

use super::SolveError;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// The sparsity pattern of a symmetric `n x n` matrix: every diagonal entry and both
/// `(i, j)` and `(j, i)` for each edge `i < j`.
#[derive(Debug, Clone)]
pub struct GraphPattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Per key `(i, j)`, the value slots of `(i, j)` (column `j`) and `(j, i)` (column `i`).
    key_slots: Vec<[usize; 2]>,
    /// Per column, the value slot of its diagonal.
    diagonal_slots: Vec<usize>,
}

impl GraphPattern {
    /// The pattern of `n` unknowns and the edges `keys`, each `(i << 32) | j` with
    /// `i < j < n`, sorted increasing without repeats.
    ///
    /// Column `c` holds the rows `i < c` of the keys `(i, c)`, then `c`, then the rows
    /// `j > c` of the keys `(c, j)`. The keys run by increasing `i` and, for one `i`, by
    /// increasing `j`: one pass over them writes every column's upper rows in order, the
    /// diagonal follows, and a second pass writes the lower rows in order.
    pub fn new(n: usize, keys: &[u64], what: &'static str) -> Result<Self, SolveError> {
        let bad = |message: String| SolveError::Backend { what, message };
        let mut count = vec![1usize; n];
        let mut previous = None;
        for &k in keys {
            let (i, j) = split(k);
            if !(i < j && j < n) || previous.is_some_and(|p| p >= k) {
                return Err(bad(format!("edge ({i}, {j}) of a {n}-unknown pattern is out of range or out of order")));
            }
            previous = Some(k);
            count[i] += 1;
            count[j] += 1;
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        for c in 0..n {
            col_ptr.push(col_ptr[c] + count[c]);
        }
        let mut next = col_ptr[..n].to_vec();
        let mut row_idx = vec![0usize; col_ptr[n]];
        let mut key_slots = vec![[0usize; 2]; keys.len()];
        for (&k, slots) in keys.iter().zip(&mut key_slots) {
            let (i, j) = split(k);
            row_idx[next[j]] = i;
            slots[0] = next[j];
            next[j] += 1;
        }
        let mut diagonal_slots = vec![0usize; n];
        for (c, slot) in next.iter_mut().enumerate() {
            row_idx[*slot] = c;
            diagonal_slots[c] = *slot;
            *slot += 1;
        }
        for (&k, slots) in keys.iter().zip(&mut key_slots) {
            let (i, j) = split(k);
            row_idx[next[i]] = j;
            slots[1] = next[i];
            next[i] += 1;
        }
        Ok(Self { n, col_ptr, row_idx, key_slots, diagonal_slots })
    }

    /// The matrix with `diagonal[c]` at `(c, c)` and `key_values[k]` at `(i, j)` and `(j, i)`
    /// for the `k`-th key `(i, j)` the pattern was made of: a scatter into the slots
    /// [`GraphPattern::new`] recorded, with no search (the stretch-energy matrices, whose
    /// values come per edge of the pattern).
    pub fn symmetric_on_keys(&self, diagonal: &[f64], key_values: &[f64], what: &'static str) -> Result<SparseColMat<usize, f64>, SolveError> {
        let n = self.n;
        if diagonal.len() != n || key_values.len() != self.key_slots.len() {
            return Err(SolveError::Backend { what, message: format!("{} diagonal entries and {} edge values for {n} unknowns and {} edges", diagonal.len(), key_values.len(), self.key_slots.len()) });
        }
        let mut values = vec![0.0; self.row_idx.len()];
        for (&s, &d) in self.diagonal_slots.iter().zip(diagonal) {
            values[s] = d;
        }
        for (&[a, b], &v) in self.key_slots.iter().zip(key_values) {
            values[a] = v;
            values[b] = v;
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, self.col_ptr.clone(), None, self.row_idx.clone());
        Ok(SparseColMat::new(symbolic, values))
    }

    /// The matrix with `diagonal[c]` at `(c, c)` and, for each `(i, j, v)` of `off_diagonal`
    /// (`i != j`, both orders meaning the same entry), `v` added at `(i, j)` and `(j, i)`;
    /// every other entry of the pattern is an explicit zero. An edge outside the pattern is
    /// an error.
    pub fn symmetric(
        &self,
        diagonal: &[f64],
        off_diagonal: impl IntoIterator<Item = (usize, usize, f64)>,
        what: &'static str,
    ) -> Result<SparseColMat<usize, f64>, SolveError> {
        let n = self.n;
        if diagonal.len() != n {
            return Err(SolveError::Backend { what, message: format!("{} diagonal entries for {n} unknowns", diagonal.len()) });
        }
        let mut values = vec![0.0; self.row_idx.len()];
        let slot = |col: usize, row: usize| -> Option<usize> {
            let (lo, hi) = (self.col_ptr[col], self.col_ptr[col + 1]);
            self.row_idx[lo..hi].binary_search(&row).ok().map(|k| lo + k)
        };
        for (&s, &d) in self.diagonal_slots.iter().zip(diagonal) {
            values[s] = d;
        }
        for (i, j, v) in off_diagonal {
            let missing = || SolveError::Backend { what, message: format!("entry ({i}, {j}) is not in the matrix's pattern") };
            if i == j || i >= n || j >= n {
                return Err(missing());
            }
            let (a, b) = (slot(j, i).ok_or_else(missing)?, slot(i, j).ok_or_else(missing)?);
            values[a] += v;
            values[b] += v;
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, self.col_ptr.clone(), None, self.row_idx.clone());
        Ok(SparseColMat::new(symbolic, values))
    }
}

fn split(key: u64) -> (usize, usize) {
    ((key >> 32) as usize, (key & 0xffff_ffff) as usize)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::TripletList;

    fn key(i: usize, j: usize) -> u64 {
        ((i as u64) << 32) | j as u64
    }

    /// A deterministic pseudo-random sorted edge set on `n` unknowns.
    fn random_keys(n: usize, count: usize, seed: u64) -> Vec<u64> {
        let mut s = seed;
        let mut keys: Vec<u64> = (0..count)
            .filter_map(|_| {
                s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                let (a, b) = ((s >> 33) as usize % n, (s >> 13) as usize % n);
                (a != b).then(|| key(a.min(b), a.max(b)))
            })
            .collect();
        keys.sort_unstable();
        keys.dedup();
        keys
    }

    #[test]
    fn matches_the_triplet_assembly_with_explicit_zeros() {
        let n = 40;
        let keys = random_keys(n, 150, 7);
        let pattern = GraphPattern::new(n, &keys, "test").unwrap();
        // Values on every other edge (the rest stay explicit zeros), given in both orders.
        let edges: Vec<(usize, usize, f64)> = keys
            .iter()
            .step_by(2)
            .enumerate()
            .map(|(k, &e)| {
                let (i, j) = split(e);
                let v = -1.0 - k as f64 * 0.25;
                if k % 3 == 0 { (j, i, v) } else { (i, j, v) }
            })
            .collect();
        let diagonal: Vec<f64> = (0..n).map(|c| 10.0 + c as f64).collect();
        let ours = pattern.symmetric(&diagonal, edges.iter().copied(), "test").unwrap();
        let mut trip = TripletList::new(n);
        for &k in &keys {
            let (i, j) = split(k);
            trip.push(i, j, 0.0);
            trip.push(j, i, 0.0);
        }
        for &(i, j, v) in &edges {
            trip.push(i, j, v);
            trip.push(j, i, v);
        }
        for (c, &d) in diagonal.iter().enumerate() {
            trip.push(c, c, d);
        }
        let reference = trip.assemble("test").unwrap();
        assert_eq!(ours.symbolic().col_ptr(), reference.symbolic().col_ptr());
        assert_eq!(ours.symbolic().row_idx(), reference.symbolic().row_idx());
        assert_eq!(ours.val(), reference.val());
        assert!(ours.val().iter().filter(|&&v| v == 0.0).count() > keys.len() / 2);
    }

    #[test]
    fn scatter_on_keys_matches_the_searched_assembly() {
        let n = 60;
        let keys = random_keys(n, 300, 11);
        let pattern = GraphPattern::new(n, &keys, "test").unwrap();
        let values: Vec<f64> = (0..keys.len()).map(|k| -0.5 - (k as f64 * 0.37).sin()).collect();
        let diagonal: Vec<f64> = (0..n).map(|c| 20.0 + c as f64).collect();
        let scattered = pattern.symmetric_on_keys(&diagonal, &values, "test").unwrap();
        let searched = pattern.symmetric(&diagonal, keys.iter().zip(&values).map(|(&k, &v)| (split(k).0, split(k).1, v)), "test").unwrap();
        assert_eq!(scattered.symbolic().col_ptr(), searched.symbolic().col_ptr());
        assert_eq!(scattered.symbolic().row_idx(), searched.symbolic().row_idx());
        assert_eq!(scattered.val(), searched.val());
        assert!(pattern.symmetric_on_keys(&diagonal, &values[1..], "test").is_err());
        assert!(pattern.symmetric_on_keys(&diagonal[1..], &values, "test").is_err());
    }

    #[test]
    fn refuses_bad_keys_and_edges_outside_the_pattern() {
        assert!(GraphPattern::new(3, &[key(0, 3)], "test").is_err());
        assert!(GraphPattern::new(3, &[key(1, 1)], "test").is_err());
        assert!(GraphPattern::new(3, &[key(1, 2), key(0, 1)], "test").is_err());
        let p = GraphPattern::new(3, &[key(0, 1)], "test").unwrap();
        let err = p.symmetric(&[1.0; 3], [(1, 2, -1.0)], "test").unwrap_err();
        assert!(err.to_string().contains("(1, 2)"), "{err}");
        assert!(p.symmetric(&[1.0; 2], [], "test").is_err());
        assert!(p.symmetric(&[1.0; 3], [(0, 0, 1.0)], "test").is_err());
    }
}
