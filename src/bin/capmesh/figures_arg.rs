//! `--figures DIR` of `param`, `remesh` and `harmonics`: the figures are drawn by
//! `capmesh::figures`; this only names the input and says where the index is.

use capmesh::figures::{FigureError, FigureSet};
use std::path::Path;

/// The input's file name, which titles the figure index.
pub fn name(input: &Path) -> String {
    input.file_name().map_or_else(|| input.display().to_string(), |n| n.to_string_lossy().into_owned())
}

/// Say where the figures went, or why they could not be written.
pub fn done(written: Result<FigureSet, FigureError>) -> Result<(), String> {
    let set = written.map_err(|e| format!("figures: {e}"))?;
    outln!("figures: {} ({} figures)", set.index.display(), set.figures.len());
    Ok(())
}
