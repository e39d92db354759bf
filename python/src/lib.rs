//! `capmesh._capmesh`: the Python extension module (PyO3). The public package is
//! `python/capmesh/__init__.py`, which wraps these functions.
//!
//! An edge and nothing more: [`arrays`] turns numpy arrays into [`capmesh::TriMesh`] and back,
//! [`options`] turns keyword arguments into the library's options (named as the CLI's flags),
//! [`errors`] maps the library's error enums to Python exceptions, [`progress`] forwards the
//! library's [`capmesh::Progress`] reports to a Python callable; [`api`] holds the functions,
//! [`inverse`] the map kept for `CapMap.inverse`, [`shape`] one row of `capmesh.cohort.shape`.
//! Every computation runs with the GIL released.

mod api;
mod arrays;
mod errors;
mod inverse;
mod options;
mod progress;
mod shape;

use pyo3::prelude::*;

#[pymodule]
fn _capmesh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_function(wrap_pyfunction!(api::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(api::write_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(api::parameterize, m)?)?;
    m.add_function(wrap_pyfunction!(api::remesh, m)?)?;
    m.add_function(wrap_pyfunction!(api::metrics, m)?)?;
    m.add_function(wrap_pyfunction!(api::harmonics, m)?)?;
    m.add_class::<inverse::NativeMap>()?;
    m.add_function(wrap_pyfunction!(shape::shape_row, m)?)?;
    m.add_function(wrap_pyfunction!(shape::check_shape_options, m)?)?;
    m.add_function(wrap_pyfunction!(shape::is_mesh_path, m)?)?;
    Ok(())
}
