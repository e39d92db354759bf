//! The planar step `h_r o r g` of the paper (Sec. 3.1.2): the initial disk map `g` scaled to
//! the disk of radius `r`, then moved by the optimal transport map `h_r` whose target masses
//! are the vertex areas (Eq. 11, normalised to the disk's sigma-mass). A vertex goes to the
//! sigma-weighted centroid of its power cell; boundary vertices are put on the circle.
//!
//! One [`PlanarTransport`] serves the whole radius search: its solver is rescaled to each new
//! radius, so Newton starts from the previous radius's weights.

use crate::omt::{CellIntegrals, OmtError, OtOptions, OtReport, OtSolver, RadialDensity};
use crate::progress::Progress;

/// The transport map at one radius.
#[derive(Debug, Clone)]
pub struct TransportMap {
    /// Cell centroids (boundary vertices on the circle).
    pub centroids: Vec<[f64; 2]>,
    /// Cell masses.
    pub masses: Vec<f64>,
    /// Solver report.
    pub report: OtReport,
}

/// Planar transport maps of one initial disk map at any radius.
pub struct PlanarTransport<'a> {
    disk_map: &'a [[f64; 2]],
    on_boundary: &'a [bool],
    target: &'a [f64],
    density: &'a dyn RadialDensity,
    options: OtOptions,
    solver: Option<OtSolver<'a>>,
    /// Newton iterations over all radii.
    pub newton_iterations: usize,
    /// Transport solves.
    pub solves: usize,
    /// Symbolic factorizations of Newton matrices over all radii.
    pub symbolic_factorizations: usize,
}

impl<'a> PlanarTransport<'a> {
    /// Transport of `disk_map` (unit disk positions) towards `target` masses.
    pub fn new(
        disk_map: &'a [[f64; 2]],
        on_boundary: &'a [bool],
        target: &'a [f64],
        density: &'a dyn RadialDensity,
        options: OtOptions,
    ) -> Self {
        Self { disk_map, on_boundary, target, density, options, solver: None, newton_iterations: 0, solves: 0, symbolic_factorizations: 0 }
    }

    fn solver_at(&mut self, r: f64) -> Result<&mut OtSolver<'a>, OmtError> {
        Ok(match self.solver {
            Some(ref mut s) => {
                let scale = r / s.radius();
                s.rescale(scale);
                s
            }
            None => {
                let sites: Vec<[f64; 2]> = self.disk_map.iter().map(|p| [r * p[0], r * p[1]]).collect();
                self.solver.insert(OtSolver::new(&sites, r, self.density)?)
            }
        })
    }

    /// Vertex positions of `h_r o r g` on the disk of radius `r` (cell centroids), the cell
    /// masses and the solver's report.
    pub fn map_at(&mut self, r: f64, progress: &dyn Progress) -> Result<TransportMap, OmtError> {
        let tolerance = self.options.tolerance;
        self.map_at_tolerance(r, tolerance, progress)
    }

    /// [`PlanarTransport::map_at`] with the relative mass tolerance `tolerance` instead of the
    /// options' (the radius search needs less accuracy than the final map).
    pub fn map_at_tolerance(&mut self, r: f64, tolerance: f64, progress: &dyn Progress) -> Result<TransportMap, OmtError> {
        let options = OtOptions { tolerance, ..self.options.clone() };
        let (target, on_boundary) = (self.target, self.on_boundary);
        let solver = self.solver_at(r)?;
        let (cells, report) = solver.solve(target, &options, progress)?;
        let centroids = positions(&cells, solver.sites(), on_boundary, r);
        self.newton_iterations += report.iterations;
        self.symbolic_factorizations += report.symbolic_factorizations;
        self.solves += 1;
        Ok(TransportMap { centroids, masses: cells.mass, report })
    }
}

/// Centroids of the cells; boundary vertices projected onto the circle of radius `r`.
fn positions(cells: &CellIntegrals, sites: &[[f64; 2]], on_boundary: &[bool], r: f64) -> Vec<[f64; 2]> {
    (0..sites.len())
        .map(|i| {
            let c = cells.centroid(i).unwrap_or(sites[i]);
            if on_boundary[i] {
                let n = (c[0] * c[0] + c[1] * c[1]).sqrt();
                if n > 0.0 {
                    return [r * c[0] / n, r * c[1] / n];
                }
            }
            c
        })
        .collect()
}
