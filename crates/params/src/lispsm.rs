//! Light Space Perspective Shadow Maps: Wimmer, Scherzer, Purgathofer, EGSR 2004, doi
//! 10.2312/EGWR/EGSR04/143-151 (LiSPSM; formulas.md §2), with the uniform map and PSM as the limits
//! of its one parameter, and the authors' later Δz form.
//!
//! Notation: the eye sees depths `z ∈ [zn, zf]`; the warp frustum P has its projection centre at
//! distance `n` before its near plane and `f = n + zf − zn` before its far plane (view ⟂ light).
//! `n = zn` is PSM; `n → ∞` is the uniform map (pass `f64::INFINITY`). In this crate's normalised
//! terms `λ = n/(zf − zn)` ([`warp_for_near_distance`]).

use crate::domain::{DepthRange, LightAngle, WarpParameter};
use crate::error::ParamError;

/// λ = n/(zf − zn) for the warp near distance `n ∈ (0, ∞]` of the perpendicular case, where P's depth
/// is the eye's depth range. `Err` names `n`.
pub fn warp_for_near_distance(range: DepthRange, n: f64) -> Result<WarpParameter, ParamError> {
    WarpParameter::from_near_distance(n, range.length())
}

/// The shadow-map coordinate of eye depth `z` (LiSPSM eq. 2 with the sign corrected, formulas.md
/// §2.1): `s(z') = f(z' − n)/(z'(f − n))`, `z' = z − zn + n`, so `s(zn) = 0` and `s(zf) = 1` exactly.
/// Evaluated on the unit-depth frustum (§9.1). `Err` names `n` or `z`.
pub fn s(range: DepthRange, n: f64, z: f64) -> Result<f64, ParamError> {
    let warp = warp_for_near_distance(range, n)?;
    let z = range.check_depth("z", z)?;
    Ok(warp.warp_unchecked(range.fraction(z)))
}

/// `ds/dz = f n/((z − zn + n)² (f − n))` (LiSPSM §4.3; formulas.md §2.2), evaluated as
/// `(1/(zf − zn))·(1+μ)/(1+μτ)²`. `Err` names `n` or `z`.
pub fn ds_dz(range: DepthRange, n: f64, z: f64) -> Result<f64, ParamError> {
    let warp = warp_for_near_distance(range, n)?;
    let z = range.check_depth("z", z)?;
    Ok(1.0 / (range.length() * warp.stretch_unchecked(range.fraction(z))))
}

/// The perspective aliasing error along z for view ⟂ light (LiSPSM eq. 3; formulas.md §2.2):
///
/// `dp/ds = (z − zn + n)²/z · (zf − zn)/(n (n + zf − zn))`
///
/// evaluated as `(zf − zn)/z · (λ + τ)²/(λ(λ + 1))` with `τ = (z − zn)/(zf − zn)` so that `n = ∞`
/// gives the uniform map's `(zf − zn)/z` exactly. Convex in z with its one minimum at `z = n − zn`
/// (for `n > zn`). `Err` names `n` or `z`.
pub fn dp_ds(range: DepthRange, n: f64, z: f64) -> Result<f64, ParamError> {
    let warp = warp_for_near_distance(range, n)?;
    let z = range.check_depth("z", z)?;
    Ok(dp_ds_unchecked(range, warp, z))
}

pub(crate) fn dp_ds_unchecked(range: DepthRange, warp: WarpParameter, z: f64) -> f64 {
    range.length() / z * warp.stretch_unchecked(range.fraction(z))
}

/// The error across the light–view plane, `dp/dt`, normalised so that P encloses the view frustum
/// laterally (formulas.md §2.8, correcting LiSPSM §4.3's "ds/dt" and its missing factor):
///
/// `dp/dt = (z − zn + n)/z · zf/(n + zf − zn)`
///
/// PSM (`n = zn`) gives exactly 1; the uniform map (`n = ∞`) gives `zf/z`. `Err` names `n` or `z`.
pub fn dp_dt(range: DepthRange, n: f64, z: f64) -> Result<f64, ParamError> {
    let warp = warp_for_near_distance(range, n)?;
    let z = range.check_depth("z", z)?;
    let tau = range.fraction(z);
    let lambda = warp.lambda();
    let ratio = if lambda >= 1.0 {
        let mu = warp.inverse_lambda();
        (1.0 + tau * mu) / (1.0 + mu)
    } else {
        (lambda + tau) / (lambda + 1.0)
    };
    Ok(range.far() / z * ratio)
}

/// The larger of the errors at `zn` and `zf`, which is the maximum over `[zn, zf]` because eq. 3 is
/// convex in z (formulas.md §2.4). `Err` names `n`.
pub fn max_error(range: DepthRange, n: f64) -> Result<f64, ParamError> {
    let warp = warp_for_near_distance(range, n)?;
    Ok(dp_ds_unchecked(range, warp, range.near()).max(dp_ds_unchecked(range, warp, range.far())))
}

/// The uniform (focused, unwarped) map's error, the limit `n → ∞` of eq. 3 (LiSPSM §4.3):
/// `dp/ds = (zf − zn)/z`. `Err` names `z`.
pub fn uniform_dp_ds(range: DepthRange, z: f64) -> Result<f64, ParamError> {
    let z = range.check_depth("z", z)?;
    Ok(range.length() / z)
}

/// PSM's error, eq. 3 at `n = zn` (LiSPSM §4.3): `dp/ds = z (zf − zn)/(zn zf)`. `Err` names `z`.
pub fn psm_dp_ds(range: DepthRange, z: f64) -> Result<f64, ParamError> {
    let z = range.check_depth("z", z)?;
    Ok(z / range.near() * (range.length() / range.far()))
}

/// `n_opt = zn + √(zn zf)` (LiSPSM §4.3; formulas.md §2.5): the n that makes eq. 3 equal at `zn`
/// and `zf`, which is its L∞ optimum. Equals Lloyd's `(zf − zn)/(√(zf/zn) − 1)`.
#[must_use]
pub fn n_opt(range: DepthRange) -> f64 {
    range.near() + range.geometric_mean()
}

/// The maximum error at `n_opt`: `(zf − zn)/√(zn zf) = √(zf/zn) − √(zn/zf)` (formulas.md §2.5).
#[must_use]
pub fn max_error_at_n_opt(range: DepthRange) -> f64 {
    range.length() / range.geometric_mean()
}

/// The minimum error at `n_opt`, reached at `z* = √(zn zf)`:
/// `4(√zf − √zn)/(√zf + √zn)`, evaluated as `4(zf − zn)/(√zf + √zn)²` (formulas.md §2.5).
#[must_use]
pub fn min_error_at_n_opt(range: DepthRange) -> f64 {
    let sum = range.near().sqrt() + range.far().sqrt();
    4.0 * range.length() / (sum * sum)
}

/// Where eq. 3 has its one minimum over `z > 0`: `z* = n − zn` (formulas.md §2.4), or `None` when
/// `n ≤ zn` (the error then increases over the whole range) or `n = ∞` (it decreases). `Err` names
/// `n`.
pub fn error_minimum_depth(range: DepthRange, n: f64) -> Result<Option<f64>, ParamError> {
    warp_for_near_distance(range, n)?;
    Ok((n > range.near() && n.is_finite()).then(|| n - range.near()))
}

/// The paper's general-angle parameter `n'_opt = n_opt / sin γ` (LiSPSM §4.4). A heuristic, not
/// an optimum (formulas.md §2.6): it only forces convergence to the uniform map as `γ → 0`.
/// Returns `f64::INFINITY` (uniform) at `γ = 0`.
#[must_use]
pub fn n_opt_general(range: DepthRange, gamma: LightAngle) -> f64 {
    if gamma.is_parallel() {
        f64::INFINITY
    } else {
        n_opt(range) / gamma.sin()
    }
}

/// The Δz variant (LiSPSM §4.4; formulas.md §2.7): `n_opt` with `zf` replaced by `z0 + Δz`,
/// `Δz = d sin γ`, then divided by `sin γ`:
///
/// `n' = (z0 + √(z0 (z0 + d sin γ)))/sin γ`
///
/// where `z0` is the eye depth of B's nearest point and `d` the depth of the warp frustum P along
/// light-space depth (the extent of B perpendicular to the light). Returns `f64::INFINITY` (uniform) at
/// `γ = 0`. `Err` names `z0` or `depth`.
pub fn n_delta_z(z0: f64, depth: f64, gamma: LightAngle) -> Result<f64, ParamError> {
    check_positive("z0", z0)?;
    check_positive("depth", depth)?;
    if gamma.is_parallel() {
        return Ok(f64::INFINITY);
    }
    let z1 = z0 + depth * gamma.sin();
    Ok((z0 + z0.sqrt() * z1.sqrt()) / gamma.sin())
}

/// The authors' 2006 general form `n = d/(√(z1/z0) − 1)` (formulas.md §2.7, §7), for a warp
/// frustum of depth `d` over eye depths `[z0, z1]`, in its stable form (formulas.md §9.2):
///
/// `n = d (z0 + √(z0 z1))/(z1 − z0)`
///
/// where `z1 − z0` is exact for the nearly equal depths at which the printed form is 0/0. With
/// `z1 = z0 + d sin γ` it equals [`n_delta_z`]. Returns `f64::INFINITY` (uniform) when `z1 = z0`.
/// `Err` names `depth`, `z0` or `z1`.
pub fn n_general(depth: f64, z0: f64, z1: f64) -> Result<f64, ParamError> {
    check_positive("depth", depth)?;
    check_positive("z0", z0)?;
    ParamError::finite("z1", z1)?;
    ParamError::require("z1", z1, z1 >= z0, || format!("at least z0 ({z0})"))?;
    if z1 == z0 {
        return Ok(f64::INFINITY);
    }
    Ok(depth * (z0 + z0.sqrt() * z1.sqrt()) / (z1 - z0))
}

fn check_positive(name: &'static str, value: f64) -> Result<f64, ParamError> {
    ParamError::finite(name, value)?;
    ParamError::require(name, value, value > 0.0, || "greater than 0".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn range(near: f64, far: f64) -> DepthRange {
        DepthRange::new(near, far).unwrap()
    }

    #[test]
    fn warp_maps_the_range_onto_the_unit_interval() {
        let r = range(1.0, 100.0);
        for n in [1.0, 11.0, 1e6, f64::INFINITY] {
            assert_eq!(s(r, n, 1.0).unwrap(), 0.0);
            assert_eq!(s(r, n, 100.0).unwrap(), 1.0);
        }
    }

    #[test]
    fn bad_inputs_name_the_parameter() {
        let r = range(1.0, 100.0);
        assert_eq!(dp_ds(r, 0.0, 2.0).unwrap_err().parameter(), "n");
        assert_eq!(dp_ds(r, f64::NAN, 2.0).unwrap_err().parameter(), "n");
        assert_eq!(dp_ds(r, 11.0, 0.5).unwrap_err().parameter(), "z");
        assert_eq!(dp_ds(r, 11.0, f64::NAN).unwrap_err().parameter(), "z");
        assert_eq!(n_general(1.0, 2.0, 1.0).unwrap_err().parameter(), "z1");
        assert_eq!(
            n_delta_z(0.0, 1.0, LightAngle::PERPENDICULAR)
                .unwrap_err()
                .parameter(),
            "z0"
        );
    }

    #[test]
    fn parallel_light_gives_the_uniform_map() {
        let parallel = LightAngle::from_degrees(0.0).unwrap();
        assert_eq!(n_opt_general(range(1.0, 100.0), parallel), f64::INFINITY);
        assert_eq!(n_delta_z(1.0, 50.0, parallel).unwrap(), f64::INFINITY);
        assert_eq!(n_general(50.0, 1.0, 1.0).unwrap(), f64::INFINITY);
    }

    #[test]
    fn minimum_location() {
        let r = range(1.0, 100.0);
        assert_eq!(error_minimum_depth(r, 11.0).unwrap(), Some(10.0));
        assert_eq!(error_minimum_depth(r, 1.0).unwrap(), None);
        assert_eq!(error_minimum_depth(r, f64::INFINITY).unwrap(), None);
    }
}
