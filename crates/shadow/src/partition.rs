//! A partition of a light's shadow: the eye depths it serves, the face or culling sphere that
//! bounds it, and its map's set-up — what planning makes and selection ([`crate::served`]) reads.

use glam::DVec3;

use crate::faces::FaceRegion;
use crate::setup::LightSetup;

/// One part of a partitioned shadow: the eye depths it serves (z-partitioning), the part of the
/// light's view it serves (face partitioning), and its map's set-up.
#[derive(Clone, Debug, PartialEq)]
pub struct Partition {
    /// The eye depth where it starts.
    pub near: f64,
    /// The eye depth where it ends.
    pub far: f64,
    /// For a face partition ([`crate::faces`]), the face of its z-partition's view whose projection
    /// it serves; `None`: all of the view at these depths.
    pub face: Option<FaceRegion>,
    /// For a cascade fitted to a bounding sphere, the sphere (`SelectionRule::Containing` tests
    /// it); `None` otherwise.
    pub sphere: Option<CullingSphere>,
    /// Its light set-up, planned for the sub-frustum `[near, far]` (and the face).
    pub setup: LightSetup,
}

/// A cascade's culling sphere (Unity URP: `_CascadeShadowSplitSpheres`): the bound the
/// `SelectionRule::Containing` rule tests where a cascade has one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CullingSphere {
    /// Its centre, world space.
    pub centre: DVec3,
    /// Its radius.
    pub radius: f64,
}

impl Partition {
    /// Whether its map contains `world`: inside its culling sphere (`|p − c|² < r²`) where it has
    /// one, else inside its map's window (`x, y ∈ [0, 1)`, depth in `[0, 1]`).
    #[must_use]
    pub fn contains(&self, world: DVec3) -> bool {
        if let Some(sphere) = self.sphere {
            return (world - sphere.centre).length_squared() < sphere.radius * sphere.radius;
        }
        self.setup.mapping.window(world).is_some_and(|w| {
            (0.0..1.0).contains(&w.x) && (0.0..1.0).contains(&w.y) && (0.0..=1.0).contains(&w.z)
        })
    }
}
