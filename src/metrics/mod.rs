//! Distortion and remeshing metrics, shared by the pipeline reports, the CLI, the tests and
//! the benchmarks.

pub mod distortion;

pub use distortion::{angle_distortion, area_distortion, beltrami_abs, conformal_energy, Stats};
