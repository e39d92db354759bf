//! Associated Legendre functions `P_n^m(x)`, `0 <= m <= n <= N`, on `[-1, 1]` (paper Sec.
//! "Adaptive Harmonics (AH)", the ALP definition before Eq. (22)).
//!
//! # Convention
//!
//! `P_n^m` is the paper's
//!
//! ```text
//! P_n^m(x) = (-1)^m / (2^n n!) (1 - x^2)^(m/2) d^(n+m)/dx^(n+m) (x^2 - 1)^n,
//! ```
//!
//! so it carries the Condon-Shortley phase `(-1)^m`: `P_1^1(x) = -sqrt(1 - x^2)`. Since
//! `(n + m)! / (n - m)!` overflows `f64` near `n = 85`, the functions are computed in the *fully
//! normalized* form
//!
//! ```text
//! Pbar_n^m(x) = sqrt((2n + 1) / 2 * (n - m)! / (n + m)!) P_n^m(x),
//! integral_{-1}^{1} Pbar_n^m(x) Pbar_k^m(x) dx = delta_nk,
//! ```
//!
//! by the recurrences (each applied to normalized values, so nothing overflows; `s = sqrt(1 - x^2)`)
//!
//! ```text
//! Pbar_0^0     = 1 / sqrt(2)
//! Pbar_m^m     = -sqrt((2m + 1) / (2m)) s Pbar_(m-1)^(m-1)                (from P_m^m = -(2m-1) s P_(m-1)^(m-1))
//! Pbar_(m+1)^m = sqrt(2m + 3) x Pbar_m^m                                  (from P_(m+1)^m = (2m+1) x P_m^m)
//! Pbar_n^m     = a_nm (x Pbar_(n-1)^m - Pbar_(n-2)^m / a_(n-1)m),  a_nm = sqrt((4n^2 - 1) / (n^2 - m^2))
//! ```
//!
//! the last one being `(n - m) P_n^m = (2n - 1) x P_(n-1)^m - (n + m - 1) P_(n-2)^m` rescaled.
//! All recurrences run upward in `n` at fixed `m`, the stable direction. Values are stored in a
//! flat triangle indexed by [`triangle_index`]`(n, m) = n (n + 1) / 2 + m`.

use super::HarmonicsError;

/// Largest order `N` the Legendre tables and the harmonic bases accept.
pub const MAX_ORDER: usize = 500;

/// Number of `(n, m)` pairs with `0 <= m <= n <= n_max`: `(n_max + 1)(n_max + 2) / 2`
/// (saturating).
pub fn triangle_len(n_max: usize) -> usize {
    triangle_index(n_max.saturating_add(1), 0)
}

/// Position of `(n, m)` (with `m <= n`) in the flat triangle: `n (n + 1) / 2 + m` (saturating).
pub fn triangle_index(n: usize, m: usize) -> usize {
    let (a, b) = if n % 2 == 0 {
        (n / 2, n.saturating_add(1))
    } else {
        (n, n / 2 + 1)
    };
    a.saturating_mul(b).saturating_add(m)
}

/// The fully normalized `Pbar_n^m` for every `0 <= m <= n <= n_max` at one `x`, flat, indexed by
/// [`triangle_index`]. See the module docs for the normalization.
pub fn normalized_legendre(x: f64, n_max: usize) -> Result<Vec<f64>, HarmonicsError> {
    let table = NormalizedLegendre::new(n_max)?;
    let mut out = Vec::new();
    table.fill(x, &mut out)?;
    Ok(out)
}

/// The paper's (unnormalized) `P_n^m(x)`, Condon-Shortley phase included; computed as the
/// normalized value divided by its normalization. Returns [`HarmonicsError::Overflow`] when the
/// value does not fit in `f64` (large `m`, around `n = m > 150`).
pub fn associated_legendre(n: usize, m: usize, x: f64) -> Result<f64, HarmonicsError> {
    if m > n {
        return Err(HarmonicsError::InvalidDegree { n, m });
    }
    let values = normalized_legendre(x, n)?;
    let normalized = values[triangle_index(n, m)];
    // ln of (n + m)! / (n - m)! as a sum, to stay finite for any n.
    let ln_ratio: f64 = (n - m + 1..=n + m).map(|k| (k as f64).ln()).sum();
    let ln_scale = 0.5 * (ln_ratio + (2.0 / (2 * n + 1) as f64).ln());
    let value = normalized * ln_scale.exp();
    if normalized != 0.0 && !value.is_finite() {
        return Err(HarmonicsError::Overflow { n, m });
    }
    Ok(if normalized == 0.0 { 0.0 } else { value })
}

/// Recurrence coefficients for all `Pbar_n^m` up to one order, kept so that evaluating at many
/// points costs no square roots beyond one per point.
#[derive(Debug, Clone)]
pub struct NormalizedLegendre {
    n_max: usize,
    /// `-sqrt((2m + 1) / (2m))` for `m = 1..=n_max` (index `m`; index 0 unused).
    diagonal: Vec<f64>,
    /// `sqrt(2m + 3)` for `m = 0..n_max`.
    first: Vec<f64>,
    /// `a_nm` at `triangle_index(n, m)` (used for `n >= m + 2`).
    a: Vec<f64>,
    /// `1 / a_(n-1)m` at `triangle_index(n, m)` (used for `n >= m + 2`).
    b: Vec<f64>,
}

impl NormalizedLegendre {
    /// Coefficients up to order `n_max` (at most [`MAX_ORDER`]).
    pub fn new(n_max: usize) -> Result<Self, HarmonicsError> {
        if n_max > MAX_ORDER {
            return Err(HarmonicsError::OrderTooLarge {
                order: n_max,
                max: MAX_ORDER,
            });
        }
        let len = triangle_len(n_max);
        let mut diagonal = vec![0.0; n_max + 1];
        let mut first = vec![0.0; n_max + 1];
        let (mut a, mut b) = (vec![0.0; len], vec![0.0; len]);
        for m in 0..=n_max {
            let mf = m as f64;
            if m > 0 {
                diagonal[m] = -((2.0 * mf + 1.0) / (2.0 * mf)).sqrt();
            }
            first[m] = (2.0 * mf + 3.0).sqrt();
            for n in m + 2..=n_max {
                let nf = n as f64;
                let n1 = nf - 1.0;
                a[triangle_index(n, m)] = ((4.0 * nf * nf - 1.0) / ((nf - mf) * (nf + mf))).sqrt();
                b[triangle_index(n, m)] = (((n1 - mf) * (n1 + mf)) / (4.0 * n1 * n1 - 1.0)).sqrt();
            }
        }
        Ok(Self {
            n_max,
            diagonal,
            first,
            a,
            b,
        })
    }

    /// The largest order.
    pub fn order(&self) -> usize {
        self.n_max
    }

    /// All `Pbar_n^m(x)` into `out` (resized to [`triangle_len`]). `x` must be in `[-1, 1]`.
    pub fn fill(&self, x: f64, out: &mut Vec<f64>) -> Result<(), HarmonicsError> {
        if !(-1.0..=1.0).contains(&x) {
            return Err(HarmonicsError::ArgumentOutOfRange { x });
        }
        let s = ((1.0 - x) * (1.0 + x)).max(0.0).sqrt();
        self.fill_with_sine(x, s, out);
        Ok(())
    }

    /// As [`Self::fill`] with `s = sqrt(1 - x^2)` given by the caller, who may know it more
    /// accurately than `1 - x^2` does (near `x = +-1`). `x` in `[-1, 1]`, `s >= 0` unchecked.
    pub(crate) fn fill_with_sine(&self, x: f64, s: f64, out: &mut Vec<f64>) {
        let n_max = self.n_max;
        out.clear();
        out.resize(triangle_len(n_max), 0.0);
        let mut pmm = std::f64::consts::FRAC_1_SQRT_2;
        for m in 0..=n_max {
            if m > 0 {
                pmm *= self.diagonal[m] * s;
            }
            out[triangle_index(m, m)] = pmm;
            if m == n_max {
                break;
            }
            let mut older = pmm;
            let mut old = self.first[m] * x * pmm;
            out[triangle_index(m + 1, m)] = old;
            for n in m + 2..=n_max {
                let k = triangle_index(n, m);
                let value = self.a[k] * (x * old - self.b[k] * older);
                out[k] = value;
                older = old;
                old = value;
            }
        }
    }
}
