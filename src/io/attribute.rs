//! Per-vertex data of a surface, read from their own files: GIFTI data files (`.shape.gii`,
//! `.func.gii`, `.label.gii`, any `.gii` array that is not the surface's) and FreeSurfer
//! curvature-format files (`lh.thickness`, `lh.curv`, `lh.sulc`, ...). They are what the
//! inverse map carries from the input surface to the remeshed one.
//!
//! The format comes from the extension (`.gii`, optionally `.gz`) or else from the content
//! (XML, or the curvature magic bytes). Values are kept as the file stores them: scalars as
//! `f32` (GIFTI `FLOAT64` arrays are rounded), labels as `i32`; NaN is allowed (some data mark
//! the medial wall with it). [`read_vertex_attributes_for`] also checks the count against the
//! mesh.

use std::path::Path;

use super::error::ReadError;
use super::{freesurfer, gifti, load};
use crate::mesh::TriMesh;

/// The values of one attribute, one per vertex.
#[derive(Debug, Clone, PartialEq)]
pub enum AttributeData {
    /// Continuous values (thickness, curvature, a time point, ...).
    Scalar(Vec<f32>),
    /// Integer labels (a parcellation); see [`VertexAttribute::label_table`].
    Label(Vec<i32>),
}

impl AttributeData {
    /// Number of values.
    pub fn len(&self) -> usize {
        match self {
            AttributeData::Scalar(v) => v.len(),
            AttributeData::Label(v) => v.len(),
        }
    }

    /// `true` when there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One per-vertex attribute.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexAttribute {
    /// The array's `Name` metadata in GIFTI (else its intent and index, e.g. `shape 0`; a
    /// column `c` of a 2-D array gets `[c]` appended), the file name for FreeSurfer.
    pub name: String,
    /// The values.
    pub data: AttributeData,
    /// For labels, the GIFTI `LabelTable`'s (key, name) pairs; empty otherwise.
    pub label_table: Vec<(i32, String)>,
}

/// A per-vertex data file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AttributeFormat {
    /// GIFTI data arrays (`.gii`).
    Gifti,
    /// FreeSurfer curvature format (new or old style).
    FreeSurferCurv,
}

impl AttributeFormat {
    /// From the extension (`.gii`, `.gii.gz`), else `None`.
    pub fn from_path(path: &Path) -> Option<AttributeFormat> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        let name = name.strip_suffix(".gz").unwrap_or(&name);
        name.ends_with(".gii").then_some(AttributeFormat::Gifti)
    }

    /// From the first bytes: XML is GIFTI, the curvature magic bytes or the old format's exact
    /// size are FreeSurfer.
    pub fn from_content(bytes: &[u8]) -> Option<AttributeFormat> {
        if super::looks_like_xml(bytes) {
            Some(AttributeFormat::Gifti)
        } else if bytes.starts_with(&freesurfer::CURV_MAGIC) || freesurfer::is_old_curv(bytes) {
            Some(AttributeFormat::FreeSurferCurv)
        } else {
            None
        }
    }
}

/// Read the per-vertex attributes of a GIFTI data file or a FreeSurfer curvature file
/// (optionally gzip-compressed, `.gz`).
pub fn read_vertex_attributes(path: &Path) -> Result<Vec<VertexAttribute>, ReadError> {
    let bytes = load(path)?;
    let format = AttributeFormat::from_path(path)
        .or_else(|| AttributeFormat::from_content(&bytes))
        .ok_or_else(|| ReadError::WrongKind {
            path: path.to_path_buf(),
            message: "not a per-vertex data file capmesh reads: neither GIFTI (.gii, XML) nor a \
                      FreeSurfer curvature file (lh.thickness, lh.curv); convert it to a \
                      .shape.gii with nibabel or 'mris_convert -c'"
                .into(),
        })?;
    parse(path, &bytes, format)
}

/// [`read_vertex_attributes`], then check that every attribute has one value per vertex of
/// `mesh`.
pub fn read_vertex_attributes_for(path: &Path, mesh: &TriMesh) -> Result<Vec<VertexAttribute>, ReadError> {
    let attributes = read_vertex_attributes(path)?;
    if let Some(a) = attributes.iter().find(|a| a.data.len() != mesh.n_vertices()) {
        return Err(ReadError::AttributeLength {
            path: path.to_path_buf(),
            name: a.name.clone(),
            found: a.data.len(),
            expected: mesh.n_vertices(),
        });
    }
    Ok(attributes)
}

/// Parse per-vertex attributes from memory (for fuzzing and tests). Errors name the file
/// `<bytes>`.
pub fn read_vertex_attributes_from_bytes(
    bytes: &[u8],
    format: AttributeFormat,
) -> Result<Vec<VertexAttribute>, ReadError> {
    parse(Path::new("<bytes>"), bytes, format)
}

fn parse(path: &Path, bytes: &[u8], format: AttributeFormat) -> Result<Vec<VertexAttribute>, ReadError> {
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(ReadError::Empty {
            path: path.to_path_buf(),
        });
    }
    match format {
        AttributeFormat::Gifti => gifti::read_attributes(path, bytes),
        AttributeFormat::FreeSurferCurv => {
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let name = name.strip_suffix(".gz").unwrap_or(&name).to_string();
            Ok(vec![freesurfer::read_curv(path, bytes, name)?])
        }
    }
}
