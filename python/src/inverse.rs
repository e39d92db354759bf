//! `_capmesh.NativeMap`: a parameterization kept with the mesh it was computed from, so that
//! `capmesh.CapMap.inverse(points)` can run the library's [`capmesh::InverseMap`] (paper
//! Sec. 4.2: cap points back to the input surface). The point location is the library's; this
//! file only converts arrays: a located point becomes its face, barycentric coordinates and
//! position, a point off the cap (or not finite) face `-1` and NaN.

use capmesh::{CapMap, InverseMapError, InverseOptions, SurfacePoint, TriMesh};
use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::arrays;
use crate::errors::{input, MeshError};

/// A [`CapMap`] and its mesh (owned: the Python object outlives the call that made it).
#[pyclass(module = "capmesh._capmesh", frozen)]
pub struct NativeMap {
    mesh: TriMesh,
    map: CapMap,
}

impl NativeMap {
    pub fn new(mesh: TriMesh, map: CapMap) -> Self {
        Self { mesh, map }
    }
}

fn to_py(error: InverseMapError) -> PyErr {
    match error {
        InverseMapError::NoFaces => MeshError::new_err(error.to_string()),
        _ => input(error.to_string()),
    }
}

type Located<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<i64>>, Bound<'py, PyArray2<f64>>);

#[pymethods]
impl NativeMap {
    /// inverse(points (k, 3) float64, tolerance) -> (positions (k, 3), faces (k,), barycentric (k, 3))
    #[pyo3(signature = (points, tolerance = InverseOptions::default().tolerance))]
    fn inverse<'py>(&self, py: Python<'py>, points: PyReadonlyArray2<'py, f64>, tolerance: f64) -> PyResult<Located<'py>> {
        let shape = points.shape();
        if shape.len() != 2 || shape[1] != 3 {
            return Err(input(format!("points must have shape (k, 3), not {shape:?}: one row (X, Y, Z) per cap point")));
        }
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(input(format!("tolerance = {tolerance} must be a finite number >= 0 (the distance a point may lie off the cap)")));
        }
        let rows: Vec<[f64; 3]> = points.as_array().rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect();
        let options = InverseOptions::default().with_tolerance(tolerance);
        let located: Vec<Option<SurfacePoint>> = py.allow_threads(|| {
            let inverse = self.map.inverse_with(&self.mesh, options)?;
            Ok::<_, InverseMapError>(inverse.locate_all(&rows))
        }).map_err(to_py)?;
        let k = located.len();
        let (mut positions, mut faces, mut bary) = (Array2::from_elem((k, 3), f64::NAN), vec![-1i64; k], Array2::from_elem((k, 3), f64::NAN));
        for (i, p) in located.iter().enumerate() {
            if let Some(p) = p {
                faces[i] = p.face as i64;
                for c in 0..3 {
                    positions[[i, c]] = p.position[c];
                    bary[[i, c]] = p.barycentric[c];
                }
            }
        }
        Ok((PyArray2::from_owned_array(py, positions), PyArray1::from_vec(py, faces), PyArray2::from_owned_array(py, bary)))
    }

    /// The cap points, (n, 3) float64.
    fn cap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::f64_rows(py, &self.map.cap)
    }

    /// The disk points, (n, 2) float64.
    fn plane<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::f64_rows(py, &self.map.plane)
    }
}
