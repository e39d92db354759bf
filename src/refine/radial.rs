//! Radial mass correction of a planar map (ours; docs/method.md section 20): every free vertex
//! moves along its ray from the disk's centre so that the vertices within each radius cover,
//! on the domain, their share of the surface's area. It removes a map's error in the radial
//! marginal of the area, a smooth error that the face-level refinement ([`super::area_refine`])
//! removes only slowly: a multilevel map's band of compressed faces around the puncture, left
//! by its decimated copy.

use crate::cap::Domain;
use crate::mesh::geometry::{folded_faces, vertex_areas};
use std::f64::consts::PI;

/// Radial bins of the correction: the correction is piecewise linear in the radius between
/// the bins' edges, each bin holding as many free vertices (at least [`MIN_BIN_VERTICES`]).
const BINS: usize = 256;

/// Fewest free vertices per bin: fewer bins on small meshes, so that the correction stays
/// smooth at the scale of a ring of vertices.
const MIN_BIN_VERTICES: usize = 64;

/// Outermost bins whose vertices do not move. Next to a closed surface's puncture the faces
/// cover more of the domain than their share whatever the map (the four corners of the
/// punctured quad on the rim leave circular segments for them to fill, docs/method.md
/// section 9), and correcting them squeezed everything else: with the last bin free the
/// corrected 130k folded surface's map folded faces, with 2, 4 or 8 held it came to mean
/// |d_area| 0.0050 from 0.0057, and the 194k brain's to 0.0073, 0.0074, 0.0078 from 0.0082.
const HELD_BINS: usize = 2;

/// Radii closer than this fraction of the disk's radius count as one (a ring of a regular
/// mesh, whose radii differ by rounding): a bin edge never passes between them.
const SAME_RADIUS: f64 = 1e-9;

/// Rounds of putting back the corners of faces the correction folded.
const REVERT_ROUNDS: usize = 20;

/// What the correction did.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct RadialReport {
    /// Largest move of a vertex, relative to the disk's radius.
    pub max_move: f64,
    /// Whether the corrected map was kept (it is not when it would fold a face).
    pub kept: bool,
    /// Vertices put back where their move folded a face.
    pub reverted: usize,
}

/// The area of `domain` within planar radius `rho`: the unit sphere's cap that the inverse
/// stereographic projection puts there, `4 pi rho^2 / (1 + rho^2)`, or the planar disk's.
fn area_within(domain: Domain, rho: f64) -> f64 {
    if domain == Domain::Disk { PI * rho * rho } else { 4.0 * PI * rho * rho / (1.0 + rho * rho) }
}

/// The planar radius within which `domain` has area `a` ([`area_within`]'s inverse).
fn radius_of_area(domain: Domain, a: f64) -> f64 {
    if domain == Domain::Disk { (a / PI).max(0.0).sqrt() } else { (a / (4.0 * PI - a)).max(0.0).sqrt() }
}

/// Move the free vertices of `plane` (the map of `faces` onto a disk of radius `radius`
/// centred at the origin, whose `fixed` vertices lie on the rim; lifted onto `domain`)
/// radially so that the domain area within each radius is the share of the surface's
/// (`vertices`) area of the vertices inside it. The corrected map is kept only when it folds
/// no face that was unfolded.
pub(crate) fn correct_radially(plane: &mut [[f64; 2]], vertices: &[[f64; 3]], faces: &[[u32; 3]], fixed: &[bool], radius: f64, domain: Domain) -> RadialReport {
    let mass = vertex_areas(vertices, faces);
    let mut free: Vec<usize> = (0..plane.len()).filter(|&v| !fixed[v] && mass[v] > 0.0).collect();
    let bins = (free.len() / MIN_BIN_VERTICES).min(BINS);
    let total: f64 = (0..plane.len()).map(|v| mass[v]).sum();
    if bins < 2 || !(total > 0.0) {
        return RadialReport::default();
    }
    let radii: Vec<f64> = plane.iter().map(|p| p[0].hypot(p[1])).collect();
    let r = |v: usize| radii[v];
    free.sort_by(|&a, &b| r(a).total_cmp(&r(b)).then(a.cmp(&b)));
    // Bin edges at equal counts of free vertices: the radius there and the mass inside it
    // (the fixed rim is outside every edge but the last).
    let mut edges: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    let (mut inside, mut lo) = (0.0, 0);
    let mut masses = Vec::with_capacity(bins);
    for k in 1..bins {
        // The edge halfway between the last vertex of this bin and the first of the next,
        // past any vertices at the same radius (a ring of a regular mesh is not split).
        let mut hi = (k * free.len() / bins).max(lo + 1);
        while hi < free.len() && r(free[hi]) <= r(free[hi - 1]) + SAME_RADIUS * radius {
            hi += 1;
        }
        if hi >= free.len() {
            break;
        }
        inside += free[lo..hi].iter().map(|&v| mass[v]).sum::<f64>();
        edges.push((0.5 * (r(free[hi - 1]) + r(free[hi])), 0.0));
        masses.push(inside);
        lo = hi;
    }
    if masses.is_empty() {
        return RadialReport::default();
    }
    // The outermost bins are held (HELD_BINS): the anchor's domain area is shared by the
    // masses inside it.
    let anchor = edges.len() - HELD_BINS.min(edges.len() - 1);
    let (r_anchor, m_anchor) = (edges[anchor].0, masses[anchor - 1]);
    let a_anchor = area_within(domain, r_anchor);
    for k in 1..edges.len() {
        edges[k].1 = if k < anchor { radius_of_area(domain, a_anchor * masses[k - 1] / m_anchor) } else { edges[k].0 };
    }
    edges.push((radius, radius));
    let before = folded_faces(plane, faces).len();
    let old: Vec<[f64; 2]> = plane.to_vec();
    let mut max_move = 0.0f64;
    for &v in &free {
        let rv = r(v);
        let k = edges.partition_point(|e| e.0 <= rv).clamp(1, edges.len() - 1);
        let ((r0, s0), (r1, s1)) = (edges[k - 1], edges[k]);
        let t = if r1 > r0 { ((rv - r0) / (r1 - r0)).clamp(0.0, 1.0) } else { 0.0 };
        let target = s0 + t * (s1 - s0);
        if rv > 0.0 && target.is_finite() {
            let scale = target / rv;
            plane[v] = [plane[v][0] * scale, plane[v][1] * scale];
            max_move = max_move.max((target - rv).abs() / radius);
        }
    }
    // A face folded by the moves (a sliver of the map turned over by a move of a fraction of
    // a percent of the radius): its corners go back, until no face that was unfolded is
    // folded.
    let mut reverted = 0;
    let mut folded = folded_faces(plane, faces);
    for _ in 0..REVERT_ROUNDS {
        if folded.len() <= before {
            break;
        }
        for &f in &folded {
            for &v in &faces[f] {
                let v = v as usize;
                if plane[v] != old[v] {
                    plane[v] = old[v];
                    reverted += 1;
                }
            }
        }
        folded = folded_faces(plane, faces);
    }
    let kept = folded.len() <= before;
    if !kept {
        plane.copy_from_slice(&old);
    }
    RadialReport { max_move, kept, reverted }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cap::{inverse_stereographic, radius_of_z_star, stereographic};
    use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};
    use crate::mesh::topology::is_boundary_vertex;
    use crate::metrics::{area_distortion, Stats};

    /// A spherical cap is mapped exactly by the stereographic projection (its faces lift back
    /// onto themselves). Distorted radially inside 0.8 of its radius (`r -> r (1 + 0.25
    /// sin^2(pi r / 0.8 R))`, a band of faces too large, then too small), the correction
    /// brings the mean |d_area| down to a twentieth, folding nothing; the exact map is left within
    /// a hundredth of an edge.
    #[test]
    fn a_radially_distorted_cap_comes_back() {
        let z0 = -0.5;
        let cap = spherical_cap(z0, 40, spherical_cap_sectors(z0, 40));
        let fixed = is_boundary_vertex(&cap);
        let radius = radius_of_z_star(z0);
        let exact: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        let d_area = |plane: &[[f64; 2]]| {
            let lifted: Vec<[f64; 3]> = plane.iter().map(|&q| inverse_stereographic(q)).collect();
            Stats::of(area_distortion(&cap.vertices, &lifted, &cap.faces)).mean_abs
        };
        let mut distorted: Vec<[f64; 2]> = exact
            .iter()
            .map(|q| {
                let r = q[0].hypot(q[1]);
                let t = std::f64::consts::PI * r / (0.8 * radius);
                let s = if t < std::f64::consts::PI { 1.0 + 0.25 * t.sin().powi(2) } else { 1.0 };
                [q[0] * s, q[1] * s]
            })
            .collect();
        let before = d_area(&distorted);
        let report = correct_radially(&mut distorted, &cap.vertices, &cap.faces, &fixed, radius, Domain::Adaptive);
        let after = d_area(&distorted);
        eprintln!("mean |d_area| {before} -> {after}, {report:?}");
        assert!(report.kept && folded_faces(&distorted, &cap.faces).is_empty(), "{report:?}");
        assert!(before > 0.05 && after < 0.05 * before, "mean |d_area| {before} -> {after}");
        let edge = radius / 40.0;
        let mut same = exact.clone();
        let report = correct_radially(&mut same, &cap.vertices, &cap.faces, &fixed, radius, Domain::Adaptive);
        assert!(report.kept && report.max_move * radius < 0.01 * edge, "{report:?}");
    }
}
