//! Least-squares adaptive harmonics representation of a surface (paper Sec. "Adaptive
//! Harmonics (AH)", Eq. (26)-(28)): `V ~ A C`, with `V` the `k x 3` vertex coordinates, `A` the
//! `k x (N + 1)^2` matrix of the basis functions of [`super::basis`] at the vertices' cap
//! positions and `C` the coefficients.
//!
//! # Solver
//!
//! The paper writes the pseudo-inverse as `(A^T A)^-1 A^T V` (Eq. 28). Forming `A^T A` squares
//! the condition number, so `C` is computed from a Householder QR factorization `A = Q R`
//! (faer's dense blocked QR): `C = R^-1 (Q^T V)`. Because the columns are ordered by order `n`,
//! the first `(n + 1)^2` columns of `Q R` are the QR factorization of the order-`n` matrix, so one
//! factorization gives the exact least-squares fit at *every* order `n <= N`
//! ([`fit_all_orders`]): the leading block of `R` and the leading rows of `Q^T V`. This is the
//! same as refitting at each order, not a truncation of the order-`N` coefficients (the basis is
//! orthonormal on the cap, Eq. 22-24, but not on a finite point set).
//!
//! [`fit_with_errors_in`] also measures every order's reconstruction error and the top order's
//! reconstruction from the same design matrix (one product with every order's coefficients side
//! by side), so that the basis is evaluated once per point; [`order_errors`] and
//! [`HarmonicFit::reconstruct`] evaluate it again, for fits from elsewhere.
//!
//! A column whose diagonal entry `|R_jj|` falls below `max(k, p) eps max|R_ii|` is reported as
//! [`HarmonicsError::RankDeficient`] instead of producing huge coefficients.
//!
//! With the adaptive harmonics every reconstruction is constant along the cap's boundary circle
//! (see [`super::basis`], "The boundary circle"): for an open surface,
//! [`OrderError::max_distance`] stays near the size of the boundary loop at every order. The
//! spherical cap harmonics ([`super::scha`], [`BasisKind::SphericalCap`]) have the same layout
//! (`(N + 1)^2` functions, orders in sequence), so the same solver fits them
//! ([`fit_all_orders_in`]) and their reconstruction keeps the boundary loop (Neumann or mixed).
//!
//! # Cost
//!
//! Building `A` is `O(k N^2)`; the QR is about `2 k p^2` flops (`p = (N + 1)^2`) and needs two
//! copies of `A` (`16 k p` bytes) at its peak: for `k = 50 000` points and `N = 20` that is
//! 19 GFlop and 350 MB.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::householder;
use faer::linalg::solvers::Qr;
use faer::{Conj, Mat};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::any_basis::{BasisPoint, HarmonicBasis};
use super::basis::{basis_degree, basis_len};
use super::kind::BasisKind;
use super::HarmonicsError;

/// Largest design matrix (`points * (order + 1)^2` entries) the fit builds: 1.6 GB of `f64`
/// (twice that at the QR's peak).
pub const MAX_DESIGN_ENTRIES: usize = 200_000_000;

/// Rows of the design matrix filled per parallel task.
const ROW_CHUNK: usize = 512;

/// Harmonic coefficients of a surface: `v(theta, phi) ~ sum_(n <= order) sum_m C_n^m
/// A_n^m(theta, phi)` (Eq. 27), `A_n^m` the adaptive harmonics or the spherical cap harmonics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HarmonicFit {
    /// The basis (default, also when absent from JSON: the adaptive harmonics).
    #[serde(default)]
    pub basis: BasisKind,
    /// The cap's lower bound `Z*`.
    pub z_star: f64,
    /// The largest order `N`.
    pub order: usize,
    /// `C_n^m` (one `[x, y, z]` per basis function) in [`super::basis::basis_index`] order,
    /// `(order + 1)^2` of them.
    pub coefficients: Vec<[f64; 3]>,
}

/// Reconstruction error of the fit at one order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OrderError {
    /// The order `n` of the fit.
    pub order: usize,
    /// Mean Euclidean distance between reconstructed and original points.
    pub mean_distance: f64,
    /// Largest such distance.
    pub max_distance: f64,
    /// `mean_distance` divided by the original points' bounding-box diagonal.
    pub mean_relative: f64,
    /// `max_distance` divided by the original points' bounding-box diagonal.
    pub max_relative: f64,
}

/// Least-squares fit of `values` (one per point, typically the mesh vertices) at the cap
/// positions `cap_points` on `Z >= z_star` with the `(order + 1)^2` adaptive harmonics of
/// orders `n <= order`.
pub fn fit(
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
    order: usize,
) -> Result<HarmonicFit, HarmonicsError> {
    fit_in(BasisKind::Adaptive, cap_points, values, z_star, order)
}

/// As [`fit`], in the basis `kind`.
pub fn fit_in(
    kind: BasisKind,
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
    order: usize,
) -> Result<HarmonicFit, HarmonicsError> {
    let mut fits = fit_all_orders_in(kind, cap_points, values, z_star, order)?;
    fits.pop().ok_or(HarmonicsError::TooFewPoints {
        points: cap_points.len(),
        basis: basis_len(order),
        order,
    })
}

/// The least-squares fits at every order `0..=order` (element `n` is the fit at order `n`), from
/// one QR factorization (see the module docs), in the adaptive harmonics.
pub fn fit_all_orders(
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
    order: usize,
) -> Result<Vec<HarmonicFit>, HarmonicsError> {
    fit_all_orders_in(BasisKind::Adaptive, cap_points, values, z_star, order)
}

/// As [`fit_all_orders`], in the basis `kind`.
pub fn fit_all_orders_in(
    kind: BasisKind,
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
    order: usize,
) -> Result<Vec<HarmonicFit>, HarmonicsError> {
    Ok(solve(kind, cap_points, values, z_star, order)?.0)
}

/// The fits of every order (as [`fit_all_orders_in`]) with their reconstruction errors (as
/// [`order_errors`]) and the order-`order` reconstruction at `cap_points` (as
/// [`HarmonicFit::reconstruct`]), all from the one design matrix of the fit: the basis is
/// evaluated once per point instead of three times (the dominant cost of a spherical cap
/// basis, whose radial functions are polynomial expansions of a few dozen terms).
pub fn fit_with_errors_in(
    kind: BasisKind,
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
    order: usize,
) -> Result<FitWithErrors, HarmonicsError> {
    let (fits, design) = solve(kind, cap_points, values, z_star, order)?;
    // Every order's coefficients side by side (zero past its own functions): one product
    // gives every order's reconstruction at every point.
    let p = design.ncols();
    let stacked = Mat::from_fn(p, 3 * fits.len(), |j, col| {
        let coefficients = &fits[col / 3].coefficients;
        coefficients.get(j).map_or(0.0, |c| c[col % 3])
    });
    let product = &design * &stacked;
    drop(design);
    let orders = fits.len();
    let distances: Vec<f64> = (0..values.len())
        .flat_map(|i| {
            let product = &product;
            (0..orders).map(move |n| distance([product[(i, 3 * n)], product[(i, 3 * n + 1)], product[(i, 3 * n + 2)]], values[i]))
        })
        .collect();
    let errors = summarize(&fits, &distances, values);
    let top = 3 * (orders - 1);
    let reconstructed = (0..values.len()).map(|i| [product[(i, top)], product[(i, top + 1)], product[(i, top + 2)]]).collect();
    Ok(FitWithErrors { fits, errors, reconstructed })
}

/// What [`fit_with_errors_in`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct FitWithErrors {
    /// The least-squares fit at every order `0..=order` (element `n` at order `n`).
    pub fits: Vec<HarmonicFit>,
    /// Each fit's reconstruction error, as [`order_errors`] measures it.
    pub errors: Vec<OrderError>,
    /// The order-`order` fit evaluated at the cap points.
    pub reconstructed: Vec<[f64; 3]>,
}

/// The fits of every order and the design matrix they were solved from.
fn solve(
    kind: BasisKind,
    cap_points: &[[f64; 3]],
    values: &[[f64; 3]],
    z_star: f64,
    order: usize,
) -> Result<(Vec<HarmonicFit>, Mat<f64>), HarmonicsError> {
    let basis = HarmonicBasis::new(kind, z_star, order)?;
    let (k, p) = (cap_points.len(), basis.len());
    if values.len() != k {
        return Err(HarmonicsError::LengthMismatch {
            points: k,
            values: values.len(),
        });
    }
    if k < p {
        return Err(HarmonicsError::TooFewPoints {
            points: k,
            basis: p,
            order,
        });
    }
    let entries = k.saturating_mul(p);
    if entries > MAX_DESIGN_ENTRIES {
        return Err(HarmonicsError::TooLarge {
            entries,
            max: MAX_DESIGN_ENTRIES,
        });
    }
    if let Some(index) = values.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
        return Err(HarmonicsError::NonFinite { what: "value", index });
    }
    let coords = coordinates(&basis, cap_points)?;

    let design = design_matrix(&basis, &coords);
    let qr = Qr::new(design.as_ref());

    let r = qr.R();
    let largest = (0..p).map(|j| r[(j, j)].abs()).fold(0.0f64, f64::max);
    let tolerance = k.max(p) as f64 * f64::EPSILON * largest;
    for j in 0..p {
        let pivot = r[(j, j)].abs();
        if pivot.is_nan() || pivot <= tolerance {
            let (n, m) = basis_degree(j);
            return Err(HarmonicsError::RankDeficient {
                column: j,
                n,
                m,
                pivot,
                largest,
            });
        }
    }

    // Q^T V, whose leading rows are the right-hand sides of every truncated problem.
    let mut rhs = Mat::from_fn(k, 3, |i, c| values[i][c]);
    let block = qr.Q_coeff().nrows();
    let par = faer::get_global_parallelism();
    let mut buffer = MemBuffer::new(
        householder::apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<f64>(k, block, 3),
    );
    householder::apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
        qr.Q_basis(),
        qr.Q_coeff(),
        Conj::Yes,
        rhs.as_mut(),
        par,
        MemStack::new(&mut buffer),
    );

    let mut fits = Vec::with_capacity(order + 1);
    for n in 0..=order {
        let size = basis_len(n);
        let mut coefficients = vec![[0.0; 3]; size];
        for c in 0..3 {
            for i in (0..size).rev() {
                let mut sum = rhs[(i, c)];
                for (j, coefficient) in coefficients.iter().enumerate().take(size).skip(i + 1) {
                    sum -= r[(i, j)] * coefficient[c];
                }
                coefficients[i][c] = sum / r[(i, i)];
            }
        }
        fits.push(HarmonicFit {
            basis: kind,
            z_star,
            order: n,
            coefficients,
        });
    }
    Ok((fits, design))
}

impl HarmonicFit {
    /// The basis this fit is expressed in; checks that the fit is consistent.
    pub fn basis(&self) -> Result<HarmonicBasis, HarmonicsError> {
        self.check()?;
        HarmonicBasis::new(self.basis, self.z_star, self.order)
    }

    /// Checks that the fit has `(order + 1)^2` finite coefficients (without building its basis).
    pub fn check(&self) -> Result<(), HarmonicsError> {
        let expected = basis_len(self.order);
        if self.coefficients.len() != expected || !self.coefficients.iter().flatten().all(|c| c.is_finite()) {
            return Err(HarmonicsError::InvalidFit {
                order: self.order,
                expected,
                found: self.coefficients.len(),
            });
        }
        Ok(())
    }

    /// The representation at `cap_points` using only the terms of orders
    /// `n <= min(order_limit, self.order)` (Eq. 27). This *truncates* the coefficients; for the
    /// least-squares fit at a lower order use [`fit_all_orders`].
    pub fn reconstruct(&self, cap_points: &[[f64; 3]], order_limit: usize) -> Result<Vec<[f64; 3]>, HarmonicsError> {
        let basis = self.basis()?;
        let limit = order_limit.min(self.order);
        let coords = coordinates(&basis, cap_points)?;
        let coefficients = &self.coefficients[..basis_len(limit)];
        Ok(coords
            .par_chunks(ROW_CHUNK)
            .flat_map_iter(|chunk| {
                let (mut scratch, mut values) = (Vec::new(), vec![0.0; basis.len()]);
                chunk
                    .iter()
                    .map(|c| {
                        basis.fill(c, &mut scratch, &mut values);
                        combine(&values[..coefficients.len()], coefficients)
                    })
                    .collect::<Vec<_>>()
            })
            .collect())
    }

    /// Reconstruction error at every order `0..=self.order` against the `original` points
    /// (normally the values this fit was made from), each order *refitted* by least squares
    /// on `cap_points` and `original` (one QR, see [`fit_all_orders`]): only `z_star` and
    /// `order` of `self` are used. Relative errors are divided by the bounding-box diagonal of
    /// `original` (when that is 0 they are 0 for a zero distance and infinite otherwise).
    pub fn errors_by_order(
        &self,
        cap_points: &[[f64; 3]],
        original: &[[f64; 3]],
    ) -> Result<Vec<OrderError>, HarmonicsError> {
        let fits = fit_all_orders_in(self.basis, cap_points, original, self.z_star, self.order)?;
        order_errors(&fits, cap_points, original)
    }
}

/// Reconstruction error of each fit in `fits` (for instance the output of [`fit_all_orders`])
/// against the `original` points at `cap_points`, one [`OrderError`] per fit in the same order.
/// Every fit must have the same `z_star` ([`HarmonicsError::MixedZStar`] otherwise). Relative errors are divided by the bounding-box
/// diagonal of `original` (when that is 0 they are 0 for a zero distance and infinite
/// otherwise). The basis is evaluated once per point, at the largest order.
pub fn order_errors(
    fits: &[HarmonicFit],
    cap_points: &[[f64; 3]],
    original: &[[f64; 3]],
) -> Result<Vec<OrderError>, HarmonicsError> {
    let Some(first) = fits.first() else {
        return Ok(Vec::new());
    };
    if original.len() != cap_points.len() {
        return Err(HarmonicsError::LengthMismatch {
            points: cap_points.len(),
            values: original.len(),
        });
    }
    let z_star = first.z_star;
    for f in fits {
        f.check()?;
        if f.z_star.to_bits() != z_star.to_bits() {
            return Err(HarmonicsError::MixedZStar {
                first: z_star,
                other: f.z_star,
            });
        }
        if f.basis != first.basis {
            return Err(HarmonicsError::WrongBasis {
                expected: first.basis.name(),
                found: f.basis.name(),
            });
        }
    }
    let top = fits.iter().map(|f| f.order).max().unwrap_or(0);
    let basis = HarmonicBasis::new(first.basis, z_star, top)?;
    let coords = coordinates(&basis, cap_points)?;
    let orders = fits.len();
    // distances[i * orders + j]: distance of point i under fit j.
    let distances: Vec<f64> = coords
        .par_chunks(ROW_CHUNK)
        .zip(original.par_chunks(ROW_CHUNK))
        .flat_map_iter(|(chunk, targets)| {
            let (mut scratch, mut values) = (Vec::new(), vec![0.0; basis.len()]);
            let mut out = Vec::with_capacity(chunk.len() * orders);
            for (c, target) in chunk.iter().zip(targets) {
                basis.fill(c, &mut scratch, &mut values);
                for fit in fits {
                    let y = combine(&values[..fit.coefficients.len()], &fit.coefficients);
                    out.push(distance(y, *target));
                }
            }
            out.into_iter()
        })
        .collect();
    Ok(summarize(fits, &distances, original))
}

/// Mean and max of `distances[i * fits.len() + j]` (point `i` under fit `j`) per fit, also
/// relative to the bounding-box diagonal of `original`.
fn summarize(fits: &[HarmonicFit], distances: &[f64], original: &[[f64; 3]]) -> Vec<OrderError> {
    let orders = fits.len();
    let diagonal = bounding_box_diagonal(original);
    let relative = |d: f64| {
        if diagonal > 0.0 {
            d / diagonal
        } else if d == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    };
    let k = original.len().max(1) as f64;
    fits
        .iter()
        .enumerate()
        .map(|(j, fit)| {
            let (sum, max) = distances
                .iter()
                .skip(j)
                .step_by(orders)
                .fold((0.0, 0.0f64), |(s, m), &d| (s + d, m.max(d)));
            let mean = sum / k;
            OrderError {
                order: fit.order,
                mean_distance: mean,
                max_distance: max,
                mean_relative: relative(mean),
                max_relative: relative(max),
            }
        })
        .collect()
}

/// Checked coordinates of every point (first bad point reported).
pub(crate) fn coordinates(basis: &HarmonicBasis, cap_points: &[[f64; 3]]) -> Result<Vec<BasisPoint>, HarmonicsError> {
    cap_points
        .iter()
        .enumerate()
        .map(|(i, &p)| basis.coordinates(i, p))
        .collect()
}

/// The `k x p` matrix of the basis at the points, filled in parallel by row blocks.
fn design_matrix(basis: &HarmonicBasis, coords: &[BasisPoint]) -> Mat<f64> {
    let p = basis.len();
    let mut design = Mat::<f64>::zeros(coords.len(), p);
    design
        .par_row_chunks_mut(ROW_CHUNK)
        .zip(coords.par_chunks(ROW_CHUNK))
        .for_each(|(mut block, chunk)| {
            let (mut scratch, mut values) = (Vec::new(), vec![0.0; p]);
            for (i, c) in chunk.iter().enumerate() {
                basis.fill(c, &mut scratch, &mut values);
                for (j, &v) in values.iter().enumerate() {
                    block[(i, j)] = v;
                }
            }
        });
    design
}

/// `sum_j values[j] * coefficients[j]`.
fn combine(values: &[f64], coefficients: &[[f64; 3]]) -> [f64; 3] {
    let mut y = [0.0; 3];
    for (v, c) in values.iter().zip(coefficients) {
        for d in 0..3 {
            y[d] += v * c[d];
        }
    }
    y
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

pub(crate) fn bounding_box_diagonal(points: &[[f64; 3]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in points {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    if points.is_empty() {
        return 0.0;
    }
    distance(lo, hi)
}
