//! The parameterization options `param` and `remesh` share (paper Sec. 3: the initial map
//! and its `lambda`, the smoothing and refinement of the transport map, the puncture end
//! of closed surfaces, the radius search's coarse level), and how they set [`ParamOptions`].

use capmesh::param::{OpenInitialMap, ParamOptions, PunctureEnd};
use capmesh::refine::Smoothing;

/// Parameterization options of the command line (each defaults to the library's default).
#[derive(clap::Args, Debug, Clone)]
pub struct MapArgs {
    /// Initial map of open surfaces: composite (default: stretch energy composed with
    /// lambda*mu) or conformal (the paper's disk conformal map).
    #[arg(long, default_value = "composite")]
    pub initial: OpenInitialMap,
    /// lambda of the closed-surface quasi-conformal composition (paper: 0.2).
    #[arg(long, default_value_t = capmesh::flatten::closed::DEFAULT_LAMBDA)]
    pub lambda: f64,
    /// lambda of the composite initial map of open surfaces.
    #[arg(long, default_value_t = capmesh::param::DEFAULT_OPEN_LAMBDA)]
    pub open_lambda: f64,
    /// Closed surfaces: keep the result of --lambda (an error or a poor map) instead of
    /// mapping again with a larger lambda (0.5, 0.8, then 1) when the transport stalls on an
    /// initial map that squeezes part of the surface below double precision, or the map's
    /// mean |d_area| is above 0.3 (very elongated surfaces).
    #[arg(long)]
    pub no_lambda_fallback: bool,
    /// Smoothing of the final centroid map: auto (default) or a strength >= 0
    /// (0 is the paper's plain centroid map).
    #[arg(long, default_value = "auto")]
    pub smoothing: Smoothing,
    /// Sweeps of the face-level area refinement after transport (0 is the paper's map).
    #[arg(long, default_value_t = capmesh::param::DEFAULT_AREA_REFINEMENT)]
    pub area_refinement: usize,
    /// Closed surfaces: puncture at the best end of the principal axis (searches the
    /// radius from both, finishes the better), at the bottom (lower input Z) or at the top.
    #[arg(long, default_value = "best")]
    pub puncture_end: PunctureEnd,
    /// Transport sites of the radius search: a mesh of n vertices searches on a coarse
    /// level of at most max(this, n / 16) sites (closed surfaces: max(min(this, max(n /
    /// 4, 250)), n / 16)), when that is fewer than n / 2, and solves the full problem at
    /// r* only (0: search at full resolution, the paper's method).
    #[arg(long, default_value_t = capmesh::param::DEFAULT_SEARCH_SITES)]
    pub search_sites: usize,
    /// Closed surfaces of more vertices than this are mapped through a decimated copy of
    /// --coarse-vertices vertices, whose map is prolonged to every vertex and refined there
    /// (near-linear time and memory); 0: never.
    #[arg(long, default_value_t = capmesh::param::DEFAULT_MULTILEVEL_ABOVE)]
    pub multilevel_above: usize,
    /// Vertices of the decimated copy of a large closed surface (see --multilevel-above).
    #[arg(long, default_value_t = capmesh::param::DEFAULT_COARSE_VERTICES)]
    pub coarse_vertices: usize,
    /// Exit 0 with a poor map (mean |d_area| above 0.3 on the adaptive cap; the report's
    /// quality is "poor") instead of 3. The outputs are written either way.
    #[arg(long)]
    pub allow_poor_map: bool,
}

impl MapArgs {
    /// Set these options on `options` (its domain is left as it is; `allow_poor_map` is the
    /// command's, not the library's).
    pub fn apply(&self, options: &mut ParamOptions) {
        options.open.initial = self.initial;
        options.open.lambda = self.open_lambda;
        options.closed.flatten.lambda = self.lambda;
        options.closed.puncture_end = self.puncture_end;
        if self.no_lambda_fallback {
            options.closed.lambda_fallbacks.clear();
        }
        options.closed.multilevel_above = self.multilevel_above;
        options.closed.coarse_vertices = self.coarse_vertices;
        options.search.sites = self.search_sites;
        options.refinement.smoothing = self.smoothing;
        options.refinement.area_refinement = self.area_refinement;
    }
}
