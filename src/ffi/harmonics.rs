//! The adaptive harmonics entry point and its options.

use std::ffi::{c_char, c_void};

use super::handle::{capmesh_v1_mesh, clear_optional_out, clear_out, json_string};
use super::options::{capmesh_v1_param_options, capmesh_v1_param_options_default, param_options};
use super::progress::{capmesh_v1_progress_fn, CallbackProgress};
use super::status::{capmesh_v1_status, guard, Failure};
use super::view::{capmesh_v1_mesh_view, read_view};
use crate::harmonics::pipeline::DEFAULT_ORDER;
use crate::harmonics::{analyze, BasisKind, CapBoundary, HarmonicsOptions};

/// `capmesh_v1_harmonics_options.basis`: the paper's adaptive harmonics (default).
pub const CAPMESH_V1_BASIS_AH: i32 = 0;
/// `capmesh_v1_harmonics_options.basis`: spherical cap harmonics (keep an open surface's
/// boundary loop), with the rim condition `boundary`.
pub const CAPMESH_V1_BASIS_SCHA: i32 = 1;

/// `capmesh_v1_harmonics_options.boundary`: Neumann rim condition (default).
pub const CAPMESH_V1_BOUNDARY_NEUMANN: i32 = 0;
/// `capmesh_v1_harmonics_options.boundary`: Dirichlet rim condition.
pub const CAPMESH_V1_BOUNDARY_DIRICHLET: i32 = 1;
/// `capmesh_v1_harmonics_options.boundary`: Haines' mixed set.
pub const CAPMESH_V1_BOUNDARY_MIXED: i32 = 2;

/// Harmonics options. Start from `capmesh_v1_harmonics_options_default()`.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct capmesh_v1_harmonics_options {
    /// Largest order `N` of the fit (`(N + 1)^2` basis functions); the mesh needs at least
    /// that many vertices. Default 10.
    pub order: u32,
    /// Parameterization options (the planar disk domain is refused).
    pub param: capmesh_v1_param_options,
    /// One of `CAPMESH_V1_BASIS_*`. Default adaptive harmonics (0).
    pub basis: i32,
    /// One of `CAPMESH_V1_BOUNDARY_*`, used with `CAPMESH_V1_BASIS_SCHA`. Default Neumann (0).
    pub boundary: i32,
    /// 0 (default): the reconstruction has the input's connectivity. Otherwise it is a uniform
    /// cap mesh of about this many faces (a smooth remesh of the representation).
    pub resample_faces: u32,
}

/// The defaults documented on each field.
#[no_mangle]
pub extern "C" fn capmesh_v1_harmonics_options_default() -> capmesh_v1_harmonics_options {
    capmesh_v1_harmonics_options {
        order: DEFAULT_ORDER as u32,
        param: capmesh_v1_param_options_default(),
        basis: CAPMESH_V1_BASIS_AH,
        boundary: CAPMESH_V1_BOUNDARY_NEUMANN,
        resample_faces: 0,
    }
}

fn harmonics_options(o: &capmesh_v1_harmonics_options) -> Result<HarmonicsOptions, Failure> {
    let boundary = match o.boundary {
        CAPMESH_V1_BOUNDARY_NEUMANN => CapBoundary::Neumann,
        CAPMESH_V1_BOUNDARY_DIRICHLET => CapBoundary::Dirichlet,
        CAPMESH_V1_BOUNDARY_MIXED => CapBoundary::Mixed,
        b => return Err(Failure::invalid_argument(format!("boundary = {b} is not 0 (Neumann), 1 (Dirichlet) or 2 (mixed)"))),
    };
    let basis = match o.basis {
        CAPMESH_V1_BASIS_AH => BasisKind::Adaptive,
        CAPMESH_V1_BASIS_SCHA => BasisKind::SphericalCap(boundary),
        b => return Err(Failure::invalid_argument(format!("basis = {b} is not 0 (adaptive harmonics) or 1 (spherical cap harmonics)"))),
    };
    Ok(HarmonicsOptions::default()
        .with_order(o.order as usize)
        .with_param(param_options(&o.param)?)
        .with_basis(basis)
        .with_resample_faces((o.resample_faces > 0).then_some(o.resample_faces as usize)))
}

/// Parameterize `mesh` onto its cap, fit it with the harmonics `options->basis` of every order
/// up to `options->order` (NULL: defaults) and reconstruct it. On success `*out_reconstructed`
/// is the input connectivity at the order-N positions (or, with `options->resample_faces > 0`,
/// a uniform cap mesh of about that many faces on the order-N surface) and `*out_report_json`
/// (unless NULL) the JSON report (`basis`, `z_star`, `order`, `errors_by_order` with mean/max
/// errors per order, `boundary_max_relative`, `aspect_ratio`, `singular_values`, `param`,
/// `seconds`, ...).
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
        let mesh = output.resampled.as_ref().unwrap_or(&output.reconstructed);
        unsafe { *out_reconstructed = capmesh_v1_mesh::from_trimesh(mesh).into_raw() };
        Ok(())
    })
}
