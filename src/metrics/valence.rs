//! Vertex valence: the share of interior vertices (on no boundary edge) joined to exactly six
//! others, the valence of a regular triangulation. Stars of slivers where a pulled-back grid's
//! rings meet show up as vertices of other valence (issue 26).

use crate::mesh::topology::{is_boundary_vertex, vertex_neighbors};
use crate::mesh::TriMesh;

/// Share (0-1) of the interior vertices of `mesh` that have 6 neighbours (0 when there is no
/// interior vertex). Vertices used by no face are not counted.
pub fn interior_valence6_share(mesh: &TriMesh) -> f64 {
    let boundary = is_boundary_vertex(mesh);
    let neighbors = vertex_neighbors(mesh);
    let (mut interior, mut six) = (0usize, 0usize);
    for (v, list) in neighbors.iter().enumerate() {
        if list.is_empty() || boundary[v] {
            continue;
        }
        interior += 1;
        six += usize::from(list.len() == 6);
    }
    if interior == 0 {
        0.0
    } else {
        six as f64 / interior as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::{grid_disk, icosphere};

    #[test]
    fn icosphere_has_twelve_irregular_vertices() {
        // Subdividing the icosahedron keeps its 12 valence-5 vertices; all others have 6.
        let mesh = icosphere(3);
        let n = mesh.n_vertices() as f64;
        assert!((interior_valence6_share(&mesh) - (n - 12.0) / n).abs() < 1e-12);
    }

    #[test]
    fn counts_by_hand_on_an_open_mesh() {
        let mesh = grid_disk(5);
        let boundary = is_boundary_vertex(&mesh);
        let neighbors = vertex_neighbors(&mesh);
        let interior: Vec<usize> = (0..mesh.n_vertices()).filter(|&v| !boundary[v]).collect();
        let six = interior.iter().filter(|&&v| neighbors[v].len() == 6).count();
        assert!(!interior.is_empty());
        assert_eq!(interior_valence6_share(&mesh), six as f64 / interior.len() as f64);
        // One triangle: no interior vertex.
        let tri = TriMesh::new(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2]]);
        assert_eq!(interior_valence6_share(&tri), 0.0);
    }
}
