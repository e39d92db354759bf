//! The radius search on a coarse level (omt::coarse_level) finds a cap as good as the search
//! at full resolution, with a fraction of the full-resolution Newton iterations.

mod common;

use common::data;

use capmesh::param::{parameterize, ParamOptions};
use capmesh::io::read_mesh;
use capmesh::progress::NoProgress;

/// Open surfaces' full-resolution search takes a dozen solves; the coarse one must do with
/// under half their Newton iterations. A closed surface's search starts at its bound and ends
/// after two solves (`brent::minimize_from_lower_bound`), so at full resolution it costs two
/// solves to the search's tolerance against one to the final map's after a coarse search:
/// there the coarse search must still save at least a quarter of them.
fn compare(name: &str, z_tolerance: f64) {
    let mesh = read_mesh(&data(name)).unwrap_or_else(|e| panic!("{e}"));
    let full_options = ParamOptions::default().with_search_sites(0);
    let full = parameterize(&mesh, &full_options, &NoProgress).unwrap_or_else(|e| panic!("{name}: {e}")).report;
    let coarse = parameterize(&mesh, &ParamOptions::default(), &NoProgress).unwrap_or_else(|e| panic!("{name}: {e}")).report;
    eprintln!(
        "{name}: full Z* {:.4} d_area {:.4} d_angle {:.4} newton {} {:.1}s | coarse ({:?} sites) Z* {:.4} d_area {:.4} d_angle {:.4} newton {} + {} coarse {:.1}s",
        full.z_star.unwrap(),
        full.area_distortion.mean_abs,
        full.angle_distortion.mean_abs,
        full.newton_iterations,
        full.seconds,
        coarse.search_sites,
        coarse.z_star.unwrap(),
        coarse.area_distortion.mean_abs,
        coarse.angle_distortion.mean_abs,
        coarse.newton_iterations,
        coarse.coarse_newton_iterations,
        coarse.seconds
    );
    assert_eq!(full.search_sites, None);
    let sites = coarse.search_sites.unwrap_or_else(|| panic!("{name}: no coarse search"));
    assert!(sites <= capmesh::param::DEFAULT_SEARCH_SITES && 2 * sites < mesh.n_vertices());
    assert_eq!(coarse.transport_solves, 1, "{name}: only r* is solved at full resolution");
    let closed = name.starts_with("closed_");
    let most = if closed { 0.75 } else { 0.5 };
    assert!((coarse.newton_iterations as f64) < most * full.newton_iterations as f64, "{name}: {} vs {}", coarse.newton_iterations, full.newton_iterations);
    assert!((coarse.z_star.unwrap() - full.z_star.unwrap()).abs() < z_tolerance, "{name}: Z*");
    assert_eq!(coarse.flipped_faces, 0);
    assert!(coarse.angle_distortion.mean_abs < 1.02 * full.angle_distortion.mean_abs, "{name}: d_angle");
    assert!(coarse.area_distortion.mean_abs < 1.1 * full.area_distortion.mean_abs, "{name}: d_area");
}

#[test]
fn face_open() {
    // The face's energy is flat around its minimum (Z* -0.02 and -0.08 differ by 0.6%).
    compare("open_face_choi.obj.gz", 0.1);
}

#[test]
fn brain12k_closed() {
    compare("closed_brain12k_choi.obj.gz", 0.01);
}

#[test]
fn hippocampus_closed() {
    compare("closed_hippocampus_choi.obj.gz", 0.01);
}

#[test]
fn left_ventricle_open() {
    // 4.2k vertices: the smallest open mesh the default coarse search applies to.
    compare("open_lv_endo_rabbit_chaste.obj.gz", 0.1);
}

#[test]
fn bird_skull_closed() {
    // 2.1k vertices: closed surfaces search on a quarter of their vertices at most.
    compare("closed_bird_skull_CPallidusA_choi.obj.gz", 0.01);
}

#[test]
fn bunny_closed() {
    compare("closed_bunny_npm.obj.gz", 0.01);
}

#[test]
fn coarse_level_size_follows_the_mesh_size() {
    use capmesh::param::{search_level_sites, DEFAULT_SEARCH_SITES, MIN_SEARCH_SITES};
    let d = DEFAULT_SEARCH_SITES;
    for closed in [false, true] {
        assert_eq!(search_level_sites(53_054, d, closed), Some(53_054 / 16));
        assert_eq!(search_level_sites(12_502, d, closed), Some(d));
        assert_eq!(search_level_sites(53_054, 0, closed), None);
        // An explicit small request is honoured down to n / 16.
        assert_eq!(search_level_sites(2_000, 100, closed), Some(125));
    }
    // Open surfaces: only meshes of more than twice the requested sites.
    assert_eq!(search_level_sites(6_002, d, false), Some(d));
    assert_eq!(search_level_sites(2_105, d, false), None);
    // Closed ones: a quarter of the vertices at most, from 2 * MIN_SEARCH_SITES vertices.
    assert_eq!(search_level_sites(6_002, d, true), Some(1_500));
    assert_eq!(search_level_sites(2_105, d, true), Some(526));
    assert_eq!(search_level_sites(600, d, true), Some(MIN_SEARCH_SITES));
    assert_eq!(search_level_sites(500, d, true), None);
}

/// After a coarse search the map at `r*` is solved to `TRANSPORT_TOLERANCE` (1e-3), not to
/// the search's `MASS_TOLERANCE` (1e-5): on the face the last full-resolution Newton step is
/// saved, the search and its `Z*` are the same, and the distortions after the refinement stay
/// within 1%.
#[test]
fn final_map_at_the_transport_tolerance_saves_a_newton_step_at_the_same_quality() {
    use capmesh::param::{MASS_TOLERANCE, TRANSPORT_TOLERANCE};
    let mesh = read_mesh(&data("open_face_choi.obj.gz")).unwrap_or_else(|e| panic!("{e}"));
    let loose = ParamOptions::default();
    assert_eq!(loose.transport.tolerance, TRANSPORT_TOLERANCE);
    assert_eq!(loose.search.tolerance, MASS_TOLERANCE);
    let mut tight = loose.clone();
    tight.transport.tolerance = MASS_TOLERANCE;
    let a = parameterize(&mesh, &loose, &NoProgress).unwrap_or_else(|e| panic!("{e}")).report;
    let b = parameterize(&mesh, &tight, &NoProgress).unwrap_or_else(|e| panic!("{e}")).report;
    eprintln!(
        "face: final tolerance 1e-3: {} Newton steps, d_area {:.5}, d_angle {:.4}; 1e-5: {}, {:.5}, {:.4}",
        a.newton_iterations, a.area_distortion.mean_abs, a.angle_distortion.mean_abs, b.newton_iterations, b.area_distortion.mean_abs, b.angle_distortion.mean_abs
    );
    assert!(a.search_sites.is_some());
    assert_eq!(a.z_star, b.z_star);
    assert_eq!(a.coarse_newton_iterations, b.coarse_newton_iterations);
    assert!(a.newton_iterations < b.newton_iterations, "{} against {}", a.newton_iterations, b.newton_iterations);
    assert!((a.area_distortion.mean_abs - b.area_distortion.mean_abs).abs() < 0.01 * b.area_distortion.mean_abs);
    assert!((a.angle_distortion.mean_abs - b.angle_distortion.mean_abs).abs() < 0.01 * b.angle_distortion.mean_abs);
    assert_eq!(a.flipped_faces, 0);
}
