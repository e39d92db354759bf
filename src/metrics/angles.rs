//! Triangle shape by angles: the mean over faces of each face's smallest angle, the share of
//! faces with an angle below 30 degrees, and the largest and smallest angles of the mesh.
//!
//! An equilateral mesh has 60 degrees everywhere; a remesh is called well shaped when its
//! mean smallest angle is near 50 degrees or more and few faces have an angle below 30
//! (issue 26). A face with a zero-length edge or zero area counts with a smallest angle of 0
//! and a largest of 180 degrees (the limits of a collapsing triangle).

use crate::mesh::geometry::triangle_angles;
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Angle below which a face counts as a sliver in [`AngleQuality::share_below_30`].
pub const SLIVER_ANGLE_DEG: f64 = 30.0;

/// Angle statistics of a triangle mesh, in degrees.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct AngleQuality {
    /// Mean over faces of the face's smallest angle.
    pub mean_min_angle_deg: f64,
    /// Share (0-1) of faces with an angle below [`SLIVER_ANGLE_DEG`].
    pub share_below_30: f64,
    /// Smallest angle of any face.
    pub min_angle_deg: f64,
    /// Largest angle of any face.
    pub max_angle_deg: f64,
}

/// Smallest and largest angle of a face, degrees (0 and 180 for a degenerate face).
pub fn face_angle_range(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> (f64, f64) {
    let t = triangle_angles(a, b, c);
    let lo = t[0].min(t[1]).min(t[2]).to_degrees();
    let hi = t[0].max(t[1]).max(t[2]).to_degrees();
    // A zero-area face: all three corners read 0 (atan2(0, x >= 0)), or 0 and 180.
    let sum = (t[0] + t[1] + t[2]).to_degrees();
    if !lo.is_finite() || !hi.is_finite() || (sum - 180.0).abs() > 1e-6 {
        return (0.0, 180.0);
    }
    (lo, hi)
}

/// [`AngleQuality`] of `mesh` (all zero for a mesh without faces). The mean is summed in
/// face order, whatever the thread count.
pub fn angle_quality(mesh: &TriMesh) -> AngleQuality {
    angle_quality_of(&mesh.vertices, &mesh.faces)
}

/// [`angle_quality`] of the faces `faces` on `vertices`.
pub fn angle_quality_of(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> AngleQuality {
    if faces.is_empty() {
        return AngleQuality::default();
    }
    let ranges: Vec<(f64, f64)> = faces
        .par_iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| vertices[v as usize]);
            face_angle_range(a, b, c)
        })
        .collect();
    let n = ranges.len() as f64;
    AngleQuality {
        mean_min_angle_deg: ranges.iter().map(|r| r.0).sum::<f64>() / n,
        share_below_30: ranges.iter().filter(|r| r.0 < SLIVER_ANGLE_DEG).count() as f64 / n,
        min_angle_deg: ranges.iter().map(|r| r.0).fold(f64::INFINITY, f64::min),
        max_angle_deg: ranges.iter().map(|r| r.1).fold(0.0, f64::max),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::{grid_disk, icosphere};

    /// A flat equilateral strip: every angle 60 degrees.
    #[test]
    fn equilateral_mesh() {
        let h = 3f64.sqrt() / 2.0;
        let mut vertices = Vec::new();
        for row in 0..4 {
            for i in 0..6 {
                vertices.push([i as f64 + 0.5 * (row % 2) as f64, row as f64 * h, 0.0]);
            }
        }
        let mut faces = Vec::new();
        for row in 0..3u32 {
            for i in 0..5u32 {
                let (a, b, c, d) = (row * 6 + i, row * 6 + i + 1, (row + 1) * 6 + i, (row + 1) * 6 + i + 1);
                if row % 2 == 0 {
                    faces.push([a, b, c]);
                    faces.push([b, d, c]);
                } else {
                    faces.push([a, b, d]);
                    faces.push([a, d, c]);
                }
            }
        }
        let q = angle_quality(&TriMesh::new(vertices, faces));
        for x in [q.mean_min_angle_deg, q.min_angle_deg, q.max_angle_deg] {
            assert!((x - 60.0).abs() < 1e-9, "{q:?}");
        }
        assert_eq!(q.share_below_30, 0.0);
    }

    /// The statistics against angles computed from the law of cosines, face by face.
    #[test]
    fn matches_law_of_cosines() {
        for mesh in [icosphere(2), grid_disk(6)] {
            let q = angle_quality(&mesh);
            let mut mins = Vec::new();
            let mut maxs: f64 = 0.0;
            for f in &mesh.faces {
                let p = f.map(|v| mesh.vertices[v as usize]);
                let len = |i: usize, j: usize| crate::mesh::geometry::norm(crate::mesh::geometry::sub(p[i], p[j]));
                let (a, b, c) = (len(1, 2), len(2, 0), len(0, 1));
                let ang = [((b * b + c * c - a * a) / (2.0 * b * c)).acos(), ((c * c + a * a - b * b) / (2.0 * c * a)).acos(), ((a * a + b * b - c * c) / (2.0 * a * b)).acos()].map(f64::to_degrees);
                mins.push(ang.iter().cloned().fold(f64::INFINITY, f64::min));
                maxs = maxs.max(ang.iter().cloned().fold(0.0, f64::max));
            }
            let mean = mins.iter().sum::<f64>() / mins.len() as f64;
            let below = mins.iter().filter(|&&m| m < 30.0).count() as f64 / mins.len() as f64;
            assert!((q.mean_min_angle_deg - mean).abs() < 1e-9);
            assert!((q.max_angle_deg - maxs).abs() < 1e-9);
            assert_eq!(q.share_below_30, below);
        }
    }

    #[test]
    fn degenerate_face_counts_as_sliver() {
        let mesh = TriMesh::new(vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2], [0, 1, 3]]);
        let q = angle_quality(&mesh);
        assert_eq!(q.min_angle_deg, 0.0);
        assert_eq!(q.max_angle_deg, 180.0);
        assert_eq!(q.share_below_30, 0.5);
        assert!((q.mean_min_angle_deg - 22.5).abs() < 1e-9);
    }
}
