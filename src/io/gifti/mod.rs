//! GIFTI (`.gii`, `.surf.gii`; the neuroimaging surface format of the NIfTI group): an XML file
//! of `DataArray`s. A surface is the first `NIFTI_INTENT_POINTSET` array (`N x 3` coordinates)
//! and the first `NIFTI_INTENT_TRIANGLE` array (`M x 3` 0-based vertex indices); every other
//! array of a data file (`.shape.gii`, `.func.gii`, `.label.gii`) is a per-vertex attribute
//! (`NIFTI_INTENT_LABEL` arrays as labels with the file's `LabelTable`, the others as scalars,
//! one attribute per column).
//!
//! XML is parsed by `roxmltree` (errors carry its line); arrays are decoded by [`array`] and
//! written by [`write`]. Errors name the file, the line of the array, what is wrong and what to
//! do.

mod array;
mod data_write;
mod write;

use std::path::Path;

pub(crate) use data_write::write_attribute;
pub use write::{Endian, GiftiEncoding, GiftiFloat, GiftiOptions};
pub(crate) use write::write;

use self::array::{line_of, Array, Values};
use super::attribute::{AttributeData, VertexAttribute};
use super::error::{Location, ReadError};
use super::parse_error;
use crate::mesh::TriMesh;

const POINTSET: &str = "NIFTI_INTENT_POINTSET";
const TRIANGLE: &str = "NIFTI_INTENT_TRIANGLE";
const LABEL: &str = "NIFTI_INTENT_LABEL";

/// Parse the XML of a GIFTI file.
fn document<'i>(path: &Path, data: &'i [u8]) -> Result<roxmltree::Document<'i>, ReadError> {
    let text = std::str::from_utf8(data).map_err(|e| {
        let line = 1 + data[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count();
        parse_error(
            path,
            Location::Line(line),
            "the file is not UTF-8 text, so not a GIFTI (XML) file; check that it is the right \
             file and not cut short"
                .into(),
        )
    })?;
    let options = roxmltree::ParsingOptions {
        // GIFTI files start with `<!DOCTYPE GIFTI SYSTEM "...gifti.dtd">`; roxmltree never
        // fetches the external DTD and limits entity expansion.
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| {
        parse_error(
            path,
            Location::Line(e.pos().row as usize),
            format!("malformed XML ({e}); the file is truncated or corrupt, export it again"),
        )
    })?;
    let root = doc.root_element();
    if !root.has_tag_name("GIFTI") {
        return Err(parse_error(
            path,
            Location::Line(line_of(root)),
            format!(
                "the root element is <{}>, not <GIFTI>: this XML file is not a GIFTI file",
                root.tag_name().name()
            ),
        ));
    }
    Ok(doc)
}

/// The file's `DataArray`s, checked.
fn arrays<'a, 'i>(path: &Path, doc: &'a roxmltree::Document<'i>) -> Result<Vec<Array<'a, 'i>>, ReadError> {
    doc.root_element()
        .children()
        .filter(|n| n.has_tag_name("DataArray"))
        .map(|n| Array::new(path, n))
        .collect()
}

/// Read a GIFTI surface.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    let doc = document(path, data)?;
    let arrays = arrays(path, &doc)?;
    let points = arrays.iter().find(|a| a.intent == POINTSET);
    let triangles = arrays.iter().find(|a| a.intent == TRIANGLE);
    let (points, triangles) = match (points, triangles) {
        (Some(p), Some(t)) => (p, t),
        (None, None) => {
            return Err(ReadError::WrongKind {
                path: path.to_path_buf(),
                message: format!(
                    "this GIFTI file has no surface (no NIFTI_INTENT_POINTSET and \
                     NIFTI_INTENT_TRIANGLE arrays) but {} data array(s): it holds per-vertex \
                     values; read it as vertex attributes together with its surface (.surf.gii)",
                    arrays.len()
                ),
            })
        }
        (Some(p), None) => {
            return Err(missing(path, TRIANGLE, &format!("a point set (line {}) without triangles", p.line)))
        }
        (None, Some(t)) => {
            return Err(missing(path, POINTSET, &format!("triangles (line {}) without vertices", t.line)))
        }
    };
    let vertices = read_points(path, points)?;
    let faces = read_triangles(path, triangles, vertices.len())?;
    Ok(TriMesh::new(vertices, faces))
}

fn missing(path: &Path, intent: &str, what: &str) -> ReadError {
    ReadError::WrongKind {
        path: path.to_path_buf(),
        message: format!(
            "this GIFTI file has {what}: no {intent} array; a surface needs both \
             NIFTI_INTENT_POINTSET and NIFTI_INTENT_TRIANGLE, export the full surface"
        ),
    }
}

/// Check that an array is `rows x 3`.
fn rows_of_three(path: &Path, a: &Array, what: &str) -> Result<usize, ReadError> {
    match a.dims[..] {
        [rows, 3] => Ok(rows),
        _ => Err(parse_error(
            path,
            Location::Line(a.line),
            format!(
                "the {what} array has dimensions {:?}, expected [n, 3]; the file is corrupt, \
                 export it again",
                a.dims
            ),
        )),
    }
}

fn read_points(path: &Path, a: &Array) -> Result<Vec<[f64; 3]>, ReadError> {
    let n = rows_of_three(path, a, "NIFTI_INTENT_POINTSET")?;
    if n > u32::MAX as usize {
        return Err(parse_error(path, Location::Line(a.line), format!("{n} vertices are more than capmesh supports")));
    }
    let values = match a.decode(path)? {
        Values::Float(v) => v,
        Values::Int(v) => v.into_iter().map(|i| i as f64).collect(),
    };
    let vertices: Vec<[f64; 3]> = values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    if let Some(k) = vertices.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(parse_error(
            path,
            Location::Line(a.line),
            format!(
                "vertex {k} has a coordinate that is not a finite number (NaN or infinity); fix \
                 or delete that vertex in the source data"
            ),
        ));
    }
    Ok(vertices)
}

fn read_triangles(path: &Path, a: &Array, n_vertices: usize) -> Result<Vec<[u32; 3]>, ReadError> {
    rows_of_three(path, a, "NIFTI_INTENT_TRIANGLE")?;
    let Values::Int(values) = a.decode(path)? else {
        return Err(ReadError::UnsupportedGifti {
            path: path.to_path_buf(),
            at: Location::Line(a.line),
            message: "the triangle array holds floating-point numbers, not integer indices".into(),
        });
    };
    let mut faces = Vec::with_capacity(values.len() / 3);
    for c in values.chunks_exact(3) {
        if let Some(&index) = c.iter().find(|&&i| i < 0 || i as u64 >= n_vertices as u64) {
            return Err(ReadError::IndexOutOfRange {
                path: path.to_path_buf(),
                at: Location::Line(a.line),
                index,
                n_vertices,
            });
        }
        faces.push([c[0] as u32, c[1] as u32, c[2] as u32]);
    }
    Ok(faces)
}

/// Read the per-vertex data arrays of a GIFTI file (every array but the surface's).
pub(crate) fn read_attributes(path: &Path, data: &[u8]) -> Result<Vec<VertexAttribute>, ReadError> {
    let doc = document(path, data)?;
    let arrays = arrays(path, &doc)?;
    let table = label_table(path, &doc)?;
    let mut out = Vec::new();
    for (k, a) in arrays.iter().enumerate() {
        if a.intent == POINTSET || a.intent == TRIANGLE {
            continue;
        }
        let at = Location::Line(a.line);
        let (rows, columns) = match a.dims[..] {
            [rows] => (rows, 1),
            [rows, columns] => (rows, columns),
            _ => {
                return Err(ReadError::UnsupportedGifti {
                    path: path.to_path_buf(),
                    at,
                    message: format!("a data array with {} dimensions (per-vertex data have 1 or 2)", a.dims.len()),
                })
            }
        };
        let name = a.meta("Name").filter(|s| !s.is_empty()).unwrap_or_else(|| {
            format!("{} {k}", a.intent.trim_start_matches("NIFTI_INTENT_").to_ascii_lowercase())
        });
        let values = a.decode(path)?;
        for c in 0..columns {
            let name = if columns == 1 { name.clone() } else { format!("{name}[{c}]") };
            let column = (0..rows).map(|r| r * columns + c);
            let data = if a.intent == LABEL {
                let Values::Int(v) = &values else {
                    return Err(ReadError::UnsupportedGifti {
                        path: path.to_path_buf(),
                        at,
                        message: "a label array of floating-point numbers (labels are integers)".into(),
                    });
                };
                let labels = column
                    .map(|i| {
                        i32::try_from(v[i]).map_err(|_| {
                            parse_error(path, at, format!("label {} does not fit a 32-bit integer; the file is corrupt", v[i]))
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                AttributeData::Label(labels)
            } else {
                AttributeData::Scalar(match &values {
                    Values::Float(v) => column.map(|i| v[i] as f32).collect(),
                    Values::Int(v) => column.map(|i| v[i] as f32).collect(),
                })
            };
            let label_table = if a.intent == LABEL { table.clone() } else { Vec::new() };
            out.push(VertexAttribute { name, data, label_table });
        }
    }
    if out.is_empty() {
        return Err(ReadError::WrongKind {
            path: path.to_path_buf(),
            message: "this GIFTI file holds a surface and no per-vertex data arrays; read it as a \
                      mesh, and the data from their own file (.shape.gii, .func.gii, .label.gii)"
                .into(),
        });
    }
    Ok(out)
}

/// The file's `LabelTable`: (key, name) pairs.
fn label_table(path: &Path, doc: &roxmltree::Document) -> Result<Vec<(i32, String)>, ReadError> {
    let Some(table) = doc.root_element().children().find(|n| n.has_tag_name("LabelTable")) else {
        return Ok(Vec::new());
    };
    table
        .children()
        .filter(|n| n.has_tag_name("Label"))
        .map(|label| {
            let key = label.attribute("Key").or_else(|| label.attribute("Index")).unwrap_or("");
            let key = key.trim().parse::<i32>().map_err(|_| {
                parse_error(
                    path,
                    Location::Line(line_of(label)),
                    format!("the label's Key '{}' is not an integer; the file is corrupt, export it again", key.trim()),
                )
            })?;
            Ok((key, label.text().unwrap_or("").trim().to_string()))
        })
        .collect()
}
