//! Values of the workspace's types as numpy arrays.

use glam::{DMat4, DVec3};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

/// A 4 × 4 matrix as a numpy array, row by row (`m[i, j]` is row `i`, column `j`).
pub(crate) fn matrix<'py>(py: Python<'py>, m: &DMat4) -> PyResult<Bound<'py, PyArray2<f64>>> {
    PyArray1::from_vec(py, m.transpose().to_cols_array().to_vec()).reshape([4, 4])
}

/// Vectors as an N × 3 array.
pub(crate) fn vectors<'py>(py: Python<'py>, values: &[DVec3]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = values.iter().flat_map(|v| v.to_array()).collect();
    PyArray1::from_vec(py, flat)
        .reshape([values.len(), 3])
        .expect("N × 3 values")
}
