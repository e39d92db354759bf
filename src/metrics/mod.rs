//! Distortion and remeshing metrics, shared by the pipeline reports, the CLI, the tests and
//! the benchmarks.

pub mod angles;
pub mod closest;
pub(crate) mod distortion;
pub(crate) mod hausdorff;
pub(crate) mod remeshing;
pub(crate) mod sampling;
pub(crate) mod self_intersection;
pub(crate) mod tri_tri;
pub(crate) mod valence;

pub use distortion::{angle_distortion, area_distortion, beltrami_abs, conformal_energy, conformal_energy_surface_weighted, Stats};
pub use remeshing::{face_area_deviation, remesh_metrics, RemeshMetrics};
pub use self_intersection::{count_self_intersecting_faces, self_intersecting_faces};
