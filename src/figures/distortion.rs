//! The histograms of a parameterization's distortion (paper Sec. 4.1 and Fig. 4-5): `d_area`
//! per face and `d_angle` per corner, over their whole range, counting exactly the values
//! whose statistics the report gives.

use super::histogram::{value_range, Histogram, HistogramChart};
use super::plot::write_chart;
use super::FigureError;
use crate::cap::CapMap;
use std::path::{Path, PathBuf};

/// The `d_area` histogram of `map`'s faces.
pub fn area_histogram(map: &CapMap, bins: usize) -> Histogram {
    let (lo, hi) = value_range(&map.face_area_distortion);
    Histogram::of("faces", map.face_area_distortion.iter().copied(), lo, hi, bins)
}

/// The `d_angle` histogram of `map`'s corners, in degrees.
pub fn angle_histogram(map: &CapMap, bins: usize) -> Histogram {
    let degrees: Vec<f64> = map.corner_angle_distortion.iter().map(|a| a.to_degrees()).collect();
    let (lo, hi) = value_range(&degrees);
    Histogram::of("corners", degrees, lo, hi, bins)
}

/// Draw `histogram` of a distortion measure to `dir/stem.png` (and `.svg`).
pub fn write_distortion(histogram: &Histogram, title: &str, x_label: &str, dir: &Path, stem: &str, size: (u32, u32), svg: bool) -> Result<(PathBuf, Option<PathBuf>), FigureError> {
    let chart = HistogramChart { title: title.to_string(), x_label: x_label.to_string(), series: vec![histogram] };
    write_chart(&chart, dir, stem, size, svg)
}
