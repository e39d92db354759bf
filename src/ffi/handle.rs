//! Result meshes handed to the caller as opaque handles, and the JSON report strings.

use std::ffi::{c_char, CString};

use super::status::Failure;
use crate::cap::SurfacePoint;
use crate::mesh::TriMesh;

/// A mesh produced by capmesh. Opaque; read it with the `capmesh_v1_mesh_*` accessors and
/// release it with `capmesh_v1_mesh_free`.
#[allow(non_camel_case_types)]
pub struct capmesh_v1_mesh {
    positions: Vec<f64>,
    triangles: Vec<u32>,
    /// Per vertex, its input face and barycentric weights (`capmesh_v1_remesh_located`).
    sources: Option<(Vec<u32>, Vec<f64>)>,
}

impl capmesh_v1_mesh {
    pub(crate) fn from_trimesh(mesh: &TriMesh) -> Self {
        Self {
            positions: mesh.vertices.iter().flatten().copied().collect(),
            triangles: mesh.faces.iter().flatten().copied().collect(),
            sources: None,
        }
    }

    /// With each vertex's point of the input surface (one per vertex of the mesh).
    pub(crate) fn with_sources(mut self, points: &[SurfacePoint]) -> Self {
        let faces = points.iter().map(|p| p.face as u32).collect();
        let weights = points.iter().flat_map(|p| p.barycentric).collect();
        self.sources = Some((faces, weights));
        self
    }

    pub(crate) fn into_raw(self) -> *mut capmesh_v1_mesh {
        Box::into_raw(Box::new(self))
    }
}

/// Number of vertices of `mesh` (0 for NULL).
///
/// # Safety
/// `mesh` is NULL or a handle returned by capmesh and not yet released with
/// `capmesh_v1_mesh_free` (the same holds for every accessor below).
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_vertex_count(mesh: *const capmesh_v1_mesh) -> usize {
    // SAFETY: by the contract above, a non-NULL handle came from `into_raw` and is alive.
    unsafe { mesh.as_ref() }.map_or(0, |m| m.positions.len() / 3)
}

/// Number of triangles of `mesh` (0 for NULL).
///
/// # Safety
/// As for `capmesh_v1_mesh_vertex_count`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_face_count(mesh: *const capmesh_v1_mesh) -> usize {
    // SAFETY: as above.
    unsafe { mesh.as_ref() }.map_or(0, |m| m.triangles.len() / 3)
}

/// `3 * vertex_count` coordinates (x, y, z per vertex), owned by `mesh` (NULL for NULL).
///
/// # Safety
/// As for `capmesh_v1_mesh_vertex_count`; the pointer is valid until the mesh is released.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_positions(mesh: *const capmesh_v1_mesh) -> *const f64 {
    // SAFETY: as above.
    unsafe { mesh.as_ref() }.map_or(std::ptr::null(), |m| m.positions.as_ptr())
}

/// `3 * face_count` vertex indices, owned by `mesh` (NULL for NULL).
///
/// # Safety
/// As for `capmesh_v1_mesh_vertex_count`; the pointer is valid until the mesh is released.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_triangles(mesh: *const capmesh_v1_mesh) -> *const u32 {
    // SAFETY: as above.
    unsafe { mesh.as_ref() }.map_or(std::ptr::null(), |m| m.triangles.as_ptr())
}

/// For a mesh from `capmesh_v1_remesh_located`: `vertex_count` input triangle indices, the
/// input face each vertex lies on (NULL for other meshes and for NULL).
///
/// # Safety
/// As for `capmesh_v1_mesh_vertex_count`; the pointer is valid until the mesh is released.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_source_faces(mesh: *const capmesh_v1_mesh) -> *const u32 {
    // SAFETY: as above.
    unsafe { mesh.as_ref() }.and_then(|m| m.sources.as_ref()).map_or(std::ptr::null(), |(f, _)| f.as_ptr())
}

/// For a mesh from `capmesh_v1_remesh_located`: `3 * vertex_count` barycentric weights, per
/// vertex those of the corners of its input face (`capmesh_v1_mesh_source_faces`), in the
/// input triangle's order (non-negative, sum 1). NULL for other meshes and for NULL.
///
/// # Safety
/// As for `capmesh_v1_mesh_vertex_count`; the pointer is valid until the mesh is released.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_source_barycentrics(mesh: *const capmesh_v1_mesh) -> *const f64 {
    // SAFETY: as above.
    unsafe { mesh.as_ref() }.and_then(|m| m.sources.as_ref()).map_or(std::ptr::null(), |(_, w)| w.as_ptr())
}

/// Release a mesh returned by capmesh. NULL is accepted and ignored.
///
/// # Safety
/// `mesh` is NULL or a handle returned by capmesh, released at most once.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_mesh_free(mesh: *mut capmesh_v1_mesh) {
    if !mesh.is_null() {
        // SAFETY: a non-NULL handle came from `into_raw` and is freed once, by contract.
        drop(unsafe { Box::from_raw(mesh) });
    }
}

/// Release a string returned by capmesh (a JSON report). NULL is accepted and ignored.
///
/// # Safety
/// `text` is NULL or a string returned by capmesh, released at most once.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_string_free(text: *mut c_char) {
    if !text.is_null() {
        // SAFETY: a non-NULL string came from `CString::into_raw` and is freed once, by contract.
        drop(unsafe { CString::from_raw(text) });
    }
}

/// Serialize `report` into a C string the caller frees with `capmesh_v1_string_free`.
pub(crate) fn json_string(report: &impl serde::Serialize) -> Result<*mut c_char, Failure> {
    let text = serde_json::to_string(report)
        .map_err(|e| Failure::new(super::status::capmesh_v1_status::CAPMESH_V1_INTERNAL, format!("report serialization: {e}")))?;
    // serde_json escapes control characters, so there is no interior NUL.
    let c = CString::new(text).map_err(|e| Failure::new(super::status::capmesh_v1_status::CAPMESH_V1_INTERNAL, e.to_string()))?;
    Ok(c.into_raw())
}

/// Check an output pointer and set it to NULL.
///
/// # Safety
/// `out`, when not NULL, must be valid for writes.
pub(crate) unsafe fn clear_out<T>(out: *mut *mut T, name: &str) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::invalid_argument(format!("{name} is NULL: pass the address of a pointer to receive the result")));
    }
    // SAFETY: non-NULL and valid for writes by the caller's contract.
    unsafe { *out = std::ptr::null_mut() };
    Ok(())
}

/// Clear an optional output pointer (NULL means "not wanted").
///
/// # Safety
/// As [`clear_out`].
pub(crate) unsafe fn clear_optional_out<T>(out: *mut *mut T) {
    if !out.is_null() {
        // SAFETY: as above.
        unsafe { *out = std::ptr::null_mut() };
    }
}
