//! The C ABI (feature `capi`) called as C would call it.

use std::ffi::CStr;

use capmesh::ffi::*;

#[test]
fn version_is_the_crate_version() {
    let v = unsafe { CStr::from_ptr(capmesh_v1_version()) };
    assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}
