//! Progress reporting and cancellation, one trait for every front end.
//!
//! The CLI's progress bar, the C ABI's callback and MeshLab's `CallBackPos` all implement
//! [`Progress`]. Long stages call [`Progress::report`] now and then; returning
//! [`ControlFlow::Break`] asks the pipeline to stop, which it does with
//! [`crate::Error::Cancelled`] at the next check.

use std::ops::ControlFlow;

/// The pipeline stage a progress report belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Stage {
    /// Checking the input mesh.
    Validate,
    /// Initial flattening map onto the unit disk.
    Flatten,
    /// Search for the optimal disk radius r* (each step solves an OMT problem).
    RadiusSearch,
    /// Semi-discrete optimal transport on the disk (Newton iterations).
    Transport,
    /// Inverse stereographic projection and final metrics.
    Project,
    /// Remeshing through the cap.
    Remesh,
    /// Adaptive harmonics fit.
    Harmonics,
}

impl Stage {
    /// Short human-readable name.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Validate => "validate",
            Stage::Flatten => "flatten",
            Stage::RadiusSearch => "radius search",
            Stage::Transport => "transport",
            Stage::Project => "project",
            Stage::Remesh => "remesh",
            Stage::Harmonics => "harmonics",
        }
    }
}

/// Receives progress reports; may cancel the computation.
///
/// `fraction` is the completed fraction of `stage` in `[0, 1]` (a best estimate for iterative
/// stages). Implementations must be cheap and thread-safe.
pub trait Progress: Sync {
    /// Called by long-running stages. Return `ControlFlow::Break(())` to cancel.
    fn report(&self, stage: Stage, fraction: f64, message: &str) -> ControlFlow<()>;
}

/// A [`Progress`] that ignores every report and never cancels.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn report(&self, _stage: Stage, _fraction: f64, _message: &str) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// Any closure `Fn(Stage, f64, &str) -> ControlFlow<()>` is a progress sink.
impl<F> Progress for F
where
    F: Fn(Stage, f64, &str) -> ControlFlow<()> + Sync,
{
    fn report(&self, stage: Stage, fraction: f64, message: &str) -> ControlFlow<()> {
        self(stage, fraction, message)
    }
}

/// Cancellation marker returned by stages when a [`Progress`] asked to stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled by the progress callback")]
pub struct Cancelled;

/// Report and translate a `Break` into [`Cancelled`].
pub(crate) fn check(
    progress: &dyn Progress,
    stage: Stage,
    fraction: f64,
    message: &str,
) -> Result<(), Cancelled> {
    match progress.report(stage, fraction.clamp(0.0, 1.0), message) {
        ControlFlow::Continue(()) => Ok(()),
        ControlFlow::Break(()) => Err(Cancelled),
    }
}
