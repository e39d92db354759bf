//! The whole pipeline (validation, parameterization, remeshing) on small meshes decoded from
//! the fuzz input: errors are fine, panics are not, and every success is checked.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    capmesh_fuzz::check_pipeline(data);
});
