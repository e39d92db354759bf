//! Errors of the adaptive harmonics stage: one variant per cause.
//!
//! Every function of [`crate::harmonics`] checks its input and returns one of these instead of
//! panicking; each message says what is wrong, where (0-based point index) and what to do.

use thiserror::Error;

/// Why an adaptive harmonics computation cannot be done.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum HarmonicsError {
    /// `Z*` is not a finite number in `[-1, 1)`.
    #[error(
        "Z* = {z_star} is not a cap height: it must be finite and in [-1, 1) (Z* = -1 is the \
         whole sphere); pass the Z* of the parameterization report"
    )]
    InvalidZStar {
        /// The value given.
        z_star: f64,
    },

    /// The maximum order is larger than this module supports.
    #[error("order {order} is too large: at most {max} is supported")]
    OrderTooLarge {
        /// The order asked for.
        order: usize,
        /// The largest supported order.
        max: usize,
    },

    /// A Legendre argument outside `[-1, 1]` (or NaN).
    #[error("Legendre argument x = {x} is outside [-1, 1]")]
    ArgumentOutOfRange {
        /// The argument given.
        x: f64,
    },

    /// `P_n^m` was asked for with `m > n`.
    #[error("associated Legendre function P_{n}^{m} needs 0 <= m <= n")]
    InvalidDegree {
        /// Order `n`.
        n: usize,
        /// Degree `m`.
        m: usize,
    },

    /// The (unnormalized) result does not fit in an `f64`.
    #[error("P_{n}^{m} overflows f64; use the normalized functions instead")]
    Overflow {
        /// Order `n`.
        n: usize,
        /// Degree `m`.
        m: usize,
    },

    /// A coordinate is NaN or infinite.
    #[error("{what} {index} has a non-finite coordinate (NaN or infinity)")]
    NonFinite {
        /// `"cap point"` or `"value"`.
        what: &'static str,
        /// Index of the offending point.
        index: usize,
    },

    /// A cap point is not on the unit sphere.
    #[error(
        "cap point {index} has norm {norm}, not 1 (tolerance {tolerance}): pass the positions \
         on the cap (CapMap::cap), not the mesh vertices"
    )]
    NotOnUnitSphere {
        /// Index of the offending point.
        index: usize,
        /// Its Euclidean norm.
        norm: f64,
        /// The accepted deviation from 1.
        tolerance: f64,
    },

    /// A cap point lies below the cap `Z >= Z*`.
    #[error(
        "cap point {index} has Z = {z} < Z* = {z_star} (tolerance {tolerance}): it is not on \
         the cap; use the Z* the points were mapped with"
    )]
    OutsideCap {
        /// Index of the offending point.
        index: usize,
        /// Its height.
        z: f64,
        /// The cap's lower bound.
        z_star: f64,
        /// The accepted distance below `Z*`.
        tolerance: f64,
    },

    /// Point and value arrays of different lengths.
    #[error("{points} cap points but {values} values: give one value per point")]
    LengthMismatch {
        /// Number of points.
        points: usize,
        /// Number of values.
        values: usize,
    },

    /// A [`crate::harmonics::HarmonicFit`] whose coefficient count does not match its order
    /// (for instance edited JSON), or whose coefficients are not finite.
    #[error(
        "the harmonic fit has {found} coefficients for order {order} (expected {expected}) or a \
         non-finite coefficient; refit"
    )]
    InvalidFit {
        /// The fit's order.
        order: usize,
        /// `(order + 1)^2`.
        expected: usize,
        /// The number of coefficients found.
        found: usize,
    },

    /// Fewer points than basis functions: the least squares problem is underdetermined.
    #[error(
        "{points} points for {basis} basis functions (order {order}): the fit needs at least as \
         many points as basis functions; lower the order or use a finer mesh"
    )]
    TooFewPoints {
        /// Number of points.
        points: usize,
        /// Number of basis functions, `(order + 1)^2`.
        basis: usize,
        /// The order asked for.
        order: usize,
    },

    /// The design matrix would be too large to hold in memory.
    #[error(
        "the design matrix would have {entries} entries (more than {max}); lower the order or \
         subsample the points"
    )]
    TooLarge {
        /// `points * (order + 1)^2`.
        entries: usize,
        /// The largest accepted number of entries.
        max: usize,
    },

    /// The basis functions are linearly dependent on these points.
    #[error(
        "the basis is numerically rank deficient on these points (column {column} = A_{n}^{m}, \
         |R_jj| = {pivot:e} vs largest {largest:e}): the points do not spread over the cap \
         enough for this order; lower the order"
    )]
    RankDeficient {
        /// Basis index of the first dependent column.
        column: usize,
        /// Its order `n`.
        n: usize,
        /// Its degree `m`.
        m: isize,
        /// The diagonal entry of `R`.
        pivot: f64,
        /// The largest diagonal entry of `R`.
        largest: f64,
    },

    /// The N = 1 representation is flat or a point: its aspect ratio is infinite.
    #[error(
        "the order-1 representation is degenerate (singular values {singular_values:?}): the \
         aspect ratio is infinite"
    )]
    DegenerateShape {
        /// The singular values of the fitted 3x3 map.
        singular_values: [f64; 3],
    },

    /// Fits on different caps were given where one cap is needed.
    #[error("the fits are on different caps (Z* = {first} and Z* = {other}); use fits of one parameterization")]
    MixedZStar {
        /// `Z*` of the first fit.
        first: f64,
        /// A different `Z*`.
        other: f64,
    },

    /// The spherical cap harmonics' eigenproblem of one order could not be solved.
    #[error(
        "the spherical cap harmonics of order m = {m} on Z* = {z_star} could not be computed \
         (the eigenproblem's matrices are not positive definite); lower the order or use --basis ah"
    )]
    CapEigenFailed {
        /// The order `m`.
        m: usize,
        /// The cap's lower bound.
        z_star: f64,
    },

    /// A fit in one basis was used where another basis is needed.
    #[error("this needs a fit in the {expected} basis, but the fit is in the {found} basis; refit with that basis")]
    WrongBasis {
        /// The basis needed.
        expected: &'static str,
        /// The fit's basis.
        found: &'static str,
    },

    /// A resampling face count of 0 or too large.
    #[error("cannot resample the reconstruction with {faces} faces: give between 1 and {max}")]
    InvalidResample {
        /// The face count asked for.
        faces: usize,
        /// The largest accepted count.
        max: usize,
    },

    /// A dense decomposition failed to converge.
    #[error("the singular value decomposition did not converge")]
    SvdFailed,
}
