//! The 2-D view-frustum model shared by CAD eqs. 10–12 and GMNPR eq. 2 (formulas.md §0, §4.6,
//! §5.1): the focus body B is the view frustum V, cut by the plane that contains the light and view
//! directions, and the warp frustum P is fitted to it in light space.
//!
//! In that plane, eye depth `z` along the view axis maps to light-space depth (the warp axis,
//! perpendicular to the light) `z sin γ`, and a lateral offset `s` maps to `s cos γ`. The frustum's
//! corners are `z ∈ {n, f}` with lateral offsets `±a = ±n tan φ` and `±b = ±f tan φ`. P's near plane
//! passes through the corner with the smallest light-space depth — the lower near corner when
//! `γ ≥ φ` ("wide" case, GMNPR case 1), the lower far corner when `γ < φ` ("narrow" case, case 2) —
//! and its far plane through the upper far corner.
//!
//! Everything here is division-free in γ (no `tan γ`), so it holds exactly at γ = π/2 and γ = 0
//! (formulas.md §9.6).

use crate::domain::{DepthRange, HalfFov, LightAngle, WarpParameter};
use crate::error::ParamError;

/// Which corner of the view frustum P's near plane passes through (formulas.md §4.6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelCase {
    /// `φ ≤ γ ≤ π/2` (GMNPR case 1, the first branch of CAD eqs. 10, 11, 13): the lower near
    /// corner is nearest P's centre.
    Wide,
    /// `0 ≤ γ < φ` (GMNPR case 2, the second branch): the lower far corner is; the light looks
    /// (nearly) along the view.
    Narrow,
}

/// The view frustum in the light–view plane: a depth range and the half field of view φ in that
/// plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrustumModel {
    range: DepthRange,
    half_fov: HalfFov,
}

impl FrustumModel {
    /// The model of a view frustum with depth range `range` and half field of view `half_fov`.
    #[must_use]
    pub fn new(range: DepthRange, half_fov: HalfFov) -> Self {
        Self { range, half_fov }
    }

    /// The eye depth range `[n, f]`.
    #[must_use]
    pub fn range(&self) -> DepthRange {
        self.range
    }

    /// φ, the half field of view in the light–view plane.
    #[must_use]
    pub fn half_fov(&self) -> HalfFov {
        self.half_fov
    }

    /// `a = n tan φ`, the half-height of the near plane (CAD §4).
    #[must_use]
    pub fn near_half_height(&self) -> f64 {
        self.range.near() * self.half_fov.tan()
    }

    /// `b = f tan φ`, the half-height of the far plane (CAD §4).
    #[must_use]
    pub fn far_half_height(&self) -> f64 {
        self.range.far() * self.half_fov.tan()
    }

    /// Which branch of the model applies at γ: [`ModelCase::Wide`] for `γ ≥ φ`.
    #[must_use]
    pub fn case(&self, gamma: LightAngle) -> ModelCase {
        if gamma.radians() >= self.half_fov.radians() {
            ModelCase::Wide
        } else {
            ModelCase::Narrow
        }
    }

    /// `d = f' − n'`, the depth of the warp frustum P: the extent of B along light-space depth
    /// (CAD eq. 11 minus n'):
    /// `d = (f − n) sin γ + (a + b) cos γ` for `γ ≥ φ`, `d = 2 b cos γ` for `γ < φ`.
    /// It does not depend on n'. Positive everywhere on `0 ≤ γ ≤ π/2`.
    #[must_use]
    pub fn warp_depth(&self, gamma: LightAngle) -> f64 {
        match self.case(gamma) {
            ModelCase::Wide => {
                self.range.length() * gamma.sin()
                    + (self.near_half_height() + self.far_half_height()) * gamma.cos()
            }
            ModelCase::Narrow => 2.0 * self.far_half_height() * gamma.cos(),
        }
    }

    /// `u(z) = z'(z) − n'`: how far beyond P's near plane the view-axis point at eye depth `z` lies
    /// (CAD eq. 10 minus n'): `a cos γ + (z − n) sin γ` for `γ ≥ φ`,
    /// `b cos γ + (z − f) sin γ` for `γ < φ`. For `z` in `[n, f]`, `0 ≤ u ≤ d`; both branches are
    /// evaluated as sums of non-negative terms.
    pub(crate) fn near_plane_offset(&self, gamma: LightAngle, z: f64) -> f64 {
        match self.case(gamma) {
            ModelCase::Wide => {
                self.near_half_height() * gamma.cos() + (z - self.range.near()) * gamma.sin()
            }
            // b cos γ + (z − f) sin γ = f sin(φ − γ)/cos φ + z sin γ: two non-negative terms, so no
            // cancellation when f/n is huge and γ is just below φ.
            ModelCase::Narrow => {
                let phi = self.half_fov;
                self.range.far() * (phi.radians() - gamma.radians()).sin() / phi.cos()
                    + z * gamma.sin()
            }
        }
    }

    /// `τ(z) = u(z)/d ∈ [0, 1]`: the view-axis point's position through P's depth. `τ(n) = μ` and
    /// `τ(f) = ν` of GMNPR §3 (formulas.md §5.2).
    pub(crate) fn depth_fraction(&self, gamma: LightAngle, z: f64) -> f64 {
        self.near_plane_offset(gamma, z) / self.warp_depth(gamma)
    }

    /// The perspective aliasing along the view axis in LiSPSM's normalisation,
    /// `dp/ds = (1/z)·dz/ds` (the screen spanning `[0, 1]`, LiSPSM eq. 1 with `cos α/cos β = 1`),
    /// for a warp λ fitted to the model at angle γ:
    ///
    /// `dp/ds = d/(z sin γ) · (λ + τ)²/(λ(λ + 1))`,  `τ = u(z)/d`
    ///
    /// which is CAD eq. 12 and GMNPR eq. 2 up to their constant factors, written in the form of
    /// formulas.md §9.1 (no cancellation; the uniform map λ = ∞ gives `d/(z sin γ)` exactly).
    ///
    /// At `γ = 0` the view axis projects onto one shadow-map row and the error is unbounded: the
    /// function returns `f64::INFINITY` there, and only there. `Err` names `z` outside `[n, f]`.
    pub fn view_axis_error(
        &self,
        gamma: LightAngle,
        warp: WarpParameter,
        z: f64,
    ) -> Result<f64, ParamError> {
        let z = self.range.check_depth("z", z)?;
        Ok(self.view_axis_error_unchecked(gamma, warp, z))
    }

    pub(crate) fn view_axis_error_unchecked(
        &self,
        gamma: LightAngle,
        warp: WarpParameter,
        z: f64,
    ) -> f64 {
        if gamma.is_parallel() {
            return f64::INFINITY;
        }
        let d = self.warp_depth(gamma);
        let tau = self.near_plane_offset(gamma, z) / d;
        d / (z * gamma.sin()) * warp.stretch_unchecked(tau)
    }

    /// `max over z ∈ [n, f]` of [`Self::view_axis_error`]. The error is convex in z
    /// (`(z + c)²/z`, formulas.md §2.4, §5.7), so the maximum is at an end of the range.
    /// `f64::INFINITY` at `γ = 0` only.
    #[must_use]
    pub fn max_view_axis_error(&self, gamma: LightAngle, warp: WarpParameter) -> f64 {
        let near = self.view_axis_error_unchecked(gamma, warp, self.range.near());
        let far = self.view_axis_error_unchecked(gamma, warp, self.range.far());
        near.max(far)
    }
}
