//! Removal of low-valence vertices and short rim edges at slivers, after the last flips
//! (ours; see [`super`]).
//!
//! A free vertex with three or four neighbours that sits at a sliver cannot be mended by
//! flips: flipping one of its edges folds the pair (three neighbours) or only moves the
//! sliver. On a closed surface this happens next to the bottom fan's centre, whose crowded
//! ring leaves a ring vertex pressed against a spoke. The vertex is removed and its hole
//! triangulated (one face, or the better of a quadrilateral's two diagonals) when the new
//! faces' smallest angle is larger than the old faces', each new face keeps its planar
//! orientation (a face with the fan's centre is judged on the surface, as the flips judge
//! it) and turns by no more than the collapses allow ([`super::resample`]). A closed surface's
//! rim ring, bunched on the punctured quad, loses short edges at needles the same way
//! ([`collapse_rim_slivers`]).

use super::state::{drop_faces, link_is_two, smallest_angle, thin_face_vertices, Incidence, Role, Shaping};
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
        let candidates = thin_face_vertices(mesh, threshold, |v| mesh.role[v as usize] == Role::Free && mesh.planar(v) && matches!(incidence.of(v as usize).len(), 3 | 4));
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
        drop_faces(&mut mesh.faces, &dead);
        removed += this_pass;
    }
    removed
}

/// On a closed surface, collapse the short rim edges of the faces below [`SLIVER_DEG`]: the
/// rim ring (vertices that stay, with planar points) is bunched on the punctured quad when the
/// quad is larger than a remesh face, and its short edges make needles with the ring above,
/// which nothing else may move. One end is merged into the other (both lie on the quad's
/// boundary, so the rim stays on the surface) where the smallest angle of the faces around it
/// grows, the edge's link is two vertices, every changed face with planar corners keeps the
/// plane's orientation and none turns by more than 45 degrees. Removed vertices keep their slots
/// with no face. Returns the number of collapses.
pub(crate) fn collapse_rim_slivers(mesh: &mut Shaping) -> usize {
    let threshold = SLIVER_DEG.to_radians();
    let rim = |mesh: &Shaping, v: u32| mesh.role[v as usize] == Role::Fixed && mesh.planar(v);
    let mut collapsed = 0;
    for _ in 0..MAX_PASSES {
        let incidence = mesh.incidence();
        let x = |mesh: &Shaping, v: u32| mesh.position[v as usize];
        let mut edges: Vec<(u32, u32)> = mesh
            .faces
            .iter()
            .filter(|f| f[0] != f[1] && smallest_angle(x(mesh, f[0]), x(mesh, f[1]), x(mesh, f[2])) < threshold)
            .filter_map(|f| {
                let k = (0..3).min_by(|&i, &j| {
                    let l = |k: usize| norm(sub(x(mesh, f[k]), x(mesh, f[(k + 1) % 3])));
                    l(i).total_cmp(&l(j))
                })?;
                let (a, b) = (f[k], f[(k + 1) % 3]);
                (rim(mesh, a) && rim(mesh, b)).then_some((a.min(b), a.max(b)))
            })
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let mut dead = vec![false; mesh.faces.len()];
        let mut touched = vec![false; mesh.plane.len()];
        let mut this_pass = 0;
        for (a, b) in edges {
            let around: Vec<u32> = incidence.of(a as usize).iter().chain(incidence.of(b as usize)).copied().collect();
            if around.iter().any(|&t| dead[t as usize] || mesh.faces[t as usize].iter().any(|&v| touched[v as usize])) {
                continue;
            }
            let best = [(b, a), (a, b)]
                .into_iter()
                .filter_map(|(gone, kept)| collapse_gain(mesh, &incidence, gone, kept).map(|g| (g, gone, kept)))
                .max_by(|p, q| p.0.total_cmp(&q.0));
            let Some((_, gone, kept)) = best else { continue };
            for &t in incidence.of(gone as usize) {
                let f = &mut mesh.faces[t as usize];
                if f.contains(&kept) {
                    dead[t as usize] = true;
                } else {
                    *f = f.map(|v| if v == gone { kept } else { v });
                }
            }
            for &t in &around {
                for &v in &mesh.faces[t as usize] {
                    touched[v as usize] = true;
                }
            }
            touched[gone as usize] = true;
            this_pass += 1;
        }
        if this_pass == 0 {
            break;
        }
        drop_faces(&mut mesh.faces, &dead);
        collapsed += this_pass;
    }
    collapsed
}

/// The gain of the smallest angle around `gone` when it is merged into its neighbour `kept`
/// (`None` when the merge is not allowed or does not raise it by [`MIN_GAIN`] to at least
/// [`RIM_MIN_DEG`]).
fn collapse_gain(mesh: &Shaping, incidence: &Incidence, gone: u32, kept: u32) -> Option<f64> {
    let x = |v: u32| mesh.position[v as usize];
    if !link_is_two(mesh, incidence, gone, kept) {
        return None;
    }
    let faces = incidence.of(gone as usize);
    let old = faces.iter().map(|&t| mesh.faces[t as usize]).map(|f| smallest_angle(x(f[0]), x(f[1]), x(f[2]))).fold(f64::INFINITY, f64::min);
    let mut new = f64::INFINITY;
    for &t in faces {
        let f = mesh.faces[t as usize];
        if f.contains(&kept) {
            continue;
        }
        let g = f.map(|v| if v == gone { kept } else { v });
        let y0 = f.map(x);
        if !valid(mesh, g, cross(sub(y0[1], y0[0]), sub(y0[2], y0[0]))) {
            return None;
        }
        new = new.min(smallest_angle(x(g[0]), x(g[1]), x(g[2])));
    }
    (new.is_finite() && new > old + MIN_GAIN && new >= RIM_MIN_DEG.to_radians()).then_some(new - old)
}

/// Smallest angle (degrees) a rim collapse must leave around it: a collapse that leaves a
/// smaller one (often a face of the bottom, which nothing later mends) may block the sliver
/// removal of [`super::uncross`], which moves the free vertex at the needle instead.
const RIM_MIN_DEG: f64 = 15.0;

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
/// points) and turns by at most 45 degrees from `normal` (the removed faces' summed normal, or
/// the normal of the face it replaces).
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
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; 5], role, has_plane: vec![true; 5], orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane };
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

    /// Two rim vertices (that stay, with planar points) 0.05 apart under a free apex, over a
    /// bottom vertex without a planar point: the needle at the apex goes with the short edge.
    #[test]
    fn a_short_rim_edge_under_a_needle_is_collapsed() {
        let plane = vec![[0.0, 0.0], [0.05, 0.0], [1.0, 0.0], [0.5, 1.0], [0.0, 0.0]];
        let position = vec![[0.0, 0.0, 0.0], [0.05, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0, 0.0], [0.5, -0.5, 0.0]];
        let faces = vec![[0, 1, 3], [1, 2, 3], [1, 0, 4], [2, 1, 4]];
        let role = vec![Role::Fixed, Role::Fixed, Role::Fixed, Role::Free, Role::Fixed];
        let has_plane = vec![true, true, true, true, false];
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; 5], role, has_plane, orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane };
        assert_eq!(collapse_rim_slivers(&mut mesh), 1);
        assert_eq!(mesh.faces, vec![[0, 2, 3], [2, 0, 4]]);
        let after = mesh.faces.iter().map(|f| smallest_angle(mesh.position[f[0] as usize], mesh.position[f[1] as usize], mesh.position[f[2] as usize])).fold(f64::INFINITY, f64::min);
        assert!((after.to_degrees() - 45.0).abs() < 1e-9, "{}", after.to_degrees());
    }

    /// A well-shaped valence-4 vertex (the square's centre) stays.
    #[test]
    fn a_vertex_without_slivers_stays() {
        let plane = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        let position: Vec<[f64; 3]> = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let faces = vec![[4, 1, 2], [4, 2, 3], [4, 3, 0], [4, 0, 1]];
        let role = vec![Role::Fixed, Role::Fixed, Role::Fixed, Role::Fixed, Role::Free];
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; 5], role, has_plane: vec![true; 5], orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane };
        assert_eq!(remove_sliver_vertices(&mut mesh), 0);
        assert_eq!(mesh.faces.len(), 4);
    }
}
