//! `shadowlab._native` params: the closed forms of `shadowlab-params`, evaluated element by element
//! over equally long 1-D arrays (the Python package broadcasts its arguments to one shape first,
//! as numpy does, and reshapes the result). A value outside a formula's domain raises `ValueError`
//! naming the parameter, with the same domains as the Rust types; no NaN is returned for bad
//! input.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use shadowlab_params::bias::DepthBias;
use shadowlab_params::cad::{self, Falloff};
use shadowlab_params::splits::SplitScheme;
use shadowlab_params::{
    DepthRange, FrustumModel, HalfFov, LightAngle, ParamError, ParameterRule, WarpParameter, gmnpr,
    lispsm, vsm,
};

/// A `ParamError` as Python's `ValueError`, its message starting with the parameter's name.
pub(crate) fn value_error(error: &ParamError) -> PyErr {
    PyValueError::new_err(format!("{}: {error}", error.parameter()))
}

/// The item of `all` whose key (`key_of`) is `key`, or a `ValueError` naming `what` and listing the
/// known keys.
pub(crate) fn by_key<T: Copy>(
    what: &str,
    key: &str,
    all: &[T],
    key_of: impl Fn(T) -> &'static str,
) -> PyResult<T> {
    all.iter()
        .copied()
        .find(|t| key_of(*t) == key)
        .ok_or_else(|| {
            let known: Vec<&str> = all.iter().map(|t| key_of(*t)).collect();
            PyValueError::new_err(format!(
                "{what}: unknown {key:?}; known: {}",
                known.join(", ")
            ))
        })
}

/// `f` of the `i`-th elements of `args` for every `i`, the GIL released while it runs.
fn elementwise<'py, const N: usize>(
    py: Python<'py>,
    args: [PyReadonlyArray1<'py, f64>; N],
    f: impl Fn([f64; N]) -> Result<f64, ParamError> + Send + Sync,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let slices: Vec<&[f64]> = args
        .iter()
        .map(|a| a.as_slice())
        .collect::<Result<_, _>>()?;
    let len = slices.first().map_or(0, |s| s.len());
    if slices.iter().any(|s| s.len() != len) {
        return Err(PyValueError::new_err(
            "arguments: the arrays must have one length (broadcast them first)",
        ));
    }
    let values = py
        .detach(|| {
            (0..len)
                .map(|i| f(std::array::from_fn(|k| slices[k][i])))
                .collect::<Result<Vec<f64>, ParamError>>()
        })
        .map_err(|e| value_error(&e))?;
    Ok(PyArray1::from_vec(py, values))
}

/// A `#[pyfunction]` over equally long 1-D arrays, each element of the result `body` of the
/// arguments' elements ([`elementwise`]).
macro_rules! elementwise_fn {
    ($(#[$meta:meta])* $name:ident($($arg:ident),+) => $body:expr) => {
        $(#[$meta])*
        #[pyfunction]
        pub(crate) fn $name<'py>(
            py: Python<'py>,
            $($arg: PyReadonlyArray1<'py, f64>),+
        ) -> PyResult<Bound<'py, PyArray1<f64>>> {
            // Each argument's name is its array's outside the closure and its element inside.
            elementwise(py, [$($arg),+], |[$($arg),+]| $body)
        }
    };
}

/// The 2-D view-frustum model of CAD and GMNPR: depths `near`, `far`, half the field of view
/// `half_fov` (radians).
fn model(near: f64, far: f64, half_fov: f64) -> Result<FrustumModel, ParamError> {
    Ok(FrustumModel::new(
        DepthRange::new(near, far)?,
        HalfFov::from_radians(half_fov)?,
    ))
}

elementwise_fn! {
    /// LiSPSM eq. 3 (formulas.md §2.3): `dp/ds` at eye depth `z` for the near distance `n`.
    lispsm_dp_ds(near, far, n, z) => {
        lispsm::dp_ds(DepthRange::new(near, far)?, n, z)
    }
}

elementwise_fn! {
    /// LiSPSM §4.4: `n_opt = n + √(f n)` (the parameter at γ = 90°).
    lispsm_n_opt(near, far) => {
        Ok(lispsm::n_opt(DepthRange::new(near, far)?))
    }
}

elementwise_fn! {
    /// LiSPSM §4.4 at any angle: `n_opt = (n + √(f n))/sin γ`.
    lispsm_n_opt_general(near, far, gamma) => {
        Ok(lispsm::n_opt_general(
            DepthRange::new(near, far)?,
            LightAngle::from_radians(gamma)?,
        ))
    }
}

elementwise_fn! {
    /// LiSPSM's Δz parameter (formulas.md §2.6): `n = (z0 + √(z0 (z0 + d sin γ)))/sin γ`.
    lispsm_n_delta_z(z0, depth, gamma) => {
        lispsm::n_delta_z(z0, depth, LightAngle::from_radians(gamma)?)
    }
}

elementwise_fn! {
    /// LiSPSM eq. 3's largest `dp/ds` over `[near, far]` for the near distance `n`.
    lispsm_max_error(near, far, n) => {
        lispsm::max_error(DepthRange::new(near, far)?, n)
    }
}

/// CAD eq. 12: the aliasing error `m_z` along the warp axis at eye depth `z`.
#[pyfunction]
#[expect(
    clippy::too_many_arguments,
    reason = "the formula's inputs, one array each"
)]
pub(crate) fn cad_m_z<'py>(
    py: Python<'py>,
    near: PyReadonlyArray1<'py, f64>,
    far: PyReadonlyArray1<'py, f64>,
    half_fov: PyReadonlyArray1<'py, f64>,
    gamma: PyReadonlyArray1<'py, f64>,
    n_prime: PyReadonlyArray1<'py, f64>,
    z: PyReadonlyArray1<'py, f64>,
    resolution_ratio: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    elementwise(
        py,
        [near, far, half_fov, gamma, n_prime, z, resolution_ratio],
        |[near, far, half_fov, gamma, n_prime, z, ratio]| {
            cad::m_z(
                &model(near, far, half_fov)?,
                LightAngle::from_radians(gamma)?,
                n_prime,
                z,
                ratio,
            )
        },
    )
}

/// CAD eq. 16: `n′(γ)` with the fall-back curve `falloff` (`eq18`, `eq17`, `sin2`).
#[pyfunction]
pub(crate) fn cad_n_prime<'py>(
    py: Python<'py>,
    falloff: &str,
    near: PyReadonlyArray1<'py, f64>,
    far: PyReadonlyArray1<'py, f64>,
    half_fov: PyReadonlyArray1<'py, f64>,
    gamma: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let falloff = by_key("falloff", falloff, &Falloff::ALL, Falloff::key)?;
    elementwise(
        py,
        [near, far, half_fov, gamma],
        |[near, far, half_fov, gamma]| {
            Ok(cad::n_prime(
                &model(near, far, half_fov)?,
                LightAngle::from_radians(gamma)?,
                falloff,
            ))
        },
    )
}

elementwise_fn! {
    /// GMNPR eq. 4 (CAD eq. 13): the equal-error λ, `F(λ, θ, near) = F(λ, θ, far)`, of the branch
    /// that applies at θ; below θ₀ no λ equalises the errors, and an angle there raises `ValueError`
    /// naming `gamma` (the raw value is zero or negative).
    gmnpr_lambda_equal_error(near, far, half_fov, gamma) => {
            let lambda = gmnpr::lambda_equal_error(
                &model(near, far, half_fov)?,
                LightAngle::from_radians(gamma)?,
            );
            if lambda > 0.0 {
                Ok(lambda)
            } else {
                Err(ParamError::OutOfDomain {
                    name: "gamma",
                    value: gamma,
                    requirement: "above θ₀, where an equal-error λ exists".into(),
                })
            }
        }
}

elementwise_fn! {
    /// GMNPR eqs. 1–2: the normalised perspective error `F(λ, θ, z)`; `lam = inf` is the uniform map.
    gmnpr_error(near, far, half_fov, gamma, lam, z) => {
            gmnpr::error(
                &model(near, far, half_fov)?,
                LightAngle::from_radians(gamma)?,
                WarpParameter::from_lambda(lam)?,
                z,
            )
        }
}

elementwise_fn! {
    /// GMNPR: F's largest value over `[near, far]` (F is convex in z, formulas.md §5.7).
    gmnpr_max_error(near, far, half_fov, gamma, lam) => {
            Ok(gmnpr::max_error(
                &model(near, far, half_fov)?,
                LightAngle::from_radians(gamma)?,
                WarpParameter::from_lambda(lam)?,
            ))
        }
}

/// The warp parameter λ a rule picks (`shadowlab_params::ParameterRule`: `uniform`, `lispsm`,
/// `lispsm_dz`, `cad`, `cad_eq17`, `cad_sin2`, `gmnpr`, `glpr`, `minimax`); `inf` for the
/// uniform map. A rule undefined at an angle (GLPR for γ ≤ φ) raises `ValueError` naming `gamma`.
#[pyfunction]
pub(crate) fn rule_lambda<'py>(
    py: Python<'py>,
    rule: &str,
    near: PyReadonlyArray1<'py, f64>,
    far: PyReadonlyArray1<'py, f64>,
    half_fov: PyReadonlyArray1<'py, f64>,
    gamma: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let rule = by_key("rule", rule, &ParameterRule::ALL, ParameterRule::key)?;
    elementwise(
        py,
        [near, far, half_fov, gamma],
        |[near, far, half_fov, gamma]| {
            let angle = LightAngle::from_radians(gamma)?;
            rule.warp(&model(near, far, half_fov)?, angle)
                .map(WarpParameter::lambda)
                .ok_or(ParamError::OutOfDomain {
                    name: "gamma",
                    value: gamma,
                    requirement: format!("an angle where the {} rule is defined", rule.key()),
                })
        },
    )
}

/// The boundaries of a z-partition of `[near, far]` into `partitions` parts (CAD eqs. 5 and 19,
/// the practical split): `scheme` is `uniform`, `logarithmic`, `practical` (with `weight`) or
/// `adaptive` (with `delta` and `gamma`).
#[pyfunction]
#[pyo3(signature = (scheme, near, far, partitions, weight=0.5, delta=2.0, gamma=std::f64::consts::FRAC_PI_2))]
#[expect(
    clippy::too_many_arguments,
    reason = "each scheme's own parameters, by keyword"
)]
pub(crate) fn split_boundaries<'py>(
    py: Python<'py>,
    scheme: &str,
    near: f64,
    far: f64,
    partitions: usize,
    weight: f64,
    delta: f64,
    gamma: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let scheme = match scheme {
        "uniform" => SplitScheme::Uniform,
        "logarithmic" => SplitScheme::Logarithmic,
        "practical" => SplitScheme::Practical { weight },
        "adaptive" => SplitScheme::Adaptive {
            delta,
            gamma: LightAngle::from_radians(gamma).map_err(|e| value_error(&e))?,
        },
        other => {
            return Err(PyValueError::new_err(format!(
                "scheme: unknown {other:?}; known: uniform, logarithmic, practical, adaptive"
            )));
        }
    };
    let range = DepthRange::new(near, far).map_err(|e| value_error(&e))?;
    let boundaries = scheme
        .boundaries(range, partitions)
        .map_err(|e| value_error(&e))?;
    Ok(PyArray1::from_vec(py, boundaries))
}

/// The CAD survey's eq. 1 and Table 1: the stored depth `z_map = z1 + z_bias(z1, z2)` of the depth
/// bias `method` (`constant` with `amount` its offset, `second-depth`, `midpoint`, `dual-depth`
/// with `amount` its cap), `z1` and `z2` the first and second surfaces' depths (`z2 = inf`: none).
#[pyfunction]
pub(crate) fn bias_z_map<'py>(
    py: Python<'py>,
    method: &str,
    z1: PyReadonlyArray1<'py, f64>,
    z2: PyReadonlyArray1<'py, f64>,
    amount: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let bias = |amount: f64| match method {
        "constant" => Ok(DepthBias::Constant { offset: amount }),
        "second-depth" => Ok(DepthBias::SecondDepth),
        "midpoint" => Ok(DepthBias::Midpoint),
        "dual-depth" => Ok(DepthBias::DualDepth { max_bias: amount }),
        _ => Err(()),
    };
    if bias(0.0).is_err() {
        return Err(PyValueError::new_err(format!(
            "method: unknown {method:?}; known: constant, second-depth, midpoint, dual-depth"
        )));
    }
    elementwise(py, [z1, z2, amount], |[z1, z2, amount]| {
        bias(amount).expect("the method was checked").z_map(z1, z2)
    })
}

elementwise_fn! {
    /// VSM (the CAD survey's eq. 2 on shifted moments): the Chebyshev upper bound on the lit fraction
    /// at receiver depth `t` of depths with mean `mean` and variance `variance` (floored at
    /// `min_variance`).
    vsm_lit_fraction(mean, variance, t, min_variance) => {
            // Moments about the mean itself: m1 = 0, m2 = the variance.
            vsm::ShiftedMoments::new(mean, 0.0, variance)?.lit_fraction(t, min_variance)
        }
}
