//! Power cells clipped to the disk of radius `r`, and the integrals the Newton method needs:
//! cell masses, first moments (for the sigma-weighted centroids) and the Hessian entries
//! `d m_i / d w_j = -int_{cell_i ∩ cell_j} sigma ds / (2 |y_i - y_j|)`
//! (Kitagawa, Mérigot and Thibert 2019; the paper's Eq. 8 energy in weight form).
//!
//! Geometry traversal is apart from the integrand. Every piece is integrated from the origin
//! (fan triangles, circular sectors), so a cell's integral is the sum over its edges: each
//! power-cell edge (the dual of a triangulation edge, clipped to the disk) is integrated once
//! and added to one of its cells, taken from the other. Only the cells that meet the circle,
//! lie on the convex hull or have no edge inside the disk are walked whole: [`dual_polygon`]
//! walks the dual polygon of one site and [`clip_to_disk`] clips it to the disk, arcs
//! included; [`integrate_cell`] hands each piece (a straight edge or an arc of the circle) to
//! a [`RadialDensity`].

use super::density::RadialDensity;
use super::triangulation::{RegularTriangulation, NONE};
use rayon::prelude::*;

/// Integrals of every cell, and the off-diagonal Hessian entries per triangulation edge.
#[derive(Debug, Clone, Default)]
pub struct CellIntegrals {
    /// sigma-mass of each cell.
    pub mass: Vec<f64>,
    /// First moment `int x sigma` of each cell (empty from [`integrate_masses`]).
    pub moment: Vec<[f64; 2]>,
    /// `(i, j, c)` with `i < j` and `c = int sigma ds / (2 |y_i - y_j|)` over their common edge.
    pub edges: Vec<(u32, u32, f64)>,
}

impl CellIntegrals {
    /// sigma-weighted centroid of cell `i` (`None` for an empty cell). Needs the moments
    /// ([`integrate`]; panics on integrals from [`integrate_masses`]).
    pub fn centroid(&self, i: usize) -> Option<[f64; 2]> {
        let m = self.mass[i];
        (m > 0.0).then(|| [self.moment[i][0] / m, self.moment[i][1] / m])
    }
}

/// The portion of segment `a -> b` inside the disk of radius `r`, in the direction `a -> b`,
/// with flags telling whether each end lies on the circle. Roots are computed from the
/// endpoint nearer the origin so far-away power centers keep the clipped points accurate.
pub fn clip_segment(a: [f64; 2], b: [f64; 2], r: f64) -> Option<([f64; 2], [f64; 2], bool, bool)> {
    let na = a[0] * a[0] + a[1] * a[1];
    let nb = b[0] * b[0] + b[1] * b[1];
    let r2 = r * r;
    if na <= r2 && nb <= r2 {
        return Some((a, b, false, false));
    }
    let (p, q, reversed) = if na <= nb { (a, b, false) } else { (b, a, true) };
    let e = [q[0] - p[0], q[1] - p[1]];
    let aa = e[0] * e[0] + e[1] * e[1];
    if aa == 0.0 {
        return None;
    }
    let bb = p[0] * e[0] + p[1] * e[1];
    let cc = p[0] * p[0] + p[1] * p[1] - r2;
    let disc = bb * bb - aa * cc;
    if disc <= 0.0 {
        return None;
    }
    // Stable roots of aa s^2 + 2 bb s + cc = 0; qq != 0 because disc > 0.
    let sgn = if bb >= 0.0 { 1.0 } else { -1.0 };
    let qq = -(bb + sgn * disc.sqrt());
    let (mut s1, mut s2) = (qq / aa, cc / qq);
    if s1 > s2 {
        std::mem::swap(&mut s1, &mut s2);
    }
    let lo = s1.max(0.0);
    let hi = s2.min(1.0);
    if lo >= hi {
        return None;
    }
    let at = |s: f64| if s == 1.0 { q } else if s == 0.0 { p } else { [p[0] + s * e[0], p[1] + s * e[1]] };
    let (x_lo, x_hi) = (at(lo), at(hi));
    let (lo_on, hi_on) = (lo > 0.0, hi < 1.0);
    Some(if reversed { (x_hi, x_lo, hi_on, lo_on) } else { (x_lo, x_hi, lo_on, hi_on) })
}

/// One boundary piece of a clipped cell.
#[derive(Debug, Clone, Copy)]
pub enum Piece {
    /// A straight edge shared with site `label` ([`NONE`] for a far closing edge).
    Segment {
        /// Start point.
        a: [f64; 2],
        /// End point.
        b: [f64; 2],
        /// The neighbouring site.
        label: u32,
    },
    /// An arc of the circle of radius `r`, counter-clockwise from angle `alpha` to `beta`.
    Arc {
        /// Start angle.
        alpha: f64,
        /// End angle (`>= alpha`).
        beta: f64,
    },
}

/// The dual polygon of site `i` into `pts` and `labels` (cleared first): counter-clockwise
/// vertices with the neighbour label of the edge that starts at each vertex. Hull sites get
/// unbounded cells closed by far points.
pub fn dual_polygon(tri: &RegularTriangulation, centers: &[[f64; 2]], i: usize, far: f64, pts: &mut Vec<[f64; 2]>, labels: &mut Vec<u32>) {
    pts.clear();
    labels.clear();
    let t0 = tri.vertex_triangle[i];
    if t0 == NONE {
        return;
    }
    let corner = |t: usize| tri.triangles[t].iter().position(|&v| v as usize == i).unwrap_or(0);
    // Rotate clockwise to the hull, if the site is on it.
    let mut t = t0 as usize;
    let mut on_hull = false;
    let n_guard = tri.triangles.len() + 1;
    for _ in 0..n_guard {
        let k = corner(t);
        let cw = tri.neighbors[t][(k + 2) % 3];
        if cw == NONE {
            on_hull = true;
            break;
        }
        t = cw as usize;
        if t == t0 as usize {
            break;
        }
    }
    let start = t;
    let yi = tri.sites[i];
    let first_a = tri.triangles[start][(corner(start) + 1) % 3];
    for _ in 0..n_guard {
        let k = corner(t);
        let b = tri.triangles[t][(k + 2) % 3];
        pts.push(centers[t]);
        labels.push(b);
        let next = tri.neighbors[t][(k + 1) % 3];
        if next == NONE || next as usize == start {
            if next == NONE && on_hull {
                // Ray of the hull edge (b -> i), then a far closing point, then the ray of (i -> first_a).
                let pb = tri.sites[b as usize];
                let nb = unit([yi[1] - pb[1], -(yi[0] - pb[0])]);
                let pa = tri.sites[first_a as usize];
                let na = unit([pa[1] - yi[1], -(pa[0] - yi[0])]);
                let c_end = centers[t];
                let c_start = centers[start];
                let fb = [c_end[0] + far * nb[0], c_end[1] + far * nb[1]];
                let fa = [c_start[0] + far * na[0], c_start[1] + far * na[1]];
                let mid = unit([na[0] + nb[0], na[1] + nb[1]]);
                let fm = [yi[0] + 2.0 * far * mid[0], yi[1] + 2.0 * far * mid[1]];
                pts.push(fb);
                labels.push(NONE);
                pts.push(fm);
                labels.push(NONE);
                pts.push(fa);
                labels.push(first_a);
            }
            break;
        }
        t = next as usize;
    }
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let n = (v[0] * v[0] + v[1] * v[1]).sqrt();
    if n == 0.0 {
        [0.0, 0.0]
    } else {
        [v[0] / n, v[1] / n]
    }
}

/// The clipped segments of a polygon: `(start, end, label, enters, exits)`.
pub type ClippedSegment = ([f64; 2], [f64; 2], u32, bool, bool);

/// Clip a convex counter-clockwise polygon to the disk of radius `r`: its boundary pieces
/// into `pieces` (cleared first; `segs` is scratch). Returns whether the disk lies entirely
/// inside the polygon: no pieces and `false` means the cell misses the disk.
pub fn clip_to_disk(pts: &[[f64; 2]], labels: &[u32], r: f64, segs: &mut Vec<ClippedSegment>, pieces: &mut Vec<Piece>) -> bool {
    let n = pts.len();
    segs.clear();
    pieces.clear();
    for k in 0..n {
        if let Some((a, b, enters, exits)) = clip_segment(pts[k], pts[(k + 1) % n], r) {
            segs.push((a, b, labels[k], enters, exits));
        }
    }
    if segs.is_empty() {
        // The disk is inside the polygon iff the origin is on the left of every edge.
        let full = n >= 3
            && (0..n).all(|k| {
                let (a, b) = (pts[k], pts[(k + 1) % n]);
                (b[0] - a[0]) * (-a[1]) - (b[1] - a[1]) * (-a[0]) >= 0.0
            });
        return full;
    }
    let m = segs.len();
    for k in 0..m {
        let (a, b, label, _, exits) = segs[k];
        pieces.push(Piece::Segment { a, b, label });
        if exits {
            // Find the next segment that enters; the arc runs counter-clockwise to it.
            let (na, _, _, enters, _) = segs[(k + 1) % m];
            if enters {
                let alpha = b[1].atan2(b[0]);
                let mut beta = na[1].atan2(na[0]);
                while beta < alpha {
                    beta += 2.0 * std::f64::consts::PI;
                }
                pieces.push(Piece::Arc { alpha, beta });
            }
        }
    }
    false
}

/// Mass and first moment of a clipped cell.
pub fn integrate_cell(pieces: &[Piece], full: bool, r: f64, density: &dyn RadialDensity) -> (f64, [f64; 2]) {
    (cell_mass(pieces, full, r, density), cell_moment(pieces, full, r, density))
}

/// Mass of a clipped cell.
fn cell_mass(pieces: &[Piece], full: bool, r: f64, density: &dyn RadialDensity) -> f64 {
    if full {
        return density.disk_mass(r);
    }
    let mass: f64 = pieces
        .iter()
        .map(|p| match *p {
            Piece::Segment { a, b, .. } => density.fan_mass(a, b),
            Piece::Arc { alpha, beta } => density.sector_mass(r, alpha, beta),
        })
        .sum();
    mass.max(0.0)
}

/// First moment of a clipped cell.
fn cell_moment(pieces: &[Piece], full: bool, r: f64, density: &dyn RadialDensity) -> [f64; 2] {
    if full {
        return [0.0, 0.0];
    }
    let mut mom = [0.0, 0.0];
    for p in pieces {
        let q = match *p {
            Piece::Segment { a, b, .. } => density.fan_moment(a, b),
            Piece::Arc { alpha, beta } => density.sector_moment(r, alpha, beta),
        };
        mom[0] += q[0];
        mom[1] += q[1];
    }
    mom
}

/// Power centers of the triangles and the length of the far closing edges of unbounded cells.
fn centers_and_far(tri: &RegularTriangulation, r: f64) -> (Vec<[f64; 2]>, f64) {
    let mut centers = Vec::new();
    let far = centers_into(tri, r, &mut centers);
    (centers, far)
}

/// [`centers_and_far`] into `centers` (its buffer reused); returns the far length.
fn centers_into(tri: &RegularTriangulation, r: f64, centers: &mut Vec<[f64; 2]>) -> f64 {
    centers.clear();
    centers.par_extend((0..tri.triangles.len()).into_par_iter().map(|t| tri.power_center(t)));
    let max_c = centers.iter().map(|c| c[0].abs().max(c[1].abs())).fold(0.0f64, f64::max);
    4.0 * (r + max_c.min(1e8 * r.max(1.0))) + 1.0
}

/// The work buffers of [`integrate_masses_with`], kept between calls: the transport's trial
/// steps integrate the masses of a large mesh again and again, and on a virtual machine a
/// buffer written fresh each time costs page faults (docs/method.md section 20).
#[derive(Default)]
pub(crate) struct MassScratch {
    centers: Vec<[f64; 2]>,
    edges: Vec<ClippedEdge<(f64, f64)>>,
}

/// All cell integrals of the current (regular) triangulation, clipped to the disk of radius `r`.
pub fn integrate(tri: &RegularTriangulation, r: f64, density: &dyn RadialDensity) -> CellIntegrals {
    let mut cells = integrate_masses(tri, r, density);
    cells.moment = cell_moments(tri, r, density);
    cells
}

/// The first moments of every cell (what [`integrate`] adds to [`integrate_masses`]), each
/// power-cell edge's fan moment computed once for both its cells like the masses.
pub fn cell_moments(tri: &RegularTriangulation, r: f64, density: &dyn RadialDensity) -> Vec<[f64; 2]> {
    let (centers, far) = centers_and_far(tri, r);
    let edges = clipped_edges(tri, &centers, far, r, |_, _, x0, x1| density.fan_moment(x0, x1));
    let mut moment = vec![[0.0; 2]; tri.sites.len()];
    for e in &edges {
        let (i, j, [x, y]) = (e.i as usize, e.j as usize, e.value);
        moment[j] = [moment[j][0] + x, moment[j][1] + y];
        moment[i] = [moment[i][0] - x, moment[i][1] - y];
    }
    for (v, m) in walked_cells(tri, &centers, far, r, &edges, |pieces, full| cell_moment(pieces, full, r, density)) {
        moment[v] = m;
    }
    moment
}

/// Buffers of one cell's polygon and pieces, reused from cell to cell.
#[derive(Default)]
struct CellScratch {
    pts: Vec<[f64; 2]>,
    labels: Vec<u32>,
    segs: Vec<ClippedSegment>,
    pieces: Vec<Piece>,
}

/// Masses and Hessian entries only (`moment` left empty): what each Newton iteration needs.
/// The moments take a Gauss-Legendre rule per cell edge, so they are left to the end of
/// each solve.
///
/// Each power-cell edge's fan mass and Hessian entry come from one arctangent
/// ([`RadialDensity::fan_mass_and_segment_integral`]) instead of three per interior edge
/// for whole-cell walks.
pub fn integrate_masses(tri: &RegularTriangulation, r: f64, density: &dyn RadialDensity) -> CellIntegrals {
    integrate_masses_with(tri, r, density, &mut MassScratch::default())
}

/// [`integrate_masses`] with its work buffers in `scratch` (the same values).
pub(crate) fn integrate_masses_with(tri: &RegularTriangulation, r: f64, density: &dyn RadialDensity, scratch: &mut MassScratch) -> CellIntegrals {
    let MassScratch { centers, edges } = scratch;
    let far = centers_into(tri, r, centers);
    let centers = &*centers;
    clipped_edges_into(tri, centers, far, r, edges, |pi, pj, x0, x1| {
        let (fan, s) = density.fan_mass_and_segment_integral(x0, x1);
        let d = ((pi[0] - pj[0]).powi(2) + (pi[1] - pj[1]).powi(2)).sqrt();
        (fan, if s > 0.0 && d > 0.0 { s / (2.0 * d) } else { 0.0 })
    });
    let edges = &*edges;
    // Sum the fans in edge order (deterministic whatever the threads' split).
    let mut mass = vec![0.0; tri.sites.len()];
    for e in edges {
        mass[e.j as usize] += e.value.0;
        mass[e.i as usize] -= e.value.0;
    }
    for (v, m) in walked_cells(tri, centers, far, r, edges, |pieces, full| cell_mass(pieces, full, r, density)) {
        mass[v] = m;
    }
    for m in &mut mass {
        *m = m.max(0.0);
    }
    let edges = edges.iter().filter(|e| e.value.1 > 0.0).map(|e| (e.i.min(e.j), e.i.max(e.j), e.value.1)).collect();
    CellIntegrals { mass, moment: Vec::new(), edges }
}

/// One power-cell edge clipped to the disk with `value` integrated on it: its sites
/// (`a -> b` runs counter-clockwise around `j`, clockwise around `i`), and whether both its
/// ends are inside the disk and it is bounded.
#[derive(Debug, Clone, Copy)]
struct ClippedEdge<T> {
    i: u32,
    j: u32,
    value: T,
    whole: bool,
}

/// Every power-cell edge (the dual of each triangulation edge, from the triangles' power
/// `centers`; hull edges give rays of length `far`) clipped to the disk of radius `r`, with
/// `f(y_i, y_j, start, end)` of the clipped segment. In parallel over the triangles, each
/// edge once, in triangle order.
fn clipped_edges<T: Send>(tri: &RegularTriangulation, centers: &[[f64; 2]], far: f64, r: f64, f: impl Fn([f64; 2], [f64; 2], [f64; 2], [f64; 2]) -> T + Sync) -> Vec<ClippedEdge<T>> {
    let mut out = Vec::new();
    clipped_edges_into(tri, centers, far, r, &mut out, f);
    out
}

/// [`clipped_edges`] into `out` (its buffer reused, the same order).
fn clipped_edges_into<T: Send>(tri: &RegularTriangulation, centers: &[[f64; 2]], far: f64, r: f64, out: &mut Vec<ClippedEdge<T>>, f: impl Fn([f64; 2], [f64; 2], [f64; 2], [f64; 2]) -> T + Sync) {
    let f = &f;
    out.clear();
    out.par_extend((0..tri.triangles.len())
        .into_par_iter()
        .flat_map_iter(|t| {
            let tr = tri.triangles[t];
            (0..3).filter_map(move |k| {
                let u = tri.neighbors[t][k];
                let (i, j) = (tr[(k + 1) % 3], tr[(k + 2) % 3]);
                let (pi, pj) = (tri.sites[i as usize], tri.sites[j as usize]);
                let (a, b) = if u == NONE {
                    // Hull edge i -> j: ray outward (to the right of i -> j).
                    let nrm = unit([pj[1] - pi[1], -(pj[0] - pi[0])]);
                    let c = centers[t];
                    (c, [c[0] + far * nrm[0], c[1] + far * nrm[1]])
                } else if (u as usize) > t {
                    (centers[t], centers[u as usize])
                } else {
                    return None;
                };
                let (x0, x1, on0, on1) = clip_segment(a, b, r)?;
                Some(ClippedEdge { i, j, value: f(pi, pj, x0, x1), whole: !(on0 || on1 || u == NONE) })
            })
        }));
}

/// `f` of the cells whose sum over `edges` is not their integral, from their whole clipped
/// polygons: cells that meet the circle (their arcs), lie on the hull (unbounded) or have no
/// edge inside the disk (empty, or holding the whole disk).
fn walked_cells<T: Send, E>(tri: &RegularTriangulation, centers: &[[f64; 2]], far: f64, r: f64, edges: &[ClippedEdge<E>], f: impl Fn(&[Piece], bool) -> T + Sync) -> Vec<(usize, T)> {
    let n = tri.sites.len();
    let (mut inside, mut walk) = (vec![false; n], vec![false; n]);
    for e in edges {
        for v in [e.i as usize, e.j as usize] {
            inside[v] = true;
            walk[v] |= !e.whole;
        }
    }
    let walked: Vec<usize> = (0..n).filter(|&v| walk[v] || !inside[v]).collect();
    walked
        .into_par_iter()
        .map_init(CellScratch::default, |s, v| {
            dual_polygon(tri, centers, v, far, &mut s.pts, &mut s.labels);
            let full = clip_to_disk(&s.pts, &s.labels, r, &mut s.segs, &mut s.pieces);
            (v, f(&s.pieces, full))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::omt::{StereographicDensity, UniformDensity};

    /// The reference: `f` of every site's whole power cell (from the triangles' power
    /// `centers` and the far length of [`centers_and_far`]) clipped to the disk of radius
    /// `r`, as the cells were integrated before the edge sums.
    fn per_clipped_cell<T: Send>(tri: &RegularTriangulation, centers: &[[f64; 2]], far: f64, r: f64, f: impl Fn(&[Piece], bool) -> T + Sync) -> Vec<T> {
        (0..tri.sites.len())
            .into_par_iter()
            .map_init(CellScratch::default, |s, i| {
                dual_polygon(tri, centers, i, far, &mut s.pts, &mut s.labels);
                let full = clip_to_disk(&s.pts, &s.labels, r, &mut s.segs, &mut s.pieces);
                f(&s.pieces, full)
            })
            .collect()
    }

    /// Sites on a jittered grid in the square [-1, 1]^2 with weights that make some cells
    /// much larger than others.
    fn weighted_triangulation() -> RegularTriangulation {
        let m = 23;
        let mut sites = Vec::new();
        let mut weights = Vec::new();
        for a in 0..m {
            for b in 0..m {
                let (x, y) = (2.0 * a as f64 / (m - 1) as f64 - 1.0, 2.0 * b as f64 / (m - 1) as f64 - 1.0);
                let k = (a * m + b) as f64;
                sites.push([x + 0.02 * (1.7 * k).sin(), y + 0.02 * (2.3 * k).cos()]);
                weights.push(0.003 * (0.9 * k).sin());
            }
        }
        let mut tri = RegularTriangulation::delaunay(&sites).unwrap();
        assert!(tri.update_weights(&weights));
        tri
    }

    /// Buffers kept from a call on another triangulation and radius change nothing: the same
    /// bits as fresh ones.
    #[test]
    fn masses_with_reused_buffers_are_the_same_bits() {
        let tri = weighted_triangulation();
        let other = RegularTriangulation::delaunay(&tri.sites[..200]).unwrap();
        let density = StereographicDensity;
        let mut scratch = MassScratch::default();
        integrate_masses_with(&other, 2.0, &density, &mut scratch);
        for r in [0.45, 1.6] {
            let fresh = integrate_masses(&tri, r, &density);
            let reused = integrate_masses_with(&tri, r, &density, &mut scratch);
            let bits = |c: &CellIntegrals| (c.mass.iter().map(|m| m.to_bits()).collect::<Vec<_>>(), c.edges.iter().map(|e| (e.0, e.1, e.2.to_bits())).collect::<Vec<_>>());
            assert_eq!(bits(&fresh), bits(&reused), "r {r}");
        }
    }

    #[test]
    fn edge_summed_masses_and_moments_equal_whole_cell_integrals() {
        let tri = weighted_triangulation();
        // Disks inside the sites' hull, cutting through it, and holding all of it.
        for r in [0.45, 0.93, 1.6] {
            for density in [&StereographicDensity as &dyn RadialDensity, &UniformDensity] {
                let fast = integrate_masses(&tri, r, density);
                let (centers, far) = centers_and_far(&tri, r);
                let whole = per_clipped_cell(&tri, &centers, far, r, |pieces, full| cell_mass(pieces, full, r, density));
                let total: f64 = whole.iter().sum();
                assert!((total - density.disk_mass(r)).abs() < 1e-9 * total, "r {r}: {total}");
                let outside = whole.iter().filter(|&&m| m == 0.0).count();
                if r < 1.0 {
                    assert!(outside > 10, "r {r}: the disk should miss some cells");
                }
                for (v, (a, b)) in fast.mass.iter().zip(&whole).enumerate() {
                    assert!((a - b).abs() <= 1e-12 * total, "r {r} cell {v}: {a} vs {b}");
                }
                let moments = cell_moments(&tri, r, density);
                let whole_moments = per_clipped_cell(&tri, &centers, far, r, |pieces, full| cell_moment(pieces, full, r, density));
                for (v, (a, b)) in moments.iter().zip(&whole_moments).enumerate() {
                    for k in 0..2 {
                        assert!((a[k] - b[k]).abs() <= 1e-12 * total * r, "r {r} cell {v}: moment {a:?} vs {b:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn joint_fan_and_segment_integrals_equal_the_separate_ones() {
        let d = StereographicDensity;
        for (a, b) in [([0.3, -0.2], [0.5, 0.9]), ([1.5, 0.1], [-0.4, 2.0]), ([-0.9, 0.9], [0.2, -0.05])] {
            let (fan, seg) = d.fan_mass_and_segment_integral(a, b);
            assert!((fan - d.fan_mass(a, b)).abs() < 1e-15 * fan.abs().max(1.0));
            assert!((seg - d.segment_integral(a, b)).abs() < 1e-15 * seg.abs().max(1.0));
        }
    }
}
