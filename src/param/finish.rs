//! The second half of a parameterization: the transport map at `r*`, its regularisation and
//! fold repair, the area refinement, and the report.

use super::options::ParamOptions;
use super::prepare::Prepared;
use super::report::{MapQuality, ParamReport};
use super::search::{search_radius, transport_density, Searched};
use crate::cap::domain::Domain;
use crate::cap::stereographic::{inverse_stereographic, z_star_of_radius};
use crate::cap::CapMap;
use crate::error::Error;
use crate::linalg::cotangent_weights;
use crate::mesh::geometry::{folded_faces, lift};
use crate::mesh::topology::within_rings;
use crate::mesh::{repair, SurfaceKind, TriMesh};
use crate::metrics::{angle_distortion, area_distortion, conformal_energy, Stats};
use crate::omt::planar_transport::PlanarTransport;
use crate::omt::OmtError;
use crate::progress::{self, Progress, Stage};
use crate::refine::area_refine::{refine_areas, RefineOptions};
use crate::refine::regularize::{regularise, PUNCTURE_HELD_RINGS};
use std::time::Instant;

/// [`super::parameterize`] of the prepared `mesh` with the puncture end fixed by
/// `options.closed.puncture`: the radius search, then [`finish`].
pub(crate) fn parameterize_once(mesh: &TriMesh, prepared: &Prepared, options: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let searched = search_radius(prepared, options, false, progress)?;
    finish(mesh, searched, options, progress)
}

/// The second half of [`parameterize_once`]: the transport map at the searched radius (unless
/// the search solved it), its regularisation and fold repair, the area refinement and the
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
        radius,
        map,
        search_area_distortion: _,
        curve,
        search_sites,
        coarse_newton_iterations,
        mut newton_iterations,
        mut solves,
        symbolic_factorizations: mut symbolic,
        flatten_seconds,
        transport_seconds: search_seconds,
    } = s;
    let Prepared { start, welded, kind, .. } = prepared;
    let (start, kind, work) = (*start, *kind, &welded.mesh);
    let t_ot = Instant::now();
    let transported = match map {
        Some(map) => map,
        None => {
            let mut transport = PlanarTransport::new(&disk, &on_boundary, &target, transport_density(options.domain), options.transport.clone());
            let map = transport.map_at(radius, progress)?;
            newton_iterations += transport.newton_iterations;
            solves += transport.solves;
            symbolic += transport.symbolic_factorizations;
            map
        }
    };
    let transport_seconds = search_seconds + t_ot.elapsed().as_secs_f64();
    let to_cap = |p: &[[f64; 2]]| -> Vec<[f64; 3]> {
        if options.domain == Domain::Disk {
            lift(p)
        } else {
            p.iter().map(|&q| inverse_stereographic(q)).collect()
        }
    };
    let t_reg = Instant::now();
    let cot = cotangent_weights(&work.vertices, &faces);
    let held = if kind == SurfaceKind::ClosedSphere { within_rings(&on_boundary, &faces, PUNCTURE_HELD_RINGS) } else { on_boundary.clone() };
    let chosen = regularise(&transported, &work.vertices, &faces, &cot, &on_boundary, &held, radius, options.smoothing, &to_cap).map_err(OmtError::Linear)?;
    let (kappa, mut plane, untangle_report, trials) = (chosen.kappa, chosen.positions, chosen.untangle, chosen.trials);
    let lift_one = |q: [f64; 2]| if options.domain == Domain::Disk { [q[0], q[1], 0.0] } else { inverse_stereographic(q) };
    let regularise_seconds = t_reg.elapsed().as_secs_f64();
    progress::check(progress, Stage::Project, 0.0, "area refinement")?;
    let t_refine = Instant::now();
    let refinement = refine_areas(&mut plane, &work.vertices, &faces, &on_boundary, &lift_one, RefineOptions { sweeps: options.area_refinement, ..Default::default() });
    let refine_seconds = t_refine.elapsed().as_secs_f64();
    progress::check(progress, Stage::Project, 0.0, "inverse stereographic projection")?;
    let cap_work = to_cap(&plane);
    let flipped_faces = folded_faces(&plane, &faces).len();
    let spherical = options.domain != Domain::Disk;
    let area_stats = Stats::of(area_distortion(&work.vertices, &cap_work, &faces));
    let report = ParamReport {
        domain: options.domain,
        kind,
        n_vertices: mesh.n_vertices(),
        n_faces: mesh.n_faces(),
        welded_vertices: welded.merged_vertices,
        r_star: spherical.then_some(radius),
        z_star: spherical.then(|| z_star_of_radius(radius)),
        quality: MapQuality::of(options.domain, area_stats.mean_abs),
        area_distortion: area_stats,
        angle_distortion: Stats::of(angle_distortion(&work.vertices, &cap_work, &faces)),
        conformal_energy: conformal_energy(&work.vertices, &plane, &faces),
        flipped_faces,
        untangle: untangle_report,
        area_refinement: refinement,
        smoothing_kappa: kappa,
        smoothing_trials: trials,
        newton_iterations,
        search_sites,
        coarse_newton_iterations,
        transport_solves: solves,
        transport_symbolic_factorizations: symbolic,
        radius_curve: curve,
        flatten: flatten_report,
        puncture,
        puncture_trials: Vec::new(),
        lambda_fallbacks: Vec::new(),
        seconds: start.elapsed().as_secs_f64(),
        flatten_seconds,
        transport_seconds,
        regularise_seconds,
        refine_seconds,
    };
    // Back to the input's vertex numbering; vertices no face uses go to the origin.
    let plane_all = welded.old_to_new.iter().map(|&v| plane.get(v as usize).copied().unwrap_or([0.0; 2])).collect();
    let cap_all = welded.old_to_new.iter().map(|&v| cap_work.get(v as usize).copied().unwrap_or([0.0; 3])).collect();
    let bottom_faces = match &report.puncture {
        Some(p) => {
            let key = |f: [u32; 3]| {
                let mut k = f;
                k.sort_unstable();
                k
            };
            let quad: Vec<[u32; 3]> = p.faces.iter().map(|&f| key(work.faces[f])).collect();
            (0..mesh.n_faces()).filter(|&f| quad.contains(&key(mesh.faces[f].map(|v| welded.old_to_new.get(v as usize).copied().unwrap_or(repair::REMOVED))))).collect()
        }
        None => Vec::new(),
    };
    Ok(CapMap { plane: plane_all, cap: cap_all, bottom_faces, kind: report.kind, report })
}
