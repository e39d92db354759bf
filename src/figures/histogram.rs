//! [`Histogram`]: the counts behind every histogram figure, and the chart that draws one or
//! two of them over the same bins (a remesh against its input).

use super::font::FAMILY;
use super::plot::{text, Chart};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Counts of values in equal bins over `[lo, hi]`. Every finite value is counted: values
/// below `lo` in the first bin, above `hi` in the last (the figures say when a range is
/// clipped); non-finite values are left out, as [`crate::metrics::Stats`] leaves them out.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Histogram {
    /// What was counted (the legend's text).
    pub label: String,
    /// Lower end of the first bin.
    pub lo: f64,
    /// Upper end of the last bin.
    pub hi: f64,
    /// Values per bin.
    pub counts: Vec<usize>,
}

impl Histogram {
    /// Count the finite `values` in `bins` (at least 1) equal bins over `[lo, hi]`.
    pub fn of(label: &str, values: impl IntoIterator<Item = f64>, lo: f64, hi: f64, bins: usize) -> Self {
        let bins = bins.max(1);
        let mut counts = vec![0usize; bins];
        let width = (hi - lo) / bins as f64;
        for v in values.into_iter().filter(|v| v.is_finite()) {
            let k = if width > 0.0 { ((v - lo) / width).floor() } else { 0.0 };
            counts[(k.max(0.0) as usize).min(bins - 1)] += 1;
        }
        Self { label: label.to_string(), lo, hi, counts }
    }

    /// How many values were counted.
    pub fn total(&self) -> usize {
        self.counts.iter().sum()
    }

    /// Width of one bin.
    pub fn bin_width(&self) -> f64 {
        (self.hi - self.lo) / self.counts.len() as f64
    }
}

/// The range `[min, max]` of the finite `values`, widened a little when it is a single point;
/// `[-1, 1]` when there is no finite value.
pub fn value_range(values: &[f64]) -> (f64, f64) {
    let (lo, hi) = values.iter().filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    if !(lo <= hi) {
        (-1.0, 1.0)
    } else if lo == hi {
        let pad = 0.5 * lo.abs().max(1e-9);
        (lo - pad, hi + pad)
    } else {
        (lo, hi)
    }
}

/// Colours of the first and second series.
const COLOURS: [RGBColor; 2] = [RGBColor(120, 120, 120), RGBColor(33, 102, 172)];

/// One or two histograms over the same bins, as bars of the share of their values in each
/// bin (so that a remesh and its input, of different sizes, compare).
pub struct HistogramChart<'a> {
    /// Title over the chart.
    pub title: String,
    /// What the x axis measures.
    pub x_label: String,
    /// The series (the first drawn first, greyed when there are two).
    pub series: Vec<&'a Histogram>,
}

impl Chart for HistogramChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let first = self.series.first().ok_or("no histogram to draw")?;
        let share = |h: &Histogram, k: usize| 100.0 * h.counts[k] as f64 / h.total().max(1) as f64;
        let top = self.series.iter().flat_map(|h| (0..h.counts.len()).map(move |k| share(h, k))).fold(0.0, f64::max).max(1e-9);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FAMILY, 18))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(56)
            .build_cartesian_2d(first.lo..first.hi, 0.0..1.08 * top)
            .map_err(text)?;
        chart
            .configure_mesh()
            .light_line_style(TRANSPARENT)
            .disable_x_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc("share (%)")
            .label_style((FAMILY, 13))
            .axis_desc_style((FAMILY, 14))
            .draw()
            .map_err(text)?;
        let alpha = if self.series.len() > 1 { 0.55 } else { 0.85 };
        for (i, h) in self.series.iter().enumerate() {
            let colour = COLOURS[i.min(1)];
            let w = h.bin_width();
            let bars = (0..h.counts.len()).filter(|&k| h.counts[k] > 0).map(|k| {
                let x = h.lo + w * k as f64;
                Rectangle::new([(x, 0.0), (x + w, share(h, k))], colour.mix(alpha).filled())
            });
            chart
                .draw_series(bars)
                .map_err(text)?
                .label(format!("{} ({} values)", h.label, h.total()))
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], colour.mix(alpha).filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .label_font((FAMILY, 13))
            .draw()
            .map_err(text)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_finite_value_is_counted_once() {
        let v = [-3.0, 0.0, 0.1, 0.5, 0.99, 1.0, 7.0, f64::NAN, f64::INFINITY];
        let h = Histogram::of("v", v, 0.0, 1.0, 4);
        assert_eq!(h.counts, vec![3, 0, 1, 3]);
        assert_eq!(h.total(), 7);
        assert_eq!(value_range(&[2.0, f64::NAN]), (1.0, 3.0));
    }
}
