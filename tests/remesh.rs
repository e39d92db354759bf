//! Remeshing through the cap (paper Sec. 4.2) on every shared mesh: the output is manifold
//! with the input's topology (an open disk, or a closed genus-0 surface whose bottom is
//! pulled back onto the punctured quad), the uniform grid hits the requested face count
//! within 10%, its face-area deviation is below the input's, and no face has zero area.

use capmesh::io::read_mesh;
use capmesh::mesh::{validate, SurfaceKind};
use capmesh::metrics::face_area_deviation;
use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, Optimize, Placement, RemeshOptions};

mod common;

/// `max_relative_to_input`: the largest accepted ratio of the output's `d_face_relative` to
/// the input's (below 1 means more uniform than the input).
fn check(name: &str, max_relative_to_input: f64) {
    let mesh = read_mesh(&common::data(name)).unwrap();
    let target = 5000;
    let (out, rep) = remesh(&mesh, &RemeshOptions::default().with_grid(CapGrid::Uniform { faces: target }), &NoProgress)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let (input_kind, _) = validate(&mesh).unwrap();
    let (kind, _) = validate(&out).unwrap_or_else(|e| panic!("{name}: remeshed mesh invalid: {e}"));
    assert_eq!(kind, input_kind, "{name}");
    let q = &rep.quality;
    assert!((q.faces as f64 - target as f64).abs() <= 0.1 * target as f64, "{name}: {} faces", q.faces);
    let (_, input_rel) = face_area_deviation(&mesh);
    eprintln!(
        "{name}: d_face_rel {:.4} (input {:.4}), d_surface_sampled_rel {:.2e}, min angle {:.2} deg",
        q.d_face_relative, input_rel, q.d_surface_sampled_relative, q.min_angle_deg
    );
    assert!(
        q.d_face_relative < max_relative_to_input * input_rel,
        "{name}: d_face_relative {} vs input {}",
        q.d_face_relative,
        input_rel
    );
    // The default's polish equalizes the areas itself: no pure-area sweep after it
    // ([`equalization_runs_on_closed_surfaces`] checks the sweeps of `--optimize area`).
    assert_eq!(rep.area_equalization.sweeps, 0, "{name}");
    // No degenerate output face (see `RemeshMetrics::zero_area_faces` for where they arise).
    assert_eq!(q.zero_area_faces, 0, "{name}: zero-area faces in the remesh");
    // The vertices are fitted off the surface (`remesh::fit`; on it with
    // `Placement::OnSurface`, [`every_input_kind_remeshes`]) by a fraction of an edge, and the
    // fit lowered its own measure.
    assert!(rep.fit.fitted && rep.fit.rms_after < rep.fit.rms_before, "{name}: {:?}", rep.fit);
    let edges: Vec<f64> = out.faces.iter().flat_map(|f| (0..3).map(move |k| (f[k], f[(k + 1) % 3]))).map(|(a, b)| {
        let (p, q) = (out.vertices[a as usize], out.vertices[b as usize]);
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    }).collect();
    let mean_edge = edges.iter().sum::<f64>() / edges.len() as f64;
    assert!(q.d_surface_vertex > 0.0 && q.d_surface_vertex <= 0.3 * mean_edge, "{name}: vertices {} off the surface, mean edge {mean_edge}", q.d_surface_vertex);
    assert!(q.d_surface_sampled_relative < 0.01, "{name}: {}", q.d_surface_sampled_relative);
    // The input's crossing faces, counted while it is mapped, are the input's.
    assert_eq!(q.self_intersecting_faces_input, capmesh::metrics::count_self_intersecting_faces(&mesh), "{name}");
}

#[test]
fn face() {
    check("open_face_choi.obj.gz", 1.0);
}

#[test]
fn left_ventricle() {
    check("open_lv_endo_rabbit_chaste.obj.gz", 1.0);
}

#[test]
fn meg_helmet() {
    check("open_meg_helmet_babysquid_mne.obj.gz", 1.0);
}

#[test]
fn hippocampus_sheet() {
    check("open_hippocampus_sheet_hippunfold.obj.gz", 1.0);
}

#[test]
fn hand() {
    check("open_hand_choi.obj.gz", 1.0);
}

#[test]
fn closed_bunny() {
    check("closed_bunny_npm.obj.gz", 1.0);
}

#[test]
fn closed_hippocampus() {
    check("closed_hippocampus_choi.obj.gz", 1.0);
}

#[test]
fn closed_brain_12k() {
    check("closed_brain12k_choi.obj.gz", 1.0);
}

#[test]
fn closed_brain_48k() {
    check("closed_brain_choi.obj.gz", 1.0);
}

/// A closed input of many more vertices than the remesh needs (the 48k brain at 5000 faces)
/// is mapped through a decimated copy sized to the remesh (`RemeshOptions::coarse_map`, the
/// default), prolonged to every vertex and refined there by a few sweeps: the remesh meets
/// issue 26's bars as the fine map's does, at about the same distance to the input, and the
/// map stays good.
#[test]
fn fine_closed_input_maps_at_the_remesh_detail() {
    let mesh = read_mesh(&common::data("closed_brain_choi.obj.gz")).unwrap();
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 5000 });
    let (_, copy) = remesh(&mesh, &options, &NoProgress).unwrap();
    let (_, fine) = remesh(&mesh, &options.clone().with_coarse_map(false), &NoProgress).unwrap();
    let copy_vertices = |r: &capmesh::RemeshReport| r.param.multilevel.as_ref().map(|m| m.coarse_vertices);
    // The copy is sized to the remesh, or an eighth of the input when that is more.
    assert_eq!(copy_vertices(&copy), Some(capmesh::remesh::remesh_copy_vertices(5000).max(mesh.n_vertices() / capmesh::param::COARSE_RATIO)));
    assert_eq!(copy_vertices(&fine), None, "the fine map is one level below 100k vertices");
    // A sized remesh measures its faces by the surface they cover through the map: its map
    // is the options' (one level here).
    let sized = options.clone().with_shape(capmesh::remesh::shape::ShapeOptions::default().with_sizing(capmesh::Sizing::Curvature { strength: 3.0 }));
    assert_eq!(copy_vertices(&remesh(&mesh, &sized, &NoProgress).unwrap().1), None);
    for (name, r) in [("copy", &copy), ("fine", &fine)] {
        let q = &r.quality;
        eprintln!("{name}: mean |d_area| {:.4}, d_face_rel {:.4}, mean smallest angle {:.2}, d_surf {:.3e}", r.param.area_distortion.mean_abs, q.d_face_relative, q.mean_min_angle_deg, q.d_surface_sampled_relative);
        assert!(q.d_face_relative <= 0.035 && q.mean_min_angle_deg >= 48.0 && q.min_angle_deg >= 15.0, "{name}: {q:?}");
        assert_eq!((r.param.flipped_faces, q.self_intersecting_faces), (0, 0), "{name}");
    }
    // Refined by a few sweeps only (`remesh::REMESH_COPY_SWEEPS`): a coarser map, still good.
    assert_eq!(copy.param.area_refinement.sweeps, capmesh::remesh::REMESH_COPY_SWEEPS);
    assert!(copy.param.area_distortion.mean_abs < 4.0 * fine.param.area_distortion.mean_abs && copy.param.area_distortion.mean_abs < 0.03);
    let ratio = copy.quality.d_surface_sampled_relative / fine.quality.d_surface_sampled_relative;
    assert!(ratio < 1.05, "the copy's remesh is {ratio} times as far from the input");
}

#[test]
fn closed_lung_lobe() {
    check("closed_lung_rml_chaste.obj.gz", 1.0);
}

#[test]
fn closed_bird_skull() {
    check("closed_bird_skull_CPallidusA_choi.obj.gz", 1.0);
}

#[test]
fn closed_lat_long_is_watertight() {
    let path = common::data("closed_bunny_npm.obj.gz");
    let mesh = read_mesh(&path).unwrap();
    let (out, _) = remesh(&mesh, &RemeshOptions::default().with_grid(CapGrid::LatLong { rings: 40, sectors: 80 }), &NoProgress).unwrap();
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::ClosedSphere);
    // The bottom disk is scaled onto the punctured quad: no face collapses onto its sides.
    let zero = capmesh::mesh::repair::zero_area_faces(&out, capmesh::mesh::repair::DEFAULT_ZERO_AREA_REL_TOL);
    assert!(zero.is_empty(), "{} zero-area faces", zero.len());
}

#[test]
fn lat_long_grid_has_rings_times_sectors_layout() {
    let path = common::data("open_meg_helmet_babysquid_mne.obj.gz");
    let mesh = read_mesh(&path).unwrap();
    let (rings, sectors) = (12, 24);
    let (out, _) = remesh(&mesh, &RemeshOptions::default().with_grid(CapGrid::LatLong { rings, sectors }), &NoProgress).unwrap();
    // A pole, then `rings` rings of `sectors` vertices; a fan of `sectors` faces at the pole and
    // two faces per quad.
    assert_eq!(out.n_vertices(), 1 + rings * sectors);
    assert_eq!(out.n_faces(), sectors + 2 * sectors * (rings - 1));
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::OpenDisk);
}

/// Coarse inputs, whose boundary polygon (an open surface's boundary, a closed one's punctured
/// quad) leaves wide circular segments of the disk uncovered: cap points there used to be
/// located on the polygon's sides, and the faces between them pulled back with zero area
/// (2026-12-01, before the rim band: the icosphere of 42 vertices 99 of 5000 faces, 165 of the
/// lat/long mesh; the bunny with one face removed 9 and 60; a two-triangle square 1614 and
/// 930). The rim band now goes onto the polygon.
#[test]
fn coarse_inputs_remesh_without_zero_area_faces() {
    let mut holed = read_mesh(&common::data("closed_bunny_npm.obj.gz")).unwrap();
    holed.faces.remove(0);
    let square = capmesh::TriMesh::new(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.1]], vec![[0, 1, 2], [1, 3, 2]]);
    let cases = [
        ("icosphere 12", capmesh::mesh::shapes::icosphere(0)),
        ("icosphere 42", capmesh::mesh::shapes::icosphere(1)),
        ("icosphere 162", capmesh::mesh::shapes::icosphere(2)),
        ("bunny with a hole", holed),
        ("two triangles", square),
    ];
    for (name, mesh) in cases {
        for grid in [CapGrid::Uniform { faces: 5000 }, CapGrid::LatLong { rings: 40, sectors: 64 }] {
            for placement in [Placement::OnSurface, Placement::Fitted] {
                let (out, rep) = remesh(&mesh, &RemeshOptions::default().with_grid(grid).with_placement(placement), &NoProgress).unwrap_or_else(|e| panic!("{name}: {e}"));
                let (input_kind, _) = validate(&mesh).unwrap();
                let (kind, _) = validate(&out).unwrap_or_else(|e| panic!("{name} {grid:?} {placement:?}: remeshed mesh invalid: {e}"));
                assert_eq!(kind, input_kind, "{name} {grid:?} {placement:?}");
                assert_eq!(rep.quality.zero_area_faces, 0, "{name} {grid:?} {placement:?}: zero-area faces");
                assert!(out.vertices.iter().flatten().all(|x| x.is_finite()), "{name} {grid:?} {placement:?}");
                if placement == Placement::OnSurface {
                    assert!(rep.quality.d_surface_vertex_relative < 1e-9, "{name} {grid:?}: vertices off the surface");
                } else {
                    // The fit lowered its own measure (sampled distances along the faces' normals).
                    assert!(rep.fit.rms_after <= rep.fit.rms_before * (1.0 + 1e-9), "{name} {grid:?}: {:?}", rep.fit);
                }
            }
        }
    }
}

/// `--optimize area`'s equalization runs and helps on closed surfaces (it once stopped after
/// one sweep there, its planar orientation taken from the flat bottom's reversed faces).
#[test]
fn equalization_runs_on_closed_surfaces() {
    for name in ["closed_bunny_npm.obj.gz", "closed_brain12k_choi.obj.gz"] {
        let mesh = read_mesh(&common::data(name)).unwrap();
        let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 3000 }).with_optimize(Optimize::Area);
        let (_, rep) = remesh(&mesh, &options, &NoProgress).unwrap_or_else(|e| panic!("{name}: {e}"));
        let eq = &rep.area_equalization;
        assert!(eq.sweeps > 1 && eq.mean_abs_after < 0.9 * eq.mean_abs_before, "{name}: equalization {eq:?}");
    }
}
