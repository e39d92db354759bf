//! STL reading: capmesh's reader against stl_io's `read_stl`, on the same bytes, in one run.
//!
//! `cargo run --release --bin stl -- MESH` writes MESH as binary STL (capmesh's writer) and as
//! ASCII STL (here), then prints read times (best of 5) and the errors both give on broken files.

use std::io::Cursor;
use std::path::PathBuf;
use std::time::Instant;

use capmesh::io::{read_mesh_from_bytes, write_mesh_to_bytes, Format};

fn ascii(mesh: &capmesh::TriMesh) -> Vec<u8> {
    let mut s = String::from("solid eval\n");
    for f in &mesh.faces {
        s.push_str("  facet normal 0 0 0\n    outer loop\n");
        for &v in f {
            let p = mesh.vertices[v as usize];
            s.push_str(&format!("      vertex {:e} {:e} {:e}\n", p[0] as f32, p[1] as f32, p[2] as f32));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid eval\n");
    s.into_bytes()
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

fn main() {
    let path = PathBuf::from(std::env::args().nth(1).expect("usage: stl MESH"));
    let mesh = capmesh::io::read_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
    let binary = write_mesh_to_bytes(&mesh, Format::Stl).expect("binary STL");
    let text = ascii(&mesh);
    let name = path.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    println!("mesh `{name}`: {} vertices, {} faces; read from memory, best of 5, one thread", mesh.vertices.len(), mesh.faces.len());
    println!();
    println!("| STL | bytes | capmesh (ms) | stl_io 0.8 `read_stl` (ms) | ratio | same vertices and faces |");
    println!("|---|---:|---:|---:|---:|---|");
    for (label, bytes) in [("binary", &binary), ("ASCII", &text)] {
        let ours = read_mesh_from_bytes(bytes, Format::Stl).expect("capmesh reads it");
        let theirs = stl_io::read_stl(&mut Cursor::new(bytes)).expect("stl_io reads it");
        let same = ours.vertices.len() == theirs.vertices.len()
            && ours.faces.len() == theirs.faces.len()
            && ours.faces.iter().zip(&theirs.faces).all(|(a, b)| a.map(|v| v as usize) == b.vertices)
            && ours.vertices.iter().zip(&theirs.vertices).all(|(a, b)| (0..3).all(|i| a[i] as f32 == b[i]));
        let t_ours = best(&mut || {
            std::hint::black_box(read_mesh_from_bytes(bytes, Format::Stl).unwrap());
        });
        let t_theirs = best(&mut || {
            std::hint::black_box(stl_io::read_stl(&mut Cursor::new(bytes)).unwrap());
        });
        println!("| {label} | {} | {:.1} | {:.1} | {:.2} | {} |", bytes.len(), t_ours * 1e3, t_theirs * 1e3, t_theirs / t_ours,
            if same { "yes".to_string() } else { format!("no: capmesh {}/{}, stl_io {}/{}", ours.vertices.len(), ours.faces.len(), theirs.vertices.len(), theirs.faces.len()) });
    }
    println!();
    println!("Errors on broken files:");
    println!();
    let tri = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("ASCII, a coordinate `one`", format!("{tri}facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex one 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n").into_bytes()),
        ("ASCII, a facet with two vertices", format!("{tri}facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n").into_bytes()),
        ("binary, truncated mid-facet", binary[..binary.len() - 20].to_vec()),
        ("binary, a NaN coordinate", {
            let mut b = binary.clone();
            b[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
            b
        }),
    ];
    println!("| file | capmesh | stl_io |");
    println!("|---|---|---|");
    for (label, bytes) in cases {
        let ours = match read_mesh_from_bytes(&bytes, Format::Stl) {
            Ok(m) => format!("read ({} faces)", m.faces.len()),
            Err(e) => format!("`{e}`"),
        };
        let theirs = match std::panic::catch_unwind(|| stl_io::read_stl(&mut Cursor::new(&bytes))) {
            Ok(Ok(m)) => format!("read ({} faces)", m.faces.len()),
            Ok(Err(e)) => format!("`{e}`"),
            Err(_) => "panic".to_string(),
        };
        println!("| {label} | {} | {} |", ours.replace('\n', " ").replace('|', "\\|"), theirs.replace('\n', " ").replace('|', "\\|"));
    }
}
