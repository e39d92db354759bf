//! Repair and improvement of a planar map after the transport, used by the parameterization
//! ([`crate::param`]) and the remeshing ([`mod@crate::remesh`]): fold repair ([`untangle`], with
//! [`kernel_untangle`] and [`boundary_polygon`]), the regularisation of the centroid map
//! ([`regularize`]) and the face-level area refinement ([`area_refine`]).

mod area_local;
pub mod area_refine;
pub mod boundary_polygon;
pub mod kernel_untangle;
pub mod regularize;
pub mod untangle;

pub use area_refine::{AreaRefineReport, RefineOptions};
pub use regularize::{Smoothing, SmoothingTrial};
pub use untangle::UntangleReport;
