//! numpy arrays <-> [`TriMesh`]: vertices `(n, 3)` float32 or float64, faces `(m, 3)` int32,
//! int64 or uint32, any strides (read in place, converted once into the library's types).
//! Checked here, before the library sees them: shapes, finite coordinates, indices in range;
//! each error names the array, the row and what to do.

use capmesh::TriMesh;
use numpy::ndarray::ArrayView2;
use numpy::{PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::input;

fn check_shape(name: &str, shape: &[usize]) -> PyResult<()> {
    if shape.len() != 2 || shape[1] != 3 {
        return Err(input(format!("{name} must have shape (n, 3), not {shape:?}; pass one row of three numbers per {}", if name == "vertices" { "vertex" } else { "triangle" })));
    }
    Ok(())
}

fn rows_f64<T: Copy + Into<f64>>(a: ArrayView2<'_, T>) -> PyResult<Vec<[f64; 3]>> {
    let mut out = Vec::with_capacity(a.nrows());
    for (i, row) in a.rows().into_iter().enumerate() {
        let p = [row[0].into(), row[1].into(), row[2].into()];
        if !p.iter().all(|c| c.is_finite()) {
            return Err(input(format!("vertices[{i}] = {p:?} has a non-finite coordinate; remove or fix that vertex")));
        }
        out.push(p);
    }
    Ok(out)
}

/// The vertices of a `(n, 3)` float32 or float64 array.
pub fn vertices(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[f64; 3]>> {
    if let Ok(a) = obj.downcast::<PyArray2<f64>>() {
        check_shape("vertices", a.shape())?;
        return rows_f64(a.readonly().as_array());
    }
    if let Ok(a) = obj.downcast::<PyArray2<f32>>() {
        check_shape("vertices", a.shape())?;
        return rows_f64(a.readonly().as_array());
    }
    Err(input(format!("vertices must be a numpy array of shape (n, 3) and dtype float32 or float64, not {}", describe(obj))))
}

fn rows_index<T: Copy + TryInto<u32> + std::fmt::Debug>(a: ArrayView2<'_, T>, n_vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    let mut out = Vec::with_capacity(a.nrows());
    for (f, row) in a.rows().into_iter().enumerate() {
        let mut tri = [0u32; 3];
        for k in 0..3 {
            match row[k].try_into() {
                Ok(v) if (v as usize) < n_vertices => tri[k] = v,
                _ => {
                    return Err(input(format!(
                        "faces[{f}] = [{:?}, {:?}, {:?}] refers to vertex {:?}, outside 0..{n_vertices} (there are {n_vertices} vertices); indices are 0-based",
                        row[0], row[1], row[2], row[k]
                    )))
                }
            }
        }
        out.push(tri);
    }
    Ok(out)
}

/// The faces of a `(m, 3)` int32, int64 or uint32 array, checked against `n_vertices`.
pub fn faces(obj: &Bound<'_, PyAny>, n_vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    if let Ok(a) = obj.downcast::<PyArray2<i64>>() {
        check_shape("faces", a.shape())?;
        return rows_index(a.readonly().as_array(), n_vertices);
    }
    if let Ok(a) = obj.downcast::<PyArray2<i32>>() {
        check_shape("faces", a.shape())?;
        return rows_index(a.readonly().as_array(), n_vertices);
    }
    if let Ok(a) = obj.downcast::<PyArray2<u32>>() {
        check_shape("faces", a.shape())?;
        return rows_index(a.readonly().as_array(), n_vertices);
    }
    Err(input(format!("faces must be a numpy array of shape (m, 3) and dtype int32, int64 or uint32, not {}", describe(obj))))
}

/// A [`TriMesh`] of a vertex and a face array.
pub fn mesh(vertices_obj: &Bound<'_, PyAny>, faces_obj: &Bound<'_, PyAny>) -> PyResult<TriMesh> {
    let v = vertices(vertices_obj)?;
    let f = faces(faces_obj, v.len())?;
    Ok(TriMesh::new(v, f))
}

fn describe(obj: &Bound<'_, PyAny>) -> String {
    let shape = obj.getattr("shape").ok().map(|s| s.to_string()).unwrap_or_default();
    let dtype = obj.getattr("dtype").ok().map(|s| s.to_string()).unwrap_or_else(|| obj.get_type().to_string());
    format!("{dtype} {shape}").trim().to_string()
}

/// `(n, D)` float64 array of rows.
pub fn f64_rows<'py, const D: usize>(py: Python<'py>, rows: &[[f64; D]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    numpy::ndarray::Array2::from_shape_vec((rows.len(), D), flat).map(|a| PyArray2::from_owned_array(py, a)).expect("rows of D values")
}

/// `(m, 3)` int64 array of faces (numpy's and trimesh's default index type).
pub fn faces_array<'py>(py: Python<'py>, faces: &[[u32; 3]]) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = faces.iter().flatten().map(|&v| i64::from(v)).collect();
    numpy::ndarray::Array2::from_shape_vec((faces.len(), 3), flat).map(|a| PyArray2::from_owned_array(py, a)).expect("rows of 3 indices")
}
