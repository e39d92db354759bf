//! The structural checks that refuse an input with a named [`MeshError`] before any
//! topology is built on it: no faces, an index out of range, a face with a repeated corner, a
//! duplicated face, a pinched vertex (the surface touching itself). [`super::topology`] and
//! [`super::validate`] run them in that order; [`super::repair`] repairs what they name.

use crate::mesh::error::MeshError;
use crate::mesh::topology::{corner_fans, sorted_face, Edge, MAX_FACES};
use crate::mesh::TriMesh;

/// [`MeshError::Empty`] when there are no vertices or no faces.
pub(crate) fn check_not_empty(mesh: &TriMesh) -> Result<(), MeshError> {
    if mesh.vertices.is_empty() || mesh.faces.is_empty() {
        return Err(MeshError::Empty {
            n_vertices: mesh.n_vertices(),
            n_faces: mesh.n_faces(),
        });
    }
    if mesh.n_faces() > MAX_FACES {
        return Err(MeshError::TooLarge {
            n_faces: mesh.n_faces(),
            max: MAX_FACES,
        });
    }
    Ok(())
}

/// [`MeshError::IndexOutOfRange`] for the first face with an invalid vertex index.
pub(crate) fn check_indices(mesh: &TriMesh) -> Result<(), MeshError> {
    let n = mesh.n_vertices();
    for (f, face) in mesh.faces.iter().enumerate() {
        for &v in face {
            if v as usize >= n {
                return Err(MeshError::IndexOutOfRange {
                    face: f,
                    index: v,
                    n_vertices: n,
                });
            }
        }
    }
    Ok(())
}

/// [`MeshError::DegenerateFace`] for the first face with a repeated vertex.
pub(crate) fn check_degenerate(mesh: &TriMesh) -> Result<(), MeshError> {
    for (f, &[a, b, c]) in mesh.faces.iter().enumerate() {
        if a == b || b == c || a == c {
            return Err(MeshError::DegenerateFace {
                face: f,
                vertices: [a, b, c],
            });
        }
    }
    Ok(())
}

/// [`MeshError::DuplicateFace`] for the duplicate with the smallest face index.
pub(crate) fn check_duplicates(mesh: &TriMesh) -> Result<(), MeshError> {
    let mut keyed: Vec<([u32; 3], u32)> = mesh.faces.iter().enumerate().map(|(f, &face)| (sorted_face(face), f as u32)).collect();
    keyed.sort_unstable();
    // (later face, first face) with the smallest later face over all groups of equal faces.
    let mut worst: Option<(usize, usize)> = None;
    let mut i = 0;
    while i < keyed.len() {
        let mut j = i + 1;
        while j < keyed.len() && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        if j - i >= 2 {
            let (first, later) = (keyed[i].1 as usize, keyed[i + 1].1 as usize);
            if worst.map_or(true, |(f, _)| later < f) {
                worst = Some((later, first));
            }
        }
        i = j;
    }
    match worst {
        Some((face, first)) => Err(MeshError::DuplicateFace { face, first }),
        None => Ok(()),
    }
}

/// [`MeshError::NonManifoldVertex`] for the smallest vertex whose face corners form more than
/// one fan ([`corner_fans`]).
pub(crate) fn check_vertex_fans(mesh: &TriMesh, edges: &[Edge]) -> Result<(), MeshError> {
    let faces = &mesh.faces;
    let mut corners = corner_fans(mesh, edges);
    const UNSET: u32 = u32::MAX;
    let mut first_root = vec![UNSET; mesh.n_vertices()];
    let mut bad: Option<u32> = None;
    for (f, face) in faces.iter().enumerate() {
        for (k, &v) in face.iter().enumerate() {
            let root = corners.find((3 * f + k) as u32);
            let slot = &mut first_root[v as usize];
            if *slot == UNSET {
                *slot = root;
            } else if *slot != root && bad.map_or(true, |b| v < b) {
                bad = Some(v);
            }
        }
    }
    let Some(vertex) = bad else { return Ok(()) };
    let mut roots: Vec<u32> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        for (k, &v) in face.iter().enumerate() {
            if v == vertex {
                roots.push(corners.find((3 * f + k) as u32));
            }
        }
    }
    roots.sort_unstable();
    roots.dedup();
    Err(MeshError::NonManifoldVertex {
        vertex,
        fans: roots.len(),
    })
}
