//! Pull-back of a cap mesh onto the surface by the inverse map `f^-1` (paper Sec. 4.2): each
//! cap vertex goes to the plane by stereographic projection, is located in the planar image
//! of the surface, and takes the barycentric combination of the original positions.

use super::grid::ClosedCapGrid;
use super::locate::Locator;
use crate::cap::{stereographic, CapMap};
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Positions on the surface of the cap points `cap`, for a surface whose vertices sit at
/// `plane` (same numbering as `surface.vertices`) in the disk. `None` if the planar mesh is
/// empty.
pub fn pull_back(surface: &TriMesh, plane: &[[f64; 2]], cap: &[[f64; 3]]) -> Option<Vec<[f64; 3]>> {
    let locator = Locator::new(plane, &surface.faces);
    cap.par_iter()
        .map(|&x| {
            let loc = locator.locate(stereographic(x))?;
            let [a, b, c] = surface.faces[loc.face].map(|v| surface.vertices[v as usize]);
            let w = loc.bary;
            Some([0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]))
        })
        .collect()
}

/// Positions on a closed surface of the closed cap grid `grid`: cap vertices (the rim
/// included) through the plane as in [`pull_back`], restricted to the faces that are not
/// punctured; bottom-disk vertices by locating them, in the `(X, Y)` plane of the bottom, in
/// the two punctured faces whose corners `map` put on the rim. `None` if a part is empty.
pub fn pull_back_closed(surface: &TriMesh, map: &CapMap, grid: &ClosedCapGrid) -> Option<Vec<[f64; 3]>> {
    let (bottom, top): (Vec<usize>, Vec<usize>) = (0..surface.n_faces()).partition(|f| map.bottom_faces.contains(f));
    let top_mesh = TriMesh::new(surface.vertices.clone(), top.iter().map(|&f| surface.faces[f]).collect());
    let split = grid.first_bottom_vertex.min(grid.mesh.vertices.len());
    let mut positions = pull_back(&top_mesh, &map.plane, &grid.mesh.vertices[..split])?;
    if split < grid.mesh.vertices.len() {
        let bottom_faces: Vec<[u32; 3]> = bottom.iter().map(|&f| surface.faces[f]).collect();
        let flat: Vec<[f64; 2]> = map.cap.iter().map(|p| [p[0], p[1]]).collect();
        let locator = Locator::new(&flat, &bottom_faces);
        let mut corners: Vec<[f64; 2]> = bottom_faces.iter().flatten().map(|&v| flat[v as usize]).collect();
        corners.sort_by(|a, b| a[1].atan2(a[0]).total_cmp(&b[1].atan2(b[0])));
        corners.dedup();
        let rim_radius = corners.iter().map(|c| c[0].hypot(c[1])).fold(0.0, f64::max);
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
fn onto_polygon(p: [f64; 2], corners: &[[f64; 2]], rim_radius: f64) -> [f64; 2] {
    let m = corners.len();
    let len = p[0].hypot(p[1]);
    if m < 3 || len == 0.0 || rim_radius <= 0.0 {
        return p;
    }
    let u = [p[0] / len, p[1] / len];
    for k in 0..m {
        let (a, b) = (corners[k], corners[(k + 1) % m]);
        // Origin strictly inside: every side turns counter-clockwise around it.
        if a[0] * b[1] - a[1] * b[0] <= 0.0 {
            return p;
        }
    }
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
            let scale = t / rim_radius;
            return [p[0] * scale, p[1] * scale];
        }
    }
    p
}
