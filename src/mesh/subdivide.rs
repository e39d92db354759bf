//! Midpoint (1:4) subdivision: every face split into four by its edge midpoints, the
//! midpoints left on the flat face (no smoothing), so the subdivided mesh is the same
//! surface with four times the faces.
//!
//! The scale tests and the stage benchmark (issue 27) use it to make large meshes whose map
//! must be as good as their coarse version's: the geometry, and so the ideal map, does not
//! change.

use super::fasthash::FastMap;
use super::geometry::{add, scale};
use super::TriMesh;

/// `mesh` with every face split into four at its edge midpoints, `times` times over.
///
/// Vertices keep their indices; each edge's midpoint is added once (shared by both faces of
/// an interior edge), so a closed surface stays closed and an open one keeps its boundary
/// loop (with its midpoints). Face orientation is kept. The mesh has `V + E` vertices and
/// `4 F` faces after one step. Faces with an out-of-range index are dropped (the input is
/// not validated here: [`crate::mesh::validate()`] says what is wrong with such a mesh).
pub fn subdivide_midpoint(mesh: &TriMesh, times: usize) -> TriMesh {
    let mut out = mesh.clone();
    for _ in 0..times {
        out = subdivide_once(&out);
    }
    out
}

/// One 1:4 step of [`subdivide_midpoint`].
fn subdivide_once(mesh: &TriMesh) -> TriMesh {
    let n = mesh.vertices.len();
    let mut vertices = mesh.vertices.clone();
    vertices.reserve(mesh.faces.len() * 3 / 2 + 8);
    let mut midpoint: FastMap<(u32, u32), u32> = FastMap::default();
    midpoint.reserve(mesh.faces.len() * 3 / 2 + 8);
    let mut faces = Vec::with_capacity(4 * mesh.faces.len());
    for &[a, b, c] in &mesh.faces {
        if [a, b, c].iter().any(|&v| v as usize >= n) {
            continue;
        }
        let mut mid = |p: u32, q: u32| -> u32 {
            *midpoint.entry((p.min(q), p.max(q))).or_insert_with(|| {
                vertices.push(scale(add(mesh.vertices[p as usize], mesh.vertices[q as usize]), 0.5));
                (vertices.len() - 1) as u32
            })
        };
        let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
        faces.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    TriMesh::new(vertices, faces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::geometry::{cross, dot, face_areas, sub};
    use crate::mesh::shapes::{grid_disk, icosphere};
    use crate::mesh::Topology;

    fn normal(m: &TriMesh, f: usize) -> [f64; 3] {
        let [a, b, c] = m.face_points(f);
        cross(sub(b, a), sub(c, a))
    }

    #[test]
    fn a_closed_surface_stays_closed_with_the_same_area_and_orientation() {
        let m = icosphere(2);
        let s = subdivide_midpoint(&m, 2);
        assert_eq!(s.faces.len(), 16 * m.faces.len());
        // Euler: V - E + F = 2 with E = 3F/2.
        assert_eq!(s.vertices.len(), 2 + s.faces.len() / 2);
        let topo = Topology::build(&s).unwrap();
        assert!(topo.boundary_loops.is_empty());
        assert_eq!(topo.euler_characteristic, 2);
        let area = |m: &TriMesh| face_areas(&m.vertices, &m.faces).iter().sum::<f64>();
        assert!((area(&s) - area(&m)).abs() < 1e-12 * area(&m), "{} vs {}", area(&s), area(&m));
        // Every child face's normal points the way of its parent's (the first four are face 0's
        // children after one step; after two, the first sixteen).
        let n0 = normal(&m, 0);
        for f in 0..16 {
            let nf = normal(&s, f);
            assert!(dot(n0, nf) > 0.99 * (dot(n0, n0) * dot(nf, nf)).sqrt(), "face {f}");
        }
    }

    #[test]
    fn an_open_disk_keeps_one_boundary_loop_twice_as_long() {
        let m = grid_disk(4);
        let s = subdivide_midpoint(&m, 1);
        let (a, b) = (Topology::build(&m).unwrap(), Topology::build(&s).unwrap());
        assert_eq!(b.boundary_loops.len(), 1);
        assert_eq!(b.boundary_loops[0].len(), 2 * a.boundary_loops[0].len());
        assert_eq!(subdivide_midpoint(&m, 0), m);
    }
}
