//! The command line on neuroimaging surfaces: `check` reads a FreeSurfer surface that has no
//! extension, `param` writes the cap mesh of a GIFTI surface as GIFTI and as FreeSurfer, and a
//! per-vertex data file given as a mesh is refused with a message saying what it is.

mod common;

use std::io::Read;
use std::path::Path;
use std::process::Command;

use capmesh::io::read_mesh;
use common::TempDir;

fn capmesh() -> Command {
    Command::new(env!("CARGO_BIN_EXE_capmesh"))
}

fn neuro(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/neuro").join(name)
}

#[test]
fn check_reads_a_freesurfer_surface_without_extension() {
    let dir = TempDir::new("neuro-cli-check");
    let mut raw = Vec::new();
    flate2::read::GzDecoder::new(std::fs::File::open(neuro("brain12k.pial.gz")).unwrap()).read_to_end(&mut raw).unwrap();
    let input = dir.file("lh_pial_no_extension", &raw);
    let out = capmesh().args(["check", "--json"]).arg(&input).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["n_vertices"], 12502, "{json}");
    assert_eq!(json["n_faces"], 25000, "{json}");
    assert_eq!(json["kind"], "closed_sphere", "{json}");
}

#[test]
fn param_writes_gifti_and_freesurfer() {
    let dir = TempDir::new("neuro-cli-param");
    let input = neuro("brain12k.surf.gii.gz");
    let source = read_mesh(&input).unwrap();
    for name in ["lh.cap.surf.gii", "lh.cap.sphere"] {
        let output = dir.join(name);
        let out = capmesh().args(["param", "--quiet"]).arg(&input).arg("-o").arg(&output).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let cap = read_mesh(&output).unwrap();
        assert_eq!(cap.faces, source.faces, "{name}: the cap mesh keeps the connectivity");
        // On the unit sphere, to float32 precision.
        assert!(cap.vertices.iter().all(|p| ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < 1e-6), "{name}");
    }
}

#[test]
fn a_data_file_is_refused_as_a_mesh() {
    let out = capmesh().arg("check").arg(neuro("brain12k_curv.shape.gii")).output().unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("brain12k_curv.shape.gii") && stderr.contains("per-vertex values"), "{stderr}");
}
