//! [`FigureError`], what can go wrong while drawing or writing the figures.

use std::path::PathBuf;

/// An error of [`super::param_figures`], [`super::remesh_figures`] or
/// [`super::harmonics_figures`].
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// The figure directory or a file in it could not be created or written.
    #[error("cannot write {}: {source}; check that the directory is writable and the disk not full", path.display())]
    Io {
        /// The directory or file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// Plotters could not draw a figure (its message says why).
    #[error("cannot draw the figure {figure}: {message}")]
    Draw {
        /// The figure's file name.
        figure: String,
        /// Plotters' message.
        message: String,
    },
    /// The bundled font could not be loaded (a damaged build).
    #[error("the bundled figure font cannot be loaded; rebuild capmesh")]
    Font,
    /// The PNG encoder refused the image.
    #[error("cannot encode {}: {message}", path.display())]
    Encode {
        /// The PNG file.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
    /// Nothing to draw: the mesh or the values are empty, or the options ask for an empty
    /// image.
    #[error("cannot draw the figure {figure}: {why}")]
    Empty {
        /// The figure's file name.
        figure: String,
        /// What is missing.
        why: String,
    },
}

impl FigureError {
    /// A plotters error while drawing `figure`.
    pub(super) fn draw(figure: &str, e: impl std::fmt::Display) -> Self {
        Self::Draw { figure: figure.to_string(), message: e.to_string() }
    }
}
