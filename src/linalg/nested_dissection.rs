//! Geometric nested dissection: a fill-reducing elimination order for a sparse symmetric
//! matrix whose unknowns have positions (George 1973; coordinate bisection as in Gilbert,
//! Miller and Teng 1998), used instead of minimum degree when the positions are known.
//!
//! The unknowns are split at the median along the longest side of their bounding box; the
//! smaller of the two one-sided separators (the vertices of one half with a neighbour in the
//! other) is eliminated after both halves, which are ordered the same way recursively down to
//! leaves of [`LEAF`] unknowns. The splits depend on the positions only, so they are computed
//! once ([`Dissection`]) and each pattern only picks its separators; the halves are ordered
//! in parallel. On the planar transport sites the separators are curves of
//! about `sqrt(n)` unknowns (positions in any dimension work, but on a folded surface's 3D
//! positions the cuts are long: see [`crate::omt::newton::NESTED_DISSECTION_SITES`]).
//!
//! Against faer's AMD on the transport Hessians: on the 53k hand the ordering and symbolic
//! analysis are faster and the factor somewhat larger, a Newton step faster overall; on the
//! 101k synthetic disk the factor is smaller too. Leaves of 8 gave the least fill; splitting
//! at the medians of all the positions once, instead of at the medians of what each
//! separator leaves, orders faster at the same fill; both one-sided separators of a split
//! come from one scan of the first half's edges.
//!
//! Measured and dropped: METIS's multilevel nested dissection (`METIS_NodeND` through the
//! metis-sys crate) for the flattening systems, whose pattern is fixed: far less fill than
//! AMD on the large meshes, but its ordering took as long as the factorizations saved, so
//! the flattening was no faster; METIS on a contracted graph ordered faster and lost the
//! fill it had won.

/// Unknowns per leaf at most (eliminated in the order they come).
pub const LEAF: usize = 8;

/// Parts of more unknowns than this are split on two threads (rayon): below it the
/// work is shorter than handing it over.
const PARALLEL_PART: usize = 4096;

/// The geometric half of a nested dissection, computed once for fixed positions: the
/// points in an order where every part (a range of it, starting with the whole) is split
/// at its middle into the halves below and above the median along the longest side of the
/// part's bounding box, recursively down to [`LEAF`] points. [`Dissection::order`] then only
/// looks at a pattern's edges to find each split's separator; the transport's Newton
/// matrices change pattern every step but their sites never move (fixing the splits here
/// halves the ordering's time against redoing them on the parts the separators leave).
#[derive(Debug, Clone)]
pub struct Dissection {
    /// `points_in_order[k]`: the point at position `k` of the split order.
    points_in_order: Vec<usize>,
    /// The inverse: `rank[v]` is the position of point `v`.
    rank: Vec<usize>,
}

impl Dissection {
    /// The split order of `points`.
    pub fn new<const D: usize>(points: &[[f64; D]]) -> Self {
        let n = points.len();
        let mut points_in_order: Vec<usize> = (0..n).collect();
        split_points(points, &mut points_in_order);
        let mut rank = vec![0; n];
        for (k, &v) in points_in_order.iter().enumerate() {
            rank[v] = k;
        }
        Self { points_in_order, rank }
    }

    /// Number of unknowns.
    pub fn len(&self) -> usize {
        self.rank.len()
    }

    /// The elimination order for the pattern (`col_ptr`, `row_idx`) of `self.len()`
    /// unknowns: at each split the smaller of the two one-sided separators (the unknowns of
    /// one half, not in an earlier separator, with such a neighbour in the other half) is
    /// eliminated after both halves, which are ordered the same way. `order[k]` is the unknown
    /// eliminated `k`-th; the pattern may hold either or both triangles, and row indices
    /// `>= self.len()` are ignored.
    pub fn order(&self, col_ptr: &[usize], row_idx: &[usize]) -> Vec<usize> {
        let n = self.len();
        let mut taken = vec![false; n];
        let mut order = vec![0; n];
        let pattern = Pattern { col_ptr, row_idx };
        self.dissect(&pattern, 0, &mut taken, &mut order);
        order
    }

    /// Order the part at positions `lo..lo + taken.len()`; `taken` marks its unknowns already
    /// in a separator, `out` receives the others (as many as it is long).
    fn dissect(&self, pattern: &Pattern, lo: usize, taken: &mut [bool], out: &mut [usize]) {
        let len = taken.len();
        let at = |k: usize| self.points_in_order[lo + k];
        if len <= LEAF {
            let live = (0..len).filter(|&k| !taken[k]).map(at);
            for (slot, v) in out.iter_mut().zip(live) {
                *slot = v;
            }
            return;
        }
        let mid = len / 2;
        // Both one-sided separators from one scan of the first half's edges (the pattern is
        // symmetric: an edge between live unknowns of the two halves puts its first-half end
        // in the first separator and its second-half end in the second); each in position
        // order.
        let mut first = Vec::new();
        let mut in_second = vec![false; len - mid];
        for k in (0..mid).filter(|&k| !taken[k]) {
            let mut crosses = false;
            for &u in pattern.neighbours(at(k)) {
                let r = self.rank.get(u).map_or(usize::MAX, |&r| r.wrapping_sub(lo));
                if (mid..len).contains(&r) && !taken[r] {
                    crosses = true;
                    in_second[r - mid] = true;
                }
            }
            if crosses {
                first.push(k);
            }
        }
        let second_len = in_second.iter().filter(|&&m| m).count();
        let chosen: Vec<usize> = if first.len() <= second_len { first } else { (mid..len).filter(|&k| in_second[k - mid]).collect() };
        for &k in &chosen {
            taken[k] = true;
        }
        let live_first = taken[..mid].iter().filter(|&&t| !t).count();
        let live_second = taken[mid..].iter().filter(|&&t| !t).count();
        let (out_first, rest) = out.split_at_mut(live_first);
        let (out_second, out_separator) = rest.split_at_mut(live_second);
        for (slot, &k) in out_separator.iter_mut().zip(&chosen) {
            *slot = at(k);
        }
        let (taken_first, taken_second) = taken.split_at_mut(mid);
        if len > PARALLEL_PART {
            rayon::join(
                || self.dissect(pattern, lo, taken_first, out_first),
                || self.dissect(pattern, lo + mid, taken_second, out_second),
            );
        } else {
            self.dissect(pattern, lo, taken_first, out_first);
            self.dissect(pattern, lo + mid, taken_second, out_second);
        }
    }
}

/// A pattern's columns.
struct Pattern<'a> {
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
}

impl Pattern<'_> {
    fn neighbours(&self, v: usize) -> &[usize] {
        match (self.col_ptr.get(v), self.col_ptr.get(v + 1)) {
            (Some(&a), Some(&b)) => self.row_idx.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }
}

/// Reorder `part` (point indices) so that its halves are the points below and above the
/// median along the longest side of its bounding box, each half reordered the same way.
fn split_points<const D: usize>(points: &[[f64; D]], part: &mut [usize]) {
    if part.len() <= LEAF {
        return;
    }
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for &v in part.iter() {
        for k in 0..D {
            lo[k] = lo[k].min(points[v][k]);
            hi[k] = hi[k].max(points[v][k]);
        }
    }
    let axis = (0..D).fold(0, |best, k| if hi[k] - lo[k] > hi[best] - lo[best] { k } else { best });
    let mid = part.len() / 2;
    part.select_nth_unstable_by(mid, |&a, &b| points[a][axis].total_cmp(&points[b][axis]).then(a.cmp(&b)));
    let (first, second) = part.split_at_mut(mid);
    if first.len() + second.len() > PARALLEL_PART {
        rayon::join(|| split_points(points, first), || split_points(points, second));
    } else {
        split_points(points, first);
        split_points(points, second);
    }
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
        let order = Dissection::new(&points).order(&col_ptr, &row_idx);
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
        let nd = factor_entries(&col_ptr, &row_idx, &Dissection::new(&points).order(&col_ptr, &row_idx));
        let natural = factor_entries(&col_ptr, &row_idx, &(0..m * m).collect::<Vec<_>>());
        // Natural (banded) order: about m^3 = 64000 entries; nested dissection O(n log n).
        assert!(natural > 60_000, "{natural}");
        assert!(nd < natural / 2, "nested dissection {nd}, natural {natural}");
    }

    /// The order by the definition of [`Dissection::order`]: each one-sided separator found
    /// by its own scan of its half.
    fn order_by_definition(d: &Dissection, col_ptr: &[usize], row_idx: &[usize]) -> Vec<usize> {
        fn part(d: &Dissection, p: &Pattern, lo: usize, taken: &mut [bool], out: &mut Vec<usize>) {
            let len = taken.len();
            let at = |k: usize| d.points_in_order[lo + k];
            if len <= LEAF {
                out.extend((0..len).filter(|&k| !taken[k]).map(at));
                return;
            }
            let mid = len / 2;
            let one_sided = |from: std::ops::Range<usize>, other: std::ops::Range<usize>, taken: &[bool]| -> Vec<usize> {
                from.filter(|&k| !taken[k] && p.neighbours(at(k)).iter().any(|&u| other.contains(&d.rank[u].wrapping_sub(lo)) && !taken[d.rank[u] - lo])).collect()
            };
            let (first, second) = (one_sided(0..mid, mid..len, taken), one_sided(mid..len, 0..mid, taken));
            let chosen = if first.len() <= second.len() { first } else { second };
            for &k in &chosen {
                taken[k] = true;
            }
            let (a, b) = taken.split_at_mut(mid);
            part(d, p, lo, a, out);
            part(d, p, lo + mid, b, out);
            out.extend(chosen.iter().map(|&k| at(k)));
        }
        let mut out = Vec::new();
        part(d, &Pattern { col_ptr, row_idx }, 0, &mut vec![false; d.len()], &mut out);
        out
    }

    #[test]
    fn one_scan_finds_the_separators_of_the_definition() {
        // A triangulated grid with pseudo-random diagonals and jittered points.
        let m = 45;
        let id = |i: usize, j: usize| i * m + j;
        let mut s = 12345u64;
        let mut next = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 33) as f64 / (1u64 << 31) as f64
        };
        let points: Vec<[f64; 2]> = (0..m * m).map(|v| [(v / m) as f64 + 0.3 * next(), (v % m) as f64 + 0.3 * next()]).collect();
        let mut neighbours = vec![vec![]; m * m];
        let mut link = |a: usize, b: usize| {
            neighbours[a].push(b);
            neighbours[b].push(a);
        };
        for i in 0..m {
            for j in 0..m {
                if i + 1 < m {
                    link(id(i, j), id(i + 1, j));
                }
                if j + 1 < m {
                    link(id(i, j), id(i, j + 1));
                }
                if i + 1 < m && j + 1 < m {
                    if next() < 0.5 { link(id(i, j), id(i + 1, j + 1)) } else { link(id(i + 1, j), id(i, j + 1)) }
                }
            }
        }
        let (mut col_ptr, mut row_idx) = (vec![0], Vec::new());
        for (v, list) in neighbours.iter_mut().enumerate() {
            list.push(v);
            list.sort_unstable();
            row_idx.extend_from_slice(list);
            col_ptr.push(row_idx.len());
        }
        let d = Dissection::new(&points);
        assert_eq!(d.order(&col_ptr, &row_idx), order_by_definition(&d, &col_ptr, &row_idx));
    }

    #[test]
    fn three_dimensional_points_work_too() {
        // A grid bent into a half cylinder: the longest side of the box is along the axis.
        let (flat, col_ptr, row_idx) = grid(20);
        let points: Vec<[f64; 3]> = flat.iter().map(|p| [p[0], 10.0 * (p[1] / 6.4).cos(), 10.0 * (p[1] / 6.4).sin()]).collect();
        let order = Dissection::new(&points).order(&col_ptr, &row_idx);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..400).collect::<Vec<_>>());
        let natural = factor_entries(&col_ptr, &row_idx, &(0..400).collect::<Vec<_>>());
        assert!(factor_entries(&col_ptr, &row_idx, &order) < natural);
    }
}
