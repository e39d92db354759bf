//! The one font of the figures, bundled so that text draws the same on every machine (no
//! system fonts or fontconfig needed): Go Regular, by Bigelow & Holmes for the Go project,
//! under a BSD 3-clause licence (`font/LICENSE`).

use super::FigureError;
use plotters::style::FontStyle;
use std::sync::OnceLock;

/// Go Regular (TrueType).
static GO_REGULAR: &[u8] = include_bytes!("font/Go-Regular.ttf");

/// The family name the figures ask for.
pub(super) const FAMILY: &str = "sans-serif";

/// Register the bundled font with plotters once (under [`FAMILY`], which plotters' axis labels
/// use by default).
pub(super) fn ensure() -> Result<(), FigureError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    if *REGISTERED.get_or_init(|| plotters::style::register_font(FAMILY, FontStyle::Normal, GO_REGULAR).is_ok()) {
        Ok(())
    } else {
        Err(FigureError::Font)
    }
}
