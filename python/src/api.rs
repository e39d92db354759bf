//! The functions of `capmesh._capmesh`. Each converts its arguments, runs the library with the
//! GIL released and converts the result; reports are returned as JSON text (the library's
//! serde form, as in the CLI's `--report`), which `capmesh/__init__.py` turns into a dict.

use std::path::PathBuf;

use capmesh::{CapGrid, TriMesh};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays;
use crate::errors::{self, input};
use crate::inverse::NativeMap;
use crate::options;
use crate::progress::PyProgress;

type Arrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

fn json<T: serde::Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| errors::InternalError::new_err(format!("cannot encode the report: {e}")))
}

/// Run `work` with the GIL released, reporting to `progress`. A cancellation (which a stage
/// may report inside its own error) raises `capmesh.Cancelled`, or the callback's own
/// exception when it raised one.
fn run<T: Send>(py: Python<'_>, progress: Option<Py<PyAny>>, work: impl FnOnce(&PyProgress) -> capmesh::Result<T> + Send) -> PyResult<T> {
    let sink = PyProgress::new(progress);
    let result = py.allow_threads(|| work(&sink));
    result.map_err(|e| match sink.take_raised() {
        _ if !sink.cancelled() => errors::to_py(e),
        Some(raised) => raised,
        None => errors::Cancelled::new_err(capmesh::progress::Cancelled.to_string()),
    })
}

/// read_mesh(path) -> (vertices, faces)
#[pyfunction]
pub fn read_mesh(py: Python<'_>, path: PathBuf) -> PyResult<Arrays<'_>> {
    let mesh = py.allow_threads(|| capmesh::read_mesh(&path)).map_err(|e| errors::ReadError::new_err(e.to_string()))?;
    Ok((arrays::f64_rows(py, &mesh.vertices), arrays::faces_array(py, &mesh.faces)))
}

/// write_mesh(path, vertices, faces)
#[pyfunction]
pub fn write_mesh(py: Python<'_>, path: PathBuf, vertices: &Bound<'_, PyAny>, faces: &Bound<'_, PyAny>) -> PyResult<()> {
    let mesh = arrays::mesh(vertices, faces)?;
    py.allow_threads(|| capmesh::write_mesh(&path, &mesh)).map_err(|e| errors::WriteError::new_err(e.to_string()))
}

/// parameterize(vertices, faces, domain="adaptive", progress=None, **options)
///   -> (NativeMap, report_json): the map kept with its mesh for `CapMap.inverse`.
#[pyfunction]
#[pyo3(signature = (vertices, faces, domain="adaptive", progress=None, **options))]
pub fn parameterize<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    domain: &str,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<(NativeMap, String)> {
    let mesh = arrays::mesh(vertices, faces)?;
    let options = options::param(domain, options)?;
    let map = run(py, progress, |sink| capmesh::parameterize(&mesh, &options, sink))?;
    let report = json(&map.report)?;
    Ok((NativeMap::new(mesh, map), report))
}

/// remesh(vertices, faces, faces_target=5000, lat_long=None, progress=None, **options)
///   -> (vertices, faces, report_json)
#[pyfunction]
#[pyo3(signature = (vertices, faces, faces_target=5000, lat_long=None, progress=None, **options))]
pub fn remesh<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    faces_target: usize,
    lat_long: Option<(usize, usize)>,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>, String)> {
    let mesh = arrays::mesh(vertices, faces)?;
    let grid = match lat_long {
        Some((rings, sectors)) => CapGrid::LatLong { rings, sectors },
        None if faces_target == 0 => return Err(input("faces_target must be at least 1")),
        None => CapGrid::Uniform { faces: faces_target },
    };
    let options = options::remesh(grid, options)?;
    let (out, report) = run(py, progress, |sink| capmesh::remesh(&mesh, &options, sink))?;
    Ok((arrays::f64_rows(py, &out.vertices), arrays::faces_array(py, &out.faces), json(&report)?))
}

/// metrics(original_vertices, original_faces, remeshed_vertices, remeshed_faces) -> report_json
#[pyfunction]
pub fn metrics(py: Python<'_>, v0: &Bound<'_, PyAny>, f0: &Bound<'_, PyAny>, v1: &Bound<'_, PyAny>, f1: &Bound<'_, PyAny>) -> PyResult<String> {
    let (a, b): (TriMesh, TriMesh) = (arrays::mesh(v0, f0)?, arrays::mesh(v1, f1)?);
    let q = py.allow_threads(|| capmesh::metrics::remesh_metrics(&a, &b));
    json(&q)
}

/// harmonics(vertices, faces, order=10, domain="adaptive", progress=None, **options)
///   -> (reconstructed_vertices, coefficients, report_json)
#[pyfunction]
#[pyo3(signature = (vertices, faces, order=capmesh::harmonics::pipeline::DEFAULT_ORDER, domain="adaptive", progress=None, **options))]
pub fn harmonics<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    order: usize,
    domain: &str,
    progress: Option<Py<PyAny>>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>, String)> {
    let mesh = arrays::mesh(vertices, faces)?;
    let options = capmesh::HarmonicsOptions::default().with_order(order).with_param(options::param(domain, options)?);
    let out = run(py, progress, |sink| capmesh::analyze(&mesh, &options, sink))?;
    Ok((arrays::f64_rows(py, &out.reconstructed.vertices), arrays::f64_rows(py, &out.fit.coefficients), json(&out.report)?))
}
