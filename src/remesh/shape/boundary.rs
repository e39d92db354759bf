//! Boundary vertices of an open remesh slide along the input's boundary (ours; see
//! [`super`]): a one-dimensional relaxation by the boundary's arc length on the surface, with
//! the input's corners kept.
//!
//! The planar map sends the input's boundary loop onto a convex polygon inscribed in the rim,
//! in the loop's order by angle. A point at arc length `s` along the loop is the same
//! fraction along a side in the plane and along the input's boundary edge on the surface, so
//! a sliding vertex stays exactly on the input boundary and its planar point on the polygon.

use super::smooth::{ring_faces_same_side, ring_valid_in_plane};
use super::state::{Incidence, Role, Shaping};
use crate::mesh::geometry::{dot, norm, sub};
use crate::mesh::TriMesh;

/// An input boundary vertex whose angle between its two boundary edges is below this (in
/// degrees) is a corner: the remesh keeps a vertex on it.
pub(crate) const CORNER_DEG: f64 = 150.0;

/// Halvings of a slide before the vertex stays.
const HALVINGS: usize = 5;

/// The input's boundary loop, parameterised by arc length on the surface.
pub(crate) struct Track {
    /// Planar points of the loop's vertices, by angle.
    plane: Vec<[f64; 2]>,
    /// Their surface positions.
    position: Vec<[f64; 3]>,
    /// Angle of each planar point.
    angle: Vec<f64>,
    /// Arc length at each vertex (`arc[0] = 0`), and the loop's length last.
    arc: Vec<f64>,
}

impl Track {
    /// The boundary loop of `surface` (its vertices flagged in `boundary`) at the planar
    /// points `plane`; `None` with fewer than three boundary vertices.
    pub(crate) fn new(surface: &TriMesh, plane: &[[f64; 2]], boundary: &[bool]) -> Option<Self> {
        let mut loop_: Vec<usize> = (0..surface.vertices.len()).filter(|&v| boundary[v]).collect();
        let angle_of = |v: usize| plane[v][1].atan2(plane[v][0]);
        loop_.sort_by(|&a, &b| angle_of(a).total_cmp(&angle_of(b)));
        if loop_.len() < 3 {
            return None;
        }
        let position: Vec<[f64; 3]> = loop_.iter().map(|&v| surface.vertices[v]).collect();
        let mut arc = Vec::with_capacity(loop_.len() + 1);
        arc.push(0.0);
        for k in 0..loop_.len() {
            let next = position[(k + 1) % loop_.len()];
            arc.push(arc[k] + norm(sub(next, position[k])));
        }
        Some(Self { plane: loop_.iter().map(|&v| plane[v]).collect(), position, angle: loop_.iter().map(|&v| angle_of(v)).collect(), arc })
    }

    /// The loop's length on the surface.
    pub(crate) fn length(&self) -> f64 {
        *self.arc.last().unwrap_or(&0.0)
    }

    /// Planar and surface point at arc length `s` (taken modulo the length).
    pub(crate) fn at(&self, s: f64) -> ([f64; 2], [f64; 3]) {
        let m = self.plane.len();
        let s = s.rem_euclid(self.length());
        let k = self.arc.partition_point(|&a| a <= s).saturating_sub(1).min(m - 1);
        let len = self.arc[k + 1] - self.arc[k];
        let t = if len > 0.0 { ((s - self.arc[k]) / len).clamp(0.0, 1.0) } else { 0.0 };
        let (p0, p1) = (self.plane[k], self.plane[(k + 1) % m]);
        let (x0, x1) = (self.position[k], self.position[(k + 1) % m]);
        ([0, 1].map(|i| p0[i] + t * (p1[i] - p0[i])), [0, 1, 2].map(|i| x0[i] + t * (x1[i] - x0[i])))
    }

    /// Arc length of the planar point `q` (on or near the polygon): its side by angle, then
    /// its projection on that side.
    pub(crate) fn arc_of(&self, q: [f64; 2]) -> f64 {
        let m = self.plane.len();
        let a = q[1].atan2(q[0]);
        // Side k runs from vertex k to k + 1; before the first angle or after the last: the
        // closing side m - 1.
        let k = match self.angle.partition_point(|&x| x <= a) {
            0 => m - 1,
            i => i - 1,
        };
        let (p0, p1) = (self.plane[k], self.plane[(k + 1) % m]);
        let e = [p1[0] - p0[0], p1[1] - p0[1]];
        let len2 = e[0] * e[0] + e[1] * e[1];
        let t = if len2 > 0.0 { (((q[0] - p0[0]) * e[0] + (q[1] - p0[1]) * e[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
        self.arc[k] + t * (self.arc[k + 1] - self.arc[k])
    }

    /// Arc lengths of the input's corners at the scale `scale` (see [`CORNER_DEG`]): the
    /// boundary vertices where the angle between the points `scale` before and after them
    /// along the boundary is below the bound and smallest within `scale` (a scanned
    /// boundary's jags below the remesh's edge length are not corners).
    pub(crate) fn corners(&self, scale: f64) -> Vec<f64> {
        let m = self.position.len();
        let cos_corner = CORNER_DEG.to_radians().cos();
        let length = self.length();
        if !(scale > 0.0 && length > 4.0 * scale) {
            return Vec::new();
        }
        let cos_at: Vec<f64> = (0..m)
            .map(|k| {
                let x = self.position[k];
                let (u, w) = (sub(self.at(self.arc[k] - scale).1, x), sub(self.at(self.arc[k] + scale).1, x));
                let l = norm(u) * norm(w);
                if l > 0.0 { dot(u, w) / l } else { -1.0 }
            })
            .collect();
        // A larger cosine is a sharper corner; ties go to the first vertex.
        (0..m)
            .filter(|&k| {
                cos_at[k] > cos_corner
                    && (0..m).all(|j| {
                        let d = (self.arc[j] - self.arc[k]).rem_euclid(length);
                        let near = d.min(length - d) <= scale && j != k;
                        !near || cos_at[j] < cos_at[k] || (cos_at[j] == cos_at[k] && j > k)
                    })
            })
            .map(|k| self.arc[k])
            .collect()
    }
}

/// The remesh's boundary cycle: for each vertex, its successor and predecessor along the
/// boundary (`u32::MAX` off the boundary).
pub(crate) fn boundary_cycle(faces: &[[u32; 3]], n: usize) -> (Vec<u32>, Vec<u32>) {
    let mut directed = crate::mesh::fasthash::FastMap::<(u32, u32), ()>::default();
    for f in faces {
        for k in 0..3 {
            directed.insert((f[k], f[(k + 1) % 3]), ());
        }
    }
    let (mut next, mut prev) = (vec![u32::MAX; n], vec![u32::MAX; n]);
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if !directed.contains_key(&(b, a)) {
                next[a as usize] = b;
                prev[b as usize] = a;
            }
        }
    }
    (next, prev)
}

/// Signed shortest difference `to - from` on a loop of length `length`.
fn loop_difference(from: f64, to: f64, length: f64) -> f64 {
    let d = (to - from).rem_euclid(length);
    if d > 0.5 * length { d - length } else { d }
}

/// Put a remesh vertex on each input corner (the one nearest by arc length, when the move
/// keeps its faces valid) and fix it there. `arc[v]` holds each boundary vertex's arc length.
pub(crate) fn pin_corners(mesh: &mut Shaping, incidence: &Incidence, track: &Track, arc: &mut [f64], scale: f64) -> usize {
    let length = track.length();
    let boundary: Vec<usize> = (0..mesh.role.len()).filter(|&v| mesh.role[v] == Role::Boundary).collect();
    let mut pinned = 0;
    for s in track.corners(scale) {
        let Some(&v) = boundary.iter().filter(|&&v| mesh.role[v] == Role::Boundary).min_by(|&&a, &&b| {
            loop_difference(arc[a], s, length).abs().total_cmp(&loop_difference(arc[b], s, length).abs())
        }) else {
            break;
        };
        let (q, x) = track.at(s);
        let ring = incidence.of(v);
        if ring_valid_in_plane(mesh, ring, v, q) && ring_faces_same_side(mesh, ring, v, x) {
            mesh.plane[v] = q;
            mesh.position[v] = x;
            arc[v] = s;
            mesh.role[v] = Role::Fixed;
            pinned += 1;
        }
    }
    pinned
}

/// The slid position of boundary vertex `v` (between its boundary neighbours `prev` and
/// `next`, at the middle of their arc), halved until its faces stay valid: the planar point,
/// the surface point and the arc length, or `None`.
pub(crate) fn slide_vertex(mesh: &Shaping, incidence: &Incidence, track: &Track, arc: &[f64], v: usize, prev: usize, next: usize) -> Option<([f64; 2], [f64; 3], f64)> {
    let length = track.length();
    if !(length > 0.0) {
        return None;
    }
    let gap = (arc[next] - arc[prev]).rem_euclid(length);
    let target = arc[prev] + 0.5 * gap;
    let delta = loop_difference(arc[v], target, length);
    let ring = incidence.of(v);
    let mut step = 1.0;
    for _ in 0..=HALVINGS {
        let s = (arc[v] + step * delta).rem_euclid(length);
        let (q, x) = track.at(s);
        if ring_valid_in_plane(mesh, ring, v, q) && ring_faces_same_side(mesh, ring, v, x) {
            return Some((q, x, s));
        }
        step *= 0.5;
    }
    None
}
