//! Generalized Minimum-Norm Perspective Shadow Maps: *Theory to Practice: Generalized Minimum-Norm
//! Perspective Shadow Maps*, ICEC 2007, LNCS 4740, pp. 66–78 (GMNPR; formulas.md §5), with the
//! generalized linear reparameterization GLPR it compares against, and the true minimax parameter of
//! formulas.md §5.8, which none of the papers has.
//!
//! GMNPR writes θ for the light angle this crate calls γ ([`LightAngle`]); functions take it as
//! `gamma` and errors name it so. `T = tan φ/tan θ` is never formed: every formula is evaluated in a
//! division-free sin/cos form (formulas.md §9.6), so θ = π/2 and θ → 0 are exact.

use crate::cad;
use crate::domain::{LightAngle, WarpParameter};
use crate::error::ParamError;
use crate::model::{FrustumModel, ModelCase};

/// GMNPR's normalised perspective error `F = (1/tan φ)·(1/z)·dz/ds` (eq. 1, the screen spanning
/// `[−1, 1]`) for the warp λ at angle θ (eq. 2):
///
/// `F(λ, θ, z) = ψ(λ, θ) (z + ϕ(λ, θ))²/z`
///
/// evaluated in the form of [`FrustumModel::view_axis_error`] (formulas.md §9.1): exact for the
/// uniform map (λ = ∞), where `F = d/(z tan φ sin θ)`. `f64::INFINITY` at `θ = 0` only. `Err` names `z`.
pub fn error(
    model: &FrustumModel,
    gamma: LightAngle,
    warp: WarpParameter,
    z: f64,
) -> Result<f64, ParamError> {
    Ok(model.view_axis_error(gamma, warp, z)? / model.half_fov().tan())
}

/// `max over z ∈ [n, f]` of [`error`]: F is convex in z (formulas.md §5.7), so this is
/// `max(F(n), F(f))`. `f64::INFINITY` at `θ = 0` only.
#[must_use]
pub fn max_error(model: &FrustumModel, gamma: LightAngle, warp: WarpParameter) -> f64 {
    model.max_view_axis_error(gamma, warp) / model.half_fov().tan()
}

/// ψ(λ, θ) of GMNPR eq. 2 exactly as printed (formulas.md §5.1), with `T = tan φ/tan θ`:
/// `1/(tan φ · D · λ(λ+1))`, `D = f − n + (f + n) T` for `θ ≥ φ`;
/// `(1/tan φ)·tan θ/(2 f λ(λ+1) tan φ)` for `θ < φ`.
/// For a finite `λ > 0` and `θ > 0`; `Err` names `lambda` or `gamma`.
pub fn psi(model: &FrustumModel, gamma: LightAngle, lambda: f64) -> Result<f64, ParamError> {
    let lambda = check_lambda(lambda)?;
    let t = t_ratio(model, gamma)?;
    let tan_phi = model.half_fov().tan();
    let range = model.range();
    Ok(match model.case(gamma) {
        ModelCase::Wide => {
            let d = range.length() + (range.far() + range.near()) * t;
            1.0 / (tan_phi * d * lambda * (lambda + 1.0))
        }
        ModelCase::Narrow => 1.0 / tan_phi / (2.0 * range.far() * lambda * (lambda + 1.0)) / t,
    })
}

/// ϕ(λ, θ) of GMNPR eq. 2 exactly as printed: `D λ + n T − n` for `θ ≥ φ`,
/// `f (2λ + 1) T − f` for `θ < φ`. F's one minimum over `z > 0` is at `z = ϕ` when `ϕ > 0`
/// (formulas.md §5.7). For a finite `λ > 0` and `θ > 0`; `Err` names `lambda` or `gamma`.
pub fn phi(model: &FrustumModel, gamma: LightAngle, lambda: f64) -> Result<f64, ParamError> {
    let lambda = check_lambda(lambda)?;
    let t = t_ratio(model, gamma)?;
    let range = model.range();
    Ok(match model.case(gamma) {
        ModelCase::Wide => {
            let d = range.length() + (range.far() + range.near()) * t;
            d * lambda + range.near() * t - range.near()
        }
        ModelCase::Narrow => range.far() * (2.0 * lambda + 1.0) * t - range.far(),
    })
}

/// μ(θ) of GMNPR §3 (formulas.md §5.2): the near point's position through the warp frustum's depth,
/// `τ(n)`; `F(λ, θ, n) ∝ (λ + μ)²/(λ(λ+1))`.
#[must_use]
pub fn mu(model: &FrustumModel, gamma: LightAngle) -> f64 {
    model.depth_fraction(gamma, model.range().near())
}

/// ν(θ) of GMNPR §3: the far point's position `τ(f)`; `1/2` in the narrow case.
#[must_use]
pub fn nu(model: &FrustumModel, gamma: LightAngle) -> f64 {
    model.depth_fraction(gamma, model.range().far())
}

/// λ1(θ), the equal-error parameter of GMNPR eq. 4 for `θ ∈ [φ, π/2]`, in its division-free form
/// (formulas.md §5.3):
/// `λ1 = ((n + √(fn)) sin θ − n tan φ cos θ)/((f − n) sin θ + (f + n) tan φ cos θ)`.
/// Equals `n'_1/(f' − n')` of CAD eq. 13. Raw: the formula is evaluated at any θ, but means
/// something only on `[φ, π/2]`.
#[must_use]
pub fn lambda1(model: &FrustumModel, gamma: LightAngle) -> f64 {
    let range = model.range();
    let (sin, cos) = (gamma.sin(), gamma.cos());
    let numerator = (range.near() + range.geometric_mean()) * sin - model.near_half_height() * cos;
    let depth = range.length() * sin + (model.near_half_height() + model.far_half_height()) * cos;
    numerator / depth
}

/// λ2(θ), the equal-error parameter of GMNPR eq. 4 for `θ ∈ [0, φ]`:
/// `λ2 = (f + √(fn))/(2f) · tan θ/tan φ − 1/2`, evaluated as `n'_2/(2 f tan φ cos θ)` with the
/// stable `n'_2` of [`cad::n2`]. Raw: negative below θ_0, where no λ equalises the errors
/// (formulas.md §9.5); `±∞` at θ = π/2, far outside its branch.
#[must_use]
pub fn lambda2(model: &FrustumModel, gamma: LightAngle) -> f64 {
    cad::n2(model, gamma) / (2.0 * model.far_half_height() * gamma.cos())
}

/// The equal-error λ of the branch that applies at θ (GMNPR eq. 4): `F(λ, θ, n) = F(λ, θ, f)`.
/// Evaluated as `n'/d` with CAD's `n'_1` or `n'_2` ([`cad::n_equal_error`]; the two papers' forms
/// are the same, formulas.md §5.3), which is [`lambda1`] for `θ ≥ φ` and [`lambda2`] below. Raw:
/// may be zero or negative below θ_0.
#[must_use]
pub fn lambda_equal_error(model: &FrustumModel, gamma: LightAngle) -> f64 {
    cad::n_equal_error(model, gamma) / model.warp_depth(gamma)
}

/// λ2*(θ) = λ1(φ)/tan(πθ/(4φ)) = √(fn)/(2f)/tan(πθ/(4φ)) (GMNPR eq. 7), GMNPR's replacement for
/// λ2 on `[0, φ]`: continuous with λ1 at φ and `→ ∞` (uniform) as `θ → 0`. `None` above φ, where it is
/// not defined; `UNIFORM` at θ = 0.
#[must_use]
pub fn lambda2_star(model: &FrustumModel, gamma: LightAngle) -> Option<WarpParameter> {
    let phi = model.half_fov().radians();
    if gamma.radians() > phi {
        return None;
    }
    let range = model.range();
    let at_phi = 0.5 * (range.near() / range.far()).sqrt();
    let x = std::f64::consts::FRAC_PI_4 * gamma.radians() / phi;
    // λ1(φ)·cos x/sin x: the division by sin x gives +∞ at θ = 0 exactly.
    Some(WarpParameter::from_positive(at_phi * x.cos() / x.sin()))
}

/// λ_GMNPR (GMNPR eq. 8): λ1(θ) on `[φ, π/2]`, λ2*(θ) below; `UNIFORM` at θ = 0.
#[must_use]
pub fn lambda_gmnpr(model: &FrustumModel, gamma: LightAngle) -> WarpParameter {
    match lambda2_star(model, gamma) {
        Some(warp) if model.case(gamma) == ModelCase::Narrow => warp,
        // λ1 > 0 on [φ, π/2]: its numerator is √(fn) sin φ at φ and grows with θ.
        _ => WarpParameter::from_positive(lambda1(model, gamma)),
    }
}

/// λ_LiSPSM (GMNPR eq. 9): LiSPSM's `n_opt/sin θ` normalised by the model's warp depth,
/// `λ = (n + √(fn))/(d sin θ)` (formulas.md §5.6). `UNIFORM` at θ = 0.
#[must_use]
pub fn lambda_lispsm(model: &FrustumModel, gamma: LightAngle) -> WarpParameter {
    let range = model.range();
    WarpParameter::from_positive(
        (range.near() + range.geometric_mean()) / (model.warp_depth(gamma) * gamma.sin()),
    )
}

/// λ_GLPR, the generalized linear perspective reparameterization (GMNPR §3, after Zhang et al.):
/// the λ with `ϕ(λ, θ) = 0`, so that `F ∝ z`, extending PSM to general angles. On `(φ, π/2]` it is
/// `λ = n (1 − T)/D`, evaluated as `n sin(θ − φ)/(cos φ · d)`. `None` on `[0, φ]`, where no positive
/// λ makes F linear.
#[must_use]
pub fn lambda_glpr(model: &FrustumModel, gamma: LightAngle) -> Option<WarpParameter> {
    let phi = model.half_fov();
    let lambda = model.range().near() * (gamma.radians() - phi.radians()).sin()
        / (phi.cos() * model.warp_depth(gamma));
    WarpParameter::from_lambda(lambda).ok()
}

/// The λ that minimises the near error `F(λ, θ, n)` alone: `μ/(1 − 2μ)` (formulas.md §5.8),
/// evaluated as `a cos θ/((f − n)(sin θ + tan φ cos θ))` for `θ ≥ φ` and `u(n)/(2 (f − n) sin θ)`
/// below, so neither branch cancels. Raw: `0` at θ = π/2 (where F(n) decreases towards λ → 0) and
/// `+∞` (uniform) at θ = 0.
#[must_use]
pub fn lambda_near_minimizer(model: &FrustumModel, gamma: LightAngle) -> f64 {
    let range = model.range();
    let near_offset = model.near_plane_offset(gamma, range.near());
    let (sin, cos) = (gamma.sin(), gamma.cos());
    let denominator = match model.case(gamma) {
        ModelCase::Wide => range.length() * (sin + model.half_fov().tan() * cos),
        ModelCase::Narrow => 2.0 * range.length() * sin,
    };
    near_offset / denominator
}

/// The true L∞-optimal λ in the 2-D model (formulas.md §5.8; not in any of the papers):
///
/// `λ_minimax(θ) = max(λ_equal-error(θ), μ/(1 − 2μ))`
///
/// F(f) decreases in λ and F(n) has its one minimum at `μ/(1 − 2μ)`, so equal error is the minimax
/// only where that minimum lies below it. Below θ1 (and for `f/n < 2.618` near φ) the near
/// minimiser is the optimum; it rises smoothly to ∞ as θ → 0. `UNIFORM` at θ = 0.
#[must_use]
pub fn lambda_minimax(model: &FrustumModel, gamma: LightAngle) -> WarpParameter {
    // Positive everywhere: the near minimiser is positive below π/2, and λ1(π/2) > 0.
    WarpParameter::from_positive(
        lambda_equal_error(model, gamma).max(lambda_near_minimizer(model, gamma)),
    )
}

/// θ_0: below it λ2 < 0 (formulas.md §5.4, §9.5); the same angle as CAD's γ_0.
#[must_use]
pub fn theta0(model: &FrustumModel) -> LightAngle {
    crate::cad::gamma0(model)
}

/// θ1, where λ2 equals the near minimiser μ/(1 − 2μ):
/// `tan θ1/tan φ = f/√((f − n)(f + √(fn)))` (formulas.md §5.8). Below θ1 the equal-error λ2 is not
/// the minimax. `θ1 ≤ φ` exactly when `f/n ≥ ((1 + √5)/2)² ≈ 2.618`; for thinner ranges the near
/// minimiser governs the whole narrow case.
#[must_use]
pub fn theta1(model: &FrustumModel) -> LightAngle {
    let range = model.range();
    let denominator = (range.length() * (range.far() + range.geometric_mean())).sqrt();
    LightAngle::from_valid_radians(model.far_half_height().atan2(denominator))
}

fn check_lambda(lambda: f64) -> Result<f64, ParamError> {
    ParamError::finite("lambda", lambda)?;
    ParamError::require("lambda", lambda, lambda > 0.0, || "greater than 0".into())
}

/// `T = tan φ/tan θ = tan φ cos θ/sin θ`, for θ > 0.
fn t_ratio(model: &FrustumModel, gamma: LightAngle) -> Result<f64, ParamError> {
    ParamError::require("gamma", gamma.radians(), !gamma.is_parallel(), || {
        "greater than 0 (the printed ψ and ϕ are singular at 0)".into()
    })?;
    Ok(model.half_fov().tan() * gamma.cos() / gamma.sin())
}
