//! A remesh against its input (paper Sec. 4.2's measures as distributions): the face areas,
//! each divided by its mesh's mean face area so that meshes of different sizes compare, and
//! the smallest angle of each face (degrees, 0 to 60).

use super::histogram::{Histogram, HistogramChart};
use super::plot::write_chart;
use super::FigureError;
use crate::mesh::geometry::{face_areas, triangle_angles};
use crate::mesh::TriMesh;
use std::path::{Path, PathBuf};

/// Upper end of the relative face-area axis: larger faces are counted in the last bin.
pub const AREA_AXIS_END: f64 = 4.0;

/// Each face's area divided by the mean face area of `mesh`.
pub fn relative_areas(mesh: &TriMesh) -> Vec<f64> {
    let a = face_areas(&mesh.vertices, &mesh.faces);
    let mean = a.iter().filter(|x| x.is_finite()).sum::<f64>() / a.len().max(1) as f64;
    a.iter().map(|x| if mean > 0.0 { x / mean } else { f64::NAN }).collect()
}

/// The smallest angle of each face in degrees (`NaN` for a degenerate face).
pub fn smallest_angles(mesh: &TriMesh) -> Vec<f64> {
    (0..mesh.n_faces())
        .map(|f| {
            let [a, b, c] = mesh.face_points(f);
            let t = triangle_angles(a, b, c);
            t[0].min(t[1]).min(t[2]).to_degrees()
        })
        .collect()
}

/// The relative face-area histograms of `input` and `remeshed` over `[0, AREA_AXIS_END]`.
pub fn area_histograms(input: &TriMesh, remeshed: &TriMesh, bins: usize) -> [Histogram; 2] {
    [("input", input), ("remesh", remeshed)].map(|(label, m)| Histogram::of(label, relative_areas(m), 0.0, AREA_AXIS_END, bins))
}

/// The smallest-angle histograms of `input` and `remeshed` over `[0, 60]` degrees.
pub fn angle_histograms(input: &TriMesh, remeshed: &TriMesh, bins: usize) -> [Histogram; 2] {
    [("input", input), ("remesh", remeshed)].map(|(label, m)| Histogram::of(label, smallest_angles(m), 0.0, 60.0, bins))
}

/// Draw the two histograms (input, remesh) to `dir/stem.png` (and `.svg`).
pub fn write_comparison(histograms: &[Histogram; 2], title: &str, x_label: &str, dir: &Path, stem: &str, size: (u32, u32), svg: bool) -> Result<(PathBuf, Option<PathBuf>), FigureError> {
    let chart = HistogramChart { title: title.to_string(), x_label: x_label.to_string(), series: histograms.iter().collect() };
    write_chart(&chart, dir, stem, size, svg)
}
