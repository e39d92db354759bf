//! Removal of slivers and self-crossing faces from the finished remesh (ours; see [`super`] and
//! docs/method.md, "18. Remesh shape").
//!
//! Every remesh vertex lies on the input surface, but a flat triangle between three surface
//! points can still cut through a neighbouring one where the surface bends sharply at the
//! remesh's scale (between fingers, at the rim of an ear), and the last slivers sit at the same
//! places. On the shared meshes every crossing is local: the two faces share a vertex or are at
//! most two rings apart. The pass runs twice, first on the faces with an angle below
//! [`MIN_ANGLE`], then on the crossing faces (MeshLab's test,
//! [`crate::metrics::self_intersection`]): it flips an edge of a flagged face where that helps,
//! then moves the free vertices of flagged faces in the map's plane, lifted through the inverse
//! map as everywhere in the shape stage, to the best of a few candidates (towards the planar
//! centroid of the neighbours or towards one neighbour, or along the relaxation step). A change
//! is kept only if it lowers the crossings among the faces around it (or, for a sliver, raises
//! its smallest angle without adding a crossing) and leaves no new angle below the bound; every
//! face stays oriented in the mesh's chart (`super::state::Chart`), so the mesh stays an
//! embedding and no vertex leaves the surface.

mod collapse;
mod local;

pub(crate) use local::{faces_around, local_crossings};

use super::flips::bend_cos;
use super::smooth::{relax_vertex, ring_valid_in_plane};
use super::worst::compass;
use super::state::{edge_faces, smallest_angle, third, Incidence, Role, Shaping, SurfaceLift};
use crate::metrics::self_intersection::self_intersecting_faces;
use crate::mesh::geometry::{norm, sub, triangle_area};
use crate::mesh::TriMesh;

/// Rounds of detection and moves.
const ROUNDS: usize = 10;

/// Degrees: a move may lower the smallest angle of a vertex's faces to no less than this (or
/// their smallest angle before the move, if lower).
const MIN_ANGLE: f64 = 15.0;

/// Smallest gain (radians) of a smallest angle for a move or flip made for it alone.
const MIN_GAIN: f64 = 1e-3;

/// Steps of the compass ([`super::worst::compass`]) tried around a vertex of a crossing face,
/// in mean planar edge lengths.
const COMPASS_STEPS: [f64; 3] = [0.3, 0.15, 0.07];

/// Fractions of the way to the planar neighbour centroid that are tried.
const FRACTIONS: [f64; 5] = [1.0, 0.75, 0.5, 0.25, 0.1];

/// What the pass did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct UncrossReport {
    /// Self-crossing faces before the pass.
    pub before: usize,
    /// Self-crossing faces after it.
    pub after: usize,
    /// Of those, faces within two remesh edge lengths of a face of the input that crosses
    /// another (crossings a remesh on the surface inherits; `super::super::from_cap`).
    pub at_input_crossings: usize,
    /// Vertex moves made.
    pub moves: usize,
    /// Edge flips made.
    pub flips: usize,
    /// Edge collapses made where flips and moves left crossing faces.
    pub collapses: usize,
    /// Faces with an angle below 15 degrees before the pass.
    pub slivers_before: usize,
    /// Faces with an angle below 15 degrees after it.
    pub slivers_after: usize,
}

/// The best move of free vertex `v` that lowers its local crossing count (or, when `slivers`,
/// raises the smallest angle of its faces from below [`MIN_ANGLE`] with as many crossings):
/// planar point, surface point and hint.
fn uncross_vertex(mesh: &Shaping, incidence: &Incidence, v: usize, lift: &SurfaceLift, slivers: bool) -> Option<([f64; 2], [f64; 3], u32)> {
    let ring = incidence.of(v);
    let near = faces_around(mesh, incidence, v);
    let now = local_crossings(mesh, ring, &near, v, mesh.position[v]);
    // The planar centroid of the neighbours.
    let (mut c, mut k) = ([0.0f64; 2], 0.0);
    for &t in ring {
        for &u in &mesh.faces[t as usize] {
            if u as usize != v && mesh.planar(u) {
                c[0] += mesh.plane[u as usize][0];
                c[1] += mesh.plane[u as usize][1];
                k += 1.0;
            }
        }
    }
    let q0 = mesh.plane[v];
    let ring_angle = |x: [f64; 3]| {
        ring.iter()
            .map(|&t| {
                let p = mesh.faces[t as usize].map(|u| if u as usize == v { x } else { mesh.position[u as usize] });
                if triangle_area(p[0], p[1], p[2]) > 0.0 { smallest_angle(p[0], p[1], p[2]) } else { 0.0 }
            })
            .fold(f64::INFINITY, f64::min)
    };
    // A move may not leave a sliver the ring did not have.
    let angle_now = ring_angle(mesh.position[v]);
    let floor = angle_now.min(MIN_ANGLE.to_radians());
    if now == 0 && !(slivers && angle_now < MIN_ANGLE.to_radians()) {
        return None;
    }
    let mut candidates: Vec<[f64; 2]> = Vec::new();
    if k > 0.0 {
        let c = [c[0] / k, c[1] / k];
        candidates.extend(FRACTIONS.iter().map(|&s| [q0[0] + s * (c[0] - q0[0]), q0[1] + s * (c[1] - q0[1])]));
    }
    if let Some((q, _, _)) = relax_vertex(mesh, incidence, v, lift, &|_| 1.0, None) {
        candidates.push(q);
    }
    // Towards each neighbour: a fold may open in one direction only.
    for &t in ring {
        for &u in &mesh.faces[t as usize] {
            if u as usize != v && mesh.planar(u) {
                let p = mesh.plane[u as usize];
                candidates.extend([0.3, 0.15].map(|s| [q0[0] + s * (p[0] - q0[0]), q0[1] + s * (p[1] - q0[1])]));
            }
        }
    }
    // For a crossing, a compass around the vertex, scaled by its planar edges: where the map
    // stretches, the way out of a crossing may lie across the neighbours' directions.
    if now > 0 {
        let (mut spread, mut count) = (0.0, 0usize);
        for &t in ring {
            for &u in &mesh.faces[t as usize] {
                if u as usize != v && mesh.planar(u) {
                    let p = mesh.plane[u as usize];
                    spread += ((p[0] - q0[0]).powi(2) + (p[1] - q0[1]).powi(2)).sqrt();
                    count += 1;
                }
            }
        }
        if count > 0 {
            let edge = spread / count as f64;
            for fraction in COMPASS_STEPS {
                candidates.extend(compass(q0, fraction * edge));
            }
        }
    }
    // Crossings, smallest angle, planar point, surface point, face.
    type Candidate = (usize, f64, [f64; 2], [f64; 3], u32);
    let mut best: Option<Candidate> = None;
    for q in candidates {
        if !ring_valid_in_plane(mesh, ring, v, q) {
            continue;
        }
        let Some((x, face)) = lift.lift(q, mesh.hint[v]) else { continue };
        let angle = ring_angle(x);
        if !(angle > 0.0 && angle >= floor) {
            continue;
        }
        let count = local_crossings(mesh, ring, &near, v, x);
        // Fewer crossings, or as many and a larger smallest angle; the fewest crossings
        // first, then the best-shaped ring.
        let better = count < now || (slivers && count == now && angle > angle_now + MIN_GAIN);
        if better && best.as_ref().map_or(true, |b| count < b.0 || (count == b.0 && angle > b.1)) {
            best = Some((count, angle, q, x, face));
        }
    }
    best.map(|(_, _, q, x, face)| (q, x, face))
}

/// Flip an edge of face `t` if that lowers the crossings among the faces around it (or, when
/// `slivers`, raises the pair's smallest angle from below [`MIN_ANGLE`] with as many crossings
/// and no sharper bend than the crease bound `acos(cos_crease)` or the pair's own), keeping
/// both new faces oriented in the plane and no smaller angle than the pair had (or
/// [`MIN_ANGLE`]). Returns whether it flipped.
fn uncross_by_flip(mesh: &mut Shaping, incidence: &Incidence, t: u32, slivers: bool, cos_crease: f64) -> bool {
    let edges = edge_faces(&mesh.faces);
    let f = mesh.faces[t as usize];
    for k in 0..3 {
        let (a, b) = (f[k], f[(k + 1) % 3]);
        let Some(&pair) = edges.get(&(a.min(b), a.max(b))) else { continue };
        // t1 runs a -> b (it is t), t2 runs b -> a.
        let (t1, t2) = if a < b { (pair[0], pair[1]) } else { (pair[1], pair[0]) };
        if t1 != t || t2 == u32::MAX {
            continue;
        }
        let (Some(c), Some(d)) = (third(mesh.faces[t1 as usize], a, b), third(mesh.faces[t2 as usize], b, a)) else { continue };
        if c == d || edges.contains_key(&(c.min(d), c.max(d))) || ![a, b, c, d].iter().all(|&v| mesh.planar(v)) {
            continue;
        }
        let [pa, pb, pc, pd] = [a, b, c, d].map(|v| mesh.plane[v as usize]);
        if !(mesh.oriented(pc, pa, pd, 0.0) && mesh.oriented(pd, pb, pc, 0.0)) {
            continue;
        }
        let [xa, xb, xc, xd] = [a, b, c, d].map(|v| mesh.position[v as usize]);
        let (new_faces, old_faces) = ([[xc, xa, xd], [xd, xb, xc]], [[xa, xb, xc], [xb, xa, xd]]);
        if new_faces.iter().any(|p| !(triangle_area(p[0], p[1], p[2]) > 0.0)) {
            continue;
        }
        let worst = |fs: &[[[f64; 3]; 3]; 2]| fs.iter().map(|p| smallest_angle(p[0], p[1], p[2])).fold(f64::INFINITY, f64::min);
        let (angle_old, angle_new) = (worst(&old_faces), worst(&new_faces));
        if angle_new < angle_old.min(MIN_ANGLE.to_radians()) {
            continue;
        }
        // A sliver flip (no crossing removed) may bend the pair no more than the crease bound
        // or than it was bent.
        let bent_ok = bend_cos(xc, xd, xb, xa) >= bend_cos(xa, xb, xc, xd).min(cos_crease);
        let sliver_gain = slivers && angle_old < MIN_ANGLE.to_radians() && angle_new > angle_old + MIN_GAIN && bent_ok;
        let mut near = faces_around(mesh, incidence, a as usize);
        near.extend(faces_around(mesh, incidence, b as usize));
        near.sort_unstable();
        near.dedup();
        let before = local_crossings(mesh, &[t1, t2], &near, usize::MAX, [0.0; 3]);
        let (old1, old2) = (mesh.faces[t1 as usize], mesh.faces[t2 as usize]);
        mesh.faces[t1 as usize] = [c, a, d];
        mesh.faces[t2 as usize] = [d, b, c];
        let after = local_crossings(mesh, &[t1, t2], &near, usize::MAX, [0.0; 3]);
        if after < before || (after == before && sliver_gain) {
            return true;
        }
        mesh.faces[t1 as usize] = old1;
        mesh.faces[t2 as usize] = old2;
    }
    false
}

/// Whether the planar face `f` is a sliver as [`uncross`] counts them (an angle below
/// [`MIN_ANGLE`]).
fn is_sliver(position: &[[f64; 3]], has_plane: &[bool], f: [u32; 3]) -> bool {
    f.iter().all(|&u| has_plane[u as usize]) && is_thin(position, f)
}

/// The faces of `faces` with a planar point at every corner and an angle below
/// [`MIN_ANGLE`] (the slivers [`uncross`] counts).
pub(crate) fn sliver_count(position: &[[f64; 3]], faces: &[[u32; 3]], has_plane: &[bool]) -> usize {
    faces.iter().filter(|&&f| is_sliver(position, has_plane, f)).count()
}

/// Whether face `f` has an angle below [`MIN_ANGLE`].
fn is_thin(position: &[[f64; 3]], f: [u32; 3]) -> bool {
    let p = f.map(|u| position[u as usize]);
    smallest_angle(p[0], p[1], p[2]) < MIN_ANGLE.to_radians()
}

/// The faces at a closed surface's bottom (a corner without a planar point: the merged bottom
/// vertex, `super::bottom`, or the bottom disk when it is not merged) with an angle below
/// [`MIN_ANGLE`]: slivers that [`uncross`] does not count, since no move in the plane reaches
/// the bottom, and that nothing later mends.
pub(crate) fn slivers_at_bottom(position: &[[f64; 3]], faces: &[[u32; 3]], has_plane: &[bool]) -> usize {
    faces
        .iter()
        .filter(|f| f.iter().any(|&u| !has_plane[u as usize]) && is_thin(position, **f))
        .count()
}

/// The slivers ([`is_sliver`]) of `faces` whose shortest edge joins two vertices that stay
/// (`fixed`): no move or flip of the shape stage changes that edge.
pub(crate) fn slivers_on_fixed_edges(position: &[[f64; 3]], faces: &[[u32; 3]], has_plane: &[bool], fixed: &[bool]) -> usize {
    faces
        .iter()
        .filter(|&&f| is_sliver(position, has_plane, f))
        .filter(|f| {
            let k = (0..3).min_by(|&i, &j| {
                let l = |k: usize| norm(sub(position[f[k] as usize], position[f[(k + 1) % 3] as usize]));
                l(i).total_cmp(&l(j))
            });
            k.is_some_and(|k| fixed[f[k] as usize] && fixed[f[(k + 1) % 3] as usize])
        })
        .count()
}

/// Flip and move around the slivers, then the crossing faces, of `mesh` until none is left or a
/// round changes nothing (at most [`ROUNDS`] rounds each). `crease` is the shape stage's bound
/// (radians, [`super::ShapeOptions::crease_deg`]). Deterministic: faces and vertices are
/// visited in index order.
pub(crate) fn uncross(mesh: &mut Shaping, lift: &SurfaceLift, crease: f64) -> UncrossReport {
    let cos_crease = crease.cos();
    let crossing = |mesh: &Shaping| self_intersecting_faces(&TriMesh::new(mesh.position.clone(), mesh.faces.clone()));
    let slivers = |mesh: &Shaping| -> Vec<u32> { (0..mesh.faces.len() as u32).filter(|&t| is_sliver(&mesh.position, &mesh.has_plane, mesh.faces[t as usize])).collect() };
    let (before, slivers_before) = (crossing(mesh).len(), sliver_count(&mesh.position, &mesh.faces, &mesh.has_plane));
    let mut report = UncrossReport { before, after: before, slivers_before, slivers_after: slivers_before, ..Default::default() };
    // Slivers first (a move or flip for an angle may not add a local crossing), then the
    // crossings (a move or flip for a crossing may not leave an angle below the bound).
    for sliver_phase in [true, false] {
        let flag = |mesh: &Shaping| if sliver_phase { slivers(mesh) } else { crossing(mesh) };
        let mut flagged = flag(mesh);
        for _ in 0..ROUNDS {
            if flagged.is_empty() {
                break;
            }
            let mut flips = 0;
            for &t in &flagged {
                if uncross_by_flip(mesh, &mesh.incidence(), t, sliver_phase, cos_crease) {
                    flips += 1;
                }
            }
            report.flips += flips;
            let incidence = mesh.incidence();
            let mut verts: Vec<u32> = flagged.iter().flat_map(|&t| mesh.faces[t as usize]).filter(|&u| mesh.role[u as usize] == Role::Free).collect();
            verts.sort_unstable();
            verts.dedup();
            let mut moved = 0;
            for v in verts {
                if let Some((q, x, face)) = uncross_vertex(mesh, &incidence, v as usize, lift, sliver_phase) {
                    mesh.plane[v as usize] = q;
                    mesh.position[v as usize] = x;
                    mesh.hint[v as usize] = face;
                    moved += 1;
                }
            }
            report.moves += moved;
            flagged = flag(mesh);
            if moved + flips == 0 {
                // Crossings that no flip or move undoes: an edge collapse at each, then the
                // flips and moves again.
                let collapsed = if sliver_phase || flagged.is_empty() { 0 } else { collapse::uncross_by_collapse(mesh, &flagged) };
                report.collapses += collapsed;
                if collapsed == 0 {
                    break;
                }
                flagged = flag(mesh);
            }
        }
    }
    (report.after, report.slivers_after) = (crossing(mesh).len(), sliver_count(&mesh.position, &mesh.faces, &mesh.has_plane));
    report
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two slivers with the same short edge: counted when both of its ends stay, not when one
    /// of them is free; a fat face and a face without a planar point are no slivers.
    #[test]
    fn slivers_on_edges_that_stay_are_counted() {
        let position = vec![[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.05, 2.0, 0.0], [0.05, -2.0, 0.0], [1.0, 1.0, 0.0], [1.0, -1.0, 0.0]];
        let faces = vec![[0, 1, 2], [1, 0, 3], [1, 5, 4]];
        let has_plane = vec![true; 6];
        assert_eq!(slivers_on_fixed_edges(&position, &faces, &has_plane, &[true, true, false, false, false, false]), 2);
        assert_eq!(slivers_on_fixed_edges(&position, &faces, &has_plane, &[true, false, false, false, false, false]), 0);
        let mut no_plane = has_plane.clone();
        no_plane[2] = false;
        assert_eq!(slivers_on_fixed_edges(&position, &faces, &no_plane, &[true, true, false, false, false, false]), 1);
    }

    /// Faces of a bottom vertex (no planar point) below 15 degrees are counted, whatever their
    /// other corners; the same faces with planar points everywhere, or fat, are not.
    #[test]
    fn slivers_at_the_bottom_are_counted() {
        let position = vec![[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.05, 2.0, 0.0], [0.05, -2.0, 0.0], [1.0, 1.0, 0.0], [1.0, -1.0, 0.0]];
        let faces = vec![[0, 1, 2], [1, 0, 3], [1, 5, 4]];
        assert_eq!(slivers_at_bottom(&position, &faces, &[true; 6]), 0);
        assert_eq!(slivers_at_bottom(&position, &faces, &[true, true, false, true, true, true]), 1);
        assert_eq!(slivers_at_bottom(&position, &faces, &[false, true, true, true, true, true]), 2);
        assert_eq!(slivers_at_bottom(&position, &faces, &[true, true, true, true, false, true]), 0);
    }
}
