//! The planar step `h_r o r g` of the paper (Sec. 3.1.2): the initial disk map `g` scaled to
//! the disk of radius `r`, then moved by the optimal transport map `h_r` whose target masses
//! are the vertex areas (Eq. 11, normalised to the disk's sigma-mass). A vertex goes to the
//! sigma-weighted centroid of its power cell; boundary vertices are put on the circle.
//!
//! One [`PlanarTransport`] serves the whole radius search: its solver is rescaled to each new
//! radius, so Newton starts from the previous radius's weights. From the third radius on it
//! also tries weights predicted from the two solves nearest in `ln r` (ours: the weights of
//! the disk scaled to radius 1 interpolated linearly in `ln r`, or extrapolated), and starts
//! from them when the triangulation reaches them and every cell keeps mass
//! ([`OtSolver::try_weights`]; the radius search's golden and parabolic steps land between
//! earlier radii). That saves a fifth to a third of an open surface's search Newton steps
//! (fewer on closed surfaces, whose search jumps between far radii) for a flip pass and an
//! integration per try; `Z*` moves within the search's tolerance.

use super::{CellIntegrals, OmtError, OtOptions, OtReport, OtSolver, RadialDensity};
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
    /// `(ln r, w / r^2)` of every solve: the weights of the disk scaled to radius 1.
    solved: Vec<(f64, Vec<f64>)>,
    /// Solves that started from predicted weights.
    pub predicted_starts: usize,
    /// Whether solves start from predicted weights (see the module docs).
    predict: bool,
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
        Self { disk_map, on_boundary, target, density, options, solver: None, newton_iterations: 0, solves: 0, symbolic_factorizations: 0, solved: Vec::new(), predicted_starts: 0, predict: true }
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

    /// Whether later solves start from weights predicted from the earlier ones (default) or
    /// from the last solve's weights, scaled.
    pub fn set_prediction(&mut self, predict: bool) {
        self.predict = predict;
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
        let predicted = if self.predict { predict_weights(&self.solved, r) } else { None };
        let solver = self.solver_at(r)?;
        let took_prediction = predicted.is_some_and(|w| solver.try_weights(&w, target));
        let (cells, report) = solver.solve(target, &options, progress)?;
        let scaled = solver.weights().iter().map(|w| w / (r * r)).collect();
        let centroids = positions(&cells, solver.sites(), on_boundary, r);
        self.predicted_starts += usize::from(took_prediction);
        self.solved.push((r.ln(), scaled));
        self.newton_iterations += report.iterations;
        self.symbolic_factorizations += report.symbolic_factorizations;
        self.solves += 1;
        Ok(TransportMap { centroids, masses: cells.mass, report })
    }
}

/// Weights at radius `r` interpolated (or extrapolated) linearly in `ln r` from the two
/// solves nearest to it, each scaled to radius `r`; `None` with fewer than two solves.
fn predict_weights(solved: &[(f64, Vec<f64>)], r: f64) -> Option<Vec<f64>> {
    let t = r.ln();
    let mut order: Vec<usize> = (0..solved.len()).collect();
    order.sort_by(|&a, &b| (solved[a].0 - t).abs().total_cmp(&(solved[b].0 - t).abs()));
    let (&a, &b) = (order.first()?, order.get(1)?);
    let ((ta, wa), (tb, wb)) = (&solved[a], &solved[b]);
    if ta == tb {
        return None;
    }
    let s = (t - ta) / (tb - ta);
    Some(wa.iter().zip(wb).map(|(x, y)| r * r * (x + s * (y - x))).collect())
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prediction_is_exact_for_weights_linear_in_log_radius() {
        // Scaled weights a + b ln r at three radii; the prediction at any radius (between
        // them or beyond) from the two nearest is exact, times r^2.
        let (a, b) = ([0.3, -1.0, 2.0], [0.5, 0.25, -4.0]);
        let scaled = |r: f64| -> Vec<f64> { (0..3).map(|i| a[i] + b[i] * r.ln()).collect() };
        let solved: Vec<(f64, Vec<f64>)> = [0.5, 2.0, 1.0].iter().map(|&r: &f64| (r.ln(), scaled(r))).collect();
        for r in [0.7, 1.5, 3.0, 0.2] {
            let w = predict_weights(&solved, r).unwrap();
            for i in 0..3 {
                assert!((w[i] - r * r * scaled(r)[i]).abs() < 1e-12, "r {r}: {w:?}");
            }
        }
        assert!(predict_weights(&solved[..1], 1.2).is_none());
    }

    #[test]
    fn prediction_uses_the_two_nearest_solves() {
        // Constant scaled weights near r = 1, a far solve with other ones: the far solve is
        // not used, so the prediction at 1.1 is the constant.
        let solved = vec![(0.0, vec![1.0, 2.0]), (10f64.ln(), vec![50.0, -50.0]), (0.2, vec![1.0, 2.0])];
        let w = predict_weights(&solved, 1.1).unwrap();
        assert!((w[0] - 1.21).abs() < 1e-12 && (w[1] - 2.42).abs() < 1e-12, "{w:?}");
    }
}
