//! Removal of low-valence vertices at slivers, after the last flips (ours; see [`super`]).
//!
//! A free vertex with three or four neighbours that sits at a sliver cannot be mended by
//! flips: flipping one of its edges folds the pair (three neighbours) or only moves the
//! sliver. On a closed surface this happens next to the bottom fan's centre, whose crowded
//! ring leaves a ring vertex pressed against a spoke. The vertex is removed and its hole
//! triangulated (one face, or the better of a quadrilateral's two diagonals) when the new
//! faces' smallest angle is larger than the old faces', each new face keeps its planar
//! orientation (a face with the fan's centre is judged on the surface, as the flips judge
//! it) and turns by no more than the collapses allow ([`super::resample`]).

use super::state::{smallest_angle, Incidence, Role, Shaping};
use crate::mesh::geometry::{cross, dot, norm, sub};

/// Faces whose smallest angle (degrees) is below this have their low-valence vertices
/// considered for removal.
pub(crate) const SLIVER_DEG: f64 = 20.0;

/// Smallest gain (radians) of the smallest angle for a removal.
const MIN_GAIN: f64 = 1e-3;

/// Cosine of the largest turn of a new face's normal against the removed faces' mean
/// normal (45 degrees, as a collapse's turn in [`super::resample`]).
const MAX_TURN_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Passes over the slivers at most.
const MAX_PASSES: usize = 4;

/// Remove the free vertices of valence 3 or 4 at the faces of `mesh` whose smallest angle is
/// below [`SLIVER_DEG`], where that raises the smallest angle around them. Removed vertices
/// keep their slots with no face (see [`super::resample::compact`]). Returns the number of
/// vertices removed.
pub(crate) fn remove_sliver_vertices(mesh: &mut Shaping) -> usize {
    let threshold = SLIVER_DEG.to_radians();
    let mut removed = 0;
    for _ in 0..MAX_PASSES {
        let incidence = mesh.incidence();
        let mut candidates: Vec<u32> = mesh
            .faces
            .iter()
            .filter(|f| f[0] != f[1] && smallest_angle(mesh.position[f[0] as usize], mesh.position[f[1] as usize], mesh.position[f[2] as usize]) < threshold)
            .flatten()
            .copied()
            .filter(|&v| mesh.role[v as usize] == Role::Free && mesh.planar(v) && matches!(incidence.of(v as usize).len(), 3 | 4))
            .collect();
        candidates.sort_unstable();
        candidates.dedup();
        let mut dead = vec![false; mesh.faces.len()];
        let mut touched = vec![false; mesh.plane.len()];
        let mut this_pass = 0;
        for u in candidates {
            let ring_faces = incidence.of(u as usize);
            if ring_faces.iter().any(|&t| dead[t as usize]) || touched[u as usize] {
                continue;
            }
            let Some(ring) = ordered_ring(mesh, ring_faces, u) else { continue };
            if ring.iter().any(|&v| touched[v as usize]) {
                continue;
            }
            let Some(new_faces) = best_fill(mesh, &incidence, ring_faces, &ring) else { continue };
            for (k, &t) in ring_faces.iter().enumerate() {
                match new_faces.get(k) {
                    Some(&f) => mesh.faces[t as usize] = f,
                    None => dead[t as usize] = true,
                }
            }
            touched[u as usize] = true;
            for &v in &ring {
                touched[v as usize] = true;
            }
            this_pass += 1;
        }
        if this_pass == 0 {
            break;
        }
        let mut k = 0;
        mesh.faces.retain(|_| {
            k += 1;
            !dead[k - 1]
        });
        removed += this_pass;
    }
    removed
}

/// The neighbours of interior vertex `u` in the faces' order around it (`None` when its
/// faces do not close one cycle around it).
fn ordered_ring(mesh: &Shaping, ring_faces: &[u32], u: u32) -> Option<Vec<u32>> {
    // Each face (u, x, y), in its own order: x is followed by y.
    let steps: Vec<(u32, u32)> = ring_faces
        .iter()
        .map(|&t| {
            let f = mesh.faces[t as usize];
            let k = f.iter().position(|&v| v == u)?;
            Some((f[(k + 1) % 3], f[(k + 2) % 3]))
        })
        .collect::<Option<_>>()?;
    let mut ring = vec![steps[0].0];
    while ring.len() < steps.len() {
        let last = *ring.last()?;
        let next = steps.iter().find(|s| s.0 == last)?.1;
        if ring.contains(&next) {
            return None;
        }
        ring.push(next);
    }
    let last = *ring.last()?;
    let closes = steps.iter().any(|s| s.0 == last && s.1 == ring[0]);
    closes.then_some(ring)
}

/// The triangulation of the hole `ring` (3 or 4 vertices, in the removed faces' order) with
/// the largest smallest angle, when that is larger than the removed faces' and every new face
/// passes [`valid`]; `None` otherwise.
fn best_fill(mesh: &Shaping, incidence: &Incidence, ring_faces: &[u32], ring: &[u32]) -> Option<Vec<[u32; 3]>> {
    let x = |v: u32| mesh.position[v as usize];
    let face_angle = |f: [u32; 3]| smallest_angle(x(f[0]), x(f[1]), x(f[2]));
    let old = ring_faces.iter().map(|&t| face_angle(mesh.faces[t as usize])).fold(f64::INFINITY, f64::min);
    let mut normal = [0.0; 3];
    for &t in ring_faces {
        let f = mesh.faces[t as usize];
        let n = cross(sub(x(f[1]), x(f[0])), sub(x(f[2]), x(f[0])));
        normal = [normal[0] + n[0], normal[1] + n[1], normal[2] + n[2]];
    }
    let options: Vec<Vec<[u32; 3]>> = match *ring {
        [a, b, c] => vec![vec![[a, b, c]]],
        // A new diagonal must not exist already; it may be a new spoke of a fan (both new
        // faces then hold the centre, as after a flip into a spoke, [`super::flips`]).
        [a, b, c, d] => [[a, b, c, d], [b, c, d, a]]
            .into_iter()
            .filter(|&[p, _, r, _]| (mesh.planar(p) || mesh.planar(r)) && !adjacent(mesh, incidence, p, r))
            .map(|[p, q, r, s]| vec![[p, q, r], [p, r, s]])
            .collect(),
        _ => Vec::new(),
    };
    options
        .into_iter()
        .filter(|faces| faces.iter().all(|&f| valid(mesh, f, normal)))
        .map(|faces| (faces.iter().map(|&f| face_angle(f)).fold(f64::INFINITY, f64::min), faces))
        .filter(|(angle, _)| *angle > old + MIN_GAIN)
        .max_by(|p, q| p.0.total_cmp(&q.0))
        .map(|(_, faces)| faces)
}

/// Whether `a` and `b` share an edge.
fn adjacent(mesh: &Shaping, incidence: &Incidence, a: u32, b: u32) -> bool {
    incidence.of(a as usize).iter().any(|&t| mesh.faces[t as usize].contains(&b))
}

/// Whether new face `f` keeps the planar orientation (when all its corners have planar
/// points) and turns by at most 45 degrees from `normal`, the removed faces' summed normal.
fn valid(mesh: &Shaping, f: [u32; 3], normal: [f64; 3]) -> bool {
    let y = f.map(|v| mesh.position[v as usize]);
    let n = cross(sub(y[1], y[0]), sub(y[2], y[0]));
    if !(norm(n) > 0.0 && dot(n, normal) > MAX_TURN_COS * norm(n) * norm(normal)) {
        return false;
    }
    if f.iter().all(|&v| mesh.planar(v)) {
        let p = f.map(|v| mesh.plane[v as usize]);
        return mesh.oriented(p[0], p[1], p[2], 0.0);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan of four faces around a free vertex pressed against one side: removing it leaves
    /// two faces with a larger smallest angle.
    #[test]
    fn a_valence_four_vertex_at_a_sliver_is_removed() {
        let plane = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.02]];
        let position: Vec<[f64; 3]> = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let faces = vec![[4, 1, 2], [4, 2, 3], [4, 3, 0], [4, 0, 1]];
        let role = vec![Role::Fixed, Role::Fixed, Role::Fixed, Role::Fixed, Role::Free];
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; 5], role, has_plane: vec![true; 5], orientation: 1.0 };
        let before = mesh.faces.iter().map(|f| smallest_angle(mesh.position[f[0] as usize], mesh.position[f[1] as usize], mesh.position[f[2] as usize])).fold(f64::INFINITY, f64::min);
        assert!(before.to_degrees() < SLIVER_DEG);
        assert_eq!(remove_sliver_vertices(&mut mesh), 1);
        assert_eq!(mesh.faces.len(), 2);
        assert!(mesh.faces.iter().all(|f| !f.contains(&4)));
        let after = mesh.faces.iter().map(|f| smallest_angle(mesh.position[f[0] as usize], mesh.position[f[1] as usize], mesh.position[f[2] as usize])).fold(f64::INFINITY, f64::min);
        assert!((after.to_degrees() - 45.0).abs() < 1e-9, "{}", after.to_degrees());
        // Both triangles keep the planar orientation.
        for f in &mesh.faces {
            let p = f.map(|v| mesh.plane[v as usize]);
            assert!(mesh.oriented(p[0], p[1], p[2], 0.0));
        }
    }

    /// A well-shaped valence-4 vertex (the square's centre) stays.
    #[test]
    fn a_vertex_without_slivers_stays() {
        let plane = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        let position: Vec<[f64; 3]> = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let faces = vec![[4, 1, 2], [4, 2, 3], [4, 3, 0], [4, 0, 1]];
        let role = vec![Role::Fixed, Role::Fixed, Role::Fixed, Role::Fixed, Role::Free];
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; 5], role, has_plane: vec![true; 5], orientation: 1.0 };
        assert_eq!(remove_sliver_vertices(&mut mesh), 0);
        assert_eq!(mesh.faces.len(), 4);
    }
}
