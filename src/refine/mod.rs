//! Repair and improvement of a planar map after the transport, used by the parameterization
//! ([`crate::param`]) and the remeshing ([`mod@crate::remesh`]): fold repair (`untangle`, with
//! `kernel_untangle` and `boundary_polygon`), the smoothing of the centroid map
//! (`smoothing`), the face-level area refinement ([`area_refine`]) and the radial mass
//! correction of multilevel maps (`radial`).

mod area_local;
pub mod area_refine;
pub(crate) mod boundary_polygon;
pub(crate) mod energy_untangle;
pub(crate) mod kernel_untangle;
pub(crate) mod prolong;
pub(crate) mod radial;
pub(crate) mod smoothing;
pub(crate) mod untangle;

pub use area_refine::{AreaRefineReport, RefineOptions};
pub use prolong::ProlongReport;
pub use radial::RadialReport;
pub use smoothing::{Smoothing, SmoothingTrial};
pub use untangle::UntangleReport;
