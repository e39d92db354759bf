//! The `capmesh` command line: check, param, remesh, metrics, harmonics, shape. This file holds
//! the argument definitions (clap) and the dispatch; each command with more than a few lines
//! runs in its own `*_cmd.rs`.

/// `println!` that never panics: when the reader of standard output has gone
/// (`capmesh check mesh.obj | head -1`) the program ends quietly, like other command-line
/// tools; another write error becomes the command's error. Use in functions returning
/// `Result<_, String>`.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::write_line(format_args!($($arg)*))?
    };
}

mod attributes_arg;
mod basis_args;
mod cli_progress;
mod failure;
mod figures_arg;
mod harmonics_cmd;
mod interrupt;
mod map_args;
mod outputs;
mod param_cmd;
mod poor_map;
mod quality_table;
mod remesh_cmd;
mod shape_cmd;
mod shape_csv;
mod shape_groups;

use basis_args::BasisArgs;
use capmesh::cap::Domain;
use capmesh::io;
use capmesh::mesh;
use clap::{Parser, Subcommand};
use failure::Failure;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub(crate) use poor_map::{refuse_poor, warn_if_poor};
pub(crate) use quality_table::print_quality;

#[derive(Parser)]
#[command(name = "capmesh", version, about = "Adaptive area-preserving parameterization onto a spherical cap, remeshing through it, and adaptive harmonics")]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// No progress bar.
    #[arg(long, global = true)]
    quiet: bool,
    /// Worker threads (default: one per core, or RAYON_NUM_THREADS). `param` and `remesh`
    /// write the same bytes on any number of threads.
    #[arg(long, global = true, value_parser = clap::value_parser!(u16).range(1..))]
    threads: Option<u16>,
}

#[derive(Subcommand)]
enum Command {
    /// Check a mesh: counts, boundary loops, components, Euler characteristic, and whether it
    /// is an open disk or a closed genus-0 surface. Exits non-zero otherwise.
    Check {
        /// Mesh file (.obj, .ply, .off, .stl, .gii, FreeSurfer lh.pial, optionally .gz).
        input: PathBuf,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Parameterize a surface onto the adaptive spherical cap (or a fixed baseline domain).
    Param {
        /// Input mesh.
        input: PathBuf,
        /// Output mesh: the input's connectivity with vertices on the cap.
        #[arg(short, long)]
        output: PathBuf,
        /// Domain: adaptive (default), disk, hemisphere, sphere or radius=R.
        #[arg(long, default_value = "adaptive")]
        domain: Domain,
        /// Write a JSON report here.
        #[arg(long)]
        report: Option<PathBuf>,
        /// Also write the input mesh with the map as texture coordinates (.obj: vt, .ply:
        /// texture_u/texture_v; the disk scaled into [0,1]^2).
        #[arg(long, value_name = "OUT")]
        uv: Option<PathBuf>,
        /// Write figures (PNG, SVG) and an index.md linking them into this directory.
        #[arg(long, value_name = "DIR")]
        figures: Option<PathBuf>,
        #[command(flatten)]
        map: map_args::MapArgs,
    },
    /// Remesh a surface through its adaptive cap: a uniform cap mesh of about N faces
    /// (default) or a latitude/longitude mesh, pulled back by the inverse map. Closed
    /// surfaces come back closed (the cap's flat bottom goes onto the punctured quad).
    Remesh(remesh_cmd::RemeshArgs),
    /// Adaptive harmonics representation: parameterize onto the adaptive cap, fit every order up
    /// to N by least squares, write the order-N reconstruction (the input's connectivity), the
    /// coefficients and the reconstruction error of each order.
    Harmonics {
        /// Input mesh.
        input: PathBuf,
        /// Largest order N ((N + 1)^2 basis functions).
        #[arg(long, default_value_t = capmesh::harmonics::pipeline::DEFAULT_ORDER)]
        order: usize,
        /// Output mesh: the reconstructed surface.
        #[arg(short, long)]
        output: PathBuf,
        /// Write the coefficients as JSON here (z_star, order, q1, q2, list of n, m, x, y, z).
        #[arg(long)]
        coefficients: Option<PathBuf>,
        /// Write a JSON report here (error per order, aspect ratio, parameterization).
        #[arg(long)]
        report: Option<PathBuf>,
        /// Write the cap map here (the input's connectivity with its vertices on the cap): the
        /// points at which the coefficients are evaluated.
        #[arg(long)]
        cap_mesh: Option<PathBuf>,
        /// Domain: adaptive (default), hemisphere, sphere or radius=R.
        #[arg(long, default_value = "adaptive")]
        domain: Domain,
        /// Write figures (PNG, SVG) and an index.md linking them into this directory.
        #[arg(long, value_name = "DIR")]
        figures: Option<PathBuf>,
        /// Exit 0 with a poor map (mean |d_area| above 0.3 on the adaptive cap) instead of 3.
        #[arg(long)]
        allow_poor_map: bool,
        #[command(flatten)]
        basis: BasisArgs,
        /// Write the reconstruction on a uniform cap mesh of about N faces to -o (a smooth
        /// remesh) instead of on the input's connectivity.
        #[arg(long, value_name = "N")]
        resample_faces: Option<usize>,
    },
    /// Shape analysis of many meshes in parallel: Z* and the order-1 (N = 1) aspect ratio
    /// sigma1/sigma3 of each, one CSV row per mesh, sorted by file. Failed meshes get a
    /// 'failed' row; the command then exits 1 after writing the CSV (3 when rows are only
    /// poor). Rows are appended to CSV.partial as meshes finish; --resume reuses them.
    Shape {
        /// Mesh files and/or directories (searched recursively for .obj, .ply, .off, .stl, .gii,
        /// FreeSurfer surface names such as lh.pial, optionally .gz).
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
        /// Output CSV file.
        #[arg(long)]
        csv: PathBuf,
        /// Meshes analysed at once (default: one per worker thread, see --threads).
        #[arg(long)]
        jobs: Option<usize>,
        /// Domain: adaptive (default), hemisphere, sphere or radius=R.
        #[arg(long, default_value = "adaptive")]
        domain: Domain,
        /// Keep the rows of an earlier run (the CSV and CSV.partial) whose file is unchanged:
        /// same size and modification time (--resume), or same SHA-256 (--resume=hash); run
        /// only the rest. Use the same options as the earlier run.
        #[arg(long, num_args = 0..=1, require_equals = true, default_missing_value = "mtime")]
        resume: Option<shape_csv::ResumeBy>,
        /// With --resume: analyse the meshes of 'failed' rows again.
        #[arg(long, requires = "resume")]
        retry_failed: bool,
        /// Exit 0 when rows are poor (quality column) instead of 3.
        #[arg(long)]
        allow_poor_map: bool,
        #[command(flatten)]
        basis: BasisArgs,
        /// CSV file of `file,group` rows: compare the aspect ratios of the groups (Welch's
        /// t-test, effect size, means and spreads) on stdout and in NAME.groups.json and
        /// NAME.groups.csv next to --csv NAME.csv.
        #[arg(long, value_name = "GROUPS_CSV")]
        groups: Option<PathBuf>,
    },
    /// Remeshing metrics of any remeshed surface against its original: d_face, surface
    /// distances (mean and one-sided Hausdorff), angles, valence, self-intersecting faces.
    Metrics {
        /// The original mesh.
        original: PathBuf,
        /// The remeshed mesh.
        remeshed: PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // Commands that write files stop cleanly on SIGINT and SIGTERM; `check` and `metrics`
    // keep the default (they write nothing).
    if matches!(cli.command, Command::Param { .. } | Command::Remesh(_) | Command::Harmonics { .. } | Command::Shape { .. }) {
        if let Err(e) = interrupt::install() {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    }
    if let Some(n) = cli.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(usize::from(n)).build_global() {
            eprintln!("error: cannot start {n} worker threads: {e}");
            return ExitCode::FAILURE;
        }
    }
    // The whole command on a worker thread of rayon's pool, so that the parallel loops of the
    // reading, the metrics and the writing are split in place too (the library's entry
    // points do this for the pipeline itself, see `capmesh::pool`); measurably faster on the
    // small meshes than the library's alone.
    match rayon::scope(|_| run(cli)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => failure.report(),
    }
}

pub(crate) fn read(path: &Path) -> Result<capmesh::TriMesh, String> {
    io::read_mesh(path).map_err(|e| e.to_string())
}

/// One line on standard output (see [`outln`]).
pub(crate) fn write_line(args: std::fmt::Arguments) -> Result<(), String> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_fmt(args).and_then(|()| out.write_all(b"\n")) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(e) => Err(format!("cannot write to standard output: {e}")),
    }
}

pub(crate) fn refuse_overwrite(input: &Path, output: &Path) -> Result<(), String> {
    if io::same_file(input, output) {
        return Err(format!("refusing to overwrite the input file {}; choose another output path", input.display()));
    }
    Ok(())
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Harmonics { input, order, output, coefficients, report, cap_mesh, domain, figures, allow_poor_map, basis, resample_faces } => {
            let basis = basis.kind()?;
            harmonics_cmd::run(harmonics_cmd::HarmonicsArgs {
                input,
                order,
                output,
                coefficients,
                report,
                cap_mesh,
                domain,
                figures,
                allow_poor_map,
                basis,
                resample_faces,
                quiet: cli.quiet,
            })
        }
        Command::Shape { inputs, csv, jobs, domain, resume, retry_failed, allow_poor_map, basis, groups } => {
            let basis = basis.kind()?;
            shape_cmd::run(shape_cmd::ShapeArgs { inputs, csv, jobs, domain, resume, retry_failed, allow_poor_map, basis, groups, quiet: cli.quiet })
        }
        Command::Remesh(args) => remesh_cmd::run(remesh_cmd::RemeshArgs { quiet: cli.quiet, ..args }),
        Command::Metrics { original, remeshed, json } => {
            let (a, b) = (read(&original)?, read(&remeshed)?);
            let q = capmesh::metrics::remesh_metrics(&a, &b);
            if json {
                outln!("{}", serde_json::to_string_pretty(&q).map_err(|e| e.to_string())?);
            } else {
                print_quality(&q)?;
            }
            Ok(())
        }
        Command::Check { input, json } => {
            // The repairs `param` and `remesh` make, each once, before counting.
            let mut m = read(&input)?;
            let mut done = Vec::new();
            let summary = loop {
                let summary = mesh::inspect(&m);
                match summary.as_ref().err().and_then(|e| param_cmd::repair(&m, e, &done)) {
                    Some((fixed, r)) => {
                        done.push(r);
                        m = fixed;
                    }
                    None => break summary,
                }
            };
            let (split_vertices, duplicate_faces, reoriented_faces) = param_cmd::Repair::counts(&done);
            let summary = summary.map_err(|e| format!("{}: {e}", input.display()))?;
            if json {
                #[derive(serde::Serialize)]
                struct Checked<'a> {
                    #[serde(flatten)]
                    summary: &'a mesh::MeshSummary,
                    split_vertices: usize,
                    duplicate_faces: usize,
                    reoriented_faces: usize,
                }
                let checked = Checked { summary: &summary, split_vertices, duplicate_faces, reoriented_faces };
                outln!("{}", serde_json::to_string_pretty(&checked).map_err(|e| e.to_string())?);
            } else {
                outln!("file                 {}", input.display());
                outln!("vertices             {}", summary.n_vertices);
                outln!("faces                {}", summary.n_faces);
                outln!("edges                {}", summary.n_edges);
                outln!("boundary loops       {}", summary.boundary_loops);
                if summary.boundary_loops > 0 {
                    outln!("boundary length      {:.3} of sqrt(area)", summary.boundary_length_ratio);
                }
                outln!("components           {}", summary.n_components);
                outln!("Euler characteristic {}", summary.euler_characteristic);
                if let Some(g) = summary.genus {
                    outln!("genus                {g}");
                }
                outln!("zero-area faces      {}", summary.zero_area_faces);
                outln!("coincident vertices  {}", summary.coincident_vertex_pairs);
                if split_vertices > 0 {
                    outln!("pinched vertices     split, {split_vertices} copies (the surface touches itself there; param and remesh split them too)");
                }
                if duplicate_faces > 0 {
                    outln!("repeated faces       dropped, {duplicate_faces} (param and remesh drop them too)");
                }
                if reoriented_faces > 0 {
                    outln!("misoriented faces    flipped, {reoriented_faces} (wound against their neighbours; param and remesh flip them too)");
                }
            }
            // The full validation names why the surface cannot be mapped.
            mesh::validate(&m).map_err(|e| format!("{}: {e}", input.display()))?;
            if !json {
                if let Some(kind) = summary.kind {
                    outln!("surface              {kind}");
                }
                if let Some(note) = param_cmd::small_boundary_note(&input, &m) {
                    outln!("{note}");
                }
            }
            Ok(())
        }
        Command::Param { input, output, domain, report, uv, figures, map } => {
            param_cmd::run(param_cmd::ParamArgs { input, output, domain, report, uv, figures, map, quiet: cli.quiet })
        }
    }
}
