//! Crossings counted around one vertex (ours; see [`super`]): the faces within a few rings of
//! it, and the crossing pairs between its own faces and those, with the vertex at a trial
//! point. Every crossing on the shared meshes is this local (docs/method.md, "18. Remesh
//! shape"), so a move or flip is judged by these counts instead of a whole-mesh test.

use crate::metrics::self_intersection::face_pair_intersects;
use crate::remesh::shape::state::{Incidence, Shaping};

/// Rings around a vertex whose faces are tested against its own.
const RINGS: usize = 3;

/// The faces within [`RINGS`] rings of vertex `v`, sorted.
pub(crate) fn faces_around(mesh: &Shaping, incidence: &Incidence, v: usize) -> Vec<u32> {
    let mut verts = vec![v as u32];
    let mut faces: Vec<u32> = Vec::new();
    let mut frontier = vec![v as u32];
    for _ in 0..RINGS {
        let mut next = Vec::new();
        for &u in &frontier {
            for &t in incidence.of(u as usize) {
                faces.push(t);
                for &w in &mesh.faces[t as usize] {
                    if !verts.contains(&w) {
                        verts.push(w);
                        next.push(w);
                    }
                }
            }
        }
        frontier = next;
    }
    faces.sort_unstable();
    faces.dedup();
    faces
}

/// Crossing pairs between the faces `ring` (at `v`, with `v` at `x`) and the faces `near`.
pub(crate) fn local_crossings(mesh: &Shaping, ring: &[u32], near: &[u32], v: usize, x: [f64; 3]) -> usize {
    let at = |u: u32| if u as usize == v { x } else { mesh.position[u as usize] };
    let mut count = 0;
    for &r in ring {
        for &g in near {
            // A pair of two ring faces is counted once, from its lower face.
            if g == r || (ring.contains(&g) && g < r) {
                continue;
            }
            let (lo, hi) = (r.min(g), r.max(g));
            if face_pair_intersects(mesh.faces[lo as usize], mesh.faces[hi as usize], at) {
                count += 1;
            }
        }
    }
    count
}
