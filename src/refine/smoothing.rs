//! Optional smoothing of the centroid map.
//!
//! The transport map moves each vertex to the centroid of its power cell, which is exact in
//! mass but noisy at the scale of one cell: a thin triangle can lose or gain most of its area
//! even though its vertices' cells have the right mass. The smoothed positions solve
//! `min sum_i tau_i |P_i - c_i|^2 + beta E_D(P)` with `E_D` the Dirichlet energy of the surface
//! (cotangent Laplacian) and `beta = kappa * mean(tau)`: beyond about one edge length the map
//! follows the transport map, below it the map is locally harmonic, so thin triangles keep
//! the area share of their neighbours. `kappa = 0` is the paper's plain centroid map.
//!
//! Large systems are solved by conjugate gradients from the centroids
//! ([`ITERATIVE_UNKNOWNS`]), the others (and any whose gradients stall) by sparse Cholesky.

use super::area_refine::{refine_areas, RefineOptions};
use crate::omt::planar_transport::TransportMap;
use super::untangle::{untangle, untangle_locally, PendingRepair, UntangleReport};
use crate::linalg::{jacobi_cg2_or_give_up, CotanWeights, SolveError, SpdSolver};
use faer::sparse::SparseColMat;
use crate::metrics::{area_distortion, Stats};
use rayon::prelude::*;

/// Smooths centroid maps of one mesh; keeps the factorization's symbolic part (clones share
/// it, see [`CentroidSmoother::prime`]).
#[derive(Clone)]
pub struct CentroidSmoother<'a> {
    weights: &'a CotanWeights,
    fixed: &'a [bool],
    solver: SpdSolver,
    /// Factor every system, however large: conjugate gradients gave up on one
    /// ([`CentroidSmoother::prime`]).
    factored: bool,
}

impl<'a> CentroidSmoother<'a> {
    /// A smoother for the mesh whose cotangent weights are `weights`; `fixed` vertices keep
    /// their centroid.
    pub fn new(weights: &'a CotanWeights, fixed: &'a [bool]) -> Self {
        Self { weights, fixed, solver: SpdSolver::new(), factored: false }
    }

    /// Prepare the smoothing of centroids `c` with masses `tau` at several strengths, `kappa`
    /// (> 0) first, so that clones of the smoother solve the others. A system above
    /// [`ITERATIVE_UNKNOWNS`] is tried by conjugate gradients at `kappa`: if they converge,
    /// their solution is returned and the other strengths are tried the same way; if they
    /// give up, every strength is factored without trying them (on a 124k marching-cubes
    /// surface they gave up on all four strengths the search tried, after 300 iterations
    /// each). A factored system's symbolic factorization (every `kappa > 0` gives the same
    /// pattern) is computed here, so that clones factor numerically only.
    pub fn prime(&mut self, c: &[[f64; 2]], tau: &[f64], kappa: f64) -> Result<Option<Vec<[f64; 2]>>, SolveError> {
        if self.iterative() {
            if let Some(p) = self.smooth_iteratively(c, tau, kappa) {
                return Ok(Some(p));
            }
            self.factored = true;
        }
        if let Some((mat, _, _)) = self.system(c, tau, 1.0)? {
            self.solver.analyze(&mat, "centroid smoothing")?;
        }
        Ok(None)
    }

    /// Smoothed positions for centroids `c` with masses `tau`.
    pub fn smooth(&mut self, c: &[[f64; 2]], tau: &[f64], kappa: f64) -> Result<Vec<[f64; 2]>, SolveError> {
        if kappa <= 0.0 {
            return Ok(c.to_vec());
        }
        if self.iterative() {
            if let Some(p) = self.smooth_iteratively(c, tau, kappa) {
                return Ok(p);
            }
        }
        self.smooth_factored(c, tau, kappa)
    }

    /// [`CentroidSmoother::smooth`] by sparse Cholesky.
    fn smooth_factored(&mut self, c: &[[f64; 2]], tau: &[f64], kappa: f64) -> Result<Vec<[f64; 2]>, SolveError> {
        let Some((mat, mut rhs, index)) = self.system(c, tau, kappa)? else { return Ok(c.to_vec()) };
        self.solver.factor(&mat, "centroid smoothing")?;
        self.solver.solve_in_place(&mut rhs, "centroid smoothing")?;
        Ok((0..c.len()).map(|v| index[v].map_or(c[v], |i| [rhs[0][i], rhs[1][i]])).collect())
    }

    /// Whether the systems are tried by conjugate gradients: more than
    /// [`ITERATIVE_UNKNOWNS`] unknowns, and no give-up in [`CentroidSmoother::prime`].
    fn iterative(&self) -> bool {
        !self.factored && self.fixed.iter().filter(|&&f| !f).count() > ITERATIVE_UNKNOWNS
    }

    /// [`CentroidSmoother::smooth`] by conjugate gradients from the centroids; `None` when
    /// they do not converge within [`ITERATIVE_MAX_ITERATIONS`] or give up before
    /// ([`jacobi_cg2_or_give_up`]).
    fn smooth_iteratively(&self, c: &[[f64; 2]], tau: &[f64], kappa: f64) -> Option<Vec<[f64; 2]>> {
        let n = c.len();
        let beta = kappa * tau.iter().sum::<f64>() / n as f64;
        let free = |v: usize| !self.fixed[v];
        // Fixed vertices are unknowns too, with the equation x = c (diagonal 1).
        let mut diagonal: Vec<f64> = (0..n).map(|v| if free(v) { tau[v] } else { 1.0 }).collect();
        let mut rhs: Vec<[f64; 2]> = (0..n).map(|v| if free(v) { [tau[v] * c[v][0], tau[v] * c[v][1]] } else { c[v] }).collect();
        let mut coupled: Vec<(u32, u32, f64)> = Vec::with_capacity(self.weights.edges.len());
        for (&(a, b), &w) in self.weights.edges.iter().zip(&self.weights.weights) {
            let (i, j, w) = (a as usize, b as usize, beta * w);
            for (x, y) in [(i, j), (j, i)] {
                if free(x) {
                    diagonal[x] += w;
                    if !free(y) {
                        rhs[x][0] += w * c[y][0];
                        rhs[x][1] += w * c[y][1];
                    }
                }
            }
            if free(i) && free(j) {
                coupled.push((a, b, w));
            }
        }
        let apply = |x: &[[f64; 2]], y: &mut [[f64; 2]]| {
            for ((y, x), d) in y.iter_mut().zip(x).zip(&diagonal) {
                *y = [d * x[0], d * x[1]];
            }
            for &(a, b, w) in &coupled {
                let (a, b) = (a as usize, b as usize);
                y[a] = [y[a][0] - w * x[b][0], y[a][1] - w * x[b][1]];
                y[b] = [y[b][0] - w * x[a][0], y[b][1] - w * x[a][1]];
            }
        };
        let mut x = c.to_vec();
        jacobi_cg2_or_give_up(apply, &diagonal, &rhs, &mut x, ITERATIVE_TOLERANCE, ITERATIVE_MAX_ITERATIONS).converged.then_some(x)
    }

    /// The smoothing system (matrix, right-hand sides, free-vertex numbering) for `kappa`;
    /// `None` when no vertex is free.
    #[allow(clippy::type_complexity)]
    fn system(&self, c: &[[f64; 2]], tau: &[f64], kappa: f64) -> Result<Option<(SparseColMat<usize, f64>, Vec<Vec<f64>>, Vec<Option<usize>>)>, SolveError> {
        let n = c.len();
        let beta = kappa * tau.iter().sum::<f64>() / n as f64;
        let mut index = vec![None; n];
        let mut m = 0;
        for v in 0..n {
            if !self.fixed[v] {
                index[v] = Some(m);
                m += 1;
            }
        }
        if m == 0 {
            return Ok(None);
        }
        let mut trip = self.weights.restricted_laplacian(&index, m, |w| beta * w);
        let mut rhs = vec![vec![0.0; m], vec![0.0; m]];
        for v in 0..n {
            if let Some(i) = index[v] {
                trip.push(i, i, tau[v]);
                rhs[0][i] += tau[v] * c[v][0];
                rhs[1][i] += tau[v] * c[v][1];
            }
        }
        for (&(a, b), &w) in self.weights.edges.iter().zip(&self.weights.weights) {
            for (x, y) in [(a, b), (b, a)] {
                if let (Some(i), true) = (index[x as usize], self.fixed[y as usize]) {
                    rhs[0][i] += beta * w * c[y as usize][0];
                    rhs[1][i] += beta * w * c[y as usize][1];
                }
            }
        }
        Ok(Some((trip.assemble("centroid smoothing")?, rhs, index)))
    }
}

/// Above this many free vertices the smoothing systems are solved by conjugate gradients
/// (Jacobi preconditioner, from the centroids, [`crate::linalg::jacobi_cg2_or_give_up`]) instead of a
/// sparse Cholesky factorization, which each candidate `kappa` needs anew: on the large
/// meshes a few dozen iterations at [`ITERATIVE_TOLERANCE`] beat a factorization. The small
/// systems, where the factorization is as fast, and any that does not converge within
/// [`ITERATIVE_MAX_ITERATIONS`] (a lung lobe's cotangent weights span many orders of
/// magnitude) are factored.
pub const ITERATIVE_UNKNOWNS: usize = 20_000;

/// Relative residual at which the smoothing's conjugate gradients stop.
pub const ITERATIVE_TOLERANCE: f64 = 1e-10;

/// Conjugate-gradient iterations after which the smoothing system is factored instead.
pub const ITERATIVE_MAX_ITERATIONS: usize = 300;

/// How the centroid map is smoothed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Smoothing {
    /// Walk the grid `AUTO_KAPPAS` (0 included) from `kappa = 1` towards smaller measured
    /// mean `|d_area|` after fold repair and 4 sweeps of area refinement on a copy, and keep
    /// the grid's local minimum (docs/method.md section 8). The default.
    #[default]
    Auto,
    /// A fixed `kappa` (0 is the paper's plain centroid map).
    Fixed(f64),
}

impl std::str::FromStr for Smoothing {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s == "auto" {
            return Ok(Smoothing::Auto);
        }
        s.parse::<f64>()
            .ok()
            .filter(|k| k.is_finite() && *k >= 0.0)
            .map(Smoothing::Fixed)
            .ok_or_else(|| format!("smoothing must be 'auto' or a number >= 0, not '{s}'"))
    }
}

/// The candidates of [`Smoothing::Auto`].
pub const AUTO_KAPPAS: [f64; 7] = [0.0, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0];

/// One tried smoothing strength.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct SmoothingTrial {
    /// Strength.
    pub kappa: f64,
    /// Mean `|d_area|` on the cap after fold repair and, when no fold is left and the strength
    /// was searched ([`Smoothing::Auto`]), 4 sweeps of area refinement on a copy (the
    /// candidates' score).
    pub mean_abs_area_distortion: f64,
    /// Folded faces before repair.
    pub folded_before_repair: usize,
    /// Folded faces after it: more than 0 when even the convex-combination solves failed, or
    /// when they were not run because another strength was fold-free without them.
    pub folded_after_repair: usize,
}

/// The smoothed map that was kept.
#[derive(Debug, Clone)]
pub struct SmoothedMap {
    /// Strength used.
    pub kappa: f64,
    /// Final planar positions (folds repaired).
    pub positions: Vec<[f64; 2]>,
    /// The fold repair of the kept map.
    pub untangle: UntangleReport,
    /// Every strength tried.
    pub trials: Vec<SmoothingTrial>,
}

/// Rings around the puncture of a closed surface that the smoothing leaves at their centroids
/// (see [`crate::mesh::topology::within_rings`]).
///
/// Near the puncture the stereographic density is tiny at the closed surfaces' radius
/// (`Z* = -0.9945`, `r* = 19`), so a few vertices span the outer half of the disk with faces
/// a tenth of the radius long; the Dirichlet term drags them, the fold repair's local solves
/// cannot untangle what that folds, and its whole-mesh solve (four fixed corners) squeezes
/// the map. Measured on the synthetic 41k ellipsoid at `kappa = 3`: mean `|d_area|` 0.59 with
/// no ring held, 0.0062 with 3 (6 and 10 rings: 0.0060, 0.0058); on the 164k ellipsoid
/// every `kappa > 0` collapsed without it. Open surfaces hold none: the hippocampal sheet lost (0.0219 -> 0.0235).
pub const PUNCTURE_HELD_RINGS: usize = 3;

/// Lifts a planar point onto the domain where areas are measured (the cap or the disk).
pub type ToDomain<'a> = dyn Fn([f64; 2]) -> [f64; 3] + Sync + 'a;

/// Sweeps of the area refinement ([`super::area_refine`]) a candidate of [`Smoothing::Auto`]
/// is scored after: the refinement that follows removes the noise of a weakly smoothed map
/// but not the broad area error a strong Dirichlet term leaves, so the candidates are ranked
/// by what the refinement leaves them. Scored before it, the search kept `kappa = 10` on a
/// 60k marching-cubes ellipsoid (final mean |d_area| 0.0041; `kappa = 3`: 0.0029) and on its
/// 519k copy's decimated level (0.0076 after prolongation; `kappa = 1`: 0.0054), `kappa = 3`
/// on the lung lobe (0.0184; `kappa = 1`: 0.0148) (docs/method.md, "Smoothing").
pub(crate) const SCORE_SWEEPS: usize = 4;

/// Smooth the transport map `map` of the surface `(vertices, faces)`, repair its folds
/// and keep the candidate with no fold left and the smallest mean `|d_area|` measured on the
/// domain after [`SCORE_SWEEPS`] sweeps of area refinement (`to_domain` lifts planar points
/// onto the cap or the planar disk). `fixed`
/// vertices (the boundary) never move; `held` vertices (a superset, see
/// [`PUNCTURE_HELD_RINGS`]) are not smoothed but the fold repair may move them.
/// The candidates are independent and evaluated in parallel.
#[allow(clippy::too_many_arguments)]
pub fn smooth_centroid_map(
    map: &TransportMap,
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    weights: &CotanWeights,
    fixed: &[bool],
    held: &[bool],
    radius: f64,
    smoothing: Smoothing,
    to_domain: &ToDomain<'_>,
) -> Result<SmoothedMap, SolveError> {
    // One symbolic factorization for all candidates (they run in parallel on clones), or
    // conjugate gradients for all, as the first strength the walk tries decides.
    let mut primed = CentroidSmoother::new(weights, held);
    let first = AUTO_KAPPAS[AUTO_START];
    let probed = if smoothing == Smoothing::Auto { primed.prime(&map.centroids, &map.masses, first)? } else { None };
    let evaluate = |kappa: f64| -> Result<Candidate, SolveError> {
        let mut p = match &probed {
            Some(p) if kappa == first => p.clone(),
            _ => primed.clone().smooth(&map.centroids, &map.masses, kappa)?,
        };
        let (rep, pending) = match untangle_locally(&mut p, faces, fixed, radius) {
            Ok(rep) => (rep, None),
            Err(pending) => (pending.report_so_far(&p, radius), Some(pending)),
        };
        Ok(Candidate::new(kappa, p, rep, pending, vertices, faces, fixed, to_domain, SCORE_SWEEPS))
    };
    // The convex-combination solves of a candidate its local repair left folded.
    let finish = |c: &mut Candidate| {
        if let Some(pending) = c.pending.take() {
            let rep = pending.finish(&mut c.kept.positions, faces, fixed, radius);
            *c = Candidate::new(c.kept.kappa, std::mem::take(&mut c.kept.positions), rep, None, vertices, faces, fixed, to_domain, SCORE_SWEEPS);
        }
    };
    let mut done: Vec<Candidate> = match smoothing {
        Smoothing::Fixed(k) => {
            let mut p = primed.clone().smooth(&map.centroids, &map.masses, k)?;
            let rep = untangle(&mut p, faces, fixed, radius);
            // One candidate: nothing to rank, measured as it is.
            vec![Candidate::new(k, p, rep, None, vertices, faces, fixed, to_domain, 0)]
        }
        Smoothing::Auto => walk_grid(&evaluate, &finish)?,
    };
    let best = best_of(done.iter()).ok_or(SolveError::Singular { what: "centroid-map smoothing (no candidate)" })?;
    let trials = done.iter().map(|c| c.trial).collect();
    let mut kept = done.swap_remove(best).kept;
    kept.trials = trials;
    Ok(kept)
}

/// Position of the candidate with the smallest key (the first of equals); `None` when there
/// is none.
fn best_of<'c>(candidates: impl Iterator<Item = &'c Candidate>) -> Option<usize> {
    candidates.enumerate().fold(None, |best: Option<(usize, &Candidate)>, (i, c)| match best {
        Some((j, b)) if !(c.key < b.key) => Some((j, b)),
        _ => Some((i, c)),
    }).map(|(i, _)| i)
}

/// Mean `|d_area|` above which the local search of [`Smoothing::Auto`] evaluates the whole
/// grid (the threshold of the CLI's poor-map warning).
pub const WALK_TRUST: f64 = 0.3;

/// Where [`Smoothing::Auto`] starts on [`AUTO_KAPPAS`] (`kappa = 1`).
const AUTO_START: usize = 4;

/// The local search of [`Smoothing::Auto`]: the start and its two neighbours, then, while
/// the best candidate has a neighbour on the grid not yet evaluated, that neighbour and the
/// next one beyond it (two at a time, in parallel). On the eleven shared meshes the measured
/// distortion is unimodal on the grid, so this finds the grid's minimum with 3 to 5
/// evaluations instead of 7; the ones left out are the most expensive (small `kappa` leaves
/// hundreds of folds to repair on the hand). When the best
/// found is still poor (mean `|d_area|` above [`WALK_TRUST`], or a fold left) the rest of the
/// grid is evaluated too: on the synthetic 164k-vertex ellipsoid every `kappa > 0` collapses
/// (mean `|d_area|` 1.5 to 2.4) and only the plain map (`kappa = 0`) is good.
///
/// A candidate whose local fold repair left folds ([`PendingRepair`]) counts as folded while
/// the grid is walked; its convex-combination solves are made only when no candidate is
/// fold-free without them (`settle`): on the 1M-vertex ellipsoid they took half of the
/// whole run for a strength that lost.
fn walk_grid(evaluate: &(dyn Fn(f64) -> Result<Candidate, SolveError> + Sync), finish: &(dyn Fn(&mut Candidate) + Sync)) -> Result<Vec<Candidate>, SolveError> {
    let mut done: Vec<(usize, Candidate)> = Vec::new();
    // The grid points `indices`, in parallel, added to `done`.
    let evaluate_all = |indices: &[usize], done: &mut Vec<(usize, Candidate)>| -> Result<(), SolveError> {
        let batch: Vec<Candidate> = indices.par_iter().map(|&i| evaluate(AUTO_KAPPAS[i])).collect::<Result<_, _>>()?;
        done.extend(indices.iter().copied().zip(batch));
        Ok(())
    };
    let mut next: Vec<usize> = vec![AUTO_START - 1, AUTO_START, AUTO_START + 1];
    while !next.is_empty() {
        evaluate_all(&next, &mut done)?;
        let Some(best) = best_of(done.iter().map(|(_, c)| c)) else { break };
        let at = done[best].0;
        let seen = |i: usize| done.iter().any(|(j, _)| *j == i);
        next.clear();
        if at > 0 && !seen(at - 1) {
            next.extend([at - 1, at.saturating_sub(2)].into_iter().filter(|&i| !seen(i)));
        } else if at + 1 < AUTO_KAPPAS.len() && !seen(at + 1) {
            next.extend([at + 1, (at + 2).min(AUTO_KAPPAS.len() - 1)].into_iter().filter(|&i| !seen(i)));
        }
        next.dedup();
    }
    // When every candidate is folded, the convex-combination solves of all that need them.
    let settle = |done: &mut Vec<(usize, Candidate)>| {
        if best_of(done.iter().map(|(_, c)| c)).is_some_and(|b| done[b].1.key.0) {
            done.par_iter_mut().for_each(|(_, c)| finish(c));
        }
    };
    settle(&mut done);
    let poor = best_of(done.iter().map(|(_, c)| c)).is_some_and(|b| done[b].1.key.0 || !(done[b].1.key.1 <= WALK_TRUST));
    if poor {
        let rest: Vec<usize> = (0..AUTO_KAPPAS.len()).filter(|i| !done.iter().any(|(j, _)| j == i)).collect();
        evaluate_all(&rest, &mut done)?;
        settle(&mut done);
    }
    done.sort_by_key(|(i, _)| *i);
    Ok(done.into_iter().map(|(_, c)| c).collect())
}

/// One evaluated smoothing strength.
struct Candidate {
    /// (any fold left, mean `|d_area|`), compared lexicographically.
    key: (bool, f64),
    trial: SmoothingTrial,
    kept: SmoothedMap,
    /// The convex-combination solves still to be made, if the local repair left folds.
    pending: Option<PendingRepair>,
}

impl Candidate {
    /// The candidate of strength `kappa` at planar positions `p` after the repair `rep`,
    /// measured on the domain after `score_sweeps` sweeps of area refinement on a copy.
    #[allow(clippy::too_many_arguments)]
    fn new(kappa: f64, p: Vec<[f64; 2]>, rep: UntangleReport, pending: Option<PendingRepair>, vertices: &[[f64; 3]], faces: &[[u32; 3]], fixed: &[bool], to_domain: &ToDomain<'_>, score_sweeps: usize) -> Self {
        // A folded candidate is not refined (the refinement keeps orientations, it does not
        // repair them): it ranks behind every fold-free one anyway.
        let lifted: Vec<[f64; 3]> = if rep.folded_after == 0 && score_sweeps > 0 {
            let mut q = p.clone();
            refine_areas(&mut q, vertices, faces, fixed, to_domain, RefineOptions::default().with_sweeps(score_sweeps));
            q.iter().map(|&x| to_domain(x)).collect()
        } else {
            p.iter().map(|&x| to_domain(x)).collect()
        };
        let d = Stats::of(area_distortion(vertices, &lifted, faces)).mean_abs;
        let trial = SmoothingTrial { kappa, mean_abs_area_distortion: d, folded_before_repair: rep.folded_before, folded_after_repair: rep.folded_after };
        Self { key: (rep.folded_after > 0, d), trial, kept: SmoothedMap { kappa, positions: p, untangle: rep, trials: Vec::new() }, pending }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cap::stereographic;
    use crate::linalg::cotangent_weights;
    use crate::mesh::geometry::vertex_areas;
    use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};
    use crate::mesh::topology::is_boundary_vertex;

    #[test]
    fn conjugate_gradients_and_the_factorization_smooth_alike() {
        let cap = spherical_cap(0.0, 90, spherical_cap_sectors(0.0, 90));
        let fixed = is_boundary_vertex(&cap);
        assert!(fixed.iter().filter(|&&f| !f).count() > ITERATIVE_UNKNOWNS, "{} vertices", cap.vertices.len());
        // Centroids: the stereographic image with a deterministic jitter of the interior.
        let c: Vec<[f64; 2]> = cap
            .vertices
            .iter()
            .enumerate()
            .map(|(v, &p)| {
                let q = stereographic(p);
                let t = v as f64 * 2.399;
                if fixed[v] { q } else { [q[0] + 0.003 * t.sin(), q[1] + 0.003 * t.cos()] }
            })
            .collect();
        let tau = vertex_areas(&cap.vertices, &cap.faces);
        let weights = cotangent_weights(&cap.vertices, &cap.faces);
        let mut smoother = CentroidSmoother::new(&weights, &fixed);
        for kappa in [0.3, 3.0] {
            let iterative = smoother.smooth_iteratively(&c, &tau, kappa).expect("conjugate gradients converge on a regular cap");
            let factored = smoother.smooth_factored(&c, &tau, kappa).unwrap();
            let moved = c.iter().zip(&factored).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
            let apart = iterative.iter().zip(&factored).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
            // The unit disk's radius is 1 and edges are about 0.02 long: the smoothing moves
            // vertices by more than 1e-3, the two solutions agree to 1e-6.
            assert!(moved > 1e-3 && apart < 1e-6, "kappa {kappa}: smoothing moved {moved:e}, solutions {apart:e} apart");
            assert_eq!(smoother.smooth(&c, &tau, kappa).unwrap(), iterative);
        }
    }
}
