//! Semi-discrete optimal transport on a disk (paper Sec. 2.2 and 3.1.2, after Zhao et al.
//! 2013): the power diagram of the sites clipped to the disk of radius `r`
//! ([`cells`]), kept as a regular triangulation updated by flips ([`triangulation`]), with
//! exact density integrals (`density`) and a damped Newton driver (`newton`).

pub mod cells;
pub(crate) mod coarse_level;
pub(crate) mod density;
pub(crate) mod newton;
pub(crate) mod pattern;
pub mod options;
pub mod planar_transport;
pub mod triangulation;

pub use cells::CellIntegrals;
pub use density::{RadialDensity, StereographicDensity, UniformDensity};
pub use newton::OtSolver;
pub use options::{OmtError, OtOptions, OtReport};
