//! Last moves at the smallest angles (ours; see [`super`] and docs/method.md, "Remesh shape").
//!
//! The polish weighs the areas ten times the shape, so a face left thin by the last flips and
//! the sliver removals stays thin when its vertices' areas are right: a remesh's smallest
//! angle is usually one such face, next to a vertex of valence 3-4 or 8-13. Here the free
//! vertices of the faces whose smallest angle is below [`RAISE_BELOW_DEG`] take the polish's
//! step with the shape term weighted [`SHAPE_WEIGHT`] times the area term, kept only when the
//! smallest angle of their faces grows; a few passes, each followed by the max-min-angle
//! flips. Where that step does not raise it, a compass search for the point of the largest
//! smallest angle does ([`max_min_angle_search`]), and once more after the last untangling.

use super::flips::flip_to_max_min_angle;
use super::covered::Covered;
use super::polish::polish_vertex;
use super::smooth::{ring_faces_same_side, ring_valid_in_plane};
use super::uncross::{faces_around, local_crossings};
use crate::mesh::geometry::triangle_area;
use super::state::{Incidence, ring_least, smallest_angle, thin_face_vertices, Role, Shaping, SurfaceLift};

/// Faces whose smallest angle (degrees) is below this have their free vertices moved.
pub(crate) const RAISE_BELOW_DEG: f64 = 25.0;

/// Weight of the shape term against the area term in these moves (the polish's is 0.1). With
/// 3 the smallest angle rose on 6 of the 11 shared meshes at 5000 faces (12k brain 15.9 ->
/// 24.1 degrees; four unchanged, the hand's kept start changed) at 0-6% more
/// `d_face_relative`; 10 gave the same angles at up to 10% more, 1 smaller gains
/// (docs/method.md, "Remesh shape").
const SHAPE_WEIGHT: f64 = 3.0;

/// Passes at most (each over the faces still below [`RAISE_BELOW_DEG`]).
const PASSES: usize = 4;

/// Smallest gain (radians) of the smallest angle of a vertex's faces for a move.
const MIN_GAIN: f64 = 1e-4;

/// Move the free vertices of `mesh`'s faces below [`RAISE_BELOW_DEG`] where that raises the
/// smallest angle of their faces (`ln_target(t)`: `ln` of face `t`'s target area, of the
/// areas `covered` measures when given; `crease` as in [`flip_to_max_min_angle`]). Returns
/// the vertex moves and the flips made.
pub(crate) fn raise_smallest_angles(mesh: &mut Shaping, lift: &SurfaceLift, ln_target: &dyn Fn(usize) -> f64, covered: Option<&Covered>, crease: f64) -> (usize, usize) {
    let threshold = RAISE_BELOW_DEG.to_radians();
    let (mut moves, mut flips) = (0, 0);
    for _ in 0..PASSES {
        let incidence = mesh.incidence();
        let candidates = thin_face_vertices(mesh, threshold, |v| mesh.role[v as usize] == Role::Free && mesh.planar(v));
        let mut this_pass = 0;
        for v in candidates {
            let v = v as usize;
            let ring = incidence.of(v);
            let before = ring_least(mesh, ring, v, mesh.position[v], smallest_angle);
            let step = polish_vertex(mesh, &incidence, v, lift, ln_target, SHAPE_WEIGHT, covered)
                .filter(|&(_, x, _)| ring_least(mesh, ring, v, x, smallest_angle) > before + MIN_GAIN)
                .or_else(|| max_min_angle_search(mesh, &incidence, v, lift, before));
            if let Some((q, x, hint)) = step {
                mesh.plane[v] = q;
                mesh.position[v] = x;
                mesh.hint[v] = hint;
                this_pass += 1;
            }
        }
        moves += this_pass;
        if this_pass == 0 {
            break;
        }
        flips += flip_to_max_min_angle(mesh, crease);
    }
    (moves, flips)
}

/// After the last untangling ([`super::uncross`], whose moves may leave an angle down to 15
/// degrees): the free vertices of faces below [`RAISE_BELOW_DEG`] take the
/// [`max_min_angle_search`] move, which adds no crossing. Returns the moves.
pub(crate) fn raise_by_search(mesh: &mut Shaping, lift: &SurfaceLift) -> usize {
    let incidence = mesh.incidence();
    let candidates = thin_face_vertices(mesh, RAISE_BELOW_DEG.to_radians(), |v| mesh.role[v as usize] == Role::Free && mesh.planar(v));
    let mut moves = 0;
    for v in candidates {
        let v = v as usize;
        let before = ring_least(mesh, incidence.of(v), v, mesh.position[v], smallest_angle);
        if let Some((q, x, hint)) = max_min_angle_search(mesh, &incidence, v, lift, before) {
            mesh.plane[v] = q;
            mesh.position[v] = x;
            mesh.hint[v] = hint;
            moves += 1;
        }
    }
    moves
}

/// Largest relative change of a face's area in a [`max_min_angle_search`] move.
const AREA_CHANGE: f64 = 0.1;

/// Compass directions of [`max_min_angle_search`] and of the untangling's moves ([`compass`]).
const DIRECTIONS: usize = 8;

/// The [`DIRECTIONS`] points at distance `h` around the planar point `centre`.
pub(crate) fn compass(centre: [f64; 2], h: f64) -> impl Iterator<Item = [f64; 2]> {
    (0..DIRECTIONS).map(move |k| {
        let angle = std::f64::consts::TAU * k as f64 / DIRECTIONS as f64;
        [centre[0] + h * angle.cos(), centre[1] + h * angle.sin()]
    })
}

/// Step lengths of [`max_min_angle_search`], as fractions of the ring's mean planar edge.
const SEARCH_STEPS: [f64; 4] = [0.15, 0.07, 0.03, 0.015];

/// A move of free vertex `v` (faces `ring`, smallest angle `before`) that raises the smallest
/// angle of its faces when the polish's step does not: a compass search in the map's plane,
/// [`DIRECTIONS`] directions at each of [`SEARCH_STEPS`], from the best point found so far,
/// each trial lifted onto the surface and kept only with every face valid in the plane and
/// on the same side on the surface. A vertex between two faces that pull its angle
/// opposite ways (valence 5 beside 8) has its best point where the two smallest angles are
/// equal; the polish's smooth energy does not aim there. A trial that makes the faces around
/// `v` cross more of their neighbours within a few rings is refused (the last untangling
/// would otherwise undo the move with a thinner face).
fn max_min_angle_search(mesh: &Shaping, incidence: &Incidence, v: usize, lift: &SurfaceLift, before: f64) -> Option<([f64; 2], [f64; 3], u32)> {
    let ring = incidence.of(v);
    let near = faces_around(mesh, incidence, v);
    let crossings = local_crossings(mesh, ring, &near, v, mesh.position[v]);
    let areas = |x: [f64; 3]| ring.iter().map(move |&t| {
        let p = mesh.faces[t as usize].map(|w| if w as usize == v { x } else { mesh.position[w as usize] });
        triangle_area(p[0], p[1], p[2])
    });
    let area0: Vec<f64> = areas(mesh.position[v]).collect();
    let q0 = mesh.plane[v];
    let mut spread = 0.0;
    let mut count = 0usize;
    for &t in ring {
        for u in mesh.faces[t as usize] {
            if u as usize != v {
                let p = mesh.plane[u as usize];
                spread += ((p[0] - q0[0]).powi(2) + (p[1] - q0[1]).powi(2)).sqrt();
                count += 1;
            }
        }
    }
    if count == 0 || !(spread > 0.0) {
        return None;
    }
    let edge = spread / count as f64;
    let mut best: Option<([f64; 2], [f64; 3], u32, f64)> = None;
    for fraction in SEARCH_STEPS {
        let h = fraction * edge;
        for q in compass(best.map_or(q0, |b| b.0), h) {
            if !ring_valid_in_plane(mesh, ring, v, q) {
                continue;
            }
            let Some((x, face)) = lift.lift(q, mesh.hint[v]) else { continue };
            if !ring_faces_same_side(mesh, ring, v, x) {
                continue;
            }
            let least = ring_least(mesh, ring, v, x, smallest_angle);
            let kept_areas = areas(x).zip(&area0).all(|(a, a0)| (a / a0 - 1.0).abs() <= AREA_CHANGE);
            if least > best.map_or(before + MIN_GAIN, |b| b.3) && kept_areas && local_crossings(mesh, ring, &near, v, x) <= crossings {
                best = Some((q, x, face, least));
            }
        }
    }
    best.map(|(q, x, face, _)| (q, x, face))
}
