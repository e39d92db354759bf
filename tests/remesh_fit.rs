//! The least-squares vertex placement (`remesh::fit`, docs/method.md section 22): the faces of
//! a fitted remesh follow the input surface closer than the chords of a remesh whose vertices
//! lie on it, at the same faces, areas and angles.

use capmesh::io::read_mesh;
use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, Placement, RemeshOptions};
use capmesh::TriMesh;

mod common;

/// The remesh of `mesh` at `faces` faces, fitted and on the surface.
fn both(mesh: &TriMesh, faces: usize) -> [(TriMesh, capmesh::RemeshReport); 2] {
    [Placement::Fitted, Placement::OnSurface].map(|p| {
        let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces }).with_placement(p);
        remesh(mesh, &options, &NoProgress).unwrap()
    })
}

/// On a sphere the chords lie inside: the fitted vertices move out (their mean radius above
/// the on-surface remesh's), and the mean face-sampled distance falls to well
/// under the chords' (in one dimension a parabola's best line is at 3/8 of the chord's mean
/// distance).
#[test]
fn a_sphere_is_fitted_from_outside() {
    let sphere = capmesh::mesh::shapes::icosphere(5);
    let [(fitted, f), (chords, c)] = both(&sphere, 800);
    let radius = |m: &TriMesh| m.vertices.iter().map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()).collect::<Vec<f64>>();
    let (rf, rc) = (radius(&fitted), radius(&chords));
    let mean = |r: &[f64]| r.iter().sum::<f64>() / r.len() as f64;
    eprintln!("radius: fitted mean {:.5}, on the surface {:.5}; d_surf {:.3e} vs {:.3e}", mean(&rf), mean(&rc), f.quality.d_surface_sampled_relative, c.quality.d_surface_sampled_relative);
    assert!(mean(&rf) > mean(&rc), "the fitted vertices did not move out");
    let ratio = f.quality.d_surface_sampled_relative / c.quality.d_surface_sampled_relative;
    assert!(ratio < 0.6, "d_surf fitted / on the surface = {ratio}");
    assert!(f.fit.fitted && !c.fit.fitted && f.fit.rms_after < 0.6 * f.fit.rms_before, "{:?}", f.fit);
    assert!(c.quality.d_surface_vertex_relative < 1e-9 && f.quality.d_surface_vertex_relative > 0.0);
}

/// On a closed and an open anatomical surface: at least a third off the sampled distance,
/// the areas and angles within the bars of issue 26, no crossing face, the open one's boundary
/// on the input's.
#[test]
fn anatomical_surfaces_are_fitted_closer() {
    for name in ["closed_hippocampus_choi.obj.gz", "open_lv_endo_rabbit_chaste.obj.gz"] {
        let mesh = read_mesh(&common::data(name)).unwrap();
        let [(fitted, f), (_, c)] = both(&mesh, 3000);
        let (qf, qc) = (&f.quality, &c.quality);
        eprintln!("{name}: d_surf {:.3e} vs {:.3e}, d_face {:.4} vs {:.4}, mean smallest angle {:.2} vs {:.2}", qf.d_surface_sampled_relative, qc.d_surface_sampled_relative, qf.d_face_relative, qc.d_face_relative, qf.mean_min_angle_deg, qc.mean_min_angle_deg);
        assert!(qf.d_surface_sampled_relative < 0.67 * qc.d_surface_sampled_relative, "{name}");
        assert!(qf.hausdorff_distance_relative <= 1.05 * qc.hausdorff_distance_relative, "{name}");
        assert!(qf.d_face_relative <= 0.035 && qf.mean_min_angle_deg >= 48.0 && qf.min_angle_deg >= 15.0, "{name}: {qf:?}");
        assert_eq!(qf.self_intersecting_faces, 0, "{name}");
        assert_eq!(qf.zero_area_faces, 0, "{name}");
        assert_eq!((qf.faces, qf.vertices), (qc.faces, qc.vertices), "{name}: the fit changes no connectivity");
        // An open remesh's boundary stays on the input's boundary.
        let distance = capmesh::metrics::closest::SurfaceDistance::new(&mesh);
        let boundary = capmesh::mesh::topology::is_boundary_vertex(&fitted);
        let off = fitted.vertices.iter().zip(&boundary).filter(|(_, &b)| b).map(|(&p, _)| distance.distance(p)).fold(0.0, f64::max);
        assert!(off <= 1e-9 * mesh.bounding_box_diagonal(), "{name}: a boundary vertex {off} off the input");
        assert_eq!(boundary.iter().any(|&b| b), name.starts_with("open"), "{name}");
    }
}

/// A remesh sized by covered areas (`--sizing curvature`) is fitted without keeping its chord
/// areas, which are not what it equalizes (docs/method.md section 22, "Sized remeshes"): on
/// the 12k brain the fit takes more than 30% off the on-surface remesh's sampled distance
/// (about 24% while the fit kept the chord areas), at the sized remesh's angle bars.
#[test]
fn a_sized_remesh_is_fitted_with_its_chord_areas_free() {
    let mesh = read_mesh(&common::data("closed_brain12k_choi.obj.gz")).unwrap();
    let [(_, f), (_, c)] = [Placement::Fitted, Placement::OnSurface].map(|p| {
        let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 5000 }).with_placement(p);
        let options = options.clone().with_shape(options.shape.with_sizing(capmesh::Sizing::Curvature { strength: 3.0 }));
        remesh(&mesh, &options, &NoProgress).unwrap()
    });
    let (qf, qc) = (&f.quality, &c.quality);
    let ratio = qf.d_surface_sampled_relative / qc.d_surface_sampled_relative;
    eprintln!("d_surf {:.3e} vs {:.3e} ({ratio:.3}), d_face {:.4} vs {:.4}, mean smallest angle {:.2}", qf.d_surface_sampled_relative, qc.d_surface_sampled_relative, qf.d_face_relative, qc.d_face_relative, qf.mean_min_angle_deg);
    assert!(ratio < 0.7, "d_surf fitted / on the surface = {ratio}");
    assert!(qf.mean_min_angle_deg >= 46.0 && qf.min_angle_deg >= 15.0 && qf.share_faces_angle_below_30 <= 0.02, "{qf:?}");
    assert_eq!((qf.self_intersecting_faces, qf.zero_area_faces), (0, 0));
}
