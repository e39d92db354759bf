//! [`CapMap`], the result of a parameterization.

use crate::mesh::{SurfaceKind, TriMesh};
use crate::param::ParamReport;

/// A parameterization onto the cap (or the planar disk).
#[derive(Debug, Clone)]
pub struct CapMap {
    /// Positions on the disk of radius `r*` (`h_r* o r* g`), one per input vertex.
    pub plane: Vec<[f64; 2]>,
    /// Positions on the unit sphere (`Z >= Z*`), or `(x, y, 0)` for the planar disk.
    pub cap: Vec<[f64; 3]>,
    /// Input faces of the punctured quad of a closed surface: they map to the cap's flat
    /// bottom (their corners on the rim `Z = Z*`). Empty for open surfaces.
    pub bottom_faces: Vec<usize>,
    /// Area distortion `d_area` of each input face (paper Sec. 4.1): the values whose
    /// statistics are [`ParamReport::area_distortion`], in face order; `NaN` for the faces
    /// not measured (the punctured quad's, which go to the cap's flat bottom, and faces that
    /// welding made degenerate).
    pub face_area_distortion: Vec<f64>,
    /// Angle distortion `d_angle` of each input corner (three per face, radians): the values
    /// of [`ParamReport::angle_distortion`]; `NaN` for the corners of faces not measured.
    pub corner_angle_distortion: Vec<f64>,
    /// The kind of surface mapped (as in [`ParamReport::kind`]).
    pub kind: SurfaceKind,
    /// What was measured.
    pub report: ParamReport,
}

impl CapMap {
    /// The input mesh with its vertices moved onto the cap (same connectivity).
    pub fn cap_mesh(&self, mesh: &TriMesh) -> TriMesh {
        TriMesh::new(self.cap.clone(), mesh.faces.clone())
    }

    /// The map as texture coordinates, one per input vertex: the planar disk (radius `r*`,
    /// whose inverse stereographic image is the cap; the unit disk for the planar domain)
    /// scaled into `[0, 1]^2`, its centre at `(0.5, 0.5)`. A closed surface's punctured quad
    /// has its corners on the disk's rim.
    pub fn uv(&self) -> Vec<[f64; 2]> {
        let radius = self.report.r_star.unwrap_or_else(|| self.plane.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max));
        let scale = if radius > 0.0 { 0.5 / radius } else { 0.0 };
        self.plane.iter().map(|p| [(0.5 + scale * p[0]).clamp(0.0, 1.0), (0.5 + scale * p[1]).clamp(0.0, 1.0)]).collect()
    }
}
