//! The radius search (paper Sec. 3.1.2, Eq. 12): the objective, the area-normalised mean
//! `|mu|^2`, at every evaluated cap bound `Z*` (the search variable), and the chosen `Z*`
//! (radius `r*`) marked.

use super::font::FAMILY;
use super::plot::{text, write_chart, Chart};
use super::FigureError;
use crate::param::ParamReport;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The chart of `report.radius_curve`.
pub struct RadiusCurve<'a> {
    /// The parameterization's report (a fixed domain has no curve: one point or none).
    pub report: &'a ParamReport,
}

impl Chart for RadiusCurve<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let mut samples: Vec<(f64, f64)> = self.report.radius_curve.iter().filter(|s| s.z_star.is_finite() && s.energy.is_finite()).map(|s| (s.z_star, s.energy)).collect();
        if samples.is_empty() {
            return Err("the radius search evaluated no radius (a fixed domain)".into());
        }
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (zlo, zhi) = samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| (lo.min(s.0), hi.max(s.0)));
        let (elo, ehi) = samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| (lo.min(s.1), hi.max(s.1)));
        let zpad = ((zhi - zlo) * 0.06).max(0.02);
        let epad = ((ehi - elo) * 0.1).max(1e-3 * ehi.abs().max(1e-9));
        let title = match (self.report.r_star, self.report.z_star) {
            (Some(r), Some(z)) => format!("radius search: r* = {r:.4}, Z* = {z:.4} ({} solves)", samples.len()),
            _ => "radius search".to_string(),
        };
        let mut chart = ChartBuilder::on(root)
            .caption(title, (FAMILY, 18))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(70)
            .build_cartesian_2d((zlo - zpad)..(zhi + zpad), (elo - epad)..(ehi + epad))
            .map_err(text)?;
        chart
            .configure_mesh()
            .light_line_style(TRANSPARENT)
            .x_desc("cap bound Z*")
            .y_desc("mean |mu|^2 (Eq. 12)")
            .label_style((FAMILY, 13))
            .axis_desc_style((FAMILY, 14))
            .y_label_formatter(&|v| format!("{v:.4}"))
            .draw()
            .map_err(text)?;
        let line = RGBColor(33, 102, 172);
        chart.draw_series(LineSeries::new(samples.iter().copied(), line.stroke_width(2))).map_err(text)?.label("evaluations").legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], line.stroke_width(2)));
        chart.draw_series(samples.iter().map(|&p| Circle::new(p, 4, line.filled()))).map_err(text)?;
        if let Some(z) = self.report.z_star {
            let best = self.report.radius_curve.iter().filter(|s| s.energy.is_finite()).min_by(|a, b| a.energy.total_cmp(&b.energy)).map_or(elo, |s| s.energy);
            let red = RGBColor(178, 24, 43);
            chart.draw_series(std::iter::once(PathElement::new(vec![(z, elo - epad), (z, ehi + epad)], red.mix(0.6).stroke_width(1)))).map_err(text)?;
            chart
                .draw_series(std::iter::once(Circle::new((z, best), 7, red.stroke_width(3))))
                .map_err(text)?
                .label("r* (chosen)")
                .legend(move |(x, y)| Circle::new((x + 8, y), 5, red.stroke_width(2)));
        }
        chart.configure_series_labels().position(SeriesLabelPosition::UpperRight).background_style(WHITE.mix(0.85)).border_style(BLACK.mix(0.3)).label_font((FAMILY, 13)).draw().map_err(text)?;
        Ok(())
    }
}

/// Draw the radius-search curve of `report` to `dir/stem.png` (and `.svg`).
pub fn write_radius_curve(report: &ParamReport, dir: &Path, stem: &str, size: (u32, u32), svg: bool) -> Result<(PathBuf, Option<PathBuf>), FigureError> {
    write_chart(&RadiusCurve { report }, dir, stem, size, svg)
}
