//! The logarithmic parameterisation `s = ln(z/zn)/ln(zf/zn)` (LiSPSM §4.3 as the ideal the
//! perspective warps approximate; Lloyd et al., *Logarithmic Perspective Shadow Maps*, ACM TOG 27(4),
//! 2008; formulas.md §2.9). `ds = dz/(z ln(zf/zn))` makes the perspective error `dp/ds = ln(zf/zn)`
//! constant over the whole range: the least L∞ error any parameterisation can have in this model.

use crate::domain::DepthRange;
use crate::error::ParamError;

/// The shadow-map coordinate `s(z) = ln(z/zn)/ln(zf/zn)`, with `ln(z/zn)` evaluated as
/// `ln_1p((z − zn)/zn)`; `s(zn) = 0` and `s(zf) = 1` exactly. `Err` names `z`.
pub fn s(range: DepthRange, z: f64) -> Result<f64, ParamError> {
    let z = range.check_depth("z", z)?;
    if z == range.far() {
        return Ok(1.0);
    }
    Ok(((z - range.near()) / range.near()).ln_1p() / range.log_ratio())
}

/// The inverse, `z(s) = zn (zf/zn)^s`, exact at `s = 0` and `s = 1`. `Err` names `s` outside
/// `[0, 1]`.
pub fn depth(range: DepthRange, s: f64) -> Result<f64, ParamError> {
    ParamError::require("s", s, (0.0..=1.0).contains(&s), || "in [0, 1]".into())?;
    Ok(range.geometric_lerp(s))
}

/// `ds/dz = 1/(z ln(zf/zn))`. `Err` names `z`.
pub fn ds_dz(range: DepthRange, z: f64) -> Result<f64, ParamError> {
    let z = range.check_depth("z", z)?;
    Ok(1.0 / (z * range.log_ratio()))
}

/// The constant perspective error `dp/ds = (1/z)·dz/ds = ln(zf/zn)` (formulas.md §2.9).
#[must_use]
pub fn dp_ds(range: DepthRange) -> f64 {
    range.log_ratio()
}
