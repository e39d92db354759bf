//! Triangle meshes: the [`TriMesh`] type, topology (edges, boundary loops, components, Euler
//! characteristic), geometry (areas, angles), validation and small repairs, and procedural
//! shapes used by tests and benchmarks.

pub(crate) mod checks;
pub(crate) mod error;
pub(crate) mod fasthash;
pub mod geometry;
pub mod holes;
pub(crate) mod decimate;
pub mod repair;
pub mod shapes;
pub mod short_edges;
pub(crate) mod split_long;
pub mod subdivide;
pub mod topology;
mod trimesh;
mod unionfind;
pub mod validate;

pub use error::MeshError;
pub use topology::Topology;
pub use trimesh::TriMesh;
pub use subdivide::subdivide_midpoint;
pub use validate::{inspect, validate, MeshSummary, SurfaceKind};
