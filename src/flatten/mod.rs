//! Initial flattening maps onto the unit disk (paper Sec. 3.1.1 for open surfaces, Sec. 3.2.1
//! for punctured closed surfaces).

pub mod beltrami;
pub mod closed;
pub(crate) mod disk_conformal;
pub mod harmonic;
pub(crate) mod mobius;
pub mod puncture;
pub mod stretch_energy;

pub use disk_conformal::{disk_conformal_map, DiskConformalOptions, DiskConformalReport};

use crate::linalg::SolveError;

/// Errors of the flattening stage.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum FlattenError {
    /// A linear solve failed.
    #[error("flattening: {0}")]
    Linear(#[from] SolveError),
    /// A Beltrami coefficient reached 1 (the map is not quasi-conformal).
    #[error("Beltrami coefficient of norm {norm:.3} >= 1: the map folds; lower lambda")]
    BeltramiOutOfRange {
        /// Its norm.
        norm: f64,
    },
    /// lambda outside [0, 1].
    #[error("lambda = {lambda} is outside [0, 1]")]
    LambdaOutOfRange {
        /// The value given.
        lambda: f64,
    },
    /// No pair of adjacent triangles could be punctured.
    #[error("no pair of adjacent triangles to puncture: the closed mesh has no interior edge")]
    NoPuncture,
    /// The mesh's topology could not be read.
    #[error("{0}")]
    Mesh(String),
    /// The boundary loop is too short to map onto a circle.
    #[error("the boundary loop has only {len} vertices; a disk map needs at least 3")]
    BoundaryTooShort {
        /// Loop length.
        len: usize,
    },
}

/// Put the `fixed` vertices at their positions in `pos`; return the fixed mask, a compact
/// numbering of the free vertices (`usize::MAX` for fixed ones) and their count.
pub(crate) fn pin(pos: &mut [[f64; 2]], fixed: &[(u32, [f64; 2])]) -> (Vec<bool>, Vec<usize>, usize) {
    let n = pos.len();
    let mut is_fixed = vec![false; n];
    for &(v, p) in fixed {
        pos[v as usize] = p;
        is_fixed[v as usize] = true;
    }
    let mut index = vec![usize::MAX; n];
    let mut n_free = 0;
    for v in 0..n {
        if !is_fixed[v] {
            index[v] = n_free;
            n_free += 1;
        }
    }
    (is_fixed, index, n_free)
}
