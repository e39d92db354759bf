//! Placing remesh vertices on the creases (see [`super`]): points along each chain about one
//! edge length apart, the nearest free vertex of each moved onto it through the map.

use super::grid::PointGrid;
use super::join::{join, Around};
use crate::mesh::geometry::{norm, sub};
use crate::remesh::shape::smooth::{ring_faces_same_side, ring_valid_in_plane};
use crate::remesh::shape::state::{Incidence, Role, Shaping, SurfaceLift};

/// A chain shorter than this many remesh edge lengths is not kept (a scanned surface's
/// jags and short folds).
const MIN_CHAIN_EDGES: f64 = 3.0;

/// A vertex farther than this many edge lengths from a crease point is not moved onto it.
const REACH: f64 = 0.75;

/// A crease point this close (in edge lengths) to a vertex already on a crease takes that
/// vertex (a junction of chains).
const JUNCTION: f64 = 0.25;

/// A crease point this close (in edge lengths) to a vertex on another crease point gets no
/// vertex.
const CROWDED: f64 = 0.6;

/// A crease vertex of a face whose smallest angle is below this (degrees) at the end of the
/// iterations is freed, for the sliver removal and the moves for shape
/// ([`crate::remesh::shape::sliver`], [`crate::remesh::shape::worst`]).
pub(crate) const RELEASE_BELOW_DEG: f64 = 15.0;

/// The vertex of a crease point skipped as crowded.
const SKIPPED: u32 = u32::MAX - 1;

/// Halvings of a taken vertex's move towards its crease point.
const HALVINGS: usize = 5;

/// A point along a crease: planar and surface position.
type CreasePoint = ([f64; 2], [f64; 3]);

/// Points along `chain` spaced by about `len` (both ends included), planar and on the
/// surface; none for a chain shorter than [`MIN_CHAIN_EDGES`] edge lengths.
fn chain_points(lift: &SurfaceLift, chain: &[u32], len: f64) -> Vec<CreasePoint> {
    let inverse = lift.inverse();
    let (x, p) = (&inverse.mesh().vertices, &inverse.map().plane);
    let mut arc = vec![0.0];
    for w in chain.windows(2) {
        let l = norm(sub(x[w[1] as usize], x[w[0] as usize]));
        arc.push(arc.last().copied().unwrap_or(0.0) + l);
    }
    let total = *arc.last().unwrap_or(&0.0);
    if !(total >= MIN_CHAIN_EDGES * len) {
        return Vec::new();
    }
    let n = (total / len).round().max(1.0) as usize;
    let closed = chain.first() == chain.last();
    let count = if closed { n } else { n + 1 };
    (0..count)
        .map(|k| {
            let s = total * k as f64 / n as f64;
            let i = arc.partition_point(|&a| a <= s).saturating_sub(1).min(chain.len() - 2);
            let seg = arc[i + 1] - arc[i];
            let t = if seg > 0.0 { ((s - arc[i]) / seg).clamp(0.0, 1.0) } else { 0.0 };
            let (a, b) = (chain[i] as usize, chain[i + 1] as usize);
            ([0, 1].map(|c| p[a][c] + t * (p[b][c] - p[a][c])), [0, 1, 2].map(|c| x[a][c] + t * (x[b][c] - x[a][c])))
        })
        .collect()
}

/// The crease points of a remesh and the vertex put on each (see the module docs).
pub(crate) struct CreaseSnap {
    /// Each chain's points: planar point, surface point and the vertex on it (`u32::MAX`:
    /// none yet, [`SKIPPED`]: none), and whether the chain is a closed loop.
    runs: Vec<(Vec<(CreasePoint, u32)>, bool)>,
    /// The remesh's edge length.
    len: f64,
}

impl CreaseSnap {
    /// The points along the creases `chains` spaced by about `len` (the remesh's edge length).
    pub(crate) fn new(lift: &SurfaceLift, chains: &[Vec<u32>], len: f64) -> Self {
        let runs = if len > 0.0 {
            chains
                .iter()
                .map(|chain| (chain_points(lift, chain, len).into_iter().map(|p| (p, u32::MAX)).collect::<Vec<_>>(), chain.first() == chain.last()))
                .filter(|(points, _)| !points.is_empty())
                .collect()
        } else {
            Vec::new()
        };
        Self { runs, len }
    }

    /// The vertices of each pair of consecutive crease points (around a closed loop too).
    fn pairs(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.runs.iter().flat_map(|(points, closed)| {
            let m = points.len();
            (0..if *closed { m } else { m.saturating_sub(1) }).map(move |k| (points[k].1, points[(k + 1) % m].1))
        })
    }

    /// Consecutive crease points joined by an edge of `mesh`, and all such pairs.
    pub(crate) fn joined(&self, mesh: &Shaping) -> (usize, usize) {
        let around = Around::new(mesh);
        let (mut joined, mut pairs) = (0, 0);
        for (u, w) in self.pairs() {
            pairs += 1;
            joined += usize::from(u < SKIPPED && w < SKIPPED && around.joined(mesh, u, w));
        }
        (joined, pairs)
    }

    /// Vertices on their crease points.
    pub(crate) fn placed(&self, mesh: &Shaping) -> usize {
        self.runs.iter().flat_map(|(points, _)| points).filter(|((q, _), v)| *v < SKIPPED && mesh.plane[*v as usize] == *q).count()
    }

    /// Move free vertices of `mesh` onto the points that have none yet (the nearest whose
    /// faces stay valid; it takes the role [`Role::Crease`]), then join consecutive placed
    /// points by edge flips. Returns the edges flipped.
    pub(crate) fn attempt(&mut self, mesh: &mut Shaping, lift: &SurfaceLift) -> usize {
        let len = self.len;
        if self.runs.is_empty() {
            return 0;
        }
        let incidence: Incidence = mesh.incidence();
        // Free vertices with faces (a collapsed vertex has none).
        let free = (0..mesh.plane.len()).filter(|&v| mesh.role[v] == Role::Free && mesh.planar(v as u32) && !incidence.of(v).is_empty());
        let grid = PointGrid::new(len, free.map(|v| (v as u32, mesh.position[v])));
        // The points that have a vertex, and it (judged by the point: the vertex may still
        // be on its way).
        let mut placed: Vec<([f64; 3], u32)> = self.runs.iter().flat_map(|(points, _)| points).filter(|(_, v)| *v < SKIPPED).map(|((_, x), v)| (*x, *v)).collect();
        for (points, _) in &mut self.runs {
            for ((_, x), at) in points.iter_mut() {
                if *at != u32::MAX {
                    continue;
                }
                // A junction shared with another chain: the vertex already there. A point
                // crowded by another crease's vertex (parallel creases closer than an edge
                // length, points next to a junction) is skipped for good.
                let nearest = placed.iter().map(|&(y, v)| (norm(sub(y, *x)), v)).min_by(|a, b| a.0.total_cmp(&b.0));
                match nearest {
                    Some((d, v)) if d < JUNCTION * len => {
                        *at = v;
                        continue;
                    }
                    Some((d, _)) if d < CROWDED * len => {
                        *at = SKIPPED;
                        continue;
                    }
                    _ => {}
                }
                // The nearest vertex still free is taken; it travels onto the point over the
                // iterations (see below).
                let nearest = grid.near(*x, REACH * len).filter(|&(v, _)| mesh.role[v as usize] == Role::Free).min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                if let Some((v, _)) = nearest {
                    mesh.role[v as usize] = Role::Crease;
                    placed.push((*x, v));
                    *at = v;
                }
            }
        }
        // Each taken vertex moves onto its point, or as far towards it as its faces allow
        // (halving the move; it stays on the surface, lifted through the map). A vertex
        // shared at a junction goes to its first point.
        let mut seen = vec![false; mesh.plane.len()];
        for (points, _) in &self.runs {
            for &((q, x), v) in points {
                if v >= SKIPPED || std::mem::replace(&mut seen[v as usize], true) || mesh.plane[v as usize] == q {
                    continue;
                }
                let (v, q0) = (v as usize, mesh.plane[v as usize]);
                let ring = incidence.of(v);
                let mut step = 1.0;
                for _ in 0..=HALVINGS {
                    let p = [q0[0] + step * (q[0] - q0[0]), q0[1] + step * (q[1] - q0[1])];
                    let lifted = if step == 1.0 { Some((x, mesh.hint[v])) } else { lift.lift(p, mesh.hint[v]) };
                    if let Some((y, h)) = lifted {
                        if ring_valid_in_plane(mesh, ring, v, p) && ring_faces_same_side(mesh, ring, v, y) {
                            mesh.plane[v] = p;
                            mesh.position[v] = y;
                            mesh.hint[v] = h;
                            break;
                        }
                    }
                    step *= 0.5;
                }
            }
        }
        let mut flips = 0;
        let mut around = Around::new(mesh);
        for (u, w) in self.pairs() {
            if u < SKIPPED && w < SKIPPED && u != w && !around.joined(mesh, u, w) {
                flips += join(mesh, &mut around, u, w);
            }
        }
        flips
    }
}

/// Free the crease vertices of the faces of `mesh` below [`RELEASE_BELOW_DEG`]: a thin face
/// costs more than a point off the crease. Returns the vertices freed.
pub(crate) fn release_thin(mesh: &mut Shaping) -> usize {
    let thin = crate::remesh::shape::state::thin_face_vertices(mesh, RELEASE_BELOW_DEG.to_radians(), |v| mesh.role[v as usize] == Role::Crease);
    for &v in &thin {
        mesh.role[v as usize] = Role::Free;
    }
    thin.len()
}
