//! One type for either basis ([`BasisKind`]): the fit, the reconstruction and the errors are
//! written once against [`HarmonicBasis`], which evaluates the adaptive harmonics
//! ([`CapBasis`]) or the spherical cap harmonics ([`SchaBasis`]) at cap points.
//!
//! A spherical cap basis costs one small eigenproblem per order `m` to build, and one analysis
//! builds the same basis several times (fit, errors, reconstruction): the last few are kept in
//! a process-wide cache keyed by `(Z*, N, rim condition)` and shared ([`Arc`]).

use std::sync::{Arc, Mutex};

use super::basis::{CapBasis, CapCoordinates};
use super::kind::{BasisKind, CapBoundary};
use super::scha::{SchaBasis, SchaPoint};
use super::HarmonicsError;

/// A basis of `(N + 1)^2` functions on the cap `Z >= Z*`, indexed `n^2 + n + m`.
#[derive(Debug, Clone)]
pub enum HarmonicBasis {
    /// The paper's adaptive harmonics.
    Adaptive(CapBasis),
    /// Spherical cap harmonics.
    SphericalCap(Arc<SchaBasis>),
}

/// A checked cap point in the form its basis evaluates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BasisPoint {
    /// For the adaptive harmonics.
    Adaptive(CapCoordinates),
    /// For the spherical cap harmonics.
    SphericalCap(SchaPoint),
}

impl HarmonicBasis {
    /// The basis `kind` on `Z >= z_star` up to `order`.
    pub fn new(kind: BasisKind, z_star: f64, order: usize) -> Result<Self, HarmonicsError> {
        Ok(match kind {
            BasisKind::Adaptive => Self::Adaptive(CapBasis::new(z_star, order)?),
            BasisKind::SphericalCap(b) => Self::SphericalCap(cached(z_star, order, b)?),
        })
    }

    /// Which basis this is.
    pub fn kind(&self) -> BasisKind {
        match self {
            Self::Adaptive(_) => BasisKind::Adaptive,
            Self::SphericalCap(b) => BasisKind::SphericalCap(b.boundary()),
        }
    }

    /// Number of functions, `(N + 1)^2`.
    pub fn len(&self) -> usize {
        match self {
            Self::Adaptive(b) => b.len(),
            Self::SphericalCap(b) => b.len(),
        }
    }

    /// Never true.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The largest order `N`.
    pub fn order(&self) -> usize {
        match self {
            Self::Adaptive(b) => b.order(),
            Self::SphericalCap(b) => b.order(),
        }
    }

    /// The degree of function `(n, m)`: `n` for the adaptive harmonics, the non-integer
    /// `nu_n^m` for the spherical cap harmonics; `None` when `|m| > n` or `n > N`.
    pub fn degree(&self, n: usize, m: isize) -> Option<f64> {
        if m.unsigned_abs() > n || n > self.order() {
            return None;
        }
        match self {
            Self::Adaptive(_) => Some(n as f64),
            Self::SphericalCap(b) => b.degree(n, m),
        }
    }

    /// Checks cap point `p` (number `index`, for error messages).
    pub fn coordinates(&self, index: usize, p: [f64; 3]) -> Result<BasisPoint, HarmonicsError> {
        Ok(match self {
            Self::Adaptive(b) => BasisPoint::Adaptive(b.coordinates(index, p)?),
            Self::SphericalCap(b) => BasisPoint::SphericalCap(b.coordinates(index, p)?),
        })
    }

    /// Every function at `p` in index order.
    pub fn evaluate(&self, p: [f64; 3]) -> Result<Vec<f64>, HarmonicsError> {
        match self {
            Self::Adaptive(b) => b.evaluate(p),
            Self::SphericalCap(b) => b.evaluate(p),
        }
    }

    /// Every function at `point` into `out[..self.len()]`; `scratch` is reused between calls.
    /// A point checked by the other kind of basis leaves `out` unchanged (a debug assertion).
    pub(crate) fn fill(&self, point: &BasisPoint, scratch: &mut Vec<f64>, out: &mut [f64]) {
        match (self, point) {
            (Self::Adaptive(b), BasisPoint::Adaptive(c)) => b.fill(c, scratch, out),
            (Self::SphericalCap(b), BasisPoint::SphericalCap(c)) => b.fill(c, scratch, out),
            // Points come from `self.coordinates`; a point of the other basis is a caller bug.
            _ => debug_assert!(false, "a cap point checked by the other harmonic basis"),
        }
    }
}

/// Spherical cap bases kept by [`cached`].
const CACHED_BASES: usize = 8;

type CacheEntry = ((u64, usize, CapBoundary), Arc<SchaBasis>);

/// The spherical cap basis of `(z_star, order, boundary)`, from the cache or built (and kept).
fn cached(z_star: f64, order: usize, boundary: CapBoundary) -> Result<Arc<SchaBasis>, HarmonicsError> {
    static CACHE: Mutex<Vec<CacheEntry>> = Mutex::new(Vec::new());
    let key = (z_star.to_bits(), order, boundary);
    if let Ok(cache) = CACHE.lock() {
        if let Some((_, basis)) = cache.iter().find(|(k, _)| *k == key) {
            return Ok(Arc::clone(basis));
        }
    }
    let basis = Arc::new(SchaBasis::new(z_star, order, boundary)?);
    if let Ok(mut cache) = CACHE.lock() {
        if cache.len() >= CACHED_BASES {
            cache.remove(0);
        }
        cache.push((key, Arc::clone(&basis)));
    }
    Ok(basis)
}
