//! The one preparation of a parameterization: the input's hard errors checked, coincident
//! vertices welded and the surface classified, once for every puncture end and `lambda` tried.

use super::options::ParamOptions;
use crate::error::Error;
use crate::mesh::geometry::{norm, sub};
use crate::mesh::repair::{self, Welded};
use crate::mesh::short_edges::collapse_short_edges;
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

/// Shortest edge, as a fraction of the mean edge, that [`without_short_edges`] keeps. On the
/// canonical unfoldiso hippocampal surface of hippunfold-plot (a grid whose first and last
/// rows collapse: 637 faces below a thousandth of the mean area), the transport stalled at
/// every step; with the edges below 1% collapsed (a first prototype) it mapped in 10.7 s,
/// below 5% in 1.4 s (mean |d_area| 0.022 and 0.021; docs/method.md section 23).
pub(crate) const SHORT_EDGE_FRACTION: f64 = 0.05;

/// `prepared` with its edges shorter than [`SHORT_EDGE_FRACTION`] of the mean edge collapsed
/// ([`collapse_short_edges`]), each input vertex going to its vertex there; `None` when no
/// edge could be collapsed. The collapsed mesh keeps the surface's kind.
pub(crate) fn without_short_edges(prepared: &Prepared) -> Result<Option<(Prepared, usize)>, Error> {
    let mesh = &prepared.welded.mesh;
    let (sum, count) = mesh.faces.iter().flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3]))).fold((0.0, 0usize), |(s, c), (a, b)| (s + norm(sub(mesh.vertices[a as usize], mesh.vertices[b as usize])), c + 1));
    if count == 0 {
        return Ok(None);
    }
    let collapsed = collapse_short_edges(mesh, SHORT_EDGE_FRACTION * sum / count as f64);
    if collapsed.merged_vertices == 0 {
        return Ok(None);
    }
    let (kind, topology) = validate(&collapsed.mesh)?;
    if kind != prepared.kind {
        return Err(Error::Internal(format!("collapsing short edges made a {kind:?} of a {:?}", prepared.kind)));
    }
    let old_to_new = prepared.welded.old_to_new.iter().map(|&v| collapsed.old_to_new.get(v as usize).copied().unwrap_or(repair::REMOVED)).collect();
    let edges = collapsed.merged_vertices;
    let welded = Welded {
        old_to_new,
        // The weld's own count (the report gives the collapses apart).
        merged_vertices: prepared.welded.merged_vertices,
        removed_faces: prepared.welded.removed_faces + collapsed.removed_faces,
        removed_unreferenced: prepared.welded.removed_unreferenced + collapsed.removed_unreferenced,
        split_vertices: prepared.welded.split_vertices,
        mesh: collapsed.mesh,
    };
    Ok(Some((Prepared { start: prepared.start, welded, kind, topology, input_closed: prepared.input_closed }, edges)))
}
