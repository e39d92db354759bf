//! Möbius normalisation of a disk map: the automorphism `z -> (z - a) / (1 - conj(a) z)` that
//! puts the area-weighted centroid of the vertices at the origin.
//!
//! A disk conformal map is unique up to the three-parameter group of disk automorphisms; the
//! choice matters for the transport step that follows, which works best when the surface is
//! spread evenly over the disk. Composition with an automorphism keeps the map conformal.

/// Apply `z -> (z - a) / (1 - conj(a) z)`.
#[inline]
pub fn disk_automorphism(z: [f64; 2], a: [f64; 2]) -> [f64; 2] {
    // numerator z - a; denominator 1 - conj(a) z
    let num = [z[0] - a[0], z[1] - a[1]];
    let den = [1.0 - (a[0] * z[0] + a[1] * z[1]), -(a[0] * z[1] - a[1] * z[0])];
    let d2 = den[0] * den[0] + den[1] * den[1];
    [
        (num[0] * den[0] + num[1] * den[1]) / d2,
        (num[1] * den[0] - num[0] * den[1]) / d2,
    ]
}

/// Move the `weights`-weighted centroid of `uv` to the origin by disk automorphisms (a few
/// fixed-point steps; each step is exact for the centroid it sees). Points on the unit circle
/// stay on it.
pub fn center_by_mobius(uv: &mut [[f64; 2]], weights: &[f64], boundary: &[u32]) {
    let total: f64 = weights.iter().sum();
    if !(total > 0.0) {
        return;
    }
    for _ in 0..50 {
        let mut c = [0.0, 0.0];
        for (p, w) in uv.iter().zip(weights) {
            c[0] += w * p[0];
            c[1] += w * p[1];
        }
        c = [c[0] / total, c[1] / total];
        let r = (c[0] * c[0] + c[1] * c[1]).sqrt();
        if r < 1e-9 {
            break;
        }
        // Damp long steps: the centroid of the image moves less than a.
        let a = if r > 0.5 { [c[0] * 0.5 / r, c[1] * 0.5 / r] } else { c };
        for p in uv.iter_mut() {
            *p = disk_automorphism(*p, a);
        }
    }
    for &b in boundary {
        let p = uv[b as usize];
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
        if r > 0.0 {
            uv[b as usize] = [p[0] / r, p[1] / r];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn automorphism_keeps_circle_and_sends_a_to_zero() {
        let a = [0.3, -0.4];
        let z = disk_automorphism(a, a);
        assert!(z[0].abs() < 1e-15 && z[1].abs() < 1e-15);
        for k in 0..10 {
            let t = k as f64;
            let w = disk_automorphism([t.cos(), t.sin()], a);
            assert!(((w[0] * w[0] + w[1] * w[1]).sqrt() - 1.0).abs() < 1e-12);
        }
    }
}
