//! Long edges split at their midpoints, the faces with them (the surface unchanged): what
//! `remesh` maps where an input's edges are several times longer than the remesh's
//! (docs/method.md section 25, "Long edges"). The map is piecewise linear on the input's faces and its transport has
//! a site at each input vertex only, so a region spanned by long faces (a decimated long
//! bone's shaft: needles from one end to the other) has no say in the map at the remesh's
//! scale; split, it has sites all along.

use super::fasthash::FastMap;
use super::geometry::{add, norm, scale, sub};
use super::TriMesh;

/// `mesh` with its long edges split ([`split_long_edges`]), and where each face came from.
#[derive(Debug, Clone)]
pub(crate) struct SplitMesh {
    /// The split mesh: the input's vertices first (same indices), then the midpoints.
    pub mesh: TriMesh,
    /// Each face's face of the input it lies in.
    pub parent: Vec<u32>,
    /// Each face's corners as barycentric coordinates of its parent face.
    pub corners: Vec<[[f64; 3]; 3]>,
    /// Edges split.
    pub splits: usize,
}

impl SplitMesh {
    /// The point with barycentric coordinates `barycentric` in face `face` of the split mesh,
    /// as a face of the input and barycentric coordinates there (the same point).
    pub(crate) fn parent_point(&self, face: usize, barycentric: [f64; 3]) -> (usize, [f64; 3]) {
        let corners = self.corners[face];
        (self.parent[face] as usize, std::array::from_fn(|i| (0..3).map(|k| barycentric[k] * corners[k][i]).sum()))
    }
}

/// `mesh` with every edge longer than `max_len` split at its midpoint, pass after pass, until
/// none is longer or the next pass would make more than `max_faces` faces; `None` when no
/// edge is longer (or a face indexes no vertex or a coordinate is not finite, which the map's
/// own checks report). In a pass every long edge is split and each face with split edges is
/// cut along the lines between its edges' midpoints (red-green refinement): one split edge
/// halves the face; two cut off the corner between them and split the rest by its shorter
/// diagonal; three give the 1:4 split. A needle (two long sides) is so sliced across into
/// pieces of the bound's length, not into thinner needles.
pub(crate) fn split_long_edges(mesh: &TriMesh, max_len: f64, max_faces: usize) -> Option<SplitMesh> {
    let n = mesh.vertices.len();
    if !(max_len > 0.0 && max_len.is_finite()) || mesh.faces.iter().flatten().any(|&v| v as usize >= n) || mesh.vertices.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let length = |v: &[[f64; 3]], a: u32, b: u32| norm(sub(v[a as usize], v[b as usize]));
    // Most inputs have no long edge: no copy of them.
    if !mesh.faces.iter().any(|f| (0..3).any(|k| length(&mesh.vertices, f[k], f[(k + 1) % 3]) > max_len)) {
        return None;
    }
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut out = SplitMesh { mesh: mesh.clone(), parent: (0..mesh.faces.len() as u32).collect(), corners: vec![identity; mesh.faces.len()], splits: 0 };
    loop {
        let SplitMesh { mesh: m, parent, corners, splits } = &mut out;
        // The long edges' midpoints, numbered in the faces' order.
        let mut midpoint: FastMap<(u32, u32), u32> = FastMap::default();
        let mut added = 0usize;
        let mut children = 0usize;
        for f in &m.faces {
            let mut cut = 0;
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                if length(&m.vertices, a, b) > max_len {
                    cut += 1;
                    let next = (n + added) as u32;
                    midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                        added += 1;
                        next
                    });
                }
            }
            children += [1, 2, 3, 4][cut];
        }
        if added == 0 || children > max_faces {
            break;
        }
        let base = m.vertices.len() as u32;
        let mut new_vertices = vec![[0.0; 3]; added];
        for (&(a, b), &v) in &midpoint {
            new_vertices[(v - n as u32) as usize] = scale(add(m.vertices[a as usize], m.vertices[b as usize]), 0.5);
        }
        // Midpoint numbers from `n` on: shifted after the vertices of earlier passes.
        let shift = base - n as u32;
        m.vertices.extend(new_vertices);
        let mid = |a: u32, b: u32| midpoint.get(&(a.min(b), a.max(b))).map(|&v| v + shift);
        let mut faces = Vec::with_capacity(children);
        let mut new_parent = Vec::with_capacity(children);
        let mut new_corners = Vec::with_capacity(children);
        for (t, f) in m.faces.iter().enumerate() {
            let c = corners[t];
            let half = |i: usize, j: usize| -> [f64; 3] { std::array::from_fn(|s| 0.5 * (c[i][s] + c[j][s])) };
            let cuts: [Option<u32>; 3] = std::array::from_fn(|k| mid(f[k], f[(k + 1) % 3]));
            let mut push = |face: [u32; 3], w: [[f64; 3]; 3]| {
                faces.push(face);
                new_parent.push(parent[t]);
                new_corners.push(w);
            };
            match cuts.iter().filter(|x| x.is_some()).count() {
                0 => push(*f, c),
                1 => {
                    // Rotate so that the cut edge is (p, q), r opposite.
                    let k = (0..3).find(|&k| cuts[k].is_some()).unwrap_or(0);
                    let (p, q, r) = (k, (k + 1) % 3, (k + 2) % 3);
                    let mv = cuts[k].unwrap_or(f[p]);
                    push([f[p], mv, f[r]], [c[p], half(p, q), c[r]]);
                    push([mv, f[q], f[r]], [half(p, q), c[q], c[r]]);
                }
                2 => {
                    // Rotate so that the uncut edge is (p, q): cuts on (q, r) and (r, p).
                    let k = (0..3).find(|&k| cuts[k].is_none()).unwrap_or(0);
                    let (p, q, r) = (k, (k + 1) % 3, (k + 2) % 3);
                    let (mqr, mrp) = (cuts[q].unwrap_or(f[q]), cuts[r].unwrap_or(f[r]));
                    let (wqr, wrp) = (half(q, r), half(r, p));
                    push([mqr, f[r], mrp], [wqr, c[r], wrp]);
                    let v = |u: u32| m.vertices[u as usize];
                    if norm(sub(v(f[p]), v(mqr))) <= norm(sub(v(f[q]), v(mrp))) {
                        push([f[p], f[q], mqr], [c[p], c[q], wqr]);
                        push([f[p], mqr, mrp], [c[p], wqr, wrp]);
                    } else {
                        push([f[p], f[q], mrp], [c[p], c[q], wrp]);
                        push([f[q], mqr, mrp], [c[q], wqr, wrp]);
                    }
                }
                _ => {
                    let [m01, m12, m20] = cuts.map(|x| x.unwrap_or(0));
                    let (w01, w12, w20) = (half(0, 1), half(1, 2), half(2, 0));
                    push([f[0], m01, m20], [c[0], w01, w20]);
                    push([m01, f[1], m12], [w01, c[1], w12]);
                    push([m20, m12, f[2]], [w20, w12, c[2]]);
                    push([m01, m12, m20], [w01, w12, w20]);
                }
            }
        }
        m.faces = faces;
        *parent = new_parent;
        *corners = new_corners;
        *splits += added;
    }
    (out.splits > 0).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::geometry::face_areas;
    use crate::mesh::Topology;

    /// A closed triangular prism of length 10 and side 0.5 whose sides are needles from one
    /// end to the other (as quadric decimation leaves a long bone's shaft).
    fn needle_prism() -> TriMesh {
        let ring = |x: f64| (0..3).map(move |k| {
            let a = k as f64 * std::f64::consts::TAU / 3.0;
            [x, 0.3 * a.cos(), 0.3 * a.sin()]
        });
        let vertices: Vec<[f64; 3]> = ring(0.0).chain(ring(10.0)).collect();
        let mut faces = vec![[0, 2, 1], [3, 4, 5]];
        for k in 0..3u32 {
            let (a, b) = (k, (k + 1) % 3);
            faces.push([a, b, b + 3]);
            faces.push([a, b + 3, a + 3]);
        }
        TriMesh::new(vertices, faces)
    }

    /// The split prism is the same closed surface (area, topology, orientation kept, every
    /// edge at most the bound), and each face's corners are where its parent's barycentric
    /// coordinates say.
    #[test]
    fn a_needle_prism_is_split_to_the_bound_on_the_same_surface() {
        let prism = needle_prism();
        let split = split_long_edges(&prism, 0.5, 100_000).unwrap();
        let m = &split.mesh;
        let area = |m: &TriMesh| face_areas(&m.vertices, &m.faces).iter().sum::<f64>();
        assert!((area(m) - area(&prism)).abs() < 1e-12 * area(&prism));
        let topology = Topology::build(m).unwrap();
        assert!(topology.is_closed() && topology.genus() == Some(0));
        for f in &m.faces {
            for k in 0..3 {
                assert!(norm(sub(m.vertices[f[k] as usize], m.vertices[f[(k + 1) % 3] as usize])) <= 0.5 + 1e-12);
            }
        }
        assert!(m.faces.len() > 100 && split.splits > 40, "{} faces, {} splits", m.faces.len(), split.splits);
        for (t, f) in m.faces.iter().enumerate() {
            for (k, &v) in f.iter().enumerate() {
                let (p, w) = split.parent_point(t, std::array::from_fn(|s| if s == k { 1.0 } else { 0.0 }));
                let corners = prism.faces[p].map(|u| prism.vertices[u as usize]);
                let x: [f64; 3] = std::array::from_fn(|i| (0..3).map(|s| w[s] * corners[s][i]).sum());
                assert!(norm(sub(x, m.vertices[v as usize])) < 1e-12, "face {t} corner {k}");
            }
        }
    }

    /// Nothing longer than the bound: no copy; a face limit stops the splitting.
    #[test]
    fn short_edges_are_left_and_the_face_limit_holds() {
        let prism = needle_prism();
        assert!(split_long_edges(&prism, 20.0, 100_000).is_none());
        let capped = split_long_edges(&prism, 0.01, 64).unwrap();
        assert!(capped.mesh.faces.len() <= 64, "{}", capped.mesh.faces.len());
    }
}
