//! The shared open meshes (face, left ventricle, MEG helmet, hand, hippocampus sheet) map onto
//! the adaptive cap with no folded face and mean |d_area| <= 0.12, and the adaptive map's mean
//! |d_angle| is no larger than the hemisphere baseline's (paper Table 1). The transport's
//! finer backtracking of its logarithmic steps saves Newton steps on the hand.

mod common;

use common::data;

use capmesh::param::MASS_TOLERANCE;
use capmesh::cap::Domain;
use capmesh::param::{parameterize, ParamOptions};
use capmesh::io::read_mesh;
use capmesh::progress::NoProgress;

fn check(name: &str) {
    let mesh = read_mesh(&data(name)).unwrap_or_else(|e| panic!("{e}"));
    let adaptive = parameterize(&mesh, &ParamOptions::default(), &NoProgress).unwrap_or_else(|e| panic!("{name}: {e}"));
    let hemi = parameterize(&mesh, &ParamOptions::default().with_domain(Domain::Hemisphere), &NoProgress)
        .unwrap_or_else(|e| panic!("{name} (hemisphere): {e}"));
    let (a, h) = (&adaptive.report, &hemi.report);
    eprintln!(
        "{name}: adaptive Z* {:.3} d_area {:.4} d_angle {:.4} flips {} (folded before repair {} uniform {}) | hemisphere d_area {:.4} d_angle {:.4} | {:.1}s",
        a.z_star.unwrap(),
        a.area_distortion.mean_abs,
        a.angle_distortion.mean_abs,
        a.flipped_faces,
        a.untangle.folded_before,
        a.untangle.uniform_vertices,
        h.area_distortion.mean_abs,
        h.angle_distortion.mean_abs,
        a.seconds
    );
    assert_eq!(a.flipped_faces, 0, "{name}: folded faces");
    // The Newton matrices keep a pattern that covers the flips (omt::newton): most iterations
    // of the radius search reuse a symbolic factorization.
    let iterations = a.newton_iterations + a.coarse_newton_iterations;
    assert!(
        a.transport_symbolic_factorizations < iterations,
        "{name}: {} symbolic factorizations for {} Newton iterations",
        a.transport_symbolic_factorizations,
        iterations
    );
    assert!(a.area_distortion.mean_abs <= 0.12, "{name}: mean |d_area| = {}", a.area_distortion.mean_abs);
    assert!(
        a.angle_distortion.mean_abs <= h.angle_distortion.mean_abs,
        "{name}: adaptive mean |d_angle| {} > hemisphere {}",
        a.angle_distortion.mean_abs,
        h.angle_distortion.mean_abs
    );
}

#[test]
fn face() {
    check("open_face_choi.obj.gz");
}

#[test]
fn left_ventricle() {
    check("open_lv_endo_rabbit_chaste.obj.gz");
}

#[test]
fn meg_helmet() {
    check("open_meg_helmet_babysquid_mne.obj.gz");
}

#[test]
fn hand() {
    check("open_hand_choi.obj.gz");
}

#[test]
fn hippocampus_sheet_with_coincident_vertices() {
    check("open_hippocampus_sheet_hippunfold.obj.gz");
}

/// The logarithmic steps' finer backtracking (`OtOptions::log_step_shrink`, 1/sqrt 2 while
/// longer than 0.2) against halving, on the hand (53k vertices): its cold full-resolution
/// solve accepts longer damped steps and takes fewer Newton steps, to the same map. Both
/// solve to the search's tolerance, so that neither saves its last step by landing just
/// below the default final one (halving did: 7 steps against 6), and factor every step
/// (steps with the last factorization count as steps too).
#[test]
fn finer_backtracking_of_logarithmic_steps_saves_full_resolution_newton_steps() {
    let mesh = read_mesh(&data("open_hand_choi.obj.gz")).unwrap_or_else(|e| panic!("{e}"));
    let mut options = ParamOptions::default();
    options.transport.tolerance = MASS_TOLERANCE;
    options.transport.stale_step_error = 0.0;
    let mut halving = options.clone();
    halving.transport.log_step_shrink = 0.5;
    let (a, b) = (parameterize(&mesh, &options, &NoProgress).unwrap(), parameterize(&mesh, &halving, &NoProgress).unwrap());
    let (ra, rb) = (&a.report, &b.report);
    eprintln!(
        "hand: 1/sqrt 2 {} + {} Newton steps, d_area {:.4}; halving {} + {}, d_area {:.4}",
        ra.newton_iterations, ra.coarse_newton_iterations, ra.area_distortion.mean_abs, rb.newton_iterations, rb.coarse_newton_iterations, rb.area_distortion.mean_abs
    );
    assert!(ra.newton_iterations + 2 <= rb.newton_iterations, "{} against {}", ra.newton_iterations, rb.newton_iterations);
    assert!((ra.z_star.unwrap() - rb.z_star.unwrap()).abs() < 1e-3);
    assert!((ra.area_distortion.mean_abs - rb.area_distortion.mean_abs).abs() < 0.05 * rb.area_distortion.mean_abs);
    assert!((ra.angle_distortion.mean_abs - rb.angle_distortion.mean_abs).abs() < 0.01 * rb.angle_distortion.mean_abs);
    assert_eq!(ra.flipped_faces, 0);
}

/// The report's typed kind and domain serialize as the words the JSON has always carried.
#[test]
fn report_kind_and_domain_serialize_as_strings() {
    use capmesh::mesh::{shapes, SurfaceKind};
    let disk = shapes::spherical_cap(0.2, 8, 24);
    let map = parameterize(&disk, &ParamOptions::default().with_domain(Domain::Radius(1.5)), &NoProgress).unwrap();
    assert_eq!((map.kind, map.report.kind), (SurfaceKind::OpenDisk, SurfaceKind::OpenDisk));
    assert_eq!(map.report.domain, Domain::Radius(1.5));
    let json = serde_json::to_value(&map.report).unwrap();
    assert_eq!(json["kind"], "open disk");
    assert_eq!(json["domain"], "radius=1.5");
    let closed = parameterize(&shapes::icosphere(2), &ParamOptions::default(), &NoProgress).unwrap();
    let json = serde_json::to_value(&closed.report).unwrap();
    assert_eq!((json["kind"].as_str(), json["domain"].as_str()), (Some("closed genus-0"), Some("adaptive")));
}
