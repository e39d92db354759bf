//! Gauss-Legendre quadrature on `[-1, 1]`, for integrating over the cap in `cos(theta)`: the
//! adaptive harmonics are orthonormal for `d(cos theta) d(phi)` (paper Eq. (22)-(24)), and a
//! product of two of them at equal `|m|` is a polynomial in `cos(theta)`, which an `n`-point rule
//! integrates exactly up to degree `2n - 1`.
//!
//! Nodes are the roots of the Legendre polynomial `P_n`, found by Newton's method from the
//! asymptotic guesses `cos(pi (i - 1/4) / (n + 1/2))`; weights are `2 / ((1 - x^2) P_n'(x)^2)`.

use super::HarmonicsError;

/// Largest number of nodes [`gauss_legendre`] accepts.
pub const MAX_NODES: usize = 10_000;

/// `(node, weight)` pairs of the `n`-point Gauss-Legendre rule on `[-1, 1]`, nodes in decreasing
/// order. `n = 0` gives an empty rule.
pub fn gauss_legendre(n: usize) -> Result<Vec<(f64, f64)>, HarmonicsError> {
    if n > MAX_NODES {
        return Err(HarmonicsError::OrderTooLarge {
            order: n,
            max: MAX_NODES,
        });
    }
    let nf = n as f64;
    let mut rule = Vec::with_capacity(n);
    for i in 1..=n {
        let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (nf + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            let (p, dp) = legendre_and_derivative(n, x);
            derivative = dp;
            let step = p / dp;
            x -= step;
            if step.abs() <= 1e-16 * x.abs().max(1e-3) {
                derivative = legendre_and_derivative(n, x).1;
                break;
            }
        }
        let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
        rule.push((x, weight));
    }
    Ok(rule)
}

/// `(P_n(x), P_n'(x))` for `|x| < 1` by the three-term recurrence.
fn legendre_and_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut older, mut old) = (0.0, 1.0);
    for k in 1..=n {
        let kf = k as f64;
        let value = ((2.0 * kf - 1.0) * x * old - (kf - 1.0) * older) / kf;
        older = old;
        old = value;
    }
    let derivative = n as f64 * (x * old - older) / (x * x - 1.0);
    (old, derivative)
}
