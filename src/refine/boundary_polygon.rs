//! Fitting the planar map into its boundary polygon.
//!
//! The boundary vertices sit on the circle of radius `r`, so the image of a valid (fold-free)
//! piecewise-linear map is the polygon they span, not the disk. The transport map fills the
//! whole disk (paper Sec. 3.1.2): every vertex whose cell centroid lies between a boundary
//! edge and its arc folds a face. On open surfaces the boundary has hundreds of vertices and
//! those slivers are thin; a punctured closed surface (Sec. 3.2.1) has only the four corners
//! of its quad, the polygon is a square with 36% of the disk outside it, and on large meshes
//! (41k-vertex ellipsoid, 48k brain) hundreds of vertices land there. Repairing those folds
//! one region at a time cannot succeed while the outer boundary is the circle, and the last
//! resort, a whole-mesh convex-combination solve with four fixed corners, squeezed the map
//! (mean `|d_area|` 0.4 to 1.4).
//!
//! [`fit_into_boundary_polygon`] moves vertices along rays from the centre with
//! `rho' = rho0 + (rho - rho0) (rho_poly(theta) - rho0) / (r - rho0)` for `rho > rho0`, where
//! `rho_poly(theta)` is the polygon's radius in that direction and `rho0 = 2 rho_in - r` with
//! `rho_in` the polygon's inradius: a homeomorphism of the disk onto the polygon that is the
//! identity inside `rho0` and compresses radially by at most one half (when `rho_in >= r / 2`,
//! as for the four corners of a punctured quad; otherwise `rho0 = 0`). With the stereographic
//! density the annulus outside `rho0` carries little mass when `r` is large (the closed
//! surfaces' optimum), so the added area distortion is small and the area refinement
//! ([`super::area_refine`]) takes most of it back.

use crate::mesh::geometry::signed_area_2d;

/// `p x q`, the z component of the cross product.
fn cross(p: [f64; 2], q: [f64; 2]) -> f64 {
    p[0] * q[1] - p[1] * q[0]
}

/// Vertices that [`fit_into_boundary_polygon`] moved, or why it did nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PolygonFit {
    /// Every free vertex was inside the polygon already.
    Inside,
    /// The fixed vertices do not surround the centre (an angular gap of at least pi), or
    /// there are fewer than three of them: no fit.
    NoPolygon,
    /// This many free vertices moved.
    Moved(usize),
}

/// The convex polygon of the fixed vertices on the circle, in angular order.
struct BoundaryPolygon {
    /// Corners sorted by angle.
    corners: Vec<[f64; 2]>,
    /// Their angles, increasing in `(-pi, pi]`.
    angles: Vec<f64>,
}

impl BoundaryPolygon {
    fn new(pos: &[[f64; 2]], fixed: &[bool]) -> Option<Self> {
        let mut corners: Vec<([f64; 2], f64)> = pos.iter().zip(fixed).filter(|(_, &f)| f).map(|(&p, _)| (p, p[1].atan2(p[0]))).collect();
        if corners.len() < 3 {
            return None;
        }
        corners.sort_by(|a, b| a.1.total_cmp(&b.1));
        let n = corners.len();
        let widest = (0..n)
            .map(|i| {
                let next = if i + 1 < n { corners[i + 1].1 } else { corners[0].1 + std::f64::consts::TAU };
                next - corners[i].1
            })
            .fold(0.0, f64::max);
        if widest >= std::f64::consts::PI - 1e-9 {
            return None;
        }
        Some(Self { angles: corners.iter().map(|c| c.1).collect(), corners: corners.into_iter().map(|c| c.0).collect() })
    }

    /// Distance from the centre to the polygon's boundary in direction `theta`.
    fn radius_at(&self, theta: f64) -> f64 {
        let n = self.corners.len();
        // The edge (i, i + 1) whose angular span holds theta; the last edge wraps around.
        let i = match self.angles.partition_point(|&a| a <= theta) {
            0 => n - 1,
            k => k - 1,
        };
        let (a, b) = (self.corners[i], self.corners[(i + 1) % n]);
        let u = [theta.cos(), theta.sin()];
        let e = [b[0] - a[0], b[1] - a[1]];
        cross(e, a) / cross(e, u)
    }

    /// The smallest distance from the centre to an edge's line.
    fn inradius(&self) -> f64 {
        let n = self.corners.len();
        (0..n)
            .map(|i| {
                let (a, b) = (self.corners[i], self.corners[(i + 1) % n]);
                let e = [b[0] - a[0], b[1] - a[1]];
                cross(a, e).abs() / (e[0] * e[0] + e[1] * e[1]).sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether `p` is strictly inside (every edge has it on its left).
    fn contains(&self, p: [f64; 2]) -> bool {
        let n = self.corners.len();
        (0..n).all(|i| {
            signed_area_2d(self.corners[i], self.corners[(i + 1) % n], p) > 0.0
        })
    }
}

/// Move the free vertices of `pos` into the polygon of the `fixed` ones (on the circle of
/// radius `radius`) when any lies outside it; see the module docs.
pub fn fit_into_boundary_polygon(pos: &mut [[f64; 2]], fixed: &[bool], radius: f64) -> PolygonFit {
    let Some(polygon) = BoundaryPolygon::new(pos, fixed) else { return PolygonFit::NoPolygon };
    let inradius = polygon.inradius();
    // Points well inside the inscribed circle need no test against every edge (on the
    // 53k-vertex hand, 1200 edges per point were 1.5% of the parameterization's time).
    let inner = if polygon.contains([0.0, 0.0]) { inradius * (1.0 - 1e-9) } else { 0.0 };
    let surely_inside = |p: [f64; 2]| p[0] * p[0] + p[1] * p[1] < inner * inner;
    if (0..pos.len()).all(|v| fixed[v] || surely_inside(pos[v]) || polygon.contains(pos[v])) {
        return PolygonFit::Inside;
    }
    let rho0 = (2.0 * inradius - radius).max(0.0);
    let mut moved = 0;
    for v in 0..pos.len() {
        let p = pos[v];
        let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
        if fixed[v] || rho <= rho0 {
            continue;
        }
        let theta = p[1].atan2(p[0]);
        // Centroids lie in the disk; guard against round-off just outside it.
        let rho_c = rho.min(radius);
        let target = rho0 + (rho_c - rho0) * (polygon.radius_at(theta) - rho0) / (radius - rho0);
        let s = target / rho;
        pos[v] = [p[0] * s, p[1] * s];
        moved += 1;
    }
    PolygonFit::Moved(moved)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four corners on the circle of radius 2 (a slightly irregular quad) and a spiral of free
    /// points filling the disk.
    fn quad_and_spiral() -> (Vec<[f64; 2]>, Vec<bool>) {
        let r = 2.0;
        let mut pos: Vec<[f64; 2]> = [0.1f64, 1.7, 3.3, 4.6].iter().map(|&t| [r * t.cos(), r * t.sin()]).collect();
        let mut fixed = vec![true; 4];
        for k in 0..2000 {
            let rho = r * ((k as f64 + 0.5) / 2000.0).sqrt();
            let t = k as f64 * 2.399963;
            pos.push([rho * t.cos(), rho * t.sin()]);
            fixed.push(false);
        }
        (pos, fixed)
    }

    #[test]
    fn every_free_point_ends_inside_and_rays_keep_their_order() {
        let (mut pos, fixed) = quad_and_spiral();
        let before = pos.clone();
        let fit = fit_into_boundary_polygon(&mut pos, &fixed, 2.0);
        assert!(matches!(fit, PolygonFit::Moved(m) if m > 100), "{fit:?}");
        let polygon = BoundaryPolygon::new(&pos, &fixed).unwrap();
        assert!((0..pos.len()).all(|v| fixed[v] || polygon.contains(pos[v])));
        let rho0 = 2.0 * polygon.inradius() - 2.0;
        for v in 0..pos.len() {
            let (p, q) = (before[v], pos[v]);
            let (rp, rq) = ((p[0] * p[0] + p[1] * p[1]).sqrt(), (q[0] * q[0] + q[1] * q[1]).sqrt());
            // Along its own ray, never outwards, unchanged inside rho0.
            assert!((p[1].atan2(p[0]) - q[1].atan2(q[0])).abs() < 1e-12 || rp == 0.0);
            assert!(rq <= rp + 1e-15);
            if rp <= rho0 {
                assert_eq!(p, q);
            }
        }
        // Two points on one ray keep their order (the map is monotone along rays).
        let theta = 0.9f64;
        let mut two = vec![pos[0], pos[1], pos[2], pos[3], [1.5 * theta.cos(), 1.5 * theta.sin()], [1.9 * theta.cos(), 1.9 * theta.sin()]];
        let fixed_two = [true, true, true, true, false, false];
        fit_into_boundary_polygon(&mut two, &fixed_two, 2.0);
        let norm = |p: [f64; 2]| (p[0] * p[0] + p[1] * p[1]).sqrt();
        assert!(norm(two[4]) < norm(two[5]));
    }

    #[test]
    fn polygon_radius_is_the_distance_to_the_edge_on_a_square() {
        // Corners of the square at 45 degrees on the circle of radius sqrt(2): edges at x, y = +-1.
        let s = 2f64.sqrt();
        let pos: Vec<[f64; 2]> = [1.0f64, 3.0, 5.0, 7.0].iter().map(|k| k * std::f64::consts::FRAC_PI_4).map(|t| [s * t.cos(), s * t.sin()]).collect();
        let polygon = BoundaryPolygon::new(&pos, &[true; 4]).unwrap();
        for k in 0..64 {
            let t = -3.1 + 0.097 * k as f64;
            let expected = 1.0 / t.cos().abs().max(t.sin().abs());
            assert!((polygon.radius_at(t) - expected).abs() < 1e-12, "theta {t}");
        }
        assert!((polygon.inradius() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn no_fit_when_inside_or_when_the_corners_leave_the_centre_outside() {
        let (mut pos, fixed) = quad_and_spiral();
        fit_into_boundary_polygon(&mut pos, &fixed, 2.0);
        let again = pos.clone();
        assert_eq!(fit_into_boundary_polygon(&mut pos, &fixed, 2.0), PolygonFit::Inside);
        assert_eq!(pos, again);
        // Three corners within a half circle.
        let mut half: Vec<[f64; 2]> = [0.1f64, 0.8, 1.5].iter().map(|&t| [t.cos(), t.sin()]).collect();
        half.push([0.0, -0.9]);
        assert_eq!(fit_into_boundary_polygon(&mut half, &[true, true, true, false], 1.0), PolygonFit::NoPolygon);
    }
}
