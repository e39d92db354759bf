//! `--sizing surface` (`Sizing::Surface`): faces measured by the surface they cover rather
//! than by their chords, so that a remesh coarser than the surface's folds keeps its vertices
//! in them; `--sizing curvature` (`Sizing::Curvature`): besides, smaller faces where the
//! surface is curved at the same face count (docs/method.md section 19).

use capmesh::io::read_mesh;
use capmesh::metrics::angles::angle_quality;
use capmesh::mesh::TriMesh;
use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, Placement, RemeshOptions};
use capmesh::Creases;

mod common;

fn load(name: &str) -> TriMesh {
    read_mesh(&common::data(name)).unwrap()
}

/// The uniform remesh's report, and the remesh and report with `sizing`, of `name` at 5000
/// faces with the vertices on the surface.
fn uniform_and_sized(name: &str, sizing: &str) -> (capmesh::remesh::RemeshReport, TriMesh, capmesh::remesh::RemeshReport) {
    let mesh = load(name);
    let options = RemeshOptions::default().with_placement(Placement::OnSurface).with_grid(CapGrid::Uniform { faces: 5000 });
    let (_, uniform) = remesh(&mesh, &options, &NoProgress).unwrap();
    let sized_options = options.clone().with_shape(options.shape.with_sizing(sizing.parse().unwrap()));
    let (sized, rep) = remesh(&mesh, &sized_options, &NoProgress).unwrap();
    (uniform, sized, rep)
}

/// `--sizing curvature` on the face (a nose, lips and eyes on a gently curved sheet): at the
/// same face count the faces shrink where the surface is curved, so their areas spread
/// (d_face_rel grows) and the sampled distance to the input falls.
#[test]
fn curvature_sizing_follows_the_surface_closer() {
    let (uniform, sized, rep) = uniform_and_sized("open_face_choi.obj.gz", "curvature");
    let (u, s) = (&uniform.quality, &rep.quality);
    eprintln!("uniform: d_surf {:.3e}, d_face_rel {:.4}; curvature: {:.3e}, {:.4}", u.d_surface_sampled_relative, u.d_face_relative, s.d_surface_sampled_relative, s.d_face_relative);
    assert!(s.d_surface_sampled_relative < 0.85 * u.d_surface_sampled_relative);
    assert!(s.d_face_relative > 2.0 * u.d_face_relative, "the areas should follow the curvature");
    assert!((s.faces as f64 - u.faces as f64).abs() <= 0.1 * u.faces as f64, "{} vs {} faces", s.faces, u.faces);
    assert!(s.d_surface_vertex_relative < 1e-9 && s.zero_area_faces == 0);
    let a = angle_quality(&sized);
    assert!(a.share_below_30 <= 0.02 && a.mean_min_angle_deg >= 45.0, "{a:?}");
}

/// The 12k brain at 5000 faces is coarser than its sulci: a face across a sulcus has a chord
/// far smaller than the surface it covers. Sized by covered areas the remesh keeps its
/// vertices in the sulci and lies closer to the input than the uniform remesh, whose chord
/// areas are equal (with chord areas the sized remesh came out farther: 3.33e-3 of the
/// diagonal against the uniform 3.27e-3). Its angles stay at the sized remesh's bar.
#[test]
fn a_sized_remesh_keeps_its_vertices_in_the_folds() {
    let (uniform, sized, rep) = uniform_and_sized("closed_brain12k_choi.obj.gz", "curvature");
    let (u, s) = (&uniform.quality, &rep.quality);
    eprintln!("uniform: d_surf {:.3e}; curvature: {:.3e}, mean smallest angle {:.2}", u.d_surface_sampled_relative, s.d_surface_sampled_relative, s.mean_min_angle_deg);
    assert!(s.d_surface_sampled_relative < 0.8 * u.d_surface_sampled_relative, "{:.3e} vs {:.3e}", s.d_surface_sampled_relative, u.d_surface_sampled_relative);
    assert!((s.faces as f64 - u.faces as f64).abs() <= 0.1 * u.faces as f64, "{} vs {} faces", s.faces, u.faces);
    assert_eq!(s.self_intersecting_faces, 0);
    let a = angle_quality(&sized);
    assert!(a.share_below_30 <= 0.02 && a.mean_min_angle_deg >= 46.0, "{a:?}");
}

/// The decimated lung lobe has thin sharp edges where its fissures cut it: a uniform remesh's
/// faces across such an edge have chords far smaller than the surface they cover, equal chord
/// areas pull the vertices off the edge and the remesh cuts it. Equal covered areas
/// (`--sizing surface`) keep them there: the remesh lies closer to the input (measured 5.27e-4
/// -> 3.79e-4 of the diagonal), its chord areas are less equal, its angles at the sized bar.
#[test]
fn a_surface_sized_remesh_keeps_its_vertices_on_thin_edges() {
    let (uniform, sized, rep) = uniform_and_sized("closed_lung_rml_chaste_decimated.obj.gz", "surface");
    let (u, s) = (&uniform.quality, &rep.quality);
    eprintln!("uniform: d_surf {:.3e}, d_face_rel {:.4}; surface: {:.3e}, {:.4}", u.d_surface_sampled_relative, u.d_face_relative, s.d_surface_sampled_relative, s.d_face_relative);
    assert_eq!(rep.shape.sizing.to_string(), "surface");
    assert!(s.d_surface_sampled_relative < 0.85 * u.d_surface_sampled_relative, "{:.3e} vs {:.3e}", s.d_surface_sampled_relative, u.d_surface_sampled_relative);
    assert!(s.d_face_relative > u.d_face_relative, "chord areas: {} vs {}", s.d_face_relative, u.d_face_relative);
    assert!((s.faces as f64 - u.faces as f64).abs() <= 0.1 * u.faces as f64, "{} vs {} faces", s.faces, u.faces);
    assert!(s.d_surface_vertex_relative < 1e-9 && s.zero_area_faces == 0);
    assert_eq!(s.self_intersecting_faces, 0);
    let a = angle_quality(&sized);
    assert!(a.share_below_30 <= 0.02 && a.mean_min_angle_deg >= 46.0, "{a:?}");
}

/// `--sizing curvature` keeps the input's creases by default (`Creases::Auto`): on the lung
/// lobe, whose fissures cut it with sharp edges, vertices go onto them and the remesh lies
/// closer to the input than with `--creases off` (measured 2.06e-4 -> 1.69e-4 of the diagonal
/// at 5000 faces), its angles at the creased sized bar of 45 degrees.
#[test]
fn curvature_sizing_keeps_creases_by_default() {
    let mesh = load("closed_lung_rml_chaste.obj.gz");
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 5000 });
    let curvature = options.shape.with_sizing("curvature".parse().unwrap());
    let (kept, auto) = remesh(&mesh, &options.clone().with_shape(curvature), &NoProgress).unwrap();
    let (_, off) = remesh(&mesh, &options.clone().with_shape(curvature.with_creases(Creases::Off)), &NoProgress).unwrap();
    let (a, o) = (&auto.quality, &off.quality);
    eprintln!("creases off: d_surf {:.3e}; auto: {:.3e}, {:?}", o.d_surface_sampled_relative, a.d_surface_sampled_relative, auto.shape);
    assert!(auto.shape.keep_creases && auto.shape.crease_bound_deg == 60.0 && auto.shape.crease_vertices >= 50, "{:?}", auto.shape);
    assert!(!off.shape.keep_creases && off.shape.crease_vertices == 0, "{:?}", off.shape);
    assert!(a.d_surface_sampled_relative < 0.9 * o.d_surface_sampled_relative, "{:.3e} vs {:.3e}", a.d_surface_sampled_relative, o.d_surface_sampled_relative);
    assert_eq!(a.self_intersecting_faces, 0);
    assert_eq!(a.zero_area_faces, 0);
    let q = angle_quality(&kept);
    assert!(q.share_below_30 <= 0.02 && q.mean_min_angle_deg >= 45.0 && q.min_angle_deg >= 15.0, "{q:?}");
    // The uniform remesh does not keep them unless asked.
    assert!(!options.shape.keeps_creases() && options.shape.crease_deg == 60.0);
    assert!(options.shape.with_creases(Creases::Keep).keeps_creases());
}
