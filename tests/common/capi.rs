//! Calling the C ABI (feature `capi`) from a test as C would: a mesh as the flat arrays a view
//! points into, and the last error message.

use std::ffi::CStr;

use capmesh::ffi::{capmesh_v1_last_error, capmesh_v1_mesh_view};
use capmesh::TriMesh;

/// Flat arrays kept alive while a view points into them.
pub struct Arrays {
    pub positions: Vec<f64>,
    pub triangles: Vec<u32>,
}

impl Arrays {
    /// The arrays of `mesh`.
    pub fn of(mesh: &TriMesh) -> Self {
        Self {
            positions: mesh.vertices.iter().flatten().copied().collect(),
            triangles: mesh.faces.iter().flatten().copied().collect(),
        }
    }
    /// A view into the arrays.
    pub fn view(&self) -> capmesh_v1_mesh_view {
        capmesh_v1_mesh_view {
            positions: self.positions.as_ptr(),
            vertex_count: self.positions.len() / 3,
            triangles: self.triangles.as_ptr(),
            face_count: self.triangles.len() / 3,
        }
    }
}

/// The message of the calling thread's last failed call.
pub fn last_error() -> String {
    unsafe { CStr::from_ptr(capmesh_v1_last_error()) }.to_string_lossy().into_owned()
}
