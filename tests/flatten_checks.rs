//! Quantities computed two ways: the stretch energy's gradient against finite differences,
//! the linear Beltrami solver against a map with a known coefficient, and the disk conformal
//! map's conformality on an analytic shape; the over-relaxed stretch-energy iteration against
//! the plain one on a real mesh.

use capmesh::flatten::beltrami::{beltrami_coefficients, linear_beltrami_solver};
use capmesh::flatten::stretch_energy::{stretch_energy, stretch_energy_map, stretch_gradient, StretchOptions};
use capmesh::io::read_mesh;
use capmesh::mesh::geometry::folded_faces;
use capmesh::flatten::{disk_conformal_map, DiskConformalOptions};
use capmesh::mesh::shapes::{grid_disk, spherical_cap, spherical_cap_sectors};
use capmesh::mesh::{validate, TriMesh};
use capmesh::metrics::{beltrami_abs, Stats};

/// A smooth non-conformal planar map of the unit disk.
fn warp(p: [f64; 3]) -> [f64; 2] {
    let (x, y) = (p[0], p[1]);
    [x + 0.25 * x * y + 0.1 * y * y, 0.8 * y + 0.2 * x * x - 0.05 * x * y]
}

#[test]
fn stretch_gradient_matches_finite_differences() {
    let mesh = grid_disk(6);
    let f: Vec<[f64; 2]> = mesh.vertices.iter().map(|&p| warp(p)).collect();
    let g = stretch_gradient(&mesh.vertices, &mesh.faces, &f);
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    let scale = g.iter().map(|v| v[0].abs().max(v[1].abs())).fold(0.0, f64::max);
    for v in (0..f.len()).step_by(3) {
        for k in 0..2 {
            let mut fp = f.clone();
            fp[v][k] += h;
            let mut fm = f.clone();
            fm[v][k] -= h;
            let fd = (stretch_energy(&mesh.vertices, &mesh.faces, &fp) - stretch_energy(&mesh.vertices, &mesh.faces, &fm)) / (2.0 * h);
            worst = worst.max((fd - g[v][k]).abs());
        }
    }
    assert!(scale > 0.0);
    assert!(worst < 1e-6 * scale.max(1.0), "worst {worst:.3e} vs scale {scale:.3e}");
}

#[test]
fn beltrami_solver_reproduces_a_map_from_its_own_coefficient() {
    let mesh = grid_disk(8);
    let (_, topo) = validate(&mesh).unwrap();
    let target: Vec<[f64; 2]> = mesh.vertices.iter().map(|&p| warp(p)).collect();
    let mu = beltrami_coefficients(&mesh.vertices, &mesh.faces, &target);
    assert!(mu.iter().any(|m| m[0].hypot(m[1]) > 0.05), "test map should not be conformal");
    let fixed: Vec<(u32, [f64; 2])> = topo.boundary_loops[0].iter().map(|&b| (b, target[b as usize])).collect();
    let solved = linear_beltrami_solver(&mesh.vertices, &mesh.faces, &mu, &fixed).unwrap();
    let err = solved
        .iter()
        .zip(&target)
        .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
        .fold(0.0, f64::max);
    assert!(err < 1e-9, "max error {err:.3e}");
}

#[test]
fn disk_conformal_map_of_a_cap_is_conformal() {
    // Stereographic projection maps the cap conformally onto a disk, so the discrete map
    // must have small |mu| everywhere (up to discretization).
    let mesh: TriMesh = spherical_cap(0.3, 20, spherical_cap_sectors(0.3, 20));
    let (_, topo) = validate(&mesh).unwrap();
    let (uv, report) = disk_conformal_map(&mesh.vertices, &mesh.faces, &topo.boundary_loops[0], &DiskConformalOptions::default()).unwrap();
    assert_eq!(report.flipped_faces, 0);
    let mu = Stats::of(mesh.faces.iter().map(|f| {
        let [a, b, c] = f.map(|v| v as usize);
        beltrami_abs([mesh.vertices[a], mesh.vertices[b], mesh.vertices[c]], [uv[a], uv[b], uv[c]])
    }));
    assert!(mu.mean_abs < 0.02 && mu.max_abs < 0.1, "{mu:?}");
    // The boundary lies on the unit circle.
    for &b in &topo.boundary_loops[0] {
        let p = uv[b as usize];
        assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-12);
    }
}

#[test]
fn over_relaxed_stretch_iteration_needs_fewer_iterations() {
    // The face (17k vertices), boundary held on the circle of its disk conformal map.
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/open_face_choi.obj.gz");
    let mesh = read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
    let (_, topo) = validate(&mesh).unwrap();
    let (uv, _) = disk_conformal_map(&mesh.vertices, &mesh.faces, &topo.boundary_loops[0], &DiskConformalOptions::default()).unwrap();
    let fixed: Vec<(u32, [f64; 2])> = topo.boundary_loops[0].iter().map(|&b| (b, uv[b as usize])).collect();
    let run = |over_relaxation: f64, max_iterations: usize| {
        let options = StretchOptions::default().with_max_iterations(max_iterations).with_tolerance(0.0).with_over_relaxation(over_relaxation);
        stretch_energy_map(&mesh.vertices, &mesh.faces, &fixed, &uv, &options).unwrap()
    };
    // The over-relaxed iteration must get lower in 10 iterations than the plain one in 15.
    let (plain, plain_report) = run(1.0, 15);
    let (over, over_report) = run(StretchOptions::default().over_relaxation, 10);
    eprintln!("plain {plain_report:?}\nover-relaxed {over_report:?}");
    assert_eq!(plain_report.over_relaxed, 0);
    assert!(over_report.over_relaxed > 0, "{over_report:?}");
    assert!(folded_faces(&over, &mesh.faces).len() <= folded_faces(&plain, &mesh.faces).len());
    assert_eq!(plain_report.initial_energy_ratio, over_report.initial_energy_ratio);
    assert!(
        over_report.final_energy_ratio < plain_report.final_energy_ratio,
        "over-relaxed {} vs plain {}",
        over_report.final_energy_ratio,
        plain_report.final_energy_ratio
    );
    assert!(stretch_energy(&mesh.vertices, &mesh.faces, &over) < stretch_energy(&mesh.vertices, &mesh.faces, &plain));
}

#[test]
fn stretch_steps_with_a_reused_factorization_reach_the_same_energy() {
    // The hippocampal sheet (7k vertices), boundary on the circle by arc length as in the
    // open surfaces' composite map, from the harmonic map: every iteration factoring its own
    // matrix against only the first 3 (the later steps solve with the third's factorization).
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/open_hippocampus_sheet_hippunfold.obj.gz");
    let raw = read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
    // Welded as the pipeline does (coincident vertices make zero-area faces).
    let mesh = capmesh::mesh::repair::weld_coincident(&raw, 1e-9 * raw.bounding_box_diagonal()).mesh;
    let (_, topo) = validate(&mesh).unwrap();
    let fixed = capmesh::flatten::closed::on_circle_by_arc_length(&mesh.vertices, &topo.boundary_loops[0]);
    let weights = capmesh::linalg::cotangent_weights(&mesh.vertices, &mesh.faces);
    let (initial, _) = capmesh::flatten::harmonic::harmonic_extension(mesh.vertices.len(), &mesh.faces, &weights, &fixed).unwrap();
    let run = |factored_iterations: usize| {
        let options = StretchOptions::default().with_tolerance(0.0).with_factored_iterations(factored_iterations).with_refactor_period(0);
        stretch_energy_map(&mesh.vertices, &mesh.faces, &fixed, &initial, &options).unwrap()
    };
    let (every, every_report) = run(usize::MAX);
    let (reused, reused_report) = run(3);
    eprintln!("every {every_report:?}\nreused {reused_report:?}");
    assert_eq!(every_report.reused_factorizations, 0);
    assert!(reused_report.reused_factorizations >= 4, "{reused_report:?}");
    assert_eq!(every_report.iterations, reused_report.iterations);
    // Both remove most of the start's excess over the equiareal minimum (ratio 1), and end
    // within 0.1% of each other.
    for r in [&every_report, &reused_report] {
        assert!(r.final_energy_ratio - 1.0 < 0.05 * (r.initial_energy_ratio - 1.0), "{r:?}");
    }
    let (a, b) = (stretch_energy(&mesh.vertices, &mesh.faces, &every), stretch_energy(&mesh.vertices, &mesh.faces, &reused));
    assert!((a - b).abs() < 1e-3 * a, "every iteration factored {a}, reused {b}");
    let folds = (folded_faces(&every, &mesh.faces).len(), folded_faces(&reused, &mesh.faces).len());
    eprintln!("folded faces: every {} reused {}", folds.0, folds.1);
    assert!(folds.1 <= folds.0, "folded faces: every iteration factored {}, reused {}", folds.0, folds.1);
}
