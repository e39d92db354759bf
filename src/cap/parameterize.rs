//! The adaptive area-preserving parameterization `f = phi^-1 o h_r* o r* g` (paper Eq. 14) and
//! its fixed-domain baselines.
//!
//! Open disks (Sec. 3.1): disk conformal map `g`, then for each radius `r` the transport map
//! `h_r` on the disk of radius `r` with the stereographic density; `r*` minimises the
//! area-normalised mean of `|mu|^2` of `(h_r o r g)^-1` (Eq. 12) by Brent's method over `Z*`
//! in `[-0.995, 0.995]` (closed surfaces: run in the variable `atanh(Z*)`, tolerance on
//! `Z*`; large meshes: on a coarse level of transport sites, [`crate::omt::coarse_level`], with
//! only `r*` solved at full resolution); then the inverse stereographic projection.

use crate::refine::area_refine::{refine_areas, AreaRefineReport, RefineOptions};
use super::brent;
use crate::omt::coarse_level::CoarseLevel;
use super::domain::{Domain, MAX_RADIUS, MIN_RADIUS};
use super::lambda_fallback::{is_closed, is_precision_failure, next_lambda, LambdaFallback, DEFAULT_LAMBDA_FALLBACKS, POOR_MAP_AREA_DISTORTION};
use crate::omt::planar_transport::{PlanarTransport, TransportMap};
pub use super::puncture_end::{PunctureEnd, PunctureTrial};
use crate::refine::regularize::{regularise, Smoothing, SmoothingTrial, PUNCTURE_HELD_RINGS};
use crate::refine::untangle::UntangleReport;
use super::stereographic::{inverse_stereographic, radius_of_z_star, z_star_of_radius};
use crate::error::Error;
use crate::flatten::closed::{composite_disk_map, flatten_closed, ClosedFlattenOptions, ClosedFlattenReport};
use crate::flatten::puncture::Puncture;
use crate::flatten::stretch_energy::StretchOptions;
use crate::flatten::{disk_conformal_map, DiskConformalOptions, DiskConformalReport};
use crate::mesh::geometry::{folded_faces, lift, vertex_areas};
use crate::mesh::topology::within_rings;
use crate::mesh::{repair, validate, SurfaceKind, TriMesh};
use crate::linalg::cotangent_weights;
use crate::metrics::{angle_distortion, area_distortion, conformal_energy, conformal_energy_surface_weighted, Stats};
use crate::omt::{OmtError, OtOptions, RadialDensity, StereographicDensity, UniformDensity};
use crate::progress::{self, Progress, Stage};
use std::time::Instant;

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
/// since the regularisation and the face-level refinement that follow move the vertices far
/// more. Newton converges quadratically there, so this saves the last step whenever the one
/// before it lands below `1e-3`, with mean `|d_area|` and `|d_angle|` within 1% of
/// [`MASS_TOLERANCE`]'s; at `5e-3` the 100k ellipsoid's mean `|d_area|` rose 11%.
pub const TRANSPORT_TOLERANCE: f64 = 1e-3;

/// Options of [`parameterize`].
#[derive(Debug, Clone)]
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
    /// level of at most [`search_level_sites`] sites (see [`crate::omt::coarse_level`]:
    /// `max(search_sites, n / SEARCH_RATIO)` when that is less than half the vertices; a
    /// closed surface also at most a quarter of its vertices, [`SMALL_SEARCH_RATIO`]) and
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
    /// Regularisation of the final centroid map (see [`crate::refine::regularize`]);
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

/// Largest ratio of vertices to coarse sites in the radius search. The coarse energy follows
/// the full one only while the coarse level resolves the map: on the synthetic 164k-vertex
/// ellipsoid, 2565 sites (1 in 64) put the minimum at `Z* = -0.967` where the full curve
/// falls to the bound `-0.9945` (mean `|d_area|` 0.13 instead of 0.010), while 7683 sites
/// (1 in 21) follow it to the bound. The shared meshes search on 1 in 3 to 1 in 21.
pub const SEARCH_RATIO: usize = 16;

/// Smallest ratio of vertices to requested coarse sites in the radius search of a closed
/// surface: below `4 * search_sites` vertices it searches on a quarter of its vertices at
/// most (a covering by 2-hop balls, about 1 site in 8 to 10) instead of at full resolution
/// or on 1-hop balls (1 in 3 or 4). The closed surfaces' energy falls to the bound of `Z*`
/// (every shared closed mesh), which the coarse search finds as well, with the same `Z*` and
/// distortions within 0.2%. Open surfaces keep their searches: their minima are interior and
/// a coarse level this small moves them (the sampled caps of `tests/param_cap_anchor.rs`
/// would miss their `Z*` by more than the 0.02 allowed).
pub const SMALL_SEARCH_RATIO: usize = 4;

/// Fewest coarse sites requested of a closed surface's coarse radius search: closed meshes
/// of fewer than `2 * MIN_SEARCH_SITES` vertices search at full resolution (milliseconds).
pub const MIN_SEARCH_SITES: usize = 250;

/// The most transport sites of the radius search's coarse level for a mesh of `n` vertices
/// (see [`ParamOptions::search_sites`]), or `None` when it searches at full resolution:
/// `max(search_sites, n / SEARCH_RATIO)` sites, for a closed surface
/// `max(min(search_sites, max(n / SMALL_SEARCH_RATIO, MIN_SEARCH_SITES)), n / SEARCH_RATIO)`,
/// when that is fewer than half the vertices; `None` for `search_sites = 0`.
pub fn search_level_sites(n: usize, search_sites: usize, closed: bool) -> Option<usize> {
    if search_sites == 0 {
        return None;
    }
    let cap = if closed { (n / SMALL_SEARCH_RATIO).max(MIN_SEARCH_SITES) } else { usize::MAX };
    let sites = search_sites.min(cap).max(n / SEARCH_RATIO);
    (2 * sites < n).then_some(sites)
}

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

/// The initial flattening's report, by surface kind.
#[derive(Debug, Clone, serde::Serialize)]
#[serde(untagged)]
pub enum FlattenReport {
    /// Disk conformal map of an open surface.
    Open(DiskConformalReport),
    /// Puncture, stretch energy and quasi-conformal composition of a closed surface.
    Closed(ClosedFlattenReport),
}

/// One evaluation of the radius search.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RadiusSample {
    /// Disk radius.
    pub r: f64,
    /// Cap bound for that radius.
    pub z_star: f64,
    /// Area-normalised mean `|mu|^2`.
    pub energy: f64,
    /// Newton iterations of that transport solve (on the coarse level when the search ran
    /// there).
    pub newton_iterations: usize,
}

/// Serialize a report field as its `Display` string (the JSON keeps the words of the
/// command-line output).
fn as_display<T: std::fmt::Display, S: serde::Serializer>(value: &T, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.collect_str(value)
}

/// Everything measured about one parameterization.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ParamReport {
    /// Domain used (serialized as its display string, e.g. `"adaptive"`, `"radius=1.5"`).
    #[serde(serialize_with = "as_display")]
    pub domain: Domain,
    /// Surface kind (serialized as its display string, `"open disk"` or `"closed genus-0"`).
    #[serde(serialize_with = "as_display")]
    pub kind: SurfaceKind,
    /// Input vertices.
    pub n_vertices: usize,
    /// Input faces.
    pub n_faces: usize,
    /// Vertices merged with a coincident one before mapping.
    pub welded_vertices: usize,
    /// Optimal (or fixed) disk radius; `None` for the planar disk.
    pub r_star: Option<f64>,
    /// Cap bound `Z*`; `None` for the planar disk.
    pub z_star: Option<f64>,
    /// Per-face area distortion statistics.
    pub area_distortion: Stats,
    /// Per-corner angle distortion statistics (radians).
    pub angle_distortion: Stats,
    /// Area-normalised mean `|mu|^2` at the final radius.
    pub conformal_energy: f64,
    /// Faces with non-positive orientation in the final map.
    pub flipped_faces: usize,
    /// Regularisation strength of the final centroid map (0: the paper's plain map).
    pub smoothing_kappa: f64,
    /// Every regularisation tried, with its measured area distortion.
    pub smoothing_trials: Vec<SmoothingTrial>,
    /// The repair of folded faces after transport (see [`crate::refine::untangle`]).
    pub untangle: UntangleReport,
    /// The face-level area refinement (see [`crate::refine::area_refine`]).
    pub area_refinement: AreaRefineReport,
    /// Newton iterations over all full-resolution transport solves.
    pub newton_iterations: usize,
    /// Sites of the coarse level the radius search ran on; `None` when it ran at full
    /// resolution.
    pub search_sites: Option<usize>,
    /// Newton iterations of the coarse radius search.
    pub coarse_newton_iterations: usize,
    /// Transport solves.
    pub transport_solves: usize,
    /// Symbolic factorizations of the transport Newton matrices, coarse search included
    /// (the other iterations reused one).
    pub transport_symbolic_factorizations: usize,
    /// Radius search evaluations in order.
    pub radius_curve: Vec<RadiusSample>,
    /// Initial flattening report.
    pub flatten: FlattenReport,
    /// The punctured quadrilateral of a closed surface (indices in the welded mesh).
    pub puncture: Option<Puncture>,
    /// Both ends tried when the puncture end is [`PunctureEnd::Best`] (empty otherwise).
    pub puncture_trials: Vec<PunctureTrial>,
    /// The composition factors tried for a closed surface and not kept (its transport
    /// stalled or its map was poor, [`ParamOptions::closed_lambda_fallbacks`]); `flatten`
    /// has the `lambda` kept. Empty when the first worked.
    pub lambda_fallbacks: Vec<LambdaFallback>,
    /// Wall-clock seconds of the whole parameterization (for [`PunctureEnd::Best`] both
    /// ends' searches, in parallel, and the kept end's second half; the stage seconds below
    /// are the kept end's).
    pub seconds: f64,
    /// Seconds spent in the initial flattening.
    pub flatten_seconds: f64,
    /// Seconds spent in transport solves (radius search included).
    pub transport_seconds: f64,
    /// Seconds spent in the regularisation trials and fold repair.
    pub regularise_seconds: f64,
    /// Seconds spent in the face-level area refinement.
    pub refine_seconds: f64,
}

/// A parameterization onto the cap (or the planar disk).
#[derive(Debug, Clone)]
pub struct CapMap {
    /// Positions on the disk of radius `r*` (`h_r* o r* g`), one per input vertex.
    pub plane: Vec<[f64; 2]>,
    /// Positions on the unit sphere (`Z >= Z*`), or `(x, y, 0)` for the planar disk.
    pub cap: Vec<[f64; 3]>,
    /// Input faces of the punctured quad of a closed surface: they map to the cap's flat
    /// bottom (their corners on the rim `Z = Z*`). Empty for open surfaces.
    pub bottom_faces: Vec<usize>,
    /// The kind of surface mapped (as in [`ParamReport::kind`]).
    pub kind: SurfaceKind,
    /// What was measured.
    pub report: ParamReport,
}

impl CapMap {
    /// The input mesh with its vertices moved onto the cap (same connectivity).
    pub fn cap_mesh(&self, mesh: &TriMesh) -> TriMesh {
        TriMesh::new(self.cap.clone(), mesh.faces.clone())
    }
}

/// Parameterize an open disk-like or closed genus-0 `mesh` onto the domain of `options`.
///
/// A closed surface whose transport stalls (its initial map squeezes part of the surface
/// below double precision) or whose map is poor is mapped again with the next of
/// [`ParamOptions::closed_lambda_fallbacks`] (see [`super::lambda_fallback`]);
/// [`ParamReport::lambda_fallbacks`] lists the attempts not kept, `report.flatten` the
/// `lambda` used, and `report.seconds` then covers every attempt.
///
/// The work runs on a worker thread of rayon's pool; `progress` is called on this thread
/// (see `crate::pool`).
pub fn parameterize(mesh: &TriMesh, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    crate::pool::on_pool(progress, |progress| parameterize_with_fallbacks(mesh, options, progress))
}

/// [`parameterize`] on the current thread.
fn parameterize_with_fallbacks(mesh: &TriMesh, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    options.domain.check().map_err(Error::InvalidOption)?;
    let start = Instant::now();
    // Every attempt not returned, the best poor map so far and the last transport failure.
    let mut attempts = Vec::new();
    let mut best: Option<(f64, CapMap)> = None;
    let mut failure: Option<Error> = None;
    let mut attempt = options.clone();
    // Whether the mesh is a closed surface, checked once, on the first fallback.
    let closed = std::cell::OnceCell::new();
    loop {
        let lambda = attempt.closed.lambda;
        match parameterize_at_lambda(mesh, &attempt, progress) {
            Ok(map) if !is_poor(&map) => return Ok(with_fallbacks(map, attempts, start)),
            Ok(map) => {
                let d = map.report.area_distortion.mean_abs;
                attempts.push(LambdaFallback { lambda, reason: format!("mean |d_area| {d:.3} is above {POOR_MAP_AREA_DISTORTION}"), mean_abs_area_distortion: Some(d) });
                if !best.as_ref().is_some_and(|(_, b)| b.report.area_distortion.mean_abs <= d) {
                    best = Some((lambda, map));
                }
            }
            Err(e) if is_precision_failure(&e) => {
                attempts.push(LambdaFallback { lambda, reason: e.to_string(), mean_abs_area_distortion: None });
                failure = Some(e);
            }
            Err(e) => return Err(e),
        }
        match next_lambda(options, lambda).filter(|_| *closed.get_or_init(|| is_closed(mesh, options))) {
            Some(next) => attempt.closed.lambda = next,
            None => {
                return match (best, failure) {
                    (Some((kept, map)), _) => {
                        attempts.retain(|a| a.lambda != kept);
                        Ok(with_fallbacks(map, attempts, start))
                    }
                    (None, Some(e)) => Err(e),
                    // Each attempt keeps a map or a failure; this is for the compiler.
                    (None, None) => Err(Error::Internal("no parameterization was attempted".into())),
                };
            }
        }
    }
}

/// A map poor enough that a closed surface is mapped again with a larger `lambda`: mean
/// `|d_area|` above [`POOR_MAP_AREA_DISTORTION`] on the adaptive cap.
fn is_poor(map: &CapMap) -> bool {
    map.report.domain == Domain::Adaptive && !(map.report.area_distortion.mean_abs <= POOR_MAP_AREA_DISTORTION)
}

/// `map` with the attempts not kept, its wall time counted from `start` when there were any.
fn with_fallbacks(mut map: CapMap, fallbacks: Vec<LambdaFallback>, start: Instant) -> CapMap {
    if !fallbacks.is_empty() {
        map.report.seconds = start.elapsed().as_secs_f64();
    }
    map.report.lambda_fallbacks = fallbacks;
    map
}

/// [`parameterize`] at `options.closed.lambda`, without fallbacks.
fn parameterize_at_lambda(mesh: &TriMesh, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let at = |other_end: bool| {
        let mut o = options.clone();
        o.closed.puncture.other_end = other_end;
        o
    };
    match options.puncture_end {
        PunctureEnd::Bottom => parameterize_once(mesh, &at(false), progress),
        PunctureEnd::Top => parameterize_once(mesh, &at(true), progress),
        PunctureEnd::Best => super::puncture_end::parameterize_best_end(mesh, &at(false), &at(true), progress),
    }
}

/// [`parameterize`] with the puncture end fixed by `options.closed.puncture`.
pub(super) fn parameterize_once(mesh: &TriMesh, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let searched = search_radius(mesh, options, false, progress)?;
    finish(mesh, searched, options, progress)
}

/// A parameterization up to its radius (the first half of [`parameterize_once`]): the checked
/// and welded mesh, its initial disk map and the radius search.
pub(super) struct Searched {
    start: Instant,
    welded: repair::Welded,
    kind: SurfaceKind,
    faces: Vec<[u32; 3]>,
    disk: Vec<[f64; 2]>,
    on_boundary: Vec<bool>,
    target: Vec<f64>,
    flatten_report: FlattenReport,
    pub(super) puncture: Option<Puncture>,
    radius: f64,
    /// The transport map at `radius` when the search solved it at full resolution.
    map: Option<TransportMap>,
    /// Mean `|d_area|` of the search's map at `r*` on the cap (the coarse level's map
    /// prolonged to every vertex when the search ran there); `None` without a search or when
    /// not asked for.
    pub(super) search_area_distortion: Option<f64>,
    curve: Vec<RadiusSample>,
    search_sites: Option<usize>,
    coarse_newton_iterations: usize,
    /// Full-resolution Newton iterations and solves so far, and symbolic factorizations at
    /// either level.
    newton_iterations: usize,
    solves: usize,
    symbolic_factorizations: usize,
    flatten_seconds: f64,
    transport_seconds: f64,
}

/// The best radius of a search so far: its energy, and its full-resolution map when the
/// search runs at full resolution, else the coarse map prolonged to every vertex.
struct SearchBest {
    r: f64,
    energy: f64,
    map: Option<TransportMap>,
    prolonged: Vec<[f64; 2]>,
}

/// The source density of the transport: uniform on the planar disk, stereographic on the
/// cap's disks.
fn transport_density(domain: Domain) -> &'static dyn RadialDensity {
    if domain == Domain::Disk {
        &UniformDensity
    } else {
        &StereographicDensity
    }
}

/// Check, weld and flatten `mesh`, and find the radius (the search of the adaptive domain).
/// With `rank_ends`, also measure the search map at `r*`
/// ([`Searched::search_area_distortion`], which [`PunctureEnd::Best`] compares).
pub(super) fn search_radius(mesh: &TriMesh, options: &ParamOptions, rank_ends: bool, progress: &dyn Progress) -> Result<Searched, Error> {
    let start = Instant::now();
    progress::check(progress, Stage::Validate, 0.0, "checking the mesh")?;
    // Hard errors of the input as given (indices out of range, repeated indices in a face,
    // NaN, duplicate faces, non-manifold edges): welding would drop such faces silently.
    let input_topology = crate::mesh::validate::checked_topology(mesh)?;
    let diag = mesh.bounding_box_diagonal();
    let welded = repair::weld_coincident(mesh, options.weld_tolerance * diag);
    let work = &welded.mesh;
    // Nothing welded or dropped: the input's topology is the welded mesh's.
    let (kind, topology) = if work.vertices.len() == mesh.vertices.len() && work.faces == mesh.faces {
        crate::mesh::validate::classify_checked(input_topology)?
    } else {
        validate(work)?
    };
    progress::check(progress, Stage::Flatten, 0.0, "initial flattening")?;
    let t_flat = Instant::now();
    let (faces, boundary, disk, flatten_report, puncture) = match kind {
        SurfaceKind::OpenDisk => {
            let boundary = topology.boundary_loops[0].clone();
            if options.open_initial == OpenInitialMap::Composite {
                let stretch = StretchOptions { factored_iterations: options.open_factored_iterations, refactor_period: 0, ..options.closed.stretch.clone() };
                let composite = ClosedFlattenOptions { lambda: options.open_lambda, stretch, ..options.closed.clone() };
                let (disk, rep) = composite_disk_map(&work.vertices, &work.faces, &boundary, &composite)?;
                (work.faces.clone(), boundary, disk, FlattenReport::Closed(rep), None)
            } else {
                let (disk, rep) = disk_conformal_map(&work.vertices, &work.faces, &boundary, &options.flatten)?;
                (work.faces.clone(), boundary, disk, FlattenReport::Open(rep), None)
            }
        }
        SurfaceKind::ClosedSphere => {
            let flat = flatten_closed(work, &options.closed)?;
            (flat.faces, flat.puncture.quad.to_vec(), flat.uv, FlattenReport::Closed(flat.report), Some(flat.puncture))
        }
    };
    let flatten_seconds = t_flat.elapsed().as_secs_f64();
    let mut on_boundary = vec![false; work.n_vertices()];
    for &b in &boundary {
        on_boundary[b as usize] = true;
    }
    let target = vertex_areas(&work.vertices, &faces);
    let density = transport_density(options.domain);
    let mut transport = PlanarTransport::new(&disk, &on_boundary, &target, density, options.transport.clone());
    let t_ot = Instant::now();
    let mut curve = Vec::new();
    let (mut search_sites, mut coarse_newton_iterations, mut coarse_symbolic) = (None, 0, 0);
    let mut search_area_distortion = None;
    let (radius, transported) = match options.domain {
        Domain::Disk => (1.0, None),
        Domain::Adaptive => {
            let coarse = search_level_sites(disk.len(), options.search_sites, kind == SurfaceKind::ClosedSphere).and_then(|sites| CoarseLevel::build(&disk, &faces, &on_boundary, &target, sites));
            let mut coarse_transport = coarse.as_ref().map(|c| PlanarTransport::new(&c.sites, &c.on_boundary, &c.masses, density, options.transport.clone()));
            search_sites = coarse.as_ref().map(CoarseLevel::len);
            let mut best: Option<SearchBest> = None;
            let mut evals = 0usize;
            let max_evals = options.max_search_evaluations;
            let search_tolerance = options.search_tolerance;
            // Closed surfaces search over w = atanh(Z*) (= -ln r): their optimum is at the
            // lower bound (the cap becomes the whole sphere but for the punctured quad), and
            // golden steps towards it shrink the distance geometrically in r rather than in
            // Z*: 10 solves instead of 17 on the shared meshes, with the tolerance kept on Z*
            // (dZ*/dw = 1 - Z*^2); started at the bound, 2. Open surfaces search over Z*
            // itself, as the paper's fminbnd: their objective can have several local minima
            // (hippocampal sheet: 0.2965 at Z* = 0.126, 0.3191 at 0.725), and the other
            // variable's first evaluations land in the worse basin there.
            let in_atanh = kind == SurfaceKind::ClosedSphere;
            let to_z = |w: f64| if in_atanh { w.tanh() } else { w };
            let mut objective = |w: f64| -> Result<f64, Error> {
                let z = to_z(w);
                let r = radius_of_z_star(z);
                evals += 1;
                progress::check(progress, Stage::RadiusSearch, evals as f64 / max_evals as f64, &format!("r = {r:.4}, Z* = {z:.4}"))?;
                let (prolonged, iterations, map) = match (coarse.as_ref(), coarse_transport.as_mut()) {
                    (Some(level), Some(ct)) => {
                        let map = ct.map_at_tolerance(r, search_tolerance, progress)?;
                        (level.prolong(&map.centroids), map.report.iterations, None)
                    }
                    _ => {
                        let map = transport.map_at_tolerance(r, search_tolerance, progress)?;
                        (Vec::new(), map.report.iterations, Some(map))
                    }
                };
                let centroids: &[[f64; 2]] = map.as_ref().map_or(&prolonged, |m| &m.centroids);
                let e = if kind == SurfaceKind::OpenDisk {
                    conformal_energy(&work.vertices, centroids, &faces)
                } else {
                    conformal_energy_surface_weighted(&work.vertices, centroids, &faces)
                };
                curve.push(RadiusSample { r, z_star: z, energy: e, newton_iterations: iterations });
                if best.as_ref().map_or(true, |b| e < b.energy) {
                    best = Some(SearchBest { r, energy: e, map, prolonged });
                }
                Ok(e)
            };
            let (z_lo, z_hi) = (z_star_of_radius(MAX_RADIUS), z_star_of_radius(MIN_RADIUS));
            let z_tolerance = options.z_tolerance;
            if in_atanh {
                // Their energy falls all the way to the bound on every shared closed mesh:
                // the search starts there and ends after two solves when the energy rises
                // inwards (`brent::minimize_from_lower_bound`).
                brent::minimize_from_lower_bound(&mut objective, z_lo.atanh(), z_hi.atanh(), |w: f64| z_tolerance * w.cosh().powi(2), max_evals)?;
            } else {
                brent::minimize(&mut objective, z_lo, z_hi, z_tolerance, max_evals)?;
            }
            coarse_newton_iterations = coarse_transport.as_ref().map_or(0, |t| t.newton_iterations);
            coarse_symbolic = coarse_transport.as_ref().map_or(0, |t| t.symbolic_factorizations);
            let SearchBest { r, map, prolonged, .. } = best.ok_or_else(|| Error::Internal("radius search made no evaluation".into()))?;
            if rank_ends {
                let on_cap: Vec<[f64; 3]> = map.as_ref().map_or(&prolonged, |m| &m.centroids).iter().map(|&q| inverse_stereographic(q)).collect();
                search_area_distortion = Some(Stats::of(area_distortion(&work.vertices, &on_cap, &faces)).mean_abs);
            }
            match map {
                Some(map) if search_tolerance <= options.transport.tolerance => (r, Some(map)),
                Some(_) => (r, Some(transport.map_at(r, progress)?)),
                // A coarse search: the full problem is solved by `finish`.
                None => (r, None),
            }
        }
        fixed => (fixed.fixed_radius().unwrap_or(1.0), None),
    };
    let transport_seconds = t_ot.elapsed().as_secs_f64();
    let (newton_iterations, solves, symbolic) = (transport.newton_iterations, transport.solves, transport.symbolic_factorizations);
    drop(transport);
    Ok(Searched {
        start,
        kind,
        faces,
        disk,
        on_boundary,
        target,
        flatten_report,
        puncture,
        radius,
        map: transported,
        search_area_distortion,
        curve,
        search_sites,
        coarse_newton_iterations,
        newton_iterations,
        solves,
        symbolic_factorizations: symbolic + coarse_symbolic,
        flatten_seconds,
        transport_seconds,
        welded,
    })
}

/// The second half of [`parameterize_once`]: the transport map at the searched radius (unless
/// the search solved it), its regularisation and fold repair, the area refinement and the
/// report.
pub(super) fn finish(mesh: &TriMesh, s: Searched, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let Searched {
        start,
        welded,
        kind,
        faces,
        disk,
        on_boundary,
        target,
        flatten_report,
        puncture,
        radius,
        map,
        search_area_distortion: _,
        curve,
        search_sites,
        coarse_newton_iterations,
        mut newton_iterations,
        mut solves,
        symbolic_factorizations: mut symbolic,
        flatten_seconds,
        transport_seconds: search_seconds,
    } = s;
    let work = &welded.mesh;
    let t_ot = Instant::now();
    let transported = match map {
        Some(map) => map,
        None => {
            let mut transport = PlanarTransport::new(&disk, &on_boundary, &target, transport_density(options.domain), options.transport.clone());
            let map = transport.map_at(radius, progress)?;
            newton_iterations += transport.newton_iterations;
            solves += transport.solves;
            symbolic += transport.symbolic_factorizations;
            map
        }
    };
    let transport_seconds = search_seconds + t_ot.elapsed().as_secs_f64();
    let to_cap = |p: &[[f64; 2]]| -> Vec<[f64; 3]> {
        if options.domain == Domain::Disk {
            lift(p)
        } else {
            p.iter().map(|&q| inverse_stereographic(q)).collect()
        }
    };
    let t_reg = Instant::now();
    let cot = cotangent_weights(&work.vertices, &faces);
    let held = if kind == SurfaceKind::ClosedSphere { within_rings(&on_boundary, &faces, PUNCTURE_HELD_RINGS) } else { on_boundary.clone() };
    let chosen = regularise(&transported, &work.vertices, &faces, &cot, &on_boundary, &held, radius, options.smoothing, &to_cap).map_err(OmtError::Linear)?;
    let (kappa, mut plane, untangle_report, trials) = (chosen.kappa, chosen.positions, chosen.untangle, chosen.trials);
    let lift_one = |q: [f64; 2]| if options.domain == Domain::Disk { [q[0], q[1], 0.0] } else { inverse_stereographic(q) };
    let regularise_seconds = t_reg.elapsed().as_secs_f64();
    progress::check(progress, Stage::Project, 0.0, "area refinement")?;
    let t_refine = Instant::now();
    let refinement = refine_areas(&mut plane, &work.vertices, &faces, &on_boundary, &lift_one, RefineOptions { sweeps: options.area_refinement, ..Default::default() });
    let refine_seconds = t_refine.elapsed().as_secs_f64();
    progress::check(progress, Stage::Project, 0.0, "inverse stereographic projection")?;
    let cap_work = to_cap(&plane);
    let flipped_faces = folded_faces(&plane, &faces).len();
    let spherical = options.domain != Domain::Disk;
    let report = ParamReport {
        domain: options.domain,
        kind,
        n_vertices: mesh.n_vertices(),
        n_faces: mesh.n_faces(),
        welded_vertices: welded.merged_vertices,
        r_star: spherical.then_some(radius),
        z_star: spherical.then(|| z_star_of_radius(radius)),
        area_distortion: Stats::of(area_distortion(&work.vertices, &cap_work, &faces)),
        angle_distortion: Stats::of(angle_distortion(&work.vertices, &cap_work, &faces)),
        conformal_energy: conformal_energy(&work.vertices, &plane, &faces),
        flipped_faces,
        untangle: untangle_report,
        area_refinement: refinement,
        smoothing_kappa: kappa,
        smoothing_trials: trials,
        newton_iterations,
        search_sites,
        coarse_newton_iterations,
        transport_solves: solves,
        transport_symbolic_factorizations: symbolic,
        radius_curve: curve,
        flatten: flatten_report,
        puncture,
        puncture_trials: Vec::new(),
        lambda_fallbacks: Vec::new(),
        seconds: start.elapsed().as_secs_f64(),
        flatten_seconds,
        transport_seconds,
        regularise_seconds,
        refine_seconds,
    };
    // Back to the input's vertex numbering; vertices no face uses go to the origin.
    let plane_all = welded.old_to_new.iter().map(|&v| plane.get(v as usize).copied().unwrap_or([0.0; 2])).collect();
    let cap_all = welded.old_to_new.iter().map(|&v| cap_work.get(v as usize).copied().unwrap_or([0.0; 3])).collect();
    let bottom_faces = match &report.puncture {
        Some(p) => {
            let key = |f: [u32; 3]| {
                let mut k = f;
                k.sort_unstable();
                k
            };
            let quad: Vec<[u32; 3]> = p.faces.iter().map(|&f| key(work.faces[f])).collect();
            (0..mesh.n_faces()).filter(|&f| quad.contains(&key(mesh.faces[f].map(|v| welded.old_to_new.get(v as usize).copied().unwrap_or(repair::REMOVED))))).collect()
        }
        None => Vec::new(),
    };
    Ok(CapMap { plane: plane_all, cap: cap_all, bottom_faces, kind: report.kind, report })
}
