//! Stereographic projection with the convention of the design notes:
//! `phi^-1(x, y) = (2x, 2y, 1 - |x|^2) / (1 + |x|^2)`, so the origin goes to the north pole and
//! the disk of radius `r` onto the cap `Z >= Z* = (1 - r^2) / (1 + r^2)` (paper Eq. 13 with the
//! sign corrected; the printed Eq. 2 maps to the lower cap).

/// Inverse stereographic projection of a plane point onto the unit sphere.
#[inline]
pub fn inverse_stereographic(p: [f64; 2]) -> [f64; 3] {
    let q = p[0] * p[0] + p[1] * p[1];
    let d = 1.0 + q;
    [2.0 * p[0] / d, 2.0 * p[1] / d, (1.0 - q) / d]
}

/// Stereographic projection from the south pole: the inverse of [`inverse_stereographic`].
/// The south pole itself has no image (returns infinities).
#[inline]
pub fn stereographic(x: [f64; 3]) -> [f64; 2] {
    let d = 1.0 + x[2];
    [x[0] / d, x[1] / d]
}

/// The cap's lower bound `Z*` for a disk of radius `r`.
#[inline]
pub fn z_star_of_radius(r: f64) -> f64 {
    (1.0 - r * r) / (1.0 + r * r)
}

/// The disk radius whose image is the cap `Z >= z` (`-1 < z < 1`).
#[inline]
pub fn radius_of_z_star(z: f64) -> f64 {
    ((1.0 - z) / (1.0 + z)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_cap_bound() {
        for p in [[0.0, 0.0], [0.3, -0.7], [2.0, 5.0], [-10.0, 0.1]] {
            let x = inverse_stereographic(p);
            assert!(((x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1.0).abs() < 1e-14);
            let q = stereographic(x);
            assert!((q[0] - p[0]).abs() < 1e-12 * (1.0 + p[0].abs()) && (q[1] - p[1]).abs() < 1e-12 * (1.0 + p[1].abs()));
        }
        for r in [0.05, 0.5, 1.0, 3.0, 20.0] {
            let z = z_star_of_radius(r);
            assert!((inverse_stereographic([r, 0.0])[2] - z).abs() < 1e-14);
            assert!((radius_of_z_star(z) - r).abs() < 1e-12 * r);
        }
        assert_eq!(z_star_of_radius(1.0), 0.0);
    }
}
