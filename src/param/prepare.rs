//! The one preparation of a parameterization: the input's hard errors checked, coincident
//! vertices welded and the surface classified, once for every puncture end and `lambda` tried.

use super::options::ParamOptions;
use crate::error::Error;
use crate::mesh::repair::{self, Welded};
use crate::mesh::topology::Topology;
use crate::mesh::validate::{checked_topology, classify, classify_checked};
use crate::mesh::{validate, MeshError, SurfaceKind, TriMesh};
use std::time::Instant;

/// A mesh checked, welded and classified.
pub(crate) struct Prepared {
    /// When the preparation started (the parameterization's wall time counts from here).
    pub(super) start: Instant,
    /// The welded mesh and the map from input vertices to its vertices.
    pub(super) welded: Welded,
    /// The welded mesh's kind.
    pub(super) kind: SurfaceKind,
    /// The welded mesh's topology.
    pub(super) topology: Topology,
    /// Whether the input as given (before welding) is a closed genus-0 surface: only then are
    /// both puncture ends searched ([`super::PunctureEnd::Best`]).
    pub(super) input_closed: bool,
}

/// Check `mesh` (indices, finite coordinates, manifold edges: errors that welding would
/// hide), weld its vertices closer than `options.weld_tolerance` times the bounding-box
/// diagonal, and classify the welded mesh (an error unless it is an open disk or a closed
/// genus-0 surface).
pub(crate) fn prepare(mesh: &TriMesh, options: &ParamOptions) -> Result<Prepared, Error> {
    let start = Instant::now();
    // Hard errors of the input as given (indices out of range, repeated indices in a face,
    // NaN, duplicate faces, non-manifold edges): welding would drop such faces silently.
    let input_topology = checked_topology(mesh)?;
    let input_closed = classify(&input_topology) == Some(SurfaceKind::ClosedSphere);
    let diag = mesh.bounding_box_diagonal();
    let welded = repair::weld_coincident(mesh, options.weld_tolerance * diag);
    // Nothing welded or dropped: the input's topology is the welded mesh's.
    let (welded, (kind, topology)) = if welded.mesh.vertices.len() == mesh.vertices.len() && welded.mesh.faces == mesh.faces {
        (welded, classify_checked(input_topology)?)
    } else {
        match validate(&welded.mesh) {
            Err(MeshError::NonManifoldVertex { .. }) => {
                let split = split_pinches(mesh, welded)?;
                let validated = validate(&split.mesh)?;
                (split, validated)
            }
            validated => (welded, validated?),
        }
    };
    Ok(Prepared { start, welded, kind, topology, input_closed })
}

/// `welded` with the pinched vertices that welding made (coincident vertices of two sheets
/// that touch at a point, or the copies [`repair::split_pinched_vertices`] made of a pinched
/// input) split again, one vertex per fan. `input` is manifold, so each of its vertices has
/// its faces in one fan of the welded vertex: the input vertex goes to that fan's vertex.
fn split_pinches(input: &TriMesh, welded: Welded) -> Result<Welded, Error> {
    let split = repair::split_pinched_vertices(&welded.mesh)?;
    let mut old_to_new = welded.old_to_new.clone();
    // The split keeps every face of the welded mesh, in order.
    for (f, new) in repair::kept_faces(input, &welded.old_to_new).zip(&split.mesh.faces) {
        for (&v, &w) in input.faces[f].iter().zip(new) {
            old_to_new[v as usize] = w;
        }
    }
    Ok(Welded { mesh: split.mesh, old_to_new, split_vertices: welded.split_vertices + split.copy_of.len(), ..welded })
}
