//! Checking that a mesh is something capmesh can map: an oriented manifold that is a single
//! open disk or a single closed genus-0 surface.
//!
//! [`inspect`] reports hard errors (broken indices, non-finite coordinates, non-manifold or
//! inconsistently oriented input) and otherwise summarises the mesh; [`validate`] additionally
//! requires one component, genus 0 and at most one boundary loop.
//!
//! Unreferenced vertices and zero-area faces are *not* errors here: they are counted in the
//! summary, [`crate::mesh::repair::weld_coincident`] removes them (with the coincident vertices
//! that usually cause zero-area faces), and [`require_clean`] turns them into errors for code
//! that cannot cope with them.

use std::fmt;

use serde::Serialize;

use crate::mesh::error::MeshError;
use crate::mesh::geometry::{norm, sub, triangle_area};
use crate::mesh::repair::{
    coincident_vertices, default_weld_tolerance, zero_area_faces, DEFAULT_ZERO_AREA_REL_TOL,
};
use crate::mesh::checks::{check_indices, check_not_empty};
use crate::mesh::topology::Topology;
use crate::mesh::TriMesh;

/// The two kinds of surface capmesh maps onto a spherical cap.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceKind {
    /// One boundary loop, genus 0.
    OpenDisk,
    /// No boundary, genus 0.
    ClosedSphere,
}

impl fmt::Display for SurfaceKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SurfaceKind::OpenDisk => "open disk",
            SurfaceKind::ClosedSphere => "closed genus-0",
        })
    }
}

/// What [`inspect`] found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshSummary {
    /// Number of vertices (including unreferenced ones).
    pub n_vertices: usize,
    /// Number of faces.
    pub n_faces: usize,
    /// Number of edges.
    pub n_edges: usize,
    /// Number of boundary loops.
    pub boundary_loops: usize,
    /// Number of connected components.
    pub n_components: usize,
    /// `V - E + F` over referenced vertices.
    pub euler_characteristic: i64,
    /// Genus when there is a single component.
    pub genus: Option<i64>,
    /// `Some` for a single-component open disk or closed genus-0 surface.
    pub kind: Option<SurfaceKind>,
    /// Faces with (relative) zero area, see [`crate::mesh::repair::zero_area_faces`].
    pub zero_area_faces: usize,
    /// Vertices within `1e-9 x` bounding-box diagonal of another vertex (the number that
    /// welding would merge away; equals the number of pairs when they come in pairs).
    pub coincident_vertex_pairs: usize,
    /// Vertices used by no face.
    pub unreferenced_vertices: usize,
    /// The boundary loops' total length against the square root of the surface's area (0 when
    /// closed; see [`SMALL_BOUNDARY`]).
    pub boundary_length_ratio: f64,
}

/// Boundary length, against the square root of the area, below which an open surface looks
/// like a closed one with a hole (missing faces), which the mapping treats as a disk: the
/// bundled open surfaces have 1.1-3.7, the closed hippocampus without two faces 0.13.
pub const SMALL_BOUNDARY: f64 = 0.25;

/// The boundary loops' total length over the square root of the area of `mesh`, whose
/// topology is `topology` (0 for a closed surface or one without area).
pub fn boundary_length_ratio(mesh: &TriMesh, topology: &Topology) -> f64 {
    let at = |v: u32| mesh.vertices[v as usize];
    let length: f64 = topology.boundary_loops.iter().flat_map(|l| l.iter().zip(l.iter().cycle().skip(1))).map(|(&a, &b)| norm(sub(at(a), at(b)))).sum();
    let area: f64 = mesh.faces.iter().map(|f| triangle_area(at(f[0]), at(f[1]), at(f[2]))).sum();
    if area > 0.0 { length / area.sqrt() } else { 0.0 }
}

/// For an open surface whose boundary is shorter than [`SMALL_BOUNDARY`] of the square root
/// of its area: its boundary edges and that ratio (a closed surface with a hole?). `None`
/// otherwise, and for a mesh that is not a valid surface.
pub fn small_boundary(mesh: &TriMesh) -> Option<(usize, f64)> {
    small_boundary_of(mesh, &Topology::build(mesh).ok()?)
}

/// [`small_boundary`] of `mesh` whose topology is `topology` (built already).
pub(crate) fn small_boundary_of(mesh: &TriMesh, topology: &Topology) -> Option<(usize, f64)> {
    let edges: usize = topology.boundary_loops.iter().map(|l| l.len()).sum();
    let ratio = boundary_length_ratio(mesh, topology);
    (edges > 0 && ratio < SMALL_BOUNDARY).then_some((edges, ratio))
}

/// Largest bounding-box side accepted: its fourth power (squared areas) stays below
/// `f64::MAX` (about 1.8e308) with room to spare. (The error message quotes the range.)
pub const MAX_EXTENT: f64 = 1e60;

/// Smallest non-zero bounding-box side accepted: its fourth power stays above the smallest
/// normal `f64` (about 2.2e-308).
pub const MIN_EXTENT: f64 = 1e-60;

/// [`MeshError::NonFiniteCoordinate`] for the first vertex with a NaN or infinite coordinate,
/// then [`MeshError::ScaleOutOfRange`] when the bounding box's largest side is outside
/// [`MIN_EXTENT`]..[`MAX_EXTENT`] (a bunny scaled by 1e200 was refused as "not positive
/// definite", by 1e-200 as having no interior edge: its lengths squared had overflowed or
/// underflowed).
pub fn check_finite(mesh: &TriMesh) -> Result<(), MeshError> {
    if let Some(vertex) = mesh.vertices.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(MeshError::NonFiniteCoordinate { vertex });
    }
    // The largest side, not the diagonal: squaring the sides could overflow already.
    let extent = mesh.bounding_box().map_or(0.0, |(lo, hi)| (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max));
    if extent > MAX_EXTENT || (extent > 0.0 && extent < MIN_EXTENT) {
        return Err(MeshError::ScaleOutOfRange { exponent: extent.log10().round() as i32 });
    }
    Ok(())
}

/// The kind of a single-component surface from its topology.
pub fn classify(topology: &Topology) -> Option<SurfaceKind> {
    if topology.n_components != 1 || topology.genus() != Some(0) {
        return None;
    }
    match topology.boundary_loops.len() {
        0 => Some(SurfaceKind::ClosedSphere),
        1 => Some(SurfaceKind::OpenDisk),
        _ => None,
    }
}

fn unreferenced(mesh: &TriMesh) -> Vec<bool> {
    let mut unused = vec![true; mesh.n_vertices()];
    for face in &mesh.faces {
        for &v in face {
            if let Some(u) = unused.get_mut(v as usize) {
                *u = false;
            }
        }
    }
    unused
}

/// The hard checks shared by [`inspect`] and [`validate`].
pub(crate) fn checked_topology(mesh: &TriMesh) -> Result<Topology, MeshError> {
    check_not_empty(mesh)?;
    check_indices(mesh)?;
    check_finite(mesh)?;
    Topology::build(mesh)
}

/// Check for hard errors, in this order: [`MeshError::Empty`],
/// [`MeshError::IndexOutOfRange`], [`MeshError::NonFiniteCoordinate`],
/// [`MeshError::DegenerateFace`], [`MeshError::DuplicateFace`],
/// [`MeshError::NonManifoldEdge`], [`MeshError::InconsistentOrientation`],
/// [`MeshError::NonManifoldVertex`]; otherwise summarise the mesh. `kind` is `None` when the
/// mesh is neither a single-component disk nor a single-component closed genus-0 surface.
pub fn inspect(mesh: &TriMesh) -> Result<MeshSummary, MeshError> {
    let topology = checked_topology(mesh)?;
    Ok(MeshSummary {
        n_vertices: topology.n_vertices,
        n_faces: topology.n_faces,
        n_edges: topology.n_edges,
        boundary_loops: topology.boundary_loops.len(),
        n_components: topology.n_components,
        euler_characteristic: topology.euler_characteristic,
        genus: topology.genus(),
        kind: classify(&topology),
        zero_area_faces: zero_area_faces(mesh, DEFAULT_ZERO_AREA_REL_TOL).len(),
        coincident_vertex_pairs: coincident_vertices(mesh, default_weld_tolerance(mesh)),
        unreferenced_vertices: unreferenced(mesh).iter().filter(|&&u| u).count(),
        boundary_length_ratio: boundary_length_ratio(mesh, &topology),
    })
}

/// [`inspect`], then require a single component ([`MeshError::SeveralComponents`]), genus 0
/// ([`MeshError::NotSimplyConnected`]) and at most one boundary loop
/// ([`MeshError::SeveralBoundaryLoops`]). `Ok` means a single-component open disk or closed
/// genus-0 surface.
///
/// Unreferenced vertices and zero-area faces are accepted (see the module docs); weld first
/// with [`crate::mesh::repair::weld_coincident`], or call [`require_clean`].
pub fn validate(mesh: &TriMesh) -> Result<(SurfaceKind, Topology), MeshError> {
    classify_checked(checked_topology(mesh)?)
}

/// [`validate`]'s checks after [`checked_topology`], on its result.
pub(crate) fn classify_checked(topology: Topology) -> Result<(SurfaceKind, Topology), MeshError> {
    if topology.n_components > 1 {
        return Err(MeshError::SeveralComponents {
            count: topology.n_components,
        });
    }
    let loops = topology.boundary_loops.len();
    let genus = (2 - topology.euler_characteristic - loops as i64).div_euclid(2);
    if genus != 0 {
        return Err(MeshError::NotSimplyConnected {
            genus,
            boundary_loops: loops,
        });
    }
    if loops > 1 {
        return Err(MeshError::SeveralBoundaryLoops { count: loops });
    }
    match classify(&topology) {
        Some(kind) => Ok((kind, topology)),
        None => Err(MeshError::NotSimplyConnected {
            genus,
            boundary_loops: loops,
        }),
    }
}

/// [`MeshError::UnreferencedVertex`] for the first vertex no face uses, then
/// [`MeshError::ZeroAreaFace`] for the first face with area at most `zero_area_rel_tol` times
/// its longest edge squared. Meshes returned by
/// [`crate::mesh::repair::weld_coincident`] never have unreferenced vertices.
pub fn require_clean(mesh: &TriMesh, zero_area_rel_tol: f64) -> Result<(), MeshError> {
    if let Some(vertex) = unreferenced(mesh).iter().position(|&u| u) {
        return Err(MeshError::UnreferencedVertex { vertex });
    }
    if let Some(&face) = zero_area_faces(mesh, zero_area_rel_tol).first() {
        return Err(MeshError::ZeroAreaFace { face });
    }
    Ok(())
}
