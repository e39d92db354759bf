//! capmesh's half of the nibabel round trip (`tests/nibabel/roundtrip.py`, run by `.ci/run`):
//! reads the GIFTI and FreeSurfer files of tests/data/neuro and dumps what capmesh reads as raw
//! little-endian arrays, writes two surfaces in every GIFTI variant and as FreeSurfer, and
//! lists it all in `manifest.json` for the Python side to compare with nibabel.
//!
//! `cargo run --release --example nibabel_roundtrip -- OUT_DIR`

use std::path::{Path, PathBuf};

use capmesh::io::{
    read_mesh, read_vertex_attributes, write_mesh_with, AttributeData, Endian, GiftiEncoding, GiftiFloat, GiftiOptions,
    WriteOptions,
};
use capmesh::TriMesh;
use serde_json::{json, Value};

fn dump(path: &Path, bytes: Vec<u8>) -> String {
    std::fs::write(path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    path.display().to_string()
}

/// Vertices as f64 and faces as u32, little endian.
fn dump_mesh(out: &Path, stem: &str, mesh: &TriMesh) -> (String, String) {
    let v = mesh.vertices.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
    let f = mesh.faces.iter().flatten().flat_map(|i| i.to_le_bytes()).collect();
    (dump(&out.join(format!("{stem}.vertices.f64")), v), dump(&out.join(format!("{stem}.faces.u32")), f))
}

fn main() -> Result<(), String> {
    let out = PathBuf::from(std::env::args().nth(1).ok_or("usage: nibabel_roundtrip OUT_DIR")?);
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let neuro = data.join("neuro");
    let mut entries: Vec<Value> = Vec::new();

    // 1. What capmesh reads from the real files.
    for name in ["brain12k.surf.gii.gz", "brain12k.pial.gz", "nibabel_ascii.gii"] {
        let file = neuro.join(name);
        let mesh = read_mesh(&file).map_err(|e| e.to_string())?;
        let (vertices, faces) = dump_mesh(&out, name, &mesh);
        entries.push(json!({"kind": "read_surface", "file": file, "vertices": vertices, "faces": faces}));
    }
    for name in [
        "brain12k_curv.shape.gii",
        "brain12k.curv",
        "nibabel_rh.aparc.annot.gii",
        "nibabel_task.func.gii",
    ] {
        let file = neuro.join(name);
        let attributes = read_vertex_attributes(&file).map_err(|e| e.to_string())?;
        let arrays: Vec<Value> = attributes
            .iter()
            .enumerate()
            .map(|(k, a)| {
                let (kind, bytes) = match &a.data {
                    AttributeData::Scalar(v) => ("f32", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
                    AttributeData::Label(v) => ("i32", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
                };
                json!({"type": kind, "path": dump(&out.join(format!("{name}.{k}.{kind}")), bytes)})
            })
            .collect();
        entries.push(json!({"kind": "read_attributes", "file": file, "arrays": arrays}));
    }

    // 2. What capmesh writes, for nibabel to read: a float32-exact surface and one with f64
    // coordinates.
    let sources = [
        ("brain12k", read_mesh(&neuro.join("brain12k.surf.gii.gz")).map_err(|e| e.to_string())?),
        ("bunny", read_mesh(&data.join("closed_bunny_npm.obj.gz")).map_err(|e| e.to_string())?),
    ];
    for (stem, mesh) in &sources {
        let (vertices, faces) = dump_mesh(&out, &format!("{stem}.source"), mesh);
        for encoding in [GiftiEncoding::Ascii, GiftiEncoding::Base64Binary, GiftiEncoding::GzipBase64Binary] {
            for coordinates in [GiftiFloat::Float32, GiftiFloat::Float64] {
                for endian in [Endian::Little, Endian::Big] {
                    let gifti = GiftiOptions::default().with_encoding(encoding).with_coordinates(coordinates).with_endian(endian);
                    let file = out.join(format!("{stem}_{encoding:?}_{coordinates:?}_{endian:?}.surf.gii"));
                    write_mesh_with(&file, mesh, &WriteOptions::default().with_gifti(gifti)).map_err(|e| e.to_string())?;
                    entries.push(json!({"kind": "written_gifti", "file": file, "vertices": vertices, "faces": faces,
                                        "float32": coordinates == GiftiFloat::Float32}));
                }
            }
        }
        let file = out.join(format!("{stem}.pial"));
        write_mesh_with(&file, mesh, &WriteOptions::default()).map_err(|e| e.to_string())?;
        entries.push(json!({"kind": "written_freesurfer", "file": file, "vertices": vertices, "faces": faces, "float32": true}));
    }
    let manifest = out.join("manifest.json");
    std::fs::write(&manifest, serde_json::to_string_pretty(&entries).map_err(|e| e.to_string())?)
        .map_err(|e| format!("{}: {e}", manifest.display()))?;
    println!("{} entries in {}", entries.len(), manifest.display());
    Ok(())
}
