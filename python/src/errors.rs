//! The library's errors as Python exceptions, one class per stage's error enum, all under
//! `capmesh.CapmeshError`. The message is the library's own text, the one the CLI prints after
//! `error: `.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(capmesh, CapmeshError, PyException, "Base class of every capmesh error.");
create_exception!(capmesh, InputError, CapmeshError, "Bad arguments: array shapes or dtypes, an index out of range, a non-finite coordinate, an option out of range, an unsupported request.");
create_exception!(capmesh, ReadError, CapmeshError, "A mesh file could not be read (the message names the file and the element).");
create_exception!(capmesh, WriteError, CapmeshError, "A mesh file could not be written.");
create_exception!(capmesh, MeshError, CapmeshError, "The mesh is not a surface capmesh can map (open disk or closed genus 0).");
create_exception!(capmesh, ComputeError, CapmeshError, "The flattening, the optimal transport or the harmonics fit failed.");
create_exception!(capmesh, InternalError, CapmeshError, "A bug in capmesh: please report it with the input.");
create_exception!(capmesh, Cancelled, CapmeshError, "The progress callback returned False.");

/// Add the exception classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("CapmeshError", py.get_type::<CapmeshError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("ReadError", py.get_type::<ReadError>())?;
    m.add("WriteError", py.get_type::<WriteError>())?;
    m.add("MeshError", py.get_type::<MeshError>())?;
    m.add("ComputeError", py.get_type::<ComputeError>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    m.add("Cancelled", py.get_type::<Cancelled>())?;
    Ok(())
}

/// The exception of a library error.
pub fn to_py(error: capmesh::Error) -> PyErr {
    use capmesh::Error as E;
    let message = error.to_string();
    match error {
        E::Read(_) => ReadError::new_err(message),
        E::Write(_) => WriteError::new_err(message),
        E::Mesh(_) => MeshError::new_err(message),
        E::Flatten(_) | E::Transport(_) | E::Harmonics(_) => ComputeError::new_err(message),
        E::Unsupported(_) | E::InvalidOption(_) => InputError::new_err(message),
        E::Cancelled(_) => Cancelled::new_err(message),
        _ => InternalError::new_err(message),
    }
}

/// An [`InputError`] with this message.
pub fn input(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}
