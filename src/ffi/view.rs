//! Mesh views: the caller's arrays, borrowed for the duration of one call, checked and copied
//! into a [`TriMesh`].

use super::status::{capmesh_v1_status, Failure};
use crate::mesh::TriMesh;

/// A triangle mesh owned by the caller, read during one call.
///
/// `positions` holds `3 * vertex_count` doubles (x, y, z per vertex); `triangles` holds
/// `3 * face_count` vertex indices, counter-clockwise seen from outside.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct capmesh_v1_mesh_view {
    /// `3 * vertex_count` coordinates.
    pub positions: *const f64,
    /// Number of vertices.
    pub vertex_count: usize,
    /// `3 * face_count` vertex indices.
    pub triangles: *const u32,
    /// Number of triangles.
    pub face_count: usize,
}

/// Largest vertex count: indices are 32-bit.
const MAX_VERTICES: usize = u32::MAX as usize;

fn invalid_mesh(message: String) -> Failure {
    Failure::new(capmesh_v1_status::CAPMESH_V1_INVALID_MESH, message)
}

/// Check `view` (named `what` in messages) and copy it into a [`TriMesh`].
///
/// NULL view or arrays, counts whose byte size overflows and counts above `u32::MAX` are
/// invalid arguments; no vertices or faces, indices `>= vertex_count` and non-finite
/// coordinates make an invalid mesh. Topology is left to the library's validation.
///
/// # Safety
/// `view`, when not NULL, must point to a valid view whose arrays hold at least the counted
/// elements.
pub(crate) unsafe fn read_view(view: *const capmesh_v1_mesh_view, what: &str) -> Result<TriMesh, Failure> {
    // SAFETY: the caller guarantees `view` is NULL or valid.
    let view = unsafe { view.as_ref() }.ok_or_else(|| Failure::invalid_argument(format!("{what}: the mesh view pointer is NULL")))?;
    let (nv, nf) = (view.vertex_count, view.face_count);
    if nv > MAX_VERTICES {
        return Err(Failure::invalid_argument(format!("{what}: vertex_count {nv} exceeds the 32-bit index range")));
    }
    let byte_limit = isize::MAX as usize;
    if nv.checked_mul(3 * 8).map_or(true, |b| b > byte_limit) || nf.checked_mul(3 * 4).map_or(true, |b| b > byte_limit) {
        return Err(Failure::invalid_argument(format!("{what}: face_count {nf} is too large (the arrays cannot exist)")));
    }
    if nv > 0 && view.positions.is_null() {
        return Err(Failure::invalid_argument(format!("{what}: positions is NULL but vertex_count is {nv}")));
    }
    if nf > 0 && view.triangles.is_null() {
        return Err(Failure::invalid_argument(format!("{what}: triangles is NULL but face_count is {nf}")));
    }
    if nv == 0 || nf == 0 {
        return Err(invalid_mesh(format!(
            "{what}: the mesh is empty ({nv} vertices, {nf} faces); pass triangles, not a point cloud"
        )));
    }
    if (view.positions as usize) % std::mem::align_of::<f64>() != 0 || (view.triangles as usize) % std::mem::align_of::<u32>() != 0 {
        return Err(Failure::invalid_argument(format!("{what}: positions or triangles is not properly aligned")));
    }
    // SAFETY: non-NULL, aligned, and the caller guarantees the counted elements exist.
    let positions = unsafe { std::slice::from_raw_parts(view.positions, 3 * nv) };
    let triangles = unsafe { std::slice::from_raw_parts(view.triangles, 3 * nf) };
    let vertices: Vec<[f64; 3]> = positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    if let Some(v) = vertices.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(invalid_mesh(format!("{what}: vertex {v} has a non-finite coordinate (NaN or infinity)")));
    }
    let faces: Vec<[u32; 3]> = triangles.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    for (f, face) in faces.iter().enumerate() {
        if let Some(&i) = face.iter().find(|&&i| i as usize >= nv) {
            return Err(invalid_mesh(format!(
                "{what}: triangle {f} refers to vertex {i}, but vertex_count is {nv} (valid indices 0..{nv}); \
                 check the counts and the index base (indices are 0-based)"
            )));
        }
    }
    Ok(TriMesh::new(vertices, faces))
}
