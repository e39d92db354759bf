//! Fold repair by minimizing a regularized distortion energy over a small region.
//!
//! The convex-combination solve of [`super::untangle`] is guaranteed fold-free only inside a
//! convex outline; near a closed surface's puncture, where a few faces span a fifth of the
//! disk, its regions reach far inwards and fold faces at their rim, and on large meshes the
//! growth ended in the whole-mesh solve that squeezes the map (issue 27). Here the vertices of
//! a few rings of the mesh around the folds minimize instead the sum over their faces of
//! Garanzha et al.'s untangling energy ("Foldover-free maps in 50 lines of code", ACM TOG
//! 2021), written from the paper:
//! `f(J) = ((1 - theta) |J|^2 + theta (det J^2 + 1)) / chi(det J, eps)` with
//! `chi(D, eps) = (D + sqrt(eps^2 + D^2)) / 2`, `J` the Jacobian from a face's reference
//! shape (its shape when the repair starts, mirrored if it is folded) to its current one.
//! For `eps -> 0` the energy is infinite on folded faces; for `eps > 0` it is finite and
//! smooth, and lowering `eps` as the smallest determinant rises pulls folded faces over.
//! Faces that are not folded start at `J = I`, the energy's minimum, so they move only as far
//! as the folds pull them. The minimization is a Gauss-Seidel sweep of per-vertex Newton
//! steps in a fixed order (the same result on any number of threads); a step never folds
//! more of a vertex's faces than it had folded.

use crate::mesh::geometry::{folded_faces, signed_area_2d};
use crate::mesh::topology::VertexFaces;
use std::collections::HashMap;

/// Weight of the area term against the shape term.
const THETA: f64 = 0.5;

/// Rounds of `eps` updates at most (each sweeps [`SWEEPS_PER_ROUND`] times).
const MAX_ROUNDS: usize = 60;

/// Gauss-Seidel sweeps between `eps` updates. With 8, the bird skull's hardest smoothing
/// candidate needed the whole mesh (and 60 rounds); with 16, 147 vertices and 38 rounds.
const SWEEPS_PER_ROUND: usize = 16;

/// Rounds without fewer folded faces after which an attempt gives up (the caller then tries
/// a larger region): a region whose fixed rim leaves no room keeps its last folds while `eps`
/// shrinks, and on the bird skull such attempts took 60 rounds each before.
const STALL_ROUNDS: usize = 12;

/// Step halvings before a vertex stays.
const HALVINGS: usize = 12;

type M2 = [[f64; 2]; 2];

/// The inverse of the reference edge matrix `[r1 - r0, r2 - r0]` of a face: mirrored when the
/// face is folded, an equilateral triangle of the same mean edge length when it is degenerate.
fn reference_inverse(r: [[f64; 2]; 3]) -> M2 {
    let e1 = [r[1][0] - r[0][0], r[1][1] - r[0][1]];
    let e2 = [r[2][0] - r[0][0], r[2][1] - r[0][1]];
    let len = (e1[0].hypot(e1[1]) + e2[0].hypot(e2[1]) + (e2[0] - e1[0]).hypot(e2[1] - e1[1])) / 3.0;
    let mut m = [[e1[0], e2[0]], [e1[1], e2[1]]];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if det.abs() < 1e-6 * len * len {
        let l = len.max(f64::MIN_POSITIVE.sqrt());
        m = [[l, 0.5 * l], [0.0, 0.5 * 3f64.sqrt() * l]];
    } else if det < 0.0 {
        m[1] = [-m[1][0], -m[1][1]];
    }
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    [[m[1][1] / det, -m[0][1] / det], [-m[1][0] / det, m[0][0] / det]]
}

fn chi(d: f64, eps: f64) -> f64 {
    0.5 * (d + (eps * eps + d * d).sqrt())
}

/// Jacobian of the face `p` against its reference inverse `m`.
fn jacobian(p: [[f64; 2]; 3], m: &M2) -> M2 {
    let e = [[p[1][0] - p[0][0], p[2][0] - p[0][0]], [p[1][1] - p[0][1], p[2][1] - p[0][1]]];
    let mut j = [[0.0; 2]; 2];
    for a in 0..2 {
        for b in 0..2 {
            j[a][b] = e[a][0] * m[0][b] + e[a][1] * m[1][b];
        }
    }
    j
}

fn det(j: &M2) -> f64 {
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

/// The energy of a face with Jacobian `j`.
fn face_energy(j: &M2, eps: f64) -> f64 {
    let d = det(j);
    let frob = j[0][0] * j[0][0] + j[0][1] * j[0][1] + j[1][0] * j[1][0] + j[1][1] * j[1][1];
    ((1.0 - THETA) * frob + THETA * (d * d + 1.0)) / chi(d, eps)
}

/// Gradient of [`face_energy`] with respect to corner `k` of the face.
fn face_gradient(p: [[f64; 2]; 3], m: &M2, k: usize, eps: f64) -> [f64; 2] {
    let j = jacobian(p, m);
    let d = det(&j);
    let frob = j[0][0] * j[0][0] + j[0][1] * j[0][1] + j[1][0] * j[1][0] + j[1][1] * j[1][1];
    let a = (1.0 - THETA) * frob + THETA * (d * d + 1.0);
    let c = chi(d, eps);
    let dc = 0.5 * (1.0 + d / (eps * eps + d * d).sqrt());
    let cof = [[j[1][1], -j[1][0]], [-j[0][1], j[0][0]]];
    let mut g = [[0.0; 2]; 2];
    for r in 0..2 {
        for s in 0..2 {
            let da = 2.0 * (1.0 - THETA) * j[r][s] + 2.0 * THETA * d * cof[r][s];
            g[r][s] = da / c - a / (c * c) * dc * cof[r][s];
        }
    }
    // dE/dedge = G M^T: column 0 for corner 1, column 1 for corner 2.
    let col = |q: usize| [g[0][0] * m[q][0] + g[0][1] * m[q][1], g[1][0] * m[q][0] + g[1][1] * m[q][1]];
    match k {
        1 => col(0),
        2 => col(1),
        _ => {
            let (a, b) = (col(0), col(1));
            [-(a[0] + b[0]), -(a[1] + b[1])]
        }
    }
}

/// Repair the folds among the faces of `region` (vertices that may move; the others stay) by
/// the energy above. Returns whether no face touching the region is folded afterwards; on
/// failure `pos` holds the last iterate. Each sweep spends the region's size from `budget`; an attempt that exhausts it fails.
pub(crate) fn energy_untangle(pos: &mut [[f64; 2]], faces: &[[u32; 3]], incidence: &VertexFaces, region: &[u32], budget: &mut usize) -> bool {
    // Local numbering of the touched faces and their reference inverses.
    let mut local: HashMap<u32, u32> = HashMap::new();
    let mut touched: Vec<u32> = Vec::new();
    for &v in region {
        for &t in incidence.of(v as usize) {
            local.entry(t).or_insert_with(|| {
                touched.push(t);
                (touched.len() - 1) as u32
            });
        }
    }
    let corners = |t: u32, pos: &[[f64; 2]]| faces[t as usize].map(|u| pos[u as usize]);
    let reference: Vec<M2> = touched.iter().map(|&t| reference_inverse(corners(t, pos))).collect();
    // Per region vertex: (local face, corner of the vertex in it).
    let stars: Vec<Vec<(u32, u8)>> = region
        .iter()
        .map(|&v| {
            incidence
                .of(v as usize)
                .iter()
                .map(|&t| (local[&t], faces[t as usize].iter().position(|&u| u == v).unwrap_or(0) as u8))
                .collect()
        })
        .collect();
    let min_det = |pos: &[[f64; 2]]| touched.iter().zip(&reference).map(|(&t, m)| det(&jacobian(corners(t, pos), m))).fold(f64::INFINITY, f64::min);
    let count = |pos: &[[f64; 2]]| touched.iter().filter(|&&t| {
        let c = corners(t, pos);
        signed_area_2d(c[0], c[1], c[2]) <= 0.0
    }).count();
    let folded = |pos: &[[f64; 2]]| count(pos) > 0;
    if !folded(pos) {
        return true;
    }
    let total = |pos: &[[f64; 2]], eps: f64| touched.iter().zip(&reference).map(|(&t, m)| face_energy(&jacobian(corners(t, pos), m), eps)).sum::<f64>();
    let mut dmin = min_det(pos);
    let mut eps = (1e-12 + 0.04 * dmin.min(0.0).powi(2)).sqrt();
    let (mut fewest, mut since) = (count(pos), 0usize);
    for _ in 0..MAX_ROUNDS {
        let now = count(pos);
        if now < fewest {
            (fewest, since) = (now, 0);
        } else {
            since += 1;
            if since > STALL_ROUNDS {
                return false;
            }
        }
        let before = total(pos, eps);
        for _ in 0..SWEEPS_PER_ROUND {
            if *budget < region.len() {
                return false;
            }
            *budget -= region.len();
            for (i, &v) in region.iter().enumerate() {
                newton_step(pos, faces, &touched, &reference, &stars[i], v as usize, eps);
            }
        }
        if !folded(pos) {
            return true;
        }
        let after = total(pos, eps);
        dmin = min_det(pos);
        let sigma = (1.0 - after / before).max(0.1);
        let mu = (1.0 - sigma) * chi(dmin, eps);
        eps = if dmin < mu { 2.0 * (mu * (mu - dmin)).sqrt() } else { 1e-10 };
    }
    !folded(pos)
}

/// One damped Newton step of vertex `v` on the sum of its faces' energies (Hessian by
/// central differences of the gradient).
fn newton_step(pos: &mut [[f64; 2]], faces: &[[u32; 3]], touched: &[u32], reference: &[M2], star: &[(u32, u8)], v: usize, eps: f64) {
    let face_at = |pos: &[[f64; 2]], x: [f64; 2], t: u32| {
        let mut c = faces[touched[t as usize] as usize].map(|u| pos[u as usize]);
        for (k, &u) in faces[touched[t as usize] as usize].iter().enumerate() {
            if u as usize == v {
                c[k] = x;
            }
        }
        c
    };
    let energy = |pos: &[[f64; 2]], x: [f64; 2]| star.iter().map(|&(t, _)| face_energy(&jacobian(face_at(pos, x, t), &reference[t as usize]), eps)).sum::<f64>();
    let gradient = |pos: &[[f64; 2]], x: [f64; 2]| {
        star.iter().fold([0.0; 2], |g, &(t, k)| {
            let d = face_gradient(face_at(pos, x, t), &reference[t as usize], k as usize, eps);
            [g[0] + d[0], g[1] + d[1]]
        })
    };
    let folded_count = |pos: &[[f64; 2]], x: [f64; 2]| star.iter().filter(|&&(t, _)| {
        let c = face_at(pos, x, t);
        signed_area_2d(c[0], c[1], c[2]) <= 0.0
    }).count();
    let x0 = pos[v];
    let e0 = energy(pos, x0);
    let g = gradient(pos, x0);
    if !(e0.is_finite() && g[0].is_finite() && g[1].is_finite()) || g == [0.0; 2] {
        return;
    }
    // Finite-difference step: a millionth of the star's size.
    let size = star
        .iter()
        .flat_map(|&(t, _)| face_at(pos, x0, t))
        .map(|p| (p[0] - x0[0]).abs().max((p[1] - x0[1]).abs()))
        .fold(0.0, f64::max);
    let h = 1e-6 * size.max(f64::MIN_POSITIVE);
    let mut hess = [[0.0; 2]; 2];
    for a in 0..2 {
        let (mut xp, mut xm) = (x0, x0);
        xp[a] += h;
        xm[a] -= h;
        let (gp, gm) = (gradient(pos, xp), gradient(pos, xm));
        for b in 0..2 {
            hess[b][a] = (gp[b] - gm[b]) / (2.0 * h);
        }
    }
    let off = 0.5 * (hess[0][1] + hess[1][0]);
    let (mut h00, mut h11) = (hess[0][0], hess[1][1]);
    // Shift the Hessian until it is positive definite (gradient descent in the limit).
    let trace = h00.abs() + h11.abs();
    let mut shift = 0.0;
    while !(h00 + shift > 0.0 && (h00 + shift) * (h11 + shift) - off * off > 0.0) {
        shift = if shift == 0.0 { 1e-8 * trace.max(1e-300) } else { shift * 10.0 };
        if !shift.is_finite() {
            return;
        }
    }
    h00 += shift;
    h11 += shift;
    let dt = h00 * h11 - off * off;
    let d = [-(h11 * g[0] - off * g[1]) / dt, -(h00 * g[1] - off * g[0]) / dt];
    let folds = folded_count(pos, x0);
    let mut step = 1.0;
    for _ in 0..=HALVINGS {
        let x = [x0[0] + step * d[0], x0[1] + step * d[1]];
        if energy(pos, x) < e0 && folded_count(pos, x) <= folds {
            pos[v] = x;
            return;
        }
        step *= 0.5;
    }
}

/// Rings of the mesh around the folds that `energy_repair` tries, in order.
const ENERGY_RINGS: [usize; 5] = [2, 4, 8, 16, 32];

/// Largest region `energy_repair` tries, unless a 32nd of the mesh is more. Its sweeps cost
/// the region's size each, and where the folds are many and far apart (a closed surface mapped
/// onto the fixed hemisphere: 628 folds on the 48k brain, every attempt failing) attempts up to
/// 32 rings took minutes; on the meshes where it succeeds the region had 34 to 370 vertices.
const ENERGY_MAX_REGION: usize = 2000;

/// Vertex steps (region size times sweeps, over all attempts) `energy_repair` may spend,
/// at least; [`ENERGY_STEPS_PER_VERTEX`] times the mesh's vertices where that is more. Where
/// it succeeds on the bundled meshes and the 48k brain subdivided once and twice it spent at
/// most 90k; a failing attempt on 1245 vertices (the 48k brain on the fixed hemisphere, 281
/// folds) spent 1.2 s before this bound.
const ENERGY_VERTEX_STEPS: usize = 300_000;

/// Vertex steps per mesh vertex `energy_repair` may spend: on the synthetic 1M ellipsoid a
/// smoothing candidate with 378 folds ran out of 300k steps, and its convex-combination solves
/// then took most of a minute (and squeezed the map to mean `|d_area|` 3.0).
const ENERGY_STEPS_PER_VERTEX: usize = 4;

/// Repair the folded faces `folded` by [`energy_untangle`] over the vertices within `k` rings
/// of them ([`ENERGY_RINGS`]), in rounds ([`ENERGY_ROUNDS`]); `rings[v]` is the ordered
/// one-ring of `v` (`None` on the boundary) and `fixed` vertices stay. Returns the largest
/// region tried when an attempt leaves no fold (then `pos` holds it), `None` otherwise (then
/// `pos` is unchanged).
pub(crate) fn energy_repair(pos: &mut [[f64; 2]], faces: &[[u32; 3]], rings: &[Option<Vec<u32>>], fixed: &[bool], folded: &[usize]) -> Option<usize> {
    let n = pos.len();
    let incidence = VertexFaces::new(n, faces);
    let original = pos.to_vec();
    let mut budget = ENERGY_VERTEX_STEPS.max(ENERGY_STEPS_PER_VERTEX * n);
    // The start of the current round and its folds; the best attempt of a round that left
    // fewer folds starts the next one (see `ENERGY_ROUNDS`).
    let mut start = original.clone();
    let mut folds = folded.to_vec();
    let mut largest = 0;
    for _ in 0..ENERGY_ROUNDS {
        let mut best: Option<(Vec<usize>, Vec<[f64; 2]>)> = None;
        let mut hops = vec![false; n];
        let mut frontier: Vec<u32> = folds.iter().flat_map(|&f| faces[f]).collect();
        frontier.sort_unstable();
        frontier.dedup();
        let mut reached: Vec<u32> = frontier.clone();
        for &v in &frontier {
            hops[v as usize] = true;
        }
        let mut grown = 0;
        for k in ENERGY_RINGS {
            while grown < k && !frontier.is_empty() {
                let mut next = Vec::new();
                for &v in &frontier {
                    for &u in rings[v as usize].iter().flatten() {
                        if !hops[u as usize] {
                            hops[u as usize] = true;
                            next.push(u);
                        }
                    }
                }
                reached.extend_from_slice(&next);
                frontier = next;
                grown += 1;
            }
            let mut region: Vec<u32> = reached.iter().copied().filter(|&v| !fixed[v as usize] && rings[v as usize].is_some()).collect();
            if region.len() > ENERGY_MAX_REGION.max(n / 32) {
                break;
            }
            region.sort_unstable();
            largest = largest.max(region.len());
            // Changed vertices go back to the round's start before each attempt.
            for &v in &reached {
                pos[v as usize] = start[v as usize];
            }
            let ok = energy_untangle(pos, faces, &incidence, &region, &mut budget);
            let left = folded_faces(pos, faces);
            if ok && left.is_empty() {
                return Some(largest);
            }
            let halved = 2 * left.len() <= folds.len();
            if left.len() < best.as_ref().map_or(folds.len(), |b| b.0.len()) {
                best = Some((left, pos.to_vec()));
            }
            // At most half the folds left: new, small regions around them rather than larger
            // ones around all.
            if halved || frontier.is_empty() || budget == 0 {
                break;
            }
        }
        match best {
            Some((left, kept)) => {
                folds = left;
                start = kept;
                pos.copy_from_slice(&start);
            }
            None => break,
        }
    }
    pos.copy_from_slice(&original);
    None
}

/// Rounds of `energy_repair` at most: a round whose best attempt left fewer folds than it
/// started with (but some) starts the next round from there, with new regions around the
/// folds left; an attempt that leaves at most half of its round's folds ends the round. On
/// the synthetic 1M ellipsoid (smoothing `kappa` 3) 238 folds went to 20, 23, 15 and 5 in
/// regions of 460 to 2327 vertices, none to 0, and the convex-combination solves that followed
/// squeezed the map (mean `|d_area|` 2.9).
const ENERGY_ROUNDS: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;

    /// The gradient of a face's energy against central differences, on a folded face.
    #[test]
    fn gradient_matches_finite_differences() {
        let reference = reference_inverse([[0.0, 0.0], [1.0, 0.1], [0.3, 0.9]]);
        let p = [[0.1, 0.0], [0.9, 0.2], [0.6, -0.1]];
        let eps = 0.3;
        for k in 0..3 {
            let g = face_gradient(p, &reference, k, eps);
            for a in 0..2 {
                let h = 1e-6;
                let (mut pp, mut pm) = (p, p);
                pp[k][a] += h;
                pm[k][a] -= h;
                let fd = (face_energy(&jacobian(pp, &reference), eps) - face_energy(&jacobian(pm, &reference), eps)) / (2.0 * h);
                assert!((fd - g[a]).abs() < 1e-6 * (1.0 + fd.abs()), "corner {k}, axis {a}: {fd} vs {}", g[a]);
            }
        }
    }

    /// Two neighbouring vertices of a planar cap mesh swapped (their faces fold, and neither
    /// vertex's ring has a kernel the other leaves free): the minimization over two rings
    /// around them unfolds every face and moves nothing outside the region.
    #[test]
    fn a_swapped_pair_is_unfolded_inside_its_region() {
        use crate::cap::stereographic;
        use crate::mesh::geometry::folded_faces;
        use crate::mesh::shapes::{spherical_cap, spherical_cap_sectors};
        let cap = spherical_cap(0.0, 20, spherical_cap_sectors(0.0, 20));
        let start: Vec<[f64; 2]> = cap.vertices.iter().map(|&p| stereographic(p)).collect();
        // An interior edge half way out: swap its two ends.
        let near = |p: [f64; 2]| (p[0] - 0.5).hypot(p[1]);
        let f = (0..cap.faces.len()).min_by(|&a, &b| near(start[cap.faces[a][0] as usize]).total_cmp(&near(start[cap.faces[b][0] as usize]))).unwrap();
        let (a, b) = (cap.faces[f][0] as usize, cap.faces[f][1] as usize);
        let mut pos = start.clone();
        pos.swap(a, b);
        assert!(!folded_faces(&pos, &cap.faces).is_empty());
        let incidence = VertexFaces::new(pos.len(), &cap.faces);
        // Two rings: the pair's faces' corners, then theirs.
        let mut region: Vec<u32> = [a, b].iter().flat_map(|&v| incidence.of(v).iter().flat_map(|&t| cap.faces[t as usize])).collect();
        let grown: Vec<u32> = region.iter().flat_map(|&v| incidence.of(v as usize).iter().flat_map(|&t| cap.faces[t as usize])).collect();
        region.extend(grown);
        region.sort_unstable();
        region.dedup();
        let mut budget = usize::MAX;
        assert!(energy_untangle(&mut pos, &cap.faces, &incidence, &region, &mut budget));
        assert!(folded_faces(&pos, &cap.faces).is_empty());
        for v in (0..pos.len()).filter(|v| region.binary_search(&(*v as u32)).is_err()) {
            assert_eq!(pos[v], start[v], "vertex {v} outside the region moved");
        }
    }

    /// A face at its reference shape is at the energy's minimum over rotations and scalings.
    #[test]
    fn reference_shape_is_the_minimum() {
        let r = [[0.0, 0.0], [1.0, 0.2], [0.4, 0.8]];
        let m = reference_inverse(r);
        let e0 = face_energy(&jacobian(r, &m), 1e-10);
        for s in [0.8, 1.2] {
            let scaled = r.map(|p| [s * p[0], s * p[1]]);
            assert!(face_energy(&jacobian(scaled, &m), 1e-10) > e0);
        }
        for k in 0..3 {
            assert!(face_gradient(r, &m, k, 1e-10).iter().all(|g| g.abs() < 1e-9));
        }
    }
}
