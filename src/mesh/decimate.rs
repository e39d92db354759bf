//! Decimation by half-edge collapses, shortest edge first, that records every collapse so
//! that a map of the coarse mesh can be prolonged back to the input vertex by vertex (the
//! multilevel parameterization of large closed surfaces, `crate::param::multilevel`; the
//! progressive meshes of Hoppe 1996 with the kept vertex fixed).
//!
//! A half-edge collapse removes one vertex and keeps the other where it is, so the coarse
//! mesh's vertices are input vertices. A collapse is made only when it keeps the surface a
//! manifold of the same topology (the link condition: the edge's endpoints share exactly the
//! two neighbours opposite it), leaves every vertex at least 3 and at most
//! [`MAX_VALENCE`] neighbours, turns no moved face by more than [`MAX_NORMAL_TURN_COS`]'s
//! angle and makes none worse shaped than [`MIN_SHAPE`] (or than its star's worst).

use super::geometry::{cross, dot, norm, sub};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Most neighbours a kept vertex may have after a collapse: fans wider than this make the
/// coarse map's faces thin.
pub(crate) const MAX_VALENCE: usize = 12;

/// Smallest cosine between a moved face's normal before and after a collapse (60 degrees).
const MAX_NORMAL_TURN_COS: f64 = 0.5;

/// Smallest shape quality `4 sqrt(3) A / (l0^2 + l1^2 + l2^2)` (1 for an equilateral
/// triangle) of a moved face, unless its star's worst face was already worse.
const MIN_SHAPE: f64 = 0.4;

/// One collapse: `removed` went into `kept`; `star` (an offset into [`Hierarchy::stars`],
/// `star_len` entries) lists the removed vertex's faces at that moment as the pairs `(a, b)`
/// of the faces `(removed, a, b)` in their orientation.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Collapse {
    pub removed: u32,
    pub kept: u32,
    pub star: u32,
    pub star_len: u32,
}

/// The collapses of a decimation, in the order made, and the coarse mesh they left.
#[derive(Debug, Clone)]
pub(crate) struct Hierarchy {
    pub collapses: Vec<Collapse>,
    pub stars: Vec<[u32; 2]>,
    /// The coarse mesh's faces, in input vertex numbers.
    pub coarse_faces: Vec<[u32; 3]>,
    /// Whether each input vertex is a coarse vertex.
    pub is_coarse: Vec<bool>,
}

impl Hierarchy {
    /// The removed vertex's star of `c`.
    pub fn star(&self, c: &Collapse) -> &[[u32; 2]] {
        &self.stars[c.star as usize..(c.star + c.star_len) as usize]
    }
}

/// Decimate the closed manifold mesh `(vertices, faces)` by half-edge collapses, shortest edge
/// first, until at most `target` vertices are left or no allowed collapse remains. `locked`
/// vertices are never removed. An edge's length is divided by the smaller `scale` of its
/// endpoints (in `(0, 1]`; 1 everywhere for a uniform decimation): where the scale is small
/// the edges look long and are kept, so the coarse mesh is finer there.
pub(crate) fn decimate(vertices: &[[f64; 3]], faces: &[[u32; 3]], locked: &[bool], scale: &[f64], target: usize) -> Hierarchy {
    let n = vertices.len();
    let mut faces = faces.to_vec();
    let mut alive = vec![true; faces.len()];
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (f, t) in faces.iter().enumerate() {
        for &v in t {
            incident[v as usize].push(f as u32);
        }
    }
    let length = |a: u32, b: u32| norm(sub(vertices[a as usize], vertices[b as usize])) / scale[a as usize].min(scale[b as usize]);
    // A closed mesh has each edge in two faces, once in each direction.
    let edges: Vec<(u32, u32)> = faces.iter().flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3]))).filter(|(a, b)| a < b).collect();
    let shortest = edges.iter().map(|&(a, b)| length(a, b)).filter(|&l| l > 0.0).fold(f64::INFINITY, f64::min);
    let mut queue = BucketQueue::new(if shortest.is_finite() { shortest } else { 1.0 });
    let push = |queue: &mut BucketQueue, a: u32, b: u32| queue.push(length(a, b), a.min(b), a.max(b));
    for &(a, b) in &edges {
        push(&mut queue, a, b);
    }
    drop(edges);
    let mut removed = vec![false; n];
    let mut left = n;
    let mut collapses = Vec::new();
    let mut stars = Vec::new();
    let mut scratch = Scratch::default();
    while left > target {
        let Some((a, b)) = queue.pop() else { break };
        if removed[a as usize] || removed[b as usize] || !incident[a as usize].iter().any(|&f| faces[f as usize].contains(&b)) {
            continue;
        }
        // Remove the endpoint whose removal leaves the better shaped faces.
        let shape_of = |v: u32, u: u32, scratch: &mut Scratch| if locked[v as usize] { None } else { allowed(vertices, &faces, &incident, v, u, scratch) };
        let (ab, ba) = (shape_of(a, b, &mut scratch), shape_of(b, a, &mut scratch));
        let (v, u) = match (ab, ba) {
            (Some(x), Some(y)) => if x >= y { (a, b) } else { (b, a) },
            (Some(_), None) => (a, b),
            (None, Some(_)) => (b, a),
            (None, None) => continue,
        };
        // Record v's star, then move its faces to u.
        let star = stars.len() as u32;
        for &f in &incident[v as usize] {
            let t = faces[f as usize];
            let k = t.iter().position(|&x| x == v).unwrap_or(0);
            stars.push([t[(k + 1) % 3], t[(k + 2) % 3]]);
        }
        collapses.push(Collapse { removed: v, kept: u, star, star_len: stars.len() as u32 - star });
        let moved = std::mem::take(&mut incident[v as usize]);
        for f in moved {
            let t = &mut faces[f as usize];
            if t.contains(&u) {
                alive[f as usize] = false;
                for &w in t.iter() {
                    if w != v {
                        incident[w as usize].retain(|&g| g != f);
                    }
                }
            } else {
                for x in t.iter_mut() {
                    if *x == v {
                        *x = u;
                    }
                }
                incident[u as usize].push(f);
                let t = *t;
                for &w in &t {
                    if w != u {
                        push(&mut queue, u, w);
                    }
                }
            }
        }
        removed[v as usize] = true;
        left -= 1;
    }
    let coarse_faces = faces.iter().zip(&alive).filter(|(_, &a)| a).map(|(t, _)| *t).collect();
    Hierarchy { collapses, stars, coarse_faces, is_coarse: removed.iter().map(|&r| !r).collect() }
}

/// A priority queue of edges by length (ties by vertex numbers), in buckets of
/// [`BUCKETS_PER_E`] per factor `e` of length above the shortest edge, each bucket a binary
/// heap: the same order as one heap, where one heap of the 776k brain's 2-4 million entries
/// spent a tenth of the multilevel map's time in `pop` (cache misses; 5.7 s of decimation,
/// 2.4 s in buckets). The order matters: buckets emptied last in, first out (lengths within
/// 0.4% in any order) left a coarse copy that mapped at mean |d_area| 0.014 instead of 0.011.
struct BucketQueue {
    buckets: Vec<BinaryHeap<Reverse<(u64, u32, u32)>>>,
    /// No bucket below this one holds an edge.
    lowest: usize,
    ln_shortest: f64,
}

/// Buckets per factor `e` of edge length.
const BUCKETS_PER_E: f64 = 256.0;

impl BucketQueue {
    fn new(shortest: f64) -> BucketQueue {
        BucketQueue { buckets: Vec::new(), lowest: 0, ln_shortest: shortest.ln() }
    }

    fn push(&mut self, length: f64, a: u32, b: u32) {
        let k = ((length.ln() - self.ln_shortest) * BUCKETS_PER_E).max(0.0);
        // Lengths are finite and positive on a valid mesh; anything else goes last.
        let k = if k.is_finite() { (k as usize).min(MAX_BUCKETS) } else { MAX_BUCKETS };
        if k >= self.buckets.len() {
            self.buckets.resize_with(k + 1, BinaryHeap::new);
        }
        self.buckets[k].push(Reverse((length.to_bits(), a, b)));
        self.lowest = self.lowest.min(k);
    }

    fn pop(&mut self) -> Option<(u32, u32)> {
        while self.lowest < self.buckets.len() {
            if let Some(Reverse((_, a, b))) = self.buckets[self.lowest].pop() {
                return Some((a, b));
            }
            self.lowest += 1;
        }
        None
    }
}

/// The last bucket (lengths `e^64` times the shortest, or not finite).
const MAX_BUCKETS: usize = 64 * BUCKETS_PER_E as usize;

/// Reused buffers of [`allowed`].
#[derive(Default)]
struct Scratch {
    neighbours: Vec<u32>,
    u_neighbours: Vec<u32>,
}

/// Whether the half-edge collapse of `v` into `u` is allowed (see the module doc), and if so
/// the worst shape of the faces it moves.
fn allowed(vertices: &[[f64; 3]], faces: &[[u32; 3]], incident: &[Vec<u32>], v: u32, u: u32, scratch: &mut Scratch) -> Option<f64> {
    let (fv, fu) = (&incident[v as usize], &incident[u as usize]);
    // The faces of the edge and their opposite vertices.
    let mut opposite = [u32::MAX; 2];
    let mut shared = 0;
    for &f in fv {
        let t = faces[f as usize];
        if t.contains(&u) {
            if shared == 2 {
                return None;
            }
            opposite[shared] = t.iter().copied().find(|&w| w != u && w != v)?;
            shared += 1;
        }
    }
    if shared != 2 || opposite[0] == opposite[1] {
        return None;
    }
    // Link condition: the common neighbours of u and v are the two opposite vertices.
    let Scratch { neighbours: nb, u_neighbours: seen_u } = scratch;
    neighbours_into(faces, fv, v, nb);
    neighbours_into(faces, fu, u, seen_u);
    let u_neighbours = seen_u.len();
    let common = seen_u.iter().filter(|&&w| w != v && nb.binary_search(&w).is_ok()).count();
    if common != 2 {
        return None;
    }
    // Valences: u gets v's neighbours but v and the two opposite ones; those lose one.
    let new_valence = u_neighbours + nb.len() - 4;
    if new_valence > MAX_VALENCE {
        return None;
    }
    for &w in &opposite {
        // On a closed manifold a vertex has as many neighbours as faces.
        if incident[w as usize].len() <= 3 {
            return None;
        }
    }
    // The moved faces keep their orientation and a fair shape.
    let mut worst_before = f64::INFINITY;
    let mut worst_after = f64::INFINITY;
    for &f in fv {
        let t = faces[f as usize];
        if t.contains(&u) {
            continue;
        }
        let p = t.map(|w| vertices[w as usize]);
        let q = t.map(|w| vertices[if w == v { u } else { w } as usize]);
        let (n0, n1) = (normal(p), normal(q));
        let (l0, l1) = (norm(n0), norm(n1));
        if l1 <= 0.0 || dot(n0, n1) < MAX_NORMAL_TURN_COS * l0 * l1 {
            return None;
        }
        worst_before = worst_before.min(shape(p));
        worst_after = worst_after.min(shape(q));
    }
    (worst_after >= MIN_SHAPE.min(worst_before)).then_some(worst_after)
}

/// The sorted neighbours of `v`, whose faces are `incident`, into `out`.
fn neighbours_into(faces: &[[u32; 3]], incident: &[u32], v: u32, out: &mut Vec<u32>) {
    out.clear();
    for &f in incident {
        out.extend(faces[f as usize].iter().copied().filter(|&w| w != v));
    }
    out.sort_unstable();
    out.dedup();
}

fn normal(p: [[f64; 3]; 3]) -> [f64; 3] {
    cross(sub(p[1], p[0]), sub(p[2], p[0]))
}

/// `4 sqrt(3) A / (l0^2 + l1^2 + l2^2)`: 1 for an equilateral triangle, 0 for a degenerate one.
fn shape(p: [[f64; 3]; 3]) -> f64 {
    let s: f64 = (0..3).map(|k| {
        let e = sub(p[(k + 1) % 3], p[k]);
        dot(e, e)
    }).sum();
    if s > 0.0 { 2.0 * 3f64.sqrt() * norm(normal(p)) / s } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;
    use crate::mesh::topology::Topology;

    #[test]
    fn sphere_decimates_to_a_closed_genus0_mesh_and_records_every_removal() {
        let mesh = shapes::icosphere(4);
        let n = mesh.vertices.len();
        let mut locked = vec![false; n];
        locked[0] = true;
        let h = decimate(&mesh.vertices, &mesh.faces, &locked, &vec![1.0; n], n / 4);
        let kept = h.is_coarse.iter().filter(|&&k| k).count();
        assert!(kept <= n / 4 + 1 && kept > n / 8, "kept {kept} of {n}");
        assert!(h.is_coarse[0]);
        assert_eq!(h.collapses.len(), n - kept);
        // Euler characteristic 2 and every edge in two faces.
        let coarse = crate::mesh::TriMesh::new(mesh.vertices.clone(), h.coarse_faces.clone());
        let topo = Topology::build(&coarse).unwrap();
        assert_eq!(topo.boundary_loops.len(), 0);
        assert_eq!(kept as i64 - topo.n_edges as i64 + h.coarse_faces.len() as i64, 2);
        for c in &h.collapses {
            assert!(!h.is_coarse[c.removed as usize]);
            assert!(h.star(c).len() >= 3);
        }
    }
}
