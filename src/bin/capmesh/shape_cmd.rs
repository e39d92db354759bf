//! `capmesh shape`: the paper's N = 1 shape analysis (aspect ratio `sigma1 / sigma3` of the
//! order-1 adaptive harmonics representation) of a cohort of meshes, in parallel, into a CSV
//! file with one row per mesh. A mesh that fails gets a `failed` row with its error; the
//! command then exits non-zero, after writing the whole CSV. `--basis scha` uses the spherical
//! cap harmonics; `--groups` adds the cohort comparison ([`crate::shape_groups`]).

use crate::read;
use capmesh::param::FlattenReport;
use capmesh::cap::Domain;
use capmesh::param::ParamOptions;
use capmesh::harmonics::{analyze, BasisKind, HarmonicsOptions, HarmonicsReport};
use capmesh::io::Format;
use capmesh::mesh::SurfaceKind;
use capmesh::progress::NoProgress;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `capmesh shape`.
pub struct ShapeArgs {
    pub inputs: Vec<PathBuf>,
    pub csv: PathBuf,
    pub jobs: Option<usize>,
    pub domain: Domain,
    pub basis: BasisKind,
    pub groups: Option<PathBuf>,
    pub quiet: bool,
}

/// CSV columns, in order.
const HEADER: &str = "file,status,vertices,faces,kind,z_star,aspect_ratio,ellipsoid_aspect_ratio,\
                      sigma1,sigma2,sigma3,mean_abs_area_distortion,lambda,seconds,error";

/// One mesh's outcome.
struct Row {
    file: PathBuf,
    result: Result<(usize, HarmonicsReport), String>,
}

/// Run `capmesh shape`.
pub fn run(args: ShapeArgs) -> Result<(), String> {
    let files = collect(&args.inputs)?;
    if files.is_empty() {
        return Err("no mesh files (.obj, .ply, .off, .stl, optionally .gz) in the given paths".into());
    }
    for f in &files {
        if capmesh::io::same_file(f, &args.csv) {
            return Err(format!("refusing to overwrite the input file {}; choose another CSV path", f.display()));
        }
    }
    // The groups file is checked before any mesh is analysed.
    let groups = match &args.groups {
        Some(path) => {
            let rows = crate::shape_groups::read(path)?;
            let matched = crate::shape_groups::match_files(&rows, &files, path)?;
            Some((rows, matched))
        }
        None => None,
    };
    // `--jobs`, else as many as the global pool's threads (`--threads`).
    let jobs = args.jobs.unwrap_or_else(rayon::current_num_threads).max(1);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs).build().map_err(|e| format!("cannot start worker threads: {e}"))?;
    let bar = counter(files.len(), args.quiet);
    let options = HarmonicsOptions::default()
        .with_order(1)
        .with_param(ParamOptions::default().with_domain(args.domain))
        .with_basis(args.basis);
    let rows: Vec<Row> = pool.install(|| {
        files
            .par_iter()
            .map(|file| {
                let result = read(file).and_then(|mesh| {
                    analyze(&mesh, &options, &NoProgress)
                        .map(|out| (mesh.n_faces(), out.report))
                        .map_err(|e| e.to_string())
                });
                bar.inc(1);
                bar.set_message(file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default());
                Row { file: file.clone(), result }
            })
            .collect()
    });
    bar.finish_and_clear();

    let mut text = String::from(HEADER);
    text.push('\n');
    for row in &rows {
        text.push_str(&csv_line(row));
        text.push('\n');
    }
    std::fs::write(&args.csv, text).map_err(|e| format!("cannot write {}: {e}", args.csv.display()))?;

    let failed: Vec<&Row> = rows.iter().filter(|r| r.result.is_err()).collect();
    outln!(
        "{} meshes, {} analysed, {} failed; CSV written to {}",
        rows.len(),
        rows.len() - failed.len(),
        failed.len(),
        args.csv.display()
    );
    if let Some((assignments, matched)) = &groups {
        // `rows` is in the order of `files`.
        let ratios: Vec<Option<f64>> = rows.iter().map(|r| r.result.as_ref().ok().map(|(_, rep)| rep.aspect_ratio)).collect();
        crate::shape_groups::compare(assignments, matched, &ratios, &files, &args.csv)?;
    }
    if failed.is_empty() {
        return Ok(());
    }
    let mut msg = format!("{} of {} meshes failed (rows with status 'failed' in the CSV):", failed.len(), rows.len());
    for row in failed {
        if let Err(e) = &row.result {
            let _ = write!(msg, "\n  {}: {e}", row.file.display());
        }
    }
    Err(msg)
}

/// The mesh files of `inputs`: files as given, directories searched recursively for the
/// supported extensions (sorted). A file that cannot be read gets a failed row later.
fn collect(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let mut found = Vec::new();
            walk(input, &mut found)?;
            found.sort();
            files.extend(found);
        } else {
            files.push(input.clone());
        }
    }
    Ok(files)
}

/// Mesh files under `dir` (symbolic links to directories are not followed).
fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("cannot read directory {}: {e}", dir.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot read directory {}: {e}", dir.display()))?;
        let path = entry.path();
        let kind = entry.file_type().map_err(|e| format!("{}: {e}", path.display()))?;
        if kind.is_dir() {
            walk(&path, out)?;
        } else if Format::from_path(&path).is_some() && path.is_file() {
            out.push(path);
        }
    }
    Ok(())
}

fn csv_line(row: &Row) -> String {
    let file = quote(&row.file.display().to_string());
    match &row.result {
        Ok((faces, r)) => {
            let kind = if r.param.kind == SurfaceKind::OpenDisk { "open" } else { "closed" };
            let [s1, s2, s3] = r.singular_values;
            // The composition factor a closed surface was mapped with (another than asked
            // when it fell back, see `param::lambda_fallback`).
            let lambda = match (&r.param.flatten, kind) {
                (FlattenReport::Closed(f), "closed") => f.lambda.to_string(),
                _ => String::new(),
            };
            format!(
                "{file},ok,{},{faces},{kind},{},{},{},{s1},{s2},{s3},{},{lambda},{:.3},",
                r.vertices, r.z_star, r.aspect_ratio, r.ellipsoid_aspect_ratio, r.param.area_distortion.mean_abs, r.seconds
            )
        }
        Err(e) => format!("{file},failed,,,,,,,,,,,,,{}", quote(e)),
    }
}

/// A CSV field in double quotes, inner quotes doubled (RFC 4180).
fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}

/// A counter bar on stderr (hidden with `--quiet` or when stderr is not a terminal).
fn counter(total: usize, quiet: bool) -> ProgressBar {
    let bar = ProgressBar::new(total as u64);
    if quiet {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    if let Ok(style) = ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} meshes, last: {msg}") {
        bar.set_style(style);
    }
    bar
}
