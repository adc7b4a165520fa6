//! Lights: where shadows come from. A directional light has a direction; a point light a position; a
//! spot light a position and a frustum L (PSM §4.1: for directional and omnidirectional lights L is
//! all space).

use glam::DVec3;

use crate::camera::{Perspective, ViewPose};
use crate::error::HullError;
use crate::finite::{finite_vec, unit_vec};
use crate::frustum::Frustum;

/// A light source.
///
/// # Guarantees
/// Finite data; a directional light's vector is unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    kind: Kind,
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Directional {
        to_light: DVec3,
    },
    Point {
        position: DVec3,
    },
    Spot {
        position: DVec3,
        frustum: Box<Frustum>,
    },
}

/// Where the light is, as the extrusion needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Source {
    /// A unit vector pointing toward a light at infinity.
    Direction(DVec3),
    /// A light position.
    Position(DVec3),
}

impl Light {
    /// A directional light; `to_light` points **from the scene toward the light** (the opposite of
    /// the direction light travels), as LiSPSM §3.4's light vector and formulas.md §3.2's `l` do.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] or [`HullError::ZeroVector`] naming `to_light`.
    pub fn directional(to_light: DVec3) -> Result<Self, HullError> {
        Ok(Self {
            kind: Kind::Directional {
                to_light: unit_vec(to_light, "to_light")?,
            },
        })
    }

    /// An omnidirectional point light (L is all space).
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `position`.
    pub fn point(position: DVec3) -> Result<Self, HullError> {
        Ok(Self {
            kind: Kind::Point {
                position: finite_vec(position, "position")?,
            },
        })
    }

    /// A spot light at `pose.eye()` shining along `pose.forward()`, whose light frustum L is the
    /// perspective frustum of `cone` (its field of view, aspect, near and far).
    #[must_use]
    pub fn spot(pose: &ViewPose, cone: &Perspective) -> Self {
        Self {
            kind: Kind::Spot {
                position: pose.eye(),
                frustum: Box::new(Frustum::perspective(pose, cone)),
            },
        }
    }

    /// The unit vector toward a directional light; `None` for point and spot lights.
    #[must_use]
    pub fn to_light(&self) -> Option<DVec3> {
        match &self.kind {
            Kind::Directional { to_light } => Some(*to_light),
            Kind::Point { .. } | Kind::Spot { .. } => None,
        }
    }

    /// The position of a point or spot light; `None` for a directional light.
    #[must_use]
    pub fn position(&self) -> Option<DVec3> {
        match &self.kind {
            Kind::Directional { .. } => None,
            Kind::Point { position } | Kind::Spot { position, .. } => Some(*position),
        }
    }

    /// The light frustum L of a spot light; `None` (all space) otherwise.
    #[must_use]
    pub fn frustum(&self) -> Option<&Frustum> {
        match &self.kind {
            Kind::Spot { frustum, .. } => Some(frustum),
            Kind::Directional { .. } | Kind::Point { .. } => None,
        }
    }

    /// LiSPSM §3.4's light vector, a unit vector pointing toward the light: a directional light's
    /// vector; for a spot light the reversed spot direction ("the spot direction vector is used");
    /// for a point light, which the paper leaves open, the direction from `reference` (e.g. the
    /// centroid of B) to the light.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `reference`; [`HullError::ZeroVector`] naming `reference` if it
    /// is at a point light's position.
    pub fn light_vector(&self, reference: DVec3) -> Result<DVec3, HullError> {
        let reference = finite_vec(reference, "reference")?;
        match &self.kind {
            Kind::Directional { to_light } => Ok(*to_light),
            Kind::Spot { frustum, .. } => Ok(-frustum.view_direction()),
            Kind::Point { position } => unit_vec(*position - reference, "reference"),
        }
    }

    pub(crate) fn source(&self) -> Source {
        match &self.kind {
            Kind::Directional { to_light } => Source::Direction(*to_light),
            Kind::Point { position } | Kind::Spot { position, .. } => Source::Position(*position),
        }
    }
}
