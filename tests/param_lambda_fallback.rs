//! Very elongated closed surfaces (`param::lambda_fallback`): the shared bunny stretched along
//! its principal axis. At the paper's `lambda = 0.2` its initial map squeezes the far end
//! below double precision and the transport stalls (10 and 50 times), and at `lambda = 0.5`
//! the 50 times stretched one comes out far from area preserving; the parameterization maps
//! it again with a larger `lambda`, keeps a fold-free map within the poor-map threshold and
//! says what it tried. The unstretched bunny keeps `lambda = 0.2` with nothing tried, and
//! without fallbacks the stalled transport is the error.
//!
//! (Before the closed surfaces' radius search started at its bound, the 50 times stretched
//! bunny's search found an interior minimum of the energy, `r = 8.2`, where `lambda = 0.2`
//! gave a poor map instead of a stalled one; from the bound it finds the lower energy there,
//! 0.9114 against 0.9211, and ends with mean |d_area| 0.137 instead of 0.170.)

mod common;

use capmesh::param::{POOR_MAP_AREA_DISTORTION, RESCUE_FROM_LAMBDA};
use capmesh::param::FlattenReport;
use capmesh::cap::CapMap;
use capmesh::param::{parameterize, ParamOptions};
use capmesh::io::read_mesh;
use capmesh::mesh::TriMesh;
use capmesh::omt::OmtError;
use capmesh::progress::NoProgress;
use capmesh::Error;
use std::path::PathBuf;

/// The bunny with its `x` coordinates (its principal axis once stretched) times `factor`.
fn stretched_bunny(factor: f64) -> TriMesh {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/closed_bunny_npm.obj.gz");
    let mut mesh = read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
    for p in &mut mesh.vertices {
        p[0] *= factor;
    }
    mesh
}

fn used_lambda(map: &CapMap) -> f64 {
    match &map.report.flatten {
        FlattenReport::Closed(r) => r.lambda,
        FlattenReport::Open(_) => panic!("a closed surface reports the closed flattening"),
    }
}

/// Fold-free, within the poor-map threshold, and every attempt listed below the `lambda`
/// kept, in increasing order.
fn check_rescued(map: &CapMap, name: &str) {
    let r = &map.report;
    assert_eq!(r.flipped_faces, 0, "{name}: folded faces");
    assert!(r.area_distortion.mean_abs <= POOR_MAP_AREA_DISTORTION, "{name}: mean |d_area| {}", r.area_distortion.mean_abs);
    let kept = used_lambda(map);
    assert!(!r.lambda_fallbacks.is_empty(), "{name}: nothing tried before lambda {kept}");
    assert_eq!(r.lambda_fallbacks[0].lambda, 0.2, "{name}: the paper's lambda first");
    for pair in r.lambda_fallbacks.windows(2) {
        assert!(pair[0].lambda < pair[1].lambda, "{name}: {:?}", r.lambda_fallbacks);
    }
    assert!(r.lambda_fallbacks.iter().all(|f| f.lambda < kept), "{name}: kept {kept}, tried {:?}", r.lambda_fallbacks);
}

#[test]
fn the_bunny_keeps_the_papers_lambda() {
    let map = parameterize(&stretched_bunny(1.0), &ParamOptions::default(), &NoProgress).expect("bunny");
    assert_eq!(used_lambda(&map), 0.2);
    assert!(map.report.lambda_fallbacks.is_empty(), "{:?}", map.report.lambda_fallbacks);
}

#[test]
fn a_stalled_transport_is_retried_with_a_larger_lambda() {
    let mesh = stretched_bunny(10.0);
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress).unwrap_or_else(|e| panic!("bunny x10: {e}"));
    check_rescued(&map, "bunny x10");
    let first = &map.report.lambda_fallbacks[0];
    assert!(first.mean_abs_area_distortion.is_none() && first.reason.contains("stalled"), "{first:?}");
    // Without fallbacks the first failure is the answer.
    let options = ParamOptions::default().with_closed_lambda_fallbacks(Vec::new());
    match parameterize(&mesh, &options, &NoProgress) {
        Err(Error::Transport(OmtError::Stalled { .. })) => {}
        Err(e) => panic!("bunny x10 without fallbacks: unexpected error {e}"),
        Ok(map) => panic!("bunny x10 mapped at lambda 0.2 (mean |d_area| {}): update the fallback docs", map.report.area_distortion.mean_abs),
    }
}

#[test]
fn a_poor_map_is_replaced_by_a_better_one() {
    let map = parameterize(&stretched_bunny(50.0), &ParamOptions::default(), &NoProgress).unwrap_or_else(|e| panic!("bunny x50: {e}"));
    check_rescued(&map, "bunny x50");
    let poor = map.report.lambda_fallbacks.iter().find(|f| f.mean_abs_area_distortion.is_some()).expect("a lambda gave a map");
    let d = poor.mean_abs_area_distortion.expect("a map");
    assert!(d > POOR_MAP_AREA_DISTORTION && d > 2.0 * map.report.area_distortion.mean_abs, "{poor:?}");
}

/// A long bone (shaft 21 times as long as wide) stalls at every `lambda` with the
/// flattening's 10 stretch-energy iterations; the rescue round maps it again from
/// `RESCUE_FROM_LAMBDA` with more iterations, fold-free (mean |d_area| 0.028, and 0.029 for
/// the same bone written to OBJ), and lists every stalled attempt. Without the round the
/// error names every `lambda` tried. Which `lambda` stalls moves with the last digits of such
/// a mesh (at `half` 8 this one maps at 0.5), so the test pins the bone.
#[test]
fn a_surface_that_stalls_at_every_lambda_is_rescued_by_longer_stretch() {
    let mesh = common::long_bone(8.5, 212, 32);
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress).unwrap_or_else(|e| panic!("long bone: {e}"));
    let r = &map.report;
    assert_eq!(r.flipped_faces, 0);
    assert!(r.area_distortion.mean_abs < 0.1, "mean |d_area| {}", r.area_distortion.mean_abs);
    let tried: Vec<(f64, usize)> = r.lambda_fallbacks.iter().map(|f| (f.lambda, f.stretch_iterations)).collect();
    let flattening = ParamOptions::default().closed.flatten.stretch.max_iterations;
    assert_eq!(tried, [0.2, 0.5, 0.8, 1.0].map(|l| (l, flattening)), "{:?}", r.lambda_fallbacks);
    assert!(r.lambda_fallbacks.iter().all(|f| f.reason.contains("stalled")), "{:?}", r.lambda_fallbacks);
    assert_eq!(used_lambda(&map), RESCUE_FROM_LAMBDA);
    match &r.flatten {
        FlattenReport::Closed(c) => assert!(c.stretch.iterations > flattening, "{:?}", c.stretch),
        FlattenReport::Open(_) => unreachable!(),
    }
    let mut options = ParamOptions::default();
    options.closed = options.closed.with_rescue_stretch_iterations(0);
    match parameterize(&mesh, &options, &NoProgress) {
        // Every remedy the stalled transport's own message names was tried: the error says so.
        Err(e @ Error::Transport(OmtError::EveryLambdaFailed { .. })) => {
            let text = e.to_string();
            assert!(text.contains("(0.2, 0.5, 0.8, 1)") && text.contains("stalled") && text.contains("too elongated") && !text.contains("larger lambda"), "{text}");
        }
        Err(e) => panic!("long bone without the rescue round: unexpected error {e}"),
        Ok(map) => panic!("long bone mapped without the rescue round (mean |d_area| {}): update the test", map.report.area_distortion.mean_abs),
    }
}

