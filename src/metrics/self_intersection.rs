//! Self-intersecting faces: faces that cross another face of the same mesh that is not their
//! edge neighbour, as MeshLab counts them (`Select Self Intersecting Faces`, pymeshlab's
//! `compute_selection_by_self_intersections_per_face`, which is vcglib's
//! `tri::Clean::SelfIntersections` with `TestFaceFaceIntersection`).
//!
//! The pair test follows vcglib's, case by case of the number of vertices the two faces share
//! (as indices, not positions):
//! - 3 (a duplicated face): the faces intersect;
//! - 2 (edge neighbours): they never do;
//! - 1: the segment joining the midpoints of the two edges at the shared vertex of the face
//!   with the lower index (its opposite edge moved halfway towards the shared vertex, which
//!   keeps the shared vertex itself out of the test) is tested against the other face, and it
//!   must hit that face's interior (barycentric coordinates above 1e-6, not on an edge);
//!   a hit near the other face's border ends the test with "no intersection", as in vcglib;
//!   otherwise the other face's such segment is tested against the first face the same way.
//!   So a face sharing exactly one vertex with another still counts when they cross away
//!   from that vertex; two coplanar faces folded over each other at a shared vertex do not
//!   (the segment is parallel to the face), as in MeshLab. vcglib's bound for "parallel" is
//!   an absolute determinant of 1e-6 (an area), kept here to give MeshLab's count: on a mesh
//!   whose edges are much shorter than 1e-3 units, faces that share a vertex are then
//!   seldom found to cross (scale such a mesh up to count them);
//! - 0: a closed triangle-triangle test (touching counts) on `f64` orientations, with a
//!   planar test for coplanar pieces (vcglib uses Möller's interval test, which also counts
//!   touching triangles); a face whose corners are within a relative 1e-12 of the other's
//!   plane is coplanar with it (`tri_tri::COPLANAR`), so that the rounding residues of a flat
//!   region's faces do not make them touch.
//!
//! Candidate pairs come from a uniform grid of the faces' bounding boxes (cells about twice
//! the mean face extent, stored as sorted `(cell, face)` pairs, not as a hash map). Each pair
//! of overlapping boxes is tested in exactly one cell, the one holding the lower corner of the
//! boxes' overlap, so there is no de-duplication; cells are processed in parallel and their
//! results collected in cell order, so the faces found do not depend on the thread count.
//!
//! Agreement with MeshLab (pymeshlab 2025.7.post1, which computes in `f32`;
//! `benchmarks/self_intersection_check.py`): on the 11 meshes of tests/data, each as input,
//! as capmesh's remesh at 5000 faces, as MeshLab's isotropic remesh and with its vertices
//! jittered by 0.4 mean edges (up to 10768 flagged faces), the counts are equal on 43 of 44,
//! with the remeshes of the area-only stage (bird skull, hand and bunny: 247, 227 and 96 in
//! both) and again with those of the shape stage (0, 48 and 0; face 24, hippocampus sheet 6,
//! 48k brain 4); the one difference is the hippocampus sheet input, 769 here against 737,
//! whose 28 zero-area faces the two triangle tests treat differently. On two synthetic
//! marching-cubes long bones (`benchmarks/external.py`) both count none.

use super::tri_tri::segment_hits_triangle;
pub use super::tri_tri::triangles_intersect;
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// vcglib's margin on the barycentric coordinates of a segment's hit (`EPSIL`).
const BARY_EPS: f64 = 1e-6;

/// Faces of `mesh` that intersect another face (MeshLab's definition, see the module docs),
/// sorted by index.
pub fn self_intersecting_faces(mesh: &TriMesh) -> Vec<u32> {
    let pairs = intersecting_pairs(mesh);
    let mut flagged = vec![false; mesh.n_faces()];
    for (f, g) in pairs {
        flagged[f as usize] = true;
        flagged[g as usize] = true;
    }
    flagged.iter().enumerate().filter(|(_, &x)| x).map(|(f, _)| f as u32).collect()
}

/// Number of [`self_intersecting_faces`].
pub fn count_self_intersecting_faces(mesh: &TriMesh) -> usize {
    self_intersecting_faces(mesh).len()
}

/// Whether faces `f` and `g` (different indices) of `mesh` intersect by MeshLab's test.
pub fn faces_intersect(mesh: &TriMesh, f: usize, g: usize) -> bool {
    let (f, g) = (f.min(g), f.max(g));
    face_pair_intersects(mesh.faces[f], mesh.faces[g], |v| mesh.vertices[v as usize])
}

/// Whether the faces `a` and `b` (corner indices; `a` the one of lower face index) with corner
/// positions `position` intersect by MeshLab's test ([`faces_intersect`]).
pub(crate) fn face_pair_intersects(a: [u32; 3], b: [u32; 3], position: impl Fn(u32) -> [f64; 3]) -> bool {
    let p = a.map(&position);
    let q = b.map(&position);
    let mut shared = 0;
    let mut at = (0, 0);
    for i in 0..3 {
        for j in 0..3 {
            if a[i] == b[j] {
                shared += 1;
                at = (i, j);
            }
        }
    }
    if shared >= 2 {
        // Edge neighbours never intersect; a duplicated face always does.
        return shared >= 3;
    }
    match shared {
        0 => triangles_intersect(p, q),
        _ => {
            let (i0, i1) = at;
            let s = p[i0];
            let mid = |x: [f64; 3]| [0.5 * (x[0] + s[0]), 0.5 * (x[1] + s[1]), 0.5 * (x[2] + s[2])];
            for (from, to, k) in [(p, q, i0), (q, p, i1)] {
                let seg = (mid(from[(k + 1) % 3]), mid(from[(k + 2) % 3]));
                if let Some((u, v)) = segment_hits_triangle(seg.0, seg.1, to) {
                    return !(u + v >= 1.0 || u <= BARY_EPS || v <= BARY_EPS);
                }
            }
            false
        }
    }
}

/// All pairs `(f, g)`, `f < g`, of intersecting faces, in a fixed order.
fn intersecting_pairs(mesh: &TriMesh) -> Vec<(u32, u32)> {
    let n = mesh.n_faces();
    if n < 2 {
        return Vec::new();
    }
    let boxes: Vec<[[f64; 3]; 2]> = mesh
        .faces
        .par_iter()
        .map(|t| {
            let q = t.map(|v| mesh.vertices[v as usize]);
            [[0, 1, 2].map(|k| q[0][k].min(q[1][k]).min(q[2][k])), [0, 1, 2].map(|k| q[0][k].max(q[1][k]).max(q[2][k]))]
        })
        .collect();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for b in &boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(b[0][k]);
            hi[k] = hi[k].max(b[1][k]);
        }
    }
    if !(0..3).all(|k| lo[k].is_finite() && hi[k].is_finite()) {
        // Non-finite coordinates: no meaningful grid; test every pair (only for tiny meshes
        // in practice, as readers reject such files).
        return brute_force_pairs(mesh);
    }
    let mean_extent = boxes.iter().map(|b| (0..3).map(|k| b[1][k] - b[0][k]).fold(0.0, f64::max)).sum::<f64>() / n as f64;
    let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    // At most 2^20 cells along an axis (keys pack 21 bits per axis); cells grow while the
    // faces' boxes would fill too many of them (long slivers across the mesh).
    let mut cell = (2.0 * mean_extent).max(diag * 1e-6).max(1e-300);
    for k in 0..3 {
        cell = cell.max((hi[k] - lo[k]) / (1u64 << 20) as f64);
    }
    let index = |x: f64, k: usize, cell: f64| (((x - lo[k]) / cell).floor() as i64).clamp(0, (1 << 20) - 1);
    let span = |b: &[[f64; 3]; 2], cell: f64| -> ([i64; 3], [i64; 3]) { ([0, 1, 2].map(|k| index(b[0][k], k, cell)), [0, 1, 2].map(|k| index(b[1][k], k, cell))) };
    loop {
        let entries: u64 = boxes
            .par_iter()
            .map(|b| {
                let (i0, i1) = span(b, cell);
                (0..3).map(|k| (i1[k] - i0[k] + 1) as u64).product::<u64>()
            })
            .sum();
        if entries <= 16 * n as u64 + 1024 {
            break;
        }
        cell *= 2.0;
    }
    let mut entries: Vec<(u64, u32)> = boxes
        .par_iter()
        .enumerate()
        .flat_map_iter(|(f, b)| {
            let (i0, i1) = span(b, cell);
            (i0[2]..=i1[2]).flat_map(move |z| (i0[1]..=i1[1]).flat_map(move |y| (i0[0]..=i1[0]).map(move |x| (key(x, y, z), f as u32))))
        })
        .collect();
    entries.par_sort_unstable();
    let mut starts: Vec<usize> = (0..entries.len()).filter(|&i| i == 0 || entries[i].0 != entries[i - 1].0).collect();
    starts.push(entries.len());
    starts
        .par_windows(2)
        .flat_map_iter(|w| {
            let group = &entries[w[0]..w[1]];
            let cell_key = group[0].0;
            let boxes = &boxes;
            let mut found = Vec::new();
            for (i, &(_, f)) in group.iter().enumerate() {
                let bf = &boxes[f as usize];
                for &(_, g) in &group[i + 1..] {
                    let bg = &boxes[g as usize];
                    if !(0..3).all(|k| bf[0][k] <= bg[1][k] && bg[0][k] <= bf[1][k]) {
                        continue;
                    }
                    // Test the pair only in the cell of the overlap's lower corner.
                    let corner = [0, 1, 2].map(|k| index(bf[0][k].max(bg[0][k]), k, cell));
                    if key(corner[0], corner[1], corner[2]) != cell_key {
                        continue;
                    }
                    if faces_intersect(mesh, f as usize, g as usize) {
                        found.push((f, g));
                    }
                }
            }
            found.into_iter()
        })
        .collect()
}

/// Every intersecting pair by testing all `n (n - 1) / 2` pairs (for tests and odd inputs).
fn brute_force_pairs(mesh: &TriMesh) -> Vec<(u32, u32)> {
    let n = mesh.n_faces();
    (0..n).flat_map(|f| (f + 1..n).filter(move |&g| faces_intersect(mesh, f, g)).map(move |g| (f as u32, g as u32))).collect()
}

/// Hash key of a grid cell (21 bits per axis).
#[inline]
fn key(x: i64, y: i64, z: i64) -> u64 {
    ((x as u64) << 42) | ((y as u64) << 21) | z as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::{icosphere, torus, uv_sphere};
    use crate::metrics::tri_tri::tests::random;

    fn brute_force(mesh: &TriMesh) -> Vec<u32> {
        let mut flagged = vec![false; mesh.n_faces()];
        for (f, g) in brute_force_pairs(mesh) {
            flagged[f as usize] = true;
            flagged[g as usize] = true;
        }
        (0..mesh.n_faces() as u32).filter(|&f| flagged[f as usize]).collect()
    }

    #[test]
    fn smooth_closed_surfaces_have_none() {
        for mesh in [icosphere(4), uv_sphere(30, 40), torus(1.0, 0.3, 40, 20)] {
            assert_eq!(count_self_intersecting_faces(&mesh), 0);
        }
    }

    #[test]
    fn two_crossing_triangles() {
        // Two triangles that pierce each other, sharing no vertex, and a third far away.
        let mesh = TriMesh::new(
            vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.0], [9.0, 9.0, 9.0], [9.0, 10.0, 9.0], [10.0, 9.0, 9.0]],
            vec![[0, 1, 2], [3, 4, 5], [6, 7, 8]],
        );
        assert_eq!(self_intersecting_faces(&mesh), vec![0, 1]);
        // Moved apart, they do not.
        let mut apart = mesh.clone();
        for v in 3..6 {
            apart.vertices[v][0] += 5.0;
        }
        assert!(self_intersecting_faces(&apart).is_empty());
        // Touching at a point (a vertex on the other's interior) counts, as in vcglib's test.
        let touching = TriMesh::new(vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.5, 1.0], [1.5, 0.5, 1.0]], vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(self_intersecting_faces(&touching), vec![0, 1]);
    }

    #[test]
    fn faces_sharing_a_vertex() {
        // Face 1 shares vertex 0 with face 0 and passes through face 0 away from it.
        let v = vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [1.0, 1.0, -1.0], [1.0, 1.0, 1.0]];
        let crossing = TriMesh::new(v.clone(), vec![[0, 1, 2], [0, 3, 4]]);
        assert_eq!(self_intersecting_faces(&crossing), vec![0, 1]);
        // The same faces when face 1 only leans over face 0: no intersection.
        let mut leaning = crossing.clone();
        leaning.vertices[3] = [1.0, 1.0, 0.5];
        assert!(self_intersecting_faces(&leaning).is_empty());
        // Edge neighbours never count, even folded flat onto each other.
        let folded = TriMesh::new(vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.5, 0.5, 0.0]], vec![[0, 1, 2], [1, 0, 3]]);
        assert!(self_intersecting_faces(&folded).is_empty());
        // A duplicated face does.
        let dup = TriMesh::new(v, vec![[0, 1, 2], [2, 0, 1]]);
        assert_eq!(self_intersecting_faces(&dup), vec![0, 1]);
    }

    /// The grid against every pair, on spheres whose vertices are pushed about at random
    /// (many intersections of every kind) and on a mesh of random triangles.
    #[test]
    fn grid_matches_brute_force() {
        let mut rand = random(11);
        for (k, base) in [icosphere(2), icosphere(3), uv_sphere(12, 17)].into_iter().enumerate() {
            for amount in [0.02, 0.1, 0.4] {
                let mut mesh = base.clone();
                for p in &mut mesh.vertices {
                    for x in p.iter_mut() {
                        *x += amount * (rand() - 0.5);
                    }
                }
                let fast = self_intersecting_faces(&mesh);
                assert_eq!(fast, brute_force(&mesh), "mesh {k}, noise {amount}");
                if amount >= 0.4 {
                    assert!(!fast.is_empty(), "mesh {k}, noise {amount}: some faces cross");
                }
            }
        }
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        for f in 0..300u32 {
            let c = [rand() * 5.0, rand() * 5.0, rand() * 5.0];
            for _ in 0..3 {
                vertices.push([c[0] + rand() - 0.5, c[1] + rand() - 0.5, c[2] + rand() - 0.5]);
            }
            faces.push([3 * f, 3 * f + 1, 3 * f + 2]);
        }
        let soup = TriMesh::new(vertices, faces);
        let fast = self_intersecting_faces(&soup);
        assert_eq!(fast, brute_force(&soup));
        assert!(fast.len() > 10);
    }

    /// The same faces on one and on four threads (the grid's cells are split between them).
    #[test]
    fn independent_of_the_thread_count() {
        let mut rand = random(3);
        let mut mesh = icosphere(4);
        for p in &mut mesh.vertices {
            for x in p.iter_mut() {
                *x += 0.2 * (rand() - 0.5);
            }
        }
        let run = |threads: usize| rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| self_intersecting_faces(&mesh));
        let one = run(1);
        assert!(!one.is_empty());
        assert_eq!(one, run(4));
    }
}
