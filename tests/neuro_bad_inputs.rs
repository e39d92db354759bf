//! Damaged GIFTI and FreeSurfer files: each error names the file, the line (GIFTI) or byte
//! offset (FreeSurfer), what is wrong and what to do; and thousands of deterministic mutations
//! of real files (byte flips, truncations, insertions) never panic and never give out-of-range
//! indices.

mod common;

use std::io::Read;
use std::path::Path;

use capmesh::io::{
    read_mesh, read_mesh_from_bytes, read_vertex_attributes, read_vertex_attributes_from_bytes, write_mesh_to_bytes,
    write_mesh_to_bytes_with, AttributeFormat, Format, GiftiEncoding, GiftiOptions, Location, ReadError, WriteOptions,
};
use capmesh::mesh::shapes::icosphere;
use capmesh::TriMesh;
use common::{Rng, TempDir};

fn neuro_bytes(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/neuro").join(name);
    let raw = std::fs::read(&path).unwrap();
    if name.ends_with(".gz") {
        let mut out = Vec::new();
        flate2::read::GzDecoder::new(&raw[..]).read_to_end(&mut out).unwrap();
        out
    } else {
        raw
    }
}

/// A GIFTI surface with one POINTSET (3 vertices) and one TRIANGLE array; `points` and
/// `triangles` are the `<DataArray ...>` attribute overrides and `<Data>` contents.
fn gifti(points_attrs: &str, points: &str, tri_attrs: &str, triangles: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!DOCTYPE GIFTI SYSTEM \"http://www.nitrc.org/frs/download.php/115/gifti.dtd\">\n\
         <GIFTI Version=\"1.0\" NumberOfDataArrays=\"2\">\n\
         <DataArray Intent=\"NIFTI_INTENT_POINTSET\" {points_attrs}>\n<Data>{points}</Data>\n</DataArray>\n\
         <DataArray Intent=\"NIFTI_INTENT_TRIANGLE\" {tri_attrs}>\n<Data>{triangles}</Data>\n</DataArray>\n\
         </GIFTI>\n"
    )
}

const P: &str = r#"DataType="NIFTI_TYPE_FLOAT32" Dimensionality="2" Dim0="3" Dim1="3" Encoding="ASCII""#;
const T: &str = r#"DataType="NIFTI_TYPE_INT32" Dimensionality="2" Dim0="1" Dim1="3" Encoding="ASCII""#;
const XYZ: &str = "0 0 0\n1 0 0\n0 1 0";

fn read_gifti(text: &str) -> Result<TriMesh, ReadError> {
    read_mesh_from_bytes(text.as_bytes(), Format::Gifti)
}

/// The error's message, checked to contain every piece.
fn message(err: &ReadError, pieces: &[&str]) -> String {
    let text = err.to_string();
    for p in pieces {
        assert!(text.contains(p), "'{p}' missing from: {text}");
    }
    text
}

#[test]
fn the_hand_written_sample_reads() {
    let mesh = read_gifti(&gifti(P, XYZ, T, "0 1 2")).unwrap();
    assert_eq!((mesh.n_vertices(), mesh.faces.clone()), (3, vec![[0, 1, 2]]));
}

#[test]
fn gifti_errors_name_the_line_and_what_to_do() {
    // Truncated XML (cut inside the triangle array).
    let text = gifti(P, XYZ, T, "0 1 2");
    let cut = &text[..text.len() - 40];
    let err = read_gifti(cut).unwrap_err();
    assert!(matches!(err, ReadError::Parse { at: Location::Line(_), .. }), "{err}");
    message(&err, &["<bytes>, line", "malformed XML", "truncated or corrupt"]);

    // Too few ASCII values.
    let err = read_gifti(&gifti(P, "0 0 0\n1 0 0\n0 1", T, "0 1 2")).unwrap_err();
    assert!(matches!(err, ReadError::Parse { at: Location::Line(5), .. }), "{err}");
    message(&err, &["hold 8 values but the array announces 9 values (3 x 3)", "export it again"]);
    // Too many.
    let err = read_gifti(&gifti(P, "0 0 0\n1 0 0\n0 1 0 7", T, "0 1 2")).unwrap_err();
    message(&err, &["more values than the 9 values (3 x 3)"]);
    // Not a number.
    let err = read_gifti(&gifti(P, "0 0 0\n1 zero 0\n0 1 0", T, "0 1 2")).unwrap_err();
    message(&err, &["line 5", "'zero' is not a number"]);
    // NaN coordinate.
    let err = read_gifti(&gifti(P, "0 0 0\n1 NaN 0\n0 1 0", T, "0 1 2")).unwrap_err();
    message(&err, &["line 4", "vertex 1", "not a finite number"]);
    // Index out of range.
    let err = read_gifti(&gifti(P, XYZ, T, "0 1 3")).unwrap_err();
    assert!(matches!(err, ReadError::IndexOutOfRange { index: 3, n_vertices: 3, at: Location::Line(9), .. }), "{err}");
    // Triangles as floats.
    let float_t = T.replace("INT32", "FLOAT32");
    let err = read_gifti(&gifti(P, XYZ, &float_t, "0 1 2")).unwrap_err();
    assert!(matches!(err, ReadError::UnsupportedGifti { .. }), "{err}");
    message(&err, &["floating-point numbers, not integer indices", "nibabel"]);
    // Wrong shape.
    let err = read_gifti(&gifti(&P.replace("Dim1=\"3\"", "Dim1=\"2\""), "0 0 1 0 0 1", T, "0 1 2")).unwrap_err();
    message(&err, &["line 4", "dimensions [3, 2], expected [n, 3]"]);
    // Missing attribute, bad count, unknown type, external data, unknown encoding.
    let err = read_gifti(&gifti(&P.replace("Dim0=\"3\" ", ""), XYZ, T, "0 1 2")).unwrap_err();
    message(&err, &["line 4", "no 'Dim0' attribute"]);
    let err = read_gifti(&gifti(&P.replace("Dim0=\"3\"", "Dim0=\"-3\""), XYZ, T, "0 1 2")).unwrap_err();
    message(&err, &["'Dim0' is '-3', not a count"]);
    let err = read_gifti(&gifti(&P.replace("FLOAT32", "COMPLEX64"), XYZ, T, "0 1 2")).unwrap_err();
    assert!(matches!(err, ReadError::UnsupportedGifti { at: Location::Line(4), .. }), "{err}");
    message(&err, &["data type 'NIFTI_TYPE_COMPLEX64'", "save it again"]);
    let err = read_gifti(&gifti(&P.replace("ASCII", "ExternalFileBinary"), "", T, "0 1 2")).unwrap_err();
    message(&err, &["external file (ExternalFileBinary)"]);
    let err = read_gifti(&gifti(&P.replace("ASCII", "Base32"), XYZ, T, "0 1 2")).unwrap_err();
    message(&err, &["encoding 'Base32'"]);
    // Binary data need a byte order; ASCII data ignore it.
    let err = read_gifti(&gifti(&P.replace("ASCII", "Base64Binary"), "AAAA", T, "0 1 2")).unwrap_err();
    message(&err, &["line 4", "no byte order ('Endian') for binary data"]);
    let err = read_gifti(&gifti(&P.replace("ASCII\"", "Base64Binary\" Endian=\"Middle\""), "AAAA", T, "0 1 2")).unwrap_err();
    message(&err, &["byte order 'Middle'"]);
    assert!(read_gifti(&gifti(&format!("{P} Endian=\"Middle\""), XYZ, T, "0 1 2")).is_ok());
    // Not GIFTI, not UTF-8, no surface.
    let err = read_gifti("<?xml version=\"1.0\"?>\n<svg></svg>\n").unwrap_err();
    message(&err, &["line 2", "<svg>, not <GIFTI>"]);
    let err = read_mesh_from_bytes(b"<GIFTI>\n\xff\xfe</GIFTI>", Format::Gifti).unwrap_err();
    message(&err, &["line 2", "not UTF-8"]);
    let err = read_gifti("<GIFTI Version=\"1.0\" NumberOfDataArrays=\"0\"/>").unwrap_err();
    assert!(matches!(err, ReadError::WrongKind { .. }), "{err}");
}

#[test]
fn binary_gifti_errors() {
    let mesh = icosphere(1);
    for encoding in [GiftiEncoding::Base64Binary, GiftiEncoding::GzipBase64Binary] {
        let options = WriteOptions::default().with_gifti(GiftiOptions::default().with_encoding(encoding));
        let text = String::from_utf8(write_mesh_to_bytes_with(&mesh, Format::Gifti, &options).unwrap()).unwrap();
        assert!(read_gifti(&text).is_ok());
        // A character that is not base64.
        let bad = text.replacen("<Data>", "<Data>*", 1);
        message(&read_gifti(&bad).unwrap_err(), &["base64 data is corrupt", "export it again"]);
        // Dropping 4 base64 characters (3 bytes) leaves the data short.
        let start = text.find("<Data>").unwrap() + 6;
        let short = format!("{}{}", &text[..start], &text[start + 4..]);
        let err = read_gifti(&short).unwrap_err();
        match encoding {
            GiftiEncoding::Base64Binary => message(&err, &["the data hold 501 bytes but the array announces 126 values (42 x 3)"]),
            _ => message(&err, &["compressed data is corrupt"]),
        };
        // More rows announced than stored.
        let more = text.replacen("Dim0=\"42\"", "Dim0=\"43\"", 1);
        message(&read_gifti(&more).unwrap_err(), &["129 values (43 x 3)", "truncated or corrupt"]);
    }
}

#[test]
fn freesurfer_errors_name_the_byte_offset() {
    let bytes = write_mesh_to_bytes(&icosphere(1), Format::FreeSurfer).unwrap();
    // Header: magic (3), "created by capmesh\n\n" (20), counts at 23 and 27, data from 31.
    assert_eq!(&bytes[3..23], b"created by capmesh\n\n");
    for cut in [0, 2, 10, 25, 31, 100, bytes.len() - 1] {
        let err = read_mesh_from_bytes(&bytes[..cut], Format::FreeSurfer).unwrap_err();
        match cut {
            0 => assert!(matches!(err, ReadError::Empty { .. }), "{err}"),
            10 => {
                message(&err, &["byte offset 3", "creation line", "no end"]);
            }
            _ => {
                assert!(matches!(err, ReadError::Truncated { .. }), "cut {cut}: {err}");
                message(&err, &["truncated", "produce it again"]);
            }
        };
    }
    let mut bad = bytes.clone();
    bad[2] = 0x00;
    message(&read_mesh_from_bytes(&bad, Format::FreeSurfer).unwrap_err(), &["byte offset 0", "magic bytes FF FF FE"]);
    bad[2] = 0xFD;
    let err = read_mesh_from_bytes(&bad, Format::FreeSurfer).unwrap_err();
    assert!(matches!(err, ReadError::WrongKind { .. }), "{err}");
    message(&err, &["quadrangle surface", "mris_convert"]);
    // Negative vertex count.
    let mut neg = bytes.clone();
    neg[23] = 0xFF;
    message(&read_mesh_from_bytes(&neg, Format::FreeSurfer).unwrap_err(), &["byte offset 23", "number of vertices is -"]);
    // A face index past the vertices: the first face starts after 42 vertices.
    let mut idx = bytes.clone();
    let face0 = 31 + 42 * 12;
    idx[face0..face0 + 4].copy_from_slice(&42i32.to_be_bytes());
    let err = read_mesh_from_bytes(&idx, Format::FreeSurfer).unwrap_err();
    assert!(matches!(err, ReadError::IndexOutOfRange { index: 42, n_vertices: 42, at: Location::Byte(b), .. } if b == face0 as u64), "{err}");
    // A NaN coordinate.
    let mut nan = bytes;
    nan[35..39].copy_from_slice(&f32::NAN.to_be_bytes());
    let err = read_mesh_from_bytes(&nan, Format::FreeSurfer).unwrap_err();
    assert!(matches!(err, ReadError::NonFinite { at: Location::Byte(31), .. }), "{err}");
}

#[test]
fn curvature_errors() {
    let good = neuro_bytes("brain12k.curv");
    assert_eq!(read_vertex_attributes_from_bytes(&good, AttributeFormat::FreeSurferCurv).unwrap()[0].data.len(), 12502);
    let err = read_vertex_attributes_from_bytes(&good[..good.len() - 2], AttributeFormat::FreeSurferCurv).unwrap_err();
    assert!(matches!(err, ReadError::Truncated { expected: 50023, found: 50021, .. }), "{err}");
    message(&err, &["announces 12502 values"]);
    let mut three = good.clone();
    three[11..15].copy_from_slice(&3i32.to_be_bytes());
    message(&read_vertex_attributes_from_bytes(&three, AttributeFormat::FreeSurferCurv).unwrap_err(), &["byte offset 11", "3 values per vertex"]);
    let err = read_vertex_attributes_from_bytes(b"hello world", AttributeFormat::FreeSurferCurv).unwrap_err();
    message(&err, &["byte offset 0", "not a FreeSurfer curvature file", ".shape.gii"]);
    // An old-style file: 3-byte counts, int16 hundredths.
    let mut old = vec![0, 0, 3, 0, 0, 1];
    for v in [150i16, -25, 0] {
        old.extend_from_slice(&v.to_be_bytes());
    }
    let a = read_vertex_attributes_from_bytes(&old, AttributeFormat::FreeSurferCurv).unwrap();
    assert_eq!(a[0].data, capmesh::io::AttributeData::Scalar(vec![1.5, -0.25, 0.0]));
    // A file of unknown kind, by path.
    let dir = TempDir::new("attr-unknown");
    let err = read_vertex_attributes(&dir.file("values.txt", b"1 2 3\n")).unwrap_err();
    assert!(matches!(err, ReadError::WrongKind { .. }), "{err}");
    message(&err, &["values.txt", "neither GIFTI", "mris_convert -c"]);
}

#[test]
fn unknown_content_keeps_the_unknown_format_message() {
    let dir = TempDir::new("neuro-unknown");
    let err = read_mesh(&dir.file("surface", b"\x00\x01\x02 not a mesh")).unwrap_err();
    assert!(matches!(err, ReadError::UnknownFormat { .. }), "{err}");
    message(&err, &["GIFTI", "FreeSurfer surfaces (lh.pial, recognised by content)"]);
}

fn mutate(bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for _ in 0..1 + rng.below(4) {
        if b.is_empty() {
            break;
        }
        let i = rng.below(b.len());
        match rng.below(5) {
            0 => b[i] ^= 1 << rng.below(8),
            1 => b.truncate(i),
            2 => b.insert(i, rng.next() as u8),
            3 => b[i] = *b"0123456789-<>\"= \nA+/"[..].get(rng.below(20)).unwrap_or(&b'0'),
            _ => {
                let j = (i + 1 + rng.below(16)).min(b.len());
                b.drain(i..j);
            }
        }
    }
    b
}

/// `rounds` mutations of `bytes` read as `format`: no panic, in-range indices, some refused.
fn survives(format: Format, bytes: &[u8], seed: u64, rounds: usize) {
    assert!(read_mesh_from_bytes(bytes, format).is_ok(), "{format:?}: the unmutated file must read");
    let mut rng = Rng(seed);
    let mut refused = 0;
    for round in 0..rounds {
        let m = mutate(bytes, &mut rng);
        match std::panic::catch_unwind(|| read_mesh_from_bytes(&m, format)) {
            Ok(Ok(mesh)) => {
                let n = mesh.vertices.len();
                assert!(mesh.faces.iter().flatten().all(|&v| (v as usize) < n), "{format:?} round {round}");
            }
            Ok(Err(_)) => refused += 1,
            Err(_) => panic!("{format:?} round {round}: the reader panicked"),
        }
    }
    assert!(refused > 0, "{format:?}: no mutation was refused");
}

#[test]
fn gifti_and_freesurfer_readers_survive_mutations() {
    let mesh = icosphere(1);
    for encoding in [GiftiEncoding::Ascii, GiftiEncoding::Base64Binary, GiftiEncoding::GzipBase64Binary] {
        let options = WriteOptions::default().with_gifti(GiftiOptions::default().with_encoding(encoding));
        survives(Format::Gifti, &write_mesh_to_bytes_with(&mesh, Format::Gifti, &options).unwrap(), 11 + encoding as u64, 1500);
    }
    survives(Format::Gifti, &neuro_bytes("nibabel_ascii.gii"), 21, 1500);
    survives(Format::FreeSurfer, &write_mesh_to_bytes(&mesh, Format::FreeSurfer).unwrap(), 31, 3000);
}

#[test]
fn attribute_readers_survive_mutations() {
    for (name, format, seed) in [
        ("nibabel_task.func.gii", AttributeFormat::Gifti, 41),
        ("nibabel_rh.aparc.annot.gii", AttributeFormat::Gifti, 42),
        ("brain12k.curv", AttributeFormat::FreeSurferCurv, 43),
    ] {
        let bytes = neuro_bytes(name);
        let mut rng = Rng(seed);
        let mut refused = 0;
        for round in 0..300 {
            let m = mutate(&bytes, &mut rng);
            match std::panic::catch_unwind(|| read_vertex_attributes_from_bytes(&m, format)) {
                Ok(Ok(_)) => {}
                Ok(Err(_)) => refused += 1,
                Err(_) => panic!("{name} round {round}: the reader panicked"),
            }
        }
        assert!(refused > 0, "{name}: no mutation was refused");
    }
}
