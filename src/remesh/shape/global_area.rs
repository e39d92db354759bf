//! A global Gauss-Newton step of the area term (ours; see [`super`] and docs/method.md,
//! section 18).
//!
//! The polish's per-vertex steps ([`super::polish`]) remove an area error that changes from
//! face to face, but a smooth one (a region whose faces are all a little too large) only
//! diffuses out about a ring per iteration. This step solves for all free vertices' planar
//! displacements `u` at once:
//! `min sum_f (g_f . u - r_f)^2 + alpha sum_e |u_i - u_j|^2 / l_e^2`,
//! where `r_f = ln(target_f / S_f)` is the log error of face `f`'s surface area `S_f`, `g_f`
//! the gradient of `ln S_f` with respect to its corners' planar points (through the inverse
//! map's differential where each corner lies: the map is linear on each input face) and `l_e`
//! an edge's planar length. The second term keeps the displacement smooth at the faces' own
//! scale, so the step carries the error's low frequencies and leaves the shape to the polish.
//! The normal equations are sparse and symmetric positive definite (2 unknowns a vertex, 2 x 2
//! blocks between neighbours) and solved by sparse Cholesky. The step is applied to every
//! vertex at once ([`apply_step`]), as it was solved.

use super::smooth::{face_same_side, face_valid_in_chart};
use super::state::{Incidence, Role, Shaping, SurfaceLift};
use crate::linalg::SpdSolver;
use crate::mesh::geometry::{ln_triangle_area_gradient, signed_area_2d, triangle_area};
use nalgebra::{Matrix3x2, Vector3};
use rayon::prelude::*;
use crate::mesh::topology::within_rings;
use super::blocks::BlockSystem;

/// Polish iterations between two global steps ([`super::ShapeOptions::area_steps`] of them
/// from the polish's first iteration). Every 5 for the first 30 lowered the areas' spread more
/// than every 20 over the whole polish; every 10 over the whole polish lowered it further, at
/// 40-50% more time and lower angles.
pub(crate) const AREA_STEP_SPACING: usize = 5;

/// Rings of vertices around a closed surface's merged bottom vertex that the global steps
/// leave still (the polish still moves them): with one, the closed hippocampus at 10000 faces
/// kept a 25.6-degree smallest angle, but the decimated lung lobe's star a 12.6-degree spoke
/// face.
const BOTTOM_RINGS: usize = 2;

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
/// `t`'s target area; `alpha` weighs the smoothness term. With `lift`, each face's gradient is
/// its surface area's through the inverse map's differential at each corner; without (a mesh
/// whose planar points are its surface points) it is its planar area's. `solver` keeps its
/// analysis for the next step while the flips leave the vertices' neighbours as they are.
pub(crate) fn global_area_step(mesh: &Shaping, incidence: &Incidence, lift: Option<&SurfaceLift>, ln_target: &dyn Fn(usize) -> f64, alpha: f64, solver: &mut SpdSolver) -> Option<Vec<[f64; 2]>> {
    // Vertices within BOTTOM_RINGS edges of a closed surface's merged bottom (no planar
    // point) stay: the plane is most distorted there and the spoke faces have no planar area.
    let bottom: Vec<bool> = mesh.has_plane.iter().map(|&p| !p).collect();
    let near = if bottom.contains(&true) { within_rings(&bottom, &mesh.faces, BOTTOM_RINGS) } else { bottom };
    let mut system = BlockSystem::new(mesh, incidence, |v| mesh.role[v] == Role::Free && !near[v])?;
    // Each unknown vertex's differential of the inverse map where it lies.
    let jacobian: Vec<Option<Matrix3x2<f64>>> = match lift {
        Some(lift) => (0..mesh.plane.len())
            .into_par_iter()
            .map(|v| if system.unknown(v as u32) == u32::MAX { None } else { lift.lift(mesh.plane[v], mesh.hint[v]).and_then(|(_, face)| lift.jacobian(face)) })
            .collect(),
        None => Vec::new(),
    };
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
        let mut grad = ln_area_gradient(p, planar);
        // Through the inverse map's differential at each corner where it is known: the
        // first-order change of the surface area itself.
        for k in 0..3 {
            if let Some(Some(j)) = jacobian.get(f[k] as usize) {
                let g = j.tr_mul(&Vector3::from(ln_triangle_area_gradient(x[k], x[(k + 1) % 3], x[(k + 2) % 3])));
                grad[k] = [g[0], g[1]];
            }
        }
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

/// A vertex's proposed place: planar point, surface point and hint (`u32::MAX`: keep its own).
type Proposal = Option<([f64; 2], [f64; 3], u32)>;

/// The global step `u` applied to every vertex at once, as it was solved (a vertex that
/// stays while its neighbours move makes a new area error). `place(q, hint)` is the surface
/// point of planar point `q` and the face it lies in (the lift, trying the vertex's hint).
/// The vertices of a face that would fold, in the chart or on the surface, keep their place,
/// and the faces are checked again until none folds. Returns the vertices moved.
pub(crate) fn apply_step(mesh: &mut Shaping, u: &[[f64; 2]], place: &(dyn Fn([f64; 2], u32) -> Option<([f64; 3], u32)> + Sync)) -> usize {
    let proposals: Vec<Proposal> = (0..mesh.plane.len())
        .into_par_iter()
        .map(|v| {
            if u[v] == [0.0, 0.0] {
                return None;
            }
            let q = [mesh.plane[v][0] + u[v][0], mesh.plane[v][1] + u[v][1]];
            place(q, mesh.hint[v]).map(|(x, h)| (q, x, h))
        })
        .collect();
    let mut moving: Vec<bool> = proposals.iter().map(Option::is_some).collect();
    loop {
        let folded: Vec<usize> = mesh
            .faces
            .par_iter()
            .enumerate()
            .filter(|(_, f)| f.iter().any(|&w| moving[w as usize]) && folds(mesh, f, &proposals, &moving))
            .map(|(t, _)| t)
            .collect();
        if folded.is_empty() {
            break;
        }
        for t in folded {
            for w in mesh.faces[t] {
                moving[w as usize] = false;
            }
        }
    }
    let mut moved = 0;
    for (v, proposal) in proposals.into_iter().enumerate() {
        if let (true, Some((q, x, h))) = (moving[v], proposal) {
            mesh.plane[v] = q;
            mesh.position[v] = x;
            if h != u32::MAX {
                mesh.hint[v] = h;
            }
            moved += 1;
        }
    }
    moved
}

/// Whether face `f` folds with its `moving` corners at their `proposals`: on the surface
/// ([`face_same_side`]) or in the chart ([`face_valid_in_chart`]).
fn folds(mesh: &Shaping, f: &[u32; 3], proposals: &[Proposal], moving: &[bool]) -> bool {
    let at = |w: u32| proposals[w as usize].filter(|_| moving[w as usize]);
    let new_x = f.map(|w| at(w).map_or(mesh.position[w as usize], |p| p.1));
    let new_p = f.map(|w| at(w).map_or(mesh.plane[w as usize], |p| p.0));
    !face_same_side(f.map(|w| mesh.position[w as usize]), new_x) || !face_valid_in_chart(mesh, *f, new_p)
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
        let u = global_area_step(&mesh, &incidence, None, &|_| ln_mean, SMOOTHNESS, &mut SpdSolver::new()).expect("solvable");
        for v in 0..u.len() {
            if mesh.role[v] != Role::Free {
                assert_eq!(u[v], [0.0, 0.0]);
            }
        }
        let moved = apply_step(&mut mesh, &u, &flat_place);
        assert_eq!(moved, u.iter().filter(|d| **d != [0.0, 0.0]).count(), "every vertex moves");
        let after = area_error(&mesh);
        assert!(after < 0.1 * before, "area error {before} -> {after}");
    }

    /// The lift of the flat grids: the planar point itself, no hint.
    fn flat_place(q: [f64; 2], _hint: u32) -> Option<([f64; 3], u32)> {
        Some(([q[0], q[1], 0.0], u32::MAX))
    }

    /// A step that would fold faces: the vertices of the folding faces stay, the others move,
    /// and no face ends folded.
    #[test]
    fn a_step_that_folds_keeps_the_folding_faces_corners_in_place() {
        let k = 8;
        let mut mesh = bumped_grid(k, 0.0);
        let at = |i: usize, j: usize| j * (k + 1) + i;
        let mut u = vec![[0.0; 2]; mesh.plane.len()];
        // Vertex (2, 2) jumps three cells: its faces fold. Vertex (6, 6) moves a tenth of one.
        u[at(2, 2)] = [3.0 / k as f64, 0.0];
        u[at(6, 6)] = [0.1 / k as f64, 0.05 / k as f64];
        u[at(3, 2)] = [0.01 / k as f64, 0.0];
        let before = mesh.plane.clone();
        let moved = apply_step(&mut mesh, &u, &flat_place);
        assert_eq!(moved, 1, "only the far vertex moves");
        assert_eq!(mesh.plane[at(2, 2)], before[at(2, 2)]);
        assert_eq!(mesh.plane[at(3, 2)], before[at(3, 2)], "a neighbour of the folding vertex stays");
        assert_ne!(mesh.plane[at(6, 6)], before[at(6, 6)]);
        for f in &mesh.faces {
            let p = f.map(|v| mesh.plane[v as usize]);
            assert!(signed_area_2d(p[0], p[1], p[2]) > 0.0, "face {f:?} folded");
        }
    }

    /// The step's linear model: the change of each face's log area for a small multiple of
    /// the step matches `grad ln P . u` (the gradients the system is built from) to first order.
    #[test]
    fn the_linear_model_matches_a_small_step() {
        let mesh = bumped_grid(6, 0.1);
        let incidence = mesh.incidence();
        let u = global_area_step(&mesh, &incidence, None, &|_| -3.0, SMOOTHNESS, &mut SpdSolver::new()).expect("solvable");
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
