//! The cap: stereographic projection, the radius search and the whole parameterization
//! (paper Sec. 3.1.2-3.1.3 and 3.2).

pub mod brent;
pub mod domain;
pub mod lambda_fallback;
pub mod parameterize;
pub mod puncture_end;
pub mod stereographic;

pub use domain::Domain;
pub use lambda_fallback::{LambdaFallback, DEFAULT_LAMBDA_FALLBACKS};
pub use parameterize::{parameterize, CapMap, OpenInitialMap, ParamOptions, ParamReport, PunctureEnd, PunctureTrial, RadiusSample};
pub use crate::refine::Smoothing;
pub use stereographic::{inverse_stereographic, radius_of_z_star, stereographic, z_star_of_radius};
