//! The options of closed genus-0 surfaces: the puncture and flattening (paper Sec. 3.2.1),
//! which end is punctured, and the larger `lambda` values tried when the transport fails.

use crate::flatten::closed::ClosedFlattenOptions;

/// Where a closed surface is punctured (paper Sec. 3.2.1 punctures "the bottom" after aligning
/// the principal axis with `Z`; which end is the bottom is a convention).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PunctureEnd {
    /// Search the radius with the puncture at each end of the principal axis (in parallel),
    /// then finish the end whose search map at `r*` has the smaller mean `|d_area|` (the
    /// coarse level's map prolonged to every vertex, before the full transport solve, fold
    /// repair and refinement; with a fixed domain, which has no search, both ends are
    /// finished and the final maps compared). The result does not depend on how the input
    /// is oriented, and it is better on the shared meshes (bunny 0.039 instead of 0.16).
    /// The search maps rank the ends as the finished maps do on the shared closed meshes (or
    /// tie), and deciding before the full-resolution half lets the kept end's second half run
    /// on both cores.
    #[default]
    Best,
    /// The end with the lower input `Z` (the paper's "bottom" for an input standing along `Z`).
    Bottom,
    /// The other end.
    Top,
}

crate::named::named_enum!(PunctureEnd, "puncture end", Best => "best", Bottom => "bottom", Top => "top");

/// The default [`ClosedOptions::lambda_fallbacks`]: each tried in turn, above the
/// `lambda` that failed. 0.5 and 0.8 rescued the stretched meshes above (the bunny
/// stretched 10 times at 0.5, 50 times at 1); 1 (the stretch
/// energy map alone) is the last resort because the fit of the map's angles is worst there.
pub const DEFAULT_LAMBDA_FALLBACKS: [f64; 3] = [0.5, 0.8, 1.0];

/// The default [`ClosedOptions::rescue_stretch_iterations`]. A long bone of a femur's
/// proportions (shaft 20 times as long as wide), which stalled at every `lambda` with the
/// flattening's 10 (and with 20), maps at `lambda` 0.8 with 40 (mean |d_area| 0.231, stretch
/// energy ratio 1751 -> 1.59, map 7.6 s), 80 (0.211, ratio 1.12, 3.8 s: the transport
/// converges faster from the better spread start) or 160 (0.222, 4.6 s); an analytic bone of
/// revolution (tests/common `long_bone` at half length 8, 200 rings of 24 vertices, written
/// to OBJ) at 0.029, 0.028 and 0.028. docs/method.md section 13.
pub const DEFAULT_RESCUE_STRETCH_ITERATIONS: usize = 80;

/// How closed genus-0 surfaces are punctured and flattened before the transport. Build them
/// from [`ClosedOptions::default`] with the `with_*` setters: new options may be added without
/// notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ClosedOptions {
    /// The puncture and flattening (`lambda`, puncture, stretch energy). Default
    /// [`ClosedFlattenOptions::default`] (`lambda` 0.2, the paper's).
    pub flatten: ClosedFlattenOptions,
    /// Which end of the principal axis is punctured. Default [`PunctureEnd::Best`].
    pub puncture_end: PunctureEnd,
    /// Larger `flatten.lambda` values tried in turn when the transport stalls on a too
    /// compressive initial map or the map is poor (see `crate::param::lambda_fallback`);
    /// empty keeps the first `lambda`'s result. Default [`DEFAULT_LAMBDA_FALLBACKS`]
    /// (0.5, 0.8, 1).
    pub lambda_fallbacks: Vec<f64>,
    /// Stretch-energy iterations of a last round of attempts, made only when the transport
    /// stalled at every `lambda` (no map at all): the fallbacks from
    /// [`crate::param::RESCUE_FROM_LAMBDA`] are tried again with this many iterations, which
    /// spread a far end that 10 leave squeezed below double precision (see
    /// `crate::param::lambda_fallback`). Not more than the flattening's own iterations, or
    /// no fallbacks: no such round. Default [`DEFAULT_RESCUE_STRETCH_ITERATIONS`].
    pub rescue_stretch_iterations: usize,
    /// Closed surfaces of more vertices than this are mapped through a decimated copy of
    /// [`ClosedOptions::coarse_vertices`] vertices, whose map is prolonged to every vertex
    /// and refined there (see `crate::param::multilevel`); 0: never. Default
    /// [`DEFAULT_MULTILEVEL_ABOVE`].
    pub multilevel_above: usize,
    /// Vertices of the decimated copy of a large closed surface (at least; an eighth of the
    /// input's when that is more, [`crate::param::COARSE_RATIO`]). Default
    /// [`DEFAULT_COARSE_VERTICES`].
    pub coarse_vertices: usize,
    /// Sweeps of the area refinement at full resolution after the decimated copy's map is
    /// prolonged; `None`: [`super::RefinementOptions::area_refinement`]'s. A remesh whose
    /// shape stage equalizes the areas on the surface itself asks for fewer (see
    /// `crate::remesh::REMESH_COPY_SWEEPS`). Default `None`.
    pub prolonged_refinement: Option<usize>,
}

/// The default [`ClosedOptions::multilevel_above`].
pub const DEFAULT_MULTILEVEL_ABOVE: usize = 100_000;

/// The default [`ClosedOptions::coarse_vertices`]: with 25000 instead of 50000 the maps of
/// closed surfaces of 130k vertices took 2.5-2.6 s instead of 3.5-3.8 s at 13-20% more mean
/// |d_area| (0.0050-0.0062), their remeshes the same figures (docs/method.md section 20).
pub const DEFAULT_COARSE_VERTICES: usize = 25_000;

impl Default for ClosedOptions {
    fn default() -> Self {
        Self {
            flatten: ClosedFlattenOptions::default(),
            puncture_end: PunctureEnd::Best,
            lambda_fallbacks: DEFAULT_LAMBDA_FALLBACKS.to_vec(),
            rescue_stretch_iterations: DEFAULT_RESCUE_STRETCH_ITERATIONS,
            multilevel_above: DEFAULT_MULTILEVEL_ABOVE,
            coarse_vertices: DEFAULT_COARSE_VERTICES,
            prolonged_refinement: None,
        }
    }
}

impl ClosedOptions {
    /// Set [`ClosedOptions::flatten`].
    pub fn with_flatten(mut self, flatten: ClosedFlattenOptions) -> Self {
        self.flatten = flatten;
        self
    }

    /// Set the `lambda` of the flattening ([`ClosedFlattenOptions::lambda`], in `[0, 1]`).
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.flatten.lambda = lambda;
        self
    }

    /// Set [`ClosedOptions::puncture_end`].
    pub fn with_puncture_end(mut self, puncture_end: PunctureEnd) -> Self {
        self.puncture_end = puncture_end;
        self
    }

    /// Set [`ClosedOptions::lambda_fallbacks`] (empty: none).
    pub fn with_lambda_fallbacks(mut self, lambda_fallbacks: Vec<f64>) -> Self {
        self.lambda_fallbacks = lambda_fallbacks;
        self
    }

    /// Set [`ClosedOptions::rescue_stretch_iterations`] (0: no last round).
    pub fn with_rescue_stretch_iterations(mut self, iterations: usize) -> Self {
        self.rescue_stretch_iterations = iterations;
        self
    }

    /// Set [`ClosedOptions::multilevel_above`] (0: never).
    pub fn with_multilevel_above(mut self, multilevel_above: usize) -> Self {
        self.multilevel_above = multilevel_above;
        self
    }

    /// Set [`ClosedOptions::coarse_vertices`].
    pub fn with_coarse_vertices(mut self, coarse_vertices: usize) -> Self {
        self.coarse_vertices = coarse_vertices;
        self
    }

    /// Set [`ClosedOptions::prolonged_refinement`] (`None`: the area refinement's sweeps).
    pub fn with_prolonged_refinement(mut self, sweeps: Option<usize>) -> Self {
        self.prolonged_refinement = sweeps;
        self
    }
}
