//! Beltrami coefficients of piecewise-linear maps and the linear Beltrami solver (Lui, Lam,
//! Yau and Gu 2013), used by the quasi-conformal composition of the paper's Sec. 3.2.1
//! (after Choi, Lam and Lui 2015, FLASH).
//!
//! For a face with Beltrami coefficient `mu = rho + i tau`, a map `f = u + i v` with that
//! coefficient satisfies `div(A grad u) = div(A grad v) = 0` with
//! `A = [[(rho-1)^2 + tau^2, -2 tau], [-2 tau, (1+rho)^2 + tau^2]] / (1 - |mu|^2)`,
//! gradients taken in the face's own isometric 2D frame. With `mu = 0`, `A = I` and the system
//! is the cotangent Laplacian. The P1 stiffness matrix is symmetric positive definite once
//! some vertices are fixed.

use super::{pin, FlattenError};
use crate::linalg::{SpdSolver, TripletList};
use crate::mesh::geometry::{cross, dot, norm, sub};

/// The face's corners in an isometric 2D frame: `(0, 0)`, `(l1, 0)`, `(x2, y2)` with `y2 > 0`.
/// `None` for a degenerate face.
pub fn local_frame(p: [[f64; 3]; 3]) -> Option<[[f64; 2]; 3]> {
    let e1 = sub(p[1], p[0]);
    let e2 = sub(p[2], p[0]);
    let l1 = norm(e1);
    let a2 = norm(cross(e1, e2));
    if l1 == 0.0 || a2 == 0.0 {
        return None;
    }
    Some([[0.0, 0.0], [l1, 0.0], [dot(e2, e1) / l1, a2 / l1]])
}

/// Beltrami coefficient `(re, im)` of the affine map from the triangle `p` (2D, counter-
/// clockwise) to `q`: `mu = f_zbar / f_z`. `None` when degenerate.
pub fn beltrami_2d(p: [[f64; 2]; 3], q: [[f64; 2]; 3]) -> Option<[f64; 2]> {
    let (x1, y1) = (p[1][0] - p[0][0], p[1][1] - p[0][1]);
    let (x2, y2) = (p[2][0] - p[0][0], p[2][1] - p[0][1]);
    let det = x1 * y2 - x2 * y1;
    if det == 0.0 {
        return None;
    }
    let (u1, v1) = (q[1][0] - q[0][0], q[1][1] - q[0][1]);
    let (u2, v2) = (q[2][0] - q[0][0], q[2][1] - q[0][1]);
    // Solve [x1 y1; x2 y2] [gx; gy] = [g1; g2] for the gradients of u and v.
    let ux = (u1 * y2 - u2 * y1) / det;
    let uy = (x1 * u2 - x2 * u1) / det;
    let vx = (v1 * y2 - v2 * y1) / det;
    let vy = (x1 * v2 - x2 * v1) / det;
    // f_z = ((ux + vy) + i (vx - uy)) / 2, f_zbar = ((ux - vy) + i (vx + uy)) / 2.
    let (a, b) = (ux + vy, vx - uy);
    let (c, d) = (ux - vy, vx + uy);
    let den = a * a + b * b;
    if den == 0.0 {
        return None;
    }
    Some([(c * a + d * b) / den, (d * a - c * b) / den])
}

/// Beltrami coefficient of each face of the map from the surface `vertices` to `plane`
/// (0 for degenerate faces).
pub fn beltrami_coefficients(vertices: &[[f64; 3]], faces: &[[u32; 3]], plane: &[[f64; 2]]) -> Vec<[f64; 2]> {
    faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| v as usize);
            local_frame([vertices[a], vertices[b], vertices[c]])
                .and_then(|p| beltrami_2d(p, [plane[a], plane[b], plane[c]]))
                .unwrap_or([0.0, 0.0])
        })
        .collect()
}

/// Solve for the map with Beltrami coefficient `mu` (one per face, `|mu| < 1`, relative to the
/// surface) with the vertices in `fixed` held at their positions.
pub fn linear_beltrami_solver(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    mu: &[[f64; 2]],
    fixed: &[(u32, [f64; 2])],
) -> Result<Vec<[f64; 2]>, FlattenError> {
    linear_beltrami_solver_with(vertices, faces, mu, fixed, &mut SpdSolver::new())
}

/// [`linear_beltrami_solver`] with `solver` (its symbolic factorization is reused when an
/// earlier system had the same free vertices).
pub(crate) fn linear_beltrami_solver_with(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    mu: &[[f64; 2]],
    fixed: &[(u32, [f64; 2])],
    solver: &mut SpdSolver,
) -> Result<Vec<[f64; 2]>, FlattenError> {
    let n = vertices.len();
    let mut pos = vec![[0.0; 2]; n];
    let (is_fixed, index, n_free) = pin(&mut pos, fixed);
    let mut trip = TripletList::with_capacity(n_free, 9 * faces.len());
    let mut rhs = vec![vec![0.0; n_free], vec![0.0; n_free]];
    for (f, m) in faces.iter().zip(mu) {
        let [a, b, c] = f.map(|v| v as usize);
        let Some(p) = local_frame([vertices[a], vertices[b], vertices[c]]) else { continue };
        let (rho, tau) = (m[0], m[1]);
        let s = 1.0 - rho * rho - tau * tau;
        if !(s > 0.0) {
            return Err(FlattenError::BeltramiOutOfRange { norm: (rho * rho + tau * tau).sqrt() });
        }
        let a1 = ((rho - 1.0).powi(2) + tau * tau) / s;
        let a2 = -2.0 * tau / s;
        let a3 = ((1.0 + rho).powi(2) + tau * tau) / s;
        let area = 0.5 * p[1][0] * p[2][1];
        // grad phi_k = perp(edge opposite k) / (2 area).
        let grads: [[f64; 2]; 3] = std::array::from_fn(|k| {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            [(p[i][1] - p[j][1]) / (2.0 * area), (p[j][0] - p[i][0]) / (2.0 * area)]
        });
        let verts = [a, b, c];
        for i in 0..3 {
            for j in 0..3 {
                let gi = grads[i];
                let gj = grads[j];
                let k = area * (gi[0] * (a1 * gj[0] + a2 * gj[1]) + gi[1] * (a2 * gj[0] + a3 * gj[1]));
                let (vi, vj) = (verts[i], verts[j]);
                if is_fixed[vi] {
                    continue;
                }
                if is_fixed[vj] {
                    rhs[0][index[vi]] -= k * pos[vj][0];
                    rhs[1][index[vi]] -= k * pos[vj][1];
                } else {
                    trip.push(index[vi], index[vj], k);
                }
            }
        }
    }
    if n_free > 0 {
        let mat = trip.assemble("Beltrami")?;
        solver.factor(&mat, "Beltrami")?;
        solver.solve_in_place(&mut rhs, "Beltrami")?;
        for v in 0..n {
            if !is_fixed[v] {
                pos[v] = [rhs[0][index[v]], rhs[1][index[v]]];
            }
        }
    }
    Ok(pos)
}
