//! `capmesh::harmonics::analyze` as a library call on a real mesh: progress with
//! `Stage::Harmonics` ending at 1, cancellation, harmonics errors reaching `capmesh::Error`
//! before the parameterization runs, and vertices used by no face left out of the fit.

use capmesh::harmonics::{analyze, analyze_map, HarmonicsError, HarmonicsOptions};
use capmesh::progress::Stage;
use capmesh::{Error, NoProgress, TriMesh};
use std::ops::ControlFlow;
use std::path::Path;
use std::sync::Mutex;

fn helmet() -> TriMesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/open_meg_helmet_babysquid_mne.obj.gz");
    capmesh::io::read_mesh(&path).unwrap()
}

#[test]
fn analyze_reports_harmonics_progress_and_can_be_cancelled() {
    let mesh = helmet();
    let seen = Mutex::new(Vec::new());
    let record = |stage: Stage, fraction: f64, _: &str| {
        seen.lock().unwrap().push((stage, fraction));
        ControlFlow::Continue(())
    };
    let options = HarmonicsOptions::default().with_order(6);
    assert_eq!(HarmonicsOptions::default().order, 10);
    let out = analyze(&mesh, &options, &record).unwrap();
    let seen = seen.into_inner().unwrap();
    let harmonics: Vec<f64> = seen.iter().filter(|(s, _)| *s == Stage::Harmonics).map(|&(_, f)| f).collect();
    assert!(seen.iter().any(|(s, _)| *s == Stage::RadiusSearch), "the parameterization reports too");
    assert!(harmonics.windows(2).all(|w| w[0] <= w[1]) && harmonics.last() == Some(&1.0), "{harmonics:?}");
    assert_eq!(seen.last().map(|s| s.0), Some(Stage::Harmonics));

    let r = &out.report;
    assert_eq!((r.order, r.vertices, r.fitted_vertices, r.basis_functions), (6, 2171, 2171, 49));
    assert_eq!(out.fit.order, 6);
    assert_eq!(out.fit.coefficients.len(), 49);
    assert_eq!(Some(r.z_star), r.param.z_star);
    assert_eq!(out.reconstructed.faces, mesh.faces);
    assert_eq!(r.errors_by_order.len(), 7);
    let mean: Vec<f64> = r.errors_by_order.iter().map(|e| e.mean_relative).collect();
    assert!(mean.windows(2).all(|w| w[1] < w[0]), "{mean:?}");
    assert!(r.aspect_ratio >= 1.0 && r.ellipsoid_aspect_ratio >= 1.0);
    assert!((r.aspect_ratio - r.singular_values[0] / r.singular_values[2]).abs() < 1e-12 * r.aspect_ratio);
    assert!(r.seconds >= r.fit_seconds && r.seconds >= r.param.seconds);
    let json = serde_json::to_value(r).unwrap();
    for key in ["z_star", "order", "vertices", "errors_by_order", "aspect_ratio", "seconds", "param"] {
        assert!(json.get(key).is_some(), "report lacks {key}");
    }

    let cancel = |stage: Stage, _: f64, _: &str| {
        if stage == Stage::Harmonics {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    assert!(matches!(analyze(&mesh, &options, &cancel), Err(Error::Cancelled(_))));
}

#[test]
fn harmonics_errors_reach_the_crate_error_before_parameterizing() {
    let mesh = helmet();
    let started = Mutex::new(false);
    let watch = |_: Stage, _: f64, _: &str| {
        *started.lock().unwrap() = true;
        ControlFlow::Continue(())
    };
    let err = analyze(&mesh, &HarmonicsOptions::default().with_order(46), &watch).unwrap_err();
    assert!(
        matches!(err, Error::Harmonics(HarmonicsError::TooFewPoints { points: 2171, basis: 2209, order: 46 })),
        "{err}"
    );
    let err = analyze(&mesh, &HarmonicsOptions::default().with_order(501), &watch).unwrap_err();
    assert!(matches!(err, Error::Harmonics(HarmonicsError::OrderTooLarge { order: 501, .. })), "{err}");
    assert!(!*started.lock().unwrap(), "the parameterization ran for an impossible request");
}

#[test]
fn unreferenced_vertices_keep_their_position() {
    let mut mesh = helmet();
    let stray = [1.0e3, -2.0e3, 5.0e2];
    mesh.vertices.push(stray);
    let map = capmesh::param::parameterize(&mesh, &Default::default(), &NoProgress).unwrap();
    let out = analyze_map(&mesh, &map, &HarmonicsOptions::default().with_order(3), &NoProgress).unwrap();
    assert_eq!((out.report.vertices, out.report.fitted_vertices), (2172, 2171));
    assert_eq!(out.reconstructed.vertices[2171], stray);
    // The fit ignores the stray vertex: the same errors as without it.
    let clean = analyze_map(&helmet(), &map_without_last(&map), &HarmonicsOptions::default().with_order(3), &NoProgress).unwrap();
    for (a, b) in out.report.errors_by_order.iter().zip(&clean.report.errors_by_order) {
        assert!((a.mean_distance - b.mean_distance).abs() <= 1e-12 * b.mean_distance, "{a:?} vs {b:?}");
    }
    // A map of another mesh is refused.
    let err = analyze_map(&helmet(), &map, &HarmonicsOptions::default().with_order(3), &NoProgress).unwrap_err();
    assert!(err.to_string().contains("2172 cap positions for a mesh of 2171 vertices"), "{err}");
}

fn map_without_last(map: &capmesh::CapMap) -> capmesh::CapMap {
    let mut m = map.clone();
    m.cap.pop();
    m.plane.pop();
    m
}

#[test]
fn errors_from_the_design_matrix_equal_the_errors_of_a_fresh_evaluation() {
    // fit_with_errors_in measures the errors and the reconstruction from the fit's own design
    // matrix; order_errors and reconstruct evaluate the basis again. Same numbers, both bases.
    use capmesh::harmonics::{fit_all_orders_in, fit_with_errors_in, order_errors, BasisKind, CapBoundary};
    let mesh = helmet();
    let map = capmesh::parameterize(&mesh, &capmesh::ParamOptions::default(), &NoProgress).unwrap();
    let z_star = map.report.z_star.unwrap();
    for kind in [BasisKind::Adaptive, BasisKind::SphericalCap(CapBoundary::Neumann)] {
        let together = fit_with_errors_in(kind, &map.cap, &mesh.vertices, z_star, 8).unwrap();
        let fits = fit_all_orders_in(kind, &map.cap, &mesh.vertices, z_star, 8).unwrap();
        assert_eq!(together.fits.len(), fits.len());
        for (a, b) in together.fits.iter().zip(&fits) {
            assert_eq!((a.basis, a.z_star, a.order, a.coefficients.len()), (b.basis, b.z_star, b.order, b.coefficients.len()));
            let worst = a.coefficients.iter().zip(&b.coefficients).flat_map(|(x, y)| (0..3).map(move |d| (x[d] - y[d]).abs())).fold(0.0f64, f64::max);
            assert!(worst < 1e-9, "{kind:?} order {}: coefficients differ by {worst}", a.order);
        }
        let errors = order_errors(&fits, &map.cap, &mesh.vertices).unwrap();
        assert_eq!(together.errors.len(), 9);
        for (a, b) in together.errors.iter().zip(&errors) {
            assert_eq!(a.order, b.order);
            assert!((a.mean_relative - b.mean_relative).abs() <= 1e-9 * b.mean_relative, "{kind:?} {a:?} {b:?}");
            assert!((a.max_relative - b.max_relative).abs() <= 1e-9 * b.max_relative, "{kind:?} {a:?} {b:?}");
        }
        let again = fits[8].reconstruct(&map.cap, 8).unwrap();
        let worst = together.reconstructed.iter().zip(&again).flat_map(|(a, b)| (0..3).map(move |d| (a[d] - b[d]).abs())).fold(0.0f64, f64::max);
        assert!(worst < 1e-9, "{kind:?}: reconstructions differ by {worst}");
    }
}
