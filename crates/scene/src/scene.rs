//! A resolved scene: the mesh, the camera, the lights and the shadow settings a scene file
//! suggests, every value validated and every default filled in (see [`crate::scene_file`]).

use glam::{DMat4, DVec3};
use shadowlab_hull::{Light, NdcDepth, Perspective, ViewPose};

use crate::bounds::Bounds;
use crate::mesh::Mesh;

/// A scene ready to render: one mesh, a camera, at least one light, and shadow settings.
///
/// # Guarantees
/// From [`crate::load_scene`], [`crate::parse_scene`] and [`crate::builtin_scene`]: `lights` is
/// not empty; the mesh has one group per mesh entry of the file, in file order, named by the
/// entry's `name`, so a triangle's group id is the index of the entry it came from. The fields are
/// public, so a hand-built value carries no guarantee.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The scene's name (the file's `name`, or its stem).
    pub name: String,
    /// The eye's camera.
    pub camera: Camera,
    /// The lights, in file order; at least one.
    pub lights: Vec<SceneLight>,
    /// Every mesh entry, transformed and merged ([`Mesh::try_merged`]); group `k` is entry `k`.
    pub mesh: Mesh,
    /// What the file suggests for the shadow technique; unvalidated.
    pub shadow: ShadowSettings,
}

impl Scene {
    /// The axis-aligned bounds of the mesh: the scene box S of the focusing papers.
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        self.mesh.bounds()
    }
}

/// The eye's camera: where it is, how it projects, and the size of its image.
///
/// # Guarantees
/// From a scene file: `width` and `height` are at least 1 and `projection.aspect()` is
/// `width / height`.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Position and orientation (`ViewPose::look_at` / `look_to`): the camera looks down its
    /// eye-space −z.
    pub pose: ViewPose,
    /// The perspective projection: vertical field of view in radians, aspect = width / height,
    /// near and far distances along the view direction.
    pub projection: Perspective,
    /// The image width in pixels.
    pub width: u32,
    /// The image height in pixels.
    pub height: u32,
}

impl Camera {
    /// The world → clip matrix `projection · view` for the given NDC depth range (column vectors,
    /// `clip = M · (p, 1)`); [`NdcDepth::NegativeOneToOne`] is GL's clip space, which
    /// `shadowlab-raster` draws.
    #[must_use]
    pub fn view_projection(&self, ndc: NdcDepth) -> DMat4 {
        self.projection.matrix(ndc) * self.pose.view_matrix()
    }
}

/// A light of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneLight {
    /// A light at infinity.
    Directional {
        /// The unit vector **from the scene toward the light** (hull's convention, LiSPSM §3.4's
        /// light vector): the negated, normalised `direction` of the scene file, which is the
        /// direction the light *travels*.
        to_light: DVec3,
    },
    /// A spot light at `pose.eye()`, shining along `pose.forward()`.
    Spot {
        /// Position and travel direction (and an up vector that orients the light's image).
        pose: ViewPose,
        /// The cone as a perspective frustum: `fov_y` is the full cone angle, aspect 1, near and
        /// far along the travel direction. Its frustum is the light frustum L of PSM §4.1.
        cone: Perspective,
    },
    /// An omnidirectional point light (`KHR_lights_punctual`'s `point`): it lights every direction
    /// (PSM §4.1: its light frustum L is all space).
    Point {
        /// Where it is.
        position: DVec3,
        /// The distance beyond which it lights nothing (`KHR_lights_punctual`'s `range`); `None`:
        /// unlimited. Positive and finite.
        range: Option<f64>,
    },
}

impl SceneLight {
    /// hull's [`Light`]: [`Light::directional`], [`Light::spot`] or [`Light::point`].
    ///
    /// # Panics
    /// If `to_light` is zero or not finite, or `position` not finite, which a scene file's light
    /// never is (only a hand-built value can be).
    #[must_use]
    pub fn light(&self) -> Light {
        match self {
            Self::Directional { to_light } => Light::directional(*to_light)
                .unwrap_or_else(|error| panic!("SceneLight::light: {error}")),
            Self::Spot { pose, cone } => Light::spot(pose, cone),
            Self::Point { position, .. } => {
                Light::point(*position).unwrap_or_else(|error| panic!("SceneLight::light: {error}"))
            }
        }
    }
}

/// The shadow settings a scene file may suggest (its `[shadow]` table). They are raw and optional
/// here: the `shadow` crate and the command-line tool validate the names and values, and settings
/// given on the command line override these.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShadowSettings {
    /// The technique, e.g. `"lispsm"`.
    pub technique: Option<String>,
    /// The technique's warp parameter, as text (e.g. a rule's name).
    pub parameter: Option<String>,
    /// The warp's λ, instead of a named parameter (finite).
    pub lambda: Option<f64>,
    /// The warp's near distance n, instead of a named parameter (finite).
    pub n: Option<f64>,
    /// The focus body, e.g. `"light"`.
    pub focus: Option<String>,
    /// The shadow map's width and height in texels.
    pub resolution: Option<u32>,
    /// The number of z-partitions (cascades); the field `partitions` (or `splits`, its former name).
    pub partitions: Option<u32>,
    /// How the view frustum is split, e.g. `"practical"`.
    pub split_scheme: Option<String>,
    /// The depth bias.
    pub bias: Option<String>,
    /// The lookup filter, e.g. `"pcf"`.
    pub filter: Option<String>,
    /// The scene-optimized map's read-back size, `"WxH"`.
    pub optimal_readback: Option<String>,
    /// The side of its initial map.
    pub optimal_initial: Option<u32>,
    /// Its most iterations.
    pub optimal_iterations: Option<u32>,
    /// Its border around the samples (finite).
    pub optimal_border: Option<f64>,
}
