//! Radially symmetric source densities on the plane and their exact integrals over the pieces
//! of a clipped power cell (fan triangles from the origin, circular sectors, straight edges).
//!
//! The paper's source measure (Sec. 3.1.2, Eq. 10) is the stereographic density
//! `sigma(x) = 4 / (1 + |x|^2)^2`, the area element of the unit sphere pulled back by the inverse
//! stereographic projection, so the sigma-mass of a planar region is the area of its image on
//! the sphere. The fixed planar-disk baseline (Zhao et al. 2013) uses the uniform density.
//!
//! Every cell piece is integrated from the origin: a polygon's mass is the signed sum of the
//! fan triangles `(0, a, b)` over its edges plus sectors over its arcs. Masses and edge
//! integrals are exact closed forms; first moments (for centroids) use Gauss-Legendre
//! quadrature along each edge of a smooth, bounded integrand.

/// Gauss-Legendre nodes on [0, 1] and weights (6 points), for first moments along edges.
const GL_NODES: [f64; 6] = [
    0.033_765_242_898_423_98,
    0.169_395_306_766_867_74,
    0.380_690_406_958_401_56,
    0.619_309_593_041_598_4,
    0.830_604_693_233_132_3,
    0.966_234_757_101_576,
];
const GL_WEIGHTS: [f64; 6] = [
    0.085_662_246_189_585_17,
    0.180_380_786_524_069_3,
    0.233_956_967_286_345_5,
    0.233_956_967_286_345_5,
    0.180_380_786_524_069_3,
    0.085_662_246_189_585_17,
];

/// A radially symmetric density `sigma(|x|)` on the plane with the integrals the transport
/// solver needs.
pub trait RadialDensity: Sync {
    /// The density at radius `rho`.
    fn at(&self, rho: f64) -> f64;
    /// Mass per radian of the disk of radius `r`: `int_0^r rho sigma(rho) d rho`.
    fn radial_mass(&self, r: f64) -> f64;
    /// First radial moment per radian: `int_0^r rho^2 sigma(rho) d rho`.
    fn radial_moment(&self, r: f64) -> f64;
    /// Signed mass of the fan triangle `(0, a, b)` (positive when counter-clockwise).
    fn fan_mass(&self, a: [f64; 2], b: [f64; 2]) -> f64;
    /// `int sigma ds` along the segment `ab`.
    fn segment_integral(&self, a: [f64; 2], b: [f64; 2]) -> f64;

    /// [`RadialDensity::fan_mass`] and [`RadialDensity::segment_integral`] of one segment
    /// (the transport integrates each power-cell edge once for both).
    fn fan_mass_and_segment_integral(&self, a: [f64; 2], b: [f64; 2]) -> (f64, f64) {
        (self.fan_mass(a, b), self.segment_integral(a, b))
    }

    /// Mass of the disk of radius `r`.
    fn disk_mass(&self, r: f64) -> f64 {
        2.0 * std::f64::consts::PI * self.radial_mass(r)
    }

    /// Signed first moment `int x sigma dA` of the fan triangle `(0, a, b)`.
    ///
    /// With `p(s) = a + s (b - a)`, the fan is swept by `d theta = cross(a, b) / |p|^2 ds` and
    /// the moment is `int_0^1 M(|p|) p / |p|^3 cross(a, b) ds`, `M` the radial moment.
    fn fan_moment(&self, a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        let cr = a[0] * b[1] - a[1] * b[0];
        if cr == 0.0 {
            return [0.0, 0.0];
        }
        let mut m = [0.0, 0.0];
        for (s, w) in GL_NODES.iter().zip(GL_WEIGHTS.iter()) {
            let p = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
            let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
            if rho == 0.0 {
                continue;
            }
            let f = self.radial_moment(rho) / (rho * rho * rho) * w * cr;
            m[0] += f * p[0];
            m[1] += f * p[1];
        }
        m
    }

    /// Mass of the sector of the disk of radius `r` between angles `alpha` and `beta`
    /// (counter-clockwise, `beta >= alpha`).
    fn sector_mass(&self, r: f64, alpha: f64, beta: f64) -> f64 {
        (beta - alpha) * self.radial_mass(r)
    }

    /// First moment of that sector.
    fn sector_moment(&self, r: f64, alpha: f64, beta: f64) -> [f64; 2] {
        let k = self.radial_moment(r);
        [k * (beta.sin() - alpha.sin()), k * (alpha.cos() - beta.cos())]
    }
}

/// Foot-of-perpendicular parameters of the line through `a` and `b`: distance `d` from the
/// origin, arc parameters `s_a <= s_b` along the unit direction, and the orientation sign of
/// the fan `(0, a, b)`. `None` for a zero-length segment.
fn line_frame(a: [f64; 2], b: [f64; 2]) -> Option<(f64, f64, f64, f64)> {
    let dx = b[0] - a[0];
    let dy = b[1] - a[1];
    let len = (dx * dx + dy * dy).sqrt();
    if len == 0.0 {
        return None;
    }
    let u = [dx / len, dy / len];
    let sa = a[0] * u[0] + a[1] * u[1];
    let sb = b[0] * u[0] + b[1] * u[1];
    // Signed distance: cross(u, a) = cross(u, p0).
    let signed_d = u[0] * a[1] - u[1] * a[0];
    Some((signed_d.abs(), sa, sb, -signed_d.signum()))
}

/// The stereographic density `4 / (1 + |x|^2)^2` (paper Eq. 10).
#[derive(Debug, Clone, Copy, Default)]
pub struct StereographicDensity;

impl RadialDensity for StereographicDensity {
    fn at(&self, rho: f64) -> f64 {
        let q = 1.0 + rho * rho;
        4.0 / (q * q)
    }

    fn radial_mass(&self, r: f64) -> f64 {
        // int_0^r 4 rho / (1 + rho^2)^2 = 2 r^2 / (1 + r^2)
        2.0 * r * r / (1.0 + r * r)
    }

    fn radial_moment(&self, r: f64) -> f64 {
        // int_0^r 4 rho^2 / (1 + rho^2)^2 = 2 (atan r - r / (1 + r^2))
        if r < 1e-3 {
            // Series 4 r^3 / 3 - 8 r^5 / 5 + 12 r^7 / 7 avoids cancellation.
            let r2 = r * r;
            return r * r2 * (4.0 / 3.0 - r2 * (8.0 / 5.0 - r2 * 12.0 / 7.0));
        }
        2.0 * (r.atan() - r / (1.0 + r * r))
    }

    fn fan_mass(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        stereographic_fan_and_segment(a, b).0
    }

    fn fan_mass_and_segment_integral(&self, a: [f64; 2], b: [f64; 2]) -> (f64, f64) {
        stereographic_fan_and_segment(a, b)
    }

    fn segment_integral(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        stereographic_fan_and_segment(a, b).1
    }
}

/// The stereographic density's fan mass of `(0, a, b)` and `int sigma ds` along `ab`, which
/// share the frame and the arctangent. In polar coordinates about the foot of the
/// perpendicular, the fan's mass is `int 2 rho^2 / (1 + rho^2) d theta = [2 d / q atan(s / q)]`
/// and the segment's integral `int 4 / (q^2 + s^2)^2 ds`, with `q^2 = 1 + d^2`.
fn stereographic_fan_and_segment(a: [f64; 2], b: [f64; 2]) -> (f64, f64) {
    let Some((d, sa, sb, sign)) = line_frame(a, b) else { return (0.0, 0.0) };
    let q2 = 1.0 + d * d;
    let q = q2.sqrt();
    let angle = atan_difference(sb / q, sa / q);
    let rational = |s: f64| s / (2.0 * q2 * (q2 + s * s));
    (sign * 2.0 * d / q * angle, 4.0 * (rational(sb) - rational(sa) + angle / (2.0 * q2 * q)))
}

/// `atan(x) - atan(y)` by one `atan2` (the difference of two angles in `(-pi/2, pi/2)` is
/// the angle of `(x - y, 1 + x y)`): half the arctangents of the cell integrals, which were
/// a tenth of a parameterization's time, and no cancellation for nearby `x` and `y`.
fn atan_difference(x: f64, y: f64) -> f64 {
    (x - y).atan2(1.0 + x * y)
}

/// The uniform density `1` (the planar disk OMT baseline of Zhao et al. 2013).
#[derive(Debug, Clone, Copy, Default)]
pub struct UniformDensity;

impl RadialDensity for UniformDensity {
    fn at(&self, _rho: f64) -> f64 {
        1.0
    }
    fn radial_mass(&self, r: f64) -> f64 {
        0.5 * r * r
    }
    fn radial_moment(&self, r: f64) -> f64 {
        r * r * r / 3.0
    }
    fn fan_mass(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        0.5 * (a[0] * b[1] - a[1] * b[0])
    }
    fn segment_integral(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
    }
    fn fan_moment(&self, a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        let m = self.fan_mass(a, b);
        [m * (a[0] + b[0]) / 3.0, m * (a[1] + b[1]) / 3.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force midpoint integration of sigma over the fan triangle (0, a, b).
    fn brute_fan(d: &dyn RadialDensity, a: [f64; 2], b: [f64; 2]) -> (f64, [f64; 2]) {
        let n = 600;
        let (mut m, mut mx, mut my) = (0.0, 0.0, 0.0);
        let cr = a[0] * b[1] - a[1] * b[0];
        for i in 0..n {
            for j in 0..(n - i) {
                for (u, v) in [
                    ((i as f64 + 1.0 / 3.0) / n as f64, (j as f64 + 1.0 / 3.0) / n as f64),
                    ((i as f64 + 2.0 / 3.0) / n as f64, (j as f64 + 2.0 / 3.0) / n as f64),
                ] {
                    if u + v > 1.0 {
                        continue;
                    }
                    let p = [u * a[0] + v * b[0], u * a[1] + v * b[1]];
                    let w = d.at((p[0] * p[0] + p[1] * p[1]).sqrt()) * 0.5 * cr / (n * n) as f64;
                    m += w;
                    mx += w * p[0];
                    my += w * p[1];
                }
            }
        }
        (m, [mx, my])
    }

    #[test]
    fn fan_mass_and_moment_match_brute_force() {
        let d = StereographicDensity;
        for (a, b) in [
            ([0.3, -0.2], [0.5, 0.9]),
            ([1.5, 0.1], [-0.4, 2.0]),
            ([0.9, 0.9], [0.2, 0.05]),
        ] {
            let (m, mom) = brute_fan(&d, a, b);
            assert!((d.fan_mass(a, b) - m).abs() < 1e-4 * m.abs(), "{} vs {}", d.fan_mass(a, b), m);
            let q = d.fan_moment(a, b);
            assert!((q[0] - mom[0]).abs() < 2e-4 * m.abs() && (q[1] - mom[1]).abs() < 2e-4 * m.abs());
            // Orientation: reversing the edge flips the sign.
            assert!((d.fan_mass(b, a) + d.fan_mass(a, b)).abs() < 1e-14);
        }
    }

    #[test]
    fn atan_difference_is_the_difference_of_arctangents() {
        // Both signs of 1 + x y (the difference beyond pi/2 when x y < -1), far and near.
        let values: [f64; 11] = [-1e8, -50.0, -3.0, -1.0, -0.2, 0.0, 1e-9, 0.7, 2.5, 40.0, 1e7];
        for &x in &values {
            for &y in &values {
                let exact = x.atan() - y.atan();
                assert!((atan_difference(x, y) - exact).abs() < 1e-14, "{x} {y}: {} vs {exact}", atan_difference(x, y));
            }
        }
        // Nearby arguments: the difference keeps its relative accuracy.
        let (x, y) = (0.3 + 1e-12, 0.3);
        assert!((atan_difference(x, y) / (1e-12 / 1.09) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn disk_mass_is_cap_area() {
        // The disk of radius r maps to the cap Z >= (1 - r^2) / (1 + r^2), of area 2 pi (1 - Z*).
        let d = StereographicDensity;
        for r in [0.1, 1.0, 3.0] {
            let z = (1.0 - r * r) / (1.0 + r * r);
            assert!((d.disk_mass(r) - 2.0 * std::f64::consts::PI * (1.0 - z)).abs() < 1e-12);
            // A regular 2000-gon's fan masses approach the disk mass.
            let n = 2000;
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let t = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                    [r * t.cos(), r * t.sin()]
                })
                .collect();
            let poly: f64 = (0..n).map(|k| d.fan_mass(pts[k], pts[(k + 1) % n])).sum();
            assert!((poly - d.disk_mass(r)).abs() < 1e-5 * d.disk_mass(r));
        }
    }

    #[test]
    fn segment_integral_matches_quadrature() {
        let d = StereographicDensity;
        let (a, b): ([f64; 2], [f64; 2]) = ([-0.7, 0.4], [1.2, 0.9]);
        let n = 20000;
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let mut s = 0.0;
        for k in 0..n {
            let t = (k as f64 + 0.5) / n as f64;
            let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
            s += d.at((p[0] * p[0] + p[1] * p[1]).sqrt()) * len / n as f64;
        }
        assert!((d.segment_integral(a, b) - s).abs() < 1e-8);
    }
}
