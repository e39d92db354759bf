//! Shape analysis with the order-1 representation (paper Sec. "Shape analysis of demented and
//! non-demented cortical surfaces", Eq. (29)): the aspect ratio `sigma_1 / sigma_3`.
//!
//! # Aspect ratio ([`aspect_ratio`])
//!
//! As the paper does: fit the surface at order `N = 1` (four functions), take that
//! representation `y_i` at the cap points, and solve the least-squares problem
//!
//! ```text
//! min_(A, c) sum_i |y_i - c - A x_i|^2
//! ```
//!
//! with `x_i` the (unit) cap points, by a dense QR of the `k x 4` matrix `[1 | x_i^T]`. The
//! translation `c` is added to the paper's `min_A sum |y_i - A x_i|^2` so that the result does not
//! depend on where the surface sits. The singular values `sigma_1 >= sigma_2 >= sigma_3` of the
//! `3 x 3` matrix `A` (nalgebra's `SVD` of a `Matrix3`) give the ratio.
//!
//! On the whole sphere (`Z* = -1`) the order-1 functions are `1, X, Y, Z`, so an ellipsoid
//! `y = D x` is reproduced exactly and its ratio is exact. On a smaller cap the order-1 functions
//! are `1, t, s cos(phi), s sin(phi)` with `t = q1 Z + q2`, `s = q1 sqrt((1 - Z)(Z - Z*))`,
//! which are not affine in `x`: the ratio of `D x` is then smaller than that of `D` (for
//! `D = diag(3, 2, 1)` on the hemisphere the `X` and `Y` axes shrink by the same factor while `Z`
//! is exact).
//!
//! # The order-1 ellipsoid ([`order_one_ellipsoid`])
//!
//! Exactly, the order-1 representation *is* an ellipsoid, but over the "stretched" unit sphere
//! `x~ = (s cos(phi), s sin(phi), t)` (the cap mapped onto the whole sphere by `Z -> t`): since
//! `A_0^0 = sqrt(q1 / (4 pi))` and `(A_1^1, A_1^-1, A_1^0) = sqrt(3 q1 / (4 pi)) x~`,
//!
//! ```text
//! y = sqrt(q1 / (4 pi)) C_0^0 + sqrt(3 q1 / (4 pi)) [C_1^1 | C_1^-1 | C_1^0] x~,
//! ```
//!
//! whose semi-axes are the singular values of that matrix. This is closed form, needs no second
//! least-squares problem, and coincides with [`aspect_ratio`] for `Z* = -1`. It exists for the
//! adaptive harmonics only (the spherical cap harmonics' order-1 functions are not linear in a
//! stretched sphere); [`aspect_ratio_in`] gives the paper's ratio in either basis.

use faer::linalg::solvers::{Qr, SolveLstsq};
use faer::Mat;
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

use super::any_basis::HarmonicBasis;
use super::fit::{fit_in, HarmonicFit};
use super::kind::BasisKind;
use super::HarmonicsError;

/// The paper's aspect ratio of the order-1 representation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AspectRatio {
    /// `sigma_1 / sigma_3`.
    pub ratio: f64,
    /// `sigma_1 >= sigma_2 >= sigma_3`.
    pub singular_values: [f64; 3],
    /// The fitted `A` (row-major: `y[r] = translation[r] + sum_c A[r][c] x[c]`).
    pub linear_map: [[f64; 3]; 3],
    /// The fitted `c`.
    pub translation: [f64; 3],
}

/// The order-1 representation as an ellipsoid `center + axes x~`, `|x~| = 1` (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OrderOneEllipsoid {
    /// Its centre `sqrt(q1 / (4 pi)) C_0^0`.
    pub center: [f64; 3],
    /// `sqrt(3 q1 / (4 pi)) [C_1^1 | C_1^-1 | C_1^0]` (row-major).
    pub axes: [[f64; 3]; 3],
    /// Singular values of `axes` (the semi-axis lengths), largest first.
    pub semi_axes: [f64; 3],
}

impl OrderOneEllipsoid {
    /// `semi_axes[0] / semi_axes[2]`.
    pub fn aspect_ratio(&self) -> f64 {
        self.semi_axes[0] / self.semi_axes[2]
    }
}

/// Aspect ratio `sigma_1 / sigma_3` of the order-1 representation of `values` (the vertices) at
/// `cap_points` on `Z >= z_star`, as described in the module docs.
pub fn aspect_ratio(cap_points: &[[f64; 3]], values: &[[f64; 3]], z_star: f64) -> Result<AspectRatio, HarmonicsError> {
    aspect_ratio_in(BasisKind::Adaptive, cap_points, values, z_star)
}

/// As [`aspect_ratio`], with the order-1 representation in the basis `kind`.
pub fn aspect_ratio_in(
    kind: BasisKind,
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
) -> Result<AspectRatio, HarmonicsError> {
    let order_one = fit_in(kind, cap_points, values, z_star, 1)?;
    let y = order_one.reconstruct(cap_points, 1)?;
    let k = cap_points.len();
    let unit = |i: usize| {
        let p = cap_points[i];
        let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / norm, p[1] / norm, p[2] / norm]
    };
    let design = Mat::from_fn(k, 4, |i, j| if j == 0 { 1.0 } else { unit(i)[j - 1] });
    let rhs = Mat::from_fn(k, 3, |i, c| y[i][c]);
    let qr = Qr::new(design.as_ref());
    let r = qr.R();
    let largest = (0..4).map(|j| r[(j, j)].abs()).fold(0.0f64, f64::max);
    let tolerance = k as f64 * f64::EPSILON * largest;
    if let Some(j) = (0..4).find(|&j| r[(j, j)].is_nan() || r[(j, j)].abs() <= tolerance) {
        return Err(HarmonicsError::RankDeficient {
            column: j,
            n: usize::from(j > 0),
            m: 0,
            pivot: r[(j, j)].abs(),
            largest,
        });
    }
    let solution = qr.solve_lstsq(rhs.as_ref());
    let translation = [solution[(0, 0)], solution[(0, 1)], solution[(0, 2)]];
    let linear_map: [[f64; 3]; 3] = std::array::from_fn(|row| std::array::from_fn(|col| solution[(1 + col, row)]));
    let singular_values = singular_values(&linear_map)?;
    Ok(AspectRatio {
        ratio: ratio(singular_values)?,
        singular_values,
        linear_map,
        translation,
    })
}

/// The exact ellipsoid of the order-1 terms of `fit` (module docs); `fit.order` must be at
/// least 1. For the least-squares order-1 representation pass a fit made at order 1. Adaptive
/// harmonics only ([`HarmonicsError::WrongBasis`] otherwise).
pub fn order_one_ellipsoid(fit: &HarmonicFit) -> Result<OrderOneEllipsoid, HarmonicsError> {
    let basis = match fit.basis()? {
        HarmonicBasis::Adaptive(b) => b,
        HarmonicBasis::SphericalCap(_) => {
            return Err(HarmonicsError::WrongBasis { expected: "ah", found: fit.basis.name() });
        }
    };
    if fit.order < 1 {
        return Err(HarmonicsError::InvalidFit {
            order: fit.order,
            expected: 4,
            found: fit.coefficients.len(),
        });
    }
    let c = &fit.coefficients;
    let zonal = (basis.q1() / (4.0 * std::f64::consts::PI)).sqrt();
    let linear = 3.0f64.sqrt() * zonal;
    // Columns x~_1, x~_2, x~_3 carry C_1^1 (index 3), C_1^-1 (index 1), C_1^0 (index 2).
    let columns = [c[3], c[1], c[2]];
    let axes: [[f64; 3]; 3] = std::array::from_fn(|row| std::array::from_fn(|col| linear * columns[col][row]));
    let semi_axes = singular_values(&axes)?;
    Ok(OrderOneEllipsoid {
        center: [zonal * c[0][0], zonal * c[0][1], zonal * c[0][2]],
        axes,
        semi_axes,
    })
}

/// Singular values of a 3x3 matrix, largest first.
fn singular_values(a: &[[f64; 3]; 3]) -> Result<[f64; 3], HarmonicsError> {
    if !a.iter().flatten().all(|v| v.is_finite()) {
        return Err(HarmonicsError::SvdFailed);
    }
    // nalgebra's bidiagonalising SVD; `0` iterations means "until converged".
    let svd = Matrix3::from_fn(|i, j| a[i][j]).try_svd(false, false, f64::EPSILON, 0).ok_or(HarmonicsError::SvdFailed)?;
    let mut out = [svd.singular_values[0], svd.singular_values[1], svd.singular_values[2]];
    out.sort_by(|x, y| y.total_cmp(x));
    Ok(out)
}

fn ratio(s: [f64; 3]) -> Result<f64, HarmonicsError> {
    if s.iter().any(|v| v.is_nan()) || s[0] <= 0.0 || s[2] <= s[0] * 1e-14 {
        return Err(HarmonicsError::DegenerateShape { singular_values: s });
    }
    Ok(s[0] / s[2])
}
