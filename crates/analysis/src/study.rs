//! A study: one scene, every combination of techniques, resolutions, partitions and filters,
//! each measured against the exact truth in the same run.

use std::time::{Duration, Instant};

use shadowlab_raster::{DepthFormat, EyeImage, NO_TRIANGLE};
use shadowlab_scene::{Scene, SceneLight};
use shadowlab_shadow::optimal::OptimalOptions;
use shadowlab_shadow::{
    Bias, Filter, FocusPolicy, FrameOptions, LightShadow, LightSource, Lookup, PlanOptions,
    ShadowError, Shadows, Splits, Technique, Timings, eye_pass, lit_with, render_shadows,
    scene_eye, served, view::shade_eye,
};
use shadowlab_trace::Bvh;

use crate::aliasing::{AliasingStats, FrameFootprints, footprints_served};
use crate::attribution::{Attribution, Causes, attribute, cause_image};
use crate::classify::{Misclassification, difference_image, disagreement, misclassification};
use crate::error::AnalysisError;
use crate::images::{HeatScale, heatmap, value_range};
use crate::leaks::{FilterLeaks, filter_leaks, filterable_method};
use crate::truth::{Truth, exact_truth, map_truth, scene_bvh};
use crate::view_axis::{AxisCurve, curves};

/// Side of the uniform shadow map used as the alternative truth (Chong and Gortler used 3700²).
pub const MAP_TRUTH_RESOLUTION: u32 = 4096;

/// What to measure.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyOptions {
    /// The techniques.
    pub techniques: Vec<Technique>,
    /// Shadow-map sides.
    pub resolutions: Vec<u32>,
    /// Partition counts (1: one map).
    pub partitions: Vec<usize>,
    /// How partitions split the depth range.
    pub splits: Splits,
    /// Filters.
    pub filters: Vec<Filter>,
    /// The bias of every lookup.
    pub bias: Bias,
    /// The maps' depth format.
    pub format: DepthFormat,
    /// Also compute the high-resolution uniform map's truth and its disagreement with the exact one.
    pub map_truth: bool,
    /// Keep pictures (footprint heat map, difference image, its causes) of each technique at this
    /// resolution, with the first partition count and filter; `None`: no pictures.
    pub pictures_at: Option<u32>,
    /// The scene-optimized map's settings (its step direction is the technique's).
    pub optimal: OptimalOptions,
    /// The body B every map is fitted to.
    pub focus: FocusPolicy,
    /// How many times each combination's shadows are made for its timing (≥ 1; 1 for anything
    /// but a timing): its time is the run of median total time, its spread half the range of the
    /// totals ([`Outcome::time_spread`]). The results other than timings are the first run's.
    pub timing_runs: usize,
}

/// The timing runs per combination of `analyze` by default: the fewest that have a median.
pub const DEFAULT_TIMING_RUNS: usize = 3;

/// The techniques `analyze` measures by default for directional and spot lights (the engines'
/// presets are measured when named).
pub const DEFAULT_TECHNIQUES: &str =
    "uniform,uniform_limited,psm,lispsm,lispsm:minimax,logarithmic,optimal,sdsm";

/// What a study measures by default for a scene whose lights are all point lights.
pub const POINT_LIGHT_TECHNIQUES: &str = "cube,dual-paraboloid,psm";

/// The shadow-map sides `analyze` measures by default (Chong and Gortler's: 750 to 2000).
pub const DEFAULT_RESOLUTIONS: [u32; 6] = [750, 1000, 1250, 1500, 1750, 2000];

/// The techniques a study of `scene` measures when none are named: `directed` (a comma-separated
/// list of specs) for directional and spot lights, [`POINT_LIGHT_TECHNIQUES`] for a scene of point
/// lights, and PSM — the one technique that serves both — for a scene that mixes them.
///
/// # Panics
/// If `directed` does not parse (the lists are the tool's own constants).
#[must_use]
pub fn default_techniques(scene: &Scene, directed: &str) -> Vec<Technique> {
    let point = |light: &SceneLight| matches!(light, SceneLight::Point { .. });
    let list = match (
        scene.lights.iter().any(point),
        scene.lights.iter().all(point),
    ) {
        (false, _) => directed,
        (true, true) => POINT_LIGHT_TECHNIQUES,
        (true, false) => "psm",
    };
    list.split(',')
        .map(|spec| Technique::parse_spec(spec).expect("the default lists parse"))
        .collect()
}

/// The pictures of one combination: rows from the bottom, like the eye image, one pixel per eye
/// pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Pictures {
    /// What they show.
    pub setting: Setting,
    /// The view shaded with this combination's shadows (`shadowlab_shadow::view::shade_eye`).
    pub eye: Vec<[u8; 3]>,
    /// The texel footprint per pixel on [`HeatScale::PIXELS_PER_TEXEL`] (first light).
    pub heatmap: Vec<[u8; 3]>,
    /// The least and greatest footprint in the heat map, pixels per texel (`None`: no pixel has
    /// one), which its colour bar states.
    pub footprint_range: Option<(f64, f64)>,
    /// Misclassified pixels ([`difference_image`]).
    pub difference: Vec<[u8; 3]>,
    /// Misclassified pixels by cause ([`cause_image`]).
    pub causes: Vec<[u8; 3]>,
}

impl Pictures {
    /// The pictures of `setting`'s `shadows` of `scene`, seen in `eye` and judged by `truth`,
    /// with the footprints `footprints` and the errors' causes `attribution`.
    #[must_use]
    pub fn of(
        setting: &Setting,
        scene: &Scene,
        (eye, truth): (&EyeImage, &Truth),
        shadows: &Shadows,
        footprints: &FrameFootprints,
        attribution: &Attribution,
    ) -> Self {
        let totals: Vec<Option<f64>> = footprints
            .each_pixel()
            .map(|f| f.map(|f| f.total))
            .collect();
        Self {
            setting: setting.clone(),
            eye: shade_eye(eye, &shadows.lights, &shadows.lit, scene),
            heatmap: heatmap(&totals, eye.width, eye.height, HeatScale::PIXELS_PER_TEXEL),
            footprint_range: value_range(&totals),
            difference: difference_image(truth, &shadows.lit, eye),
            causes: cause_image(attribution, truth, eye),
        }
    }
}

/// One combination's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    /// The technique.
    pub technique: Technique,
    /// Shadow-map side.
    pub resolution: u32,
    /// Partition count.
    pub partitions: usize,
    /// The filter.
    pub filter: Filter,
}

/// One combination, measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// What was measured.
    pub setting: Setting,
    /// Its result, or why the technique is not defined for the scene.
    pub outcome: Result<Outcome, String>,
}

/// What a combination costs and buys.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Misclassified pixels against the exact truth.
    pub errors: Misclassification,
    /// The misclassified pixels by cause ([`crate::attribution`]); they sum to `errors.total()`.
    pub causes: Causes,
    /// Texels spent: the sum of every map's side² over every light — the maps' memory in texels
    /// (a preset's cascades and a merged SDSM count as they were made, whatever the setting asked).
    pub texels: u64,
    /// The texel footprint on screen (pixels per texel) over the visible pixels of the first
    /// light: total, perspective part, projection part.
    pub footprint: [AliasingStats; 3],
    /// Planning time (bodies, parameters, optimizer).
    pub planning: Duration,
    /// Shadow-map rendering time.
    pub shadow_pass: Duration,
    /// Lookup time.
    pub lookup: Duration,
    /// The time the analysis took to attribute the errors to causes (first run; not the
    /// technique's, so not part of [`Outcome::time`]).
    pub attribution: Duration,
    /// The time the analysis took to measure every pixel's texel footprint and their statistics
    /// (first run; not part of [`Outcome::time`] either).
    pub footprints: Duration,
    /// Half the range of the total times over the timing runs ([`StudyOptions::timing_runs`]):
    /// the planning, shadow-pass and lookup times are the median run's, and a time is known to
    /// within ± this. Zero for one run.
    pub time_spread: Duration,
    /// For a filterable map's filter (VSM, ESM, EVSM, MSM): its errors against the nearest
    /// lookup of the same maps ([`crate::leaks`]); `None` for the other filters.
    pub leaks: Option<FilterLeaks>,
}

impl Outcome {
    /// What the technique costs per frame: planning, shadow pass and lookup.
    #[must_use]
    pub fn time(&self) -> Duration {
        self.planning + self.shadow_pass + self.lookup
    }
}

/// A scene's study.
#[derive(Clone, Debug, PartialEq)]
pub struct Study {
    /// The scene's name.
    pub scene: String,
    /// The timing runs of each combination ([`StudyOptions::timing_runs`]).
    pub timing_runs: usize,
    /// The bias of every lookup ([`StudyOptions::bias`]).
    pub bias: Bias,
    /// The body every map is fitted to ([`StudyOptions::focus`]); `None` for maps given from
    /// outside (an evaluated set-up: nothing was fitted).
    pub focus: Option<FocusPolicy>,
    /// Eye image size.
    pub width: u32,
    /// Eye image height.
    pub height: u32,
    /// Pixels with a visible surface.
    pub visible: u64,
    /// The exact truth's time (BVH build and rays).
    pub truth_time: Duration,
    /// How the high-resolution uniform map's truth disagrees with the exact one, if computed.
    pub map_truth: Option<Misclassification>,
    /// Every combination, in the order techniques × resolutions × partitions × filters.
    pub measurements: Vec<Measurement>,
    /// The exact truth.
    pub truth: Truth,
    /// Pictures, if asked for ([`StudyOptions::pictures_at`]), in technique order.
    pub pictures: Vec<Pictures>,
    /// The error along the view axis per technique (first light): measured over the closed form.
    pub view_axis: Vec<AxisCurve>,
}

/// Every combination of `options`, in order. An engine's preset plans its own cascades, so it has
/// one combination per resolution and filter, with its directional light's cascade count as its
/// partitions, whatever partition counts the study names.
#[must_use]
pub fn settings(options: &StudyOptions) -> Vec<Setting> {
    let mut out = Vec::new();
    for technique in &options.techniques {
        let partitions = match technique {
            Technique::Engine(engine, _) => vec![engine.cascades()],
            _ => options.partitions.clone(),
        };
        for resolution in &options.resolutions {
            for partitions in &partitions {
                for filter in &options.filters {
                    out.push(Setting {
                        technique: *technique,
                        resolution: *resolution,
                        partitions: *partitions,
                        filter: *filter,
                    });
                }
            }
        }
    }
    out
}

/// The shadows of one combination for the scene's eye pass `eye` (exposed so callers can keep them
/// for pictures); `bvh` is the scene's hierarchy, which the logarithmic map is cast against.
///
/// # Errors
/// As `shadowlab_shadow::render_shadows`.
pub fn render(
    scene: &Scene,
    options: &StudyOptions,
    setting: &Setting,
    eye: &EyePass,
    bvh: &Bvh,
) -> Result<Shadows, ShadowError> {
    render_shadows(
        scene,
        &frame_options(options, setting),
        &eye.image,
        eye.nearest_visible,
        Some(bvh),
    )
}

/// The frame options of one combination of a study (no snapping).
#[must_use]
pub fn frame_options(options: &StudyOptions, setting: &Setting) -> FrameOptions {
    FrameOptions {
        plan: PlanOptions {
            technique: setting.technique,
            partitions: setting.partitions,
            splits: options.splits,
            focus: options.focus,
            optimal: options.optimal,
        },
        resolution: setting.resolution,
        format: options.format,
        lookup: Lookup::new(options.bias, setting.filter),
        snap_texels: 0,
    }
}

/// The scene's eye pass, made once per study.
#[derive(Clone, Debug, PartialEq)]
pub struct EyePass {
    /// Depth, triangle, position and normal per pixel.
    pub image: EyeImage,
    /// The nearest visible eye depth (PSM's near plane).
    pub nearest_visible: Option<f64>,
}

impl EyePass {
    /// Pixels with a visible surface.
    #[must_use]
    pub fn visible(&self) -> u64 {
        self.image
            .triangle
            .iter()
            .filter(|t| **t != NO_TRIANGLE)
            .count() as u64
    }

    /// The eye pass of `scene`'s camera.
    ///
    /// # Errors
    /// The rasterizer's.
    pub fn new(scene: &Scene) -> Result<Self, ShadowError> {
        let (image, nearest_visible) = eye_pass(scene)?;
        Ok(Self {
            image,
            nearest_visible,
        })
    }
}

/// The texel footprint of every pixel, through the map (partition) that serves it; first light.
#[must_use]
pub fn frame_footprints(scene: &Scene, eye: &EyeImage, shadows: &Shadows) -> FrameFootprints {
    footprints_of(scene, eye, &shadows.lights)
}

/// [`frame_footprints`] of the lights' maps (of a [`Shadows`] or a `shadowlab_shadow::Frame`).
#[must_use]
pub fn footprints_of(scene: &Scene, eye: &EyeImage, lights: &[LightShadow]) -> FrameFootprints {
    let Some(shadow) = lights.first() else {
        return FrameFootprints::none(eye.triangle.len());
    };
    let view = scene_eye(scene);
    let maps: Vec<_> = shadow
        .maps
        .iter()
        .map(|(_, map)| (&map.setup, map.resolution))
        .collect();
    footprints_served(&maps, eye, &scene.camera, |pixel| {
        // The partition the lookup reads (the nearer of two it blends).
        served(
            &shadow.maps,
            |(p, _)| p,
            &shadow.selection,
            &view,
            eye.position[pixel],
        )
        .map(|s| s.index)
    })
}

/// Measures a combination's shadows, looked up with `filter`, against the truth; `bvh` is the
/// scene's ray-casting hierarchy, which attributing the errors casts against.
///
/// # Errors
/// [`AnalysisError::BvhMismatch`] if `bvh` is not the scene's.
pub fn measure(
    scene: &Scene,
    truth: &Truth,
    eye: &EyeImage,
    shadows: &Shadows,
    filter: Filter,
    bvh: &Bvh,
) -> Result<Outcome, AnalysisError> {
    let attributed = attributed(scene, eye, truth, shadows, |_, _| filter, bvh)?;
    let footprints = footprinted(scene, eye, shadows);
    let leaks = leaked(scene, eye, truth, shadows, &filter);
    Ok(outcome(truth, shadows, &footprints, &attributed, leaks))
}

/// The per-pixel footprints of `shadows` ([`frame_footprints`]) and the time they took.
pub(crate) fn footprinted(
    scene: &Scene,
    eye: &EyeImage,
    shadows: &Shadows,
) -> (FrameFootprints, Duration) {
    let start = Instant::now();
    let footprints = frame_footprints(scene, eye, shadows);
    (footprints, start.elapsed())
}

/// A filterable map's errors against the nearest lookup of the same maps ([`filter_leaks`]), if
/// `filter` is one: `shadows`' maps read again with the nearest filter and their own biases.
pub(crate) fn leaked(
    scene: &Scene,
    eye: &EyeImage,
    truth: &Truth,
    shadows: &Shadows,
    filter: &Filter,
) -> Option<FilterLeaks> {
    let method = filterable_method(filter)?;
    let view = scene_eye(scene);
    let nearest: Vec<Vec<f64>> = shadows
        .lights
        .iter()
        .map(|light| {
            let nearest: Vec<Lookup> = light
                .lookups
                .iter()
                .map(|l| Lookup::new(l.bias, Filter::Nearest))
                .collect();
            lit_with(light, &nearest, &view, eye)
        })
        .collect();
    Some(filter_leaks(
        truth,
        eye.width as usize,
        method,
        (&shadows.lit, &nearest),
    ))
}

/// The attribution of `shadows`' errors ([`attribute`]; `filter(light, partition)`) and its time.
pub(crate) fn attributed(
    scene: &Scene,
    eye: &EyeImage,
    truth: &Truth,
    shadows: &Shadows,
    filter: impl Fn(usize, usize) -> Filter,
    bvh: &Bvh,
) -> Result<(Attribution, Duration), AnalysisError> {
    let start = Instant::now();
    let attribution = attribute(
        scene,
        eye,
        truth,
        (&shadows.lights, &shadows.lit),
        filter,
        bvh,
    )?;
    Ok((attribution, start.elapsed()))
}

/// The outcome of shadows whose per-pixel footprints are `footprints` and whose errors are
/// attributed as `attribution`, each measured in the time given; the footprints' statistics are
/// timed here and added to theirs.
pub(crate) fn outcome(
    truth: &Truth,
    shadows: &Shadows,
    (footprints, footprint_time): &(FrameFootprints, Duration),
    (attribution, attribution_time): &(Attribution, Duration),
    leaks: Option<FilterLeaks>,
) -> Outcome {
    let start = Instant::now();
    let footprint = footprints.stats();
    let footprints = *footprint_time + start.elapsed();
    Outcome {
        errors: misclassification(truth, &shadows.lit),
        causes: attribution.counts,
        texels: shadows
            .lights
            .iter()
            .flat_map(|l| &l.maps)
            .map(|(_, map)| u64::from(map.resolution) * u64::from(map.resolution))
            .sum(),
        footprint,
        planning: shadows.timings.planning,
        shadow_pass: shadows.timings.shadow_pass,
        lookup: shadows.timings.lookup,
        attribution: *attribution_time,
        footprints,
        time_spread: Duration::ZERO,
        leaks,
    }
}

/// Sets `outcome`'s times from `runs` timings of its shadows (the first is the outcome's own): the
/// run of median total time (the lower median for an even count) and half the totals' range.
fn time_from_runs(outcome: &mut Outcome, runs: &[Timings]) {
    let total = |t: &Timings| t.planning + t.shadow_pass + t.lookup;
    let mut sorted: Vec<&Timings> = runs.iter().collect();
    sorted.sort_by_key(|t| total(t));
    let (Some(fastest), Some(slowest)) = (sorted.first(), sorted.last()) else {
        return;
    };
    let median = sorted[(sorted.len() - 1) / 2];
    outcome.planning = median.planning;
    outcome.shadow_pass = median.shadow_pass;
    outcome.lookup = median.lookup;
    outcome.time_spread = (total(slowest) - total(fastest)) / 2;
}

/// What every combination of a frame is measured against, made once per frame: the eye pass,
/// the scene's ray-casting hierarchy and the exact truth.
#[derive(Debug)]
pub struct Ground {
    /// The eye pass.
    pub eye: EyePass,
    /// The scene's hierarchy (the truth's, the logarithmic map's and the attribution's rays).
    pub bvh: Bvh,
    /// The exact truth.
    pub truth: Truth,
    /// The time the three took.
    pub truth_time: Duration,
}

impl Ground {
    /// The ground of `scene`'s frame.
    ///
    /// # Errors
    /// The truth's errors (bad scene geometry).
    pub fn new(scene: &Scene) -> Result<Self, AnalysisError> {
        let start = Instant::now();
        let eye = EyePass::new(scene)?;
        let bvh = scene_bvh(scene)?;
        let truth = exact_truth(scene, &eye.image, &bvh)?;
        Ok(Self {
            eye,
            bvh,
            truth,
            truth_time: start.elapsed(),
        })
    }
}

/// A combination's first run, as [`measure_setting`] shows it before letting it go.
#[derive(Clone, Copy, Debug)]
pub struct FirstRun<'a> {
    /// Its maps and lookups.
    pub shadows: &'a Shadows,
    /// The texel footprint per pixel (first light).
    pub footprints: &'a FrameFootprints,
    /// Its errors' causes per pixel.
    pub attribution: &'a Attribution,
}

/// Measures one combination of `options` on the frame `ground` was made for: its shadows (every
/// timing run), errors, causes, footprints and a filterable map's leaks, showing the first run to
/// `first_run` before its buffers are dropped. A rendering error for which `undefined` gives a
/// reason (`ShadowError::undefined_reason` for a study, `ShadowError::frame_reason` for a sweep)
/// is a measurement too: that reason.
///
/// # Errors
/// Other rendering failures, and `first_run`'s.
pub fn measure_setting<E: From<AnalysisError>>(
    scene: &Scene,
    (options, setting): (&StudyOptions, &Setting),
    ground: &Ground,
    undefined: fn(&ShadowError) -> Option<String>,
    first_run: impl FnOnce(&FirstRun<'_>) -> Result<(), E>,
) -> Result<Measurement, E> {
    let (eye, truth, bvh) = (&ground.eye, &ground.truth, &ground.bvh);
    let outcome = match render(scene, options, setting, eye, bvh) {
        Ok(shadows) => {
            let footprints = footprinted(scene, &eye.image, &shadows);
            let attribution = attributed(
                scene,
                &eye.image,
                truth,
                &shadows,
                |_, _| setting.filter,
                bvh,
            )?;
            first_run(&FirstRun {
                shadows: &shadows,
                footprints: &footprints.0,
                attribution: &attribution.0,
            })?;
            let leaks = leaked(scene, &eye.image, truth, &shadows, &setting.filter);
            let mut measured = outcome(truth, &shadows, &footprints, &attribution, leaks);
            let mut runs = vec![shadows.timings];
            // The timing runs need none of the first run's buffers.
            drop((shadows, footprints, attribution));
            for _ in 1..options.timing_runs {
                runs.push(
                    render(scene, options, setting, eye, bvh)
                        .map_err(AnalysisError::from)?
                        .timings,
                );
            }
            time_from_runs(&mut measured, &runs);
            Ok(measured)
        }
        Err(e) => match undefined(&e) {
            Some(reason) => Err(reason),
            None => return Err(AnalysisError::from(e).into()),
        },
    };
    Ok(Measurement {
        setting: setting.clone(),
        outcome,
    })
}

/// Runs the study, calling `progress(done, total, next)` before each combination (`next`, the one
/// about to be measured) and once at the end (`None`).
///
/// # Errors
/// The truth's errors (bad scene geometry); combinations whose technique is not defined for the
/// scene are recorded as such, other failures abort.
pub fn run(
    scene: &Scene,
    options: &StudyOptions,
    progress: impl FnMut(usize, usize, Option<&Setting>),
) -> Result<Study, AnalysisError> {
    run_observed(scene, options, progress, |_| Ok(()))
}

/// One combination's per-pixel results, as [`run_observed`] shows them before it lets them go.
#[derive(Clone, Copy, Debug)]
pub struct Observed<'a> {
    /// The combination.
    pub setting: &'a Setting,
    /// The study's eye pass.
    pub eye: &'a EyePass,
    /// The exact truth.
    pub truth: &'a Truth,
    /// The combination's maps and lookups (its first timing run).
    pub shadows: &'a Shadows,
    /// The texel footprint per pixel (first light).
    pub footprints: &'a FrameFootprints,
}

/// [`run`], showing each defined combination's per-pixel results to `observe` (e.g. to write
/// them out, [`crate::export`]) before they are dropped; an error from `observe` ends the run.
///
/// # Errors
/// As [`run`], and `observe`'s.
pub fn run_observed<E: From<AnalysisError>>(
    scene: &Scene,
    options: &StudyOptions,
    mut progress: impl FnMut(usize, usize, Option<&Setting>),
    mut observe: impl FnMut(&Observed<'_>) -> Result<(), E>,
) -> Result<Study, E> {
    for light in &scene.lights {
        let light = LightSource::from_scene(light);
        for technique in &options.techniques {
            technique.check_light(&light).map_err(AnalysisError::from)?;
        }
    }
    let ground = Ground::new(scene)?;
    let map_truth = if options.map_truth {
        let approximate = map_truth(scene, &ground.eye.image, MAP_TRUTH_RESOLUTION)?;
        Some(disagreement(&ground.truth, &approximate))
    } else {
        None
    };
    let mut techniques = options.techniques.clone();
    techniques.dedup();
    let view_axis = curves(scene, &techniques)?;
    let all = settings(options);
    let mut measurements = Vec::with_capacity(all.len());
    let mut pictures = Vec::new();
    for (k, setting) in all.iter().enumerate() {
        progress(k, all.len(), Some(setting));
        let undefined = ShadowError::undefined_reason;
        let measurement =
            measure_setting(scene, (options, setting), &ground, undefined, |first| {
                let pictured = options.pictures_at == Some(setting.resolution)
                    && options.partitions.first() == Some(&setting.partitions)
                    && options.filters.first() == Some(&setting.filter);
                if pictured {
                    pictures.push(Pictures::of(
                        setting,
                        scene,
                        (&ground.eye.image, &ground.truth),
                        first.shadows,
                        first.footprints,
                        first.attribution,
                    ));
                }
                observe(&Observed {
                    setting,
                    eye: &ground.eye,
                    truth: &ground.truth,
                    shadows: first.shadows,
                    footprints: first.footprints,
                })
            })?;
        measurements.push(measurement);
    }
    progress(all.len(), all.len(), None);
    Ok(Study {
        scene: scene.name.clone(),
        timing_runs: options.timing_runs.max(1),
        bias: options.bias,
        focus: Some(options.focus),
        width: scene.camera.width,
        height: scene.camera.height,
        visible: ground.eye.visible(),
        truth_time: ground.truth_time,
        map_truth,
        measurements,
        truth: ground.truth,
        pictures,
        view_axis,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    fn timings(planning: u64, shadow_pass: u64, lookup: u64) -> Timings {
        Timings {
            eye_pass: Duration::ZERO,
            planning: ms(planning),
            shadow_pass: ms(shadow_pass),
            lookup: ms(lookup),
        }
    }

    fn outcome_of(errors: u64, runs: &[Timings]) -> Outcome {
        let stats = AliasingStats {
            max: 0.0,
            p99: 0.0,
            mean: 0.0,
            count: 0,
        };
        let mut o = Outcome {
            errors: Misclassification {
                visible: 100,
                falsely_lit: errors,
                falsely_shadowed: 0,
            },
            causes: Causes {
                aliasing: errors,
                ..Causes::default()
            },
            texels: 0,
            footprint: [stats; 3],
            planning: Duration::ZERO,
            shadow_pass: Duration::ZERO,
            lookup: Duration::ZERO,
            attribution: Duration::ZERO,
            footprints: Duration::ZERO,
            time_spread: Duration::ZERO,
            leaks: None,
        };
        time_from_runs(&mut o, runs);
        o
    }

    #[test]
    fn a_time_is_the_median_runs_phases_and_half_the_range() {
        let o = outcome_of(0, &[timings(1, 10, 9), timings(2, 30, 8), timings(1, 5, 4)]);
        // Totals 20, 40, 10: the median run is the first; the range 30.
        assert_eq!(
            (o.planning, o.shadow_pass, o.lookup),
            (ms(1), ms(10), ms(9))
        );
        assert_eq!(o.time_spread, ms(15));
        let one = outcome_of(0, &[timings(1, 2, 3)]);
        assert_eq!((one.time(), one.time_spread), (ms(6), Duration::ZERO));
    }

    #[test]
    fn a_combination_is_dominated_only_beyond_the_spread() {
        let fast = outcome_of(10, &[timings(0, 100, 0), timings(0, 110, 0)]);
        // Slower by 4 ms, within the spreads (5 + 0): not dominated.
        let close = outcome_of(20, &[timings(0, 104, 0)]);
        // Slower by 20 ms, beyond them: dominated.
        let slow = outcome_of(20, &[timings(0, 120, 0)]);
        assert!(!crate::report::dominates(&fast, &close));
        assert!(crate::report::dominates(&fast, &slow));
        // Fewer errors are never dominated by more, however fast.
        assert!(!crate::report::dominates(&slow, &fast));
    }
}
