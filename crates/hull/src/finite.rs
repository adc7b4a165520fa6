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

/// The power of two that brings `largest`, a magnitude (≥ 0), near 1 ([`power_of_two_inverse`]);
/// 1 for 0.
pub(crate) fn rescale_for(largest: f64) -> f64 {
    if largest > 0.0 {
        power_of_two_inverse(largest)
    } else {
        1.0
    }
}

/// Coordinates smaller than this, after rescaling the largest to about 1 ([`power_of_two_inverse`]),
/// are taken as zero by the exact orientation predicates ([`flush_tiny`]). `robust::orient2d` and
/// `orient3d` are exact only while none of their products and error terms underflow; products of
/// coordinates of at least 2^-300 stay above 2^-600 and their error terms far above the subnormals.
/// Found by the hull fuzzer: points spanning 1.6e233 to 8.3e-275 gave a non-convex "hull".
pub(crate) const ORIENTATION_FLOOR: f64 = f64::from_bits((1023 - 300) << 52);

/// `value`, or 0 when its magnitude is below [`ORIENTATION_FLOOR`]: the perturbation that keeps
/// the orientation predicates exact on rescaled coordinates. The predicates then decide the exact
/// hull of the flushed points, the same way every time.
pub(crate) fn flush_tiny(value: f64) -> f64 {
    if value.abs() < ORIENTATION_FLOOR {
        0.0
    } else {
        value
    }
}

#[cfg(test)]
mod floor_tests {
    use super::*;

    #[test]
    fn the_floor_is_two_to_the_minus_300() {
        assert_eq!(ORIENTATION_FLOOR, 2f64.powi(-300));
        assert_eq!(flush_tiny(2f64.powi(-301)), 0.0);
        assert_eq!(flush_tiny(-2f64.powi(-300)), -2f64.powi(-300));
    }
}
