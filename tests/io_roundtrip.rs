//! Every format round-trips procedural and real meshes; format variants are read correctly.

mod common;

use common::{data, TempDir};

use std::path::Path;

use capmesh::io::{
    read_mesh, read_mesh_from_bytes, same_file, write_mesh, write_mesh_to_bytes, write_ply_ascii,
    Format,
};
use capmesh::mesh::shapes::{grid_disk, icosphere, spherical_cap, spherical_cap_sectors};
use capmesh::mesh::{validate, SurfaceKind, TriMesh};

/// Awkward values that must survive text formats exactly.
fn tricky_mesh() -> TriMesh {
    TriMesh::new(
        vec![
            [0.1, -0.0, 1e-300],
            [123_456_789.123_456_79, 1e300, -2.5e-7],
            [f64::MIN_POSITIVE, -1.0 / 3.0, 5e-324],
            [std::f64::consts::PI, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

fn assert_same(a: &TriMesh, b: &TriMesh, what: &str) {
    assert_eq!(a.faces, b.faces, "{what}: faces");
    assert_eq!(a.vertices.len(), b.vertices.len(), "{what}: vertex count");
    for (p, q) in a.vertices.iter().zip(&b.vertices) {
        for k in 0..3 {
            assert_eq!(p[k].to_bits(), q[k].to_bits(), "{what}: {p:?} vs {q:?}");
        }
    }
}

/// STL stores f32 triangle soups: compare face by face with f32 precision.
fn assert_same_stl(original: &TriMesh, read: &TriMesh, what: &str) {
    assert_eq!(original.n_faces(), read.n_faces(), "{what}: face count");
    assert_eq!(
        original.n_vertices(),
        read.n_vertices(),
        "{what}: vertex count"
    );
    for f in 0..original.n_faces() {
        let (p, q) = (original.face_points(f), read.face_points(f));
        for k in 0..3 {
            for j in 0..3 {
                assert_eq!(q[k][j], f64::from(p[k][j] as f32), "{what}: face {f}");
            }
        }
    }
}

fn procedural() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("icosphere", icosphere(3)),
        (
            "cap",
            spherical_cap(0.2, 12, spherical_cap_sectors(0.2, 12)),
        ),
        ("disk", grid_disk(6)),
    ]
}

#[test]
fn every_format_round_trips_procedural_meshes_through_files() {
    let dir = TempDir::new("procedural");
    for (name, mesh) in procedural() {
        for ext in ["obj", "ply", "off", "stl", "OBJ"] {
            let path = dir.path(&format!("{name}.{ext}"));
            write_mesh(&path, &mesh).unwrap();
            let back = read_mesh(&path).unwrap();
            if ext == "stl" {
                assert_same_stl(&mesh, &back, &format!("{name}.{ext}"));
            } else {
                assert_same(&mesh, &back, &format!("{name}.{ext}"));
            }
        }
        let ascii = dir.path(&format!("{name}_ascii.ply"));
        write_ply_ascii(&ascii, &mesh).unwrap();
        assert!(std::fs::read(&ascii)
            .unwrap()
            .starts_with(b"ply\nformat ascii 1.0\n"));
        assert_same(&mesh, &read_mesh(&ascii).unwrap(), "ascii ply");
    }
}

#[test]
fn text_formats_keep_full_f64_precision() {
    let mesh = tricky_mesh();
    for format in [Format::Obj, Format::Ply, Format::Off] {
        let bytes = write_mesh_to_bytes(&mesh, format).unwrap();
        let back = read_mesh_from_bytes(&bytes, format).unwrap();
        assert_same(&mesh, &back, &format!("{format}"));
    }
    let dir = TempDir::new("precision");
    let path = dir.path("t.ply");
    write_ply_ascii(&path, &mesh).unwrap();
    assert_same(&mesh, &read_mesh(&path).unwrap(), "ascii ply");
}

#[test]
fn real_face_mesh_round_trips() {
    let path = data("open_face_choi.obj.gz");
    let mesh = read_mesh(&path).unwrap();
    assert_eq!((mesh.n_vertices(), mesh.n_faces()), (17157, 34144));
    let (kind, topo) = validate(&mesh).unwrap();
    assert_eq!(kind, SurfaceKind::OpenDisk);
    assert_eq!(topo.euler_characteristic, 1);
    let dir = TempDir::new("face");
    for ext in ["obj", "ply", "off"] {
        let out = dir.path(&format!("face.{ext}"));
        write_mesh(&out, &mesh).unwrap();
        assert_same(&mesh, &read_mesh(&out).unwrap(), ext);
    }
    let out = dir.path("face.stl");
    write_mesh(&out, &mesh).unwrap();
    let back = read_mesh(&out).unwrap();
    assert_eq!(back.n_faces(), mesh.n_faces());
    assert_eq!(validate(&back).unwrap().0, SurfaceKind::OpenDisk);
}

#[test]
fn gzip_round_trips_and_matches_the_plain_file() {
    let dir = TempDir::new("gzip");
    let mesh = icosphere(2);
    for ext in ["obj.gz", "ply.gz", "off.GZ", "stl.gz"] {
        let path = dir.path(&format!("m.{ext}"));
        write_mesh(&path, &mesh).unwrap();
        assert_eq!(
            &std::fs::read(&path).unwrap()[..2],
            &[0x1f, 0x8b],
            "{ext} is gzip"
        );
        let back = read_mesh(&path).unwrap();
        if ext.starts_with("stl") {
            assert_same_stl(&mesh, &back, ext);
        } else {
            assert_same(&mesh, &back, ext);
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    for name in ["open_face_choi.obj", "closed_bunny_npm.obj"] {
        let (plain, gz) = (root.join(name), root.join(format!("{name}.gz")));
        if plain.exists() && gz.exists() {
            assert_same(&read_mesh(&plain).unwrap(), &read_mesh(&gz).unwrap(), name);
        }
    }
}

#[test]
fn real_bunny_is_closed_genus_0() {
    let mesh = read_mesh(&data("closed_bunny_npm.obj.gz")).unwrap();
    assert_eq!((mesh.n_vertices(), mesh.n_faces()), (1839, 3674));
    assert_eq!(validate(&mesh).unwrap().0, SurfaceKind::ClosedSphere);
}

fn unit_square() -> TriMesh {
    TriMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

#[test]
fn obj_variants() {
    let text = "# comment\r\nmtllib a.mtl\r\no square\r\nv 0 0 0\r\nv 1 0 0 1.0\r\nv 1 1 0 0.5 0.5 0.5\r\n\
                v 0 1 0\r\nvn 0 0 1\r\nvt 0 0\r\ng group\r\nusemtl m\r\ns off\r\nf 1/1/1 2/1/1 3//1 4/1 # quad\r\n";
    assert_same(
        &unit_square(),
        &read_mesh_from_bytes(text.as_bytes(), Format::Obj).unwrap(),
        "obj",
    );
    let negative = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4 -2 -1\n";
    assert_same(
        &unit_square(),
        &read_mesh_from_bytes(negative.as_bytes(), Format::Obj).unwrap(),
        "negative",
    );
    // Old-Mac line endings and faces before their vertices.
    let cr = "f 1 2 3\rf 1 3 4\rv 0 0 0\rv 1 0 0\rv 1 1 0\rv 0 1 0\r";
    assert_same(
        &unit_square(),
        &read_mesh_from_bytes(cr.as_bytes(), Format::Obj).unwrap(),
        "cr",
    );
}

/// What the OBJ reader keeps that a reader renumbering vertices by first use (tobj) would not:
/// vertices in file order whatever order the faces use them in, a vertex no face uses, and a
/// comment after a record (docs/dependencies.md, issue 30).
#[test]
fn obj_keeps_file_vertex_order_and_trailing_comments() {
    let text = "v 0 0 0 # origin\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 3 4 1 # first face\nf 3 1 2\n";
    let mesh = read_mesh_from_bytes(text.as_bytes(), Format::Obj).unwrap();
    let mut expected = unit_square().vertices;
    expected.push([5.0, 5.0, 5.0]);
    assert_eq!(mesh.vertices, expected);
    assert_eq!(mesh.faces, vec![[2, 3, 0], [2, 0, 1]]);
}

/// ASCII PLY values are whitespace-separated tokens: an element may span lines, or share one.
#[test]
fn ply_ascii_values_may_span_lines() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n\
                property double z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n\
                0 0\n0\n1 0 0 1 1 0\n0 1 0\n3 0 1 2 3\n0 2 3\n";
    assert_same(&unit_square(), &read_mesh_from_bytes(text.as_bytes(), Format::Ply).unwrap(), "ascii ply layout");
}

#[test]
fn off_variants() {
    let variants = [
        "OFF\n# comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
        "OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
        "# leading comment\n\nCOFF\n4 1 4\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 1 1 1 255\n4 0 1 2 3 255 0 0\n",
        "4 1\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
        "NOFF\r\n4 2 0\r\n0 0 0 0 0 1\r\n1 0 0 0 0 1\r\n1 1 0 0 0 1\r\n0 1 0 0 0 1\r\n3 0 1 2\r\n3 0 2 3\r\n",
    ];
    for v in variants {
        assert_same(
            &unit_square(),
            &read_mesh_from_bytes(v.as_bytes(), Format::Off).unwrap(),
            v,
        );
    }
}

#[test]
fn ply_ascii_with_extra_elements_and_lists() {
    let text = "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info x\r\nelement material 1\r\n\
                property list uchar float weights\r\nproperty uchar id\r\n\
                element vertex 4\r\nproperty int confidence\r\nproperty float x\r\nproperty list uint8 int32 tags\r\n\
                property double y\r\nproperty short z\r\nproperty uchar red\r\n\
                element face 1\r\nproperty uchar flags\r\nproperty list uchar uint vertex_indices\r\nproperty float quality\r\n\
                element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n\
                3 0.5 0.25 1 7\n\
                9 0 2 5 6 0 0 255\n9 1 0 0 0 255\n9 1 1 1 1.0 0 255\n9 0 3 1 2 3 1 0 255\n\
                0 4 0 1 2 3 0.5\n0 1\n";
    assert_same(
        &unit_square(),
        &read_mesh_from_bytes(text.as_bytes(), Format::Ply).unwrap(),
        "ascii ply",
    );
}

/// Binary PLY with every scalar type, big or little endian.
fn binary_ply(big: bool) -> Vec<u8> {
    let order = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut out = format!(
        "ply\nformat {order} 1.0\nelement vertex 4\nproperty char a\nproperty float x\nproperty list ushort short l\n\
         property double y\nproperty int z\nproperty uint b\nproperty ushort c\n\
         element face 1\nproperty list uint ushort vertex_index\nproperty uchar d\nend_header\n"
    )
    .into_bytes();
    fn put<const N: usize>(out: &mut Vec<u8>, le: [u8; N], big: bool) {
        let mut b = le;
        if big {
            b.reverse();
        }
        out.extend_from_slice(&b);
    }
    for p in [[0i32, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]] {
        put(&mut out, (-5i8).to_le_bytes(), big);
        put(&mut out, (p[0] as f32).to_le_bytes(), big);
        put(&mut out, 2u16.to_le_bytes(), big);
        put(&mut out, (-1i16).to_le_bytes(), big);
        put(&mut out, 7i16.to_le_bytes(), big);
        put(&mut out, (p[1] as f64).to_le_bytes(), big);
        put(&mut out, p[2].to_le_bytes(), big);
        put(&mut out, 99u32.to_le_bytes(), big);
        put(&mut out, 3u16.to_le_bytes(), big);
    }
    put(&mut out, 4u32.to_le_bytes(), big);
    for i in 0..4u16 {
        put(&mut out, i.to_le_bytes(), big);
    }
    out.push(1);
    out
}

#[test]
fn ply_binary_both_byte_orders_and_all_types() {
    for big in [false, true] {
        let mesh = read_mesh_from_bytes(&binary_ply(big), Format::Ply).unwrap();
        assert_same(
            &unit_square(),
            &mesh,
            if big { "big endian" } else { "little endian" },
        );
    }
}

#[test]
fn stl_ascii_and_binary_starting_with_solid() {
    let ascii = "solid square\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n\
                 vertex 1 1 0\n    endloop\n  endfacet\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n\
                 vertex 1 1 0\n      vertex 0 1 0\n    endloop\n  endfacet\nendsolid square\n";
    assert_same(
        &unit_square(),
        &read_mesh_from_bytes(ascii.as_bytes(), Format::Stl).unwrap(),
        "ascii stl",
    );

    let mut binary = write_mesh_to_bytes(&unit_square(), Format::Stl).unwrap();
    binary[..5].copy_from_slice(b"solid");
    assert_same(
        &unit_square(),
        &read_mesh_from_bytes(&binary, Format::Stl).unwrap(),
        "binary stl 'solid'",
    );
}

#[test]
fn same_file_detects_links_and_paths() {
    let dir = TempDir::new("same");
    let a = dir.path("a.obj");
    write_mesh(&a, &unit_square()).unwrap();
    let b = dir.path("b.obj");
    write_mesh(&b, &unit_square()).unwrap();
    assert!(same_file(&a, &a));
    assert!(same_file(&a, &dir.join(".").join("a.obj")));
    assert!(!same_file(&a, &b));
    assert!(!same_file(&a, &dir.path("missing.obj")));
    #[cfg(unix)]
    {
        let link = dir.path("link.obj");
        std::os::unix::fs::symlink(&a, &link).unwrap();
        assert!(same_file(&a, &link));
        let hard = dir.path("hard.obj");
        std::fs::hard_link(&a, &hard).unwrap();
        assert!(same_file(&hard, &a));
    }
}

#[test]
fn large_obj_round_trips() {
    // 81920 faces, about 4 MB: every vertex and face comes back exactly (no time limit: the
    // speed of the reader is the benchmarks' business, not a test's).
    let mesh = icosphere(6);
    let dir = TempDir::new("large");
    let path = dir.path("large.obj");
    write_mesh(&path, &mesh).unwrap();
    let back = read_mesh(&path).unwrap();
    assert_same(&mesh, &back, "large obj");
}

#[test]
fn gzip_bytes_read_like_the_file_and_garbage_is_an_error() {
    use std::io::Write;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/closed_bunny_npm.obj.gz");
    let from_file = capmesh::io::read_mesh(&path).unwrap();
    let from_bytes = capmesh::io::read_mesh_from_gzip_bytes(&std::fs::read(&path).unwrap(), capmesh::io::Format::Obj).unwrap();
    assert_eq!(from_file.vertices, from_bytes.vertices);
    assert_eq!(from_file.faces, from_bytes.faces);
    let err = capmesh::io::read_mesh_from_gzip_bytes(b"not gzip at all", capmesh::io::Format::Obj).unwrap_err();
    assert!(err.to_string().contains("<bytes>.gz"), "{err}");
    // A valid gzip stream of an empty file.
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(b"").unwrap();
    let empty = enc.finish().unwrap();
    let err = capmesh::io::read_mesh_from_gzip_bytes(&empty, capmesh::io::Format::Obj).unwrap_err();
    assert!(matches!(err, capmesh::io::ReadError::Empty { .. }), "{err}");
}
