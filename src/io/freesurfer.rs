//! FreeSurfer binary files, big endian: triangle surfaces (`lh.pial`, `lh.white`, ...) and
//! per-vertex curvature-format data (`lh.curv`, `lh.thickness`, `lh.sulc`, ...).
//!
//! A triangle surface is the magic bytes `0xFF 0xFF 0xFE`, a creation line ending in `\n` (and
//! usually a second `\n`), the vertex and face counts (`int32`), the coordinates (`float32`,
//! `x y z` per vertex) and the faces (`int32`, 0-based). Whatever follows the faces (volume
//! geometry and command-line tags) is ignored; the coordinates are returned as stored (the
//! surface RAS of FreeSurfer, without the tags' `c_ras` shift). Quadrangle surfaces (magic
//! `0xFF 0xFF 0xFF` or `0xFF 0xFF 0xFD`) are refused. Files are recognised by their magic
//! bytes, so no extension is needed.
//!
//! A new-style curvature file is `0xFF 0xFF 0xFF`, the vertex count, face count and values per
//! vertex (`int32`, the last must be 1), then one `float32` per vertex. Old-style files
//! (3-byte vertex and face counts, then `int16` hundredths) are recognised by their exact size.
//!
//! The writer stores the coordinates as 32-bit floats (precision is lost, as in STL).

use std::io::Write;
use std::path::Path;

use super::attribute::{AttributeData, VertexAttribute};
use super::error::{Location, ReadError};
use super::parse_error;
use crate::mesh::TriMesh;

/// Magic bytes of a triangle surface.
pub(crate) const TRIANGLE_MAGIC: [u8; 3] = [0xFF, 0xFF, 0xFE];
/// Magic bytes of a new-style curvature file (also of an old quadrangle surface).
pub(crate) const CURV_MAGIC: [u8; 3] = [0xFF, 0xFF, 0xFF];
/// Magic bytes of a newer quadrangle surface.
const NEW_QUAD_MAGIC: [u8; 3] = [0xFF, 0xFF, 0xFD];

fn truncated(path: &Path, what: String, expected: u64, found: usize) -> ReadError {
    ReadError::Truncated {
        path: path.to_path_buf(),
        what,
        expected,
        found: found as u64,
    }
}

fn be_i32(data: &[u8], at: usize) -> i32 {
    i32::from_be_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]])
}

fn be_f32(data: &[u8], at: usize) -> f32 {
    f32::from_be_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]])
}

/// A count read at byte `at`, which must not be negative.
fn count(path: &Path, data: &[u8], at: usize, what: &str) -> Result<usize, ReadError> {
    let n = be_i32(data, at);
    usize::try_from(n).map_err(|_| {
        parse_error(
            path,
            Location::Byte(at as u64),
            format!("the number of {what} is {n}; the file is corrupt, produce it again"),
        )
    })
}

/// Parse a FreeSurfer triangle surface.
pub(crate) fn read(path: &Path, data: &[u8]) -> Result<TriMesh, ReadError> {
    if data.len() < 3 {
        return Err(truncated(path, "bytes (a FreeSurfer surface starts with 3 magic bytes)".into(), 3, data.len()));
    }
    let magic = [data[0], data[1], data[2]];
    if magic == CURV_MAGIC || magic == NEW_QUAD_MAGIC {
        return Err(ReadError::WrongKind {
            path: path.to_path_buf(),
            message: format!(
                "the file starts with the magic bytes {magic:02X?}: a FreeSurfer per-vertex data file \
                 (lh.curv, lh.thickness: read it as vertex attributes with its surface) or a \
                 quadrangle surface, which capmesh does not read (convert it to triangles with \
                 'mris_convert lh.orig lh.orig.gii')"
            ),
        });
    }
    if magic != TRIANGLE_MAGIC {
        return Err(parse_error(
            path,
            Location::Byte(0),
            "not a FreeSurfer triangle surface: it does not start with the magic bytes FF FF FE; \
             check that it is a surface file (lh.pial, lh.white, ...) and not a volume or label"
                .into(),
        ));
    }
    // The creation line ("created by <user> on <date>") and its blank line.
    let line_end = data[3..]
        .iter()
        .take(4096)
        .position(|&b| b == b'\n')
        .ok_or_else(|| {
            parse_error(
                path,
                Location::Byte(3),
                "the creation line after the magic bytes has no end (no newline in 4096 bytes); \
                 the file is truncated or not a FreeSurfer surface"
                    .into(),
            )
        })?;
    let mut at = 3 + line_end + 1;
    if data.get(at) == Some(&b'\n') {
        at += 1;
    }
    if data.len() < at + 8 {
        return Err(truncated(path, "bytes (the vertex and face counts)".into(), (at + 8) as u64, data.len()));
    }
    let nv = count(path, data, at, "vertices")?;
    let nf = count(path, data, at + 4, "faces")?;
    at += 8;
    let needed = at as u64 + 12 * nv as u64 + 12 * nf as u64;
    if (data.len() as u64) < needed {
        return Err(truncated(
            path,
            format!("bytes (the header announces {nv} vertices and {nf} faces)"),
            needed,
            data.len(),
        ));
    }
    let mut vertices = Vec::with_capacity(nv);
    for v in 0..nv {
        let o = at + 12 * v;
        let p = [be_f32(data, o), be_f32(data, o + 4), be_f32(data, o + 8)].map(f64::from);
        if !p.iter().all(|x| x.is_finite()) {
            return Err(ReadError::NonFinite {
                path: path.to_path_buf(),
                at: Location::Byte(o as u64),
            });
        }
        vertices.push(p);
    }
    at += 12 * nv;
    let mut faces = Vec::with_capacity(nf);
    for f in 0..nf {
        let o = at + 12 * f;
        let face = [be_i32(data, o), be_i32(data, o + 4), be_i32(data, o + 8)];
        if let Some(&index) = face.iter().find(|&&i| i < 0 || i as usize >= nv) {
            return Err(ReadError::IndexOutOfRange {
                path: path.to_path_buf(),
                at: Location::Byte(o as u64),
                index: i64::from(index),
                n_vertices: nv,
            });
        }
        faces.push(face.map(|i| i as u32));
    }
    Ok(TriMesh::new(vertices, faces))
}

/// Write a FreeSurfer triangle surface. The mesh has been checked by the caller (indices,
/// finiteness, float32 range, int32 counts).
pub(crate) fn write(w: &mut dyn Write, mesh: &TriMesh) -> std::io::Result<()> {
    w.write_all(&TRIANGLE_MAGIC)?;
    w.write_all(b"created by capmesh\n\n")?;
    w.write_all(&(mesh.n_vertices() as i32).to_be_bytes())?;
    w.write_all(&(mesh.n_faces() as i32).to_be_bytes())?;
    for x in mesh.vertices.iter().flatten() {
        w.write_all(&(*x as f32).to_be_bytes())?;
    }
    for &i in mesh.faces.iter().flatten() {
        w.write_all(&(i as i32).to_be_bytes())?;
    }
    Ok(())
}

/// `true` when `data` is an old-style curvature file (3-byte counts, `int16` values): the size
/// must match exactly.
pub(crate) fn is_old_curv(data: &[u8]) -> bool {
    data.len() >= 6
        && data[..3] != CURV_MAGIC
        && data.len() as u64 == 6 + 2 * u64::from(u32::from_be_bytes([0, data[0], data[1], data[2]]))
}

/// Parse a FreeSurfer curvature-format file into one scalar attribute named `name`.
pub(crate) fn read_curv(path: &Path, data: &[u8], name: String) -> Result<VertexAttribute, ReadError> {
    let values = if data.starts_with(&CURV_MAGIC) {
        if data.len() < 15 {
            return Err(truncated(path, "bytes (a curvature file's 15-byte header)".into(), 15, data.len()));
        }
        let nv = count(path, data, 3, "vertices")?;
        count(path, data, 7, "faces")?;
        let per_vertex = be_i32(data, 11);
        if per_vertex != 1 {
            return Err(parse_error(
                path,
                Location::Byte(11),
                format!(
                    "{per_vertex} values per vertex; capmesh reads curvature files with one value \
                     per vertex (lh.curv, lh.thickness, lh.sulc)"
                ),
            ));
        }
        let needed = 15 + 4 * nv as u64;
        if (data.len() as u64) < needed {
            return Err(truncated(path, format!("bytes (the header announces {nv} values)"), needed, data.len()));
        }
        (0..nv).map(|v| be_f32(data, 15 + 4 * v)).collect()
    } else if is_old_curv(data) {
        let nv = (data.len() - 6) / 2;
        (0..nv)
            .map(|v| f32::from(i16::from_be_bytes([data[6 + 2 * v], data[7 + 2 * v]])) / 100.0)
            .collect()
    } else {
        return Err(parse_error(
            path,
            Location::Byte(0),
            "not a FreeSurfer curvature file: it does not start with FF FF FF and its size does \
             not fit the old format; per-vertex data are read from FreeSurfer curvature files \
             (lh.thickness, lh.curv) and GIFTI files (.shape.gii, .func.gii, .label.gii)"
                .into(),
        ));
    };
    Ok(VertexAttribute {
        name,
        data: AttributeData::Scalar(values),
        label_table: Vec::new(),
    })
}
