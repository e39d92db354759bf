//! The options of the initial map of open surfaces (paper Sec. 3.1.1, and the composite map
//! of Sec. 3.2.1 that capmesh uses by default: departure in docs/method.md).

use crate::flatten::DiskConformalOptions;

/// `lambda` of the composite initial map of open surfaces. The paper flattens open surfaces
/// conformally; on elongated or branching surfaces (the hand, the hippocampal sheet) that
/// squeezes protrusions by orders of magnitude and the transport map inherits the error. Its
/// closed-surface recipe with `lambda = 0.5` keeps every shared open mesh at or below the
/// paper's open-surface distortion (docs/method.md).
pub const DEFAULT_OPEN_LAMBDA: f64 = 0.5;

/// Stretch-energy iterations of the open surfaces' initial map that factor their own
/// matrix; the later ones reuse the last factorization (the matrix changes little once the
/// map nears its fixed point) unless their step goes uphill or folds a face. Against
/// factoring every iteration the final energies agree to 3-4 digits and the maps' mean
/// `|d_area|` and `|d_angle|` to 2%, with 6-7 of the 10 iterations reusing a factorization.
/// Closed surfaces factor every iteration (see the option's doc).
pub const DEFAULT_OPEN_FACTORED_ITERATIONS: usize = 3;

/// Initial flattening of open surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OpenInitialMap {
    /// Disk conformal map (paper Sec. 3.1.1).
    Conformal,
    /// Stretch energy map composed with `lambda * mu` (the closed-surface recipe, Sec. 3.2.1).
    #[default]
    Composite,
}

crate::named::named_enum!(OpenInitialMap, "initial map", Conformal => "conformal", Composite => "composite");

/// How open (disk-like) surfaces are flattened before the transport. Build them from
/// [`OpenOptions::default`] with the `with_*` setters: new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct OpenOptions {
    /// Initial map. Default [`OpenInitialMap::Composite`]; [`OpenInitialMap::Conformal`] is
    /// the paper's disk conformal map.
    pub initial: OpenInitialMap,
    /// Options of the disk conformal map ([`OpenInitialMap::Conformal`]). Default
    /// [`DiskConformalOptions::default`].
    pub conformal: DiskConformalOptions,
    /// `lambda` of the composite initial map. Default [`DEFAULT_OPEN_LAMBDA`].
    pub lambda: f64,
    /// Stretch-energy iterations of the composite initial map that factor their own matrix;
    /// the later ones reuse the last factorization
    /// ([`crate::flatten::stretch_energy::StretchOptions::factored_iterations`]). Default
    /// [`DEFAULT_OPEN_FACTORED_ITERATIONS`].
    pub factored_iterations: usize,
}

impl Default for OpenOptions {
    fn default() -> Self {
        Self {
            initial: OpenInitialMap::Composite,
            conformal: DiskConformalOptions::default(),
            lambda: DEFAULT_OPEN_LAMBDA,
            factored_iterations: DEFAULT_OPEN_FACTORED_ITERATIONS,
        }
    }
}

impl OpenOptions {
    /// Set [`OpenOptions::initial`].
    pub fn with_initial(mut self, initial: OpenInitialMap) -> Self {
        self.initial = initial;
        self
    }

    /// Set [`OpenOptions::conformal`].
    pub fn with_conformal(mut self, conformal: DiskConformalOptions) -> Self {
        self.conformal = conformal;
        self
    }

    /// Set [`OpenOptions::lambda`] (in `[0, 1]`).
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.lambda = lambda;
        self
    }

    /// Set [`OpenOptions::factored_iterations`].
    pub fn with_factored_iterations(mut self, factored_iterations: usize) -> Self {
        self.factored_iterations = factored_iterations;
        self
    }
}
