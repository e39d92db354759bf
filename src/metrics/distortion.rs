//! Distortion of a parameterization (paper Sec. 4.1): per-face area distortion
//! `d_area(T) = ln( (Area f(T) / sum Area f) / (Area T / sum Area) )` and per-corner angle
//! distortion `d_angle = angle in f(T) - angle in T` (radians), plus the Beltrami coefficient
//! `|mu|` of each face's affine map (Sec. 2.1), whose area-weighted mean square is the radius
//! search objective (Eq. 12).

use crate::mesh::geometry::{triangle_angles, triangle_area};
use nalgebra::{Matrix2, Vector2, Vector3};

/// Summary statistics of a distortion measure.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Mean of the absolute values.
    pub mean_abs: f64,
    /// Mean of the values.
    pub mean: f64,
    /// Standard deviation of the values.
    pub std: f64,
    /// Largest absolute value.
    pub max_abs: f64,
    /// How many values were measured.
    pub count: usize,
}

impl Stats {
    /// Statistics of the finite values of `values`.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let (mut n, mut s, mut sa, mut s2, mut mx) = (0usize, 0.0, 0.0, 0.0, 0.0f64);
        for v in values.into_iter().filter(|v| v.is_finite()) {
            n += 1;
            s += v;
            sa += v.abs();
            s2 += v * v;
            mx = mx.max(v.abs());
        }
        if n == 0 {
            return Self::default();
        }
        let nf = n as f64;
        let mean = s / nf;
        Self { mean_abs: sa / nf, mean, std: (s2 / nf - mean * mean).max(0.0).sqrt(), max_abs: mx, count: n }
    }
}

/// Area distortion of each face between `source` and `target` positions of the same faces.
/// Faces of zero area on either side give `NaN` (left out of [`Stats`]).
pub fn area_distortion(source: &[[f64; 3]], target: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<f64> {
    let area = |p: &[[f64; 3]], f: &[u32; 3]| triangle_area(p[f[0] as usize], p[f[1] as usize], p[f[2] as usize]);
    let a_src: Vec<f64> = faces.iter().map(|f| area(source, f)).collect();
    let a_tgt: Vec<f64> = faces.iter().map(|f| area(target, f)).collect();
    let s_src: f64 = a_src.iter().sum();
    let s_tgt: f64 = a_tgt.iter().sum();
    a_src
        .iter()
        .zip(&a_tgt)
        .map(|(s, t)| if *s > 0.0 && *t > 0.0 { ((t / s_tgt) / (s / s_src)).ln() } else { f64::NAN })
        .collect()
}

/// Angle distortion of every corner (three per face, in face order), radians.
pub fn angle_distortion(source: &[[f64; 3]], target: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<f64> {
    let mut out = Vec::with_capacity(3 * faces.len());
    for f in faces {
        let [a, b, c] = f.map(|v| v as usize);
        let s = triangle_angles(source[a], source[b], source[c]);
        let t = triangle_angles(target[a], target[b], target[c]);
        for k in 0..3 {
            out.push(t[k] - s[k]);
        }
    }
    out
}

/// `|mu|` of the affine map from the surface triangle `p` onto the planar triangle `q`.
/// `NaN` when either triangle is degenerate.
pub fn beltrami_abs(p: [[f64; 3]; 3], q: [[f64; 2]; 3]) -> f64 {
    let [p0, p1, p2] = p.map(Vector3::from);
    let (e1, e2) = (p1 - p0, p2 - p0);
    let l1 = e1.norm();
    let area2 = e1.cross(&e2).norm();
    if l1 == 0.0 || area2 == 0.0 {
        return f64::NAN;
    }
    // The surface triangle in a frame of its plane, edges (l1, 0) and (x2, y2): the columns
    // of the upper triangular `frame`; the planar edges are the columns of `planar`.
    let frame = Matrix2::new(l1, e2.dot(&e1) / l1, 0.0, area2 / l1);
    let [q0, q1, q2] = q.map(Vector2::from);
    let planar = Matrix2::from_columns(&[q1 - q0, q2 - q0]);
    // The affine map's Jacobian J solves J frame = planar; as frame^T J^T = planar^T it is a
    // forward substitution (exact divisions by l1 and y2, no inverse formed).
    let Some(jt) = frame.transpose().solve_lower_triangular(&planar.transpose()) else {
        return f64::NAN;
    };
    let (a, b, c, d) = (jt[(0, 0)], jt[(1, 0)], jt[(0, 1)], jt[(1, 1)]);
    // f_z = ((a + d) + i (c - b)) / 2, f_zbar = ((a - d) + i (c + b)) / 2.
    let fz = ((a + d).powi(2) + (c - b).powi(2)).sqrt();
    let fzb = ((a - d).powi(2) + (c + b).powi(2)).sqrt();
    if fz == 0.0 {
        return f64::NAN;
    }
    fzb / fz
}

/// The radius-search objective: the mean of `|mu|^2` weighted by planar face area
/// (the paper's Eq. 12 normalised by the domain's area, so it does not favour small disks).
pub fn conformal_energy(surface: &[[f64; 3]], plane: &[[f64; 2]], faces: &[[u32; 3]]) -> f64 {
    weighted_mean_mu2(surface, plane, faces, |_, q| crate::mesh::geometry::signed_area_2d(q[0], q[1], q[2]).abs())
}

/// The mean of `|mu|^2` weighted by surface face area: the radius objective of punctured
/// closed surfaces, whose planar map has faces spanning the circular segments of the rim
/// (tiny on the surface, a third of the disk in the plane) that would dominate the
/// planar-area weighting of [`conformal_energy`].
pub fn conformal_energy_surface_weighted(surface: &[[f64; 3]], plane: &[[f64; 2]], faces: &[[u32; 3]]) -> f64 {
    weighted_mean_mu2(surface, plane, faces, |p, _| crate::mesh::geometry::triangle_area(p[0], p[1], p[2]))
}

/// `sum w |mu|^2 / sum w` over the faces with a finite `|mu|`, `w = weight(surface triangle,
/// planar triangle)`; infinite when no face counts.
fn weighted_mean_mu2(
    surface: &[[f64; 3]],
    plane: &[[f64; 2]],
    faces: &[[u32; 3]],
    weight: impl Fn(&[[f64; 3]; 3], &[[f64; 2]; 3]) -> f64,
) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for f in faces {
        let [a, b, c] = f.map(|v| v as usize);
        let (p, q) = ([surface[a], surface[b], surface[c]], [plane[a], plane[b], plane[c]]);
        let mu = beltrami_abs(p, q);
        if mu.is_finite() {
            let w = weight(&p, &q);
            num += mu * mu * w;
            den += w;
        }
    }
    if den > 0.0 {
        num / den
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn similarity_has_zero_mu_and_shear_has_known_mu() {
        let p = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.3, 0.8, 1.0]];
        // Rotation + scaling: conformal.
        let (cs, sn, s) = (0.6f64, 0.8f64, 2.5f64);
        let q = p.map(|x| [s * (cs * x[0] - sn * x[1]), s * (sn * x[0] + cs * x[1])]);
        assert!(beltrami_abs(p, q) < 1e-12);
        // Stretch by k along x: mu = (k - 1) / (k + 1).
        let k = 3.0;
        let q = p.map(|x| [k * x[0], x[1]]);
        assert!((beltrami_abs(p, q) - (k - 1.0) / (k + 1.0)).abs() < 1e-12);
    }

    #[test]
    fn identity_has_no_distortion() {
        let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.2]];
        let f = vec![[0, 1, 2], [1, 3, 2]];
        let scaled: Vec<[f64; 3]> = v.iter().map(|p| [3.0 * p[0], 3.0 * p[1], 3.0 * p[2]]).collect();
        assert!(Stats::of(area_distortion(&v, &scaled, &f)).max_abs < 1e-12);
        assert!(Stats::of(angle_distortion(&v, &scaled, &f)).max_abs < 1e-12);
    }
}
