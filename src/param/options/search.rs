//! The options of the radius search: Brent's method over `Z*` (paper Sec. 3.1.2, Eq. 12),
//! run on a coarse level of transport sites for large meshes (docs/method.md).

/// Relative L1 mass error (`sum |m_i - tau_i| / sum tau_i`) at which the radius search's
/// transport solves stop. Newton's last step takes the error from about `1e-6` to `1e-10`;
/// `1e-5` leaves the maps' mean `|d_area|` and `|d_angle|` within 1% of `1e-7`'s and saves a
/// Newton step on most meshes. A search at full resolution hands over its map at `r*`
/// without another solve. `1e-3` for the search and the final map alike was worse: the
/// search's energies, not the final map, need the digits.
pub const MASS_TOLERANCE: f64 = 1e-5;

/// Transport sites of the radius search by default (see [`SearchOptions::sites`]):
/// against 4000 the mean |d_area| and |d_angle| stay within 1% on the shared meshes, and the
/// 4k-8k-vertex meshes search on a coarse level too; at 1000 the 12k brain's map was worse.
pub const DEFAULT_SEARCH_SITES: usize = 2000;

/// How the radius `r*` of the adaptive cap is searched. Build them from
/// [`SearchOptions::default`] with the `with_*` setters: new options may be added without
/// notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct SearchOptions {
    /// Absolute tolerance on `Z*`. Default `1e-3`.
    pub z_tolerance: f64,
    /// Maximum transport solves. Default 30.
    pub max_evaluations: usize,
    /// Relative mass tolerance of the search's transport solves. A search at full resolution
    /// hands over its map at `r*` when this is no looser than the final map's
    /// ([`crate::ParamOptions::transport`]'s tolerance, the default), else solves it on, warm,
    /// to that. Each search step saves about one Newton iteration (hand: 39 instead of 45 in
    /// all) and `Z*` does not move. Looser is faster but not safe: at `1e-2` the hand needs 26
    /// iterations, while the 48k brain's search stops at `Z* = -0.991` instead of the bound
    /// and its mean `|d_area|` goes from 0.013 to 0.40. Default [`MASS_TOLERANCE`] (`1e-5`).
    pub tolerance: f64,
    /// Transport sites. A mesh of `n` vertices searches on a coarse level of at most
    /// [`crate::param::search_level_sites`] sites (see `crate::omt::coarse_level`:
    /// `max(sites, n / SEARCH_RATIO)` when that is less than half the vertices; a closed
    /// surface also at most a quarter of its vertices, [`crate::param::SMALL_SEARCH_RATIO`])
    /// and solves the full transport problem at `r*` only; 0 always searches at full
    /// resolution (the paper's method). Default [`DEFAULT_SEARCH_SITES`].
    pub sites: usize,
}

impl Default for SearchOptions {
    fn default() -> Self {
        Self { z_tolerance: 1e-3, max_evaluations: 30, tolerance: MASS_TOLERANCE, sites: DEFAULT_SEARCH_SITES }
    }
}

impl SearchOptions {
    /// Set [`SearchOptions::z_tolerance`].
    pub fn with_z_tolerance(mut self, z_tolerance: f64) -> Self {
        self.z_tolerance = z_tolerance;
        self
    }

    /// Set [`SearchOptions::max_evaluations`].
    pub fn with_max_evaluations(mut self, max_evaluations: usize) -> Self {
        self.max_evaluations = max_evaluations;
        self
    }

    /// Set [`SearchOptions::tolerance`].
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Set [`SearchOptions::sites`] (0: search at full resolution).
    pub fn with_sites(mut self, sites: usize) -> Self {
        self.sites = sites;
        self
    }
}
