//! Validated inputs: the eye depth range, the half field of view, the light angle and the warp
//! parameter λ. A value of these types is always inside the domain of every formula that takes it.

use std::f64::consts::FRAC_PI_2;

use crate::error::ParamError;

/// The eye's depth range `[zn, zf]` (written `[n, f]` in CAD and GMNPR): distances along the view
/// axis, in one world unit.
///
/// # Guarantees
/// `0 < near < far`, both finite, and `far / near` finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthRange {
    near: f64,
    far: f64,
}

impl DepthRange {
    /// A depth range; `Err` names `near` or `far` when `0 < near < far` (finite, with a finite ratio)
    /// does not hold.
    pub fn new(near: f64, far: f64) -> Result<Self, ParamError> {
        ParamError::finite("near", near)?;
        ParamError::finite("far", far)?;
        ParamError::require("near", near, near > 0.0, || "greater than 0".into())?;
        ParamError::require("far", far, far > near, || {
            format!("greater than near ({near})")
        })?;
        ParamError::require("far", far, (far / near).is_finite(), || {
            format!("such that far/near is finite (near = {near})")
        })?;
        Ok(Self { near, far })
    }

    /// `zn`, the near distance.
    #[must_use]
    pub fn near(self) -> f64 {
        self.near
    }

    /// `zf`, the far distance.
    #[must_use]
    pub fn far(self) -> f64 {
        self.far
    }

    /// `zf − zn`. Exact whenever `zf ≤ 2 zn` (Sterbenz), which is where cancellation would matter.
    #[must_use]
    pub fn length(self) -> f64 {
        self.far - self.near
    }

    /// `zf / zn`.
    #[must_use]
    pub fn ratio(self) -> f64 {
        self.far / self.near
    }

    /// `√(zn·zf)`, computed as `√zn·√zf` so that the product cannot overflow.
    #[must_use]
    pub fn geometric_mean(self) -> f64 {
        self.near.sqrt() * self.far.sqrt()
    }

    /// `ln(zf/zn)`, computed as `ln_1p((zf − zn)/zn)`: accurate when `zf/zn → 1`.
    #[must_use]
    pub fn log_ratio(self) -> f64 {
        (self.length() / self.near).ln_1p()
    }

    /// `√(zf/zn) − 1`, computed as `(zf − zn)/(zn + √(zn·zf))` (formulas.md §9.2): no cancellation
    /// when `zf/zn → 1`.
    #[must_use]
    pub fn sqrt_ratio_minus_one(self) -> f64 {
        self.length() / (self.near + self.geometric_mean())
    }

    /// Whether `z` lies in `[zn, zf]`.
    #[must_use]
    pub fn contains(self, z: f64) -> bool {
        self.near <= z && z <= self.far
    }

    /// The depth a fraction `t ∈ [0, 1]` of the way from `zn` to `zf`, linearly; exact at both ends.
    /// `t` is clamped to `[0, 1]`.
    #[must_use]
    pub fn lerp(self, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        if t >= 1.0 {
            self.far
        } else {
            (self.near + self.length() * t).min(self.far)
        }
    }

    /// The depth a fraction `t ∈ [0, 1]` of the way from `zn` to `zf` geometrically,
    /// `zn·(zf/zn)^t`; exact at both ends. `t` is clamped to `[0, 1]`.
    #[must_use]
    pub fn geometric_lerp(self, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        if t >= 1.0 {
            self.far
        } else {
            (self.near * (self.log_ratio() * t).exp()).clamp(self.near, self.far)
        }
    }

    /// `Ok(z)` if `z ∈ [zn, zf]`, else an error naming `name`.
    pub(crate) fn check_depth(self, name: &'static str, z: f64) -> Result<f64, ParamError> {
        ParamError::finite(name, z)?;
        ParamError::require(name, z, self.contains(z), || {
            format!("in the depth range [{}, {}]", self.near, self.far)
        })
    }

    /// `(z − zn)/(zf − zn) ∈ [0, 1]` for a depth already checked to lie in the range.
    pub(crate) fn fraction(self, z: f64) -> f64 {
        (z - self.near) / self.length()
    }
}

/// An angle with its sine and cosine, exact at the ends of its domain.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Angle {
    radians: f64,
    sin: f64,
    cos: f64,
}

impl Angle {
    /// `sin` and `cos` of `radians`, taking the f64 nearest π/2 to be π/2 exactly (so `cos = 0` and
    /// `sin = 1` there) and 0 to give `sin = 0`, `cos = 1` exactly.
    fn new(radians: f64) -> Self {
        let (sin, cos) = if radians == FRAC_PI_2 {
            (1.0, 0.0)
        } else {
            radians.sin_cos()
        };
        Self { radians, sin, cos }
    }
}

/// φ: half the eye's field of view, in the plane that contains the light and view directions.
///
/// # Guarantees
/// `0 < φ < π/2`; `tan φ` is finite and positive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfFov {
    angle: Angle,
    tan: f64,
}

impl HalfFov {
    /// From the full field of view in degrees, `0 < fov < 180`; `Err` names `fov`.
    pub fn from_full_fov_degrees(fov: f64) -> Result<Self, ParamError> {
        ParamError::finite("fov", fov)?;
        ParamError::require("fov", fov, fov > 0.0 && fov < 180.0, || {
            "strictly between 0 and 180 degrees".into()
        })?;
        Ok(Self::from_valid_radians((fov / 2.0).to_radians()))
    }

    /// From φ in radians, `0 < φ < π/2`; `Err` names `half_fov`.
    pub fn from_radians(phi: f64) -> Result<Self, ParamError> {
        ParamError::finite("half_fov", phi)?;
        ParamError::require("half_fov", phi, phi > 0.0 && phi < FRAC_PI_2, || {
            "strictly between 0 and pi/2 radians".into()
        })?;
        Ok(Self::from_valid_radians(phi))
    }

    fn from_valid_radians(phi: f64) -> Self {
        let angle = Angle::new(phi);
        Self {
            angle,
            tan: angle.sin / angle.cos,
        }
    }

    /// φ in radians.
    #[must_use]
    pub fn radians(self) -> f64 {
        self.angle.radians
    }

    /// φ in degrees (half the full field of view).
    #[must_use]
    pub fn degrees(self) -> f64 {
        self.angle.radians.to_degrees()
    }

    /// `tan φ`.
    #[must_use]
    pub fn tan(self) -> f64 {
        self.tan
    }

    /// `sin φ`.
    #[must_use]
    pub fn sin(self) -> f64 {
        self.angle.sin
    }

    /// `cos φ`.
    #[must_use]
    pub fn cos(self) -> f64 {
        self.angle.cos
    }
}

/// γ (LiSPSM, CAD) = θ (GMNPR): the smallest angle between the light direction and the view
/// direction. `π/2` is the ideal case (light perpendicular to the view), `0` the "dueling frusta"
/// case (light parallel to the view).
///
/// # Guarantees
/// `0 ≤ γ ≤ π/2`. At `γ = π/2` (the f64 nearest it) `sin γ = 1` and `cos γ = 0` exactly; at `γ = 0`,
/// `sin γ = 0` and `cos γ = 1` exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAngle {
    angle: Angle,
}

impl LightAngle {
    /// The ideal angle, π/2: light perpendicular to the view.
    pub const PERPENDICULAR: Self = Self {
        angle: Angle {
            radians: FRAC_PI_2,
            sin: 1.0,
            cos: 0.0,
        },
    };

    /// From degrees, `0 ≤ γ ≤ 90`; `Err` names `gamma`.
    pub fn from_degrees(gamma: f64) -> Result<Self, ParamError> {
        ParamError::finite("gamma", gamma)?;
        ParamError::require("gamma", gamma, (0.0..=90.0).contains(&gamma), || {
            "between 0 and 90 degrees".into()
        })?;
        Ok(Self::from_valid_radians(if gamma == 90.0 {
            FRAC_PI_2
        } else {
            gamma.to_radians()
        }))
    }

    /// From radians, `0 ≤ γ ≤ π/2`; `Err` names `gamma`.
    pub fn from_radians(gamma: f64) -> Result<Self, ParamError> {
        ParamError::finite("gamma", gamma)?;
        ParamError::require("gamma", gamma, (0.0..=FRAC_PI_2).contains(&gamma), || {
            "between 0 and pi/2 radians".into()
        })?;
        Ok(Self::from_valid_radians(gamma))
    }

    /// From radians already known to lie in `[0, π/2]`.
    pub(crate) fn from_valid_radians(gamma: f64) -> Self {
        debug_assert!((0.0..=FRAC_PI_2).contains(&gamma), "gamma = {gamma}");
        Self {
            angle: Angle::new(gamma),
        }
    }

    /// γ in radians.
    #[must_use]
    pub fn radians(self) -> f64 {
        self.angle.radians
    }

    /// γ in degrees.
    #[must_use]
    pub fn degrees(self) -> f64 {
        self.angle.radians.to_degrees()
    }

    /// `sin γ`.
    #[must_use]
    pub fn sin(self) -> f64 {
        self.angle.sin
    }

    /// `cos γ`.
    #[must_use]
    pub fn cos(self) -> f64 {
        self.angle.cos
    }

    /// Whether the light is exactly parallel to the view (`γ = 0`), where every parameter of the
    /// papers degenerates to the uniform map.
    #[must_use]
    pub fn is_parallel(self) -> bool {
        self.angle.sin == 0.0
    }
}

/// λ = n'/(f' − n') (GMNPR §2): the near distance of the warp frustum P normalised by P's depth. The
/// one free parameter of every perspective warp in the papers; unit-free.
///
/// `λ → ∞` is the uniform (standard) shadow map; a small λ is a strong, PSM-like warp.
///
/// # Guarantees
/// `0 < λ ≤ ∞` with λ normal, so `μ = 1/λ` is finite. `λ = ∞` (see [`Self::UNIFORM`]) means "uniform", and every function taking a
/// `WarpParameter` returns the uniform map's value for it, never NaN.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct WarpParameter {
    lambda: f64,
}

impl WarpParameter {
    /// The uniform (standard, unwarped) shadow map: λ = ∞.
    pub const UNIFORM: Self = Self {
        lambda: f64::INFINITY,
    };

    /// From λ ∈ (0, ∞]; `Err` names `lambda`. λ must be at least the smallest normal f64
    /// (2.2e-308), so that `μ = 1/λ` is finite.
    pub fn from_lambda(lambda: f64) -> Result<Self, ParamError> {
        ParamError::require("lambda", lambda, lambda >= f64::MIN_POSITIVE, || {
            "greater than 0 (infinity means uniform)".into()
        })?;
        Ok(Self { lambda })
    }

    /// From a λ a formula of this crate has shown to be positive (possibly infinite).
    pub(crate) fn from_positive(lambda: f64) -> Self {
        debug_assert!(lambda >= f64::MIN_POSITIVE, "lambda = {lambda}");
        Self { lambda }
    }

    /// From P's near distance `n' ∈ (0, ∞]` and its depth `d = f' − n'` (finite, > 0):
    /// `λ = n'/d`. `Err` names `n` or `depth`.
    pub fn from_near_distance(near: f64, depth: f64) -> Result<Self, ParamError> {
        ParamError::require("n", near, near > 0.0, || {
            "greater than 0 (infinity means uniform)".into()
        })?;
        ParamError::finite("depth", depth)?;
        ParamError::require("depth", depth, depth > 0.0, || "greater than 0".into())?;
        Self::from_lambda(near / depth)
    }

    /// λ; `f64::INFINITY` for the uniform map.
    #[must_use]
    pub fn lambda(self) -> f64 {
        self.lambda
    }

    /// `μ = 1/λ ∈ [0, ∞)`, the form of formulas.md §9.1 that is exact for the uniform map (`μ = 0`).
    #[must_use]
    pub fn inverse_lambda(self) -> f64 {
        1.0 / self.lambda
    }

    /// P's near distance `n' = λ·d` for a warp frustum of depth `d`; infinite for the uniform map.
    #[must_use]
    pub fn near_distance(self, depth: f64) -> f64 {
        self.lambda * depth
    }

    /// Whether this is the uniform map (λ = ∞).
    #[must_use]
    pub fn is_uniform(self) -> bool {
        self.lambda.is_infinite()
    }

    /// The warp's shadow-map coordinate `s(τ) = (λ+1)τ/(λ+τ)` of a point a fraction `τ ∈ [0, 1]` of
    /// P's depth beyond its near plane (LiSPSM eq. 2, corrected sign, formulas.md §2.1, on the
    /// unit-depth frustum of §9.1: `s = τ(1+μ)/(1+μτ)`, `μ = 1/λ`). `s(0) = 0`, `s(1) = 1` exactly.
    /// `Err` names `tau` outside `[0, 1]`.
    pub fn warp(self, tau: f64) -> Result<f64, ParamError> {
        Ok(self.warp_unchecked(check_unit("tau", tau)?))
    }

    /// The inverse of [`Self::warp`]: `τ(s) = s/(1 + (1−s)/λ)`. `Err` names `s` outside `[0, 1]`.
    pub fn unwarp(self, s: f64) -> Result<f64, ParamError> {
        let s = check_unit("s", s)?;
        let lambda = self.lambda;
        Ok(if lambda >= 1.0 {
            s / (1.0 + (1.0 - s) * self.inverse_lambda())
        } else {
            s * lambda / (lambda + (1.0 - s))
        })
    }

    /// `ds/dτ = λ(λ+1)/(λ+τ)²`, evaluated as `(1+μ)/(1+μτ)²`. `Err` names `tau` outside `[0, 1]`.
    pub fn warp_slope(self, tau: f64) -> Result<f64, ParamError> {
        Ok(1.0 / self.stretch_unchecked(check_unit("tau", tau)?))
    }

    /// [`Self::warp`] for a `τ` known to lie in `[0, 1]`; the form is chosen by λ as in
    /// [`Self::stretch_unchecked`].
    pub(crate) fn warp_unchecked(self, tau: f64) -> f64 {
        let lambda = self.lambda;
        if tau >= 1.0 {
            1.0
        } else if lambda >= 1.0 {
            let mu = self.inverse_lambda();
            tau * (1.0 + mu) / (1.0 + mu * tau)
        } else {
            (lambda + 1.0) * tau / (lambda + tau)
        }
    }

    /// `dτ/ds = (λ+τ)²/(λ(λ+1))`: by how much the warp stretches depth at `τ` relative to the
    /// uniform map. Evaluated as `(1+τ/λ)²/(1+1/λ)` for λ ≥ 1 and as written for λ < 1, so that no
    /// term overflows or cancels; exactly 1 for the uniform map. `τ` may lie a little outside
    /// `[0, 1]` (a point outside P), as long as `λ + τ > 0`.
    pub(crate) fn stretch_unchecked(self, tau: f64) -> f64 {
        let lambda = self.lambda;
        if lambda >= 1.0 {
            let mu = self.inverse_lambda();
            let a = 1.0 + tau * mu;
            a * a / (1.0 + mu)
        } else {
            let a = lambda + tau;
            a * a / (lambda * (lambda + 1.0))
        }
    }
}

fn check_unit(name: &'static str, value: f64) -> Result<f64, ParamError> {
    ParamError::require(name, value, (0.0..=1.0).contains(&value), || {
        "in [0, 1]".into()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_range_rejects_each_bad_input_by_name() {
        let cases = [
            (f64::NAN, 1.0, "near"),
            (1.0, f64::INFINITY, "far"),
            (0.0, 1.0, "near"),
            (-1.0, 1.0, "near"),
            (2.0, 2.0, "far"),
            (2.0, 1.0, "far"),
            (1e-300, 1e300, "far"),
        ];
        for (near, far, name) in cases {
            let err = DepthRange::new(near, far).unwrap_err();
            assert_eq!(err.parameter(), name, "{near} {far}: {err}");
        }
    }

    #[test]
    fn lerp_is_exact_at_both_ends_and_monotone() {
        let r = DepthRange::new(0.1, 0.3).unwrap();
        assert_eq!(r.lerp(0.0), 0.1);
        assert_eq!(r.lerp(1.0), 0.3);
        assert_eq!(r.geometric_lerp(0.0), 0.1);
        assert_eq!(r.geometric_lerp(1.0), 0.3);
        let mut last = 0.0;
        for i in 0..=1000 {
            let z = r.geometric_lerp(f64::from(i) / 1000.0);
            assert!(z >= last);
            last = z;
        }
    }

    #[test]
    fn angles_are_exact_at_their_ends() {
        let g = LightAngle::from_degrees(90.0).unwrap();
        assert_eq!((g.sin(), g.cos()), (1.0, 0.0));
        assert_eq!(g, LightAngle::PERPENDICULAR);
        let g = LightAngle::from_radians(0.0).unwrap();
        assert_eq!((g.sin(), g.cos()), (0.0, 1.0));
        assert!(g.is_parallel());
        assert!(!LightAngle::from_radians(1e-300).unwrap().is_parallel());
        assert_eq!(
            LightAngle::from_degrees(90.5).unwrap_err().parameter(),
            "gamma"
        );
        assert_eq!(
            LightAngle::from_degrees(-0.1).unwrap_err().parameter(),
            "gamma"
        );
        assert_eq!(
            HalfFov::from_full_fov_degrees(180.0)
                .unwrap_err()
                .parameter(),
            "fov"
        );
        assert_eq!(
            HalfFov::from_full_fov_degrees(0.0).unwrap_err().parameter(),
            "fov"
        );
    }

    #[test]
    fn warp_parameter_domain() {
        assert!(WarpParameter::from_lambda(0.0).is_err());
        assert!(WarpParameter::from_lambda(f64::NAN).is_err());
        assert!(
            WarpParameter::from_lambda(f64::INFINITY)
                .unwrap()
                .is_uniform()
        );
        assert_eq!(WarpParameter::UNIFORM.inverse_lambda(), 0.0);
        assert_eq!(
            WarpParameter::from_near_distance(1.0, 0.0)
                .unwrap_err()
                .parameter(),
            "depth"
        );
    }

    #[test]
    fn warp_is_exact_at_the_ends_and_inverts() {
        for lambda in [1e-9, 0.05, 1.0, 7.0, 1e12, f64::INFINITY] {
            let w = WarpParameter::from_lambda(lambda).unwrap();
            assert_eq!(w.warp(0.0).unwrap(), 0.0);
            assert_eq!(w.warp(1.0).unwrap(), 1.0);
            for i in 0..=64 {
                let tau = f64::from(i) / 64.0;
                let back = w.unwarp(w.warp(tau).unwrap()).unwrap();
                // The inverse amplifies the rounding of s by its slope dτ/ds.
                let conditioning = (1.0 / w.warp_slope(tau).unwrap()).max(1.0);
                let tolerance = 4.0 * f64::EPSILON * conditioning;
                assert!((back - tau).abs() <= tolerance, "{lambda} {tau} {back}");
            }
        }
        assert_eq!(WarpParameter::UNIFORM.warp(0.3).unwrap(), 0.3);
        assert_eq!(WarpParameter::UNIFORM.warp_slope(0.3).unwrap(), 1.0);
        assert_eq!(
            WarpParameter::UNIFORM.warp(1.5).unwrap_err().parameter(),
            "tau"
        );
    }
}
