//! Pull-back of a cap mesh onto the surface by the inverse map `f^-1` (paper Sec. 4.2): each
//! cap vertex goes to the plane by stereographic projection, is located in the planar image
//! of the surface, and takes the barycentric combination of the original positions.

use super::locate::Locator;
use crate::cap::stereographic;
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
