//! The adaptive harmonics pipeline: parameterize a surface onto its adaptive cap, fit it with the
//! adaptive harmonics of every order up to `N` (paper Eq. 26-28), reconstruct it, and measure the
//! reconstruction error per order and the paper's `N = 1` aspect ratio (Eq. 29).
//!
//! ```text
//! param::parameterize -> CapMap { cap, report.z_star }
//!   -> fit_with_errors_in (one design matrix, one QR)
//!        -> HarmonicFit at every order n <= N
//!        -> mean / max vertex distance per order n <= N
//!        -> the input's connectivity at the order-N positions
//!   -> aspect_ratio, order_one_ellipsoid -> sigma_1 / sigma_3 of the order-1 representation
//! ```
//!
//! The basis is [`HarmonicsOptions::basis`]: the paper's adaptive harmonics (default) or the
//! spherical cap harmonics ([`super::scha`]); with [`HarmonicsOptions::resample_faces`] the
//! order-`N` surface is also evaluated on a uniform cap mesh ([`super::resample`]).
//!
//! [`analyze`] does all of it; [`analyze_map`] starts from a parameterization already computed
//! (the CLI uses it to also write the cap positions, which the coefficients need to be
//! evaluated). Progress is reported with [`Stage::Harmonics`] after the parameterization's own
//! stages; a `Break` cancels with [`Error::Cancelled`].
//!
//! With the adaptive harmonics every `m > 0` basis function vanishes on the cap's boundary
//! circle `Z = Z*` (see [`super::basis`]), so in the reconstruction of an open surface the whole
//! boundary loop collapses to one point, at every order; the maximum error therefore stays near
//! the size of the boundary loop while the mean error falls with `N`. The spherical cap
//! harmonics (Neumann or mixed rim condition) keep the loop; the report's
//! `boundary_max_relative` measures it. A closed surface has no rim (its cap's rim is the
//! puncture): the spherical cap harmonics are then fitted on the whole sphere
//! ([`super::scha::basis_cap`], `HarmonicsReport::basis_z_star = -1`).
//!
//! Vertices used by no face have no cap position: they are left out of the fit and of the
//! errors and keep their input position in the reconstruction.

use std::time::Instant;

use serde::Serialize;

use super::basis::basis_len;
use super::cap_legendre::MAX_CAP_ORDER;
use super::fit::{fit_in, fit_with_errors_in, FitWithErrors, HarmonicFit, OrderError, MAX_DESIGN_ENTRIES};
use super::kind::BasisKind;
use super::legendre::MAX_ORDER;
use super::resample::resample;
use super::scha::basis_cap;
use super::shape::{aspect_ratio_in, order_one_ellipsoid};
use super::HarmonicsError;
use crate::cap::CapMap;
use crate::param::{parameterize, ParamOptions, ParamReport};
use crate::error::Error;
use crate::mesh::{SurfaceKind, TriMesh};
use crate::progress::{self, Progress, Stage};

/// Default largest order `N` of [`HarmonicsOptions`].
pub const DEFAULT_ORDER: usize = 10;

/// Options of [`analyze`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct HarmonicsOptions {
    /// Largest order `N` of the fit: `(N + 1)^2` basis functions. Default [`DEFAULT_ORDER`]
    /// (10). At most 500, and the mesh needs at least `(N + 1)^2` vertices.
    pub order: usize,
    /// Parameterization options. Default: the adaptive cap ([`ParamOptions::default`]); the
    /// planar disk domain is refused (the harmonics live on a spherical cap).
    pub param: ParamOptions,
    /// The basis. Default [`BasisKind::Adaptive`] (the paper's); the spherical cap harmonics
    /// accept orders up to 100.
    pub basis: BasisKind,
    /// Also evaluate the order-`N` surface on a uniform cap mesh of about this many faces
    /// ([`HarmonicsOutput::resampled`]). Default `None`.
    pub resample_faces: Option<usize>,
}

impl Default for HarmonicsOptions {
    fn default() -> Self {
        Self {
            order: DEFAULT_ORDER,
            param: ParamOptions::default(),
            basis: BasisKind::Adaptive,
            resample_faces: None,
        }
    }
}

impl HarmonicsOptions {
    /// Set the largest order `N`.
    pub fn with_order(mut self, order: usize) -> Self {
        self.order = order;
        self
    }

    /// Set the parameterization options.
    pub fn with_param(mut self, param: ParamOptions) -> Self {
        self.param = param;
        self
    }

    /// Set the basis.
    pub fn with_basis(mut self, basis: BasisKind) -> Self {
        self.basis = basis;
        self
    }

    /// Set (or clear) the face count of the resampled reconstruction.
    pub fn with_resample_faces(mut self, faces: Option<usize>) -> Self {
        self.resample_faces = faces;
        self
    }
}

/// What [`analyze`] measured.
#[derive(Debug, Clone, Serialize)]
pub struct HarmonicsReport {
    /// The basis of the fit.
    pub basis: BasisKind,
    /// The parameterization's cap `Z >= Z*`.
    pub z_star: f64,
    /// The cap of the basis: `z_star`, except for the spherical cap harmonics of a closed
    /// surface, fitted on the whole sphere (`-1`; [`super::scha::basis_cap`]).
    pub basis_z_star: f64,
    /// The largest order `N`.
    pub order: usize,
    /// Input vertices.
    pub vertices: usize,
    /// Vertices in the fit (those used by a face).
    pub fitted_vertices: usize,
    /// `(N + 1)^2`.
    pub basis_functions: usize,
    /// Reconstruction error of the least-squares fit at each order `0..=N` (each order fitted
    /// on its own, from one QR factorization): mean and max vertex distance, absolute and
    /// divided by the bounding-box diagonal of the fitted vertices.
    pub errors_by_order: Vec<OrderError>,
    /// The paper's aspect ratio `sigma_1 / sigma_3` of the order-1 representation (least-squares
    /// `y ~ c + A x` over the unit cap points, [`super::shape::aspect_ratio`]); infinite (JSON
    /// `null`) when that representation is flat.
    pub aspect_ratio: f64,
    /// `sigma_1 >= sigma_2 >= sigma_3` of that `A`.
    pub singular_values: [f64; 3],
    /// Ratio of the largest to the smallest semi-axis of the order-1 representation as the
    /// exact ellipsoid over the stretched sphere ([`super::shape::order_one_ellipsoid`]); equal
    /// to `aspect_ratio` when `Z* = -1`.
    pub ellipsoid_aspect_ratio: f64,
    /// Semi-axes of that ellipsoid, largest first. The ellipsoid exists for the adaptive
    /// harmonics only: with the spherical cap harmonics these and `ellipsoid_aspect_ratio` are
    /// NaN (JSON `null`).
    pub ellipsoid_semi_axes: [f64; 3],
    /// Boundary vertices of the input (on edges used by one face); 0 for a closed surface.
    pub boundary_vertices: usize,
    /// Largest distance between a boundary vertex and its order-`N` reconstruction, divided by
    /// the bounding-box diagonal of the fitted vertices; `null` for a closed surface.
    pub boundary_max_relative: Option<f64>,
    /// Faces of the resampled reconstruction, when one was asked for.
    pub resampled_faces: Option<usize>,
    /// Seconds of the fit, errors and aspect ratios (after the parameterization).
    pub fit_seconds: f64,
    /// Seconds of the whole analysis, parameterization included.
    pub seconds: f64,
    /// The parameterization.
    pub param: ParamReport,
}

/// The result of [`analyze`].
#[derive(Debug, Clone)]
pub struct HarmonicsOutput {
    /// The input's connectivity with its vertices at the order-`N` reconstruction.
    pub reconstructed: TriMesh,
    /// The order-`N` coefficients (evaluate them at the cap positions of the parameterization).
    pub fit: HarmonicFit,
    /// The order-`N` surface on a uniform cap mesh, when [`HarmonicsOptions::resample_faces`]
    /// was set.
    pub resampled: Option<TriMesh>,
    /// What was measured.
    pub report: HarmonicsReport,
}

/// Parameterize `mesh` with `options.param`, fit it with the basis `options.basis` up to
/// `options.order`, reconstruct it and measure the errors and the aspect ratio.
///
/// The order and the vertex count are checked before the (expensive) parameterization.
///
/// The work runs on a worker thread of rayon's pool; `progress` is called on this thread
/// (see `crate::pool`).
pub fn analyze(mesh: &TriMesh, options: &HarmonicsOptions, progress: &dyn Progress) -> Result<HarmonicsOutput, Error> {
    check_request(mesh, options)?;
    crate::pool::on_pool(progress, |progress| {
        let map = parameterize(mesh, &options.param, progress)?;
        analyze_map(mesh, &map, options, progress)
    })
}

/// As [`analyze`], from the parameterization `map` of `mesh` (its `cap` holds one position per
/// vertex of `mesh`); `options.param` is not used. `seconds` in the report adds the
/// parameterization's own time.
pub fn analyze_map(
    mesh: &TriMesh,
    map: &CapMap,
    options: &HarmonicsOptions,
    progress: &dyn Progress,
) -> Result<HarmonicsOutput, Error> {
    let start = Instant::now();
    check_request(mesh, options)?;
    let (order, kind) = (options.order, options.basis);
    let z_star = map.report.z_star.ok_or_else(|| {
        Error::InvalidOption(
            "adaptive harmonics need a spherical cap domain (adaptive, hemisphere, sphere or radius=R), not the planar disk"
                .into(),
        )
    })?;
    if map.cap.len() != mesh.n_vertices() {
        return Err(Error::InvalidOption(format!(
            "the parameterization has {} cap positions for a mesh of {} vertices; pass the map of this mesh",
            map.cap.len(),
            mesh.n_vertices()
        )));
    }
    let closed = map.report.kind == SurfaceKind::ClosedSphere;
    let basis_z_star = match kind {
        BasisKind::Adaptive => z_star,
        BasisKind::SphericalCap(_) => basis_cap(z_star, closed),
    };
    let used = referenced(mesh);
    let cap: Vec<[f64; 3]> = used.iter().map(|&v| map.cap[v]).collect();
    let values: Vec<[f64; 3]> = used.iter().map(|&v| mesh.vertices[v]).collect();

    progress::check(progress, Stage::Harmonics, 0.0, &format!("fitting orders 0..={order}"))?;
    // One design matrix for the fits, their errors and the reconstruction.
    let FitWithErrors { fits, errors: errors_by_order, reconstructed: positions } =
        fit_with_errors_in(kind, &cap, &values, basis_z_star, order)?;
    let top = fits.last().cloned().ok_or(HarmonicsError::TooFewPoints {
        points: cap.len(),
        basis: basis_len(order),
        order,
    })?;
    progress::check(progress, Stage::Harmonics, 0.7, "reconstruction errors measured")?;

    progress::check(progress, Stage::Harmonics, 0.8, "order-1 aspect ratio")?;
    let (ratio, singular_values) = match aspect_ratio_in(kind, &cap, &values, basis_z_star) {
        Ok(a) => (a.ratio, a.singular_values),
        Err(HarmonicsError::DegenerateShape { singular_values }) => (f64::INFINITY, singular_values),
        Err(e) => return Err(e.into()),
    };
    let (ellipsoid_aspect_ratio, ellipsoid_semi_axes) = if kind == BasisKind::Adaptive {
        let order_one = match fits.get(1) {
            Some(f) => f.clone(),
            None => fit_in(kind, &cap, &values, basis_z_star, 1)?,
        };
        let ellipsoid = order_one_ellipsoid(&order_one)?;
        (ellipsoid.aspect_ratio(), ellipsoid.semi_axes)
    } else {
        (f64::NAN, [f64::NAN; 3])
    };

    let mut vertices = mesh.vertices.clone();
    for (&v, p) in used.iter().zip(positions) {
        vertices[v] = p;
    }
    let boundary = boundary_vertices(mesh);
    let diagonal = super::fit::bounding_box_diagonal(&values);
    let boundary_max_relative = (!boundary.is_empty() && diagonal > 0.0).then(|| {
        boundary.iter().map(|&v| distance(vertices[v], mesh.vertices[v])).fold(0.0f64, f64::max) / diagonal
    });
    let resampled = match options.resample_faces {
        Some(faces) => {
            progress::check(progress, Stage::Harmonics, 0.9, "resampling on a cap mesh")?;
            Some(resample(&top, faces)?)
        }
        None => None,
    };
    progress::check(progress, Stage::Harmonics, 1.0, "done")?;
    let fit_seconds = start.elapsed().as_secs_f64();
    let report = HarmonicsReport {
        basis: kind,
        z_star,
        basis_z_star,
        order,
        vertices: mesh.n_vertices(),
        fitted_vertices: used.len(),
        basis_functions: basis_len(order),
        errors_by_order,
        aspect_ratio: ratio,
        singular_values,
        ellipsoid_aspect_ratio,
        ellipsoid_semi_axes,
        boundary_vertices: boundary.len(),
        boundary_max_relative,
        resampled_faces: resampled.as_ref().map(TriMesh::n_faces),
        fit_seconds,
        seconds: map.report.seconds + fit_seconds,
        param: map.report.clone(),
    };
    Ok(HarmonicsOutput {
        reconstructed: TriMesh::new(vertices, mesh.faces.clone()),
        fit: top,
        resampled,
        report,
    })
}

/// The checks [`analyze`] makes before parameterizing: the order is at most 500 (100 for the
/// spherical cap harmonics), the mesh has at least `(order + 1)^2` vertices used by faces, the
/// design matrix fits in memory and the resampling face count is valid.
pub fn check_request(mesh: &TriMesh, options: &HarmonicsOptions) -> Result<(), HarmonicsError> {
    let order = options.order;
    let max = match options.basis {
        BasisKind::Adaptive => MAX_ORDER,
        BasisKind::SphericalCap(_) => MAX_CAP_ORDER,
    };
    if order > max {
        return Err(HarmonicsError::OrderTooLarge { order, max });
    }
    if let Some(faces) = options.resample_faces {
        let max = super::resample::MAX_RESAMPLE_FACES;
        if faces == 0 || faces > max {
            return Err(HarmonicsError::InvalidResample { faces, max });
        }
    }
    let points = referenced(mesh).len();
    let basis = basis_len(order);
    if points < basis {
        return Err(HarmonicsError::TooFewPoints { points, basis, order });
    }
    let entries = points.saturating_mul(basis);
    if entries > MAX_DESIGN_ENTRIES {
        return Err(HarmonicsError::TooLarge {
            entries,
            max: MAX_DESIGN_ENTRIES,
        });
    }
    Ok(())
}

/// Vertices on an edge used by exactly one face, ascending.
fn boundary_vertices(mesh: &TriMesh) -> Vec<usize> {
    let mut edges = std::collections::HashMap::new();
    for f in &mesh.faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0usize) += 1;
        }
    }
    let n = mesh.n_vertices();
    let mut on = vec![false; n];
    for ((a, b), count) in edges {
        if count == 1 {
            for v in [a as usize, b as usize] {
                if let Some(o) = on.get_mut(v) {
                    *o = true;
                }
            }
        }
    }
    (0..n).filter(|&v| on[v]).collect()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Indices of the vertices some face uses (out-of-range indices ignored), ascending.
fn referenced(mesh: &TriMesh) -> Vec<usize> {
    let n = mesh.n_vertices();
    let mut used = vec![false; n];
    for f in &mesh.faces {
        for &v in f {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    (0..n).filter(|&v| used[v]).collect()
}
