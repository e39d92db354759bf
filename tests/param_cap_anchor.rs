//! Analytic anchor (design notes, "Sanity anchor"): a mesh sampled from the spherical cap
//! `Z >= z0` must come back as that cap, with `Z*` equal to its own height and near-zero
//! area distortion.

use capmesh::cap::Domain;
use capmesh::param::{parameterize, ParamOptions};
use capmesh::mesh::shapes::{spherical_cap, spherical_cap_sectors};
use capmesh::progress::NoProgress;

fn check(z0: f64) {
    let rings = 24;
    let mesh = spherical_cap(z0, rings, spherical_cap_sectors(z0, rings));
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress).expect("cap maps");
    let r = &map.report;
    let z = r.z_star.expect("spherical domain has Z*");
    eprintln!("z0 {z0}: Z* {z:.4} d_area {:.4} d_angle {:.4} evals {}", r.area_distortion.mean_abs, r.angle_distortion.mean_abs, r.radius_curve.len());
    assert!((z - z0).abs() < 0.02, "z0 = {z0}: Z* = {z}");
    assert!(r.area_distortion.mean_abs < 0.02, "z0 = {z0}: mean |d_area| = {}", r.area_distortion.mean_abs);
    assert_eq!(r.flipped_faces, 0);
    // Every cap vertex is on the unit sphere above Z*.
    for p in &map.cap {
        assert!(((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < 1e-9);
        assert!(p[2] >= z - 1e-9);
    }
}

#[test]
fn small_cap_comes_back() {
    check(0.6);
}

#[test]
fn hemisphere_comes_back() {
    check(0.0);
}

#[test]
fn large_cap_comes_back() {
    check(-0.5);
}

#[test]
fn fixed_domains_have_their_z_star() {
    let mesh = spherical_cap(0.2, 12, spherical_cap_sectors(0.2, 12));
    for (domain, z) in [(Domain::Hemisphere, 0.0), (Domain::Radius(0.5), 0.6), (Domain::Sphere, -0.995)] {
        let map = parameterize(&mesh, &ParamOptions::default().with_domain(domain), &NoProgress).unwrap();
        let zs = map.report.z_star.unwrap();
        assert!((zs - z).abs() < 1e-3, "{domain}: Z* = {zs}");
    }
    let disk = parameterize(&mesh, &ParamOptions::default().with_domain(Domain::Disk), &NoProgress).unwrap();
    assert!(disk.report.z_star.is_none());
    assert!(disk.cap.iter().all(|p| p[2] == 0.0 && p[0] * p[0] + p[1] * p[1] <= 1.0 + 1e-9));
}
