//! Multilevel parameterization of large closed surfaces (ours, not the paper's; issue 27).
//!
//! The paper's pipeline (Sec. 3.2) factors sparse matrices of the whole mesh many times
//! (stretch energy iterations, transport Newton steps), whose cost grows like `n^1.3-1.5` on
//! a 2-core machine: a 776k-vertex brain took 6 times its 194k version. Above
//! [`super::ClosedOptions::multilevel_above`] vertices the surface is instead:
//! 1. punctured where the one-level pipeline would puncture it (both ends for
//!    [`super::PunctureEnd::Best`]), those quads locked;
//! 2. decimated by half-edge collapses to [`super::ClosedOptions::coarse_vertices`]
//!    vertices ([`crate::mesh::decimate`]), each collapse recorded;
//! 3. parameterized at that size by the whole pipeline (radius search, transport, fold
//!    repair, refinement, puncture end and `lambda` fallbacks), punctured at the same quad;
//! 4. prolonged: the removed vertices put back in reverse order, each inside the polygon of
//!    its star so that no face folds ([`crate::refine::prolong`]), then corrected radially
//!    (`refine::radial`: the copy's band of compressed faces around the puncture);
//! 5. refined at full resolution by the face-level area refinement (linear per sweep) and
//!    measured like any map ([`super::finish::conclude`]).
//!
//! The map is thus the coarse map's at the scale of the coarse faces and the refinement's
//! below it; the report's `multilevel` section has both levels' figures.

use super::finish::{cap_point, conclude, plane_point};
use super::options::{ParamOptions, PunctureEnd};
use super::prepare::Prepared;
use super::report::MultilevelReport;
use crate::cap::CapMap;
use crate::error::Error;
use crate::flatten::puncture::{choose_puncture, Puncture};
use crate::flatten::FlattenError;
use crate::mesh::decimate::{decimate, Hierarchy};
use crate::mesh::geometry::{folded_faces, norm, signed_area_2d, sub, triangle_area, vertex_areas};
use crate::mesh::topology::{edge_faces, sorted_face};
use crate::mesh::{SurfaceKind, TriMesh};
use crate::progress::{self, Progress, Stage};
use crate::refine::area_refine::{refine_towards, RefineOptions};
use crate::refine::prolong::{mean_value_weights, prolong, DomainPoints};
use crate::refine::radial::correct_radially;
use crate::refine::untangle::untangle;
use std::time::Instant;

/// Whether the prepared mesh is mapped through a decimated copy: a closed genus-0 input of
/// more than [`super::ClosedOptions::multilevel_above`] vertices (when that is not 0) and
/// more than twice [`super::ClosedOptions::coarse_vertices`].
pub(crate) fn applies(prepared: &Prepared, options: &ParamOptions) -> bool {
    let n = prepared.welded.mesh.n_vertices();
    let closed = &options.closed;
    prepared.kind == SurfaceKind::ClosedSphere
        && prepared.input_closed
        && closed.multilevel_above > 0
        && n > closed.multilevel_above
        && n > 2 * closed.coarse_vertices
}

/// [`super::parameterize`] through a decimated copy (see the module doc).
pub(crate) fn parameterize_multilevel(mesh: &TriMesh, prepared: &Prepared, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let work = &prepared.welded.mesh;
    let n = work.n_vertices();
    progress::check(progress, Stage::Flatten, 0.0, "decimating")?;
    let t_decimate = Instant::now();
    let edges: Vec<(u32, u32, usize, usize)> = edge_faces(work)?.into_iter().filter_map(|e| Some((e.a, e.b, e.left? as usize, e.right? as usize))).collect();
    let ends: &[bool] = match options.closed.puncture_end {
        PunctureEnd::Bottom => &[false],
        PunctureEnd::Top => &[true],
        PunctureEnd::Best => &[false, true],
    };
    let punctures = ends
        .iter()
        .map(|&other_end| {
            let o = options.closed.flatten.puncture.clone().with_other_end(other_end);
            choose_puncture(&work.vertices, &work.faces, &edges, &o).ok_or(FlattenError::NoPuncture)
        })
        .collect::<Result<Vec<Puncture>, _>>()?;
    let mut locked = vec![false; n];
    for p in &punctures {
        for v in p.quad {
            locked[v as usize] = true;
        }
    }
    let target = coarse_size(n, options.closed.coarse_vertices);
    let scale = graded_scale(&work.vertices, &punctures, (n as f64 / target as f64).sqrt());
    let hierarchy = decimate(&work.vertices, &work.faces, &locked, &scale, target);
    let fine_of_coarse: Vec<u32> = (0..n as u32).filter(|&v| hierarchy.is_coarse[v as usize]).collect();
    let mut coarse_of_fine = vec![u32::MAX; n];
    for (c, &v) in fine_of_coarse.iter().enumerate() {
        coarse_of_fine[v as usize] = c as u32;
    }
    let coarse = TriMesh::new(
        fine_of_coarse.iter().map(|&v| work.vertices[v as usize]).collect(),
        hierarchy.coarse_faces.iter().map(|f| f.map(|v| coarse_of_fine[v as usize])).collect(),
    );
    let decimate_seconds = t_decimate.elapsed().as_secs_f64();

    // The coarse mesh punctured at the same quads (the unused end's entry is never read).
    let mut given = [[0u32; 2]; 2];
    for (&end, p) in ends.iter().zip(&punctures) {
        given[end as usize] = [coarse_of_fine[p.quad[0] as usize], coarse_of_fine[p.quad[2] as usize]];
    }
    let level_sizes = level_sizes(coarse.n_vertices(), n);
    let (masses, level_masses) = restricted_masses(&work.vertices, &work.faces, &hierarchy, &level_sizes);
    let mut coarse_options = options.clone();
    coarse_options.vertex_masses = Some(std::sync::Arc::new(fine_of_coarse.iter().map(|&v| masses[v as usize]).collect()));
    coarse_options.closed.flatten.puncture.given = Some(given);
    coarse_options.closed.multilevel_above = 0;
    let t_coarse = Instant::now();
    let coarse_map = super::parameterize_with_fallbacks(&coarse, &coarse_options, progress)?;
    let coarse_seconds = t_coarse.elapsed().as_secs_f64();

    // The fine puncture the coarse map kept.
    let sorted = |q: [u32; 4]| {
        let mut q = q;
        q.sort_unstable();
        q
    };
    let kept = coarse_map.report.puncture.as_ref().map(|p| sorted(p.quad.map(|v| fine_of_coarse[v as usize])));
    let puncture = punctures
        .into_iter()
        .find(|p| Some(sorted(p.quad)) == kept)
        .ok_or_else(|| Error::Internal("the decimated surface was punctured elsewhere than the input".into()))?;

    let faces: Vec<[u32; 3]> = work.faces.iter().enumerate().filter(|(f, _)| !puncture.faces.contains(f)).map(|(_, t)| *t).collect();
    let mut on_boundary = vec![false; n];
    for v in puncture.quad {
        on_boundary[v as usize] = true;
    }
    progress::check(progress, Stage::Project, 0.0, "prolonging the map")?;
    let t_prolong = Instant::now();
    let coarse_faces: Vec<[u32; 3]> = coarse.faces.iter().enumerate().filter(|(f, _)| !coarse_map.report.puncture.as_ref().is_some_and(|p| p.faces.contains(f))).map(|(_, t)| *t).collect();
    let signed = |t: &[u32; 3]| {
        let p = t.map(|v| coarse_map.plane[v as usize]);
        signed_area_2d(p[0], p[1], p[2])
    };
    let total: f64 = coarse_faces.iter().map(signed).sum();
    let orientation = if total < 0.0 { -1.0 } else { 1.0 };
    let mut plane = vec![[0.0; 2]; n];
    for (c, &v) in fine_of_coarse.iter().enumerate() {
        plane[v as usize] = coarse_map.plane[c];
    }
    let lift_one = |q: [f64; 2]| cap_point(options.domain, q);
    let punctured = puncture.faces.map(|f| work.faces[f]);
    let mut at_level = |k: usize, plane: &mut [[f64; 2]], faces: &[[u32; 3]], present: &[bool]| {
        refine_level(plane, &work.vertices, &level_masses[k], faces, present, &punctured, &on_boundary, &lift_one);
    };
    let project = |q: [f64; 3]| plane_point(options.domain, q);
    let domain = DomainPoints { lift: &lift_one, project: &project };
    let prolonged = prolong(&mut plane, &work.vertices, &hierarchy, orientation, &domain, &level_sizes, &mut at_level);
    // Rounding can leave a vertex no unfolded place (`unplaced`): the fold repair of the
    // one-level pipeline unties what it folded.
    let folded = folded_faces(&plane, &faces).len();
    let untangle = (folded > 0).then(|| untangle(&mut plane, &faces, &on_boundary, coarse_map.report.r_star.unwrap_or(1.0)));
    // The copy's band of compressed faces around the puncture is a radial error: corrected
    // at once (docs/method.md section 20).
    let radial = correct_radially(&mut plane, &work.vertices, &faces, &on_boundary, coarse_map.report.r_star.unwrap_or(1.0), options.domain);
    let prolong_seconds = t_prolong.elapsed().as_secs_f64();

    let mut report = coarse_map.report;
    report.multilevel = Some(MultilevelReport {
        coarse_vertices: coarse.n_vertices(),
        coarse_mean_abs_area_distortion: report.area_distortion.mean_abs,
        prolong: prolonged,
        folded_after_prolong: folded,
        untangle,
        radial,
        decimate_seconds,
        coarse_seconds,
        prolong_seconds,
    });
    report.n_vertices = mesh.n_vertices();
    report.n_faces = mesh.n_faces();
    report.welded_vertices = prepared.welded.merged_vertices;
    report.split_vertices = prepared.welded.split_vertices;
    report.puncture = Some(puncture);
    // The full-resolution sweeps are `prolonged_refinement`'s when the options ask for them.
    let refined;
    let options = match options.closed.prolonged_refinement {
        Some(sweeps) => {
            refined = options.clone().with_area_refinement(sweeps);
            &refined
        }
        None => options,
    };
    conclude(mesh, prepared, &faces, &on_boundary, plane, options, progress, report)
}

/// The decimation's length scale ([`decimate`]): the decimated copy keeps the input's edge
/// length at the punctured quads and grows it by [`GRADING`] times the distance from them,
/// up to the uniform decimation's (`growth` times the quads' sides). A quad of the input's
/// size amid faces `growth` times larger flattens badly: the 1M-vertex ellipsoid decimated
/// to 125k uniformly around its quad mapped at mean |d_area| 5.2 with `lambda` 0.2 (the
/// decimated mesh punctured at a quad of its own size: 0.0056).
fn graded_scale(vertices: &[[f64; 3]], punctures: &[Puncture], growth: f64) -> Vec<f64> {
    let quads: Vec<([f64; 3], f64)> = punctures
        .iter()
        .map(|p| {
            let q = p.quad.map(|v| vertices[v as usize]);
            let centre = [0, 1, 2].map(|k| q.iter().map(|x| x[k]).sum::<f64>() / 4.0);
            let side = (0..4).map(|k| norm(sub(q[(k + 1) % 4], q[k]))).sum::<f64>() / 4.0;
            (centre, side)
        })
        .collect();
    vertices
        .iter()
        .map(|&x| {
            quads
                .iter()
                .map(|&(c, h)| ((h + GRADING * norm(sub(x, c))) / (growth * h)).min(1.0))
                .fold(1.0, f64::min)
                .max(f64::MIN_POSITIVE)
        })
        .collect()
}

/// Growth of the decimated copy's edge length with the distance from a punctured quad. On
/// the 1M-vertex ellipsoid the final map's mean |d_area| was 0.0141 with 0.25 (a band of
/// compressed faces around the puncture, there in the decimated copy's map already), 0.0082
/// with 0.1 and 0.0077 with 0.05 (its map at full resolution: 0.0074); the 776k brain's
/// 0.0080 either way.
const GRADING: f64 = 0.05;

/// The decimated copy's vertices for an input of `n`: `coarse_vertices`, or an eighth of the
/// input when that is more ([`COARSE_RATIO`]).
pub(crate) fn coarse_size(n: usize, coarse_vertices: usize) -> usize {
    coarse_vertices.max(n / COARSE_RATIO)
}

/// Most input vertices per vertex of the decimated copy: the 776k-vertex brain (the 48k
/// brain subdivided twice) decimated to 50k mapped at mean |d_area| 0.0117, 1.7 times the 48k
/// brain's own map, and at 0.0086 decimated to 100k, in about the same time (the coarse map
/// took 1 s more, the levels between less).
pub const COARSE_RATIO: usize = 8;

/// Each level of the prolongation has this many times the vertices of the one before.
const LEVEL_GROWTH: usize = 2;

/// Area refinement sweeps at each level of the prolongation but the last (which gets
/// [`super::RefinementOptions::area_refinement`]).
const LEVEL_SWEEPS: usize = 5;

/// The sizes of the prolongation's levels between a coarse mesh of `coarse` vertices and the
/// input's `n`: `coarse` times powers of [`LEVEL_GROWTH`], below three quarters of `n` (a
/// level nearly as large as the input would be refined twice over: the 776k brain's copy of
/// an eighth of it had a level 2 vertices short of the input, 1.3 s of its 16 s).
fn level_sizes(coarse: usize, n: usize) -> Vec<usize> {
    std::iter::successors(Some(coarse * LEVEL_GROWTH), |&s| Some(s * LEVEL_GROWTH)).take_while(|&s| s < n - n / 4).collect()
}

/// The area refinement of one level of the prolongation: the faces of the mesh so far but
/// the `punctured` ones, on its own vertices (`present`), the puncture's quad held. Each
/// face's target is its share of its vertices' `masses` (the input's area they stand for):
/// a third of the face's area times each corner's mass over its vertex area.
#[allow(clippy::too_many_arguments)]
fn refine_level(
    plane: &mut [[f64; 2]],
    vertices: &[[f64; 3]],
    masses: &[f64],
    faces: &[[u32; 3]],
    present: &[bool],
    punctured: &[[u32; 3]; 2],
    on_boundary: &[bool],
    lift: &(dyn Fn([f64; 2]) -> [f64; 3] + Sync),
) {
    let skip = punctured.map(sorted_face);
    let global: Vec<u32> = (0..present.len() as u32).filter(|&v| present[v as usize]).collect();
    let mut local = vec![u32::MAX; present.len()];
    for (i, &v) in global.iter().enumerate() {
        local[v as usize] = i as u32;
    }
    let level_faces: Vec<[u32; 3]> = faces.iter().filter(|t| !skip.contains(&sorted_face(**t))).map(|t| t.map(|v| local[v as usize])).collect();
    let mut level_plane: Vec<[f64; 2]> = global.iter().map(|&v| plane[v as usize]).collect();
    let level_vertices: Vec<[f64; 3]> = global.iter().map(|&v| vertices[v as usize]).collect();
    let fixed: Vec<bool> = global.iter().map(|&v| on_boundary[v as usize]).collect();
    let target = level_targets(&level_vertices, &level_faces, &global.iter().map(|&v| masses[v as usize]).collect::<Vec<f64>>());
    let mut lifted: Vec<[f64; 3]> = level_plane.iter().map(|&p| lift(p)).collect();
    refine_towards(&mut level_plane, &mut lifted, &target, &level_faces, &fixed, &|_, p| lift(p), RefineOptions::default().with_sweeps(LEVEL_SWEEPS));
    for (i, &v) in global.iter().enumerate() {
        plane[v as usize] = level_plane[i];
    }
}

/// Each face's share of the `masses` of a level's vertices: its area times the ratio of mass
/// to area around it, taken as a ratio of sums (over each face's corners, then averaged
/// over each vertex's faces, [`RATIO_PASSES`] times) because a single vertex's ratio is
/// noisy (a vertex's mass comes from the collapses near it, its area from its own faces).
fn level_targets(vertices: &[[f64; 3]], faces: &[[u32; 3]], masses: &[f64]) -> Vec<f64> {
    let face_area: Vec<f64> = faces.iter().map(|t| triangle_area(vertices[t[0] as usize], vertices[t[1] as usize], vertices[t[2] as usize])).collect();
    let areas = vertex_areas(vertices, faces);
    let (mut m, mut a) = (masses.to_vec(), areas.clone());
    let mut face_ratio = vec![1.0; faces.len()];
    for _ in 0..RATIO_PASSES {
        for (r, t) in face_ratio.iter_mut().zip(faces) {
            let (sm, sa) = t.iter().fold((0.0, 0.0), |(x, y), &v| (x + m[v as usize], y + a[v as usize]));
            *r = if sa > 0.0 { sm / sa } else { 1.0 };
        }
        // The vertices' ratios, as mass and area: their faces' ratios weighted by area.
        m.iter_mut().for_each(|x| *x = 0.0);
        a.iter_mut().for_each(|x| *x = 0.0);
        for ((t, &r), &fa) in faces.iter().zip(&face_ratio).zip(&face_area) {
            for &v in t {
                m[v as usize] += r * fa;
                a[v as usize] += fa;
            }
        }
    }
    face_area.iter().zip(&face_ratio).map(|(fa, r)| fa * r).collect()
}

/// Smoothing passes of [`level_targets`]' mass-to-area ratio.
const RATIO_PASSES: usize = 3;

/// The area of the input surface each vertex stands for at the coarse level, and at each of
/// the `level_sizes`: every vertex starts with a third of its faces' areas, and each collapse
/// hands the removed vertex's mass to its star by the mean value weights the prolongation
/// puts it back with (the restriction is the prolongation's transpose, as in multigrid). The
/// transport of the decimated copy then spreads the input's area, not the decimated
/// surface's, which lost area where it cut across folds.
fn restricted_masses(vertices: &[[f64; 3]], faces: &[[u32; 3]], hierarchy: &Hierarchy, level_sizes: &[usize]) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mut mass = vertex_areas(vertices, faces);
    let mut levels = vec![Vec::new(); level_sizes.len()];
    let mut size = vertices.len();
    let mut weights = Vec::new();
    for c in &hierarchy.collapses {
        mean_value_weights(vertices, c.removed, hierarchy.star(c), &mut weights);
        let total: f64 = weights.iter().map(|w| w.1).sum();
        let m = std::mem::take(&mut mass[c.removed as usize]);
        if total > 0.0 && total.is_finite() {
            for &(w, k) in &weights {
                mass[w as usize] += m * k / total;
            }
        } else {
            mass[c.kept as usize] += m;
        }
        size -= 1;
        if let Some(k) = level_sizes.iter().position(|&s| s == size) {
            levels[k] = mass.clone();
        }
    }
    (mass, levels)
}

#[cfg(test)]
mod tests {
    use super::level_sizes;

    #[test]
    fn levels_double_up_to_three_quarters_of_the_input() {
        // The 776k brain through its copy of an eighth: no level 2 vertices short of it.
        assert_eq!(level_sizes(96_970, 775_762), vec![193_940, 387_880]);
        assert_eq!(level_sizes(25_000, 193_942), vec![50_000, 100_000]);
        assert_eq!(level_sizes(10_000, 14_000), Vec::<usize>::new());
    }
}
