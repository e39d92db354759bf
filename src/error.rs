//! The crate's error type: one variant per stage, each wrapping that stage's own error enum,
//! so a user can tell "your mesh has two boundary loops" from "the solver did not converge".

use crate::cap::InverseMapError;
use crate::flatten::FlattenError;
use crate::harmonics::HarmonicsError;
use crate::io::{ReadError, WriteError};
use crate::mesh::MeshError;
use crate::omt::OmtError;
use crate::progress::Cancelled;

/// Any error of the capmesh pipeline.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading a mesh file failed.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// Writing a mesh file failed.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// The mesh is not a surface capmesh can map.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The initial flattening failed.
    #[error(transparent)]
    Flatten(#[from] FlattenError),
    /// The optimal transport failed.
    #[error(transparent)]
    Transport(#[from] OmtError),
    /// The adaptive harmonics fit failed.
    #[error(transparent)]
    Harmonics(#[from] HarmonicsError),
    /// The inverse map could not be built or asked.
    #[error(transparent)]
    Inverse(#[from] InverseMapError),
    /// The input is valid but asks for something not supported.
    #[error("{0}")]
    Unsupported(String),
    /// An option is out of range.
    #[error("invalid option: {0}")]
    InvalidOption(String),
    /// Cancelled through the progress callback.
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
    /// A bug in capmesh: an invariant the code relies on does not hold. Please report it with
    /// the input that caused it.
    #[error("internal error (a bug in capmesh, please report it): {0}")]
    Internal(String),
}

/// Shorthand for results with [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
