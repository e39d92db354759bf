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
}
