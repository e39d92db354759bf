//! `remesh --attribute PATH|NAME`: the per-vertex data files read against the input (or the
//! PLY input's vertex properties named), and where
//! their values carried to the remesh go (PLY vertex properties, or GIFTI data files beside a
//! GIFTI output). The carrying is [`capmesh::carry_attribute`].

use crate::failure::Failure;
use capmesh::io::atomic::StagedFile;
use capmesh::io::{Format, VertexAttribute, VertexProperties};
use capmesh::{AttributeData, TriMesh};
use std::path::{Path, PathBuf};

/// Read every `--attribute` against the input mesh, in the order given: a path of an existing
/// file is a per-vertex data file; otherwise, for a PLY input, the name of one of its vertex
/// properties (`quality`, `red`, ...). Refuse an output format that cannot hold them before
/// any work is done.
pub fn read_all(paths: &[PathBuf], input_path: &Path, input: &TriMesh, output: &Path) -> Result<Vec<VertexAttribute>, Failure> {
    if paths.is_empty() {
        return Ok(Vec::new());
    }
    if !matches!(Format::from_path(output), Some(Format::Ply | Format::Gifti)) {
        return Err(format!("--attribute needs a .ply output (vertex properties) or a .gii output (data files beside it), not {}", output.display()).into());
    }
    let input_is_ply = Format::from_path(input_path) == Some(Format::Ply);
    let names: Vec<&str> = paths.iter().filter(|p| !p.is_file()).filter_map(|p| p.to_str()).collect();
    if let Some(p) = paths.iter().find(|p| !p.is_file() && (!input_is_ply || p.to_str().is_none())) {
        return Err(format!(
            "--attribute {}: there is no such file, and only a PLY input's vertex properties can be named \
             ({} is not PLY); pass a per-vertex data file (.gii, FreeSurfer curv)",
            p.display(),
            input_path.display()
        )
        .into());
    }
    let mut from_ply = if names.is_empty() {
        Vec::new()
    } else {
        let (mesh, attributes) = capmesh::io::read_ply_with_vertex_attributes(input_path, &names).map_err(|e| format!("--attribute: {e}"))?;
        if mesh.n_vertices() != input.n_vertices() {
            return Err(format!("{}: read {} vertices with the properties, {} without (a bug)", input_path.display(), mesh.n_vertices(), input.n_vertices()).into());
        }
        attributes
    }
    .into_iter();
    let mut all = Vec::new();
    for p in paths {
        if p.is_file() {
            all.extend(capmesh::io::read_vertex_attributes_for(p, input).map_err(|e| e.to_string())?);
        } else {
            all.extend(from_ply.next());
        }
    }
    Ok(all)
}

/// A name usable as a PLY property and in a file name: letters, digits and `_`.
fn clean(name: &str, index: usize) -> String {
    let s: String = name.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
    let s = s.trim_matches('_').to_string();
    if s.is_empty() || s.chars().next().is_some_and(|c| c.is_ascii_digit()) {
        format!("attribute{index}_{s}")
    } else {
        s
    }
}

/// The carried attributes as PLY vertex properties (labels as their float value).
pub fn ply_properties(carried: &[VertexAttribute]) -> VertexProperties {
    let mut extra = VertexProperties::default();
    let mut used: Vec<String> = Vec::new();
    for (i, a) in carried.iter().enumerate() {
        let mut name = clean(&a.name, i);
        if used.contains(&name) || ["x", "y", "z", "texture_u", "texture_v"].contains(&name.as_str()) {
            name = format!("{name}_{i}");
        }
        used.push(name.clone());
        let values = match &a.data {
            AttributeData::Scalar(v) => v.clone(),
            AttributeData::Label(v) => v.iter().map(|&x| x as f32).collect(),
        };
        extra = extra.with_scalar(name, values);
    }
    extra
}

/// The GIFTI data files beside `output` (`brain.surf.gii` -> `brain.NAME.shape.gii` or
/// `.label.gii`), staged.
pub fn stage_gifti(output: &Path, carried: &[VertexAttribute]) -> Result<Vec<(PathBuf, StagedFile)>, Failure> {
    let file = output.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let lower = file.to_ascii_lowercase();
    let mut stem = &file[..];
    for suffix in [".gz", ".gii", ".surf"] {
        if lower[..stem.len()].ends_with(suffix) {
            stem = &stem[..stem.len() - suffix.len()];
        }
    }
    let mut staged = Vec::new();
    for (i, a) in carried.iter().enumerate() {
        let kind = if matches!(a.data, AttributeData::Label(_)) { "label" } else { "shape" };
        let path = output.with_file_name(format!("{stem}.{}.{kind}.gii", clean(&a.name, i)));
        if staged.iter().any(|(p, _): &(PathBuf, StagedFile)| *p == path) {
            return Err(format!("two attributes would both be written to {}; give them different names", path.display()).into());
        }
        let file = capmesh::io::stage_vertex_attribute(&path, a, &Default::default())?;
        staged.push((path, file));
    }
    Ok(staged)
}
