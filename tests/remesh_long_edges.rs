//! Inputs with edges much longer than the remesh's (as quadric decimation leaves a long
//! bone's shaft: needles from one end to the other) are mapped with those edges split
//! (`RemeshReport::split_edges`, docs/method.md section 25, "Long edges"): without, the map has
//! no site along the shaft and the remesh there is far from the bars of issue 26.

use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, RemeshOptions};
use capmesh::TriMesh;

/// A capsule along x (shaft radius `r`, from `-half` to `half`, hemispherical ends of `rings`
/// rings and `sectors` sectors) whose shaft is one band of needles: each side quad from one
/// end's rim to the other's split by a diagonal.
fn needle_capsule(r: f64, half: f64, rings: usize, sectors: usize) -> TriMesh {
    let mut vertices = Vec::new();
    let mut faces: Vec<[u32; 3]> = Vec::new();
    // Per end: the pole, then rings from the pole to the rim (the rim last).
    for sign in [-1.0f64, 1.0] {
        vertices.push([sign * (half + r), 0.0, 0.0]);
        for i in 1..=rings {
            let polar = i as f64 / rings as f64 * std::f64::consts::FRAC_PI_2;
            for j in 0..sectors {
                let a = j as f64 / sectors as f64 * std::f64::consts::TAU;
                vertices.push([sign * (half + r * polar.cos()), r * polar.sin() * a.cos(), r * polar.sin() * a.sin()]);
            }
        }
    }
    let per_end = (1 + rings * sectors) as u32;
    let ring = |end: u32, i: usize, j: usize| end * per_end + 1 + ((i - 1) * sectors + j % sectors) as u32;
    for end in 0..2u32 {
        // Outward orientation: the -x end turns the other way round.
        let orient = |f: [u32; 3]| if end == 0 { [f[0], f[2], f[1]] } else { f };
        for j in 0..sectors {
            faces.push(orient([end * per_end, ring(end, 1, j), ring(end, 1, j + 1)]));
            for i in 1..rings {
                let (a, b, c, d) = (ring(end, i, j), ring(end, i, j + 1), ring(end, i + 1, j), ring(end, i + 1, j + 1));
                faces.push(orient([a, c, d]));
                faces.push(orient([a, d, b]));
            }
        }
    }
    for j in 0..sectors {
        let (a, b, c, d) = (ring(0, rings, j), ring(0, rings, j + 1), ring(1, rings, j), ring(1, rings, j + 1));
        faces.push([a, b, d]);
        faces.push([a, d, c]);
    }
    TriMesh::new(vertices, faces)
}

#[test]
fn a_shaft_of_needles_is_split_for_its_map_and_remeshes_near_the_bars() {
    let capsule = needle_capsule(0.5, 6.0, 6, 24);
    let topology = capmesh::mesh::validate(&capsule).expect("a closed genus-0 capsule");
    assert_eq!(topology.0, capmesh::mesh::SurfaceKind::ClosedSphere);
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 2000 });
    let (split_mesh, split) = remesh(&capsule, &options, &NoProgress).unwrap();
    let (_, unsplit) = remesh(&capsule, &options.clone().with_subdivide_coarse(false), &NoProgress).unwrap();
    let (s, u) = (&split.quality, &unsplit.quality);
    eprintln!(
        "split {} edges: d_face_rel {:.4} / {:.4}, mean smallest angle {:.2} / {:.2}, below 30: {:.4} / {:.4}, smallest {:.1} / {:.1}",
        split.split_edges, s.d_face_relative, u.d_face_relative, s.mean_min_angle_deg, u.mean_min_angle_deg, s.share_faces_angle_below_30, u.share_faces_angle_below_30, s.min_angle_deg, u.min_angle_deg
    );
    assert!(split.split_edges > 100 && unsplit.split_edges == 0);
    // The bars of issue 26 (the mean smallest angle, 48.1 here, with half a degree to spare),
    // and far better than the map without the splits (33.4 degrees, 41% of faces below 30).
    assert!(s.d_face_relative <= 0.035 && s.mean_min_angle_deg >= 47.5 && s.share_faces_angle_below_30 <= 0.02 && s.min_angle_deg >= 15.0, "{s:?}");
    assert!(s.d_face_relative < 0.5 * u.d_face_relative && s.mean_min_angle_deg > u.mean_min_angle_deg + 2.0, "{s:?} against {u:?}");
    assert_eq!(s.zero_area_faces, 0);
    assert!(validate(&split_mesh));
}

/// A closed genus-0 mesh.
fn validate(mesh: &TriMesh) -> bool {
    capmesh::mesh::validate(mesh).is_ok_and(|(kind, _)| kind == capmesh::mesh::SurfaceKind::ClosedSphere)
}
