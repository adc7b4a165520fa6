//! One frame of a scene: the eye pass, every light's shadow maps, and the lookups — timed per
//! phase, as the analyzer needs them.

use std::time::{Duration, Instant};

use glam::{DMat4, DVec3};
use rayon::prelude::*;
use shadowlab_hull::{Aabb, NdcDepth};
use shadowlab_raster::{
    DepthFormat, EyeImage, EyeTarget, NO_TRIANGLE, RasterOptions, Rasterizer, Triangles,
};
use shadowlab_scene::{Scene, SceneLight};
use shadowlab_trace::Bvh;

use crate::error::ShadowError;
use crate::gather::gather;
use crate::input::{Eye, FocusPolicy, LightSource, PlanInput};
use crate::lanes::LANES;
use crate::lookup::Lookup;
use crate::map::{MapOptions, ShadowMap};
use crate::optimal::{self, OptimalOptions};
use crate::partition::{Partition, Region};
use crate::plan::{Splits, plan_partitions};
use crate::selection::Selection;
use crate::serving::{Served, served, sole_map};
use crate::snap::snap_to_texels;
use crate::technique::Technique;
use crate::{cube, paraboloid, sdsm};

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
    /// How each map is read (`lookups[k]` for `maps[k]`).
    pub lookups: Vec<Lookup>,
    /// Which map serves a visible point ([`served`]).
    pub selection: Selection,
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
            SceneLight::Point { position, range } => Self::Point {
                position: *position,
                range: *range,
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
    let image = eye_image(
        scene,
        &scene.camera.view_projection(NdcDepth::NegativeOneToOne),
    )?;
    let eye = scene_eye(scene);
    let (e, v) = (eye.pose.eye(), eye.pose.forward());
    let nearest = image
        .triangle
        .iter()
        .zip(&image.position)
        .filter(|(t, _)| **t != NO_TRIANGLE)
        .map(|(_, p)| (*p - e).dot(v))
        .fold(f64::INFINITY, f64::min);
    Ok((image, nearest.is_finite().then_some(nearest)))
}

/// The eye pass of `scene`'s mesh through `clip_from_world` (world → GL clip space), into an
/// image of the size of the scene's camera: depth, triangle, world position and normal per pixel
/// (row 0 at the bottom). [`eye_pass`] draws it through the scene's camera; a camera given as
/// matrices (a set-up file's) is drawn through those matrices, so that the same matrices give the
/// same image.
///
/// # Errors
/// The rasterizer's.
pub fn eye_image(scene: &Scene, clip_from_world: &DMat4) -> Result<EyeImage, ShadowError> {
    let camera = &scene.camera;
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let mut target = EyeTarget::new(camera.width, camera.height, DepthFormat::F32)?;
    Rasterizer::new(RasterOptions::default()).draw_eye(&mut target, mesh, clip_from_world)?;
    Ok(target.resolve(mesh, scene.mesh.normals(), clip_from_world)?)
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

/// Plans one light of `scene` as `options` says, for maps of `resolution` texels: `partitions`
/// z-partitions split by `splits` (one: the whole view), each with the technique, focused on
/// `focus`, PSM's near plane at `nearest_visible_depth`. [`Technique::Optimal`] is planned from the
/// scene itself with the optimizer's settings and the technique's step direction: a low-resolution
/// eye pass, then each partition optimized on its own samples
/// ([`crate::optimal::plan_partitions`]). [`Technique::Sdsm`] is fitted to the visible samples of
/// `eye`, the eye pass ([`crate::sdsm::plan`]). An engine's preset ([`Technique::Engine`]) plans its own
/// cascades ([`crate::presets`]); the partition count and splits do not apply to it.
///
/// # Errors
/// As [`plan_partitions`] (or [`crate::optimal::plan_partitions`], [`crate::Engine::plan`],
/// [`crate::sdsm::plan`]); [`ShadowError::NotDefined`] for SDSM without an eye pass; an invalid
/// scene box.
pub fn plan_light(
    scene: &Scene,
    light: &SceneLight,
    options: &PlanOptions,
    nearest_visible_depth: Option<f64>,
    resolution: u32,
    eye: Option<&EyeImage>,
) -> Result<Vec<Partition>, ShadowError> {
    let input = scene_input(scene, light, nearest_visible_depth, options.focus)?;
    options.technique.check_light(&input.light)?;
    let partitions = options.partitions.max(1);
    match options.technique {
        Technique::Cube | Technique::DualParaboloid => {
            let (near, far) = (input.eye.projection.near(), input.eye.projection.far());
            let (positions, triangles) = (scene.mesh.positions(), scene.mesh.triangles());
            let faces = if options.technique == Technique::Cube {
                cube::plan(&input, positions, triangles)?
            } else {
                paraboloid::plan(&input, positions, triangles)?
            };
            return Ok(faces
                .into_iter()
                .map(|(face, setup)| Partition {
                    near,
                    far,
                    face: Some(Region::LightFace(face)),
                    sphere: None,
                    setup,
                })
                .collect());
        }
        Technique::Engine(engine, choices) => {
            return engine.plan(&input, options.technique, choices, resolution);
        }
        Technique::Sdsm(variant) => {
            let image = eye.ok_or_else(|| ShadowError::NotDefined {
                technique: "sdsm",
                reason: "sample distribution shadow maps are fitted to an eye pass's samples, \
                         and none was given"
                    .into(),
            })?;
            let samples = gather(&image.position, |pixel, _| {
                image.triangle[pixel] != NO_TRIANGLE
            });
            return sdsm::plan(&input, &samples, variant, partitions);
        }
        _ => {}
    }
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

/// Plans every light of `scene` as `options` says ([`plan_light`]), with each map's window snapped
/// to its texel grid when `options.snap_texels` is set ([`snap_to_texels`]): the partitions, per
/// light in the scene's order, that [`render_shadows`] renders. `nearest_visible` is the eye
/// pass's nearest visible depth (PSM's near plane), `eye` the eye pass (SDSM's samples).
///
/// # Errors
/// As [`plan_light`].
pub fn plan_frame(
    scene: &Scene,
    options: &FrameOptions,
    nearest_visible: Option<f64>,
    eye: Option<&EyeImage>,
) -> Result<Vec<Vec<Partition>>, ShadowError> {
    scene
        .lights
        .iter()
        .map(|light| {
            let mut partitions = plan_light(
                scene,
                light,
                &options.plan,
                nearest_visible,
                options.resolution,
                eye,
            )?;
            if options.snap_texels > 0 {
                for partition in &mut partitions {
                    partition.setup =
                        snap_to_texels(&partition.setup, options.resolution, options.snap_texels);
                }
            }
            Ok(partitions)
        })
        .collect()
}

/// The shadows of `scene` as `options` says, for its eye pass `eye` (from [`eye_pass`], with
/// `nearest_visible` its nearest visible depth): plan ([`plan_frame`]), render the maps, look
/// every visible point up ([`shadows_of`]). A study that tries many options on one view makes the
/// eye pass once. `bvh`, the scene's ray-casting hierarchy, is what the logarithmic map is cast
/// against; without it one is built.
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
    let start = Instant::now();
    let planned = plan_frame(scene, options, nearest_visible, Some(eye))?;
    let planning = start.elapsed();
    let map_options = MapOptions {
        resolution: options.resolution,
        format: options.format,
        second_depth: options.lookup.bias.needs_second_depth(),
    };
    let lights = scene
        .lights
        .iter()
        .zip(planned)
        .map(|(light, partitions)| LightMaps {
            light: LightSource::from_scene(light),
            selection: selection_of(options.plan.technique, light),
            partitions: partitions
                .into_iter()
                .map(|partition| PartitionMap {
                    lookup: match options.plan.technique {
                        // An engine's preset reads its maps with its own bias.
                        Technique::Engine(engine, _) => Lookup::new(
                            engine.bias(&partition, options.resolution),
                            options.lookup.filter,
                        ),
                        _ => options.lookup.clone(),
                    },
                    partition,
                    source: MapSource::Render(map_options),
                })
                .collect(),
        })
        .collect();
    let mut shadows = shadows_of(scene, eye, lights, bvh)?;
    shadows.timings.planning = planning;
    Ok(shadows)
}

/// Where one partition's map comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum MapSource {
    /// Rendered from the partition's set-up: rasterized, or cast for the logarithmic map.
    Render(MapOptions),
    /// Given depths, stored as their format stores them ([`ShadowMap::from_depths`]): a map read
    /// back from another renderer, looked up as it is.
    Depths(GivenDepths),
}

/// A map's depths as given ([`MapSource::Depths`]): window depths in `[0, 1]`, `resolution²` of
/// them, row-major with row 0 at the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct GivenDepths {
    /// Side of the square map, in texels.
    pub resolution: u32,
    /// How the depths are stored.
    pub format: DepthFormat,
    /// Nearest depth per texel.
    pub nearest: Vec<f64>,
    /// Second-nearest depth per texel, for the biases that read it.
    pub second: Option<Vec<f64>>,
}

/// One partition of a light's shadow with how its map is made and read ([`shadows_of`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PartitionMap {
    /// The partition: the eye depths it serves and its set-up.
    pub partition: Partition,
    /// Its map: rendered, or given.
    pub source: MapSource,
    /// How its map is read (every pixel it serves is looked up with this bias and filter).
    pub lookup: Lookup,
}

/// One light's shadow to make ([`shadows_of`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LightMaps {
    /// The light.
    pub light: LightSource,
    /// Its partitions, nearest first (one if unpartitioned); each pixel is served by one of them,
    /// or blended from two, as `selection` says ([`served`]).
    pub partitions: Vec<PartitionMap>,
    /// Which map serves a visible point.
    pub selection: Selection,
}

/// The selection of `technique`'s maps of `light`: an engine's for a directional light
/// ([`crate::Engine::selection`]), shadowlab's otherwise ([`Selection::DEFAULT`]).
#[must_use]
pub fn selection_of(technique: Technique, light: &SceneLight) -> Selection {
    match (technique, light) {
        (Technique::Engine(engine, choices), SceneLight::Directional { .. }) => {
            engine.selection(choices)
        }
        _ => Selection::DEFAULT,
    }
}

/// The shadows of `lights` for `scene`'s eye pass `eye`: each partition's map rendered (or its
/// given depths stored), then every visible point looked up in the map of the partition that
/// serves it (or blended from the two that do, faded: [`served`]), with that partition's lookup. Planning takes no time here (`timings.planning` is zero): the partitions come planned.
/// `bvh` is what logarithmic maps are cast against; without it one is built, if one is needed.
///
/// # Errors
/// The rasterizer's; [`ShadowError::Trace`] if a hierarchy cannot be built or a texel's ray is
/// invalid; [`ShadowError::Raster`] if given depths do not fill their map.
pub fn shadows_of(
    scene: &Scene,
    eye: &EyeImage,
    lights: Vec<LightMaps>,
    bvh: Option<&Bvh>,
) -> Result<Shadows, ShadowError> {
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let view = scene_eye(scene);
    let cast = lights
        .iter()
        .flat_map(|l| &l.partitions)
        .any(|p| matches!(p.source, MapSource::Render(_)) && p.partition.setup.mapping.is_cast());
    let built;
    let bvh = match (bvh, cast) {
        (Some(bvh), _) => Some(bvh),
        (None, true) => {
            built = Bvh::new(scene.mesh.positions(), scene.mesh.triangles())?;
            Some(&built)
        }
        (None, false) => None,
    };
    let mut timings = Timings::default();
    let mut shadows = Vec::with_capacity(lights.len());
    for light in lights {
        let start = Instant::now();
        let mut maps = Vec::with_capacity(light.partitions.len());
        let mut light_lookups = Vec::with_capacity(light.partitions.len());
        for PartitionMap {
            partition,
            source,
            lookup,
        } in light.partitions
        {
            let map = match source {
                MapSource::Render(options) => match bvh {
                    Some(bvh) if partition.setup.mapping.is_cast() => {
                        ShadowMap::cast(&partition.setup, bvh, options)
                    }
                    _ => ShadowMap::render(&partition.setup, mesh, options),
                }?,
                MapSource::Depths(given) => ShadowMap::from_depths(
                    partition.setup.clone(),
                    given.resolution,
                    given.format,
                    given.nearest,
                    given.second,
                )?,
            };
            maps.push((partition, map));
            light_lookups.push(lookup);
        }
        timings.shadow_pass += start.elapsed();
        shadows.push(LightShadow {
            light: light.light,
            maps,
            lookups: light_lookups,
            selection: light.selection,
        });
    }

    let start = Instant::now();
    let lit = shadows
        .iter()
        .map(|shadow| lit_at(shadow, &view, eye))
        .collect();
    timings.lookup = start.elapsed();
    Ok(Shadows {
        lights: shadows,
        lit,
        timings,
    })
}

/// Rows of pixels looked up per parallel job; any size gives the same result.
const LOOKUP_ROWS: usize = 8;

/// How lit each visible point of `image` (an eye pass seen by `eye`) is by one light's `shadow`:
/// read with the lookup of the map that serves it, blended and faded as the light's selection
/// says; 1 where nothing is visible. The shadows need not be this eye pass's own: a walk reads one
/// frame's points in the previous frame's maps (the temporal study's surface shimmer).
#[must_use]
pub fn lit_at(shadow: &LightShadow, eye: &Eye, image: &EyeImage) -> Vec<f64> {
    lit_with(shadow, &shadow.lookups, eye, image)
}

/// [`lit_at`] with each map read by `lookups[k]` instead of its own lookup (one per map): the same
/// maps read another way, e.g. with the nearest filter to tell a filter's errors from the map's.
///
/// # Panics
/// If `lookups` does not hold one lookup per map.
#[must_use]
pub fn lit_with(shadow: &LightShadow, lookups: &[Lookup], eye: &Eye, image: &EyeImage) -> Vec<f64> {
    assert_eq!(lookups.len(), shadow.maps.len(), "one lookup per map");
    let width = image.width as usize;
    // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers").
    let mut lit: Vec<f64> = rayon::iter::repeat_n(1.0, image.triangle.len()).collect();
    // Whether four pixels served by one map may be looked up together (`lit_rows_together`),
    // decided once: the path every other lookup takes is left as it was.
    let together = lookups.iter().any(Lookup::reads_together);
    lit.par_chunks_mut(width * LOOKUP_ROWS)
        .enumerate()
        .for_each(|(chunk, rows)| {
            let first = chunk * width * LOOKUP_ROWS;
            if together {
                lit_rows_together(shadow, lookups, eye, image, first, rows);
                return;
            }
            for (k, value) in rows.iter_mut().enumerate() {
                let pixel = first + k;
                if image.triangle[pixel] == NO_TRIANGLE {
                    continue;
                }
                let position: DVec3 = image.position[pixel];
                let normal = image.normal[pixel];
                let Some(serving) =
                    served(&shadow.maps, |(p, _)| p, &shadow.selection, eye, position)
                else {
                    continue;
                };
                *value = serving.combine(|index| {
                    lookups[index].lit_fraction(&shadow.maps[index].1, position, normal)
                });
            }
        });
    lit
}

/// [`lit_with`]'s work on the pixels `rows` from `first`, four neighbours at a time where one map
/// serves them all ([`lit_block`]), one by one elsewhere.
fn lit_rows_together(
    shadow: &LightShadow,
    lookups: &[Lookup],
    eye: &Eye,
    image: &EyeImage,
    first: usize,
    rows: &mut [f64],
) {
    let sole = sole_map(&shadow.maps, &shadow.selection);
    let serving = |pixel: usize| {
        if image.triangle[pixel] == NO_TRIANGLE {
            return None;
        }
        if sole.is_some() {
            return sole;
        }
        served(
            &shadow.maps,
            |(p, _)| p,
            &shadow.selection,
            eye,
            image.position[pixel],
        )
    };
    for (block, values) in rows.chunks_mut(LANES).enumerate() {
        let first = first + block * LANES;
        // Each pixel's map asked once, from one call site (so that the rule is inlined here),
        // into an array read field by field (see `lit_block`).
        let mut served = [None; LANES];
        for (k, served) in served.iter_mut().take(values.len()).enumerate() {
            *served = serving(first + k);
        }
        if let Ok(values) = <&mut [f64; LANES]>::try_from(&mut *values)
            && let Some(lit) = lit_block(shadow, lookups, image, first, &served)
        {
            *values = lit;
            continue;
        }
        for (k, value) in values.iter_mut().enumerate() {
            let Some(serving) = &served[k] else {
                continue;
            };
            let (position, normal) = (image.position[first + k], image.normal[first + k]);
            *value = serving.combine(|index| {
                lookups[index].lit_fraction(&shadow.maps[index].1, position, normal)
            });
        }
    }
}

/// The lit fractions of the [`LANES`] pixels from `first`, served as `served` says, looked up
/// together (`Lookup::lit_fractions`: the same values as one by one) if all are visible and served
/// by one map without a blend; `None` otherwise.
///
/// `served` is only read field by field, and the points where they lie: an array of lanes built by
/// `array::from_fn` and moved whole is read back by vector loads that wait for the scalar stores
/// that wrote it (a store-forwarding stall; docs/benchmarks.md).
fn lit_block(
    shadow: &LightShadow,
    lookups: &[Lookup],
    image: &EyeImage,
    first: usize,
    served: &[Option<Served>; LANES],
) -> Option<[f64; LANES]> {
    let index = served[0].as_ref()?.index;
    let one_map = |served: &Option<Served>| {
        served
            .as_ref()
            .is_some_and(|served| served.index == index && served.blend.is_none())
    };
    if !served.iter().all(one_map) {
        return None;
    }
    let lanes = first..first + LANES;
    let lit = lookups[index].lit_fractions(
        &shadow.maps[index].1,
        image.position[lanes.clone()].try_into().ok()?,
        image.normal[lanes].try_into().ok()?,
    )?;
    // `Served::combine` (no blend: the one map's value, faded) with the block's values.
    Some(std::array::from_fn(|k| {
        served[k]
            .as_ref()
            .map_or(lit[k], |served| served.combine(|_| lit[k]))
    }))
}
