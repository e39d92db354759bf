//! Mesh files: OBJ, PLY (ASCII and binary), OFF and STL (ASCII and binary), chosen by the
//! file extension (case-insensitive), each optionally gzip-compressed (`mesh.obj.gz`).
//!
//! Readers load the whole file into memory (read-only; the input is never modified) and parse
//! it by hand; they never panic, and every error names the file, the line (text) or byte
//! offset (binary), what is wrong and what to do. Polygons are fan-triangulated. Readers check
//! syntax, index ranges and finiteness; topology is checked by [`crate::mesh::validate()`].
//!
//! Writers use a buffered writer and full `f64` precision (shortest round-tripping decimal in
//! the text formats, `double` in PLY; STL stores 32-bit floats). They refuse meshes with
//! out-of-range indices or non-finite coordinates, and write through [`atomic`]: the target
//! holds its earlier content or the complete new file, never a part. Use [`same_file`] to
//! refuse overwriting an input file.

pub mod atomic;
pub mod error;
mod obj;
mod off;
mod ply;
mod stl;
mod text;

use std::fmt;
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

pub use error::{Location, ReadError, WriteError};

use crate::mesh::TriMesh;

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// Stanford PLY (`.ply`): reads ASCII and binary; writes binary little endian.
    Ply,
    /// Object File Format (`.off`).
    Off,
    /// STL (`.stl`): reads ASCII and binary; writes binary.
    Stl,
}

impl Format {
    /// The format for an extension (without the dot, any case).
    pub fn from_extension(extension: &str) -> Option<Format> {
        match extension.to_ascii_lowercase().as_str() {
            "obj" => Some(Format::Obj),
            "ply" => Some(Format::Ply),
            "off" => Some(Format::Off),
            "stl" => Some(Format::Stl),
            _ => None,
        }
    }

    /// The format of a path from its extension; for `name.obj.gz` the extension before `.gz`.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("gz") {
            return Format::from_extension(Path::new(path.file_stem()?).extension()?.to_str()?);
        }
        Format::from_extension(ext)
    }

    /// The usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Ply => "ply",
            Format::Off => "off",
            Format::Stl => "stl",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Format::Obj => "OBJ",
            Format::Ply => "PLY",
            Format::Off => "OFF",
            Format::Stl => "STL",
        })
    }
}

/// Largest decompressed size of a `.gz` mesh.
const MAX_DECOMPRESSED: u64 = 1 << 34;

/// `true` when the path ends in `.gz` (any case): read and written gzip-compressed.
pub fn is_gzip(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"))
}

/// The extension for messages (`obj`, or `vtk.gz` for a compressed file).
fn extension_of(path: &Path) -> String {
    let ext = |p: &Path| {
        p.extension()
            .map(|e| e.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    match path.file_stem() {
        Some(stem) if is_gzip(path) => format!("{}.{}", ext(Path::new(stem)), ext(path)),
        _ => ext(path),
    }
}

fn gunzip(path: &Path, bytes: &[u8]) -> Result<Vec<u8>, ReadError> {
    let mut out = Vec::with_capacity(bytes.len().saturating_mul(4));
    let result = flate2::read::MultiGzDecoder::new(bytes)
        .take(MAX_DECOMPRESSED + 1)
        .read_to_end(&mut out);
    let source = match result {
        Ok(n) if (n as u64) <= MAX_DECOMPRESSED => return Ok(out),
        Ok(_) => std::io::Error::other("the decompressed data is larger than 16 GiB"),
        Err(e) => e,
    };
    Err(ReadError::Decompress {
        path: path.to_path_buf(),
        source,
    })
}

/// Read a mesh; the format comes from the extension (`.obj`, `.ply`, `.off`, `.stl`, each
/// optionally followed by `.gz`).
pub fn read_mesh(path: &Path) -> Result<TriMesh, ReadError> {
    let format = Format::from_path(path).ok_or_else(|| ReadError::UnknownFormat {
        path: path.to_path_buf(),
        extension: extension_of(path),
    })?;
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    if is_gzip(path) {
        let bytes = gunzip(path, &bytes)?;
        return parse(path, &bytes, format);
    }
    parse(path, &bytes, format)
}

/// Parse a mesh from memory (for fuzzing and tests). Errors name the file `<bytes>`.
pub fn read_mesh_from_bytes(bytes: &[u8], format: Format) -> Result<TriMesh, ReadError> {
    parse(Path::new("<bytes>"), bytes, format)
}

/// Decompress gzip `bytes` and parse the result (for fuzzing and tests). Errors name the file
/// `<bytes>.gz`.
pub fn read_mesh_from_gzip_bytes(bytes: &[u8], format: Format) -> Result<TriMesh, ReadError> {
    let path = Path::new("<bytes>.gz");
    parse(path, &gunzip(path, bytes)?, format)
}

fn parse(path: &Path, bytes: &[u8], format: Format) -> Result<TriMesh, ReadError> {
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(ReadError::Empty {
            path: path.to_path_buf(),
        });
    }
    let mesh = match format {
        Format::Obj => obj::read(path, bytes),
        Format::Ply => ply::read(path, bytes),
        Format::Off => off::read(path, bytes),
        Format::Stl => stl::read(path, bytes),
    }?;
    if mesh.vertices.is_empty() && mesh.faces.is_empty() {
        return Err(ReadError::Empty {
            path: path.to_path_buf(),
        });
    }
    if mesh.faces.is_empty() {
        return Err(ReadError::NoFaces {
            path: path.to_path_buf(),
            n_vertices: mesh.n_vertices(),
        });
    }
    Ok(mesh)
}

/// Write a mesh; the format comes from the extension (PLY is binary little endian), gzip-
/// compressed when the name ends in `.gz`.
/// An existing file is replaced, atomically ([`atomic`]): check [`same_file`] against the
/// inputs first.
pub fn write_mesh(path: &Path, mesh: &TriMesh) -> Result<(), WriteError> {
    commit(path, stage_mesh(path, mesh)?)
}

/// [`write_mesh`] up to the last step: the complete file waits under a temporary name for
/// [`atomic::StagedFile::commit`] (or [`atomic::commit_all`] with the other outputs of a run).
pub fn stage_mesh(path: &Path, mesh: &TriMesh) -> Result<atomic::StagedFile, WriteError> {
    let format = Format::from_path(path).ok_or_else(|| WriteError::UnknownFormat {
        path: path.to_path_buf(),
        extension: extension_of(path),
    })?;
    stage_with(path, mesh, format, false)
}

/// Write ASCII PLY (whatever the extension; gzip-compressed when it ends in `.gz`).
pub fn write_ply_ascii(path: &Path, mesh: &TriMesh) -> Result<(), WriteError> {
    commit(path, stage_with(path, mesh, Format::Ply, true)?)
}

fn commit(path: &Path, staged: atomic::StagedFile) -> Result<(), WriteError> {
    staged.commit().map_err(|source| WriteError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Encode a mesh in memory (PLY as binary little endian). Errors name the file `<bytes>`.
pub fn write_mesh_to_bytes(mesh: &TriMesh, format: Format) -> Result<Vec<u8>, WriteError> {
    let path = Path::new("<bytes>");
    check_writable(path, mesh, format)?;
    let mut out = Vec::new();
    encode(&mut out, mesh, format, false).map_err(|source| WriteError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(out)
}

fn encode(w: &mut dyn Write, mesh: &TriMesh, format: Format, ascii: bool) -> std::io::Result<()> {
    match format {
        Format::Obj => obj::write(w, mesh),
        Format::Ply if ascii => ply::write_ascii(w, mesh),
        Format::Ply => ply::write_binary(w, mesh),
        Format::Off => off::write(w, mesh),
        Format::Stl => stl::write(w, mesh),
    }
}

fn stage_with(path: &Path, mesh: &TriMesh, format: Format, ascii: bool) -> Result<atomic::StagedFile, WriteError> {
    check_writable(path, mesh, format)?;
    atomic::stage(path, |file| {
        if is_gzip(path) {
            // Buffer in front of the encoder: the writers make many small writes.
            let gz = flate2::write::GzEncoder::new(file, flate2::Compression::fast());
            let mut buffered = BufWriter::with_capacity(1 << 20, gz);
            encode(&mut buffered, mesh, format, ascii)?;
            buffered.into_inner().map_err(|e| e.into_error())?.finish()?;
            Ok(())
        } else {
            encode(file, mesh, format, ascii)
        }
    })
}

/// Refuse meshes the file would misrepresent.
fn check_writable(path: &Path, mesh: &TriMesh, format: Format) -> Result<(), WriteError> {
    let n = mesh.n_vertices();
    for (face, f) in mesh.faces.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&v| v as usize >= n) {
            return Err(WriteError::IndexOutOfRange {
                path: path.to_path_buf(),
                face,
                index,
                n_vertices: n,
            });
        }
    }
    if let Some(vertex) = mesh
        .vertices
        .iter()
        .position(|p| !p.iter().all(|x| x.is_finite()))
    {
        return Err(WriteError::NonFinite {
            path: path.to_path_buf(),
            vertex,
        });
    }
    if format == Format::Stl {
        if mesh.n_faces() > u32::MAX as usize {
            return Err(WriteError::Unsupported {
                path: path.to_path_buf(),
                message: "STL stores at most 4294967295 triangles; use PLY".into(),
            });
        }
        let limit = f64::from(f32::MAX);
        if let Some(vertex) = mesh
            .vertices
            .iter()
            .position(|p| p.iter().any(|x| x.abs() > limit))
        {
            return Err(WriteError::Unsupported {
                path: path.to_path_buf(),
                message: format!(
                    "vertex {vertex} does not fit STL's 32-bit floats; use PLY or OBJ"
                ),
            });
        }
    }
    Ok(())
}

/// `true` when `a` and `b` name the same existing file (same device and inode on Unix, same
/// canonical path elsewhere), including through symbolic or hard links. `false` when either
/// does not exist.
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        ma.dev() == mb.dev() && ma.ino() == mb.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (ma, mb);
        match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
    }
}

/// Fan-triangulate a polygon `p0 p1 .. pk` into `(p0, pi, pi+1)`.
pub(crate) fn fan(polygon: &[u32], faces: &mut Vec<[u32; 3]>) {
    if let Some((&first, rest)) = polygon.split_first() {
        for w in rest.windows(2) {
            faces.push([first, w[0], w[1]]);
        }
    }
}

/// A [`ReadError::Parse`].
pub(crate) fn parse_error(path: &Path, at: Location, message: String) -> ReadError {
    ReadError::Parse {
        path: PathBuf::from(path),
        at,
        message,
    }
}
