//! The regular (weighted Delaunay) triangulation of the transport sites, kept up to date by
//! edge flips as the weights change.
//!
//! The power diagram of sites `y_i` with weights `w_i` (power distance `|x - y_i|^2 - w_i`) is
//! the dual of the regular triangulation: the lower convex hull of the lifted points
//! `(y_i, |y_i|^2 - w_i)`. It starts as spade's Delaunay triangulation (all weights equal) and
//! is brought to the regular triangulation of new weights by Lawson flips with exact
//! predicates (`robust::orient3d` on the lifted points, `robust::orient2d` for convexity), so
//! the flips terminate. Between Newton steps the weights move a little and only a few edges
//! flip: this is the warm start of the transport solver. A site whose power cell empties in the
//! whole plane would have to leave the triangulation; the damped Newton method never accepts
//! such weights, and [`RegularTriangulation::update_weights`] reports it as `false`.

use robust::{orient2d, orient3d, Coord, Coord3D};
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

/// Marks "no triangle" (a hull edge) in the adjacency.
pub const NONE: u32 = u32::MAX;

/// Errors building the triangulation.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum TriangulationError {
    /// Two sites coincide to machine precision.
    #[error("{count} transport sites coincide in the plane (the initial flattening squeezed part of the surface below double precision)")]
    CoincidentSites {
        /// How many sites were merged.
        count: usize,
    },
    /// Spade refused a point.
    #[error("cannot triangulate the transport sites: {0}")]
    Insertion(String),
}

/// A point for spade's Delaunay triangulation carrying the index of its site.
pub(crate) struct Site {
    /// Position.
    pub(crate) p: Point2<f64>,
    /// Index in the caller's site list.
    pub(crate) id: u32,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

/// A triangulation of the sites with counter-clockwise triangles and adjacency.
#[derive(Debug, Clone)]
pub struct RegularTriangulation {
    /// Site positions.
    pub sites: Vec<[f64; 2]>,
    /// Weights (power distance `|x - y_i|^2 - w_i`).
    pub weights: Vec<f64>,
    /// Triangles, counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
    /// `neighbors[t][k]`: the triangle across the edge opposite corner `k`, or [`NONE`].
    pub neighbors: Vec<[u32; 3]>,
    /// One triangle incident to each site.
    pub vertex_triangle: Vec<u32>,
    /// Total number of flips performed (for reports).
    pub flips: usize,
}

/// [`RegularTriangulation::update_weights`] gives up after `STUCK_EDGES_BASE + n /
/// STUCK_EDGES_RATIO` flips that could not be made (`n` sites). The transport's line search
/// tries long steps first and most of them make sites redundant, which the flips only find
/// out at the end: on the hand's full-resolution solve every accepted trial met no stuck
/// edge, the rejected ones up to hundreds of thousands. Giving up early changed no Newton
/// iteration count and no map on the shared and synthetic meshes; a trial refused too early
/// would only shorten that Newton step.
pub const STUCK_EDGES_RATIO: usize = 64;

/// See [`STUCK_EDGES_RATIO`].
pub const STUCK_EDGES_BASE: usize = 64;

impl RegularTriangulation {
    /// The Delaunay triangulation of `sites` (all weights zero).
    pub fn delaunay(sites: &[[f64; 2]]) -> Result<Self, TriangulationError> {
        let elems: Vec<Site> = sites
            .iter()
            .enumerate()
            .map(|(i, p)| Site { p: Point2::new(p[0], p[1]), id: i as u32 })
            .collect();
        let dt: DelaunayTriangulation<Site> = DelaunayTriangulation::bulk_load(elems)
            .map_err(|e| TriangulationError::Insertion(format!("{e:?}")))?;
        if dt.num_vertices() != sites.len() {
            return Err(TriangulationError::CoincidentSites { count: sites.len() - dt.num_vertices() });
        }
        let triangles: Vec<[u32; 3]> = dt
            .inner_faces()
            .map(|f| {
                let v = f.vertices();
                [v[0].data().id, v[1].data().id, v[2].data().id]
            })
            .collect();
        let mut tri = Self {
            sites: sites.to_vec(),
            weights: vec![0.0; sites.len()],
            triangles,
            neighbors: Vec::new(),
            vertex_triangle: Vec::new(),
            flips: 0,
        };
        tri.orient_ccw();
        tri.rebuild_adjacency();
        Ok(tri)
    }

    fn orient_ccw(&mut self) {
        for t in &mut self.triangles {
            let [a, b, c] = *t;
            if orient2d(co(self.sites[a as usize]), co(self.sites[b as usize]), co(self.sites[c as usize])) < 0.0 {
                t.swap(1, 2);
            }
        }
    }

    /// Recompute `neighbors` and `vertex_triangle` from `triangles`.
    pub fn rebuild_adjacency(&mut self) {
        let nt = self.triangles.len();
        let mut half: Vec<(u64, u32)> = Vec::with_capacity(3 * nt);
        for (t, tri) in self.triangles.iter().enumerate() {
            for k in 0..3 {
                let a = tri[(k + 1) % 3] as u64;
                let b = tri[(k + 2) % 3] as u64;
                let key = if a < b { (a << 32) | b } else { (b << 32) | a };
                half.push((key, (t as u32) * 3 + k as u32));
            }
        }
        half.sort_unstable();
        self.neighbors = vec![[NONE; 3]; nt];
        let mut i = 0;
        while i < half.len() {
            if i + 1 < half.len() && half[i].0 == half[i + 1].0 {
                let (t1, k1) = ((half[i].1 / 3) as usize, (half[i].1 % 3) as usize);
                let (t2, k2) = ((half[i + 1].1 / 3) as usize, (half[i + 1].1 % 3) as usize);
                self.neighbors[t1][k1] = t2 as u32;
                self.neighbors[t2][k2] = t1 as u32;
                i += 2;
            } else {
                i += 1;
            }
        }
        self.vertex_triangle = vec![NONE; self.sites.len()];
        for (t, tri) in self.triangles.iter().enumerate() {
            for &v in tri {
                self.vertex_triangle[v as usize] = t as u32;
            }
        }
    }

    /// The lifted point of `v` relative to site `o`: `(p - q, |p - q|^2 - (w_p - w_q))`.
    /// Lifting relative to a nearby site keeps the small differences that decide regularity
    /// (an absolute lift `|p|^2` rounds them away for sites closer than about 1e-8).
    fn lifted(&self, v: u32, o: u32) -> Coord3D<f64> {
        let p = self.sites[v as usize];
        let q = self.sites[o as usize];
        let (x, y) = (p[0] - q[0], p[1] - q[1]);
        Coord3D { x, y, z: x * x + y * y - (self.weights[v as usize] - self.weights[o as usize]) }
    }

    /// Is the edge opposite corner `k` of triangle `t` locally regular?
    fn locally_regular(&self, t: usize, k: usize) -> bool {
        let u = self.neighbors[t][k];
        if u == NONE {
            return true;
        }
        let [a, b, c] = self.triangles[t];
        let d = self.opposite_vertex(t, k);
        // d strictly below the plane through the lifted a, b, c: not regular.
        orient3d(self.lifted(a, d), self.lifted(b, d), self.lifted(c, d), Coord3D { x: 0.0, y: 0.0, z: 0.0 }) <= 0.0
    }

    /// The vertex of the neighbour across edge `k` of `t` that is not on that edge.
    fn opposite_vertex(&self, t: usize, k: usize) -> u32 {
        let u = self.neighbors[t][k] as usize;
        let ku = self.neighbors[u].iter().position(|&x| x == t as u32).unwrap_or(0);
        self.triangles[u][ku]
    }

    /// Flip the edge opposite corner `k` of `t` if the quadrilateral is strictly convex.
    /// Returns the two triangles, or `None` when the flip is impossible.
    fn flip(&mut self, t: usize, k: usize) -> Option<(usize, usize)> {
        let u = self.neighbors[t][k] as usize;
        let ku = self.neighbors[u].iter().position(|&x| x == t as u32)?;
        let c = self.triangles[t][k];
        let a = self.triangles[t][(k + 1) % 3];
        let b = self.triangles[t][(k + 2) % 3];
        let d = self.triangles[u][ku];
        // New triangles (c, a, d) and (d, b, c): both must be counter-clockwise.
        let s = |v: u32| co(self.sites[v as usize]);
        if orient2d(s(c), s(a), s(d)) <= 0.0 || orient2d(s(d), s(b), s(c)) <= 0.0 {
            return None;
        }
        // Outer neighbours before the flip.
        let n_ta = self.neighbors[t][(k + 2) % 3]; // across (c, a)
        let n_tb = self.neighbors[t][(k + 1) % 3]; // across (b, c)
        let n_ua = self.neighbors[u][(ku + 1) % 3]; // across (a, d) in u = (d, b, a) order
        let n_ub = self.neighbors[u][(ku + 2) % 3]; // across (d, b)
        // Check u's orientation assumption: u = (d, b, a) rotated.
        debug_assert_eq!(self.triangles[u][(ku + 1) % 3], b);
        self.triangles[t] = [c, a, d];
        self.triangles[u] = [d, b, c];
        // t = (c, a, d): opposite c is (a, d) -> n_ua; opposite a is (d, c) -> u; opposite d is (c, a) -> n_ta.
        self.neighbors[t] = [n_ua, u as u32, n_ta];
        // u = (d, b, c): opposite d is (b, c) -> n_tb; opposite b is (c, d) -> t; opposite c is (d, b) -> n_ub.
        self.neighbors[u] = [n_tb, t as u32, n_ub];
        self.relink(n_ua, u, t);
        self.relink(n_tb, t, u);
        for v in [c, a, d] {
            self.vertex_triangle[v as usize] = t as u32;
        }
        self.vertex_triangle[b as usize] = u as u32;
        self.flips += 1;
        Some((t, u))
    }

    fn relink(&mut self, n: u32, old: usize, new: usize) {
        if n == NONE {
            return;
        }
        if let Some(slot) = self.neighbors[n as usize].iter_mut().find(|x| **x == old as u32) {
            *slot = new as u32;
        }
    }

    /// Set new weights and flip until every edge is locally regular. Returns `false` when
    /// that cannot be reached by flips (some site has become redundant); the triangulation is
    /// then left in an intermediate state and must be restored by the caller. A non-regular
    /// edge whose quad is not convex cannot flip yet; more than
    /// `STUCK_EDGES_BASE + n / STUCK_EDGES_RATIO` such events end the attempt early with
    /// `false` (see [`STUCK_EDGES_RATIO`]).
    pub fn update_weights(&mut self, weights: &[f64]) -> bool {
        self.update_weights_with(weights, &mut Vec::new())
    }

    /// [`RegularTriangulation::update_weights`] with its edge stack's buffer in `stack`
    /// (kept between calls by the transport's trial steps: see [`super::cells::MassScratch`]).
    pub(crate) fn update_weights_with(&mut self, weights: &[f64], stack: &mut Vec<(u32, u8)>) -> bool {
        self.weights.copy_from_slice(weights);
        let nt = self.triangles.len();
        stack.clear();
        stack.reserve(3 * nt);
        for t in 0..nt {
            for k in 0..3 {
                let u = self.neighbors[t][k];
                if u != NONE && (u as usize) > t {
                    stack.push((t as u32, k as u8));
                }
            }
        }
        let budget = 50 * nt + 1000;
        let stuck_budget = STUCK_EDGES_BASE + self.sites.len() / STUCK_EDGES_RATIO;
        let mut flips = 0usize;
        let mut stuck = 0usize;
        while let Some((t, k)) = stack.pop() {
            let (t, k) = (t as usize, k as usize);
            if self.locally_regular(t, k) {
                continue;
            }
            match self.flip(t, k) {
                Some((t1, t2)) => {
                    flips += 1;
                    if flips > budget {
                        return false;
                    }
                    for tt in [t1, t2] {
                        for kk in 0..3 {
                            if self.neighbors[tt][kk] != NONE {
                                stack.push((tt as u32, kk as u8));
                            }
                        }
                    }
                }
                None => {
                    stuck += 1;
                    if stuck > stuck_budget {
                        return false;
                    }
                }
            }
        }
        if stuck == 0 {
            return true;
        }
        self.is_regular()
    }

    /// Make `self` a copy of `other`, reusing `self`'s buffers.
    pub(crate) fn copy_from(&mut self, other: &Self) {
        // Destructured, so that a new field cannot be forgotten here.
        let Self { sites, weights, triangles, neighbors, vertex_triangle, flips } = other;
        self.sites.clone_from(sites);
        self.weights.clone_from(weights);
        self.triangles.clone_from(triangles);
        self.neighbors.clone_from(neighbors);
        self.vertex_triangle.clone_from(vertex_triangle);
        self.flips = *flips;
    }

    /// Every interior edge locally regular.
    pub fn is_regular(&self) -> bool {
        (0..self.triangles.len()).all(|t| (0..3).all(|k| self.locally_regular(t, k)))
    }

    /// Power center of triangle `t`: the point with equal power distance to its three sites.
    pub fn power_center(&self, t: usize) -> [f64; 2] {
        let [a, b, c] = self.triangles[t];
        let (pa, pb, pc) = (self.sites[a as usize], self.sites[b as usize], self.sites[c as usize]);
        let (wa, wb, wc) = (self.weights[a as usize], self.weights[b as usize], self.weights[c as usize]);
        // 2 <x, p - pa> = |p|^2 - |pa|^2 - (w - wa), relative to pa for accuracy.
        let bx = pb[0] - pa[0];
        let by = pb[1] - pa[1];
        let cx = pc[0] - pa[0];
        let cy = pc[1] - pa[1];
        let rb = bx * bx + by * by - (wb - wa);
        let rc = cx * cx + cy * cy - (wc - wa);
        let det = 2.0 * (bx * cy - by * cx);
        if det == 0.0 {
            // Flat triangle: put the center far away along the common normal.
            return [pa[0] + 1e12 * (-by), pa[1] + 1e12 * bx];
        }
        [pa[0] + (rb * cy - rc * by) / det, pa[1] + (bx * rc - cx * rb) / det]
    }
}

#[inline]
fn co(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random_points(n: usize, seed: u64) -> Vec<[f64; 2]> {
        let mut s = seed;
        let mut next = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((s >> 11) as f64) / ((1u64 << 53) as f64)
        };
        (0..n).map(|_| [2.0 * next() - 1.0, 2.0 * next() - 1.0]).collect()
    }

    #[test]
    fn flips_reach_regular_triangulation_and_back() {
        let pts = random_points(400, 7);
        let mut tri = RegularTriangulation::delaunay(&pts).unwrap();
        assert!(tri.is_regular());
        let w: Vec<f64> = pts.iter().map(|p| 0.02 * (3.0 * p[0]).sin() * p[1]).collect();
        assert!(tri.update_weights(&w));
        assert!(tri.is_regular());
        assert!(tri.flips > 0);
        // Back to zero weights gives a Delaunay triangulation with the same triangle count.
        let n_before = tri.triangles.len();
        assert!(tri.update_weights(&vec![0.0; pts.len()]));
        assert_eq!(tri.triangles.len(), n_before);
        assert!(tri.is_regular());
        // All triangles counter-clockwise.
        for t in &tri.triangles {
            let s = |v: u32| co(pts[v as usize]);
            assert!(orient2d(s(t[0]), s(t[1]), s(t[2])) > 0.0);
        }
    }

    /// A triangulation copied into another one's buffers, then updated with a kept stack,
    /// ends as a clone updated afresh does.
    #[test]
    fn copied_triangulations_update_like_clones() {
        let pts = random_points(400, 11);
        let mut current = RegularTriangulation::delaunay(&pts).unwrap();
        let w: Vec<f64> = pts.iter().map(|p| 0.02 * (3.0 * p[0]).sin() * p[1]).collect();
        assert!(current.update_weights(&w));
        let mut spare = RegularTriangulation::delaunay(&random_points(150, 3)).unwrap();
        let mut stack = vec![(7, 1); 50];
        let w2: Vec<f64> = w.iter().map(|x| -0.5 * x).collect();
        spare.copy_from(&current);
        assert!(spare.update_weights_with(&w2, &mut stack));
        let mut fresh = current.clone();
        assert!(fresh.update_weights(&w2));
        let key = |t: &RegularTriangulation| (t.sites.clone(), t.weights.clone(), t.triangles.clone(), t.neighbors.clone(), t.vertex_triangle.clone(), t.flips);
        assert_eq!(key(&spare), key(&fresh));
    }

    #[test]
    fn unreachable_weights_are_refused_early() {
        // A strong smooth weight field hides sites: flips cannot reach it.
        let pts = random_points(2000, 11);
        let field = |a: f64| pts.iter().map(|p| a * (3.0 * p[0]).sin() * p[1]).collect::<Vec<f64>>();
        let mut tri = RegularTriangulation::delaunay(&pts).unwrap();
        let before = tri.flips;
        assert!(!tri.update_weights(&field(0.3)));
        let made = tri.flips - before;
        // 141 flips with the stuck-edge allowance, 1274 without.
        assert!(made < 500, "{made} flips before giving up");
        // A weaker one that needs more flips than the stuck-edge allowance is still reached.
        let mut tri = RegularTriangulation::delaunay(&pts).unwrap();
        let before = tri.flips;
        assert!(tri.update_weights(&field(0.1)));
        assert!(tri.is_regular());
        assert!(tri.flips - before > STUCK_EDGES_BASE + pts.len() / STUCK_EDGES_RATIO, "{} flips", tri.flips - before);
    }

    #[test]
    fn power_center_is_equidistant() {
        let pts = random_points(50, 3);
        let mut tri = RegularTriangulation::delaunay(&pts).unwrap();
        let w: Vec<f64> = (0..50).map(|i| 1e-5 * i as f64).collect();
        assert!(tri.update_weights(&w));
        for t in 0..tri.triangles.len() {
            let c = tri.power_center(t);
            let pw = |v: u32| {
                let p = pts[v as usize];
                (c[0] - p[0]).powi(2) + (c[1] - p[1]).powi(2) - w[v as usize]
            };
            let [a, b, cc] = tri.triangles[t];
            assert!((pw(a) - pw(b)).abs() < 1e-9 && (pw(a) - pw(cc)).abs() < 1e-9);
        }
    }
}
