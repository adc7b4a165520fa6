//! What a technique produces: the light's view and projection (or, for the logarithmic map, its
//! exact non-projective mapping), and what it decided on the way.

use glam::{DMat4, DVec3};
use wide::f64x4;

use crate::homogeneous::point_of;
use crate::lanes::{self, LANES, Vectors};
use crate::logarithmic_map::LogarithmicMap;
use crate::paraboloid_map::ParaboloidMap;
use crate::technique::Technique;

/// How world points map to the shadow map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShadowMapping {
    /// GL clip space = `projection · view · (p, 1)`; window coordinates `(ndc + 1)/2`. Depth grows
    /// away from the light, so the depth test is `Less` for every technique (PSM's inverted lights
    /// included: their depth axis is flipped instead of the test).
    Projective(ProjectiveMapping),
    /// The logarithmic parameterisation, evaluated exactly (see [`LogarithmicMap`]).
    Logarithmic(LogarithmicMap),
    /// One hemisphere of a point light's dual-paraboloid map, evaluated exactly (see
    /// [`ParaboloidMap`]).
    Paraboloid(ParaboloidMap),
}

/// A [`ShadowMapping`] that maps four points at a time, in `wide` lanes (`lanes` module; each
/// lane the one-point function's IEEE operations in its order, so its bits).
#[derive(Clone, Copy, Debug)]
pub enum LaneMapping<'a> {
    /// World → GL clip space of a projective mapping.
    Projective(&'a DMat4),
    /// The logarithmic map.
    Logarithmic(&'a LogarithmicMap),
    /// A paraboloid hemisphere.
    Paraboloid(&'a ParaboloidMap),
}

impl LaneMapping<'_> {
    /// [`ShadowMapping::window`] of four points, and the lanes where it is `None` (their
    /// coordinates are meaningless numbers). A projective map's clip coordinates are divided as
    /// [`lanes::point_of`] divides them.
    #[inline(always)]
    #[must_use]
    pub fn windows(self, points: Vectors) -> (Vectors, [bool; LANES]) {
        let (ndc, undefined) = match self {
            Self::Projective(m) => {
                let clip = points.transformed(m, 1.0);
                let behind = clip[3].to_array().map(|w| w <= 0.0);
                (lanes::point_of(clip), behind)
            }
            Self::Logarithmic(map) => map.ndc_lanes(points),
            Self::Paraboloid(map) => map.ndc_lanes(points),
        };
        let (one, half) = (f64x4::ONE, f64x4::splat(0.5));
        let window = Vectors {
            x: (ndc.x + one) * half,
            y: (ndc.y + one) * half,
            z: (ndc.z + one) * half,
        };
        (window, undefined)
    }
}

/// A projective mapping: a view and a projection matrix, and their product formed once.
///
/// Every window position is `(projection · view) · (p, 1)` with the product already made, so a
/// lookup, a containment test or a depth gradient costs one matrix–vector product, not a
/// matrix–matrix product as well; the product is the same bits however often it is formed.
#[derive(Clone, Copy, Debug)]
pub struct ProjectiveMapping {
    view: DMat4,
    projection: DMat4,
    clip_from_world: DMat4,
}

impl ProjectiveMapping {
    /// The mapping `projection · view`.
    #[must_use]
    pub fn new(view: DMat4, projection: DMat4) -> Self {
        Self {
            view,
            projection,
            clip_from_world: projection * view,
        }
    }

    /// World → the technique's light view space (light space, or the virtual camera's eye space
    /// for PSM).
    #[must_use]
    pub fn view(&self) -> DMat4 {
        self.view
    }

    /// Light view space → GL clip space of the shadow map.
    #[must_use]
    pub fn projection(&self) -> DMat4 {
        self.projection
    }

    /// World → GL clip space: `projection · view`.
    #[must_use]
    pub fn clip_from_world(&self) -> DMat4 {
        self.clip_from_world
    }
}

/// Two mappings are equal when their view and projection are (the product follows from them).
impl PartialEq for ProjectiveMapping {
    fn eq(&self, other: &Self) -> bool {
        self.view == other.view && self.projection == other.projection
    }
}

impl ShadowMapping {
    /// The shadow-map window coordinates of a world point: `x, y ∈ [0, 1]` across the map and
    /// depth in `[0, 1]` (GL window depth) where the point lies inside the map's volume; `None` if
    /// the mapping sends it behind its projection centre.
    #[inline]
    #[must_use]
    pub fn window(&self, world: DVec3) -> Option<DVec3> {
        let ndc = match self {
            Self::Projective(mapping) => {
                let clip = mapping.clip_from_world * world.extend(1.0);
                if clip.w <= 0.0 {
                    return None;
                }
                point_of(clip)
            }
            Self::Logarithmic(map) => map.ndc(world)?,
            Self::Paraboloid(map) => map.ndc(world)?,
        };
        Some((ndc + DVec3::ONE) * 0.5)
    }

    /// The mapping as code that maps four points at a time takes it ([`LaneMapping`]).
    #[must_use]
    pub fn in_lanes(&self) -> LaneMapping<'_> {
        match self {
            Self::Projective(mapping) => LaneMapping::Projective(&mapping.clip_from_world),
            Self::Logarithmic(map) => LaneMapping::Logarithmic(map),
            Self::Paraboloid(map) => LaneMapping::Paraboloid(map),
        }
    }

    /// Whether the map is made by casting a ray per texel (the logarithmic and paraboloid maps,
    /// which are not projective: [`crate::ShadowMap::cast`]) rather than rasterized.
    #[must_use]
    pub fn is_cast(&self) -> bool {
        !matches!(self, Self::Projective(_))
    }

    /// World → GL clip space, for the projective techniques.
    #[must_use]
    pub fn clip_from_world(&self) -> Option<DMat4> {
        match self {
            Self::Projective(mapping) => Some(mapping.clip_from_world),
            Self::Logarithmic(_) | Self::Paraboloid(_) => None,
        }
    }
}

/// The warp a light-space technique chose, and what it chose it from.
#[derive(Clone, Debug, PartialEq)]
pub struct WarpReport {
    /// λ = n'/d; `f64::INFINITY` for the uniform map.
    pub lambda: f64,
    /// n', the distance from the projection reference point to P's near plane (world units in
    /// light space; spot lights: the spot's normalized device space); infinite for uniform.
    pub near_distance: f64,
    /// d, B's extent along the warp axis.
    pub depth: f64,
    /// The rule's formula and its source, in words.
    pub formula: String,
    /// The inputs the rule used, by name (`z_n`, `z_f`, `z0`, `z1`, `d`, `gamma_degrees`, …).
    pub inputs: Vec<(&'static str, f64)>,
}

/// A planned shadow map: how to render it and what was decided.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSetup {
    /// The technique that made it.
    pub technique: Technique,
    /// World → shadow map.
    pub mapping: ShadowMapping,
    /// γ, the angle between the view and light directions, radians in `[0, π/2]`.
    pub gamma: f64,
    /// φ, half the view's field of view in the light–view plane, radians.
    pub half_fov: f64,
    /// The warp parameter, for the light-space techniques (LiSPSM, uniform, logarithmic).
    pub warp: Option<WarpReport>,
    /// PSM only: the virtual camera's shift back along the view direction, and the near distance
    /// it kept.
    pub psm: Option<PsmReport>,
    /// The vertices of the focus body the map was fitted to, in world space.
    pub focus_body: Vec<DVec3>,
}

/// What PSM decided.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PsmReport {
    /// Δ, the virtual camera's shift back along the view direction (formulas.md §3.3).
    pub shift: f64,
    /// The near distance used (the nearest visible depth, or the camera's near plane).
    pub near: f64,
    /// Whether the light lies behind the viewer, so that it is *inverted* in post-perspective space
    /// (its rays converge): the shadow map keeps the surface furthest from the post-perspective
    /// light point (PSM §4.3; formulas.md §3.2).
    pub inverted: bool,
    /// Whether the light is parallel to the image plane, where it stays directional in
    /// post-perspective space (`|w'| ≤` [`crate::psm::DIRECTIONAL_W`] relative).
    pub directional: bool,
}
