//! Points sampled on the faces of a mesh and their distances to another surface: the base of
//! the face-sampled mean distance and of the one-sided Hausdorff distance.
//!
//! Each face gives four samples: its centroid and the midpoints between the centroid and the
//! corners, so a face's interior is seen whatever its size, and the vertices (which lie on the
//! original surface for every remesher that projects) are not.

use super::closest::SurfaceDistance;
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Sample points on each face of `mesh`, four per face in face order (see the module docs).
pub fn face_samples(mesh: &TriMesh) -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(4 * mesh.n_faces());
    for f in &mesh.faces {
        let [a, b, c] = f.map(|v| mesh.vertices[v as usize]);
        let g = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0];
        out.push(g);
        for p in [a, b, c] {
            out.push([(g[0] + p[0]) / 2.0, (g[1] + p[1]) / 2.0, (g[2] + p[2]) / 2.0]);
        }
    }
    out
}

/// Consecutive samples that share the nearest-face hint of [`distances`].
const HINT_CHUNK: usize = 512;

/// Distance from each point to the surface `to`, in the order of `points`.
///
/// Distances are computed in parallel. Each query starts from the previous one's nearest face
/// (the samples come face by face, so that face bounds the search at once), within fixed
/// chunks: which face ties are broken by, and so the last digits, do not depend on how the
/// threads split the work.
pub fn distances(points: &[[f64; 3]], to: &SurfaceDistance) -> Vec<f64> {
    points
        .par_chunks(HINT_CHUNK)
        .flat_map_iter(|chunk| {
            let mut hint = None;
            chunk.iter().map(move |&p| to.distance_near(p, &mut hint))
        })
        .collect()
}

/// Mean of `d`, summed in order (0 when empty): the figure does not depend on thread timing.
pub fn mean(d: &[f64]) -> f64 {
    if d.is_empty() {
        0.0
    } else {
        d.iter().sum::<f64>() / d.len() as f64
    }
}
