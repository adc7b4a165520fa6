//! An engine's own shadows, evaluated: a set-up file's matrices (or its depth images) against the
//! exact truth, frame by frame, with the measurements `analyze` makes and shimmer as `temporal`
//! counts it.
//!
//! Each frame is drawn through its camera's matrices (the scene's camera where the frame has
//! none); each partition's map is rendered from its matrices with shadowlab's rasterizer, or read
//! from its depth image and stored in its depth format, and every visible pixel is looked up in
//! the map of the partition that serves it ([`shadowlab_shadow::served`]: the first whose `far`
//! lies beyond the pixel's eye depth) with that partition's bias and filter — the lookups `analyze`
//! makes. The result of a frame is a [`Study`] of one measurement, which `report::report` writes
//! as it writes `analyze`'s; over two or more frames, the shimmering pixels of consecutive frames
//! (first light) as [`crate::temporal`] counts them.
//!
//! A set-up written by [`crate::setup_file::setup_for`] evaluates to the measurement `analyze`
//! makes of the same technique, bit for bit but for the times.

use std::time::Instant;

use shadowlab_hull::NdcDepth;
use shadowlab_raster::image_in::{depth_from_exr, depth_from_npy, depth_from_png16};
use shadowlab_raster::{EyeImage, NO_TRIANGLE};
use shadowlab_scene::{Camera, Scene, SceneLight};
use shadowlab_shadow::{
    Bias, Eye, Filter, GivenDepths, LightMaps, LightSetup, LightSource, MapOptions, MapSource,
    Partition, PartitionMap, ProjectiveMapping, Selection, ShadowError, ShadowMapping, Shadows,
    eye_image, shadows_of,
};

use crate::aliasing::FrameFootprints;
use crate::setup_file::{
    DEPTH_IMAGE_SLACK_BYTES, DepthImage, ImageKind, Setup, SetupError, SetupPartition, read_bounded,
};
use crate::study::{
    Measurement, Pictures, Setting, Study, attributed, footprinted, leaked, outcome,
};
use crate::temporal::{Stability, shimmer};
use crate::truth::LIT_THRESHOLD;
use crate::truth::{exact_truth, scene_bvh};

/// Evaluates `setup` on `scene`, calling `frame_done(k, study)` as each frame `k` is measured:
/// the study of that frame's eye pass and truth, holding one measurement, the set-up's (labelled
/// by the file's technique, [`shadowlab_shadow::Technique::Given`] if it names none, with the
/// first light's first partition's map size and filter and its number of partitions), and the
/// frame's footprint heat map, difference image and causes picture if `pictures`. A frame is
/// dropped once its study is handed over, so a long set-up needs the memory of one frame.
///
/// Returns, for two frames or more, the shimmering pixels between consecutive frames (first
/// light, `snap_texels` 0: the matrices are measured as given).
///
/// Times: planning is zero (nothing is planned); the shadow pass is rendering the given matrices
/// or reading and storing the given images; the truth's time is the eye pass and the rays (and,
/// in the first frame, the ray-casting hierarchy).
///
/// # Errors
/// [`SetupError::Field`] if a frame has another number of lights than the scene, or (over
/// several frames) another image size than the first, or a depth image holds a value outside
/// `[0, 1]`; [`SetupError::ImageRead`] and [`SetupError::Image`] for a depth image that cannot
/// be read or is not its map's; [`SetupError::Analysis`] if the eye pass, the truth, or a map
/// fails.
pub fn evaluate(
    scene: &Scene,
    setup: &Setup,
    pictures: bool,
    mut frame_done: impl FnMut(usize, Study),
) -> Result<Option<Stability>, SetupError> {
    evaluate_observed(scene, setup, pictures, |study, frame| {
        frame_done(frame.index, study);
        Ok::<(), SetupError>(())
    })
}

/// One evaluated frame's per-pixel results, as [`evaluate_observed`] shows them before it lets
/// them go (the exact truth is the study's).
#[derive(Clone, Copy, Debug)]
pub struct EvaluatedFrame<'a> {
    /// The frame's index in the set-up.
    pub index: usize,
    /// The frame's eye pass.
    pub eye: &'a EyeImage,
    /// The frame's maps and lookups.
    pub shadows: &'a Shadows,
    /// The texel footprint per pixel (first light).
    pub footprints: &'a FrameFootprints,
}

/// [`evaluate`], handing each frame's study to `observe` with the frame's per-pixel results (e.g.
/// to write them out, [`crate::export`]) before they are dropped; an error from `observe` ends the
/// evaluation.
///
/// # Errors
/// As [`evaluate`], and `observe`'s.
pub fn evaluate_observed<E: From<SetupError>>(
    scene: &Scene,
    setup: &Setup,
    pictures: bool,
    mut observe: impl FnMut(Study, &EvaluatedFrame<'_>) -> Result<(), E>,
) -> Result<Option<Stability>, E> {
    let problem = |field: String, problem: String| SetupError::Field {
        path: setup.path.clone(),
        field,
        problem,
    };
    let start = Instant::now();
    let bvh = scene_bvh(scene).map_err(SetupError::from)?;
    let mut hierarchy_time = start.elapsed();
    let mut moved = scene.clone();
    let mut first_size = None;
    // The previous frame's shadow states and truth, first light (`None`: nothing visible).
    let mut previous: Option<(States, States)> = None;
    let mut counts = Vec::new();
    for (k, frame) in setup.frames.iter().enumerate() {
        if frame.lights.len() != scene.lights.len() {
            return Err(problem(
                format!("frames[{k}].lights"),
                format!(
                    "{} lights for a scene with {}: one entry per light of the scene, in its \
                     order",
                    frame.lights.len(),
                    scene.lights.len()
                ),
            )
            .into());
        }
        let clip_from_world = match &frame.camera {
            Some(camera) => {
                let (width, height) = camera
                    .size
                    .unwrap_or((scene.camera.width, scene.camera.height));
                moved.camera = Camera {
                    pose: camera.pose,
                    projection: camera.projection,
                    width,
                    height,
                };
                camera.clip_from_world
            }
            None => {
                moved.camera = scene.camera.clone();
                scene.camera.view_projection(NdcDepth::NegativeOneToOne)
            }
        };
        let size = (moved.camera.width, moved.camera.height);
        match first_size {
            None => first_size = Some(size),
            Some(first) if first != size => {
                return Err(problem(
                    format!("frames[{k}].camera"),
                    format!(
                        "an image of {}×{} after frame 0's {}×{}: shimmer compares the same \
                         pixels of consecutive frames",
                        size.0, size.1, first.0, first.1
                    ),
                )
                .into());
            }
            Some(_) => {}
        }

        let start = Instant::now();
        let eye = eye_image(&moved, &clip_from_world).map_err(SetupError::from)?;
        let truth = exact_truth(&moved, &eye, &bvh).map_err(SetupError::from)?;
        let truth_time = start.elapsed() + std::mem::take(&mut hierarchy_time);

        let start = Instant::now();
        let lights = scene
            .lights
            .iter()
            .zip(&frame.lights)
            .map(|(light, partitions)| {
                Ok(LightMaps {
                    light: LightSource::from_scene(light),
                    selection: Selection::DEFAULT,
                    partitions: partitions
                        .iter()
                        .map(|p| partition_map(setup, &moved.camera, light, p))
                        .collect::<Result<_, SetupError>>()?,
                })
            })
            .collect::<Result<Vec<_>, SetupError>>()?;
        let reading = start.elapsed();
        let mut shadows = shadows_of(&moved, &eye, lights, Some(&bvh)).map_err(SetupError::from)?;
        shadows.timings.shadow_pass += reading;

        let footprints = footprinted(&moved, &eye, &shadows);
        // Each partition's errors are attributed with the filter it was looked up with.
        let attribution = attributed(
            &moved,
            &eye,
            &truth,
            &shadows,
            |light, partition| frame.lights[light][partition].lookup.filter,
            &bvh,
        )
        .map_err(SetupError::from)?;
        let setting = setting(setup, frame.lights.first());
        let frame_pictures = if pictures {
            vec![Pictures::of(
                &setting,
                &moved,
                (&eye, &truth),
                &shadows,
                &footprints.0,
                &attribution.0,
            )]
        } else {
            Vec::new()
        };
        let leaks = leaked(&moved, &eye, &truth, &shadows, &setting.filter);
        let measured = outcome(&truth, &shadows, &footprints, &attribution, leaks);

        let states: States = match shadows.lit.first() {
            Some(lit) => eye
                .triangle
                .iter()
                .zip(lit)
                .map(|(t, l)| (*t != NO_TRIANGLE).then_some(*l >= LIT_THRESHOLD))
                .collect(),
            None => vec![None; eye.triangle.len()],
        };
        let truth_states = truth
            .lit
            .first()
            .cloned()
            .unwrap_or_else(|| vec![None; eye.triangle.len()]);
        if let Some((before, truth_before)) = &previous {
            counts.push(shimmer(before, &states, truth_before, &truth_states));
        }
        previous = Some((states, truth_states));

        let visible = eye.triangle.iter().filter(|t| **t != NO_TRIANGLE).count();
        let study = Study {
            scene: scene.name.clone(),
            timing_runs: 1,
            bias: frame
                .lights
                .first()
                .and_then(|partitions| partitions.first())
                .map_or(Bias::DEFAULT, |p| p.lookup.bias),
            focus: None,
            width: eye.width,
            height: eye.height,
            visible: visible as u64,
            truth_time,
            map_truth: None,
            measurements: vec![Measurement {
                setting,
                outcome: Ok(measured),
            }],
            truth,
            pictures: frame_pictures,
            view_axis: Vec::new(),
        };
        observe(
            study,
            &EvaluatedFrame {
                index: k,
                eye: &eye,
                shadows: &shadows,
                footprints: &footprints.0,
            },
        )?;
    }
    Ok((setup.frames.len() > 1).then_some(Stability {
        technique: setup.technique,
        snap_texels: 0,
        shimmer: Ok(counts),
        surface_shimmer: None,
    }))
}

/// Per pixel, lit or not (`None`: nothing visible).
type States = Vec<Option<bool>>;

/// The setting a frame's measurement is labelled with: the set-up's technique, and its first
/// light's first partition's map size and filter and its number of partitions.
fn setting(setup: &Setup, first_light: Option<&Vec<SetupPartition>>) -> Setting {
    let first = first_light.and_then(|partitions| partitions.first());
    Setting {
        technique: setup.technique,
        resolution: first.map_or(0, |p| p.map_size),
        partitions: first_light.map_or(0, Vec::len),
        filter: first.map_or(Filter::Nearest, |p| p.lookup.filter),
    }
}

/// One partition of a frame as `shadows_of` takes it: its set-up (the given matrices; γ and φ
/// from `camera` and `light`, no focus body, warp or PSM report: nothing was planned), and its
/// map, rendered or read from its depth images.
fn partition_map(
    setup: &Setup,
    camera: &Camera,
    light: &SceneLight,
    partition: &SetupPartition,
) -> Result<PartitionMap, SetupError> {
    let toward = LightSource::from_scene(light).toward_from(camera.pose.eye());
    let gamma = shadowlab_hull::light_view_angle(camera.pose.forward(), toward)
        .map_err(ShadowError::from)?;
    let eye = Eye {
        pose: camera.pose,
        projection: camera.projection,
    };
    let light_setup = LightSetup {
        technique: setup.technique,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(
            partition.view,
            partition.projection,
        )),
        gamma,
        half_fov: eye.half_fov_toward(toward),
        warp: None,
        psm: None,
        focus_body: Vec::new(),
    };
    let source = match &partition.depth_image {
        None => MapSource::Render(MapOptions {
            resolution: partition.map_size,
            format: partition.format,
            second_depth: partition.lookup.bias.needs_second_depth(),
        }),
        Some(image) => MapSource::Depths(GivenDepths {
            resolution: partition.map_size,
            format: partition.format,
            nearest: read_depths(setup, image, partition.map_size)?,
            second: partition
                .second_depth_image
                .as_ref()
                .map(|second| read_depths(setup, second, partition.map_size))
                .transpose()?,
        }),
    };
    Ok(PartitionMap {
        partition: Partition {
            near: partition.near,
            far: partition.far,
            face: None,
            sphere: None,
            setup: light_setup,
        },
        source,
        lookup: partition.lookup.clone(),
    })
}

/// The window depths of `image`, a map of side `side`: read (at most
/// `8·side² + DEPTH_IMAGE_SLACK_BYTES` bytes), decoded with its size checked, each value checked
/// to be a window depth, and `1 − v` taken for a reversed set-up.
fn read_depths(setup: &Setup, image: &DepthImage, side: u32) -> Result<Vec<f64>, SetupError> {
    let texels = u64::from(side) * u64::from(side);
    let bytes = read_bounded(
        &image.path,
        8 * texels + DEPTH_IMAGE_SLACK_BYTES,
        "a depth image of this map size",
        "8 bytes a texel, plus DEPTH_IMAGE_SLACK_BYTES",
    )
    .map_err(|source| SetupError::ImageRead {
        path: setup.path.clone(),
        field: image.field.clone(),
        source,
    })?;
    let decoded = match image.kind {
        ImageKind::Exr => depth_from_exr(&bytes, side, side),
        ImageKind::Npy => depth_from_npy(&bytes, side, side),
        ImageKind::Png16 => depth_from_png16(&bytes, side, side),
    }
    .map_err(|source| SetupError::Image {
        path: setup.path.clone(),
        field: image.field.clone(),
        image: image.path.clone(),
        source: Box::new(source),
    })?;
    let side = side as usize;
    if let Some((texel, value)) = decoded
        .iter()
        .enumerate()
        .find(|(_, v)| !(0.0..=1.0).contains(*v))
    {
        return Err(SetupError::Field {
            path: setup.path.clone(),
            field: image.field.clone(),
            problem: format!(
                "{}: texel ({}, {}) (column, row from the bottom) holds {value}; window depths \
                 lie in [0, 1]",
                image.path.display(),
                texel % side,
                texel / side
            ),
        });
    }
    Ok(if image.reversed {
        decoded.into_iter().map(|v| 1.0 - v).collect()
    } else {
        decoded
    })
}
