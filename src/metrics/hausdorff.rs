//! One-sided Hausdorff distance from a remesh to its original: the largest distance from a
//! point sampled on the remesh's faces ([`super::sampling::face_samples`]) to the original
//! surface. Where the mean sampled distance says how closely a remesh follows the surface on
//! the whole, this says how far its worst chord strays (across a thin part, a fold, a crease).
//!
//! Being a maximum over four samples per face (edges and corners are not sampled), it is a
//! lower bound of the exact one-sided Hausdorff distance of the continuous surfaces; the two
//! meet as the faces get small against the surface's features.

/// Largest of `d` (0 when empty).
pub fn max_distance(d: &[f64]) -> f64 {
    d.iter().cloned().fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::closest::closest_on_triangle;
    use crate::mesh::geometry::{norm, sub};
    use crate::mesh::shapes::{grid_disk, icosphere};
    use crate::metrics::closest::SurfaceDistance;
    use crate::metrics::sampling::{distances, face_samples};
    use crate::mesh::TriMesh;

    /// The largest distance from the face samples of `from` to `to`, as the remesh metrics
    /// take it ([`crate::metrics::remeshing`]).
    fn one_sided_hausdorff(from: &TriMesh, to: &SurfaceDistance) -> f64 {
        max_distance(&distances(&face_samples(from), to))
    }

    /// A disk lifted by `h` above itself is `h` away everywhere.
    #[test]
    fn lifted_disk() {
        let disk = grid_disk(8);
        let mut lifted = disk.clone();
        for p in &mut lifted.vertices {
            p[2] += 0.125;
        }
        let d = one_sided_hausdorff(&lifted, &SurfaceDistance::new(&disk));
        assert!((d - 0.125).abs() < 1e-12, "{d}");
        assert!(one_sided_hausdorff(&disk, &SurfaceDistance::new(&disk)) < 1e-15);
    }

    /// Against the brute-force minimum over every face, for a coarse sphere against a fine
    /// one, in both directions.
    #[test]
    fn matches_brute_force() {
        let (coarse, fine) = (icosphere(1), icosphere(3));
        for (from, to) in [(&coarse, &fine), (&fine, &coarse)] {
            let brute = face_samples(from)
                .iter()
                .map(|&p| {
                    to.faces
                        .iter()
                        .map(|t| {
                            let q = t.map(|v| to.vertices[v as usize]);
                            norm(sub(p, closest_on_triangle(p, q[0], q[1], q[2])))
                        })
                        .fold(f64::INFINITY, f64::min)
                })
                .fold(0.0, f64::max);
            let fast = one_sided_hausdorff(from, &SurfaceDistance::new(to));
            assert!((fast - brute).abs() <= 1e-12, "{fast} vs {brute}");
            assert!(fast > 0.01);
        }
    }
}
