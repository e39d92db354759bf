//! Legendre functions of non-integer degree on a spherical cap: the radial parts
//! `Theta_j^m(theta)` of the spherical cap harmonics (Haines 1985; Shaqfa, Choi and Beyer 2021),
//! computed numerically for one order `m` and one rim condition.
//!
//! # The problem
//!
//! On the cap `0 <= theta <= theta_c` (`x = cos(theta)` in `[Z*, 1]`, `Z* = cos(theta_c)`),
//! the Sturm-Liouville problem
//!
//! ```text
//! -((1 - x^2) Theta')' + m^2 / (1 - x^2) Theta = lambda Theta,     lambda = nu (nu + 1),
//! ```
//!
//! regular at the pole `x = 1`, with `dTheta/dtheta = 0` (Neumann) or `Theta = 0` (Dirichlet) at
//! `x = Z*`. Its eigenvalues `lambda_0 < lambda_1 < ...` give the non-integer degrees `nu_j`;
//! the eigenfunctions `P_nu^-m(cos theta)` are orthogonal in `integral_{Z*}^{1} . dx`, the
//! sphere's area element once the azimuth is integrated.
//!
//! # The method: Rayleigh-Ritz in a weighted polynomial basis
//!
//! Every regular solution is `Theta = (1 - x^2)^(m/2) f(x)` with `f` analytic on `[Z*, 1]`
//! (a polynomial of degree `nu - m` when `nu` is an integer). The trial functions are
//!
//! ```text
//! Phi_i(x) = (1 - x^2)^(m/2) h(x) p_i(x),   i < n,   h = 1 (Neumann) or x - Z* (Dirichlet),
//! ```
//!
//! with `p_i` the polynomials orthonormal for the weight `(1 - x^2)^m h(x)^2` on `[Z*, 1]`, so
//! that the `Phi_i` are orthonormal in `dx` (no ill-conditioned Gram matrix, whatever `m` or the
//! cap size). The `p_i` come from the Lanczos process (with full reorthogonalization) on the
//! Gauss-Legendre discretization of that weight, which yields their three-term recurrence;
//! `n + m + 4` nodes integrate every product below exactly. The energy matrix
//!
//! ```text
//! K_ik = integral_{Z*}^{1} (1 - x^2) Phi_i' Phi_k' + m^2 / (1 - x^2) Phi_i Phi_k dx
//! ```
//!
//! is symmetric; its eigenpairs (faer's self-adjoint eigensolver, after a Cholesky reduction by
//! the computed mass matrix, which is the identity up to rounding) are the Ritz approximations.
//! The Neumann condition is the energy's natural boundary condition, so it needs no constraint;
//! the Dirichlet one is built into `h`. Ritz values converge from above and, the eigenfunctions
//! being analytic, geometrically in `n`: `n = 2 count + 24` trial functions give the lowest
//! `count` eigenvalues to near machine precision (tested against the hemisphere's integer
//! degrees and against the hypergeometric form of `P_nu^-m`). On caps close to the whole sphere
//! the eigenfunctions have a singularity at `x = -1`, just outside the cap, and the convergence
//! rate falls like `sqrt(1 + Z*)`: `3 / sqrt(1 + Z*)` more trial functions are used (at most
//! 160; at `Z* = -0.9999` the degrees are then accurate to about `1e-5`, which changes a fit
//! only through which functions it uses, not how well they are evaluated). Trailing
//! coefficients below `1e-11` of an eigenfunction's largest are dropped for evaluation.
//!
//! Each `Theta_j` is normalized to `integral_{Z*}^{1} Theta_j^2 dx = 1` and signed so that
//! `f(1) > 0` (positive next to the pole). At `Z* = -1` the Neumann functions are the
//! normalized associated Legendre functions of integer degree `m, m + 1, ...`.

use faer::{Mat, Side};

use super::quadrature::gauss_legendre;
use super::HarmonicsError;

/// Largest order of the spherical cap harmonics.
pub const MAX_CAP_ORDER: usize = 100;

/// Trial functions beyond twice the number of eigenfunctions wanted.
const EXTRA_TRIAL: usize = 24;

/// Largest number of further trial functions for caps close to the whole sphere.
const MAX_EXTRA_NEAR_SPHERE: usize = 160;

/// Relative size below which trailing coefficients of an eigenfunction are dropped.
const TRUNCATION: f64 = 1e-11;

/// The rim condition of one family (the mixed basis combines two families).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rim {
    /// `dTheta/dtheta = 0` at `theta_c`.
    Neumann,
    /// `Theta = 0` at `theta_c`.
    Dirichlet,
}

/// The lowest `count` radial functions `Theta_j^m`, `j < count`, of one order and rim condition.
#[derive(Debug, Clone)]
pub struct CapLegendre {
    m: usize,
    z_star: f64,
    rim: Rim,
    /// `p_0`, constant.
    p0: f64,
    /// Lanczos recurrence: `x p_i = beta[i + 1] p_(i+1) + alpha[i] p_i + beta[i] p_(i-1)`.
    alpha: Vec<f64>,
    beta: Vec<f64>,
    /// `1 / beta[i]` (0 for `i = 0`), to evaluate without divisions.
    inverse_beta: Vec<f64>,
    /// Degrees `nu_j`, ascending.
    degrees: Vec<f64>,
    /// Eigenvalues `lambda_j = nu_j (nu_j + 1)`.
    eigenvalues: Vec<f64>,
    /// `Theta_j = (1 - x^2)^(m/2) h(x) sum_(i < lengths[j]) coefficients[j * n + i] p_i(x)`.
    coefficients: Vec<f64>,
    /// Number of coefficients kept for each function (trailing ones below [`TRUNCATION`]
    /// times the largest dropped).
    lengths: Vec<usize>,
    /// Trial functions `n`.
    n: usize,
}

impl CapLegendre {
    /// The lowest `count` eigenfunctions of order `m` on `[z_star, 1]` with the rim condition
    /// `rim`. `z_star` must be in `[-1, 1)`.
    pub fn new(z_star: f64, m: usize, count: usize, rim: Rim) -> Result<Self, HarmonicsError> {
        if !(z_star.is_finite() && (-1.0..1.0).contains(&z_star) && 1.0 - z_star >= 1e-9) {
            return Err(HarmonicsError::InvalidZStar { z_star });
        }
        if m > MAX_CAP_ORDER || count > MAX_CAP_ORDER + 1 {
            return Err(HarmonicsError::OrderTooLarge {
                order: m.max(count),
                max: MAX_CAP_ORDER,
            });
        }
        // Near Z* = -1 the eigenfunctions have a nearby singularity at x = -1 (outside the
        // cap), which slows the polynomial convergence: more trial functions, ~ 1 / sqrt(1 + Z*).
        let near_sphere = (3.0 / (1.0 + z_star).max(1e-12).sqrt()).ceil().min(MAX_EXTRA_NEAR_SPHERE as f64) as usize;
        let n = 2 * count + EXTRA_TRIAL + near_sphere;
        let mut this = Self {
            m,
            z_star,
            rim,
            p0: 0.0,
            alpha: Vec::new(),
            beta: Vec::new(),
            inverse_beta: Vec::new(),
            degrees: Vec::new(),
            eigenvalues: Vec::new(),
            coefficients: Vec::new(),
            lengths: Vec::new(),
            n,
        };
        if count == 0 {
            return Ok(this);
        }
        let nodes = Nodes::new(z_star, n + m + 4)?;
        this.lanczos(&nodes)?;
        this.solve(&nodes, count)?;
        Ok(this)
    }

    /// The order `m`.
    pub fn order(&self) -> usize {
        self.m
    }

    /// Number of functions.
    pub fn len(&self) -> usize {
        self.degrees.len()
    }

    /// True when no function was asked for.
    pub fn is_empty(&self) -> bool {
        self.degrees.is_empty()
    }

    /// The degrees `nu_j`, ascending.
    pub fn degrees(&self) -> &[f64] {
        &self.degrees
    }

    /// Polynomial terms kept to evaluate each function (at most the trial size).
    pub fn terms(&self) -> &[usize] {
        &self.lengths
    }

    /// The eigenvalues `nu_j (nu_j + 1)`, ascending.
    pub fn eigenvalues(&self) -> &[f64] {
        &self.eigenvalues
    }

    /// `Theta_j(x)` for every `j` into `out[..self.len()]`, at `x = cos(theta)` in `[Z*, 1]` with
    /// `s = sin(theta)` given by the caller (more accurate near the pole than `sqrt(1 - x^2)`).
    /// `p` is scratch space.
    pub fn fill(&self, x: f64, s: f64, p: &mut Vec<f64>, out: &mut [f64]) {
        let Some(&longest) = self.lengths.iter().max() else {
            return;
        };
        self.polynomials_up_to(x, longest, p);
        let g = s.powi(self.m as i32) * self.h(x);
        for (j, o) in out.iter_mut().enumerate().take(self.len()) {
            let row = &self.coefficients[j * self.n..j * self.n + self.lengths[j]];
            *o = g * dot4(row, p);
        }
    }

    fn h(&self, x: f64) -> f64 {
        match self.rim {
            Rim::Neumann => 1.0,
            Rim::Dirichlet => x - self.z_star,
        }
    }

    fn h_derivative(&self) -> f64 {
        match self.rim {
            Rim::Neumann => 0.0,
            Rim::Dirichlet => 1.0,
        }
    }

    /// `p_i(x)`, `i < n`, by the recurrence.
    fn polynomials(&self, x: f64, p: &mut Vec<f64>) {
        self.polynomials_up_to(x, self.n, p);
    }

    /// `p_i(x)`, `i < len <= n`.
    fn polynomials_up_to(&self, x: f64, len: usize, p: &mut Vec<f64>) {
        p.clear();
        p.push(self.p0);
        let (mut older, mut old) = (0.0, self.p0);
        for i in 0..len.min(self.n).saturating_sub(1) {
            let next = ((x - self.alpha[i]) * old - self.beta[i] * older) * self.inverse_beta[i + 1];
            p.push(next);
            older = old;
            old = next;
        }
    }

    /// `p_i(x)` and `p_i'(x)`, `i < n`.
    fn polynomials_and_derivatives(&self, x: f64, p: &mut Vec<f64>, dp: &mut Vec<f64>) {
        self.polynomials(x, p);
        dp.clear();
        dp.push(0.0);
        let (mut older, mut old) = (0.0, 0.0);
        for i in 0..self.n - 1 {
            let next = ((x - self.alpha[i]) * old + p[i] - self.beta[i] * older) / self.beta[i + 1];
            dp.push(next);
            older = old;
            old = next;
        }
    }

    /// The recurrence of the polynomials orthonormal for `w_q (1 - x_q^2)^m h(x_q)^2`.
    fn lanczos(&mut self, nodes: &Nodes) -> Result<(), HarmonicsError> {
        let n = self.n;
        let root: Vec<f64> = (0..nodes.len())
            .map(|q| (nodes.w[q]).sqrt() * nodes.s[q].powi(self.m as i32) * self.h(nodes.x[q]).abs())
            .collect();
        let norm = dot(&root, &root).sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(HarmonicsError::CapEigenFailed { m: self.m, z_star: self.z_star });
        }
        self.p0 = 1.0 / norm;
        let mut vectors: Vec<Vec<f64>> = vec![root.iter().map(|v| v / norm).collect()];
        self.alpha = vec![0.0; n];
        self.beta = vec![0.0; n];
        for i in 0..n {
            let v = &vectors[i];
            let mut w: Vec<f64> = v.iter().zip(&nodes.x).map(|(a, x)| a * x).collect();
            self.alpha[i] = dot(v, &w);
            if i + 1 == n {
                break;
            }
            for (k, wk) in w.iter_mut().enumerate() {
                *wk -= self.alpha[i] * vectors[i][k] + if i > 0 { self.beta[i] * vectors[i - 1][k] } else { 0.0 };
            }
            for _ in 0..2 {
                for u in &vectors {
                    let c = dot(u, &w);
                    for (wk, uk) in w.iter_mut().zip(u) {
                        *wk -= c * uk;
                    }
                }
            }
            let b = dot(&w, &w).sqrt();
            if !(b > 1e-12 * (1.0 - self.z_star) && b.is_finite()) {
                return Err(HarmonicsError::CapEigenFailed { m: self.m, z_star: self.z_star });
            }
            self.beta[i + 1] = b;
            vectors.push(w.iter().map(|v| v / b).collect());
        }
        self.inverse_beta = self.beta.iter().map(|&b| if b > 0.0 { 1.0 / b } else { 0.0 }).collect();
        Ok(())
    }

    /// Mass and energy matrices by quadrature, the eigenpairs, the lowest `count` kept.
    fn solve(&mut self, nodes: &Nodes, count: usize) -> Result<(), HarmonicsError> {
        let (n, m) = (self.n, self.m as f64);
        let mut mass = vec![0.0; n * n];
        let mut energy = vec![0.0; n * n];
        let (mut p, mut dp) = (Vec::new(), Vec::new());
        let (mut phi, mut dphi) = (vec![0.0; n], vec![0.0; n]);
        for q in 0..nodes.len() {
            let (x, s, w) = (nodes.x[q], nodes.s[q], nodes.w[q]);
            self.polynomials_and_derivatives(x, &mut p, &mut dp);
            let sm = s.powi(self.m as i32);
            let g = sm * self.h(x);
            // g' = s^m h' - m x s^(m - 2) h; s > 0 at every Gauss node.
            let dg = sm * self.h_derivative() - if self.m > 0 { m * x * sm / (s * s) * self.h(x) } else { 0.0 };
            for i in 0..n {
                phi[i] = g * p[i];
                dphi[i] = dg * p[i] + g * dp[i];
            }
            let (a, b) = (w * s * s, w * m * m / (s * s));
            for i in 0..n {
                for k in 0..=i {
                    mass[i * n + k] += w * phi[i] * phi[k];
                    energy[i * n + k] += a * dphi[i] * dphi[k] + b * phi[i] * phi[k];
                }
            }
        }
        let fail = || HarmonicsError::CapEigenFailed { m: self.m, z_star: self.z_star };
        // Cholesky mass = L L^T (lower triangles filled above), then C = L^-1 K L^-T.
        let l = cholesky(&mass, n).ok_or_else(fail)?;
        let k_full = |i: usize, j: usize| if j <= i { energy[i * n + j] } else { energy[j * n + i] };
        // Y = L^-1 K (column by column forward substitution), then C = L^-1 Y^T.
        let mut y = vec![0.0; n * n];
        for col in 0..n {
            let column: Vec<f64> = (0..n).map(|i| k_full(i, col)).collect();
            let solved = forward(&l, n, &column);
            for i in 0..n {
                y[i * n + col] = solved[i];
            }
        }
        let mut c = Mat::<f64>::zeros(n, n);
        for row in 0..n {
            let column: Vec<f64> = (0..n).map(|j| y[row * n + j]).collect();
            let solved = forward(&l, n, &column);
            for (i, v) in solved.into_iter().enumerate() {
                c[(i, row)] = v;
            }
        }
        // Symmetrize away rounding.
        for i in 0..n {
            for j in 0..i {
                let v = 0.5 * (c[(i, j)] + c[(j, i)]);
                c[(i, j)] = v;
                c[(j, i)] = v;
            }
        }
        let eigen = c.self_adjoint_eigen(Side::Lower).map_err(|_| fail())?;
        let (values, vectors) = (eigen.S(), eigen.U());
        self.degrees.clear();
        self.eigenvalues.clear();
        self.coefficients = vec![0.0; count * n];
        let mut p_one = Vec::new();
        self.polynomials(1.0, &mut p_one);
        for j in 0..count {
            let lambda = values[j].max(0.0);
            if !lambda.is_finite() {
                return Err(fail());
            }
            // Back to the p_i basis: coefficients = L^-T y.
            let column: Vec<f64> = (0..n).map(|i| vectors[(i, j)]).collect();
            let mut coefficients = backward_transposed(&l, n, &column);
            let at_pole: f64 = coefficients.iter().zip(&p_one).map(|(a, b)| a * b).sum::<f64>() * self.h(1.0);
            if at_pole < 0.0 {
                coefficients.iter_mut().for_each(|v| *v = -*v);
            }
            let largest = coefficients.iter().fold(0.0f64, |a, c| a.max(c.abs()));
            let length = coefficients.iter().rposition(|c| c.abs() > TRUNCATION * largest).map_or(1, |i| i + 1);
            self.lengths.push(length);
            self.coefficients[j * n..(j + 1) * n].copy_from_slice(&coefficients);
            self.eigenvalues.push(lambda);
            self.degrees.push(0.5 * ((1.0 + 4.0 * lambda).sqrt() - 1.0));
        }
        Ok(())
    }
}

/// Gauss-Legendre nodes on `[Z*, 1]` with `s = sqrt(1 - x^2)` computed from `1 - x` and `1 + x`
/// without cancellation.
struct Nodes {
    x: Vec<f64>,
    s: Vec<f64>,
    w: Vec<f64>,
}

impl Nodes {
    fn new(z_star: f64, count: usize) -> Result<Self, HarmonicsError> {
        let half = 0.5 * (1.0 - z_star);
        let (mut x, mut s, mut w) = (Vec::new(), Vec::new(), Vec::new());
        for (t, weight) in gauss_legendre(count)? {
            let above = half * (1.0 - t);
            let below = half * (1.0 + t);
            x.push(1.0 - above);
            s.push((above * ((1.0 + z_star) + below)).max(0.0).sqrt());
            w.push(weight * half);
        }
        Ok(Self { x, s, w })
    }

    fn len(&self) -> usize {
        self.x.len()
    }
}

/// `sum a_i b_i` over the shorter slice with four partial sums (the evaluation's inner loop).
fn dot4(a: &[f64], b: &[f64]) -> f64 {
    let len = a.len().min(b.len());
    let (a, b) = (&a[..len], &b[..len]);
    let mut acc = [0.0; 4];
    let chunks = len / 4;
    for c in 0..chunks {
        for k in 0..4 {
            acc[k] += a[4 * c + k] * b[4 * c + k];
        }
    }
    let mut tail = 0.0;
    for i in 4 * chunks..len {
        tail += a[i] * b[i];
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Lower Cholesky factor (row-major `n x n`) of the matrix whose lower triangle is `a`.
fn cholesky(a: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let mut sum = a[i * n + j];
            for k in 0..j {
                sum -= l[i * n + k] * l[j * n + k];
            }
            if i == j {
                if !(sum > 0.0) {
                    return None;
                }
                l[i * n + i] = sum.sqrt();
            } else {
                l[i * n + j] = sum / l[j * n + j];
            }
        }
    }
    Some(l)
}

/// `L^-1 b`.
fn forward(l: &[f64], n: usize, b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; n];
    for i in 0..n {
        let mut sum = b[i];
        for k in 0..i {
            sum -= l[i * n + k] * out[k];
        }
        out[i] = sum / l[i * n + i];
    }
    out
}

/// `L^-T b`.
fn backward_transposed(l: &[f64], n: usize, b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; n];
    for i in (0..n).rev() {
        let mut sum = b[i];
        for k in i + 1..n {
            sum -= l[k * n + i] * out[k];
        }
        out[i] = sum / l[i * n + i];
    }
    out
}
