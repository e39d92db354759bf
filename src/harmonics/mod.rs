//! Adaptive harmonics (AH): spherical-harmonics-like functions on the cap `Z >= Z*` and the
//! least-squares surface representation built on them (paper Sec. "Adaptive Harmonics (AH)",
//! Eq. (22)-(28), and the shape analysis of Eq. (29)).
//!
//! ```text
//! legendre   : Pbar_n^m(x), fully normalized associated Legendre functions    (before Eq. 22)
//! basis      : A_n^m on the cap, q1 = 2/(1-Z*), q2 = -(1+Z*)/(1-Z*)          (Eq. 22-25)
//! kind       : BasisKind: adaptive harmonics (default) or spherical cap harmonics
//! cap_legendre: non-integer degree Legendre functions on the cap (Rayleigh-Ritz)
//! scha       : spherical cap harmonics, Neumann / Dirichlet / mixed rim condition
//! any_basis  : HarmonicBasis, either basis behind one type for fit and reconstruction
//! resample   : the reconstruction on a uniform cap mesh of any size (a smooth remesh)
//! cohort     : groups of aspect ratios compared by Welch's t-test (the paper's cohort study)
//! fit        : C = argmin |A C - V| by Householder QR, all orders at once     (Eq. 26-28)
//! shape      : aspect ratio sigma_1 / sigma_3 of the order-1 representation    (Eq. 29)
//! quadrature : Gauss-Legendre rules, to integrate over the cap in cos(theta)
//! pipeline   : analyze = parameterize + fit + errors per order + aspect ratios
//! ```
//!
//! The basis is orthonormal for `integral f g d(cos theta) d(phi)` over `[Z*, 1] x [-pi, pi]`,
//! which is the area integral over the cap (see [`basis`]). The paper's printed `q1, q2` have the
//! wrong sign; the corrected values above are the design notes' and make `q1 Z* + q2 = -1`,
//! `q1 + q2 = 1`.
//!
//! ```no_run
//! use capmesh::{harmonics, parameterize, read_mesh, NoProgress, ParamOptions};
//! let mesh = read_mesh(std::path::Path::new("tests/data/open_face_choi.obj.gz"))?;
//! let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress)?;
//! let z_star = map.report.z_star.unwrap_or(-1.0);
//! let fit = harmonics::fit(&map.cap, &mesh.vertices, z_star, 15)?;
//! let smooth = fit.reconstruct(&map.cap, 5)?; // truncated to orders n <= 5
//! for e in fit.errors_by_order(&map.cap, &mesh.vertices)? {
//!     println!("N = {:2}: mean relative error {:.4}", e.order, e.mean_relative);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub(crate) mod any_basis;
pub mod basis;
pub mod cap_legendre;
pub mod cohort;
pub(crate) mod error;
pub mod fit;
pub mod legendre;
pub mod pipeline;
pub(crate) mod kind;
pub(crate) mod quadrature;
pub(crate) mod resample;
pub mod scha;
pub(crate) mod shape;

pub use basis::{basis_degree, basis_index, basis_len, CapBasis};
pub use error::HarmonicsError;
pub use any_basis::HarmonicBasis;
pub use cohort::{compare_groups, welch_t_test, CohortError, GroupComparison, GroupSummary, WelchTest};
pub use fit::{fit, fit_all_orders, fit_all_orders_in, fit_in, fit_with_errors_in, order_errors, FitWithErrors, HarmonicFit, OrderError};
pub use kind::{BasisKind, CapBoundary};
pub use resample::resample;
pub use scha::SchaBasis;
pub use pipeline::{analyze, analyze_map, HarmonicsOptions, HarmonicsOutput, HarmonicsReport};
pub use legendre::{associated_legendre, normalized_legendre, NormalizedLegendre};
pub use quadrature::gauss_legendre;
pub use shape::{aspect_ratio, aspect_ratio_in, order_one_ellipsoid, AspectRatio, OrderOneEllipsoid};
