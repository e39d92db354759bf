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
    let mut repaired = Vec::new();
    while let Err(capmesh::Error::Mesh(e)) = &cap {
        let kind = std::mem::discriminant(e);
        if repaired.contains(&kind) {
            break;
        }
        repaired.push(kind);
        let Some(fixed) = repair(&input, &m, e) else { break };
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

/// The input repaired for `error`, said on standard output: pinched vertices split, repeated
/// faces dropped, faces wound against their neighbours flipped (the outputs keep the input's
/// vertices in their order); `None` for any other error, or when the repair does not apply.
fn repair(input: &Path, m: &capmesh::TriMesh, error: &capmesh::mesh::MeshError) -> Option<capmesh::TriMesh> {
    use capmesh::mesh::{repair, MeshError};
    match error {
        MeshError::NonManifoldVertex { .. } => Some(split_pinches(input, m.clone())),
        MeshError::DuplicateFace { .. } => repair::remove_duplicate_faces(m).map(|d| {
            let _ = crate::write_line(format_args!("{}", duplicate_note(input, d.removed_faces)));
            d.mesh
        }),
        MeshError::InconsistentOrientation { .. } => repair::orient_coherently(m).map(|o| {
            let _ = crate::write_line(format_args!("{}", reorient_note(input, o.flipped_faces)));
            o.mesh
        }),
        _ => None,
    }
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

/// The pinched input with those vertices split, one per fan (the outputs then have the
/// input's vertices in their order and the copies after them), said on standard output; the
/// input itself when the split fails (the parameterization then names why).
pub(crate) fn split_pinches(input: &Path, m: capmesh::TriMesh) -> capmesh::TriMesh {
    match capmesh::mesh::repair::split_pinched_vertices(&m) {
        Ok(split) if !split.copy_of.is_empty() => {
            let _ = crate::write_line(format_args!("{}", pinch_note(input, split.copy_of.len())));
            split.mesh
        }
        _ => m,
    }
}

/// What the commands say when they split pinched vertices.
pub(crate) fn pinch_note(input: &Path, copies: usize) -> String {
    let copies = if copies == 1 { "1 copy".to_string() } else { format!("{copies} copies") };
    format!("{}: the surface touches itself at some vertices: split them, one vertex per fan of faces ({copies} appended)", input.display())
}
