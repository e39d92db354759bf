//! The reconstruction on a mesh of the cap instead of the input's connectivity: a smooth remesh
//! of the harmonic representation with about any number of faces.
//!
//! The cap `Z >= Z*` is triangulated by [`crate::remesh::grid::uniform_cap`] (rings equally
//! spaced in polar angle, near-equilateral faces of near-equal area on the sphere) and every
//! grid vertex is sent to the fitted surface `sum C_n^m A_n^m` (paper Eq. 27). With the spherical
//! cap harmonics the grid's rim becomes the reconstructed boundary loop; with the adaptive
//! harmonics the whole rim ring collapses to one point (see [`super::basis`], "The boundary
//! circle"), leaving degenerate faces there. Faces are spread evenly on the cap, so their size
//! on the surface follows the parameterization's area distortion (small for the area-preserving
//! map).

use super::fit::HarmonicFit;
use super::HarmonicsError;
use crate::mesh::TriMesh;
use crate::remesh::grid::uniform_cap;

/// Largest face count [`resample`] accepts.
pub const MAX_RESAMPLE_FACES: usize = 20_000_000;

/// The order-`fit.order` representation evaluated on a uniform cap mesh of about `faces`
/// faces (at least 1, at most `MAX_RESAMPLE_FACES`).
pub fn resample(fit: &HarmonicFit, faces: usize) -> Result<TriMesh, HarmonicsError> {
    if faces == 0 || faces > MAX_RESAMPLE_FACES {
        return Err(HarmonicsError::InvalidResample { faces, max: MAX_RESAMPLE_FACES });
    }
    fit.basis()?;
    let grid = uniform_cap(fit.z_star, faces);
    // Grid points are on the unit sphere up to rounding; the rim ring is at Z* exactly.
    let positions = fit.reconstruct(&grid.vertices, fit.order)?;
    Ok(TriMesh::new(positions, grid.faces))
}
