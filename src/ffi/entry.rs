//! The entry points: parameterize, remesh, metrics.

use std::ffi::{c_char, c_void};

use super::handle::{capmesh_v1_mesh, clear_optional_out, clear_out, json_string};
use super::options::{capmesh_v1_param_options, capmesh_v1_param_options_default, capmesh_v1_remesh_options, param_options, remesh_options};
use super::progress::{capmesh_v1_progress_fn, CallbackProgress};
use super::status::{guard, capmesh_v1_status, Failure};
use super::view::{capmesh_v1_mesh_view, read_view};
use crate::param::parameterize;
use crate::metrics::remesh_metrics;
use crate::remesh::{remesh, remesh_located};

/// Write the optional report string.
///
/// # Safety
/// `out`, when not NULL, must be valid for writes.
unsafe fn write_report(out: *mut *mut c_char, report: &impl serde::Serialize) -> Result<(), Failure> {
    if !out.is_null() {
        let text = json_string(report)?;
        // SAFETY: non-NULL and writable by contract.
        unsafe { *out = text };
    }
    Ok(())
}

/// Parameterize `mesh` (an open disk or a closed genus-0 surface) onto the cap of `options`
/// (NULL: defaults). On success `*out_cap` is the input connectivity with the vertices moved
/// onto the unit sphere (`Z >= Z*`; `(x, y, 0)` for the planar disk domain), freed with
/// `capmesh_v1_mesh_free`, and `*out_report_json`, unless `out_report_json` is NULL, the JSON
/// report (`z_star`, `r_star`, `area_distortion`, `angle_distortion`, ...), freed with
/// `capmesh_v1_string_free`. On failure both are NULL.
///
/// # Safety
/// Every non-NULL pointer must be valid as documented on its type; `progress` must be safe to
/// call with `user_data` for the duration of the call.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_parameterize(
    mesh: *const capmesh_v1_mesh_view,
    options: *const capmesh_v1_param_options,
    progress: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    out_cap: *mut *mut capmesh_v1_mesh,
    out_report_json: *mut *mut c_char,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        unsafe { clear_optional_out(out_report_json) };
        unsafe { clear_out(out_cap, "out_cap") }?;
        let input = unsafe { read_view(mesh, "mesh") }?;
        let options = match unsafe { options.as_ref() } {
            Some(o) => param_options(o)?,
            None => param_options(&capmesh_v1_param_options_default())?,
        };
        let progress = CallbackProgress::new(progress, user_data);
        let map = parameterize(&input, &options, &progress)?;
        unsafe { write_report(out_report_json, &map.report) }?;
        unsafe { *out_cap = capmesh_v1_mesh::from_trimesh(&map.cap_mesh(&input)).into_raw() };
        Ok(())
    })
}

/// Remesh `mesh` through its cap: a uniform or latitude/longitude cap mesh pulled back onto the
/// surface (an open disk gives an open disk, a closed genus-0 surface a closed genus-0 mesh;
/// the pulled-back areas are equalized with the library's default sweeps). `options` NULL
/// means defaults (uniform, 5000 faces). On success `*out_mesh` is the new mesh and
/// `*out_report_json` (unless NULL) the JSON report (`param`, `area_equalization`, `quality`
/// with `faces`, `d_face_relative`, `d_surface_sampled_relative`, ..., `seconds`).
///
/// # Safety
/// As `capmesh_v1_parameterize`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_remesh(
    mesh: *const capmesh_v1_mesh_view,
    options: *const capmesh_v1_remesh_options,
    progress: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    out_mesh: *mut *mut capmesh_v1_mesh,
    out_report_json: *mut *mut c_char,
) -> capmesh_v1_status {
    unsafe { remesh_entry(mesh, options, progress, user_data, out_mesh, out_report_json, false) }
}

/// `capmesh_v1_remesh`, also recording where each new vertex lies on the input: the mesh's
/// `capmesh_v1_mesh_source_faces` and `capmesh_v1_mesh_source_barycentrics` give each vertex's
/// input triangle and the weights of its corners (through the inverse map), with which per-vertex
/// data of the input (colour, quality, thickness...) can be interpolated onto the remesh.
///
/// # Safety
/// As `capmesh_v1_parameterize`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_remesh_located(
    mesh: *const capmesh_v1_mesh_view,
    options: *const capmesh_v1_remesh_options,
    progress: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    out_mesh: *mut *mut capmesh_v1_mesh,
    out_report_json: *mut *mut c_char,
) -> capmesh_v1_status {
    unsafe { remesh_entry(mesh, options, progress, user_data, out_mesh, out_report_json, true) }
}

/// `capmesh_v1_remesh` and, when `located`, `capmesh_v1_remesh_located` (the new mesh also
/// carries each vertex's input triangle and barycentric weights).
///
/// # Safety
/// As `capmesh_v1_parameterize`.
unsafe fn remesh_entry(
    mesh: *const capmesh_v1_mesh_view,
    options: *const capmesh_v1_remesh_options,
    progress: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    out_mesh: *mut *mut capmesh_v1_mesh,
    out_report_json: *mut *mut c_char,
    located: bool,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        unsafe { clear_optional_out(out_report_json) };
        unsafe { clear_out(out_mesh, "out_mesh") }?;
        let input = unsafe { read_view(mesh, "mesh") }?;
        let options = match unsafe { options.as_ref() } {
            Some(o) => remesh_options(o)?,
            None => remesh_options(&super::options::capmesh_v1_remesh_options_default())?,
        };
        let progress = CallbackProgress::new(progress, user_data);
        let (out, report, points) = if located {
            remesh_located(&input, &options, &progress)?
        } else {
            let (out, report) = remesh(&input, &options, &progress)?;
            (out, report, Vec::new())
        };
        if located && points.len() != out.n_vertices() {
            return Err(Failure::new(
                capmesh_v1_status::CAPMESH_V1_INTERNAL,
                format!("the remesh located {} of its {} vertices", points.len(), out.n_vertices()),
            ));
        }
        unsafe { write_report(out_report_json, &report) }?;
        let out = capmesh_v1_mesh::from_trimesh(&out);
        let out = if located { out.with_sources(&points) } else { out };
        unsafe { *out_mesh = out.into_raw() };
        Ok(())
    })
}

/// Remeshing quality of `remeshed` against `original` (any two triangle meshes): the JSON
/// object has `faces`, `vertices`, `d_face`, `d_face_relative`, `d_surface_vertex(_relative)`,
/// `d_surface_sampled(_relative)`, `min_angle_deg`, `zero_area_faces`, `mean_min_angle_deg`,
/// `share_faces_angle_below_30`, `max_angle_deg`, `share_interior_valence_6`,
/// `self_intersecting_faces(_input)` and `hausdorff_distance(_relative)`. `out_report_json`
/// must not be NULL.
///
/// # Safety
/// As `capmesh_v1_parameterize`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_metrics(
    original: *const capmesh_v1_mesh_view,
    remeshed: *const capmesh_v1_mesh_view,
    out_report_json: *mut *mut c_char,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        unsafe { clear_out(out_report_json, "out_report_json") }?;
        let a = unsafe { read_view(original, "original") }?;
        let b = unsafe { read_view(remeshed, "remeshed") }?;
        let metrics = remesh_metrics(&a, &b);
        unsafe { write_report(out_report_json, &metrics) }?;
        Ok(())
    })
}
