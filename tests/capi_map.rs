//! The cap map handle of the C ABI (feature `capi`, issue 31): `capmesh_v1_parameterize_map`,
//! the inverse map of cap points back onto the input (the cap vertices give the input vertices
//! back, points off the cap are reported per point), the forward map, the texture coordinates,
//! `capmesh_v1_remesh_located`'s source points, and misuse returning errors with a message.

mod common;

use std::ffi::CStr;
use std::ptr::{null, null_mut};

use capmesh::ffi::capmesh_v1_status::*;
use capmesh::ffi::*;
use capmesh::TriMesh;
use common::capi::{last_error, Arrays};
use common::data;

fn read(name: &str) -> TriMesh {
    capmesh::io::read_mesh(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A map handle of `mesh`, and its report.
fn map_of(arrays: &Arrays) -> (*mut capmesh_v1_map, serde_json::Value) {
    let (mut map, mut report) = (null_mut(), null_mut());
    let status = unsafe { capmesh_v1_parameterize_map(&arrays.view(), null(), None, null_mut(), &mut map, &mut report) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    assert!(!map.is_null() && !report.is_null());
    let text = unsafe { CStr::from_ptr(report) }.to_string_lossy().into_owned();
    unsafe { capmesh_v1_string_free(report) };
    (map, serde_json::from_str(&text).unwrap())
}

/// What `capmesh_v1_map_inverse` wrote for `points`.
struct Inverse {
    positions: Vec<f64>,
    faces: Vec<u32>,
    barycentrics: Vec<f64>,
    located: Vec<i32>,
    count: usize,
}

fn inverse(map: *const capmesh_v1_map, points: &[f64]) -> Inverse {
    let n = points.len() / 3;
    let mut out = Inverse { positions: vec![0.0; 3 * n], faces: vec![7; n], barycentrics: vec![0.0; 3 * n], located: vec![-1; n], count: 0 };
    let status = unsafe {
        capmesh_v1_map_inverse(
            map,
            points.as_ptr(),
            n,
            out.positions.as_mut_ptr(),
            out.faces.as_mut_ptr(),
            out.barycentrics.as_mut_ptr(),
            out.located.as_mut_ptr(),
            &mut out.count,
        )
    };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    assert_eq!(last_error(), "");
    out
}

/// The cap vertices of `name` come back as its input vertices, on a face holding the vertex
/// with its corner's weight 1; the forward map of that surface point is the cap vertex again.
fn cap_vertices_give_the_input_back(name: &str) {
    let mesh = read(name);
    let arrays = Arrays::of(&mesh);
    let (map, report) = map_of(&arrays);
    let nv = unsafe { capmesh_v1_map_vertex_count(map) };
    assert_eq!(nv, mesh.n_vertices());
    assert_eq!(unsafe { capmesh_v1_map_face_count(map) }, mesh.n_faces());
    let cap = unsafe { std::slice::from_raw_parts(capmesh_v1_map_cap_positions(map), 3 * nv) }.to_vec();
    let z_star = report["z_star"].as_f64().unwrap();
    assert!(cap.chunks(3).all(|p| p[2] >= z_star - 1e-9), "{name}: a cap vertex below Z* = {z_star}");

    let out = inverse(map, &cap);
    assert_eq!(out.count, nv, "{name}: {} of {nv} cap vertices located", out.count);
    assert!(out.located.iter().all(|&s| s == CAPMESH_V1_POINT_LOCATED));
    let diag = mesh.bounding_box_diagonal();
    let mut worst = 0.0f64;
    for v in 0..nv {
        let d = (0..3).map(|k| (out.positions[3 * v + k] - mesh.vertices[v][k]).powi(2)).sum::<f64>().sqrt();
        worst = worst.max(d);
        let face = out.faces[v] as usize;
        assert!(face < mesh.n_faces(), "{name}: vertex {v} on face {face}");
        let w = &out.barycentrics[3 * v..3 * v + 3];
        assert!(w.iter().all(|&b| b >= 0.0) && (w.iter().sum::<f64>() - 1.0).abs() < 1e-9, "{name}: weights {w:?}");
    }
    assert!(worst <= 1e-9 * diag, "{name}: a cap vertex came back {worst} from its input vertex (diagonal {diag})");

    // Forward: the located surface points go back to the cap vertices.
    let mut forward = vec![0.0; 3 * nv];
    let status = unsafe { capmesh_v1_map_forward(map, out.faces.as_ptr(), out.barycentrics.as_ptr(), nv, forward.as_mut_ptr()) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    let worst = forward.iter().zip(&cap).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst < 1e-6, "{name}: forward of the inverse moved a cap vertex by {worst}");

    // The texture coordinates are those of `param --uv` (CapMap::uv), inside [0, 1]^2.
    let uv = unsafe { std::slice::from_raw_parts(capmesh_v1_map_uv(map), 2 * nv) };
    let want = capmesh::parameterize(&mesh, &capmesh::ParamOptions::default(), &capmesh::NoProgress).unwrap().uv();
    let worst = uv.chunks(2).zip(&want).map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs())).fold(0.0, f64::max);
    assert!(worst < 1e-12, "{name}: uv differs from CapMap::uv by {worst}");
    assert!(uv.iter().all(|t| (0.0..=1.0).contains(t)));
    unsafe { capmesh_v1_map_free(map) };
}

#[test]
fn an_open_surface_inverts_its_cap_vertices() {
    cap_vertices_give_the_input_back("open_meg_helmet_babysquid_mne.obj.gz");
}

#[test]
fn a_closed_surface_inverts_its_cap_vertices_and_its_bottom() {
    cap_vertices_give_the_input_back("closed_bunny_npm.obj.gz");
}

#[test]
fn points_off_the_cap_are_reported_not_guessed() {
    let mesh = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&mesh);
    let (map, report) = map_of(&arrays);
    let z_star = report["z_star"].as_f64().unwrap();
    let below = (z_star - 0.1).max(-1.0);
    let s = (1.0 - below * below).sqrt();
    #[rustfmt::skip]
    let points = [
        0.0, 0.0, 1.0,            // the north pole: on every cap
        0.0, 0.0, 2.0,            // off the sphere
        s, 0.0, below,            // on the sphere, below Z*
        f64::NAN, 0.0, 1.0,       // not a point
        0.0, 0.0, 0.5,            // inside the ball
    ];
    let out = inverse(map, &points);
    assert_eq!(out.located, [CAPMESH_V1_POINT_LOCATED, CAPMESH_V1_POINT_OFF_CAP, CAPMESH_V1_POINT_OFF_CAP, CAPMESH_V1_POINT_OFF_CAP, CAPMESH_V1_POINT_OFF_CAP]);
    assert_eq!(out.count, 1);
    assert!((out.faces[0] as usize) < mesh.n_faces());
    for i in 1..5 {
        assert_eq!(out.faces[i], CAPMESH_V1_NO_FACE);
        assert!(out.positions[3 * i..3 * i + 3].iter().chain(&out.barycentrics[3 * i..3 * i + 3]).all(|x| x.is_nan()));
    }
    // Only the statuses wanted: the other outputs may be NULL.
    let mut located = [9; 5];
    let status = unsafe { capmesh_v1_map_inverse(map, points.as_ptr(), 5, null_mut(), null_mut(), null_mut(), located.as_mut_ptr(), null_mut()) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    assert_eq!(located, out.located.as_slice());
    unsafe { capmesh_v1_map_free(map) };
}

#[test]
fn map_misuse_returns_errors_with_a_message() {
    let mesh = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&mesh);
    let expect = |status: capmesh_v1_status, want: capmesh_v1_status, words: &str| {
        assert_eq!(status, want, "{}", last_error());
        assert!(last_error().contains(words), "'{}' does not say '{words}'", last_error());
    };
    // No place for the handle; NULL mesh; a mesh with an index out of range.
    let status = unsafe { capmesh_v1_parameterize_map(&arrays.view(), null(), None, null_mut(), null_mut(), null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "out_map");
    let mut map = 1usize as *mut capmesh_v1_map;
    let status = unsafe { capmesh_v1_parameterize_map(null(), null(), None, null_mut(), &mut map, null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "mesh");
    assert!(map.is_null(), "the output is reset on failure");
    let mut bad = Arrays::of(&mesh);
    bad.triangles[4] = mesh.n_vertices() as u32;
    let status = unsafe { capmesh_v1_parameterize_map(&bad.view(), null(), None, null_mut(), &mut map, null_mut()) };
    expect(status, CAPMESH_V1_INVALID_MESH, "triangle 1");
    assert!(map.is_null());

    let (map, _) = map_of(&arrays);
    let point = [0.0, 0.0, 1.0];
    let mut located = [0i32; 1];
    let (mut faces, mut weights, mut cap) = ([0u32; 1], [1.0, 0.0, 0.0], [0.0; 3]);
    // NULL handle, NULL points, NULL statuses, an impossible count.
    let status = unsafe { capmesh_v1_map_inverse(null(), point.as_ptr(), 1, null_mut(), null_mut(), null_mut(), located.as_mut_ptr(), null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "map is NULL");
    let status = unsafe { capmesh_v1_map_inverse(map, null(), 1, null_mut(), null_mut(), null_mut(), located.as_mut_ptr(), null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "cap_points is NULL");
    let status = unsafe { capmesh_v1_map_inverse(map, point.as_ptr(), 1, null_mut(), null_mut(), null_mut(), null_mut(), null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "out_located");
    let status = unsafe { capmesh_v1_map_inverse(map, point.as_ptr(), usize::MAX / 2, null_mut(), null_mut(), null_mut(), located.as_mut_ptr(), null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "too large");
    // Nothing to do is not an error.
    let status = unsafe { capmesh_v1_map_inverse(map, null(), 0, null_mut(), null_mut(), null_mut(), null_mut(), null_mut()) };
    expect(status, CAPMESH_V1_OK, "");
    // Forward: a face out of range and weights that are not a point of the face name the point.
    faces[0] = mesh.n_faces() as u32;
    let status = unsafe { capmesh_v1_map_forward(map, faces.as_ptr(), weights.as_ptr(), 1, cap.as_mut_ptr()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "surface point 0: face");
    faces[0] = 0;
    weights = [0.5, 0.7, -0.2];
    let status = unsafe { capmesh_v1_map_forward(map, faces.as_ptr(), weights.as_ptr(), 1, cap.as_mut_ptr()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "barycentric");
    assert_eq!(cap, [0.0; 3], "nothing is written on failure");
    let status = unsafe { capmesh_v1_map_forward(map, faces.as_ptr(), weights.as_ptr(), 1, null_mut()) };
    expect(status, CAPMESH_V1_INVALID_ARGUMENT, "out_cap_points");
    // Accessors and free accept NULL.
    unsafe {
        assert_eq!(capmesh_v1_map_vertex_count(null()), 0);
        assert!(capmesh_v1_map_cap_positions(null()).is_null() && capmesh_v1_map_uv(null()).is_null());
        capmesh_v1_map_free(null_mut());
        capmesh_v1_map_free(map);
    }
}

#[test]
fn remesh_located_gives_each_vertex_its_input_point() {
    let mesh = read("open_meg_helmet_babysquid_mne.obj.gz");
    let arrays = Arrays::of(&mesh);
    let mut options = capmesh_v1_remesh_options_default();
    options.faces = 1500;
    let diag = mesh.bounding_box_diagonal();
    // The largest distance between a remesh vertex and its source point.
    let worst_of = |options: &capmesh_v1_remesh_options| {
        let mut out = null_mut();
        let status = unsafe { capmesh_v1_remesh_located(&arrays.view(), options, None, null_mut(), &mut out, null_mut()) };
        assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
        let nv = unsafe { capmesh_v1_mesh_vertex_count(out) };
        let positions = unsafe { std::slice::from_raw_parts(capmesh_v1_mesh_positions(out), 3 * nv) };
        let faces = unsafe { std::slice::from_raw_parts(capmesh_v1_mesh_source_faces(out), nv) };
        let weights = unsafe { std::slice::from_raw_parts(capmesh_v1_mesh_source_barycentrics(out), 3 * nv) };
        let mut worst = 0.0f64;
        for v in 0..nv {
            let corners = mesh.faces[faces[v] as usize].map(|c| mesh.vertices[c as usize]);
            let w = &weights[3 * v..3 * v + 3];
            assert!(w.iter().all(|&b| b >= 0.0) && (w.iter().sum::<f64>() - 1.0).abs() < 1e-9, "vertex {v}: weights {w:?}");
            for k in 0..3 {
                let want = w[0] * corners[0][k] + w[1] * corners[1][k] + w[2] * corners[2][k];
                worst = worst.max((positions[3 * v + k] - want).abs());
            }
        }
        unsafe { capmesh_v1_mesh_free(out) };
        worst
    };
    // On the surface each vertex is the barycentric combination of its input face's corners;
    // fitted (the default) it is off that point along its normal by a fraction of an edge.
    let fitted = worst_of(&options);
    let mut on_surface = options;
    on_surface.placement = CAPMESH_V1_PLACEMENT_ON_SURFACE;
    let worst = worst_of(&on_surface);
    assert!(worst <= 1e-6 * diag, "a remesh vertex is {worst} from its source point (diagonal {diag})");
    assert!(fitted > worst && fitted <= 0.01 * diag, "a fitted vertex is {fitted} from its source point (diagonal {diag})");

    // The plain remesh records no sources.
    let mut plain = null_mut();
    let status = unsafe { capmesh_v1_remesh(&arrays.view(), &options, None, null_mut(), &mut plain, null_mut()) };
    assert_eq!(status, CAPMESH_V1_OK, "{}", last_error());
    assert!(unsafe { capmesh_v1_mesh_source_faces(plain) }.is_null());
    assert!(unsafe { capmesh_v1_mesh_source_barycentrics(plain) }.is_null());
    unsafe { capmesh_v1_mesh_free(plain) };
}
