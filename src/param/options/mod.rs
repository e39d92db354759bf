//! The options of [`super::parameterize`]: the domain and the transport, then one group each
//! for open surfaces ([`open`]), closed surfaces ([`closed`]), the radius search ([`search`])
//! and the refinement after the transport ([`refinement`]), with their defaults and why they
//! are what they are (departures from the paper: docs/method.md).

mod check;
pub(crate) mod closed;
pub(crate) mod open;
pub(crate) mod refinement;
pub(crate) mod search;

use crate::cap::Domain;
use crate::omt::OtOptions;
use crate::refine::Smoothing;
pub use closed::{ClosedOptions, PunctureEnd, DEFAULT_COARSE_VERTICES, DEFAULT_LAMBDA_FALLBACKS, DEFAULT_MULTILEVEL_ABOVE, DEFAULT_RESCUE_STRETCH_ITERATIONS};
pub use open::{OpenInitialMap, OpenOptions, DEFAULT_OPEN_FACTORED_ITERATIONS, DEFAULT_OPEN_LAMBDA};
pub use refinement::{RefinementOptions, DEFAULT_AREA_REFINEMENT};
pub use search::{SearchOptions, DEFAULT_SEARCH_SITES, MASS_TOLERANCE};

/// Relative L1 mass error at which the final full-resolution transport stops (the map at
/// `r*` after a coarse radius search, and the fixed domains' maps): a 0.1% mass error, the
/// level below which the area refinement stops too ([`crate::refine::area_refine::GOOD_ENOUGH`]),
/// since the smoothing and the face-level refinement that follow move the vertices far
/// more. Newton converges quadratically there, so this saves the last step whenever the one
/// before it lands below `1e-3`, with mean `|d_area|` and `|d_angle|` within 1% of
/// [`MASS_TOLERANCE`]'s; at `5e-3` the 100k ellipsoid's mean `|d_area|` rose 11%.
pub const TRANSPORT_TOLERANCE: f64 = 1e-3;

/// Options of [`super::parameterize`]: the domain, the transport and the weld, then one group
/// per stage. Build them from [`ParamOptions::default`] with the `with_*` setters (or by
/// setting fields): new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ParamOptions {
    /// Target domain. Default [`Domain::Adaptive`].
    pub domain: Domain,
    /// Transport solver options; their tolerance is the final map's (at `r*` after a coarse
    /// search, or at a fixed domain's radius). Default: [`OtOptions::default`] with the
    /// relative mass tolerance [`TRANSPORT_TOLERANCE`].
    pub transport: OtOptions,
    /// Vertices closer than this times the bounding-box diagonal are welded before mapping
    /// (coincident vertices make zero-area faces). Default `1e-9`.
    pub weld_tolerance: f64,
    /// The initial map of open surfaces. Default [`OpenOptions::default`].
    pub open: OpenOptions,
    /// The puncture and initial map of closed surfaces, and their `lambda` fallbacks. Default
    /// [`ClosedOptions::default`].
    pub closed: ClosedOptions,
    /// The radius search of the adaptive domain. Default [`SearchOptions::default`].
    pub search: SearchOptions,
    /// The smoothing and area refinement after the transport. Default
    /// [`RefinementOptions::default`].
    pub refinement: RefinementOptions,
    /// The transport's target mass of each input vertex, in place of its area (a third of
    /// its faces' areas): the fine surface's area each vertex of a decimated copy stands for
    /// (`crate::param::multilevel`). Default `None`.
    pub(crate) vertex_masses: Option<std::sync::Arc<Vec<f64>>>,
}

impl Default for ParamOptions {
    fn default() -> Self {
        Self {
            domain: Domain::Adaptive,
            transport: OtOptions::default().with_tolerance(TRANSPORT_TOLERANCE),
            weld_tolerance: 1e-9,
            open: OpenOptions::default(),
            closed: ClosedOptions::default(),
            search: SearchOptions::default(),
            refinement: RefinementOptions::default(),
            vertex_masses: None,
        }
    }
}

impl ParamOptions {
    /// Set the domain.
    pub fn with_domain(mut self, d: Domain) -> Self {
        self.domain = d;
        self
    }

    /// Set the transport solver's options (their tolerance is the final map's).
    pub fn with_transport(mut self, transport: OtOptions) -> Self {
        self.transport = transport;
        self
    }

    /// Set the weld tolerance, relative to the bounding-box diagonal.
    pub fn with_weld_tolerance(mut self, weld_tolerance: f64) -> Self {
        self.weld_tolerance = weld_tolerance;
        self
    }

    /// Set the options of open surfaces.
    pub fn with_open(mut self, open: OpenOptions) -> Self {
        self.open = open;
        self
    }

    /// Set the options of closed surfaces.
    pub fn with_closed(mut self, closed: ClosedOptions) -> Self {
        self.closed = closed;
        self
    }

    /// Set the options of the radius search.
    pub fn with_search(mut self, search: SearchOptions) -> Self {
        self.search = search;
        self
    }

    /// Set the options of the refinement after the transport.
    pub fn with_refinement(mut self, refinement: RefinementOptions) -> Self {
        self.refinement = refinement;
        self
    }

    /// Set the most transport solves of the radius search ([`SearchOptions::max_evaluations`]).
    pub fn with_max_search_evaluations(mut self, max_evaluations: usize) -> Self {
        self.search.max_evaluations = max_evaluations;
        self
    }

    /// Set the transport sites of the radius search ([`SearchOptions::sites`]; 0: search at
    /// full resolution).
    pub fn with_search_sites(mut self, sites: usize) -> Self {
        self.search.sites = sites;
        self
    }

    /// Set the smoothing of the final centroid map ([`RefinementOptions::smoothing`]).
    pub fn with_smoothing(mut self, smoothing: Smoothing) -> Self {
        self.refinement.smoothing = smoothing;
        self
    }

    /// Set the sweeps of the face-level area refinement ([`RefinementOptions::area_refinement`];
    /// 0: the paper's map).
    pub fn with_area_refinement(mut self, area_refinement: usize) -> Self {
        self.refinement.area_refinement = area_refinement;
        self
    }

    /// Set which end of a closed surface is punctured ([`ClosedOptions::puncture_end`]).
    pub fn with_puncture_end(mut self, puncture_end: PunctureEnd) -> Self {
        self.closed.puncture_end = puncture_end;
        self
    }

    /// Set the larger `lambda` values tried on closed surfaces
    /// ([`ClosedOptions::lambda_fallbacks`]; empty: none).
    pub fn with_closed_lambda_fallbacks(mut self, lambda_fallbacks: Vec<f64>) -> Self {
        self.closed.lambda_fallbacks = lambda_fallbacks;
        self
    }
}
