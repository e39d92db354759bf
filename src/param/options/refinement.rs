//! The options of what follows the transport at `r*`: the smoothing of the centroid map and
//! the face-level area refinement (departures from the paper: docs/method.md).

use crate::refine::Smoothing;

/// Sweeps of the area refinement by default (over-relaxed, see
/// [`crate::refine::area_refine::RefineOptions`]). On the shared closed meshes (1.8k to 48k
/// vertices) the centroid map leaves a mean `|d_area|` of 0.2 to 0.5 after fold repair; 30
/// sweeps bring it below 0.2 (docs/method.md).
pub const DEFAULT_AREA_REFINEMENT: usize = crate::refine::area_refine::DEFAULT_SWEEPS;

/// How the map at `r*` is smoothed and refined. Build them from [`RefinementOptions::default`]
/// with the `with_*` setters: new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct RefinementOptions {
    /// Smoothing of the final centroid map (see `crate::refine::smoothing`);
    /// `Smoothing::Fixed(0.0)` is the paper's plain centroid map. Default [`Smoothing::Auto`].
    pub smoothing: Smoothing,
    /// Gauss-Seidel sweeps of the face-level area refinement (see
    /// [`crate::refine::area_refine`]); 0 is the paper's map. Default
    /// [`DEFAULT_AREA_REFINEMENT`].
    pub area_refinement: usize,
}

impl Default for RefinementOptions {
    fn default() -> Self {
        Self { smoothing: Smoothing::Auto, area_refinement: DEFAULT_AREA_REFINEMENT }
    }
}

impl RefinementOptions {
    /// Set [`RefinementOptions::smoothing`].
    pub fn with_smoothing(mut self, smoothing: Smoothing) -> Self {
        self.smoothing = smoothing;
        self
    }

    /// Set [`RefinementOptions::area_refinement`] (0: the paper's map).
    pub fn with_area_refinement(mut self, area_refinement: usize) -> Self {
        self.area_refinement = area_refinement;
        self
    }
}
