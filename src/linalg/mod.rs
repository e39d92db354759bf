//! Linear algebra: the cotangent Laplacian and sparse direct solvers (faer) that keep their
//! symbolic factorization for reuse.

pub mod graph_matrix;
pub mod laplacian;
pub mod nested_dissection;
pub mod sparse;

pub use graph_matrix::GraphPattern;
pub use laplacian::{cotangent_weights, CotanWeights};
pub use sparse::{LuSolver, ScatterAssembler, SolveError, SpdSolver, TripletList};
