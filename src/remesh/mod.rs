//! Remeshing through the cap (paper Sec. 4.2): parameterize, build a uniform or
//! latitude/longitude mesh of the cap `Z >= Z*`, pull it back onto the surface.

pub(crate) mod equalize;
pub(crate) mod fit;
pub(crate) mod from_cap;
pub(crate) mod grid;
pub(crate) mod locate;
mod options;
pub(crate) mod pullback;
pub(crate) mod sample;
pub mod shape;
pub(crate) mod sizing;
pub(crate) mod transfer;

pub use fit::FitReport;
pub use options::{CapGrid, Holes, Optimize, Pieces, Placement, RemeshOptions, DEFAULT_AREA_EQUALIZATION, MAX_GRID_FACES};

use crate::refine::area_refine::AreaRefineReport;
use crate::param::{parameterize, ParamOptions, ParamReport, PunctureEnd};
use crate::error::Error;
use crate::cap::{stereographic, CapMap, SurfacePoint};
use crate::mesh::topology::is_boundary_vertex;
use crate::mesh::geometry::triangle_area;
use crate::mesh::repair::{keep_main_component, repair_for, MainComponent, Repaired};
use crate::mesh::{MeshError, SurfaceKind, TriMesh};
use crate::metrics::remeshing::remesh_metrics_with;
use crate::metrics::RemeshMetrics;
use crate::progress::{self, Progress, Stage};
use rayon::prelude::*;
use std::time::Instant;

/// What [`remesh`] measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RemeshReport {
    /// The parameterization.
    pub param: ParamReport,
    /// What was optimised after the pull-back.
    pub optimize: Optimize,
    /// The shape stage (all zero when it did not run).
    pub shape: shape::ShapeReport,
    /// The area equalization of the pulled-back mesh.
    pub area_equalization: AreaRefineReport,
    /// The least-squares vertex placement ([`Placement::Fitted`]; `fitted` false otherwise).
    pub fit: FitReport,
    /// Quality of the result against the input.
    pub quality: RemeshMetrics,
    /// Seconds of the whole remeshing (parameterization and quality metrics included).
    pub seconds: f64,
    /// Seconds spent pulling the cap mesh back (with the isotropic samples' construction).
    pub pullback_seconds: f64,
    /// Seconds spent in the shape stage of the start kept (the starts tried before it count
    /// in [`RemeshReport::seconds`] only).
    pub shape_seconds: f64,
    /// Seconds spent in the area equalization.
    pub equalize_seconds: f64,
    /// Seconds spent measuring the result ([`RemeshReport::quality`]).
    pub metrics_seconds: f64,
    /// Copies made of pinched input vertices, one per fan beyond the first
    /// ([`split_pinched_vertices`](crate::mesh::repair::split_pinched_vertices); 0 for a manifold input).
    pub split_vertices: usize,
    /// Input faces flipped to agree with their neighbours ([`orient_coherently`](crate::mesh::repair::orient_coherently); 0 for a
    /// coherently oriented input).
    pub reoriented_faces: usize,
    /// Input faces dropped as repeats of an earlier face ([`remove_duplicate_faces`](crate::mesh::repair::remove_duplicate_faces)).
    pub duplicate_faces: usize,
    /// Pieces of the input dropped besides the largest (at most [`DROPPED_AREA_SHARE`] of
    /// the area, [`keep_main_component`]); the metrics are against the piece kept.
    pub dropped_components: usize,
    /// The dropped pieces' share of the input's area.
    pub dropped_area_share: f64,
    /// Midpoint subdivisions of the input made for its map ([`subdivision_levels`]; 0: mapped
    /// as it is). The parameterization's counts are the subdivided mesh's.
    pub subdivided: usize,
    /// Edges of the input (after its subdivisions) longer than [`SPLIT_LONGER_THAN`] of the
    /// remesh's split at their midpoints for its map (0: none was that long). The
    /// parameterization's counts are the split mesh's.
    pub split_edges: usize,
    /// Holes of the input filled ([`Holes::Fill`]; 0 otherwise, and for a closed input); the
    /// metrics are against the filled surface.
    pub filled_holes: usize,
}

/// The planar positions of those `vertices` that lie on the rim (an open surface's boundary,
/// a closed one's punctured quad), by angle and without repeats: the polygon the planar map
/// covers; and the rim's radius. Points off the rim (a seam that the parameterization welded
/// shut looks like boundary in the input) are left out.
fn polygon_of(vertices: impl Iterator<Item = u32>, plane: &[[f64; 2]]) -> (Vec<[f64; 2]>, f64) {
    let points: Vec<[f64; 2]> = vertices.filter_map(|v| plane.get(v as usize).copied()).collect();
    let rim_radius = points.iter().map(|c| c[0].hypot(c[1])).fold(0.0, f64::max);
    pullback::polygon_by_angle(points.into_iter().filter(|c| c[0].hypot(c[1]) >= (1.0 - RIM_TOLERANCE) * rim_radius).collect())
}

/// Relative distance below the rim's radius within which a boundary point counts as on it.
const RIM_TOLERANCE: f64 = 1e-6;

/// Remesh a surface through its adaptive cap: an open disk gives an open disk, a closed
/// genus-0 surface a closed genus-0 mesh (the cap grid closed by a flat bottom disk that is
/// pulled back onto the punctured quad).
///
/// The work runs on a worker thread of rayon's pool; `progress` is called on this thread
/// (see `crate::pool`).
pub fn remesh(mesh: &TriMesh, options: &RemeshOptions, progress: &dyn Progress) -> Result<(TriMesh, RemeshReport), Error> {
    crate::pool::on_pool(progress, |progress| remesh_here(mesh, options, progress, false)).map(|(m, r, _)| (m, r))
}

/// [`remesh`], also returning each remesh vertex's point of the input surface (face and
/// barycentric coordinates, through the inverse map): what [`transfer::carry_attribute`]
/// carries per-vertex data with. A vertex fitted off the surface ([`Placement::Fitted`]) gets
/// the surface point it was moved from along its normal.
pub fn remesh_located(mesh: &TriMesh, options: &RemeshOptions, progress: &dyn Progress) -> Result<(TriMesh, RemeshReport, Vec<SurfacePoint>), Error> {
    crate::pool::on_pool(progress, |progress| remesh_here(mesh, options, progress, true))
}

/// The pull-back of the cap grid of `options` through `map` and the stages after it; each
/// remesh vertex's surface point too when `locate`.
fn remesh_with(mesh: &TriMesh, map: &CapMap, options: &RemeshOptions, shaped: bool, locate: bool, input_crossings: &from_cap::InputCrossings, progress: &dyn Progress) -> Result<(from_cap::FromCap, Vec<SurfacePoint>), Error> {
    let closed = map.report.kind != SurfaceKind::OpenDisk;
    let z_star = map.report.z_star.ok_or_else(|| Error::InvalidOption("remeshing needs a spherical cap domain, not the planar disk".into()))?;
    progress::check(progress, Stage::Remesh, 0.0, "pulling the cap mesh back")?;
    let cap = match options.grid {
        CapGrid::Uniform { faces } => grid::uniform_cap(z_star, faces.max(1)),
        CapGrid::LatLong { rings, sectors } => grid::lat_long(z_star, rings, sectors),
    };
    // The inverse map, its point location built once for the pull-back and the shape stage.
    let inverse = map.inverse(mesh)?;
    let input_boundary = is_boundary_vertex(mesh);
    let ctx = from_cap::Context { mesh, map, inverse: &inverse, options, closed, shaped, input_boundary: &input_boundary, input_crossings };
    let mut result = if shaped {
        // The shape stage starts from an isotropic sample of the surface where the grid's
        // lift is stretched ([`from_cap::from_best_start`]). Cap points are lifted as in the
        // pull-back: inside the polygon the planar map covers.
        let (corners, rim_radius) = if closed {
            polygon_of(map.bottom_faces.iter().filter_map(|&f| mesh.faces.get(f)).flatten().copied(), &map.plane)
        } else {
            polygon_of((0..mesh.n_vertices() as u32).filter(|&v| input_boundary[v as usize]), &map.plane)
        };
        let place = |points: &[[f64; 3]]| -> Vec<Option<[f64; 3]>> {
            let mut q: Vec<[f64; 2]> = points.iter().map(|&x| stereographic(x)).collect();
            pullback::rim_band_into_polygon(&mut q, &corners, rim_radius);
            q.par_iter().map(|&q| inverse.locate_plane(q).map(|p| p.position)).collect()
        };
        let surface_area: f64 = mesh.faces.iter().map(|f| triangle_area(mesh.vertices[f[0] as usize], mesh.vertices[f[1] as usize], mesh.vertices[f[2] as usize])).sum();
        from_cap::from_best_start(&ctx, cap, &place, surface_area, progress)?
    } else {
        from_cap::pull_back_and_optimize(&ctx, cap, progress)?
    };
    // The vertices' surface points (where they are, unless fitted off the surface).
    let mut on_surface = Vec::new();
    if options.placement == Placement::Fitted {
        let sweeps = match options.optimize {
            Optimize::None => 0,
            _ => options.area_equalization,
        };
        // A sized remesh's faces are measured by the surface they cover (`shape::covered`):
        // the fit leaves their chord areas free.
        let keep_areas = !(shaped && options.shape.sizing.by_covered());
        let input = fit::FitInput { faces: &result.faces, has_plane: &result.has_plane, fixed: &result.fixed, sweeps, keep_areas };
        result.fit = fit::fit_to_surface(&inverse, &input, &mut result.planar, &mut result.positions, &mut on_surface);
    }
    let surface = if on_surface.is_empty() { &result.positions } else { &on_surface };
    let points = if locate { transfer::surface_points(&inverse, &result.planar, &result.has_plane, surface) } else { Vec::new() };
    Ok((result, points))
}

/// The other end of a closed map punctured at the end [`PunctureEnd::Best`] kept: the trial
/// without a finished map (`None` when the map had no two trials).
fn other_end(map: &CapMap) -> Option<PunctureEnd> {
    match &map.report.puncture_trials[..] {
        [bottom, top] if bottom.mean_abs_area_distortion.is_some() && top.mean_abs_area_distortion.is_none() => Some(PunctureEnd::Top),
        [bottom, top] if top.mean_abs_area_distortion.is_some() && bottom.mean_abs_area_distortion.is_none() => Some(PunctureEnd::Bottom),
        _ => None,
    }
}

/// [`remesh`] on the current thread; the surface points only when `locate`.
///
/// A closed surface whose shape-stage remesh misses the quality bar
/// ([`from_cap::meets_bar`]) or, uniform, spreads its areas more than
/// [`from_cap::RETRY_AREA_SPREAD`], with [`PunctureEnd::Best`], is mapped again punctured at
/// the other end and remeshed from that map; the better remesh is kept
/// ([`from_cap::end_rank`]). The
/// two ends' search maps often tie, and the finished maps then differ near the puncture
/// (docs/method.md section 18, "Finely triangulated inputs").
///
/// Four repairs are made when the input needs them, each reported: repeated faces are
/// dropped ([`remove_duplicate_faces`]), faces wound against their neighbours are flipped
/// ([`orient_coherently`]; each piece keeps the orientation of most of its faces), a vertex
/// where the surface touches itself is split, one per fan ([`split_pinched_vertices`]; the
/// faces keep their order), and of several pieces the largest is remeshed when the others
/// hold at most [`DROPPED_AREA_SHARE`] of the area ([`keep_main_component`]: marching cubes
/// leaves such specks), or whatever they hold with [`Pieces::Largest`]. Surface points name the input's faces, with weights in the order of
/// the input's corners, either way. With [`Holes::Fill`] a manifold input's holes are filled
/// before all of these; a point in a hole names the input face across the hole's rim
/// ([`FilledHoles::on_input`](crate::mesh::holes::FilledHoles::on_input)).
fn remesh_here(mesh: &TriMesh, options: &RemeshOptions, progress: &dyn Progress, locate: bool) -> Result<(TriMesh, RemeshReport, Vec<SurfacePoint>), Error> {
    options.check().map_err(Error::InvalidOption)?;
    // Holes are filled first (a manifold input's): the repairs below then renumber the filled
    // surface's faces, and its points go back to the input's at the end.
    let filled = if options.holes == Holes::Fill { crate::mesh::holes::fill_holes(mesh) } else { None };
    let base = filled.as_ref().map_or(mesh, |f| &f.mesh);
    let mut work = std::borrow::Cow::Borrowed(base);
    let (mut split, mut kept, mut deduplicated): (Option<usize>, Option<MainComponent>, Option<usize>) = (None, None, None);
    // The input face of each face of `work`, once a repair has renumbered them.
    let mut to_input: Option<Vec<u32>> = None;
    let input_face = |to_input: &Option<Vec<u32>>, t: usize| to_input.as_ref().map_or(t, |m| m[t] as usize);
    // The input faces flipped, and how many.
    let mut flipped: Option<(Vec<bool>, usize)> = None;
    loop {
        match remesh_manifold(&work, options, progress, locate) {
            // Each repair once (`mesh::repair::repair_for`, as the CLI's param and check).
            Err(Error::Mesh(e))
                if match e {
                    MeshError::DuplicateFace { .. } => deduplicated.is_none(),
                    MeshError::InconsistentOrientation { .. } => flipped.is_none(),
                    MeshError::NonManifoldVertex { .. } => split.is_none(),
                    _ => false,
                } =>
            {
                match repair_for(&work, &e)? {
                    Some(Repaired::Deduplicated(d)) => {
                        to_input = Some(d.faces.iter().map(|&t| input_face(&to_input, t as usize) as u32).collect());
                        deduplicated = Some(d.removed_faces);
                        work = std::borrow::Cow::Owned(d.mesh);
                    }
                    Some(Repaired::Reoriented(o)) => {
                        let mut by_input = vec![false; base.n_faces()];
                        for (t, _) in o.flipped.iter().enumerate().filter(|(_, &f)| f) {
                            by_input[input_face(&to_input, t)] = true;
                        }
                        flipped = Some((by_input, o.flipped_faces));
                        work = std::borrow::Cow::Owned(o.mesh);
                    }
                    Some(Repaired::Split(s)) => {
                        split = Some(s.copy_of.len());
                        work = std::borrow::Cow::Owned(s.mesh);
                    }
                    None => return Err(Error::Mesh(e)),
                }
            }
            Err(Error::Mesh(e @ MeshError::SeveralComponents { .. })) if kept.is_none() => {
                match keep_main_component(&work) {
                    Some(mut main) if main.dropped_area_share <= DROPPED_AREA_SHARE || options.pieces == Pieces::Largest => {
                        to_input = Some(main.faces.iter().map(|&t| input_face(&to_input, t as usize) as u32).collect());
                        work = std::borrow::Cow::Owned(std::mem::take(&mut main.mesh));
                        kept = Some(main);
                    }
                    _ => return Err(Error::Mesh(e)),
                }
            }
            Ok((out, mut report, mut points)) => {
                report.split_vertices = split.unwrap_or(0);
                report.duplicate_faces = deduplicated.unwrap_or(0);
                if let Some(main) = &kept {
                    report.dropped_components = main.dropped_components;
                    report.dropped_area_share = main.dropped_area_share;
                }
                for p in &mut points {
                    p.face = input_face(&to_input, p.face);
                }
                if let Some((by_input, count)) = &flipped {
                    report.reoriented_faces = *count;
                    // A flipped face lists the input face's corners as (0, 2, 1).
                    for p in points.iter_mut().filter(|p| by_input[p.face]) {
                        p.barycentric.swap(1, 2);
                    }
                }
                if let Some(f) = &filled {
                    report.filled_holes = f.holes;
                    for p in &mut points {
                        (p.face, p.barycentric) = f.on_input(p.face, p.barycentric);
                    }
                }
                return Ok((out, report, points));
            }
            Err(e) => return Err(e),
        }
    }
}

/// Most midpoint subdivisions of a coarse input ([`subdivision_levels`]).
pub const MAX_SUBDIVISIONS: usize = 3;

/// Most faces a coarse input is subdivided to ([`subdivision_levels`]): beyond, a closed
/// surface would be mapped through a decimated copy again (`--multilevel-above`).
pub const MAX_SUBDIVIDED_FACES: usize = 200_000;

/// How many times an input of `faces` faces is midpoint-subdivided (1:4, the surface
/// unchanged) before its map, for a uniform remesh of `asked` faces: the fewest that give
/// the map at least as many faces as the remesh, at most [`MAX_SUBDIVISIONS`] and
/// [`MAX_SUBDIVIDED_FACES`] faces. The map is piecewise linear on the input's faces; where
/// it is strongly anisotropic (a long bone's shaft on the cap) a remesh face spanning
/// several of them is stretched differently at its corners, so the shape stage's linear
/// models of the map are off and the moves and flips that the surface triangles want fold
/// the chart's (docs/method.md section 25, "Coarse inputs").
pub fn subdivision_levels(faces: usize, asked: usize) -> usize {
    let mut levels = 0;
    let mut n = faces.max(1);
    while n < asked && levels < MAX_SUBDIVISIONS && 4 * n <= MAX_SUBDIVIDED_FACES {
        n *= 4;
        levels += 1;
    }
    levels
}

/// Vertices of the decimated copy through which a remesh of about `faces` faces maps a fine
/// closed input ([`RemeshOptions::coarse_map`]): [`REMESH_COPY_PER_FACE`] per remesh face, at
/// least [`MIN_REMESH_COPY`].
pub fn remesh_copy_vertices(faces: u64) -> usize {
    let copy = (faces as f64 * REMESH_COPY_PER_FACE).ceil();
    if copy < usize::MAX as f64 { (copy as usize).max(MIN_REMESH_COPY) } else { usize::MAX }
}

/// Copy vertices per remesh face (2.4 per remesh vertex): see docs/method.md section 20,
/// "Maps sized to the remesh".
pub const REMESH_COPY_PER_FACE: f64 = 1.2;

/// The smallest copy [`remesh_copy_vertices`] asks for.
pub const MIN_REMESH_COPY: usize = 6_000;

/// Area refinement sweeps at full resolution after the copy's map is prolonged
/// ([`crate::ClosedOptions::prolonged_refinement`]): the shape stage equalizes the remesh's
/// areas on the surface, the map is its chart (docs/method.md section 20).
pub const REMESH_COPY_SWEEPS: usize = 10;

/// The parameterization options of a remesh of about `faces` faces: with
/// [`RemeshOptions::coarse_map`] and the shape stage (`shaped`, which measures the faces on
/// the surface itself), a closed input of more than twice [`remesh_copy_vertices`] maps
/// through a copy of that size (or of the options' own size when smaller), refined at full
/// resolution by [`REMESH_COPY_SWEEPS`] sweeps (unless the options say); the options'
/// "never" (`multilevel_above` 0) stands. Without the shape stage the map's own area
/// distortion sets the remesh's areas, and a sized remesh measures its faces by the surface
/// they cover through the map: both get the options' map.
fn map_options(options: &RemeshOptions, faces: u64, shaped: bool) -> ParamOptions {
    let mut param = options.param.clone();
    if options.coarse_map && shaped && !options.shape.sizing.by_covered() && param.closed.multilevel_above > 0 {
        let copy = remesh_copy_vertices(faces);
        param.closed.coarse_vertices = param.closed.coarse_vertices.min(copy);
        param.closed.multilevel_above = param.closed.multilevel_above.min(2 * copy);
        param.closed.prolonged_refinement.get_or_insert(REMESH_COPY_SWEEPS);
    }
    param
}

/// Largest share of the input's area in pieces besides the largest that `remesh` drops
/// (specks of a segmentation); above it several pieces are an error.
pub const DROPPED_AREA_SHARE: f64 = 0.01;

/// [`remesh_here`] on one piece without pinched vertices: mapped through a subdivided copy
/// when it is coarser than the remesh ([`subdivision_levels`]), with its edges longer than
/// the remesh's split ([`SPLIT_LONGER_THAN`]).
fn remesh_manifold(mesh: &TriMesh, options: &RemeshOptions, progress: &dyn Progress, locate: bool) -> Result<(TriMesh, RemeshReport, Vec<SurfacePoint>), Error> {
    let start = Instant::now();
    // Refused before the parameterization, which would be wasted.
    let asked = options.grid.approximate_faces();
    if asked > MAX_GRID_FACES {
        return Err(Error::InvalidOption(format!("a cap mesh of about {asked} faces is more than capmesh remeshes (at most {MAX_GRID_FACES}); ask for fewer faces, rings or sectors")));
    }
    let shaped = options.optimize == Optimize::ShapeAndArea && matches!(options.grid, CapGrid::Uniform { .. });
    let refine = options.subdivide_coarse && shaped;
    let levels = if refine { subdivision_levels(mesh.n_faces(), asked as usize) } else { 0 };
    let subdivided = (levels > 0).then(|| crate::mesh::subdivide_midpoint(mesh, levels));
    let base = subdivided.as_ref().unwrap_or(mesh);
    let split = if refine { crate::mesh::split_long::split_long_edges(base, SPLIT_LONGER_THAN * remesh_edge_length(mesh, asked), MAX_SUBDIVIDED_FACES) } else { None };
    if levels > 0 || split.is_some() {
        // The input's own errors name its own elements: checked before its refined copy is
        // mapped (subdividing drops faces with indices out of range), and the input as it is
        // mapped again when the copy's preparation fails (an error there is cheap).
        crate::mesh::validate::checked_topology(mesh)?;
        let work = Refined { mesh: split.as_ref().map_or(base, |s| &s.mesh), levels, split: split.as_ref() };
        return match remesh_work(mesh, &work, options, shaped, progress, locate, start) {
            Err(Error::Mesh(_)) => remesh_work(mesh, &Refined::none(mesh), options, shaped, progress, locate, start),
            other => other,
        };
    }
    remesh_work(mesh, &Refined::none(mesh), options, shaped, progress, locate, start)
}

/// Input edges longer than this many of the remesh's edges (the edge of an equilateral
/// triangle of the input's mean area over the remesh's faces) are split for the map
/// (`mesh::split_long`; docs/method.md section 25, "Long edges"): the transport then has
/// sites along a decimated long bone's shaft, and the shape stage's linear models of the map
/// hold across a remesh face. 3: at 1 and 2 the decimated bones came out the same from more
/// vertices, and at 2 the fsaverage5 cortices at 20000 faces split edges for a lower smallest
/// angle.
pub const SPLIT_LONGER_THAN: f64 = 3.0;

/// The edge of an equilateral triangle of `mesh`'s mean area over `faces` faces: the remesh's
/// edge length. The input is not validated yet: faces with an index out of range and areas
/// that are not finite are left out (the map's checks name them).
fn remesh_edge_length(mesh: &TriMesh, faces: u64) -> f64 {
    let corner = |v: u32| mesh.vertices.get(v as usize).copied();
    let area: f64 = mesh
        .faces
        .iter()
        .filter_map(|f| Some(crate::mesh::geometry::triangle_area(corner(f[0])?, corner(f[1])?, corner(f[2])?)))
        .filter(|a| a.is_finite())
        .sum();
    crate::mesh::geometry::equilateral_edge(area, faces.max(1) as f64)
}

/// The mesh a remesh maps: the input midpoint-subdivided `levels` times, then its long edges
/// split (`split`), or the input itself.
struct Refined<'a> {
    mesh: &'a TriMesh,
    levels: usize,
    split: Option<&'a crate::mesh::split_long::SplitMesh>,
}

impl<'a> Refined<'a> {
    /// The input as it is.
    fn none(mesh: &'a TriMesh) -> Self {
        Self { mesh, levels: 0, split: None }
    }

    /// A point of the refined mesh (face, barycentric coordinates) as the input's.
    fn input_point(&self, face: usize, barycentric: [f64; 3]) -> (usize, [f64; 3]) {
        let (face, barycentric) = self.split.map_or((face, barycentric), |s| s.parent_point(face, barycentric));
        crate::mesh::subdivide::parent_point(face, barycentric, self.levels)
    }
}

/// [`remesh_manifold`] with the map made of `work`, a refinement of `mesh`: the metrics are
/// against `mesh`, the surface points name its faces.
#[allow(clippy::too_many_arguments)]
fn remesh_work(mesh: &TriMesh, refined: &Refined<'_>, options: &RemeshOptions, shaped: bool, progress: &dyn Progress, locate: bool, start: Instant) -> Result<(TriMesh, RemeshReport, Vec<SurfacePoint>), Error> {
    let work = refined.mesh;
    let param = map_options(options, options.grid.approximate_faces(), shaped);
    // The input's own crossing faces (a metric) are counted while it is mapped: the map
    // leaves a core idle at times. Not an input the map will refuse (an index out of range,
    // a coordinate not finite or out of scale): it is counted after the map, if the map is made.
    let countable = crate::mesh::checks::check_indices(mesh).is_ok() && crate::mesh::validate::check_finite(mesh).is_ok();
    let (map, input_crossing) = rayon::join(|| parameterize(work, &param, progress), || countable.then(|| crate::metrics::count_self_intersecting_faces(mesh)));
    let mut map = map?;
    // The input's crossing faces, found once for both puncture ends if a remesh crosses.
    let input_crossings = from_cap::InputCrossings::new(work);
    let (mut result, mut points) = remesh_with(work, &map, options, shaped, locate, &input_crossings, progress)?;
    let closed = map.report.kind != SurfaceKind::OpenDisk;
    let uniform = !options.shape.sizing.by_covered();
    if shaped && closed && param.closed.puncture_end == PunctureEnd::Best && from_cap::end_worth_retrying(&result, uniform) {
        if let Some(other) = other_end(&map) {
            let mut param = param.clone();
            param.closed.puncture_end = other;
            // The other end failing is no reason to fail the remesh already made (unless the
            // user cancelled).
            let other = parameterize(work, &param, progress).and_then(|m| remesh_with(work, &m, options, shaped, locate, &input_crossings, progress).map(|r| (m, r)));
            if let Err(e @ Error::Cancelled(_)) = other {
                return Err(e);
            }
            if let Ok((other_map, (other_result, other_points))) = other {
                // Both ends finished: the kept map's report gives both final maps.
                let mut trials = map.report.puncture_trials.clone();
                for t in &mut trials {
                    if other_map.report.puncture.as_ref().is_some_and(|p| p.axis == t.axis) {
                        t.mean_abs_area_distortion = Some(other_map.report.area_distortion.mean_abs);
                    }
                }
                if from_cap::end_rank(&other_result, uniform) < from_cap::end_rank(&result, uniform) {
                    (map, result, points) = (other_map, other_result, other_points);
                }
                map.report.puncture_trials = trials;
                result.shape.ends = 2;
            }
        }
    }
    let from_cap::FromCap { faces, planar: _, positions, has_plane: _, shape: shape_report, equalization, pullback_seconds, shape_seconds, equalize_seconds, fit, .. } = result;
    let out = TriMesh::new(positions, faces);
    for p in &mut points {
        (p.face, p.barycentric) = refined.input_point(p.face, p.barycentric);
    }
    let t_metrics = Instant::now();
    let quality = remesh_metrics_with(mesh, &out, input_crossing);
    let metrics_seconds = t_metrics.elapsed().as_secs_f64();
    let report = RemeshReport {
        param: map.report,
        optimize: options.optimize,
        shape: shape_report,
        area_equalization: equalization,
        fit,
        quality,
        seconds: start.elapsed().as_secs_f64(),
        pullback_seconds,
        shape_seconds,
        equalize_seconds,
        metrics_seconds,
        split_vertices: 0,
        reoriented_faces: 0,
        duplicate_faces: 0,
        dropped_components: 0,
        dropped_area_share: 0.0,
        filled_holes: 0,
        subdivided: refined.levels,
        split_edges: refined.split.map_or(0, |s| s.splits),
    };
    Ok((out, report, points))
}
