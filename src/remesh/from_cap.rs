//! One cap mesh pulled back onto the surface and the stages after it (paper Sec. 4.2; the
//! shape stage, area equalization and the removal of crossing faces are ours, docs/method.md
//! sections 15 and 18): what [`super::remesh`] runs on the uniform or latitude/longitude grid,
//! and, for the shape stage, on the starts of [`from_best_start`] in turn (isotropic samples of
//! [`super::sample`], then the grid) until one meets the quality bar.

use super::sample::Place;
use super::{equalize, grid, polygon_of, pullback, sample, shape, sizing, Optimize, RemeshOptions};
use crate::cap::{stereographic, CapMap, InverseMap};
use crate::error::Error;
use crate::mesh::geometry::{face_areas, triangle_area};
use crate::mesh::TriMesh;
use crate::metrics::self_intersection::self_intersecting_faces;
use crate::metrics::closest::SurfaceDistance;
use crate::progress::{self, Progress, Stage};
use crate::refine::area_refine::AreaRefineReport;
use rayon::prelude::*;
use std::time::Instant;

/// What the pull-back of every cap mesh shares.
pub(crate) struct Context<'a> {
    /// The input surface.
    pub mesh: &'a TriMesh,
    /// Its map onto the cap.
    pub map: &'a CapMap,
    /// The inverse map.
    pub inverse: &'a InverseMap<'a>,
    /// The remesh's options.
    pub options: &'a RemeshOptions,
    /// Whether the surface is closed (the cap mesh is closed by a bottom disk).
    pub closed: bool,
    /// Whether the shape stage runs.
    pub shaped: bool,
    /// The input's boundary vertices (none on a closed surface).
    pub input_boundary: &'a [bool],
    /// The input's own crossing faces, shared by both puncture ends' remeshes.
    pub input_crossings: &'a InputCrossings<'a>,
}

/// A cap mesh pulled back and optimized.
pub(crate) struct FromCap {
    /// The remesh's faces.
    pub faces: Vec<[u32; 3]>,
    /// Each vertex's point in the map's plane (meaningless where `has_plane` is false).
    pub planar: Vec<[f64; 2]>,
    /// Each vertex's point on the surface.
    pub positions: Vec<[f64; 3]>,
    /// Whether each vertex has a planar point (not so a closed surface's bottom).
    pub has_plane: Vec<bool>,
    /// The shape stage (its `uncross` included).
    pub shape: shape::ShapeReport,
    /// The area equalization.
    pub equalization: AreaRefineReport,
    /// Seconds of the pull-back.
    pub pullback_seconds: f64,
    /// Seconds of the shape stage.
    pub shape_seconds: f64,
    /// Seconds of the area equalization.
    pub equalize_seconds: f64,
    /// The remesh's mean smallest angle (degrees).
    pub mean_min_angle_deg: f64,
    /// The remesh's d_face_rel (mean |area - mean area| / mean area).
    pub d_face_relative: f64,
    /// Slivers left whose shortest edge joins two vertices that stay (a closed surface's rim
    /// ring, bunched on the punctured quad when the quad is larger than [`MERGE_QUAD_FACES`]
    /// remesh faces): every
    /// start has them, so they do not send [`from_best_start`] to the next one.
    pub slivers_at_rim: usize,
    /// Faces below 15 degrees at a closed surface's bottom (the merged bottom vertex, or the
    /// bottom disk when it is not merged; [`shape::uncross::slivers_at_bottom`]): counted with
    /// the slivers, which they are not in the untangling's report.
    pub slivers_at_bottom: usize,
    /// Which vertices the stages kept in place (the rim, the bottom).
    pub fixed: Vec<bool>,
    /// The least-squares vertex placement (made last, [`super::fit`]).
    pub fit: super::FitReport,
}

/// The mean smallest angle (degrees) a remesh from a start must reach, with no crossing face
/// of its own (none away from the input's crossings) and no sliver left, for the other starts
/// not to be tried: the bar of issue 26.
const GOOD_MEAN_ANGLE_DEG: f64 = 48.0;

/// [`GOOD_MEAN_ANGLE_DEG`] of a sized remesh (`--sizing surface` or `curvature`), whose faces are
/// measured by the surface they cover (`shape::covered`): the shared meshes' sized remeshes
/// come to 46.4-51.5 degrees, and at the uniform bar the other starts and puncture end,
/// tried on 8 of 11, took 2-6 times as long for the same figures.
const SIZED_MEAN_ANGLE_DEG: f64 = 46.0;

/// [`SIZED_MEAN_ANGLE_DEG`] of a sized remesh with vertices on the input's creases (curvature
/// sizing keeps them by default): the faces beside a crease have a side along it. The lung
/// lobe's curvature-sized remesh came to 45.7-45.8 degrees from every start and both puncture
/// ends; at 46 all six were tried, about 4 times the time, for no better angle.
const CREASED_SIZED_MEAN_ANGLE_DEG: f64 = 45.0;

/// Whether a remesh made by the shape stage meets the bar of [`GOOD_MEAN_ANGLE_DEG`] (or
/// [`SIZED_MEAN_ANGLE_DEG`], [`CREASED_SIZED_MEAN_ANGLE_DEG`]): no crossing face of its own, no
/// sliver but at the rim, the mean smallest angle.
pub(crate) fn meets_bar(r: &FromCap) -> bool {
    let bar = match (r.shape.sizing.by_covered(), r.shape.crease_vertices > 0) {
        (false, _) => GOOD_MEAN_ANGLE_DEG,
        (true, false) => SIZED_MEAN_ANGLE_DEG,
        (true, true) => CREASED_SIZED_MEAN_ANGLE_DEG,
    };
    own_crossings(r) == 0 && slivers(r) <= r.slivers_at_rim && r.mean_min_angle_deg >= bar
}

/// The remesh's slivers: the untangling's and those at a closed surface's bottom vertex.
fn slivers(r: &FromCap) -> usize {
    r.shape.uncross.slivers_after + r.slivers_at_bottom
}

/// The order in which remeshes are preferred (lowest first): crossing faces of their own, then
/// slivers, then the higher mean smallest angle.
pub(crate) fn rank(r: &FromCap) -> (usize, usize, f64) {
    (own_crossings(r), slivers(r), -r.mean_min_angle_deg)
}

/// The largest punctured quad, in mean remesh faces, whose rim ring and bottom disk the shape
/// stage merges into one vertex (`shape::bottom`). Not merged, a quad of one to two faces kept
/// a rim ring of several vertices bunched on its boundary, with slivers no pass mends: the
/// marching-cubes hippocampus at 10000 faces (quad 1.3 faces) had a smallest angle of 5.3
/// degrees, 15.4 merged; the bundled closed meshes at 10000 faces: 12k brain 13.0 -> 15.4,
/// hippocampus 15.0 -> 19.8, lung lobe 17.7 -> 21.1 (d_face_rel lower on the three), bird skull
/// 15.3 -> 15.0 (its mean smallest angle 48.03 -> 48.16). Raised from two faces to four once
/// the thinnest faces were raised by a compass search (`shape::worst`): a quad of 2-4 faces
/// kept as a rim ring and a disk holds about 19 faces a sixth of the mean area (the bunny at
/// 5000 faces, quad 3.5 faces: 0.003 of its d_face_rel 0.032); merged, d_face_rel fell on all
/// eight remeshes that changed (5000-20000 faces; 12k brain at 20000 0.0211 -> 0.0172, bunny
/// at 5000 0.0323 -> 0.0288) and the smallest angle rose on six (12k brain at 20000 10.1 ->
/// 25.2) and fell on two (bunny at 5000 22.4 -> 20.3, bird skull at 10000 18.5 -> 15.6).
pub(crate) const MERGE_QUAD_FACES: f64 = 4.0;

/// The d_face_rel above which a uniform remesh is polished again, longer, from the same start
/// ([`polish_longer`]): the bar of issue 26 (0.035). The shared meshes' remeshes come to
/// 0.015-0.023 and are not.
pub(crate) const LONGER_POLISH_ABOVE: f64 = 0.035;

/// The polish iterations and global area steps, at least, of a longer polish
/// ([`polish_longer`]). On a long bone twenty times as long as wide the smooth part of the
/// area error still falls by a few percent a global step after the default six, faces being
/// carried along the shaft (docs/method.md section 18, "A longer polish"): at 5000 faces
/// d_face_rel 0.0485 -> 0.0389 (0.0318 from the top end alone), quadric-decimated
/// 0.0407 -> 0.0328.
pub(crate) const LONGER_POLISH: (usize, usize) = (200, 20);

/// The options of a longer polish of `r` ([`LONGER_POLISH`]), when `r` is a uniform remesh
/// whose areas are spread beyond [`LONGER_POLISH_ABOVE`] after a polish at least as long as
/// the default's and shorter than [`LONGER_POLISH`] (options asking for a shorter polish keep
/// it; no global area steps where they make none).
fn polish_longer(options: &RemeshOptions, r: &FromCap) -> Option<RemeshOptions> {
    let shape = &options.shape;
    let (iterations, steps) = LONGER_POLISH;
    let steps = if shape.area_steps == 0 { 0 } else { shape.area_steps.max(steps) };
    let longer = shape.with_polish_iterations(shape.polish_iterations.max(iterations)).with_area_steps(steps);
    let uniform = !shape.sizing.by_covered();
    let polishes_more = longer.polish_iterations > shape.polish_iterations || longer.area_steps > shape.area_steps;
    // A polish shorter than the default's was asked for (speed over areas): it stands.
    let full = shape.polish_iterations >= shape::ShapeOptions::default().polish_iterations;
    (uniform && full && r.d_face_relative > LONGER_POLISH_ABOVE && polishes_more).then(|| RemeshOptions { shape: longer, ..options.clone() })
}

/// The order in which a remesh and its longer polish are preferred (lowest first): crossing
/// faces of their own, slivers, areas spread beyond [`LONGER_POLISH_ABOVE`], then the higher
/// mean smallest angle.
fn area_rank(r: &FromCap) -> (usize, usize, bool, f64) {
    (own_crossings(r), slivers(r), r.d_face_relative > LONGER_POLISH_ABOVE, -r.mean_min_angle_deg)
}

/// The d_face_rel above which a closed surface's uniform remesh also tries the other puncture
/// end ([`super::remesh`]): the bar of issue 26 is 0.035 on most meshes. The two ends' maps
/// often tie in the search and differ in the finished map's area spread near the puncture; a
/// marching-cubes copy of the bunny came back at 0.042 from one end, 0.024 from the other.
pub(crate) const RETRY_AREA_SPREAD: f64 = 0.04;

/// Whether a closed surface's remesh makes the other puncture end worth trying: it misses
/// [`meets_bar`], or its uniform areas are spread more than [`RETRY_AREA_SPREAD`].
pub(crate) fn end_worth_retrying(r: &FromCap, uniform: bool) -> bool {
    !meets_bar(r) || spreads_areas(r, uniform)
}

/// Whether a uniform remesh's areas are spread more than [`RETRY_AREA_SPREAD`].
fn spreads_areas(r: &FromCap, uniform: bool) -> bool {
    uniform && r.d_face_relative > RETRY_AREA_SPREAD
}

/// The order in which the two puncture ends' remeshes are preferred (lowest first): crossing
/// faces of their own, slivers, then whether uniform areas are spread more than
/// [`RETRY_AREA_SPREAD`], then the higher mean smallest angle.
pub(crate) fn end_rank(r: &FromCap, uniform: bool) -> (usize, usize, bool, f64) {
    (own_crossings(r), slivers(r), spreads_areas(r, uniform), -r.mean_min_angle_deg)
}

/// Crossing faces not at the input's own crossings.
fn own_crossings(r: &FromCap) -> usize {
    r.shape.uncross.after.saturating_sub(r.shape.uncross.at_input_crossings)
}

/// The shape stage's remesh from the best start (docs/method.md section 18, "Isotropic
/// start"): `cap`'s lift when it is near-isotropic; else isotropic samples of the surface
/// (`place` lifts cap points, `surface_area` is the input's), then `cap` itself, until a remesh
/// has no crossing face of its own, no sliver and a mean smallest angle of
/// [`GOOD_MEAN_ANGLE_DEG`]; of those made, the one with the fewest crossing faces of its own,
/// then slivers, then the highest mean smallest angle is kept. Crossing faces within two edge
/// lengths of the input's own crossings are the input's ([`InputCrossings`]): a face scan that
/// crosses itself made every start miss the bar, and three starts cost three shape stages.
pub(crate) fn from_best_start(ctx: &Context, cap: TriMesh, place: &Place<'_>, surface_area: f64, progress: &dyn Progress) -> Result<FromCap, Error> {
    // Crossing faces of a start's remesh that lie at crossings of the input are inherited
    // from it (any remesh on the surface has them): only the others count against a start.
    let input_crossings = ctx.input_crossings;
    let mut best: Option<FromCap> = None;
    let keep = |r: FromCap, best: &mut Option<FromCap>| {
        let better = best.as_ref().map_or(true, |b| rank(&r) < rank(b));
        if better {
            *best = Some(r);
        }
        better
    };
    let mut starts = 0;
    // The best remesh's start, for a longer polish (`polish_longer`).
    let mut best_start: Option<TriMesh> = None;
    let t = Instant::now();
    let isotropic = sample::grid_is_isotropic(&cap, place);
    let mut sample_seconds = t.elapsed().as_secs_f64();
    if !isotropic {
        for variant in 0..sample::SAMPLES {
            let t = Instant::now();
            let Some(start) = sample::isotropic_cap(&cap, surface_area, place, variant) else { break };
            sample_seconds += t.elapsed().as_secs_f64();
            let mut r = pull_back_and_optimize(ctx, start.clone(), progress)?;
            starts += 1;
            r.shape.start = shape::Start::Sample;
            r.shape.uncross.at_input_crossings = input_crossings.near(&r);
            if keep(r, &mut best) {
                best_start = Some(start);
            }
            if best.as_ref().is_some_and(meets_bar) {
                break;
            }
        }
    }
    if !best.as_ref().is_some_and(meets_bar) {
        let mut r = pull_back_and_optimize(ctx, cap.clone(), progress)?;
        starts += 1;
        r.shape.uncross.at_input_crossings = input_crossings.near(&r);
        if keep(r, &mut best) {
            best_start = Some(cap);
        }
    }
    let mut best = best.ok_or_else(|| Error::Internal("no remesh start was tried".into()))?;
    if let (Some(start), Some(longer)) = (best_start, polish_longer(ctx.options, &best)) {
        let ctx = Context { options: &longer, ..*ctx };
        let mut r = pull_back_and_optimize(&ctx, start, progress)?;
        r.shape.start = best.shape.start;
        r.shape.longer_polish = true;
        r.shape.uncross.at_input_crossings = input_crossings.near(&r);
        if area_rank(&r) < area_rank(&best) {
            best = r;
        }
    }
    best.pullback_seconds += sample_seconds;
    best.shape.starts = starts;
    best.shape.ends = 1;
    Ok(best)
}

/// The input's faces that cross another (MeshLab's test), found when a remesh first has a
/// crossing face.
pub(crate) struct InputCrossings<'a> {
    mesh: &'a TriMesh,
    crossing: std::cell::OnceCell<TriMesh>,
}

impl<'a> InputCrossings<'a> {
    pub(crate) fn new(mesh: &'a TriMesh) -> Self {
        Self { mesh, crossing: std::cell::OnceCell::new() }
    }

    /// How many crossing faces of `r`'s remesh have their centroid within two remesh edge
    /// lengths (equilateral faces of the mean area) of a crossing face of the input.
    fn near(&self, r: &FromCap) -> usize {
        if r.shape.uncross.after == 0 {
            return 0;
        }
        let crossing = self.crossing.get_or_init(|| {
            let faces: Vec<[u32; 3]> = self_intersecting_faces(self.mesh).into_iter().map(|f| self.mesh.faces[f as usize]).collect();
            TriMesh::new(self.mesh.vertices.clone(), faces)
        });
        if crossing.faces.is_empty() || r.faces.is_empty() {
            return 0;
        }
        let area: f64 = face_areas(&r.positions, &r.faces).iter().sum();
        let reach = 2.0 * crate::mesh::geometry::equilateral_edge(area, r.faces.len() as f64);
        let remesh = TriMesh::new(r.positions.clone(), r.faces.clone());
        let distance = SurfaceDistance::new(crossing);
        self_intersecting_faces(&remesh)
            .into_iter()
            .filter(|&f| {
                let [a, b, c] = remesh.faces[f as usize].map(|v| remesh.vertices[v as usize]);
                distance.distance(std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0)) <= reach
            })
            .count()
    }
}

/// Pull `cap` (rim ring last) back onto the surface of `ctx` and run the stages after it.
pub(crate) fn pull_back_and_optimize(ctx: &Context, cap: TriMesh, progress: &dyn Progress) -> Result<FromCap, Error> {
    let Context { mesh, map, inverse, options, closed, shaped, input_boundary, .. } = *ctx;
    let t_pull = Instant::now();
    let no_face = || Error::Unsupported("the parameterized mesh has no face to pull back from".into());
    let top_faces: Vec<[u32; 3]> = (0..mesh.n_faces()).filter(|f| !map.bottom_faces.contains(f)).map(|f| mesh.faces[f]).collect();
    // The rim (the cap grid's last ring) and the bottom stay where the pull-back put them.
    let rim = cap.vertices.iter().rev().take_while(|p| Some(p[2]) == cap.vertices.last().map(|q| q[2])).count();
    let first_fixed = cap.vertices.len() - rim;
    // Each cap vertex's point in the plane of the map, where the pull-back locates it and
    // the equalization moves it. The planar map covers the polygon of its boundary (an open
    // surface's boundary, a closed one's punctured quad), inscribed in the rim: cap points
    // near the rim are moved inside it ([`pullback::rim_band_into_polygon`]).
    // The input's boundary vertices (none on a closed surface): the rim polygon and the track.
    let (grid_mesh, planar, mut positions, in_plane) = if closed {
        let grid = grid::close_bottom(cap);
        let split = grid.first_bottom_vertex.min(grid.mesh.vertices.len());
        let mut planar: Vec<[f64; 2]> = grid.mesh.vertices.iter().map(|&x| stereographic(x)).collect();
        let quad: Vec<u32> = map.bottom_faces.iter().filter_map(|&f| mesh.faces.get(f)).flatten().copied().collect();
        let (corners, rim_radius) = polygon_of(quad.into_iter(), &map.plane);
        pullback::rim_band_into_polygon(&mut planar[..split], &corners, rim_radius);
        let positions = pullback::pull_back_closed_from(mesh, map, &grid, &planar[..split]).ok_or_else(no_face)?;
        (grid.mesh, planar, positions, split)
    } else {
        let mut planar: Vec<[f64; 2]> = cap.vertices.iter().map(|&x| stereographic(x)).collect();
        let (corners, rim_radius) = polygon_of((0..mesh.n_vertices() as u32).filter(|&v| input_boundary[v as usize]), &map.plane);
        pullback::rim_band_into_polygon(&mut planar, &corners, rim_radius);
        let positions = planar.par_iter().map(|&q| inverse.locate_plane(q).map(|p| p.position)).collect::<Option<Vec<_>>>().ok_or_else(no_face)?;
        let n = cap.vertices.len();
        (cap, planar, positions, n)
    };
    let pullback_seconds = t_pull.elapsed().as_secs_f64();
    let n = grid_mesh.vertices.len();
    let mut fixed: Vec<bool> = (0..n).map(|v| v >= first_fixed).collect();
    let mut planar = planar;
    let mut faces = grid_mesh.faces;
    let t_shape = Instant::now();
    let mut shape_report = shape::ShapeReport::default();
    let mut has_plane: Vec<bool> = (0..n).map(|v| v < in_plane).collect();
    let mut face_targets: Vec<f64> = Vec::new();
    // The punctured quad's area against a remesh face's: the bottom is merged only when the
    // quad is no larger than [`MERGE_QUAD_FACES`] faces (on a coarse input the quad is a
    // sizeable part of the surface, and the ring above the rim could not reach across it).
    let quad_area: f64 = map.bottom_faces.iter().filter_map(|&f| mesh.faces.get(f)).map(|f| triangle_area(mesh.vertices[f[0] as usize], mesh.vertices[f[1] as usize], mesh.vertices[f[2] as usize])).sum();
    let surface_area: f64 = mesh.faces.iter().map(|f| triangle_area(mesh.vertices[f[0] as usize], mesh.vertices[f[1] as usize], mesh.vertices[f[2] as usize])).sum();
    if shaped && closed && quad_area * faces.len() as f64 <= MERGE_QUAD_FACES * surface_area {
        // The rim ring and the bottom disk become one vertex on the punctured quad (the disk's
        // centre), fanned to the ring above ([`shape::bottom`]).
        let centre = positions.get(in_plane).or(positions.get(first_fixed)).copied();
        if let Some((f, p, x)) = centre.and_then(|c| shape::bottom::merge_bottom(&faces, &planar, &positions, first_fixed, c)) {
            faces = f;
            planar = p;
            positions = x;
            has_plane = (0..positions.len()).map(|v| v < first_fixed).collect();
            fixed = (0..positions.len()).map(|v| v >= first_fixed).collect();
        }
    }
    if shaped {
        progress::check(progress, Stage::Remesh, 0.3, "shaping the triangles")?;
        let lift = shape::state::SurfaceLift::new(inverse);
        let track = if closed { None } else { shape::boundary::Track::new(mesh, &map.plane, input_boundary) };
        let density = sizing::vertex_density(mesh, options.shape.sizing, faces.len());
        let input = shape::ShapeInput { lift: &lift, track: track.as_ref(), has_plane: &has_plane, fixed: &fixed, density: density.as_deref(), chart: chart(closed) };
        let shaped = shape::optimize_shape(&input, faces, &mut planar, &mut positions, &options.shape);
        faces = shaped.faces;
        fixed = shaped.stays;
        has_plane = shaped.has_plane;
        face_targets = shaped.face_target;
        shape_report = shaped.report;
    }
    let shape_seconds = t_shape.elapsed().as_secs_f64();
    progress::check(progress, Stage::Remesh, 0.5, "equalizing the areas")?;
    let t_eq = Instant::now();
    let sweeps = match options.optimize {
        Optimize::None => 0,
        _ if shaped => options.shape.area_sweeps,
        _ => options.area_equalization,
    };
    // Targets: the cap triangles' areas while the cap grid's connectivity is kept; the
    // sizing's (equal areas by default) once the shape stage has changed it.
    let target: Vec<f64> = if shaped {
        face_targets
    } else {
        faces.iter().map(|f| triangle_area(grid_mesh.vertices[f[0] as usize], grid_mesh.vertices[f[1] as usize], grid_mesh.vertices[f[2] as usize])).collect()
    };
    let equalization = equalize::equalize_areas(mesh, &top_faces, &map.plane, &faces, &target, &fixed, &mut planar, &mut positions, sweeps);
    let equalize_seconds = t_eq.elapsed().as_secs_f64();
    // The equalization can bend faces through their neighbours where the surface is sharp at
    // the remesh's scale: crossing faces are untangled last ([`shape::uncross`]).
    let mut uncross_report = shape::uncross::UncrossReport::default();
    if shaped {
        let lift = shape::state::SurfaceLift::new(inverse);
        let role: Vec<shape::state::Role> = (0..positions.len()).map(|v| if fixed[v] || !has_plane[v] { shape::state::Role::Fixed } else { shape::state::Role::Free }).collect();
        let orientation = shape::state::planar_orientation(&faces, &planar, &has_plane, &role, chart(closed));
        let mut state = shape::state::Shaping { faces, plane: planar, position: positions, hint: vec![u32::MAX; has_plane.len()], role, has_plane: has_plane.clone(), orientation, chart: chart(closed) };
        uncross_report = shape::uncross::uncross(&mut state, &lift, options.shape.crease_deg.to_radians());
        if uncross_report.moves + uncross_report.flips + uncross_report.collapses > 0 {
            let raised = shape::worst::raise_by_search(&mut state, &lift);
            shape_report.angle_moves += raised;
            // The moves for angles add no crossing but may mend the slivers the untangling
            // left: the bar is judged on the faces as they end.
            if raised > 0 {
                uncross_report.slivers_after = shape::uncross::sliver_count(&state.position, &state.faces, &state.has_plane);
            }
        }
        if uncross_report.collapses > 0 {
            // Collapsed vertices have no face left: drop them, renumbering the rest.
            shape::resample::compact(&mut state, &mut vec![0.0; has_plane.len()]);
            fixed = state.role.iter().map(|&r| r != shape::state::Role::Free).collect();
            has_plane = state.has_plane.clone();
        }
        (faces, planar, positions) = (state.faces, state.plane, state.position);
    }
    let mean_min_angle_deg = crate::metrics::angles::angle_quality_of(&positions, &faces).mean_min_angle_deg;
    let (_, d_face_relative) = crate::metrics::remeshing::area_deviation(&positions, &faces);
    let slivers_at_rim = if shaped && closed { shape::uncross::slivers_on_fixed_edges(&positions, &faces, &has_plane, &fixed) } else { 0 };
    let slivers_at_bottom = if shaped && closed { shape::uncross::slivers_at_bottom(&positions, &faces, &has_plane) } else { 0 };
    Ok(FromCap { faces, planar, positions, has_plane, shape: shape::ShapeReport { uncross: uncross_report, ..shape_report }, equalization, pullback_seconds, shape_seconds, equalize_seconds, mean_min_angle_deg, d_face_relative, slivers_at_rim, slivers_at_bottom, fixed, fit: super::FitReport::default() })
}

/// Where the shape stage keeps the remesh's faces oriented: on the cap for a closed surface,
/// whose stereographic plane bends a band around the cap (a long bone's shaft) into an
/// annulus and refuses the flips its surface triangles want; in the plane for an open one
/// (docs/method.md section 18, "Orientation on the cap").
fn chart(closed: bool) -> shape::state::Chart {
    if closed { shape::state::Chart::Cap } else { shape::state::Chart::Plane }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A remesh's figures as the retry decisions read them.
    fn made(mean_angle: f64, d_face: f64) -> FromCap {
        FromCap {
            faces: Vec::new(),
            planar: Vec::new(),
            positions: Vec::new(),
            has_plane: Vec::new(),
            shape: Default::default(),
            equalization: Default::default(),
            pullback_seconds: 0.0,
            shape_seconds: 0.0,
            equalize_seconds: 0.0,
            mean_min_angle_deg: mean_angle,
            d_face_relative: d_face,
            slivers_at_rim: 0,
            slivers_at_bottom: 0,
            fixed: Vec::new(),
            fit: Default::default(),
        }
    }

    /// A uniform remesh whose areas are spread beyond the bar is polished again with at least
    /// `LONGER_POLISH`'s iterations and global steps (no steps where the options make none);
    /// a sized remesh, an even one, options asking for a polish shorter than the default's and
    /// options that already polish as long are not.
    #[test]
    fn a_longer_polish_is_asked_for_spread_uniform_areas_only() {
        let options = RemeshOptions::default();
        let (iterations, steps) = LONGER_POLISH;
        let longer = polish_longer(&options, &made(48.5, 0.05)).expect("spread areas: a longer polish");
        assert_eq!((longer.shape.polish_iterations, longer.shape.area_steps), (iterations, steps));
        assert_eq!(longer.shape.relax_iterations, options.shape.relax_iterations, "only the polish changes");
        assert!(polish_longer(&options, &made(48.5, LONGER_POLISH_ABOVE)).is_none(), "at the bar: as it is");
        let sized = RemeshOptions { shape: options.shape.with_sizing(crate::remesh::sizing::Sizing::Surface), ..options.clone() };
        assert!(polish_longer(&sized, &made(48.5, 0.2)).is_none(), "a sized remesh's spread is its purpose");
        let no_steps = RemeshOptions { shape: options.shape.with_area_steps(0), ..options.clone() };
        let longer = polish_longer(&no_steps, &made(48.5, 0.05)).expect("a longer polish without global steps");
        assert_eq!((longer.shape.polish_iterations, longer.shape.area_steps), (iterations, 0));
        let no_polish = RemeshOptions { shape: options.shape.with_relax_iterations(0).with_polish_iterations(0), ..options.clone() };
        assert!(polish_longer(&no_polish, &made(35.0, 0.3)).is_none(), "no polish asked for: none made");
        let short = RemeshOptions { shape: options.shape.with_relax_iterations(2).with_polish_iterations(3), ..options.clone() };
        assert!(polish_longer(&short, &made(40.0, 0.2)).is_none(), "a short polish asked for: it stands");
        let long_already = RemeshOptions { shape: options.shape.with_polish_iterations(300).with_area_steps(30), ..options.clone() };
        assert!(polish_longer(&long_already, &made(48.5, 0.05)).is_none(), "nothing longer to try");
        // Of the two, fewer spread areas first, then the angles.
        assert!(area_rank(&made(47.5, 0.03)) < area_rank(&made(48.5, 0.04)));
        assert!(area_rank(&made(48.5, 0.04)) < area_rank(&made(47.5, 0.05)));
    }

    /// The other puncture end is tried for a uniform remesh below the angle bar or with its
    /// areas spread beyond `RETRY_AREA_SPREAD` (not for a sized one's spread, which is its
    /// purpose), and of two ends the even one is preferred before the angles.
    #[test]
    fn the_other_end_is_tried_for_angles_or_spread_areas() {
        assert!(!end_worth_retrying(&made(48.5, 0.03), true));
        assert!(end_worth_retrying(&made(47.5, 0.03), true));
        assert!(end_worth_retrying(&made(48.5, 0.049), true));
        assert!(!end_worth_retrying(&made(48.5, 0.2), false));
        assert!(end_rank(&made(48.2, 0.03), true) < end_rank(&made(49.0, 0.049), true));
        assert!(end_rank(&made(49.0, 0.03), true) < end_rank(&made(48.2, 0.03), true));
    }

    /// A sliver at a closed surface's bottom vertex misses the bar like any other (the next
    /// start and the other end are tried), and ranks a remesh below one without it.
    #[test]
    fn a_sliver_at_the_bottom_misses_the_bar() {
        let mut thin = made(49.0, 0.02);
        thin.slivers_at_bottom = 1;
        assert!(meets_bar(&made(49.0, 0.02)));
        assert!(!meets_bar(&thin));
        assert!(end_worth_retrying(&thin, true));
        assert!(rank(&made(48.1, 0.02)) < rank(&thin));
        assert!(end_rank(&made(48.1, 0.02), true) < end_rank(&thin, true));
    }
}
