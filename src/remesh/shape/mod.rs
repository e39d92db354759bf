//! Shape optimisation of the pulled-back remesh (ours; the paper pulls the cap mesh back as
//! is, Sec. 4.2, and measures only its areas). See docs/method.md, "18. Remesh shape".
//!
//! An area-preserving map has Jacobian singular values `s1 s2 = 1` with `s1 / s2` up to 3-10
//! where the angle distortion is large, so a uniform cap grid comes back as a lattice of
//! equal areas stretched by `s1 / s2`: no connectivity of those points is well shaped. This
//! stage moves the points and changes the connectivity:
//! 1. relaxation iterations: valence and max-min-angle edge flips judged on the surface
//!    triangles (`flips`), then tangential relaxation towards a centroidal tessellation on
//!    the surface, made in the map's plane and lifted through the inverse map (`smooth`);
//!    boundary vertices of an open surface slide along the input's boundary, its corners
//!    kept (`boundary`); optionally edge splits and collapses (`resample`), by length in the
//!    first half and by the regions' area error in the second (`rebalance`);
//! 2. polish iterations: angle flips and a joint area-and-shape Gauss-Newton step (`polish`),
//!    the first few replaced by a global Gauss-Newton step of the area term (`global_area`);
//! 3. the last flips, removals of vertices at slivers (`sliver`) and moves of the vertices of
//!    the faces still thin, weighted for shape (`worst`).
//!
//! The areas are the faces' chord areas, or with `--sizing surface` or `curvature` the surface
//! areas they cover (`covered`), so that a remesh coarser than the surface's folds keeps its
//! vertices in them.
//!
//! The stage starts from the pulled-back cap grid or, where that lift is stretched, from an
//! isotropic sample of the surface (`super::sample`, chosen by `super::remesh`).
//! A closed surface's rim and bottom disk may first be merged into one vertex (`bottom`).
//! Every vertex stays exactly on the input surface (it is always the lift of a planar point)
//! and the mesh stays an embedding in its chart: the plane for an open surface, the cap for a
//! closed one (`state::Chart`, docs/method.md section 18, "Orientation on the cap"). The area
//! equalization (`super::equalize`) runs after it.

pub(crate) mod blocks;
pub(crate) mod bottom;
pub(crate) mod boundary;
pub(crate) mod covered;
pub(crate) mod crease;
pub(crate) mod flips;
pub(crate) mod global_area;
mod options;
pub(crate) mod polish;
pub(crate) mod rebalance;
mod report;
pub(crate) mod resample;
pub(crate) mod sliver;
pub(crate) mod smooth;
pub(crate) mod state;
pub(crate) mod uncross;
pub(crate) mod worst;

pub use options::{Creases, ShapeOptions, COVERED_SHAPE_WEIGHT, DEFAULT_CREASE_DEG, DEFAULT_POLISH_TOLERANCE, DEFAULT_SHAPE_WEIGHT};
pub use report::{ShapeReport, Start};
pub use uncross::UncrossReport;

use crate::mesh::geometry::{dot, sub};
use rayon::prelude::*;
use state::{Role, Shaping, SurfaceLift};

/// The edge length of equilateral faces of `mesh`'s mean area.
fn target_length(mesh: &Shaping) -> f64 {
    crate::mesh::geometry::equilateral_edge(polish::ln_mean_area(mesh).exp(), 1.0)
}

/// A vertex's move: its new planar point, surface point, input face (`u32::MAX`: unknown)
/// and, on the boundary, arc length.
type Move = ([f64; 2], [f64; 3], u32, f64);

/// The shape stage's input: the pulled-back remesh and what each of its vertices may do.
pub(crate) struct ShapeInput<'a> {
    /// The inverse map.
    pub lift: &'a SurfaceLift<'a>,
    /// The boundary track of an open surface (`None` for a closed one: its rim stays).
    pub track: Option<&'a boundary::Track>,
    /// Whether each vertex has a planar point (not so a closed surface's bottom).
    pub has_plane: &'a [bool],
    /// Whether each vertex stays (rim and bottom of a closed surface).
    pub fixed: &'a [bool],
    /// The sizing's relative vertex density at each input vertex (`None`: uniform).
    pub density: Option<&'a [f64]>,
    /// Where the faces keep their orientation: the cap for a closed surface, the plane for an
    /// open one ([`state::Chart`]).
    pub chart: state::Chart,
}

/// Each remesh vertex's relative density: the input's `density` at its surface point (1 for
/// a vertex without a planar point, and everywhere when uniform).
fn vertex_densities(mesh: &Shaping, lift: &SurfaceLift, density: Option<&[f64]>) -> Vec<f64> {
    let Some(density) = density else { return vec![1.0; mesh.plane.len()] };
    (0..mesh.plane.len())
        .into_par_iter()
        .map(|v| if mesh.has_plane[v] { lift.interpolate(mesh.plane[v], mesh.hint[v], density).filter(|r| *r > 0.0).unwrap_or(1.0) } else { 1.0 })
        .collect()
}

/// The sizing's edge length factor: `density^(-1/2)` at the edge's midpoint.
fn length_factor(rho: &[f64]) -> impl Fn(u32, u32) -> f64 + '_ {
    move |a, b| (0.5 * (rho[a as usize] + rho[b as usize])).powf(-0.5)
}

/// Each face's density: the mean of its vertices'.
fn face_densities(faces: &[[u32; 3]], rho: &[f64]) -> Vec<f64> {
    faces.iter().map(|f| f.iter().map(|&v| rho[v as usize]).sum::<f64>() / 3.0).collect()
}

/// `ln` of each face's target area: areas proportional to `1 / face_rho` with the mesh's
/// total area.
fn ln_face_targets(mesh: &Shaping, face_rho: &[f64]) -> Vec<f64> {
    let ln_scale = polish::ln_mean_area(mesh) + (mesh.faces.len() as f64 / face_rho.iter().map(|r| 1.0 / r).sum::<f64>()).ln();
    face_rho.iter().map(|r| ln_scale - r.ln()).collect()
}

/// What [`optimize_shape`] returns besides the positions and planar points it moves in place.
pub(crate) struct Shaped {
    /// The new faces (vertices added and removed).
    pub faces: Vec<[u32; 3]>,
    /// Which vertices must stay in later stages (the rim and bottom of a closed surface, the
    /// boundary of an open one).
    pub stays: Vec<bool>,
    /// Which vertices have a planar point.
    pub has_plane: Vec<bool>,
    /// Each face's relative target area (all 1 when uniform).
    pub face_target: Vec<f64>,
    /// What the stage did.
    pub report: ShapeReport,
}

/// Run the relaxation and polish iterations of `options` on the remesh `(faces, plane,
/// position)` ([`Shaped`]; positions and planar points in place).
pub(crate) fn optimize_shape(
    input: &ShapeInput,
    faces: Vec<[u32; 3]>,
    plane: &mut Vec<[f64; 2]>,
    position: &mut Vec<[f64; 3]>,
    options: &ShapeOptions,
) -> Shaped {
    let n = plane.len();
    let before = crate::metrics::angles::angle_quality_of(position, &faces);
    let mut report = ShapeReport { before, after: before, sizing: options.sizing, keep_creases: options.keeps_creases(), crease_bound_deg: options.crease_deg, ..Default::default() };
    let (next, _) = boundary::boundary_cycle(&faces, n);
    let role: Vec<Role> = (0..n)
        .map(|v| {
            if input.fixed[v] && input.track.is_some() && next[v] != u32::MAX && input.has_plane[v] {
                Role::Boundary
            } else if input.fixed[v] || !input.has_plane[v] || next[v] != u32::MAX {
                Role::Fixed
            } else {
                Role::Free
            }
        })
        .collect();
    let orientation = state::planar_orientation(&faces, plane, input.has_plane, &role, input.chart);
    let has_plane = input.has_plane.to_vec();
    let mut mesh = Shaping { faces, plane: std::mem::take(plane), position: std::mem::take(position), hint: vec![u32::MAX; n], role, has_plane, orientation, chart: input.chart };
    let mut arc = vec![0.0f64; n];
    if let Some(track) = input.track {
        for v in 0..n {
            if mesh.role[v] == Role::Boundary {
                arc[v] = track.arc_of(mesh.plane[v]);
            }
        }
        let incidence = mesh.incidence();
        let scale = target_length(&mesh);
        report.corners_kept = boundary::pin_corners(&mut mesh, &incidence, track, &mut arc, scale);
    }
    let crease = options.crease_deg.to_radians();
    // A sized remesh measures its faces by the surface they cover (`covered`): fidelity is
    // what sizing is for.
    let by_covered = options.sizing.by_covered();
    let on_cap = input.lift.inverse().map().report.z_star.is_some();
    let (lloyd, mu) = (options.relax_iterations, if by_covered { COVERED_SHAPE_WEIGHT * options.shape_weight / DEFAULT_SHAPE_WEIGHT } else { options.shape_weight });
    // The target edge length: equilateral faces of the pulled-back mesh's mean area.
    let target_len = target_length(&mesh);
    let (faces0, mut len_factor) = (mesh.faces.len(), 1.0f64);
    let mut cycle: Option<(Vec<u32>, Vec<u32>)> = None;
    let mut flipper: Option<flips::Flipper> = None;
    let mut area_solver = crate::linalg::SpdSolver::new();
    let snap_creases = options.keeps_creases();
    let mut creases: Option<crease::CreaseSnap> = None;
    for it in 0..lloyd + options.polish_iterations {
        // Creases once the resampling is over (vertex numbers stay from then on).
        if snap_creases && it >= lloyd / 2 {
            let snap = creases.get_or_insert_with(|| crease::CreaseSnap::new(input.lift, &crease::crease_chains(input.lift, crease, target_len * len_factor), target_len * len_factor));
            let joined = snap.attempt(&mut mesh, input.lift);
            report.flips += joined;
            if joined > 0 {
                flipper = None;
            }
        }
        let resampled = options.resample && it < lloyd / 2 && target_len > 0.0;
        if resampled {
            // Splits and collapses balance at a slightly different count than asked for:
            // the target length follows the face count back to the pulled-back mesh's.
            len_factor *= (mesh.faces.len() as f64 / faces0 as f64).sqrt();
            let len = target_len * len_factor;
            // The sizing's lengths scale as density^(-1/2).
            let rho = vertex_densities(&mesh, input.lift, input.density);
            report.splits += resample::split_long_edges(&mut mesh, input.track, &mut arc, input.lift, resample::SPLIT * len, &length_factor(&rho));
            let incidence = mesh.incidence();
            let rho = vertex_densities(&mesh, input.lift, input.density);
            report.collapses += resample::collapse_short_edges(&mut mesh, &incidence, input.lift, resample::COLLAPSE * len, resample::SPLIT * len, &length_factor(&rho));
            if let Some(track) = input.track {
                let incidence = mesh.incidence();
                report.collapses += resample::collapse_short_boundary_edges(&mut mesh, &incidence, track, &mut arc, resample::BOUNDARY_COLLAPSE * len, resample::SPLIT * len, &length_factor(&rho));
            }
        }
        // The second half of the relaxation moves faces from where they are too small to
        // where they are too large (`rebalance`): uniform remeshes only, whose targets are
        // the mean chord area and whose length factor is 1.
        let rebalanced = options.resample && !by_covered && target_len > 0.0 && (lloyd / 2..lloyd).contains(&it) && {
            let ln_mean = polish::ln_mean_area(&mesh);
            let (splits, collapses) = rebalance::rebalance(&mut mesh, input.track, &mut arc, input.lift, &|_| ln_mean, resample::SPLIT * target_len * len_factor, &|_, _| 1.0);
            report.rebalance_splits += splits;
            report.rebalance_collapses += collapses;
            splits + collapses > 0
        };
        let faces_changed = resampled || rebalanced;
        // The edge table lives across iterations: only splits and collapses change the faces
        // besides the flips themselves.
        let mut kept = match flipper.take() {
            Some(mut f) if !faces_changed => {
                f.refresh(&mesh);
                f
            }
            _ => flips::Flipper::new(&mesh, crease),
        };
        let flipped = flips::flip_valence_then_angle(&mut kept, &mut mesh, it < lloyd);
        report.flips += flipped;
        flipper = Some(kept);
        // An open surface's boundary cycle changes with splits and collapses only (a flipped
        // edge is an interior one); a closed surface's rim does not slide.
        if input.track.is_some() && (cycle.is_none() || faces_changed) {
            cycle = Some(boundary::boundary_cycle(&mesh.faces, mesh.plane.len()));
        }
        let (next, prev) = cycle.as_ref().map_or((&[][..], &[][..]), |(n, p)| (&n[..], &p[..]));
        let incidence = mesh.incidence();
        let classes = mesh.color_classes(&incidence);
        // Face targets: areas proportional to 1 / density with the mesh's total area.
        let rho = vertex_densities(&mesh, input.lift, input.density);
        let face_rho = face_densities(&mesh.faces, &rho);
        let targets = ln_face_targets(&mesh, &face_rho);
        let target = |t: usize| targets[t];
        let weight = |t: usize| face_rho[t];
        let covered = if by_covered { covered::Covered::new(&mesh, on_cap) } else { None };
        // A global area step every AREA_STEP_SPACING polish iterations from the first
        // (global_area): the smooth part of the area error in one solve.
        let polish_it = it.checked_sub(lloyd);
        let global = match polish_it {
            Some(k) if !by_covered && k % global_area::AREA_STEP_SPACING == 0 && k / global_area::AREA_STEP_SPACING < options.area_steps => global_area::global_area_step(&mesh, &incidence, Some(input.lift), &target, global_area::SMOOTHNESS, &mut area_solver),
            _ => None,
        };
        report.area_steps += usize::from(global.is_some());
        // A global step moves every vertex at once, as it was solved (`global_area::apply_step`).
        if let Some(u) = global {
            report.moves += global_area::apply_step(&mut mesh, &u, &|q, hint| input.lift.lift(q, hint));
            report.iterations += 1;
            continue;
        }
        let mut moved_sq = 0.0;
        for class in &classes {
            let moves: Vec<(u32, Option<Move>)> = class
                .par_iter()
                .map(|&v| {
                    let v_ = v as usize;
                    let step = match (mesh.role[v_], input.track) {
                        (Role::Free, _) if it < lloyd => smooth::relax_vertex(&mesh, &incidence, v_, input.lift, &weight, covered.as_ref()).map(|(q, x, h)| (q, x, h, 0.0)),
                        (Role::Free, _) => polish::polish_vertex(&mesh, &incidence, v_, input.lift, &target, mu, covered.as_ref()).map(|(q, x, h)| (q, x, h, 0.0)),
                        (Role::Boundary, Some(track)) => boundary::slide_vertex(&mesh, &incidence, track, &arc, v_, prev[v_] as usize, next[v_] as usize).map(|(q, x, s)| (q, x, u32::MAX, s)),
                        _ => None,
                    };
                    (v, step)
                })
                .collect();
            for (v, step) in moves {
                if let Some((q, x, h, s)) = step {
                    let v = v as usize;
                    let d = sub(x, mesh.position[v]);
                    moved_sq += dot(d, d);
                    mesh.plane[v] = q;
                    mesh.position[v] = x;
                    if h != u32::MAX {
                        mesh.hint[v] = h;
                    }
                    if mesh.role[v] == Role::Boundary {
                        arc[v] = s;
                    }
                    report.moves += 1;
                }
            }
        }
        report.iterations += 1;
        // Converged: no flip, and the vertices moved by a tiny fraction of an edge.
        let after_global = polish_it.is_some_and(|k| k >= options.area_steps * global_area::AREA_STEP_SPACING);
        if after_global && flipped == 0 && moved_sq < (options.polish_tolerance.max(0.0) * target_len * len_factor).powi(2) * mesh.position.len() as f64 {
            break;
        }
    }
    if lloyd + options.polish_iterations > 0 {
        report.flips += flips::flip_to_max_min_angle(&mut mesh, crease);
        if creases.is_some() {
            report.crease_released = crease::release_thin(&mut mesh);
        }
        report.sliver_removals = sliver::remove_sliver_vertices(&mut mesh);
        // A closed surface's bottom (no planar point) is below its rim ring.
        if mesh.has_plane.iter().any(|&p| !p) {
            report.sliver_removals += sliver::collapse_rim_slivers(&mut mesh);
        }
        if report.sliver_removals > 0 {
            report.flips += flips::flip_to_max_min_angle(&mut mesh, crease);
        }
        // Thin faces left by the last flips and removals: their vertices moved for shape.
        let rho = vertex_densities(&mesh, input.lift, input.density);
        let targets = ln_face_targets(&mesh, &face_densities(&mesh.faces, &rho));
        let covered = if by_covered { covered::Covered::new(&mesh, on_cap) } else { None };
        let (moves, flips) = worst::raise_smallest_angles(&mut mesh, input.lift, &|t| targets[t], covered.as_ref(), crease);
        report.angle_moves = moves;
        report.flips += flips;
        // The moves and flips for shape can leave a vertex of valence 3 or 4 at a sliver
        // (next to a closed surface's bottom fan): removed as above.
        let late = sliver::remove_sliver_vertices(&mut mesh);
        if late > 0 {
            report.sliver_removals += late;
            report.flips += flips::flip_to_max_min_angle(&mut mesh, crease);
        }
    }
    if let Some(c) = &creases {
        report.crease_vertices = c.placed(&mesh);
        (report.crease_edges, report.crease_pairs) = c.joined(&mesh);
    }
    resample::compact(&mut mesh, &mut arc);
    let face_target = face_densities(&mesh.faces, &vertex_densities(&mesh, input.lift, input.density)).iter().map(|r| 1.0 / r).collect();
    report.after = crate::metrics::angles::angle_quality_of(&mesh.position, &mesh.faces);
    let stays = mesh.role.iter().map(|&r| r != Role::Free).collect();
    *plane = mesh.plane;
    *position = mesh.position;
    Shaped { faces: mesh.faces, stays, has_plane: mesh.has_plane, face_target, report }
}
