//! Sparse symmetric systems with one 2 x 2 block per pair of neighbouring free vertices: the
//! normal equations of the global area steps ([`super::global_area`]), whose unknowns are the
//! free vertices' planar displacements.

use super::state::{Incidence, Shaping};
use crate::linalg::SpdSolver;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// The pattern, values and right-hand side of such a system.
pub(crate) struct BlockSystem {
    /// Each vertex's unknown (`u32::MAX`: not free).
    index: Vec<u32>,
    /// The free vertices, in unknown order.
    free: Vec<usize>,
    /// Free neighbour list of each unknown (itself included, sorted): `nb[start[i]..start[i + 1]]`.
    start: Vec<usize>,
    nb: Vec<u32>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    rhs: Vec<f64>,
}

impl BlockSystem {
    /// A zero system over the vertices of `mesh` for which `is_free` holds (and that have
    /// faces); `None` when there are none.
    pub(crate) fn new(mesh: &Shaping, incidence: &Incidence, is_free: impl Fn(usize) -> bool) -> Option<Self> {
        let n = mesh.plane.len();
        let mut index = vec![u32::MAX; n];
        let mut free = Vec::new();
        for v in 0..n {
            if is_free(v) && !incidence.of(v).is_empty() {
                index[v] = free.len() as u32;
                free.push(v);
            }
        }
        if free.is_empty() {
            return None;
        }
        let mut start = Vec::with_capacity(free.len() + 1);
        let mut nb: Vec<u32> = Vec::with_capacity(free.len() * 7);
        let mut row: Vec<u32> = Vec::new();
        start.push(0);
        for &v in &free {
            row.clear();
            row.extend(incidence.of(v).iter().flat_map(|&t| mesh.faces[t as usize]).map(|u| index[u as usize]).filter(|&i| i != u32::MAX));
            row.sort_unstable();
            row.dedup();
            nb.extend_from_slice(&row);
            start.push(nb.len());
        }
        let m = free.len();
        // Column 2i + a holds rows 2j + b for j in nb(i): 4 entries a block, 2 per column.
        let col_ptr: Vec<usize> = (0..=2 * m).map(|c| if c == 2 * m { 4 * start[m] } else { 4 * start[c / 2] + (c % 2) * 2 * (start[c / 2 + 1] - start[c / 2]) }).collect();
        let row_idx: Vec<usize> = (0..2 * m).flat_map(|c| nb[start[c / 2]..start[c / 2 + 1]].iter().flat_map(|&j| [2 * j as usize, 2 * j as usize + 1])).collect();
        let values = vec![0.0f64; row_idx.len()];
        Some(Self { index, free, start, nb, col_ptr, row_idx, values, rhs: vec![0.0; 2 * m] })
    }

    /// The unknown of vertex `v` (`u32::MAX`: not free).
    pub(crate) fn unknown(&self, v: u32) -> u32 {
        self.index[v as usize]
    }

    /// Add `w` to entry `(a, b)` of block `(i, j)` (unknowns `i`, `j`, which must be
    /// neighbours).
    pub(crate) fn add(&mut self, i: u32, a: usize, j: u32, b: usize, w: f64) {
        let (s, e) = (self.start[i as usize], self.start[i as usize + 1]);
        let k = s + self.nb[s..e].binary_search(&j).unwrap_or(0);
        let col = 2 * i as usize + a;
        self.values[self.col_ptr[col] + 2 * (k - s) + b] += w;
    }

    /// Add `w` to component `a` of unknown `i`'s right-hand side.
    pub(crate) fn add_rhs(&mut self, i: u32, a: usize, w: f64) {
        self.rhs[2 * i as usize + a] += w;
    }

    /// Solve with each diagonal entry raised by `damping` times itself; each vertex's
    /// displacement (zero where not free), or `None` when the system cannot be solved.
    pub(crate) fn solve(mut self, damping: f64, solver: &mut SpdSolver, what: &'static str) -> Option<Vec<[f64; 2]>> {
        let m = self.free.len();
        for i in 0..m {
            let s = self.start[i];
            let k = s + self.nb[s..self.start[i + 1]].binary_search(&(i as u32)).unwrap_or(0);
            for a in 0..2 {
                let e = self.col_ptr[2 * i + a] + 2 * (k - s) + a;
                self.values[e] += damping * self.values[e] + 1e-300;
            }
        }
        let symbolic = SymbolicSparseColMat::new_checked(2 * m, 2 * m, self.col_ptr, None, self.row_idx);
        let matrix = SparseColMat::new(symbolic, self.values);
        solver.factor(&matrix, what).ok()?;
        let mut cols = vec![self.rhs];
        solver.solve_in_place(&mut cols, what).ok()?;
        let u = &cols[0];
        if !u.iter().all(|x| x.is_finite()) {
            return None;
        }
        let mut out = vec![[0.0, 0.0]; self.index.len()];
        for (i, &v) in self.free.iter().enumerate() {
            out[v] = [u[2 * i], u[2 * i + 1]];
        }
        Some(out)
    }
}
