//! Gzip-wrapped input: the first byte picks the format, the rest is decompressed (or refused)
//! and parsed; never a panic.
#![no_main]

use capmesh::io::{read_mesh_from_gzip_bytes, Format};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else { return };
    let formats = [Format::Obj, Format::Ply, Format::Off, Format::Stl, Format::Gifti, Format::FreeSurfer];
    let format = formats[pick as usize % formats.len()];
    if let Ok(mesh) = read_mesh_from_gzip_bytes(rest, format) {
        capmesh_fuzz::check_indices(&mesh);
    }
});
