//! Last moves at the smallest angles (ours; see [`super`] and docs/method.md, "Remesh shape").
//!
//! The polish weighs the areas ten times the shape, so a face left thin by the last flips and
//! the sliver removals stays thin when its vertices' areas are right: a remesh's smallest
//! angle is usually one such face, next to a vertex of valence 3-4 or 8-13. Here the free
//! vertices of the faces whose smallest angle is below [`RAISE_BELOW_DEG`] take the polish's
//! step with the shape term weighted [`SHAPE_WEIGHT`] times the area term, kept only when the
//! smallest angle of their faces grows; a few passes, each followed by the max-min-angle
//! flips.

use super::flips::flip_to_max_min_angle;
use super::polish::polish_vertex;
use super::state::{ring_least, smallest_angle, thin_face_vertices, Role, Shaping, SurfaceLift};

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
/// smallest angle of their faces (`ln_target(t)`: `ln` of face `t`'s target area; `crease` as
/// in [`flip_to_max_min_angle`]). Returns the vertex moves and the flips made.
pub(crate) fn raise_smallest_angles(mesh: &mut Shaping, lift: &SurfaceLift, ln_target: &dyn Fn(usize) -> f64, crease: f64) -> (usize, usize) {
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
            let Some((q, x, hint)) = polish_vertex(mesh, &incidence, v, lift, ln_target, SHAPE_WEIGHT) else { continue };
            if ring_least(mesh, ring, v, x, smallest_angle) > before + MIN_GAIN {
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
