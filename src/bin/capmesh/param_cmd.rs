//! `capmesh param`: parameterize one mesh onto the adaptive spherical cap (or a fixed baseline
//! domain) and write the cap mesh, optionally the input with the map as texture coordinates,
//! a JSON report and figures.

use crate::failure::{self, Failure};
use crate::{cli_progress, figures_arg, map_args, outputs};
use crate::{read, refuse_overwrite, refuse_poor, warn_if_poor};
use capmesh::cap::Domain;
use capmesh::param::{parameterize, ParamOptions};
use std::path::{Path, PathBuf};

/// Arguments of `capmesh param`.
pub struct ParamArgs {
    pub input: PathBuf,
    pub output: PathBuf,
    pub domain: Domain,
    pub report: Option<PathBuf>,
    pub uv: Option<PathBuf>,
    pub figures: Option<PathBuf>,
    pub map: map_args::MapArgs,
    pub quiet: bool,
}

/// Run `capmesh param`.
pub fn run(args: ParamArgs) -> Result<(), Failure> {
    let ParamArgs { input, output, domain, report, uv, figures, map, quiet } = args;
    refuse_overwrite(&input, &output)?;
    let extra: Vec<&Path> = report.iter().chain(uv.iter()).map(|p| p.as_path()).collect();
    for p in &extra {
        refuse_overwrite(&input, p)?;
    }
    outputs::refuse_duplicates(&[&[output.as_path()][..], &extra].concat())?;
    let mut m = read(&input)?;
    let bar = cli_progress::Bar::new(quiet);
    let mut options = ParamOptions::default().with_domain(domain);
    map.apply(&mut options);
    let mut cap = parameterize(&m, &options, &bar);
    // A pinched input is mapped with those vertices split, repeated faces dropped and stray
    // faces flipped (the library refuses such inputs); each repair at most once.
    let mut done = Vec::new();
    while let Err(capmesh::Error::Mesh(e)) = &cap {
        let Some((fixed, r)) = repair(&m, e, &done) else { break };
        outln!("{}", r.note(&input));
        done.push(r);
        m = fixed;
        cap = parameterize(&m, &options, &bar);
    }
    let cap = cap.map_err(|e| failure::of_pipeline("param", &input, bar.stage(), e))?;
    bar.finish();
    let mut staged = vec![outputs::stage_mesh(&output, &cap.cap_mesh(&m))?];
    if let Some(path) = &uv {
        let extra = capmesh::io::VertexProperties::default().with_uv(cap.uv());
        staged.push(capmesh::io::stage_mesh_with_properties(path, &m, &extra, &Default::default())?);
    }
    let r = &cap.report;
    outln!(
        "{}: {} onto {}: Z* = {}, mean |d_area| = {:.4}, mean |d_angle| = {:.4} rad, flipped faces = {}, {:.2} s",
        input.display(),
        r.kind,
        r.domain,
        r.z_star.map_or("-".to_string(), |z| format!("{z:.4}")),
        r.area_distortion.mean_abs,
        r.angle_distortion.mean_abs,
        r.flipped_faces,
        r.seconds
    );
    if r.kind == capmesh::mesh::SurfaceKind::OpenDisk {
        if let Some(note) = small_boundary_note(&input, &m) {
            outln!("{note}");
        }
    }
    warn_if_poor(&input, r);
    if let Some(path) = report {
        staged.push(outputs::stage_json(&path, r)?);
    }
    outputs::commit(staged, || format!("param of {} stopped while writing", input.display()))?;
    if let Some(dir) = figures {
        figures_arg::done(capmesh::figures::param_figures(&dir, &figures_arg::name(&input), &m, &cap, &Default::default()))?;
    }
    refuse_poor(&input, r, map.allow_poor_map)
}

/// A repair the commands make instead of refusing an input, and its count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Repair {
    /// Pinched vertices split: copies made.
    Split(usize),
    /// Repeated faces dropped.
    Deduplicated(usize),
    /// Faces flipped to agree with their neighbours.
    Reoriented(usize),
}

impl Repair {
    /// Vertices split, faces dropped and faces flipped by `done`.
    pub(crate) fn counts(done: &[Repair]) -> (usize, usize, usize) {
        done.iter().fold((0, 0, 0), |(s, d, o), r| match *r {
            Repair::Split(n) => (s + n, d, o),
            Repair::Deduplicated(n) => (s, d + n, o),
            Repair::Reoriented(n) => (s, d, o + n),
        })
    }

    /// What the commands say about it.
    pub(crate) fn note(self, input: &Path) -> String {
        match self {
            Repair::Split(n) => pinch_note(input, n),
            Repair::Deduplicated(n) => duplicate_note(input, n),
            Repair::Reoriented(n) => reorient_note(input, n),
        }
    }
}

/// `m` repaired for `error` by `capmesh::mesh::repair::repair_for` (which the library's
/// remesh calls too) unless `done` holds that kind of repair already: pinched vertices split
/// (the input's vertices keep their numbers, the copies come after them), repeated faces
/// dropped, faces wound against their neighbours flipped; `None` for any other error, or
/// when the repair does not apply.
pub(crate) fn repair(m: &capmesh::TriMesh, error: &capmesh::mesh::MeshError, done: &[Repair]) -> Option<(capmesh::TriMesh, Repair)> {
    use capmesh::mesh::repair::{repair_for, Repaired};
    let same = |r: &Repair| done.iter().any(|d| std::mem::discriminant(d) == std::mem::discriminant(r));
    // A split that meets a worse defect leaves the error as validation gave it.
    let (mesh, r) = match repair_for(m, error).ok()?? {
        Repaired::Split(s) => {
            let n = s.copy_of.len();
            (s.mesh, Repair::Split(n))
        }
        Repaired::Deduplicated(d) => (d.mesh, Repair::Deduplicated(d.removed_faces)),
        Repaired::Reoriented(o) => (o.mesh, Repair::Reoriented(o.flipped_faces)),
    };
    (!same(&r)).then_some((mesh, r))
}

/// What the commands say about an open surface whose boundary is short against its size
/// (`capmesh::mesh::validate::small_boundary`): a closed surface with a hole is mapped as a
/// disk, and the user may have wanted it closed.
pub(crate) fn small_boundary_note(input: &Path, m: &capmesh::TriMesh) -> Option<String> {
    let (edges, ratio) = capmesh::mesh::validate::small_boundary(m)?;
    Some(format!(
        "{}: an open surface, but its boundary ({edges} edges) is only {ratio:.3} of the square root of its area: \
         a closed surface with a hole? param and remesh map it as a disk; fill the hole (MeshLab: 'Close Holes') to map it as closed",
        input.display()
    ))
}

/// What the commands say when they drop `n` repeated faces.
pub(crate) fn duplicate_note(input: &Path, n: usize) -> String {
    format!("{}: {n} face{} repeated an earlier face's vertices: dropped", input.display(), if n == 1 { "" } else { "s" })
}

/// What the commands say when they flip `n` faces wound against their neighbours.
pub(crate) fn reorient_note(input: &Path, n: usize) -> String {
    let (s, their) = if n == 1 { ("", "its") } else { ("s", "their") };
    format!("{}: {n} face{s} wound against {their} neighbours: flipped to agree with them", input.display())
}

/// What the commands say when they split pinched vertices.
pub(crate) fn pinch_note(input: &Path, copies: usize) -> String {
    let copies = if copies == 1 { "1 copy".to_string() } else { format!("{copies} copies") };
    format!("{}: the surface touches itself at some vertices: split them, one vertex per fan of faces ({copies} appended)", input.display())
}
