//! A global Gauss-Newton step of the area term (ours; see [`super`] and docs/method.md,
//! section 18).
//!
//! The polish's per-vertex steps ([`super::polish`]) remove an area error that changes from
//! face to face, but a smooth one (a region whose faces are all a little too large) only
//! diffuses out about a ring per iteration. This step solves for all free vertices' planar
//! displacements `u` at once:
//! `min sum_f (grad ln P_f . u - r_f)^2 + alpha sum_e |u_i - u_j|^2 / l_e^2`,
//! where `P_f` is face `f`'s planar area (its surface area changes in the same ratio while
//! the map's local scale is held), `r_f = ln(target_f / S_f)` the log error of its surface
//! area `S_f` and `l_e` an edge's planar length. The second term keeps the displacement
//! smooth at the faces' own scale, so the step carries the error's low frequencies and leaves
//! the shape to the polish. The normal equations are sparse and symmetric positive definite
//! (2 unknowns a vertex, 2 x 2 blocks between neighbours) and solved by sparse Cholesky.

use super::smooth::{ring_faces_same_side, ring_valid_in_plane};
use super::state::{ring_least, smallest_angle_tan, Incidence, Role, Shaping, SurfaceLift};
use crate::linalg::SpdSolver;
use crate::mesh::geometry::{signed_area_2d, triangle_area};
use crate::mesh::topology::within_rings;
use super::blocks::BlockSystem;

/// Polish iterations between two global steps ([`super::ShapeOptions::area_steps`] of them
/// from the polish's first iteration). Every 5 for the first 30 lowered the areas' spread more
/// than every 20 over the whole polish; every 10 over the whole polish lowered it further, at
/// 40-50% more time and lower angles.
pub(crate) const AREA_STEP_SPACING: usize = 5;

/// A vertex takes its global step only where the smallest angle of its faces stays at least
/// this (degrees), or does not fall below its present one: the step does not weigh shape.
/// 30 let the hand's mean smallest angle fall by 0.2 degrees; 45 kept every shared mesh's
/// within 0.2 of its value without the steps, the hand's unchanged.
const ANGLE_GUARD_DEG: f64 = 45.0;

/// Rings of vertices around a closed surface's merged bottom vertex that the global steps
/// leave still (the polish still moves them): with one, the closed hippocampus at 10000 faces
/// kept a 25.6-degree smallest angle, but the decimated lung lobe's star a 12.6-degree spoke
/// face.
const BOTTOM_RINGS: usize = 2;

/// Halvings of a vertex's step before it stays.
const HALVINGS: usize = 3;

/// Weight of the smoothness term (`alpha` above), relative to the area term: smaller moves
/// rougher error out in one step but disturbs the shape more. On the bunny, bird skull,
/// left ventricle and 12k brain, 0.1 gave lower `d_face_relative` than 1 at the same angles,
/// 0.03 about the same areas as 0.1 with lower angles.
pub(crate) const SMOOTHNESS: f64 = 0.1;

/// Levenberg-Marquardt damping of each unknown, relative to its own diagonal entry (the
/// planar faces' scale varies by orders of magnitude over the disk).
const DAMPING: f64 = 1e-6;

/// The planar displacement of every vertex (zero for those that do not move freely), or
/// `None` when nothing moves or the system cannot be solved. `ln_target(t)` is `ln` of face
/// `t`'s target area; `alpha` weighs the smoothness term. `solver` keeps its analysis for
/// the next step while the flips leave the vertices' neighbours as they are.
pub(crate) fn global_area_step(mesh: &Shaping, incidence: &Incidence, ln_target: &dyn Fn(usize) -> f64, alpha: f64, solver: &mut SpdSolver) -> Option<Vec<[f64; 2]>> {
    // Vertices within BOTTOM_RINGS edges of a closed surface's merged bottom (no planar
    // point) stay: the plane is most distorted there and the spoke faces have no planar area.
    let bottom: Vec<bool> = mesh.has_plane.iter().map(|&p| !p).collect();
    let near = if bottom.contains(&true) { within_rings(&bottom, &mesh.faces, BOTTOM_RINGS) } else { bottom };
    let mut system = BlockSystem::new(mesh, incidence, |v| mesh.role[v] == Role::Free && !near[v])?;
    for (t, f) in mesh.faces.iter().enumerate() {
        if !f.iter().all(|&u| mesh.has_plane[u as usize]) || f.iter().all(|&u| system.unknown(u) == u32::MAX) {
            continue;
        }
        let p = f.map(|u| mesh.plane[u as usize]);
        let planar = signed_area_2d(p[0], p[1], p[2]);
        let x = f.map(|u| mesh.position[u as usize]);
        let surface = triangle_area(x[0], x[1], x[2]);
        if planar == 0.0 || !(surface > 0.0) {
            continue;
        }
        let r = ln_target(t) - surface.ln();
        let grad = ln_area_gradient(p, planar);
        let ids = f.map(|u| system.unknown(u));
        for i in 0..3 {
            if ids[i] == u32::MAX {
                continue;
            }
            for a in 0..2 {
                system.add_rhs(ids[i], a, grad[i][a] * r);
            }
            for j in 0..3 {
                if ids[j] == u32::MAX {
                    continue;
                }
                for a in 0..2 {
                    for b in 0..2 {
                        system.add(ids[i], a, ids[j], b, grad[i][a] * grad[j][b]);
                    }
                }
            }
        }
        // Smoothness on the face's edges (an interior edge counts half from each side).
        for k in 0..3 {
            let (ia, ib) = (ids[k], ids[(k + 1) % 3]);
            let (pa, pb) = (p[k], p[(k + 1) % 3]);
            let l2 = (pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2);
            if !(l2 > 0.0) {
                continue;
            }
            let w = 0.5 * alpha / l2;
            for c in 0..2 {
                if ia != u32::MAX {
                    system.add(ia, c, ia, c, w);
                }
                if ib != u32::MAX {
                    system.add(ib, c, ib, c, w);
                }
                if ia != u32::MAX && ib != u32::MAX {
                    system.add(ia, c, ib, c, -w);
                    system.add(ib, c, ia, c, -w);
                }
            }
        }
    }
    system.solve(DAMPING, solver, "global area step")
}

/// The gradient of `ln |signed area|` of the planar triangle `p` (signed area `planar`) with
/// respect to each corner: `(y_{k+1} - y_{k+2}, x_{k+2} - x_{k+1}) / (2 area)`.
pub(crate) fn ln_area_gradient(p: [[f64; 2]; 3], planar: f64) -> [[f64; 2]; 3] {
    std::array::from_fn(|k| {
        let (a, b) = (p[(k + 1) % 3], p[(k + 2) % 3]);
        [0.5 * (a[1] - b[1]) / planar, 0.5 * (b[0] - a[0]) / planar]
    })
}

/// Vertex `v` moved by its global step `u` (clamped to a quarter of its shortest planar
/// edge, where the linearisation holds), halved until its faces stay valid in the plane and
/// on the surface and keep their smallest angle ([`ANGLE_GUARD_DEG`]); `None` if none does.
pub(crate) fn move_vertex(mesh: &Shaping, incidence: &Incidence, v: usize, lift: &SurfaceLift, u: [f64; 2]) -> Option<([f64; 2], [f64; 3], u32)> {
    let ring = incidence.of(v);
    let q0 = mesh.plane[v];
    let shortest = ring
        .iter()
        .flat_map(|&t| mesh.faces[t as usize])
        .filter(|&w| w as usize != v && mesh.has_plane[w as usize])
        .map(|w| {
            let p = mesh.plane[w as usize];
            (p[0] - q0[0]).hypot(p[1] - q0[1])
        })
        .fold(f64::INFINITY, f64::min);
    let len = u[0].hypot(u[1]);
    if !(len > 0.0) || !shortest.is_finite() {
        return None;
    }
    let scale = (0.25 * shortest / len).min(1.0);
    let floor = ring_least(mesh, ring, v, mesh.position[v], smallest_angle_tan).min(ANGLE_GUARD_DEG.to_radians().tan());
    let mut step = scale;
    for _ in 0..=HALVINGS {
        let q = [q0[0] + step * u[0], q0[1] + step * u[1]];
        if ring_valid_in_plane(mesh, ring, v, q) {
            if let Some((x, face)) = lift.lift(q, mesh.hint[v]) {
                if ring_faces_same_side(mesh, ring, v, x) && ring_least(mesh, ring, v, x, smallest_angle_tan) >= floor {
                    return Some((q, x, face));
                }
            }
        }
        step *= 0.5;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::shape::polish::ln_mean_area;
    use crate::remesh::shape::state::test_meshes::flat_grid;

    /// A flat `k x k` square grid (planar point = surface point), its border fixed and its
    /// interior displaced by a smooth bump `amp * sin(pi x) sin(pi y)` along x: the faces'
    /// areas vary smoothly, the error the global step is for.
    fn bumped_grid(k: usize, amp: f64) -> Shaping {
        flat_grid(k, |i, j| {
            let (x, y) = (i as f64 / k as f64, j as f64 / k as f64);
            let border = i == 0 || j == 0 || i == k || j == k;
            let dx = if border { 0.0 } else { amp * (std::f64::consts::PI * x).sin() * (std::f64::consts::PI * y).sin() };
            ([x + dx, y], if border { Role::Fixed } else { Role::Free })
        })
    }

    /// Sum of squared log errors of the faces' surface areas against the mean.
    fn area_error(mesh: &Shaping) -> f64 {
        let ln_mean = ln_mean_area(mesh);
        mesh.faces.iter().map(|f| {
            let x = f.map(|u| mesh.position[u as usize]);
            (triangle_area(x[0], x[1], x[2]).ln() - ln_mean).powi(2)
        }).sum()
    }

    fn apply(mesh: &mut Shaping, u: &[[f64; 2]], s: f64) {
        for v in 0..mesh.plane.len() {
            mesh.plane[v] = [mesh.plane[v][0] + s * u[v][0], mesh.plane[v][1] + s * u[v][1]];
            mesh.position[v] = [mesh.plane[v][0], mesh.plane[v][1], 0.0];
        }
    }

    /// One step removes most of a smooth area error (which per-vertex steps spread about a
    /// ring per sweep), and moves only the free vertices.
    #[test]
    fn one_step_removes_most_of_a_smooth_area_error() {
        let mut mesh = bumped_grid(16, 0.08);
        let incidence = mesh.incidence();
        let before = area_error(&mesh);
        let ln_mean = ln_mean_area(&mesh);
        let u = global_area_step(&mesh, &incidence, &|_| ln_mean, SMOOTHNESS, &mut SpdSolver::new()).expect("solvable");
        for v in 0..u.len() {
            if mesh.role[v] != Role::Free {
                assert_eq!(u[v], [0.0, 0.0]);
            }
        }
        apply(&mut mesh, &u, 1.0);
        let after = area_error(&mesh);
        assert!(after < 0.1 * before, "area error {before} -> {after}");
    }

    /// The step's linear model: the change of each face's log area for a small multiple of
    /// the step matches `grad ln P . u` (the gradients the system is built from) to first order.
    #[test]
    fn the_linear_model_matches_a_small_step() {
        let mesh = bumped_grid(6, 0.1);
        let incidence = mesh.incidence();
        let u = global_area_step(&mesh, &incidence, &|_| -3.0, SMOOTHNESS, &mut SpdSolver::new()).expect("solvable");
        let ln_area = |m: &Shaping, f: [u32; 3]| { let p = f.map(|v| m.plane[v as usize]); signed_area_2d(p[0], p[1], p[2]).ln() };
        let h = 1e-6;
        let mut moved = bumped_grid(6, 0.1);
        apply(&mut moved, &u, h);
        for &f in &mesh.faces {
            let p = f.map(|v| mesh.plane[v as usize]);
            let planar = signed_area_2d(p[0], p[1], p[2]);
            let g = ln_area_gradient(p, planar);
            let predicted: f64 = (0..3).map(|k| h * (g[k][0] * u[f[k] as usize][0] + g[k][1] * u[f[k] as usize][1])).sum();
            let actual = ln_area(&moved, f) - ln_area(&mesh, f);
            assert!((actual - predicted).abs() < 1e-4 * predicted.abs() + 1e-12, "{actual} vs {predicted}");
        }
    }
}
