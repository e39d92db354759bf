//! Exact point-to-surface distance: the closest point on a triangle (Ericson, Real-Time
//! Collision Detection, 5.1.5) with a uniform grid of triangle bounding boxes searched in
//! growing shells.

use crate::mesh::geometry::{add, dot, norm, scale, sub};
use crate::mesh::TriMesh;

/// Closest point of triangle `abc` to `p`.
pub fn closest_on_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return add(a, scale(ab, v));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return add(a, scale(ac, w));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return add(b, scale(sub(c, b), w));
    }
    let denom = va + vb + vc;
    if denom == 0.0 {
        return a;
    }
    let (v, w) = (vb / denom, vc / denom);
    add(a, add(scale(ab, v), scale(ac, w)))
}

/// Distance queries against one mesh.
pub struct SurfaceDistance<'a> {
    mesh: &'a TriMesh,
    lo: [f64; 3],
    cell: f64,
    n: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl<'a> SurfaceDistance<'a> {
    /// Index the faces of `mesh`.
    pub fn new(mesh: &'a TriMesh) -> Self {
        let (lo, hi) = mesh.bounding_box().unwrap_or(([0.0; 3], [1.0; 3]));
        let ext = sub(hi, lo);
        let vol = (ext[0].max(1e-12) * ext[1].max(1e-12) * ext[2].max(1e-12)).max(1e-300);
        let target_cells = (mesh.n_faces() as f64 / 2.0).max(1.0);
        let cell = (vol / target_cells).cbrt().max(norm(ext) * 1e-4).max(1e-300);
        let n = [0, 1, 2].map(|k| ((ext[k] / cell).ceil() as usize).clamp(1, 512));
        let mut cells = vec![Vec::new(); n[0] * n[1] * n[2]];
        let this_idx = |x: f64, k: usize| (((x - lo[k]) / cell).floor().max(0.0) as usize).min(n[k] - 1);
        for (f, t) in mesh.faces.iter().enumerate() {
            let q = t.map(|v| mesh.vertices[v as usize]);
            let mut i0 = [0usize; 3];
            let mut i1 = [0usize; 3];
            for k in 0..3 {
                let (a, b) = (q[0][k].min(q[1][k]).min(q[2][k]), q[0][k].max(q[1][k]).max(q[2][k]));
                i0[k] = this_idx(a, k);
                i1[k] = this_idx(b, k);
            }
            for z in i0[2]..=i1[2] {
                for y in i0[1]..=i1[1] {
                    for x in i0[0]..=i1[0] {
                        cells[(z * n[1] + y) * n[0] + x].push(f as u32);
                    }
                }
            }
        }
        Self { mesh, lo, cell, n, cells }
    }

    /// Distance from `p` to the surface.
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        let c = [0, 1, 2].map(|k| (((p[k] - self.lo[k]) / self.cell).floor().max(0.0) as usize).min(self.n[k] - 1));
        let mut best = f64::INFINITY;
        let max_ring = self.n[0].max(self.n[1]).max(self.n[2]);
        for ring in 0..=max_ring {
            let lo = c.map(|x| x.saturating_sub(ring));
            let hi = [0, 1, 2].map(|k| (c[k] + ring).min(self.n[k] - 1));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let on_shell = ring == 0 || x == lo[0] || x == hi[0] || y == lo[1] || y == hi[1] || z == lo[2] || z == hi[2];
                        if !on_shell {
                            continue;
                        }
                        for &f in &self.cells[(z * self.n[1] + y) * self.n[0] + x] {
                            let t = self.mesh.faces[f as usize].map(|v| self.mesh.vertices[v as usize]);
                            best = best.min(norm(sub(p, closest_on_triangle(p, t[0], t[1], t[2]))));
                        }
                    }
                }
            }
            // Points outside the searched block are at least `ring * cell` away.
            if best <= ring as f64 * self.cell {
                break;
            }
        }
        best
    }
}
