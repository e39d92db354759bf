//! What the commands that parameterize (`param`, `remesh`, `harmonics`) say about a poor map:
//! a warning on stderr, and exit code 3 unless `--allow-poor-map` (README: "Exit codes").

use crate::failure::Failure;
use capmesh::cap::Domain;
use std::path::Path;

/// Mean |d_area| above which the map is reported as poor on stderr (the bundled meshes map
/// at 0.008-0.13; a failed fold repair gives 0.4 and more); closed surfaces are mapped again
/// with a larger lambda above it first.
const POOR_AREA_DISTORTION: f64 = capmesh::param::POOR_MAP_AREA_DISTORTION;

/// Say on stderr when a map is fold-free but far from area preserving, rather than let a poor
/// result pass silently, when a closed surface needed a larger `lambda` than asked, and when
/// short edges were collapsed before mapping.
pub(crate) fn warn_if_poor(input: &Path, r: &capmesh::ParamReport) {
    if let capmesh::param::FlattenReport::Closed(used) = &r.flatten {
        // The rescue round retries a lambda with more stretch-energy iterations
        // (capmesh::param::RESCUE_FROM_LAMBDA): its attempts name their iterations.
        let first_iterations = r.lambda_fallbacks.first().map(|f| f.stretch_iterations);
        for tried in &r.lambda_fallbacks {
            eprintln!("warning: {}: not kept: lambda = {}: {}", input.display(), tried.describe(first_iterations.unwrap_or_default()), tried.reason);
        }
        if r.lambda_fallbacks.iter().any(|f| f.lambda == used.lambda) {
            eprintln!(
                "warning: {}: mapped with lambda = {} after {} stretch-energy iterations (the transport stalled at every lambda \
                 with the flattening's {}; report: lambda_fallbacks)",
                input.display(),
                used.lambda,
                used.stretch.iterations,
                first_iterations.unwrap_or_default()
            );
        } else if !r.lambda_fallbacks.is_empty() {
            eprintln!(
                "warning: {}: mapped with lambda = {} (a less conformal initial map that squeezes the surface less; \
                 report: lambda_fallbacks; --no-lambda-fallback keeps the first lambda's result)",
                input.display(),
                used.lambda
            );
        }
    }
    if r.collapsed_short_edges > 0 {
        eprintln!(
            "warning: {}: mapped with {} edges shorter than 5% of the mean edge collapsed (the triangulation's needles stalled \
             the transport or left the map folded or poor; a collapsed vertex shares its neighbour's point of the map; \
             report: collapsed_short_edges)",
            input.display(),
            r.collapsed_short_edges
        );
    }
    if r.domain == Domain::Adaptive && r.area_distortion.mean_abs > POOR_AREA_DISTORTION {
        // The options that change an open surface's map are not a closed one's.
        let options = if r.kind == capmesh::mesh::SurfaceKind::OpenDisk { "another --smoothing, --open-lambda or --initial" } else { "--puncture-end bottom or top, another --smoothing or --lambda" };
        eprintln!(
            "warning: {}: mean |d_area| = {:.3} is far from area preserving (fold repair moved a vertex by {:.0}% of the disk radius); \
             try {options}, and check the report's untangle and smoothing_trials",
            input.display(),
            r.area_distortion.mean_abs,
            100.0 * r.untangle.max_displacement
        );
    }
}

/// `Err(Failure::PoorMap)` for a poor map unless `allow` (`--allow-poor-map`).
pub(crate) fn refuse_poor(input: &Path, r: &capmesh::ParamReport, allow: bool) -> Result<(), Failure> {
    if r.quality == capmesh::MapQuality::Poor && !allow {
        return Err(Failure::PoorMap(format!(
            "{}: poor map (mean |d_area| = {:.3}, above {POOR_AREA_DISTORTION}; quality: poor in the report); \
             the outputs are written; pass --allow-poor-map to accept it",
            input.display(),
            r.area_distortion.mean_abs
        )));
    }
    Ok(())
}
