//! Which harmonic basis a fit uses: the paper's adaptive harmonics (AH, the default) or the
//! spherical cap harmonics (SCHA) that keep an open surface's boundary loop.
//!
//! | [`BasisKind`] | functions | on the rim `Z = Z*` |
//! |---|---|---|
//! | `Adaptive` | `P_n^m(q1 cos(theta) + q2)`, integer `n` ([`super::basis`]) | every `m > 0` term vanishes: the boundary collapses to a point |
//! | `SphericalCap(Neumann)` | `Theta_k^m(theta)` with `Theta'(theta_c) = 0` ([`super::scha`]) | free: the boundary loop is fitted |
//! | `SphericalCap(Dirichlet)` | `Theta(theta_c) = 0` | every term vanishes: the loop collapses to the origin |
//! | `SphericalCap(Mixed)` | Neumann for `k - m` even, Dirichlet for `k - m` odd (Haines 1985) | fitted by the Neumann half |
//!
//! All have `(N + 1)^2` functions of orders `k <= N`, indexed `k^2 + k + m`. A closed surface
//! has no rim (its cap's rim is the puncture): `SphericalCap` of any condition is then fitted on
//! the whole sphere, the real spherical harmonics ([`super::scha::basis_cap`]).

use serde::{Deserialize, Serialize};

/// The boundary condition at the cap's rim `theta = theta_c` that fixes the non-integer degrees
/// of the spherical cap harmonics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CapBoundary {
    /// `dTheta/dtheta = 0` on the rim: a complete orthonormal basis whose sums take any value
    /// on the rim (the default).
    #[default]
    Neumann,
    /// `Theta = 0` on the rim: a complete orthonormal basis of functions vanishing on the rim.
    Dirichlet,
    /// Haines' set: the Neumann functions for `k - m` even and the Dirichlet ones for `k - m`
    /// odd (at `Z* = 0` the hemisphere's spherical harmonics); complete, not orthogonal.
    Mixed,
}

crate::named::named_enum!(CapBoundary, "cap boundary condition", Neumann => "neumann", Dirichlet => "dirichlet", Mixed => "mixed");

/// The harmonic basis of a fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BasisKind {
    /// The paper's adaptive harmonics (Eq. 22-25), the default.
    #[default]
    Adaptive,
    /// Spherical cap harmonics on the true polar angle with the given rim condition.
    SphericalCap(CapBoundary),
}

impl BasisKind {
    /// `"ah"` or `"scha"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Adaptive => "ah",
            Self::SphericalCap(_) => "scha",
        }
    }

    /// The rim condition of a spherical cap basis.
    pub fn boundary(self) -> Option<CapBoundary> {
        match self {
            Self::Adaptive => None,
            Self::SphericalCap(b) => Some(b),
        }
    }

    /// The basis named `name` (`ah` or `scha`), with `boundary` for `scha`.
    pub fn from_name(name: &str, boundary: CapBoundary) -> Result<Self, String> {
        match name.to_ascii_lowercase().as_str() {
            "ah" | "adaptive" => Ok(Self::Adaptive),
            "scha" | "cap" => Ok(Self::SphericalCap(boundary)),
            _ => Err(format!("unknown harmonic basis '{name}': use ah (adaptive harmonics) or scha (spherical cap harmonics)")),
        }
    }
}
