//! The options of [`super::parameterize`]: the domain, the radius search, the initial maps,
//! the refinement and the fallbacks, with their defaults and why they are what they are.

use crate::cap::Domain;
use crate::flatten::closed::ClosedFlattenOptions;
use crate::flatten::DiskConformalOptions;
use crate::omt::OtOptions;
use crate::refine::Smoothing;

/// Relative L1 mass error (`sum |m_i - tau_i| / sum tau_i`) at which the radius search's
/// transport solves stop. Newton's last step takes the error from about `1e-6` to `1e-10`;
/// `1e-5` leaves the maps' mean `|d_area|` and `|d_angle|` within 1% of `1e-7`'s and saves a
/// Newton step on most meshes. A search at full resolution hands over its map at `r*`
/// without another solve. `1e-3` for the search and the final map alike was worse: the
/// search's energies, not the final map, need the digits.
pub const MASS_TOLERANCE: f64 = 1e-5;

/// Relative L1 mass error at which the final full-resolution transport stops (the map at
/// `r*` after a coarse radius search, and the fixed domains' maps): a 0.1% mass error, the
/// level below which the area refinement stops too ([`crate::refine::area_refine::GOOD_ENOUGH`]),
/// since the smoothing and the face-level refinement that follow move the vertices far
/// more. Newton converges quadratically there, so this saves the last step whenever the one
/// before it lands below `1e-3`, with mean `|d_area|` and `|d_angle|` within 1% of
/// [`MASS_TOLERANCE`]'s; at `5e-3` the 100k ellipsoid's mean `|d_area|` rose 11%.
pub const TRANSPORT_TOLERANCE: f64 = 1e-3;

/// Options of [`super::parameterize`]. Build them from [`ParamOptions::default`] with the
/// `with_*` setters (or by setting fields): new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ParamOptions {
    /// Target domain. Default [`Domain::Adaptive`].
    pub domain: Domain,
    /// Absolute tolerance on `Z*` for the radius search. Default `1e-3`.
    pub z_tolerance: f64,
    /// Maximum transport solves in the radius search. Default 30.
    pub max_search_evaluations: usize,
    /// Transport solver options; their tolerance is the final map's (at `r*` after a coarse
    /// search, or at a fixed domain's radius). Default: [`OtOptions::default`] with the
    /// relative mass tolerance [`TRANSPORT_TOLERANCE`].
    pub transport: OtOptions,
    /// Relative mass tolerance of the transport solves inside the radius search. A search at
    /// full resolution hands over its map at `r*` when this is no looser than
    /// `transport.tolerance` (the default), else solves it on, warm, to that. Each
    /// search step saves about one Newton iteration (hand: 39 instead of 45 in all) and `Z*`
    /// does not move. Looser is faster but not safe: at `1e-2` the hand needs 26 iterations,
    /// while the 48k brain's search stops at `Z* = -0.991` instead of the bound and its mean
    /// `|d_area|` goes from 0.013 to 0.40. Default [`MASS_TOLERANCE`] (`1e-5`).
    pub search_tolerance: f64,
    /// Transport sites of the radius search. A mesh of `n` vertices searches on a coarse
    /// level of at most [`super::search_level_sites`] sites (see [`crate::omt::coarse_level`]:
    /// `max(search_sites, n / SEARCH_RATIO)` when that is less than half the vertices; a
    /// closed surface also at most a quarter of its vertices, [`super::SMALL_SEARCH_RATIO`]) and
    /// solves the full transport problem at `r*` only; 0 always searches at full resolution
    /// (the paper's method). Default [`DEFAULT_SEARCH_SITES`].
    pub search_sites: usize,
    /// Disk conformal map options.
    pub flatten: DiskConformalOptions,
    /// Initial map of open surfaces. Default [`OpenInitialMap::Composite`];
    /// [`OpenInitialMap::Conformal`] is the paper's disk conformal map.
    pub open_initial: OpenInitialMap,
    /// `lambda` of the composite initial map of open surfaces. Default [`DEFAULT_OPEN_LAMBDA`].
    pub open_lambda: f64,
    /// Stretch-energy iterations of the composite initial map of open surfaces that factor
    /// their own matrix; the later ones reuse the last factorization
    /// ([`crate::flatten::stretch_energy::StretchOptions::factored_iterations`]). Default
    /// [`DEFAULT_OPEN_FACTORED_ITERATIONS`].
    pub open_factored_iterations: usize,
    /// Smoothing of the final centroid map (see [`crate::refine::smoothing`]);
    /// `Smoothing::Fixed(0.0)` is the paper's plain centroid map. Default [`Smoothing::Auto`].
    pub smoothing: Smoothing,
    /// Closed-surface flattening options (lambda, puncture, stretch energy).
    pub closed: ClosedFlattenOptions,
    /// Gauss-Seidel sweeps of the face-level area refinement after transport (see
    /// [`crate::refine::area_refine`]); 0 is the paper's map. Default [`DEFAULT_AREA_REFINEMENT`].
    pub area_refinement: usize,
    /// Which end of a closed surface's principal axis is punctured. Default
    /// [`PunctureEnd::Best`].
    pub puncture_end: PunctureEnd,
    /// Vertices closer than this times the bounding-box diagonal are welded before mapping
    /// (coincident vertices make zero-area faces). Default `1e-9`.
    pub weld_tolerance: f64,
    /// Larger `closed.lambda` values tried in turn when the transport of a closed surface
    /// stalls on a too compressive initial map or its map is poor (see
    /// [`super::lambda_fallback`]); empty keeps the first `lambda`'s result. Default
    /// [`DEFAULT_LAMBDA_FALLBACKS`] (0.5, 0.8, 1).
    pub closed_lambda_fallbacks: Vec<f64>,
}

impl Default for ParamOptions {
    fn default() -> Self {
        Self {
            domain: Domain::Adaptive,
            z_tolerance: 1e-3,
            max_search_evaluations: 30,
            transport: OtOptions::default().with_tolerance(TRANSPORT_TOLERANCE),
            search_tolerance: MASS_TOLERANCE,
            search_sites: DEFAULT_SEARCH_SITES,
            flatten: DiskConformalOptions::default(),
            closed: ClosedFlattenOptions::default(),
            smoothing: Smoothing::Auto,
            open_initial: OpenInitialMap::Composite,
            open_lambda: DEFAULT_OPEN_LAMBDA,
            open_factored_iterations: DEFAULT_OPEN_FACTORED_ITERATIONS,
            area_refinement: DEFAULT_AREA_REFINEMENT,
            puncture_end: PunctureEnd::Best,
            weld_tolerance: 1e-9,
            closed_lambda_fallbacks: DEFAULT_LAMBDA_FALLBACKS.to_vec(),
        }
    }
}

impl ParamOptions {
    /// Set the domain.
    pub fn with_domain(mut self, d: Domain) -> Self {
        self.domain = d;
        self
    }

    /// Set the absolute tolerance on `Z*` of the radius search.
    pub fn with_z_tolerance(mut self, z_tolerance: f64) -> Self {
        self.z_tolerance = z_tolerance;
        self
    }

    /// Set the most transport solves of the radius search.
    pub fn with_max_search_evaluations(mut self, max_search_evaluations: usize) -> Self {
        self.max_search_evaluations = max_search_evaluations;
        self
    }

    /// Set the transport solver's options (their tolerance is the final map's).
    pub fn with_transport(mut self, transport: OtOptions) -> Self {
        self.transport = transport;
        self
    }

    /// Set the relative mass tolerance of the radius search's transport solves.
    pub fn with_search_tolerance(mut self, search_tolerance: f64) -> Self {
        self.search_tolerance = search_tolerance;
        self
    }

    /// Set the transport sites of the radius search (0: search at full resolution).
    pub fn with_search_sites(mut self, search_sites: usize) -> Self {
        self.search_sites = search_sites;
        self
    }

    /// Set the disk conformal map's options.
    pub fn with_flatten(mut self, flatten: DiskConformalOptions) -> Self {
        self.flatten = flatten;
        self
    }

    /// Set the initial map of open surfaces.
    pub fn with_open_initial(mut self, open_initial: OpenInitialMap) -> Self {
        self.open_initial = open_initial;
        self
    }

    /// Set `lambda` of the composite initial map of open surfaces.
    pub fn with_open_lambda(mut self, open_lambda: f64) -> Self {
        self.open_lambda = open_lambda;
        self
    }

    /// Set the stretch-energy iterations of open surfaces that factor their own matrix.
    pub fn with_open_factored_iterations(mut self, open_factored_iterations: usize) -> Self {
        self.open_factored_iterations = open_factored_iterations;
        self
    }

    /// Set the smoothing of the final centroid map.
    pub fn with_smoothing(mut self, smoothing: Smoothing) -> Self {
        self.smoothing = smoothing;
        self
    }

    /// Set the closed-surface flattening's options.
    pub fn with_closed(mut self, closed: ClosedFlattenOptions) -> Self {
        self.closed = closed;
        self
    }

    /// Set the sweeps of the face-level area refinement (0: the paper's map).
    pub fn with_area_refinement(mut self, area_refinement: usize) -> Self {
        self.area_refinement = area_refinement;
        self
    }

    /// Set which end of a closed surface is punctured.
    pub fn with_puncture_end(mut self, puncture_end: PunctureEnd) -> Self {
        self.puncture_end = puncture_end;
        self
    }

    /// Set the weld tolerance, relative to the bounding-box diagonal.
    pub fn with_weld_tolerance(mut self, weld_tolerance: f64) -> Self {
        self.weld_tolerance = weld_tolerance;
        self
    }

    /// Set the larger `lambda` values tried on closed surfaces (empty: none).
    pub fn with_closed_lambda_fallbacks(mut self, closed_lambda_fallbacks: Vec<f64>) -> Self {
        self.closed_lambda_fallbacks = closed_lambda_fallbacks;
        self
    }
}

/// `lambda` of the composite initial map of open surfaces. The paper flattens open surfaces
/// conformally; on elongated or branching surfaces (the hand, the hippocampal sheet) that
/// squeezes protrusions by orders of magnitude and the transport map inherits the error. Its
/// closed-surface recipe with `lambda = 0.5` keeps every shared open mesh at or below the
/// paper's open-surface distortion (see README).
pub const DEFAULT_OPEN_LAMBDA: f64 = 0.5;

/// Stretch-energy iterations of the open surfaces' initial map that factor their own
/// matrix; the later ones reuse the last factorization (the matrix changes little once the
/// map nears its fixed point) unless their step goes uphill or folds a face. Against
/// factoring every iteration the final energies agree to 3-4 digits and the maps' mean
/// `|d_area|` and `|d_angle|` to 2%, with 6-7 of the 10 iterations reusing a factorization.
/// Closed surfaces factor every iteration (see the option's doc).
pub const DEFAULT_OPEN_FACTORED_ITERATIONS: usize = 3;

/// Transport sites of the radius search by default (see [`ParamOptions::search_sites`]):
/// against 4000 the mean |d_area| and |d_angle| stay within 1% on the shared meshes, and the
/// 4k-8k-vertex meshes search on a coarse level too; at 1000 the 12k brain's map was worse.
pub const DEFAULT_SEARCH_SITES: usize = 2000;

/// Sweeps of the area refinement by default (over-relaxed, see
/// [`crate::refine::area_refine::RefineOptions`]). On the shared closed meshes (1.8k to 48k vertices)
/// the centroid map leaves a mean `|d_area|` of 0.2 to 0.5 after fold repair; 30 sweeps bring
/// it below 0.2 (README).
pub const DEFAULT_AREA_REFINEMENT: usize = crate::refine::area_refine::DEFAULT_SWEEPS;

/// Initial flattening of open surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OpenInitialMap {
    /// Disk conformal map (paper Sec. 3.1.1).
    Conformal,
    /// Stretch energy map composed with `lambda * mu` (the closed-surface recipe, Sec. 3.2.1).
    #[default]
    Composite,
}

impl std::str::FromStr for OpenInitialMap {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "conformal" => Ok(OpenInitialMap::Conformal),
            "composite" => Ok(OpenInitialMap::Composite),
            _ => Err(format!("unknown initial map '{s}': use conformal or composite")),
        }
    }
}

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

impl std::str::FromStr for PunctureEnd {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "best" => Ok(PunctureEnd::Best),
            "bottom" => Ok(PunctureEnd::Bottom),
            "top" => Ok(PunctureEnd::Top),
            _ => Err(format!("unknown puncture end '{s}': use best, bottom or top")),
        }
    }
}

/// The default [`ParamOptions::closed_lambda_fallbacks`]: each tried in turn, above the
/// `lambda` that failed. 0.5 and 0.8 rescued the stretched meshes above (the bunny
/// stretched 10 times at 0.5, 50 times at 1); 1 (the stretch
/// energy map alone) is the last resort because the fit of the map's angles is worst there.
pub const DEFAULT_LAMBDA_FALLBACKS: [f64; 3] = [0.5, 0.8, 1.0];
