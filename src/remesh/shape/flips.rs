//! Edge flips towards the largest smallest angle, judged on the surface triangles (ours; the
//! paper keeps the cap grid's connectivity, Sec. 4.2).
//!
//! An edge is flipped when the smallest 3-D angle of its two faces grows, the flipped pair is
//! positively oriented in the map's plane (the planar mesh stays an embedding, so every later
//! lift lands on the right sheet), no edge is doubled, and neither the old nor the new pair is
//! bent by more than the crease bound (creases of the input are kept). Each accepted flip
//! raises the pair's smallest angle, so a pass cannot cycle; passes repeat until none flips.

use super::state::{edge_faces, smallest_angle, third, Shaping};
use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, dot, norm, sub};

/// Smallest gain of the pair's smallest angle (radians) for a flip: ties are not flipped back
/// and forth.
const MIN_GAIN: f64 = 1e-6;

/// Planar area a flipped face must keep, relative to the pair's planar area.
const MIN_PLANAR_SHARE: f64 = 1e-6;

/// Passes at most in one call (the first over every edge, the others over the edges of the
/// pairs flipped in the pass before).
const MAX_PASSES: usize = 8;

/// Flip edges of `mesh` until no flip raises a pair's smallest angle (at most
/// [`MAX_PASSES`] passes); `crease` is the largest angle (radians) between the normals of the
/// two faces, before and after, of a flipped edge. Returns the number of flips.
pub(crate) fn flip_to_max_min_angle(mesh: &mut Shaping, crease: f64) -> usize {
    flip(mesh, crease, Criterion::MinAngle)
}

/// Flip edges of `mesh` while a flip brings the valences of its four vertices closer to the
/// regular ones (6 inside, 4 on the boundary) without making the pair's smallest angle fall
/// below [`VALENCE_FLOOR_DEG`] or below what it was (as in isotropic remeshing, Botsch and
/// Kobbelt 2004); the sum of squared valence excesses falls with every flip, so a pass
/// cannot cycle. Returns the number of flips.
pub(crate) fn flip_to_regular_valence(mesh: &mut Shaping, crease: f64) -> usize {
    flip(mesh, crease, Criterion::Valence)
}

/// Smallest angle (degrees) a valence flip may leave in its pair (unless it was smaller).
pub(crate) const VALENCE_FLOOR_DEG: f64 = 25.0;

/// What a flip must improve.
#[derive(Clone, Copy, PartialEq)]
enum Criterion {
    MinAngle,
    Valence,
}

fn flip(mesh: &mut Shaping, crease: f64, criterion: Criterion) -> usize {
    let n = mesh.plane.len();
    let mut valence = vec![0i32; n];
    for f in &mesh.faces {
        for &v in f {
            valence[v as usize] += 1;
        }
    }
    // Each undirected edge: its two faces (the one where it runs a -> b, then b -> a).
    let mut edges = edge_faces(&mesh.faces);
    // Regular valence: 6 inside, 4 on the boundary (a boundary vertex has one face fewer
    // than neighbours, so count faces: 6 inside, 3 on the boundary).
    let mut regular = vec![6i32; n];
    for (&(a, b), f) in &edges {
        if f[0] == u32::MAX || f[1] == u32::MAX {
            regular[a as usize] = 3;
            regular[b as usize] = 3;
        }
    }
    let mut keys: Vec<(u32, u32)> = edges.iter().filter(|(_, f)| f[0] != u32::MAX && f[1] != u32::MAX).map(|(&k, _)| k).collect();
    keys.sort_unstable();
    let cos_crease = crease.cos();
    let mut flips = 0;
    let mut changed: Vec<(u32, u32)> = Vec::new();
    for _ in 0..MAX_PASSES {
        let mut this_pass = 0;
        for &(a, b) in &keys {
            let Some(&[t1, t2]) = edges.get(&(a, b)) else { continue };
            if t1 == u32::MAX || t2 == u32::MAX {
                continue;
            }
            // t1 runs a -> b, so t1 = (a, b, c); t2 runs b -> a, so t2 = (b, a, d).
            let c = third(mesh.faces[t1 as usize], a, b);
            let d = third(mesh.faces[t2 as usize], b, a);
            let (Some(c), Some(d)) = (c, d) else { continue };
            if c == d || edges.contains_key(&(c.min(d), c.max(d))) || ![a, b, c, d].iter().all(|&v| mesh.planar(v)) {
                continue;
            }
            let better = match criterion {
                Criterion::MinAngle => improves(mesh, [a, b, c, d], cos_crease, None),
                Criterion::Valence => {
                    let dev = |v: u32, change: i32| {
                        let e = valence[v as usize] + change - regular[v as usize];
                        e * e
                    };
                    let before = dev(a, 0) + dev(b, 0) + dev(c, 0) + dev(d, 0);
                    let after = dev(a, -1) + dev(b, -1) + dev(c, 1) + dev(d, 1);
                    after < before && improves(mesh, [a, b, c, d], cos_crease, Some(VALENCE_FLOOR_DEG.to_radians()))
                }
            };
            if !better {
                continue;
            }
            valence[a as usize] -= 1;
            valence[b as usize] -= 1;
            valence[c as usize] += 1;
            valence[d as usize] += 1;
            // New faces (c, a, d) and (d, b, c), replacing t1 and t2.
            mesh.faces[t1 as usize] = [c, a, d];
            mesh.faces[t2 as usize] = [d, b, c];
            edges.remove(&(a, b));
            // t2 = (d, b, c) runs c -> d, t1 = (c, a, d) runs d -> c.
            edges.insert((c.min(d), c.max(d)), if c < d { [t2, t1] } else { [t1, t2] });
            // Edge (b, c) moved from t1 to t2, edge (a, d) from t2 to t1.
            reassign(&mut edges, b, c, t1, t2);
            reassign(&mut edges, a, d, t2, t1);
            this_pass += 1;
            // The next pass visits the edges of the flipped pairs only: an angle verdict
            // depends on the pair alone (a valence verdict also on the four valences, whose
            // other edges wait for the next call).
            for (u, v) in [(a, c), (c, b), (b, d), (d, a), (c, d)] {
                changed.push((u.min(v), u.max(v)));
            }
        }
        flips += this_pass;
        if this_pass == 0 {
            break;
        }
        keys = std::mem::take(&mut changed);
        keys.sort_unstable();
        keys.dedup();
    }
    flips
}

/// Replace face `from` by `to` among the faces of edge `(u, v)`.
fn reassign(edges: &mut FastMap<(u32, u32), [u32; 2]>, u: u32, v: u32, from: u32, to: u32) {
    if let Some(slot) = edges.get_mut(&(u.min(v), u.max(v))) {
        for t in slot.iter_mut() {
            if *t == from {
                *t = to;
            }
        }
    }
}

/// Whether flipping edge `(a, b)` of faces `(a, b, c)`, `(b, a, d)` to `(c, a, d)`, `(d, b, c)`
/// raises the smallest 3-D angle (or, with a `floor`, leaves it at least at the floor or at
/// what it was), keeps the planar orientation and stays within the crease bound.
fn improves(mesh: &Shaping, [a, b, c, d]: [u32; 4], cos_crease: f64, floor: Option<f64>) -> bool {
    let x = |v: u32| mesh.position[v as usize];
    let p = |v: u32| mesh.plane[v as usize];
    let old = smallest_angle(x(a), x(b), x(c)).min(smallest_angle(x(b), x(a), x(d)));
    let new = smallest_angle(x(c), x(a), x(d)).min(smallest_angle(x(d), x(b), x(c)));
    let enough = match floor {
        None => new > old + MIN_GAIN,
        Some(floor) => new >= old.min(floor),
    };
    if !enough {
        return false;
    }
    let pair = (mesh.orientation * crate::mesh::geometry::signed_area_2d(p(a), p(b), p(c))).abs()
        + (mesh.orientation * crate::mesh::geometry::signed_area_2d(p(b), p(a), p(d))).abs();
    let floor = MIN_PLANAR_SHARE * pair;
    if !(mesh.oriented(p(c), p(a), p(d), floor) && mesh.oriented(p(d), p(b), p(c), floor)) {
        return false;
    }
    // Neither pair may bend by more than the crease bound; or the new pair bends less than
    // the old one when
    // that one is folded back beyond FOLD_DEG, which is a fold of the remesh (the surface
    // sampled too coarsely there, as across the tip of an ear), not a crease of the input.
    let (old_bend, new_bend) = (bend_cos(x(a), x(b), x(c), x(d)), bend_cos(x(c), x(d), x(b), x(a)));
    (old_bend >= cos_crease && new_bend >= cos_crease) || (old_bend < FOLD_DEG.to_radians().cos() && new_bend > old_bend)
}

/// A pair of faces bent by more than this (degrees) is a fold of the remesh, not a crease.
const FOLD_DEG: f64 = 120.0;

/// Cosine of the angle between the normals of `(a, b, c)` and `(b, a, d)`: 1 when flat, -1
/// when folded back (1 for a degenerate face, which the angle test has already judged).
pub(crate) fn bend_cos(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let n1 = cross(sub(b, a), sub(c, a));
    let n2 = cross(sub(a, b), sub(d, b));
    let l = norm(n1) * norm(n2);
    if l > 0.0 { dot(n1, n2) / l } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::shape::state::Role;

    fn quad(z_d: f64) -> Shaping {
        // Quad a=(0,0), b=(4,0.2)... split along the long diagonal a-b: two flat slivers.
        let plane = vec![[0.0, 0.0], [4.0, 0.0], [2.0, 0.5], [2.0, -0.5]];
        let position = vec![[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [2.0, 0.5, 0.0], [2.0, -0.5, z_d]];
        Shaping { faces: vec![[0, 1, 2], [1, 0, 3]], plane, position, hint: vec![u32::MAX; 4], role: vec![Role::Free; 4], has_plane: vec![true; 4], orientation: 1.0 }
    }

    #[test]
    fn a_sliver_pair_is_flipped_to_the_short_diagonal() {
        let mut mesh = quad(0.0);
        assert_eq!(flip_to_max_min_angle(&mut mesh, 60f64.to_radians()), 1);
        let mut edges: Vec<[u32; 2]> = mesh.faces.iter().flat_map(|f| (0..3).map(move |k| { let (a, b) = (f[k], f[(k + 1) % 3]); [a.min(b), a.max(b)] })).collect();
        edges.sort_unstable();
        assert!(edges.contains(&[2, 3]) && !edges.contains(&[0, 1]), "{:?}", mesh.faces);
        // Both faces keep the planar orientation.
        for f in &mesh.faces {
            let [a, b, c] = f.map(|v| mesh.plane[v as usize]);
            assert!(crate::mesh::geometry::signed_area_2d(a, b, c) > 0.0);
        }
        // Flipping again would lower the smallest angle: nothing more happens.
        assert_eq!(flip_to_max_min_angle(&mut mesh, 60f64.to_radians()), 0);
    }

    #[test]
    fn a_crease_is_kept() {
        // d lifted far out of the plane: the flipped pair would bend by about 80 degrees.
        let mut mesh = quad(3.0);
        let before = mesh.faces.clone();
        flip_to_max_min_angle(&mut mesh, 30f64.to_radians());
        assert_eq!(mesh.faces, before);
    }
}
