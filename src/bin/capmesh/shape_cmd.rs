//! `capmesh shape`: the paper's N = 1 shape analysis (aspect ratio `sigma1 / sigma3` of the
//! order-1 adaptive harmonics representation) of a cohort of meshes, in parallel, into a CSV
//! file with one row per mesh, sorted by file.
//!
//! Nothing is lost when the run stops: each row is appended to `CSV.partial` (header first,
//! flushed per row) as its mesh finishes; the CSV itself is written atomically at the end,
//! sorted, and the partial file removed. `--resume` keeps the rows of the CSV and of
//! `CSV.partial` whose file is unchanged ([`crate::shape_csv`]) and analyses only the rest,
//! so a resumed run writes the same bytes as an uninterrupted one (each mesh is analysed on one
//! thread, so the rows do not depend on `--jobs` or `--threads` either). A mesh that fails gets a
//! `failed` row with its error (`--resume --retry-failed` analyses it again); the command then
//! exits 1, after writing the CSV; rows whose map is poor exit 3 unless `--allow-poor-map`.
//! `--basis scha` uses the spherical cap harmonics; `--groups` adds the cohort comparison
//! ([`crate::shape_groups`]).

use crate::failure::Failure;
use crate::interrupt;
use crate::read;
use crate::shape_csv::{self, EarlierRow, Identity, ResumeBy, HEADER};
use capmesh::cap::Domain;
use capmesh::harmonics::{analyze, BasisKind, HarmonicsOptions};
use capmesh::io::Format;
use capmesh::param::ParamOptions;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Arguments of `capmesh shape`.
pub struct ShapeArgs {
    pub inputs: Vec<PathBuf>,
    pub csv: PathBuf,
    pub jobs: Option<usize>,
    pub domain: Domain,
    pub resume: Option<ResumeBy>,
    pub retry_failed: bool,
    pub allow_poor_map: bool,
    pub basis: BasisKind,
    pub groups: Option<PathBuf>,
    pub quiet: bool,
}

/// One mesh's row: its file (as in the CSV), the line, its error if it failed, whether poor.
struct Row {
    file: String,
    line: String,
    error: Option<String>,
    poor: bool,
}

/// The rows appended as meshes finish, and the first write error.
struct Journal {
    file: std::fs::File,
    error: Option<std::io::Error>,
}

/// `CSV.partial`: the rows of a run in progress.
fn partial_path(csv: &Path) -> PathBuf {
    let mut name = csv.as_os_str().to_owned();
    name.push(".partial");
    PathBuf::from(name)
}

fn write_error(path: &Path, source: std::io::Error) -> Failure {
    capmesh::io::WriteError::Io { path: path.to_path_buf(), source }.into()
}

/// Run `capmesh shape`.
pub fn run(args: ShapeArgs) -> Result<(), Failure> {
    let files = collect(&args.inputs)?;
    if files.is_empty() {
        return Err(Failure::Error("no mesh files (.obj, .ply, .off, .stl, .gii, lh.pial, ..., optionally .gz) in the given paths".into()));
    }
    let partial = partial_path(&args.csv);
    for f in &files {
        for out in [&args.csv, &partial] {
            if capmesh::io::same_file(f, out) {
                return Err(Failure::Error(format!("refusing to overwrite the input file {}; choose another CSV path", f.display())));
            }
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

    // The rows of an earlier run that can be kept.
    let mut earlier: HashMap<String, EarlierRow> = HashMap::new();
    if args.resume.is_some() {
        let ignored = shape_csv::read_earlier(&args.csv, &mut earlier)? + shape_csv::read_earlier(&partial, &mut earlier)?;
        if ignored > 0 {
            eprintln!("warning: {ignored} incomplete row(s) of the earlier run ignored (cut short when it was stopped); their meshes are analysed again");
        }
    } else if partial.exists() {
        eprintln!(
            "warning: {} (the rows of a stopped run) is started anew; use --resume to keep its rows",
            partial.display()
        );
    }
    let mut rows: Vec<Row> = Vec::new();
    let mut todo: Vec<(String, &PathBuf)> = Vec::new();
    for file in &files {
        let key = file.display().to_string();
        if let (Some(by), Some(row)) = (args.resume, earlier.remove(&key)) {
            let retry = row.error.is_some() && args.retry_failed;
            let now = if by == ResumeBy::Hash { Identity::full(file) } else { Identity::stat(file) };
            if !retry && now.unchanged(&row.id, by) {
                rows.push(Row { file: key, line: row.line, error: row.error, poor: row.poor });
                continue;
            }
        }
        todo.push((key, file));
    }
    let kept = rows.len();

    // The journal: header and kept rows first, then each row as its mesh finishes.
    let mut file = std::fs::File::create(&partial).map_err(|e| write_error(&partial, e))?;
    let mut head = format!("{HEADER}\n");
    for row in &rows {
        head.push_str(&row.line);
        head.push('\n');
    }
    file.write_all(head.as_bytes()).and_then(|()| file.flush()).map_err(|e| write_error(&partial, e))?;
    let journal = Mutex::new(Journal { file, error: None });

    // `--jobs`, else as many as the global pool's threads (`--threads`).
    let jobs = args.jobs.unwrap_or_else(rayon::current_num_threads).max(1);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs).build().map_err(|e| format!("cannot start worker threads: {e}"))?;
    let bar = counter(todo.len(), args.quiet);
    let options = HarmonicsOptions::default().with_order(1).with_param(ParamOptions::default().with_domain(args.domain)).with_basis(args.basis);
    let journal_failed = || journal.lock().map_or(true, |j| j.error.is_some());
    let new_rows: Vec<Row> = pool.install(|| {
        todo.par_iter()
            .filter_map(|(key, file)| {
                if interrupt::requested() || journal_failed() {
                    return None;
                }
                // The file as it is read (a file changed meanwhile runs again on --resume).
                let id = Identity::full(file);
                // Each mesh on one thread of its own: the fit's parallel QR rounds differently
                // on another number of threads, and the rows must not depend on --jobs (a
                // resumed run may use another).
                let result = rayon::ThreadPoolBuilder::new().num_threads(1).build().map_err(|e| format!("cannot start a worker thread: {e}")).and_then(|one| {
                    one.install(|| {
                        read(file).and_then(|mesh| {
                            analyze(&mesh, &options, &interrupt::Stop).map(|out| (mesh.n_faces(), out.report)).map_err(|e| e.to_string())
                        })
                    })
                });
                if result.is_err() && interrupt::requested() {
                    return None; // stopped, not failed: no row
                }
                let line = shape_csv::line(key, &result, &id);
                if let Ok(mut j) = journal.lock() {
                    if j.error.is_none() {
                        if let Err(e) = j.file.write_all(format!("{line}\n").as_bytes()).and_then(|()| j.file.flush()) {
                            j.error = Some(e);
                        }
                    }
                }
                bar.inc(1);
                bar.set_message(file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default());
                let poor = matches!(&result, Ok((_, r)) if r.param.quality == capmesh::MapQuality::Poor);
                Some(Row { file: key.clone(), line, error: result.err(), poor })
            })
            .collect()
    });
    bar.finish_and_clear();
    let analysed = new_rows.len();
    rows.extend(new_rows);
    let journal = journal.into_inner().map_err(|_| "the CSV journal's lock was poisoned".to_string())?;
    if let Some(e) = journal.error {
        return Err(write_error(&partial, e));
    }
    drop(journal.file);
    let finished = rows.len();
    let stopped = || {
        format!(
            "shape stopped after {finished} of {} meshes ({kept} kept from the earlier run); their rows are in {}: \
             rerun the same command with --resume to finish",
            files.len(),
            partial.display()
        )
    };
    interrupt::check(stopped)?;

    // The CSV, sorted by file, written atomically; then the journal goes.
    rows.sort_by(|a, b| a.file.cmp(&b.file));
    let mut text = format!("{HEADER}\n");
    for row in &rows {
        text.push_str(&row.line);
        text.push('\n');
    }
    let staged = capmesh::io::atomic::stage(&args.csv, |w| w.write_all(text.as_bytes()))?;
    interrupt::check(stopped)?;
    capmesh::io::atomic::commit_all(vec![staged])?;
    if let Err(e) = std::fs::remove_file(&partial) {
        eprintln!("warning: cannot remove {}: {e}; delete it (the CSV is complete)", partial.display());
    }

    if let Some((assignments, matched)) = &groups {
        // Each file's aspect ratio from its row (kept or new), in the order of `files`.
        let by_file: HashMap<&str, &Row> = rows.iter().map(|r| (r.file.as_str(), r)).collect();
        let ratios: Vec<Option<f64>> = files
            .iter()
            .map(|f| by_file.get(f.display().to_string().as_str()).filter(|r| r.error.is_none()).and_then(|r| shape_csv::aspect_ratio_of(&r.line)))
            .collect();
        crate::shape_groups::compare(assignments, matched, &ratios, &files, &args.csv)?;
    }

    let failed: Vec<&Row> = rows.iter().filter(|r| r.error.is_some()).collect();
    let poor = rows.iter().filter(|r| r.poor).count();
    outln!(
        "{} meshes, {analysed} analysed, {kept} kept from an earlier run, {} failed, {poor} poor; CSV written to {}",
        rows.len(),
        failed.len(),
        args.csv.display()
    );
    if !failed.is_empty() {
        let mut msg = format!("{} of {} meshes failed (rows with status 'failed' in the CSV):", failed.len(), rows.len());
        for row in failed {
            let _ = write!(msg, "\n  {}: {}", row.file, row.error.as_deref().unwrap_or_default());
        }
        return Err(Failure::Error(msg));
    }
    if poor > 0 && !args.allow_poor_map {
        return Err(Failure::PoorMap(format!(
            "{poor} of {} meshes have a poor map (quality 'poor' in the CSV: mean |d_area| above {}); \
             pass --allow-poor-map to accept them",
            rows.len(),
            capmesh::param::POOR_MAP_AREA_DISTORTION
        )));
    }
    Ok(())
}

/// The mesh files of `inputs`: files as given, directories searched recursively for the
/// supported extensions; sorted by path, each once. A file that cannot be read gets a failed
/// row later.
fn collect(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for input in inputs {
        if input.is_dir() {
            walk(input, &mut files)?;
        } else {
            files.push(input.clone());
        }
    }
    files.sort_by_key(|f| f.display().to_string());
    files.dedup_by_key(|f| f.display().to_string());
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
        } else if Format::from_path(&path).is_some() && path.is_file() && !is_temporary(&path) {
            out.push(path);
        }
    }
    Ok(())
}

/// A temporary of capmesh's atomic writes (another run writing into the cohort's directory).
fn is_temporary(path: &Path) -> bool {
    path.file_name().and_then(|n| n.to_str()).is_some_and(capmesh::io::atomic::is_temporary_name)
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
