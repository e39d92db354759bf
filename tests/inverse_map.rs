//! The inverse map as an object ([`capmesh::InverseMap`]): cap points of the input's vertices
//! locate back onto them, random cap points come back on the surface and map forward to
//! themselves, points off the cap are refused.

mod common;

use capmesh::{parameterize, read_mesh, CapMap, NoProgress, ParamOptions, TriMesh};
use common::{data, Rng};

fn mapped(name: &str) -> (TriMesh, CapMap) {
    let mesh = read_mesh(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress).unwrap_or_else(|e| panic!("{name}: {e}"));
    (mesh, map)
}


fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

fn check(name: &str) {
    let (mesh, map) = mapped(name);
    let inverse = map.inverse(&mesh).unwrap();
    let diag = mesh.bounding_box_diagonal();
    let used: Vec<bool> = {
        let mut u = vec![false; mesh.n_vertices()];
        mesh.faces.iter().flatten().for_each(|&v| u[v as usize] = true);
        u
    };
    // Every vertex's cap point (batch form) locates back onto the vertex.
    let located = inverse.locate_all(&map.cap);
    let mut worst = 0.0f64;
    for (v, found) in located.iter().enumerate().filter(|(v, _)| used[*v]) {
        let p = found.unwrap_or_else(|| panic!("{name}: vertex {v}'s cap point {:?} not located", map.cap[v]));
        worst = worst.max(distance(p.position, mesh.vertices[v]));
    }
    assert!(worst <= 1e-9 * diag, "{name}: a vertex located {worst} away (diagonal {diag})");
    // Random points of each face: forward to the cap, back to the same surface point.
    let mut rng = Rng(7);
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let face = rng.below(mesh.n_faces());
        let (a, b) = ((rng.next() >> 11) as f64 / (1u64 << 53) as f64, (rng.next() >> 11) as f64 / (1u64 << 53) as f64);
        let (a, b) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
        let w = [1.0 - a - b, a, b];
        let x = inverse.cap_point(face, w).unwrap();
        let [p, q, r] = mesh.faces[face].map(|v| mesh.vertices[v as usize]);
        let want = [0, 1, 2].map(|k| w[0] * p[k] + w[1] * q[k] + w[2] * r[k]);
        let got = inverse.locate(x).unwrap_or_else(|| panic!("{name}: face {face} {w:?} -> {x:?} not located"));
        worst = worst.max(distance(got.position, want));
    }
    // Folded or near-degenerate planar faces can move a point within its neighbourhood.
    assert!(worst <= 1e-6 * diag, "{name}: forward then inverse moved a point {worst} (diagonal {diag})");
    // Random points of the cap (Z >= Z*) come back on the surface: on one of its faces.
    let z_star = map.report.z_star.unwrap();
    for _ in 0..2000 {
        let z = z_star + (1.0 - z_star) * ((rng.next() >> 11) as f64 / (1u64 << 53) as f64);
        let t = 2.0 * std::f64::consts::PI * ((rng.next() >> 11) as f64 / (1u64 << 53) as f64);
        let s = (1.0 - z * z).max(0.0).sqrt();
        let p = inverse.locate([s * t.cos(), s * t.sin(), z]).unwrap_or_else(|| panic!("{name}: cap point at z {z} not located"));
        let w = p.barycentric;
        assert!(w.iter().all(|&b| b >= 0.0) && (w.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{name}: {w:?}");
        let [a, b, c] = mesh.faces[p.face].map(|v| mesh.vertices[v as usize]);
        let want = [0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]);
        assert!(distance(p.position, want) <= 1e-12 * diag, "{name}: position not on its face");
    }
    // Off the cap: below Z*, off the sphere, not finite.
    let below = (z_star - 1e-3).max(-1.0);
    let s = (1.0 - below * below).sqrt();
    assert_eq!(inverse.locate([s, 0.0, below]), None, "{name}: a point below the cap was located");
    assert_eq!(inverse.locate([0.0, 0.0, 1.01]), None, "{name}: a point off the sphere was located");
    assert_eq!(inverse.locate([0.0, 0.0, 0.5]), None, "{name}: a point inside the sphere was located");
    assert_eq!(inverse.locate([f64::NAN, 0.0, 1.0]), None);
    // A map of another mesh, a face that does not exist, weights that are not a point.
    let other = TriMesh::new(mesh.vertices[..3].to_vec(), vec![[0, 1, 2]]);
    assert!(map.inverse(&other).is_err(), "{name}: a mesh of another size was accepted");
    assert!(inverse.cap_point(mesh.n_faces(), [1.0, 0.0, 0.0]).is_err());
    assert!(inverse.cap_point(0, [0.5, 0.6, -0.1]).is_err());
}

#[test]
fn open_meg_helmet() {
    check("open_meg_helmet_babysquid_mne.obj");
}

#[test]
fn closed_bunny() {
    check("closed_bunny_npm.obj");
}
