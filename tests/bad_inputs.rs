//! A corpus of bad inputs, each with the exact error it must produce, and robustness checks:
//! no panic on mangled files, and reading never modifies the input.

mod common;

use common::{data, TempDir};

use std::path::PathBuf;

use capmesh::io::{
    read_mesh, read_mesh_from_bytes, write_mesh, write_mesh_to_bytes, Format, Location, ReadError,
    WriteError,
};
use capmesh::mesh::repair::{default_weld_tolerance, keep_main_component, split_pinched_vertices, weld_coincident};
use capmesh::mesh::shapes::{annulus, grid_disk, icosphere, spherical_cap, torus};
use capmesh::mesh::validate::require_clean;
use capmesh::mesh::{inspect, validate, MeshError, SurfaceKind, TriMesh};

fn read_str(dir: &TempDir, name: &str, text: &str) -> Result<TriMesh, ReadError> {
    read_mesh(&dir.file(name, text.as_bytes()))
}

fn mesh(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> TriMesh {
    TriMesh::new(vertices.to_vec(), faces.to_vec())
}

/// Four corners of the unit square and a fifth point.
const SQUARE: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.5, 1.0],
];

// ---------------------------------------------------------------- file-level errors

#[test]
fn empty_files() {
    let dir = TempDir::new("empty");
    for name in ["e.obj", "e.ply", "e.off", "e.stl"] {
        let err = read_mesh(&dir.file(name, b"")).unwrap_err();
        assert!(matches!(err, ReadError::Empty { .. }), "{name}: {err}");
        assert!(err.to_string().contains(name), "{err}");
    }
    let err = read_str(&dir, "comments.obj", "# nothing here\n\n").unwrap_err();
    assert!(matches!(err, ReadError::Empty { .. }), "{err}");
    let err = read_str(&dir, "zero.off", "OFF\n0 0 0\n").unwrap_err();
    assert!(matches!(err, ReadError::Empty { .. }), "{err}");
}

#[test]
fn point_cloud_has_no_faces() {
    let dir = TempDir::new("cloud");
    let err = read_str(&dir, "cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap_err();
    assert!(
        matches!(err, ReadError::NoFaces { n_vertices: 3, .. }),
        "{err}"
    );
}

#[test]
fn unknown_format_and_missing_file() {
    let dir = TempDir::new("unknown");
    let err = read_mesh(&dir.file("mesh.vtk", b"# vtk")).unwrap_err();
    assert!(
        matches!(&err, ReadError::UnknownFormat { extension, .. } if extension == "vtk"),
        "{err}"
    );
    let err = read_mesh(&dir.join("missing.obj")).unwrap_err();
    assert!(matches!(err, ReadError::Io { .. }), "{err}");
    let err = write_mesh(&dir.join("out.xyz"), &grid_disk(1)).unwrap_err();
    assert!(matches!(err, WriteError::UnknownFormat { .. }), "{err}");
    let err = write_mesh(&dir.join("no/such/dir/out.obj"), &grid_disk(1)).unwrap_err();
    assert!(matches!(err, WriteError::Io { .. }), "{err}");
}

#[test]
fn truncated_ply_ascii() {
    let dir = TempDir::new("trunc-ply-ascii");
    let text = "ply\nformat ascii 1.0\nelement vertex 1000\nproperty float x\nproperty float y\n\
                property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
                0 0 0\n1 0 0\n";
    let err = read_str(&dir, "t.ply", text).unwrap_err();
    assert!(
        matches!(&err, ReadError::Truncated { expected: 1000, found: 2, what, .. } if what == "vertices"),
        "{err}"
    );
}

#[test]
fn truncated_ply_binary() {
    let dir = TempDir::new("trunc-ply-bin");
    let full = write_mesh_to_bytes(&icosphere(1), Format::Ply).unwrap();
    // Cut inside the face data: 42 vertices of 24 bytes after the header, then 13-byte faces.
    let header = full.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let cut = header + 42 * 24 + 13 * 10 + 5;
    let err = read_mesh(&dir.file("t.ply", &full[..cut])).unwrap_err();
    assert!(
        matches!(&err, ReadError::Truncated { expected: 80, found: 10, what, .. } if what == "faces"),
        "{err}"
    );
    let cut = header + 200 + 7;
    let err = read_mesh(&dir.file("v.ply", &full[..cut])).unwrap_err();
    assert!(
        matches!(&err, ReadError::Truncated { expected: 42, found: 8, what, .. } if what == "vertices"),
        "{err}"
    );
    let err = read_mesh(&dir.file("h.ply", &full[..header - 4])).unwrap_err();
    assert!(matches!(err, ReadError::Parse { .. }), "{err}");
}

#[test]
fn truncated_binary_stl() {
    let dir = TempDir::new("trunc-stl");
    let full = write_mesh_to_bytes(&icosphere(1), Format::Stl).unwrap();
    assert_eq!(full.len(), 84 + 50 * 80);
    let err = read_mesh(&dir.file("t.stl", &full[..84 + 50 * 30 + 20])).unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Truncated {
                expected: 4084,
                found: 1604,
                ..
            }
        ),
        "{err}"
    );
    let err = read_mesh(&dir.file("h.stl", &full[..40])).unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Truncated {
                expected: 84,
                found: 40,
                ..
            }
        ),
        "{err}"
    );
    // A binary STL whose header starts with "solid" is still recognised as truncated binary.
    let mut solid = full.clone();
    solid[..5].copy_from_slice(b"solid");
    let err = read_mesh(&dir.file("s.stl", &solid[..2000])).unwrap_err();
    assert!(matches!(err, ReadError::Truncated { .. }), "{err}");
}

#[test]
fn corrupt_gzip() {
    let dir = TempDir::new("gzip");
    let good = dir.join("m.obj.gz");
    write_mesh(&good, &icosphere(2)).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    let err = read_mesh(&dir.file("cut.obj.gz", &bytes[..bytes.len() / 2])).unwrap_err();
    assert!(matches!(err, ReadError::Decompress { .. }), "{err}");
    let err = read_mesh(&dir.file("plain.obj.gz", b"v 0 0 0\n")).unwrap_err();
    assert!(matches!(err, ReadError::Decompress { .. }), "{err}");
    let err = read_mesh(&dir.file("m.vtk.gz", &bytes)).unwrap_err();
    assert!(
        matches!(&err, ReadError::UnknownFormat { extension, .. } if extension == "vtk.gz"),
        "{err}"
    );
}

#[test]
fn truncated_off() {
    let dir = TempDir::new("trunc-off");
    let err = read_str(
        &dir,
        "t.off",
        "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n",
    )
    .unwrap_err();
    assert!(
        matches!(&err, ReadError::Truncated { expected: 2, found: 1, what, .. } if what == "faces"),
        "{err}"
    );
}

#[test]
fn obj_nan_coordinate_names_the_line() {
    let dir = TempDir::new("nan");
    for bad in ["nan", "NaN", "inf", "-inf", "1e999"] {
        let text = format!("# header\nv 0 0 0\nv 1 {bad} 0\nv 0 1 0\nf 1 2 3\n");
        let err = read_str(&dir, "nan.obj", &text).unwrap_err();
        assert!(
            matches!(
                err,
                ReadError::NonFinite {
                    at: Location::Line(3),
                    ..
                }
            ),
            "{bad}: {err}"
        );
        assert!(err.to_string().contains("line 3"), "{err}");
    }
    let err = read_str(
        &dir,
        "nan.off",
        "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n",
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::NonFinite {
                at: Location::Line(4),
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn obj_index_out_of_range_names_the_line() {
    let dir = TempDir::new("index");
    let cases: [(&str, i64, usize); 4] = [
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n", 9, 5),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 0, 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", -4, 4),
        ("f 1 2 3\nv 0 0 0\nv 1 0 0\n", 3, 1),
    ];
    for (text, index, line) in cases {
        let err = read_str(&dir, "i.obj", text).unwrap_err();
        assert!(
            matches!(err, ReadError::IndexOutOfRange { at: Location::Line(l), index: i, .. } if l == line && i == index),
            "{text:?}: {err}"
        );
    }
    let err = read_str(&dir, "i.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::IndexOutOfRange {
                at: Location::Line(6),
                index: 3,
                n_vertices: 3,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn malformed_text() {
    let dir = TempDir::new("malformed");
    let err = read_str(&dir, "m.obj", "v 0 0 0\nv 1 x 0\n").unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Parse {
                at: Location::Line(2),
                ..
            }
        ),
        "{err}"
    );
    let err = read_str(&dir, "m.obj", "v 0 0 0\nv 1 0\n").unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Parse {
                at: Location::Line(2),
                ..
            }
        ),
        "{err}"
    );
    let err = read_str(&dir, "m.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Parse {
                at: Location::Line(3),
                ..
            }
        ),
        "{err}"
    );
    let err = read_str(&dir, "m.off", "OFF BINARY\n").unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Parse {
                at: Location::Line(1),
                ..
            }
        ),
        "{err}"
    );
    let err = read_str(&dir, "m.ply", "not a ply\n").unwrap_err();
    assert!(
        matches!(
            err,
            ReadError::Parse {
                at: Location::Line(1),
                ..
            }
        ),
        "{err}"
    );
    let err = read_str(
        &dir,
        "m.stl",
        "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n",
    )
    .unwrap_err();
    assert!(matches!(err, ReadError::Parse { .. }), "{err}");
}

#[test]
fn unsupported_ply() {
    let dir = TempDir::new("ply");
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let strips = format!("{head}element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    let err = read_str(&dir, "s.ply", &strips).unwrap_err();
    assert!(matches!(err, ReadError::UnsupportedPly { .. }), "{err}");
    let no_list =
        format!("{head}element face 1\nproperty int a\nend_header\n0 0 0\n1 0 0\n0 1 0\n3\n");
    let err = read_str(&dir, "n.ply", &no_list).unwrap_err();
    assert!(matches!(err, ReadError::UnsupportedPly { .. }), "{err}");
    let no_z = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n";
    let err = read_str(&dir, "z.ply", no_z).unwrap_err();
    assert!(matches!(err, ReadError::UnsupportedPly { .. }), "{err}");
    let fmt = "ply\nformat binary_middle_endian 1.0\nend_header\n";
    let err = read_str(&dir, "f.ply", fmt).unwrap_err();
    assert!(matches!(err, ReadError::UnsupportedPly { .. }), "{err}");
}

#[test]
fn writers_refuse_broken_meshes() {
    let bad_index = mesh(&SQUARE[..3], &[[0, 1, 7]]);
    assert!(matches!(
        write_mesh_to_bytes(&bad_index, Format::Obj),
        Err(WriteError::IndexOutOfRange {
            face: 0,
            index: 7,
            ..
        })
    ));
    let nan = mesh(
        &[[0.0, f64::NAN, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[[0, 1, 2]],
    );
    assert!(matches!(
        write_mesh_to_bytes(&nan, Format::Ply),
        Err(WriteError::NonFinite { vertex: 0, .. })
    ));
    let huge = mesh(
        &[[1e300, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[[0, 1, 2]],
    );
    assert!(matches!(
        write_mesh_to_bytes(&huge, Format::Stl),
        Err(WriteError::Unsupported { .. })
    ));
}

// ---------------------------------------------------------------- mesh-level errors

#[test]
fn mesh_hard_errors() {
    type Case = (&'static str, TriMesh, fn(&MeshError) -> bool);
    let cases: Vec<Case> = vec![
        ("empty", TriMesh::default(), |e| {
            matches!(
                e,
                MeshError::Empty {
                    n_vertices: 0,
                    n_faces: 0
                }
            )
        }),
        ("no faces", mesh(&SQUARE, &[]), |e| {
            matches!(
                e,
                MeshError::Empty {
                    n_vertices: 5,
                    n_faces: 0
                }
            )
        }),
        ("index", mesh(&SQUARE, &[[0, 1, 2], [0, 2, 5]]), |e| {
            matches!(
                e,
                MeshError::IndexOutOfRange {
                    face: 1,
                    index: 5,
                    n_vertices: 5
                }
            )
        }),
        (
            "nan",
            mesh(
                &[[0.0; 3], [1.0, f64::NAN, 0.0], [0.0, 1.0, 0.0]],
                &[[0, 1, 2]],
            ),
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 1 }),
        ),
        (
            "huge coordinates",
            mesh(&[[0.0; 3], [1e200, 0.0, 0.0], [0.0, 1e200, 0.0]], &[[0, 1, 2]]),
            |e| matches!(e, MeshError::ScaleOutOfRange { exponent: 200 }),
        ),
        (
            "tiny coordinates",
            mesh(&[[0.0; 3], [1e-200, 0.0, 0.0], [0.0, 1e-200, 0.0]], &[[0, 1, 2]]),
            |e| matches!(e, MeshError::ScaleOutOfRange { exponent: -200 }),
        ),
        (
            "repeated index",
            mesh(&SQUARE, &[[0, 1, 2], [0, 2, 2]]),
            |e| {
                matches!(
                    e,
                    MeshError::DegenerateFace {
                        face: 1,
                        vertices: [0, 2, 2]
                    }
                )
            },
        ),
        (
            "duplicate face",
            mesh(&SQUARE, &[[0, 1, 2], [0, 2, 3], [2, 0, 1]]),
            |e| matches!(e, MeshError::DuplicateFace { face: 2, first: 0 }),
        ),
        (
            "duplicate flipped face",
            mesh(&SQUARE, &[[0, 1, 2], [0, 2, 3], [0, 2, 1]]),
            |e| matches!(e, MeshError::DuplicateFace { face: 2, first: 0 }),
        ),
        // Three faces on edge 0-2.
        (
            "non-manifold edge",
            mesh(&SQUARE, &[[0, 1, 2], [0, 2, 3], [2, 0, 4]]),
            |e| {
                matches!(
                    e,
                    MeshError::NonManifoldEdge {
                        a: 0,
                        b: 2,
                        faces: 3
                    }
                )
            },
        ),
        // Face 1 is flipped: both faces use the edge 2 -> 0.
        (
            "flipped face",
            mesh(&SQUARE, &[[0, 1, 2], [0, 3, 2]]),
            |e| {
                matches!(
                    e,
                    MeshError::InconsistentOrientation {
                        a: 2,
                        b: 0,
                        faces: [0, 1]
                    }
                )
            },
        ),
        // Two triangles touching at vertex 2 only.
        (
            "bowtie",
            mesh(
                &[
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.5, 0.5, 0.0],
                    [0.0, 1.0, 0.0],
                    [1.0, 1.0, 0.0],
                ],
                &[[0, 1, 2], [2, 4, 3]],
            ),
            |e| matches!(e, MeshError::NonManifoldVertex { vertex: 2, fans: 2 }),
        ),
    ];
    for (name, m, expected) in cases {
        let err = inspect(&m).unwrap_err();
        assert!(expected(&err), "{name}: got {err:?}");
        let err = validate(&m).unwrap_err();
        assert!(expected(&err), "{name}: validate got {err:?}");
    }
}

#[test]
fn two_fans_sharing_a_vertex_on_closed_surfaces() {
    // Two tetrahedra glued at one vertex: every edge is manifold, the vertex is not.
    let tet = |o: [f64; 3]| -> Vec<[f64; 3]> {
        vec![
            o,
            [o[0] + 1.0, o[1], o[2]],
            [o[0], o[1] + 1.0, o[2]],
            [o[0], o[1], o[2] + 1.0],
        ]
    };
    let mut vertices = tet([0.0; 3]);
    vertices.extend(tet([-1.0, -1.0, -1.0])[..3].iter().copied());
    // Second tetrahedron uses vertex 3 of the first as its apex.
    let faces = vec![
        [0, 2, 1],
        [0, 1, 3],
        [1, 2, 3],
        [0, 3, 2],
        [4, 6, 5],
        [4, 5, 3],
        [5, 6, 3],
        [4, 3, 6],
    ];
    let err = inspect(&TriMesh::new(vertices, faces)).unwrap_err();
    assert_eq!(err, MeshError::NonManifoldVertex { vertex: 3, fans: 2 });
}

#[test]
fn splitting_pinched_vertices_gives_one_vertex_per_fan() {
    // The bowtie: two triangles touching at vertex 2; the second gets a copy of it.
    let bowtie = mesh(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]], &[[0, 1, 2], [2, 4, 3]]);
    let split = split_pinched_vertices(&bowtie).unwrap();
    assert_eq!(split.copy_of, vec![2]);
    assert_eq!(split.mesh.faces, vec![[0, 1, 2], [5, 4, 3]]);
    assert_eq!(split.mesh.vertices[5], split.mesh.vertices[2]);
    assert_eq!(inspect(&split.mesh).unwrap().n_components, 2);
    // A manifold mesh comes back as it is; a non-manifold edge is still an error.
    let sphere = icosphere(1);
    let same = split_pinched_vertices(&sphere).unwrap();
    assert!(same.copy_of.is_empty() && same.mesh == sphere);
    let fin = mesh(&SQUARE, &[[0, 1, 4], [1, 0, 2], [0, 1, 3]]);
    assert!(matches!(split_pinched_vertices(&fin), Err(MeshError::NonManifoldEdge { .. }) | Err(MeshError::InconsistentOrientation { .. })));
}

#[test]
fn two_components() {
    let a = grid_disk(2);
    let mut b = grid_disk(2);
    let offset = a.n_vertices() as u32;
    let mut m = a.clone();
    m.vertices
        .extend(b.vertices.iter().map(|p| [p[0] + 3.0, p[1], p[2]]));
    b.faces
        .iter_mut()
        .for_each(|f| f.iter_mut().for_each(|v| *v += offset));
    m.faces.extend(b.faces);
    let summary = inspect(&m).unwrap();
    assert_eq!((summary.n_components, summary.kind), (2, None));
    assert_eq!(
        validate(&m).unwrap_err(),
        MeshError::SeveralComponents { count: 2 }
    );
    // Of two equal pieces the one met first is kept, with half the area dropped.
    let main = keep_main_component(&m).unwrap();
    assert_eq!(main.mesh, a);
    assert_eq!(main.faces, (0..a.n_faces() as u32).collect::<Vec<_>>());
    assert_eq!(main.dropped_components, 1);
    assert!((main.dropped_area_share - 0.5).abs() < 1e-12);
    assert!(keep_main_component(&a).is_none());
}

#[test]
fn annulus_has_two_boundary_loops() {
    let err = validate(&annulus(0.5, 1.0, 4, 32)).unwrap_err();
    assert_eq!(err, MeshError::SeveralBoundaryLoops { count: 2 });
}

#[test]
fn torus_is_genus_one() {
    let err = validate(&torus(1.0, 0.3, 32, 12)).unwrap_err();
    assert_eq!(
        err,
        MeshError::NotSimplyConnected {
            genus: 1,
            boundary_loops: 0
        }
    );
}

#[test]
fn bird_skull_is_genus_two() {
    let m = read_mesh(&data("bad_genus2_bird_skull_choi.obj.gz")).unwrap();
    assert_eq!((m.n_vertices(), m.n_faces()), (5755, 11514));
    let s = inspect(&m).unwrap();
    assert_eq!(
        (s.euler_characteristic, s.genus, s.kind),
        (-2, Some(2), None)
    );
    assert_eq!(
        validate(&m).unwrap_err(),
        MeshError::NotSimplyConnected {
            genus: 2,
            boundary_loops: 0
        }
    );
}

#[test]
fn hippocampus_needs_welding() {
    let m = read_mesh(&data("open_hippocampus_sheet_hippunfold.obj.gz")).unwrap();
    let before = inspect(&m).unwrap();
    assert_eq!(before.coincident_vertex_pairs, 14, "{before:?}");
    assert_eq!(before.zero_area_faces, 28, "{before:?}");
    let welded = weld_coincident(&m, default_weld_tolerance(&m));
    assert_eq!(welded.merged_vertices, 14);
    let (kind, topo) = validate(&welded.mesh).unwrap();
    assert_eq!(kind, SurfaceKind::OpenDisk);
    assert_eq!(topo.boundary_loops.len(), 1);
    let after = inspect(&welded.mesh).unwrap();
    assert_eq!(
        (
            after.zero_area_faces,
            after.coincident_vertex_pairs,
            after.unreferenced_vertices
        ),
        (0, 0, 0)
    );
    require_clean(&welded.mesh, 1e-12).unwrap();
}

#[test]
fn unreferenced_vertices_and_zero_area_faces_are_accepted_by_validate() {
    let m = mesh(&SQUARE, &[[0, 1, 2], [0, 2, 3]]);
    assert_eq!(validate(&m).unwrap().0, SurfaceKind::OpenDisk);
    assert_eq!(inspect(&m).unwrap().unreferenced_vertices, 1);
    assert_eq!(
        require_clean(&m, 1e-12).unwrap_err(),
        MeshError::UnreferencedVertex { vertex: 4 }
    );
    // Collinear corners: (0,0,0), (1,0,0), (2,0,0).
    let flat = mesh(
        &[[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
        &[[0, 1, 3], [1, 2, 3], [0, 2, 1]],
    );
    assert_eq!(inspect(&flat).unwrap().zero_area_faces, 1);
    assert_eq!(
        require_clean(&flat, 1e-12).unwrap_err(),
        MeshError::ZeroAreaFace { face: 2 }
    );
}

// ---------------------------------------------------------------- robustness

/// Deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

#[test]
fn mangled_files_never_panic() {
    let small = spherical_cap(0.5, 2, 8);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut inputs: Vec<(Format, Vec<u8>)> = Vec::new();
    for format in [Format::Obj, Format::Ply, Format::Off, Format::Stl] {
        inputs.push((format, write_mesh_to_bytes(&small, format).unwrap()));
    }
    inputs.push((Format::Stl, b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n".to_vec()));
    let dir = TempDir::new("fuzz");
    let ascii = dir.join("a.ply");
    capmesh::io::write_ply_ascii(&ascii, &small).unwrap();
    inputs.push((Format::Ply, std::fs::read(&ascii).unwrap()));
    let specials: &[&[u8]] = &[
        b" ",
        b"\n",
        b"-",
        b"/",
        b"#",
        b"nan",
        b"4294967295",
        b"-1",
        b"99999999999999999999",
        b"\0",
        b"\xff",
    ];
    for (format, bytes) in &inputs {
        // Every prefix (truncation).
        for cut in 0..bytes.len().min(2000) {
            let _ = read_mesh_from_bytes(&bytes[..cut], *format);
        }
        // Random byte edits and token insertions.
        for _ in 0..3000 {
            let mut b = bytes.clone();
            for _ in 0..1 + rng.next() % 4 {
                let i = (rng.next() as usize) % b.len();
                if rng.next() % 2 == 0 {
                    b[i] = rng.next() as u8;
                } else {
                    let s = specials[(rng.next() as usize) % specials.len()];
                    b.splice(i..i, s.iter().copied());
                }
            }
            if let Ok(m) = read_mesh_from_bytes(&b, *format) {
                let _ = inspect(&m);
                let _ = validate(&m);
                let _ = weld_coincident(&m, 1e-9);
            }
        }
    }
}

#[test]
fn reading_never_modifies_the_input() {
    let dir = TempDir::new("readonly");
    let mut paths: Vec<PathBuf> = [
        "open_face_choi.obj.gz",
        "bad_genus2_bird_skull_choi.obj.gz",
        "open_hippocampus_sheet_hippunfold.obj.gz",
        "open_lv_endo_rabbit_chaste.obj.gz",
        "closed_bunny_npm.obj.gz",
    ]
    .iter()
    .map(|n| data(n))
    .collect();
    let cap = spherical_cap(0.0, 6, 24);
    for ext in ["obj", "ply", "off", "stl"] {
        let p = dir.join(format!("cap.{ext}"));
        write_mesh(&p, &cap).unwrap();
        paths.push(p);
    }
    paths.push(dir.file(
        "broken.ply",
        b"ply\nformat ascii 1.0\nelement vertex 9\nend_header\n1 2",
    ));
    for path in paths {
        let before = std::fs::read(&path).unwrap();
        let meta = std::fs::metadata(&path).unwrap();
        let (mtime, len, readonly) = (
            meta.modified().unwrap(),
            meta.len(),
            meta.permissions().readonly(),
        );
        let _ = read_mesh(&path);
        let _ = read_mesh(&path);
        let meta = std::fs::metadata(&path).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), before, "{}", path.display());
        assert_eq!(
            (
                meta.modified().unwrap(),
                meta.len(),
                meta.permissions().readonly()
            ),
            (mtime, len, readonly)
        );
    }
}

#[test]
fn error_messages_are_informative() {
    let dir = TempDir::new("messages");
    let err = read_str(&dir, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("m.obj") && text.contains("line 4") && text.contains('9'),
        "{text}"
    );
    let err = MeshError::NonManifoldEdge {
        a: 3,
        b: 7,
        faces: 3,
    }
    .to_string();
    assert!(
        err.contains('3') && err.contains('7') && err.contains("Repair non Manifold Edges"),
        "{err}"
    );
}

#[test]
fn huge_announced_counts_fail_fast() {
    let inputs: [(&[u8], Format); 5] = [
        (b"ply\nformat ascii 1.0\nelement junk 18446744073709551615\nend_header\n", Format::Ply),
        (b"ply\nformat binary_little_endian 1.0\nelement vertex 4294967295\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0", Format::Ply),
        (b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n4294967295 0 1 2\n", Format::Ply),
        (b"OFF\n3 18446744073709551615 0\n0 0 0\n1 0 0\n0 1 0\n", Format::Off),
        (b"\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\xff\xff\xff\xff", Format::Stl),
    ];
    // Failing fast means from the counts against the bytes present, before anything the
    // size of the announced count is allocated or read: each input gets the error that says
    // so (no clock: a time limit would only measure the machine).
    let errors: Vec<ReadError> = inputs.iter().map(|&(bytes, format)| read_mesh_from_bytes(bytes, format).unwrap_err()).collect();
    assert!(matches!(errors[0], ReadError::Empty { .. }), "{:?}", errors[0]);
    assert!(matches!(&errors[1], ReadError::Truncated { what, expected: 4294967295, found: 0, .. } if what == "vertices"), "{:?}", errors[1]);
    assert!(matches!(&errors[2], ReadError::Truncated { what, expected: 1, found: 0, .. } if what == "faces"), "{:?}", errors[2]);
    assert!(matches!(errors[3], ReadError::Parse { at: Location::Line(2), .. }), "{:?}", errors[3]);
    assert!(matches!(errors[4], ReadError::Truncated { expected: 214748364834, found: 84, .. }), "{:?}", errors[4]);
}

/// Meshes built in memory (library and C ABI users) go through the same hard checks before
/// welding: a face with an index out of range or a repeated index is an error, not a face
/// silently dropped (found by the `pipeline` fuzz target: the remesh pull-back then indexed
/// past the map).
#[test]
fn in_memory_meshes_with_bad_faces_are_refused_by_the_pipeline() {
    use capmesh::param::{parameterize, ParamOptions};
    use capmesh::remesh::{remesh, RemeshOptions};
    use capmesh::{Error, NoProgress};
    let cap = spherical_cap(0.3, 4, 12);
    let n = cap.vertices.len() as u32;
    let mut out_of_range = cap.clone();
    out_of_range.faces[3][1] = n + 1;
    let mut repeated = cap.clone();
    repeated.faces[5] = [2, 2, 7];
    for (m, what) in [(&out_of_range, "index out of range"), (&repeated, "repeated index")] {
        let p = parameterize(m, &ParamOptions::default(), &NoProgress).err();
        let r = remesh(m, &RemeshOptions::default(), &NoProgress).err();
        for e in [p, r] {
            match e {
                Some(Error::Mesh(MeshError::IndexOutOfRange { .. })) if what == "index out of range" => {}
                Some(Error::Mesh(MeshError::DegenerateFace { .. })) if what == "repeated index" => {}
                other => panic!("{what}: {other:?}"),
            }
        }
    }
}

/// OBJ, OFF and ASCII STL read a vertex's coordinates alike (`io::read_point`): a missing
/// coordinate, a word and a NaN are each refused with the line named.
#[test]
fn vertex_coordinates_are_checked_alike_in_every_text_format() {
    let dir = TempDir::new("coordinates");
    let stl = |v: &str| format!("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n{v}\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
    let off = |v: &str| format!("OFF\n3 1 0\n0 0 0\n{v}\n0 1 0\n3 0 1 2\n");
    let obj = |v: &str| format!("v 0 0 0\n{v}\nv 0 1 0\nf 1 2 3\n");
    let cases: [(&str, String, &str); 9] = [
        ("a.obj", obj("v 1 0"), "line 2"),
        ("b.obj", obj("v 1 zero 0"), "'zero' is not a number"),
        ("c.obj", obj("v 1 nan 0"), "line 2"),
        ("a.off", off("1 0"), "found 2"),
        ("b.off", off("1 zero 0"), "'zero' is not a number"),
        ("c.off", off("1 nan 0"), "line 4"),
        ("a.stl", stl("vertex 1 0"), "found 2"),
        ("b.stl", stl("vertex 1 zero 0"), "'zero' is not a number"),
        ("c.stl", stl("vertex 1 nan 0"), "line 5"),
    ];
    for (name, text, says) in cases {
        let err = read_str(&dir, name, &text).unwrap_err();
        assert!(err.to_string().contains(says), "{name}: {err}");
        if text.contains("nan") {
            assert!(matches!(err, ReadError::NonFinite { .. }), "{name}: {err}");
        }
    }
}
