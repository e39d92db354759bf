//! What [`super::parameterize`] measured: [`ParamReport`] and the records it holds.

use crate::cap::Domain;
use crate::flatten::closed::ClosedFlattenReport;
use crate::flatten::puncture::Puncture;
use crate::flatten::DiskConformalReport;
use crate::mesh::SurfaceKind;
use crate::metrics::Stats;
use crate::refine::{AreaRefineReport, ProlongReport, SmoothingTrial, UntangleReport};

/// The initial flattening's report, by surface kind.
#[derive(Debug, Clone, serde::Serialize)]
#[serde(untagged)]
pub enum FlattenReport {
    /// Disk conformal map of an open surface.
    Open(DiskConformalReport),
    /// Puncture, stretch energy and quasi-conformal composition of a closed surface.
    Closed(ClosedFlattenReport),
}

/// One evaluation of the radius search.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RadiusSample {
    /// Disk radius.
    pub r: f64,
    /// Cap bound for that radius.
    pub z_star: f64,
    /// Area-normalised mean `|mu|^2`.
    pub energy: f64,
    /// Newton iterations of that transport solve (on the coarse level when the search ran
    /// there).
    pub newton_iterations: usize,
}

/// Serialize a report field as its `Display` string (the JSON keeps the words of the
/// command-line output).
fn as_display<T: std::fmt::Display, S: serde::Serializer>(value: &T, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.collect_str(value)
}

/// Whether a map passed capmesh's own quality check (the command line exits with code 3 on a
/// poor map unless `--allow-poor-map`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MapQuality {
    /// On the adaptive cap, mean `|d_area|` at most [`super::POOR_MAP_AREA_DISTORTION`].
    Good,
    /// On the adaptive cap, mean `|d_area|` above [`super::POOR_MAP_AREA_DISTORTION`] or not
    /// finite: fold-free but far from area preserving.
    Poor,
    /// A fixed domain (disk, hemisphere, sphere, radius=R): not rated, since those distort
    /// area by design.
    Unrated,
}

impl MapQuality {
    /// The quality of a map onto `domain` with mean `|d_area|` `mean_abs_area_distortion`.
    pub fn of(domain: Domain, mean_abs_area_distortion: f64) -> MapQuality {
        if domain != Domain::Adaptive {
            MapQuality::Unrated
        } else if mean_abs_area_distortion <= super::POOR_MAP_AREA_DISTORTION {
            MapQuality::Good
        } else {
            MapQuality::Poor
        }
    }

    /// `"good"`, `"poor"` or `"unrated"`, as in the JSON reports and the shape CSV.
    pub fn name(self) -> &'static str {
        match self {
            MapQuality::Good => "good",
            MapQuality::Poor => "poor",
            MapQuality::Unrated => "unrated",
        }
    }
}

impl std::fmt::Display for MapQuality {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Everything measured about one parameterization.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ParamReport {
    /// Domain used (serialized as its display string, e.g. `"adaptive"`, `"radius=1.5"`).
    #[serde(serialize_with = "as_display")]
    pub domain: Domain,
    /// Surface kind (serialized as its display string, `"open disk"` or `"closed genus-0"`).
    #[serde(serialize_with = "as_display")]
    pub kind: SurfaceKind,
    /// Input vertices.
    pub n_vertices: usize,
    /// Input faces.
    pub n_faces: usize,
    /// Vertices merged with a coincident one before mapping.
    pub welded_vertices: usize,
    /// Copies made of vertices where welding left the surface touching itself, one per fan
    /// beyond the first ([`crate::mesh::repair::split_pinched_vertices`]).
    pub split_vertices: usize,
    /// Edges shorter than 5% of the mean edge collapsed before mapping, after the transport
    /// stalled on the mesh as given or left its map folded or poor, and the map of the
    /// collapsed mesh was better (a degenerate triangulation's needles; 0 otherwise,
    /// [`crate::mesh::short_edges`]).
    pub collapsed_short_edges: usize,
    /// Optimal (or fixed) disk radius; `None` for the planar disk.
    pub r_star: Option<f64>,
    /// Cap bound `Z*`; `None` for the planar disk.
    pub z_star: Option<f64>,
    /// Per-face area distortion statistics.
    pub area_distortion: Stats,
    /// `poor` when the mean `|d_area|` on the adaptive cap is above
    /// [`super::POOR_MAP_AREA_DISTORTION`] (see [`MapQuality`]).
    pub quality: MapQuality,
    /// Per-corner angle distortion statistics (radians).
    pub angle_distortion: Stats,
    /// Area-normalised mean `|mu|^2` at the final radius.
    pub conformal_energy: f64,
    /// Faces with non-positive orientation in the final map.
    pub flipped_faces: usize,
    /// Smoothing strength of the final centroid map (0: the paper's plain map).
    pub smoothing_kappa: f64,
    /// Every smoothing strength tried, with its measured area distortion.
    pub smoothing_trials: Vec<SmoothingTrial>,
    /// The repair of folded faces after transport (see `crate::refine::untangle`).
    pub untangle: UntangleReport,
    /// The face-level area refinement (see [`crate::refine::area_refine`]).
    pub area_refinement: AreaRefineReport,
    /// Newton iterations over all full-resolution transport solves.
    pub newton_iterations: usize,
    /// Sites of the coarse level the radius search ran on; `None` when it ran at full
    /// resolution.
    pub search_sites: Option<usize>,
    /// Times a closed surface's coarse radius search ended inside the bound of `Z*` and was
    /// made again on a finer level (docs/method.md section 5; `search_sites` and
    /// `radius_curve` are the kept search's: the finest, unless its transport failed). Where
    /// the full transport fails at the refined radius, `r_star` is the first search's.
    pub search_refinements: usize,
    /// Newton iterations of the coarse radius search (every level's).
    pub coarse_newton_iterations: usize,
    /// Transport solves.
    pub transport_solves: usize,
    /// Symbolic factorizations of the transport Newton matrices, coarse search included
    /// (the other iterations reused one).
    pub transport_symbolic_factorizations: usize,
    /// Radius search evaluations in order.
    pub radius_curve: Vec<RadiusSample>,
    /// Initial flattening report.
    pub flatten: FlattenReport,
    /// The punctured quadrilateral of a closed surface (indices in the welded mesh).
    pub puncture: Option<Puncture>,
    /// Both ends tried when the puncture end is [`super::PunctureEnd::Best`] (empty otherwise).
    pub puncture_trials: Vec<PunctureTrial>,
    /// The composition factors tried for a closed surface and not kept (its transport
    /// stalled or its map was poor, [`super::ClosedOptions::lambda_fallbacks`]); `flatten`
    /// has the `lambda` kept. Empty when the first worked.
    pub lambda_fallbacks: Vec<LambdaFallback>,
    /// The multilevel parameterization of a large closed surface (see
    /// [`super::ClosedOptions::multilevel_above`]): the stages above ran on a decimated mesh,
    /// whose map was prolonged to every vertex and refined there. `None` when the surface was
    /// mapped at its own resolution.
    pub multilevel: Option<MultilevelReport>,
    /// Wall-clock seconds of the whole parameterization (for [`super::PunctureEnd::Best`] both
    /// ends' searches, in parallel, and the kept end's second half; the stage seconds below
    /// are the kept end's).
    pub seconds: f64,
    /// Seconds spent in the initial flattening.
    pub flatten_seconds: f64,
    /// Seconds spent in transport solves (radius search included).
    pub transport_seconds: f64,
    /// Seconds spent in the smoothing trials and fold repair (JSON: `regularise_seconds`, its
    /// name before the concept had one name).
    #[serde(rename = "regularise_seconds")]
    pub smoothing_seconds: f64,
    /// Seconds spent in the face-level area refinement.
    pub refine_seconds: f64,
}

/// The multilevel parameterization of a large closed surface (`crate::param::multilevel`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct MultilevelReport {
    /// Vertices of the decimated mesh that was parameterized.
    pub coarse_vertices: usize,
    /// Mean `|d_area|` of the decimated mesh's map.
    pub coarse_mean_abs_area_distortion: f64,
    /// How the removed vertices were put back.
    pub prolong: ProlongReport,
    /// Faces the prolonged map folded (only where rounding left an inserted vertex no
    /// unfolded place, [`ProlongReport::unplaced`]).
    pub folded_after_prolong: usize,
    /// The fold repair of those faces, when there were any.
    pub untangle: Option<UntangleReport>,
    /// The radial mass correction of the prolonged map (docs/method.md section 20).
    pub radial: crate::refine::RadialReport,
    /// Seconds of the decimation (the punctures chosen first).
    pub decimate_seconds: f64,
    /// Seconds of the decimated mesh's parameterization.
    pub coarse_seconds: f64,
    /// Seconds of the prolongation.
    pub prolong_seconds: f64,
}

/// One end tried by [`super::PunctureEnd::Best`].
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct PunctureTrial {
    /// The principal axis direction called "up" for this trial.
    pub axis: [f64; 3],
    /// Mean `|d_area|` of the radius search's map at `r*` (the criterion; `None` for a
    /// fixed domain).
    pub search_area_distortion: Option<f64>,
    /// Mean `|d_area|` of the finished map: the kept end's, and both ends' when both were
    /// finished (fixed domains).
    pub mean_abs_area_distortion: Option<f64>,
}

/// One `lambda` tried for a closed surface whose map was not kept: its transport failed, or
/// its map was poor and a later one was better.
#[derive(Debug, Clone, serde::Serialize)]
pub struct LambdaFallback {
    /// The composition factor tried.
    pub lambda: f64,
    /// The stretch-energy iterations its initial map was allowed: the flattening's own, or
    /// [`super::ClosedOptions::rescue_stretch_iterations`] in the rescue round.
    pub stretch_iterations: usize,
    /// Why it was not kept (the transport's error, or the map's distortion).
    pub reason: String,
    /// The map's mean `|d_area|` when there was a map.
    pub mean_abs_area_distortion: Option<f64>,
}

impl LambdaFallback {
    /// The attempt as `lambda`, with its stretch-energy iterations when they are not
    /// `flattening`'s (the rescue round's): `0.8` or `0.8 with 80 stretch-energy iterations`.
    pub fn describe(&self, flattening: usize) -> String {
        if self.stretch_iterations == flattening {
            format!("{}", self.lambda)
        } else {
            format!("{} with {} stretch-energy iterations", self.lambda, self.stretch_iterations)
        }
    }
}
