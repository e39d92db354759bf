//! Stretch energy minimisation (Yueh, Lin, Wu and Yau 2019), the equiareal initial map of the
//! paper's closed-surface pipeline (Sec. 3.2.1).
//!
//! The stretch energy of a planar map `f` of a triangle mesh is
//! `E_S(f) = sum_T |f(T)|^2 / |T|`; with the boundary fixed (so the total image area is fixed)
//! it is minimised exactly when every face keeps its share of the area. Its gradient is
//! `2 L_S(f) f`, where `L_S(f)` is the Laplacian of the image's cotangent weights scaled by
//! each face's stretch `|f(T)| / |T|`; on a corner `k` facing edge `ij` that weight is
//! `(f_i - f_k) . (f_j - f_k) / (4 |T|)`, defined even for folded image faces. The
//! minimiser is found by the fixed-point iteration `L_S(f^k)_II f^{k+1}_I = -L_S(f^k)_IB f_B`,
//! here over-relaxed (ours, [`StretchOptions::over_relaxation`]): the plain iteration's tail
//! converges slowly (hand: energy ratio 1.0034 after 10 iterations, 1.0028 after 25). Later
//! iterations may solve with an earlier iteration's factorization (ours,
//! [`StretchOptions::factored_iterations`]): the same step, `f - L_S(f)^-1 L_S(f) f`, with
//! an older `L_S`, at two triangular solves instead of a factorization: the open surfaces'
//! after their third iteration, the closed surfaces' every other iteration
//! ([`StretchOptions::refactor_period`]; a factorization one step old is nearly as good as a
//! fresh one, while one seven steps old lost).
//!
//! Measured and dropped (closed surfaces, whose punctured maps start far from equiareal):
//! conjugate gradients on each iteration's system preconditioned by the previous
//! iteration's factor (no convergence in 60 iterations: the stretch weights change by
//! orders of magnitude between iterations); starting from the harmonic map equalized
//! radially (Lambert-like; a far better first iteration, but the tail converges as
//! slowly); Anderson acceleration of depth 2-5 as a third candidate beside the plain and
//! over-relaxed steps (lower energies early, no better final maps); and fewer iterations
//! (6 instead of 10 left the bird skull's and the 48k brain's maps worse).

use super::{pin, FlattenError};
use crate::linalg::{GraphPattern, SpdSolver};
use faer::sparse::SparseColMat;
use rayon::prelude::*;
use crate::mesh::geometry::{folded_faces, signed_area_2d, triangle_area};

/// Options of the stretch energy minimisation. Build them from [`StretchOptions::default`]
/// with the `with_*` setters: new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct StretchOptions {
    /// Maximum fixed-point iterations. Default 10: each costs a sparse factorization, or two
    /// triangular solves with a reused one (see [`StretchOptions::refactor_period`]). With
    /// the over-relaxation below, 10 iterations leave the final cap map about as 25 plain ones
    /// did (mean |d_area| and |d_angle| within 2% on the shared meshes but the small bunny);
    /// 10 plain iterations left the hand's map worse.
    pub max_iterations: usize,
    /// Stop when the relative energy decrease falls below this. Default `1e-6`.
    pub tolerance: f64,
    /// Over-relaxation `omega` of each step: `f + omega (T(f) - f)`, where `T(f)` is the
    /// fixed-point update, kept when its energy is below the plain step's and it folds no more
    /// faces. Default 1.8 (the hand's energy ratio reached 1.0028 in 14 iterations against
    /// 25 plain ones); 1 is the plain iteration of Yueh et al.
    pub over_relaxation: f64,
    /// Iterations that factor their own matrix `L_S(f)`; each later one solves for the step
    /// `f - L_S(f)^-1 (L_S(f) f)` (the exact iteration, written with the energy's gradient
    /// `L_S(f) f`) with the last factorization instead, and factors its own only when that
    /// step does not lower the energy or folds faces, or when [`StretchOptions::refactor_period`]
    /// says so. Default 0 (the first iteration factors anyway; the closed surfaces' maps
    /// factor every other iteration by the period): with 3 and no period the closed surfaces'
    /// punctured maps, far from converged after 10 iterations, lost (bunny's final mean
    /// |d_area| 0.037 -> 0.042, 48k brain's energy ratio 5.5 -> 6.3); the open surfaces' maps
    /// use [`crate::param::OpenOptions::factored_iterations`] and no period.
    pub factored_iterations: usize,
    /// After the first `factored_iterations`, iteration `k` factors its own matrix when `k`
    /// is a multiple of this (0: never), so the iterations between reuse a factorization one
    /// step old. Default 2, the closed surfaces' flattening: 6-7 factorizations instead of 10
    /// (a stale step is tried at each odd iteration and kept 3-5 times), a lower final stretch
    /// energy on half of the shared closed meshes, and the same final cap maps to 0.5% (but the
    /// small bird skull and bunny, which move with any change). Every iteration factoring is
    /// `factored_iterations = usize::MAX`.
    pub refactor_period: usize,
}

impl StretchOptions {
    /// Set [`StretchOptions::max_iterations`].
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Set [`StretchOptions::tolerance`].
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Set [`StretchOptions::over_relaxation`] (1: the plain iteration).
    pub fn with_over_relaxation(mut self, over_relaxation: f64) -> Self {
        self.over_relaxation = over_relaxation;
        self
    }

    /// Set [`StretchOptions::factored_iterations`].
    pub fn with_factored_iterations(mut self, factored_iterations: usize) -> Self {
        self.factored_iterations = factored_iterations;
        self
    }

    /// Set [`StretchOptions::refactor_period`] (0: never refactor after `factored_iterations`).
    pub fn with_refactor_period(mut self, refactor_period: usize) -> Self {
        self.refactor_period = refactor_period;
        self
    }

    /// How many of the `max_iterations` factor their own matrix when every stale step is
    /// kept (each rejected one adds a factorization).
    pub fn planned_factorizations(&self) -> usize {
        (0..self.max_iterations).filter(|&it| self.factors_at(it)).count()
    }

    /// Whether iteration `it` factors its own matrix by the schedule (the first always does).
    fn factors_at(&self, it: usize) -> bool {
        it == 0 || it < self.factored_iterations || (self.refactor_period > 0 && it % self.refactor_period == 0)
    }
}

impl Default for StretchOptions {
    fn default() -> Self {
        Self { max_iterations: 10, tolerance: 1e-6, over_relaxation: 1.8, factored_iterations: 0, refactor_period: 2 }
    }
}

/// What the minimisation did.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct StretchReport {
    /// Iterations.
    pub iterations: usize,
    /// Iterations whose over-relaxed step was kept.
    pub over_relaxed: usize,
    /// Iterations that solved with an earlier iteration's factorization.
    pub reused_factorizations: usize,
    /// Energy before and after, divided by the minimum `(sum |f(T)|)^2 / sum |T|` (1 is
    /// perfectly equiareal).
    pub initial_energy_ratio: f64,
    /// See `initial_energy_ratio`.
    pub final_energy_ratio: f64,
}

/// `E_S(f) = sum_T |f(T)|^2 / |T|` with signed image areas.
pub fn stretch_energy(vertices: &[[f64; 3]], faces: &[[u32; 3]], f: &[[f64; 2]]) -> f64 {
    energy_with_areas(&source_areas(vertices, faces), faces, f)
}

/// `|T|` of every face.
fn source_areas(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<f64> {
    faces.par_iter().map(|t| triangle_area(vertices[t[0] as usize], vertices[t[1] as usize], vertices[t[2] as usize])).collect()
}

/// [`stretch_energy`] with the faces' areas `source` computed once (the minimisation
/// evaluates the energy two or three times per iteration); the terms in parallel, summed in
/// face order so that the result does not depend on the threads' split (the minimisation
/// compares energies).
fn energy_with_areas(source: &[f64], faces: &[[u32; 3]], f: &[[f64; 2]]) -> f64 {
    let terms: Vec<f64> = faces
        .par_iter()
        .zip(source)
        .map(|(t, &s)| {
            let img = signed_area_2d(f[t[0] as usize], f[t[1] as usize], f[t[2] as usize]);
            if s > 0.0 { img * img / s } else { 0.0 }
        })
        .collect();
    terms.iter().sum()
}

/// The gradient `2 L_S(f) f` of [`stretch_energy`].
pub fn stretch_gradient(vertices: &[[f64; 3]], faces: &[[u32; 3]], f: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let weights = corner_weights(&source_areas(vertices, faces), faces, f);
    laplacian_times(faces, &weights, f).into_iter().map(|x| [2.0 * x[0], 2.0 * x[1]]).collect()
}

/// `L(f) f` at every vertex for the Laplacian of the corner `weights`.
fn laplacian_times(faces: &[[u32; 3]], weights: &[[f64; 3]], f: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = vec![[0.0; 2]; f.len()];
    for (t, w) in faces.iter().zip(weights) {
        for k in 0..3 {
            let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
            for (a, b) in [(i, j), (j, i)] {
                out[a][0] += w[k] * (f[a][0] - f[b][0]);
                out[a][1] += w[k] * (f[a][1] - f[b][1]);
            }
        }
    }
    out
}

/// Per face, the weight of the edge opposite each corner (`source`: the faces' areas).
fn corner_weights(source: &[f64], faces: &[[u32; 3]], f: &[[f64; 2]]) -> Vec<[f64; 3]> {
    faces
        .par_iter()
        .zip(source)
        .map(|(t, &s)| {
            let [a, b, c] = t.map(|v| v as usize);
            if s <= 0.0 {
                return [0.0; 3];
            }
            let idx = [a, b, c];
            std::array::from_fn(|k| {
                let (o, i, j) = (idx[k], idx[(k + 1) % 3], idx[(k + 2) % 3]);
                let d = (f[i][0] - f[o][0]) * (f[j][0] - f[o][0]) + (f[i][1] - f[o][1]) * (f[j][1] - f[o][1]);
                d / (4.0 * s)
            })
        })
        .collect()
}

/// Marks a face side with a fixed end (no matrix entry).
const NO_EDGE: u32 = u32::MAX;

/// One right-hand side per planar coordinate, over the free vertices.
type RightHandSides = Vec<Vec<f64>>;

/// The layout of the stretch-energy matrices `L_S(f)` of one mesh: how many free-free edges
/// (free indices, `a < b`, sorted), their compressed-column pattern, and per face the edge of the
/// side opposite each corner. Each iteration sums its corner weights straight into edges
/// and diagonal through the value slots the pattern records
/// ([`GraphPattern::symmetric_on_keys`]) instead of sorting triplets and searching slots.
struct StretchLayout {
    n_free: usize,
    n_edges: usize,
    pattern: GraphPattern,
    face_edges: Vec<[u32; 3]>,
}

impl StretchLayout {
    fn new(faces: &[[u32; 3]], is_fixed: &[bool], index: &[usize], n_free: usize) -> Result<Self, FlattenError> {
        let side = |t: &[u32; 3], k: usize| -> Option<u64> {
            let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
            (!is_fixed[i] && !is_fixed[j]).then(|| {
                let (a, b) = (index[i].min(index[j]) as u64, index[i].max(index[j]) as u64);
                (a << 32) | b
            })
        };
        let mut keys: Vec<u64> = faces.iter().flat_map(|t| (0..3).filter_map(move |k| side(t, k))).collect();
        keys.sort_unstable();
        keys.dedup();
        let pattern = GraphPattern::new(n_free, &keys, "stretch energy")?;
        let face_edges = faces
            .iter()
            .map(|t| std::array::from_fn(|k| side(t, k).map_or(NO_EDGE, |key| keys.binary_search(&key).map_or(NO_EDGE, |e| e as u32))))
            .collect();
        Ok(Self { n_free, n_edges: keys.len(), pattern, face_edges })
    }

    /// `L_S(f)` on the free vertices for the corner `weights`, and the right-hand sides (the
    /// fixed vertices' terms) of `L_S(f) f = 0`.
    fn system(&self, faces: &[[u32; 3]], weights: &[[f64; 3]], f: &[[f64; 2]], is_fixed: &[bool], index: &[usize]) -> Result<(SparseColMat<usize, f64>, RightHandSides), FlattenError> {
        let n_free = self.n_free;
        let mut rhs = vec![vec![0.0; n_free], vec![0.0; n_free]];
        let mut diagonal = vec![0.0; n_free];
        // The off-diagonal entries, -(sum of the edge's corner weights), summed as such.
        let mut off_diagonal = vec![0.0; self.n_edges];
        for ((t, w), slots) in faces.iter().zip(weights).zip(&self.face_edges) {
            for k in 0..3 {
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                let wk = w[k];
                for (a, b) in [(i, j), (j, i)] {
                    if is_fixed[a] {
                        continue;
                    }
                    diagonal[index[a]] += wk;
                    if is_fixed[b] {
                        rhs[0][index[a]] += wk * f[b][0];
                        rhs[1][index[a]] += wk * f[b][1];
                    }
                }
                if slots[k] != NO_EDGE {
                    off_diagonal[slots[k] as usize] -= wk;
                }
            }
        }
        Ok((self.pattern.symmetric_on_keys(&diagonal, &off_diagonal, "stretch energy")?, rhs))
    }
}

/// Minimise the stretch energy from `initial` with the vertices in `fixed` held.
pub fn stretch_energy_map(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    fixed: &[(u32, [f64; 2])],
    initial: &[[f64; 2]],
    options: &StretchOptions,
) -> Result<(Vec<[f64; 2]>, StretchReport), FlattenError> {
    stretch_energy_map_with(vertices, faces, fixed, initial, options, &mut SpdSolver::new())
}

/// [`stretch_energy_map`] with `solver` (its symbolic factorization is reused when an
/// earlier system had the same free vertices).
pub(crate) fn stretch_energy_map_with(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    fixed: &[(u32, [f64; 2])],
    initial: &[[f64; 2]],
    options: &StretchOptions,
    solver: &mut SpdSolver,
) -> Result<(Vec<[f64; 2]>, StretchReport), FlattenError> {
    let n = vertices.len();
    let mut f = initial.to_vec();
    let (is_fixed, index, n_free) = pin(&mut f, fixed);
    let source = source_areas(vertices, faces);
    let surface_area: f64 = source.iter().sum();
    let ratio = |f: &[[f64; 2]]| {
        let img: f64 = faces.iter().map(|t| signed_area_2d(f[t[0] as usize], f[t[1] as usize], f[t[2] as usize])).sum();
        energy_with_areas(&source, faces, f) / (img * img / surface_area)
    };
    let mut report = StretchReport { initial_energy_ratio: ratio(&f), ..Default::default() };
    let mut energy = energy_with_areas(&source, faces, &f);
    let layout = StretchLayout::new(faces, &is_fixed, &index, n_free)?;
    // Whether `solver` holds a factorization of an earlier iteration's matrix, and whether
    // this iteration must factor its own (its stale step went uphill or folded faces).
    let (mut factored, mut fresh) = (false, false);
    let mut it = 0;
    while it < options.max_iterations {
        let weights = corner_weights(&source, faces, &f);
        if n_free == 0 {
            break;
        }
        let refactor = !factored || fresh || options.factors_at(it);
        let mut rhs = if refactor {
            let (mat, rhs) = layout.system(faces, &weights, &f, &is_fixed, &index)?;
            solver.factor(&mat, "stretch energy")?;
            factored = true;
            rhs
        } else {
            // The residual L_S(f) f of the free rows, solved with the last factorization.
            let mut rhs = vec![vec![0.0; n_free], vec![0.0; n_free]];
            for (v, r) in laplacian_times(faces, &weights, &f).into_iter().enumerate() {
                if !is_fixed[v] {
                    rhs[0][index[v]] = r[0];
                    rhs[1][index[v]] = r[1];
                }
            }
            rhs
        };
        solver.solve_in_place(&mut rhs, "stretch energy")?;
        let mut next = f.clone();
        for v in 0..n {
            if !is_fixed[v] {
                let x = index[v];
                next[v] = if refactor { [rhs[0][x], rhs[1][x]] } else { [f[v][0] - rhs[0][x], f[v][1] - rhs[1][x]] };
            }
        }
        let mut e = energy_with_areas(&source, faces, &next);
        if options.over_relaxation != 1.0 {
            let omega = options.over_relaxation;
            let over: Vec<[f64; 2]> = f.iter().zip(&next).map(|(a, b)| [a[0] + omega * (b[0] - a[0]), a[1] + omega * (b[1] - a[1])]).collect();
            let e_over = energy_with_areas(&source, faces, &over);
            if e_over < e && folded_faces(&over, faces).len() <= folded_faces(&next, faces).len() {
                next = over;
                e = e_over;
                report.over_relaxed += 1;
            }
        }
        // A stale matrix's step that goes uphill or folds faces the current map does not is
        // redone with this iteration's own matrix.
        if !refactor && (!(e <= energy) || folded_faces(&next, faces).len() > folded_faces(&f, faces).len()) {
            fresh = true;
            continue;
        }
        if !(e.is_finite()) || e > energy {
            report.iterations = it + 1;
            break;
        }
        fresh = false;
        if !refactor {
            report.reused_factorizations += 1;
        }
        it += 1;
        report.iterations = it;
        let decrease = (energy - e) / energy;
        f = next;
        energy = e;
        if decrease < options.tolerance {
            break;
        }
    }
    report.final_energy_ratio = ratio(&f);
    Ok((f, report))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cap::stereographic;
    use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};
    use crate::mesh::topology::is_boundary_vertex;

    #[test]
    fn assembled_system_is_half_the_energy_gradient() {
        // L_S(f) f = grad E_S / 2 on the free rows, with the fixed vertices' terms on the
        // right-hand side: the layout's matrix against `stretch_gradient`.
        let cap = spherical_cap(0.3, 10, spherical_cap_sectors(0.3, 10));
        let boundary = is_boundary_vertex(&cap);
        let mut f: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        for (v, p) in f.iter_mut().enumerate() {
            let t = v as f64 * 1.3;
            *p = [p[0] + 0.01 * t.sin(), p[1] + 0.01 * t.cos()];
        }
        let fixed: Vec<(u32, [f64; 2])> = (0..f.len()).filter(|&v| boundary[v]).map(|v| (v as u32, f[v])).collect();
        let (is_fixed, index, n_free) = pin(&mut f, &fixed);
        let layout = StretchLayout::new(&cap.faces, &is_fixed, &index, n_free).unwrap();
        let weights = corner_weights(&source_areas(&cap.vertices, &cap.faces), &cap.faces, &f);
        let (mat, rhs) = layout.system(&cap.faces, &weights, &f, &is_fixed, &index).unwrap();
        let gradient = stretch_gradient(&cap.vertices, &cap.faces, &f);
        let (col_ptr, row_idx, values) = (mat.symbolic().col_ptr(), mat.symbolic().row_idx(), mat.val());
        let mut checked = 0;
        for v in (0..f.len()).filter(|&v| !is_fixed[v]) {
            // Row index[v] of the symmetric matrix is its column.
            let c = index[v];
            let mut product = [0.0; 2];
            for k in col_ptr[c]..col_ptr[c + 1] {
                let u = (0..f.len()).find(|&u| !is_fixed[u] && index[u] == row_idx[k]).unwrap();
                product[0] += values[k] * f[u][0];
                product[1] += values[k] * f[u][1];
            }
            for d in 0..2 {
                let lhs = product[d] - rhs[d][c];
                assert!((lhs - 0.5 * gradient[v][d]).abs() < 1e-12 * (1.0 + gradient[v][d].abs()), "vertex {v}: {lhs} vs {}", 0.5 * gradient[v][d]);
            }
            checked += 1;
        }
        assert!(checked > 100);
    }
}
