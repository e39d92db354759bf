//! Figures a user can look at (feature `figures`, on with the command line's `--figures
//! DIR`): for a parameterization the paper's histograms of `d_area` and `d_angle` (Sec. 4.1,
//! Fig. 4-5), the radius-search curve with `r*` marked (Sec. 3.1.2), shaded views of the
//! input and of the map on its cap coloured by `d_area`; for a remesh the histograms of
//! relative face area and smallest angle against the input's and the remesh with its edges;
//! for a harmonics fit the reconstruction and its error per order (Sec. 3.3). Each run also
//! writes `DIR/index.md`, linking the figures under the report's headline numbers.
//!
//! Charts are drawn with plotters, as PNG and SVG; the shaded views by this module's own
//! z-buffer rasterizer (`raster`: orthographic, flat Lambert shading, three fixed views) as
//! PNG. Text uses a bundled font, so nothing is needed from the system. Everything is drawn
//! single-threaded in a fixed order and encoded with fixed settings: the same input gives the
//! same bytes.
//!
//! Every histogram counts every finite value of its measure ([`Histogram`]), so its total is
//! the report's count (for `d_area`, [`crate::ParamReport::area_distortion`]`.count`); the
//! counts are returned with the figures ([`Figure::histograms`]).

mod cap;
mod colormap;
mod distortion;
mod encode;
mod error;
mod error_curve;
mod font;
mod histogram;
mod index;
mod plot;
mod radius_curve;
pub(crate) mod raster;
mod remesh_quality;
mod shaded;
mod text;
mod views;

pub use encode::RgbImage;
pub use error::FigureError;
pub use histogram::Histogram;
pub use remesh_quality::{relative_areas, smallest_angles, AREA_AXIS_END};

use crate::cap::CapMap;
use crate::harmonics::HarmonicsOutput;
use crate::mesh::TriMesh;
use crate::remesh::RemeshReport;
use std::path::{Path, PathBuf};

/// Default side of one shaded view, pixels.
pub const DEFAULT_VIEW_SIZE: u32 = 300;
/// Default size of a chart, pixels.
pub const DEFAULT_CHART_SIZE: (u32, u32) = (640, 420);
/// Default number of histogram bins.
pub const DEFAULT_BINS: usize = 50;

/// Options of the figures.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct FigureOptions {
    /// Side of one of the three shaded views in pixels (default [`DEFAULT_VIEW_SIZE`], 300;
    /// 16 to 4096): a rendering is `3 * view_size` wide.
    pub view_size: u32,
    /// Width and height of a chart in pixels (default [`DEFAULT_CHART_SIZE`], 640 x 420;
    /// 160 x 120 to 8192 x 8192).
    pub chart_size: (u32, u32),
    /// Bins of every histogram (default [`DEFAULT_BINS`], 50).
    pub bins: usize,
    /// Also write each chart as SVG (default true).
    pub svg: bool,
}

impl Default for FigureOptions {
    fn default() -> Self {
        Self { view_size: DEFAULT_VIEW_SIZE, chart_size: DEFAULT_CHART_SIZE, bins: DEFAULT_BINS, svg: true }
    }
}

impl FigureOptions {
    /// Set the side of one shaded view.
    pub fn with_view_size(mut self, pixels: u32) -> Self {
        self.view_size = pixels;
        self
    }
    /// Set the size of a chart.
    pub fn with_chart_size(mut self, width: u32, height: u32) -> Self {
        self.chart_size = (width, height);
        self
    }
    /// Set the number of histogram bins.
    pub fn with_bins(mut self, bins: usize) -> Self {
        self.bins = bins;
        self
    }
    /// Write (or not) an SVG beside each chart's PNG.
    pub fn with_svg(mut self, svg: bool) -> Self {
        self.svg = svg;
        self
    }
}

/// What a figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum FigureKind {
    /// Histogram of `d_area` per face.
    AreaDistortion,
    /// Histogram of `d_angle` per corner.
    AngleDistortion,
    /// The radius-search objective against `Z*`, `r*` marked.
    RadiusCurve,
    /// Shaded views of the input.
    Input,
    /// Shaded views of the map on its cap, coloured by `d_area`.
    CapAreaDistortion,
    /// Histograms of relative face area, input and remesh.
    FaceAreas,
    /// Histograms of the smallest angle per face, input and remesh.
    SmallestAngles,
    /// Shaded views of the remesh with its edges.
    Remesh,
    /// Shaded views of the harmonic reconstruction.
    Reconstruction,
    /// Reconstruction error per order.
    ReconstructionError,
}

impl FigureKind {
    /// The file name without extension.
    pub fn stem(self) -> &'static str {
        match self {
            Self::AreaDistortion => "area_distortion",
            Self::AngleDistortion => "angle_distortion",
            Self::RadiusCurve => "radius_curve",
            Self::Input => "input",
            Self::CapAreaDistortion => "cap_area_distortion",
            Self::FaceAreas => "face_areas",
            Self::SmallestAngles => "smallest_angles",
            Self::Remesh => "remesh",
            Self::Reconstruction => "reconstruction",
            Self::ReconstructionError => "reconstruction_error",
        }
    }

    /// One sentence saying how to read the figure (the index's caption).
    pub fn caption(self) -> &'static str {
        match self {
            Self::AreaDistortion => "d_area = ln of a face's share of the cap's area over its share of the surface's; 0 is area preserving (paper Sec. 4.1).",
            Self::AngleDistortion => "d_angle = each corner's angle on the cap minus on the surface, degrees; 0 is conformal.",
            Self::RadiusCurve => "Every radius the search evaluated, by its cap bound Z*, and the one chosen (paper Eq. 12).",
            Self::Input => "The input surface, orthographic views along -Y, +X and +Z.",
            Self::CapAreaDistortion => "The input's faces on the cap: red grew, blue shrank, white kept their share of the area; grey faces go to the cap's flat bottom.",
            Self::FaceAreas => "Face area over the mesh's mean face area; an equal-area remesh peaks at 1 (larger than the axis end: last bin).",
            Self::SmallestAngles => "The smallest angle of each face, degrees; 60 is equilateral.",
            Self::Remesh => "The remesh with its edges, the same views as the input.",
            Self::Reconstruction => "The order-N harmonic reconstruction (the input's connectivity), the same views as the input.",
            Self::ReconstructionError => "Mean and largest vertex distance of the order-n fit over the bounding-box diagonal.",
        }
    }
}

/// One figure written.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Figure {
    /// What it shows.
    pub kind: FigureKind,
    /// Its title in the index.
    pub title: String,
    /// The PNG file.
    pub png: PathBuf,
    /// The SVG file (charts, with [`FigureOptions::svg`]).
    pub svg: Option<PathBuf>,
    /// PNG width in pixels.
    pub width: u32,
    /// PNG height in pixels.
    pub height: u32,
    /// The histograms drawn (empty for the other figures).
    pub histograms: Vec<Histogram>,
}

/// The figures of one run and their index.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FigureSet {
    /// The figures, in the index's order.
    pub figures: Vec<Figure>,
    /// `DIR/index.md`.
    pub index: PathBuf,
}

impl FigureSet {
    /// The figure of `kind`, if written.
    pub fn get(&self, kind: FigureKind) -> Option<&Figure> {
        self.figures.iter().find(|f| f.kind == kind)
    }
}

fn create_dir(dir: &Path) -> Result<(), FigureError> {
    std::fs::create_dir_all(dir).map_err(|source| FigureError::Io { path: dir.to_path_buf(), source })
}

fn chart(kind: FigureKind, title: &str, (png, svg): (PathBuf, Option<PathBuf>), options: &FigureOptions, histograms: Vec<Histogram>) -> Figure {
    Figure { kind, title: title.to_string(), png, svg, width: options.chart_size.0, height: options.chart_size.1, histograms }
}

fn rendering(kind: FigureKind, title: &str, (png, (width, height)): (PathBuf, (u32, u32))) -> Figure {
    Figure { kind, title: title.to_string(), png, svg: None, width, height, histograms: Vec::new() }
}

/// The figures of a parameterization: `d_area` and `d_angle` histograms, the radius curve
/// (adaptive domain), the input and the cap coloured by `d_area`.
fn param_set(dir: &Path, mesh: &TriMesh, map: &CapMap, options: &FigureOptions) -> Result<Vec<Figure>, FigureError> {
    let (size, svg, o) = (options.chart_size, options.svg, options);
    let r = &map.report;
    let mut out = Vec::new();
    let h = distortion::area_histogram(map, o.bins);
    let title = format!("area distortion: mean |d_area| = {:.4}", r.area_distortion.mean_abs);
    let files = distortion::write_distortion(&h, &title, "d_area", dir, FigureKind::AreaDistortion.stem(), size, svg)?;
    out.push(chart(FigureKind::AreaDistortion, "Area distortion d_area", files, o, vec![h]));
    let h = distortion::angle_histogram(map, o.bins);
    let title = format!("angle distortion: mean |d_angle| = {:.2} deg", r.angle_distortion.mean_abs.to_degrees());
    let files = distortion::write_distortion(&h, &title, "d_angle (degrees)", dir, FigureKind::AngleDistortion.stem(), size, svg)?;
    out.push(chart(FigureKind::AngleDistortion, "Angle distortion d_angle", files, o, vec![h]));
    if !r.radius_curve.is_empty() {
        let files = radius_curve::write_radius_curve(r, dir, FigureKind::RadiusCurve.stem(), size, svg)?;
        out.push(chart(FigureKind::RadiusCurve, "Radius search", files, o, Vec::new()));
    }
    let files = shaded::write_shaded(mesh, shaded::INPUT_COLOUR, false, &format!("input: {} vertices, {} faces", mesh.n_vertices(), mesh.n_faces()), dir, FigureKind::Input.stem(), o.view_size)?;
    out.push(rendering(FigureKind::Input, "Input", files));
    let files = cap::write_cap(mesh, map, dir, FigureKind::CapAreaDistortion.stem(), o.view_size)?;
    out.push(rendering(FigureKind::CapAreaDistortion, "The map on its cap, coloured by d_area", files));
    Ok(out)
}

fn param_headline(r: &crate::ParamReport) -> Vec<(String, String)> {
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    vec![
        ("surface".into(), r.kind.to_string()),
        ("domain".into(), r.domain.to_string()),
        ("vertices, faces".into(), format!("{}, {}", r.n_vertices, r.n_faces)),
        ("r*".into(), opt(r.r_star)),
        ("Z*".into(), opt(r.z_star)),
        ("mean abs d_area (faces counted)".into(), format!("{:.4} ({})", r.area_distortion.mean_abs, r.area_distortion.count)),
        ("max abs d_area".into(), format!("{:.4}", r.area_distortion.max_abs)),
        ("mean abs d_angle".into(), format!("{:.4} rad ({:.2} deg)", r.angle_distortion.mean_abs, r.angle_distortion.mean_abs.to_degrees())),
        ("flipped faces".into(), r.flipped_faces.to_string()),
    ]
}

/// Write the figures of the parameterization `map` of `mesh` into `dir` (created if
/// missing) with `DIR/index.md`; `name` (the input's file name) titles the index.
pub fn param_figures(dir: &Path, name: &str, mesh: &TriMesh, map: &CapMap, options: &FigureOptions) -> Result<FigureSet, FigureError> {
    create_dir(dir)?;
    let figures = param_set(dir, mesh, map, options)?;
    let index = index::write_index(dir, &format!("capmesh param: {name}"), &param_headline(&map.report), &figures)?;
    Ok(FigureSet { figures, index })
}

/// Write the figures of the remesh `remeshed` of `input` into `dir` (created if missing)
/// with `DIR/index.md`: the radius curve of its parameterization, the relative face-area and
/// smallest-angle histograms against the input's, the input and the remesh with its edges.
pub fn remesh_figures(dir: &Path, name: &str, input: &TriMesh, remeshed: &TriMesh, report: &RemeshReport, options: &FigureOptions) -> Result<FigureSet, FigureError> {
    create_dir(dir)?;
    let (size, svg, o) = (options.chart_size, options.svg, options);
    let mut figures = Vec::new();
    let areas = remesh_quality::area_histograms(input, remeshed, o.bins);
    let files = remesh_quality::write_comparison(&areas, "face area / mean face area", "relative face area", dir, FigureKind::FaceAreas.stem(), size, svg)?;
    figures.push(chart(FigureKind::FaceAreas, "Face areas, remesh against input", files, o, areas.to_vec()));
    let angles = remesh_quality::angle_histograms(input, remeshed, o.bins);
    let title = format!("smallest angle per face (remesh mean {:.1} deg)", report.quality.mean_min_angle_deg);
    let files = remesh_quality::write_comparison(&angles, &title, "smallest angle (degrees)", dir, FigureKind::SmallestAngles.stem(), size, svg)?;
    figures.push(chart(FigureKind::SmallestAngles, "Smallest angles, remesh against input", files, o, angles.to_vec()));
    if !report.param.radius_curve.is_empty() {
        let files = radius_curve::write_radius_curve(&report.param, dir, FigureKind::RadiusCurve.stem(), size, svg)?;
        figures.push(chart(FigureKind::RadiusCurve, "Radius search", files, o, Vec::new()));
    }
    let files = shaded::write_shaded(input, shaded::INPUT_COLOUR, false, &format!("input: {} vertices, {} faces", input.n_vertices(), input.n_faces()), dir, FigureKind::Input.stem(), o.view_size)?;
    figures.push(rendering(FigureKind::Input, "Input", files));
    let files = shaded::write_shaded(remeshed, shaded::REMESH_COLOUR, true, &format!("remesh: {} vertices, {} faces", remeshed.n_vertices(), remeshed.n_faces()), dir, FigureKind::Remesh.stem(), o.view_size)?;
    figures.push(rendering(FigureKind::Remesh, "Remesh", files));
    let q = &report.quality;
    let mut headline = vec![
        ("faces (input)".into(), format!("{} ({})", q.faces, input.n_faces())),
        ("Z*".into(), report.param.z_star.map_or("-".to_string(), |z| format!("{z:.4}"))),
        ("d_face (relative)".into(), format!("{:.4e} ({:.4})", q.d_face, q.d_face_relative)),
        ("smallest angle, mean smallest angle".into(), format!("{:.2} deg, {:.2} deg", q.min_angle_deg, q.mean_min_angle_deg)),
        ("faces with an angle below 30 deg".into(), format!("{:.2}%", 100.0 * q.share_faces_angle_below_30)),
        ("Hausdorff distance / diagonal".into(), format!("{:.3e}", q.hausdorff_distance_relative)),
        ("mean abs d_area of the map".into(), format!("{:.4}", report.param.area_distortion.mean_abs)),
    ];
    headline.push(("self-intersecting faces (input)".into(), format!("{} ({})", q.self_intersecting_faces, q.self_intersecting_faces_input)));
    let index = index::write_index(dir, &format!("capmesh remesh: {name}"), &headline, &figures)?;
    Ok(FigureSet { figures, index })
}

/// Write the figures of the harmonics fit `output` of `mesh` (parameterized by `map`) into
/// `dir` (created if missing) with `DIR/index.md`: the parameterization's figures, the
/// reconstruction and its error per order.
pub fn harmonics_figures(dir: &Path, name: &str, mesh: &TriMesh, map: &CapMap, output: &HarmonicsOutput, options: &FigureOptions) -> Result<FigureSet, FigureError> {
    create_dir(dir)?;
    let mut figures = param_set(dir, mesh, map, options)?;
    let r = &output.report;
    let title = format!("order-{} reconstruction", r.order);
    let files = shaded::write_shaded(&output.reconstructed, shaded::RECONSTRUCTION_COLOUR, false, &title, dir, FigureKind::Reconstruction.stem(), options.view_size)?;
    figures.push(rendering(FigureKind::Reconstruction, "Harmonic reconstruction", files));
    let files = error_curve::write_error_curve(r, dir, FigureKind::ReconstructionError.stem(), options.chart_size, options.svg)?;
    figures.push(chart(FigureKind::ReconstructionError, "Reconstruction error per order", files, options, Vec::new()));
    let mut headline = vec![("order N (basis functions)".into(), format!("{} ({})", r.order, r.basis_functions))];
    if let Some(last) = r.errors_by_order.last() {
        headline.push(("mean, max error / diagonal at N".into(), format!("{:.3e}, {:.3e}", last.mean_relative, last.max_relative)));
    }
    headline.push(("order-1 aspect ratio".into(), format!("{:.4}", r.aspect_ratio)));
    headline.extend(param_headline(&map.report));
    let index = index::write_index(dir, &format!("capmesh harmonics: {name}"), &headline, &figures)?;
    Ok(FigureSet { figures, index })
}
