//! Errors found while checking a mesh: one variant per cause.
//!
//! Every message says what is wrong, where (0-based face and vertex indices, both end vertices
//! of an edge) and what the user can do about it.

use thiserror::Error;

/// Why a mesh cannot be used (see [`crate::mesh::validate()`]).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no vertices or no faces.
    #[error(
        "the mesh is empty ({n_vertices} vertices, {n_faces} faces): there is no surface to map; \
         export the surface as triangles (not as a point cloud or as lines)"
    )]
    Empty {
        /// Number of vertices.
        n_vertices: usize,
        /// Number of faces.
        n_faces: usize,
    },

    /// A face refers to a vertex that does not exist.
    #[error(
        "face {face} refers to vertex {index}, but the mesh has only {n_vertices} vertices \
         (valid indices 0..{n_vertices}); the file is corrupt or truncated, re-export it"
    )]
    IndexOutOfRange {
        /// Face index.
        face: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices.
        n_vertices: usize,
    },

    /// A vertex coordinate is NaN or infinite.
    #[error(
        "vertex {vertex} has a non-finite coordinate (NaN or infinity); fix or delete that \
         vertex in the source data"
    )]
    NonFiniteCoordinate {
        /// Vertex index.
        vertex: usize,
    },

    /// The coordinates are too large or too small for double precision: squared lengths and
    /// areas (the fourth power of the size) overflow or underflow.
    #[error(
        "the mesh's bounding box is about 1e{exponent} across, outside 1e-60..1e60: its squared \
         lengths and areas overflow or underflow double precision; rescale the coordinates \
         (e.g. to millimetres)"
    )]
    ScaleOutOfRange {
        /// Base-10 exponent of the bounding box's largest side.
        exponent: i32,
    },

    /// A face uses the same vertex twice.
    #[error(
        "face {face} uses a vertex more than once (vertices {} {} {}); remove degenerate faces \
         (MeshLab: 'Remove Duplicate Faces' and 'Remove Zero Area Faces', or weld the mesh)",
        vertices[0], vertices[1], vertices[2]
    )]
    DegenerateFace {
        /// Face index.
        face: usize,
        /// The face's three vertex indices.
        vertices: [u32; 3],
    },

    /// A face has the same vertex set as an earlier face.
    #[error(
        "face {face} has the same three vertices as face {first}; remove duplicate faces: \
         `capmesh remesh` does, the library has capmesh::mesh::repair::remove_duplicate_faces \
         (MeshLab: 'Remove Duplicate Faces')"
    )]
    DuplicateFace {
        /// The later face.
        face: usize,
        /// The earlier face with the same vertices.
        first: usize,
    },

    /// More than two faces share one edge.
    #[error(
        "edge between vertices {a} and {b} is shared by {faces} faces (a surface allows at most 2); \
         repair it in MeshLab with 'Repair non Manifold Edges'"
    )]
    NonManifoldEdge {
        /// Smaller vertex index of the edge.
        a: u32,
        /// Larger vertex index of the edge.
        b: u32,
        /// Number of faces on the edge.
        faces: usize,
    },

    /// Two faces traverse an edge in the same direction.
    #[error(
        "edge from vertex {a} to vertex {b} is used in the same direction by faces {} and {}: \
         the surface is non-orientable or some faces are flipped; make the orientation consistent: \
         `capmesh remesh` flips the faces wound against their neighbours, the library has \
         capmesh::mesh::repair::orient_coherently (MeshLab: 'Re-Orient all faces coherently')",
        faces[0], faces[1]
    )]
    InconsistentOrientation {
        /// Start vertex of the directed edge.
        a: u32,
        /// End vertex of the directed edge.
        b: u32,
        /// The two faces that use `a -> b`.
        faces: [usize; 2],
    },

    /// The faces around a vertex form more than one fan.
    #[error(
        "vertex {vertex} joins {fans} separate fans of faces (the surface touches itself at this \
         point); split it, one vertex per fan: `capmesh remesh`, `param` and `check` do, the library \
         has capmesh::mesh::repair::split_pinched_vertices (MeshLab: 'Split Vertices on Non \
         Manifold Vertices')"
    )]
    NonManifoldVertex {
        /// Vertex index.
        vertex: u32,
        /// Number of separate fans around it.
        fans: usize,
    },

    /// The mesh is made of several separate pieces.
    #[error(
        "the mesh has {count} connected components, but capmesh maps one surface at a time \
         (`remesh` drops pieces holding at most 1% of the area, and with --largest-piece any \
         but the largest); split the components (MeshLab: 'Split in Connected Components') and \
         keep one, or delete small pieces ('Remove Isolated pieces')"
    )]
    SeveralComponents {
        /// Number of components.
        count: usize,
    },

    /// An open surface with more than one boundary loop (e.g. an annulus).
    #[error(
        "the surface has {count} boundary loops, but an open surface must be a disk with exactly \
         one; fill the extra holes (MeshLab: 'Close Holes') or cut the surface so that a single \
         boundary remains"
    )]
    SeveralBoundaryLoops {
        /// Number of boundary loops.
        count: usize,
    },

    /// The surface has handles (genus > 0).
    #[error(
        "the surface has genus {genus} (with {boundary_loops} boundary loops): it has handles and \
         cannot be mapped onto a cap; cut the surface to a disk or remove the handles first"
    )]
    NotSimplyConnected {
        /// Genus.
        genus: i64,
        /// Number of boundary loops.
        boundary_loops: usize,
    },

    /// A vertex that no face uses.
    #[error(
        "vertex {vertex} is not used by any face; remove unreferenced vertices (MeshLab: \
         'Remove Unreferenced Vertices', or capmesh's weld repair)"
    )]
    UnreferencedVertex {
        /// Vertex index.
        vertex: usize,
    },

    /// The mesh is too large for 32-bit indexing of its half-edges.
    #[error(
        "the mesh has {n_faces} faces, more than capmesh supports ({max}); decimate it first \
         (MeshLab: 'Simplification: Quadric Edge Collapse Decimation')"
    )]
    TooLarge {
        /// Number of faces.
        n_faces: usize,
        /// Largest supported number of faces.
        max: usize,
    },

    /// A face with distinct but collinear (or coincident) vertices.
    #[error(
        "face {face} has zero area (its three vertices are distinct but collinear or coincident); \
         weld close vertices or remove it (MeshLab: 'Remove Zero Area Faces')"
    )]
    ZeroAreaFace {
        /// Face index.
        face: usize,
    },
}
