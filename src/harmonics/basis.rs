//! The adaptive harmonics `A_n^m(theta, phi)` on the cap `Z >= Z*` (paper Sec. "Adaptive
//! Harmonics (AH)", Eq. (22)-(24)).
//!
//! # Definition
//!
//! With `x = cos(theta)` in `[Z*, 1]` mapped onto `[-1, 1]` by `t = q1 x + q2`,
//!
//! ```text
//! q1 = 2 / (1 - Z*),   q2 = -(1 + Z*) / (1 - Z*)
//! ```
//!
//! (the design notes' correction of the paper's printed signs: `q1 Z* + q2 = -1`, `q1 + q2 = 1`),
//! the shifted functions `Ptilde_n^m(x) = P_n^m(q1 x + q2)` (with `P_n^m` as in
//! [`super::legendre`], Condon-Shortley phase included), the constant
//!
//! ```text
//! K_n^m = sqrt(q1 (2n + 1) (n - |m|)! / (4 pi (n + |m|)!))                        (Eq. 24)
//! ```
//!
//! and, exactly as the paper writes them,
//!
//! ```text
//! A_n^m = (-1)^|m| sqrt(2) K_n^m sin(|m| phi) Ptilde_n^|m|(cos theta)   m < 0
//! A_n^m = (-1)^|m| sqrt(2) K_n^m cos(m phi)   Ptilde_n^m(cos theta)     m > 0
//! A_n^0 = K_n^0 Ptilde_n^0(cos theta)
//! ```
//!
//! The `(-1)^|m|` cancels the Condon-Shortley phase of `P_n^m`, so for instance
//! `A_1^1 = sqrt(3 q1 / (4 pi)) sqrt(1 - t^2) cos(phi)` is positive where `X > 0`. In terms of
//! the normalized functions `Pbar` of [`super::legendre`], `K_n^m Ptilde_n^m = sqrt(q1 / (2 pi))
//! Pbar_n^m(t)`, which is how they are computed (no factorials).
//!
//! # Orthonormality (the inner product)
//!
//! The `(N + 1)^2` functions of orders `n <= N` are orthonormal in
//!
//! ```text
//! <f, g> = integral_{Z*}^{1} integral_{-pi}^{pi} f g d(phi) d(cos theta)
//!        = integral over the cap of f g dA,    dA = sin(theta) d(theta) d(phi),
//! ```
//!
//! the area element of the unit sphere: the `phi` integral separates the `m`, and for equal `m`,
//! `integral_{Z*}^{1} Ptilde_n^m Ptilde_k^m dx = 2 (n + m)! / (q1 (2n + 1) (n - m)!) delta_nk`
//! (Eq. 22, integral over `[Z*, 1]`), which `K_n^m` normalizes to `1 / (2 pi)`. For `Z* = -1`
//! (`q1 = 1`, `q2 = 0`) they are the usual real spherical harmonics.
//!
//! # The boundary circle
//!
//! On the boundary `Z = Z*` the argument is `t = -1`, where `P_n^m` vanishes for every `m > 0`:
//! only the zonal functions `A_n^0` are non-zero there, so *any* combination of adaptive
//! harmonics is constant along the boundary circle (the map `Z -> t` sends the cap onto the whole
//! sphere `(sqrt(1 - t^2) cos(phi), sqrt(1 - t^2) sin(phi), t)` and its boundary onto the pole
//! `t = -1`; the hemispherical harmonics the paper extends behave the same way). A reconstructed
//! open surface therefore has its boundary loop pinched to one point; its largest error does not
//! fall with the order, while its mean error does. For closed surfaces (`Z*` near -1 around the
//! puncture) this is harmless.
//!
//! # Order of the functions
//!
//! Index `n^2 + n + m`, `m = -n..=n` ([`basis_index`]): `A_0^0, A_1^-1, A_1^0, A_1^1, A_2^-2,
//! ...`, the order of the paper's coefficient vector `C = (C_0^0, C_1^-1, C_1^0, ...)`.
//!
//! # Points
//!
//! A point `(X, Y, Z)` has `theta = acos(Z)`, `phi = atan2(Y, X)`. It must be on the unit sphere
//! (norm within [`SPHERE_TOLERANCE`] of 1; it is then normalized, as the paper's
//! `theta = acos(Z / |v|)` does) and on the cap (`Z >= Z* -` [`CAP_TOLERANCE`]; points that far
//! below count as on the boundary circle). `t` and `sqrt(1 - t^2)` are computed as
//! `((Z - Z*) - (1 - Z)) / (1 - Z*)` and `2 sqrt((1 - Z)(Z - Z*)) / (1 - Z*)`, which keep full
//! relative accuracy at the pole and on the boundary circle even when `Z*` is close to 1.

use std::f64::consts::PI;

use super::legendre::{triangle_index, NormalizedLegendre, MAX_ORDER};
use super::HarmonicsError;

/// Accepted deviation of a cap point's norm from 1.
pub const SPHERE_TOLERANCE: f64 = 1e-6;

/// Accepted distance of a cap point below `Z*` (such points are moved onto the boundary circle).
pub const CAP_TOLERANCE: f64 = 1e-8;

/// Number of basis functions of orders `n <= order`: `(order + 1)^2` (saturating).
pub fn basis_len(order: usize) -> usize {
    order.saturating_add(1).saturating_mul(order.saturating_add(1))
}

/// Index of `A_n^m` in the basis: `n^2 + n + m`, or `None` when `|m| > n`.
pub fn basis_index(n: usize, m: isize) -> Option<usize> {
    if m.unsigned_abs() > n {
        return None;
    }
    let centre = n.checked_mul(n)?.checked_add(n)?;
    centre.checked_add_signed(m)
}

/// `(n, m)` of the basis function at `index` (inverse of [`basis_index`]).
pub fn basis_degree(index: usize) -> (usize, isize) {
    // n = floor(sqrt(index)), computed in u128 so that no product overflows.
    let target = index as u128;
    let mut n = (index as f64).sqrt() as u128;
    while n * n > target {
        n -= 1;
    }
    while (n + 1) * (n + 1) <= target {
        n += 1;
    }
    // index - n^2 is in 0..=2n, so m = index - n^2 - n is in -n..=n.
    let offset = (target - n * n) as i128 - n as i128;
    (n as usize, offset as isize)
}

/// A point of the cap in the form the basis needs: `t = q1 cos(theta) + q2`,
/// `s = sqrt(1 - t^2)`, and the azimuth as `(cos(phi), sin(phi))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CapCoordinates {
    /// `t = q1 cos(theta) + q2`, in `[-1, 1]`.
    pub t: f64,
    /// `sqrt(1 - t^2)`.
    pub s: f64,
    /// `cos(phi)`.
    pub cos_phi: f64,
    /// `sin(phi)`.
    pub sin_phi: f64,
}

/// The adaptive harmonics of orders `n <= order` on the cap `Z >= z_star`.
#[derive(Debug, Clone)]
pub struct CapBasis {
    z_star: f64,
    order: usize,
    q1: f64,
    q2: f64,
    legendre: NormalizedLegendre,
}

impl CapBasis {
    /// The basis on `Z >= z_star` (`z_star` in `[-1, 1)`) up to `order` (at most
    /// [`MAX_ORDER`]).
    pub fn new(z_star: f64, order: usize) -> Result<Self, HarmonicsError> {
        if !(z_star.is_finite() && (-1.0..1.0).contains(&z_star)) {
            return Err(HarmonicsError::InvalidZStar { z_star });
        }
        if order > MAX_ORDER {
            return Err(HarmonicsError::OrderTooLarge { order, max: MAX_ORDER });
        }
        let d = 1.0 - z_star;
        let (q1, q2) = (2.0 / d, -(1.0 + z_star) / d);
        if !q1.is_finite() {
            return Err(HarmonicsError::InvalidZStar { z_star });
        }
        Ok(Self {
            z_star,
            order,
            q1,
            q2,
            legendre: NormalizedLegendre::new(order)?,
        })
    }

    /// The cap's lower bound `Z*`.
    pub fn z_star(&self) -> f64 {
        self.z_star
    }

    /// The largest order `N`.
    pub fn order(&self) -> usize {
        self.order
    }

    /// `q1 = 2 / (1 - Z*)`.
    pub fn q1(&self) -> f64 {
        self.q1
    }

    /// `q2 = -(1 + Z*) / (1 - Z*)`.
    pub fn q2(&self) -> f64 {
        self.q2
    }

    /// Number of functions, `(N + 1)^2`.
    pub fn len(&self) -> usize {
        basis_len(self.order)
    }

    /// Never true (there is always `A_0^0`); present for symmetry with [`Self::len`].
    pub fn is_empty(&self) -> bool {
        false
    }

    /// All `A_n^m` at the point `p = (X, Y, Z)` of the cap, in [`basis_index`] order.
    pub fn evaluate(&self, p: [f64; 3]) -> Result<Vec<f64>, HarmonicsError> {
        let mut out = Vec::new();
        self.evaluate_into(p, &mut out)?;
        Ok(out)
    }

    /// As [`Self::evaluate`], into `out` (resized to [`Self::len`]).
    pub fn evaluate_into(&self, p: [f64; 3], out: &mut Vec<f64>) -> Result<(), HarmonicsError> {
        let coords = self.coordinates(0, p)?;
        let mut scratch = Vec::new();
        out.clear();
        out.resize(self.len(), 0.0);
        self.fill(&coords, &mut scratch, out);
        Ok(())
    }

    /// All `A_n^m` at polar angle `theta` (in `[0, acos(Z*)]`, up to [`CAP_TOLERANCE`] in
    /// `cos(theta)`) and azimuth `phi` (any finite angle).
    pub fn evaluate_angles(&self, theta: f64, phi: f64) -> Result<Vec<f64>, HarmonicsError> {
        if !(theta.is_finite() && phi.is_finite()) {
            return Err(HarmonicsError::NonFinite {
                what: "angle pair",
                index: 0,
            });
        }
        let half = (0.5 * theta).sin();
        let coords =
            self.coordinates_from_heights(0, 2.0 * half * half, theta.cos() - self.z_star, phi.cos(), phi.sin())?;
        let mut scratch = Vec::new();
        let mut out = vec![0.0; self.len()];
        self.fill(&coords, &mut scratch, &mut out);
        Ok(out)
    }

    /// Checks the point `p` (number `index`, for error messages) and returns its coordinates.
    pub fn coordinates(&self, index: usize, p: [f64; 3]) -> Result<CapCoordinates, HarmonicsError> {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(HarmonicsError::NonFinite {
                what: "cap point",
                index,
            });
        }
        let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if norm.is_nan() || (norm - 1.0).abs() > SPHERE_TOLERANCE {
            return Err(HarmonicsError::NotOnUnitSphere {
                index,
                norm,
                tolerance: SPHERE_TOLERANCE,
            });
        }
        let z = p[2] / norm;
        let rho = p[0].hypot(p[1]);
        let (cos_phi, sin_phi) = if rho > 0.0 {
            (p[0] / rho, p[1] / rho)
        } else {
            (1.0, 0.0)
        };
        self.coordinates_from_heights(index, 1.0 - z, z - self.z_star, cos_phi, sin_phi)
    }

    /// Coordinates from `above = 1 - Z` and `below = Z - Z*`.
    fn coordinates_from_heights(
        &self,
        index: usize,
        above: f64,
        below: f64,
        cos_phi: f64,
        sin_phi: f64,
    ) -> Result<CapCoordinates, HarmonicsError> {
        if below < -CAP_TOLERANCE {
            return Err(HarmonicsError::OutsideCap {
                index,
                z: below + self.z_star,
                z_star: self.z_star,
                tolerance: CAP_TOLERANCE,
            });
        }
        let (above, below) = (above.max(0.0), below.max(0.0));
        let d = 1.0 - self.z_star;
        let t = ((below - above) / d).clamp(-1.0, 1.0);
        let s = (2.0 * (above * below).sqrt() / d).min(1.0);
        Ok(CapCoordinates { t, s, cos_phi, sin_phi })
    }

    /// All `A_n^m` at `coords` into `out[..self.len()]` (`out` must be that long); `scratch`
    /// holds the Legendre triangle.
    pub(crate) fn fill(&self, coords: &CapCoordinates, scratch: &mut Vec<f64>, out: &mut [f64]) {
        self.legendre.fill_with_sine(coords.t, coords.s, scratch);
        let zonal = (self.q1 / (2.0 * PI)).sqrt();
        let sectoral = (self.q1 / PI).sqrt();
        let (mut cos_m, mut sin_m) = (1.0, 0.0);
        for m in 0..=self.order {
            if m > 0 {
                let c = cos_m * coords.cos_phi - sin_m * coords.sin_phi;
                sin_m = sin_m * coords.cos_phi + cos_m * coords.sin_phi;
                cos_m = c;
            }
            let phase = if m % 2 == 0 { 1.0 } else { -1.0 };
            for n in m..=self.order {
                let pbar = scratch[triangle_index(n, m)];
                let centre = n * n + n;
                if m == 0 {
                    out[centre] = zonal * pbar;
                } else {
                    let radial = sectoral * phase * pbar;
                    out[centre + m] = radial * cos_m;
                    out[centre - m] = radial * sin_m;
                }
            }
        }
    }
}
