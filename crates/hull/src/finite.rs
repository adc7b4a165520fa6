//! Input checks shared by the constructors: finite values and normalisable directions.

use glam::DVec3;

use crate::error::HullError;

/// `value` if finite, else [`HullError::NonFinite`] naming `parameter`.
pub(crate) fn finite(value: f64, parameter: &'static str) -> Result<f64, HullError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(HullError::NonFinite { parameter })
    }
}

/// `v` if all its coordinates are finite, else [`HullError::NonFinite`] naming `parameter`.
pub(crate) fn finite_vec(v: DVec3, parameter: &'static str) -> Result<DVec3, HullError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(HullError::NonFinite { parameter })
    }
}

/// `v` normalised; [`HullError::NonFinite`] or [`HullError::ZeroVector`] naming `parameter` if it
/// is not finite or cannot be normalised. Vectors are prescaled by a power of two so that tiny and
/// huge (but finite, non-zero) vectors normalise without underflow or overflow.
pub(crate) fn unit_vec(v: DVec3, parameter: &'static str) -> Result<DVec3, HullError> {
    let v = finite_vec(v, parameter)?;
    let largest = v.abs().max_element();
    if largest == 0.0 {
        return Err(HullError::ZeroVector { parameter });
    }
    let unit = (v * power_of_two_inverse(largest)).normalize();
    if unit.is_finite() {
        Ok(unit)
    } else {
        Err(HullError::ZeroVector { parameter })
    }
}

/// A power of two `2^k` with `value · 2^k` in [0.5, 2): multiplying by it is exact (barring
/// subnormals), so it rescales without changing any orientation sign.
pub(crate) fn power_of_two_inverse(value: f64) -> f64 {
    debug_assert!(value > 0.0 && value.is_finite());
    let exponent = value.log2().round().clamp(-1000.0, 1000.0);
    #[expect(
        clippy::cast_possible_truncation,
        reason = "exponent is an integer clamped to ±1000"
    )]
    let exponent = exponent as i32;
    2f64.powi(-exponent)
}
