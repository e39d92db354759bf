//! `remesh --attribute NAME` with NAME a vertex property of a PLY input (issue 31): the PLY
//! reader returns named vertex properties (floats and colour channels as scalars, other
//! integers as labels; ASCII and binary), a missing name lists the properties the file has, and
//! the CLI carries them to the remesh's PLY vertex properties (a linear function of position
//! stays that function, labels keep their set of values, colours stay in their range).

mod common;

use capmesh::io::read_ply_with_vertex_attributes;
use capmesh::{read_mesh, AttributeData, ReadError, TriMesh};
use common::{data, TempDir};
use std::path::Path;
use std::process::Command;

fn linear(p: [f64; 3]) -> f64 {
    0.3 * p[0] - 1.2 * p[1] + 0.7 * p[2] + 5.0
}

/// Per vertex: `quality` (float, a linear function of position), `red` (uchar, from x) and
/// `region` (int, five bands of x times 10 plus 3).
fn values(mesh: &TriMesh) -> (Vec<f32>, Vec<u8>, Vec<i32>) {
    let (lo, hi) = mesh.vertices.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p[0]), b.max(p[0])));
    let t = |p: &[f64; 3]| (p[0] - lo) / (hi - lo);
    let quality = mesh.vertices.iter().map(|&p| linear(p) as f32).collect();
    let red = mesh.vertices.iter().map(|p| (40.0 + 200.0 * t(p)).round() as u8).collect();
    let region = mesh.vertices.iter().map(|p| ((t(p) * 5.0) as i32).min(4) * 10 + 3).collect();
    (quality, red, region)
}

/// `mesh` as a PLY with the properties of [`values`] (ASCII or binary little endian).
fn write_ply(path: &Path, mesh: &TriMesh, binary: bool) {
    let (quality, red, region) = values(mesh);
    let mut out = format!(
        "ply\nformat {} 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         property float quality\nproperty uchar red\nproperty int region\nproperty list uchar int nothing\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        if binary { "binary_little_endian" } else { "ascii" },
        mesh.n_vertices(),
        mesh.n_faces()
    )
    .into_bytes();
    for (v, p) in mesh.vertices.iter().enumerate() {
        if binary {
            for x in p {
                out.extend_from_slice(&(*x as f32).to_le_bytes());
            }
            out.extend_from_slice(&quality[v].to_le_bytes());
            out.push(red[v]);
            out.extend_from_slice(&region[v].to_le_bytes());
            out.push(0);
        } else {
            out.extend(format!("{} {} {} {:?} {} {} 0\n", p[0] as f32, p[1] as f32, p[2] as f32, quality[v], red[v], region[v]).bytes());
        }
    }
    for f in &mesh.faces {
        if binary {
            out.push(3);
            for &i in f {
                out.extend_from_slice(&(i as i32).to_le_bytes());
            }
        } else {
            out.extend(format!("3 {} {} {}\n", f[0], f[1], f[2]).bytes());
        }
    }
    std::fs::write(path, out).unwrap();
}

fn helmet() -> TriMesh {
    read_mesh(&data("open_meg_helmet_babysquid_mne.obj.gz")).unwrap()
}

#[test]
fn named_vertex_properties_are_read_with_their_kind() {
    let mesh = helmet();
    let dir = TempDir::new("plyattr");
    let (quality, red, region) = values(&mesh);
    for binary in [false, true] {
        let path = dir.path(if binary { "binary.ply" } else { "ascii.ply" });
        write_ply(&path, &mesh, binary);
        let (read, attributes) = read_ply_with_vertex_attributes(&path, &["region", "quality", "red"]).unwrap();
        assert_eq!(read.faces, mesh.faces);
        let names: Vec<&str> = attributes.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["region", "quality", "red"]);
        assert_eq!(attributes[0].data, AttributeData::Label(region.clone()), "an int property is a label");
        assert_eq!(attributes[1].data, AttributeData::Scalar(quality.clone()), "binary {binary}");
        assert_eq!(attributes[2].data, AttributeData::Scalar(red.iter().map(|&r| f32::from(r)).collect()), "a colour channel is a scalar");
        // The input file is not modified by reading it.
        assert_eq!(read_mesh(&path).unwrap().n_vertices(), mesh.n_vertices());
    }
    // A name the file does not have: the error names the file, the property and those it has.
    let path = dir.path("ascii.ply");
    let err = read_ply_with_vertex_attributes(&path, &["thickness"]).unwrap_err();
    assert!(matches!(err, ReadError::NoPlyProperty { .. }), "{err}");
    let text = err.to_string();
    assert!(text.contains("ascii.ply") && text.contains("'thickness'") && text.contains("x, y, z, quality, red, region, nothing"), "{text}");
    // A list property and a coordinate are refused by name.
    let text = read_ply_with_vertex_attributes(&path, &["nothing"]).unwrap_err().to_string();
    assert!(text.contains("'nothing' is a list"), "{text}");
    let text = read_ply_with_vertex_attributes(&path, &["x"]).unwrap_err().to_string();
    assert!(text.contains("'x' is a coordinate"), "{text}");
    // Not a PLY file.
    let text = read_ply_with_vertex_attributes(&data("open_meg_helmet_babysquid_mne.obj.gz"), &["quality"]).unwrap_err().to_string();
    assert!(text.contains("PLY files only"), "{text}");
}

fn capmesh(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_capmesh")).arg("--quiet").args(args).output().unwrap()
}

#[test]
fn remesh_carries_ply_vertex_properties_by_name() {
    let mesh = helmet();
    let dir = TempDir::new("plyattr-cli");
    let input = dir.path("helmet.ply");
    write_ply(&input, &mesh, true);
    let before = std::fs::read(&input).unwrap();
    let output = dir.path("remeshed.ply");
    let run = capmesh(&[
        "remesh",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--faces",
        "2000",
        // On the surface: the linear function is then exact at the remesh's vertices.
        "--placement",
        "on-surface",
        "--attribute",
        "quality",
        "--attribute",
        "red",
        "--attribute",
        "region",
    ]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert_eq!(std::fs::read(&input).unwrap(), before, "the input was modified");
    let (out, attributes) = read_ply_with_vertex_attributes(&output, &["quality", "red", "region"]).unwrap();
    let scalars = |k: usize| match &attributes[k].data {
        AttributeData::Scalar(v) => v.clone(),
        AttributeData::Label(_) => panic!("the remesh writes float properties"),
    };
    // The linear function: exact on each face up to the f32 positions and values of the input.
    let quality = scalars(0);
    let range = mesh.vertices.iter().map(|&p| linear(p).abs()).fold(0.0, f64::max);
    let worst = out.vertices.iter().zip(&quality).map(|(&p, &q)| (linear(p) - f64::from(q)).abs()).fold(0.0, f64::max);
    assert!(worst <= 1e-5 * range, "quality carried with error {worst} (values up to {range})");
    // Colours stay within the input's range.
    let (_, red, region) = values(&mesh);
    let (lo, hi) = (f32::from(*red.iter().min().unwrap()), f32::from(*red.iter().max().unwrap()));
    assert!(scalars(1).iter().all(|&r| (lo..=hi).contains(&r)), "a red value outside [{lo}, {hi}]");
    // Labels: not blended, every band survives.
    let mut want: Vec<i32> = region;
    want.sort_unstable();
    want.dedup();
    let mut have: Vec<i32> = scalars(2).iter().map(|&x| x as i32).collect();
    assert!(scalars(2).iter().all(|&x| x.fract() == 0.0), "a blended label");
    have.sort_unstable();
    have.dedup();
    assert_eq!(have, want);

    // A name the input does not have fails before the work, naming the property.
    let run = capmesh(&["remesh", input.to_str().unwrap(), "-o", dir.path("x.ply").to_str().unwrap(), "--attribute", "thickness"]);
    assert!(!run.status.success());
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("'thickness'") && err.contains("quality, red, region"), "{err}");
    // A name with an input that is not PLY: says a data file is needed.
    let obj = data("open_meg_helmet_babysquid_mne.obj.gz");
    let run = capmesh(&["remesh", obj.to_str().unwrap(), "-o", dir.path("y.ply").to_str().unwrap(), "--attribute", "quality"]);
    assert!(!run.status.success());
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("--attribute quality") && err.contains("not PLY"), "{err}");
}
