//! The second half of a parameterization: the transport map at `r*`, its smoothing and
//! fold repair, the area refinement, and the report.

use super::options::ParamOptions;
use super::prepare::Prepared;
use super::report::{MapQuality, ParamReport};
use super::search::{search_radius, transport_density, Searched};
use crate::cap::domain::Domain;
use crate::cap::stereographic::{inverse_stereographic, stereographic, z_star_of_radius};
use crate::cap::CapMap;
use crate::error::Error;
use crate::linalg::cotangent_weights;
use crate::mesh::geometry::folded_faces;
use crate::mesh::topology::{sorted_face, within_rings};
use crate::mesh::{repair, SurfaceKind, TriMesh};
use crate::metrics::{angle_distortion, area_distortion, conformal_energy, Stats};
use crate::omt::planar_transport::PlanarTransport;
use crate::omt::OmtError;
use crate::progress::{self, Progress, Stage};
use crate::refine::area_refine::{refine_areas, RefineOptions};
use crate::refine::smoothing::{smooth_centroid_map, PUNCTURE_HELD_RINGS};
use std::time::Instant;

/// [`super::parameterize`] of the prepared `mesh` with the puncture end fixed by
/// `options.closed.flatten.puncture`: the radius search, then [`finish`].
pub(crate) fn parameterize_once(mesh: &TriMesh, prepared: &Prepared, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let searched = search_radius(prepared, options, false, progress)?;
    finish(mesh, searched, options, progress)
}

/// The second half of [`parameterize_once`]: the transport map at the searched radius (unless
/// the search solved it), its smoothing and fold repair, the area refinement and the
/// report.
pub(crate) fn finish(mesh: &TriMesh, s: Searched<'_>, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let Searched {
        prepared,
        faces,
        disk,
        on_boundary,
        target,
        flatten_report,
        puncture,
        mut radius,
        map,
        search_area_distortion: _,
        curve,
        search_sites,
        search_refinements,
        unrefined_radius,
        coarse_newton_iterations,
        mut newton_iterations,
        mut solves,
        symbolic_factorizations: mut symbolic,
        flatten_seconds,
        transport_seconds: search_seconds,
    } = s;
    let Prepared { welded, kind, .. } = prepared;
    let (kind, work) = (*kind, &welded.mesh);
    let t_ot = Instant::now();
    let transported = match map {
        Some(map) => map,
        None => {
            let mut transport = PlanarTransport::new(&disk, &on_boundary, &target, transport_density(options.domain), options.transport.clone());
            let mut mapped = transport.map_at(radius, progress);
            // A refined search's radius where the transport fails (a very elongated surface
            // at the bound of `Z*`): the first search's (docs/method.md section 5).
            use crate::omt::OmtError::{Linear, NotConverged, Stalled, Triangulation};
            if let (Err(Stalled { .. } | NotConverged { .. } | Linear(_) | Triangulation(_)), Some(r0)) = (&mapped, unrefined_radius) {
                radius = r0;
                transport = PlanarTransport::new(&disk, &on_boundary, &target, transport_density(options.domain), options.transport.clone());
                mapped = transport.map_at(radius, progress);
            }
            let map = mapped?;
            newton_iterations += transport.newton_iterations;
            solves += transport.solves;
            symbolic += transport.symbolic_factorizations;
            map
        }
    };
    let transport_seconds = search_seconds + t_ot.elapsed().as_secs_f64();
    let to_cap = |q: [f64; 2]| cap_point(options.domain, q);
    let t_reg = Instant::now();
    let cot = cotangent_weights(&work.vertices, &faces);
    let held = if kind == SurfaceKind::ClosedSphere { within_rings(&on_boundary, &faces, PUNCTURE_HELD_RINGS) } else { on_boundary.clone() };
    let chosen = smooth_centroid_map(&transported, &work.vertices, &faces, &cot, &on_boundary, &held, radius, options.refinement.smoothing, &to_cap).map_err(OmtError::Linear)?;
    let (kappa, plane, untangle_report, trials) = (chosen.kappa, chosen.positions, chosen.untangle, chosen.trials);
    let smoothing_seconds = t_reg.elapsed().as_secs_f64();
    let spherical = options.domain != Domain::Disk;
    let report = ParamReport {
        domain: options.domain,
        kind,
        n_vertices: mesh.n_vertices(),
        n_faces: mesh.n_faces(),
        welded_vertices: welded.merged_vertices,
        split_vertices: welded.split_vertices,
        collapsed_short_edges: 0,
        r_star: spherical.then_some(radius),
        z_star: spherical.then(|| z_star_of_radius(radius)),
        quality: MapQuality::Unrated,
        area_distortion: Stats::default(),
        angle_distortion: Stats::default(),
        conformal_energy: 0.0,
        flipped_faces: 0,
        untangle: untangle_report,
        area_refinement: Default::default(),
        smoothing_kappa: kappa,
        smoothing_trials: trials,
        newton_iterations,
        search_sites,
        search_refinements,
        coarse_newton_iterations,
        transport_solves: solves,
        transport_symbolic_factorizations: symbolic,
        radius_curve: curve,
        flatten: flatten_report,
        puncture,
        puncture_trials: Vec::new(),
        lambda_fallbacks: Vec::new(),
        multilevel: None,
        seconds: 0.0,
        flatten_seconds,
        transport_seconds,
        smoothing_seconds,
        refine_seconds: 0.0,
    };
    conclude(mesh, prepared, &faces, &on_boundary, plane, options, progress, report)
}

/// The end of every parameterization, once the planar map `plane` of the prepared mesh's
/// `faces` (the punctured ones for a closed surface) is unfolded: the face-level area
/// refinement, the inverse stereographic projection, the distortions and the [`CapMap`] in
/// the input's numbering. `report` holds what the earlier stages measured; the rest is
/// filled here.
#[allow(clippy::too_many_arguments)]
pub(crate) fn conclude(
    mesh: &TriMesh,
    prepared: &Prepared,
    faces: &[[u32; 3]],
    on_boundary: &[bool],
    mut plane: Vec<[f64; 2]>,
    options: &ParamOptions,
    progress: &dyn Progress,
    mut report: ParamReport,
) -> Result<CapMap, Error> {
    let Prepared { start, welded, .. } = prepared;
    let work = &welded.mesh;
    let faces = faces.to_vec();
    let lift_one = |q: [f64; 2]| cap_point(options.domain, q);
    progress::check(progress, Stage::Project, 0.0, "area refinement")?;
    let t_refine = Instant::now();
    report.area_refinement = refine_areas(&mut plane, &work.vertices, &faces, on_boundary, &lift_one, RefineOptions::default().with_sweeps(options.refinement.area_refinement));
    report.refine_seconds = t_refine.elapsed().as_secs_f64();
    progress::check(progress, Stage::Project, 0.0, "inverse stereographic projection")?;
    let cap_work: Vec<[f64; 3]> = plane.iter().map(|&q| lift_one(q)).collect();
    report.flipped_faces = folded_faces(&plane, &faces).len();
    let d_area = area_distortion(&work.vertices, &cap_work, &faces);
    let d_angle = angle_distortion(&work.vertices, &cap_work, &faces);
    report.area_distortion = Stats::of(d_area.iter().copied());
    report.quality = MapQuality::of(options.domain, report.area_distortion.mean_abs);
    report.angle_distortion = Stats::of(d_angle.iter().copied());
    report.conformal_energy = conformal_energy(&work.vertices, &plane, &faces);
    report.seconds = start.elapsed().as_secs_f64();
    // Back to the input's vertex numbering; vertices no face uses go to the origin.
    let plane_all = welded.old_to_new.iter().map(|&v| plane.get(v as usize).copied().unwrap_or([0.0; 2])).collect();
    let cap_all = welded.old_to_new.iter().map(|&v| cap_work.get(v as usize).copied().unwrap_or([0.0; 3])).collect();
    let bottom_faces = match &report.puncture {
        Some(p) => {
            let quad: Vec<[u32; 3]> = p.faces.iter().map(|&f| sorted_face(work.faces[f])).collect();
            (0..mesh.n_faces()).filter(|&f| quad.contains(&sorted_face(mesh.faces[f].map(|v| welded.old_to_new.get(v as usize).copied().unwrap_or(repair::REMOVED))))).collect()
        }
        None => Vec::new(),
    };
    let input_faces = measured_input_faces(mesh, &welded.old_to_new, report.puncture.as_ref().map(|p| p.faces));
    let (face_area_distortion, corner_angle_distortion) = per_input_face(mesh.n_faces(), &input_faces, &d_area, &d_angle);
    Ok(CapMap { plane: plane_all, cap: cap_all, bottom_faces, face_area_distortion, corner_angle_distortion, kind: report.kind, report })
}

/// The domain point of a planar point: the inverse stereographic projection, or `(x, y, 0)`
/// for the planar disk.
pub(crate) fn cap_point(domain: Domain, q: [f64; 2]) -> [f64; 3] {
    if domain == Domain::Disk {
        [q[0], q[1], 0.0]
    } else {
        inverse_stereographic(q)
    }
}

/// The planar point of a point near the domain: the stereographic projection of its
/// direction, or `(x, y)` for the planar disk ([`cap_point`]'s inverse).
pub(crate) fn plane_point(domain: Domain, q: [f64; 3]) -> [f64; 2] {
    if domain == Domain::Disk {
        [q[0], q[1]]
    } else {
        let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        if l > 0.0 { stereographic([q[0] / l, q[1] / l, q[2] / l]) } else { [0.0; 2] }
    }
}

/// The input face of each measured face, in order: welding keeps the input's face order and
/// drops the faces it makes degenerate ([`repair::weld_coincident`]); a closed surface's
/// flattening then drops the two faces of the punctured quad (`punctured`, indices in the
/// welded mesh) and keeps the order of the others.
fn measured_input_faces(mesh: &TriMesh, old_to_new: &[u32], punctured: Option<[usize; 2]>) -> Vec<usize> {
    repair::kept_faces(mesh, old_to_new)
        .enumerate()
        .filter(|(welded_face, _)| !punctured.is_some_and(|p| p.contains(welded_face)))
        .map(|(_, f)| f)
        .collect()
}

/// The measured faces' `d_area` and corners' `d_angle` put at their input faces (`NaN`
/// elsewhere). When the faces do not line up (they always do; a guard against a change of
/// the welding or the puncture) every value is `NaN` rather than a wrong one.
fn per_input_face(n_faces: usize, input_faces: &[usize], d_area: &[f64], d_angle: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut area = vec![f64::NAN; n_faces];
    let mut angle = vec![f64::NAN; 3 * n_faces];
    if input_faces.len() == d_area.len() && 3 * d_area.len() == d_angle.len() {
        for (k, &f) in input_faces.iter().enumerate() {
            area[f] = d_area[k];
            angle[3 * f..3 * f + 3].copy_from_slice(&d_angle[3 * k..3 * k + 3]);
        }
    }
    (area, angle)
}
