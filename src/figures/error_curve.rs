//! The harmonic reconstruction error per order (paper Sec. 3.3): mean and largest vertex
//! distance over the bounding-box diagonal, for each order `n = 0..=N`, on a log scale.

use super::font::FAMILY;
use super::plot::{text, write_chart, Chart};
use super::FigureError;
use crate::harmonics::HarmonicsReport;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The chart of `report.errors_by_order`.
pub struct ErrorCurve<'a> {
    /// The harmonics report.
    pub report: &'a HarmonicsReport,
}

impl Chart for ErrorCurve<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let errors = &self.report.errors_by_order;
        let positive = |v: f64| v.is_finite() && v > 0.0;
        let values: Vec<f64> = errors.iter().flat_map(|e| [e.mean_relative, e.max_relative]).filter(|&v| positive(v)).collect();
        if values.is_empty() {
            return Err("no positive reconstruction error to plot".into());
        }
        // log10 of the errors on a linear axis, labelled with the errors themselves.
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min).log10() - 0.15;
        let hi = values.iter().copied().fold(0.0, f64::max).log10() + 0.15;
        let n_max = errors.iter().map(|e| e.order).max().unwrap_or(0) as f64;
        let mut chart = ChartBuilder::on(root)
            .caption(format!("harmonic reconstruction error, order N = {}", self.report.order), (FAMILY, 18))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.5..n_max + 0.5, lo..hi)
            .map_err(text)?;
        chart
            .configure_mesh()
            .light_line_style(TRANSPARENT)
            .x_desc("order n")
            .y_desc("distance / diagonal")
            .label_style((FAMILY, 13))
            .axis_desc_style((FAMILY, 14))
            .x_labels(errors.len().clamp(2, 12))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{:.1e}", 10f64.powf(*v)))
            .draw()
            .map_err(text)?;
        let series = [("mean", RGBColor(33, 102, 172), true), ("max", RGBColor(178, 24, 43), false)];
        for (name, colour, mean) in series {
            let points: Vec<(f64, f64)> = errors.iter().map(|e| (e.order as f64, if mean { e.mean_relative } else { e.max_relative })).filter(|p| positive(p.1)).map(|(n, v)| (n, v.log10())).collect();
            chart.draw_series(LineSeries::new(points.iter().copied(), colour.stroke_width(2))).map_err(text)?.label(name).legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour.stroke_width(2)));
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled()))).map_err(text)?;
        }
        chart.configure_series_labels().position(SeriesLabelPosition::UpperRight).background_style(WHITE.mix(0.85)).border_style(BLACK.mix(0.3)).label_font((FAMILY, 13)).draw().map_err(text)?;
        Ok(())
    }
}

/// Draw the error per order of `report` to `dir/stem.png` (and `.svg`).
pub fn write_error_curve(report: &HarmonicsReport, dir: &Path, stem: &str, size: (u32, u32), svg: bool) -> Result<(PathBuf, Option<PathBuf>), FigureError> {
    write_chart(&ErrorCurve { report }, dir, stem, size, svg)
}
