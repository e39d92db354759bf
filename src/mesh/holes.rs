//! Filling an open surface's holes (ours; docs/method.md, "Holes"): a closed surface with
//! some faces missing (a segmentation cut by the volume's edge, a gap in a scan) is a disk
//! whose boundary is far shorter than the surface is wide, and a disk's map squeezes it
//! (the bundled bunny with the six faces around one vertex removed maps at mean |d_area|
//! 7.9). Filled, it is a closed surface, mapped by puncturing it.
//!
//! Each boundary loop gets one vertex at the mean of its vertices and a fan of faces to it,
//! wound against the loop's faces so that the orientation stays coherent.

use super::topology::{edge_faces, Topology};
use super::TriMesh;
use std::collections::HashMap;

/// A surface with its holes filled: the input's vertices and faces first, in their order,
/// then one vertex per hole and the fans' faces.
#[derive(Debug, Clone)]
pub struct FilledHoles {
    /// The filled surface.
    pub mesh: TriMesh,
    /// Holes filled (the input's boundary loops).
    pub holes: usize,
    /// For each added face, in order: the input face across its edge on the hole's rim, and
    /// the corners (indices 0..3 in that input face) of that edge as they come in the added
    /// face's first two corners.
    pub across: Vec<(usize, [usize; 2])>,
}

impl FilledHoles {
    /// The input face and corner weights of a point of the filled surface given by `face`
    /// and `barycentric` there: itself on an input face; on an added face, the point of the
    /// rim edge across it that shares its weights on the rim's two corners, the hole's
    /// vertex's weight split evenly between them (the input has no point inside the hole).
    pub fn on_input(&self, face: usize, barycentric: [f64; 3]) -> (usize, [f64; 3]) {
        let n_input = self.mesh.n_faces() - self.across.len();
        let Some(&(input, [i, j])) = face.checked_sub(n_input).and_then(|k| self.across.get(k)) else { return (face, barycentric) };
        let mut w = [0.0; 3];
        w[i] = barycentric[0] + 0.5 * barycentric[2];
        w[j] = barycentric[1] + 0.5 * barycentric[2];
        (input, w)
    }
}

/// Fill every hole of `mesh` (see the module docs). `None` when `mesh` is not a manifold
/// (its [`Topology`] cannot be built) or has no boundary.
pub fn fill_holes(mesh: &TriMesh) -> Option<FilledHoles> {
    let topology = Topology::build(mesh).ok()?;
    if topology.boundary_loops.is_empty() {
        return None;
    }
    // The face of each boundary edge, keyed by the edge's direction in it.
    let rim: HashMap<(u32, u32), usize> = edge_faces(mesh)
        .ok()?
        .iter()
        .filter_map(|e| match (e.left, e.right) {
            (Some(t), None) => Some(((e.a, e.b), t as usize)),
            (None, Some(t)) => Some(((e.b, e.a), t as usize)),
            _ => None,
        })
        .collect();
    let mut vertices = mesh.vertices.clone();
    let mut faces = mesh.faces.clone();
    let mut across = Vec::new();
    for ring in &topology.boundary_loops {
        let m = ring.len() as f64;
        let centre = ring.iter().fold([0.0; 3], |s, &v| {
            let p = mesh.vertices[v as usize];
            [s[0] + p[0] / m, s[1] + p[1] / m, s[2] + p[2] / m]
        });
        let c = vertices.len() as u32;
        vertices.push(centre);
        for (&a, &b) in ring.iter().zip(ring.iter().cycle().skip(1)) {
            // The loop runs as its faces do (a -> b in face t): the added face runs b -> a.
            let t = *rim.get(&(a, b))?;
            let k = mesh.faces[t].iter().position(|&v| v == a)?;
            faces.push([b, a, c]);
            across.push((t, [(k + 1) % 3, k]));
        }
    }
    Some(FilledHoles { holes: topology.boundary_loops.len(), mesh: TriMesh { vertices, faces }, across })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::icosphere;

    /// An icosphere with the faces around two vertices removed: two holes, filled into a
    /// closed surface (Euler characteristic 2, coherently oriented), the input's vertices and
    /// faces first and unchanged.
    #[test]
    fn two_holes_filled_give_a_closed_coherent_sphere() {
        let sphere = icosphere(2);
        let (v1, v2) = (0u32, 5u32);
        let faces: Vec<[u32; 3]> = sphere.faces.iter().copied().filter(|f| !f.contains(&v1) && !f.contains(&v2)).collect();
        let open = TriMesh { vertices: sphere.vertices.clone(), faces };
        let filled = fill_holes(&open).unwrap();
        assert_eq!(filled.holes, 2);
        assert_eq!(filled.mesh.faces[..open.n_faces()], open.faces[..]);
        assert_eq!(filled.mesh.vertices[..open.n_vertices()], open.vertices[..]);
        assert_eq!(filled.across.len(), filled.mesh.n_faces() - open.n_faces());
        let topology = Topology::build(&filled.mesh).unwrap();
        assert!(topology.boundary_loops.is_empty());
        // The two removed vertices are unused now: V - E + F over used vertices.
        assert_eq!(topology.euler_characteristic, 2);
        // Coherent: every edge is met once each way.
        let mut seen = std::collections::HashSet::new();
        for f in &filled.mesh.faces {
            for k in 0..3 {
                assert!(seen.insert((f[k], f[(k + 1) % 3])), "edge {:?} twice the same way", (f[k], f[(k + 1) % 3]));
            }
        }
        // A closed mesh has nothing to fill.
        assert!(fill_holes(&filled.mesh).is_none());
    }

    /// A point on an added face names the input face across the rim, on the rim's edge.
    #[test]
    fn a_point_in_a_hole_names_the_rim_edge_across() {
        let sphere = icosphere(1);
        let faces: Vec<[u32; 3]> = sphere.faces.iter().copied().filter(|f| !f.contains(&0)).collect();
        let open = TriMesh { vertices: sphere.vertices.clone(), faces };
        let filled = fill_holes(&open).unwrap();
        let n = open.n_faces();
        for (k, &(t, [i, j])) in filled.across.iter().enumerate() {
            let added = filled.mesh.faces[n + k];
            assert_eq!([open.faces[t][i], open.faces[t][j]], [added[0], added[1]]);
            let (face, w) = filled.on_input(n + k, [0.2, 0.3, 0.5]);
            assert_eq!(face, t);
            assert!((w[i] - 0.45).abs() < 1e-15 && (w[j] - 0.55).abs() < 1e-15 && w[3 - i - j] == 0.0);
        }
        assert_eq!(filled.on_input(3, [0.2, 0.3, 0.5]), (3, [0.2, 0.3, 0.5]));
    }
}
