//! Point location in a planar triangulation with a uniform grid of triangle bounding boxes.
//! A query outside every triangle (the cap grid's boundary lies on the circle, the mapped
//! mesh's boundary is a polygon inscribed in it) goes to the nearest point of the nearest
//! triangle, so the pull-back is robust at the boundary.

use crate::mesh::geometry::signed_area_2d;

/// A located point: the triangle and barycentric coordinates (non-negative, sum 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// Triangle index.
    pub face: usize,
    /// Barycentric coordinates of the point (or of its nearest point in the triangle).
    pub bary: [f64; 3],
}

/// Grid over the triangles of a planar mesh.
pub struct Locator<'a> {
    points: &'a [[f64; 2]],
    faces: &'a [[u32; 3]],
    lo: [f64; 2],
    cell: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

impl<'a> Locator<'a> {
    /// Build the grid (about two triangles per cell).
    pub fn new(points: &'a [[f64; 2]], faces: &'a [[u32; 3]]) -> Self {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in points {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let w = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-300);
        let n = ((faces.len() as f64 / 2.0).sqrt().ceil() as usize).clamp(1, 4096);
        let cell = w / n as f64 * (1.0 + 1e-9);
        let (nx, ny) = (n, n);
        let mut cells = vec![Vec::new(); nx * ny];
        for (f, t) in faces.iter().enumerate() {
            let q = t.map(|v| points[v as usize]);
            let (x0, x1) = (q[0][0].min(q[1][0]).min(q[2][0]), q[0][0].max(q[1][0]).max(q[2][0]));
            let (y0, y1) = (q[0][1].min(q[1][1]).min(q[2][1]), q[0][1].max(q[1][1]).max(q[2][1]));
            let (i0, i1) = (Self::idx(x0, lo[0], cell, nx), Self::idx(x1, lo[0], cell, nx));
            let (j0, j1) = (Self::idx(y0, lo[1], cell, ny), Self::idx(y1, lo[1], cell, ny));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    cells[j * nx + i].push(f as u32);
                }
            }
        }
        Self { points, faces, lo, cell, nx, ny, cells }
    }

    fn idx(x: f64, lo: f64, cell: f64, n: usize) -> usize {
        (((x - lo) / cell).floor().max(0.0) as usize).min(n - 1)
    }

    fn barycentric(&self, f: usize, p: [f64; 2]) -> [f64; 3] {
        let [a, b, c] = self.faces[f].map(|v| self.points[v as usize]);
        let area = signed_area_2d(a, b, c);
        if area == 0.0 {
            return [f64::NEG_INFINITY; 3];
        }
        [signed_area_2d(p, b, c) / area, signed_area_2d(a, p, c) / area, signed_area_2d(a, b, p) / area]
    }

    /// Locate `p`: a containing triangle if any, else the nearest point of the nearest
    /// triangle among growing rings of grid cells.
    pub fn locate(&self, p: [f64; 2]) -> Option<Location> {
        let (ci, cj) = (Self::idx(p[0], self.lo[0], self.cell, self.nx), Self::idx(p[1], self.lo[1], self.cell, self.ny));
        let mut best: Option<(f64, Location)> = None;
        let max_ring = self.nx.max(self.ny);
        for ring in 0..=max_ring {
            let (i0, i1) = (ci.saturating_sub(ring), (ci + ring).min(self.nx - 1));
            let (j0, j1) = (cj.saturating_sub(ring), (cj + ring).min(self.ny - 1));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    if ring > 0 && i != i0 && i != i1 && j != j0 && j != j1 {
                        continue;
                    }
                    for &f in &self.cells[j * self.nx + i] {
                        let bary = self.barycentric(f as usize, p);
                        if bary.iter().all(|&b| b >= -1e-12) {
                            let s: f64 = bary.iter().map(|b| b.max(0.0)).sum();
                            return Some(Location { face: f as usize, bary: bary.map(|b| b.max(0.0) / s) });
                        }
                        let (d, loc) = self.nearest_in(f as usize, p);
                        if best.as_ref().map_or(true, |(bd, _)| d < *bd) {
                            best = Some((d, loc));
                        }
                    }
                }
            }
            // Once something was found, one more ring guarantees the nearest.
            if let Some((d, loc)) = best {
                if d <= (ring as f64) * self.cell {
                    return Some(loc);
                }
            }
        }
        best.map(|(_, l)| l)
    }

    /// Distance from `p` to triangle `f` and the barycentric coordinates of the nearest point.
    fn nearest_in(&self, f: usize, p: [f64; 2]) -> (f64, Location) {
        let q = self.faces[f].map(|v| self.points[v as usize]);
        let mut best = (f64::INFINITY, [1.0, 0.0, 0.0]);
        for k in 0..3 {
            let (a, b) = (q[k], q[(k + 1) % 3]);
            let e = [b[0] - a[0], b[1] - a[1]];
            let len2 = e[0] * e[0] + e[1] * e[1];
            let t = if len2 > 0.0 { (((p[0] - a[0]) * e[0] + (p[1] - a[1]) * e[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
            let x = [a[0] + t * e[0], a[1] + t * e[1]];
            let d = ((x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2)).sqrt();
            if d < best.0 {
                let mut bary = [0.0; 3];
                bary[k] = 1.0 - t;
                bary[(k + 1) % 3] = t;
                best = (d, bary);
            }
        }
        (best.0, Location { face: f, bary: best.1 })
    }
}
