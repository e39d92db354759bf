//! A larger composition factor `lambda` for closed surfaces whose transport runs out of
//! floating-point precision (ours; the paper fixes `lambda = 0.2`, Sec. 3.2.1).
//!
//! With `lambda = 0.2` the initial map of a closed surface is nearly conformal, and a
//! conformal map squeezes the far end of an elongated surface exponentially (a strip of
//! aspect ratio `a` by about `exp(pi a)`). Stretched along their principal axis, the shared
//! bunny from 10 times and the closed hippocampus from 20 times had hundreds of vertices
//! mapped within `1e-12` of each other; the power diagram's weights then need differences
//! below the resolution of `f64`, the flips of every Newton step fail however short the step,
//! and the transport stops with [`OmtError::Stalled`] at a mass error near `1e-4` (the bunny
//! stretched 10 times maps from `lambda` 0.5, 20 times from 0.8; open surfaces, whose whole
//! boundary lies on the circle, map up to x20 at their default `lambda`). Stretched 50 times,
//! the bunny mapped, but with a mean `|d_area|` of 2.48 after a fold repair that moved
//! vertices across the disk. A
//! larger `lambda` keeps more of the stretch-energy map, which spreads the area instead of
//! squeezing it, so [`super::parameterize()`] maps a closed surface again with the next value
//! of [`super::ClosedOptions::lambda_fallbacks`] when its transport stalls or its map is poor
//! (mean `|d_area|` above [`POOR_MAP_AREA_DISTORTION`]), keeps the first map that is not
//! poor, else the least distorted, and lists the other attempts in
//! [`super::ParamReport::lambda_fallbacks`]. Meshes that map well at the first `lambda` (all
//! the shared ones) pay nothing.
//!
//! A long bone of a femur's proportions (shaft 20 times as long as wide) stalls at every
//! `lambda`: its 10 stretch-energy iterations leave the energy 3-10 times its minimum and the
//! far end still squeezed. When no attempt gave a map at all, the fallbacks from
//! [`RESCUE_FROM_LAMBDA`] are tried once more with
//! [`super::ClosedOptions::rescue_stretch_iterations`] iterations (the rescue round): only
//! surfaces that would otherwise be refused pay for it, and a surface with a poor map keeps
//! it (more iterations there once turned a poor map of the bunny stretched 300 times into a
//! stalled transport).

use super::options::ParamOptions;
use crate::error::Error;
use crate::omt::OmtError;

/// Mean `|d_area|` above which a closed surface's map counts as poor and the next `lambda`
/// is tried (the command line warns above it too). The shared meshes map at 0.008-0.13; the
/// bunny stretched 50 times along its axis mapped at 2.48 with `lambda` 0.2, 1.94 with 0.5,
/// stalled at 0.8 and mapped at 0.17 with 1.
pub const POOR_MAP_AREA_DISTORTION: f64 = 0.3;

/// Whether `error` is the transport losing precision on a too compressive initial map (the
/// failure a larger `lambda` can cure), as opposed to bad input or a cancellation.
pub(super) fn is_precision_failure(error: &Error) -> bool {
    matches!(error, Error::Transport(OmtError::Stalled { .. } | OmtError::NotConverged { .. } | OmtError::Triangulation(_) | OmtError::EveryLambdaFailed { .. }))
}

/// The next `lambda` to try after `failed`, if any.
pub(super) fn next_lambda(options: &ParamOptions, failed: f64) -> Option<f64> {
    options.closed.lambda_fallbacks.iter().copied().filter(|&l| l > failed && l <= 1.0).reduce(f64::min)
}

/// The smallest `lambda` of the rescue round: when the transport stalled at every `lambda`,
/// the fallbacks from this one are tried again with
/// [`super::ClosedOptions::rescue_stretch_iterations`] stretch-energy iterations. Below it
/// the conformal part of the composition squeezes the far end whatever the stretch map
/// spreads. An analytic long bone of revolution (tests/common `long_bone` at half length 8,
/// 200 rings of 24 vertices, written to OBJ) mapped at 0.8 with 40 iterations (mean |d_area|
/// 0.029), at 1 with 20 (0.053).
pub const RESCUE_FROM_LAMBDA: f64 = 0.8;

/// The error of a closed surface whose every attempt in `attempts` failed (the last with
/// `last`): [`OmtError::EveryLambdaFailed`] naming what was tried when there was more than one
/// attempt, else `last` itself (no fallbacks: its message names the remedy).
pub(super) fn every_lambda_failed(attempts: &[super::LambdaFallback], last: Error) -> Error {
    let Error::Transport(omt) = &last else { return last };
    if attempts.len() < 2 {
        return last;
    }
    let first = attempts[0].stretch_iterations;
    let tried = attempts.iter().map(|a| a.describe(first)).collect::<Vec<_>>().join(", ");
    Error::Transport(OmtError::EveryLambdaFailed { tried, last: omt.outcome() })
}

/// The first `lambda` of the rescue round: the smallest of the fallbacks and the asked
/// `lambda` that is at least both [`RESCUE_FROM_LAMBDA`] and the asked one, or `None` when
/// there is no such round (no fallbacks, or no more iterations than the flattening makes
/// anyway).
pub(super) fn rescue_lambda(options: &ParamOptions) -> Option<f64> {
    let asked = options.closed.flatten.lambda;
    if options.closed.lambda_fallbacks.is_empty() || options.closed.rescue_stretch_iterations <= options.closed.flatten.stretch.max_iterations {
        return None;
    }
    let from = RESCUE_FROM_LAMBDA.max(asked);
    options.closed.lambda_fallbacks.iter().copied().chain([asked]).filter(|&l| (from..=1.0).contains(&l)).reduce(f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::omt::triangulation::TriangulationError;

    #[test]
    fn fallbacks_go_up_in_order_and_stop_at_one() {
        let mut options = ParamOptions::default();
        assert_eq!(next_lambda(&options, 0.2), Some(0.5));
        assert_eq!(next_lambda(&options, 0.5), Some(0.8));
        assert_eq!(next_lambda(&options, 0.8), Some(1.0));
        assert_eq!(next_lambda(&options, 1.0), None);
        options.closed.lambda_fallbacks = vec![1.5, 0.9, 0.3];
        assert_eq!(next_lambda(&options, 0.2), Some(0.3));
        assert_eq!(next_lambda(&options, 0.3), Some(0.9));
        assert_eq!(next_lambda(&options, 0.9), None, "values above 1 are not lambdas");
        options.closed.lambda_fallbacks.clear();
        assert_eq!(next_lambda(&options, 0.2), None);
    }

    #[test]
    fn the_rescue_round_starts_at_0_8_or_the_asked_lambda() {
        let mut options = ParamOptions::default();
        assert_eq!(rescue_lambda(&options), Some(RESCUE_FROM_LAMBDA));
        options.closed.flatten.lambda = 0.9;
        assert_eq!(rescue_lambda(&options), Some(0.9), "not below the asked lambda");
        options.closed.rescue_stretch_iterations = options.closed.flatten.stretch.max_iterations;
        assert_eq!(rescue_lambda(&options), None, "no more iterations: no round");
        let mut options = ParamOptions::default();
        options.closed.lambda_fallbacks.clear();
        assert_eq!(rescue_lambda(&options), None, "--no-lambda-fallback: no round");
    }

    #[test]
    fn only_transport_failures_call_for_another_lambda() {
        assert!(is_precision_failure(&Error::Transport(OmtError::Stalled { iteration: 0, error: 1e-4 })));
        assert!(is_precision_failure(&Error::Transport(OmtError::Triangulation(TriangulationError::CoincidentSites { count: 2 }))));
        assert!(!is_precision_failure(&Error::Transport(OmtError::Invalid("x".into()))));
        assert!(!is_precision_failure(&Error::InvalidOption("x".into())));
    }
}
