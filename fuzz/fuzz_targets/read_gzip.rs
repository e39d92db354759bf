//! Gzip-wrapped input: the first byte picks the format, the rest is decompressed (or refused)
//! and parsed; never a panic.
#![no_main]

use capmesh::io::{read_mesh_from_gzip_bytes, Format};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else { return };
    let format = [Format::Obj, Format::Ply, Format::Off, Format::Stl][pick as usize % 4];
    if let Ok(mesh) = read_mesh_from_gzip_bytes(rest, format) {
        capmesh_fuzz::check_indices(&mesh);
    }
});
