//! Linear algebra: the cotangent Laplacian, sparse direct solvers (faer) that keep their
//! symbolic factorization for reuse, and conjugate gradients.

pub mod conjugate_gradient;
pub mod graph_matrix;
pub mod laplacian;
pub mod nested_dissection;
pub mod sparse;

pub use conjugate_gradient::{jacobi_cg2, CgOutcome};
pub use graph_matrix::GraphPattern;
pub use laplacian::{cotangent_weights, CotanWeights};
pub use sparse::{LuSolver, SolveError, SpdSolver, TripletList};
