//! One frame of a scene: the eye pass, every light's shadow maps, and the lookups — timed per
//! phase, as the analyzer needs them.

use std::time::{Duration, Instant};

use glam::DVec3;
use rayon::prelude::*;
use shadowlab_hull::{Aabb, NdcDepth};
use shadowlab_raster::{
    DepthFormat, EyeImage, EyeTarget, NO_TRIANGLE, RasterOptions, Rasterizer, Triangles,
};
use shadowlab_scene::{Scene, SceneLight};
use shadowlab_trace::Bvh;

use crate::error::ShadowError;
use crate::input::{Eye, FocusPolicy, LightSource, PlanInput};
use crate::lookup::Lookup;
use crate::map::{MapOptions, ShadowMap};
use crate::optimal::{self, OptimalOptions};
use crate::plan::{Partition, Splits, plan_partitions, serving};
use crate::setup::ShadowMapping;
use crate::snap::snap_to_texels;
use crate::technique::Technique;

/// How one light's maps are planned: the technique, the z-partitions, the focus body and the
/// scene-optimized map's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanOptions {
    /// The technique of every map.
    pub technique: Technique,
    /// Number of z-partitions (1: one map per light).
    pub partitions: usize,
    /// How the depth range is split when `partitions > 1`.
    pub splits: Splits,
    /// The body B each map is fitted to.
    pub focus: FocusPolicy,
    /// The scene-optimized map's settings (read-back size, initial map, iterations, border) when
    /// the technique is [`Technique::Optimal`]; their step direction is the technique's.
    pub optimal: OptimalOptions,
}

impl PlanOptions {
    /// One map per light by `technique`, focused on B = conv(V ∪ l) ∩ S ∩ L, the optimizer's
    /// defaults.
    #[must_use]
    pub fn new(technique: Technique) -> Self {
        Self {
            technique,
            partitions: 1,
            splits: Splits::DEFAULT,
            focus: FocusPolicy::Light,
            optimal: OptimalOptions::default(),
        }
    }
}

/// How a frame's shadows are made and read.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameOptions {
    /// How each light's maps are planned.
    pub plan: PlanOptions,
    /// Side of each shadow map, in texels.
    pub resolution: u32,
    /// The maps' depth format.
    pub format: DepthFormat,
    /// Bias and filter.
    pub lookup: Lookup,
    /// Texel snapping against shimmer ([`crate::snap_to_texels`]): each map's window moved so the
    /// world origin falls on the corner of this many texels' grid; 0 leaves the windows alone.
    pub snap_texels: u32,
}

/// One light's shadow: its partitions and their maps.
#[derive(Clone, Debug, PartialEq)]
pub struct LightShadow {
    /// The light.
    pub light: LightSource,
    /// The partitions (one if unpartitioned), nearest first, each with its rendered map.
    pub maps: Vec<(Partition, ShadowMap)>,
}

/// Wall-clock time of each phase of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Timings {
    /// The eye pass and its resolve into positions and normals.
    pub eye_pass: Duration,
    /// Planning: focus bodies and warp parameters.
    pub planning: Duration,
    /// Rendering the shadow maps.
    pub shadow_pass: Duration,
    /// Looking every visible point up.
    pub lookup: Duration,
}

/// A frame's shadows, made for an eye pass that already exists ([`render_shadows`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Shadows {
    /// Per light, its maps.
    pub lights: Vec<LightShadow>,
    /// Per light, how lit each pixel's visible point is (1 where nothing is visible).
    pub lit: Vec<Vec<f64>>,
    /// Time per phase (`eye_pass` is zero: the pass was made before).
    pub timings: Timings,
}

/// A rendered frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The eye pass: depth, triangle, world position and normal per pixel (row 0 at the bottom).
    pub eye: EyeImage,
    /// Per light, its maps.
    pub lights: Vec<LightShadow>,
    /// Per light, how lit each pixel's visible point is (1 where nothing is visible).
    pub lit: Vec<Vec<f64>>,
    /// Time per phase.
    pub timings: Timings,
}

impl LightSource {
    /// The light of a scene.
    #[must_use]
    pub fn from_scene(light: &SceneLight) -> Self {
        match light {
            SceneLight::Directional { to_light } => Self::Directional {
                to_light: *to_light,
            },
            SceneLight::Spot { pose, cone } => Self::Spot {
                pose: *pose,
                cone: *cone,
            },
        }
    }
}

/// The eye pass of `scene`: depth, triangle, world position and normal per pixel, and the nearest
/// eye depth of a visible surface (PSM's near plane), `None` if nothing is visible.
///
/// # Errors
/// The rasterizer's.
pub fn eye_pass(scene: &Scene) -> Result<(EyeImage, Option<f64>), ShadowError> {
    let camera = &scene.camera;
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let clip_from_world = camera.view_projection(NdcDepth::NegativeOneToOne);
    let mut target = EyeTarget::new(camera.width, camera.height, DepthFormat::F32)?;
    Rasterizer::new(RasterOptions::default()).draw_eye(&mut target, mesh, &clip_from_world)?;
    let image = target.resolve(mesh, scene.mesh.normals(), &clip_from_world)?;
    let nearest = eye_depths(&image, &scene_eye(scene))
        .iter()
        .flatten()
        .fold(f64::INFINITY, |a, b| a.min(*b));
    Ok((image, nearest.is_finite().then_some(nearest)))
}

/// The scene's camera as a technique sees it.
#[must_use]
pub fn scene_eye(scene: &Scene) -> Eye {
    Eye {
        pose: scene.camera.pose,
        projection: scene.camera.projection,
    }
}

/// The thickness a flat scene box S is given on its flat axes, relative to its largest extent: a
/// ground plane alone is a scene (nothing casts a shadow, every map must still serve it), but a
/// box with no volume has no polyhedron to clip the focus body with. 10⁻⁶ is a thousand times
/// hull's relative snap distance (`Tolerances::DEFAULT`, 10⁻⁹ of the diagonal), so the thickened
/// box is a body, and small enough to change no map's fit by more than that fraction.
pub const FLAT_SCENE_THICKNESS: f64 = 1e-6;

/// The thickness a flat scene box is given in units of ε times its largest coordinate magnitude,
/// where that is more than [`FLAT_SCENE_THICKNESS`] of its extent (a small scene far from the
/// origin): 64 times hull's `rounding_ulps`, so the box stays thicker than the snap distance.
pub const FLAT_SCENE_ULPS: f64 = 4096.0;

/// The scene box S of `scene`: its bounds, thickened symmetrically on any axis thinner than the
/// larger of [`FLAT_SCENE_THICKNESS`] × its largest extent and [`FLAT_SCENE_ULPS`]·ε × its largest
/// coordinate magnitude, so that a flat scene (a ground plane alone) is served.
///
/// # Errors
/// [`ShadowError::Geometry`] for bounds that are not a box (a hand-built scene's).
pub fn scene_box(scene: &Scene) -> Result<Aabb, ShadowError> {
    let bounds = scene.bounds();
    let size = bounds.size();
    let magnitude = bounds.min.abs().max(bounds.max.abs()).max_element();
    let thickness =
        (FLAT_SCENE_THICKNESS * size.max_element()).max(FLAT_SCENE_ULPS * f64::EPSILON * magnitude);
    let pad = (DVec3::splat(thickness) - size).max(DVec3::ZERO) * 0.5;
    Ok(Aabb::new(bounds.min - pad, bounds.max + pad)?)
}

/// What a technique plans from for `light` of `scene`: the scene's camera and box
/// ([`scene_box`]), PSM's near plane at `nearest_visible_depth`, and the `focus` policy.
///
/// # Errors
/// As [`scene_box`].
pub fn scene_input(
    scene: &Scene,
    light: &SceneLight,
    nearest_visible_depth: Option<f64>,
    focus: FocusPolicy,
) -> Result<PlanInput, ShadowError> {
    Ok(PlanInput {
        eye: scene_eye(scene),
        light: LightSource::from_scene(light),
        scene: scene_box(scene)?,
        nearest_visible_depth,
        focus,
    })
}

/// Plans one light of `scene` as `options` says: `partitions` z-partitions split by `splits` (one:
/// the whole view), each with the technique, focused on `focus`, PSM's near plane at
/// `nearest_visible_depth`. [`Technique::Optimal`] is planned from the scene itself with the
/// optimizer's settings and the technique's step direction: a low-resolution eye pass, then each
/// partition optimized on its own samples ([`crate::optimal::plan_partitions`]).
///
/// # Errors
/// As [`plan_partitions`] (or [`crate::optimal::plan_partitions`]); an invalid scene box.
pub fn plan_light(
    scene: &Scene,
    light: &SceneLight,
    options: &PlanOptions,
    nearest_visible_depth: Option<f64>,
) -> Result<Vec<Partition>, ShadowError> {
    let input = scene_input(scene, light, nearest_visible_depth, options.focus)?;
    let partitions = options.partitions.max(1);
    if let Technique::Optimal(direction) = options.technique {
        let optimal = OptimalOptions {
            direction,
            ..options.optimal
        };
        return Ok(
            optimal::plan_partitions(scene, &input, options.splits, partitions, &optimal)?
                .into_iter()
                .map(|(partition, _)| partition)
                .collect(),
        );
    }
    plan_partitions(&input, options.technique, options.splits, partitions)
}

/// Renders `scene` with shadows made as `options` says: the eye pass, then [`render_shadows`].
///
/// # Errors
/// As [`crate::plan`] (the technique undefined for a light, an empty focus body, …) and the
/// rasterizer's.
pub fn render_frame(scene: &Scene, options: &FrameOptions) -> Result<Frame, ShadowError> {
    let start = Instant::now();
    let (eye, nearest_visible) = eye_pass(scene)?;
    let eye_time = start.elapsed();
    let shadows = render_shadows(scene, options, &eye, nearest_visible, None)?;
    Ok(Frame {
        eye,
        lights: shadows.lights,
        lit: shadows.lit,
        timings: Timings {
            eye_pass: eye_time,
            ..shadows.timings
        },
    })
}

/// The shadows of `scene` as `options` says, for its eye pass `eye` (from [`eye_pass`], with
/// `nearest_visible` its nearest visible depth): plan, render the maps, look every visible point
/// up. A study that tries many options on one view makes the eye pass once. `bvh`, the scene's
/// ray-casting hierarchy, is what the logarithmic map is cast against; without it one is built.
///
/// # Errors
/// As [`render_frame`], and [`ShadowError::Trace`] if the hierarchy cannot be built.
pub fn render_shadows(
    scene: &Scene,
    options: &FrameOptions,
    eye: &EyeImage,
    nearest_visible: Option<f64>,
    bvh: Option<&Bvh>,
) -> Result<Shadows, ShadowError> {
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let depths = eye_depths(eye, &scene_eye(scene));
    let mut timings = Timings::default();
    let built;
    let bvh = match (options.plan.technique, bvh) {
        (_, Some(bvh)) => Some(bvh),
        (Technique::Logarithmic(_), None) => {
            built = Bvh::new(scene.mesh.positions(), scene.mesh.triangles())?;
            Some(&built)
        }
        _ => None,
    };
    let map_options = MapOptions {
        resolution: options.resolution,
        format: options.format,
        second_depth: options.lookup.bias.needs_second_depth(),
    };
    let mut lights = Vec::with_capacity(scene.lights.len());
    for scene_light in &scene.lights {
        let start = Instant::now();
        let mut partitions = plan_light(scene, scene_light, &options.plan, nearest_visible)?;
        if options.snap_texels > 0 {
            for partition in &mut partitions {
                partition.setup =
                    snap_to_texels(&partition.setup, options.resolution, options.snap_texels);
            }
        }
        timings.planning += start.elapsed();
        let start = Instant::now();
        let maps = partitions
            .into_iter()
            .map(|partition| {
                let map = match (&partition.setup.mapping, bvh) {
                    (ShadowMapping::Logarithmic(_), Some(bvh)) => {
                        ShadowMap::cast(&partition.setup, bvh, map_options)
                    }
                    _ => ShadowMap::render(&partition.setup, mesh, map_options),
                }?;
                Ok((partition, map))
            })
            .collect::<Result<Vec<_>, ShadowError>>()?;
        timings.shadow_pass += start.elapsed();
        lights.push(LightShadow {
            light: LightSource::from_scene(scene_light),
            maps,
        });
    }

    let start = Instant::now();
    let lit = lights
        .iter()
        .map(|shadow| look_up(eye, &depths, shadow, &options.lookup))
        .collect();
    timings.lookup = start.elapsed();
    Ok(Shadows {
        lights,
        lit,
        timings,
    })
}

/// The eye depth `(p − e)·v` of each pixel's visible point (`None` where nothing is visible).
fn eye_depths(image: &EyeImage, eye: &Eye) -> Vec<Option<f64>> {
    let (e, v) = (eye.pose.eye(), eye.pose.forward());
    image
        .triangle
        .iter()
        .zip(&image.position)
        .map(|(t, p)| (*t != NO_TRIANGLE).then(|| (*p - e).dot(v)))
        .collect()
}

/// Rows of pixels looked up per parallel job; any size gives the same result.
const LOOKUP_ROWS: usize = 8;

/// How lit each pixel's visible point is by one light.
fn look_up(
    image: &EyeImage,
    depths: &[Option<f64>],
    shadow: &LightShadow,
    lookup: &Lookup,
) -> Vec<f64> {
    let width = image.width as usize;
    let mut lit = vec![1.0; image.triangle.len()];
    lit.par_chunks_mut(width * LOOKUP_ROWS)
        .enumerate()
        .for_each(|(chunk, rows)| {
            let first = chunk * width * LOOKUP_ROWS;
            for (k, value) in rows.iter_mut().enumerate() {
                let pixel = first + k;
                let Some(depth) = depths[pixel] else {
                    continue;
                };
                let position: DVec3 = image.position[pixel];
                let index = serving(&shadow.maps, |(p, _)| p, position, depth);
                let map = &shadow.maps[index].1;
                *value = lookup.lit_fraction(map, position, image.normal[pixel]);
            }
        });
    lit
}
