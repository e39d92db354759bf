//! `capmesh remesh`: remesh one mesh through its adaptive cap (a uniform cap mesh or a
//! latitude/longitude grid pulled back by the inverse map, then the shape and area stages),
//! carry per-vertex attributes to it, and write the remesh, a JSON report and figures.

use crate::failure::{self, Failure};
use crate::{attributes_arg, cli_progress, figures_arg, map_args, outputs};
use crate::{print_quality, read, refuse_overwrite, refuse_poor, warn_if_poor};
use capmesh::io;
use capmesh::remesh::{CapGrid, RemeshOptions};
use std::path::PathBuf;

/// Arguments of `capmesh remesh` (the command line's options; `quiet` is the global flag).
#[derive(clap::Args, Debug)]
pub struct RemeshArgs {
    /// Input mesh.
    pub input: PathBuf,
    /// Output mesh.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Carry a per-vertex data file (GIFTI .shape/.func/.label.gii, FreeSurfer curv), or a
    /// vertex property of a PLY input by name (quality, red, ...), to the remesh
    /// (repeatable): PLY vertex properties, or .gii files beside a GIFTI output.
    #[arg(long, value_name = "PATH|NAME")]
    pub attribute: Vec<PathBuf>,
    /// Target face count of the uniform cap mesh.
    #[arg(long, default_value_t = 5000, conflicts_with = "lat_long")]
    pub faces: usize,
    /// Use a latitude/longitude mesh instead.
    #[arg(long)]
    pub lat_long: bool,
    /// Latitude rings (with --lat-long).
    #[arg(long, default_value_t = 40, requires = "lat_long")]
    pub rings: usize,
    /// Longitude sectors (with --lat-long).
    #[arg(long, default_value_t = 64, requires = "lat_long")]
    pub sectors: usize,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Sweeps of the area equalization of the pulled-back mesh with --optimize area (0: the
    /// paper's plain pull-back). With shape+area the shape stage's polish equalizes the
    /// areas itself and no sweeps run after it.
    #[arg(long, default_value_t = capmesh::remesh::DEFAULT_AREA_EQUALIZATION)]
    pub area_equalization: usize,
    /// What is optimised after the pull-back: shape+area (isotropic triangles of
    /// near-equal area, the default), area (the cap grid's connectivity, areas equalized)
    /// or none (the paper's plain pull-back). The --lat-long grid keeps its grid lines:
    /// area only.
    #[arg(long, default_value = "shape+area")]
    pub optimize: capmesh::remesh::Optimize,
    /// Relaxation iterations of the shape stage (edge flips and tangential relaxation on
    /// the surface).
    #[arg(long, default_value_t = capmesh::remesh::shape::ShapeOptions::default().relax_iterations)]
    pub relax_iterations: usize,
    /// Polish iterations of the shape stage (joint area and shape steps).
    #[arg(long, default_value_t = capmesh::remesh::shape::ShapeOptions::default().polish_iterations)]
    pub polish_iterations: usize,
    /// The polish stops early, after its global area steps, once an iteration flips no edge
    /// and moves the vertices by less than this root mean square, in edge lengths (0: all
    /// polish iterations run).
    #[arg(long, default_value_t = capmesh::remesh::shape::ShapeOptions::default().polish_tolerance)]
    pub polish_tolerance: f64,
    /// Global area steps of the polish: Gauss-Newton steps of the area term over all
    /// vertices at once (one every 5 polish iterations from the first; 0: none), which
    /// remove the smooth part of the area error the per-vertex steps spread slowly.
    #[arg(long, default_value_t = capmesh::remesh::shape::ShapeOptions::default().area_steps)]
    pub area_steps: usize,
    /// Weight of the shape term against the area term in the polish (larger: better
    /// angles, less equal areas).
    #[arg(long, default_value_t = capmesh::remesh::shape::ShapeOptions::default().shape_weight)]
    pub shape_weight: f64,
    /// Keep the pulled-back vertices' count and the grid's rows: no edge splits and
    /// collapses in the shape stage (they are on by default and give better angles).
    #[arg(long)]
    pub no_resample: bool,
    /// Creases: auto (the default: kept with --sizing curvature, not otherwise), keep or off.
    /// Kept, vertices are put on the input's creases (edges bent by more than --crease-angle,
    /// in chains of at least 3 edge lengths) and joined by edges: a lower surface distance on
    /// surfaces with sharp edges, worse angles on staircased segmentations.
    #[arg(long, default_value = "auto")]
    pub creases: capmesh::Creases,
    /// The same as --creases keep.
    #[arg(long, conflicts_with = "creases")]
    pub keep_creases: bool,
    /// The crease bound in degrees, in (0, 180): input edges bent more are creases (kept
    /// with --creases), and no edge flip bends a pair of faces more.
    #[arg(long, value_parser = crease_angle, default_value_t = capmesh::remesh::shape::DEFAULT_CREASE_DEG)]
    pub crease_angle: f64,
    /// Of an input in several pieces, remesh the largest whatever the others hold (by
    /// default only specks of at most 1% of the area are dropped, larger pieces refused).
    #[arg(long)]
    pub largest_piece: bool,
    /// Fill each hole of an open surface with a fan of faces to a vertex at its middle and
    /// remesh the closed surface (the remesh is closed): for a closed surface with a few faces
    /// missing, which a disk's map squeezes. Off by default
    #[arg(long)]
    pub fill_holes: bool,
    /// Map the input as it is even when it has fewer faces than the remesh asks for or edges
    /// longer than the remesh's (by default such an input is midpoint-subdivided for its map,
    /// up to 3 times, and its long edges split: the same surface, its map resolved at the
    /// remesh's scale).
    #[arg(long)]
    pub no_subdivide: bool,
    /// Map a closed input of many more vertices than the remesh needs at the detail
    /// --multilevel-above and --coarse-vertices ask for, as `capmesh param` does (by default
    /// the shape+area remesh maps it through a decimated copy of 1.2 times the remesh's faces
    /// in vertices, at least 6000, prolonged to every vertex: faster, the same remesh, a higher
    /// mean |d_area|; --optimize area|none and --lat-long always map as param does).
    #[arg(long)]
    pub fine_map: bool,
    /// Vertex placement: fitted (the default: moved along their normals so that the faces
    /// fit the input in the least-squares sense, a lower mean distance to it; the vertices
    /// leave the surface by a fraction of a face's sagitta) or on-surface (on the input,
    /// the faces its chords; with --optimize none, the paper's plain pull-back).
    #[arg(long, default_value = "fitted")]
    pub placement: capmesh::Placement,
    /// Face sizing: uniform (equal areas, the default), surface (equal surface areas covered
    /// through the map, a uniform vertex density on the surface: folds and thin edges finer
    /// than the faces keep their vertices, a lower distance to the input, less equal face
    /// areas) or curvature[=S] (smaller faces where the surface is curved, density 1 + S k L
    /// at the same face count; S = 3; faces measured as with surface; creases kept unless
    /// --creases off).
    #[arg(long, default_value = "uniform")]
    pub sizing: capmesh::Sizing,
    /// Write figures (PNG, SVG) and an index.md linking them into this directory.
    #[arg(long, value_name = "DIR")]
    pub figures: Option<PathBuf>,
    #[command(flatten)]
    pub map: map_args::MapArgs,
    /// Set from the global `--quiet`.
    #[arg(skip)]
    pub quiet: bool,
}

/// The `--report` file: the remesh's metrics and stage times at the top level, the stages'
/// reports and the parameterization's report below.
#[derive(serde::Serialize)]
struct Flat<'a> {
    /// Every figure of the remesh's metrics, at the top level (one source: a figure added to
    /// `RemeshMetrics` reaches the report).
    #[serde(flatten)]
    metrics: &'a capmesh::metrics::RemeshMetrics,
    seconds: f64,
    read_seconds: f64,
    pullback_seconds: f64,
    shape_seconds: f64,
    equalize_seconds: f64,
    metrics_seconds: f64,
    write_seconds: f64,
    split_vertices: usize,
    reoriented_faces: usize,
    duplicate_faces: usize,
    dropped_components: usize,
    dropped_area_share: f64,
    filled_holes: usize,
    subdivided: usize,
    split_edges: usize,
    quality: capmesh::MapQuality,
    optimize: capmesh::remesh::Optimize,
    shape: capmesh::remesh::shape::ShapeReport,
    area_equalization: capmesh::refine::area_refine::AreaRefineReport,
    fit: capmesh::FitReport,
    parameterization: &'a capmesh::ParamReport,
}

/// Run `capmesh remesh`.
pub fn run(args: RemeshArgs) -> Result<(), Failure> {
    let RemeshArgs {
        input,
        output,
        attribute,
        faces,
        lat_long,
        rings,
        sectors,
        report,
        area_equalization,
        optimize,
        relax_iterations,
        polish_iterations,
        polish_tolerance,
        area_steps,
        shape_weight,
        no_resample,
        creases,
        keep_creases,
        crease_angle,
        largest_piece,
        fill_holes,
        no_subdivide,
        fine_map,
        placement,
        sizing,
        figures,
        map,
        quiet,
    } = args;
    refuse_overwrite(&input, &output)?;
    if let Some(r) = &report {
        refuse_overwrite(&input, r)?;
        outputs::refuse_duplicates(&[&output, r])?;
    }
    let t_read = std::time::Instant::now();
    let m = read(&input)?;
    let attributes = attributes_arg::read_all(&attribute, &input, &m, &output)?;
    let read_seconds = t_read.elapsed().as_secs_f64();
    let bar = cli_progress::Bar::new(quiet);
    let grid = if lat_long { CapGrid::LatLong { rings, sectors } } else { CapGrid::Uniform { faces } };
    let shape = capmesh::remesh::shape::ShapeOptions::default().with_relax_iterations(relax_iterations).with_polish_iterations(polish_iterations).with_polish_tolerance(polish_tolerance).with_area_steps(area_steps).with_shape_weight(shape_weight).with_resample(!no_resample).with_sizing(sizing).with_creases(if keep_creases { capmesh::Creases::Keep } else { creases }).with_crease_deg(crease_angle);
    let mut options = RemeshOptions::default().with_grid(grid).with_area_equalization(area_equalization).with_optimize(optimize).with_shape(shape).with_placement(placement).with_subdivide_coarse(!no_subdivide).with_coarse_map(!fine_map);
    if largest_piece {
        options = options.with_pieces(capmesh::Pieces::Largest);
    }
    if fill_holes {
        options = options.with_holes(capmesh::Holes::Fill);
    }
    map.apply(&mut options.param);
    let (out, rep, points) = capmesh::remesh_located(&m, &options, &bar).map_err(|e| {
        // A tube (a vessel, an airway) has two boundary loops: filled, it is a closed surface.
        let holes = matches!(e, capmesh::Error::Mesh(capmesh::mesh::MeshError::SeveralBoundaryLoops { .. }));
        match failure::of_pipeline("remesh", &input, bar.stage(), e) {
            Failure::Error(text) if holes => Failure::Error(format!("{text}; or remesh with --fill-holes, which fills every hole and remeshes the closed surface")),
            other => other,
        }
    })?;
    bar.finish();
    let t_write = std::time::Instant::now();
    let carried: Vec<_> = attributes.iter().map(|a| capmesh::carry_attribute(&m, &points, a)).collect();
    let mut staged = if carried.is_empty() || io::Format::from_path(&output) != Some(io::Format::Ply) {
        vec![outputs::stage_mesh(&output, &out)?]
    } else {
        vec![io::stage_mesh_with_properties(&output, &out, &attributes_arg::ply_properties(&carried), &Default::default())?]
    };
    if !carried.is_empty() && io::Format::from_path(&output) == Some(io::Format::Gifti) {
        for (path, file) in attributes_arg::stage_gifti(&output, &carried)? {
            refuse_overwrite(&input, &path)?;
            staged.push(file);
        }
    }
    let write_seconds = t_write.elapsed().as_secs_f64();
    outln!("{}: remeshed onto Z* = {:.4} in {:.2} s", input.display(), rep.param.z_star.unwrap_or(f64::NAN), rep.seconds);
    if rep.dropped_components > 0 {
        outln!(
            "{}: remeshed the largest piece; dropped {} other piece{} ({:.3}% of the area)",
            input.display(),
            rep.dropped_components,
            if rep.dropped_components == 1 { "" } else { "s" },
            100.0 * rep.dropped_area_share
        );
    }
    if rep.split_vertices > 0 {
        outln!("{}", crate::param_cmd::pinch_note(&input, rep.split_vertices));
    }
    if rep.duplicate_faces > 0 {
        outln!("{}", crate::param_cmd::duplicate_note(&input, rep.duplicate_faces));
    }
    if rep.reoriented_faces > 0 {
        outln!("{}", crate::param_cmd::reorient_note(&input, rep.reoriented_faces));
    }
    if rep.filled_holes > 0 {
        outln!(
            "{}: filled {} hole{} (a fan of faces to a vertex in each) and remeshed the closed surface",
            input.display(),
            rep.filled_holes,
            if rep.filled_holes == 1 { "" } else { "s" }
        );
    }
    if rep.subdivided > 0 {
        outln!(
            "{}: mapped with every face split into {} (it has fewer faces than the remesh; --no-subdivide maps it as it is)",
            input.display(),
            4usize.pow(rep.subdivided as u32)
        );
    }
    if rep.split_edges > 0 {
        outln!(
            "{}: mapped with {} edge{} longer than the remesh's split at {} midpoint{} (--no-subdivide maps it as it is)",
            input.display(),
            rep.split_edges,
            if rep.split_edges == 1 { "" } else { "s" },
            if rep.split_edges == 1 { "its" } else { "their" },
            if rep.split_edges == 1 { "" } else { "s" }
        );
    }
    if rep.param.kind == capmesh::mesh::SurfaceKind::OpenDisk {
        if let Some(note) = crate::param_cmd::small_boundary_note(&input, &m) {
            outln!("{note}; or remesh with --fill-holes");
        }
    }
    warn_if_poor(&input, &rep.param);
    if rep.quality.zero_area_faces > 0 {
        eprintln!(
            "warning: {}: the remesh has {} zero-area faces; check the input with `capmesh check`, try fewer faces, \
             or remove them with an edge collapse",
            input.display(),
            rep.quality.zero_area_faces
        );
    }
    if rep.quality.self_intersecting_faces > rep.quality.self_intersecting_faces_input {
        eprintln!(
            "warning: {}: {} faces of the remesh cross another face (the input has {}): the surface is thinner or bends more \
             sharply than the remesh's edges there (between fingers, at a deep fold); try another --faces, and find them \
             with MeshLab's 'Select Self Intersecting Faces'",
            input.display(),
            rep.quality.self_intersecting_faces,
            rep.quality.self_intersecting_faces_input
        );
    }
    print_quality(&rep.quality)?;
    if let Some(path) = report {
        let q = &rep.quality;
        staged.push(outputs::stage_json(
            &path,
            &Flat {
                metrics: q,
                seconds: rep.seconds,
                read_seconds,
                pullback_seconds: rep.pullback_seconds,
                shape_seconds: rep.shape_seconds,
                equalize_seconds: rep.equalize_seconds,
                metrics_seconds: rep.metrics_seconds,
                write_seconds,
                split_vertices: rep.split_vertices,
                reoriented_faces: rep.reoriented_faces,
                duplicate_faces: rep.duplicate_faces,
                dropped_components: rep.dropped_components,
                dropped_area_share: rep.dropped_area_share,
                filled_holes: rep.filled_holes,
                subdivided: rep.subdivided,
                split_edges: rep.split_edges,
                quality: rep.param.quality,
                optimize: rep.optimize,
                shape: rep.shape,
                area_equalization: rep.area_equalization,
                fit: rep.fit,
                parameterization: &rep.param,
            },
        )?);
    }
    outputs::commit(staged, || format!("remesh of {} stopped while writing", input.display()))?;
    if let Some(dir) = figures {
        figures_arg::done(capmesh::figures::remesh_figures(&dir, &figures_arg::name(&input), &m, &out, &rep, &Default::default()))?;
    }
    refuse_poor(&input, &rep.param, map.allow_poor_map)
}

/// `--crease-angle`: degrees strictly between 0 and 180.
fn crease_angle(s: &str) -> Result<f64, String> {
    let deg = s.parse::<f64>().map_err(|_| format!("{s:?} is not a number of degrees"))?;
    capmesh::ShapeOptions::checked_crease_deg(deg)
}
