//! The C ABI (feature `capi`) called as C would call it: results on a real mesh, cancellation,
//! and misuse (NULL pointers, out-of-range indices, wrong counts, bad options) returning error
//! statuses with a message instead of crashing.

mod common;

use std::ffi::{c_char, c_void, CStr};
use std::ptr::{null, null_mut};

use capmesh::ffi::capmesh_v1_status::*;
use capmesh::ffi::*;
use capmesh::TriMesh;
use common::capi::{last_error, Arrays};

fn read(name: &str) -> TriMesh {
    capmesh::io::read_mesh(&common::data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn take_string(s: *mut c_char) -> String {
    assert!(!s.is_null());
    let text = unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned();
    unsafe { capmesh_v1_string_free(s) };
    text
}

/// Copy a result handle into a TriMesh and free it.
fn take_mesh(m: *mut capmesh_v1_mesh) -> TriMesh {
    assert!(!m.is_null());
    let (nv, nf) = unsafe { (capmesh_v1_mesh_vertex_count(m), capmesh_v1_mesh_face_count(m)) };
    let p = unsafe { std::slice::from_raw_parts(capmesh_v1_mesh_positions(m), 3 * nv) };
    let t = unsafe { std::slice::from_raw_parts(capmesh_v1_mesh_triangles(m), 3 * nf) };
    let mesh = TriMesh::new(p.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(), t.chunks(3).map(|c| [c[0], c[1], c[2]]).collect());
    unsafe { capmesh_v1_mesh_free(m) };
    mesh
}

#[test]
fn version_is_the_crate_version() {
    let v = unsafe { CStr::from_ptr(capmesh_v1_version()) };
    assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}

#[test]
fn remesh_uniform_and_lat_long_through_the_c_abi() {
    let input = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&input);
    let view = arrays.view();

    let mut options = capmesh_v1_remesh_options_default();
    options.faces = 2000;
    let (mut out, mut report) = (null_mut(), null_mut());
    let status = unsafe { capmesh_v1_remesh(&view, &options, None, null_mut(), &mut out, &mut report) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    assert_eq!(last_error(), "");
    let remeshed = take_mesh(out);
    let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
    let faces = remeshed.n_faces() as f64;
    assert!((faces - 2000.0).abs() <= 200.0, "{faces} faces for 2000 asked");
    assert_eq!(report["quality"]["faces"].as_u64().unwrap() as usize, remeshed.n_faces());
    let summary = capmesh::mesh::inspect(&remeshed).unwrap();
    assert_eq!(summary.kind, Some(capmesh::mesh::SurfaceKind::OpenDisk));
    assert!(report["quality"]["d_surface_sampled_relative"].as_f64().unwrap() < 0.01);

    // The metrics entry point agrees with the remesh report.
    let remeshed_arrays = Arrays::of(&remeshed);
    let mut metrics = null_mut();
    let status = unsafe { capmesh_v1_metrics(&view, &remeshed_arrays.view(), &mut metrics) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    let metrics: serde_json::Value = serde_json::from_str(&take_string(metrics)).unwrap();
    let a = metrics["d_face_relative"].as_f64().unwrap();
    let b = report["quality"]["d_face_relative"].as_f64().unwrap();
    assert!((a - b).abs() <= 1e-12 * b.max(1.0), "{a} vs {b}");

    options.grid = CAPMESH_V1_GRID_LAT_LONG;
    options.rings = 10;
    options.sectors = 24;
    let mut out = null_mut();
    let status = unsafe { capmesh_v1_remesh(&view, &options, None, null_mut(), &mut out, null_mut()) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    let lat_long = take_mesh(out);
    // A fan of `sectors` at the pole and two triangles per quad in the other rings.
    assert_eq!(lat_long.n_faces(), 24 + 2 * 24 * 9);
}

#[test]
fn parameterize_puts_the_vertices_on_the_cap() {
    let input = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&input);
    let (mut out, mut report) = (null_mut(), null_mut());
    let status = unsafe { capmesh_v1_parameterize(&arrays.view(), null(), None, null_mut(), &mut out, &mut report) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    let cap = take_mesh(out);
    let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
    let z_star = report["z_star"].as_f64().unwrap();
    assert_eq!(cap.faces, input.faces);
    for p in &cap.vertices {
        let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((norm - 1.0).abs() < 1e-9 && p[2] >= z_star - 1e-9, "{p:?} off the cap Z >= {z_star}");
    }
}

#[test]
fn harmonics_reconstruct_the_surface() {
    let input = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&input);
    let mut options = capmesh_v1_harmonics_options_default();
    options.order = 6;
    let (mut out, mut report) = (null_mut(), null_mut());
    let status = unsafe { capmesh_v1_harmonics(&arrays.view(), &options, None, null_mut(), &mut out, &mut report) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    let rec = take_mesh(out);
    let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
    assert_eq!(rec.faces, input.faces);
    assert_eq!(report["order"].as_u64(), Some(6));
    let errors = report["errors_by_order"].as_array().unwrap();
    let mean = |n: usize| errors[n]["mean_relative"].as_f64().unwrap();
    assert!(mean(6) < mean(1), "order 6 error {} not below order 1 error {}", mean(6), mean(1));

    // Too high an order for the mesh is an invalid argument, refused before the work.
    options.order = 400;
    let status = unsafe { capmesh_v1_harmonics(&arrays.view(), &options, None, null_mut(), &mut out, null_mut()) };
    assert_eq!(status, CAPMESH_V1_INVALID_ARGUMENT);
    assert!(out.is_null());
    assert!(last_error().contains("basis functions"), "{}", last_error());
}

#[test]
fn cap_harmonics_keep_the_boundary_and_resample() {
    let input = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&input);
    let mut options = capmesh_v1_harmonics_options_default();
    assert_eq!((options.basis, options.boundary, options.resample_faces), (CAPMESH_V1_BASIS_AH, CAPMESH_V1_BOUNDARY_NEUMANN, 0));
    options.order = 6;
    let boundary = |options: &capmesh_v1_harmonics_options| {
        let (mut out, mut report) = (null_mut(), null_mut());
        let status = unsafe { capmesh_v1_harmonics(&arrays.view(), options, None, null_mut(), &mut out, &mut report) };
        assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
        let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
        (take_mesh(out), report["boundary_max_relative"].as_f64().unwrap())
    };
    let (_, ah) = boundary(&options);
    options.basis = CAPMESH_V1_BASIS_SCHA;
    let (rec, scha) = boundary(&options);
    assert_eq!(rec.faces, input.faces);
    assert!(scha < 0.5 * ah, "cap harmonics boundary error {scha} vs adaptive harmonics {ah}");
    options.resample_faces = 1500;
    let (grid, _) = boundary(&options);
    assert!((1300..=1700).contains(&grid.faces.len()), "{} faces", grid.faces.len());
    options.resample_faces = u32::MAX;
    let mut out = null_mut();
    let status = unsafe { capmesh_v1_harmonics(&arrays.view(), &options, None, null_mut(), &mut out, null_mut()) };
    assert_eq!(status, CAPMESH_V1_INVALID_ARGUMENT, "{}", last_error());
    assert!(last_error().contains("resample"), "{}", last_error());
    options.resample_faces = 0;

    let mut out = null_mut();
    for (basis, boundary) in [(7, CAPMESH_V1_BOUNDARY_NEUMANN), (CAPMESH_V1_BASIS_SCHA, -1)] {
        options.basis = basis;
        options.boundary = boundary;
        let status = unsafe { capmesh_v1_harmonics(&arrays.view(), &options, None, null_mut(), &mut out, null_mut()) };
        assert_eq!(status, CAPMESH_V1_INVALID_ARGUMENT);
        assert!(out.is_null());
        assert!(last_error().contains("is not"), "{}", last_error());
    }
}

struct Calls {
    count: usize,
    stages: Vec<i32>,
    cancel_after: usize,
}

unsafe extern "C" fn count_and_cancel(user: *mut c_void, stage: i32, fraction: f64, message: *const c_char) -> i32 {
    let calls = unsafe { &mut *(user as *mut Calls) };
    assert!((0.0..=1.0).contains(&fraction));
    assert!(!message.is_null());
    calls.count += 1;
    calls.stages.push(stage);
    i32::from(calls.count >= calls.cancel_after)
}

#[test]
fn the_progress_callback_reports_and_cancels() {
    let input = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&input);
    let mut calls = Calls { count: 0, stages: vec![], cancel_after: 3 };
    let (mut out, mut report) = (null_mut(), null_mut());
    let status = unsafe {
        capmesh_v1_remesh(&arrays.view(), null(), Some(count_and_cancel), (&mut calls as *mut Calls).cast(), &mut out, &mut report)
    };
    assert_eq!(status, CAPMESH_V1_CANCELLED);
    assert!(out.is_null() && report.is_null());
    assert_eq!(calls.count, 3, "the callback is not called again after it cancelled");
    assert_eq!(calls.stages[0], CAPMESH_V1_STAGE_VALIDATE);
    assert!(last_error().contains("cancel"), "{}", last_error());

    let mut calls = Calls { count: 0, stages: vec![], cancel_after: usize::MAX };
    let status = unsafe {
        capmesh_v1_parameterize(&arrays.view(), null(), Some(count_and_cancel), (&mut calls as *mut Calls).cast(), &mut out, null_mut())
    };
    assert_eq!(status, CAPMESH_V1_OK);
    unsafe { capmesh_v1_mesh_free(out) };
    for s in [CAPMESH_V1_STAGE_VALIDATE, CAPMESH_V1_STAGE_FLATTEN, CAPMESH_V1_STAGE_RADIUS_SEARCH, CAPMESH_V1_STAGE_TRANSPORT, CAPMESH_V1_STAGE_PROJECT] {
        assert!(calls.stages.contains(&s), "stage {s} never reported: {:?}", calls.stages);
    }
}

/// A small valid open mesh: a 3 x 3 vertex grid in the plane (8 triangles).
fn grid() -> Arrays {
    let mut positions = vec![];
    for j in 0..3 {
        for i in 0..3 {
            positions.extend([i as f64, j as f64, 0.0]);
        }
    }
    let mut triangles = vec![];
    for j in 0..2u32 {
        for i in 0..2u32 {
            let v = j * 3 + i;
            triangles.extend([v, v + 1, v + 4, v, v + 4, v + 3]);
        }
    }
    Arrays { positions, triangles }
}

fn expect(status: capmesh_v1_status, want: capmesh_v1_status, words: &str) {
    assert_eq!(status, want, "last error: {}", last_error());
    assert!(last_error().contains(words), "'{}' does not mention '{words}'", last_error());
}

#[test]
fn misuse_returns_errors_with_a_message() {
    let a = grid();
    let good = a.view();
    let mut out = 1usize as *mut capmesh_v1_mesh; // garbage the call must overwrite with NULL
    unsafe {
        // NULL view, NULL output, NULL arrays.
        expect(capmesh_v1_remesh(null(), null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "NULL");
        assert!(out.is_null());
        expect(capmesh_v1_remesh(&good, null(), None, null_mut(), null_mut(), null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "out_mesh");
        expect(capmesh_v1_parameterize(&good, null(), None, null_mut(), null_mut(), null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "out_cap");
        expect(capmesh_v1_harmonics(&good, null(), None, null_mut(), null_mut(), null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "out_reconstructed");
        let v = capmesh_v1_mesh_view { positions: null(), ..good };
        expect(capmesh_v1_parameterize(&v, null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "positions is NULL");
        let v = capmesh_v1_mesh_view { triangles: null(), ..good };
        expect(capmesh_v1_parameterize(&v, null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "triangles is NULL");
        let mut report = null_mut();
        expect(capmesh_v1_metrics(&good, null(), &mut report), CAPMESH_V1_INVALID_ARGUMENT, "remeshed");
        expect(capmesh_v1_metrics(&good, &good, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "out_report_json");

        // Counts that disagree with the arrays: fewer vertices than the indices use, no faces,
        // counts whose arrays could not exist.
        let v = capmesh_v1_mesh_view { vertex_count: 5, ..good };
        expect(capmesh_v1_parameterize(&v, null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_MESH, "vertex_count is 5");
        let v = capmesh_v1_mesh_view { face_count: 0, ..good };
        expect(capmesh_v1_parameterize(&v, null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_MESH, "empty");
        let v = capmesh_v1_mesh_view { face_count: usize::MAX / 4, ..good };
        expect(capmesh_v1_parameterize(&v, null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "too large");
        let v = capmesh_v1_mesh_view { vertex_count: usize::MAX, ..good };
        expect(capmesh_v1_parameterize(&v, null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "32-bit");

        // Out-of-range index, NaN, non-manifold input.
        let mut bad = grid();
        bad.triangles[4] = 9;
        expect(capmesh_v1_remesh(&bad.view(), null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_MESH, "triangle 1 refers to vertex 9");
        let mut bad = grid();
        bad.positions[7] = f64::NAN;
        expect(capmesh_v1_remesh(&bad.view(), null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_MESH, "vertex 2");
        // (A repeated face is dropped by remesh; a third face on an interior edge is not.)
        let mut bad = grid();
        bad.triangles.extend([0, 4, 8]);
        expect(capmesh_v1_remesh(&bad.view(), null(), None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_MESH, "shared by 3 faces");
        assert!(out.is_null());

        // Options out of range.
        let mut o = capmesh_v1_remesh_options_default();
        o.grid = 7;
        expect(capmesh_v1_remesh(&good, &o, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "grid = 7");
        let mut o = capmesh_v1_remesh_options_default();
        o.faces = 0;
        expect(capmesh_v1_remesh(&good, &o, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "faces = 0");
        let mut o = capmesh_v1_remesh_options_default();
        o.grid = CAPMESH_V1_GRID_LAT_LONG;
        o.sectors = 2;
        expect(capmesh_v1_remesh(&good, &o, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "sectors = 2");
        let mut p = capmesh_v1_param_options_default();
        p.domain = 9;
        expect(capmesh_v1_parameterize(&good, &p, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "domain = 9");
        p.domain = CAPMESH_V1_DOMAIN_RADIUS;
        p.radius = -1.0;
        expect(capmesh_v1_parameterize(&good, &p, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "radius");
        // Beyond the adaptive search's range the transport degenerates (refused, not mapped).
        p.radius = 1000.0;
        expect(capmesh_v1_parameterize(&good, &p, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "radius = 1000");
        let mut p = capmesh_v1_param_options_default();
        p.lambda = f64::NAN;
        expect(capmesh_v1_parameterize(&good, &p, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "lambda");
        let mut h = capmesh_v1_harmonics_options_default();
        h.param.domain = CAPMESH_V1_DOMAIN_DISK;
        h.order = 1;
        expect(capmesh_v1_harmonics(&good, &h, None, null_mut(), &mut out, null_mut()), CAPMESH_V1_INVALID_ARGUMENT, "planar disk");
        assert!(out.is_null());
    }
    // Accessors and free functions accept NULL.
    unsafe {
        assert_eq!(capmesh_v1_mesh_vertex_count(null()), 0);
        assert_eq!(capmesh_v1_mesh_face_count(null()), 0);
        assert!(capmesh_v1_mesh_positions(null()).is_null());
        assert!(capmesh_v1_mesh_triangles(null()).is_null());
        capmesh_v1_mesh_free(null_mut());
        capmesh_v1_string_free(null_mut());
    }
}

#[test]
fn closed_surfaces_remesh_into_closed_meshes() {
    let input = read("closed_bunny_npm.obj.gz");
    let arrays = Arrays::of(&input);
    let (mut out, mut report) = (null_mut(), null_mut());
    let mut o = capmesh_v1_remesh_options_default();
    o.faces = 2000;
    let status = unsafe { capmesh_v1_remesh(&arrays.view(), &o, None, null_mut(), &mut out, &mut report) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    let remeshed = take_mesh(out);
    let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
    let faces = remeshed.n_faces() as f64;
    println!("bunny: {faces} faces for 2000 asked, d_face_relative {}", report["quality"]["d_face_relative"]);
    assert!((faces - 2000.0).abs() <= 200.0, "{faces} faces for 2000 asked");
    let summary = capmesh::mesh::inspect(&remeshed).unwrap();
    assert_eq!(summary.kind, Some(capmesh::mesh::SurfaceKind::ClosedSphere));
}

/// The refinement, equalization and puncture-end options reach the library: the report says
/// what was asked, and an unknown puncture end is refused.
#[test]
fn refinement_equalization_and_puncture_end_options_are_passed_through() {
    let input = read("closed_bunny_npm.obj.gz");
    let arrays = Arrays::of(&input);
    let (mut out, mut report) = (null_mut(), null_mut());
    let mut o = capmesh_v1_remesh_options_default();
    assert_eq!(
        (o.param.area_refinement, o.param.puncture_end, o.area_equalization),
        (capmesh::param::DEFAULT_AREA_REFINEMENT as u32, CAPMESH_V1_PUNCTURE_BEST, 30)
    );
    o.faces = 1000;
    o.param.area_refinement = 0;
    o.param.puncture_end = CAPMESH_V1_PUNCTURE_TOP;
    // The equalization's own sweeps count when the shape stage does not run.
    o.optimize = CAPMESH_V1_OPTIMIZE_AREA;
    o.area_equalization = 0;
    let status = unsafe { capmesh_v1_remesh(&arrays.view(), &o, None, null_mut(), &mut out, &mut report) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    take_mesh(out);
    let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
    assert_eq!(report["param"]["area_refinement"]["sweeps"], 0, "{}", report["param"]["area_refinement"]);
    assert_eq!(report["area_equalization"]["sweeps"], 0);
    // One end only: no trials of the other.
    assert_eq!(report["param"]["puncture_trials"].as_array().map(|a| a.len()), Some(0));
    let mut p = capmesh_v1_param_options_default();
    p.puncture_end = 5;
    let status = unsafe { capmesh_v1_parameterize(&arrays.view(), &p, None, null_mut(), &mut out, null_mut()) };
    assert_eq!(status, CAPMESH_V1_INVALID_ARGUMENT);
    assert!(last_error().contains("puncture_end = 5"), "{}", last_error());
    // The multilevel thresholds (issue 27): the bunny subdivided twice (29k vertices) goes
    // through a decimated copy when asked to, not by default.
    let fine = capmesh::mesh::subdivide_midpoint(&input, 2);
    let arrays = Arrays::of(&fine);
    let p = capmesh_v1_param_options_default();
    assert_eq!((p.multilevel_above, p.coarse_vertices), (capmesh::param::DEFAULT_MULTILEVEL_ABOVE as u32, capmesh::param::DEFAULT_COARSE_VERTICES as u32));
    for (above, expected) in [(p.multilevel_above, serde_json::Value::Null), (10_000, serde_json::json!(8000))] {
        let p = capmesh_v1_param_options { multilevel_above: above, coarse_vertices: 8000, ..p };
        let mut raw = null_mut();
        let status = unsafe { capmesh_v1_parameterize(&arrays.view(), &p, None, null_mut(), &mut out, &mut raw) };
        assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
        take_mesh(out);
        let report: serde_json::Value = serde_json::from_str(&take_string(raw)).unwrap();
        assert_eq!(report["multilevel"]["coarse_vertices"].clone(), expected, "multilevel_above {above}: {}", report["multilevel"]);
    }
}

/// A shape+area remesh maps a closed input of many more vertices than it needs (the bunny
/// subdivided twice, 29k vertices, at 1000 faces) through a copy sized to the remesh (6000
/// vertices) by default, and at one level with `coarse_map = 0`, as `capmesh_v1_parameterize`
/// does; without the shape stage (the plain pull-back), whose areas are the map's, at one
/// level too.
#[test]
fn a_remesh_maps_a_fine_closed_input_at_its_own_detail() {
    let fine = capmesh::mesh::subdivide_midpoint(&read("closed_bunny_npm.obj.gz"), 2);
    let arrays = Arrays::of(&fine);
    let o = capmesh_v1_remesh_options { faces: 1000, ..capmesh_v1_remesh_options_default() };
    assert_eq!(o.coarse_map, 1);
    let copy = serde_json::json!(capmesh::remesh::remesh_copy_vertices(1000));
    for (coarse_map, optimize, expected) in [(1, CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA, copy), (0, CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA, serde_json::Value::Null), (1, CAPMESH_V1_OPTIMIZE_NONE, serde_json::Value::Null)] {
        let o = capmesh_v1_remesh_options { coarse_map, optimize, ..o };
        let (mut out, mut raw) = (null_mut(), null_mut());
        let status = unsafe { capmesh_v1_remesh(&arrays.view(), &o, None, null_mut(), &mut out, &mut raw) };
        assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
        assert_eq!(capmesh::mesh::validate(&take_mesh(out)).unwrap().0, capmesh::mesh::SurfaceKind::ClosedSphere);
        let report: serde_json::Value = serde_json::from_str(&take_string(raw)).unwrap();
        assert_eq!(report["param"]["multilevel"]["coarse_vertices"].clone(), expected, "coarse_map {coarse_map}: {}", report["param"]["multilevel"]);
    }
}

/// Share of the faces of `mesh` with an angle below 30 degrees.
fn share_below_30(mesh: &TriMesh) -> f64 {
    capmesh::metrics::angles::angle_quality(mesh).share_below_30
}

/// The shape stage's options reach the library: the default remesh is the shape+area one
/// (well-shaped triangles), `CAPMESH_V1_OPTIMIZE_AREA` keeps the cap grid's connectivity (many
/// thin triangles where the map stretches), and out-of-range values are refused by name.
#[test]
fn the_default_remesh_optimizes_shape_and_area_through_the_c_abi() {
    let input = read("open_lv_endo_rabbit_chaste.obj.gz");
    let arrays = Arrays::of(&input);
    let mut o = capmesh_v1_remesh_options_default();
    assert_eq!(o.optimize, CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA);
    let shape = capmesh::remesh::shape::ShapeOptions::default();
    assert_eq!(
        (o.relax_iterations as usize, o.polish_iterations as usize, o.area_steps as usize, o.shape_weight, o.resample != 0, o.creases == CAPMESH_V1_CREASES_AUTO, o.polish_tolerance),
        (shape.relax_iterations, shape.polish_iterations, shape.area_steps, shape.shape_weight, shape.resample, shape.creases == capmesh::Creases::Auto, shape.polish_tolerance)
    );
    o.faces = 2000;
    let run = |o: &capmesh_v1_remesh_options| {
        let (mut out, mut report) = (null_mut(), null_mut());
        let status = unsafe { capmesh_v1_remesh(&arrays.view(), o, None, null_mut(), &mut out, &mut report) };
        assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
        let mesh = take_mesh(out);
        let report: serde_json::Value = serde_json::from_str(&take_string(report)).unwrap();
        (mesh, report)
    };

    assert_eq!(o.placement, CAPMESH_V1_PLACEMENT_FITTED);
    let (shaped, report) = run(&o);
    assert_eq!(report["optimize"], "shape+area", "{}", report["optimize"]);
    assert_eq!(report["fit"]["fitted"], true, "{}", report["fit"]);
    // The polish may stop early once converged, never before its global area steps.
    let iterations = report["shape"]["iterations"].as_u64().unwrap_or(0) as usize;
    assert!((shape.relax_iterations + 5 * shape.area_steps..=shape.relax_iterations + shape.polish_iterations).contains(&iterations), "{}", report["shape"]);
    assert_eq!((o.sizing, o.sizing_strength, &report["shape"]["sizing"]), (CAPMESH_V1_SIZING_UNIFORM, 3.0, &serde_json::json!("uniform")));
    let shaped_share = share_below_30(&shaped);
    // The polish tolerance is passed through: 0 runs every polish iteration.
    let mut every = o;
    every.polish_tolerance = 0.0;
    let (_, report) = run(&every);
    assert_eq!(report["shape"]["iterations"].as_u64(), Some((shape.relax_iterations + shape.polish_iterations) as u64), "{}", report["shape"]);

    o.optimize = CAPMESH_V1_OPTIMIZE_AREA;
    let (area, report) = run(&o);
    assert_eq!(report["optimize"], "area");
    assert_eq!(report["shape"]["iterations"].as_u64(), Some(0));
    let area_share = share_below_30(&area);
    println!("rabbit LV: faces with an angle below 30 degrees: {shaped_share:.3} shape+area, {area_share:.3} area");
    assert!(shaped_share < 0.1 && area_share > 3.0 * shaped_share, "{shaped_share} vs {area_share}");

    // The iteration counts are passed through: no iterations, no shape stage work.
    o.optimize = CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA;
    o.relax_iterations = 0;
    o.polish_iterations = 0;
    let (_, report) = run(&o);
    assert_eq!(report["shape"]["iterations"].as_u64(), Some(0), "{}", report["shape"]);
    // The sizings are passed through (their effect: tests/remesh_sizing.rs); the curvature's
    // strength only with it.
    o.sizing_strength = 2.5;
    let (_, report) = run(&o);
    assert_eq!(report["shape"]["sizing"], "uniform", "{}", report["shape"]);
    o.sizing = CAPMESH_V1_SIZING_SURFACE;
    let (_, report) = run(&o);
    assert_eq!(report["shape"]["sizing"], "surface", "{}", report["shape"]);
    o.sizing = CAPMESH_V1_SIZING_CURVATURE;
    let (_, report) = run(&o);
    assert_eq!(report["shape"]["sizing"], "curvature=2.5", "{}", report["shape"]);
    assert_eq!(report["shape"]["keep_creases"], true, "{}", report["shape"]);
    // The crease handling is passed through: off with curvature sizing.
    o.creases = CAPMESH_V1_CREASES_OFF;
    let (_, report) = run(&o);
    assert_eq!(report["shape"]["keep_creases"], false, "{}", report["shape"]);
    o.creases = CAPMESH_V1_CREASES_AUTO;
    // The placement is passed through: on the surface, no fit.
    o.placement = CAPMESH_V1_PLACEMENT_ON_SURFACE;
    let (_, report) = run(&o);
    assert_eq!(report["fit"]["fitted"], false, "{}", report["fit"]);
    assert!(report["quality"]["d_surface_vertex_relative"].as_f64().unwrap() < 1e-9, "{}", report["quality"]);
    // Holes are kept by default and filled when asked: the ventricle's base closed.
    assert_eq!(o.fill_holes, 0);
    o.fill_holes = 1;
    let (_, report) = run(&o);
    assert_eq!((&report["filled_holes"], &report["param"]["kind"]), (&serde_json::json!(1), &serde_json::json!("closed genus-0")), "{report}");
    o.fill_holes = 0;
    // An input coarser than the remesh (the ventricle's 8405 faces) is subdivided for its map
    // by default, mapped as it is when asked.
    assert_eq!(o.subdivide_coarse, 1);
    o.faces = 9000;
    let (_, report) = run(&o);
    assert!(report["subdivided"].as_u64().is_some_and(|k| k > 0), "{}", report["subdivided"]);
    o.subdivide_coarse = 0;
    let (_, report) = run(&o);
    assert_eq!(report["subdivided"].as_u64(), Some(0), "{}", report["subdivided"]);

    let mut out = null_mut();
    let mut refused = |o: &capmesh_v1_remesh_options, words: &str| {
        let status = unsafe { capmesh_v1_remesh(&arrays.view(), o, None, null_mut(), &mut out, null_mut()) };
        expect(status, CAPMESH_V1_INVALID_ARGUMENT, words);
        assert!(out.is_null());
    };
    let mut bad = capmesh_v1_remesh_options_default();
    bad.optimize = 3;
    refused(&bad, "optimize = 3");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.shape_weight = -0.5;
    refused(&bad, "shape_weight = -0.5");
    bad.shape_weight = f64::INFINITY;
    refused(&bad, "shape_weight");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.resample = 2;
    refused(&bad, "resample = 2");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.creases = 3;
    refused(&bad, "creases = 3");
    let mut bad = capmesh_v1_remesh_options_default();
    assert_eq!(bad.crease_deg, 60.0);
    bad.crease_deg = 180.0;
    refused(&bad, "crease_deg = 180");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.polish_tolerance = -1.0;
    refused(&bad, "polish_tolerance = -1");
    bad.polish_tolerance = f64::NAN;
    refused(&bad, "polish_tolerance");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.fill_holes = 2;
    refused(&bad, "fill_holes = 2");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.placement = 2;
    refused(&bad, "placement = 2");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.subdivide_coarse = 2;
    refused(&bad, "subdivide_coarse = 2");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.coarse_map = 2;
    refused(&bad, "coarse_map = 2");
    let mut bad = capmesh_v1_remesh_options_default();
    bad.sizing = 3;
    refused(&bad, "sizing = 3");
    bad.sizing = CAPMESH_V1_SIZING_CURVATURE;
    bad.sizing_strength = -1.0;
    refused(&bad, "sizing_strength = -1");
    bad.sizing_strength = 0.0;
    refused(&bad, "sizing_strength = 0");
    bad.sizing_strength = f64::NAN;
    refused(&bad, "sizing_strength");
}
