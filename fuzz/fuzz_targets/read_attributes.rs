//! Per-vertex data files: the first byte picks GIFTI or FreeSurfer curvature, the rest is
//! parsed; attributes or an error, never a panic.
#![no_main]

use capmesh::io::{read_vertex_attributes_from_bytes, AttributeData, AttributeFormat};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else { return };
    let format = [AttributeFormat::Gifti, AttributeFormat::FreeSurferCurv][pick as usize % 2];
    if let Ok(attributes) = read_vertex_attributes_from_bytes(rest, format) {
        // A curvature file is one attribute; a GIFTI file without data arrays is an error.
        match format {
            AttributeFormat::FreeSurferCurv => assert_eq!(attributes.len(), 1),
            AttributeFormat::Gifti => assert!(!attributes.is_empty()),
        }
        // Only label arrays carry a label table.
        for a in &attributes {
            assert!(matches!(a.data, AttributeData::Label(_)) || a.label_table.is_empty());
        }
    }
});
