//! Midpoint (1:4) subdivision: every face split into four by its edge midpoints, the
//! midpoints left on the flat face (no smoothing), so the subdivided mesh is the same
//! surface with four times the faces.
//!
//! `remesh` maps an input with fewer faces than the remesh through it (docs/method.md section
//! 25), and the scale tests and the stage benchmark (issue 27) make large meshes with it whose
//! map must be as good as their coarse version's: the geometry, and so the ideal map, does
//! not change.

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

/// The four children of a parent face `[a, b, c]`, in the order [`subdivide_once`] writes
/// them, as indices into the parent's six points `[a, b, c, ab, bc, ca]` (its corners, then
/// its edges' midpoints): `[a, ab, ca]`, `[ab, b, bc]`, `[ca, bc, c]`, `[ab, bc, ca]`.
const CHILDREN: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];

/// The parent's six points of [`CHILDREN`] as barycentric coordinates of the parent face.
const POINTS: [[f64; 3]; 6] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5]];

/// The point with barycentric coordinates `barycentric` in face `face` of
/// `subdivide_midpoint(mesh, levels)`, as a face of `mesh` and barycentric coordinates there
/// (the same point: the children lie flat in their parent). Holds for a mesh whose faces all
/// index its vertices (a validated one), where face `f`'s children are faces `4 f .. 4 f + 3`.
pub(crate) fn parent_point(mut face: usize, mut barycentric: [f64; 3], levels: usize) -> (usize, [f64; 3]) {
    for _ in 0..levels {
        let corners = CHILDREN[face % 4].map(|k| POINTS[k]);
        barycentric = std::array::from_fn(|i| (0..3).map(|k| barycentric[k] * corners[k][i]).sum());
        face /= 4;
    }
    (face, barycentric)
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
        let points = [a, b, c, mid(a, b), mid(b, c), mid(c, a)];
        faces.extend(CHILDREN.map(|child| child.map(|k| points[k])));
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

    /// A point of a twice-subdivided face, taken back to its parent face, is the same point.
    #[test]
    fn a_point_of_a_child_face_is_the_same_point_of_its_parent() {
        let mut m = icosphere(1);
        // Uneven faces: the children are not similar to their parent.
        for (i, p) in m.vertices.iter_mut().enumerate() {
            p[0] *= 1.0 + 0.1 * (i % 3) as f64;
        }
        let s = subdivide_midpoint(&m, 2);
        let at = |mesh: &TriMesh, f: usize, b: [f64; 3]| -> [f64; 3] {
            let [p, q, r] = mesh.face_points(f);
            std::array::from_fn(|k| b[0] * p[k] + b[1] * q[k] + b[2] * r[k])
        };
        for f in (0..s.faces.len()).step_by(7) {
            let b = [0.2, 0.3 + 0.001 * (f % 10) as f64, 0.0];
            let b = [b[0], b[1], 1.0 - b[0] - b[1]];
            let (parent, pb) = parent_point(f, b, 2);
            assert_eq!(parent, f / 16);
            assert!((pb.iter().sum::<f64>() - 1.0).abs() < 1e-12 && pb.iter().all(|&w| w >= 0.0), "{pb:?}");
            let (x, y) = (at(&s, f, b), at(&m, parent, pb));
            assert!((0..3).all(|k| (x[k] - y[k]).abs() < 1e-12), "face {f}: {x:?} vs {y:?}");
        }
        assert_eq!(parent_point(5, [0.2, 0.3, 0.5], 0), (5, [0.2, 0.3, 0.5]));
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
