//! Reading and writing meshes through OpenMesh (feature `openmesh`, links Debian's
//! `libopenmesh-dev`): every format OpenMesh knows, notably its own binary `.om`, plus `.obj`,
//! `.off`, `.ply` and `.stl`, for users whose tools speak OpenMesh.
//!
//! Points cross as `f64` (OpenMesh mesh with `Vec3d` points) and `.om` round trips are exact,
//! but OpenMesh's `.off`, `.ply`, `.obj` and `.stl` writers store single precision. Polygons
//! are triangulated by OpenMesh on reading. Writing refuses meshes OpenMesh cannot store (non-manifold edges or
//! vertices) with an error instead of dropping faces.
//!
//! ```no_run
//! # #[cfg(feature = "openmesh")] {
//! use capmesh::openmesh;
//! let mesh = openmesh::read(std::path::Path::new("face.om"))?;
//! openmesh::write(std::path::Path::new("face.off"), &mesh, &openmesh::WriteOptions::default())?;
//! # }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod bridge;

use std::path::Path;

use crate::mesh::TriMesh;

/// Why OpenMesh could not read or write a mesh.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OpenMeshError {
    /// The path is not valid UTF-8 (OpenMesh takes a C++ string).
    #[error("the path {0:?} is not valid UTF-8; rename the file")]
    Path(std::path::PathBuf),
    /// OpenMesh's reader failed.
    #[error("{0}")]
    Read(String),
    /// OpenMesh's writer failed or refused a face.
    #[error("{0}")]
    Write(String),
    /// The mesh to write refers to vertices it does not have.
    #[error("cannot write: face {face} refers to vertex {index}, but the mesh has {n_vertices} vertices")]
    IndexOutOfRange {
        /// Face index.
        face: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices.
        n_vertices: usize,
    },
}

/// Options of [`write()`]. Build them from [`WriteOptions::default`] with the `with_*` setters:
/// new options may be added without notice.
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct WriteOptions {
    /// Binary output for the formats that have one (`.ply`, `.stl`, `.off`; `.om` is always
    /// binary). Default `false`.
    pub binary: bool,
}

impl WriteOptions {
    /// Set [`WriteOptions::binary`].
    pub fn with_binary(mut self, binary: bool) -> Self {
        self.binary = binary;
        self
    }
}

fn utf8(path: &Path) -> Result<&str, OpenMeshError> {
    path.to_str().ok_or_else(|| OpenMeshError::Path(path.to_path_buf()))
}

/// Read a mesh file with OpenMesh (format from the extension).
pub fn read(path: &Path) -> Result<TriMesh, OpenMeshError> {
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    bridge::ffi::read_mesh(utf8(path)?, &mut positions, &mut triangles).map_err(|e| OpenMeshError::Read(e.what().to_string()))?;
    Ok(TriMesh::new(
        positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
        triangles.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    ))
}

/// Write `mesh` with OpenMesh (format from the extension).
pub fn write(path: &Path, mesh: &TriMesh, options: &WriteOptions) -> Result<(), OpenMeshError> {
    let n_vertices = mesh.n_vertices();
    for (face, f) in mesh.faces.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&i| i as usize >= n_vertices) {
            return Err(OpenMeshError::IndexOutOfRange { face, index, n_vertices });
        }
    }
    let positions: Vec<f64> = mesh.vertices.iter().flatten().copied().collect();
    let triangles: Vec<u32> = mesh.faces.iter().flatten().copied().collect();
    utf8(path)?;
    // Through a temporary next to `path` (it keeps the extension OpenMesh chooses the format
    // by), renamed over `path` when complete: see `crate::io::atomic`.
    let staged = crate::io::atomic::stage_path(path, |temp| {
        let temp = temp.to_str().ok_or_else(|| std::io::Error::other("the temporary's path is not valid UTF-8"))?;
        bridge::ffi::write_mesh(temp, &positions, &triangles, options.binary).map_err(|e| std::io::Error::other(e.what().to_string()))
    })
    .map_err(|e| OpenMeshError::Write(e.to_string()))?;
    staged.commit().map_err(|e| OpenMeshError::Write(crate::io::WriteError::Io { path: path.to_path_buf(), source: e }.to_string()))
}
