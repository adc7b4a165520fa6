//! shadowlab from Python: the `shadowlab._native` extension module that the `shadowlab` Python
//! package wraps (`crates/python/python/shadowlab`). Each function here is a thin, typed edge over
//! the workspace's crates: numbers and numpy arrays in, numpy arrays and plain Python values out,
//! the GIL released while the Rust code runs. Errors of bad input are Python's `ValueError`,
//! naming the parameter.

mod arrays;
mod curves;
mod params;
mod scene;
mod study;

use pyo3::prelude::*;

/// The native module: `shadowlab._native`.
#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add_function(wrap_pyfunction!(params::lispsm_dp_ds, module)?)?;
    module.add_function(wrap_pyfunction!(params::lispsm_n_opt, module)?)?;
    module.add_function(wrap_pyfunction!(params::lispsm_n_opt_general, module)?)?;
    module.add_function(wrap_pyfunction!(params::lispsm_n_delta_z, module)?)?;
    module.add_function(wrap_pyfunction!(params::lispsm_max_error, module)?)?;
    module.add_function(wrap_pyfunction!(params::cad_m_z, module)?)?;
    module.add_function(wrap_pyfunction!(params::cad_n_prime, module)?)?;
    module.add_function(wrap_pyfunction!(params::gmnpr_error, module)?)?;
    module.add_function(wrap_pyfunction!(params::gmnpr_max_error, module)?)?;
    module.add_function(wrap_pyfunction!(params::gmnpr_lambda_equal_error, module)?)?;
    module.add_function(wrap_pyfunction!(params::rule_lambda, module)?)?;
    module.add_function(wrap_pyfunction!(params::split_boundaries, module)?)?;
    module.add_function(wrap_pyfunction!(params::bias_z_map, module)?)?;
    module.add_function(wrap_pyfunction!(params::vsm_lit_fraction, module)?)?;
    module.add_function(wrap_pyfunction!(curves::figure, module)?)?;
    module.add_class::<scene::Scene>()?;
    module.add_function(wrap_pyfunction!(study::plan, module)?)?;
    module.add_function(wrap_pyfunction!(study::render_map, module)?)?;
    module.add_function(wrap_pyfunction!(study::eye_pass, module)?)?;
    module.add_function(wrap_pyfunction!(study::truth, module)?)?;
    module.add_function(wrap_pyfunction!(study::analyze, module)?)?;
    Ok(())
}
