//! Area equalization of the pulled-back mesh (ours; the paper pulls the cap mesh back as is,
//! Sec. 4.2).
//!
//! An area-preserving map keeps areas at the scale of the input's faces, but a cap triangle
//! is pulled back to a flat triangle through three surface points: where the map is strongly
//! anisotropic (mean angle distortion 0.3-0.55 rad on the shared meshes) the long edges of
//! the stretched triangles cut across the surface's curvature and the flat areas drift from
//! the cap's. This step moves the cap vertices in the plane of the map (the rim and, on closed
//! surfaces, the bottom stay) so that the pulled-back triangles' areas approach the cap
//! triangles' areas: the same Gauss-Seidel as [`crate::refine::area_refine`], with the areas
//! measured on the surface through the inverse map. Every accepted move keeps the planar
//! triangles' orientation, so the result stays an embedding pulled back from the cap.

use super::locate::{LastFaces, Locator};
use crate::refine::area_refine::{refine_towards, AreaRefineReport, RefineOptions};
use crate::mesh::TriMesh;

/// Equalize the areas of `out` (the remesh `faces` pulled back onto `surface` from the planar
/// points `plane`, one per vertex; both updated in place) towards areas proportional to
/// `target`. `surface_faces` are the faces of `surface` that the plane map `surface_plane`
/// covers; vertices flagged in `fixed` do not move.
#[allow(clippy::too_many_arguments)]
pub fn equalize_areas(
    surface: &TriMesh,
    surface_faces: &[[u32; 3]],
    surface_plane: &[[f64; 2]],
    faces: &[[u32; 3]],
    target: &[f64],
    fixed: &[bool],
    plane: &mut [[f64; 2]],
    out: &mut [[f64; 3]],
    sweeps: usize,
) -> AreaRefineReport {
    if sweeps == 0 {
        return AreaRefineReport::default();
    }
    let locator = Locator::new(surface_plane, surface_faces);
    // The refinement lifts a vertex's points near its last one (its position's
    // finite-difference neighbours, its trial steps, the next sweep's): each vertex's
    // queries try the triangle of its last query first.
    let last_face = LastFaces::new(plane.len());
    let lift = |v: usize, q: [f64; 2]| -> [f64; 3] {
        let found = locator.locate_near(q, last_face.get(v));
        if let Some(loc) = &found {
            last_face.set(v, loc.face);
        }
        match found {
            Some(loc) => {
                let [a, b, c] = surface_faces[loc.face].map(|v| surface.vertices[v as usize]);
                let w = loc.bary;
                [0, 1, 2].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k])
            }
            None => [f64::NAN; 3],
        }
    };
    refine_towards(plane, out, target, faces, fixed, &lift, RefineOptions::plain(sweeps))
}
