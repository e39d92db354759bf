//! Linear algebra: the cotangent Laplacian, sparse direct solvers (faer) that keep their
//! symbolic factorization for reuse, and conjugate gradients.

pub(crate) mod conjugate_gradient;
pub(crate) mod factor_buffer;
pub(crate) mod graph_matrix;
pub(crate) mod laplacian;
pub(crate) mod nested_dissection;
pub(crate) mod sparse;

pub use conjugate_gradient::{jacobi_cg2, jacobi_cg2_or_give_up, CgOutcome};
pub use graph_matrix::GraphPattern;
pub use laplacian::{cotangent_weights, CotanWeights};
pub use factor_buffer::release_spare;
pub use sparse::{LuSolver, SolveError, SpdSolver, TripletList};
