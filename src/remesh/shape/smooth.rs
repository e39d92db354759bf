//! Tangential relaxation towards a centroidal tessellation of uniform (or prescribed)
//! density on the surface (ours; see [`super`]).
//!
//! Each free vertex moves towards the density-weighted centroid of its one-ring's surface
//! triangles (the gradient step of the centroidal Voronoi energy, as in isotropic remeshing),
//! projected onto the tangent plane. The move is made in the map's plane through the local
//! Jacobian of the inverse map, fitted by least squares to the one-ring's planar and surface
//! edges, and the new planar point is lifted back through the inverse map: the vertex stays
//! exactly on the surface. A move is halved until every incident planar face keeps its
//! orientation and every incident surface face keeps facing the same side as before.

use super::covered::Covered;
use super::state::{Incidence, Shaping, SurfaceLift};
use crate::mesh::geometry::{cross, dot, norm, sub, triangle_area};
use nalgebra::{Matrix2, Matrix3x2, Vector2, Vector3};

/// Halvings of a move before the vertex stays.
const HALVINGS: usize = 5;

/// The relaxed position of vertex `v`: its new planar point, surface point and hint, or
/// `None` when no step keeps the one-ring valid. `weight(t)` is the density weight of face
/// `t` (1 for uniform density); each face's mass is its chord area, or with `covered` the
/// surface area it covers ([`Covered`]; faces without a planar point at every corner keep
/// their chord area).
pub(crate) fn relax_vertex(mesh: &Shaping, incidence: &Incidence, v: usize, lift: &SurfaceLift, weight: &dyn Fn(usize) -> f64, covered: Option<&Covered>) -> Option<([f64; 2], [f64; 3], u32)> {
    let ring = incidence.of(v);
    if ring.is_empty() {
        return None;
    }
    let x0 = mesh.position[v];
    let q0 = mesh.plane[v];
    // Weighted centroid of the faces' centroids and the vertex normal.
    let (mut mass, mut centroid, mut normal) = (0.0, [0.0; 3], [0.0; 3]);
    for &t in ring {
        let f = mesh.faces[t as usize];
        let [a, b, c] = f.map(|u| mesh.position[u as usize]);
        let n = cross(sub(b, a), sub(c, a));
        let area = match covered {
            Some(c) if f.iter().all(|&u| mesh.planar(u)) => c.area(f.map(|u| mesh.plane[u as usize])),
            _ => 0.5 * norm(n),
        };
        let w = area * weight(t as usize);
        for k in 0..3 {
            centroid[k] += w * (a[k] + b[k] + c[k]) / 3.0;
            normal[k] += n[k];
        }
        mass += w;
    }
    if !(mass > 0.0) {
        return None;
    }
    let centroid = centroid.map(|c| c / mass);
    let nn = norm(normal);
    if !(nn > 0.0) {
        return None;
    }
    let normal = normal.map(|c| c / nn);
    let d = sub(centroid, x0);
    let dn = dot(d, normal);
    let d = [d[0] - dn * normal[0], d[1] - dn * normal[1], d[2] - dn * normal[2]];
    let j = ring_jacobian(mesh, ring, v)?;
    // Planar step dq minimising |J dq - d|: (J^T J) dq = J^T d, by Cramer's rule (the bits
    // of the remesh depend on its rounding; docs/dependencies.md).
    let (jtj, jtd) = (j.tr_mul(&j), j.tr_mul(&Vector3::from(d)));
    let det2 = jtj.determinant();
    if !(det2 > 0.0) {
        return None;
    }
    let dq = [(jtj[(1, 1)] * jtd[0] - jtj[(0, 1)] * jtd[1]) / det2, (jtj[(0, 0)] * jtd[1] - jtj[(1, 0)] * jtd[0]) / det2];
    if !(dq[0].is_finite() && dq[1].is_finite()) {
        return None;
    }
    let mut step = 1.0;
    for _ in 0..=HALVINGS {
        let q = [q0[0] + step * dq[0], q0[1] + step * dq[1]];
        if ring_valid_in_plane(mesh, ring, v, q) {
            if let Some((x, face)) = lift.lift(q, mesh.hint[v]) {
                if ring_faces_same_side(mesh, ring, v, x) {
                    return Some((q, x, face));
                }
            }
        }
        step *= 0.5;
    }
    None
}

/// The inverse map's differential at vertex `v` (3x2: planar edge to surface edge), fitted by
/// least squares to the edges from `v` to the corners of its faces `ring`: `J = N M^-1` with
/// `M = sum e2 e2^T`, `N = sum e3 e2^T`. `None` when the planar edges do not span the plane.
pub(crate) fn ring_jacobian(mesh: &Shaping, ring: &[u32], v: usize) -> Option<Matrix3x2<f64>> {
    let (x0, q0) = (Vector3::from(mesh.position[v]), Vector2::from(mesh.plane[v]));
    let (mut m, mut n) = (Matrix2::zeros(), Matrix3x2::zeros());
    for &t in ring {
        for &u in &mesh.faces[t as usize] {
            // Not v itself, nor a vertex without a planar point (a closed surface's merged
            // bottom).
            if u as usize == v || !mesh.planar(u) {
                continue;
            }
            let e2 = Vector2::from(mesh.plane[u as usize]) - q0;
            let e3 = Vector3::from(mesh.position[u as usize]) - x0;
            m += e2 * e2.transpose();
            n += e3 * e2.transpose();
        }
    }
    if !(m.determinant() > 0.0) {
        return None;
    }
    let j = n * m.try_inverse()?;
    j.iter().all(|x| x.is_finite()).then_some(j)
}

/// Whether the faces `ring` around `v` keep the planar orientation with `v` at `q`, each
/// with at least a millionth of its current planar area ([`face_valid_in_chart`]).
pub(crate) fn ring_valid_in_plane(mesh: &Shaping, ring: &[u32], v: usize, q: [f64; 2]) -> bool {
    ring.iter().all(|&t| {
        let f = mesh.faces[t as usize];
        face_valid_in_chart(mesh, f, f.map(|u| if u as usize == v { q } else { mesh.plane[u as usize] }))
    })
}

/// Whether face `f` with its corners at planar points `p` keeps the mesh's orientation in its
/// chart with at least a millionth of its current area. A face without a planar point at every
/// corner (at a closed surface's merged bottom, [`super::bottom`]) passes: it is checked on the
/// surface only ([`face_same_side`]).
pub(crate) fn face_valid_in_chart(mesh: &Shaping, f: [u32; 3], p: [[f64; 2]; 3]) -> bool {
    if !f.iter().all(|&u| mesh.planar(u)) {
        return true;
    }
    let now = f.map(|u| mesh.plane[u as usize]);
    let area_now = mesh.chart.signed_area(now[0], now[1], now[2]);
    mesh.oriented(p[0], p[1], p[2], 1e-6 * area_now.abs())
}

/// Whether every face of `ring` around `v`, with `v` at `x`, has a positive area and turns
/// its normal by less than 90 degrees (no surface face folds over; [`face_same_side`]).
pub(crate) fn ring_faces_same_side(mesh: &Shaping, ring: &[u32], v: usize, x: [f64; 3]) -> bool {
    ring.iter().all(|&t| {
        let f = mesh.faces[t as usize];
        face_same_side(f.map(|u| mesh.position[u as usize]), f.map(|u| if u as usize == v { x } else { mesh.position[u as usize] }))
    })
}

/// Whether a surface face moved from corners `old` to `new` has a positive area and turns its
/// normal by less than 90 degrees.
pub(crate) fn face_same_side(old: [[f64; 3]; 3], new: [[f64; 3]; 3]) -> bool {
    let n0 = cross(sub(old[1], old[0]), sub(old[2], old[0]));
    let n1 = cross(sub(new[1], new[0]), sub(new[2], new[0]));
    triangle_area(new[0], new[1], new[2]) > 0.0 && dot(n0, n1) > 0.0
}
