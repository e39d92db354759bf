//! A triangulation whose rows collapse onto each other (hippunfold's unfoldiso surfaces: a
//! grid whose first and last rows meet in a curve) stalls the transport: its sites sit within
//! double precision of each other; rows a little farther apart leave the map poor. The
//! parameterization collapses the edges shorter than 5% of the mean edge and maps again, keeps
//! the better map and says so in the report; the remesh of it is as good as of the mesh as
//! given.

use capmesh::io::read_mesh;
use capmesh::mesh::TriMesh;
use capmesh::param::{parameterize, ParamOptions};
use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, RemeshOptions};

mod common;

/// The bundled open `name` with its boundary ring and the ring inside it squeezed onto the
/// next ring: each vertex of ring `r < 2` (edges from the boundary) moved to `gap` times the
/// diagonal from its nearest neighbour in ring `r + 1`, outermost last.
fn squeezed_rim(name: &str, gap: f64) -> TriMesh {
    let mut m = read_mesh(&common::data(name)).unwrap();
    let n = m.vertices.len();
    let diagonal = m.bounding_box_diagonal();
    let mut edges = std::collections::HashMap::new();
    let mut neighbours = vec![Vec::new(); n];
    for f in &m.faces {
        for k in 0..3 {
            let (a, b) = (f[k] as usize, f[(k + 1) % 3] as usize);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            neighbours[a].push(b);
        }
    }
    let mut ring = vec![usize::MAX; n];
    for (&(a, b), &count) in &edges {
        if count == 1 {
            (ring[a], ring[b]) = (0, 0);
        }
    }
    for r in 1..=2 {
        let next: Vec<usize> = (0..n).filter(|&v| ring[v] == usize::MAX && neighbours[v].iter().any(|&u| ring[u] == r - 1)).collect();
        for v in next {
            ring[v] = r;
        }
    }
    let d = |p: [f64; 3], q: [f64; 3]| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
    for r in (0..2).rev() {
        for v in (0..n).filter(|&v| ring[v] == r) {
            let Some(&u) = neighbours[v].iter().filter(|&&u| ring[u] == r + 1).min_by(|&&a, &&b| d(m.vertices[a], m.vertices[v]).total_cmp(&d(m.vertices[b], m.vertices[v]))) else { continue };
            let (p, q) = (m.vertices[v], m.vertices[u]);
            let l = d(p, q);
            m.vertices[v] = std::array::from_fn(|k| q[k] + gap * diagonal * (p[k] - q[k]) / l);
        }
    }
    m
}

fn check(name: &str) {
    let m = squeezed_rim(name, 1e-8);
    let map = parameterize(&m, &ParamOptions::default(), &NoProgress).unwrap();
    let r = &map.report;
    eprintln!("{name} squeezed: {} edges collapsed, mean |d_area| {:.4}, flipped {}", r.collapsed_short_edges, r.area_distortion.mean_abs, r.flipped_faces);
    // Without the collapses the transport stalls (the collapse is tried only then).
    assert!(r.collapsed_short_edges > 0);
    assert_eq!(r.flipped_faces, 0);
    assert!(r.area_distortion.mean_abs < 0.03, "{}", r.area_distortion.mean_abs);
    // Every input vertex has a point of the map, collapsed ones their neighbour's.
    assert_eq!(map.plane.len(), m.vertices.len());
    assert!(map.plane.iter().all(|p| p.iter().all(|x| x.is_finite())));
    let (_, rep) = remesh(&m, &RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 3000 }), &NoProgress).unwrap();
    let q = &rep.quality;
    eprintln!("{name} squeezed, remesh: d_face_rel {:.4}, min angle {:.2}, mean min angle {:.2}", q.d_face_relative, q.min_angle_deg, q.mean_min_angle_deg);
    assert!(rep.param.collapsed_short_edges > 0);
    assert!(q.d_face_relative <= 0.035 && q.min_angle_deg >= 15.0 && q.mean_min_angle_deg >= 48.0, "{q:?}");
}

#[test]
fn a_squeezed_helmet_rim_is_mapped_with_its_short_edges_collapsed() {
    check("open_meg_helmet_babysquid_mne.obj");
}

#[test]
fn a_squeezed_ventricle_rim_is_mapped_with_its_short_edges_collapsed() {
    check("open_lv_endo_rabbit_chaste.obj");
}

/// Squeezed to a millionth of the diagonal, the helmet's rim does not stall the transport but
/// leaves a poor map (mean |d_area| 0.32, its squeezed faces' areas out of reach); collapsed,
/// it maps well.
#[test]
fn a_helmet_rim_squeezed_less_is_collapsed_after_a_poor_map() {
    let m = squeezed_rim("open_meg_helmet_babysquid_mne.obj", 1e-6);
    let map = parameterize(&m, &ParamOptions::default(), &NoProgress).unwrap();
    let r = &map.report;
    eprintln!("helmet squeezed 1e-6: {} edges collapsed, mean |d_area| {:.4}, flipped {}", r.collapsed_short_edges, r.area_distortion.mean_abs, r.flipped_faces);
    assert!(r.collapsed_short_edges > 0);
    assert_eq!(r.quality, capmesh::MapQuality::Good);
    assert!(r.area_distortion.mean_abs < 0.03 && r.flipped_faces == 0, "{r:?}");
}
