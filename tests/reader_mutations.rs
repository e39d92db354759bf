//! Every reader survives damaged input: thousands of deterministic mutations (byte flips,
//! truncations, insertions, duplicated spans) of small valid OBJ, PLY (ASCII and binary), OFF
//! and STL (ASCII and binary) files either read or give an error; none panics, and whatever
//! reads has only in-range indices. A stable-toolchain stand-in for coverage-guided fuzzing
//! (issue 7 asks for cargo-fuzz as well).

mod common;

use common::Rng;

use capmesh::io::{read_mesh_from_bytes, write_mesh_to_bytes, Format};
use capmesh::mesh::shapes::spherical_cap;

fn mutate(bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for _ in 0..1 + rng.below(4) {
        if b.is_empty() {
            break;
        }
        let i = rng.below(b.len());
        match rng.below(6) {
            0 => b[i] ^= 1 << rng.below(8),
            1 => b.truncate(i),
            2 => b.insert(i, rng.next() as u8),
            3 => b[i] = *b"0123456789-.e \n/"[..].get(rng.below(16)).unwrap_or(&b'0'),
            4 => {
                let j = (i + 1 + rng.below(64)).min(b.len());
                let span = b[i..j].to_vec();
                b.splice(i..i, span);
            }
            _ => {
                let j = (i + 1 + rng.below(16)).min(b.len());
                b.drain(i..j);
            }
        }
    }
    b
}

fn check(format: Format, bytes: &[u8], seed: u64, rounds: usize) {
    assert!(read_mesh_from_bytes(bytes, format).is_ok(), "{format:?}: the unmutated file must read");
    let mut rng = Rng(seed);
    let (mut ok, mut err) = (0, 0);
    for round in 0..rounds {
        let m = mutate(bytes, &mut rng);
        let result = std::panic::catch_unwind(|| read_mesh_from_bytes(&m, format));
        match result {
            Ok(Ok(mesh)) => {
                ok += 1;
                let n = mesh.vertices.len();
                assert!(mesh.faces.iter().flatten().all(|&v| (v as usize) < n), "{format:?} round {round}: index out of range accepted");
            }
            Ok(Err(e)) => {
                err += 1;
                assert!(!e.to_string().is_empty());
            }
            Err(_) => panic!("{format:?} round {round}: the reader panicked on {} bytes", m.len()),
        }
    }
    eprintln!("{format:?}: {ok} read, {err} refused");
    assert!(err > 0, "{format:?}: no mutation was refused; the mutations are not reaching the parser");
}

fn sample_bytes(format: Format) -> Vec<u8> {
    write_mesh_to_bytes(&spherical_cap(0.3, 4, 12), format).unwrap()
}

#[test]
fn obj_reader_survives_mutations() {
    check(Format::Obj, &sample_bytes(Format::Obj), 1, 3000);
}

#[test]
fn off_reader_survives_mutations() {
    check(Format::Off, &sample_bytes(Format::Off), 2, 3000);
}

#[test]
fn binary_ply_reader_survives_mutations() {
    check(Format::Ply, &sample_bytes(Format::Ply), 3, 3000);
}

#[test]
fn ascii_ply_reader_survives_mutations() {
    let mesh = spherical_cap(0.3, 3, 8);
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.vertices.len(),
        mesh.faces.len()
    );
    for p in &mesh.vertices {
        text += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for f in &mesh.faces {
        text += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    check(Format::Ply, text.as_bytes(), 4, 3000);
}

#[test]
fn binary_stl_reader_survives_mutations() {
    check(Format::Stl, &sample_bytes(Format::Stl), 5, 3000);
}

#[test]
fn ascii_stl_reader_survives_mutations() {
    let mesh = spherical_cap(0.3, 3, 8);
    let mut text = String::from("solid cap\n");
    for f in &mesh.faces {
        text += "facet normal 0 0 1\nouter loop\n";
        for &v in f {
            let p = mesh.vertices[v as usize];
            text += &format!("vertex {} {} {}\n", p[0], p[1], p[2]);
        }
        text += "endloop\nendfacet\n";
    }
    text += "endsolid cap\n";
    check(Format::Stl, text.as_bytes(), 6, 3000);
}
