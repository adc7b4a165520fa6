//! LiSPSM light space (LiSPSM §3.4) and the angle γ between the light and view directions.
//!
//! The definitions are documented on [`LightSpace`].

use glam::{DAffine3, DMat3, DVec3};

use crate::camera::ViewPose;
use crate::error::{HullError, ValidationError};
use crate::finite::unit_vec;
use crate::tolerance::UNIT_LENGTH_TOLERANCE;

/// The length of the blended axis `d` below which it is treated as the singular configuration
/// (see [`LightSpace`]) and replaced by `y × r`. `d` has length ≥ 0.38 except within this
/// distance of one isolated view direction per light direction.
pub const SINGULAR_AXIS_LENGTH: f64 = 1e-12;

/// LiSPSM light space: an orthonormal right-handed frame.
///
/// # Axes (right-handed)
/// - **y** points toward the light (the light vector, see [`crate::Light::light_vector`]);
/// - **z** is perpendicular to y, in the plane of the light and view vectors, with the view vector
///   having a **negative** z component: `z = −ŵ` where `w = v − (v·y) y` is the view direction `v`
///   projected on the plane ⟂ y. The paper's illustration is left-handed with the view vector along
///   +z; flipping z gives the right-handed, OpenGL-like frame the paper says implementations use
///   ("the z-axis will usually be reversed"): in light space, as in eye space, the viewer looks
///   down −z;
/// - **x** = y × z completes it (so x × y = z).
///
/// # Near-parallel fallback
/// When the view is (anti-)parallel to the light, `w` vanishes and the paper's z is undefined. With
/// `s = |w| = sin γ` and a threshold `s₀` ([`LightSpace::DEFAULT_PARALLEL_SIN`]), we take
///
/// ```text
/// e = w / max(s, s₀)                  (= ŵ when s ≥ s₀; shrinks linearly to 0 as s → 0)
/// r = normalize(P_y(right + up))      (the camera's right+up diagonal, projected ⟂ y)
/// d = e + (1 − |e|) · r
/// z = −d/|d|,  x = y × z
/// ```
///
/// For `s ≥ s₀` this is exactly the paper's axis. Below, it blends continuously into the camera's
/// projected diagonal, reached at γ = 0 exactly, where the paper's axis is undefined. `d` is Lipschitz
/// in `w` with constant `2/s₀`.
///
/// **No construction can be continuous for every approach to γ = 0** while agreeing with the paper
/// outside a band: on a small circle of view directions around the light the paper's axis turns once,
/// and a map of the disk to the circle of directions cannot restrict to a degree-1 map on its boundary.
/// So the blend has one unavoidable singular configuration: `w = −(s₀/2)·r` (`d = 0`), where the axis
/// turns fast. We put it on the camera's diagonal so that sweeps of the camera's pitch or yaw through
/// the light direction, the common ones, stay smooth (|d| ≥ 0.38 along them, giving a basis change of
/// at most `6·Δθ/s₀` for a view rotation Δθ; tested); there `d` falls back to `y × r`.
///
/// # Guarantees
/// `x`, `y`, `z` unit, orthogonal, `x × y = z`; `y` is the light vector; `gamma ∈ [0, π/2]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSpace {
    x: DVec3,
    y: DVec3,
    z: DVec3,
    gamma: f64,
    fallback_weight: f64,
}

impl LightSpace {
    /// The default threshold `s₀` on `sin γ` below which the warp axis is blended with the camera's
    /// diagonal: 0.01 (γ ≈ 0.57°). LiSPSM's warp vanishes as γ → 0 (the free parameter n → ∞, §3.5),
    /// so the map is already nearly uniform there and its orientation within the plane ⟂ light is free.
    pub const DEFAULT_PARALLEL_SIN: f64 = 0.01;

    /// The largest accepted threshold: the camera's diagonal must stay far from the light direction
    /// wherever the blend uses it.
    pub const MAX_PARALLEL_SIN: f64 = 0.5;

    /// Light space for a camera `pose` and a light vector `to_light` (toward the light), with the
    /// default threshold.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] or [`HullError::ZeroVector`] naming `to_light`.
    pub fn new(pose: &ViewPose, to_light: DVec3) -> Result<Self, HullError> {
        Self::with_parallel_sin(pose, to_light, Self::DEFAULT_PARALLEL_SIN)
    }

    /// Light space with threshold `parallel_sin` = `s₀` (see [`LightSpace`]).
    ///
    /// # Errors
    /// As [`LightSpace::new`]; [`HullError::OutOfRange`] naming `parallel_sin` unless it lies in
    /// `(0, MAX_PARALLEL_SIN]`.
    pub fn with_parallel_sin(
        pose: &ViewPose,
        to_light: DVec3,
        parallel_sin: f64,
    ) -> Result<Self, HullError> {
        let y = unit_vec(to_light, "to_light")?;
        if !(parallel_sin > 0.0 && parallel_sin <= Self::MAX_PARALLEL_SIN) {
            return Err(HullError::OutOfRange {
                parameter: "parallel_sin",
                value: parallel_sin,
                min: 0.0,
                max: Self::MAX_PARALLEL_SIN,
            });
        }
        let v = pose.forward();
        // v − (v·y) y, computed as y × (v × y) to keep its direction accurate when it is short.
        let w = y.cross(v.cross(y));
        let s = w.length();
        let e = w / s.max(parallel_sin);
        let fallback_weight = if s >= parallel_sin {
            0.0
        } else {
            1.0 - s / parallel_sin
        };
        let mut d = e;
        let mut reference = DVec3::ZERO;
        if fallback_weight > 0.0 {
            let diagonal = pose.right() + pose.up();
            reference = (diagonal - y * diagonal.dot(y)).normalize();
            d += reference * fallback_weight;
        }
        if d.length() < SINGULAR_AXIS_LENGTH {
            d = y.cross(reference);
        }
        let z = -d.normalize();
        let x = y.cross(z);
        Ok(Self {
            x,
            y,
            z,
            gamma: s.atan2(v.dot(y).abs()),
            fallback_weight,
        })
    }

    /// The x axis (`y × z`).
    #[must_use]
    pub fn x_axis(&self) -> DVec3 {
        self.x
    }

    /// The y axis: toward the light.
    #[must_use]
    pub fn y_axis(&self) -> DVec3 {
        self.y
    }

    /// The z axis: ⟂ light, in the light–view plane, the view vector having a negative component.
    #[must_use]
    pub fn z_axis(&self) -> DVec3 {
        self.z
    }

    /// γ ∈ [0, π/2]: the smallest angle between the light and view directions (0 = parallel or
    /// anti-parallel, π/2 = perpendicular).
    #[must_use]
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// How much of the fallback axis is blended in: 0 for `sin γ ≥ s₀` (the paper's axis exactly), 1 at
    /// γ = 0.
    #[must_use]
    pub fn fallback_weight(&self) -> f64 {
        self.fallback_weight
    }

    /// The rotation world → light space (rows x, y, z).
    #[must_use]
    pub fn rotation(&self) -> DMat3 {
        DMat3::from_cols(self.x, self.y, self.z).transpose()
    }

    /// The rigid map world → light space with `origin` mapped to 0.
    #[must_use]
    pub fn world_to_light(&self, origin: DVec3) -> DAffine3 {
        let rotation = self.rotation();
        DAffine3::from_mat3_translation(rotation, -(rotation * origin))
    }

    /// Checks that the axes are unit, orthogonal and right-handed and γ is in range.
    ///
    /// # Errors
    /// [`ValidationError::NonFinite`] or [`ValidationError::NotOrthonormal`].
    pub fn validate(&self) -> Result<(), ValidationError> {
        let axes = [self.x, self.y, self.z];
        if axes.iter().any(|a| !a.is_finite()) || !self.gamma.is_finite() {
            return Err(ValidationError::NonFinite);
        }
        let unit = axes
            .iter()
            .all(|a| (a.length() - 1.0).abs() <= UNIT_LENGTH_TOLERANCE);
        let orthogonal = [(self.x, self.y), (self.y, self.z), (self.z, self.x)]
            .iter()
            .all(|(a, b)| a.dot(*b).abs() <= UNIT_LENGTH_TOLERANCE);
        let right_handed = (self.x.cross(self.y) - self.z).length() <= UNIT_LENGTH_TOLERANCE;
        let in_range = (0.0..=std::f64::consts::FRAC_PI_2).contains(&self.gamma);
        if unit && orthogonal && right_handed && in_range {
            Ok(())
        } else {
            Err(ValidationError::NotOrthonormal)
        }
    }
}

/// γ ∈ [0, π/2], the smallest angle between a view direction and a light vector, as
/// `atan2(|v × l|, |v·l|)` (accurate near 0 and π/2).
///
/// # Errors
/// [`HullError::NonFinite`] or [`HullError::ZeroVector`] naming `view_direction` or `to_light`.
pub fn light_view_angle(view_direction: DVec3, to_light: DVec3) -> Result<f64, HullError> {
    let v = unit_vec(view_direction, "view_direction")?;
    let l = unit_vec(to_light, "to_light")?;
    Ok(v.cross(l).length().atan2(v.dot(l).abs()))
}
