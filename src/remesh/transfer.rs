//! Per-vertex data carried from the input surface to the remesh through the inverse map
//! (what Connectome Workbench's surface resampling does for neuroimaging data): each remesh
//! vertex is a point of an input face ([`SurfacePoint`]); continuous values are interpolated
//! with its barycentric coordinates, integer labels take the value of the face's corner with
//! the largest weight (no blending: a label between two regions is one of them).

use crate::cap::{InverseMap, SurfacePoint};
use crate::io::{AttributeData, VertexAttribute};
use crate::mesh::geometry::{dot, sub};
use crate::mesh::TriMesh;
use crate::metrics::closest::closest_on_triangle;
use rayon::prelude::*;

/// Relative distance (of the surface's bounding-box diagonal) within which a remesh vertex's
/// lift through its planar point counts as its position.
const SAME_POINT: f64 = 1e-9;

/// The input surface point of each remesh vertex at `positions`: the lift of its planar point
/// where it has one (`has_plane`; vertices beyond it, added by the shape stage, are tried) and the lift lands on the position; otherwise (a closed
/// surface's bottom, a boundary vertex placed along the input's boundary) the nearest point of
/// the input's faces.
pub(crate) fn surface_points(inverse: &InverseMap, planar: &[[f64; 2]], has_plane: &[bool], positions: &[[f64; 3]]) -> Vec<SurfacePoint> {
    let mesh = inverse.mesh();
    let tol = SAME_POINT * mesh.bounding_box_diagonal();
    positions
        .par_iter()
        .enumerate()
        .map(|(v, &x)| {
            if has_plane.get(v).copied().unwrap_or(true) {
                if let Some(p) = planar.get(v).and_then(|&q| inverse.locate_plane(q)) {
                    if dot(sub(p.position, x), sub(p.position, x)).sqrt() <= tol {
                        return p;
                    }
                }
            }
            nearest(mesh, x)
        })
        .collect()
}

/// The nearest point of `mesh`'s faces to `x` (every face: used for the few vertices the
/// inverse map does not place).
fn nearest(mesh: &TriMesh, x: [f64; 3]) -> SurfacePoint {
    let mut best = (f64::INFINITY, 0usize, [0.0; 3]);
    for (f, t) in mesh.faces.iter().enumerate() {
        let [a, b, c] = t.map(|v| mesh.vertices[v as usize]);
        let p = closest_on_triangle(x, a, b, c);
        let d = dot(sub(p, x), sub(p, x));
        if d < best.0 {
            best = (d, f, p);
        }
    }
    let (_, face, p) = best;
    let [a, b, c] = mesh.faces[face].map(|v| mesh.vertices[v as usize]);
    SurfacePoint { face, barycentric: barycentric(p, a, b, c), position: p }
}

/// Barycentric coordinates of `p` (a point of triangle `abc`), clamped to the triangle.
fn barycentric(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let (v0, v1, v2) = (sub(b, a), sub(c, a), sub(p, a));
    let (d00, d01, d11, d20, d21) = (dot(v0, v0), dot(v0, v1), dot(v1, v1), dot(v2, v0), dot(v2, v1));
    let den = d00 * d11 - d01 * d01;
    if !(den.abs() > 0.0) {
        return [1.0, 0.0, 0.0];
    }
    let w1 = ((d11 * d20 - d01 * d21) / den).max(0.0);
    let w2 = ((d00 * d21 - d01 * d20) / den).max(0.0);
    let w0 = (1.0 - w1 - w2).max(0.0);
    let s = w0 + w1 + w2;
    [w0 / s, w1 / s, w2 / s]
}


/// `attribute` (one value per vertex of `mesh`) at the surface points `points`: scalars
/// interpolated, labels from the corner of largest weight. The name and label table are kept.
pub fn carry_attribute(mesh: &TriMesh, points: &[SurfacePoint], attribute: &VertexAttribute) -> VertexAttribute {
    let corners = |p: &SurfacePoint| mesh.faces[p.face].map(|v| v as usize);
    let data = match &attribute.data {
        AttributeData::Scalar(values) => AttributeData::Scalar(
            points
                .iter()
                .map(|p| {
                    let [a, b, c] = corners(p);
                    let w = p.barycentric;
                    (w[0] * f64::from(values[a]) + w[1] * f64::from(values[b]) + w[2] * f64::from(values[c])) as f32
                })
                .collect(),
        ),
        AttributeData::Label(values) => AttributeData::Label(
            points
                .iter()
                .map(|p| {
                    let k = (0..3).max_by(|&i, &j| p.barycentric[i].total_cmp(&p.barycentric[j])).unwrap_or(0);
                    values[corners(p)[k]]
                })
                .collect(),
        ),
    };
    VertexAttribute { name: attribute.name.clone(), data, label_table: attribute.label_table.clone() }
}
