//! An input with fewer faces than the remesh is mapped through a midpoint-subdivided copy
//! (docs/method.md section 25): the remesh is better shaped, its surface points name the
//! input's faces, and the input's errors and repairs name its own elements.

mod common;

use capmesh::{read_mesh, remesh, remesh_located, CapGrid, NoProgress, Placement, RemeshOptions, TriMesh};

fn skull() -> TriMesh {
    read_mesh(&common::data("closed_bird_skull_CPallidusA_choi.obj")).unwrap()
}

fn at_5000() -> RemeshOptions {
    RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 5000 })
}

/// The bird skull (4206 faces) at 5000 faces: mapped once subdivided (16824 faces), with fewer
/// faces below 30 degrees and a larger smallest angle than mapped as it is (0.06% and 27.7
/// degrees against 0.37% and 23.3; the area spreads are close, 0.024 and 0.023).
#[test]
fn a_coarse_skull_is_mapped_subdivided_and_remeshed_better_shaped() {
    let mesh = skull();
    assert!(mesh.n_faces() < 5000, "{}", mesh.n_faces());
    assert_eq!(capmesh::remesh::subdivision_levels(mesh.n_faces(), 5000), 1);
    let (_, fine) = remesh(&mesh, &at_5000(), &NoProgress).unwrap();
    let (_, plain) = remesh(&mesh, &at_5000().with_subdivide_coarse(false), &NoProgress).unwrap();
    assert_eq!((fine.subdivided, plain.subdivided), (1, 0));
    assert_eq!((fine.param.n_faces, plain.param.n_faces), (4 * mesh.n_faces(), mesh.n_faces()));
    let (f, p) = (&fine.quality, &plain.quality);
    // Both measured against the input.
    assert_eq!(f.self_intersecting_faces_input, p.self_intersecting_faces_input);
    assert!(f.share_faces_angle_below_30 < p.share_faces_angle_below_30, "below 30 degrees {} vs {}", f.share_faces_angle_below_30, p.share_faces_angle_below_30);
    assert!(f.min_angle_deg > p.min_angle_deg, "smallest angle {} vs {}", f.min_angle_deg, p.min_angle_deg);
    assert!(f.mean_min_angle_deg >= 48.0 && f.d_face_relative <= 0.035 && f.min_angle_deg >= 15.0, "{f:?}");
}

/// Each remesh vertex's surface point names an input face, and its weights there give the
/// vertex (placed on the surface).
#[test]
fn surface_points_of_a_subdivided_map_name_the_input_faces() {
    let mesh = skull();
    let (out, report, points) = remesh_located(&mesh, &at_5000().with_placement(Placement::OnSurface), &NoProgress).unwrap();
    assert_eq!(report.subdivided, 1);
    assert_eq!(points.len(), out.vertices.len());
    let tolerance = 1e-9 * mesh.bounding_box_diagonal();
    for (v, p) in points.iter().enumerate() {
        assert!(p.face < mesh.n_faces(), "vertex {v}: face {}", p.face);
        assert!(p.barycentric.iter().all(|&w| w >= -1e-12) && (p.barycentric.iter().sum::<f64>() - 1.0).abs() < 1e-9, "vertex {v}: {:?}", p.barycentric);
        let corners = mesh.face_points(p.face);
        let x: [f64; 3] = std::array::from_fn(|k| (0..3).map(|i| p.barycentric[i] * corners[i][k]).sum());
        let d = (0..3).map(|k| (x[k] - out.vertices[v][k]).powi(2)).sum::<f64>().sqrt();
        assert!(d < tolerance, "vertex {v}: {d} from its surface point");
    }
}

/// An input error is the input's, with or without the subdivision: a face with an index out
/// of range is named by its own index (subdividing would drop it silently).
#[test]
fn a_coarse_input_error_names_the_input_face() {
    let mut mesh = skull();
    let n = mesh.vertices.len() as u32;
    mesh.faces.push([0, 1, n + 5]);
    let bad = mesh.n_faces() - 1;
    let e = remesh(&mesh, &at_5000(), &NoProgress).unwrap_err().to_string();
    let plain = remesh(&mesh, &at_5000().with_subdivide_coarse(false), &NoProgress).unwrap_err().to_string();
    assert_eq!(e, plain);
    assert!(e.contains(&bad.to_string()), "{e}");
}

/// A face wound against its neighbours in a coarse input is flipped (the repair names the
/// input's face) and the repaired input is mapped subdivided.
#[test]
fn a_coarse_input_with_a_flipped_face_is_repaired_then_subdivided() {
    let mut mesh = skull();
    mesh.faces[10].swap(1, 2);
    let (_, report) = remesh(&mesh, &at_5000(), &NoProgress).unwrap();
    assert_eq!((report.reoriented_faces, report.subdivided), (1, 1));
}
