//! Per-vertex data written with a mesh: texture coordinates (the map as a UV layout, `capmesh
//! param --uv`) and named float values (attributes carried through the remesh). OBJ stores
//! texture coordinates (`vt`); PLY stores both as `float` vertex properties
//! (`texture_u`/`texture_v`, then one property per named value); other formats store neither.

use std::path::Path;

use super::error::WriteError;
use super::Format;
use crate::mesh::TriMesh;

/// Per-vertex data to write with a mesh. Default: none.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VertexProperties {
    /// Texture coordinates, one per vertex.
    pub uv: Option<Vec<[f64; 2]>>,
    /// Named values, one per vertex each (PLY only). Names are PLY property names: letters,
    /// digits and `_`, not `x`, `y`, `z`, `texture_u` or `texture_v`.
    pub scalars: Vec<(String, Vec<f32>)>,
}

impl VertexProperties {
    /// Set [`VertexProperties::uv`].
    pub fn with_uv(mut self, uv: Vec<[f64; 2]>) -> Self {
        self.uv = Some(uv);
        self
    }

    /// Add a named value per vertex.
    pub fn with_scalar(mut self, name: impl Into<String>, values: Vec<f32>) -> Self {
        self.scalars.push((name.into(), values));
        self
    }

    /// `true` when there is nothing to write.
    pub fn is_empty(&self) -> bool {
        self.uv.is_none() && self.scalars.is_empty()
    }

    /// Refuse data the file would lose or misrepresent.
    pub(crate) fn check(&self, path: &Path, mesh: &TriMesh, format: Format) -> Result<(), WriteError> {
        let unsupported = |message: String| WriteError::Unsupported { path: path.to_path_buf(), message };
        let n = mesh.n_vertices();
        if let Some(uv) = &self.uv {
            if !matches!(format, Format::Obj | Format::Ply) {
                return Err(unsupported(format!("{format} stores no texture coordinates; write .obj or .ply")));
            }
            if uv.len() != n {
                return Err(unsupported(format!("{} texture coordinates for {n} vertices (a bug in the caller)", uv.len())));
            }
            if let Some(v) = uv.iter().position(|t| !(t[0].is_finite() && t[1].is_finite())) {
                return Err(unsupported(format!("the texture coordinates of vertex {v} are not finite numbers")));
            }
        }
        let mut seen: Vec<&str> = vec!["x", "y", "z", "texture_u", "texture_v"];
        for (name, values) in &self.scalars {
            if format != Format::Ply {
                return Err(unsupported(format!("{format} stores no per-vertex values such as '{name}'; write .ply, or a GIFTI surface with its data files")));
            }
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') || seen.contains(&name.as_str()) {
                return Err(unsupported(format!("'{name}' is not a usable PLY property name (letters, digits and _, not a coordinate's and not twice)")));
            }
            seen.push(name);
            if values.len() != n {
                return Err(unsupported(format!("'{name}' has {} values for {n} vertices", values.len())));
            }
        }
        Ok(())
    }
}
