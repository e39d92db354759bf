//! Area-driven splits and collapses (ours; docs/method.md section 18, "Rebalancing").
//!
//! The resampling's length band (splits above 4/3, collapses below 4/5 of the target length,
//! [`super::resample`]) lets a region's mean edge length sit anywhere inside it: a region of
//! edges at 0.9 targets beside one at 1.1 has faces 1.5 times as large, and the polish, which
//! moves one vertex a small step at a time, cannot carry vertices across a long surface to
//! even that out. Here the faces' area ratios (area over target) are smoothed over a few
//! rings; where regions are beyond `1 +- TOLERANCE`, edges are collapsed where the smoothed
//! ratio is smallest and as many split where it is largest, as many as those regions' excess
//! or deficit of faces asks: faces move from where they are too small to where they are too
//! large, and the face count stays.

use super::boundary::Track;
use super::resample::{collapse_edges, split_edges};
use super::state::{Incidence, Shaping, SurfaceLift};
use crate::mesh::geometry::{cross, norm, sub};

/// Smoothed area ratios further than this from 1 are rebalanced.
const TOLERANCE: f64 = 0.1;

/// Passes of vertex averaging over the faces (each pass reaches a ring farther).
const SMOOTHING_PASSES: usize = 3;

/// Each vertex's area ratio (surface area over target of its faces, averaged), smoothed by
/// [`SMOOTHING_PASSES`] passes of averaging over its faces' corners; 1 at a vertex without
/// faces.
pub(crate) fn smoothed_ratio(mesh: &Shaping, incidence: &Incidence, ln_target: &dyn Fn(usize) -> f64) -> Vec<f64> {
    let ratio: Vec<f64> = mesh
        .faces
        .iter()
        .enumerate()
        .map(|(t, f)| {
            let [a, b, c] = f.map(|v| mesh.position[v as usize]);
            0.5 * norm(cross(sub(b, a), sub(c, a))) / ln_target(t).exp()
        })
        .collect();
    let n = mesh.plane.len();
    let mean_over = |v: usize, value: &dyn Fn(u32) -> f64| {
        let ring = incidence.of(v);
        if ring.is_empty() { 1.0 } else { ring.iter().map(|&t| value(t)).sum::<f64>() / ring.len() as f64 }
    };
    let mut rho: Vec<f64> = (0..n).map(|v| mean_over(v, &|t| ratio[t as usize])).collect();
    for _ in 0..SMOOTHING_PASSES {
        rho = (0..n).map(|v| mean_over(v, &|t| mesh.faces[t as usize].iter().map(|&u| rho[u as usize]).sum::<f64>() / 3.0)).collect();
    }
    rho
}

/// Collapse edges where the smoothed area ratio is smallest (below 1), then split as many
/// where it is largest (above 1), so that the face count stays: at most half the larger of
/// the summed `1 - ratio` over the faces below `1 - TOLERANCE` and the summed `ratio - 1`
/// over those above `1 + TOLERANCE` (a collapse or a split changes two faces); `max_len` and
/// `local` bound the edges a collapse may create (as in [`super::resample`]). Returns the
/// numbers of splits and collapses.
#[allow(clippy::too_many_arguments)]
pub(crate) fn rebalance(mesh: &mut Shaping, track: Option<&Track>, arc: &mut Vec<f64>, lift: &SurfaceLift, ln_target: &dyn Fn(usize) -> f64, max_len: f64, local: &dyn Fn(u32, u32) -> f64) -> (usize, usize) {
    let incidence = mesh.incidence();
    let rho = smoothed_ratio(mesh, &incidence, ln_target);
    let face_rho = |f: &[u32; 3]| f.iter().map(|&v| rho[v as usize]).sum::<f64>() / 3.0;
    let deficit: f64 = mesh.faces.iter().map(face_rho).filter(|r| *r < 1.0 - TOLERANCE).map(|r| 1.0 - r).sum();
    let excess: f64 = mesh.faces.iter().map(face_rho).filter(|r| *r > 1.0 + TOLERANCE).map(|r| r - 1.0).sum();
    // A collapse or a split changes two faces.
    let budget = 0.5 * deficit.max(excess);
    let edge = |a: u32, b: u32| 0.5 * (rho[a as usize] + rho[b as usize]);
    // Collapses first, then as many splits: the face count stays.
    let collapses = if budget >= 1.0 { collapse_edges(mesh, &incidence, lift, &|a, b, _| (edge(a, b) < 1.0).then(|| edge(a, b)), budget as usize, max_len, local) } else { 0 };
    // As many splits where the faces are largest, whether or not the region is beyond the
    // tolerance (a few regions far too small beside many a little too large, or the reverse).
    let splits = if collapses > 0 { split_edges(mesh, track, arc, lift, &|a, b, _| (edge(a, b) > 1.0).then(|| -edge(a, b)), collapses) } else { 0 };
    (splits, collapses)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::shape::state::test_meshes::flat_grid;
    use crate::remesh::shape::state::Role;

    /// A flat `k x k` grid on [0, 1]^2 whose columns right of the middle are `wide` times as
    /// wide as those left of it (x rescaled to [0, 1]).
    fn graded_grid(k: usize, wide: f64) -> Shaping {
        let half = k / 2;
        let total = half as f64 + wide * (k - half) as f64;
        let x_of = |i: usize| if i <= half { i as f64 / total } else { (half as f64 + wide * (i - half) as f64) / total };
        flat_grid(k, |i, j| ([x_of(i), j as f64 / k as f64], Role::Free))
    }

    /// Equal faces have ratio 1 everywhere; with wider columns on the right the smoothed
    /// ratio is above 1 there and below 1 on the left, where the raw ratios are, and the
    /// smoothing blurs only the few rings next to the middle.
    #[test]
    fn the_smoothed_ratio_follows_the_regions_area_error() {
        let even = graded_grid(12, 1.0);
        let inc = even.incidence();
        let ln_mean = crate::remesh::shape::polish::ln_mean_area(&even);
        assert!(smoothed_ratio(&even, &inc, &|_| ln_mean).iter().all(|r| (r - 1.0).abs() < 1e-9));
        let graded = graded_grid(12, 1.5);
        let inc = graded.incidence();
        let ln_mean = crate::remesh::shape::polish::ln_mean_area(&graded);
        let rho = smoothed_ratio(&graded, &inc, &|_| ln_mean);
        // Raw ratios: 1 / 1.25 = 0.8 on the left, 1.5 / 1.25 = 1.2 on the right.
        let at = |i: usize, j: usize| rho[j * 13 + i];
        for j in 0..=12 {
            assert!((at(0, j) - 0.8).abs() < 1e-9 && (at(12, j) - 1.2).abs() < 1e-9, "row {j}: {} {}", at(0, j), at(12, j));
            for i in 0..12 {
                assert!(at(i + 1, j) >= at(i, j) - 1e-12, "not monotone at ({i}, {j})");
            }
        }
    }
}
