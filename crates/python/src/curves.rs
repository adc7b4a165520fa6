//! `shadowlab._native` curves: the closed-form figures of `shadowlab-curves` as their tables.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use shadowlab_curves::{CurveConfig, FigureName, compute};

use crate::params::{by_key, value_error};

/// The figure `name` (`lispsm-fig6`, `cad-fig7`, `gmnpr-fig5`, `gmnpr-fig6`, `partitions`,
/// `max-error-vs-angle`) for the papers' configuration (`near`, `far`, the full field of view in
/// degrees): its title and its table's columns and rows, the numbers `shadowlab curves` writes to
/// the figure's CSV.
#[pyfunction]
#[pyo3(signature = (name, near=1.0, far=100.0, fov_degrees=60.0))]
pub(crate) fn figure(
    py: Python<'_>,
    name: &str,
    near: f64,
    far: f64,
    fov_degrees: f64,
) -> PyResult<(String, Vec<String>, Vec<Vec<f64>>)> {
    let figure = by_key("name", name, &FigureName::ALL, FigureName::key)?;
    let config = CurveConfig::new(near, far, fov_degrees).map_err(|e| value_error(&e))?;
    let curves = py
        .detach(|| compute(figure, &config))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok((
        curves.figure.title.clone(),
        curves.table.columns().to_vec(),
        curves.table.rows().to_vec(),
    ))
}
