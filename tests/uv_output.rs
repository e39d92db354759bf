//! The map as texture coordinates: `CapMap::uv` written with the input mesh (OBJ `vt`, PLY
//! `texture_u`/`texture_v`, ASCII and binary) reads back to the same values, and
//! `capmesh param --uv` on a closed surface writes the disk of radius r* scaled into [0,1]^2.

mod common;

use capmesh::io::{write_mesh_with_properties, VertexProperties, WriteOptions};
use capmesh::{parameterize, read_mesh, NoProgress, ParamOptions};
use common::{data, TempDir};
use std::process::Command;

/// The `vt` lines of an OBJ file.
fn obj_uv(text: &str) -> Vec<[f64; 2]> {
    text.lines()
        .filter_map(|l| l.strip_prefix("vt "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1]]
        })
        .collect()
}

/// The `texture_u`, `texture_v` of a PLY file written by capmesh (x, y, z double, then the
/// two floats), ASCII or binary little endian.
fn ply_uv(bytes: &[u8]) -> Vec<[f64; 2]> {
    let end = bytes.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let header = std::str::from_utf8(&bytes[..end]).unwrap();
    assert!(header.contains("property float texture_u\nproperty float texture_v\n"), "{header}");
    let n: usize = header.lines().find_map(|l| l.strip_prefix("element vertex ")).unwrap().parse().unwrap();
    if header.contains("format ascii") {
        let body = std::str::from_utf8(&bytes[end..]).unwrap();
        body.lines()
            .take(n)
            .map(|l| {
                let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
                assert_eq!(v.len(), 5, "{l}");
                [v[3], v[4]]
            })
            .collect()
    } else {
        (0..n)
            .map(|i| {
                let r = &bytes[end + 32 * i..end + 32 * (i + 1)];
                let f = |o: usize| f32::from_le_bytes(r[o..o + 4].try_into().unwrap()) as f64;
                [f(24), f(28)]
            })
            .collect()
    }
}

#[test]
fn uv_round_trips_through_obj_and_ply() {
    let mesh = read_mesh(&data("open_meg_helmet_babysquid_mne.obj")).unwrap();
    let map = parameterize(&mesh, &ParamOptions::default(), &NoProgress).unwrap();
    let uv = map.uv();
    assert_eq!(uv.len(), mesh.n_vertices());
    assert!(uv.iter().flatten().all(|&t| (0.0..=1.0).contains(&t)));
    let extra = VertexProperties::default().with_uv(uv.clone());
    let dir = TempDir::new("uv");
    let obj = dir.path("helmet.obj");
    write_mesh_with_properties(&obj, &mesh, &extra, &WriteOptions::default()).unwrap();
    assert_eq!(obj_uv(&std::fs::read_to_string(&obj).unwrap()), uv, "OBJ vt differ");
    let back = read_mesh(&obj).unwrap();
    assert_eq!(back.faces, mesh.faces, "f v/vt faces read back differently");
    for ascii in [true, false] {
        let ply = dir.path(if ascii { "a.ply" } else { "b.ply" });
        write_mesh_with_properties(&ply, &mesh, &extra, &WriteOptions::default().with_ply_ascii(ascii)).unwrap();
        let got = ply_uv(&std::fs::read(&ply).unwrap());
        assert_eq!(got.len(), uv.len());
        for (g, w) in got.iter().zip(&uv) {
            assert!((g[0] - w[0]).abs() < 1e-7 && (g[1] - w[1]).abs() < 1e-7, "PLY (ascii {ascii}) {g:?} vs {w:?}");
        }
        let back = read_mesh(&ply).unwrap();
        assert_eq!((back.vertices.clone(), back.faces.clone()), (mesh.vertices.clone(), mesh.faces.clone()), "PLY mesh changed by the extra properties");
    }
    // Formats without texture coordinates refuse them, naming the file.
    let err = write_mesh_with_properties(&dir.path("x.stl"), &mesh, &extra, &WriteOptions::default()).unwrap_err().to_string();
    assert!(err.contains("x.stl") && err.contains("texture"), "{err}");
}

#[test]
fn param_uv_of_a_closed_surface() {
    let dir = TempDir::new("uv-cli");
    let (cap, uv, report) = (dir.path("cap.obj"), dir.path("uv.obj"), dir.path("r.json"));
    let input = data("closed_bunny_npm.obj");
    let status = Command::new(env!("CARGO_BIN_EXE_capmesh"))
        .args(["--quiet", "param"])
        .arg(&input)
        .arg("-o")
        .arg(&cap)
        .arg("--uv")
        .arg(&uv)
        .arg("--report")
        .arg(&report)
        .status()
        .unwrap();
    assert!(status.success());
    let r: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let r_star = r["r_star"].as_f64().unwrap();
    let cap_mesh = read_mesh(&cap).unwrap();
    let text = std::fs::read_to_string(&uv).unwrap();
    let got = obj_uv(&text);
    let input_mesh = read_mesh(&input).unwrap();
    let written = read_mesh(&uv).unwrap();
    assert_eq!(written.vertices, input_mesh.vertices, "--uv writes the input's positions");
    assert_eq!(got.len(), cap_mesh.n_vertices());
    let mut on_rim = 0;
    for (t, x) in got.iter().zip(&cap_mesh.vertices) {
        // The cap point's stereographic image, scaled by 1 / (2 r*) about (0.5, 0.5).
        let q = [x[0] / (1.0 + x[2]), x[1] / (1.0 + x[2])];
        let want = [0.5 + q[0] / (2.0 * r_star), 0.5 + q[1] / (2.0 * r_star)];
        assert!((t[0] - want[0]).abs() < 1e-9 && (t[1] - want[1]).abs() < 1e-9, "{t:?} vs {want:?}");
        assert!((0.0..=1.0).contains(&t[0]) && (0.0..=1.0).contains(&t[1]));
        if ((t[0] - 0.5).hypot(t[1] - 0.5) - 0.5).abs() < 1e-9 {
            on_rim += 1;
        }
    }
    // The punctured quad's corners sit on the disk's rim, every other vertex inside it.
    assert!((3..=4).contains(&on_rim), "{on_rim} vertices on the rim");
}
