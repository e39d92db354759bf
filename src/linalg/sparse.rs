//! Sparse matrices assembled from triplets and direct solvers around faer.
//!
//! [`SpdSolver`] keeps the symbolic Cholesky factorization (the fill-reducing ordering and
//! elimination tree) and reuses it whenever the next matrix has the same sparsity pattern:
//! the cotangent Laplacian, the Beltrami system and every stretch-energy iteration share one
//! pattern. [`LuSolver`] does the same for unsymmetric systems.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMat, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::perm::PermRef;
use faer::{Conj, Mat, Par, Side};
use super::factor_buffer::{offer_spare, take_spare, Scratch};
use super::nested_dissection::Dissection;
use rayon::prelude::*;
use std::sync::Arc;

/// Errors of the sparse direct solvers.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum SolveError {
    /// The matrix is not (numerically) symmetric positive definite.
    #[error("the {what} matrix is not positive definite (the mesh may have degenerate or flipped triangles)")]
    NotPositiveDefinite {
        /// Which system.
        what: &'static str,
    },
    /// The matrix is singular.
    #[error("the {what} matrix is singular")]
    Singular {
        /// Which system.
        what: &'static str,
    },
    /// faer could not build the matrix or allocate the factorization.
    #[error("sparse solver failure for the {what} system: {message}")]
    Backend {
        /// Which system.
        what: &'static str,
        /// The backend's message.
        message: String,
    },
    /// The solution contains NaN or infinity.
    #[error("the {what} system produced a non-finite solution")]
    NonFinite {
        /// Which system.
        what: &'static str,
    },
}

/// Accumulates `(row, col, value)` entries; duplicates are summed on assembly.
#[derive(Debug, Clone, Default)]
pub struct TripletList {
    n: usize,
    /// `(row, col, value)`; 32-bit indices keep the list at 16 bytes an entry (the transport
    /// Hessian of a million-vertex mesh has some 20 million).
    entries: Vec<(u32, u32, f64)>,
}

impl TripletList {
    /// An empty `n x n` list.
    pub fn new(n: usize) -> Self {
        Self { n, entries: Vec::new() }
    }

    /// An empty `n x n` list with room for `cap` entries.
    pub fn with_capacity(n: usize, cap: usize) -> Self {
        Self { n, entries: Vec::with_capacity(cap) }
    }

    /// Add `value` at `(row, col)`.
    #[inline]
    pub fn push(&mut self, row: usize, col: usize, value: f64) {
        // An index beyond u32 becomes u32::MAX, which `assemble` refuses as out of range.
        let idx = |i: usize| u32::try_from(i).unwrap_or(u32::MAX);
        self.entries.push((idx(row), idx(col), value));
    }

    /// Matrix dimension.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Assemble into a compressed sparse column matrix: a counting sort by column, then each
    /// column's few entries sorted by row with duplicates summed. O(entries), several times
    /// faster than a general sort of the triplets (assembly was 15% of a parameterization).
    pub fn assemble(&self, what: &'static str) -> Result<SparseColMat<usize, f64>, SolveError> {
        let n = self.n;
        let mut count = vec![0usize; n + 1];
        for &(row, col, _) in &self.entries {
            let (row, col) = (row as usize, col as usize);
            if row >= n || col >= n {
                return Err(SolveError::Backend { what, message: format!("entry ({row}, {col}) outside a {n} x {n} matrix") });
            }
            count[col + 1] += 1;
        }
        for c in 0..n {
            count[c + 1] += count[c];
        }
        let mut next = count.clone();
        let mut bucket = vec![(0u32, 0.0f64); self.entries.len()];
        for &(row, col, val) in &self.entries {
            bucket[next[col as usize]] = (row, val);
            next[col as usize] += 1;
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(self.entries.len());
        let mut values = Vec::with_capacity(self.entries.len());
        col_ptr.push(0);
        for c in 0..n {
            let column = &mut bucket[count[c]..count[c + 1]];
            column.sort_unstable_by_key(|e| e.0);
            for &(r, v) in column.iter() {
                let r = r as usize;
                if row_idx.len() > col_ptr[c] && row_idx.last() == Some(&r) {
                    *values.last_mut().expect("values parallel to rows") += v;
                } else {
                    row_idx.push(r);
                    values.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        // Capacity was for every entry; duplicates made the matrix smaller.
        row_idx.shrink_to_fit();
        values.shrink_to_fit();
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Ok(SparseColMat::new(symbolic, values))
    }
}

fn same_pattern(a: &SparseColMat<usize, f64>, col_ptr: &[usize], row_idx: &[usize]) -> bool {
    let s = a.symbolic();
    s.col_ptr() == col_ptr && s.row_idx() == row_idx
}

fn check_finite(x: &[f64], what: &'static str) -> Result<(), SolveError> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SolveError::NonFinite { what })
    }
}

/// An analysed pattern: its columns (`col_ptr`, `row_idx`) and their symbolic factorization.
type AnalysedPattern = (Vec<usize>, Vec<usize>, SymbolicCholesky<usize>);

/// Sparse Cholesky solver for symmetric positive definite matrices, reusing the symbolic
/// factorization across matrices with the same pattern.
///
/// The factorization is always supernodal: faer picks the simplicial one below 40 flops
/// per factor entry, which covers the 2k-17k-vertex meshes' systems, and there it was the
/// slower.
///
/// Factorization and solves run on the calling thread (`Par::Seq`): the systems here have
/// 10^3 to 10^6 unknowns and a planar-graph pattern, where faer's thread pool spent more time
/// waking workers than they saved (also with the pipeline on a worker thread, `crate::pool`,
/// and for the largest systems only). Parallelism lives one level up, over independent work,
/// and over the right-hand sides of large systems (from 20 000 unknowns); only factors of
/// `PARALLEL_FACTOR_ENTRIES` (2^24) entries or more use the pool, when nothing else runs beside them.
///
/// Clones share the symbolic factorization: [`SpdSolver::analyze`] once, then clone for
/// parallel numeric factorizations of matrices with that pattern.
///
/// Measured and dropped: keeping the last minimum-degree ordering for the next pattern of the
/// same size while its factor stays within 25% of a fresh ordering's (the transport's patterns
/// change too much while the steps are damped, so the analysis was redone anyway); a nested
/// dissection by breadth-first level structures (George 1973), which gave a larger factor on
/// irregular meshes and took longer to compute. A geometric one on known positions
/// ([`SpdSolver::set_positions`], `super::nested_dissection`) is cheap enough to pay on the
/// large transport systems (see `crate::omt::newton::NESTED_DISSECTION_SITES`).
#[derive(Default, Clone)]
pub struct SpdSolver {
    symbolic: Option<Arc<AnalysedPattern>>,
    values: Vec<f64>,
    factored: bool,
    /// How many symbolic factorizations were computed (for reports and tests).
    pub symbolic_count: usize,
    /// The geometric dissection of the unknowns' planar positions, when known: the symbolic
    /// factorization then orders by nested dissection ([`super::nested_dissection`]) instead
    /// of AMD.
    dissection: Option<Arc<Dissection>>,
    /// Solve one right-hand side per thread in [`SpdSolver::solve_in_place`] (large systems);
    /// see [`SpdSolver::set_parallel_columns`].
    sequential_columns: bool,
    /// The numeric factorization's work space.
    scratch: Scratch,
    /// Tests only: factor on every thread from this many entries instead of
    /// [`PARALLEL_FACTOR_ENTRIES`].
    #[cfg(test)]
    parallel_entries: Option<usize>,
}

impl SpdSolver {
    /// A solver with nothing factored yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Order later systems by geometric nested dissection on these planar positions of their
    /// unknowns (a system of another size keeps AMD); the next factorization analyses anew.
    pub fn set_positions(&mut self, positions: Vec<[f64; 2]>) {
        self.dissection = Some(Arc::new(Dissection::new(&positions)));
        self.symbolic = None;
        self.factored = false;
    }

    /// Whether [`SpdSolver::solve_in_place`] solves the right-hand sides of a large system on
    /// separate threads (from 20 000 unknowns; the default) or all in one pass over the
    /// factor. One pass is the better when the other core is busy with another such solver:
    /// [`crate::param::PunctureEnd::Best`] flattens both ends at once, and there the two
    /// streams of each solve only compete for the memory bandwidth.
    pub fn set_parallel_columns(&mut self, parallel: bool) {
        self.sequential_columns = !parallel;
    }

    /// Factor `a` (both triangles stored); reuses the symbolic part when the pattern matches.
    pub fn factor(&mut self, a: &SparseColMat<usize, f64>, what: &'static str) -> Result<(), SolveError> {
        self.factored = false;
        let backend = |e: &dyn std::fmt::Debug| SolveError::Backend { what, message: format!("{e:?}") };
        self.analyze(a, what)?;
        let sym = &self.symbolic.as_deref().ok_or(SolveError::Singular { what })?.2;
        // No clearing: the supernodal factorization (forced in `analyze`) zeroes its values
        // itself, and clearing them first wrote the hand's 21 MB factor twice.
        take_spare(&mut self.values, sym.len_val());
        self.values.resize(sym.len_val(), 0.0);
        // Both cores for the large factorizations made while the other core waits (not while
        // two puncture ends flatten at once, see `sequential_columns`).
        #[cfg(test)]
        let parallel_entries = self.parallel_entries.unwrap_or(PARALLEL_FACTOR_ENTRIES);
        #[cfg(not(test))]
        let parallel_entries = PARALLEL_FACTOR_ENTRIES;
        let par = if !self.sequential_columns && sym.len_val() >= parallel_entries { Par::rayon(0) } else { Par::Seq };
        let req = sym.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        let scratch = self.scratch.at_least(req.unaligned_bytes_required()).map_err(|e| backend(&e))?;
        sym.factorize_numeric_llt(&mut self.values, a.as_ref(), Side::Lower, Default::default(), par, MemStack::new(scratch), Default::default())
            .map_err(|_| SolveError::NotPositiveDefinite { what })?;
        self.factored = true;
        Ok(())
    }

    /// Compute the symbolic factorization of `a`'s pattern unless the solver has it already.
    pub fn analyze(&mut self, a: &SparseColMat<usize, f64>, what: &'static str) -> Result<(), SolveError> {
        if matches!(self.symbolic.as_deref(), Some((cp, ri, _)) if same_pattern(a, cp, ri)) {
            return Ok(());
        }
        self.factored = false;
        let s = a.symbolic();
        let sym = symbolic_cholesky(s.col_ptr(), s.row_idx(), self.dissection.as_deref().filter(|d| d.len() == s.nrows()), what)?;
        self.symbolic = Some(Arc::new((s.col_ptr().to_vec(), s.row_idx().to_vec(), sym)));
        self.symbolic_count += 1;
        Ok(())
    }

    /// Reorder the analysed pattern by geometric nested dissection on these planar positions
    /// of its unknowns when that gives a smaller factor than its present ordering (a choice
    /// between fill-reducing orderings by their fill, as CHOLMOD makes between AMD and
    /// METIS); true when the dissection was kept, and the next factorization of the pattern
    /// uses it. Other patterns keep their own analysis (AMD unless
    /// [`SpdSolver::set_positions`]).
    ///
    /// The closed-surface flattening offers its harmonic map after the first solve when its
    /// later systems (11 factorizations with every stretch iteration factoring; not with the
    /// default schedule, see `flatten::closed`'s `DISSECTION_OFFER_FACTORIZATIONS`) have the
    /// same pattern. On the 164k closed ellipsoid the dissection's factor was the smaller and
    /// was kept; on the 100k ellipsoid, the 48k brain and the hand AMD's was (see
    /// `flatten::closed`'s `DISSECTION_FILL` for the fill that makes the offer).
    pub fn offer_positions(&mut self, positions: &[[f64; 2]], what: &'static str) -> Result<bool, SolveError> {
        let Some(current) = self.symbolic.clone() else { return Ok(false) };
        let (col_ptr, row_idx, present) = &*current;
        if positions.len() + 1 != col_ptr.len() {
            return Ok(false);
        }
        let dissected = symbolic_cholesky(col_ptr, row_idx, Some(&Dissection::new(positions)), what)?;
        if dissected.len_val() >= present.len_val() {
            return Ok(false);
        }
        self.symbolic = Some(Arc::new((col_ptr.clone(), row_idx.clone(), dissected)));
        self.symbolic_count += 1;
        self.factored = false;
        Ok(true)
    }

    /// Entries of the analysed pattern's Cholesky factor (its fill), if a pattern is analysed.
    pub fn factor_entries(&self) -> Option<usize> {
        self.symbolic.as_deref().map(|(_, _, sym)| sym.len_val())
    }

    /// Solve for each right-hand side column (each slice of length n) in place.
    pub fn solve_in_place(&self, rhs: &mut [Vec<f64>], what: &'static str) -> Result<(), SolveError> {
        let sym = match self.symbolic.as_deref() {
            Some((_, _, sym)) if self.factored => sym,
            _ => return Err(SolveError::Singular { what }),
        };
        let n = rhs.first().map_or(0, |c| c.len());
        let k = rhs.len();
        if k > 1 && n >= PARALLEL_COLUMNS && !self.sequential_columns {
            // One column per task: each solve streams the factor from memory, and two
            // threads streaming it beat one solve carrying both columns.
            return rhs.par_iter_mut().try_for_each(|col| self.solve_in_place(std::slice::from_mut(col), what));
        }
        let mut m = Mat::<f64>::from_fn(n, k, |i, j| rhs[j][i]);
        let mut buf = MemBuffer::try_new(sym.solve_in_place_scratch::<f64>(k, Par::Seq))
            .map_err(|e| SolveError::Backend { what, message: format!("{e:?}") })?;
        LltRef::new(sym, &self.values).solve_in_place_with_conj(Conj::No, m.as_mut(), Par::Seq, MemStack::new(&mut buf));
        copy_back(&m, rhs, what)
    }
}

/// Factors of at least this many entries are computed on every thread of the pool when the
/// solver's columns are not sequential ([`SpdSolver::set_parallel_columns`]): the
/// full-resolution transport's factorizations, made while the other core has nothing to do
/// (issue 27; on the 776k-vertex brain, 66-76 million entries each, the transport stage's
/// median fell from 44.9 to 41.1 s in four alternating pairs of runs). Smaller ones stay on
/// the calling thread (see [`SpdSolver`]). The factor comes out the same bytes on any
/// number of threads (faer splits the dense updates' rows and columns among the threads, not
/// their sums; tested).
pub const PARALLEL_FACTOR_ENTRIES: usize = 1 << 24;

impl Drop for SpdSolver {
    fn drop(&mut self) {
        offer_spare(&mut self.values);
    }
}

/// The supernodal symbolic Cholesky factorization of the symmetric pattern (`col_ptr`,
/// `row_idx`), ordered by `dissection` when given, else by AMD.
fn symbolic_cholesky(col_ptr: &[usize], row_idx: &[usize], dissection: Option<&Dissection>, what: &'static str) -> Result<SymbolicCholesky<usize>, SolveError> {
    let n = col_ptr.len() - 1;
    let pattern = SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, row_idx);
    let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL, ..Default::default() };
    let permutation = dissection.map(|d| {
        let order = d.order(col_ptr, row_idx);
        let mut inverse = vec![0usize; order.len()];
        for (k, &v) in order.iter().enumerate() {
            inverse[v] = k;
        }
        (order, inverse)
    });
    let ordering = match &permutation {
        Some((forward, inverse)) => SymmetricOrdering::Custom(PermRef::new_checked(forward, inverse, forward.len())),
        None => SymmetricOrdering::Amd,
    };
    factorize_symbolic_cholesky(pattern, Side::Lower, ordering, params).map_err(|e| SolveError::Backend { what, message: format!("{e:?}") })
}

/// Columns of `m` into `rhs`, checking they are finite.
fn copy_back(m: &Mat<f64>, rhs: &mut [Vec<f64>], what: &'static str) -> Result<(), SolveError> {
    for (j, col) in rhs.iter_mut().enumerate() {
        for (i, v) in col.iter_mut().enumerate() {
            *v = m[(i, j)];
        }
        check_finite(col, what)?;
    }
    Ok(())
}

/// Unknowns from which [`SpdSolver::solve_in_place`] solves its right-hand sides on
/// separate threads (the hand's 53k-unknown stretch-energy solves were about a fifth faster
/// so); small systems' solves are too short to share.
const PARALLEL_COLUMNS: usize = 20_000;

/// Sparse LU solver for general square matrices, reusing the symbolic factorization; runs on
/// the calling thread like [`SpdSolver`].
#[derive(Default)]
pub struct LuSolver {
    symbolic: Option<(Vec<usize>, Vec<usize>, SymbolicLu<usize>)>,
    numeric: Option<NumericLu<usize, f64>>,
}

impl LuSolver {
    /// A solver with nothing factored yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Factor `a`; reuses the symbolic part when the pattern matches.
    pub fn factor(&mut self, a: &SparseColMat<usize, f64>, what: &'static str) -> Result<(), SolveError> {
        let backend = |e: &dyn std::fmt::Debug| SolveError::Backend { what, message: format!("{e:?}") };
        let reuse = matches!(&self.symbolic, Some((cp, ri, _)) if same_pattern(a, cp, ri));
        if !reuse {
            let sym = factorize_symbolic_lu(a.symbolic(), Default::default()).map_err(|e| backend(&e))?;
            let s = a.symbolic();
            self.symbolic = Some((s.col_ptr().to_vec(), s.row_idx().to_vec(), sym));
        }
        let sym = &self.symbolic.as_ref().ok_or(SolveError::Singular { what })?.2;
        let mut numeric = self.numeric.take().unwrap_or_default();
        let mut buf = MemBuffer::try_new(sym.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())).map_err(|e| backend(&e))?;
        sym.factorize_numeric_lu(&mut numeric, a.as_ref(), Par::Seq, MemStack::new(&mut buf), Default::default())
            .map_err(|_| SolveError::Singular { what })?;
        self.numeric = Some(numeric);
        Ok(())
    }

    /// Solve for each right-hand side column in place.
    pub fn solve_in_place(&self, rhs: &mut [Vec<f64>], what: &'static str) -> Result<(), SolveError> {
        let (Some((_, _, sym)), Some(numeric)) = (&self.symbolic, &self.numeric) else {
            return Err(SolveError::Singular { what });
        };
        let n = rhs.first().map_or(0, |c| c.len());
        let k = rhs.len();
        let mut m = Mat::<f64>::from_fn(n, k, |i, j| rhs[j][i]);
        let mut buf = MemBuffer::try_new(sym.solve_in_place_scratch::<f64>(k, Par::Seq))
            .map_err(|e| SolveError::Backend { what, message: format!("{e:?}") })?;
        // Safety: `numeric` came from `factorize_numeric_lu` of a matrix with `sym`'s pattern.
        LuRef::new_unchecked(sym, numeric).solve_in_place_with_conj(Conj::No, m.as_mut(), Par::Seq, MemStack::new(&mut buf));
        copy_back(&m, rhs, what)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assembly_sums_duplicates_like_a_dense_accumulation() {
        let n = 7;
        let mut t = TripletList::new(n);
        let mut dense = vec![vec![0.0; n]; n];
        let mut state = 12345u64;
        for _ in 0..200 {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let (r, c) = ((state >> 33) as usize % n, (state >> 45) as usize % n);
            let v = ((state >> 20) % 1000) as f64 / 100.0 - 5.0;
            t.push(r, c, v);
            dense[r][c] += v;
        }
        let m = t.assemble("test").unwrap();
        let s = m.symbolic();
        for c in 0..n {
            let rows = &s.row_idx()[s.col_ptr()[c]..s.col_ptr()[c + 1]];
            assert!(rows.windows(2).all(|w| w[0] < w[1]), "rows sorted and unique in column {c}");
        }
        let back = m.to_dense();
        for r in 0..n {
            for c in 0..n {
                assert!((back[(r, c)] - dense[r][c]).abs() < 1e-12, "({r}, {c})");
            }
        }
        let mut bad = TripletList::new(2);
        bad.push(2, 0, 1.0);
        assert!(bad.assemble("test").is_err());
    }

    /// A weighted grid Laplacian plus a diagonal shift (SPD), `m x m` unknowns at grid
    /// points, numbered row by row.
    fn grid_matrix(m: usize) -> SparseColMat<usize, f64> {
        let id = |i: usize, j: usize| i * m + j;
        let mut t = TripletList::new(m * m);
        let mut state = 7u64;
        for i in 0..m {
            for j in 0..m {
                t.push(id(i, j), id(i, j), 0.1);
                for (a, b) in [(i + 1, j), (i, j + 1)] {
                    if a < m && b < m {
                        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                        let w = 0.5 + (state >> 40) as f64 / (1u64 << 24) as f64;
                        for (p, q) in [(id(i, j), id(a, b)), (id(a, b), id(i, j))] {
                            t.push(p, p, w);
                            t.push(p, q, -w);
                        }
                    }
                }
            }
        }
        t.assemble("test").unwrap()
    }

    /// The grid points of [`grid_matrix`]'s unknowns, in its numbering.
    fn grid_positions(m: usize) -> Vec<[f64; 2]> {
        (0..m * m).map(|k| [(k / m) as f64, (k % m) as f64]).collect()
    }

    /// Factor `a` with `solver` and solve for `rhs`.
    fn factor_and_solve(solver: &mut SpdSolver, a: &SparseColMat<usize, f64>, rhs: &[f64]) -> Vec<f64> {
        solver.factor(a, "test").unwrap();
        let mut x = vec![rhs.to_vec()];
        solver.solve_in_place(&mut x, "test").unwrap();
        x.remove(0)
    }

    /// `x` and `y` agree to 1e-10 of `x`'s largest entry.
    fn assert_same_solution(x: &[f64], y: &[f64]) {
        let scale = x.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for (p, q) in x.iter().zip(y) {
            assert!((p - q).abs() <= 1e-10 * scale, "{p} vs {q}");
        }
    }

    #[test]
    fn parallel_factorization_gives_the_same_bytes_on_any_number_of_threads() {
        let m = 250;
        let a = grid_matrix(m);
        let rhs: Vec<f64> = (0..m * m).map(|k| ((k * 17) % 11) as f64 - 5.0).collect();
        let on = |threads: usize, parallel: bool| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| {
                let mut s = SpdSolver::new();
                s.parallel_entries = Some(if parallel { 0 } else { usize::MAX });
                let x = factor_and_solve(&mut s, &a, &rhs);
                (x, s.values.clone())
            })
        };
        let (x_seq, l_seq) = on(1, false);
        for threads in [1, 2, 3] {
            let (x, l) = on(threads, true);
            assert!(l.iter().zip(&l_seq).all(|(p, q)| p.to_bits() == q.to_bits()), "factor on {threads} threads");
            assert!(x.iter().zip(&x_seq).all(|(p, q)| p.to_bits() == q.to_bits()), "solution on {threads} threads");
        }
    }

    #[test]
    fn offered_positions_are_kept_only_when_they_fill_less() {
        let m = 50;
        let a = grid_matrix(m);
        let rhs: Vec<f64> = (0..m * m).map(|k| ((k * 13) % 7) as f64 - 3.0).collect();
        let solve = |solver: &mut SpdSolver| factor_and_solve(solver, &a, &rhs);
        let grid = grid_positions(m);
        let fill_with = |positions: Option<&[[f64; 2]]>| {
            let mut s = SpdSolver::new();
            if let Some(p) = positions {
                s.set_positions(p.to_vec());
            }
            s.analyze(&a, "test").unwrap();
            s.factor_entries().unwrap()
        };
        let (amd, dissected) = (fill_with(None), fill_with(Some(&grid)));
        // Positions scattered at random: their dissection cuts the grid everywhere.
        let mut state = 99u64;
        let scattered: Vec<[f64; 2]> = (0..m * m)
            .map(|_| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                [(state >> 40) as f64, (state >> 20 & 0xfffff) as f64]
            })
            .collect();
        assert!(fill_with(Some(&scattered)) > amd, "a random dissection should fill more than AMD");
        let mut solver = SpdSolver::new();
        let x_amd = solve(&mut solver);
        assert!(!solver.offer_positions(&scattered, "test").unwrap());
        assert_eq!(solver.factor_entries(), Some(amd));
        assert_eq!(solver.offer_positions(&grid, "test").unwrap(), dissected < amd);
        assert_eq!(solver.factor_entries(), Some(amd.min(dissected)));
        // Whatever was kept, the next factorization of the pattern uses it and solves alike.
        let count = solver.symbolic_count;
        let x = solve(&mut solver);
        assert_eq!(solver.symbolic_count, count);
        assert_same_solution(&x_amd, &x);
        // Positions of another size are not offered.
        assert!(!solver.offer_positions(&grid[1..], "test").unwrap());
    }

    #[test]
    fn nested_dissection_ordering_solves_like_minimum_degree() {
        let m = 60;
        let a = grid_matrix(m);
        let rhs: Vec<f64> = (0..m * m).map(|k| ((k * 37) % 11) as f64 - 5.0).collect();
        let solve = |solver: &mut SpdSolver| factor_and_solve(solver, &a, &rhs);
        let mut amd = SpdSolver::new();
        let x_amd = solve(&mut amd);
        let mut nd = SpdSolver::new();
        nd.set_positions(grid_positions(m));
        let x_nd = solve(&mut nd);
        assert_same_solution(&x_amd, &x_nd);
        // New positions drop the analysis: the next factorization analyses anew.
        nd.set_positions((0..m * m).map(|k| [(k % m) as f64, (k / m) as f64]).collect());
        let before = nd.symbolic_count;
        solve(&mut nd);
        assert_eq!(nd.symbolic_count, before + 1);
    }
}
