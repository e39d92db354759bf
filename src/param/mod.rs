//! The adaptive area-preserving parameterization `f = phi^-1 o h_r* o r* g` (paper Eq. 14) and
//! its fixed-domain baselines.
//!
//! Open disks (Sec. 3.1): disk conformal map `g`, then for each radius `r` the transport map
//! `h_r` on the disk of radius `r` with the stereographic density; `r*` minimises the
//! area-normalised mean of `|mu|^2` of `(h_r o r g)^-1` (Eq. 12) by Brent's method over `Z*`
//! in `[-0.995, 0.995]` (closed surfaces: run in the variable `atanh(Z*)`, tolerance on
//! `Z*`; large meshes: on a coarse level of transport sites, `crate::omt::coarse_level`, with
//! only `r*` solved at full resolution); then the inverse stereographic projection.
//!
//! The steps, one file each: `options`, `prepare` (check, weld and classify the mesh
//! once), `search` (initial disk map and radius search), `finish` (transport at `r*`,
//! smoothing, fold repair, area refinement, report), `puncture_end` (both ends of a
//! closed surface) and `lambda_fallback` (a larger `lambda` when the transport fails);
//! `report` holds what they measure. The files import downwards only: this one calls
//! the fallbacks and the puncture ends, which call `search` and `finish`.

pub(crate) mod finish;
pub(crate) mod lambda_fallback;
pub(crate) mod multilevel;
pub(crate) mod options;
pub(crate) mod prepare;
pub(crate) mod puncture_end;
pub(crate) mod report;
pub(crate) mod search;

pub use crate::cap::CapMap;
pub use lambda_fallback::{POOR_MAP_AREA_DISTORTION, RESCUE_FROM_LAMBDA};
pub use multilevel::COARSE_RATIO;
pub use options::{
    ClosedOptions, OpenInitialMap, OpenOptions, ParamOptions, PunctureEnd, RefinementOptions, SearchOptions, DEFAULT_AREA_REFINEMENT,
    DEFAULT_COARSE_VERTICES, DEFAULT_LAMBDA_FALLBACKS, DEFAULT_MULTILEVEL_ABOVE, DEFAULT_OPEN_FACTORED_ITERATIONS, DEFAULT_RESCUE_STRETCH_ITERATIONS, DEFAULT_OPEN_LAMBDA, DEFAULT_SEARCH_SITES, MASS_TOLERANCE,
    TRANSPORT_TOLERANCE,
};
pub use report::{FlattenReport, LambdaFallback, MapQuality, MultilevelReport, ParamReport, PunctureTrial, RadiusSample};
pub use search::{search_level_sites, MIN_SEARCH_SITES, SEARCH_RATIO, SMALL_SEARCH_RATIO};

use crate::error::Error;
use crate::mesh::{SurfaceKind, TriMesh};
use crate::progress::{self, Progress, Stage};
use finish::parameterize_once;
use lambda_fallback::{every_lambda_failed, is_precision_failure, next_lambda, rescue_lambda};
use prepare::{prepare, Prepared};
use std::time::Instant;

/// Parameterize an open disk-like or closed genus-0 `mesh` onto the domain of `options`.
///
/// A closed surface whose transport stalls (its initial map squeezes part of the surface
/// below double precision) or whose map is poor is mapped again with the next of
/// [`ClosedOptions::lambda_fallbacks`] (see `lambda_fallback`);
/// [`ParamReport::lambda_fallbacks`] lists the attempts not kept, `report.flatten` the
/// `lambda` used, and `report.seconds` then covers every attempt; when the transport stalled
/// at every one, the fallbacks from [`RESCUE_FROM_LAMBDA`] are tried once more with
/// [`ClosedOptions::rescue_stretch_iterations`] stretch-energy iterations. A map that still stalls,
/// folds or is poor is made again with the edges shorter than 5% of the mean edge collapsed
/// (a degenerate triangulation's needles, [`crate::mesh::short_edges`]) and the better map
/// kept ([`ParamReport::collapsed_short_edges`]).
///
/// The work runs on a worker thread of rayon's pool; `progress` is called on this thread
/// (see `crate::pool`).
pub fn parameterize(mesh: &TriMesh, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    crate::pool::on_pool(progress, |progress| {
        let map = parameterize_with_fallbacks(mesh, options, progress);
        crate::linalg::release_spare();
        map
    })
}

/// [`parameterize`] on the current thread.
fn parameterize_with_fallbacks(mesh: &TriMesh, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    options.check().map_err(Error::InvalidOption)?;
    let start = Instant::now();
    progress::check(progress, Stage::Validate, 0.0, "checking the mesh")?;
    let prepared = prepare(mesh, options)?;
    if multilevel::applies(&prepared, options) {
        return multilevel::parameterize_multilevel(mesh, &prepared, options, progress);
    }
    let first = map_prepared(mesh, &prepared, options, progress, start);
    // A transport that cannot reach the masses of a degenerate triangulation's needles, or a
    // map they leave folded or poor: mapped again with the short edges collapsed, and the
    // better map kept (docs/method.md, "Degenerate triangulations").
    let retry = match &first {
        Err(e) => is_precision_failure(e),
        Ok(map) => map.report.flipped_faces > 0 || is_poor(map),
    };
    if !retry {
        return first;
    }
    let Some((cleaned, edges)) = prepare::without_short_edges(&prepared)? else { return first };
    let second = map_prepared(mesh, &cleaned, options, progress, start);
    let timed = |mut map: CapMap, collapsed: usize| {
        map.report.collapsed_short_edges = collapsed;
        map.report.seconds = start.elapsed().as_secs_f64();
        map
    };
    match (first, second) {
        (_, Err(e @ Error::Cancelled(_))) => Err(e),
        (Ok(a), Ok(b)) if collapse_rank(&b) < collapse_rank(&a) => Ok(timed(b, edges)),
        (Ok(a), _) => Ok(timed(a, 0)),
        (Err(_), Ok(b)) => Ok(timed(b, edges)),
        (Err(e), Err(_)) => Err(e),
    }
}

/// The order in which a map and its remap with short edges collapsed are preferred (lowest
/// first): flipped faces, then poor, then mean |d_area|.
fn collapse_rank(map: &CapMap) -> (usize, bool, f64) {
    (map.report.flipped_faces, is_poor(map), map.report.area_distortion.mean_abs)
}

/// [`parameterize`] of the prepared mesh, with the lambda fallbacks of a closed surface and,
/// when every one stalled, the rescue round (`lambda_fallback`).
fn map_prepared(mesh: &TriMesh, prepared: &Prepared, options: &ParamOptions, progress: &dyn Progress, start: Instant) -> Result<CapMap, Error> {
    // Every attempt not returned, the best poor map so far and the last transport failure.
    let mut attempts: Vec<LambdaFallback> = Vec::new();
    let mut best: Option<((f64, usize), CapMap)> = None;
    let mut failure: Option<Error> = None;
    let mut attempt = options.clone();
    let closed = prepared.kind == SurfaceKind::ClosedSphere;
    let mut rescuing = false;
    loop {
        let lambda = attempt.closed.flatten.lambda;
        let stretch_iterations = attempt.closed.flatten.stretch.max_iterations;
        let tried = |reason: String, mean_abs_area_distortion: Option<f64>| LambdaFallback { lambda, stretch_iterations, reason, mean_abs_area_distortion };
        match parameterize_at_lambda(mesh, prepared, &attempt, progress) {
            Ok(map) if !is_poor(&map) => return Ok(with_fallbacks(map, attempts, start)),
            Ok(map) => {
                let d = map.report.area_distortion.mean_abs;
                attempts.push(tried(format!("mean |d_area| {d:.3} is above {POOR_MAP_AREA_DISTORTION}"), Some(d)));
                if !best.as_ref().is_some_and(|(_, b)| b.report.area_distortion.mean_abs <= d) {
                    best = Some(((lambda, stretch_iterations), map));
                }
            }
            Err(e) if is_precision_failure(&e) => {
                attempts.push(tried(e.to_string(), None));
                failure = Some(e);
            }
            Err(e) => return Err(e),
        }
        // The rescue round only when no attempt gave a map (docs/method.md section 13).
        let rescue = if closed && !rescuing && best.is_none() { rescue_lambda(options) } else { None };
        match (next_lambda(options, lambda).filter(|_| closed), rescue) {
            (Some(next), _) => attempt.closed.flatten.lambda = next,
            (None, Some(first)) => {
                rescuing = true;
                attempt.closed.flatten.lambda = first;
                attempt.closed.flatten.stretch.max_iterations = options.closed.rescue_stretch_iterations;
            }
            (None, None) => {
                return match (best, failure) {
                    (Some((kept, map)), _) => {
                        attempts.retain(|a| (a.lambda, a.stretch_iterations) != kept);
                        Ok(with_fallbacks(map, attempts, start))
                    }
                    (None, Some(e)) => Err(every_lambda_failed(&attempts, e)),
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
    map.report.quality == MapQuality::Poor
}

/// `map` with the attempts not kept, its wall time counted from `start` when there were any.
fn with_fallbacks(mut map: CapMap, fallbacks: Vec<LambdaFallback>, start: Instant) -> CapMap {
    if !fallbacks.is_empty() {
        map.report.seconds = start.elapsed().as_secs_f64();
    }
    map.report.lambda_fallbacks = fallbacks;
    map
}

/// [`parameterize`] at `options.closed.flatten.lambda`, without fallbacks.
fn parameterize_at_lambda(mesh: &TriMesh, prepared: &Prepared, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let at = |other_end: bool| {
        let mut o = options.clone();
        o.closed.flatten.puncture.other_end = other_end;
        o
    };
    match options.closed.puncture_end {
        PunctureEnd::Bottom => parameterize_once(mesh, prepared, &at(false), progress),
        PunctureEnd::Top => parameterize_once(mesh, prepared, &at(true), progress),
        PunctureEnd::Best => puncture_end::parameterize_best_end(mesh, prepared, &at(false), &at(true), progress),
    }
}
