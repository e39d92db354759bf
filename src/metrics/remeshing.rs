//! Remeshing quality (paper Sec. 4.2): face area deviation `d_face = mean_T |Area(T) - mean
//! area|` (also divided by the mean area), surface distance `d_surface = mean_v |v - proj(v)|`
//! from the remeshed vertices to the original surface, and, because a pulled-back vertex lies
//! on the surface for every method that projects, a symmetric face-sampled distance (design
//! notes). Distances are also given divided by the original's bounding-box diagonal.
//!
//! Shape (issue 26): the angle statistics of [`super::angles`], the share of interior
//! vertices of valence 6 ([`super::valence`]), the self-intersecting faces of the remesh and
//! of the input ([`super::self_intersection`], MeshLab's definition), and the one-sided
//! Hausdorff distance from the remesh to the input ([`super::hausdorff`]).

use super::angles::angle_quality;
use super::closest::SurfaceDistance;
use super::hausdorff::max_distance;
use super::sampling::{distances, face_samples, mean};
use super::self_intersection::count_self_intersecting_faces;
use super::valence::interior_valence6_share;
use crate::mesh::geometry::face_areas;
use crate::mesh::repair::{zero_area_faces, DEFAULT_ZERO_AREA_REL_TOL};
use crate::mesh::TriMesh;

/// Quality of a remeshed surface against its original.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct RemeshMetrics {
    /// Faces of the remeshed surface.
    pub faces: usize,
    /// Vertices of the remeshed surface.
    pub vertices: usize,
    /// `mean |area - mean area|`.
    pub d_face: f64,
    /// `d_face / mean area`.
    pub d_face_relative: f64,
    /// Mean distance from remeshed vertices to the original surface.
    pub d_surface_vertex: f64,
    /// `d_surface_vertex` / bounding-box diagonal of the original.
    pub d_surface_vertex_relative: f64,
    /// Symmetric mean distance between points sampled on the faces of both surfaces.
    pub d_surface_sampled: f64,
    /// `d_surface_sampled` / bounding-box diagonal of the original.
    pub d_surface_sampled_relative: f64,
    /// Smallest angle of the remeshed surface, degrees.
    pub min_angle_deg: f64,
    /// Faces of the remeshed surface with (relatively) zero area
    /// ([`crate::mesh::repair::zero_area_faces`] at its default tolerance). capmesh's remeshes
    /// have none on the shared meshes and on coarse inputs (tests/remesh.rs; see
    /// `crate::remesh::pullback::rim_band_into_polygon` for where they came from).
    pub zero_area_faces: usize,
    /// Mean over the remesh's faces of each face's smallest angle, degrees (60 for an
    /// equilateral mesh).
    pub mean_min_angle_deg: f64,
    /// Share (0-1) of the remesh's faces with an angle below 30 degrees.
    pub share_faces_angle_below_30: f64,
    /// Largest angle of the remeshed surface, degrees.
    pub max_angle_deg: f64,
    /// Share (0-1) of the remesh's interior vertices (on no boundary edge) of valence 6.
    pub share_interior_valence_6: f64,
    /// Faces of the remesh that intersect a face other than an edge neighbour (MeshLab's
    /// `compute_selection_by_self_intersections_per_face`, see
    /// `crate::metrics::self_intersection`).
    pub self_intersecting_faces: usize,
    /// The same count for the input mesh.
    pub self_intersecting_faces_input: usize,
    /// One-sided Hausdorff distance: the largest distance from a point sampled on the
    /// remesh's faces to the original surface.
    pub hausdorff_distance: f64,
    /// `hausdorff_distance` / bounding-box diagonal of the original.
    pub hausdorff_distance_relative: f64,
}

/// Face area deviation `(d_face, d_face / mean area)`.
pub fn face_area_deviation(mesh: &TriMesh) -> (f64, f64) {
    area_deviation(&mesh.vertices, &mesh.faces)
}

/// [`face_area_deviation`] of the faces `faces` over `vertices`.
pub(crate) fn area_deviation(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> (f64, f64) {
    let a = face_areas(vertices, faces);
    if a.is_empty() {
        return (0.0, 0.0);
    }
    let mean = a.iter().sum::<f64>() / a.len() as f64;
    let d = a.iter().map(|x| (x - mean).abs()).sum::<f64>() / a.len() as f64;
    (d, if mean > 0.0 { d / mean } else { 0.0 })
}

fn mean_distance(points: &[[f64; 3]], to: &SurfaceDistance) -> f64 {
    mean(&distances(points, to))
}

/// All remeshing metrics of `remeshed` against `original`.
pub fn remesh_metrics(original: &TriMesh, remeshed: &TriMesh) -> RemeshMetrics {
    remesh_metrics_with(original, remeshed, None)
}

/// [`remesh_metrics`] with the original's self-intersecting faces already counted (`remesh`
/// counts them while it maps the input).
pub(crate) fn remesh_metrics_with(original: &TriMesh, remeshed: &TriMesh, original_crossing: Option<usize>) -> RemeshMetrics {
    let diag = original.bounding_box_diagonal().max(f64::MIN_POSITIVE);
    let (d_face, d_face_relative) = face_area_deviation(remeshed);
    let to_original = SurfaceDistance::new(original);
    let to_remeshed = SurfaceDistance::new(remeshed);
    let d_vertex = mean_distance(&remeshed.vertices, &to_original);
    // The remesh's samples give both the mean (one half of the symmetric figure) and the max.
    let from_remeshed = distances(&face_samples(remeshed), &to_original);
    let d_sampled = 0.5 * (mean(&from_remeshed) + mean_distance(&face_samples(original), &to_remeshed));
    let hausdorff = max_distance(&from_remeshed);
    let angles = angle_quality(remeshed);
    let min_angle = angles.min_angle_deg;
    let (self_intersecting, self_intersecting_input) = rayon::join(|| count_self_intersecting_faces(remeshed), || original_crossing.unwrap_or_else(|| count_self_intersecting_faces(original)));
    RemeshMetrics {
        faces: remeshed.n_faces(),
        vertices: remeshed.n_vertices(),
        d_face,
        d_face_relative,
        d_surface_vertex: d_vertex,
        d_surface_vertex_relative: d_vertex / diag,
        d_surface_sampled: d_sampled,
        d_surface_sampled_relative: d_sampled / diag,
        min_angle_deg: if min_angle.is_finite() { min_angle } else { 0.0 },
        zero_area_faces: zero_area_faces(remeshed, DEFAULT_ZERO_AREA_REL_TOL).len(),
        mean_min_angle_deg: angles.mean_min_angle_deg,
        share_faces_angle_below_30: angles.share_below_30,
        max_angle_deg: angles.max_angle_deg,
        share_interior_valence_6: interior_valence6_share(remeshed),
        self_intersecting_faces: self_intersecting,
        self_intersecting_faces_input: self_intersecting_input,
        hausdorff_distance: hausdorff,
        hausdorff_distance_relative: hausdorff / diag,
    }
}
