//! Local repair of folds by moving single vertices into the kernel of their one-ring.
//!
//! A vertex whose incident faces are folded is moved, along the straight line towards the
//! Chebyshev centre of the kernel of its one-ring polygon (the point farthest inside every
//! edge line, a three-variable linear program), only as far as needed for every incident face
//! to be positively oriented with a margin. The transport position is kept wherever it is
//! valid, so mass errors stay local; nothing is anchored to the boundary, which matters on a
//! punctured closed surface (four fixed vertices only), where a global convex-combination
//! solve collapses the map (paper Sec. 3.2 punctures a quad; this step is ours).
//!
//! Gauss-Seidel sweeps over the vertices of folded faces repeat until no fold is left or a
//! sweep moves nothing (a vertex whose ring is itself tangled has an empty kernel and waits
//! for its neighbours).

use crate::mesh::geometry::folded_faces;

/// Fraction of the kernel's inradius kept as the margin of every incident face.
const MARGIN: f64 = 0.3;

/// Maximum Gauss-Seidel sweeps.
const MAX_SWEEPS: usize = 200;

/// Move vertices of folded faces into their ring kernels; `rings[v]` is the ordered
/// counter-clockwise one-ring of `v` (`None` on the boundary), `fixed[v]` forbids moving.
/// Returns the number of vertex moves made.
pub fn kernel_untangle(pos: &mut [[f64; 2]], faces: &[[u32; 3]], rings: &[Option<Vec<u32>>], fixed: &[bool]) -> usize {
    let mut moves = 0;
    for _ in 0..MAX_SWEEPS {
        let folded = folded_faces(pos, faces);
        if folded.is_empty() {
            break;
        }
        let mut active: Vec<u32> = folded.iter().flat_map(|&f| faces[f]).collect();
        active.sort_unstable();
        active.dedup();
        let mut moved_this_sweep = 0;
        for v in active {
            let v = v as usize;
            let Some(ring) = rings[v].as_ref().filter(|_| !fixed[v]) else { continue };
            let poly: Vec<[f64; 2]> = ring.iter().map(|&u| pos[u as usize]).collect();
            if let Some(x) = move_into_kernel(pos[v], &poly) {
                pos[v] = x;
                moved_this_sweep += 1;
            }
        }
        moves += moved_this_sweep;
        if moved_this_sweep == 0 {
            break;
        }
    }
    moves
}

/// Edge lines of the ring polygon as `h(x) = (c + g . x) / |g|`, the signed distance of `x`
/// to the line of edge `(a, b)`, positive on the polygon's inner (left) side.
fn edge_lines(poly: &[[f64; 2]]) -> Vec<([f64; 2], f64)> {
    let m = poly.len();
    (0..m)
        .filter_map(|j| {
            let (a, b) = (poly[j], poly[(j + 1) % m]);
            // cross(a - x, b - x) = cross(a, b) + cross(x, a - b).
            let d = [a[0] - b[0], a[1] - b[1]];
            let g = [d[1], -d[0]];
            let len = (g[0] * g[0] + g[1] * g[1]).sqrt();
            (len > 0.0).then(|| ([g[0] / len, g[1] / len], (a[0] * b[1] - a[1] * b[0]) / len))
        })
        .collect()
}

fn distance(line: &([f64; 2], f64), x: [f64; 2]) -> f64 {
    line.1 + line.0[0] * x[0] + line.0[1] * x[1]
}

/// The point of the polygon's kernel farthest from its edge lines and that distance
/// (the Chebyshev centre), or `None` when the kernel is empty.
pub fn chebyshev_centre(poly: &[[f64; 2]]) -> Option<([f64; 2], f64)> {
    let lines = edge_lines(poly);
    let m = lines.len();
    if m < 3 {
        return None;
    }
    let scale = poly.iter().map(|p| p[0].abs().max(p[1].abs())).fold(0.0, f64::max).max(1e-300);
    let tol = 1e-12 * scale;
    let mut best: Option<([f64; 2], f64)> = None;
    // The optimum of max t s.t. h_j(x) >= t is a vertex of the LP: three active lines.
    for a in 0..m {
        for b in a + 1..m {
            for c in b + 1..m {
                let Some((x, t)) = solve_active([&lines[a], &lines[b], &lines[c]]) else { continue };
                if best.is_some_and(|(_, bt)| t <= bt) {
                    continue;
                }
                if lines.iter().all(|l| distance(l, x) >= t - tol) {
                    best = Some((x, t));
                }
            }
        }
    }
    best.filter(|&(_, t)| t > tol)
}

/// Solve `c_k + g_k . x = t` for the three lines (Cramer's rule).
fn solve_active(l: [&([f64; 2], f64); 3]) -> Option<([f64; 2], f64)> {
    // Unknowns (x0, x1, t): g0 x0 + g1 x1 - t = -c.
    let m = [[l[0].0[0], l[0].0[1], -1.0], [l[1].0[0], l[1].0[1], -1.0], [l[2].0[0], l[2].0[1], -1.0]];
    let r = [-l[0].1, -l[1].1, -l[2].1];
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det3(m);
    if d.abs() < 1e-14 {
        return None;
    }
    let with_col = |k: usize| {
        let mut mk = m;
        for i in 0..3 {
            mk[i][k] = r[i];
        }
        det3(mk) / d
    };
    Some(([with_col(0), with_col(1)], with_col(2)))
}

/// The point on the segment from `x` to the kernel's Chebyshev centre closest to `x` at which
/// every incident face keeps a margin of [`MARGIN`] times the inradius; `None` when `x` already
/// has that margin or the kernel is empty.
fn move_into_kernel(x: [f64; 2], poly: &[[f64; 2]]) -> Option<[f64; 2]> {
    let (centre, inradius) = chebyshev_centre(poly)?;
    let lines = edge_lines(poly);
    let want = MARGIN * inradius;
    let mut s: f64 = 0.0;
    for l in &lines {
        let (h0, h1) = (distance(l, x), distance(l, centre));
        if h0 < want {
            s = s.max((want - h0) / (h1 - h0));
        }
    }
    (s > 0.0).then(|| {
        let s = s.min(1.0);
        [x[0] + s * (centre[0] - x[0]), x[1] + s * (centre[1] - x[1])]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hexagon() -> Vec<[f64; 2]> {
        (0..6).map(|k| {
            let a = k as f64 * std::f64::consts::PI / 3.0;
            [a.cos(), a.sin()]
        })
        .collect()
    }

    #[test]
    fn chebyshev_centre_of_regular_hexagon_is_its_centre() {
        let (c, t) = chebyshev_centre(&hexagon()).unwrap();
        assert!(c[0].abs() < 1e-12 && c[1].abs() < 1e-12);
        assert!((t - 3f64.sqrt() / 2.0).abs() < 1e-12);
    }

    #[test]
    fn non_convex_star_has_kernel_and_bowtie_has_none() {
        // An arrow-shaped ring: star-shaped from points near the origin.
        let arrow = vec![[1.0, 0.0], [0.2, 0.2], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [0.2, -0.2]];
        let (c, t) = chebyshev_centre(&arrow).unwrap();
        assert!(t > 0.0);
        for l in edge_lines(&arrow) {
            assert!(distance(&l, c) >= t - 1e-12);
        }
        // Clockwise (inverted) ring: empty kernel.
        let mut cw = hexagon();
        cw.reverse();
        assert!(chebyshev_centre(&cw).is_none());
    }

    #[test]
    fn a_vertex_outside_its_ring_is_pulled_in_and_a_valid_one_stays() {
        let ring = hexagon();
        let inside = [0.1, -0.05];
        assert!(move_into_kernel(inside, &ring).is_none());
        let outside = [1.5, 0.3];
        let moved = move_into_kernel(outside, &ring).unwrap();
        let lines = edge_lines(&ring);
        let t = 3f64.sqrt() / 2.0;
        assert!(lines.iter().all(|l| distance(l, moved) >= MARGIN * t - 1e-12));
        // It moved only as far as needed: not to the centre.
        assert!(moved[0] > 0.05);
    }
}
