//! An isotropic start for the shape stage (ours; see docs/method.md, "Remesh shape"): the cap
//! points of a uniform remesh re-sampled so that their lifts are evenly spread on the surface.
//!
//! The uniform cap grid pulled back is a lattice stretched by the map's angle distortion. The
//! shape stage's splits and collapses rebuild its rows where an edge is stretched beyond 4/3 or
//! 4/5 of the target, but a lattice stretched by less keeps its rows: a periodic lattice is a
//! fixed point of every local relaxation (each vertex sees the same neighbourhood, so every
//! gradient vanishes), and the remeshes kept patches stretched by about 1.25 (mean smallest
//! angle about 47 degrees where an equilateral lattice has 60). Here the interior points are
//! instead a Poisson-disk sample of the surface: candidates uniform on the cap are uniform in
//! surface area (the map preserves area), their lifts are accepted greedily at a 3-D spacing
//! bisected to the grid's vertex count, and the accepted points with the grid's rim are
//! triangulated by Delaunay in the stereographic plane (an embedding of the cap). The
//! sample has no preferred direction: what is left to the shape stage is local.

use crate::mesh::geometry::sub;
use crate::mesh::TriMesh;
use crate::omt::triangulation::{RegularTriangulation, NONE};

/// Rings of the grid next to its rim kept as they are: a row of vertices along an open
/// surface's boundary (and around a closed one's puncture).
const KEPT_RINGS: usize = 1;

/// Candidates per interior grid vertex.
const CANDIDATES_PER_VERTEX: usize = 12;

/// Two points closer than the spacing on the surface but farther than this many spacings on
/// the cap (in the map's mean scale) are on two sides of a gap: both are kept. The map's angle
/// distortion stretches lengths by up to about 3 either way.
const NEAR_ON_CAP: f64 = 4.0;

/// Bisection steps on the spacing at most.
const SPACING_STEPS: usize = 24;

/// The bisection stops when the sample's count is within this fraction's inverse of the
/// grid's (1/400: 6 vertices of 2500).
const COUNT_TOLERANCE: usize = 400;

/// A pulled-back grid whose faces' mean smallest angle is at least this (degrees) is kept as
/// the shape stage's start: its rows are nearly equilateral already (the map's angle
/// distortion is small), and the relaxation from them ends better than from a sample (MEG
/// helmet: 51.0 against 49.2 degrees; the other bundled meshes' grids have 25.7 to 37.3).
pub(crate) const GRID_KEPT_ANGLE_DEG: f64 = 45.0;

/// Places cap points on the input surface (their lifts through the inverse map; `None` where
/// a point has no lift).
pub(crate) type Place<'a> = dyn Fn(&[[f64; 3]]) -> Vec<Option<[f64; 3]>> + 'a;

/// Samples tried (each from another stretch of the candidate sequence) before the grid, while
/// their remeshes miss the quality bar (`super::from_cap::from_best_start`).
pub(crate) const SAMPLES: usize = 2;

/// Whether the lift of `grid` is near-isotropic already ([`GRID_KEPT_ANGLE_DEG`]): then the
/// shape stage starts from it.
pub(crate) fn grid_is_isotropic(grid: &TriMesh, place: &Place<'_>) -> bool {
    let lifted: Option<Vec<[f64; 3]>> = place(&grid.vertices).into_iter().collect();
    lifted.is_some_and(|lifted| crate::metrics::angles::angle_quality_of(&lifted, &grid.faces).mean_min_angle_deg >= GRID_KEPT_ANGLE_DEG)
}

/// The cap mesh `grid` (rim ring last) with its interior vertices replaced by a Poisson-disk
/// sample of the surface of about as many vertices. `place` lifts cap points onto the surface
/// (`None` where the map has no point). `None` when the sample cannot be triangulated with the
/// rim as its hull (then the grid is used as it is). `variant` picks the stretch of the
/// candidate sequence (another sample of the same surface).
pub(crate) fn isotropic_cap(grid: &TriMesh, surface_area: f64, place: &Place<'_>, variant: usize) -> Option<TriMesh> {
    let z_rim = grid.vertices.last()?[2];
    let rim = grid.vertices.iter().rev().take_while(|p| p[2] == z_rim).count();
    // The grid's rings by height, lowest first: the lowest `KEPT_RINGS` stay as they are.
    let mut heights: Vec<f64> = grid.vertices.iter().map(|p| p[2]).collect();
    heights.sort_by(|a, b| a.total_cmp(b));
    heights.dedup();
    if heights.len() <= KEPT_RINGS + 2 {
        return None;
    }
    let (z_kept, z_above) = (heights[KEPT_RINGS - 1], heights[KEPT_RINGS]);
    let is_kept = |p: &[f64; 3]| p[2] <= z_kept;
    let interior = grid.vertices.iter().filter(|p| !is_kept(p)).count();
    if interior < 3 || rim < 3 {
        return None;
    }
    // Candidates keep half the spacing of the ring above the kept ones from them.
    let (theta_kept, theta_above) = (z_kept.clamp(-1.0, 1.0).acos(), z_above.clamp(-1.0, 1.0).acos());
    let theta_max = theta_kept - 0.5 * (theta_kept - theta_above);
    let z_min = theta_max.cos();
    // Candidates uniform in area on the zone z >= z_min (Archimedes: uniform in z), along an
    // additive recurrence of the plastic number (a low-discrepancy sequence: deterministic).
    let count = CANDIDATES_PER_VERTEX * interior;
    let g = 1.324_717_957_244_746_f64;
    let (a1, a2) = (1.0 / g, 1.0 / (g * g));
    let cap_points: Vec<[f64; 3]> = (0..count)
        .map(|i| {
            let i = (i + variant * count) as f64;
            let u = (0.5 + a1 * i).fract();
            let v = (0.5 + a2 * i).fract();
            let z = z_min + (1.0 - z_min) * u;
            let r = ((1.0 - z) * (1.0 + z)).max(0.0).sqrt();
            let phi = std::f64::consts::TAU * v;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect();
    let lifted = place(&cap_points);
    let rim_points: Vec<[f64; 3]> = grid.vertices.iter().filter(|p| is_kept(p)).copied().collect();
    let rim_lifted: Vec<[f64; 3]> = place(&rim_points).into_iter().collect::<Option<_>>()?;
    let candidates: Vec<(usize, [f64; 3])> = lifted.iter().enumerate().filter_map(|(i, x)| x.map(|x| (i, x))).collect();
    // Cap lengths against surface lengths: the map's mean length scale.
    let scale = (std::f64::consts::TAU * (1.0 - z_rim) / surface_area).sqrt();
    // The spacing: bisected (in log) until the greedy sample has the grid's interior count.
    // Bracketed around the spacing of a hexagonal packing of the interior count on the
    // surface's area (a greedy sample packs less densely, at a somewhat smaller spacing).
    let hexagonal = (surface_area / (0.75f64.sqrt() * interior as f64)).sqrt();
    let (mut lo, mut hi) = (0.25 * hexagonal, 2.0 * hexagonal);
    let mut best: Option<Vec<usize>> = None;
    for _ in 0..SPACING_STEPS {
        let r = (lo * hi).sqrt();
        let accepted = poisson_disk(&candidates, &cap_points, &rim_lifted, &rim_points, r, NEAR_ON_CAP * r * scale);
        if accepted.len() > interior {
            lo = r;
        } else {
            hi = r;
        }
        let off = accepted.len().abs_diff(interior);
        if best.as_ref().map_or(true, |b| off < b.len().abs_diff(interior)) {
            best = Some(accepted);
        }
        if off * COUNT_TOLERANCE <= interior {
            break;
        }
    }
    let accepted = best?;
    // Interior points first, the rim last (as in the grid).
    let mut vertices: Vec<[f64; 3]> = accepted.iter().map(|&i| cap_points[candidates[i].0]).collect();
    let m = vertices.len();
    vertices.extend_from_slice(&rim_points);
    let plane: Vec<[f64; 2]> = vertices.iter().map(|&x| crate::cap::stereographic(x)).collect();
    let tri = RegularTriangulation::delaunay(&plane).ok()?;
    // The hull must be the rim: every hull edge joins two rim vertices, one per rim vertex.
    let hull_edges = tri.neighbors.iter().zip(&tri.triangles).flat_map(|(nb, t)| (0..3).filter(move |&k| nb[k] == NONE).map(move |k| [t[(k + 1) % 3], t[(k + 2) % 3]])).collect::<Vec<_>>();
    if hull_edges.len() != rim || hull_edges.iter().flatten().any(|&v| (v as usize) < m) {
        return None;
    }
    // The grid's orientation in the stereographic plane.
    let grid_ccw = grid.faces.first().map_or(true, |f| {
        let p = f.map(|v| crate::cap::stereographic(grid.vertices[v as usize]));
        crate::mesh::geometry::signed_area_2d(p[0], p[1], p[2]) > 0.0
    });
    let faces = tri.triangles.iter().map(|&[a, b, c]| if grid_ccw { [a, b, c] } else { [a, c, b] }).collect();
    Some(TriMesh::new(vertices, faces))
}

/// The candidates (in order) accepted greedily at 3-D distance at least `r` from every accepted
/// one and from the rim's points `fixed` (cap points `fixed_cap`), unless their cap points are
/// more than `r_cap` apart (two sides of a narrow gap of the surface, as between fingers).
fn poisson_disk(candidates: &[(usize, [f64; 3])], cap: &[[f64; 3]], fixed: &[[f64; 3]], fixed_cap: &[[f64; 3]], r: f64, r_cap: f64) -> Vec<usize> {
    let cell = |x: [f64; 3]| x.map(|c| (c / r).floor() as i64);
    // Accepted points by grid cell: surface point and cap point.
    type Cells = crate::mesh::fasthash::FastMap<[i64; 3], Vec<([f64; 3], [f64; 3])>>;
    let mut grid: Cells = Default::default();
    for (&x, &y) in fixed.iter().zip(fixed_cap) {
        grid.entry(cell(x)).or_default().push((x, y));
    }
    let (r2, rc2) = (r * r, r_cap * r_cap);
    let d2 = |a: [f64; 3], b: [f64; 3]| {
        let d = sub(a, b);
        d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    };
    let mut accepted = Vec::new();
    for (i, &(j, x)) in candidates.iter().enumerate() {
        let (c, y) = (cell(x), cap[j]);
        let mut free = true;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(points) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                        if points.iter().any(|&(p, q)| d2(p, x) < r2 && d2(q, y) < rc2) {
                            free = false;
                            break 'search;
                        }
                    }
                }
            }
        }
        if free {
            grid.entry(c).or_default().push((x, y));
            accepted.push(i);
        }
    }
    accepted
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::geometry::norm;
    use crate::mesh::validate;
    use crate::mesh::SurfaceKind;
    use crate::remesh::grid::uniform_cap;

    /// Smallest distance between two of `points`.
    fn closest_pair(points: &[[f64; 3]]) -> f64 {
        let mut best = f64::INFINITY;
        for (i, a) in points.iter().enumerate() {
            for b in &points[i + 1..] {
                best = best.min(norm(sub(*a, *b)));
            }
        }
        best
    }

    /// On the cap itself (the identity map) the grid is near-isotropic and is kept; the sample
    /// made anyway is an open disk with the grid's rim, about its vertex count, on the cap.
    #[test]
    fn the_cap_itself_keeps_its_grid_and_samples_a_disk() {
        let z0 = -0.3;
        let grid = uniform_cap(z0, 2000);
        let place = |p: &[[f64; 3]]| p.iter().map(|&x| Some(x)).collect::<Vec<_>>();
        let area = std::f64::consts::TAU * (1.0 - z0);
        assert!(grid_is_isotropic(&grid, &place), "the cap's own grid is near-isotropic");
        let sample = isotropic_cap(&grid, area, &place, 0).expect("a sample of the cap");
        assert_eq!(validate(&sample).unwrap().0, SurfaceKind::OpenDisk);
        let rim = grid.vertices.iter().rev().take_while(|p| p[2] == z0).count();
        assert_eq!(sample.vertices[sample.vertices.len() - rim..], grid.vertices[grid.vertices.len() - rim..]);
        let (n, m) = (sample.vertices.len() as f64, grid.vertices.len() as f64);
        assert!((n - m).abs() <= 0.02 * m, "{n} vertices against the grid's {m}");
        assert!(sample.vertices.iter().all(|p| (norm(*p) - 1.0).abs() < 1e-12 && p[2] >= z0 - 1e-12));
        // Poisson-disk: no two points much closer than the spacing of n points on the area.
        let spacing = (area / n).sqrt();
        assert!(closest_pair(&sample.vertices) > 0.5 * spacing, "{} against {spacing}", closest_pair(&sample.vertices));
    }

    /// A surface that stretches the cap three times one way and a third the other: the grid's
    /// lift is anisotropic, so the sample is used, and its lifted points keep their distance
    /// in every direction where the grid's crowd along the compressed one.
    #[test]
    fn a_stretched_surface_gets_an_evenly_spread_sample() {
        let z0 = 0.0;
        let grid = uniform_cap(z0, 1500);
        let stretch = |x: [f64; 3]| [3.0 * x[0], x[1] / 3.0, x[2]];
        let place = |p: &[[f64; 3]]| p.iter().map(|&x| Some(stretch(x))).collect::<Vec<_>>();
        let area = std::f64::consts::TAU * (1.0 - z0);
        assert!(!grid_is_isotropic(&grid, &place), "the stretched grid is not kept");
        let sample = isotropic_cap(&grid, area, &place, 1).expect("a sample");
        // The interior points (the rim ring is the grid's in both).
        let rim = grid.vertices.iter().rev().take_while(|p| p[2] == z0).count();
        let lift = |m: &TriMesh| m.vertices[..m.vertices.len() - rim].iter().map(|&x| stretch(x)).collect::<Vec<_>>();
        let (s, g) = (closest_pair(&lift(&sample)), closest_pair(&lift(&grid)));
        assert!(s > 1.5 * g, "closest pair {s} on the sample's lift, {g} on the grid's");
    }
}
