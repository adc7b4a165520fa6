//! The CAD survey's generalised LiSPSM: Barroso & Celes, *Improved Real-Time Shadow Mapping for CAD
//! Models*, SIBGRAPI 2007, doi 10.1109/SIBGRAPI.2007.36 (CAD; formulas.md §4.6–4.7). Its eqs. 10–13
//! generalise LiSPSM's optimum to any light angle γ in the 2-D model of [`crate::model`]; eqs. 14–18
//! replace the equal-error branch by a smooth fall-back to the uniform map below a limit angle.
//!
//! Notation: `n', f'` are the warp frustum's near and far distances, `a = n tan φ`, `b = f tan φ`.

use std::f64::consts::FRAC_PI_2;

use crate::domain::{LightAngle, WarpParameter};
use crate::error::ParamError;
use crate::model::{FrustumModel, ModelCase};

/// `z'(z)`: the distance from P's centre of the view-axis point at eye depth `z` (CAD eq. 10):
/// `n' + a cos γ + (z − n) sin γ` for `γ ≥ φ`, `n' + b cos γ + (z − f) sin γ` for `γ < φ`.
/// `Err` names `n_prime` (must be > 0 and finite) or `z`.
pub fn z_prime(
    model: &FrustumModel,
    gamma: LightAngle,
    n_prime: f64,
    z: f64,
) -> Result<f64, ParamError> {
    let n_prime = check_near("n_prime", n_prime)?;
    let z = model.range().check_depth("z", z)?;
    Ok(n_prime + model.near_plane_offset(gamma, z))
}

/// `f'`: P's far distance (CAD eq. 11): `n' + (a + b) cos γ + (f − n) sin γ` for `γ ≥ φ`,
/// `n' + 2 b cos γ` for `γ < φ`. `Err` names `n_prime`.
pub fn f_prime(model: &FrustumModel, gamma: LightAngle, n_prime: f64) -> Result<f64, ParamError> {
    Ok(check_near("n_prime", n_prime)? + model.warp_depth(gamma))
}

/// The aliasing error along the warp axis (CAD eq. 12; formulas.md §4.6):
///
/// `m_z(z, n', γ) = (res_c/res_l) · 1/(2 tan φ) · z'(z)² (f' − n')/(z n' f' sin γ)`
///
/// with `res_c/res_l` the ratio of the image resolution (in the light–view plane) to the shadow-map
/// resolution (along the warp axis). Evaluated in the cancellation-free form of
/// [`FrustumModel::view_axis_error`], so `n' = ∞` (uniform) is exact; `f64::INFINITY` at `γ = 0`
/// only. `m_z = (res_c/res_l)/2 · F` with GMNPR's F. `Err` names `n_prime`, `z` or
/// `resolution_ratio`.
pub fn m_z(
    model: &FrustumModel,
    gamma: LightAngle,
    n_prime: f64,
    z: f64,
    resolution_ratio: f64,
) -> Result<f64, ParamError> {
    ParamError::finite("resolution_ratio", resolution_ratio)?;
    ParamError::require(
        "resolution_ratio",
        resolution_ratio,
        resolution_ratio > 0.0,
        || "greater than 0".into(),
    )?;
    let depth = model.warp_depth(gamma);
    ParamError::require(
        "n_prime",
        n_prime,
        n_prime / depth >= f64::MIN_POSITIVE,
        || "greater than 0 (infinity means uniform)".into(),
    )?;
    let warp = WarpParameter::from_positive(n_prime / depth);
    let error = model.view_axis_error(gamma, warp, z)?;
    Ok(resolution_ratio / (2.0 * model.half_fov().tan()) * error)
}

/// The equal-error parameter of the wide case (CAD eq. 13, first branch):
/// `n'_1(γ) = (n + √(fn)) sin γ − a cos γ`. Raw: negative for small γ, where it must not be used.
/// `n'_1(π/2) = n_opt` of LiSPSM.
#[must_use]
pub fn n1(model: &FrustumModel, gamma: LightAngle) -> f64 {
    let range = model.range();
    (range.near() + range.geometric_mean()) * gamma.sin() - model.near_half_height() * gamma.cos()
}

/// The equal-error parameter of the narrow case (CAD eq. 13, second branch):
/// `n'_2(γ) = (f + √(fn)) sin γ − b cos γ`. Raw: negative below [`gamma0`], where equal error is
/// impossible.
///
/// Evaluated as `√(fn) sin γ − f sin(φ − γ)/cos φ`: the printed form subtracts two terms of size f
/// to leave one of size `√(fn)`, losing `√(f/n)` ulps near γ_0; this form subtracts terms of size
/// `√(fn)` only.
#[must_use]
pub fn n2(model: &FrustumModel, gamma: LightAngle) -> f64 {
    let range = model.range();
    let phi = model.half_fov();
    range.geometric_mean() * gamma.sin()
        - range.far() * (phi.radians() - gamma.radians()).sin() / phi.cos()
}

/// The equal-error parameter of the branch that applies at γ (CAD eq. 13): [`n1`] for `γ ≥ φ`,
/// [`n2`] below. Raw (may be negative below [`gamma0`]).
#[must_use]
pub fn n_equal_error(model: &FrustumModel, gamma: LightAngle) -> f64 {
    match model.case(gamma) {
        ModelCase::Wide => n1(model, gamma),
        ModelCase::Narrow => n2(model, gamma),
    }
}

/// γ_0 = atan(f tan φ/(f + √(fn))): below it `n'_2 < 0` and no parameter equalises the errors
/// (formulas.md §4.6; 27.693° for f/n = 100, φ = 30°). Equal to GMNPR's θ_0.
#[must_use]
pub fn gamma0(model: &FrustumModel) -> LightAngle {
    let range = model.range();
    angle(
        model
            .far_half_height()
            .atan2(range.far() + range.geometric_mean()),
    )
}

/// γ_lim, the angle at which the near and far faces of the view frustum start to overlap in the
/// light's view (CAD eq. 15 as reconstructed in formulas.md §4.7, OCR error 8):
/// `γ_lim = atan((a + b)/(f − n)) = atan(tan φ (f + n)/(f − n))`, always above φ.
#[must_use]
pub fn gamma_lim(model: &FrustumModel) -> LightAngle {
    let range = model.range();
    angle((model.near_half_height() + model.far_half_height()).atan2(range.length()))
}

/// The fall-back curve `r(γ)` of CAD eq. 16, descending from `r(γ_lim) = 1` to `r(0) = 0`. The
/// paper's own choice (eq. 18) is garbled in the OCR; all three candidates are offered, and every
/// output names the one used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Falloff {
    /// CAD eq. 17, Zhang et al.'s PSM choice: `r = sin((γ/γ_lim)·π/2)`.
    Eq17,
    /// CAD eq. 18 as reconstructed (formulas.md §4.7, OCR error 10, confidence low–medium):
    /// `r = 1 + sin((γ/γ_lim − 1)·π/2) = 1 − cos(πγ/(2γ_lim))`, evaluated as `2 sin²(πγ/(4γ_lim))`.
    Eq18,
    /// The equally admissible alternative reading `r = sin²((γ/γ_lim)·π/2)`.
    SinSquared,
}

impl Falloff {
    /// Every fall-back curve, eq. 18 (the paper's) first.
    pub const ALL: [Self; 3] = [Self::Eq18, Self::Eq17, Self::SinSquared];

    /// A short stable name: `eq18`, `eq17`, `sin2`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Eq17 => "eq17",
            Self::Eq18 => "eq18",
            Self::SinSquared => "sin2",
        }
    }

    /// The curve as a formula, for legends and reports.
    #[must_use]
    pub fn formula(self) -> &'static str {
        match self {
            Self::Eq17 => "r = sin(γ/γlim·π/2) (eq. 17)",
            Self::Eq18 => "r = 1 + sin((γ/γlim − 1)·π/2) (eq. 18, reconstructed)",
            Self::SinSquared => "r = sin²(γ/γlim·π/2)",
        }
    }

    /// The fall-back curve by its [`Self::key`].
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.key() == key)
    }

    /// `r(γ)` for `γ_lim > 0`; 1 at `γ ≥ γ_lim`, 0 at `γ = 0`.
    #[must_use]
    pub fn r(self, gamma: LightAngle, gamma_lim: LightAngle) -> f64 {
        let x = (gamma.radians() / gamma_lim.radians()).min(1.0);
        match self {
            Self::Eq17 => (x * FRAC_PI_2).sin(),
            Self::Eq18 => {
                let h = (x * FRAC_PI_2 / 2.0).sin();
                2.0 * h * h
            }
            Self::SinSquared => {
                let h = (x * FRAC_PI_2).sin();
                h * h
            }
        }
    }
}

/// The CAD survey's final parameter (CAD eq. 16; formulas.md §4.7, OCR error 9):
///
/// `n'(γ) = n'_1(γ)` for `γ_lim ≤ γ ≤ π/2`, and `n'_1(γ_lim)/r(γ)` below, with `r` the chosen
/// [`Falloff`]. Continuous at γ_lim; `f64::INFINITY` (uniform) at `γ = 0`.
#[must_use]
pub fn n_prime(model: &FrustumModel, gamma: LightAngle, falloff: Falloff) -> f64 {
    let limit = gamma_lim(model);
    if gamma.radians() >= limit.radians() {
        n1(model, gamma)
    } else if gamma.is_parallel() {
        f64::INFINITY
    } else {
        n1(model, limit) / falloff.r(gamma, limit)
    }
}

/// [`n_prime`] as λ = n'/(f' − n') = n'/d, the form shared with GMNPR (formulas.md §4.6).
#[must_use]
pub fn warp(model: &FrustumModel, gamma: LightAngle, falloff: Falloff) -> WarpParameter {
    // n'_1 > 0 for every γ ≥ φ, and γ_lim > φ, so n' > 0 on the whole domain.
    WarpParameter::from_positive(n_prime(model, gamma, falloff) / model.warp_depth(gamma))
}

/// An angle from `atan2` of two non-negative numbers, which lies in `[0, π/2]`.
fn angle(radians: f64) -> LightAngle {
    LightAngle::from_valid_radians(radians.clamp(0.0, FRAC_PI_2))
}

fn check_near(name: &'static str, n_prime: f64) -> Result<f64, ParamError> {
    ParamError::finite(name, n_prime)?;
    ParamError::require(name, n_prime, n_prime > 0.0, || "greater than 0".into())
}
