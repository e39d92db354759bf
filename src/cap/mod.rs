//! The cap: the stereographic projection between the disk of radius `r` and the cap
//! `Z >= Z*`, the parameter domains, Brent's method for the radius search, and [`CapMap`],
//! a surface mapped onto the cap (paper Sec. 3.1.2-3.1.3), and [`InverseMap`], its inverse
//! (Sec. 4.2). The parameterization that
//! produces a [`CapMap`] is [`crate::param`].

pub(crate) mod brent;
pub(crate) mod domain;
mod inverse;
mod map;
pub mod stereographic;

pub use domain::Domain;
pub use inverse::{InverseMap, InverseMapError, InverseOptions, SurfacePoint};
pub use map::CapMap;
pub use stereographic::{inverse_stereographic, radius_of_z_star, stereographic, z_star_of_radius};
