//! OBJ and PLY reading: capmesh's readers against `tobj` and `ply-rs-bw` (typed elements), on
//! the same bytes, in one run.
//!
//! `cargo run --release --bin readers -- MESH` writes MESH as OBJ, binary PLY (both byte
//! orders) and ASCII PLY with capmesh's writers, then prints read times (best of 5, from
//! memory), whether both give the same mesh (vertices in file order, same faces), the crate's
//! PLY writer against capmesh's (time, same bytes), and the errors both give on broken files.

use std::io::Cursor;
use std::path::PathBuf;
use std::time::Instant;

use capmesh::io::{read_mesh_from_bytes, write_mesh_to_bytes, write_mesh_to_bytes_with, Format, WriteOptions};

/// ply-rs-bw's typed reading and writing, for one version of the crate (`$key`: the type
/// its `PropertyAccess` methods take the property name as).
macro_rules! ply_rs_bw {
    ($m:ident, $krate:ident, $key:ty) => {
        mod $m {
            use std::io::{BufReader, Cursor};

            use $krate::parser::Parser;
            use $krate::ply::{Addable, ElementDef, Encoding, Header, Property, PropertyAccess, PropertyDef, PropertyType, ScalarType};
            use $krate::writer::Writer;

            /// A typed vertex: what ply-rs-bw's `PropertyAccess` hands over, kept as `f64`.
            struct Vertex([f64; 3]);

            impl PropertyAccess for Vertex {
                fn new() -> Self {
                    Vertex([0.0; 3])
                }
                fn get_double(&self, name: &$key) -> Option<f64> {
                    match &name[..] {
                        "x" => Some(self.0[0]),
                        "y" => Some(self.0[1]),
                        "z" => Some(self.0[2]),
                        _ => None,
                    }
                }
                fn set_property(&mut self, name: &$key, property: Property) {
                    let k = match &name[..] {
                        "x" => 0,
                        "y" => 1,
                        "z" => 2,
                        _ => return,
                    };
                    self.0[k] = match property {
                        Property::Float(x) => f64::from(x),
                        Property::Double(x) => x,
                        _ => f64::NAN,
                    };
                }
            }

            /// A typed face: the `vertex_indices` list.
            struct Face(Vec<i64>);

            impl PropertyAccess for Face {
                fn new() -> Self {
                    Face(Vec::new())
                }
                fn set_property(&mut self, name: &$key, property: Property) {
                    if &name[..] != "vertex_indices" && &name[..] != "vertex_index" {
                        return;
                    }
                    self.0 = match property {
                        Property::ListInt(v) => v.into_iter().map(i64::from).collect(),
                        Property::ListUInt(v) => v.into_iter().map(i64::from).collect(),
                        _ => Vec::new(),
                    };
                }
            }

            /// A face to write: its three indices as `int`.
            struct WriteFace([i32; 3]);

            impl PropertyAccess for WriteFace {
                fn new() -> Self {
                    WriteFace([0; 3])
                }
                fn get_list_int(&self, _name: &$key) -> Option<&[i32]> {
                    Some(&self.0)
                }
            }

            /// The crate's writing of capmesh's PLY layout (`double` x y z, `uchar int` index lists).
            pub fn write(mesh: &capmesh::TriMesh, ascii: bool) -> Vec<u8> {
                let mut header = Header::new();
                header.encoding = if ascii { Encoding::Ascii } else { Encoding::BinaryLittleEndian };
                header.comments.push("written by capmesh".into());
                let mut vertex = ElementDef::new("vertex".into());
                vertex.count = mesh.vertices.len();
                for axis in ["x", "y", "z"] {
                    vertex.properties.add(PropertyDef::new(axis.into(), PropertyType::Scalar(ScalarType::Double)));
                }
                let mut face = ElementDef::new("face".into());
                face.count = mesh.faces.len();
                face.properties.add(PropertyDef::new("vertex_indices".into(), PropertyType::List(ScalarType::UChar, ScalarType::Int)));
                header.elements.add(vertex.clone());
                header.elements.add(face.clone());
                let mut out = Vec::new();
                let vw = Writer::<Vertex>::new();
                let fw = Writer::<WriteFace>::new();
                vw.write_header(&mut out, &header).unwrap();
                for p in &mesh.vertices {
                    let v = Vertex(*p);
                    match ascii {
                        true => vw.write_ascii_element(&mut out, &v, &vertex),
                        false => vw.write_little_endian_element(&mut out, &v, &vertex),
                    }
                    .unwrap();
                }
                for f in &mesh.faces {
                    let f = WriteFace(f.map(|i| i as i32));
                    match ascii {
                        true => fw.write_ascii_element(&mut out, &f, &face),
                        false => fw.write_little_endian_element(&mut out, &f, &face),
                    }
                    .unwrap();
                }
                out
            }

            /// The crate's reading of a PLY: header, then each element with its typed parser.
            pub fn read(bytes: &[u8]) -> Result<(Vec<[f64; 3]>, Vec<[u32; 3]>), String> {
                let mut reader = BufReader::new(Cursor::new(bytes));
                let vp = Parser::<Vertex>::new();
                let fp = Parser::<Face>::new();
                let header = vp.read_header(&mut reader).map_err(|e| e.to_string())?;
                let mut vertices = Vec::new();
                let mut faces = Vec::new();
                for (name, def) in &header.elements {
                    match &name[..] {
                        "vertex" => {
                            vertices = vp.read_payload_for_element(&mut reader, def, &header).map_err(|e| e.to_string())?.into_iter().map(|v| v.0).collect()
                        }
                        "face" => {
                            for f in fp.read_payload_for_element(&mut reader, def, &header).map_err(|e| e.to_string())? {
                                for k in 1..f.0.len().saturating_sub(1) {
                                    faces.push([f.0[0] as u32, f.0[k] as u32, f.0[k + 1] as u32]);
                                }
                            }
                        }
                        _ => {
                            let skip = Parser::<$krate::ply::DefaultElement>::new();
                            skip.read_payload_for_element(&mut reader, def, &header).map_err(|e| e.to_string())?;
                        }
                    }
                }
                Ok((vertices, faces))
            }
        }
    };
}

ply_rs_bw!(v2, ply_rs_bw, String);
ply_rs_bw!(v3, ply_rs_bw_3, str);

/// tobj's reading of an OBJ from memory, triangulated, all models concatenated.
fn tobj_read(bytes: &[u8]) -> Result<(Vec<[f64; 3]>, Vec<[u32; 3]>), String> {
    let options = tobj::LoadOptions { triangulate: true, ignore_points: true, ignore_lines: true, ..Default::default() };
    let (models, _) = tobj::load_obj_buf(&mut Cursor::new(bytes), &options, |_| Err(tobj::LoadError::OpenFileFailed)).map_err(|e| format!("{e:?}: {e}"))?;
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for m in models {
        let base = vertices.len() as u32;
        vertices.extend(m.mesh.positions.chunks(3).map(|p| [p[0], p[1], p[2]]));
        faces.extend(m.mesh.indices.chunks(3).map(|f| [base + f[0], base + f[1], base + f[2]]));
    }
    Ok((vertices, faces))
}

fn best(f: &mut dyn FnMut()) -> f64 {
    (0..5)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// capmesh's binary little-endian PLY turned big endian (header line and every value).
fn big_endian(little: &[u8]) -> Vec<u8> {
    // capmesh writes `double x y z` and `uchar int` lists: swap each value's bytes.
    let text = String::from_utf8_lossy(&little[..little.windows(11).position(|w| w == b"end_header\n").unwrap() + 11]).into_owned();
    let n_v: usize = text.lines().find(|l| l.starts_with("element vertex")).unwrap().split(' ').nth(2).unwrap().parse().unwrap();
    let mut out = text.replace("binary_little_endian", "binary_big_endian").into_bytes();
    let mut data = &little[text.len()..];
    for _ in 0..n_v * 3 {
        out.extend(data[..8].iter().rev());
        data = &data[8..];
    }
    while !data.is_empty() {
        out.push(data[0]);
        for k in 0..3 {
            out.extend(data[1 + 4 * k..5 + 4 * k].iter().rev());
        }
        data = &data[13..];
    }
    out
}

fn main() {
    let path = PathBuf::from(std::env::args().nth(1).expect("usage: readers MESH"));
    let mesh = capmesh::io::read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
    let obj = write_mesh_to_bytes(&mesh, Format::Obj).expect("OBJ");
    let ply_le = write_mesh_to_bytes(&mesh, Format::Ply).expect("PLY");
    let ply_be = big_endian(&ply_le);
    let ply_ascii = write_mesh_to_bytes_with(&mesh, Format::Ply, &WriteOptions::default().with_ply_ascii(true)).expect("ASCII PLY");
    let name = path.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    println!("mesh `{name}`: {} vertices, {} faces; read from memory, best of 5, one thread", mesh.vertices.len(), mesh.faces.len());
    println!();
    println!("| file | bytes | capmesh (ms) | crate | crate (ms) | ratio | same mesh |");
    println!("|---|---:|---:|---|---:|---:|---|");
    type Reader = fn(&[u8]) -> Result<(Vec<[f64; 3]>, Vec<[u32; 3]>), String>;
    let v2: (&str, Reader) = ("ply-rs-bw 2.0.0 typed `PropertyAccess`", v2::read);
    let v3: (&str, Reader) = ("ply-rs-bw 3.0.3 typed `PropertyAccess`", v3::read);
    let mut cases: Vec<(&str, &Vec<u8>, Format, &str, Reader)> = vec![("OBJ", &obj, Format::Obj, "tobj 4.0.5 `load_obj_buf` (triangulate)", tobj_read)];
    for (crate_name, read) in [v2, v3] {
        cases.push(("PLY binary little endian", &ply_le, Format::Ply, crate_name, read));
        cases.push(("PLY binary big endian", &ply_be, Format::Ply, crate_name, read));
        cases.push(("PLY ASCII", &ply_ascii, Format::Ply, crate_name, read));
    }
    for (label, bytes, format, crate_name, read) in cases {
        let ours = read_mesh_from_bytes(bytes, format).expect("capmesh reads it");
        let (v, f) = read(bytes).expect("the crate reads it");
        let same_vertices = v.len() == ours.vertices.len() && v.iter().zip(&ours.vertices).all(|(a, b)| a == b);
        let same_faces = f == ours.faces;
        let moved = v.iter().zip(&ours.vertices).filter(|(a, b)| a != b).count();
        let same = match (same_vertices, same_faces) {
            (true, true) => "yes".to_string(),
            _ => format!("no: {moved} of {} vertices at another index, faces {}", ours.vertices.len(), if same_faces { "equal" } else { "differ" }),
        };
        let t_ours = best(&mut || {
            std::hint::black_box(read_mesh_from_bytes(bytes, format).unwrap());
        });
        let t_theirs = best(&mut || {
            std::hint::black_box(read(bytes).unwrap());
        });
        println!("| {label} | {} | {:.1} | {crate_name} | {:.1} | {:.2} | {same} |", bytes.len(), t_ours * 1e3, t_theirs * 1e3, t_theirs / t_ours);
    }
    println!();
    println!("Writing capmesh's PLY layout (`double` x y z, `uchar int` lists) from memory to memory, best of 5:");
    println!();
    println!("| PLY | capmesh (ms) | crate `Writer`, typed | crate (ms) | ratio | same bytes |");
    println!("|---|---:|---|---:|---:|---|");
    type Write = fn(&capmesh::TriMesh, bool) -> Vec<u8>;
    for (crate_name, write) in [("ply-rs-bw 2.0.0", v2::write as Write), ("ply-rs-bw 3.0.3", v3::write as Write)] {
        for (label, ascii, ours) in [("binary little endian", false, &ply_le), ("ASCII", true, &ply_ascii)] {
            let theirs = write(&mesh, ascii);
            let same = if &theirs == ours {
                "yes".to_string()
            } else {
                let at = ours.iter().zip(&theirs).position(|(x, y)| x != y).unwrap_or(ours.len().min(theirs.len()));
                let line = |b: &[u8]| {
                    let start = b[..at].iter().rposition(|&c| c == b'\n').map_or(0, |i| i + 1);
                    let end = b[at..].iter().position(|&c| c == b'\n').map_or(b.len(), |i| at + i);
                    String::from_utf8_lossy(&b[start..end]).into_owned()
                };
                let first = if ascii { format!(", first differing line: capmesh `{}`, crate `{}`", line(ours), line(&theirs)) } else { String::new() };
                let back = read_mesh_from_bytes(&theirs, Format::Ply).map(|m| m.vertices == mesh.vertices && m.faces == mesh.faces);
                let back = match back {
                    Ok(true) => "capmesh reads back the same mesh".to_string(),
                    Ok(false) => "capmesh reads back another mesh".to_string(),
                    Err(e) => format!("capmesh cannot read it back: `{}`", e.to_string().replace('|', "/")),
                };
                format!("no: first difference at byte {at} of {}{first}; {back}", ours.len())
            };
            let options = WriteOptions::default().with_ply_ascii(ascii);
            let t_ours = best(&mut || {
                std::hint::black_box(write_mesh_to_bytes_with(&mesh, Format::Ply, &options).unwrap());
            });
            let t_theirs = best(&mut || {
                std::hint::black_box(write(&mesh, ascii));
            });
            println!("| {label} | {:.1} | {crate_name} | {:.1} | {:.2} | {same} |", t_ours * 1e3, t_theirs * 1e3, t_theirs / t_ours);
        }
    }
    println!();
    println!("Errors on broken files:");
    println!();
    let tri_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let tri_ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let errors: Vec<(&str, Format, Vec<u8>, Reader)> = vec![
        ("OBJ, a coordinate `one`", Format::Obj, format!("{tri_obj}v one 0 0\nf 1 2 3\n").into_bytes(), tobj_read),
        ("OBJ, a face index 9 of 3 vertices", Format::Obj, format!("{tri_obj}f 1 2 9\n").into_bytes(), tobj_read),
        ("OBJ, a comment after a vertex", Format::Obj, "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".as_bytes().to_vec(), tobj_read),
        ("OBJ, faces listing vertices out of file order", Format::Obj, format!("{tri_obj}f 3 1 2\n").into_bytes(), tobj_read),
        ("OBJ, a vertex no face uses (the 4th)", Format::Obj, format!("{tri_obj}v 5 5 5\nf 1 2 3\n").into_bytes(), tobj_read),
        ("OBJ, old-Mac `\\r` line endings", Format::Obj, "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r".as_bytes().to_vec(), tobj_read),
        ("PLY ASCII, a coordinate `one`", Format::Ply, format!("{tri_ply}0 0 0\none 0 0\n0 1 0\n3 0 1 2\n").into_bytes(), v2::read),
        ("PLY ASCII, a face index 9", Format::Ply, format!("{tri_ply}0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n").into_bytes(), v2::read),
        ("PLY ASCII, a vertex's values over two lines", Format::Ply, format!("{tri_ply}0 0\n0\n1 0 0\n0 1 0\n3 0 1 2\n").into_bytes(), v2::read),
        ("PLY binary, truncated mid-face", Format::Ply, ply_le[..ply_le.len() - 6].to_vec(), v2::read),
    ];
    println!("(OBJ: tobj 4.0.5; PLY: ply-rs-bw 2.0.0, typed.)");
    println!();
    println!("| file | capmesh | crate |");
    println!("|---|---|---|");
    for (label, format, bytes, read) in errors {
        let ours = match read_mesh_from_bytes(&bytes, format) {
            Ok(m) => format!("read: {} vertices, first face {:?}", m.vertices.len(), m.faces[0]),
            Err(e) => format!("{e}"),
        };
        let theirs = match std::panic::catch_unwind(|| read(&bytes)) {
            Ok(Ok((v, f))) => format!("read: {} vertices, first face {:?}", v.len(), f.first()),
            Ok(Err(e)) => e,
            Err(_) => "panicked".into(),
        };
        let clean = |s: String| s.replace('\n', " ").replace('\t', " ").replace('|', "/");
        println!("| {label} | `{}` | `{}` |", clean(ours), clean(theirs));
    }
}
