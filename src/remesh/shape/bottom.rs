//! A closed surface's bottom as one vertex (ours; see [`super`]).
//!
//! The cap grid of a closed surface is closed by a flat bottom disk that the pull-back puts
//! onto the punctured quad, two input faces usually smaller than one remesh face: its rim
//! ring and disk come back as a star of slivers. The shape stage replaces them by a single
//! vertex on the quad, fanned to the ring of grid vertices around it. That vertex has no
//! point in the map's plane (the bottom lies outside the planar map), so it stays, its faces
//! are checked on the surface only when a neighbour moves, and its edges are flipped by the
//! last max-min-angle flips only ([`super::flips::flip_to_max_min_angle`]); the neighbours
//! relax to an even fan.

/// The faces, planar points and positions with every vertex from `first_rim` on (the rim
/// ring and the bottom disk) merged into one vertex at `centre`; `None` when the merged
/// vertex's faces do not form a single fan (a grid this does not apply to).
#[allow(clippy::type_complexity)]
pub(crate) fn merge_bottom(faces: &[[u32; 3]], plane: &[[f64; 2]], position: &[[f64; 3]], first_rim: usize, centre: [f64; 3]) -> Option<(Vec<[u32; 3]>, Vec<[f64; 2]>, Vec<[f64; 3]>)> {
    let p = first_rim as u32;
    let merged: Vec<[u32; 3]> = faces
        .iter()
        .map(|f| f.map(|v| v.min(p)))
        .filter(|f| f[0] != f[1] && f[1] != f[2] && f[0] != f[2])
        .collect();
    // The fan: each neighbour of the merged vertex in exactly two of its faces, one cycle.
    let fan: Vec<[u32; 2]> = merged
        .iter()
        .filter_map(|f| (0..3).find(|&k| f[k] == p).map(|k| [f[(k + 1) % 3], f[(k + 2) % 3]]))
        .collect();
    if fan.len() < 3 {
        return None;
    }
    let mut next = std::collections::HashMap::new();
    for &[a, b] in &fan {
        if next.insert(a, b).is_some() {
            return None;
        }
    }
    let (start, mut at, mut steps) = (fan[0][0], fan[0][0], 0);
    loop {
        at = *next.get(&at)?;
        steps += 1;
        if at == start || steps > fan.len() {
            break;
        }
    }
    if at != start || steps != fan.len() {
        return None;
    }
    let mut plane: Vec<[f64; 2]> = plane[..first_rim].to_vec();
    plane.push([0.0, 0.0]);
    let mut position: Vec<[f64; 3]> = position[..first_rim].to_vec();
    position.push(centre);
    Some((merged, plane, position))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::validate;
    use crate::mesh::{SurfaceKind, TriMesh};
    use crate::remesh::grid::{close_bottom, uniform_cap};

    /// The closed cap grid with its rim and bottom merged is still a closed genus-0 mesh, and
    /// the merged vertex has as many neighbours as the ring above the rim has vertices.
    #[test]
    fn a_closed_grid_keeps_its_topology() {
        let cap = uniform_cap(-0.95, 2000);
        let n = cap.vertices.len();
        let rim = cap.vertices.iter().rev().take_while(|q| q[2] == cap.vertices[n - 1][2]).count();
        let grid = close_bottom(cap);
        let plane = vec![[0.0; 2]; grid.mesh.vertices.len()];
        let (faces, _, position) = merge_bottom(&grid.mesh.faces, &plane, &grid.mesh.vertices, n - rim, [0.0, 0.0, -1.0]).unwrap();
        let out = TriMesh::new(position, faces);
        assert_eq!(validate(&out).unwrap().0, SurfaceKind::ClosedSphere);
        assert!(out.faces.len() < grid.mesh.faces.len());
    }
}
