//! The surface area a remesh face covers, measured through the map (ours; docs/method.md
//! section 19, "Covered areas").
//!
//! The map is area-preserving onto the cap (paper Sec. 3.1, Eq. 6-9), and the cap's area
//! element on the map's plane is the stereographic density `4 / (1 + |q|^2)^2` (the planar
//! disk domain: 1). So the surface a planar triangle covers has, up to the map's own area
//! distortion, the area `K sigma(c) A_plane` with `c` its centroid and `K` one constant. Where
//! the remesh is coarser than the surface's folds (a cortex's sulci at a few thousand faces)
//! a face's chord triangle bridges the fold and has much less area than the surface it
//! covers: equal chord areas then leave the folds with too few vertices, equal covered areas
//! keep the pull-back's share of vertices in them.

use super::global_area::ln_area_gradient;
use super::state::Shaping;
use crate::mesh::geometry::{signed_area_2d, triangle_area};

/// Covered areas of a remesh's planar faces, scaled so that they sum to the faces' chord
/// areas (the targets stay in the chord areas' units).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Covered {
    /// Whether the plane is the stereographic image of a cap (else the planar disk).
    cap: bool,
    /// `K`: the faces' chord area over their `sigma`-weighted planar area.
    scale: f64,
}

impl Covered {
    /// The measure on `mesh`'s current faces; `cap` as in [`Covered::cap`]. `None` when no
    /// face has a planar point at every corner or an area.
    pub(crate) fn new(mesh: &Shaping, cap: bool) -> Option<Self> {
        let unit = Self { cap, scale: 1.0 };
        let (mut chord, mut covered) = (0.0, 0.0);
        for f in mesh.faces.iter().filter(|f| f.iter().all(|&v| mesh.planar(v))) {
            let [a, b, c] = f.map(|v| mesh.position[v as usize]);
            chord += triangle_area(a, b, c);
            covered += unit.area(f.map(|v| mesh.plane[v as usize]));
        }
        (covered > 0.0 && chord > 0.0).then_some(Self { cap, scale: chord / covered })
    }

    /// The planar density at `q`: the cap's area element, or 1 on the planar disk.
    fn sigma(&self, q: [f64; 2]) -> f64 {
        if self.cap {
            let s = 1.0 + q[0] * q[0] + q[1] * q[1];
            4.0 / (s * s)
        } else {
            1.0
        }
    }

    /// The covered area of the planar triangle `p` (either orientation).
    pub(crate) fn area(&self, p: [[f64; 2]; 3]) -> f64 {
        let c = [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0];
        self.scale * self.sigma(c) * signed_area_2d(p[0], p[1], p[2]).abs()
    }

    /// `ln` of the covered area of the planar triangle `(q, a, b)` and its gradient with
    /// respect to `q`, the density held at its value (it varies on the disk's scale, not
    /// the face's). `None` for a triangle without planar area.
    pub(crate) fn ln_area_and_gradient(&self, q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> Option<(f64, [f64; 2])> {
        let s = signed_area_2d(q, a, b);
        let area = self.area([q, a, b]);
        if !(s != 0.0 && area > 0.0) {
            return None;
        }
        Some((area.ln(), ln_area_gradient([q, a, b], s)[0]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gradient of `ln` area against central differences, on a skewed planar triangle
    /// (the planar disk's constant density: the gradient is then exact).
    #[test]
    fn ln_area_gradient_matches_finite_differences() {
        let covered = Covered { cap: false, scale: 2.5 };
        let (q, a, b) = ([0.3, -0.2], [1.4, 0.1], [0.5, 0.9]);
        let (_, g) = covered.ln_area_and_gradient(q, a, b).unwrap();
        let h = 1e-6;
        for k in 0..2 {
            let (mut qp, mut qm) = (q, q);
            qp[k] += h;
            qm[k] -= h;
            let fd = (covered.ln_area_and_gradient(qp, a, b).unwrap().0 - covered.ln_area_and_gradient(qm, a, b).unwrap().0) / (2.0 * h);
            assert!((fd - g[k]).abs() < 1e-6 * (1.0 + fd.abs()), "coordinate {k}: {fd} vs {}", g[k]);
        }
    }

    /// On the cap the covered areas of a fine planar grid sum to the cap's area: the density
    /// is the stereographic area element (a disk of radius 1 is the unit hemisphere, 2 pi).
    #[test]
    fn the_density_integrates_to_the_caps_area() {
        let covered = Covered { cap: true, scale: 1.0 };
        let n = 400;
        let mut total = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (x0, y0, h) = (-1.0 + 2.0 * i as f64 / n as f64, -1.0 + 2.0 * j as f64 / n as f64, 2.0 / n as f64);
                let c = [x0 + 0.5 * h, y0 + 0.5 * h];
                if c[0] * c[0] + c[1] * c[1] <= 1.0 {
                    total += covered.area([[x0, y0], [x0 + h, y0], [x0 + h, y0 + h]]) + covered.area([[x0, y0], [x0 + h, y0 + h], [x0, y0 + h]]);
                }
            }
        }
        assert!((total - 2.0 * std::f64::consts::PI).abs() < 0.02, "{total}");
    }
}
