//! Joint area and shape polish of the relaxed remesh (ours; see [`super`]).
//!
//! Each free vertex takes a damped Gauss-Newton step on the sum over its faces of
//! `ln(A / A_target)^2 + mu ln(L / (4 sqrt(3) A))^2`, where `A` is a face's surface area and
//! `L` the sum of its squared edge lengths: the first term is the area equalization's, the
//! second is zero exactly for an equilateral triangle. The step is taken in the map's plane
//! through the one-ring's Jacobian fit ([`super::smooth::ring_jacobian`]) and lifted back
//! through the inverse map; it is halved until the local sum falls with every incident face
//! valid in the plane and on the surface.

use super::covered::Covered;
use super::smooth::{ring_faces_same_side, ring_jacobian, ring_valid_in_plane};
use super::state::{Incidence, Shaping, SurfaceLift};
use crate::mesh::geometry::{cross, dot, ln_triangle_area_gradient, norm, sub};
use nalgebra::{Matrix2, Vector2, Vector3};

/// Halvings of a step before the vertex stays.
const HALVINGS: usize = 6;

/// `4 sqrt(3)`: `L / A` of an equilateral triangle.
const EQUILATERAL: f64 = 6.928203230275509;

/// The residuals of one face `(x, a, b)` (corner `x` moving): area and shape, and their
/// gradients with respect to `x`. `None` for a face without area.
fn residuals(x: [f64; 3], a: [f64; 3], b: [f64; 3], ln_target: f64, sqrt_mu: f64) -> Option<([f64; 2], [[f64; 3]; 2])> {
    let r = residual_values(x, a, b, ln_target, sqrt_mu)?;
    let (ea, eb, ab) = (sub(x, a), sub(x, b), sub(a, b));
    let l = dot(ea, ea) + dot(eb, eb) + dot(ab, ab);
    // grad ln A = n x (b - a) / |n|^2; grad ln L = 2 ((x - a) + (x - b)) / L.
    let g_area = ln_triangle_area_gradient(x, a, b);
    let g_len: [f64; 3] = std::array::from_fn(|k| 2.0 * (ea[k] + eb[k]) / l);
    let g_shape: [f64; 3] = std::array::from_fn(|k| sqrt_mu * (g_len[k] - g_area[k]));
    Some((r, [g_area, g_shape]))
}

/// The residuals of [`residuals`] without their gradients (the trial steps need only the
/// energy).
fn residual_values(x: [f64; 3], a: [f64; 3], b: [f64; 3], ln_target: f64, sqrt_mu: f64) -> Option<[f64; 2]> {
    let n = cross(sub(a, x), sub(b, x));
    let nn = dot(n, n);
    if !(nn > 0.0) {
        return None;
    }
    let area = 0.5 * nn.sqrt();
    let (ea, eb, ab) = (sub(x, a), sub(x, b), sub(a, b));
    let l = dot(ea, ea) + dot(eb, eb) + dot(ab, ab);
    Some([area.ln() - ln_target, sqrt_mu * (l / (EQUILATERAL * area)).ln()])
}

/// The local energy of vertex `v` at surface point `x` (planar point `q`); with `covered`
/// the area residual of each face with a planar point at every corner is its covered area's.
#[allow(clippy::too_many_arguments)]
fn local_energy(mesh: &Shaping, ring: &[u32], v: usize, x: [f64; 3], q: [f64; 2], covered: Option<&Covered>, ln_target: &dyn Fn(usize) -> f64, sqrt_mu: f64) -> Option<f64> {
    let mut e = 0.0;
    for &t in ring {
        let (a, b) = others(mesh, t, v);
        let mut r = residual_values(x, a, b, ln_target(t as usize), sqrt_mu)?;
        if let Some((ln_area, _)) = covered_residual(mesh, covered, t, v, q) {
            r[0] = ln_area - ln_target(t as usize);
        }
        e += r[0] * r[0] + r[1] * r[1];
    }
    Some(e)
}

/// `ln` of the covered area of face `t` with `v` at planar point `q`, and its gradient with
/// respect to `q` (`None` without `covered`, or when a corner has no planar point).
fn covered_residual(mesh: &Shaping, covered: Option<&Covered>, t: u32, v: usize, q: [f64; 2]) -> Option<(f64, [f64; 2])> {
    let covered = covered?;
    let f = mesh.faces[t as usize];
    if !f.iter().all(|&u| mesh.planar(u)) {
        return None;
    }
    let k = f.iter().position(|&u| u as usize == v)?;
    covered.ln_area_and_gradient(q, mesh.plane[f[(k + 1) % 3] as usize], mesh.plane[f[(k + 2) % 3] as usize])
}

/// The other two corners of face `t`, in the face's order after `v`.
fn others(mesh: &Shaping, t: u32, v: usize) -> ([f64; 3], [f64; 3]) {
    let f = mesh.faces[t as usize];
    let k = f.iter().position(|&u| u as usize == v).unwrap_or(0);
    (mesh.position[f[(k + 1) % 3] as usize], mesh.position[f[(k + 2) % 3] as usize])
}

/// The polished position of free vertex `v`: planar point, surface point and hint, or
/// `None` when no step lowers its energy. `ln_target(t)` is `ln` of face `t`'s target area;
/// `mu` weighs the shape term; with `covered` the area term is of the surface areas the
/// faces cover ([`Covered`]) instead of their chord areas.
pub(crate) fn polish_vertex(mesh: &Shaping, incidence: &Incidence, v: usize, lift: &SurfaceLift, ln_target: &dyn Fn(usize) -> f64, mu: f64, covered: Option<&Covered>) -> Option<([f64; 2], [f64; 3], u32)> {
    let ring = incidence.of(v);
    if ring.is_empty() {
        return None;
    }
    let sqrt_mu = mu.max(0.0).sqrt();
    let x0 = mesh.position[v];
    let j = ring_jacobian(mesh, ring, v)?;
    // Gauss-Newton on the planar position: residual gradients g = J^T grad.
    let (mut h, mut g, mut e0) = (Matrix2::zeros(), Vector2::zeros(), 0.0);
    for &t in ring {
        let (a, b) = others(mesh, t, v);
        let (mut r, grad) = residuals(x0, a, b, ln_target(t as usize), sqrt_mu)?;
        // The covered area's gradient is planar already.
        let planar_area = covered_residual(mesh, covered, t, v, mesh.plane[v]);
        if let Some((ln_area, _)) = planar_area {
            r[0] = ln_area - ln_target(t as usize);
        }
        for k in 0..2 {
            let gp = match planar_area {
                Some((_, g)) if k == 0 => Vector2::from(g),
                _ => j.tr_mul(&Vector3::from(grad[k])),
            };
            g += gp * r[k];
            h += gp * gp.transpose();
            e0 += r[k] * r[k];
        }
    }
    let eps = 1e-9 * (h[(0, 0)] + h[(1, 1)]);
    let (h00, h11) = (h[(0, 0)] + eps, h[(1, 1)] + eps);
    let det = h00 * h11 - h[(0, 1)] * h[(1, 0)];
    if !(det > 0.0) {
        return None;
    }
    let dq = [-(h11 * g[0] - h[(0, 1)] * g[1]) / det, -(h00 * g[1] - h[(1, 0)] * g[0]) / det];
    if !(dq[0].is_finite() && dq[1].is_finite()) {
        return None;
    }
    let q0 = mesh.plane[v];
    let mut step = 1.0;
    for _ in 0..=HALVINGS {
        let q = [q0[0] + step * dq[0], q0[1] + step * dq[1]];
        if ring_valid_in_plane(mesh, ring, v, q) {
            if let Some((x, face)) = lift.lift(q, mesh.hint[v]) {
                if ring_faces_same_side(mesh, ring, v, x) && local_energy(mesh, ring, v, x, q, covered, ln_target, sqrt_mu).is_some_and(|e| e < e0) {
                    return Some((q, x, face));
                }
            }
        }
        step *= 0.5;
    }
    None
}

/// `ln` of the mean face area of `mesh` (the uniform target).
pub(crate) fn ln_mean_area(mesh: &Shaping) -> f64 {
    let total: f64 = mesh.faces.iter().map(|f| {
        let [a, b, c] = f.map(|u| mesh.position[u as usize]);
        0.5 * norm(cross(sub(b, a), sub(c, a)))
    }).sum();
    (total / mesh.faces.len().max(1) as f64).ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The residuals' gradients against central differences, on a skewed triangle.
    #[test]
    fn gradients_match_finite_differences() {
        let (x, a, b) = ([0.1, -0.2, 0.3], [1.3, 0.1, -0.2], [0.4, 0.9, 0.5]);
        let (ln_target, sqrt_mu) = (-0.7, 0.6);
        let (_, grad) = residuals(x, a, b, ln_target, sqrt_mu).unwrap();
        let h = 1e-6;
        for k in 0..3 {
            let (mut xp, mut xm) = (x, x);
            xp[k] += h;
            xm[k] -= h;
            let (rp, _) = residuals(xp, a, b, ln_target, sqrt_mu).unwrap();
            let (rm, _) = residuals(xm, a, b, ln_target, sqrt_mu).unwrap();
            for r in 0..2 {
                let fd = (rp[r] - rm[r]) / (2.0 * h);
                assert!((fd - grad[r][k]).abs() < 1e-6 * (1.0 + fd.abs()), "residual {r}, coordinate {k}: {fd} vs {}", grad[r][k]);
            }
        }
    }

    /// The shape residual is zero exactly for an equilateral triangle, positive otherwise.
    #[test]
    fn shape_residual_vanishes_on_equilateral() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 3f64.sqrt() / 2.0, 0.0]);
        let (r, _) = residuals(a, b, c, 0.0, 1.0).unwrap();
        assert!(r[1].abs() < 1e-12, "{}", r[1]);
        let (r, _) = residuals(a, b, [0.5, 0.3, 0.0], 0.0, 1.0).unwrap();
        assert!(r[1] > 0.1, "{}", r[1]);
    }
}
