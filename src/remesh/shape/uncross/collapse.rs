//! The last resort of the crossing pass (ours; see [`super`]): an edge collapse at a
//! crumpled spot that no flip or move mends.

use super::{faces_around, local_crossings, MIN_ANGLE};
use crate::mesh::geometry::triangle_area;
use crate::remesh::shape::state::{drop_faces, link_is_two, smallest_angle, Incidence, Role, Shaping};

/// Where flips and moves leave crossing faces (a crumpled spot of a few faces across a thin
/// part), collapse an edge of a crossing face: a free vertex with a planar point merged into a
/// neighbour with one (which stays where it is), when the edge's link is two vertices, every
/// changed face keeps its planar orientation and an area, no angle falls below the faces'
/// smallest or [`MIN_ANGLE`], and the crossings among the faces around both ends fall. At most
/// one collapse per neighbourhood; the two faces of each collapsed edge are removed (the
/// vertex keeps its slot with no face). Returns the number of collapses.
pub(super) fn uncross_by_collapse(mesh: &mut Shaping, flagged: &[u32]) -> usize {
    let incidence = mesh.incidence();
    let mut dead = vec![false; mesh.faces.len()];
    let mut touched = vec![false; mesh.plane.len()];
    let mut collapses = 0;
    for &t in flagged {
        if dead[t as usize] {
            continue;
        }
        let f = mesh.faces[t as usize];
        'edges: for k in 0..3 {
            for (gone, kept) in [(f[k], f[(k + 1) % 3]), (f[(k + 1) % 3], f[k])] {
                if mesh.role[gone as usize] != Role::Free || !mesh.planar(gone) || !mesh.planar(kept) {
                    continue;
                }
                let around: Vec<u32> = incidence.of(gone as usize).iter().chain(incidence.of(kept as usize)).copied().collect();
                if around.iter().any(|&u| dead[u as usize] || mesh.faces[u as usize].iter().any(|&w| touched[w as usize])) {
                    continue;
                }
                if let Some(removed) = try_collapse(mesh, &incidence, &dead, gone, kept) {
                    for r in removed {
                        dead[r as usize] = true;
                    }
                    for &u in &around {
                        for &w in &mesh.faces[u as usize] {
                            touched[w as usize] = true;
                        }
                    }
                    touched[gone as usize] = true;
                    collapses += 1;
                    break 'edges;
                }
            }
        }
    }
    if collapses > 0 {
        drop_faces(&mut mesh.faces, &dead);
    }
    collapses
}

/// Merge `gone` into `kept` if that passes the tests of [`uncross_by_collapse`]: the faces
/// are changed in place and the two faces of the edge returned (to be removed); `None` (and
/// nothing changed) otherwise.
fn try_collapse(mesh: &mut Shaping, incidence: &Incidence, dead: &[bool], gone: u32, kept: u32) -> Option<[u32; 2]> {
    if !link_is_two(mesh, incidence, gone, kept) {
        return None;
    }
    let ring_gone = incidence.of(gone as usize);
    let removed: Vec<u32> = ring_gone.iter().copied().filter(|&t| mesh.faces[t as usize].contains(&kept)).collect();
    let [r1, r2] = removed[..] else { return None };
    let x = |v: u32| mesh.position[v as usize];
    let angle = |f: [u32; 3]| if triangle_area(x(f[0]), x(f[1]), x(f[2])) > 0.0 { smallest_angle(x(f[0]), x(f[1]), x(f[2])) } else { 0.0 };
    let old_angle = ring_gone.iter().map(|&t| angle(mesh.faces[t as usize])).fold(f64::INFINITY, f64::min);
    let changed: Vec<(u32, [u32; 3])> = ring_gone
        .iter()
        .filter(|&&t| t != r1 && t != r2)
        .map(|&t| (t, mesh.faces[t as usize].map(|v| if v == gone { kept } else { v })))
        .collect();
    for &(_, g) in &changed {
        let p = g.map(|v| mesh.plane[v as usize]);
        if g.iter().all(|&v| mesh.planar(v)) && !mesh.oriented(p[0], p[1], p[2], 0.0) {
            return None;
        }
        if !(angle(g) >= old_angle.min(MIN_ANGLE.to_radians())) {
            return None;
        }
    }
    let mut near = faces_around(mesh, incidence, gone as usize);
    near.extend(faces_around(mesh, incidence, kept as usize));
    near.retain(|&t| !dead[t as usize]);
    near.sort_unstable();
    near.dedup();
    let mut ring: Vec<u32> = incidence.of(gone as usize).iter().chain(incidence.of(kept as usize)).copied().collect();
    ring.sort_unstable();
    ring.dedup();
    let before = local_crossings(mesh, &ring, &near, usize::MAX, [0.0; 3]);
    let old: Vec<(u32, [u32; 3])> = changed.iter().map(|&(t, _)| (t, mesh.faces[t as usize])).collect();
    for &(t, g) in &changed {
        mesh.faces[t as usize] = g;
    }
    ring.retain(|&t| t != r1 && t != r2);
    near.retain(|&t| t != r1 && t != r2);
    let after = local_crossings(mesh, &ring, &near, usize::MAX, [0.0; 3]);
    if after < before {
        return Some([r1, r2]);
    }
    for (t, f) in old {
        mesh.faces[t as usize] = f;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::TriMesh;
    use crate::metrics::self_intersection::self_intersecting_faces;

    /// A flat hexagon fanned around free vertex 0, raised to a spike of height 1, and a face
    /// hanging from corner 1 across it, its two far corners at height `hang` (the other
    /// vertices stay).
    fn spike_under(hang: f64) -> Shaping {
        let mut plane = vec![[0.0, 0.0]];
        plane.extend((0..6).map(|i| {
            let a = i as f64 * std::f64::consts::PI / 3.0;
            [a.cos(), a.sin()]
        }));
        plane.extend([[2.0, -0.5], [2.0, 0.5]]);
        let mut position: Vec<[f64; 3]> = plane.iter().map(|p| [p[0], p[1], 0.0]).collect();
        position[0] = [0.0, 0.0, 1.0];
        position[7] = [-1.5, -1.5, hang];
        position[8] = [-1.5, 1.5, hang];
        let mut faces: Vec<[u32; 3]> = (1..=6u32).map(|i| [0, i, i % 6 + 1]).collect();
        faces.push([1, 7, 8]);
        let role: Vec<Role> = (0..9).map(|v| if v == 0 { Role::Free } else { Role::Fixed }).collect();
        Shaping { faces, plane, position, hint: vec![u32::MAX; 9], role, has_plane: vec![true; 9], orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane }
    }

    fn crossing(m: &Shaping) -> Vec<u32> {
        self_intersecting_faces(&TriMesh::new(m.position.clone(), m.faces.clone()))
    }

    /// The spike pierces the hanging face; no flip or move is tried here: collapsing the spike
    /// into a neighbour removes two faces, leaves the rest flat and oriented, and no face
    /// crosses.
    #[test]
    fn a_spike_through_a_face_is_collapsed() {
        let mut mesh = spike_under(0.5);
        let flagged = crossing(&mesh);
        assert!(flagged.len() >= 2 && flagged.contains(&6), "{flagged:?}");
        assert_eq!(uncross_by_collapse(&mut mesh, &flagged), 1);
        assert_eq!(mesh.faces.len(), 5);
        assert!(mesh.faces.iter().all(|f| !f.contains(&0)), "{:?}", mesh.faces);
        assert!(crossing(&mesh).is_empty(), "{:?}", crossing(&mesh));
        for f in &mesh.faces {
            let p = f.map(|v| mesh.plane[v as usize]);
            assert!(mesh.oriented(p[0], p[1], p[2], 0.0), "{f:?}");
        }
    }

    /// The face hangs above the spike's tip: nothing crosses, so a collapse (asked for here
    /// with the spike's first face flagged) would lower no crossing and is refused.
    #[test]
    fn a_spike_that_crosses_nothing_stays() {
        let mut mesh = spike_under(5.0);
        let before = mesh.faces.clone();
        assert!(crossing(&mesh).is_empty());
        assert_eq!(uncross_by_collapse(&mut mesh, &[0]), 0);
        assert_eq!(mesh.faces, before);
    }
}
