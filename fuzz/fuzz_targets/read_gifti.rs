//! Any bytes given to the GIFTI surface reader give a mesh with in-range indices or an error,
//! never a panic.
#![no_main]

use capmesh::io::Format;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    capmesh_fuzz::check_read(data, Format::Gifti);
});
