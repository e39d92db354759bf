//! Remeshing quality (paper Sec. 4.2): face area deviation `d_face = mean_T |Area(T) - mean
//! area|` (also divided by the mean area), surface distance `d_surface = mean_v |v - proj(v)|`
//! from the remeshed vertices to the original surface, and, because a pulled-back vertex lies
//! on the surface for every method that projects, a symmetric face-sampled distance (design
//! notes). Distances are also given divided by the original's bounding-box diagonal.

use super::closest::SurfaceDistance;
use crate::mesh::geometry::{face_areas, triangle_angles};
use crate::mesh::repair::{zero_area_faces, DEFAULT_ZERO_AREA_REL_TOL};
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Quality of a remeshed surface against its original.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct RemeshMetrics {
    /// Faces of the remeshed surface.
    pub faces: usize,
    /// Vertices of the remeshed surface.
    pub vertices: usize,
    /// `mean |area - mean area|`.
    pub d_face: f64,
    /// `d_face / mean area`.
    pub d_face_relative: f64,
    /// Mean distance from remeshed vertices to the original surface.
    pub d_surface_vertex: f64,
    /// `d_surface_vertex` / bounding-box diagonal of the original.
    pub d_surface_vertex_relative: f64,
    /// Symmetric mean distance between points sampled on the faces of both surfaces.
    pub d_surface_sampled: f64,
    /// `d_surface_sampled` / bounding-box diagonal of the original.
    pub d_surface_sampled_relative: f64,
    /// Smallest angle of the remeshed surface, degrees.
    pub min_angle_deg: f64,
    /// Faces of the remeshed surface with (relatively) zero area
    /// ([`crate::mesh::repair::zero_area_faces`] at its default tolerance). capmesh's remeshes
    /// have none on the shared meshes and on coarse inputs (tests/remesh.rs; see
    /// [`crate::remesh::pullback::rim_band_into_polygon`] for where they came from).
    pub zero_area_faces: usize,
}

/// Face area deviation `(d_face, d_face / mean area)`.
pub fn face_area_deviation(mesh: &TriMesh) -> (f64, f64) {
    let a = face_areas(&mesh.vertices, &mesh.faces);
    if a.is_empty() {
        return (0.0, 0.0);
    }
    let mean = a.iter().sum::<f64>() / a.len() as f64;
    let d = a.iter().map(|x| (x - mean).abs()).sum::<f64>() / a.len() as f64;
    (d, if mean > 0.0 { d / mean } else { 0.0 })
}

/// Sample points on each face: the centroid and the midpoints between it and the corners.
fn samples(mesh: &TriMesh) -> Vec<[f64; 3]> {
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

/// Consecutive samples that share the nearest-face hint of [`mean_distance`].
const HINT_CHUNK: usize = 512;

fn mean_distance(points: &[[f64; 3]], to: &SurfaceDistance) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    // Distances in parallel, summed in order: the figure does not depend on thread timing.
    // Each query starts from the previous one's nearest face (the samples come face by face,
    // so that face bounds the search at once), within fixed chunks: which face ties are
    // broken by, and so the last digits, do not depend on how the threads split the work.
    let d: Vec<f64> = points
        .par_chunks(HINT_CHUNK)
        .flat_map_iter(|chunk| {
            let mut hint = None;
            chunk.iter().map(move |&p| to.distance_near(p, &mut hint))
        })
        .collect();
    d.iter().sum::<f64>() / points.len() as f64
}

/// All remeshing metrics of `remeshed` against `original`.
pub fn remesh_metrics(original: &TriMesh, remeshed: &TriMesh) -> RemeshMetrics {
    let diag = original.bounding_box_diagonal().max(f64::MIN_POSITIVE);
    let (d_face, d_face_relative) = face_area_deviation(remeshed);
    let to_original = SurfaceDistance::new(original);
    let to_remeshed = SurfaceDistance::new(remeshed);
    let d_vertex = mean_distance(&remeshed.vertices, &to_original);
    let d_sampled = 0.5 * (mean_distance(&samples(remeshed), &to_original) + mean_distance(&samples(original), &to_remeshed));
    let min_angle = remeshed
        .faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| remeshed.vertices[v as usize]);
            triangle_angles(a, b, c).into_iter().fold(f64::INFINITY, f64::min)
        })
        .fold(f64::INFINITY, f64::min)
        .to_degrees();
    RemeshMetrics {
        faces: remeshed.n_faces(),
        vertices: remeshed.n_vertices(),
        d_face,
        d_face_relative,
        d_surface_vertex: d_vertex,
        d_surface_vertex_relative: d_vertex / diag,
        d_surface_sampled: d_sampled,
        d_surface_sampled_relative: d_sampled / diag,
        min_angle_deg: if min_angle.is_finite() { min_angle } else { 0.0 },
        zero_area_faces: zero_area_faces(remeshed, DEFAULT_ZERO_AREA_REL_TOL).len(),
    }
}
