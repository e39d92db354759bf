//! Point location in a planar triangulation with a bounding-volume hierarchy of the
//! triangles. A query outside every triangle (the cap grid's boundary lies on the circle, the
//! mapped mesh's boundary is a polygon inscribed in it) goes to the nearest point of the
//! nearest triangle, so the pull-back is robust at the boundary.
//!
//! The planar image of a cap map is far from uniform (a closed surface mapped to `Z*` near -1
//! packs most triangles near the centre of a disk of radius 20), so a uniform grid put
//! thousands of triangles in a cell; the hierarchy splits at the median and adapts.
//!
//! Each triangle's barycentric map is precomputed in the hierarchy's leaf order, so a leaf's
//! containment tests read one contiguous block (CHANGELOG.md has the measurement).

/// A located point: the triangle and barycentric coordinates (non-negative, sum 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// Triangle index.
    pub face: usize,
    /// Barycentric coordinates of the point (or of its nearest point in the triangle).
    pub bary: [f64; 3],
}

/// Triangles per leaf at most.
const LEAF: usize = 8;

use std::borrow::Cow;

/// Smallest barycentric coordinate of a point for [`Locator::locate_near`] to take its hint.
const HINT_MARGIN: f64 = 1e-9;

/// How far outside a triangle, in barycentric coordinates, a point still counts as inside
/// (rounding on shared edges).
const CONTAINMENT_TOLERANCE: f64 = 1e-12;

/// A node: its box, and either two children (`count == 0`, children at `first` and
/// `first + 1`) or `count` triangles `order[first..first + count]`.
#[derive(Debug, Clone, Copy)]
struct Node {
    lo: [f64; 2],
    hi: [f64; 2],
    first: u32,
    count: u32,
}

/// Bounding-volume hierarchy over the triangles of a planar mesh.
/// It borrows or owns (`Cow`) the points and triangles: the remesh borrows the map's,
/// [`crate::cap::InverseMap`] keeps its own subset of faces.
pub struct Locator<'a> {
    points: Cow<'a, [[f64; 2]]>,
    faces: Cow<'a, [[u32; 3]]>,
    nodes: Vec<Node>,
    order: Vec<u32>,
    /// Per position of `order`, its triangle's barycentric map (see [`Affine`]): a leaf's
    /// containment tests read one contiguous block instead of gathering corners.
    affine: Vec<Affine>,
    /// Per triangle, its position in `order`.
    position: Vec<u32>,
}

/// A triangle `(a, b, c)`'s map from a point `p` to its barycentric coordinates `(b1, b2)`
/// of `b` and `c` (`b0 = 1 - b1 - b2`): `b1 = r1 . (p - a)`, `b2 = r2 . (p - a)`, the rows of
/// the inverse of `[b - a, c - a]`. NaN for a degenerate triangle (no point is inside).
#[derive(Debug, Clone, Copy)]
struct Affine {
    a: [f64; 2],
    r1: [f64; 2],
    r2: [f64; 2],
}

impl Affine {
    fn new(q: [[f64; 2]; 3]) -> Self {
        let u = [q[1][0] - q[0][0], q[1][1] - q[0][1]];
        let v = [q[2][0] - q[0][0], q[2][1] - q[0][1]];
        let det = u[0] * v[1] - u[1] * v[0];
        if det == 0.0 || !det.is_finite() {
            return Self { a: q[0], r1: [f64::NAN; 2], r2: [f64::NAN; 2] };
        }
        Self { a: q[0], r1: [v[1] / det, -v[0] / det], r2: [-u[1] / det, u[0] / det] }
    }

    fn barycentric(&self, p: [f64; 2]) -> [f64; 3] {
        let w = [p[0] - self.a[0], p[1] - self.a[1]];
        let b1 = self.r1[0] * w[0] + self.r1[1] * w[1];
        let b2 = self.r2[0] * w[0] + self.r2[1] * w[1];
        [1.0 - b1 - b2, b1, b2]
    }
}

impl<'a> Locator<'a> {
    /// Build the hierarchy (median splits along the longer side of the centroids' box).
    pub fn new(points: impl Into<Cow<'a, [[f64; 2]]>>, faces: impl Into<Cow<'a, [[u32; 3]]>>) -> Self {
        let (points, faces) = (points.into(), faces.into());
        let boxes: Vec<([f64; 2], [f64; 2])> = faces
            .iter()
            .map(|t| {
                let q = t.map(|v| points[v as usize]);
                let lo = [q[0][0].min(q[1][0]).min(q[2][0]), q[0][1].min(q[1][1]).min(q[2][1])];
                let hi = [q[0][0].max(q[1][0]).max(q[2][0]), q[0][1].max(q[1][1]).max(q[2][1])];
                (lo, hi)
            })
            .collect();
        let mut order: Vec<u32> = (0..faces.len() as u32).collect();
        let mut nodes = vec![Node { lo: [0.0; 2], hi: [0.0; 2], first: 0, count: 0 }];
        // (node, start, end) still to build.
        let mut todo = vec![(0usize, 0usize, order.len())];
        while let Some((node, start, end)) = todo.pop() {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            let (mut clo, mut chi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for &f in &order[start..end] {
                let (a, b) = boxes[f as usize];
                for k in 0..2 {
                    lo[k] = lo[k].min(a[k]);
                    hi[k] = hi[k].max(b[k]);
                    let c = 0.5 * (a[k] + b[k]);
                    clo[k] = clo[k].min(c);
                    chi[k] = chi[k].max(c);
                }
            }
            nodes[node].lo = lo;
            nodes[node].hi = hi;
            let axis = if chi[0] - clo[0] >= chi[1] - clo[1] { 0 } else { 1 };
            if end - start <= LEAF || !(chi[axis] > clo[axis]) {
                nodes[node].first = start as u32;
                nodes[node].count = (end - start) as u32;
                continue;
            }
            let mid = start + (end - start) / 2;
            let centre = |f: &u32| {
                let (a, b) = boxes[*f as usize];
                a[axis] + b[axis]
            };
            order[start..end].select_nth_unstable_by(mid - start, |x, y| centre(x).total_cmp(&centre(y)));
            let left = nodes.len();
            nodes.push(Node { lo: [0.0; 2], hi: [0.0; 2], first: 0, count: 0 });
            nodes.push(Node { lo: [0.0; 2], hi: [0.0; 2], first: 0, count: 0 });
            nodes[node].first = left as u32;
            nodes[node].count = 0;
            todo.push((left, start, mid));
            todo.push((left + 1, mid, end));
        }
        let affine = order.iter().map(|&f| Affine::new(faces[f as usize].map(|v| points[v as usize]))).collect();
        let mut position = vec![0u32; faces.len()];
        for (k, &f) in order.iter().enumerate() {
            position[f as usize] = k as u32;
        }
        Self { points, faces, nodes, order, affine, position }
    }

    /// Barycentric coordinates by signed areas (the tests' reference for [`Affine`]).
    #[cfg(test)]
    fn barycentric(&self, f: usize, p: [f64; 2]) -> [f64; 3] {
        use crate::mesh::geometry::signed_area_2d;
        let [a, b, c] = self.faces[f].map(|v| self.points[v as usize]);
        let area = signed_area_2d(a, b, c);
        if area == 0.0 {
            return [f64::NEG_INFINITY; 3];
        }
        [signed_area_2d(p, b, c) / area, signed_area_2d(a, p, c) / area, signed_area_2d(a, b, p) / area]
    }

    /// Locate `p`: a containing triangle if any, else the nearest point of the nearest
    /// triangle. `None` only for an empty mesh or a non-finite `p`.
    pub fn locate(&self, p: [f64; 2]) -> Option<Location> {
        self.locate_near(p, None)
    }

    /// [`Locator::locate`], trying the triangle `hint` first (a query near the last one
    /// usually falls in the same triangle: the area equalization lifts a vertex's position,
    /// its finite-difference neighbours and its trial steps one after the other). The hint is
    /// taken only when `p` is inside it by a margin (`HINT_MARGIN` in barycentric
    /// coordinates), where no other triangle of an embedding contains it, so the answer is
    /// the one [`Locator::locate`] gives whatever the hint: results do not depend on which
    /// thread lifted what before.
    pub fn locate_near(&self, p: [f64; 2], hint: Option<usize>) -> Option<Location> {
        if self.faces.is_empty() || !(p[0].is_finite() && p[1].is_finite()) {
            return None;
        }
        if let Some(loc) = hint.filter(|&f| f < self.faces.len()).and_then(|f| self.inside(f, p, HINT_MARGIN)) {
            return Some(loc);
        }
        // Containing triangle: visit every node whose box holds p (with a margin for points
        // on an edge shared by two boxes).
        let mut stack = NodeStack::root();
        while let Some(n) = stack.pop() {
            let node = self.nodes[n];
            let margin = 1e-12 * (node.hi[0] - node.lo[0]).max(node.hi[1] - node.lo[1]);
            if p[0] < node.lo[0] - margin || p[0] > node.hi[0] + margin || p[1] < node.lo[1] - margin || p[1] > node.hi[1] + margin {
                continue;
            }
            if node.count == 0 {
                stack.push(node.first as usize);
                stack.push(node.first as usize + 1);
                continue;
            }
            for k in node.first as usize..(node.first + node.count) as usize {
                if let Some(loc) = self.inside_at(k, p, -CONTAINMENT_TOLERANCE) {
                    return Some(loc);
                }
            }
        }
        // Outside every triangle: branch and bound on the distance to the boxes.
        let mut best: Option<(f64, Location)> = None;
        let mut stack = NodeStack::root();
        while let Some(n) = stack.pop() {
            let node = self.nodes[n];
            if best.as_ref().is_some_and(|(d, _)| box_distance(node.lo, node.hi, p) >= *d) {
                continue;
            }
            if node.count == 0 {
                let (a, b) = (node.first as usize, node.first as usize + 1);
                let (da, db) = (self.box_distance_of(a, p), self.box_distance_of(b, p));
                // Nearer child last, so it is searched first.
                if da < db {
                    stack.push(b);
                    stack.push(a);
                } else {
                    stack.push(a);
                    stack.push(b);
                }
                continue;
            }
            for &f in &self.order[node.first as usize..(node.first + node.count) as usize] {
                let (d, loc) = self.nearest_in(f as usize, p);
                if best.as_ref().map_or(true, |(bd, _)| d < *bd) {
                    best = Some((d, loc));
                }
            }
        }
        best.map(|(_, l)| l)
    }

    /// `p`'s location in triangle `f` when every barycentric coordinate is at least `margin`
    /// (negative: containment up to rounding).
    fn inside(&self, f: usize, p: [f64; 2], margin: f64) -> Option<Location> {
        self.inside_at(self.position[f] as usize, p, margin)
    }

    /// [`Locator::inside`] for the triangle at position `k` of the hierarchy's order.
    fn inside_at(&self, k: usize, p: [f64; 2], margin: f64) -> Option<Location> {
        let bary = self.affine[k].barycentric(p);
        if bary.iter().all(|&b| b >= margin) {
            let s: f64 = bary.iter().map(|b| b.max(0.0)).sum();
            return Some(Location { face: self.order[k] as usize, bary: bary.map(|b| b.max(0.0) / s) });
        }
        None
    }

    fn box_distance_of(&self, n: usize, p: [f64; 2]) -> f64 {
        box_distance(self.nodes[n].lo, self.nodes[n].hi, p)
    }

    /// Distance from `p` to triangle `f` and the barycentric coordinates of the nearest point.
    fn nearest_in(&self, f: usize, p: [f64; 2]) -> (f64, Location) {
        let q = self.faces[f].map(|v| self.points[v as usize]);
        let mut best = (f64::INFINITY, [1.0, 0.0, 0.0]);
        for k in 0..3 {
            let (a, b) = (q[k], q[(k + 1) % 3]);
            let e = [b[0] - a[0], b[1] - a[1]];
            let len2 = e[0] * e[0] + e[1] * e[1];
            let t = if len2 > 0.0 { (((p[0] - a[0]) * e[0] + (p[1] - a[1]) * e[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
            let x = [a[0] + t * e[0], a[1] + t * e[1]];
            let d = ((x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2)).sqrt();
            if d < best.0 {
                let mut bary = [0.0; 3];
                bary[k] = 1.0 - t;
                bary[(k + 1) % 3] = t;
                best = (d, bary);
            }
        }
        (best.0, Location { face: f, bary: best.1 })
    }
}

/// The depth-first stack of a query, on the call stack (a heap vector per query showed in
/// the remesh's profile). The hierarchy's median splits keep
/// its depth below `log2(triangles)` (at most 32), and a descent holds at most one pending
/// sibling per level.
struct NodeStack {
    items: [u32; 128],
    len: usize,
}

impl NodeStack {
    fn root() -> Self {
        Self { items: [0; 128], len: 1 }
    }

    fn push(&mut self, n: usize) {
        self.items[self.len] = n as u32;
        self.len += 1;
    }

    fn pop(&mut self) -> Option<usize> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len] as usize)
    }
}

/// Distance from `p` to the box `[lo, hi]` (0 inside).
fn box_distance(lo: [f64; 2], hi: [f64; 2], p: [f64; 2]) -> f64 {
    let dx = (lo[0] - p[0]).max(0.0).max(p[0] - hi[0]);
    let dy = (lo[1] - p[1]).max(0.0).max(p[1] - hi[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Each vertex's last located face, the hint of its next query: lifts made while a vertex moves
/// (finite differences, trial steps, the next sweep's) land near its last one. Shared by the
/// parallel lifts of [`crate::refine::area_refine::refine_towards`]; the answers of
/// [`Locator::locate_near`] do not depend on the hint, so neither do the results.
pub(crate) struct LastFaces(Vec<std::sync::atomic::AtomicU32>);

impl LastFaces {
    /// No face yet for any of `n` vertices.
    pub(crate) fn new(n: usize) -> Self {
        Self((0..n).map(|_| std::sync::atomic::AtomicU32::new(u32::MAX)).collect())
    }

    /// Vertex `v`'s last face, if it has one.
    pub(crate) fn get(&self, v: usize) -> Option<usize> {
        self.0.get(v).map(|h| h.load(std::sync::atomic::Ordering::Relaxed)).filter(|&h| h != u32::MAX).map(|h| h as usize)
    }

    /// Record `face` as vertex `v`'s last.
    pub(crate) fn set(&self, v: usize, face: usize) {
        if let Some(h) = self.0.get(v) {
            h.store(face as u32, std::sync::atomic::Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cap::stereographic;
    use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};

    /// Against brute force on a very non-uniform planar mesh (a cap down to Z* = -0.99 seen
    /// through the stereographic projection: radius about 14, most triangles near the centre):
    /// inside points find a containing triangle, outside points the nearest distance, with
    /// or without a hint.
    #[test]
    fn matches_brute_force_on_a_non_uniform_mesh() {
        let cap = spherical_cap(-0.99, 40, spherical_cap_sectors(-0.99, 40));
        let plane: Vec<[f64; 2]> = cap.vertices.iter().map(|&x| stereographic(x)).collect();
        let locator = Locator::new(&plane, &cap.faces);
        let mut state = 3u64;
        let mut rand = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let rim = plane.iter().map(|p| (p[0] * p[0] + p[1] * p[1]).sqrt()).fold(0.0, f64::max);
        for i in 0..3000 {
            // Radii spread on a log scale from the centre to twice the rim.
            let r = rim * 2.0 * (1e-4f64).powf(rand()) * if i % 10 == 0 { 1.0 } else { 0.5 };
            let t = 2.0 * std::f64::consts::PI * rand();
            let p = [r * t.cos(), r * t.sin()];
            // Every other query goes through a hint: a random triangle, right or wrong.
            let hint = (i % 2 == 1).then(|| (rand() * cap.faces.len() as f64) as usize);
            let loc = locator.locate_near(p, hint).expect("non-empty mesh");
            if let Some(h) = hint {
                if locator.barycentric(h, p).iter().all(|&b| b >= HINT_MARGIN) {
                    assert_eq!(loc.face, h, "a containing hint is taken");
                }
                assert_eq!(Some(loc), locator.locate(p), "the hint changed the answer");
            }
            let brute = (0..cap.faces.len()).map(|f| locator.nearest_in(f, p).0).fold(f64::INFINITY, f64::min);
            let contained = (0..cap.faces.len()).any(|f| locator.barycentric(f, p).iter().all(|&b| b >= -1e-12));
            let q = cap.faces[loc.face].map(|v| plane[v as usize]);
            let x = [0, 1].map(|k| loc.bary[0] * q[0][k] + loc.bary[1] * q[1][k] + loc.bary[2] * q[2][k]);
            let d = ((x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2)).sqrt();
            if contained {
                assert!(d <= 1e-9 * (1.0 + r), "point {p:?} inside the mesh located {d} away");
            } else {
                assert!((d - brute).abs() <= 1e-9 * (1.0 + brute), "point {p:?}: nearest {brute}, located {d}");
            }
            assert!((loc.bary.iter().sum::<f64>() - 1.0).abs() < 1e-12 && loc.bary.iter().all(|&b| b >= 0.0));
        }
    }
}
