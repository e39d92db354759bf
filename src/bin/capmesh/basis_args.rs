//! The harmonic basis options `harmonics` and `shape` share: `--basis ah|scha` and, for the
//! spherical cap harmonics, `--boundary neumann|dirichlet|mixed`.

use capmesh::harmonics::{BasisKind, CapBoundary};

/// Basis options of the command line.
#[derive(clap::Args, Debug, Clone)]
pub struct BasisArgs {
    /// Harmonic basis: ah (the paper's adaptive harmonics, default) or scha (spherical cap
    /// harmonics on the true polar angle, which keep an open surface's boundary loop).
    #[arg(long, default_value = "ah", value_parser = ["ah", "scha"])]
    pub basis: String,
    /// Rim condition of --basis scha: neumann (default), dirichlet or mixed (Haines' set).
    #[arg(long, default_value = "neumann")]
    pub boundary: CapBoundary,
}

impl BasisArgs {
    /// The basis asked for; `--boundary` without `--basis scha` is refused.
    pub fn kind(&self) -> Result<BasisKind, String> {
        let kind = BasisKind::from_name(&self.basis, self.boundary)?;
        if kind == BasisKind::Adaptive && self.boundary != CapBoundary::default() {
            return Err(format!(
                "--boundary {} applies to the spherical cap harmonics only; add --basis scha",
                self.boundary.name()
            ));
        }
        Ok(kind)
    }
}
