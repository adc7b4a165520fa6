//! Validation of procedural parameters: each check names the parameter and the rule it breaks.

use super::ShapeError;
use crate::procedural::MAX_TRIANGLES;

/// `value` if it is finite and > 0.
pub(super) fn positive(parameter: &'static str, value: f64) -> Result<f64, ShapeError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ShapeError::InvalidParameter {
            parameter,
            value,
            requirement: "finite and > 0",
        })
    }
}

/// `value` if it is finite and ≥ 0.
pub(super) fn non_negative(parameter: &'static str, value: f64) -> Result<f64, ShapeError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ShapeError::InvalidParameter {
            parameter,
            value,
            requirement: "finite and ≥ 0",
        })
    }
}

/// `value` if it is at least `minimum`; `requirement` states the rule, e.g. `"at least 3"`.
pub(super) fn at_least(
    parameter: &'static str,
    value: u32,
    minimum: u32,
    requirement: &'static str,
) -> Result<u32, ShapeError> {
    if value >= minimum {
        Ok(value)
    } else {
        Err(ShapeError::InvalidParameter {
            parameter,
            value: f64::from(value),
            requirement,
        })
    }
}

/// Checks a triangle count against [`MAX_TRIANGLES`]. Counts are computed in u128, where products
/// of a few u32 parameters cannot overflow.
pub(super) fn triangle_budget(shape: &'static str, count: u128) -> Result<(), ShapeError> {
    if count > u128::from(MAX_TRIANGLES) {
        Err(ShapeError::TooManyTriangles {
            shape,
            count,
            max: MAX_TRIANGLES,
        })
    } else {
        Ok(())
    }
}
