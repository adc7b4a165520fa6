//! The logarithmic parameterisation (LiSPSM §4; Lloyd et al., *Logarithmic perspective shadow
//! maps*, ACM TOG 27(4), 2008), evaluated exactly in software.
//!
//! In LiSPSM's light space (viewer looking down −z, y toward the light), with `τ = (z_max − z)/d`
//! the position through B's extent `d` along the warp axis, the map is
//!
//! ```text
//! Y = 2·ln(1 + τ/λ)/ln(1 + 1/λ) − 1        the warp axis, logarithmic
//! X = (2x/w − (l + r))/(r − l),  w = 1 + τ/λ   lateral: perspective from the same point, as P's
//! depth = linear in y, growing away from the light
//! ```
//!
//! with its reference point at the eye's position along the warp axis: `λ = −z_max/d` (the eye is
//! the light-space origin). Along the view axis, whose eye depth `t` has light-space
//! `z = −t sin γ`, this gives `1 + τ/λ = t sin γ/(−z_max)`, so `s = (Y + 1)/2` is
//! `ln(t/t0)/ln(1 + 1/λ)` and the perspective aliasing `dp/ds = (1/t)·dt/ds = ln(1 + 1/λ)` is the
//! same at every depth: for `γ = 90°` and B = V, `ln(zf/zn)` (formulas.md §2.9), the constant the
//! paper predicts. The map is not projective, so no rasterizer can draw it: the shadow map is
//! made by casting one ray per texel along the light ([`LogarithmicMap::texel_ray`]).
//!
//! It exists only where B lies entirely on one side of the eye along the warp axis (`z_max < 0`);
//! for B = V that is `γ > φ`. Elsewhere [`crate::plan`] says the technique is not defined, as
//! `shadowlab-params` does for GLPR.

use glam::{DMat4, DVec2, DVec3};

use crate::error::ShadowError;
use crate::input::PlanInput;
use crate::plan::{focus_in_light_space, view_model};
use crate::setup::{LightSetup, ShadowMapping, WarpReport};
use crate::technique::Technique;
use crate::warp::Extents;

/// λ below this (the eye within a billionth of B's depth of its near plane) counts as the eye
/// touching B: the logarithm's reference point would sit on B.
const MIN_LAMBDA: f64 = 1e-9;

/// The exact logarithmic mapping of one shadow map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogarithmicMap {
    /// World → light space (projective for a spot light).
    world_to_light: DMat4,
    /// Its inverse.
    light_to_world: DMat4,
    /// B's near plane (largest z) and its extent along the warp axis.
    z_max: f64,
    depth: f64,
    /// λ = −z_max/d.
    lambda: f64,
    /// Lateral extents of x/w over B.
    left: f64,
    right: f64,
    /// B's extent along the light axis.
    y_min: f64,
    y_max: f64,
}

impl LogarithmicMap {
    /// GL NDC of a world point (`None` behind a spot light or on the eye's side of the logarithm's
    /// reference point).
    #[must_use]
    pub fn ndc(&self, world: DVec3) -> Option<DVec3> {
        let h = self.world_to_light * world.extend(1.0);
        if h.w <= 0.0 {
            return None;
        }
        let q = h.truncate() / h.w;
        let tau = (self.z_max - q.z) / self.depth;
        let w = 1.0 + tau / self.lambda;
        if w <= 0.0 {
            return None;
        }
        let x = (2.0 * q.x / w - (self.left + self.right)) / (self.right - self.left);
        let y = 2.0 * (tau / self.lambda).ln_1p() / (1.0 / self.lambda).ln_1p() - 1.0;
        let depth = (self.y_max + self.y_min - 2.0 * q.y) / (self.y_max - self.y_min);
        Some(DVec3::new(x, y, depth))
    }

    /// The derivative of [`Self::ndc`]'s `(X, Y)` at `world` along `direction` (per unit of
    /// `direction`), differentiated in closed form (the map in the module docs): with
    /// `h = M·(p, 1)`, `ḣ = M·(t, 0)`, `q = h/h_w`, `q̇ = (ḣ·h_w − h·ḣ_w)/h_w²`, `τ̇ = −q̇_z/d` and
    /// `ẇ = τ̇/λ`,
    ///
    /// `Ẋ = 2·(q̇_x·w − q_x·ẇ)/(w²·(r − l))`,  `Ẏ = 2·τ̇/((λ + τ)·ln(1 + 1/λ))`,
    ///
    /// the last with `λ·w` written `λ + τ`, which stays exact for λ near its smallest allowed
    /// value (1e-9) and for λ → ∞ (where `ln(1 + 1/λ)` is `ln_1p`'s). `None` where `ndc` is
    /// `None`.
    #[must_use]
    pub fn ndc_derivative(&self, world: DVec3, direction: DVec3) -> Option<DVec2> {
        let h = self.world_to_light * world.extend(1.0);
        if h.w <= 0.0 {
            return None;
        }
        let dh = self.world_to_light * direction.extend(0.0);
        let q = h.truncate() / h.w;
        let dq = (dh.truncate() * h.w - h.truncate() * dh.w) / (h.w * h.w);
        let tau = (self.z_max - q.z) / self.depth;
        let w = 1.0 + tau / self.lambda;
        if w <= 0.0 {
            return None;
        }
        let dtau = -dq.z / self.depth;
        let dw = dtau / self.lambda;
        let dx = 2.0 * (dq.x * w - q.x * dw) / (w * w * (self.right - self.left));
        let dy = 2.0 * dtau / ((self.lambda + tau) * (1.0 / self.lambda).ln_1p());
        Some(DVec2::new(dx, dy))
    }

    /// The ray of light through the shadow-map point at NDC `(x, y)`: its origin on B's light side
    /// (NDC depth −1) and the point where it leaves B's far side (NDC depth +1), in world space.
    /// Casting it and mapping the first hit through [`Self::ndc`] gives the texel's depth.
    #[must_use]
    pub fn texel_ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        // Inverse of Y: τ = λ·(exp(((Y + 1)/2)·ln(1 + 1/λ)) − 1), written with expm1 so that it is
        // exact near τ = 0 and for large λ.
        let tau = self.lambda * (0.5 * (y + 1.0) * (1.0 / self.lambda).ln_1p()).exp_m1();
        let w = 1.0 + tau / self.lambda;
        let lateral = 0.5 * w * (x * (self.right - self.left) + self.left + self.right);
        let z = self.z_max - tau * self.depth;
        let to_world = |light_y: f64| {
            let h = self.light_to_world * DVec3::new(lateral, light_y, z).extend(1.0);
            h.truncate() / h.w
        };
        (to_world(self.y_max), to_world(self.y_min))
    }

    /// λ = −z_max/d, the reference point's distance before B's near plane in units of B's depth.
    #[must_use]
    pub fn lambda(&self) -> f64 {
        self.lambda
    }
}

/// Plans the logarithmic map for `input`.
///
/// # Errors
/// [`ShadowError::NotDefined`] where the eye lies within B's extent along the warp axis; as
/// [`crate::plan`] otherwise.
pub(crate) fn plan(input: &PlanInput) -> Result<LightSetup, ShadowError> {
    let technique = Technique::Logarithmic;
    let (frame, world_points, points) = focus_in_light_space(input, technique)?;
    let (_, half_fov) = view_model(input)?;
    let extents = Extents::of(&points);
    let depth = extents.max.z - extents.min.z;
    if depth <= 0.0 {
        return Err(ShadowError::FlatFocusBody { axis: "warp axis" });
    }
    let lambda = -extents.max.z / depth;
    if lambda <= MIN_LAMBDA {
        return Err(ShadowError::NotDefined {
            technique: technique.key(),
            reason: format!(
                "the eye lies within the focus body's extent along the warp axis (γ = {:.4}°, φ = {:.4}°): no logarithm has its reference point outside B",
                frame.gamma().to_degrees(),
                half_fov.to_degrees()
            ),
        });
    }
    let (left, right) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, r), p| {
            let w = 1.0 + (extents.max.z - p.z) / depth / lambda;
            (l.min(p.x / w), r.max(p.x / w))
        });
    if right <= left || extents.max.y <= extents.min.y {
        return Err(ShadowError::FlatFocusBody {
            axis: "lateral axis",
        });
    }
    let world_to_light = frame.world_to_light();
    let map = LogarithmicMap {
        world_to_light,
        light_to_world: world_to_light.inverse(),
        z_max: extents.max.z,
        depth,
        lambda,
        left,
        right,
        y_min: extents.min.y,
        y_max: extents.max.y,
    };
    Ok(LightSetup {
        technique,
        mapping: ShadowMapping::Logarithmic(map),
        gamma: frame.gamma(),
        half_fov,
        warp: Some(WarpReport {
            lambda,
            near_distance: lambda * depth,
            depth,
        }),
        psm: None,
        focus_body: world_points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative agreement asked of the closed-form derivative against Richardson-extrapolated
    /// central differences (whose own error is of order 1e-10 at these steps).
    const AGREEMENT: f64 = 1e-6;

    /// The closed-form derivative matches differences of `ndc`, for λ from 1e-6 to 1e6, a spot
    /// light's projective light space and every direction.
    #[test]
    fn the_derivative_matches_differences_of_the_map() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            #[expect(clippy::cast_precision_loss, reason = "a random fraction")]
            let v = (state >> 11) as f64 / (1u64 << 53) as f64;
            v
        };
        let spot = glam::dcamera::rh::proj::opengl::perspective(1.0, 1.0, 0.5, 50.0)
            * glam::dcamera::rh::view::look_at_mat4(
                DVec3::new(1.0, 8.0, 2.0),
                DVec3::ZERO,
                DVec3::Z,
            );
        let mut compared = 0;
        for (k, lambda) in [1e-6, 1e-3, 0.3, 1.0, 7.0, 1e3, 1e6]
            .into_iter()
            .enumerate()
        {
            let world_to_light = if k % 2 == 0 { spot } else { DMat4::IDENTITY };
            let map = LogarithmicMap {
                world_to_light,
                light_to_world: world_to_light.inverse(),
                z_max: -2.0,
                depth: 2.0 / lambda,
                lambda,
                left: -1.5,
                right: 2.5,
                y_min: -3.0,
                y_max: 3.0,
            };
            for _ in 0..600 {
                let p = DVec3::new(4.0 * next() - 2.0, 4.0 * next() - 2.0, -2.0 - 6.0 * next());
                let t = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                let Some(analytic) = map.ndc_derivative(p, t) else {
                    continue;
                };
                let h = 1e-4 * p.length();
                let at = |s: f64| map.ndc(p + t * s).map(|n| DVec2::new(n.x, n.y));
                let central = |h: f64| Some((at(h)? - at(-h)?) / (2.0 * h));
                let (Some(full), Some(half)) = (central(h), central(0.5 * h)) else {
                    continue;
                };
                let numeric = (half * 4.0 - full) / 3.0;
                let scale = numeric.abs().max_element().max(1e-300);
                assert!(
                    (analytic - numeric).abs().max_element() <= AGREEMENT * scale,
                    "λ {lambda} at {p} along {t}: {analytic} vs {numeric}"
                );
                compared += 1;
            }
        }
        assert!(compared > 1000, "{compared}");
    }
}
