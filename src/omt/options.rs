//! The transport solver's options, report and errors, with the defaults of its step
//! choices and why they are what they are (the solver is `super::newton`).

use super::triangulation::TriangulationError;
use crate::linalg::SolveError;
use crate::progress::Cancelled;

/// Options of the transport solver. Build them from [`OtOptions::default`] with the `with_*`
/// setters (or by setting fields): new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct OtOptions {
    /// Stop when `sum |m_i - tau_i| / sum tau_i` is below this. Default `1e-7`.
    pub tolerance: f64,
    /// Maximum number of Newton iterations. Default 200.
    pub max_iterations: usize,
    /// Smallest damping factor tried before Newton counts as stalled (then the continuation
    /// or the caller's fallback takes over). Default `2^-10`: a shorter step gains less than
    /// 0.05% of the mass error and each halving costs a trial triangulation (docs/method.md,
    /// "2. Logarithmic and stale Newton steps, continuation").
    pub min_step: f64,
    /// Relative mass error above which a Newton step first tries the logarithmic masses'
    /// direction. Default [`LOG_STEP_ERROR`]; `f64::INFINITY` takes plain steps only.
    pub log_step_error: f64,
    /// Factor by which a rejected logarithmic step is shortened while it is longer than
    /// [`LOG_FINE_BACKTRACKING`] (then halved). Default [`LOG_STEP_SHRINK`]; 0.5 halves.
    pub log_step_shrink: f64,
    /// Relative mass error below which, after a step accepted at full length, the next step
    /// first tries the direction from the last factorization (see [`STALE_STEP_ERROR`]). Default
    /// [`STALE_STEP_ERROR`]; 0 factors every step.
    pub stale_step_error: f64,
}

impl Default for OtOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-7,
            max_iterations: 200,
            min_step: 1.0 / (1u64 << 10) as f64,
            log_step_error: LOG_STEP_ERROR,
            log_step_shrink: LOG_STEP_SHRINK,
            stale_step_error: STALE_STEP_ERROR,
        }
    }
}

impl OtOptions {
    /// Set [`OtOptions::tolerance`].
    pub fn with_tolerance(mut self, t: f64) -> Self {
        self.tolerance = t;
        self
    }
    /// Set [`OtOptions::max_iterations`].
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// Set [`OtOptions::min_step`].
    pub fn with_min_step(mut self, min_step: f64) -> Self {
        self.min_step = min_step;
        self
    }

    /// Set [`OtOptions::log_step_error`] (`f64::INFINITY`: plain steps only).
    pub fn with_log_step_error(mut self, log_step_error: f64) -> Self {
        self.log_step_error = log_step_error;
        self
    }

    /// Set [`OtOptions::log_step_shrink`].
    pub fn with_log_step_shrink(mut self, log_step_shrink: f64) -> Self {
        self.log_step_shrink = log_step_shrink;
        self
    }

    /// Set [`OtOptions::stale_step_error`] (0: factor every step).
    pub fn with_stale_step_error(mut self, stale_step_error: f64) -> Self {
        self.stale_step_error = stale_step_error;
        self
    }
}

/// Errors of the transport stage.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum OmtError {
    /// The sites could not be triangulated.
    #[error(transparent)]
    Triangulation(#[from] TriangulationError),
    /// The Newton system could not be solved.
    #[error("optimal transport Newton system: {0}")]
    Linear(#[from] SolveError),
    /// Damping reached the minimum step without progress.
    #[error("optimal transport stalled at iteration {iteration} with relative mass error {error:.3e} (the initial map squeezes part of the surface too much: for a closed surface a larger lambda spreads it; else report this mesh)")]
    Stalled {
        /// Iteration.
        iteration: usize,
        /// Relative L1 mass error reached.
        error: f64,
    },
    /// No convergence within the iteration budget.
    #[error("optimal transport did not converge in {iterations} iterations (relative mass error {error:.3e} > tolerance {tolerance:.1e}); raise max_iterations or the tolerance")]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// Error reached.
        error: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// A closed surface's transport failed at every `lambda` of its fallbacks, the rescue
    /// round's included (`crate::param::lambda_fallback`): the surface is too elongated for the
    /// map onto the cap.
    #[error("optimal transport failed at every lambda tried ({tried}), the last time {last}: the closed surface is too elongated for capmesh's map onto the cap (docs/method.md section 13, \"Not covered\"); please report this mesh")]
    EveryLambdaFailed {
        /// The `lambda` values tried, with the rescue round's stretch-energy iterations.
        tried: String,
        /// How the last attempt failed ([`OmtError::outcome`]).
        last: String,
    },
    /// Bad arguments (lengths, non-positive masses).
    #[error("invalid transport problem: {0}")]
    Invalid(String),
    /// Cancelled through the progress callback.
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
}

impl OmtError {
    /// How the transport failed, without the remedy the message names (for
    /// [`OmtError::EveryLambdaFailed`], where every remedy was tried).
    pub fn outcome(&self) -> String {
        match self {
            OmtError::Stalled { iteration, error } => format!("stalled at iteration {iteration} with relative mass error {error:.3e}"),
            OmtError::NotConverged { iterations, error, .. } => format!("did not converge in {iterations} iterations (relative mass error {error:.3e})"),
            other => other.to_string(),
        }
    }
}

/// What the solver did.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct OtReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Final relative L1 mass error.
    pub mass_error: f64,
    /// Largest relative error of a single cell.
    pub max_cell_error: f64,
    /// Edge flips done to keep the triangulation regular.
    pub flips: usize,
    /// Symbolic factorizations of the Newton matrix (the rest reused one).
    pub symbolic_factorizations: usize,
    /// Smallest damping factor accepted.
    pub min_step: f64,
    /// Continuation steps taken after plain Newton stalled (0 when it did not).
    pub continuation_steps: usize,
    /// Newton steps taken along the logarithmic masses' direction (see
    /// [`OtOptions::log_step_error`]).
    pub log_steps: usize,
    /// Newton steps taken with the previous step's factorization (see
    /// [`OtOptions::stale_step_error`]).
    pub stale_steps: usize,
}

/// Relative mass error above which each Newton step first tries the step of the logarithmic
/// masses by default ([`OtOptions::log_step_error`]), `H dw = m (ln(tau / m) + c)` (the
/// Newton step of `ln m(w) = ln tau + c`, with the constant `c` that keeps the right-hand
/// side's sum 0 as the Hessian's range requires), and falls back to the plain step
/// `H dw = tau - m` when no step length down to [`LOG_MIN_STEP`] is accepted. From the
/// Voronoi start most cells must grow or shrink by large factors, and the plain step lets the
/// cells it squeezes out vanish; below the threshold the plain step converges quadratically
/// (the logarithmic one does not). This takes fewer Newton steps on the shared meshes, with
/// the same distortions; alone, without the fallback, the logarithmic step stalled on the
/// closed hippocampus's first coarse solve.
pub const LOG_STEP_ERROR: f64 = 0.01;

/// Shortest step length tried along the logarithmic direction (see [`LOG_STEP_ERROR`]).
pub const LOG_MIN_STEP: f64 = 1.0 / 64.0;

/// Default of [`OtOptions::log_step_shrink`]: the logarithmic step's trial lengths are 1,
/// 0.71, 0.5, 0.35, 0.25, 0.18, then halved. A cold full-resolution solve accepts its first
/// steps at a quarter to a half of the logarithmic direction; a rejected trial is cheap (most
/// fail in the flips) while an accepted step costs a factorization, so the finer trials save
/// Newton steps, with the same distortions.
pub const LOG_STEP_SHRINK: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Default of [`OtOptions::stale_step_error`]: below a 1% relative mass error (where the
/// plain step converges quadratically, [`LOG_STEP_ERROR`]) and after a step accepted at full
/// length, a step first tries the plain direction `H_old dw = tau - m` with the last
/// factorization (a chord step: two triangular solves instead of an ordering, a symbolic
/// analysis and a factorization), kept when it lowers the error by [`STALE_STEP_GAIN`] at
/// full length; otherwise the step factors its own Hessian as before. So close to the
/// solution few edges flip and the Hessian changes little; at 5% the chord steps mostly
/// failed and cost a trial each. (Stale directions while the steps are damped were measured
/// and dropped: see the docs of `OtSolver::update_pattern`.)
pub const STALE_STEP_ERROR: f64 = 0.01;

/// A step with the last factorization is kept when it divides the mass error by at least
/// `1 / STALE_STEP_GAIN` (a fresh step at this stage divides it by 20 to 700; a chord step
/// that gains less would cost more steps than it saves factorizations).
pub const STALE_STEP_GAIN: f64 = 0.1;

/// Step length below which rejected logarithmic steps are halved (see [`LOG_STEP_SHRINK`]).
pub const LOG_FINE_BACKTRACKING: f64 = 0.2;
