//! Geometric nested dissection: a fill-reducing elimination order for a sparse symmetric
//! matrix whose unknowns have positions (George 1973; coordinate bisection as in Gilbert,
//! Miller and Teng 1998), used instead of minimum degree when the positions are known.
//!
//! The unknowns are split at the median along the longest side of their bounding box; the
//! smaller of the two one-sided separators (the vertices of one half with a neighbour in the
//! other) is eliminated after both halves, which are ordered the same way recursively down to
//! leaves of [`LEAF`] unknowns. On the planar transport sites the separators are curves of
//! about `sqrt(n)` unknowns (positions in any dimension work, but on a folded surface's 3D
//! positions the cuts are long: see [`crate::omt::newton::NESTED_DISSECTION_SITES`]).
//!
//! Measured against faer's AMD (2026-11-30, one run each, transport Hessians): on the 53k
//! hand the ordering and symbolic analysis take 26 ms instead of 40-59 ms, the factor has
//! 1.36 times the entries and the numeric factorization 39 ms instead of 33 ms (65 against
//! 78 ms a Newton step); on the 101k synthetic disk the factor is smaller (5.9M against 6.4M
//! entries) and a step 106 ms instead of 151 ms. Leaves of 8 gave the least fill (3.52M on
//! the hand; 16: 3.55M, 64: 3.64M, 128: 3.92M); one-sided separators always on the first
//! half gave 3.64M-3.71M.

/// Unknowns per leaf at most (eliminated in the order they come).
pub const LEAF: usize = 8;

/// The elimination order of the `n = points.len()` unknowns (positions in `D` dimensions) of
/// a symmetric pattern given by its columns (`col_ptr`, `row_idx`, either or both
/// triangles): `order[k]` is the unknown eliminated `k`-th. Row indices `>= n` are ignored.
pub fn nested_dissection<const D: usize>(points: &[[f64; D]], col_ptr: &[usize], row_idx: &[usize]) -> Vec<usize> {
    let n = points.len();
    let mut order = Vec::with_capacity(n);
    // side[v]: 0 outside the part being split, 1 first half, 2 second half.
    let mut side = vec![0u8; n];
    let neighbours = |v: usize| row_idx.get(col_ptr[v]..col_ptr[v + 1]).unwrap_or(&[]);
    let mut tasks = vec![Task::Split((0..n).collect())];
    while let Some(task) = tasks.pop() {
        let mut part = match task {
            Task::Emit(separator) => {
                order.extend(separator);
                continue;
            }
            Task::Split(part) => part,
        };
        if part.len() <= LEAF {
            order.extend(part);
            continue;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
        for &v in &part {
            for k in 0..D {
                lo[k] = lo[k].min(points[v][k]);
                hi[k] = hi[k].max(points[v][k]);
            }
        }
        let axis = (0..D).fold(0, |best, k| if hi[k] - lo[k] > hi[best] - lo[best] { k } else { best });
        let mid = part.len() / 2;
        part.select_nth_unstable_by(mid, |&a, &b| points[a][axis].total_cmp(&points[b][axis]).then(a.cmp(&b)));
        let (first, second) = part.split_at(mid);
        for &v in first {
            side[v] = 1;
        }
        for &v in second {
            side[v] = 2;
        }
        // The vertices of `from` with a neighbour on side `other`, and the rest.
        let split = |from: &[usize], other: u8| -> (Vec<usize>, Vec<usize>) {
            from.iter().partition(|&&v| !neighbours(v).iter().any(|&u| u < n && side[u] == other))
        };
        let (first_rest, first_separator) = split(first, 2);
        let (second_rest, second_separator) = split(second, 1);
        for &v in &part {
            side[v] = 0;
        }
        let (a, b, separator) = if first_separator.len() <= second_separator.len() {
            (first_rest, second.to_vec(), first_separator)
        } else {
            (first.to_vec(), second_rest, second_separator)
        };
        // Popped in reverse: the first half, the second, then the separator.
        tasks.push(Task::Emit(separator));
        tasks.push(Task::Split(b));
        tasks.push(Task::Split(a));
    }
    order
}

/// Work of [`nested_dissection`]: a part to split, or a separator to eliminate.
enum Task {
    Split(Vec<usize>),
    Emit(Vec<usize>),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 5-point Laplacian pattern of an `m x m` grid (both triangles, diagonal included)
    /// and the grid points.
    fn grid(m: usize) -> (Vec<[f64; 2]>, Vec<usize>, Vec<usize>) {
        let id = |i: usize, j: usize| i * m + j;
        let (mut col_ptr, mut row_idx, mut points) = (vec![0], Vec::new(), Vec::new());
        for i in 0..m {
            for j in 0..m {
                points.push([i as f64, j as f64]);
                let mut col = vec![id(i, j)];
                if i > 0 {
                    col.push(id(i - 1, j));
                }
                if i + 1 < m {
                    col.push(id(i + 1, j));
                }
                if j > 0 {
                    col.push(id(i, j - 1));
                }
                if j + 1 < m {
                    col.push(id(i, j + 1));
                }
                col.sort_unstable();
                row_idx.extend(col);
                col_ptr.push(row_idx.len());
            }
        }
        (points, col_ptr, row_idx)
    }

    /// Entries of the Cholesky factor of the pattern eliminated in `order` (symbolic
    /// elimination with the elimination tree's row structures, the textbook way).
    fn factor_entries(col_ptr: &[usize], row_idx: &[usize], order: &[usize]) -> usize {
        let n = order.len();
        let mut position = vec![0; n];
        for (k, &v) in order.iter().enumerate() {
            position[v] = k;
        }
        // Column structures of L in the new numbering, built by merging children.
        let mut structure: Vec<std::collections::BTreeSet<usize>> = vec![Default::default(); n];
        for (k, &v) in order.iter().enumerate() {
            for &u in &row_idx[col_ptr[v]..col_ptr[v + 1]] {
                if position[u] > k {
                    structure[k].insert(position[u]);
                }
            }
        }
        let mut total = 0;
        for k in 0..n {
            let s = std::mem::take(&mut structure[k]);
            total += s.len() + 1;
            if let Some(&parent) = s.iter().next() {
                let merged: Vec<usize> = s.iter().copied().filter(|&r| r != parent).collect();
                structure[parent].extend(merged);
            }
            structure[k] = s;
        }
        total
    }

    #[test]
    fn the_order_is_a_permutation_with_separators_last() {
        let (points, col_ptr, row_idx) = grid(30);
        let order = nested_dissection(&points, &col_ptr, &row_idx);
        let mut seen = vec![false; points.len()];
        for &v in &order {
            assert!(!seen[v], "{v} twice");
            seen[v] = true;
        }
        assert!(seen.iter().all(|&s| s));
        // The last unknowns are the top separator: a grid line of 30 unknowns splitting the
        // grid (no edge between the two halves once it is removed).
        let top: Vec<usize> = order[order.len() - 30..].to_vec();
        let line = top.iter().map(|&v| points[v][0]).fold(f64::NAN, |a, x| if a.is_nan() || a == x { x } else { f64::INFINITY });
        assert!(line.is_finite(), "top separator {top:?} is not one grid line");
    }

    #[test]
    fn fill_on_a_grid_is_that_of_a_dissection_not_of_the_natural_order() {
        let m = 40;
        let (points, col_ptr, row_idx) = grid(m);
        let nd = factor_entries(&col_ptr, &row_idx, &nested_dissection(&points, &col_ptr, &row_idx));
        let natural = factor_entries(&col_ptr, &row_idx, &(0..m * m).collect::<Vec<_>>());
        // Natural (banded) order: about m^3 = 64000 entries; nested dissection O(n log n).
        assert!(natural > 60_000, "{natural}");
        assert!(nd < natural / 2, "nested dissection {nd}, natural {natural}");
    }

    #[test]
    fn three_dimensional_points_work_too() {
        // A grid bent into a half cylinder: the longest side of the box is along the axis.
        let (flat, col_ptr, row_idx) = grid(20);
        let points: Vec<[f64; 3]> = flat.iter().map(|p| [p[0], 10.0 * (p[1] / 6.4).cos(), 10.0 * (p[1] / 6.4).sin()]).collect();
        let order = nested_dissection(&points, &col_ptr, &row_idx);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..400).collect::<Vec<_>>());
        let natural = factor_entries(&col_ptr, &row_idx, &(0..400).collect::<Vec<_>>());
        assert!(factor_entries(&col_ptr, &row_idx, &order) < natural);
    }
}
