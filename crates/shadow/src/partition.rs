//! A partition of a light's shadow: the eye depths it serves, the face or culling sphere that
//! bounds it, and its map's set-up — what planning makes and selection ([`crate::served`]) reads.

use glam::DVec3;

use crate::faces::FaceRegion;
use crate::omni::LightFace;
use crate::setup::LightSetup;

/// One part of a partitioned shadow: the eye depths it serves (z-partitioning), the part of the
/// light's view it serves (face partitioning), and its map's set-up.
#[derive(Clone, Debug, PartialEq)]
pub struct Partition {
    /// The eye depth where it starts.
    pub near: f64,
    /// The eye depth where it ends.
    pub far: f64,
    /// The part of the view it serves among partitions of the same depths: a face of its
    /// z-partition's view ([`crate::faces`]) or of a point light's cube or dual paraboloid
    /// ([`LightFace`]); `None`: all of the view at these depths.
    pub face: Option<Region>,
    /// For a cascade fitted to a bounding sphere, the sphere (`SelectionRule::Containing` tests
    /// it); `None` otherwise.
    pub sphere: Option<CullingSphere>,
    /// Its light set-up, planned for the sub-frustum `[near, far]` (and the face).
    pub setup: LightSetup,
}

/// The part of the view a partition serves among those of the same depths: the one whose region
/// holds a point most deeply serves it ([`crate::served`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Region {
    /// A face of the view frustum, as the light sees it (the logarithmic map's face partitioning).
    ViewFace(FaceRegion),
    /// A face of a point light's cube, or a hemisphere of its dual-paraboloid map.
    LightFace(LightFace),
}

impl Region {
    /// How far inside the region `world` lies (positive inside): [`FaceRegion::inside`] or
    /// [`LightFace::inside`].
    #[must_use]
    pub fn inside(&self, world: DVec3) -> f64 {
        match self {
            Self::ViewFace(face) => face.inside(world),
            Self::LightFace(face) => face.inside(world),
        }
    }

    /// Its name: the view face's (`left`, …, `far`) or the light face's (`+x`, …, `front`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::ViewFace(face) => face.name(),
            Self::LightFace(face) => face.name,
        }
    }

    /// The view face, if it is one.
    #[must_use]
    pub fn view_face(&self) -> Option<&FaceRegion> {
        match self {
            Self::ViewFace(face) => Some(face),
            Self::LightFace(_) => None,
        }
    }
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
