//! Mesh files: OBJ, PLY (ASCII and binary), OFF, STL (ASCII and binary), GIFTI (`.gii`) and
//! FreeSurfer triangle surfaces (`lh.pial`), chosen by the file extension (case-insensitive)
//! or, when the extension names none of them, by the content (GIFTI's XML, FreeSurfer's magic
//! bytes), each optionally gzip-compressed (`mesh.obj.gz`). Per-vertex data files (GIFTI
//! `.shape.gii` / `.func.gii` / `.label.gii`, FreeSurfer `lh.thickness`) are read as
//! [`VertexAttribute`]s by [`read_vertex_attributes`].
//!
//! Readers load the whole file into memory (read-only; the input is never modified) and parse
//! it by hand; they never panic, and every error names the file, the line (text) or byte
//! offset (binary), what is wrong and what to do. Polygons are fan-triangulated. Readers check
//! syntax, index ranges and finiteness; topology is checked by [`crate::mesh::validate()`].
//!
//! Writers use a buffered writer and full `f64` precision (shortest round-tripping decimal in
//! the text formats, `double` in PLY; STL, FreeSurfer and GIFTI by default store 32-bit
//! floats, see [`GiftiOptions`]). They refuse meshes with out-of-range indices or non-finite
//! coordinates, and write through [`atomic`]: the target holds its earlier content or the
//! complete new file, never a part. Use [`same_file`] to refuse overwriting an input file.

pub mod atomic;
mod attribute;
pub(crate) mod error;
mod freesurfer;
mod gifti;
mod obj;
mod off;
mod ply;
mod stl;
mod text;
mod vertex_properties;

use std::fmt;
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

pub use attribute::{
    read_vertex_attributes, read_vertex_attributes_for, read_vertex_attributes_from_bytes,
    AttributeData, AttributeFormat, VertexAttribute,
};
pub use error::{Location, ReadError, WriteError};
pub use gifti::{Endian, GiftiEncoding, GiftiFloat, GiftiOptions};
pub use vertex_properties::VertexProperties;

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
    /// GIFTI surface (`.gii`, `.surf.gii`): see [`GiftiOptions`] for what is written.
    Gifti,
    /// FreeSurfer binary triangle surface (`lh.pial`, `lh.white`, ...: recognised by content;
    /// written for the extensions `.pial`, `.white`, `.inflated`, `.sphere`, `.orig`,
    /// `.smoothwm`, `.midthickness`).
    FreeSurfer,
}

/// The surface names FreeSurfer uses as the last part of a file name (`lh.pial`).
const FREESURFER_NAMES: [&str; 7] = ["pial", "white", "inflated", "sphere", "orig", "smoothwm", "midthickness"];

/// Second extensions of GIFTI per-vertex data files: not meshes.
const GIFTI_DATA: [&str; 4] = ["shape", "func", "label", "time"];

impl Format {
    /// The format for an extension (without the dot, any case).
    pub fn from_extension(extension: &str) -> Option<Format> {
        match extension.to_ascii_lowercase().as_str() {
            "obj" => Some(Format::Obj),
            "ply" => Some(Format::Ply),
            "off" => Some(Format::Off),
            "stl" => Some(Format::Stl),
            "gii" => Some(Format::Gifti),
            e if FREESURFER_NAMES.contains(&e) => Some(Format::FreeSurfer),
            _ => None,
        }
    }

    /// The format of a path from its extension; for `name.obj.gz` the extension before `.gz`.
    /// GIFTI data files (`.shape.gii`, `.func.gii`, `.label.gii`, `.time.gii`) are not meshes:
    /// `None`.
    pub fn from_path(path: &Path) -> Option<Format> {
        let mut path = path;
        let ext = path.extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("gz") {
            path = Path::new(path.file_stem()?);
        }
        let format = Format::from_extension(path.extension()?.to_str()?)?;
        let second = Path::new(path.file_stem()?).extension().and_then(|e| e.to_str());
        if format == Format::Gifti && second.is_some_and(|e| GIFTI_DATA.contains(&e.to_ascii_lowercase().as_str())) {
            return None;
        }
        Some(format)
    }

    /// The format from the content, for the formats with a signature: FreeSurfer's magic bytes
    /// (`FF FF FE`, and the quadrangle and curvature ones so that their reader explains them)
    /// and GIFTI's XML. The text formats are only chosen by extension.
    pub fn from_content(bytes: &[u8]) -> Option<Format> {
        if bytes.len() >= 3 && bytes[..2] == [0xFF, 0xFF] && matches!(bytes[2], 0xFD..=0xFF) {
            Some(Format::FreeSurfer)
        } else if looks_like_xml(bytes) {
            Some(Format::Gifti)
        } else {
            None
        }
    }

    /// The usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Ply => "ply",
            Format::Off => "off",
            Format::Stl => "stl",
            Format::Gifti => "gii",
            Format::FreeSurfer => "pial",
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
            Format::Gifti => "GIFTI",
            Format::FreeSurfer => "FreeSurfer",
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

/// `true` when the content starts (after a byte-order mark and whitespace) with `<?xml`,
/// `<!DOCTYPE` or `<GIFTI`.
pub(crate) fn looks_like_xml(bytes: &[u8]) -> bool {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let start = bytes.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(bytes.len());
    let rest = &bytes[start..];
    [&b"<?xml"[..], b"<!DOCTYPE", b"<GIFTI"].iter().any(|s| rest.starts_with(s))
}

/// The file's bytes, decompressed when the name ends in `.gz`.
pub(crate) fn load(path: &Path) -> Result<Vec<u8>, ReadError> {
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    if is_gzip(path) {
        return gunzip(path, &bytes);
    }
    Ok(bytes)
}

/// Read a mesh; the format comes from the extension (`.obj`, `.ply`, `.off`, `.stl`, `.gii`,
/// a FreeSurfer surface name such as `.pial`, each optionally followed by `.gz`), or else from
/// the content (GIFTI, FreeSurfer: `lh.pial` needs no extension).
pub fn read_mesh(path: &Path) -> Result<TriMesh, ReadError> {
    let bytes = load(path)?;
    let format = Format::from_path(path)
        .or_else(|| Format::from_content(&bytes))
        .ok_or_else(|| ReadError::UnknownFormat {
            path: path.to_path_buf(),
            extension: extension_of(path),
        })?;
    parse(path, &bytes, format)
}

/// Read a PLY mesh (optionally `.gz`) with its scalar vertex properties `names` (`quality`,
/// `red`, `thickness`, ...), one value per vertex each: what `remesh --attribute NAME` carries.
/// Floating-point properties and the colour channels are scalars, other integer properties
/// labels. A name the file does not have is [`ReadError::NoPlyProperty`], listing those it has.
pub fn read_ply_with_vertex_attributes(path: &Path, names: &[&str]) -> Result<(TriMesh, Vec<VertexAttribute>), ReadError> {
    if Format::from_path(path) != Some(Format::Ply) {
        return Err(ReadError::WrongKind {
            path: path.to_path_buf(),
            message: "vertex properties are read by name from PLY files only; pass a per-vertex data file (.gii, FreeSurfer curv) instead".into(),
        });
    }
    let bytes = load(path)?;
    let (mesh, attributes) = ply::read_vertex_properties(path, &bytes, names)?;
    if mesh.faces.is_empty() {
        return Err(ReadError::NoFaces { path: path.to_path_buf(), n_vertices: mesh.n_vertices() });
    }
    Ok((mesh, attributes))
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
        Format::Gifti => gifti::read(path, bytes),
        Format::FreeSurfer => freesurfer::read(path, bytes),
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

/// Options of the writers whose format has variants. Defaults: binary PLY, and
/// [`GiftiOptions::default()`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub struct WriteOptions {
    /// Write PLY as ASCII instead of binary little endian.
    pub ply_ascii: bool,
    /// Encoding, coordinate type and byte order of GIFTI files.
    pub gifti: GiftiOptions,
}

impl WriteOptions {
    /// Set [`WriteOptions::ply_ascii`].
    pub fn with_ply_ascii(mut self, ply_ascii: bool) -> Self {
        self.ply_ascii = ply_ascii;
        self
    }

    /// Set [`WriteOptions::gifti`].
    pub fn with_gifti(mut self, gifti: GiftiOptions) -> Self {
        self.gifti = gifti;
        self
    }
}

/// Write a mesh; the format comes from the extension (PLY is binary little endian, GIFTI as
/// [`GiftiOptions::default()`]), gzip-compressed when the name ends in `.gz`.
/// An existing file is replaced, atomically ([`atomic`]): check [`same_file`] against the
/// inputs first.
pub fn write_mesh(path: &Path, mesh: &TriMesh) -> Result<(), WriteError> {
    write_mesh_with(path, mesh, &WriteOptions::default())
}

/// [`write_mesh`] with options for the formats that have variants (PLY, GIFTI).
pub fn write_mesh_with(path: &Path, mesh: &TriMesh, options: &WriteOptions) -> Result<(), WriteError> {
    commit(path, stage_mesh_with(path, mesh, options)?)
}

/// [`write_mesh`] up to the last step: the complete file waits under a temporary name for
/// [`atomic::StagedFile::commit`] (or [`atomic::commit_all`] with the other outputs of a run).
pub fn stage_mesh(path: &Path, mesh: &TriMesh) -> Result<atomic::StagedFile, WriteError> {
    stage_mesh_with(path, mesh, &WriteOptions::default())
}

/// [`stage_mesh`] with options for the formats that have variants (PLY, GIFTI).
pub fn stage_mesh_with(path: &Path, mesh: &TriMesh, options: &WriteOptions) -> Result<atomic::StagedFile, WriteError> {
    let format = Format::from_path(path).ok_or_else(|| WriteError::UnknownFormat {
        path: path.to_path_buf(),
        extension: extension_of(path),
    })?;
    stage_with(path, mesh, format, options)
}

/// [`stage_mesh_with`] carrying per-vertex data: texture coordinates (OBJ `vt`, PLY
/// `texture_u`/`texture_v`) and named float properties (PLY only); refused for the formats
/// that cannot store what is given.
pub fn stage_mesh_with_properties(path: &Path, mesh: &TriMesh, extra: &VertexProperties, options: &WriteOptions) -> Result<atomic::StagedFile, WriteError> {
    let format = Format::from_path(path).ok_or_else(|| WriteError::UnknownFormat {
        path: path.to_path_buf(),
        extension: extension_of(path),
    })?;
    stage_with_properties(path, mesh, extra, format, options)
}

/// [`stage_mesh_with_properties`], committed.
pub fn write_mesh_with_properties(path: &Path, mesh: &TriMesh, extra: &VertexProperties, options: &WriteOptions) -> Result<(), WriteError> {
    commit(path, stage_mesh_with_properties(path, mesh, extra, options)?)
}

/// Stage `attribute` as a GIFTI data file at `path` (`.shape.gii` for values, `.label.gii`
/// for labels by convention; `.gz` compresses), written atomically like the meshes.
pub fn stage_vertex_attribute(path: &Path, attribute: &VertexAttribute, options: &GiftiOptions) -> Result<atomic::StagedFile, WriteError> {
    atomic::stage(path, |file| {
        if is_gzip(path) {
            let mut gz = flate2::write::GzEncoder::new(BufWriter::new(file), flate2::Compression::fast());
            gifti::write_attribute(&mut gz, attribute, options)?;
            gz.finish()?.flush()
        } else {
            gifti::write_attribute(file, attribute, options)
        }
    })
}

/// Write ASCII PLY (whatever the extension; gzip-compressed when it ends in `.gz`).
pub fn write_ply_ascii(path: &Path, mesh: &TriMesh) -> Result<(), WriteError> {
    commit(path, stage_with(path, mesh, Format::Ply, &WriteOptions::default().with_ply_ascii(true))?)
}

fn commit(path: &Path, staged: atomic::StagedFile) -> Result<(), WriteError> {
    staged.commit().map_err(|source| WriteError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Encode a mesh in memory (PLY as binary little endian). Errors name the file `<bytes>`.
pub fn write_mesh_to_bytes(mesh: &TriMesh, format: Format) -> Result<Vec<u8>, WriteError> {
    write_mesh_to_bytes_with(mesh, format, &WriteOptions::default())
}

/// [`write_mesh_to_bytes`] with options.
pub fn write_mesh_to_bytes_with(mesh: &TriMesh, format: Format, options: &WriteOptions) -> Result<Vec<u8>, WriteError> {
    let path = Path::new("<bytes>");
    check_writable(path, mesh, format, options)?;
    let mut out = Vec::new();
    encode(&mut out, mesh, &VertexProperties::default(), format, options).map_err(|source| WriteError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(out)
}

fn encode(w: &mut dyn Write, mesh: &TriMesh, extra: &VertexProperties, format: Format, options: &WriteOptions) -> std::io::Result<()> {
    match format {
        Format::Obj => obj::write(w, mesh, extra),
        Format::Ply if options.ply_ascii => ply::write_ascii(w, mesh, extra),
        Format::Ply => ply::write_binary(w, mesh, extra),
        Format::Off => off::write(w, mesh),
        Format::Stl => stl::write(w, mesh),
        Format::Gifti => gifti::write(w, mesh, &options.gifti),
        Format::FreeSurfer => freesurfer::write(w, mesh),
    }
}

fn stage_with(path: &Path, mesh: &TriMesh, format: Format, options: &WriteOptions) -> Result<atomic::StagedFile, WriteError> {
    stage_with_properties(path, mesh, &VertexProperties::default(), format, options)
}

fn stage_with_properties(path: &Path, mesh: &TriMesh, extra: &VertexProperties, format: Format, options: &WriteOptions) -> Result<atomic::StagedFile, WriteError> {
    check_writable(path, mesh, format, options)?;
    extra.check(path, mesh, format)?;
    atomic::stage(path, |file| {
        if is_gzip(path) {
            // Buffer in front of the encoder: the writers make many small writes.
            let gz = flate2::write::GzEncoder::new(file, flate2::Compression::fast());
            let mut buffered = BufWriter::with_capacity(1 << 20, gz);
            encode(&mut buffered, mesh, extra, format, options)?;
            buffered.into_inner().map_err(|e| e.into_error())?.finish()?;
            Ok(())
        } else {
            encode(file, mesh, extra, format, options)
        }
    })
}

/// Refuse meshes the file would misrepresent.
fn check_writable(path: &Path, mesh: &TriMesh, format: Format, options: &WriteOptions) -> Result<(), WriteError> {
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
    if matches!(format, Format::Gifti | Format::FreeSurfer) && mesh.n_vertices().max(mesh.n_faces()) > i32::MAX as usize {
        return Err(WriteError::Unsupported {
            path: path.to_path_buf(),
            message: format!("{format} stores at most 2147483647 vertices and faces; use PLY"),
        });
    }
    let float32 = match format {
        Format::Stl | Format::FreeSurfer => true,
        Format::Gifti => options.gifti.coordinates == GiftiFloat::Float32,
        _ => false,
    };
    if format == Format::Stl && mesh.n_faces() > u32::MAX as usize {
        return Err(WriteError::Unsupported {
            path: path.to_path_buf(),
            message: "STL stores at most 4294967295 triangles; use PLY".into(),
        });
    }
    if float32 {
        let limit = f64::from(f32::MAX);
        if let Some(vertex) = mesh
            .vertices
            .iter()
            .position(|p| p.iter().any(|x| x.abs() > limit))
        {
            return Err(WriteError::Unsupported {
                path: path.to_path_buf(),
                message: format!(
                    "vertex {vertex} does not fit {format}'s 32-bit floats; use PLY or OBJ"
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
