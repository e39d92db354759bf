//! The C ABI (feature `capi`): `capmesh_v1_*` functions (parameterize, remesh, harmonics, metrics,
//! the cap map's inverse and forward map) over plain mesh views, opaque result
//! handles, status codes with a thread-local last-error text and a progress callback that can
//! cancel. `cbindgen` turns this module into `cpp/include/capmesh.h` (see `tools/capi-header`).
//!
//! Rules every entry point follows:
//! - nothing panics across the boundary: each body runs inside `status::guard`, a panic
//!   becomes [`capmesh_v1_status::CAPMESH_V1_INTERNAL`];
//! - every pointer is checked for NULL, every count for overflow, every index against the
//!   vertex count and every coordinate for NaN before the library sees the mesh;
//! - output pointers are set to NULL first and written only on success;
//! - every status-returning call resets the last error to `""`, failing calls set it.
//!
//! The symbol prefix `capmesh_v1_` is the ABI version: an incompatible change gets `v2`.

pub mod entry;
pub mod handle;
pub mod harmonics;
pub mod map;
pub mod options;
pub mod progress;
pub mod status;
pub mod view;

pub use entry::*;
pub use handle::*;
pub use harmonics::*;
pub use map::*;
pub use options::*;
pub use progress::*;
pub use status::*;
pub use view::*;
