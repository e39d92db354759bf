//! Procedural shapes, topology helpers and welding.

use capmesh::mesh::geometry::{
    cross, dot, norm, signed_area_2d, sub, triangle_angles, triangle_area,
};
use capmesh::mesh::repair::{remove_unreferenced, weld_coincident, zero_area_faces, REMOVED};
use capmesh::mesh::shapes::{
    annulus, geodesic_sphere, grid_disk, icosphere, spherical_cap, spherical_cap_sectors, torus, uv_sphere,
};
use capmesh::mesh::topology::{edge_faces, is_boundary_vertex, vertex_neighbors};
use capmesh::mesh::{inspect, validate, SurfaceKind, Topology, TriMesh};

fn signed_volume(m: &TriMesh) -> f64 {
    (0..m.n_faces())
        .map(|f| {
            let [a, b, c] = m.face_points(f);
            dot(a, cross(b, c)) / 6.0
        })
        .sum()
}

fn all_outward(m: &TriMesh) -> bool {
    (0..m.n_faces()).all(|f| {
        let [a, b, c] = m.face_points(f);
        let centroid = [
            (a[0] + b[0] + c[0]) / 3.0,
            (a[1] + b[1] + c[1]) / 3.0,
            (a[2] + b[2] + c[2]) / 3.0,
        ];
        dot(cross(sub(b, a), sub(c, a)), centroid) > 0.0
    })
}

fn all_ccw_in_plane(m: &TriMesh) -> bool {
    (0..m.n_faces()).all(|f| {
        let [a, b, c] = m.face_points(f);
        signed_area_2d([a[0], a[1]], [b[0], b[1]], [c[0], c[1]]) > 0.0
    })
}

fn loop_signed_area(m: &TriMesh, lp: &[u32]) -> f64 {
    let mut s = 0.0;
    for i in 0..lp.len() {
        let p = m.vertices[lp[i] as usize];
        let q = m.vertices[lp[(i + 1) % lp.len()] as usize];
        s += p[0] * q[1] - q[0] * p[1];
    }
    s / 2.0
}

fn min_angle_deg(m: &TriMesh) -> f64 {
    (0..m.n_faces())
        .flat_map(|f| {
            let [a, b, c] = m.face_points(f);
            triangle_angles(a, b, c)
        })
        .fold(f64::INFINITY, f64::min)
        .to_degrees()
}

fn area_ratio(m: &TriMesh) -> f64 {
    let areas: Vec<f64> = (0..m.n_faces())
        .map(|f| {
            let [a, b, c] = m.face_points(f);
            triangle_area(a, b, c)
        })
        .collect();
    let max = areas.iter().cloned().fold(0.0, f64::max);
    let min = areas.iter().cloned().fold(f64::INFINITY, f64::min);
    max / min
}

#[test]
fn spherical_cap_is_a_uniform_outward_disk() {
    for &z0 in &[0.9, 0.3, 0.0, -0.5, -0.95] {
        for &rings in &[1usize, 4, 16, 40] {
            let m = spherical_cap(z0, rings, spherical_cap_sectors(z0, rings));
            let (kind, topo) =
                validate(&m).unwrap_or_else(|e| panic!("z0={z0} rings={rings}: {e}"));
            assert_eq!(kind, SurfaceKind::OpenDisk);
            assert!(all_outward(&m), "z0={z0} rings={rings}");
            for p in &m.vertices {
                assert!((norm(*p) - 1.0).abs() < 1e-12);
                assert!(p[2] >= z0);
            }
            let lp = &topo.boundary_loops[0];
            assert!(
                lp.iter().all(|&v| m.vertices[v as usize][2] == z0),
                "boundary exactly at z0"
            );
            assert!(loop_signed_area(&m, lp) > 0.0, "boundary counter-clockwise");
            let area: f64 = (0..m.n_faces())
                .map(|f| {
                    let [a, b, c] = m.face_points(f);
                    triangle_area(a, b, c)
                })
                .sum();
            let exact = std::f64::consts::TAU * (1.0 - z0);
            if rings >= 16 {
                assert!(
                    (area - exact).abs() / exact < 0.01,
                    "area {area} vs {exact}"
                );
                assert!(
                    min_angle_deg(&m) > 30.0,
                    "z0={z0} rings={rings}: min angle {}",
                    min_angle_deg(&m)
                );
                assert!(
                    area_ratio(&m) < 3.0,
                    "z0={z0} rings={rings}: area ratio {}",
                    area_ratio(&m)
                );
            }
            assert_eq!(inspect(&m).unwrap().zero_area_faces, 0);
        }
    }
}

#[test]
fn spherical_cap_clamps_parameters() {
    for &(z0, r, s) in &[
        (f64::NAN, 0, 0),
        (1.0, 1, 1),
        (-1.0, 3, 3),
        (2.0, 0, 100),
        (-7.0, 5, 5),
    ] {
        let m = spherical_cap(z0, r, s);
        assert_eq!(
            validate(&m).unwrap().0,
            SurfaceKind::OpenDisk,
            "{z0} {r} {s}"
        );
    }
}

#[test]
fn closed_spheres() {
    for m in [
        uv_sphere(2, 3),
        uv_sphere(12, 24),
        icosphere(0),
        icosphere(3),
    ] {
        let (kind, topo) = validate(&m).unwrap();
        assert_eq!(kind, SurfaceKind::ClosedSphere);
        assert_eq!(topo.euler_characteristic, 2);
        assert!(all_outward(&m));
        assert!(signed_volume(&m) > 0.0);
    }
    let ico = icosphere(3);
    assert_eq!(ico.n_faces(), 20 * 64);
    assert!((signed_volume(&ico) - 4.0 / 3.0 * std::f64::consts::PI).abs() < 0.05);
    assert!(min_angle_deg(&ico) > 45.0);
}

#[test]
fn geodesic_spheres_have_any_frequency() {
    for f in [1, 2, 3, 7, 12] {
        let m = geodesic_sphere(f);
        assert_eq!(m.n_vertices(), 10 * f * f + 2, "f = {f}");
        assert_eq!(m.n_faces(), 20 * f * f, "f = {f}");
        let (kind, topo) = validate(&m).unwrap_or_else(|e| panic!("f = {f}: {e}"));
        assert_eq!(kind, SurfaceKind::ClosedSphere);
        assert_eq!(topo.euler_characteristic, 2);
        assert!(all_outward(&m), "f = {f}");
        assert!(m.vertices.iter().all(|&p| (dot(p, p) - 1.0).abs() < 1e-12));
        assert!(min_angle_deg(&m) > 40.0, "f = {f}: {}", min_angle_deg(&m));
    }
    // Frequency 1 is the icosahedron; frequency 2 the icosphere of one subdivision.
    let key = |m: &TriMesh| {
        let mut k: Vec<[i64; 3]> = m.vertices.iter().map(|p| p.map(|x| (x * 1e9).round() as i64)).collect();
        k.sort_unstable();
        k
    };
    assert_eq!(key(&geodesic_sphere(1)), key(&icosphere(0)));
    assert_eq!(key(&geodesic_sphere(2)), key(&icosphere(1)));
    let g = geodesic_sphere(12);
    assert!((signed_volume(&g) - 4.0 / 3.0 * std::f64::consts::PI).abs() < 0.05);
}

#[test]
fn grid_disk_is_a_ccw_unit_disk() {
    for n in [1, 2, 10] {
        let m = grid_disk(n);
        let (kind, topo) = validate(&m).unwrap();
        assert_eq!(kind, SurfaceKind::OpenDisk);
        assert!(all_ccw_in_plane(&m));
        assert!(loop_signed_area(&m, &topo.boundary_loops[0]) > 0.0);
        assert!(min_angle_deg(&m) > 40.0, "n={n}: {}", min_angle_deg(&m));
    }
    let m = grid_disk(20);
    let area: f64 = (0..m.n_faces())
        .map(|f| {
            let [a, b, c] = m.face_points(f);
            triangle_area(a, b, c)
        })
        .sum();
    assert!((area - std::f64::consts::PI).abs() < 0.02);
}

#[test]
fn annulus_has_two_loops_and_torus_genus_one() {
    let a = annulus(0.5, 1.0, 3, 24);
    let s = inspect(&a).unwrap();
    assert_eq!(
        (s.boundary_loops, s.euler_characteristic, s.genus, s.kind),
        (2, 0, Some(0), None)
    );
    assert!(all_ccw_in_plane(&a));
    let topo = Topology::build(&a).unwrap();
    let mut areas: Vec<f64> = topo
        .boundary_loops
        .iter()
        .map(|l| loop_signed_area(&a, l))
        .collect();
    areas.sort_by(f64::total_cmp);
    assert!(
        areas[0] < 0.0 && areas[1] > 0.0,
        "inner loop clockwise, outer counter-clockwise"
    );

    let t = torus(2.0, 0.5, 24, 12);
    let s = inspect(&t).unwrap();
    assert_eq!(
        (s.boundary_loops, s.euler_characteristic, s.genus, s.kind),
        (0, 0, Some(1), None)
    );
    assert!(signed_volume(&t) > 0.0);
    let exact = 2.0 * std::f64::consts::PI.powi(2) * 2.0 * 0.25;
    assert!((signed_volume(&t) - exact).abs() / exact < 0.1);
}

#[test]
fn boundary_loop_follows_face_direction() {
    let m = TriMesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[1, 2, 0]],
    );
    let topo = Topology::build(&m).unwrap();
    assert_eq!(topo.boundary_loops, vec![vec![0, 1, 2]]);
    assert_eq!(topo.genus(), Some(0));
    let mut flipped = m.clone();
    flipped.flip_orientation();
    assert_eq!(
        Topology::build(&flipped).unwrap().boundary_loops,
        vec![vec![0, 2, 1]]
    );
}

#[test]
fn adjacency_helpers() {
    let m = grid_disk(3);
    let nb = vertex_neighbors(&m);
    assert_eq!(nb[0], (1..=6).collect::<Vec<u32>>());
    for (v, list) in nb.iter().enumerate() {
        for &w in list {
            assert!(nb[w as usize].contains(&(v as u32)));
        }
    }
    let mask = is_boundary_vertex(&m);
    let topo = Topology::build(&m).unwrap();
    let on_loop: Vec<bool> = (0..m.n_vertices() as u32)
        .map(|v| topo.boundary_loops[0].contains(&v))
        .collect();
    assert_eq!(mask, on_loop);
    assert_eq!(mask.iter().filter(|&&b| b).count(), 18);

    let edges = edge_faces(&m).unwrap();
    assert_eq!(edges.len(), topo.n_edges);
    assert_eq!(edges.iter().filter(|e| e.is_boundary()).count(), 18);
    for e in &edges {
        assert!(e.a < e.b);
        if let Some(f) = e.left {
            let face = m.faces[f as usize];
            assert!((0..3).any(|k| face[k] == e.a && face[(k + 1) % 3] == e.b));
        }
        if let Some(f) = e.right {
            let face = m.faces[f as usize];
            assert!((0..3).any(|k| face[k] == e.b && face[(k + 1) % 3] == e.a));
        }
    }
    let ico = icosphere(2);
    let edges = edge_faces(&ico).unwrap();
    assert_eq!(edges.len(), 3 * ico.n_faces() / 2);
    assert!(edges.iter().all(|e| !e.is_boundary()));
}

/// Every face gets its own three vertices.
fn soup(m: &TriMesh) -> TriMesh {
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for f in &m.faces {
        let base = vertices.len() as u32;
        for &v in f {
            vertices.push(m.vertices[v as usize]);
        }
        faces.push([base, base + 1, base + 2]);
    }
    TriMesh::new(vertices, faces)
}

#[test]
fn weld_restores_a_triangle_soup() {
    let ico = icosphere(3);
    let s = soup(&ico);
    for tol in [0.0, 1e-12, 1e-6] {
        let w = weld_coincident(&s, tol);
        assert_eq!(w.mesh.n_vertices(), ico.n_vertices(), "tol {tol}");
        assert_eq!(w.mesh.n_faces(), ico.n_faces());
        assert_eq!(w.merged_vertices, s.n_vertices() - ico.n_vertices());
        assert_eq!((w.removed_faces, w.removed_unreferenced), (0, 0));
        assert_eq!(validate(&w.mesh).unwrap().0, SurfaceKind::ClosedSphere);
        for (v, &n) in w.old_to_new.iter().enumerate() {
            assert_eq!(w.mesh.vertices[n as usize], s.vertices[v]);
        }
    }
    // Perturbed copies merge within tolerance, not below it.
    let mut jitter = s.clone();
    for (i, p) in jitter.vertices.iter_mut().enumerate() {
        p[0] += (i % 7) as f64 * 1e-11;
    }
    assert_eq!(
        weld_coincident(&jitter, 1e-9).mesh.n_vertices(),
        ico.n_vertices()
    );
    assert!(weld_coincident(&jitter, 1e-13).mesh.n_vertices() > ico.n_vertices());
}

#[test]
fn weld_drops_degenerate_faces_and_unreferenced_vertices() {
    // A quad split in two, vertex 4 duplicates vertex 2, vertex 5 is unused, a sliver face
    // (1, 2, 4) becomes degenerate.
    let m = TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [5.0, 5.0, 5.0],
        ],
        vec![[0, 1, 2], [1, 4, 2], [0, 4, 3]],
    );
    let w = weld_coincident(&m, 1e-9);
    assert_eq!(w.mesh.faces, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(
        (w.merged_vertices, w.removed_faces, w.removed_unreferenced),
        (1, 1, 1)
    );
    assert_eq!(w.old_to_new, vec![0, 1, 2, 3, 2, REMOVED]);
    let r = remove_unreferenced(&m);
    assert_eq!(r.mesh.n_vertices(), 5);
    assert_eq!(r.mesh.faces, m.faces);
    assert_eq!(r.old_to_new[5], REMOVED);
}

#[test]
fn weld_handles_hostile_input() {
    let m = TriMesh::new(
        vec![
            [f64::NAN, 0.0, 0.0],
            [f64::INFINITY, 1.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            [-0.0, 0.0, 0.0],
            [1e308, -1e308, 0.0],
        ],
        vec![[0, 1, 2], [2, 3, 4], [7, 8, 9], [3, 4, 5]],
    );
    for tol in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300, 1.0, 1e300] {
        let w = weld_coincident(&m, tol);
        assert!(w
            .mesh
            .faces
            .iter()
            .flatten()
            .all(|&v| (v as usize) < w.mesh.n_vertices()));
    }
    // A million copies of one point are cheap.
    let many = TriMesh::new(vec![[1.0, 2.0, 3.0]; 1_000_000], vec![[0, 1, 2]]);
    let w = weld_coincident(&many, 1e-6);
    assert_eq!((w.mesh.n_vertices(), w.mesh.n_faces()), (0, 0));
    assert_eq!(zero_area_faces(&m, 1e-12), vec![0, 1, 3]);
}

