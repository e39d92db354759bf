//! The first half of a parameterization: the initial disk map of the prepared mesh and the
//! search for the radius `r*` (Brent's method, on a coarse level of sites for large meshes).

use super::options::{OpenInitialMap, ParamOptions};
use super::prepare::Prepared;
use super::report::{FlattenReport, RadiusSample};
use crate::cap::brent;
use crate::cap::domain::{Domain, MAX_RADIUS, MIN_RADIUS};
use crate::cap::stereographic::{inverse_stereographic, radius_of_z_star, z_star_of_radius};
use crate::error::Error;
use crate::flatten::closed::{composite_disk_map, flatten_closed};
use crate::flatten::puncture::Puncture;
use crate::flatten::disk_conformal_map;
use crate::mesh::geometry::vertex_areas;
use crate::mesh::SurfaceKind;
use crate::metrics::{area_distortion, conformal_energy, conformal_energy_surface_weighted, Stats};
use crate::omt::coarse_level::CoarseLevel;
use crate::omt::planar_transport::{PlanarTransport, TransportMap};
use crate::omt::{RadialDensity, StereographicDensity, UniformDensity};
use crate::progress::{self, Progress, Stage};
use std::time::Instant;

/// Largest ratio of vertices to coarse sites in the radius search. The coarse energy follows
/// the full one only while the coarse level resolves the map: on the synthetic 164k-vertex
/// ellipsoid, 2565 sites (1 in 64) put the minimum at `Z* = -0.967` where the full curve
/// falls to the bound `-0.9945` (mean `|d_area|` 0.13 instead of 0.010), while 7683 sites
/// (1 in 21) follow it to the bound. The shared meshes search on 1 in 3 to 1 in 21.
pub const SEARCH_RATIO: usize = 16;

/// Smallest ratio of vertices to requested coarse sites in the radius search of a closed
/// surface: below `4 * search_sites` vertices it searches on a quarter of its vertices at
/// most (a covering by 2-hop balls, about 1 site in 8 to 10) instead of at full resolution
/// or on 1-hop balls (1 in 3 or 4). The closed surfaces' energy falls to the bound of `Z*`
/// (every shared closed mesh), which the coarse search finds as well, with the same `Z*` and
/// distortions within 0.2%. Open surfaces keep their searches: their minima are interior and
/// a coarse level this small moves them (the sampled caps of `tests/param_cap_anchor.rs`
/// would miss their `Z*` by more than the 0.02 allowed).
pub const SMALL_SEARCH_RATIO: usize = 4;

/// Fewest coarse sites requested of a closed surface's coarse radius search: closed meshes
/// of fewer than `2 * MIN_SEARCH_SITES` vertices search at full resolution (milliseconds).
pub const MIN_SEARCH_SITES: usize = 250;

/// The most transport sites of the radius search's coarse level for a mesh of `n` vertices
/// (see [`super::SearchOptions::sites`]), or `None` when it searches at full resolution:
/// `max(search_sites, n / SEARCH_RATIO)` sites, for a closed surface
/// `max(min(search_sites, max(n / SMALL_SEARCH_RATIO, MIN_SEARCH_SITES)), n / SEARCH_RATIO)`,
/// when that is fewer than half the vertices; `None` for `search_sites = 0`.
pub fn search_level_sites(n: usize, search_sites: usize, closed: bool) -> Option<usize> {
    if search_sites == 0 {
        return None;
    }
    let cap = if closed { (n / SMALL_SEARCH_RATIO).max(MIN_SEARCH_SITES) } else { usize::MAX };
    let sites = search_sites.min(cap).max(n / SEARCH_RATIO);
    (2 * sites < n).then_some(sites)
}

/// A parameterization up to its radius (the first half of
/// [`super::finish::parameterize_once`]): the prepared mesh, its initial disk map and the
/// radius search.
pub(crate) struct Searched<'p> {
    pub(super) prepared: &'p Prepared,
    pub(super) faces: Vec<[u32; 3]>,
    pub(super) disk: Vec<[f64; 2]>,
    pub(super) on_boundary: Vec<bool>,
    pub(super) target: Vec<f64>,
    pub(super) flatten_report: FlattenReport,
    pub(super) puncture: Option<Puncture>,
    pub(super) radius: f64,
    /// The transport map at `radius` when the search solved it at full resolution.
    pub(super) map: Option<TransportMap>,
    /// Mean `|d_area|` of the search's map at `r*` on the cap (the coarse level's map
    /// prolonged to every vertex when the search ran there); `None` without a search or when
    /// not asked for.
    pub(super) search_area_distortion: Option<f64>,
    pub(super) curve: Vec<RadiusSample>,
    pub(super) search_sites: Option<usize>,
    pub(super) search_refinements: usize,
    /// The radius of the first search when a finer level moved it: `finish` maps there if
    /// the full transport fails at `radius`.
    pub(super) unrefined_radius: Option<f64>,
    pub(super) coarse_newton_iterations: usize,
    /// Full-resolution Newton iterations and solves so far, and symbolic factorizations at
    /// either level.
    pub(super) newton_iterations: usize,
    pub(super) solves: usize,
    pub(super) symbolic_factorizations: usize,
    pub(super) flatten_seconds: f64,
    pub(super) transport_seconds: f64,
}

/// The best radius of a search so far: its energy, and its full-resolution map when the
/// search runs at full resolution, else the coarse map prolonged to every vertex.
struct SearchBest {
    r: f64,
    energy: f64,
    map: Option<TransportMap>,
    prolonged: Vec<[f64; 2]>,
}

/// The source density of the transport: uniform on the planar disk, stereographic on the
/// cap's disks.
pub(super) fn transport_density(domain: Domain) -> &'static dyn RadialDensity {
    if domain == Domain::Disk {
        &UniformDensity
    } else {
        &StereographicDensity
    }
}

/// Flatten the prepared mesh and find the radius (the search of the adaptive domain).
/// With `rank_ends`, also measure the search map at `r*`
/// ([`Searched::search_area_distortion`], which [`super::PunctureEnd::Best`] compares).
pub(crate) fn search_radius<'p>(prepared: &'p Prepared, options: &ParamOptions, rank_ends: bool, progress: &dyn Progress) -> Result<Searched<'p>, Error> {
    let (work, kind, topology) = (&prepared.welded.mesh, prepared.kind, &prepared.topology);
    progress::check(progress, Stage::Flatten, 0.0, "initial flattening")?;
    let t_flat = Instant::now();
    let (faces, boundary, disk, flatten_report, puncture) = match kind {
        SurfaceKind::OpenDisk => {
            let boundary = topology.boundary_loops[0].clone();
            if options.open.initial == OpenInitialMap::Composite {
                let stretch = options.closed.flatten.stretch.clone().with_factored_iterations(options.open.factored_iterations).with_refactor_period(0);
                let composite = options.closed.flatten.clone().with_lambda(options.open.lambda).with_stretch(stretch);
                let (disk, rep) = composite_disk_map(&work.vertices, &work.faces, &boundary, &composite)?;
                (work.faces.clone(), boundary, disk, FlattenReport::Closed(rep), None)
            } else {
                let (disk, rep) = disk_conformal_map(&work.vertices, &work.faces, &boundary, &options.open.conformal)?;
                (work.faces.clone(), boundary, disk, FlattenReport::Open(rep), None)
            }
        }
        SurfaceKind::ClosedSphere => {
            let flat = flatten_closed(work, &options.closed.flatten)?;
            (flat.faces, flat.puncture.quad.to_vec(), flat.uv, FlattenReport::Closed(flat.report), Some(flat.puncture))
        }
    };
    let flatten_seconds = t_flat.elapsed().as_secs_f64();
    let mut on_boundary = vec![false; work.n_vertices()];
    for &b in &boundary {
        on_boundary[b as usize] = true;
    }
    let target = match &options.vertex_masses {
        // Welding keeps or merges input vertices: each welded vertex gets its inputs' masses.
        Some(masses) => {
            let mut t = vec![0.0; work.n_vertices()];
            for (&m, &v) in masses.iter().zip(&prepared.welded.old_to_new) {
                if let Some(x) = t.get_mut(v as usize) {
                    *x += m;
                }
            }
            t
        }
        None => vertex_areas(&work.vertices, &faces),
    };
    let density = transport_density(options.domain);
    let mut transport = PlanarTransport::new(&disk, &on_boundary, &target, density, options.transport.clone());
    let t_ot = Instant::now();
    let mut curve = Vec::new();
    let (mut search_sites, mut coarse_newton_iterations, mut coarse_symbolic, mut search_refinements) = (None, 0, 0, 0);
    let mut unrefined_radius = None;
    let mut search_area_distortion = None;
    let (radius, transported) = match options.domain {
        Domain::Disk => (1.0, None),
        Domain::Adaptive => {
            let mut coarse = search_level_sites(disk.len(), options.search.sites, kind == SurfaceKind::ClosedSphere).and_then(|sites| CoarseLevel::build(&disk, &faces, &on_boundary, &target, sites));
            let max_evals = options.search.max_evaluations;
            let search_tolerance = options.search.tolerance;
            // Closed surfaces search over w = atanh(Z*) (= -ln r): their optimum is at the
            // lower bound (the cap becomes the whole sphere but for the punctured quad), and
            // golden steps towards it shrink the distance geometrically in r rather than in
            // Z*: 10 solves instead of 17 on the shared meshes, with the tolerance kept on Z*
            // (dZ*/dw = 1 - Z*^2); started at the bound, 2. Open surfaces search over Z*
            // itself, as the paper's fminbnd: their objective can have several local minima
            // (hippocampal sheet: 0.2965 at Z* = 0.126, 0.3191 at 0.725), and the other
            // variable's first evaluations land in the worse basin there.
            // So do open surfaces whose boundary is short against their size (a closed
            // surface with a hole, `validate::small_boundary`): their cap is nearly the
            // sphere, and over Z* the flat objective led the search to a tiny cap (the bunny
            // with a 6-edge hole: Z* 0.9945, mean |d_area| 7.9; from the bound -0.9947, 0.05).
            let nearly_closed = kind == SurfaceKind::OpenDisk && crate::mesh::validate::small_boundary_of(work, topology).is_some();
            let in_atanh = kind == SurfaceKind::ClosedSphere || nearly_closed;
            let to_z = |w: f64| if in_atanh { w.tanh() } else { w };
            let (z_lo, z_hi) = (z_star_of_radius(MAX_RADIUS), z_star_of_radius(MIN_RADIUS));
            let z_tolerance = options.search.z_tolerance;
            // The coarser level's result while a finer one searches (see below).
            let mut coarser: Option<(SearchBest, Vec<RadiusSample>, Option<usize>)> = None;
            let mut first_radius = None;
            let best = loop {
                curve.clear();
                let mut coarse_transport = coarse.as_ref().map(|c| PlanarTransport::new(&c.sites, &c.on_boundary, &c.masses, density, options.transport.clone()));
                search_sites = coarse.as_ref().map(CoarseLevel::len);
                let mut best: Option<SearchBest> = None;
                let mut evals = 0usize;
                let mut objective = |w: f64| -> Result<f64, Error> {
                    let z = to_z(w);
                    let r = radius_of_z_star(z);
                    evals += 1;
                    progress::check(progress, Stage::RadiusSearch, evals as f64 / max_evals as f64, &format!("r = {r:.4}, Z* = {z:.4}"))?;
                    let (prolonged, iterations, map) = match (coarse.as_ref(), coarse_transport.as_mut()) {
                        (Some(level), Some(ct)) => {
                            let map = ct.map_at_tolerance(r, search_tolerance, progress)?;
                            (level.prolong(&map.centroids), map.report.iterations, None)
                        }
                        _ => {
                            let map = transport.map_at_tolerance(r, search_tolerance, progress)?;
                            (Vec::new(), map.report.iterations, Some(map))
                        }
                    };
                    let centroids: &[[f64; 2]] = map.as_ref().map_or(&prolonged, |m| &m.centroids);
                    let e = if kind == SurfaceKind::OpenDisk {
                        conformal_energy(&work.vertices, centroids, &faces)
                    } else {
                        conformal_energy_surface_weighted(&work.vertices, centroids, &faces)
                    };
                    curve.push(RadiusSample { r, z_star: z, energy: e, newton_iterations: iterations });
                    if best.as_ref().map_or(true, |b| e < b.energy) {
                        best = Some(SearchBest { r, energy: e, map, prolonged });
                    }
                    Ok(e)
                };
                let searched = if in_atanh {
                    // Their energy falls all the way to the bound on every shared closed mesh:
                    // the search starts there and ends after two solves when the energy rises
                    // inwards (`brent::minimize_from_lower_bound`).
                    brent::minimize_from_lower_bound(&mut objective, z_lo.atanh(), z_hi.atanh(), |w: f64| z_tolerance * w.cosh().powi(2), max_evals).map(|_| ())
                } else {
                    brent::minimize(&mut objective, z_lo, z_hi, z_tolerance, max_evals).map(|_| ())
                };
                coarse_newton_iterations += coarse_transport.as_ref().map_or(0, |t| t.newton_iterations);
                coarse_symbolic += coarse_transport.as_ref().map_or(0, |t| t.symbolic_factorizations);
                match (searched, coarser.take()) {
                    // A finer level whose transport fails (a very elongated surface, whose
                    // optimum is inside the bound, stalls there): the coarser level's result.
                    (Err(Error::Transport(_)), Some((kept, kept_curve, kept_sites))) => {
                        (curve, search_sites) = (kept_curve, kept_sites);
                        break kept;
                    }
                    (Err(e), _) => return Err(e),
                    (Ok(()), _) => {}
                }
                let best = best.ok_or_else(|| Error::Internal("radius search made no evaluation".into()))?;
                // A closed surface's energy falls to the bound of `Z*` wherever the search level
                // resolves the map (SEARCH_RATIO): a coarse search that ends inside it is checked
                // on the next finer level (the full problem after the finest).
                match &coarse {
                    Some(level) if in_atanh && z_star_of_radius(best.r) - z_lo > z_tolerance => {
                        coarse = level.finer(&disk, &faces, &on_boundary, &target);
                        search_refinements += 1;
                        first_radius.get_or_insert(best.r);
                        coarser = Some((best, std::mem::take(&mut curve), search_sites));
                    }
                    _ => break best,
                }
            };
            let SearchBest { r, map, prolonged, .. } = best;
            unrefined_radius = first_radius.filter(|&r0| r0 != r);
            if rank_ends {
                let on_cap: Vec<[f64; 3]> = map.as_ref().map_or(&prolonged, |m| &m.centroids).iter().map(|&q| inverse_stereographic(q)).collect();
                search_area_distortion = Some(Stats::of(area_distortion(&work.vertices, &on_cap, &faces)).mean_abs);
            }
            match map {
                Some(map) if search_tolerance <= options.transport.tolerance => (r, Some(map)),
                Some(_) => (r, Some(transport.map_at(r, progress)?)),
                // A coarse search: the full problem is solved by `finish`.
                None => (r, None),
            }
        }
        fixed => (fixed.fixed_radius().unwrap_or(1.0), None),
    };
    let transport_seconds = t_ot.elapsed().as_secs_f64();
    let (newton_iterations, solves, symbolic) = (transport.newton_iterations, transport.solves, transport.symbolic_factorizations);
    drop(transport);
    Ok(Searched {
        prepared,
        faces,
        disk,
        on_boundary,
        target,
        flatten_report,
        puncture,
        radius,
        map: transported,
        search_area_distortion,
        curve,
        search_sites,
        search_refinements,
        unrefined_radius,
        coarse_newton_iterations,
        newton_iterations,
        solves,
        symbolic_factorizations: symbolic + coarse_symbolic,
        flatten_seconds,
        transport_seconds,
    })
}
