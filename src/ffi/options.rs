//! Option structs of the C ABI, their defaults and their conversion to the library's options.

use super::status::Failure;
use crate::param::{PunctureEnd, DEFAULT_AREA_REFINEMENT, DEFAULT_COARSE_VERTICES, DEFAULT_MULTILEVEL_ABOVE};
use crate::cap::Domain;
use crate::param::ParamOptions;
use crate::refine::Smoothing;
use crate::flatten::closed::DEFAULT_LAMBDA;
use crate::remesh::shape::{Creases, ShapeOptions};
use crate::remesh::sizing::{Sizing, DEFAULT_CURVATURE_STRENGTH};
use crate::remesh::{CapGrid, Holes, Optimize, Placement, RemeshOptions, DEFAULT_AREA_EQUALIZATION};

/// `capmesh_v1_param_options.domain`: the adaptive cap of the paper (default).
pub const CAPMESH_V1_DOMAIN_ADAPTIVE: i32 = 0;
/// `capmesh_v1_param_options.domain`: the planar unit disk.
pub const CAPMESH_V1_DOMAIN_DISK: i32 = 1;
/// `capmesh_v1_param_options.domain`: the hemisphere `Z >= 0`.
pub const CAPMESH_V1_DOMAIN_HEMISPHERE: i32 = 2;
/// `capmesh_v1_param_options.domain`: nearly the whole sphere (`Z* = -0.995`).
pub const CAPMESH_V1_DOMAIN_SPHERE: i32 = 3;
/// `capmesh_v1_param_options.domain`: a fixed disk radius, `radius` (cap `Z >= (1-r^2)/(1+r^2)`).
pub const CAPMESH_V1_DOMAIN_RADIUS: i32 = 4;

/// `capmesh_v1_param_options.puncture_end`: closed surfaces are mapped with the puncture at
/// each end of the principal axis and the better map is kept (default).
pub const CAPMESH_V1_PUNCTURE_BEST: i32 = 0;
/// `capmesh_v1_param_options.puncture_end`: the end with the lower input Z.
pub const CAPMESH_V1_PUNCTURE_BOTTOM: i32 = 1;
/// `capmesh_v1_param_options.puncture_end`: the other end.
pub const CAPMESH_V1_PUNCTURE_TOP: i32 = 2;

/// `capmesh_v1_remesh_options.grid`: near-equilateral faces, about `faces` of them (default).
pub const CAPMESH_V1_GRID_UNIFORM: i32 = 0;
/// `capmesh_v1_remesh_options.grid`: `rings` latitude rings times `sectors` meridians.
pub const CAPMESH_V1_GRID_LAT_LONG: i32 = 1;

/// `capmesh_v1_remesh_options.optimize`: the shape stage (edge flips, tangential relaxation
/// and a joint area and shape polish on the surface), then the area equalization: isotropic
/// triangles of near-equal area (default). The lat-long grid keeps its grid lines and gets the
/// area equalization only.
pub const CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA: i32 = 0;
/// `capmesh_v1_remesh_options.optimize`: the area equalization alone (the cap grid's
/// connectivity, near-equal areas; `area_equalization` sweeps).
pub const CAPMESH_V1_OPTIMIZE_AREA: i32 = 1;
/// `capmesh_v1_remesh_options.optimize`: the paper's plain pull-back of the cap grid.
pub const CAPMESH_V1_OPTIMIZE_NONE: i32 = 2;

/// `capmesh_v1_remesh_options.placement`: the vertices moved along their normals so that the
/// faces fit the input in the least-squares sense (default; the CLI's `--placement fitted`).
pub const CAPMESH_V1_PLACEMENT_FITTED: i32 = 0;
/// `capmesh_v1_remesh_options.placement`: the vertices on the input surface, where the inverse
/// map puts them (the CLI's `--placement on-surface`).
pub const CAPMESH_V1_PLACEMENT_ON_SURFACE: i32 = 1;

/// `capmesh_v1_remesh_options.creases`: vertices on the input's creases with curvature
/// sizing only (default; the CLI's `--creases auto`).
pub const CAPMESH_V1_CREASES_AUTO: i32 = 0;
/// `capmesh_v1_remesh_options.creases`: vertices on the input's creases, joined by edges (the
/// CLI's `--creases keep`).
pub const CAPMESH_V1_CREASES_KEEP: i32 = 1;
/// `capmesh_v1_remesh_options.creases`: creases not kept (the CLI's `--creases off`).
pub const CAPMESH_V1_CREASES_OFF: i32 = 2;

/// `capmesh_v1_remesh_options.sizing`: equal face areas (default; the CLI's `--sizing
/// uniform`).
pub const CAPMESH_V1_SIZING_UNIFORM: i32 = 0;
/// `capmesh_v1_remesh_options.sizing`: equal surface areas covered through the map, a uniform
/// vertex density on the surface (`--sizing surface`).
pub const CAPMESH_V1_SIZING_SURFACE: i32 = 1;
/// `capmesh_v1_remesh_options.sizing`: smaller faces where the surface is curved, of strength
/// `sizing_strength` (`--sizing curvature=S`).
pub const CAPMESH_V1_SIZING_CURVATURE: i32 = 2;

/// Parameterization options. Start from `capmesh_v1_param_options_default()`.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct capmesh_v1_param_options {
    /// One of `CAPMESH_V1_DOMAIN_*`. Default adaptive (0).
    pub domain: i32,
    /// Disk radius for `CAPMESH_V1_DOMAIN_RADIUS`, in [0.05, 20] (the adaptive search's range,
    /// cap `Z*` from 0.995 down to -0.995); ignored otherwise. Default 1.
    pub radius: f64,
    /// Quasi-conformal factor of closed surfaces, in [0, 1]. Default 0.2.
    pub lambda: f64,
    /// Centroid-map smoothing strength kappa; negative = automatic choice (default),
    /// 0 = the paper's plain centroid map.
    pub smoothing: f64,
    /// Sweeps of the face-level area refinement after transport (over-relaxed Gauss-Seidel);
    /// 0 = the paper's map. Default 30.
    pub area_refinement: u32,
    /// One of `CAPMESH_V1_PUNCTURE_*` (closed surfaces). Default best (0).
    pub puncture_end: i32,
    /// Closed surfaces of more vertices than this are mapped through a decimated copy whose map
    /// is prolonged to every vertex (near-linear time and memory); 0 = never. Default 100000.
    pub multilevel_above: u32,
    /// Vertices of that decimated copy (at least; an eighth of the input's when more). Default
    /// 25000.
    pub coarse_vertices: u32,
}

/// Remeshing options. Start from `capmesh_v1_remesh_options_default()`.
#[allow(non_camel_case_types)]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct capmesh_v1_remesh_options {
    /// `CAPMESH_V1_GRID_UNIFORM` (default) or `CAPMESH_V1_GRID_LAT_LONG`.
    pub grid: i32,
    /// Target face count of the uniform grid, >= 1. Default 5000.
    pub faces: u32,
    /// Latitude rings of the lat-long grid, >= 1. Default 40.
    pub rings: u32,
    /// Meridians of the lat-long grid, >= 3. Default 64.
    pub sectors: u32,
    /// Parameterization options.
    pub param: capmesh_v1_param_options,
    /// Sweeps of the area equalization of the pulled-back mesh when the shape stage does not
    /// run (`CAPMESH_V1_OPTIMIZE_AREA`, or the lat-long grid); after the shape stage the polish
    /// equalizes the areas. 0 = the plain pull-back. Default 30.
    pub area_equalization: u32,
    /// One of `CAPMESH_V1_OPTIMIZE_*`: what is optimised after the pull-back. Default shape and
    /// area (0).
    pub optimize: i32,
    /// Relaxation iterations of the shape stage (edge flips and tangential relaxation on the
    /// surface). Default 40.
    pub relax_iterations: u32,
    /// Polish iterations of the shape stage (joint area and shape steps). Default 85.
    pub polish_iterations: u32,
    /// Weight of the shape term against the area term in the polish, finite and >= 0 (larger:
    /// better angles, less equal areas). Default 0.13.
    pub shape_weight: f64,
    /// 1 = split long and collapse short edges in the shape stage where the map is resolved
    /// at the remesh's scale (default; better angles); 0 = off (the grid's vertex count).
    pub resample: i32,
    /// One of `CAPMESH_V1_SIZING_*`: how the shape stage sizes the faces. Default uniform (0),
    /// equal areas (the paper's goal).
    pub sizing: i32,
    /// Strength of `CAPMESH_V1_SIZING_CURVATURE`, finite and > 0 (the CLI's
    /// `--sizing curvature=S`); ignored by the other sizings. Default 3.
    pub sizing_strength: f64,
    /// Global area steps of the polish (Gauss-Newton steps of the area term over all vertices
    /// at once, one every 5 polish iterations from the first; 0 = none). Default 6.
    pub area_steps: u32,
    /// One of `CAPMESH_V1_CREASES_*`: whether vertices are put on the input's creases and
    /// joined by edges. Default auto (0): with `CAPMESH_V1_SIZING_CURVATURE` only.
    pub creases: i32,
    /// The crease bound in degrees, in (0, 180): input edges bent more are creases, and no
    /// edge flip bends a pair of faces more (the CLI's `--crease-angle`). Default 60.
    pub crease_deg: f64,
    /// One of `CAPMESH_V1_PLACEMENT_*`: where the vertices are put at the end. Default fitted
    /// (0).
    pub placement: i32,
    /// 1 = fill each hole of an open surface with a fan of faces and remesh the closed
    /// surface (the CLI's `--fill-holes`; the remesh is closed); 0 = keep the holes (default).
    pub fill_holes: i32,
    /// 1 = map an input with fewer faces than the shape+area remesh through a
    /// midpoint-subdivided copy, and split its edges longer than three times the remesh's (default:
    /// the same surface, its map resolved at the remesh's scale); 0 = map it as it is (the
    /// CLI's `--no-subdivide`).
    pub subdivide_coarse: i32,
    /// 1 = with the shape stage (shape and area on the uniform grid), map a closed input of
    /// many more vertices than the remesh needs through a decimated copy of 1.2 times the
    /// remesh's faces in vertices (at least 6000), prolonged to every vertex (default:
    /// faster, the same remesh, a higher mean |d_area|); 0 = map it as
    /// `param.multilevel_above` and `param.coarse_vertices` say, as `capmesh_v1_parameterize`
    /// does (the CLI's `--fine-map`; always so without the shape stage).
    pub coarse_map: i32,
    /// The polish stops early, after its global area steps, once an iteration flips no edge
    /// and moves the vertices by less than this root mean square, in edge lengths; finite and
    /// >= 0 (0 = every polish iteration runs). Default 0.001.
    pub polish_tolerance: f64,
}

/// The defaults documented on each field.
#[no_mangle]
pub extern "C" fn capmesh_v1_param_options_default() -> capmesh_v1_param_options {
    capmesh_v1_param_options {
        domain: CAPMESH_V1_DOMAIN_ADAPTIVE,
        radius: 1.0,
        lambda: DEFAULT_LAMBDA,
        smoothing: -1.0,
        area_refinement: DEFAULT_AREA_REFINEMENT as u32,
        puncture_end: CAPMESH_V1_PUNCTURE_BEST,
        multilevel_above: DEFAULT_MULTILEVEL_ABOVE as u32,
        coarse_vertices: DEFAULT_COARSE_VERTICES as u32,
    }
}

/// The defaults documented on each field.
#[no_mangle]
pub extern "C" fn capmesh_v1_remesh_options_default() -> capmesh_v1_remesh_options {
    let shape = ShapeOptions::default();
    capmesh_v1_remesh_options {
        grid: CAPMESH_V1_GRID_UNIFORM,
        faces: 5000,
        rings: 40,
        sectors: 64,
        param: capmesh_v1_param_options_default(),
        area_equalization: DEFAULT_AREA_EQUALIZATION as u32,
        optimize: CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA,
        relax_iterations: shape.relax_iterations as u32,
        polish_iterations: shape.polish_iterations as u32,
        area_steps: shape.area_steps as u32,
        shape_weight: shape.shape_weight,
        resample: i32::from(shape.resample),
        sizing: match shape.sizing {
            Sizing::Uniform => CAPMESH_V1_SIZING_UNIFORM,
            Sizing::Surface => CAPMESH_V1_SIZING_SURFACE,
            Sizing::Curvature { .. } => CAPMESH_V1_SIZING_CURVATURE,
        },
        sizing_strength: match shape.sizing {
            Sizing::Curvature { strength } => strength,
            _ => DEFAULT_CURVATURE_STRENGTH,
        },
        creases: match shape.creases {
            Creases::Auto => CAPMESH_V1_CREASES_AUTO,
            Creases::Keep => CAPMESH_V1_CREASES_KEEP,
            Creases::Off => CAPMESH_V1_CREASES_OFF,
        },
        crease_deg: shape.crease_deg,
        placement: match crate::remesh::Placement::default() {
            Placement::Fitted => CAPMESH_V1_PLACEMENT_FITTED,
            Placement::OnSurface => CAPMESH_V1_PLACEMENT_ON_SURFACE,
        },
        fill_holes: i32::from(Holes::default() == Holes::Fill),
        subdivide_coarse: i32::from(RemeshOptions::default().subdivide_coarse),
        coarse_map: i32::from(RemeshOptions::default().coarse_map),
        polish_tolerance: shape.polish_tolerance,
    }
}

fn finite(name: &str, x: f64) -> Result<f64, Failure> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(Failure::invalid_argument(format!("{name} = {x} is not a finite number")))
    }
}

/// The library's [`ParamOptions`] for `o`, or why `o` is out of range.
pub(crate) fn param_options(o: &capmesh_v1_param_options) -> Result<ParamOptions, Failure> {
    let domain = match o.domain {
        CAPMESH_V1_DOMAIN_ADAPTIVE => Domain::Adaptive,
        CAPMESH_V1_DOMAIN_DISK => Domain::Disk,
        CAPMESH_V1_DOMAIN_HEMISPHERE => Domain::Hemisphere,
        CAPMESH_V1_DOMAIN_SPHERE => Domain::Sphere,
        CAPMESH_V1_DOMAIN_RADIUS => {
            let r = finite("radius", o.radius)?;
            Domain::Radius(r).check().map_err(Failure::invalid_argument)?;
            Domain::Radius(r)
        }
        d => {
            return Err(Failure::invalid_argument(format!(
                "domain = {d} is not one of 0 (adaptive), 1 (disk), 2 (hemisphere), 3 (sphere), 4 (fixed radius)"
            )))
        }
    };
    let lambda = finite("lambda", o.lambda)?;
    if !(0.0..=1.0).contains(&lambda) {
        return Err(Failure::invalid_argument(format!("lambda = {lambda} is outside [0, 1]")));
    }
    let smoothing = match finite("smoothing", o.smoothing)? {
        k if k < 0.0 => Smoothing::Auto,
        k => Smoothing::Fixed(k),
    };
    let puncture_end = match o.puncture_end {
        CAPMESH_V1_PUNCTURE_BEST => PunctureEnd::Best,
        CAPMESH_V1_PUNCTURE_BOTTOM => PunctureEnd::Bottom,
        CAPMESH_V1_PUNCTURE_TOP => PunctureEnd::Top,
        e => return Err(Failure::invalid_argument(format!("puncture_end = {e} is not 0 (best), 1 (bottom) or 2 (top)"))),
    };
    let mut options = ParamOptions::default().with_domain(domain);
    options.closed.flatten.lambda = lambda;
    options.closed.puncture_end = puncture_end;
    options.refinement.smoothing = smoothing;
    options.refinement.area_refinement = o.area_refinement as usize;
    options.closed.multilevel_above = o.multilevel_above as usize;
    options.closed.coarse_vertices = o.coarse_vertices as usize;
    Ok(options)
}

/// The library's [`RemeshOptions`] for `o`, or why `o` is out of range.
pub(crate) fn remesh_options(o: &capmesh_v1_remesh_options) -> Result<RemeshOptions, Failure> {
    let grid = match o.grid {
        CAPMESH_V1_GRID_UNIFORM => {
            if o.faces == 0 {
                return Err(Failure::invalid_argument("faces = 0: the uniform grid needs at least one face"));
            }
            CapGrid::Uniform { faces: o.faces as usize }
        }
        CAPMESH_V1_GRID_LAT_LONG => {
            if o.rings == 0 || o.sectors < 3 {
                return Err(Failure::invalid_argument(format!(
                    "rings = {}, sectors = {}: the lat-long grid needs rings >= 1 and sectors >= 3",
                    o.rings, o.sectors
                )));
            }
            CapGrid::LatLong { rings: o.rings as usize, sectors: o.sectors as usize }
        }
        g => return Err(Failure::invalid_argument(format!("grid = {g} is not 0 (uniform) or 1 (lat-long)"))),
    };
    let optimize = match o.optimize {
        CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA => Optimize::ShapeAndArea,
        CAPMESH_V1_OPTIMIZE_AREA => Optimize::Area,
        CAPMESH_V1_OPTIMIZE_NONE => Optimize::None,
        v => return Err(Failure::invalid_argument(format!("optimize = {v} is not 0 (shape+area), 1 (area) or 2 (none)"))),
    };
    let shape_weight = finite("shape_weight", o.shape_weight)?;
    if shape_weight < 0.0 {
        return Err(Failure::invalid_argument(format!("shape_weight = {shape_weight} is negative")));
    }
    let resample = match o.resample {
        0 => false,
        1 => true,
        r => return Err(Failure::invalid_argument(format!("resample = {r} is not 0 (off) or 1 (on)"))),
    };
    let creases = match o.creases {
        CAPMESH_V1_CREASES_AUTO => Creases::Auto,
        CAPMESH_V1_CREASES_KEEP => Creases::Keep,
        CAPMESH_V1_CREASES_OFF => Creases::Off,
        c => return Err(Failure::invalid_argument(format!("creases = {c} is not 0 (auto), 1 (keep) or 2 (off)"))),
    };
    let crease_deg = ShapeOptions::checked_crease_deg(o.crease_deg).map_err(|e| Failure::invalid_argument(format!("crease_deg = {e}")))?;
    let polish_tolerance = finite("polish_tolerance", o.polish_tolerance)?;
    if polish_tolerance < 0.0 {
        return Err(Failure::invalid_argument(format!("polish_tolerance = {polish_tolerance} is negative (0: every polish iteration runs)")));
    }
    let placement = match o.placement {
        CAPMESH_V1_PLACEMENT_FITTED => Placement::Fitted,
        CAPMESH_V1_PLACEMENT_ON_SURFACE => Placement::OnSurface,
        p => return Err(Failure::invalid_argument(format!("placement = {p} is not 0 (fitted) or 1 (on-surface)"))),
    };
    let holes = match o.fill_holes {
        0 => Holes::Keep,
        1 => Holes::Fill,
        h => return Err(Failure::invalid_argument(format!("fill_holes = {h} is not 0 (keep the holes) or 1 (fill them)"))),
    };
    let subdivide_coarse = match o.subdivide_coarse {
        0 => false,
        1 => true,
        v => return Err(Failure::invalid_argument(format!("subdivide_coarse = {v} is not 0 (map the input as it is) or 1 (subdivide a coarse input for its map)"))),
    };
    let coarse_map = match o.coarse_map {
        0 => false,
        1 => true,
        v => return Err(Failure::invalid_argument(format!("coarse_map = {v} is not 0 (map at the detail of param's options) or 1 (map a fine closed input through a copy sized to the remesh)"))),
    };
    let sizing = match o.sizing {
        CAPMESH_V1_SIZING_UNIFORM => Sizing::Uniform,
        CAPMESH_V1_SIZING_SURFACE => Sizing::Surface,
        CAPMESH_V1_SIZING_CURVATURE => match finite("sizing_strength", o.sizing_strength)? {
            s if s > 0.0 => Sizing::Curvature { strength: s },
            s => return Err(Failure::invalid_argument(format!("sizing_strength = {s} is not > 0: the curvature sizing needs a positive strength (3 by default)"))),
        },
        v => return Err(Failure::invalid_argument(format!("sizing = {v} is not 0 (uniform), 1 (surface) or 2 (curvature)"))),
    };
    let shape = ShapeOptions::default()
        .with_sizing(sizing)
        .with_relax_iterations(o.relax_iterations as usize)
        .with_polish_iterations(o.polish_iterations as usize)
        .with_area_steps(o.area_steps as usize)
        .with_shape_weight(shape_weight)
        .with_resample(resample)
        .with_polish_tolerance(polish_tolerance)
        .with_creases(creases)
        .with_crease_deg(crease_deg);
    Ok(RemeshOptions {
        grid,
        param: param_options(&o.param)?,
        area_equalization: o.area_equalization as usize,
        optimize,
        shape,
        // The C ABI keeps the default: specks dropped, larger pieces refused.
        pieces: crate::remesh::Pieces::default(),
        placement,
        holes,
        subdivide_coarse,
        coarse_map,
    })
}
