//! Errors of mesh reading and writing. Every message names the file, where in it the problem
//! is (1-based line for text formats, byte offset for binary ones), what is wrong and what to do.

use std::fmt;
use std::path::PathBuf;

use thiserror::Error;

/// A place in a mesh file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// 1-based line of a text file.
    Line(usize),
    /// 0-based byte offset in a binary file.
    Byte(u64),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(n) => write!(f, "line {n}"),
            Location::Byte(n) => write!(f, "byte offset {n}"),
        }
    }
}

/// Why a mesh file could not be read.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("cannot read {}: {source}; check the path and the file's permissions", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },

    /// Neither the extension nor the content names a supported format.
    #[error(
        "{}: unknown mesh format '{extension}'; capmesh reads .obj, .ply, .off, .stl and GIFTI \
         (.surf.gii) files and FreeSurfer surfaces (lh.pial, recognised by content), optionally \
         gzip-compressed (.obj.gz, ...); convert other formats with MeshLab or meshio",
        path.display()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Its extension (empty when it has none).
        extension: String,
    },

    /// A `.gz` file could not be decompressed.
    #[error(
        "cannot decompress {}: {source}; the .gz file is corrupt or truncated, download or \
         compress it again (or check it with 'gzip -t')",
        path.display()
    )]
    Decompress {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },

    /// The file has no vertices and no faces.
    #[error(
        "{}: the file is empty (no vertices, no faces); check that the export or download \
         finished",
        path.display()
    )]
    Empty {
        /// The file.
        path: PathBuf,
    },

    /// Malformed content.
    #[error("{}, {at}: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// What is wrong and what to do.
        message: String,
    },

    /// The file ends before everything its header announced.
    #[error(
        "{}: the file is truncated: expected {expected} {what} but it ends after {found}; it was \
         cut short (interrupted download, copy or export), produce it again",
        path.display()
    )]
    Truncated {
        /// The file.
        path: PathBuf,
        /// What was being read ("vertices", "faces", "bytes", ...).
        what: String,
        /// How many were announced.
        expected: u64,
        /// How many were present.
        found: u64,
    },

    /// A face refers to a vertex that does not exist.
    #[error(
        "{}, {at}: a face refers to vertex {index} (as written in the file), but the file has \
         {n_vertices} vertices; the file is corrupt, export it again",
        path.display()
    )]
    IndexOutOfRange {
        /// The file.
        path: PathBuf,
        /// Where the face is.
        at: Location,
        /// The index as written in the file (1-based or negative for OBJ, 0-based otherwise).
        index: i64,
        /// Number of vertices in the file.
        n_vertices: usize,
    },

    /// A vertex coordinate is NaN or infinite.
    #[error(
        "{}, {at}: a vertex coordinate is not a finite number (NaN or infinity); fix or delete \
         that vertex in the source data",
        path.display()
    )]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Where the vertex is.
        at: Location,
    },

    /// Vertices but no faces.
    #[error(
        "{}: the file has {n_vertices} vertices but no faces (a point cloud); capmesh needs a \
         triangulated surface, reconstruct one first (MeshLab: 'Surface Reconstruction: \
         Screened Poisson')",
        path.display()
    )]
    NoFaces {
        /// The file.
        path: PathBuf,
        /// Number of vertices read.
        n_vertices: usize,
    },

    /// A PLY feature capmesh does not read.
    #[error(
        "{}: unsupported PLY file: {message}; save it again as a PLY with vertex x, y, z and \
         face vertex_indices (MeshLab: File > Export Mesh As > PLY)",
        path.display()
    )]
    UnsupportedPly {
        /// The file.
        path: PathBuf,
        /// What is unsupported.
        message: String,
    },

    /// A vertex property asked for by name that the PLY file does not have.
    #[error(
        "{}: the PLY vertex element has no property '{name}' (its properties: {available}); \
         name one of them, or pass a per-vertex data file (.gii, FreeSurfer curv)",
        path.display()
    )]
    NoPlyProperty {
        /// The file.
        path: PathBuf,
        /// The property asked for.
        name: String,
        /// The vertex element's properties, comma-separated.
        available: String,
    },

    /// A GIFTI feature capmesh does not read.
    #[error(
        "{}, {at}: unsupported GIFTI file: {message}; save it again as a GIFTI with ASCII, \
         Base64Binary or GZipBase64Binary arrays (e.g. with nibabel or 'wb_command \
         -gifti-convert')",
        path.display()
    )]
    UnsupportedGifti {
        /// The file.
        path: PathBuf,
        /// Where (the line of the data array).
        at: Location,
        /// What is unsupported.
        message: String,
    },

    /// A file of per-vertex data (or a surface) was given where the other was expected.
    #[error("{}: {message}", path.display())]
    WrongKind {
        /// The file.
        path: PathBuf,
        /// What the file holds and what to do instead.
        message: String,
    },

    /// Per-vertex data for a different number of vertices than the mesh has.
    #[error(
        "{}: '{name}' has values for {found} vertices but the mesh has {expected}; the data \
         belong to another surface (e.g. fsaverage5 data on an fsaverage surface), use the \
         surface they were computed on",
        path.display()
    )]
    AttributeLength {
        /// The file.
        path: PathBuf,
        /// The attribute's name.
        name: String,
        /// Values in the file.
        found: usize,
        /// Vertices of the mesh.
        expected: usize,
    },
}

/// Why a mesh file could not be written.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum WriteError {
    /// The file could not be created or written.
    #[error("cannot write {}: {source}; {}", path.display(), write_hint(source))]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },

    /// The extension is not one of the supported formats.
    #[error(
        "{}: unknown mesh format '{extension}'; capmesh writes .obj, .ply, .off, .stl and .gii \
         files and FreeSurfer surfaces (.pial, .white, .inflated, .sphere, .orig, .smoothwm), \
         optionally gzip-compressed (.obj.gz, ...)",
        path.display()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Its extension (empty when it has none).
        extension: String,
    },

    /// The mesh refers to a vertex that does not exist.
    #[error(
        "{}: not written: face {face} refers to vertex {index}, but the mesh has {n_vertices} \
         vertices (a bug in the code that built the mesh)",
        path.display()
    )]
    IndexOutOfRange {
        /// The file.
        path: PathBuf,
        /// Face index.
        face: usize,
        /// Offending vertex index.
        index: u32,
        /// Number of vertices.
        n_vertices: usize,
    },

    /// A coordinate is NaN or infinite.
    #[error(
        "{}: not written: vertex {vertex} has a non-finite coordinate (NaN or infinity)",
        path.display()
    )]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Vertex index.
        vertex: usize,
    },

    /// The format cannot store this mesh.
    #[error("{}: not written: {message}", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// Why, and what to use instead.
        message: String,
    },
}

/// What to do about an operating-system error while writing a file.
fn write_hint(error: &std::io::Error) -> &'static str {
    #[cfg(unix)]
    if let Some(code) = error.raw_os_error() {
        match code {
            libc::ENOSPC => return "the disk is full: free space or write elsewhere; the earlier file of that name, if any, is untouched",
            libc::EDQUOT => return "the disk quota is used up: free space or write elsewhere; the earlier file of that name, if any, is untouched",
            libc::EFBIG => return "the file is larger than the limit on file size (ulimit -f) or the file system allows: raise the limit or write elsewhere",
            libc::EISDIR => return "the path is a directory: give a file name (for example DIR/out.ply)",
            libc::ENOTDIR => return "a part of the path is not a directory: check the path",
            libc::EROFS => return "the file system is read-only: write elsewhere",
            _ => {}
        }
    }
    match error.kind() {
        std::io::ErrorKind::NotFound => "the directory does not exist: create it first or check the path",
        std::io::ErrorKind::PermissionDenied => "the directory or the file is not writable: change its permissions or write elsewhere",
        _ => "check that the directory exists, is writable and has free space",
    }
}
