//! Remeshing through the cap (paper Sec. 4.2): parameterize, build a uniform or
//! latitude/longitude mesh of the cap `Z >= Z*`, pull it back onto the surface.

pub mod grid;
pub mod locate;
pub mod pullback;

use crate::cap::{parameterize, ParamOptions, ParamReport};
use crate::error::Error;
use crate::mesh::{SurfaceKind, TriMesh};
use crate::metrics::{remesh_metrics, RemeshMetrics};
use crate::progress::{self, Progress, Stage};
use std::time::Instant;

/// Which cap mesh to pull back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CapGrid {
    /// Near-equilateral faces of near-equal area, about this many faces. Default 5000.
    Uniform {
        /// Target face count.
        faces: usize,
    },
    /// Latitude rings x longitude sectors with a fan at the pole.
    LatLong {
        /// Rings from the pole to the cap's rim.
        rings: usize,
        /// Meridians.
        sectors: usize,
    },
}

impl Default for CapGrid {
    fn default() -> Self {
        CapGrid::Uniform { faces: 5000 }
    }
}

/// Options of [`remesh`].
#[derive(Debug, Clone, Default)]
pub struct RemeshOptions {
    /// The cap mesh. Default uniform with 5000 faces.
    pub grid: CapGrid,
    /// Parameterization options (adaptive cap by default).
    pub param: ParamOptions,
}

/// What [`remesh`] measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RemeshReport {
    /// The parameterization.
    pub param: ParamReport,
    /// Quality of the result against the input.
    pub quality: RemeshMetrics,
    /// Seconds of the whole remeshing (parameterization included).
    pub seconds: f64,
}

/// Remesh an open disk-like surface through its adaptive cap.
pub fn remesh(mesh: &TriMesh, options: &RemeshOptions, progress: &dyn Progress) -> Result<(TriMesh, RemeshReport), Error> {
    let start = Instant::now();
    let map = parameterize(mesh, &options.param, progress)?;
    if map.report.kind != SurfaceKind::OpenDisk.to_string() {
        return Err(Error::Unsupported(
            "remeshing closed surfaces is not supported yet (the punctured bottom is not pulled back); cut the surface open first".into(),
        ));
    }
    let z_star = map.report.z_star.ok_or_else(|| Error::InvalidOption("remeshing needs a spherical cap domain, not the planar disk".into()))?;
    progress::check(progress, Stage::Remesh, 0.0, "pulling the cap mesh back")?;
    let cap = match options.grid {
        CapGrid::Uniform { faces } => grid::uniform_cap(z_star, faces.max(1)),
        CapGrid::LatLong { rings, sectors } => grid::lat_long(z_star, rings, sectors),
    };
    let positions = pullback::pull_back(mesh, &map.plane, &cap.vertices)
        .ok_or_else(|| Error::Unsupported("the parameterized mesh has no face to pull back from".into()))?;
    let out = TriMesh::new(positions, cap.faces);
    let quality = remesh_metrics(mesh, &out);
    Ok((out, RemeshReport { param: map.report, quality, seconds: start.elapsed().as_secs_f64() }))
}
