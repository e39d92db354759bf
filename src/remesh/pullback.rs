//! Pull-back of a cap mesh onto the surface by the inverse map `f^-1` (paper Sec. 4.2): each
//! cap vertex goes to the plane by stereographic projection, is located in the planar image
//! of the surface, and takes the barycentric combination of the original positions.

use super::grid::ClosedCapGrid;
use super::locate::Locator;
use crate::cap::CapMap;
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Positions on the surface of the planar `points` (cap points by stereographic projection),
/// for a surface whose vertices sit at `plane` (same numbering as `surface.vertices`) in the
/// disk. `None` if a point lies in no face.
pub fn pull_back_planar(surface: &TriMesh, plane: &[[f64; 2]], points: &[[f64; 2]]) -> Option<Vec<[f64; 3]>> {
    let locator = Locator::new(plane, &surface.faces);
    points
        .par_iter()
        .map(|&q| {
            let loc = locator.locate(q)?;
            let [a, b, c] = surface.faces[loc.face].map(|v| surface.vertices[v as usize]);
            let w = loc.bary;
            Some([0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]))
        })
        .collect()
}

/// Positions on a closed surface of the closed cap grid `grid`: cap vertices (the rim
/// included) at their points in the plane (`top_points`, one per vertex before
/// `grid.first_bottom_vertex`) as in [`pull_back_planar`], restricted to the faces that are
/// not punctured; bottom-disk vertices by locating them, in the `(X, Y)` plane of the bottom,
/// in the two punctured faces whose corners `map` put on the rim. `None` if a part is empty.
pub fn pull_back_closed_from(surface: &TriMesh, map: &CapMap, grid: &ClosedCapGrid, top_points: &[[f64; 2]]) -> Option<Vec<[f64; 3]>> {
    let (bottom, top): (Vec<usize>, Vec<usize>) = (0..surface.n_faces()).partition(|f| map.bottom_faces.contains(f));
    let top_mesh = TriMesh::new(surface.vertices.clone(), top.iter().map(|&f| surface.faces[f]).collect());
    let split = grid.first_bottom_vertex.min(grid.mesh.vertices.len());
    let mut positions = pull_back_planar(&top_mesh, &map.plane, &top_points[..split.min(top_points.len())])?;
    if split < grid.mesh.vertices.len() {
        let bottom_faces: Vec<[u32; 3]> = bottom.iter().map(|&f| surface.faces[f]).collect();
        let flat: Vec<[f64; 2]> = map.cap.iter().map(|p| [p[0], p[1]]).collect();
        let locator = Locator::new(&flat, &bottom_faces);
        let (corners, rim_radius) = polygon_by_angle(bottom_faces.iter().flatten().map(|&v| flat[v as usize]).collect());
        for &x in &grid.mesh.vertices[split..] {
            let q = onto_polygon([x[0], x[1]], &corners, rim_radius);
            let loc = locator.locate(q)?;
            let [a, b, c] = bottom_faces[loc.face].map(|v| surface.vertices[v as usize]);
            let w = loc.bary;
            positions.push([0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]));
        }
    }
    Some(positions)
}

/// The point of the polygon `corners` (counter-clockwise by angle, inscribed in the circle of
/// radius `rim_radius` about the origin) that the radial scaling of the disk onto the polygon
/// assigns to `p`: the disk's rim goes to the polygon's sides, its centre stays. Without the
/// scaling, bottom points between a side and the rim would all land on that side (zero-area
/// faces). `p` itself when the polygon does not contain the origin.
pub(crate) fn onto_polygon(p: [f64; 2], corners: &[[f64; 2]], rim_radius: f64) -> [f64; 2] {
    let len = p[0].hypot(p[1]);
    if len == 0.0 || rim_radius <= 0.0 || !surrounds_origin(corners) {
        return p;
    }
    match polygon_radius([p[0] / len, p[1] / len], corners) {
        Some(t) => {
            let scale = t / rim_radius;
            [p[0] * scale, p[1] * scale]
        }
        None => p,
    }
}

/// The `corners` of a polygon inscribed in a circle about the origin, ordered by angle
/// (counter-clockwise) without repeats, and the radius of the farthest (the circle's).
pub(crate) fn polygon_by_angle(mut corners: Vec<[f64; 2]>) -> (Vec<[f64; 2]>, f64) {
    corners.sort_by(|a, b| a[1].atan2(a[0]).total_cmp(&b[1].atan2(b[0])));
    corners.dedup();
    let rim_radius = corners.iter().map(|c| c[0].hypot(c[1])).fold(0.0, f64::max);
    (corners, rim_radius)
}

/// Whether the polygon `corners` (counter-clockwise by angle) has the origin strictly inside:
/// every side turns counter-clockwise around it.
pub(crate) fn surrounds_origin(corners: &[[f64; 2]]) -> bool {
    let m = corners.len();
    m >= 3 && (0..m).all(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % m]);
        a[0] * b[1] - a[1] * b[0] > 0.0
    })
}

/// Move the points of the disk of radius `rim_radius` that lie within a band along its rim
/// radially so that the rim goes onto the polygon `corners` (inscribed in that circle,
/// counter-clockwise by angle, around the origin) and the band's inner circle stays: points
/// between a side and the rim would otherwise be located on that side, all of them, and the
/// cap faces there pulled back with zero area. The band is `BAND_DEPTHS` (1.5) times the deepest
/// circular segment between a side and the rim, so a boundary of many vertices moves only the
/// points within a sliver of the rim (by at most that segment's depth), and the map is
/// monotone along each ray. Points are left as they are when the polygon does not surround the origin.
pub fn rim_band_into_polygon(points: &mut [[f64; 2]], corners: &[[f64; 2]], rim_radius: f64) {
    if rim_radius <= 0.0 || !surrounds_origin(corners) {
        return;
    }
    let m = corners.len();
    let nearest_side = (0..m)
        .map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % m]);
            (a[0] * b[1] - a[1] * b[0]) / (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .fold(f64::INFINITY, f64::min);
    let depth = rim_radius - nearest_side;
    if !(depth > 0.0) {
        return;
    }
    let inner = (rim_radius - BAND_DEPTHS * depth).max(0.0);
    for p in points.iter_mut() {
        let len = p[0].hypot(p[1]);
        if !(len > inner) {
            continue;
        }
        let Some(t) = polygon_radius([p[0] / len, p[1] / len], corners) else { continue };
        let moved = inner + (len.min(rim_radius) - inner) * (t - inner) / (rim_radius - inner);
        *p = [p[0] * moved / len, p[1] * moved / len];
    }
}

/// Width of [`rim_band_into_polygon`]'s band in depths of the deepest segment: along the ray
/// through that segment's middle the band is squeezed to `1 - 1 / BAND_DEPTHS` of its width.
const BAND_DEPTHS: f64 = 1.5;

/// Distance from the origin to the polygon `corners` along the unit direction `u`, if the
/// ray meets a side.
pub(crate) fn polygon_radius(u: [f64; 2], corners: &[[f64; 2]]) -> Option<f64> {
    let m = corners.len();
    for k in 0..m {
        let (a, b) = (corners[k], corners[(k + 1) % m]);
        // Ray t u meets a + s (b - a): t u - s (b - a) = a.
        let e = [b[0] - a[0], b[1] - a[1]];
        let det = -u[0] * e[1] + u[1] * e[0];
        if det == 0.0 {
            continue;
        }
        let t = (-a[0] * e[1] + a[1] * e[0]) / det;
        let s = (u[0] * a[1] - u[1] * a[0]) / det;
        if t > 0.0 && (-1e-12..=1.0 + 1e-12).contains(&s) {
            return Some(t);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The square inscribed in the circle of radius 2.
    fn square() -> Vec<[f64; 2]> {
        [0.0f64, 90.0, 180.0, 270.0].iter().map(|d| [2.0 * d.to_radians().cos(), 2.0 * d.to_radians().sin()]).collect()
    }

    #[test]
    fn the_rim_band_goes_onto_the_polygon_and_the_inside_stays() {
        let corners = square();
        let depth = 2.0 - 2.0f64.sqrt();
        let inner = 2.0 - BAND_DEPTHS * depth;
        // Points along rays at several angles, from the centre to the rim.
        let mut points = Vec::new();
        for k in 0..24 {
            let a = (k as f64 * 15.0 + 7.0).to_radians();
            for j in 0..=20 {
                let r = 2.0 * j as f64 / 20.0;
                points.push([r * a.cos(), r * a.sin()]);
            }
        }
        let before = points.clone();
        rim_band_into_polygon(&mut points, &corners, 2.0);
        for (ray, (moved, orig)) in points.chunks(21).zip(before.chunks(21)).enumerate() {
            let u = [orig[20][0] / 2.0, orig[20][1] / 2.0];
            let to_side = polygon_radius(u, &corners).unwrap();
            for (p, q) in moved.iter().zip(orig) {
                let (r, r0) = (p[0].hypot(p[1]), q[0].hypot(q[1]));
                if r0 <= inner {
                    assert_eq!(p, q, "ray {ray}: inside the band's inner circle a point stays");
                } else {
                    // Same direction, inside the polygon.
                    assert!((p[0] * q[1] - p[1] * q[0]).abs() < 1e-12, "ray {ray}: moved off its ray");
                    assert!(r <= to_side + 1e-12, "ray {ray}: {r} beyond the side at {to_side}");
                }
            }
            // The rim point lands on the side, and the ray's points keep their order.
            let rim = moved[20][0].hypot(moved[20][1]);
            assert!((rim - to_side).abs() < 1e-12, "ray {ray}: rim at {rim}, side at {to_side}");
            for w in moved.windows(2) {
                assert!(w[1][0].hypot(w[1][1]) > w[0][0].hypot(w[0][1]), "ray {ray}: order lost");
            }
        }
    }

    #[test]
    fn a_polygon_that_does_not_surround_the_centre_moves_nothing() {
        let corners = [[2.0, 0.0], [0.0, 2.0], [-2.0, 0.0]];
        let mut points = vec![[0.0, -1.9], [1.0, 1.0]];
        let before = points.clone();
        rim_band_into_polygon(&mut points, &corners, 2.0);
        assert_eq!(points, before);
    }
}
