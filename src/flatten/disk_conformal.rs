//! Disk conformal map of a simply-connected open surface (paper Sec. 3.1.1; the paper uses
//! Choi and Lui 2015, we compute the same map, the discrete Riemann map onto the unit disk, by
//! conformal boundary scaling).
//!
//! The boundary correspondence of a conformal map onto the disk is found by the discrete
//! Yamabe equation of boundary-first flattening (Sawhney and Crane 2017): with the cotangent
//! Laplacian `L` and angle defects `Omega` (interior `2 pi - sum theta`, boundary
//! `pi - sum theta`), the log scale factor `u` solving `L u = Omega_target - Omega` gives a flat
//! metric whose boundary curvature is the target. The target for a circle gives each boundary
//! vertex curvature proportional to its (rescaled) dual boundary length; a few fixed-point
//! iterations settle it. The boundary vertices are then placed on the unit circle by rescaled
//! arc length and the interior follows by harmonic extension, which for conformal boundary data
//! is the conformal map. Finally a disk automorphism centres the vertex areas.

use super::harmonic::{count_flipped, harmonic_extension, HarmonicWeights};
use super::mobius::center_by_mobius;
use super::FlattenError;
use crate::linalg::{cotangent_weights, SpdSolver};
use crate::mesh::geometry::{angle_sums, norm, sub, vertex_areas};
use std::f64::consts::PI;

/// Options of the disk conformal map. Build them from [`DiskConformalOptions::default`] with
/// the `with_*` setters: new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct DiskConformalOptions {
    /// Fixed-point iterations of the boundary scaling. Default 30.
    pub max_iterations: usize,
    /// Stop when boundary angles move less than this (radians). Default `1e-6`.
    pub tolerance: f64,
    /// Centre the area-weighted centroid by a disk automorphism. Default true.
    pub center: bool,
}

impl Default for DiskConformalOptions {
    fn default() -> Self {
        Self { max_iterations: 30, tolerance: 1e-6, center: true }
    }
}

impl DiskConformalOptions {
    /// Set [`DiskConformalOptions::max_iterations`].
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Set [`DiskConformalOptions::tolerance`].
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Set [`DiskConformalOptions::center`].
    pub fn with_center(mut self, center: bool) -> Self {
        self.center = center;
        self
    }
}

/// What the disk conformal map did.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DiskConformalReport {
    /// Boundary scaling iterations.
    pub iterations: usize,
    /// Weights used by the harmonic extension.
    pub weights: HarmonicWeights,
    /// Faces with non-positive area in the planar map.
    pub flipped_faces: usize,
}

/// Map a disk-like mesh onto the unit disk. `boundary` is its boundary loop, ordered as the
/// boundary edges run in their faces. Returns planar positions.
pub fn disk_conformal_map(
    vertices: &[[f64; 3]],
    faces: &[[u32; 3]],
    boundary: &[u32],
    options: &DiskConformalOptions,
) -> Result<(Vec<[f64; 2]>, DiskConformalReport), FlattenError> {
    let n = vertices.len();
    if boundary.len() < 3 {
        return Err(FlattenError::BoundaryTooShort { len: boundary.len() });
    }
    let weights = cotangent_weights(vertices, faces);
    let mut on_boundary = vec![false; n];
    for &b in boundary {
        on_boundary[b as usize] = true;
    }
    // Angle defects.
    let angle_sum = angle_sums(vertices, faces);
    let omega: Vec<f64> = (0..n)
        .map(|v| if on_boundary[v] { PI - angle_sum[v] } else { 2.0 * PI - angle_sum[v] })
        .collect();
    // Laplacian with vertex `pin` removed (the system is consistent: both sides sum to 0).
    let pin = boundary[0] as usize;
    let mut index = vec![None; n];
    let mut k = 0;
    for v in 0..n {
        if v != pin {
            index[v] = Some(k);
            k += 1;
        }
    }
    let lap = weights.restricted_laplacian(&index, n - 1, |w| w).assemble("conformal scaling")?;
    let mut solver = SpdSolver::new();
    solver.factor(&lap, "conformal scaling")?;

    let m = boundary.len();
    let lengths: Vec<f64> = (0..m)
        .map(|i| norm(sub(vertices[boundary[(i + 1) % m] as usize], vertices[boundary[i] as usize])))
        .collect();
    let mut u: Vec<f64> = vec![0.0; n];
    let mut theta = vec![0.0; m];
    let mut iterations = 0;
    for it in 0..options.max_iterations {
        let scaled: Vec<f64> = (0..m)
            .map(|i| lengths[i] * (0.5 * (u[boundary[i] as usize] + u[boundary[(i + 1) % m] as usize])).exp())
            .collect();
        let total: f64 = scaled.iter().sum();
        // Boundary angles from rescaled arc length.
        let mut acc = 0.0;
        let mut max_move: f64 = 0.0;
        for i in 0..m {
            let t = 2.0 * PI * acc / total;
            max_move = max_move.max((t - theta[i]).abs());
            theta[i] = t;
            acc += scaled[i];
        }
        iterations = it + 1;
        if it > 0 && max_move < options.tolerance {
            break;
        }
        let mut target = vec![0.0; n];
        for i in 0..m {
            let dual = 0.5 * (scaled[(i + m - 1) % m] + scaled[i]);
            target[boundary[i] as usize] = 2.0 * PI * dual / total;
        }
        let mut rhs = vec![vec![0.0; n - 1]];
        for v in 0..n {
            if let Some(i) = index[v] {
                rhs[0][i] = target[v] - omega[v];
            }
        }
        solver.solve_in_place(&mut rhs, "conformal scaling")?;
        for v in 0..n {
            u[v] = index[v].map_or(0.0, |i| rhs[0][i]);
        }
    }
    let fixed: Vec<(u32, [f64; 2])> = boundary.iter().zip(&theta).map(|(&b, &t)| (b, [t.cos(), t.sin()])).collect();
    let (mut uv, used) = harmonic_extension(n, faces, &weights, &fixed)?;
    if count_flipped(&uv, faces) > faces.len() / 2 {
        // The loop ran clockwise: mirror.
        for p in &mut uv {
            p[1] = -p[1];
        }
    }
    if options.center {
        center_by_mobius(&mut uv, &vertex_areas(vertices, faces), boundary);
    }
    let flipped_faces = count_flipped(&uv, faces);
    Ok((uv, DiskConformalReport { iterations, weights: used, flipped_faces }))
}
