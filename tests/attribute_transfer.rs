//! Per-vertex data carried through the remesh by the inverse map (`remesh_located`,
//! `carry_attribute`, `capmesh remesh --attribute`): a linear function of position arrives
//! as that function of the remesh's positions, labels keep their set of values, and the CLI
//! writes PLY vertex properties and GIFTI data files beside a GIFTI output.

mod common;

use capmesh::io::read_vertex_attributes;
use capmesh::{carry_attribute, read_mesh, remesh_located, AttributeData, CapGrid, NoProgress, RemeshOptions, VertexAttribute};
use common::{data, TempDir};
use std::process::Command;

fn brain() -> std::path::PathBuf {
    data("neuro/brain12k.surf.gii")
}

#[test]
fn linear_values_and_labels_are_carried() {
    let mesh = read_mesh(&brain()).unwrap();
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 3000 });
    let (out, _, points) = remesh_located(&mesh, &options, &NoProgress).unwrap();
    assert_eq!(points.len(), out.n_vertices());
    let f = |p: [f64; 3]| 0.3 * p[0] - 1.2 * p[1] + 0.7 * p[2] + 5.0;
    let linear = VertexAttribute { name: "linear".into(), data: AttributeData::Scalar(mesh.vertices.iter().map(|&p| f(p) as f32).collect()), label_table: vec![] };
    let carried = carry_attribute(&mesh, &points, &linear);
    let AttributeData::Scalar(values) = &carried.data else { panic!("a scalar came back as labels") };
    let range = mesh.vertices.iter().map(|&p| f(p)).fold(0.0f64, |m, x| m.max(x.abs()));
    // A linear function is interpolated exactly on each face: what is left is the f32
    // rounding of the values, at each remesh vertex's surface point (the vertex itself is
    // fitted off the surface by a fraction of an edge, `Placement::Fitted`).
    let worst = points.iter().zip(values).map(|(p, &v)| (f(p.position) - f64::from(v)).abs()).fold(0.0, f64::max);
    let off = points.iter().zip(&out.vertices).map(|(p, x)| (0..3).map(|k| (p.position[k] - x[k]).powi(2)).sum::<f64>().sqrt()).fold(0.0, f64::max);
    assert!(off <= 0.05 * mesh.bounding_box_diagonal(), "a surface point {off} from its vertex");
    assert!(worst <= 1e-6 * range, "linear function carried with error {worst} (values up to {range})");
    // Labels: five regions by x; the remesh's labels are among them, all of them present.
    let (lo, hi) = mesh.vertices.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p[0]), b.max(p[0])));
    let labels: Vec<i32> = mesh.vertices.iter().map(|p| (((p[0] - lo) / (hi - lo) * 5.0) as i32).min(4) * 10 + 3).collect();
    let attr = VertexAttribute { name: "region".into(), data: AttributeData::Label(labels.clone()), label_table: vec![(3, "a".into())] };
    let carried = carry_attribute(&mesh, &points, &attr);
    let AttributeData::Label(got) = &carried.data else { panic!("labels came back as scalars") };
    let mut want: Vec<i32> = labels.clone();
    want.sort_unstable();
    want.dedup();
    let mut have = got.clone();
    have.sort_unstable();
    have.dedup();
    assert_eq!(have, want, "labels are not blended and every region survives");
    assert_eq!(carried.label_table, attr.label_table);
    // Each remesh vertex's label is one of its face's corners'.
    for (p, &l) in points.iter().zip(got) {
        assert!(mesh.faces[p.face].iter().any(|&v| labels[v as usize] == l));
    }
}

fn capmesh(args: &[&std::ffi::OsStr]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_capmesh")).arg("--quiet").args(args).output().unwrap()
}

#[test]
fn cli_writes_ply_properties_and_gifti_data_files() {
    let dir = TempDir::new("attr");
    let (curv, shape) = (data("neuro/brain12k.curv"), data("neuro/brain12k_curv.shape.gii"));
    let input_curv = &read_vertex_attributes(&curv).unwrap()[0];
    let AttributeData::Scalar(input_values) = &input_curv.data else { panic!() };
    let (lo, hi) = input_values.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let ply = dir.path("out.ply");
    let o = capmesh(&["remesh".as_ref(), brain().as_os_str(), "-o".as_ref(), ply.as_os_str(), "--faces".as_ref(), "2000".as_ref(), "--attribute".as_ref(), curv.as_os_str(), "--attribute".as_ref(), shape.as_os_str()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&ply).unwrap();
    let end = bytes.windows(10).position(|w| w == b"end_header").unwrap();
    let header = String::from_utf8_lossy(&bytes[..end]);
    assert_eq!(header.matches("property float ").count(), 2, "{header}");
    assert!(header.contains("property float brain12k_curv"), "{header}");
    let remeshed = read_mesh(&ply).unwrap();
    // GIFTI output: the data file beside it, one value per remesh vertex, within the input's range.
    let gii = dir.path("out.surf.gii");
    let o = capmesh(&["remesh".as_ref(), brain().as_os_str(), "-o".as_ref(), gii.as_os_str(), "--faces".as_ref(), "2000".as_ref(), "--attribute".as_ref(), curv.as_os_str()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let beside = dir.path("out.brain12k_curv.shape.gii");
    let back = read_vertex_attributes(&beside).unwrap_or_else(|e| panic!("{e}"));
    let AttributeData::Scalar(values) = &back[0].data else { panic!("not scalar") };
    assert_eq!(values.len(), read_mesh(&gii).unwrap().n_vertices());
    assert!(values.iter().all(|&v| v >= lo - 1e-6 && v <= hi + 1e-6), "values outside the input's range");
    assert!(values.iter().any(|&v| v != values[0]), "constant values");
    assert!(remeshed.n_vertices() > 500);
    // A format without vertex properties is refused before the work, naming the option.
    let o = capmesh(&["remesh".as_ref(), brain().as_os_str(), "-o".as_ref(), dir.path("x.stl").as_os_str(), "--attribute".as_ref(), curv.as_os_str()]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--attribute"), "{}", String::from_utf8_lossy(&o.stderr));
}
