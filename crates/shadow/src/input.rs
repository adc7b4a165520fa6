//! What a technique plans from: the eye, the light, the scene bounds.

use glam::{DMat4, DVec3, DVec4};
use shadowlab_hull::{Aabb, Frustum, HullError, Light, Perspective, ViewPose};

/// The camera whose view is shadowed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eye {
    /// Position and orientation.
    pub pose: ViewPose,
    /// Field of view, aspect, near and far.
    pub projection: Perspective,
}

impl Eye {
    /// The view frustum V.
    #[must_use]
    pub fn frustum(&self) -> Frustum {
        Frustum::perspective(&self.pose, &self.projection)
    }

    /// World → GL clip space of the eye (`projection · view`).
    #[must_use]
    pub fn view_projection(&self) -> DMat4 {
        self.projection
            .matrix(shadowlab_hull::NdcDepth::NegativeOneToOne)
            * self.pose.view_matrix()
    }

    /// φ: half the field of view in the plane that holds the view direction and `toward`, the angle
    /// at which a ray of that plane leaves the frustum's side. For a light in the camera's vertical
    /// plane it is half the vertical field of view; in the horizontal plane, half the horizontal one;
    /// in between, the angle to the frustum's edge at that azimuth. If `toward` is parallel to the
    /// view direction (γ = 0, where the plane is undefined), the vertical half angle.
    #[must_use]
    pub fn half_fov_toward(&self, toward: DVec3) -> f64 {
        let v = self.pose.forward();
        let lateral = toward - v * toward.dot(v);
        let tan_y = self.projection.tan_half_fov_y();
        let tan_x = tan_y * self.projection.aspect();
        if lateral.length() <= PARALLEL_LATERAL * toward.length() {
            return tan_y.atan();
        }
        let lateral = lateral.normalize();
        let (cos_psi, sin_psi) = (
            lateral.dot(self.pose.up()).abs(),
            lateral.dot(self.pose.right()).abs(),
        );
        // Leaving through the top/bottom side at t = tan_y/cos ψ, through the left/right side at
        // t = tan_x/sin ψ; the nearer one bounds the frustum at this azimuth.
        let through_top = if cos_psi > 0.0 {
            tan_y / cos_psi
        } else {
            f64::INFINITY
        };
        let through_side = if sin_psi > 0.0 {
            tan_x / sin_psi
        } else {
            f64::INFINITY
        };
        through_top.min(through_side).atan()
    }
}

/// Below this ratio of lateral to total length, a direction counts as parallel to the view.
const PARALLEL_LATERAL: f64 = 1e-12;

/// A light that casts the shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSource {
    /// At infinity; `to_light` is the unit vector from the scene toward the light.
    Directional {
        /// Toward the light, unit.
        to_light: DVec3,
    },
    /// A spot light at `pose.eye()` shining along `pose.forward()`, lighting the frustum of `cone`.
    Spot {
        /// Position and direction.
        pose: ViewPose,
        /// Cone (as a perspective frustum: full cone angle as `fov_y`, aspect 1), near and far.
        cone: Perspective,
    },
    /// An omnidirectional point light at `position`, lighting nothing beyond `range` (if given).
    Point {
        /// Where it is.
        position: DVec3,
        /// The distance beyond which it lights nothing; `None`: unlimited.
        range: Option<f64>,
    },
}

impl LightSource {
    /// A directional light from a vector toward it (normalised here).
    ///
    /// # Errors
    /// [`HullError::ZeroVector`] or [`HullError::NonFinite`] naming `to_light`.
    pub fn directional(to_light: DVec3) -> Result<Self, HullError> {
        let light = Light::directional(to_light)?;
        Ok(Self::Directional {
            to_light: light.to_light().unwrap_or(DVec3::Y),
        })
    }

    /// The light as `shadowlab-hull` needs it for the focus bodies.
    #[must_use]
    pub fn hull_light(&self) -> Light {
        match self {
            Self::Directional { to_light } => {
                Light::directional(*to_light).expect("a LightSource's vector is unit")
            }
            Self::Spot { pose, cone } => Light::spot(pose, cone),
            Self::Point { position, .. } => {
                Light::point(*position).expect("a LightSource's position is finite")
            }
        }
    }

    /// The unit vector from `point` toward the light.
    #[must_use]
    pub fn toward_from(&self, point: DVec3) -> DVec3 {
        match self {
            Self::Directional { to_light } => *to_light,
            Self::Spot { pose, .. } => (pose.eye() - point).normalize_or(-pose.forward()),
            Self::Point { position, .. } => (*position - point).normalize_or(DVec3::Y),
        }
    }

    /// The light in homogeneous world coordinates: `(to_light, 0)` or `(position, 1)`.
    #[must_use]
    pub fn homogeneous(&self) -> DVec4 {
        match self {
            Self::Directional { to_light } => to_light.extend(0.0),
            Self::Spot { pose, .. } => pose.eye().extend(1.0),
            Self::Point { position, .. } => position.extend(1.0),
        }
    }

    /// Its kind: `directional`, `spot` or `point`.
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Directional { .. } => "directional",
            Self::Spot { .. } => "spot",
            Self::Point { .. } => "point",
        }
    }

    /// The light's position; `None` for a directional light.
    #[must_use]
    pub fn position(&self) -> Option<DVec3> {
        match self {
            Self::Directional { .. } => None,
            Self::Spot { pose, .. } => Some(pose.eye()),
            Self::Point { position, .. } => Some(*position),
        }
    }

    /// Whether the light reaches `point` at all: always for a directional light; for a spot, when
    /// `point` lies at most half its `fov_y` from its axis; for a point light, when it lies within
    /// its range. Outside, the light's volume — not a shadow map — darkens the point.
    #[must_use]
    pub fn reaches(&self, point: DVec3) -> bool {
        match self {
            Self::Directional { .. } => true,
            Self::Spot { pose, cone } => {
                (-self.toward_from(point)).dot(pose.forward()) >= (0.5 * cone.fov_y()).cos()
            }
            Self::Point { position, range } => {
                range.is_none_or(|range| (point - *position).length() <= range)
            }
        }
    }
}

/// Everything a technique plans from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanInput {
    /// The camera.
    pub eye: Eye,
    /// The light.
    pub light: LightSource,
    /// The scene's bounding box S.
    pub scene: Aabb,
    /// The nearest eye depth of a visible surface, read back from an eye depth pass: PSM pushes
    /// its near plane there (§6). `None`: the camera's near plane.
    pub nearest_visible_depth: Option<f64>,
    /// Which body the map is focused on.
    pub focus: FocusPolicy,
}

/// The body B a shadow map is fitted to (`--focus`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FocusPolicy {
    /// `light`: B = conv(V ∪ l) ∩ S ∩ L (PSM §4.1, LiSPSM §3.3): every potential occluder of a
    /// visible point.
    #[default]
    Light,
    /// `view-scene`: B = V ∩ S, the visible part of the scene bounds — the receivers, without the
    /// occluders between them and the light (those outside it cast no shadow into the map).
    ViewScene,
    /// `view`: B = V, the view frustum alone: the 2-D model of CAD eqs. 10–12 and GMNPR eq. 2,
    /// under which the closed forms of `shadowlab-params` hold exactly — the papers' own set-up.
    /// For measurement, not for rendering (it misses occluders outside the view).
    View,
}

impl FocusPolicy {
    /// Every policy.
    pub const ALL: [Self; 3] = [Self::Light, Self::ViewScene, Self::View];

    /// Its key: `light`, `view-scene`, `view`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Light => "light",
            Self::ViewScene => "view-scene",
            Self::View => "view",
        }
    }

    /// The policy named `key`.
    ///
    /// # Errors
    /// An unknown key, with the known ones.
    pub fn parse(key: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|p| p.key() == key)
            .ok_or_else(|| format!("unknown focus {key:?}; known: light, view-scene, view"))
    }
}
