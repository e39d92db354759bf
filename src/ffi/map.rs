//! The cap map as a handle (issue 31): parameterize once with `capmesh_v1_parameterize_map`,
//! then ask where cap points lie on the surface (`capmesh_v1_map_inverse`, the inverse map
//! `f^-1` of the paper's Sec. 4.2, [`crate::InverseMap`]) and which cap point a surface point
//! maps to (`capmesh_v1_map_forward`). The handle owns the map, a copy of the input mesh and
//! the point location, built once.

use std::ffi::{c_char, c_void};

use super::handle::{clear_optional_out, clear_out, json_string};
use super::options::{capmesh_v1_param_options, capmesh_v1_param_options_default, param_options};
use super::progress::{capmesh_v1_progress_fn, CallbackProgress};
use super::status::{capmesh_v1_status, guard, Failure};
use super::view::{capmesh_v1_mesh_view, read_view};
use crate::cap::{InverseMap, InverseOptions};
use crate::param::parameterize;

/// `out_located[i]` of `capmesh_v1_map_inverse`: point `i` lies on the cap and its surface
/// point was written.
pub const CAPMESH_V1_POINT_LOCATED: i32 = 0;
/// `out_located[i]` of `capmesh_v1_map_inverse`: point `i` is off the cap (off the unit
/// sphere or below `Z*` by more than 1e-9, outside the planar disk domain, or not finite); its
/// outputs are NaN and face `CAPMESH_V1_NO_FACE`.
pub const CAPMESH_V1_POINT_OFF_CAP: i32 = 1;
/// The face written for a point off the cap.
pub const CAPMESH_V1_NO_FACE: u32 = u32::MAX;

/// A surface mapped onto its cap, with the inverse map's point location. Opaque; made by
/// `capmesh_v1_parameterize_map`, released with `capmesh_v1_map_free`.
#[allow(non_camel_case_types)]
pub struct capmesh_v1_map {
    inverse: InverseMap<'static>,
    /// `CapMap::uv`, flattened.
    uv: Vec<f64>,
}

/// Parameterize `mesh` as `capmesh_v1_parameterize` does and keep the map as a handle. On
/// success `*out_map` is the map, freed with `capmesh_v1_map_free`, and `*out_report_json`
/// (unless NULL) the parameterization's JSON report. On failure both are NULL.
///
/// # Safety
/// As `capmesh_v1_parameterize`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_parameterize_map(
    mesh: *const capmesh_v1_mesh_view,
    options: *const capmesh_v1_param_options,
    progress: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    out_map: *mut *mut capmesh_v1_map,
    out_report_json: *mut *mut c_char,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        unsafe { clear_optional_out(out_report_json) };
        unsafe { clear_out(out_map, "out_map") }?;
        let input = unsafe { read_view(mesh, "mesh") }?;
        let options = match unsafe { options.as_ref() } {
            Some(o) => param_options(o)?,
            None => param_options(&capmesh_v1_param_options_default())?,
        };
        let progress = CallbackProgress::new(progress, user_data);
        let map = parameterize(&input, &options, &progress)?;
        let report = if out_report_json.is_null() { None } else { Some(json_string(&map.report)?) };
        let uv = map.uv().into_iter().flatten().collect();
        let inverse = map
            .into_inverse(input, InverseOptions::default())
            .map_err(|e| Failure::new(capmesh_v1_status::CAPMESH_V1_INVALID_MESH, format!("mesh: {e}")))?;
        if let Some(text) = report {
            unsafe { *out_report_json = text };
        }
        unsafe { *out_map = Box::into_raw(Box::new(capmesh_v1_map { inverse, uv })) };
        Ok(())
    })
}

/// Number of vertices of the mapped mesh (0 for NULL): the length of the cap positions and
/// texture coordinates.
///
/// # Safety
/// `map` is NULL or a handle returned by `capmesh_v1_parameterize_map` and not yet released
/// (the same holds for every function below).
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_vertex_count(map: *const capmesh_v1_map) -> usize {
    // SAFETY: by the contract above.
    unsafe { map.as_ref() }.map_or(0, |m| m.inverse.mesh().n_vertices())
}

/// Number of triangles of the mapped mesh (0 for NULL): faces of `capmesh_v1_map_inverse`'s
/// and `capmesh_v1_map_forward`'s results index them, in the input's order.
///
/// # Safety
/// As for `capmesh_v1_map_vertex_count`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_face_count(map: *const capmesh_v1_map) -> usize {
    // SAFETY: as above.
    unsafe { map.as_ref() }.map_or(0, |m| m.inverse.mesh().n_faces())
}

/// `3 * vertex_count` coordinates of the input vertices on the cap (on the unit sphere,
/// `Z >= Z*`; `(x, y, 0)` for the planar disk domain), owned by `map` (NULL for NULL).
///
/// # Safety
/// As for `capmesh_v1_map_vertex_count`; the pointer is valid until the map is released.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_cap_positions(map: *const capmesh_v1_map) -> *const f64 {
    // SAFETY: as above; `[f64; 3]` elements are contiguous doubles.
    unsafe { map.as_ref() }.map_or(std::ptr::null(), |m| m.inverse.map().cap.as_ptr().cast())
}

/// `2 * vertex_count` texture coordinates (u, v per input vertex): the map's planar disk
/// scaled into `[0, 1]^2`, as written by the CLI's `param --uv`. Owned by `map` (NULL for
/// NULL).
///
/// # Safety
/// As for `capmesh_v1_map_vertex_count`; the pointer is valid until the map is released.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_uv(map: *const capmesh_v1_map) -> *const f64 {
    // SAFETY: as above.
    unsafe { map.as_ref() }.map_or(std::ptr::null(), |m| m.uv.as_ptr())
}

/// Check that `count` elements of `width` values of `size` bytes each can exist.
fn check_count(count: usize, width: usize, size: usize, what: &str) -> Result<(), Failure> {
    match count.checked_mul(width * size) {
        Some(bytes) if bytes <= isize::MAX as usize => Ok(()),
        _ => Err(Failure::invalid_argument(format!("count {count} is too large (the {what} array cannot exist)"))),
    }
}

/// A caller's array of `len` elements as a slice: NULL is an error naming `name` when
/// `len > 0`; misaligned pointers are refused.
///
/// # Safety
/// `ptr`, when not NULL, must point to `len` readable elements.
unsafe fn input_slice<'a, T>(ptr: *const T, len: usize, name: &str) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(Failure::invalid_argument(format!("{name} is NULL but count is not 0")));
    }
    if (ptr as usize) % std::mem::align_of::<T>() != 0 {
        return Err(Failure::invalid_argument(format!("{name} is not properly aligned")));
    }
    // SAFETY: non-NULL, aligned, `len` elements by the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// A caller's output array of `len` elements, `None` for NULL (not wanted).
///
/// # Safety
/// `ptr`, when not NULL, must point to `len` writable elements not aliasing the inputs.
unsafe fn output_slice<'a, T>(ptr: *mut T, len: usize, name: &str) -> Result<Option<&'a mut [T]>, Failure> {
    if ptr.is_null() || len == 0 {
        return Ok(None);
    }
    if (ptr as usize) % std::mem::align_of::<T>() != 0 {
        return Err(Failure::invalid_argument(format!("{name} is not properly aligned")));
    }
    // SAFETY: as documented.
    Ok(Some(unsafe { std::slice::from_raw_parts_mut(ptr, len) }))
}

/// The map handle or an error naming it.
///
/// # Safety
/// As for `capmesh_v1_map_vertex_count`.
unsafe fn map_ref<'a>(map: *const capmesh_v1_map) -> Result<&'a capmesh_v1_map, Failure> {
    // SAFETY: by the caller's contract.
    unsafe { map.as_ref() }
        .ok_or_else(|| Failure::invalid_argument("map is NULL: pass a handle from capmesh_v1_parameterize_map"))
}

/// The inverse map of `count` cap points `cap_points` (`3 * count` doubles, x, y, z each):
/// for each point, `out_located[i]` is `CAPMESH_V1_POINT_LOCATED` or `CAPMESH_V1_POINT_OFF_CAP`
/// (never guessed: such a point gets NaN and `CAPMESH_V1_NO_FACE`). For a located point,
/// `out_positions` gets its surface position (3 doubles), `out_faces` the input triangle
/// holding it and `out_barycentrics` the weights of that triangle's three corners (in its
/// order; non-negative, sum 1). `out_located` is required (`count` int32s); the other outputs
/// may be NULL when not wanted (`3 * count`, `count` and `3 * count` elements). A closed
/// surface's cap has a flat bottom disk `Z = Z*`, whose points are located too. `*out_count`,
/// unless `out_count` is NULL, gets the number of located points. `count` 0 does nothing.
///
/// # Safety
/// `map` as for `capmesh_v1_map_vertex_count`; every non-NULL array must hold the counted
/// elements and the outputs must not overlap the input.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_inverse(
    map: *const capmesh_v1_map,
    cap_points: *const f64,
    count: usize,
    out_positions: *mut f64,
    out_faces: *mut u32,
    out_barycentrics: *mut f64,
    out_located: *mut i32,
    out_count: *mut usize,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        let map = unsafe { map_ref(map) }?;
        check_count(count, 3, std::mem::size_of::<f64>(), "cap_points")?;
        if count > 0 && out_located.is_null() {
            return Err(Failure::invalid_argument(
                "out_located is NULL: pass an array of count int32 to receive each point's status",
            ));
        }
        let points = unsafe { input_slice(cap_points, 3 * count, "cap_points") }?;
        let located = unsafe { output_slice(out_located, count, "out_located") }?;
        let positions = unsafe { output_slice(out_positions, 3 * count, "out_positions") }?;
        let faces = unsafe { output_slice(out_faces, count, "out_faces") }?;
        let barycentrics = unsafe { output_slice(out_barycentrics, 3 * count, "out_barycentrics") }?;
        let points: Vec<[f64; 3]> = points.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        let found = map.inverse.locate_all(&points);
        let mut n = 0usize;
        let (mut located, mut positions, mut faces, mut barycentrics) = (located, positions, faces, barycentrics);
        for (i, point) in found.iter().enumerate() {
            let (status, position, face, bary) = match point {
                Some(p) => {
                    n += 1;
                    (CAPMESH_V1_POINT_LOCATED, p.position, p.face as u32, p.barycentric)
                }
                None => (CAPMESH_V1_POINT_OFF_CAP, [f64::NAN; 3], CAPMESH_V1_NO_FACE, [f64::NAN; 3]),
            };
            if let Some(out) = located.as_deref_mut() {
                out[i] = status;
            }
            if let Some(out) = positions.as_deref_mut() {
                out[3 * i..3 * i + 3].copy_from_slice(&position);
            }
            if let Some(out) = faces.as_deref_mut() {
                out[i] = face;
            }
            if let Some(out) = barycentrics.as_deref_mut() {
                out[3 * i..3 * i + 3].copy_from_slice(&bary);
            }
        }
        if !out_count.is_null() {
            unsafe { *out_count = n };
        }
        Ok(())
    })
}

/// The forward map of `count` surface points, each an input triangle `faces[i]` and the
/// weights `barycentrics[3i..3i+3]` of its corners (finite, >= 0, summing to 1): their cap
/// points in `out_cap_points` (`3 * count` doubles; on the flat bottom `Z = Z*` for a closed
/// surface's punctured quad). A face out of range or weights that are not a point of the
/// triangle fail the call with `CAPMESH_V1_INVALID_ARGUMENT` naming the point; nothing is
/// written then. `count` 0 does nothing.
///
/// # Safety
/// `map` as for `capmesh_v1_map_vertex_count`; every non-NULL array must hold the counted
/// elements and the output must not overlap the inputs.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_forward(
    map: *const capmesh_v1_map,
    faces: *const u32,
    barycentrics: *const f64,
    count: usize,
    out_cap_points: *mut f64,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        let map = unsafe { map_ref(map) }?;
        check_count(count, 3, std::mem::size_of::<f64>(), "barycentrics")?;
        if count > 0 && out_cap_points.is_null() {
            return Err(Failure::invalid_argument("out_cap_points is NULL: pass an array of 3 * count doubles"));
        }
        let faces = unsafe { input_slice(faces, count, "faces") }?;
        let weights = unsafe { input_slice(barycentrics, 3 * count, "barycentrics") }?;
        let mut cap = Vec::with_capacity(3 * count);
        for (i, (&face, w)) in faces.iter().zip(weights.chunks_exact(3)).enumerate() {
            let p = map
                .inverse
                .cap_point(face as usize, [w[0], w[1], w[2]])
                .map_err(|e| Failure::invalid_argument(format!("surface point {i}: {e}")))?;
            cap.extend_from_slice(&p);
        }
        if let Some(out) = unsafe { output_slice(out_cap_points, 3 * count, "out_cap_points") }? {
            out.copy_from_slice(&cap);
        }
        Ok(())
    })
}

/// Release a map. NULL is accepted and ignored.
///
/// # Safety
/// `map` is NULL or a handle returned by `capmesh_v1_parameterize_map`, released at most once.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_map_free(map: *mut capmesh_v1_map) {
    if !map.is_null() {
        // SAFETY: a non-NULL handle came from `Box::into_raw` and is freed once, by contract.
        drop(unsafe { Box::from_raw(map) });
    }
}
