//! The parameter domain: the adaptive cap of the paper or one of the fixed baselines it is
//! compared with (paper Sec. 4.1, Tables 1 and 2).

use std::fmt;
use std::str::FromStr;

/// Lower bound of the radius search (paper: none given; design notes: `[0.05, 20]`, i.e. `Z*`
/// from about 0.995 down to -0.995).
pub const MIN_RADIUS: f64 = 0.05;
/// Upper bound of the radius search.
pub const MAX_RADIUS: f64 = 20.0;

/// Which domain the surface is mapped onto.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Domain {
    /// The paper's method: the cap `Z >= Z*` with `r*` minimising the conformal distortion.
    #[default]
    Adaptive,
    /// The planar unit disk with uniform density (disk OMT, Zhao et al. 2013).
    Disk,
    /// The hemisphere `Z >= 0` (`r = 1`, Giri et al. 2021).
    Hemisphere,
    /// Nearly the whole sphere: `r = MAX_RADIUS`, `Z* = -0.995`.
    Sphere,
    /// A fixed disk radius `r` (cap `Z >= (1 - r^2) / (1 + r^2)`), in `[MIN_RADIUS, MAX_RADIUS]`
    /// (see [`Domain::check`]).
    Radius(f64),
}

impl Domain {
    /// `Ok` unless the domain is a fixed radius outside `[MIN_RADIUS, MAX_RADIUS]` (or not a
    /// finite number): beyond the adaptive search's range the cap is nearly a point or the
    /// whole sphere and the transport degenerates (the MEG helmet at `r = 1000`: ten folded
    /// faces and mean |d_area| 0.58; at `r = 1e6` the Newton iteration stalls).
    pub fn check(self) -> Result<(), String> {
        match self {
            Domain::Radius(r) if !(MIN_RADIUS..=MAX_RADIUS).contains(&r) => Err(format!(
                "radius = {r} is outside [{MIN_RADIUS}, {MAX_RADIUS}], the range of the adaptive search (Z* from 0.995 down to -0.995); use a radius in it"
            )),
            _ => Ok(()),
        }
    }

    /// The fixed radius of a non-adaptive spherical domain.
    pub fn fixed_radius(self) -> Option<f64> {
        match self {
            Domain::Hemisphere => Some(1.0),
            Domain::Sphere => Some(MAX_RADIUS),
            Domain::Radius(r) => Some(r),
            Domain::Adaptive | Domain::Disk => None,
        }
    }
}

impl fmt::Display for Domain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Domain::Adaptive => write!(f, "adaptive"),
            Domain::Disk => write!(f, "disk"),
            Domain::Hemisphere => write!(f, "hemisphere"),
            Domain::Sphere => write!(f, "sphere"),
            Domain::Radius(r) => write!(f, "radius={r}"),
        }
    }
}

impl FromStr for Domain {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "adaptive" => Ok(Domain::Adaptive),
            "disk" => Ok(Domain::Disk),
            "hemisphere" => Ok(Domain::Hemisphere),
            "sphere" => Ok(Domain::Sphere),
            _ => {
                let r = s
                    .strip_prefix("radius=")
                    .and_then(|v| v.parse::<f64>().ok())
                    .ok_or_else(|| format!("unknown domain '{s}': use adaptive, disk, hemisphere, sphere or radius=R with R in [{MIN_RADIUS}, {MAX_RADIUS}]"))?;
                Domain::Radius(r).check()?;
                Ok(Domain::Radius(r))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_radii_must_lie_in_the_search_range() {
        for r in [MIN_RADIUS, 1.0, MAX_RADIUS] {
            assert!(Domain::Radius(r).check().is_ok(), "{r}");
            assert_eq!(format!("radius={r}").parse::<Domain>(), Ok(Domain::Radius(r)));
        }
        for r in [0.0, -1.0, 0.049, 20.5, 1e6, f64::NAN, f64::INFINITY] {
            let e = Domain::Radius(r).check().expect_err("accepted");
            assert!(e.contains("outside [0.05, 20]"), "{e}");
            assert!(format!("radius={r}").parse::<Domain>().is_err(), "{r}");
        }
        assert!(Domain::Adaptive.check().is_ok() && Domain::Sphere.check().is_ok());
    }
}
