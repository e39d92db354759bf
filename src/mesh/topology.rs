//! Combinatorial topology of a triangle mesh: edges, boundary loops, connected components,
//! Euler characteristic and genus, plus the adjacency helpers the numerical code needs.
//!
//! Edges are found by bucketing half-edges by their smaller end vertex (a counting sort, linear
//! in the mesh size, no hashing), so this stays fast and lean for meshes with millions of faces.

use crate::mesh::checks::{check_degenerate, check_duplicates, check_indices, check_not_empty, check_vertex_fans};
use crate::mesh::error::MeshError;
use crate::mesh::unionfind::UnionFind;
use crate::mesh::TriMesh;

/// Largest number of faces whose half-edges (`3 * face + k`) can be numbered with `u32`.
pub const MAX_FACES: usize = (u32::MAX / 3) as usize;

/// Topological summary of a manifold, consistently oriented triangle mesh.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Topology {
    /// Number of vertices in the mesh (including unreferenced ones).
    pub n_vertices: usize,
    /// Number of faces.
    pub n_faces: usize,
    /// Number of distinct (undirected) edges.
    pub n_edges: usize,
    /// Boundary loops. Each follows the boundary edges in the direction they have in their
    /// faces (face `(a, b, c)` with boundary edge `a -> b` gives `..., a, b, ...`), so the
    /// boundary of a disk with counter-clockwise faces runs counter-clockwise. Each loop starts
    /// at its smallest vertex index; loops are sorted by that vertex.
    pub boundary_loops: Vec<Vec<u32>>,
    /// Number of connected components (faces sharing a vertex are connected).
    pub n_components: usize,
    /// `V - E + F`, counting only vertices used by some face.
    pub euler_characteristic: i64,
}

/// An undirected edge `a < b` with its (at most two) incident faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// Smaller vertex index.
    pub a: u32,
    /// Larger vertex index.
    pub b: u32,
    /// The face that contains the directed edge `a -> b`, if any.
    pub left: Option<u32>,
    /// The face that contains the directed edge `b -> a`, if any.
    pub right: Option<u32>,
}

impl Edge {
    /// `true` when only one face uses this edge.
    pub fn is_boundary(&self) -> bool {
        self.left.is_none() || self.right.is_none()
    }
}

impl Topology {
    /// Compute the topology, failing on anything that is not an oriented 2-manifold (with or
    /// without boundary): [`MeshError::Empty`], [`MeshError::IndexOutOfRange`],
    /// [`MeshError::DegenerateFace`], [`MeshError::DuplicateFace`],
    /// [`MeshError::NonManifoldEdge`], [`MeshError::InconsistentOrientation`],
    /// [`MeshError::NonManifoldVertex`], [`MeshError::TooLarge`].
    pub fn build(mesh: &TriMesh) -> Result<Topology, MeshError> {
        check_not_empty(mesh)?;
        check_indices(mesh)?;
        check_degenerate(mesh)?;
        check_duplicates(mesh)?;
        let edges = edge_faces(mesh)?;
        check_vertex_fans(mesh, &edges)?;

        let boundary_loops = trace_boundary_loops(mesh.n_vertices(), &edges);
        let (n_components, n_referenced) = components(mesh);
        let euler_characteristic = n_referenced as i64 - edges.len() as i64 + mesh.n_faces() as i64;
        Ok(Topology {
            n_vertices: mesh.n_vertices(),
            n_faces: mesh.n_faces(),
            n_edges: edges.len(),
            boundary_loops,
            n_components,
            euler_characteristic,
        })
    }

    /// Genus of a single connected (orientable) component: `(2 - chi - loops) / 2`.
    /// `None` when there are several components or the formula does not give a non-negative
    /// integer.
    pub fn genus(&self) -> Option<i64> {
        if self.n_components != 1 {
            return None;
        }
        let twice = 2 - self.euler_characteristic - self.boundary_loops.len() as i64;
        (twice >= 0 && twice % 2 == 0).then_some(twice / 2)
    }

    /// `true` when the mesh has no boundary.
    pub fn is_closed(&self) -> bool {
        self.boundary_loops.is_empty()
    }
}

/// A face's vertices in increasing order: the same key for the same triangle in any winding.
pub(crate) fn sorted_face(face: [u32; 3]) -> [u32; 3] {
    let mut k = face;
    k.sort_unstable();
    k
}

/// Half-edges grouped by their smaller end vertex. Half-edge `h = 3 f + k` runs from
/// `faces[f][k]` to `faces[f][(k + 1) % 3]`. Faces with an out-of-range index and edges from a
/// vertex to itself are skipped.
struct HalfEdgeBuckets {
    /// `start[v]..start[v + 1]` indexes `items` for vertex `v`.
    start: Vec<usize>,
    /// `(other end vertex, half-edge id)`, sorted within each bucket.
    items: Vec<(u32, u32)>,
}

fn face_in_range(face: &[u32; 3], n: usize) -> bool {
    face.iter().all(|&v| (v as usize) < n)
}

impl HalfEdgeBuckets {
    fn new(mesh: &TriMesh) -> Self {
        let n = mesh.n_vertices();
        let faces = &mesh.faces[..mesh.n_faces().min(MAX_FACES)];
        let mut start = vec![0usize; n + 1];
        for face in faces.iter().filter(|f| face_in_range(f, n)) {
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                if a != b {
                    start[a.min(b) as usize + 1] += 1;
                }
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut items = vec![(0u32, 0u32); start[n]];
        for (f, face) in faces.iter().enumerate() {
            if !face_in_range(face, n) {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                if a != b {
                    let slot = &mut fill[a.min(b) as usize];
                    items[*slot] = (a.max(b), (3 * f + k) as u32);
                    *slot += 1;
                }
            }
        }
        for v in 0..n {
            items[start[v]..start[v + 1]].sort_unstable();
        }
        Self { start, items }
    }

    /// Calls `visit(a, b, half_edges)` for every undirected edge `a < b`, in sorted order.
    fn for_each_edge<E>(
        &self,
        mut visit: impl FnMut(u32, u32, &[(u32, u32)]) -> Result<(), E>,
    ) -> Result<(), E> {
        for a in 0..self.start.len().saturating_sub(1) {
            let bucket = &self.items[self.start[a]..self.start[a + 1]];
            let mut i = 0;
            while i < bucket.len() {
                let b = bucket[i].0;
                let mut j = i + 1;
                while j < bucket.len() && bucket[j].0 == b {
                    j += 1;
                }
                visit(a as u32, b, &bucket[i..j])?;
                i = j;
            }
        }
        Ok(())
    }
}

/// Start vertex of half-edge `h`.
#[inline]
fn tail(faces: &[[u32; 3]], h: u32) -> u32 {
    faces[h as usize / 3][h as usize % 3]
}

/// Every edge with its incident faces, sorted by `(a, b)`.
///
/// Fails with [`MeshError::NonManifoldEdge`] when an edge has more than two faces and with
/// [`MeshError::InconsistentOrientation`] when two faces use it in the same direction. Faces
/// with out-of-range indices are reported first ([`MeshError::IndexOutOfRange`]), faces with a
/// repeated vertex next ([`MeshError::DegenerateFace`]).
pub fn edge_faces(mesh: &TriMesh) -> Result<Vec<Edge>, MeshError> {
    check_indices(mesh)?;
    check_degenerate(mesh)?;
    if mesh.n_faces() > MAX_FACES {
        return Err(MeshError::TooLarge {
            n_faces: mesh.n_faces(),
            max: MAX_FACES,
        });
    }
    let buckets = HalfEdgeBuckets::new(mesh);
    let faces = &mesh.faces;
    let mut edges = Vec::with_capacity(buckets.items.len() / 2 + 1);
    buckets.for_each_edge(|a, b, hs| {
        let mut edge = Edge {
            a,
            b,
            left: None,
            right: None,
        };
        if hs.len() > 2 {
            return Err(MeshError::NonManifoldEdge {
                a,
                b,
                faces: hs.len(),
            });
        }
        for &(_, h) in hs {
            let f = h / 3;
            let slot = if tail(faces, h) == a {
                &mut edge.left
            } else {
                &mut edge.right
            };
            if let Some(other) = *slot {
                let (from, to) = if tail(faces, h) == a { (a, b) } else { (b, a) };
                return Err(MeshError::InconsistentOrientation {
                    a: from,
                    b: to,
                    faces: [other as usize, f as usize],
                });
            }
            *slot = Some(f);
        }
        edges.push(edge);
        Ok(())
    })?;
    Ok(edges)
}

/// A face's neighbour across one of its edges and whether it walks that edge the same way.
pub(crate) type Neighbour = Option<(u32, bool)>;

/// Each face's neighbour across each of its edges (edge `k` runs from corner `k` to `k + 1`)
/// and whether that neighbour walks the edge the same way (the two disagree in orientation);
/// `None` on a boundary edge. `None` altogether when an edge has more than two faces or the
/// mesh has more than [`MAX_FACES`] faces. Faces with an out-of-range index and edges from a
/// vertex to itself are skipped (check them first).
pub(crate) fn face_neighbours(mesh: &TriMesh) -> Option<Vec<[Neighbour; 3]>> {
    if mesh.n_faces() > MAX_FACES {
        return None;
    }
    let faces = &mesh.faces;
    let mut neighbours = vec![[None; 3]; faces.len()];
    HalfEdgeBuckets::new(mesh)
        .for_each_edge(|_, _, hs| {
            match *hs {
                [(_, h), (_, g)] => {
                    let same = tail(faces, h) == tail(faces, g);
                    neighbours[h as usize / 3][h as usize % 3] = Some((g / 3, same));
                    neighbours[g as usize / 3][g as usize % 3] = Some((h / 3, same));
                }
                [_] => {}
                _ => return Err(()),
            }
            Ok(())
        })
        .ok()?;
    Some(neighbours)
}

/// Position of vertex `v` in face `f` (0, 1 or 2).
#[inline]
fn corner_of(faces: &[[u32; 3]], f: u32, v: u32) -> u32 {
    let face = faces[f as usize];
    let k = face.iter().position(|&x| x == v).unwrap_or(0);
    3 * f + k as u32
}

/// The face corners of `mesh` joined into fans: two corners at the same vertex are in one
/// set when a path of faces around the vertex, across interior edges, joins them. A vertex
/// whose corners form more than one set is pinched (the surface touches itself there).
pub(crate) fn corner_fans(mesh: &TriMesh, edges: &[Edge]) -> UnionFind {
    let faces = &mesh.faces;
    let mut corners = UnionFind::new(3 * faces.len());
    for e in edges {
        if let (Some(l), Some(r)) = (e.left, e.right) {
            for v in [e.a, e.b] {
                corners.union(corner_of(faces, l, v), corner_of(faces, r, v));
            }
        }
    }
    corners
}

/// Boundary loops of a manifold, oriented mesh (see [`Topology::boundary_loops`]).
fn trace_boundary_loops(n_vertices: usize, edges: &[Edge]) -> Vec<Vec<u32>> {
    const NONE: u32 = u32::MAX;
    let mut next = vec![NONE; n_vertices];
    for e in edges {
        match (e.left, e.right) {
            (Some(_), None) => next[e.a as usize] = e.b,
            (None, Some(_)) => next[e.b as usize] = e.a,
            _ => {}
        }
    }
    let mut visited = vec![false; n_vertices];
    let mut loops = Vec::new();
    for start in 0..n_vertices {
        if next[start] == NONE || visited[start] {
            continue;
        }
        let mut lp = Vec::new();
        let mut v = start as u32;
        while v != NONE && !visited[v as usize] {
            visited[v as usize] = true;
            lp.push(v);
            v = next[v as usize];
        }
        loops.push(lp);
    }
    loops
}

/// `(number of components, number of referenced vertices)`; components are unions of faces
/// that share a vertex. Faces with out-of-range indices are ignored.
fn components(mesh: &TriMesh) -> (usize, usize) {
    let n = mesh.n_vertices();
    let mut uf = UnionFind::new(n);
    let mut used = vec![false; n];
    for face in mesh.faces.iter().filter(|f| face_in_range(f, n)) {
        uf.union(face[0], face[1]);
        uf.union(face[1], face[2]);
        for &v in face {
            used[v as usize] = true;
        }
    }
    let mut count = 0;
    let mut referenced = 0;
    for (v, &is_used) in used.iter().enumerate() {
        if is_used {
            referenced += 1;
            if uf.find(v as u32) == v as u32 {
                count += 1;
            }
        }
    }
    (count, referenced)
}

/// Sorted, de-duplicated neighbours of every vertex (vertices joined by a face edge).
/// Faces with out-of-range indices are ignored.
pub fn vertex_neighbors(mesh: &TriMesh) -> Vec<Vec<u32>> {
    neighbors_of_faces(mesh.n_vertices(), &mesh.faces)
}

/// [`vertex_neighbors`] of `n` vertices joined by the edges of `faces`.
pub fn neighbors_of_faces(n: usize, faces: &[[u32; 3]]) -> Vec<Vec<u32>> {
    let mut count = vec![0usize; n];
    for face in faces.iter().filter(|f| face_in_range(f, n)) {
        for k in 0..3 {
            let (a, b) = (face[k], face[(k + 1) % 3]);
            if a != b {
                count[a as usize] += 1;
                count[b as usize] += 1;
            }
        }
    }
    let mut out: Vec<Vec<u32>> = count.iter().map(|&c| Vec::with_capacity(c)).collect();
    for face in faces.iter().filter(|f| face_in_range(f, n)) {
        for k in 0..3 {
            let (a, b) = (face[k], face[(k + 1) % 3]);
            if a != b {
                out[a as usize].push(b);
                out[b as usize].push(a);
            }
        }
    }
    for list in &mut out {
        list.sort_unstable();
        list.dedup();
        list.shrink_to_fit();
    }
    out
}

/// `true` for every vertex on an edge that belongs to exactly one face.
/// Faces with out-of-range indices are ignored; no manifoldness is required.
pub fn is_boundary_vertex(mesh: &TriMesh) -> Vec<bool> {
    let mut mask = vec![false; mesh.n_vertices()];
    let buckets = HalfEdgeBuckets::new(mesh);
    let _ = buckets.for_each_edge::<()>(|a, b, hs| {
        if hs.len() == 1 {
            mask[a as usize] = true;
            mask[b as usize] = true;
        }
        Ok(())
    });
    mask
}

/// The faces around each vertex, in compressed rows (vertex `v`'s at `start[v]..start[v + 1]`).
pub(crate) struct VertexFaces {
    start: Vec<usize>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// The incidence of `n` vertices in `faces`.
    pub(crate) fn new(n: usize, faces: &[[u32; 3]]) -> Self {
        let mut start = vec![0usize; n + 1];
        for f in faces {
            for &v in f {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut next = start.clone();
        let mut list = vec![0u32; start[n]];
        for (t, f) in faces.iter().enumerate() {
            for &v in f {
                list[next[v as usize]] = t as u32;
                next[v as usize] += 1;
            }
        }
        Self { start, faces: list }
    }

    /// The faces at vertex `v`.
    pub(crate) fn of(&self, v: usize) -> &[u32] {
        &self.faces[self.start[v]..self.start[v + 1]]
    }
}

/// The vertices within `rings` edges of a `marked` one (`marked` grown ring by ring along
/// the edges of `faces`).
pub fn within_rings(marked: &[bool], faces: &[[u32; 3]], rings: usize) -> Vec<bool> {
    let neighbors = neighbors_of_faces(marked.len(), faces);
    let mut within = marked.to_vec();
    let mut frontier: Vec<u32> = (0..marked.len()).filter(|&v| marked[v]).map(|v| v as u32).collect();
    for _ in 0..rings {
        let mut next = Vec::new();
        for &v in &frontier {
            for &u in &neighbors[v as usize] {
                if !within[u as usize] {
                    within[u as usize] = true;
                    next.push(u);
                }
            }
        }
        frontier = next;
    }
    within
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::grid_disk;

    #[test]
    fn rings_grow_one_at_a_time() {
        // grid_disk(n): ring i has 6 i vertices; the rim is ring n.
        let mesh = grid_disk(10);
        let rim = is_boundary_vertex(&mesh);
        let count = |h: &[bool]| h.iter().filter(|x| **x).count();
        assert_eq!(count(&within_rings(&rim, &mesh.faces, 0)), 60);
        assert_eq!(count(&within_rings(&rim, &mesh.faces, 1)), 60 + 54);
        assert_eq!(count(&within_rings(&rim, &mesh.faces, 3)), 60 + 54 + 48 + 42);
        assert_eq!(count(&within_rings(&rim, &mesh.faces, 20)), mesh.n_vertices());
    }
}
