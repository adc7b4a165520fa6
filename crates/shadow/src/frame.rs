//! Light space (LiSPSM §3.4), for directional lights in world space and for spot lights after the
//! spot's own perspective transform, where "point lights can be treated as directional lights from
//! this point on" (LiSPSM §3.4).

use glam::{DMat3, DMat4, DVec2, DVec3, DVec4};
use shadowlab_hull::{LightSpace, NdcDepth, ViewPose};

use crate::error::ShadowError;
use crate::input::{Eye, LightSource};
use crate::technique::Technique;

/// The techniques whose map does not depend on the eye's position in light space, only on the
/// focus body B: the uniform maps (κ = 0, an orthographic fit of B; frustum limiting clips B's
/// window with V's projection, which needs only V's corners) and the sample distribution map (an
/// orthographic box around the eye pass's samples, [`crate::sdsm`]). They are served where the eye
/// lies on or behind a spot light's plane, where the eye has no position in the spot's space.
const EYE_FREE_TECHNIQUES: [&str; 3] = ["uniform", "uniform_limited", "sdsm"];

/// Where a light-space technique works: an optional projective pre-transform (a spot light's
/// view-projection, after which its rays are parallel), then LiSPSM's light space with its origin at
/// the eye.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LightFrame {
    /// World → the space in which the light is directional (identity for a directional light).
    pre: DMat4,
    /// The axes (rows: x, y toward the light, z with the viewer looking down −z).
    rotation: DMat3,
    /// The eye, in the pre-transformed space: the light-space origin.
    origin: DVec3,
    /// γ, the angle between light and view directions in that space.
    gamma: f64,
}

impl LightFrame {
    /// The frame for `eye` and `light`.
    ///
    /// For a spot light whose plane the eye does not lie in front of (the eye at the light, or
    /// behind it), the techniques of [`EYE_FREE_TECHNIQUES`] get the spot's own axes: the viewer
    /// at the centre of its NDC cube looking along its image's +y, so the map is the spot's
    /// standard shadow map fitted to B.
    ///
    /// # Errors
    /// [`ShadowError::NotDefined`] for any other technique if the eye is not in front of a spot
    /// light (its perspective transform would fold the view); geometry errors from
    /// `shadowlab-hull`.
    pub(crate) fn new(
        eye: &Eye,
        light: &LightSource,
        technique: &'static str,
    ) -> Result<Self, ShadowError> {
        let (pre, pose, to_light) = match light {
            LightSource::Directional { to_light } => (DMat4::IDENTITY, eye.pose, *to_light),
            LightSource::Point { .. } => return Err(Technique::unserved_point_light(technique)),
            LightSource::Spot { pose, cone } => {
                let pre = cone.matrix(NdcDepth::NegativeOneToOne) * pose.view_matrix();
                let e = eye.pose.eye();
                let h = pre * e.extend(1.0);
                if h.w <= 0.0 {
                    if EYE_FREE_TECHNIQUES.contains(&technique) {
                        // The map does not depend on where the eye is: the spot's own axes serve.
                        let pose = ViewPose::look_to(DVec3::ZERO, DVec3::Y, DVec3::NEG_Z)?;
                        return Self::in_space(pre, &pose, DVec3::NEG_Z);
                    }
                    return Err(ShadowError::NotDefined {
                        technique,
                        reason: format!(
                            "the eye lies at or behind the spot light's position (on the far \
                             side of the plane through the light perpendicular to its \
                             direction), where the spot's perspective transform sends the eye to \
                             infinity and light space has no origin (LiSPSM §3.4); {} and psm \
                             serve such a light",
                            EYE_FREE_TECHNIQUES.join(", ")
                        ),
                    });
                }
                let origin = h.truncate() / h.w;
                // The tangent map of the projective transform at the eye carries the view and up
                // directions into the spot's space.
                let carry = |direction: DVec3| {
                    let d = pre * direction.extend(0.0);
                    (d.truncate() * h.w - h.truncate() * d.w) / (h.w * h.w)
                };
                let pose =
                    ViewPose::look_to(origin, carry(eye.pose.forward()), carry(eye.pose.up()))?;
                // In the spot's NDC its rays run along +z (near plane −1, far plane +1).
                (pre, pose, DVec3::NEG_Z)
            }
        };
        Self::in_space(pre, &pose, to_light)
    }

    /// The frame of a viewer at `pose` in the space after `pre`, where the light is directional
    /// toward `to_light`.
    fn in_space(pre: DMat4, pose: &ViewPose, to_light: DVec3) -> Result<Self, ShadowError> {
        let space = LightSpace::new(pose, to_light)?;
        Ok(Self {
            pre,
            rotation: DMat3::from_cols(space.x_axis(), space.y_axis(), space.z_axis()).transpose(),
            origin: pose.eye(),
            gamma: space.gamma(),
        })
    }

    /// The same frame turned about its y axis (the light) so that its warp axis — the direction
    /// the viewer looks along, −z — becomes `axis`, a unit vector given in this frame's (x, z);
    /// γ is kept (a face partition's warp, [`crate::faces`]).
    pub(crate) fn turned(&self, axis: DVec2) -> Self {
        // New z = −axis; new x = y × z, both written in the old frame's coordinates.
        let z = DVec3::new(-axis.x, 0.0, -axis.y);
        let x = DVec3::new(z.z, 0.0, -z.x);
        let turn = DMat3::from_cols(x, DVec3::Y, z).transpose();
        Self {
            rotation: turn * self.rotation,
            ..*self
        }
    }

    /// γ ∈ `[0, π/2]`.
    pub(crate) fn gamma(&self) -> f64 {
        self.gamma
    }

    /// World → light space, as a projective 4×4 matrix (affine for a directional light).
    pub(crate) fn world_to_light(&self) -> DMat4 {
        let rotate = DMat4::from_mat3(self.rotation);
        rotate * DMat4::from_translation(-self.origin) * self.pre
    }

    /// A world point in light space (`None` if a spot's transform sends it behind the light).
    pub(crate) fn light_point(&self, world: DVec3) -> Option<DVec3> {
        let h: DVec4 = self.world_to_light() * world.extend(1.0);
        (h.w > 0.0).then(|| h.truncate() / h.w)
    }

    /// The camera's near and far distances along its view axis, measured in the space where the
    /// light is directional: `eye`'s own for a directional light, and for a spot light the
    /// distances from the eye to the view axis's near and far points after the spot's transform
    /// (LiSPSM §3.4: "point lights can be treated as directional lights from this point on").
    /// `None` if a spot's transform sends one of them behind the light.
    pub(crate) fn view_range(&self, eye: &Eye) -> Option<(f64, f64)> {
        let projection = eye.projection;
        if self.pre == DMat4::IDENTITY {
            return Some((projection.near(), projection.far()));
        }
        let (e, v) = (eye.pose.eye(), eye.pose.forward());
        let origin = self.light_point(e)?;
        let distance = |t: f64| Some((self.light_point(e + v * t)? - origin).length());
        Some((distance(projection.near())?, distance(projection.far())?))
    }

    /// Light-space points of a set of world points; `None` if one is behind a spot light.
    pub(crate) fn light_points(&self, world: &[DVec3]) -> Option<Vec<DVec3>> {
        world.iter().map(|p| self.light_point(*p)).collect()
    }
}
