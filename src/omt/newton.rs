//! Damped Newton method for semi-discrete optimal transport (Kitagawa, Mérigot and Thibert
//! 2019), as used by the paper through Zhao et al. 2013 (Sec. 2.2, Eq. 8).
//!
//! Unknowns are the power weights `w` (the paper's heights `h` with `w_i = |y_i|^2 + 2 h_i`).
//! The gradient of the concave Kantorovich functional is `tau - m(w)` and its Hessian is the
//! weighted graph Laplacian of the power diagram ([`super::cells`]). Each step solves
//! `H dw = tau - m(w)` (one weight pinned: the diagram is invariant under a common shift) by
//! sparse Cholesky, then halves the step until every cell keeps at least `epsilon` mass and
//! the mass error drops by the factor `1 - alpha / 2`. While the mass error is above 1% the
//! step of the logarithmic masses (same matrix, another right-hand side) is tried first
//! ([`super::options::LOG_STEP_ERROR`], ours), shortened by `1/sqrt 2` at a time down to 0.2
//! ([`super::options::LOG_STEP_SHRINK`], ours). When that stalls, a continuation on the target masses takes
//! over ([`OtSolver::solve`]).
//!
//! A cold solve (Voronoi start) of a large mesh spends most of its iterations damped: on the
//! 53k hand at `r*`, with plain steps only, 7 of 11 steps (of 10 at the parameterization's
//! tolerance) are shortened, every time because the flips to the new weights fail (the
//! logarithmic steps halved took 8 in all, 4 of them shortened, to 1/4 or 1/2; shortened by
//! `1/sqrt 2`, 6, 3 of them shortened, to 0.35, 0.5 and 0.71). That is not a weakness
//! of the flips: at the first full step 34809 of the 53054 sites have no cell at all (checked
//! with qhull on the lifted points), so the damping is inherent. Three starts were measured
//! and dropped: the coarse level's weights interpolated to every site (sites become
//! redundant even at 1/8 of them, see [`crate::omt::coarse_level`]); weights rebuilt from the
//! coarse centroid map prolonged to every site, through the Legendre dual
//! `h_i = (|p_i|^2 - w_i) / 2` whose gradient at a site is its cell's centroid (least squares
//! `h_j - h_i = (p_j - p_i) . (c_i + c_j) / 2` on the mesh edges; sites redundant on the face,
//! the hand and the 48k brain, and at 1/8 of the weights the hand took 10 steps instead of
//! 11: the vertex areas vary at the fine scale, which a coarse map cannot see); and the
//! weights of the radial transport of a uniform site density onto the stereographic one
//! (hand 11 -> 10 iterations, but the 48k brain 9 -> 17: a punctured closed surface's sites
//! fill a square, not the disk).
//! Nor does starting each line search at twice the last accepted step (it would skip the
//! rejected trials): the full-resolution steps then went from 15 to 26 on the
//! lung lobe and 9 to 10 on the 48k brain.

use super::cells::{cell_moments, integrate_masses_with, CellIntegrals, MassScratch};
use std::sync::{Mutex, MutexGuard};
use super::density::RadialDensity;
use super::triangulation::RegularTriangulation;
use crate::linalg::{GraphPattern, SolveError, SpdSolver};
use crate::progress::{self, Cancelled, Progress, Stage};
use super::options::{OmtError, OtOptions, OtReport, LOG_FINE_BACKTRACKING, LOG_MIN_STEP, STALE_STEP_GAIN};
use super::pattern::{count_missing, interior_edge_keys, sorted_union};

enum NewtonFailure {
    Stalled { iteration: usize, error: f64 },
    Linear(SolveError),
    Cancelled(Cancelled),
}


/// `m_i (ln(tau_i / m_i) + c)`, with `c` such that the entries sum to 0 (cells without mass
/// take `tau_i - m_i`).
fn logarithmic_residual(mass: &[f64], tau: &[f64]) -> Vec<f64> {
    let mut r: Vec<f64> = mass.iter().zip(tau).map(|(&m, &t)| if m > 0.0 { m * (t / m).ln() } else { t - m }).collect();
    let c = -r.iter().sum::<f64>() / mass.iter().sum::<f64>();
    for (r, &m) in r.iter_mut().zip(mass) {
        *r += c * m;
    }
    r
}

/// A continuation segment ([`OtSolver::solve`]) gives up, and the continuation takes a shorter
/// one, after this many accepted Newton steps in a row each shorter than [`FALLING_STEP`] and
/// than the step before: such a segment was failing. On synthetic long bones
/// (`benchmarks/external.py`) the failing segments' steps fell by a factor 2-8 each until the
/// solve stalled at `OtOptions::min_step` 3-5 steps later, while the segments that succeeded
/// took one or two short steps before a full one (docs/method.md, "2. Logarithmic and stale
/// Newton steps, continuation").
const FALLING_STEPS: usize = 2;

/// See [`FALLING_STEPS`].
const FALLING_STEP: f64 = 1.0 / 16.0;

/// Fraction of new edges above which the Newton matrices' kept pattern restarts from the
/// current edges instead of growing (see [`OtSolver::update_pattern`]).
const MOVING_PATTERN: f64 = 0.02;

/// Above this many sites the Newton matrices are ordered by geometric nested dissection on
/// the sites ([`crate::linalg::nested_dissection`]) instead of AMD: each step's pattern is new
/// (flips), so the ordering is computed every step, and AMD's took as long as the numeric
/// factorization. Below this the two do not differ measurably, so the small systems keep AMD.
/// The flattening keeps AMD too: on a folded surface's 3D positions, or on the harmonic map's
/// planar ones, the dissection's cuts are long and its factor larger.
pub const NESTED_DISSECTION_SITES: usize = 20_000;

/// A semi-discrete transport solver for fixed sites on the disk of radius `r`; it keeps its
/// triangulation and weights so that a new radius or new targets start warm.
pub struct OtSolver<'d> {
    tri: RegularTriangulation,
    radius: f64,
    density: &'d dyn RadialDensity,
    linear: SpdSolver,
    /// Off-diagonal pattern `(i << 32) | j`, `0 < i < j`, of the Newton matrices (sorted):
    /// a superset of the current triangulation's edges (see [`OtSolver::update_pattern`]).
    pattern: Vec<u64>,
    /// The Newton matrices' layout on [`OtSolver::pattern`] (rebuilt with it).
    hessian_pattern: GraphPattern,
    /// The integrals at the current weights, when [`OtSolver::try_weights`] computed them
    /// (taken by the next [`OtSolver::solve`], dropped by [`OtSolver::rescale`]).
    current: Option<CellIntegrals>,
    /// The trial steps' buffers, kept from one trial to the next (a lock, as a trial borrows
    /// the solver shared; trials run one at a time).
    scratch: Mutex<TrialScratch>,
}

/// Buffers of [`OtSolver`]'s trial steps: a large mesh's trial steps wrote some 250 MB of
/// fresh memory each (the 776k brain), which on a virtual machine costs page faults
/// (docs/method.md section 20).
#[derive(Default)]
struct TrialScratch {
    /// A triangulation to copy the current one into (a rejected trial's, or the one an
    /// accepted trial replaced).
    spare: Option<RegularTriangulation>,
    /// [`RegularTriangulation::update_weights_with`]'s edge stack.
    stack: Vec<(u32, u8)>,
    /// [`integrate_masses_with`]'s buffers.
    masses: MassScratch,
}

impl<'d> OtSolver<'d> {
    /// A solver for `sites` on the disk of radius `radius` with source `density`.
    pub fn new(sites: &[[f64; 2]], radius: f64, density: &'d dyn RadialDensity) -> Result<Self, OmtError> {
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(OmtError::Invalid(format!("radius {radius} must be positive")));
        }
        let tri = RegularTriangulation::delaunay(sites)?;
        let mut linear = SpdSolver::new();
        if sites.len() > NESTED_DISSECTION_SITES {
            // Unknowns are the sites but the pinned first one.
            linear.set_positions(sites.iter().skip(1).copied().collect());
        }
        let hessian_pattern = GraphPattern::new(sites.len().saturating_sub(1), &[], "transport Hessian")?;
        Ok(Self { tri, radius, density, linear, pattern: Vec::new(), hessian_pattern, current: None, scratch: Mutex::default() })
    }

    /// The current radius.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The current weights.
    pub fn weights(&self) -> &[f64] {
        &self.tri.weights
    }

    /// The current sites.
    pub fn sites(&self) -> &[[f64; 2]] {
        &self.tri.sites
    }

    /// Scale sites, weights and the disk by `s`: the regular triangulation is unchanged, so
    /// this is the warm start of the radius search.
    pub fn rescale(&mut self, s: f64) {
        self.current = None;
        for p in &mut self.tri.sites {
            p[0] *= s;
            p[1] *= s;
        }
        for w in &mut self.tri.weights {
            *w *= s * s;
        }
        self.radius *= s;
    }

    /// Take `weights` instead of the current ones when the regular triangulation reaches them
    /// by flips and every cell keeps at least half the smallest target mass (`target`
    /// normalised as in [`OtSolver::solve`]): a predicted warm start. Their integrals are kept
    /// for the next solve. Returns whether they were taken. (Also requiring a smaller mass
    /// error than the current weights' cost one more integration per call and changed no
    /// choice on the shared meshes.)
    pub fn try_weights(&mut self, weights: &[f64], target: &[f64]) -> bool {
        if weights.len() != self.tri.weights.len() || target.len() != weights.len() {
            return false;
        }
        let total: f64 = target.iter().sum();
        if total.is_nan() || total <= 0.0 {
            return false;
        }
        let min_tau = self.scaled_to_disk(target).into_iter().fold(f64::INFINITY, f64::min);
        let Some((trial, c)) = self.reweighted(weights) else { return false };
        let min_m = c.mass.iter().cloned().fold(f64::INFINITY, f64::min);
        let keep = min_m >= 0.5 * min_tau;
        if keep {
            self.accept(trial);
            self.current = Some(c);
        } else {
            self.recycle(trial);
        }
        keep
    }

    /// `target` scaled to sum to the disk's mass: the masses [`OtSolver::solve`] aims at.
    fn scaled_to_disk(&self, target: &[f64]) -> Vec<f64> {
        let total: f64 = target.iter().sum();
        let disk = self.density.disk_mass(self.radius);
        target.iter().map(|t| t * disk / total).collect()
    }

    /// The triangulation with `weights` and its integrals; `None` when flips cannot reach
    /// them (a site became redundant).
    fn reweighted(&self, weights: &[f64]) -> Option<(RegularTriangulation, CellIntegrals)> {
        let mut scratch = self.trial_scratch();
        let scratch = &mut *scratch;
        let mut tri = match scratch.spare.take() {
            Some(mut spare) => {
                spare.copy_from(&self.tri);
                spare
            }
            None => self.tri.clone(),
        };
        if !tri.update_weights_with(weights, &mut scratch.stack) {
            scratch.spare = Some(tri);
            return None;
        }
        let c = integrate_masses_with(&tri, self.radius, self.density, &mut scratch.masses);
        Some((tri, c))
    }

    /// The trial steps' buffers (a poisoned lock still holds usable buffers: a panic there
    /// left nothing half-written that the next trial reads before overwriting).
    fn trial_scratch(&self) -> MutexGuard<'_, TrialScratch> {
        self.scratch.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Keep a triangulation no longer needed for the next trial to copy into.
    fn recycle(&self, tri: RegularTriangulation) {
        self.trial_scratch().spare = Some(tri);
    }

    /// Make `tri` the current triangulation (an accepted trial), the old one recycled.
    fn accept(&mut self, tri: RegularTriangulation) {
        let old = std::mem::replace(&mut self.tri, tri);
        self.recycle(old);
    }

    /// Cell masses and Hessian entries at the current weights (no moments).
    fn integrals(&self) -> CellIntegrals {
        integrate_masses_with(&self.tri, self.radius, self.density, &mut self.trial_scratch().masses)
    }

    /// Solve for weights whose cells carry the masses `target` (rescaled to sum to the disk's
    /// mass). Returns the final integrals and a report.
    ///
    /// Damped Newton is tried first. When it stalls (a strongly compressing initial map leaves
    /// cells many orders of magnitude too small), the solver continues along geometric
    /// interpolations of the targets `m0^(1-t) tau^t` from the current masses `m0`, with
    /// Newton solving each step and `t` advancing as fast as Newton allows.
    pub fn solve(
        &mut self,
        target: &[f64],
        options: &OtOptions,
        progress: &dyn Progress,
    ) -> Result<(CellIntegrals, OtReport), OmtError> {
        let n = self.tri.sites.len();
        if target.len() != n {
            return Err(OmtError::Invalid(format!("{} target masses for {} sites", target.len(), n)));
        }
        let total: f64 = target.iter().sum();
        if !(total > 0.0) || target.iter().any(|t| !(*t > 0.0 && t.is_finite())) {
            return Err(OmtError::Invalid("target masses must be positive and finite".into()));
        }
        if !(options.log_step_shrink > 0.0 && options.log_step_shrink < 1.0) {
            return Err(OmtError::Invalid(format!("log_step_shrink {} must be in (0, 1)", options.log_step_shrink)));
        }
        let disk = self.density.disk_mass(self.radius);
        let tau = self.scaled_to_disk(target);
        let flips0 = self.tri.flips;
        let symbolic0 = self.linear.symbolic_count;
        let mut report = OtReport { min_step: 1.0, ..Default::default() };
        let saved = self.tri.clone();
        let initial = self.current.take();
        let mut cells = match self.newton(&tau, initial, options, options.max_iterations, false, &mut report, progress) {
            Ok(c) => c,
            Err(NewtonFailure::Cancelled(c)) => return Err(c.into()),
            Err(NewtonFailure::Linear(e)) => return Err(e.into()),
            Err(NewtonFailure::Stalled { .. }) => {
                self.tri = saved;
                self.continuation(&tau, options, &mut report, progress)?
            }
        };
        let err = l1_error(&cells.mass, &tau) / disk;
        if err > options.tolerance {
            return Err(OmtError::NotConverged { iterations: report.iterations, error: err, tolerance: options.tolerance });
        }
        report.mass_error = err;
        report.max_cell_error = cells.mass.iter().zip(&tau).map(|(m, t)| (m - t).abs() / t).fold(0.0, f64::max);
        report.flips = self.tri.flips - flips0;
        report.symbolic_factorizations = self.linear.symbolic_count - symbolic0;
        // The iterations need masses only; the centroids need the moments once, here.
        cells.moment = cell_moments(&self.tri, self.radius, self.density);
        Ok((cells, report))
    }

    /// Continuation from the current masses to `tau` (see [`OtSolver::solve`]).
    fn continuation(
        &mut self,
        tau: &[f64],
        options: &OtOptions,
        report: &mut OtReport,
        progress: &dyn Progress,
    ) -> Result<CellIntegrals, OmtError> {
        let disk = self.density.disk_mass(self.radius);
        let m0 = self.integrals().mass;
        let floor = 1e-300f64;
        let log_m0: Vec<f64> = m0.iter().map(|m| m.max(floor).ln()).collect();
        let log_tau: Vec<f64> = tau.iter().map(|t| t.ln()).collect();
        let (mut t, mut dt) = (0.0f64, 0.125f64);
        report.continuation_steps = 0;
        loop {
            let t_try = (t + dt).min(1.0);
            let mut tau_t: Vec<f64> = log_m0.iter().zip(&log_tau).map(|(a, b)| ((1.0 - t_try) * a + t_try * b).exp()).collect();
            let s: f64 = tau_t.iter().sum();
            tau_t.iter_mut().for_each(|x| *x *= disk / s);
            let saved = self.tri.clone();
            let step_options = OtOptions { tolerance: if t_try < 1.0 { options.tolerance.max(1e-4) } else { options.tolerance }, ..options.clone() };
            match self.newton(&tau_t, None, &step_options, 40, true, report, progress) {
                Ok(cells) => {
                    report.continuation_steps += 1;
                    t = t_try;
                    if t >= 1.0 {
                        return Ok(cells);
                    }
                    dt = (dt * 2.0).min(0.5);
                }
                Err(NewtonFailure::Cancelled(c)) => return Err(c.into()),
                Err(NewtonFailure::Linear(e)) => return Err(e.into()),
                Err(NewtonFailure::Stalled { iteration, error }) => {
                    self.tri = saved;
                    dt *= 0.25;
                    if dt < 1e-6 {
                        return Err(OmtError::Stalled { iteration, error });
                    }
                }
            }
        }
    }

    /// Damped Newton towards `tau` from the current weights; a continuation segment
    /// (`segment`) also gives up on [`FALLING_STEPS`] falling short steps.
    #[allow(clippy::too_many_arguments)]
    fn newton(
        &mut self,
        tau: &[f64],
        initial: Option<CellIntegrals>,
        options: &OtOptions,
        max_iterations: usize,
        segment: bool,
        report: &mut OtReport,
        progress: &dyn Progress,
    ) -> Result<CellIntegrals, NewtonFailure> {
        let disk = self.density.disk_mass(self.radius);
        let mut cells = initial.unwrap_or_else(|| self.integrals());
        let mut err = l1_error(&cells.mass, tau) / disk;
        let min_tau = tau.iter().cloned().fold(f64::INFINITY, f64::min);
        let min_m0 = cells.mass.iter().cloned().fold(f64::INFINITY, f64::min);
        let eps = 0.5 * min_tau.min(min_m0.max(0.0));
        let err0 = err.max(options.tolerance);
        let (mut small_steps, mut falling, mut last_alpha) = (0, 0, 1.0);
        // Whether the last accepted step went the full length (either direction, or a step
        // with the last factorization), so that the solver's factorization is of a Hessian
        // close to the current one.
        let mut quadratic = false;
        for it in 0..max_iterations {
            if err <= options.tolerance {
                return Ok(cells);
            }
            let frac = ((err0.ln() - err.ln()) / (err0.ln() - options.tolerance.ln())).clamp(0.0, 1.0);
            progress::check(progress, Stage::Transport, frac, &format!("mass error {err:.2e}")).map_err(NewtonFailure::Cancelled)?;
            if quadratic && err <= options.stale_step_error {
                let (dw, _) = self.solve_directions(&cells, tau, false).map_err(NewtonFailure::Linear)?;
                if let Some((trial, c, e)) = self.trial(&dw, 1.0, tau, disk, eps, STALE_STEP_GAIN * err) {
                    self.accept(trial);
                    cells = c;
                    err = e;
                    report.iterations += 1;
                    report.stale_steps += 1;
                    continue;
                }
            }
            let (dw, dw_log) = self.newton_direction(&cells, tau, err > options.log_step_error).map_err(NewtonFailure::Linear)?;
            // The first trial step length, halved until the step is accepted: every cell
            // keeps at least `eps` and the mass error falls by the factor `1 - alpha / 2`.
            let try_step = |dw: &[f64], alpha: f64| self.trial(dw, alpha, tau, disk, eps, (1.0 - 0.5 * alpha) * err);
            let mut accepted = None;
            if let Some(d) = &dw_log {
                let mut alpha = 1.0;
                while alpha >= LOG_MIN_STEP && accepted.is_none() {
                    accepted = try_step(d, alpha).map(|t| (t, alpha));
                    alpha *= if alpha > LOG_FINE_BACKTRACKING { options.log_step_shrink } else { 0.5 };
                }
                if accepted.is_some() {
                    report.log_steps += 1;
                }
            }
            let ((trial, c, e), alpha) = match accepted {
                Some(step) => step,
                None => {
                    let mut alpha = 1.0;
                    loop {
                        if let Some(t) = try_step(&dw, alpha) {
                            break (t, alpha);
                        }
                        alpha *= 0.5;
                        if alpha < options.min_step {
                            return Err(NewtonFailure::Stalled { iteration: it, error: err });
                        }
                    }
                }
            };
            self.accept(trial);
            cells = c;
            err = e;
            report.iterations += 1;
            report.min_step = report.min_step.min(alpha);
            quadratic = alpha == 1.0;
            // Many tiny steps in a row: this path is hopeless, let the caller continue.
            small_steps = if alpha < 1e-3 { small_steps + 1 } else { 0 };
            falling = if alpha < FALLING_STEP && alpha < last_alpha { falling + 1 } else { 0 };
            last_alpha = alpha;
            if small_steps >= 4 || (segment && falling >= FALLING_STEPS) {
                return Err(NewtonFailure::Stalled { iteration: it, error: err });
            }
        }
        if err <= options.tolerance {
            Ok(cells)
        } else {
            Err(NewtonFailure::Stalled { iteration: max_iterations, error: err })
        }
    }

    /// Keep [`OtSolver::pattern`] a superset of the current Hessian's off-diagonal pattern,
    /// and [`OtSolver::hessian_pattern`] its layout.
    /// Flips change the regular triangulation's edges at most Newton iterations, and each
    /// change would cost a new symbolic factorization (AMD ordering included, as much as the
    /// numeric one); flips mostly toggle between the two diagonals of the same quads, so the
    /// union of the patterns seen soon stops growing. It restarts from the current edges when
    /// it holds 20% more than them, so the extra fill stays small, and when more than
    /// [`MOVING_PATTERN`] of the current edges are new: then the pattern is moving (the damped
    /// first steps of a cold solve) and a union would only add fill to matrices analysed anew
    /// anyway (hand at full resolution: the factor grew from 2.5M to 3.3M entries, and the
    /// transport was slower). (Keeping the AMD ordering
    /// of an earlier pattern and redoing only the elimination tree was measured and is no
    /// good: on the hand the factor grows from 2.6M to 4M-16M entries after a few flips.
    /// Nor is skipping factorizations by conjugate gradients preconditioned with the last
    /// factor: it needs 8-20 iterations per step, no cheaper than factoring,
    /// and its inexact steps tripled the Newton iterations on the 48k brain.)
    fn update_pattern(&mut self, cells: &CellIntegrals) -> Result<(), SolveError> {
        let current = interior_edge_keys(self.tri.sites.len(), &cells.edges);
        let missing = count_missing(&current, &self.pattern);
        if missing == 0 {
            return Ok(());
        }
        self.pattern = if missing as f64 > MOVING_PATTERN * current.len() as f64 {
            current
        } else {
            let union = sorted_union(&self.pattern, &current);
            if union.len() as f64 > 1.2 * current.len() as f64 { current } else { union }
        };
        // Unknowns are the sites but the pinned first one: (i, j) -> (i - 1, j - 1).
        let keys: Vec<u64> = self.pattern.iter().map(|k| k - ((1u64 << 32) | 1)).collect();
        self.hessian_pattern = GraphPattern::new(self.tri.sites.len() - 1, &keys, "transport Hessian")?;
        Ok(())
    }

    /// The weights moved by `alpha * dw` when every cell keeps at least `eps` and the mass
    /// error falls to at most `bound`: the new triangulation, integrals and error.
    fn trial(&self, dw: &[f64], alpha: f64, tau: &[f64], disk: f64, eps: f64, bound: f64) -> Option<(RegularTriangulation, CellIntegrals, f64)> {
        let w: Vec<f64> = self.tri.weights.iter().zip(dw).map(|(w, d)| w + alpha * d).collect();
        let (trial, c) = self.reweighted(&w)?;
        let e = l1_error(&c.mass, tau) / disk;
        let min_m = c.mass.iter().cloned().fold(f64::INFINITY, f64::min);
        if min_m >= eps && e <= bound {
            Some((trial, c, e))
        } else {
            self.recycle(trial);
            None
        }
    }

    /// Solve `H dw = tau - m` with `w_0` pinned, and with `logarithmic` also the step of the
    /// logarithmic masses (see [`super::options::LOG_STEP_ERROR`]) with the same factorization.
    fn newton_direction(&mut self, cells: &CellIntegrals, tau: &[f64], logarithmic: bool) -> Result<(Vec<f64>, Option<Vec<f64>>), SolveError> {
        let n = tau.len();
        if n > 1 {
            self.update_pattern(cells)?;
            // Explicit zeros on the kept pattern: while it covers the current edges the
            // matrix keeps its sparsity pattern and the symbolic factorization is reused.
            let mut diag = vec![0.0; n];
            for &(i, j, c) in &cells.edges {
                diag[i as usize] += c;
                diag[j as usize] += c;
            }
            let scale = diag.iter().cloned().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
            // A tiny regularisation keeps isolated cells (no interior edge) solvable.
            let reduced: Vec<f64> = diag[1..].iter().map(|d| d + 1e-14 * scale).collect();
            let off_diagonal = cells.edges.iter().filter(|e| e.0 > 0 && e.1 > 0).map(|&(i, j, c)| (i as usize - 1, j as usize - 1, -c));
            let h = self.hessian_pattern.symmetric(&reduced, off_diagonal, "transport Hessian")?;
            self.linear.factor(&h, "transport Hessian")?;
        }
        self.solve_directions(cells, tau, logarithmic)
    }

    /// The plain step `H dw = tau - m` (and with `logarithmic` the logarithmic one) with the
    /// last factorization of `H`, `w_0` pinned: [`OtSolver::newton_direction`]'s solve, and
    /// alone the chord step of [`super::options::STALE_STEP_ERROR`].
    fn solve_directions(&self, cells: &CellIntegrals, tau: &[f64], logarithmic: bool) -> Result<(Vec<f64>, Option<Vec<f64>>), SolveError> {
        let n = tau.len();
        if n == 1 {
            return Ok((vec![0.0], logarithmic.then(|| vec![0.0])));
        }
        let mut rhs = vec![(1..n).map(|i| tau[i] - cells.mass[i]).collect::<Vec<f64>>()];
        if logarithmic {
            rhs.push(logarithmic_residual(&cells.mass, tau)[1..].to_vec());
        }
        self.linear.solve_in_place(&mut rhs, "transport Hessian")?;
        let pinned = |x: &[f64]| std::iter::once(0.0).chain(x.iter().copied()).collect::<Vec<f64>>();
        Ok((pinned(&rhs[0]), rhs.get(1).map(|x| pinned(x))))
    }
}

fn l1_error(m: &[f64], tau: &[f64]) -> f64 {
    m.iter().zip(tau).map(|(a, b)| (a - b).abs()).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logarithmic_residual_sums_to_zero_and_is_the_plain_one_near_the_solution() {
        let tau = [1.0, 2.0, 3.0, 4.0];
        // Far from the solution: sum 0, and each entry's sign that of ln(tau / m) shifted by
        // the common constant; a cell 100 times too small asks for ln(100) of its mass.
        let far = [0.01, 2.0, 3.0, 4.99];
        let r = logarithmic_residual(&far, &tau);
        assert!(r.iter().sum::<f64>().abs() < 1e-12, "{r:?}");
        let c = r[1] / far[1];
        assert!((r[0] - 0.01 * ((1.0f64 / 0.01).ln() + c)).abs() < 1e-12);
        assert!(r[0] < 0.1 && r[0] > 0.0 && r[3] < 0.0, "{r:?}");
        // Near it (the same total, as in the solver), m (ln(tau / m) + c) = tau - m up to
        // second order.
        let near = [1.0 + 1e-4, 2.0 - 1e-4, 3.0 + 2e-4, 4.0 - 2e-4];
        let r = logarithmic_residual(&near, &tau);
        for ((r, m), t) in r.iter().zip(&near).zip(&tau) {
            assert!((r - (t - m)).abs() < 1e-7, "{r} vs {}", t - m);
        }
        // Empty cells take the plain residual.
        assert!(logarithmic_residual(&[0.0, 10.0], &[5.0, 5.0])[0] > 0.0);
    }
}
