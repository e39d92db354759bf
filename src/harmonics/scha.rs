//! Spherical cap harmonics (SCHA): a basis on the cap `Z >= Z*` that keeps the true polar angle,
//! so a reconstructed open surface keeps its boundary loop (Haines 1985; Shaqfa, Choi and Beyer
//! 2021). The paper's adaptive harmonics ([`super::basis`]) stretch the cap onto the whole
//! sphere, which sends the rim to a pole where every `m > 0` function vanishes.
//!
//! # Definition
//!
//! With `theta = acos(Z)`, `phi = atan2(Y, X)` and the radial functions `Theta_j^m` of
//! [`super::cap_legendre`] (`integral_{Z*}^{1} Theta_j^m Theta_i^m d(cos theta) = delta_ij`),
//! the function of order `k` (`0 <= k <= N`) and azimuthal degree `m` (`-k <= m <= k`) is
//!
//! ```text
//! S_k^0  = Theta_(k)^0(theta) / sqrt(2 pi)
//! S_k^m  = Theta_(k)^m(theta) cos(m phi) / sqrt(pi)      m > 0
//! S_k^-m = Theta_(k)^m(theta) sin(m phi) / sqrt(pi)
//! ```
//!
//! where `Theta_(k)^m` is, by rim condition ([`CapBoundary`]):
//!
//! - Neumann or Dirichlet: the `(k - m)`-th eigenfunction of that condition (degrees ascending);
//! - Mixed: the `(k - m) / 2`-th Neumann eigenfunction for `k - m` even, the `(k - m - 1) / 2`-th
//!   Dirichlet one for `k - m` odd (Haines' choice).
//!
//! Its degree `nu_k^m` (non-integer in general) is [`SchaBasis::degree`]. The Neumann and the
//! Dirichlet sets are each orthonormal in the sphere's area element over the cap; the mixed set
//! is not orthogonal (a Neumann and a Dirichlet function of equal `m` are not), but at `Z* = 0`
//! it is exactly the set of spherical harmonics (the hemisphere's even and odd ones) and it is
//! complete.
//!
//! # The whole sphere (`Z* = -1`): closed surfaces
//!
//! At `Z* = -1` the rim shrinks to the point `theta = pi` and there is no rim condition left:
//! the radial problem is regular at both poles, its degrees are the integers and its functions
//! the associated Legendre functions, so for every [`CapBoundary`] the basis is the real
//! spherical harmonics (the adaptive harmonics of `Z* = -1`, evaluated by their recurrence,
//! [`super::basis::CapBasis`]). This is the basis of a closed surface
//! ([`basis_cap`]): the rim `Z = Z*` of its cap is the parameterization's puncture (two faces
//! mapped to the flat bottom below `Z*`), not a boundary of the surface, and the coordinates
//! are smooth across it. A Neumann condition at that artificial rim forces a zero normal
//! derivative that the surface does not have, and the fit pays for it next to the puncture
//! (closed hippocampus at N = 15: max error 0.0199 of the diagonal at the puncture's corners,
//! against 0.0166 with the whole sphere; docs/harmonics.md).
//!
//! The index of `S_k^m` is `k^2 + k + m`, as for the adaptive harmonics, so the first
//! `(k + 1)^2` functions are the order-`k` basis and one QR fits every order ([`super::fit`](mod@super::fit)).
//!
//! # Points
//!
//! As for [`super::basis::CapBasis::coordinates`]: points on the unit sphere (normalized) with
//! `Z >= Z* - CAP_TOLERANCE` (points slightly below count as on the rim). `sin(theta)` is taken
//! as `sqrt(X^2 + Y^2) / |p|`, accurate at the pole.

use std::f64::consts::PI;

use super::basis::{basis_len, CapBasis, CapCoordinates, CAP_TOLERANCE, SPHERE_TOLERANCE};
use super::cap_legendre::{CapLegendre, Rim, MAX_CAP_ORDER};
use super::kind::CapBoundary;
use super::HarmonicsError;

/// A cap point as the spherical cap harmonics need it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SchaPoint {
    /// `cos(theta)`, in `[Z*, 1]`.
    pub x: f64,
    /// `sin(theta)`.
    pub s: f64,
    /// `cos(phi)`.
    pub cos_phi: f64,
    /// `sin(phi)`.
    pub sin_phi: f64,
}

/// The radial functions of one order `m`.
#[derive(Debug, Clone)]
struct OrderFamily {
    /// Neumann or Dirichlet functions, in the order the basis uses them when not mixed; for the
    /// mixed basis the Neumann functions.
    first: CapLegendre,
    /// For the mixed basis, the Dirichlet functions.
    second: Option<CapLegendre>,
}

/// The radial functions of every order: computed on a cap, or the integer-degree Legendre
/// functions of the whole sphere.
#[derive(Debug, Clone)]
enum Radial {
    /// `Z* > -1`: one family per order `m` ([`super::cap_legendre`]).
    Cap(Vec<OrderFamily>),
    /// `Z* = -1`: the real spherical harmonics.
    Sphere(CapBasis),
}

/// The spherical cap harmonics of orders `k <= N` on `Z >= Z*`.
#[derive(Debug, Clone)]
pub struct SchaBasis {
    z_star: f64,
    order: usize,
    boundary: CapBoundary,
    radial: Radial,
}

/// `Z*` of the basis that fits a surface parameterized on `Z >= z_star`: `z_star` for an open
/// surface, the whole sphere (`-1`) for a closed one, whose rim is the puncture (module docs).
pub fn basis_cap(z_star: f64, closed: bool) -> f64 {
    if closed {
        -1.0
    } else {
        z_star
    }
}

impl SchaBasis {
    /// The basis on `Z >= z_star` (`z_star` in `[-1, 1)`) up to `order` (at most
    /// [`MAX_CAP_ORDER`]) with the rim condition `boundary`. At `z_star = -1` (no rim) every
    /// `boundary` gives the real spherical harmonics.
    pub fn new(z_star: f64, order: usize, boundary: CapBoundary) -> Result<Self, HarmonicsError> {
        if !(z_star.is_finite() && (-1.0..1.0).contains(&z_star)) {
            return Err(HarmonicsError::InvalidZStar { z_star });
        }
        if order > MAX_CAP_ORDER {
            return Err(HarmonicsError::OrderTooLarge { order, max: MAX_CAP_ORDER });
        }
        if z_star == -1.0 {
            return Ok(Self { z_star, order, boundary, radial: Radial::Sphere(CapBasis::new(z_star, order)?) });
        }
        let families = (0..=order)
            .map(|m| {
                let count = order - m + 1;
                Ok(match boundary {
                    CapBoundary::Neumann => OrderFamily { first: CapLegendre::new(z_star, m, count, Rim::Neumann)?, second: None },
                    CapBoundary::Dirichlet => OrderFamily { first: CapLegendre::new(z_star, m, count, Rim::Dirichlet)?, second: None },
                    CapBoundary::Mixed => OrderFamily {
                        first: CapLegendre::new(z_star, m, count.div_ceil(2), Rim::Neumann)?,
                        second: Some(CapLegendre::new(z_star, m, count / 2, Rim::Dirichlet)?),
                    },
                })
            })
            .collect::<Result<Vec<_>, HarmonicsError>>()?;
        Ok(Self { z_star, order, boundary, radial: Radial::Cap(families) })
    }

    /// The cap's lower bound `Z*`.
    pub fn z_star(&self) -> f64 {
        self.z_star
    }

    /// The largest order `N`.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The rim condition.
    pub fn boundary(&self) -> CapBoundary {
        self.boundary
    }

    /// Number of functions, `(N + 1)^2`.
    pub fn len(&self) -> usize {
        basis_len(self.order)
    }

    /// Never true; present for symmetry with [`Self::len`].
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The degree `nu_k^m` of `S_k^m` (`m` of either sign), or `None` when `|m| > k` or
    /// `k > N`.
    pub fn degree(&self, k: usize, m: isize) -> Option<f64> {
        let am = m.unsigned_abs();
        if am > k || k > self.order {
            return None;
        }
        let families = match &self.radial {
            Radial::Cap(families) => families,
            Radial::Sphere(_) => return Some(k as f64),
        };
        let family = &families[am];
        let j = k - am;
        match &family.second {
            None => family.first.degrees().get(j).copied(),
            Some(dirichlet) if j % 2 == 1 => dirichlet.degrees().get(j / 2).copied(),
            Some(_) => family.first.degrees().get(j / 2).copied(),
        }
    }

    /// All `S_k^m` at the point `p = (X, Y, Z)` of the cap, in index order `k^2 + k + m`.
    pub fn evaluate(&self, p: [f64; 3]) -> Result<Vec<f64>, HarmonicsError> {
        let point = self.coordinates(0, p)?;
        let mut out = vec![0.0; self.len()];
        self.fill(&point, &mut Vec::new(), &mut out);
        Ok(out)
    }

    /// All `S_k^m` at polar angle `theta` in `[0, acos(Z*)]` and azimuth `phi`.
    pub fn evaluate_angles(&self, theta: f64, phi: f64) -> Result<Vec<f64>, HarmonicsError> {
        if !(theta.is_finite() && phi.is_finite()) {
            return Err(HarmonicsError::NonFinite { what: "angle pair", index: 0 });
        }
        let x = theta.cos();
        if x < self.z_star - CAP_TOLERANCE || theta < 0.0 {
            return Err(HarmonicsError::OutsideCap { index: 0, z: x, z_star: self.z_star, tolerance: CAP_TOLERANCE });
        }
        let point = SchaPoint { x: x.max(self.z_star), s: theta.sin().abs(), cos_phi: phi.cos(), sin_phi: phi.sin() };
        let mut out = vec![0.0; self.len()];
        self.fill(&point, &mut Vec::new(), &mut out);
        Ok(out)
    }

    /// Checks the point `p` (number `index`, for error messages) and returns its coordinates.
    pub fn coordinates(&self, index: usize, p: [f64; 3]) -> Result<SchaPoint, HarmonicsError> {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(HarmonicsError::NonFinite { what: "cap point", index });
        }
        let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if norm.is_nan() || (norm - 1.0).abs() > SPHERE_TOLERANCE {
            return Err(HarmonicsError::NotOnUnitSphere { index, norm, tolerance: SPHERE_TOLERANCE });
        }
        let z = p[2] / norm;
        if z < self.z_star - CAP_TOLERANCE {
            return Err(HarmonicsError::OutsideCap { index, z, z_star: self.z_star, tolerance: CAP_TOLERANCE });
        }
        let rho = p[0].hypot(p[1]);
        let (cos_phi, sin_phi) = if rho > 0.0 { (p[0] / rho, p[1] / rho) } else { (1.0, 0.0) };
        let (x, s) = if z < self.z_star {
            (self.z_star, ((1.0 - self.z_star) * (1.0 + self.z_star)).max(0.0).sqrt())
        } else {
            (z.min(1.0), (rho / norm).min(1.0))
        };
        Ok(SchaPoint { x, s, cos_phi, sin_phi })
    }

    /// All `S_k^m` at `point` into `out[..self.len()]`; `scratch` is reused between calls.
    pub(crate) fn fill(&self, point: &SchaPoint, scratch: &mut Vec<f64>, out: &mut [f64]) {
        let families = match &self.radial {
            Radial::Cap(families) => families,
            Radial::Sphere(sphere) => {
                // q1 = 1, q2 = 0: t = cos(theta), sqrt(1 - t^2) = sin(theta).
                let coords = CapCoordinates { t: point.x, s: point.s, cos_phi: point.cos_phi, sin_phi: point.sin_phi };
                sphere.fill(&coords, scratch, out);
                return;
            }
        };
        let zonal = 1.0 / (2.0 * PI).sqrt();
        let sectoral = 1.0 / PI.sqrt();
        let mut radial = [0.0; MAX_CAP_ORDER + 1];
        let mut second = [0.0; MAX_CAP_ORDER + 1];
        let (mut cos_m, mut sin_m) = (1.0, 0.0);
        for (m, family) in families.iter().enumerate() {
            if m > 0 {
                let c = cos_m * point.cos_phi - sin_m * point.sin_phi;
                sin_m = sin_m * point.cos_phi + cos_m * point.sin_phi;
                cos_m = c;
            }
            family.first.fill(point.x, point.s, scratch, &mut radial);
            if let Some(d) = &family.second {
                d.fill(point.x, point.s, scratch, &mut second);
            }
            for k in m..=self.order {
                let j = k - m;
                let r = match &family.second {
                    None => radial[j],
                    Some(_) if j % 2 == 1 => second[j / 2],
                    Some(_) => radial[j / 2],
                };
                let centre = k * k + k;
                if m == 0 {
                    out[centre] = zonal * r;
                } else {
                    out[centre + m] = sectoral * r * cos_m;
                    out[centre - m] = sectoral * r * sin_m;
                }
            }
        }
    }
}
