//! # capmesh
//!
//! Adaptive area-preserving parameterization of open and closed anatomical surfaces onto a
//! spherical cap `Z >= Z*` (Choi, Giri and Kumar), with remeshing through the cap and adaptive
//! harmonics.
//!
//! The pipeline, one typed stage after another (each a pure function; solvers that keep
//! factorizations between calls are objects):
//!
//! ```text
//! io::read_mesh -> TriMesh -> mesh::validate -> SurfaceKind + Topology
//!   -> flatten   : disk conformal map g            (paper Sec. 3.1.1)
//!   -> omt       : h_r on the disk of radius r     (Sec. 2.2, 3.1.2)
//!   -> cap       : r* by Brent's method, phi^-1    (Sec. 3.1.2-3.1.3, Eq. 12-14)
//!   -> metrics   : d_area, d_angle, |mu|           (Sec. 4.1)
//!   -> harmonics : adaptive harmonics fit, reconstruction, N = 1 aspect ratio (Sec. 3.3)
//! ```
//!
//! ```no_run
//! use capmesh::{parameterize, read_mesh, NoProgress, ParamOptions};
//! let mesh = read_mesh(std::path::Path::new("tests/data/open_face_choi.obj.gz"))?;
//! let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress)?;
//! println!("Z* = {:?}, mean |d_area| = {}", map.report.z_star, map.report.area_distortion.mean_abs);
//! # Ok::<(), capmesh::Error>(())
//! ```

// `!(x > 0.0)` is how this crate says "not positive, or NaN": the negated comparisons reject
// NaN on purpose, which the `partial_cmp` spelling clippy suggests would hide.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// The numerical kernels index several arrays by the same vertex or coordinate number.
#![allow(clippy::needless_range_loop)]

pub mod cap;
pub(crate) mod error;
#[cfg(feature = "capi")]
pub mod ffi;
pub mod flatten;
#[cfg(feature = "figures")]
pub mod figures;
pub mod harmonics;
pub mod io;
pub mod linalg;
pub mod mesh;
pub(crate) mod named;
pub mod metrics;
pub mod omt;
pub mod param;
#[cfg(feature = "openmesh")]
pub mod openmesh;
mod pool;
pub mod progress;
pub mod refine;
pub mod remesh;

// The entry points and their options and reports, flat at the root.
pub use cap::{CapMap, Domain, InverseMap, InverseMapError, InverseOptions, SurfacePoint};
pub use error::{Error, Result};
pub use harmonics::{analyze, HarmonicsOptions, HarmonicsOutput, HarmonicsReport};
pub use io::{
    read_mesh, read_ply_with_vertex_attributes, read_vertex_attributes, write_mesh, AttributeData,
    ReadError, VertexAttribute, WriteError,
};
pub use mesh::TriMesh;
pub use param::{parameterize, ClosedOptions, MapQuality, OpenOptions, ParamOptions, ParamReport, RefinementOptions, SearchOptions};
pub use progress::{NoProgress, Progress, Stage};
pub use remesh::shape::{Creases, ShapeOptions, ShapeReport};
pub use remesh::sizing::Sizing;
pub use remesh::transfer::carry_attribute;
pub use remesh::{remesh, remesh_located, CapGrid, FitReport, Holes, Optimize, Pieces, Placement, RemeshOptions, RemeshReport};

/// The README's examples, compiled as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
