//! `_capmesh.shape_row`: one mesh of `capmesh.cohort.shape`, the values of one row of
//! `capmesh shape`'s CSV (paper Sec. "Shape analysis": `Z*` and the aspect ratio
//! `sigma1 / sigma3` of the order-1 harmonics representation). The mesh is read from its file
//! here, on the worker that runs the row, and analysed by the library's
//! [`capmesh::analyze`] at order 1 on a rayon pool of one thread, as the CLI does for each
//! mesh: the fit's parallel QR rounds differently on other thread counts, and a row must not
//! depend on where it ran.
//!
//! The columns are the CLI's (`src/bin/capmesh/shape_csv.rs`, `HEADER`) without the file's
//! identity (`bytes`, `modified`, `sha256`), which `capmesh/cohort.py` adds. A mesh that
//! cannot be read or analysed is a row with `status = "failed"` and the error's text (line
//! breaks as spaces, as in the CSV); bad options raise `InputError` before any mesh is read.

use std::path::PathBuf;

use capmesh::harmonics::{BasisKind, CapBoundary, HarmonicsReport};
use capmesh::mesh::SurfaceKind;
use capmesh::param::{FlattenReport, ParamOptions};
use capmesh::{Domain, HarmonicsOptions, NoProgress};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::input;

/// The shape options of the CLI's `shape`: `--domain`, `--basis`, `--boundary`.
fn options(domain: &str, basis: &str, boundary: &str) -> PyResult<HarmonicsOptions> {
    let domain: Domain = domain.parse().map_err(input)?;
    let boundary: CapBoundary = boundary.parse().map_err(input)?;
    let kind = BasisKind::from_name(basis, boundary).map_err(input)?;
    if kind == BasisKind::Adaptive && boundary != CapBoundary::default() {
        return Err(input(format!("boundary = {:?} applies to the spherical cap harmonics only; pass basis=\"scha\"", boundary.name())));
    }
    Ok(HarmonicsOptions::default().with_order(1).with_param(ParamOptions::default().with_domain(domain)).with_basis(kind))
}

/// check_shape_options(domain, basis, boundary): raise `InputError` for options `shape_row`
/// would refuse (called before a cohort is sent to a cluster).
#[pyfunction]
#[pyo3(signature = (domain="adaptive", basis="ah", boundary="neumann"))]
pub fn check_shape_options(domain: &str, basis: &str, boundary: &str) -> PyResult<()> {
    options(domain, basis, boundary).map(|_| ())
}

/// is_mesh_path(path): whether `capmesh shape` takes this file when it searches a directory
/// (a format capmesh reads, not a temporary of its atomic writes).
#[pyfunction]
pub fn is_mesh_path(path: PathBuf) -> bool {
    let temporary = path.file_name().and_then(|n| n.to_str()).is_some_and(capmesh::io::atomic::is_temporary_name);
    capmesh::io::Format::from_path(&path).is_some() && !temporary
}

/// The mesh's faces and report, or the error's text.
fn analyse(path: &PathBuf, options: &HarmonicsOptions) -> Result<(usize, HarmonicsReport), String> {
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().map_err(|e| format!("cannot start a worker thread: {e}"))?;
    one.install(|| {
        let mesh = capmesh::read_mesh(path).map_err(|e| e.to_string())?;
        let out = capmesh::analyze(&mesh, options, &NoProgress).map_err(|e| e.to_string())?;
        Ok((mesh.n_faces(), out.report))
    })
}

/// shape_row(path, domain="adaptive", basis="ah", boundary="neumann") -> dict of the CSV's
/// columns from `status` to `error` (None for an empty field).
#[pyfunction]
#[pyo3(signature = (path, domain="adaptive", basis="ah", boundary="neumann"))]
pub fn shape_row<'py>(py: Python<'py>, path: PathBuf, domain: &str, basis: &str, boundary: &str) -> PyResult<Bound<'py, PyDict>> {
    let options = options(domain, basis, boundary)?;
    let result = py.allow_threads(|| analyse(&path, &options));
    let row = PyDict::new(py);
    match result {
        Ok((faces, r)) => {
            let open = r.param.kind == SurfaceKind::OpenDisk;
            // The composition factor a closed surface was mapped with (another than asked
            // when it fell back), as the CLI's column.
            let lambda = match (&r.param.flatten, open) {
                (FlattenReport::Closed(f), false) => Some(f.lambda),
                _ => None,
            };
            let [s1, s2, s3] = r.singular_values;
            row.set_item("status", "ok")?;
            row.set_item("quality", r.param.quality.to_string())?;
            row.set_item("vertices", r.vertices)?;
            row.set_item("faces", faces)?;
            row.set_item("kind", if open { "open" } else { "closed" })?;
            row.set_item("z_star", r.z_star)?;
            row.set_item("aspect_ratio", r.aspect_ratio)?;
            row.set_item("ellipsoid_aspect_ratio", r.ellipsoid_aspect_ratio)?;
            row.set_item("sigma1", s1)?;
            row.set_item("sigma2", s2)?;
            row.set_item("sigma3", s3)?;
            row.set_item("mean_abs_area_distortion", r.param.area_distortion.mean_abs)?;
            row.set_item("lambda", lambda)?;
            row.set_item("error", py.None())?;
        }
        Err(e) => {
            row.set_item("status", "failed")?;
            row.set_item("error", e.replace(['\n', '\r'], " "))?;
        }
    }
    Ok(row)
}
