//! The geometry kernels on nalgebra (issue 30): the principal axis by `SymmetricEigen`, and the
//! vector helpers, angles and Beltrami Jacobian giving the same bits as the hand-written
//! arithmetic they replaced (so `param` and `remesh` write the same bytes), on real meshes.

mod common;

use capmesh::flatten::puncture::principal_axis;
use capmesh::mesh::geometry::{cross, dot, norm, sub, triangle_angles, triangle_area};
use capmesh::metrics::beltrami_abs;
use capmesh::{read_mesh, TriMesh};
use common::{data, Rng};

fn mesh(name: &str) -> TriMesh {
    read_mesh(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The area-weighted covariance the axis diagonalises, written out (vertex area weights).
fn covariance(m: &TriMesh) -> [[f64; 3]; 3] {
    let (mut total, mut c, mut m2) = (0.0, [0.0; 3], [[0.0; 3]; 3]);
    for f in &m.faces {
        let p = f.map(|v| m.vertices[v as usize]);
        let area = triangle_area(p[0], p[1], p[2]);
        let w = area / 3.0;
        total += area;
        for q in p {
            for i in 0..3 {
                c[i] += w * q[i];
                for j in 0..3 {
                    m2[i][j] += w * q[i] * q[j];
                }
            }
        }
    }
    let c = c.map(|x| x / total);
    std::array::from_fn(|i| std::array::from_fn(|j| m2[i][j] / total - c[i] * c[j]))
}

fn times(a: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| dot(a[i], x))
}

/// On real closed and open surfaces the axis is a unit eigenvector of the covariance, of its
/// largest eigenvalue (no direction has a larger Rayleigh quotient), with the sign convention
/// (non-negative `Z`); the centroid is the covariance's.
#[test]
fn principal_axis_is_the_covariance_s_leading_eigenvector() {
    for name in ["closed_brain12k_choi.obj", "closed_bunny_npm.obj", "closed_hippocampus_choi.obj", "open_face_choi.obj"] {
        let m = mesh(name);
        let (_, axis) = principal_axis(&m.vertices, &m.faces);
        let cov = covariance(&m);
        let scale = (0..3).map(|i| cov[i][i].abs()).fold(0.0, f64::max);
        assert!((norm(axis) - 1.0).abs() < 1e-14, "{name}: |axis| = {}", norm(axis));
        assert!(axis[2] >= 0.0, "{name}: axis {axis:?} points down");
        let lambda = dot(axis, times(&cov, axis));
        let residual = sub(times(&cov, axis), axis.map(|x| lambda * x));
        assert!(norm(residual) < 1e-10 * scale, "{name}: |C a - lambda a| = {:e} (scale {scale:e})", norm(residual));
        let mut rng = Rng(7);
        for _ in 0..2000 {
            let d = [0; 3].map(|_| rng.next() as f64 / u64::MAX as f64 - 0.5);
            let d = d.map(|x| x / norm(d));
            assert!(dot(d, times(&cov, d)) <= lambda * (1.0 + 1e-12), "{name}: direction {d:?} has more variance than the axis");
        }
    }
}

/// Rotating a real surface rotates its axis with it (up to the sign convention), to 1e-12.
#[test]
fn principal_axis_turns_with_the_surface() {
    let m = mesh("closed_brain12k_choi.obj");
    let (_, axis) = principal_axis(&m.vertices, &m.faces);
    // A rotation about (1, 2, 2)/3 by 0.7 radians (Rodrigues).
    let k = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    let (s, c) = 0.7f64.sin_cos();
    let rot = |p: [f64; 3]| -> [f64; 3] {
        let kxp = cross(k, p);
        let kp = dot(k, p);
        std::array::from_fn(|i| p[i] * c + kxp[i] * s + k[i] * kp * (1.0 - c))
    };
    let turned: Vec<[f64; 3]> = m.vertices.iter().map(|&p| rot(p)).collect();
    let (_, turned_axis) = principal_axis(&turned, &m.faces);
    let expected = rot(axis);
    let sign = if dot(expected, turned_axis) < 0.0 { -1.0 } else { 1.0 };
    let err = norm(sub(turned_axis, expected.map(|x| sign * x)));
    assert!(err < 1e-12, "rotated axis {turned_axis:?}, expected +-{expected:?} (error {err:e})");
}

/// The helpers and the angles are the same bits as the hand-written arithmetic (left to
/// right sums, the usual cross product), on every face of the 12k brain.
#[test]
fn vector_helpers_give_the_hand_written_bits() {
    let m = mesh("closed_brain12k_choi.obj");
    let hand_sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let hand_dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let hand_cross = |a: [f64; 3], b: [f64; 3]| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let hand_norm = |a: [f64; 3]| hand_dot(a, a).sqrt();
    for f in &m.faces {
        let [a, b, c] = f.map(|v| m.vertices[v as usize]);
        let (u, v) = (hand_sub(b, a), hand_sub(c, a));
        assert_eq!(sub(b, a), u);
        assert_eq!(cross(u, v), hand_cross(u, v));
        assert_eq!(dot(u, v).to_bits(), hand_dot(u, v).to_bits());
        assert_eq!(norm(u).to_bits(), hand_norm(u).to_bits());
        assert_eq!(triangle_area(a, b, c).to_bits(), (0.5 * hand_norm(hand_cross(u, v))).to_bits());
        let corner = |p: [f64; 3], q: [f64; 3], r: [f64; 3]| {
            let (u, v) = (hand_sub(q, p), hand_sub(r, p));
            hand_norm(hand_cross(u, v)).atan2(hand_dot(u, v)).to_bits()
        };
        assert_eq!(triangle_angles(a, b, c).map(f64::to_bits), [corner(a, b, c), corner(b, c, a), corner(c, a, b)]);
    }
}

/// `|mu|` by nalgebra's triangular solve is the same bits as the hand-written back
/// substitution, for every face of the 12k brain mapped to a sheared, bent plane.
#[test]
fn beltrami_gives_the_hand_written_bits() {
    let m = mesh("closed_brain12k_choi.obj");
    let plane = |p: [f64; 3]| [p[0] + 0.3 * p[1] + 0.01 * p[2] * p[2], 0.8 * p[1] - 0.2 * p[2]];
    let mut finite = 0;
    for f in &m.faces {
        let p = f.map(|v| m.vertices[v as usize]);
        let q = p.map(plane);
        let (e1, e2) = (sub(p[1], p[0]), sub(p[2], p[0]));
        let (l1, area2) = (norm(e1), norm(cross(e1, e2)));
        let (x2, y2) = (dot(e2, e1) / l1, area2 / l1);
        let (u1, v1) = (q[1][0] - q[0][0], q[1][1] - q[0][1]);
        let (u2, v2) = (q[2][0] - q[0][0], q[2][1] - q[0][1]);
        let a = u1 / l1;
        let b = (u2 - a * x2) / y2;
        let c = v1 / l1;
        let d = (v2 - c * x2) / y2;
        let fz = ((a + d).powi(2) + (c - b).powi(2)).sqrt();
        let fzb = ((a - d).powi(2) + (c + b).powi(2)).sqrt();
        let mu = beltrami_abs(p, q);
        assert_eq!(mu.to_bits(), (fzb / fz).to_bits(), "face {f:?}: {mu} against {}", fzb / fz);
        finite += mu.is_finite() as usize;
    }
    assert_eq!(finite, m.faces.len());
}
