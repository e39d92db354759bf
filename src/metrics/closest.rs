//! Exact point-to-surface distance: the closest point on a triangle (Ericson, Real-Time
//! Collision Detection, 5.1.5) with a uniform grid of triangle bounding boxes searched in
//! growing shells.

use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{add, cross, dot, norm, scale, sub};
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
///
/// Faces are binned into a sparse uniform grid (a hash map of the occupied cells) whose cell
/// is about two mean edge lengths, so a cell holds a handful of faces whatever the mesh's
/// shape; a query searches shells of cells around its own until no closer face can exist.
/// Faces whose bounding box is farther than the best distance so far are skipped, and
/// [`SurfaceDistance::distance_near`] starts from the face nearest to the previous query,
/// which for samples taken in order along a surface bounds the search at once.
pub struct SurfaceDistance<'a> {
    mesh: &'a TriMesh,
    lo: [f64; 3],
    cell: f64,
    n: [i64; 3],
    cells: FastMap<u64, Vec<u32>>,
    /// Each face's bounding box (lower and upper corners).
    boxes: Vec<[[f64; 3]; 2]>,
}

impl<'a> SurfaceDistance<'a> {
    /// Index the faces of `mesh`.
    pub fn new(mesh: &'a TriMesh) -> Self {
        let (lo, hi) = mesh.bounding_box().unwrap_or(([0.0; 3], [1.0; 3]));
        let ext = sub(hi, lo);
        let diag = norm(ext);
        let area: f64 = mesh
            .faces
            .iter()
            .map(|t| {
                let q = t.map(|v| mesh.vertices[v as usize]);
                0.5 * norm(cross(sub(q[1], q[0]), sub(q[2], q[0])))
            })
            .sum();
        let mean_edge = crate::mesh::geometry::equilateral_edge(area, mesh.n_faces().max(1) as f64);
        // At most 2^20 cells along an axis (keys pack 21 bits per axis).
        let cell = (2.0 * mean_edge).max(diag * 1e-6).max(1e-300);
        let n = [0, 1, 2].map(|k| ((ext[k] / cell).ceil() as i64).clamp(1, 1 << 20));
        let cell = [0, 1, 2].map(|k| ext[k] / n[k] as f64).into_iter().fold(cell, f64::max);
        let mut cells: FastMap<u64, Vec<u32>> = FastMap::default();
        let index = |x: f64, k: usize| (((x - lo[k]) / cell).floor() as i64).clamp(0, n[k] - 1);
        let boxes: Vec<[[f64; 3]; 2]> = mesh
            .faces
            .iter()
            .map(|t| {
                let q = t.map(|v| mesh.vertices[v as usize]);
                [[0, 1, 2].map(|k| q[0][k].min(q[1][k]).min(q[2][k])), [0, 1, 2].map(|k| q[0][k].max(q[1][k]).max(q[2][k]))]
            })
            .collect();
        for (f, b) in boxes.iter().enumerate() {
            let i0 = [0, 1, 2].map(|k| index(b[0][k], k));
            let i1 = [0, 1, 2].map(|k| index(b[1][k], k));
            for z in i0[2]..=i1[2] {
                for y in i0[1]..=i1[1] {
                    for x in i0[0]..=i1[0] {
                        cells.entry(key(x, y, z)).or_default().push(f as u32);
                    }
                }
            }
        }
        Self { mesh, lo, cell, n, cells, boxes }
    }

    /// Distance from `p` to the surface.
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        self.distance_near(p, &mut None)
    }

    /// Distance from `p` to face `f`.
    #[inline]
    fn face_distance(&self, p: [f64; 3], f: u32) -> f64 {
        let t = self.mesh.faces[f as usize].map(|v| self.mesh.vertices[v as usize]);
        norm(sub(p, closest_on_triangle(p, t[0], t[1], t[2])))
    }

    /// [`SurfaceDistance::distance`], starting from the face `hint` (the nearest face of the
    /// previous query of a run of nearby points) and leaving the nearest face there. The
    /// distance is the same whatever the hint, up to rounding.
    pub fn distance_near(&self, p: [f64; 3], hint: &mut Option<u32>) -> f64 {
        let c = [0, 1, 2].map(|k| (((p[k] - self.lo[k]) / self.cell).floor() as i64).clamp(0, self.n[k] - 1));
        let mut best = f64::INFINITY;
        let mut nearest = hint.filter(|&f| (f as usize) < self.boxes.len());
        if let Some(f) = nearest {
            best = self.face_distance(p, f);
        }
        let max_ring = self.n[0].max(self.n[1]).max(self.n[2]);
        // Distance from p to the faces of its own cell's block, for the stopping test below.
        let inside = [0, 1, 2].map(|k| {
            let x = (p[k] - self.lo[k]) / self.cell - c[k] as f64;
            x.min(1.0 - x).max(0.0)
        });
        let margin = inside.iter().cloned().fold(f64::INFINITY, f64::min) * self.cell;
        for ring in 0..=max_ring {
            let lo = c.map(|x| (x - ring).max(0));
            let hi = [0, 1, 2].map(|k| (c[k] + ring).min(self.n[k] - 1));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    let inner_row = ring > 0 && z != lo[2] && z != hi[2] && y != lo[1] && y != hi[1];
                    let xs: &[i64] = if inner_row { &[lo[0], hi[0]] } else { &[] };
                    let mut visit = |x: i64| {
                        // A cell wholly farther than the best face so far holds nothing
                        // nearer: the nearest face is found in the cell of its nearest point.
                        if self.cell_distance([x, y, z], p) >= best {
                            return;
                        }
                        if let Some(faces) = self.cells.get(&key(x, y, z)) {
                            for &f in faces {
                                if box_distance2(&self.boxes[f as usize], p) >= best * best {
                                    continue;
                                }
                                let d = self.face_distance(p, f);
                                if d < best {
                                    best = d;
                                    nearest = Some(f);
                                }
                            }
                        }
                    };
                    if inner_row {
                        // Only the two ends of an inner row are on the shell.
                        visit(xs[0]);
                        if xs[1] != xs[0] {
                            visit(xs[1]);
                        }
                    } else {
                        for x in lo[0]..=hi[0] {
                            visit(x);
                        }
                    }
                }
            }
            // Points outside the searched block are at least `ring * cell` (plus p's margin
            // inside its own cell) away.
            if best <= ring as f64 * self.cell + margin {
                break;
            }
        }
        *hint = nearest;
        best
    }
}

/// Squared distance from `p` to the box `b` (0 inside).
#[inline]
fn box_distance2(b: &[[f64; 3]; 2], p: [f64; 3]) -> f64 {
    let mut d2 = 0.0;
    for k in 0..3 {
        let d = (b[0][k] - p[k]).max(0.0).max(p[k] - b[1][k]);
        d2 += d * d;
    }
    d2
}

impl SurfaceDistance<'_> {
    /// Distance from `p` to the box of cell `c` (0 inside).
    #[inline]
    fn cell_distance(&self, c: [i64; 3], p: [f64; 3]) -> f64 {
        let mut d2 = 0.0;
        for k in 0..3 {
            let lo = self.lo[k] + c[k] as f64 * self.cell;
            let d = (lo - p[k]).max(0.0).max(p[k] - (lo + self.cell));
            d2 += d * d;
        }
        d2.sqrt()
    }
}

/// Hash key of a grid cell (21 bits per axis).
#[inline]
fn key(x: i64, y: i64, z: i64) -> u64 {
    ((x as u64) << 42) | ((y as u64) << 21) | z as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::{icosphere, uv_sphere};

    /// The grid search against the brute-force minimum over every face, for points inside,
    /// on and far outside the surface, on a uniform and a very non-uniform mesh.
    #[test]
    fn grid_search_matches_brute_force() {
        for mesh in [icosphere(3), uv_sphere(40, 7)] {
            let index = SurfaceDistance::new(&mesh);
            let mut state = 7u64;
            let mut rand = || {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64
            };
            for i in 0..400 {
                let radius = [0.3, 1.0, 1.01, 3.0, 50.0][i % 5];
                let d = [rand() - 0.5, rand() - 0.5, rand() - 0.5];
                let p = scale(d, radius / norm(d).max(1e-9));
                let brute = mesh
                    .faces
                    .iter()
                    .map(|t| {
                        let q = t.map(|v| mesh.vertices[v as usize]);
                        norm(sub(p, closest_on_triangle(p, q[0], q[1], q[2])))
                    })
                    .fold(f64::INFINITY, f64::min);
                let fast = index.distance(p);
                assert!((fast - brute).abs() <= 1e-12 * (1.0 + brute), "point {p:?}: grid {fast}, brute force {brute}");
                // Any hint, near or far or out of range, gives the same distance.
                for h in [0, (i * 37) as u32 % mesh.n_faces() as u32, u32::MAX] {
                    let mut hint = Some(h);
                    let hinted = index.distance_near(p, &mut hint);
                    assert!((hinted - brute).abs() <= 1e-12 * (1.0 + brute), "point {p:?} hint {h}: {hinted}, brute force {brute}");
                    let f = hint.expect("nearest face") as usize;
                    let t = mesh.faces[f].map(|v| mesh.vertices[v as usize]);
                    assert!((norm(sub(p, closest_on_triangle(p, t[0], t[1], t[2]))) - hinted).abs() <= 1e-12 * (1.0 + brute));
                }
            }
        }
    }
}
