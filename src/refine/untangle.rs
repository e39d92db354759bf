//! Repair of folded faces in the planar transport map.
//!
//! Placing each vertex at the centroid of its power cell (Zhao et al. 2013) does not guarantee
//! an orientation-preserving piecewise-linear map: where the initial map squeezed a protrusion
//! (ears, fingers) a few triangles can fold. After single-vertex kernel moves, the folds left
//! go to an untangling-energy minimization over a few rings around them
//! ([`super::energy_untangle`]); if that fails, the repair solves one Tutte-type system
//! (Floater's convex combination maps), first near the folds and growing outwards: every
//! vertex of the region becomes a convex combination of its
//! neighbours, with the mean value coordinates of its transport position where that position
//! lies in the kernel of its neighbours' polygon (the weights then reproduce it exactly) and
//! uniform weights where it does not. With positive weights and the boundary on the circle the
//! result is an embedding (Tutte 1963, Floater 2003), and where the transport map was already
//! valid it changes only near the folds.

use super::boundary_polygon::{fit_into_boundary_polygon, PolygonFit};
use super::energy_untangle::energy_repair;
use super::kernel_untangle::kernel_untangle;
use crate::linalg::{LuSolver, TripletList};
use crate::mesh::geometry::folded_faces;
use rayon::prelude::*;

/// What the repair did.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct UntangleReport {
    /// Folded faces before the repair.
    pub folded_before: usize,
    /// Vertices moved into the boundary polygon first (see `super::boundary_polygon`).
    pub fitted_into_polygon: usize,
    /// Single-vertex moves into one-ring kernels (the first, local stage, and after each
    /// region solve, counted over all attempts).
    pub kernel_moves: usize,
    /// Vertices whose position was not a positive combination of their neighbours (they got
    /// uniform weights).
    pub uniform_vertices: usize,
    /// New region growths started around the folds an attempt left (see `untangle`).
    pub restarts: usize,
    /// Vertices of the largest region of the energy minimization (`super::energy_untangle`)
    /// that repaired the folds the kernel moves left (0 when it was not needed or did not
    /// succeed).
    pub energy_region: usize,
    /// Largest displacement of a vertex, relative to the disk radius.
    pub max_displacement: f64,
    /// Folded faces left (0 unless the solve failed).
    pub folded_after: usize,
}

/// Ordered (counter-clockwise) one-ring of every vertex whose fan closes; `None` elsewhere.
pub fn ordered_rings(n: usize, faces: &[[u32; 3]]) -> Vec<Option<Vec<u32>>> {
    // next[v]: list of (a, b) with face (v, a, b).
    let mut fans: Vec<Vec<(u32, u32)>> = vec![Vec::new(); n];
    for f in faces {
        for k in 0..3 {
            fans[f[k] as usize].push((f[(k + 1) % 3], f[(k + 2) % 3]));
        }
    }
    fans.into_iter()
        .map(|fan| {
            let first = fan.first()?.0;
            let mut ring = Vec::with_capacity(fan.len());
            let mut cur = first;
            for _ in 0..fan.len() {
                ring.push(cur);
                cur = fan.iter().find(|(a, _)| *a == cur)?.1;
            }
            (cur == first).then_some(ring)
        })
        .collect()
}

/// Mean value coordinates of `p` in the polygon `ring` (counter-clockwise), or `None` when
/// `p` is not strictly inside its kernel.
fn mean_value_weights(p: [f64; 2], ring: &[[f64; 2]]) -> Option<Vec<f64>> {
    let m = ring.len();
    let d: Vec<[f64; 2]> = ring.iter().map(|q| [q[0] - p[0], q[1] - p[1]]).collect();
    let r: Vec<f64> = d.iter().map(|v| (v[0] * v[0] + v[1] * v[1]).sqrt()).collect();
    if r.contains(&0.0) {
        return None;
    }
    let mut tan_half = Vec::with_capacity(m);
    let mut total = 0.0;
    for j in 0..m {
        let (a, b) = (d[j], d[(j + 1) % m]);
        let cr = a[0] * b[1] - a[1] * b[0];
        let dt = a[0] * b[0] + a[1] * b[1];
        let ang = cr.atan2(dt);
        if ang <= 0.0 {
            return None;
        }
        total += ang;
        tan_half.push((0.5 * ang).tan());
    }
    if (total - 2.0 * std::f64::consts::PI).abs() > 1e-6 {
        return None;
    }
    Some((0..m).map(|j| (tan_half[(j + m - 1) % m] + tan_half[j]) / r[j]).collect())
}

/// Unfold `pos` in place if any face is folded. `fixed[v]` marks vertices that must not move
/// (the boundary, on the circle of radius `radius`).
///
/// Vertices outside the polygon of the fixed ones are first moved into it
/// ([`fit_into_boundary_polygon`]): no fold-free map has them there. Then single vertices
/// move into the kernels of their rings ([`kernel_untangle`]); folds that this leaves go to
/// the energy minimization over 2 to 32 rings around them (`energy_repair`), and if no
/// region is enough, to the convex-combination solve, local first: only vertices in planar discs and
/// rings of the mesh around the folded faces move (the rest act as its boundary), both
/// growing until no fold is left (`RegionGrowth` below); the last resort is the whole mesh with
/// the fixed boundary. An attempt that unties the folds its growth started from (or leaves
/// fewer) but folds faces at its rim is kept, and a new growth starts around the folds it
/// left ([`RESTARTS`] at most). The attempt with the fewest folds left is kept (with only a few fixed
/// vertices, as on a punctured closed surface, the whole-mesh solve can fold more than a
/// local one).
pub fn untangle(pos: &mut [[f64; 2]], faces: &[[u32; 3]], fixed: &[bool], radius: f64) -> UntangleReport {
    match untangle_locally(pos, faces, fixed, radius) {
        Ok(report) => report,
        Err(pending) => pending.finish(pos, faces, fixed, radius),
    }
}

/// A fold repair whose local stages (kernel moves, the energy minimization) left folds: the
/// convex-combination solves of [`PendingRepair::finish`] are still to be made.
pub(crate) struct PendingRepair {
    report: UntangleReport,
    /// The positions before any repair.
    start: Vec<[f64; 2]>,
    /// The folded faces the local stages left.
    folded: Vec<usize>,
}

impl PendingRepair {
    /// The report as it would be if the repair stopped here (the folds left counted).
    pub(crate) fn report_so_far(&self, pos: &[[f64; 2]], radius: f64) -> UntangleReport {
        UntangleReport { folded_after: self.folded.len(), max_displacement: max_displacement(pos, &self.start, radius), ..self.report }
    }

    /// The convex-combination solves on `pos` as the local stages left it (see [`untangle`]).
    pub(crate) fn finish(self, pos: &mut [[f64; 2]], faces: &[[u32; 3]], fixed: &[bool], radius: f64) -> UntangleReport {
        let rings = ordered_rings(pos.len(), faces);
        convex_combination_repair(pos, faces, fixed, radius, &rings, self)
    }
}

/// The local stages of [`untangle`]: the fit into the boundary polygon, kernel moves and the
/// energy minimization. `Err` when folds are left for the convex-combination solves; their
/// cost grows with the region they need, and the smoothing's candidates call them only when
/// no candidate is fold-free without them (`super::smoothing`).
pub(crate) fn untangle_locally(pos: &mut [[f64; 2]], faces: &[[u32; 3]], fixed: &[bool], radius: f64) -> Result<UntangleReport, PendingRepair> {
    let folded = folded_faces(pos, faces);
    let mut report = UntangleReport { folded_before: folded.len(), ..Default::default() };
    if folded.is_empty() {
        return Ok(report);
    }
    let rings = ordered_rings(pos.len(), faces);
    let start = pos.to_vec();
    if let PolygonFit::Moved(m) = fit_into_boundary_polygon(pos, fixed, radius) {
        report.fitted_into_polygon = m;
    }
    report.kernel_moves = kernel_untangle(pos, faces, &rings, fixed);
    let folded = folded_faces(pos, faces);
    if folded.is_empty() {
        report.max_displacement = max_displacement(pos, &start, radius);
        return Ok(report);
    }
    if let Some(size) = energy_repair(pos, faces, &rings, fixed, &folded) {
        report.energy_region = size;
        report.max_displacement = max_displacement(pos, &start, radius);
        return Ok(report);
    }
    Err(PendingRepair { report, start, folded })
}

/// The convex-combination solves of [`untangle`], from where the local stages left `pos`.
fn convex_combination_repair(pos: &mut [[f64; 2]], faces: &[[u32; 3]], fixed: &[bool], radius: f64, rings: &[Option<Vec<u32>>], pending: PendingRepair) -> UntangleReport {
    let PendingRepair { mut report, start, folded } = pending;
    let n = pos.len();
    let mut original = pos.to_vec();
    let mut growth = RegionGrowth::new(&folded, faces, &original, rings, radius);
    // The folded faces at the start of the current growth (a round): an attempt that unfolds
    // all of them, or leaves fewer folds than the round started with, starts a new round of
    // small regions around the folds it left (see `RESTARTS`).
    let mut round_start = folded;
    let (mut restarts, mut attempt) = (0usize, 0usize);
    // The attempt with the fewest folds left (the region grows, so ties keep the smaller one).
    let mut best: Option<(usize, Vec<[f64; 2]>, usize)> = None;
    loop {
        attempt += 1;
        let region = growth.grow(rings);
        let whole = (0..n).all(|v| region[v] || fixed[v] || rings[v].is_none());
        pos.copy_from_slice(&original);
        let movable: Vec<bool> = (0..n).map(|v| region[v] && !fixed[v] && rings[v].is_some()).collect();
        let uniform = convex_combination_solve(pos, rings, &movable);
        // The solve unties the region's tangles but can fold faces at its rim, where the
        // region's outline is not convex at the scale of its faces; single-vertex kernel moves
        // fix part of those, so fewer and smaller attempts are needed.
        let mut left = folded_faces(pos, faces);
        if !left.is_empty() {
            report.kernel_moves += kernel_untangle(pos, faces, rings, fixed);
            left = folded_faces(pos, faces);
        }
        if best.as_ref().map_or(true, |(b, ..)| left.len() < *b) {
            best = Some((left.len(), pos.to_vec(), uniform));
        }
        if left.is_empty() || whole {
            break;
        }
        let untied = round_start.iter().all(|f| left.binary_search(f).is_err());
        let near = left.len() <= 2 * round_start.len() + RESTART_SLACK;
        if (left.len() < round_start.len() || (untied && near)) && restarts < RESTARTS {
            // This round's tangles are undone (or fewer are left): keep the attempt and
            // repair what is left in regions around those folds, instead of growing this
            // round's region towards the whole mesh.
            restarts += 1;
            report.restarts = restarts;
            original.copy_from_slice(pos);
            growth = RegionGrowth::new(&left, faces, &original, rings, radius);
            round_start = left;
            attempt = 0;
        } else if attempt >= MAX_REGION_ATTEMPTS {
            break;
        }
    }
    if let Some((left, kept, uniform)) = best {
        pos.copy_from_slice(&kept);
        report.folded_after = left;
        report.uniform_vertices = uniform;
    }
    report.max_displacement = max_displacement(pos, &start, radius);
    report
}

/// Which vertices the convex-combination solve may move: the union of planar discs around the
/// folded faces and rings of the mesh around them, both growing at each attempt.
///
/// A disc is centred at a folded face's centroid with the radius of its corners' one-rings
/// (seen from that centroid); the first attempt takes the vertices within half of those
/// radii, each next one doubles the scale, but takes at most four times as many vertices as
/// the last: near a closed surface's puncture a few faces span much of the disk, and one
/// doubling of their discs went from 596 vertices to the whole 164k-vertex ellipsoid.
/// The rings are `k = 2, 4, 8, ...` rings of the mesh around the folded faces.
///
/// The first version grew by rings only: on the hand, whose fingers the transport map
/// compresses unevenly, `k` rings are a long, non-convex strip in the plane, and a Tutte solve
/// inside a non-convex outline folds faces at the rim (Floater's guarantee needs a convex
/// boundary); two of the three smoothing candidates went through every attempt to `k = 64`
/// (25k-30k vertices). With the discs, convex in the plane, the same folds went with regions
/// of 1k-8k vertices. Discs alone left one fold next to the puncture of the 164k ellipsoid
/// at every size up to the whole mesh, which the rings repair.
struct RegionGrowth {
    /// The ring region and how many rings it has grown.
    ring: Vec<bool>,
    grown: usize,
    /// Per vertex, the smallest `distance / radius` to a disc's centre, the same values
    /// sorted, and the last attempt's scale (0 before the first); `None` with very many
    /// folds ([`DISC_EVALUATIONS`]).
    discs: Option<(Vec<f64>, Vec<f64>, f64)>,
}

/// New region growths at most that start from an attempt which untied the folds its growth
/// started from (or left fewer), around the folds it left ([`untangle`]). Measured on the
/// 48k brain midpoint-subdivided once (194k vertices, `kappa = 1`, bottom end): the 3 folds
/// left by the kernel moves became 37, 8, 5 and 8 with regions of 904 to 57k vertices, and
/// only the whole-mesh solve left none, squeezing the map to mean `|d_area|` 2.6 (the lambda
/// fallback then took a second full parameterization). With new rounds around the folds
/// left, 8 folds went to 26, 12 and 0 in regions of 108 to 358 vertices (the best end,
/// mean `|d_area|` 0.0103 instead of 3.3): the rim folds of a solve are local.
const RESTARTS: usize = 16;

/// Folds an attempt that untied its round's folds may leave, beyond twice the round's, and
/// still start a new round ([`untangle`]): more rim folds than that is a solve that went
/// wrong (on the 194k brain, restarting from any untying attempt went from 37 folds to 397,
/// 727 and on to the whole mesh).
const RESTART_SLACK: usize = 16;

/// Attempts at most (the discs grow by `2^48` over them: from `1e-12` of the disk's radius
/// to all of it; a mesh whose region cannot grow to every vertex stops here too).
const MAX_REGION_ATTEMPTS: usize = 48;

/// Above this many vertex-disc distance evaluations (vertices times folded faces) the region
/// grows by rings only, whose cost is that of the region.
const DISC_EVALUATIONS: usize = 50_000_000;

impl RegionGrowth {
    fn new(folded: &[usize], faces: &[[u32; 3]], pos: &[[f64; 2]], rings: &[Option<Vec<u32>>], radius: f64) -> Self {
        let n = pos.len();
        let mut ring = vec![false; n];
        for &f in folded {
            for &v in &faces[f] {
                ring[v as usize] = true;
            }
        }
        let discs = (folded.len().saturating_mul(n) <= DISC_EVALUATIONS).then(|| {
            let distance = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
            let discs: Vec<([f64; 2], f64)> = folded
                .iter()
                .map(|&f| {
                    let c = faces[f].map(|v| pos[v as usize]);
                    let centre = [(c[0][0] + c[1][0] + c[2][0]) / 3.0, (c[0][1] + c[1][1] + c[2][1]) / 3.0];
                    let r = faces[f]
                        .iter()
                        .filter_map(|&v| rings[v as usize].as_ref())
                        .flatten()
                        .map(|&u| distance(pos[u as usize], centre))
                        .fold(1e-12 * radius, f64::max);
                    (centre, r)
                })
                .collect();
            let reach: Vec<f64> = pos.par_iter().map(|&p| discs.iter().map(|&(c, r)| distance(p, c) / r).fold(f64::INFINITY, f64::min)).collect();
            let mut sorted = reach.clone();
            sorted.par_sort_unstable_by(f64::total_cmp);
            (reach, sorted, 0.0)
        });
        Self { ring, grown: 0, discs }
    }

    /// The next, larger region.
    fn grow(&mut self, rings: &[Option<Vec<u32>>]) -> Vec<bool> {
        let target = if self.grown == 0 { 2 } else { self.grown * 2 };
        while self.grown < target {
            let current: Vec<usize> = (0..self.ring.len()).filter(|&v| self.ring[v]).collect();
            for v in current {
                if let Some(ring) = &rings[v] {
                    for &u in ring {
                        self.ring[u as usize] = true;
                    }
                }
            }
            self.grown += 1;
        }
        let mut region = self.ring.clone();
        if let Some((reach, sorted, scale)) = self.discs.as_mut() {
            *scale = if *scale == 0.0 {
                0.5
            } else {
                let taken = sorted.partition_point(|&d| d <= *scale);
                sorted.get(4 * taken.max(1)).map_or(2.0 * *scale, |&cap| cap.min(2.0 * *scale))
            };
            for (r, &d) in region.iter_mut().zip(reach.iter()) {
                *r |= d <= *scale;
            }
        }
        region
    }
}

/// Largest distance between `a` and `b`, relative to `radius`.
fn max_displacement(a: &[[f64; 2]], b: &[[f64; 2]], radius: f64) -> f64 {
    a.iter().zip(b).map(|(p, q)| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt() / radius).fold(0.0, f64::max)
}

/// Solve for the `movable` vertices as convex combinations of their rings (mean value
/// coordinates where the current position allows, uniform otherwise); returns how many got
/// uniform weights. On a solver failure the positions are left unchanged.
///
/// Measured and dropped (issue 27): GMRES (restart 40) preconditioned by the Cholesky factor
/// of the same system with symmetrised weights `(w_ij + w_ji) / 2`, for regions of 20k
/// vertices and more. It converged (11-12 steps per coordinate at relative residual 1e-12,
/// the LU's solution to 4e-12) but was not faster: whole-mesh solves of jittered harmonic
/// maps took 0.60 / 3.79 / 14.96 CPU s against the LU's 0.50 / 2.51 / 14.00 on the 48k,
/// 194k and 776k brains (one run each, machine shared). At 776k vertices this LU, called
/// from the smoothing candidates' region growths, was 36% of the profile.
fn convex_combination_solve(pos: &mut [[f64; 2]], rings: &[Option<Vec<u32>>], movable: &[bool]) -> usize {
    let n = pos.len();
    let mut index = vec![usize::MAX; n];
    let mut m = 0;
    for v in 0..n {
        if movable[v] {
            index[v] = m;
            m += 1;
        }
    }
    let mut uniform = 0;
    let mut trip = TripletList::with_capacity(m, 8 * m);
    let mut rhs = vec![vec![0.0; m], vec![0.0; m]];
    for v in 0..n {
        let (i, Some(ring)) = (index[v], rings[v].as_ref()) else { continue };
        if i == usize::MAX {
            continue;
        }
        let poly: Vec<[f64; 2]> = ring.iter().map(|&u| pos[u as usize]).collect();
        let w = mean_value_weights(pos[v], &poly).unwrap_or_else(|| {
            uniform += 1;
            vec![1.0; ring.len()]
        });
        let sum: f64 = w.iter().sum();
        trip.push(i, i, 1.0);
        for (&u, wu) in ring.iter().zip(&w) {
            let wu = wu / sum;
            if index[u as usize] != usize::MAX {
                trip.push(i, index[u as usize], -wu);
            } else {
                rhs[0][i] += wu * pos[u as usize][0];
                rhs[1][i] += wu * pos[u as usize][1];
            }
        }
    }
    if m == 0 {
        return uniform;
    }
    let solved = trip.assemble("fold repair").and_then(|mat| {
        let mut solver = LuSolver::new();
        solver.factor(&mat, "fold repair")?;
        solver.solve_in_place(&mut rhs, "fold repair")
    });
    if solved.is_ok() {
        for v in 0..n {
            let i = index[v];
            if i != usize::MAX {
                pos[v] = [rhs[0][i], rhs[1][i]];
            }
        }
    }
    uniform
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cap::stereographic;
    use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};
    use crate::mesh::topology::is_boundary_vertex;

    #[test]
    fn a_patch_turned_over_is_repaired_near_it_only() {
        let cap = spherical_cap(0.0, 40, spherical_cap_sectors(0.0, 40));
        let fixed = is_boundary_vertex(&cap);
        let start: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        // Turn the vertices within 0.06 of (0.4, 0.2) half a turn about it: the patch's rim
        // faces fold over.
        let (centre, patch) = ([0.4, 0.2], 0.06);
        let mut pos = start.clone();
        for p in pos.iter_mut() {
            if (p[0] - centre[0]).hypot(p[1] - centre[1]) < patch {
                *p = [2.0 * centre[0] - p[0], 2.0 * centre[1] - p[1]];
            }
        }
        let rep = untangle(&mut pos, &cap.faces, &fixed, 1.0);
        assert!(rep.folded_before > 10, "{rep:?}");
        assert_eq!(rep.folded_after, 0, "{rep:?}");
        assert!(folded_faces(&pos, &cap.faces).is_empty());
        let far_moved = pos
            .iter()
            .zip(&start)
            .filter(|(_, q)| (q[0] - centre[0]).hypot(q[1] - centre[1]) > 0.5)
            .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
            .fold(0.0, f64::max);
        assert_eq!(far_moved, 0.0, "vertices far from the patch moved ({rep:?})");
        for v in (0..pos.len()).filter(|&v| fixed[v]) {
            assert_eq!(pos[v], start[v]);
        }
    }
}
