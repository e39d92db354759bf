//! The adaptive harmonics entry point and its options.

use std::ffi::{c_char, c_void};

use super::handle::{capmesh_v1_mesh, clear_optional_out, clear_out, json_string};
use super::options::{capmesh_v1_param_options, capmesh_v1_param_options_default, param_options};
use super::progress::{capmesh_v1_progress_fn, CallbackProgress};
use super::status::{capmesh_v1_status, guard, Failure};
use super::view::{capmesh_v1_mesh_view, read_view};
use crate::harmonics::pipeline::DEFAULT_ORDER;
use crate::harmonics::{analyze, HarmonicsOptions};

/// Adaptive harmonics options. Start from `capmesh_v1_harmonics_options_default()`.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct capmesh_v1_harmonics_options {
    /// Largest order `N` of the fit (`(N + 1)^2` basis functions); the mesh needs at least
    /// that many vertices. Default 10.
    pub order: u32,
    /// Parameterization options (the planar disk domain is refused).
    pub param: capmesh_v1_param_options,
}

/// The defaults documented on each field.
#[no_mangle]
pub extern "C" fn capmesh_v1_harmonics_options_default() -> capmesh_v1_harmonics_options {
    capmesh_v1_harmonics_options { order: DEFAULT_ORDER as u32, param: capmesh_v1_param_options_default() }
}

fn harmonics_options(o: &capmesh_v1_harmonics_options) -> Result<HarmonicsOptions, Failure> {
    Ok(HarmonicsOptions { order: o.order as usize, param: param_options(&o.param)? })
}

/// Parameterize `mesh` onto its cap, fit it with the adaptive harmonics of every order up to
/// `options->order` (NULL: defaults) and reconstruct it. On success `*out_reconstructed` is the
/// input connectivity at the order-N positions and `*out_report_json` (unless NULL) the JSON
/// report (`z_star`, `order`, `errors_by_order` with mean/max errors per order,
/// `aspect_ratio`, `singular_values`, `param`, `seconds`, ...).
///
/// # Safety
/// As `capmesh_v1_parameterize`.
#[no_mangle]
pub unsafe extern "C" fn capmesh_v1_harmonics(
    mesh: *const capmesh_v1_mesh_view,
    options: *const capmesh_v1_harmonics_options,
    progress: capmesh_v1_progress_fn,
    user_data: *mut c_void,
    out_reconstructed: *mut *mut capmesh_v1_mesh,
    out_report_json: *mut *mut c_char,
) -> capmesh_v1_status {
    guard(|| {
        // SAFETY (all blocks below): pointers as documented by the caller's contract.
        unsafe { clear_optional_out(out_report_json) };
        unsafe { clear_out(out_reconstructed, "out_reconstructed") }?;
        let input = unsafe { read_view(mesh, "mesh") }?;
        let options = match unsafe { options.as_ref() } {
            Some(o) => harmonics_options(o)?,
            None => harmonics_options(&capmesh_v1_harmonics_options_default())?,
        };
        let progress = CallbackProgress::new(progress, user_data);
        let output = analyze(&input, &options, &progress)?;
        if !out_report_json.is_null() {
            let text = json_string(&output.report)?;
            unsafe { *out_report_json = text };
        }
        unsafe { *out_reconstructed = capmesh_v1_mesh::from_trimesh(&output.reconstructed).into_raw() };
        Ok(())
    })
}
