//! GIFTI and FreeSurfer files on real data (tests/data/neuro, see NOTICE.md): the 12k-vertex
//! brain of tests/data and its mean curvature, written by nibabel (make_brain12k.py) as a
//! GZipBase64Binary GIFTI surface and shape file and as FreeSurfer surface and curvature
//! binaries, and nibabel's GIFTI test files (ASCII, legacy Base64 names, a label file, a
//! 10-array functional file). Expected values are what nibabel 5.4.2 reads from the same files.
//! Then round trips through every writer variant.

mod common;

use std::io::Read;
use std::path::{Path, PathBuf};

use capmesh::io::{
    read_mesh, read_mesh_from_bytes, read_vertex_attributes, read_vertex_attributes_for, write_mesh, write_mesh_with,
    AttributeData, Endian, Format, GiftiEncoding, GiftiFloat, GiftiOptions, ReadError, WriteOptions,
};
use capmesh::mesh::shapes::icosphere;
use capmesh::mesh::{validate, SurfaceKind};
use capmesh::TriMesh;
use common::TempDir;

fn neuro(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/neuro").join(name)
}

fn brain12k() -> TriMesh {
    read_mesh(&neuro("brain12k.surf.gii.gz")).unwrap()
}

#[test]
fn brain12k_gifti_surface_matches_nibabel() {
    let mesh = brain12k();
    assert_eq!((mesh.n_vertices(), mesh.n_faces()), (12502, 25000));
    assert_eq!(mesh.vertices[0], [19.24109f32, -93.55692, -23.93404].map(f64::from));
    assert_eq!(mesh.faces[0], [0, 10918, 2826]);
    let sum: f64 = mesh.vertices.iter().flatten().sum();
    assert!((sum - 193067.79661177984).abs() < 1e-6, "coordinate sum {sum}");
    let index_sum: u64 = mesh.faces.iter().flatten().map(|&i| u64::from(i)).sum();
    assert_eq!(index_sum, 473496594);
    assert_eq!(validate(&mesh).unwrap().0, SurfaceKind::ClosedSphere);
    // The same surface as the OBJ it was made from, to float32.
    let obj = read_mesh(&common::data("closed_brain12k_choi.obj.gz")).unwrap();
    assert_eq!(mesh.vertices, rounded(&obj));
    assert_eq!(mesh.faces, obj.faces);
}

#[test]
fn freesurfer_surface_equals_the_gifti_one_with_or_without_extension() {
    let gifti = brain12k();
    let fs = read_mesh(&neuro("brain12k.pial.gz")).unwrap();
    assert_eq!(fs.vertices, gifti.vertices);
    assert_eq!(fs.faces, gifti.faces);
    // No extension at all: recognised by the magic bytes.
    let mut raw = Vec::new();
    flate2::read::GzDecoder::new(std::fs::File::open(neuro("brain12k.pial.gz")).unwrap())
        .read_to_end(&mut raw)
        .unwrap();
    let dir = TempDir::new("fs-noext");
    let plain = read_mesh(&dir.file("surface", &raw)).unwrap();
    assert_eq!(plain.vertices, gifti.vertices);
    assert_eq!(plain.faces, gifti.faces);
    assert_eq!(Format::from_content(&raw), Some(Format::FreeSurfer));
}

#[test]
fn nibabel_ascii_gifti() {
    let mesh = read_mesh(&neuro("nibabel_ascii.gii")).unwrap();
    let expected = [
        [-16.07201f32, -66.187515, 21.266994],
        [-16.705893, -66.05434, 21.232786],
        [-17.61435, -65.40164, 21.071466],
    ];
    // FLOAT32 decimals are read as float32, like nibabel does.
    assert_eq!(mesh.vertices, expected.map(|p| p.map(f64::from)).to_vec());
    assert_eq!(mesh.faces, vec![[0, 1, 2]]);
}

#[test]
fn legacy_base64_names_decode_and_bad_indices_are_refused() {
    // nibabel's base64bin.gii uses GIFTI_ENCODING_B64BIN / GIFTI_ENDIAN_LITTLE; its 10
    // triangles are cut from a larger surface and name vertices up to 25604 (nibabel reads the
    // arrays without checking): capmesh decodes them and refuses the first bad index, 6402.
    let err = read_mesh(&neuro("nibabel_base64bin.gii")).unwrap_err();
    match &err {
        ReadError::IndexOutOfRange { index: 6402, n_vertices: 10, .. } => {}
        other => panic!("unexpected {other:?}"),
    }
    let text = err.to_string();
    assert!(text.contains("nibabel_base64bin.gii, line 37") && text.contains("export it again"), "{text}");
}

#[test]
fn curvature_from_gifti_and_freesurfer_agree() {
    let mesh = brain12k();
    let gifti = read_vertex_attributes_for(&neuro("brain12k_curv.shape.gii"), &mesh).unwrap();
    assert_eq!(gifti.len(), 1);
    assert_eq!(gifti[0].name, "mean curvature");
    let AttributeData::Scalar(values) = &gifti[0].data else { panic!("curvature must be scalar") };
    assert_eq!(values[..3], [0.31908748f32, 0.07830478, 0.00433728]);
    let sum: f64 = values.iter().map(|&x| f64::from(x)).sum();
    assert!((sum - 263.64272444412563).abs() < 1e-6, "{sum}");
    // The FreeSurfer file has no extension capmesh knows: recognised by content.
    let fs = read_vertex_attributes(&neuro("brain12k.curv")).unwrap();
    assert_eq!(fs.len(), 1);
    assert_eq!(fs[0].name, "brain12k.curv");
    assert_eq!(fs[0].data, gifti[0].data);
    // Data of another surface are refused with both counts.
    let bunny = read_mesh(&common::data("closed_bunny_npm.obj.gz")).unwrap();
    let err = read_vertex_attributes_for(&neuro("brain12k.curv"), &bunny).unwrap_err();
    assert!(matches!(err, ReadError::AttributeLength { found: 12502, expected: 1839, .. }), "{err}");
}

#[test]
fn label_file_with_its_table() {
    let attributes = read_vertex_attributes(&neuro("nibabel_rh.aparc.annot.gii")).unwrap();
    assert_eq!(attributes.len(), 1);
    let a = &attributes[0];
    assert_eq!(a.name, "node label");
    let AttributeData::Label(labels) = &a.data else { panic!("labels expected") };
    assert_eq!(labels.len(), 151533);
    assert_eq!(labels[..5], [9182740; 5]);
    assert_eq!(a.label_table.len(), 36);
    assert_eq!(a.label_table[0], (1639705, "unknown".to_string()));
    assert_eq!(a.label_table[1], (2647065, "bankssts".to_string()));
    // Every label used is in the table.
    assert!(labels.iter().all(|l| *l == 0 || a.label_table.iter().any(|(k, _)| k == l)));
}

#[test]
fn functional_file_gives_one_attribute_per_array() {
    let attributes = read_vertex_attributes(&neuro("nibabel_task.func.gii")).unwrap();
    assert_eq!(attributes.len(), 10);
    assert!(attributes.iter().all(|a| a.data.len() == 642));
    assert_eq!(attributes[0].name, "time_series 0");
    let AttributeData::Scalar(first) = &attributes[0].data else { panic!() };
    assert_eq!(first[..3], [545.4326f32, 640.0118, 612.9056]);
    let AttributeData::Scalar(last) = &attributes[9].data else { panic!() };
    assert_eq!(last[640..], [363.10278f32, 259.7127]);
}

#[test]
fn data_files_are_not_meshes_and_surfaces_not_data() {
    let err = read_mesh(&neuro("brain12k_curv.shape.gii")).unwrap_err();
    assert!(matches!(err, ReadError::WrongKind { .. }) && err.to_string().contains("vertex attributes"), "{err}");
    let err = read_mesh(&neuro("brain12k.curv")).unwrap_err();
    assert!(matches!(err, ReadError::WrongKind { .. }) && err.to_string().contains("mris_convert"), "{err}");
    let err = read_vertex_attributes(&neuro("brain12k.surf.gii.gz")).unwrap_err();
    assert!(matches!(err, ReadError::WrongKind { .. }) && err.to_string().contains("read it as a mesh"), "{err}");
    assert_eq!(Format::from_path(Path::new("lh.thickness.shape.gii")), None);
    assert_eq!(Format::from_path(Path::new("x.func.gii.gz")), None);
    assert_eq!(Format::from_path(Path::new("lh.surf.gii.gz")), Some(Format::Gifti));
    assert_eq!(Format::from_path(Path::new("lh.inflated")), Some(Format::FreeSurfer));
}

/// Coordinates rounded to float32, as the float32 writers store them.
fn rounded(mesh: &TriMesh) -> Vec<[f64; 3]> {
    mesh.vertices.iter().map(|p| p.map(|x| f64::from(x as f32))).collect()
}

#[test]
fn gifti_round_trips_in_every_encoding_type_and_byte_order() {
    let dir = TempDir::new("gifti-rt");
    // brain12k is float32-exact; the icosphere's f64 coordinates show the float64 option.
    for (name, mesh) in [("brain12k", brain12k()), ("icosphere", icosphere(2))] {
        for encoding in [GiftiEncoding::Ascii, GiftiEncoding::Base64Binary, GiftiEncoding::GzipBase64Binary] {
            for coordinates in [GiftiFloat::Float32, GiftiFloat::Float64] {
                for endian in [Endian::Little, Endian::Big] {
                    let gifti = GiftiOptions::default().with_encoding(encoding).with_coordinates(coordinates).with_endian(endian);
                    let path = dir.path(&format!("{name}_{encoding:?}_{coordinates:?}_{endian:?}.surf.gii"));
                    write_mesh_with(&path, &mesh, &WriteOptions::default().with_gifti(gifti)).unwrap();
                    let back = read_mesh(&path).unwrap();
                    let expected = match coordinates {
                        GiftiFloat::Float32 => rounded(&mesh),
                        GiftiFloat::Float64 => mesh.vertices.clone(),
                    };
                    let first = back.vertices.iter().zip(&expected).position(|(a, b)| a != b);
                    assert_eq!(first, None, "{}: first differing vertex", path.display());
                    assert_eq!(back.vertices.len(), expected.len());
                    assert!(back.faces == mesh.faces, "{}: faces differ", path.display());
                }
            }
        }
    }
    // The default is compressed, float32, little endian; also through gzip around the XML.
    let path = dir.path("default.gii.gz");
    write_mesh(&path, &icosphere(1)).unwrap();
    let text = {
        let mut s = String::new();
        flate2::read::GzDecoder::new(std::fs::File::open(&path).unwrap()).read_to_string(&mut s).unwrap();
        s
    };
    assert!(text.contains(r#"Encoding="GZipBase64Binary""#) && text.contains("NIFTI_TYPE_FLOAT32") && text.contains("LittleEndian"));
    assert_eq!(read_mesh(&path).unwrap().vertices, rounded(&icosphere(1)));
}

#[test]
fn freesurfer_round_trip() {
    let dir = TempDir::new("fs-rt");
    for mesh in [brain12k(), icosphere(2)] {
        let path = dir.path("lh.white");
        write_mesh(&path, &mesh).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes[..3], [0xFF, 0xFF, 0xFE]);
        let back = read_mesh_from_bytes(&bytes, Format::FreeSurfer).unwrap();
        assert_eq!(back.vertices, rounded(&mesh));
        assert_eq!(back.faces, mesh.faces);
    }
}

#[test]
fn column_major_big_endian_base64_and_labels() {
    // The fuzz seed: a label array with its table, and a 4 x 2 FLOAT32 array stored
    // column-major, big endian, Base64Binary (nibabel reads rows [1, 0.5], [2, 0.75], ...).
    let bytes = include_bytes!("../fuzz/seeds/labels.label.gii");
    let attributes = capmesh::io::read_vertex_attributes_from_bytes(bytes, capmesh::io::AttributeFormat::Gifti).unwrap();
    assert_eq!(attributes.len(), 3);
    assert_eq!(attributes[0].name, "parcels");
    assert_eq!(attributes[0].data, AttributeData::Label(vec![0, 7, 7, 0]));
    assert_eq!(attributes[0].label_table, vec![(0, "unknown".to_string()), (7, "cortex".to_string())]);
    assert_eq!(attributes[1].name, "shape 1[0]");
    assert_eq!(attributes[1].data, AttributeData::Scalar(vec![1.0, 2.0, 3.0, 4.0]));
    assert_eq!(attributes[2].name, "shape 1[1]");
    assert_eq!(attributes[2].data, AttributeData::Scalar(vec![0.5, 0.75, 0.875, 1.125]));
    assert!(attributes[1].label_table.is_empty());
}
