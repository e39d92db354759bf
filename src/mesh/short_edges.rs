//! Collapse of edges much shorter than the mesh's mean edge: the needles and collapsed rows of
//! a degenerate triangulation, which no power diagram of the transport can give their tiny
//! cells (ours; docs/method.md, "Degenerate triangulations").
//!
//! Half-edge collapses, shortest edge first: the removed vertex goes into the kept one, which
//! stays where it is (an input vertex, as in welding). A collapse is made only when it keeps
//! the surface a manifold of the same topology: the link condition (the endpoints share
//! exactly the vertices opposite the edge), no vertex left with fewer than three neighbours,
//! a boundary vertex never moved off the boundary, no edge joining two boundary vertices
//! across the interior collapsed, and no moved face turned over.

use super::geometry::{cross, dot, norm, sub};
use super::repair::{compact, Welded};
use super::topology::is_boundary_vertex;
use super::TriMesh;

/// Passes over the short edges at most.
const MAX_PASSES: usize = 8;

/// Collapse the edges of the manifold `mesh` shorter than `tolerance` (see the module docs).
/// The result has the same form as a weld: each input vertex's vertex in the new mesh, the
/// removed vertices counted in `merged_vertices` and the faces dropped in `removed_faces`.
pub fn collapse_short_edges(mesh: &TriMesh, tolerance: f64) -> Welded {
    let n = mesh.n_vertices();
    let x = &mesh.vertices;
    let length = |a: u32, b: u32| norm(sub(x[a as usize], x[b as usize]));
    let mut faces = mesh.faces.clone();
    let mut alive = vec![true; faces.len()];
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (f, t) in faces.iter().enumerate() {
        for &v in t {
            incident[v as usize].push(f as u32);
        }
    }
    let boundary = is_boundary_vertex(mesh);
    let mut rep: Vec<u32> = (0..n as u32).collect();
    // Collapses make new short edges (a squeezed row's vertices meet the row beyond): passes
    // over the live short edges until one collapses none.
    for _ in 0..MAX_PASSES {
        let mut short: Vec<(f64, u32, u32)> = faces
            .iter()
            .zip(&alive)
            .filter(|(_, &a)| a)
            .flat_map(|(t, _)| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
            .filter(|&(a, b)| a != b && length(a, b) < tolerance)
            .map(|(a, b)| (length(a, b), a, b))
            .collect();
        short.sort_by(|p, q| p.0.total_cmp(&q.0).then((p.1, p.2).cmp(&(q.1, q.2))));
        short.dedup_by(|p, q| (p.1, p.2) == (q.1, q.2));
        let mut collapsed = 0;
        for (_, a, b) in short {
            if rep[a as usize] != a || rep[b as usize] != b {
                continue;
            }
            // The boundary vertex stays: a boundary vertex moved inside would open the boundary.
            let (removed, kept) = if boundary[b as usize] && !boundary[a as usize] { (a, b) } else { (b, a) };
            if !collapsible(&faces, &alive, &incident, &boundary, x, removed, kept) {
                continue;
            }
            // The edge's faces die; the removed vertex's other faces move to the kept one.
            for f in std::mem::take(&mut incident[removed as usize]) {
                if faces[f as usize].contains(&kept) {
                    alive[f as usize] = false;
                    for v in faces[f as usize] {
                        if v != removed {
                            incident[v as usize].retain(|&g| g != f);
                        }
                    }
                } else {
                    faces[f as usize] = faces[f as usize].map(|v| if v == removed { kept } else { v });
                    incident[kept as usize].push(f);
                }
            }
            rep[removed as usize] = kept;
            collapsed += 1;
        }
        if collapsed == 0 {
            break;
        }
    }
    // Collapses chain (a kept vertex may be removed later): each vertex to its final one.
    for v in 0..n {
        let mut r = rep[v];
        while rep[r as usize] != r {
            r = rep[r as usize];
        }
        rep[v] = r;
    }
    compact(mesh, &rep, true)
}

/// Whether the half-edge collapse of `removed` into `kept` keeps the surface as it is (see the
/// module docs).
fn collapsible(faces: &[[u32; 3]], alive: &[bool], incident: &[Vec<u32>], boundary: &[bool], x: &[[f64; 3]], removed: u32, kept: u32) -> bool {
    let live = |v: u32| incident[v as usize].iter().copied().filter(|&f| alive[f as usize]);
    let neighbours = |v: u32| {
        let mut out: Vec<u32> = live(v).flat_map(|f| faces[f as usize]).filter(|&u| u != v).collect();
        out.sort_unstable();
        out.dedup();
        out
    };
    let shared: Vec<u32> = live(removed).filter(|&f| faces[f as usize].contains(&kept)).collect();
    // The edge, in one face (boundary) or two (interior).
    if shared.is_empty() || shared.len() > 2 {
        return false;
    }
    let on_boundary_edge = shared.len() == 1;
    if boundary[removed as usize] && !on_boundary_edge {
        // Both ends on the boundary (the kept one is, or it would have been removed),
        // joined across the interior: the collapse would pinch the surface.
        return false;
    }
    let opposite: Vec<u32> = shared.iter().map(|&f| faces[f as usize].into_iter().find(|&v| v != removed && v != kept).unwrap_or(kept)).collect();
    let (nr, nk) = (neighbours(removed), neighbours(kept));
    let common = nr.iter().filter(|v| nk.binary_search(v).is_ok()).count();
    if common != opposite.len() {
        return false;
    }
    // Each opposite vertex loses a neighbour; an interior one keeps at least three, a
    // boundary one two; the kept vertex keeps at least three (two on the boundary).
    if opposite.iter().any(|&o| neighbours(o).len() <= if boundary[o as usize] { 2 } else { 3 }) {
        return false;
    }
    if nr.len() + nk.len() - 2 - opposite.len() < if boundary[kept as usize] { 2 } else { 3 } {
        return false;
    }
    // No moved face turns over (a face of zero area has no side to keep).
    live(removed).filter(|&f| !faces[f as usize].contains(&kept)).all(|f| {
        let t = faces[f as usize];
        let p = t.map(|v| x[v as usize]);
        let q = t.map(|v| x[if v == removed { kept } else { v } as usize]);
        let before = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        let after = cross(sub(q[1], q[0]), sub(q[2], q[0]));
        norm(before) == 0.0 || dot(before, after) > 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::validate::{classify, checked_topology};
    use crate::mesh::SurfaceKind;

    /// A grid sheet whose first row is squeezed onto the second (1e-6 apart): its short edges
    /// go, the sheet stays an open disk, every vertex maps to a vertex of the result, and a
    /// vertex lies where an input vertex lay.
    #[test]
    fn a_squeezed_row_is_collapsed_and_the_disk_kept() {
        let k = 6usize;
        let mut vertices = Vec::new();
        for j in 0..k {
            for i in 0..k {
                let y = if j == 0 { 1.0 - 1e-6 } else { j as f64 };
                vertices.push([i as f64, y, 0.0]);
            }
        }
        let id = |i: usize, j: usize| (j * k + i) as u32;
        let mut faces = Vec::new();
        for j in 0..k - 1 {
            for i in 0..k - 1 {
                faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let mesh = TriMesh::new(vertices, faces);
        let out = collapse_short_edges(&mesh, 1e-3);
        assert!(out.merged_vertices >= 4, "{}", out.merged_vertices);
        let topology = checked_topology(&out.mesh).unwrap();
        assert_eq!(classify(&topology), Some(SurfaceKind::OpenDisk));
        for (v, &w) in out.old_to_new.iter().enumerate() {
            let d = norm(sub(mesh.vertices[v], out.mesh.vertices[w as usize]));
            assert!(d < 1e-3, "vertex {v} moved by {d}");
        }
        let shortest = out.mesh.faces.iter().flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3]))).map(|(a, b)| norm(sub(out.mesh.vertices[a as usize], out.mesh.vertices[b as usize]))).fold(f64::INFINITY, f64::min);
        assert!(shortest > 0.5, "{shortest}");
    }

    /// A tetrahedron's edges are all short, but no collapse keeps it a closed surface.
    #[test]
    fn a_tetrahedron_stays() {
        let mesh = TriMesh::new(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]);
        let out = collapse_short_edges(&mesh, 10.0);
        assert_eq!(out.merged_vertices, 0);
        assert_eq!(out.mesh.faces, mesh.faces);
    }
}
