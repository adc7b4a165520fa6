//! The sweep spec: a TOML file naming what to vary. Every field has a default, so an empty file is
//! a sweep (the default scene, its default techniques, one resolution, its own light and camera).
//! [`EXAMPLE`] is a commented spec that runs as it is; docs/cluster.md describes every field.

use std::path::{Path, PathBuf};

use serde::Deserialize;
use shadowlab_shadow::{Bias, Filter, Splits, Technique};

use crate::error::SweepError;

/// A small sweep that runs in seconds, with every field shown and commented
/// (`shadowlab sweep --example`).
pub const EXAMPLE: &str = include_str!("example.toml");

/// The shadow-map side of a spec that names none.
pub const DEFAULT_RESOLUTION: u32 = 1024;

/// The largest shadow-map side a spec may name (the rasterizer's largest target).
pub const MAX_RESOLUTION: u32 = shadowlab_raster::MAX_TARGET_SIZE;

/// The most partitions a spec may name.
pub const MAX_PARTITIONS: u32 = 16;

/// The most timing runs per cell a spec may name.
pub const MAX_TIMING_RUNS: usize = 100;

/// The most light directions or camera poses one generator may make.
pub const MAX_GENERATED: usize = 100_000;

/// The spec as written: every field optional, unknown fields refused.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpecFile {
    scenes: Option<Vec<String>>,
    techniques: Option<Vec<String>>,
    resolutions: Option<Vec<u32>>,
    partitions: Option<Vec<u32>>,
    splits: Option<String>,
    filters: Option<Vec<String>>,
    bias: Option<String>,
    timing_runs: Option<usize>,
    lights: Option<Lights>,
    cameras: Option<Cameras>,
}

/// Where each frame's first light comes from.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Lights {
    /// Each scene's own lights, as its file gives them.
    #[default]
    Scene,
    /// The first light at angles γ from the view direction, in the plane of the view and the
    /// scene's up, as `sweep-angle` places it (`shadowlab_analysis::sweep::light_at`): a point
    /// light moved around the eye at its own distance, any other light replaced by a directional
    /// one; the scene's other lights dropped.
    Gamma {
        /// The angles, degrees in `[0, 90]` (or `range`).
        #[serde(default)]
        degrees: Vec<f64>,
        /// Evenly spaced angles instead: `steps` from `from` to `to` inclusive.
        range: Option<AngleRange>,
        /// Which side the light comes from: `front` (toward the viewer, the dueling frusta) or
        /// `behind`. Default: front.
        #[serde(default)]
        side: Side,
    },
    /// Directions on a grid over the upper hemisphere (+y up): every elevation (degrees above
    /// the horizon, in `(0, 90]`) at `azimuths` evenly spaced azimuths from +x toward +z (one
    /// direction for an elevation of 90°). The first light replaced as for `gamma`.
    Sphere {
        /// Elevations, degrees.
        elevations: Vec<f64>,
        /// Azimuths per elevation (≥ 1).
        azimuths: usize,
    },
}

/// Evenly spaced angles, degrees: `steps` ≥ 2 from `from` to `to` inclusive (1 step: `from`).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AngleRange {
    /// The first angle.
    pub from: f64,
    /// The last angle.
    pub to: f64,
    /// How many.
    pub steps: usize,
}

impl AngleRange {
    /// The angles, in order.
    #[must_use]
    pub fn angles(&self) -> Vec<f64> {
        if self.steps <= 1 {
            return vec![self.from];
        }
        #[expect(clippy::cast_precision_loss, reason = "a step count")]
        let last = (self.steps - 1) as f64;
        (0..self.steps)
            .map(|k| {
                #[expect(clippy::cast_precision_loss, reason = "a step index")]
                let t = k as f64 / last;
                // Exact at both ends.
                (1.0 - t) * self.from + t * self.to
            })
            .collect()
    }
}

/// One camera pose given by the spec.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GivenPose {
    /// Where the eye is.
    pub eye: [f64; 3],
    /// What it looks at.
    pub target: [f64; 3],
    /// The up hint. Default +y.
    #[serde(default = "y_up")]
    pub up: [f64; 3],
}

fn y_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

/// `sweep_angle`'s side, as a spec names it.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// In front of the viewer, shining toward it.
    #[default]
    Front,
    /// Behind the viewer.
    Behind,
}

/// Where each frame's camera is.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Cameras {
    /// Each scene's own camera.
    #[default]
    Scene,
    /// Frames of `temporal`'s camera walk (`shadowlab_analysis::temporal::pose_at`): frames
    /// 0, `every`, 2·`every`, … (`frames` of them).
    Walk {
        /// How many poses.
        frames: usize,
        /// Walk frames between two poses (≥ 1). Default 1.
        #[serde(default = "one")]
        every: usize,
    },
    /// The poses given, in order (a camera path: the same for every scene of the spec).
    Path {
        /// The poses.
        poses: Vec<GivenPose>,
    },
    /// Random poses around the scene's camera ([`crate::frames::random_pose`]): the eye moved by
    /// up to `reach` × the scene's radius, the view turned by up to `turn_degrees`; drawn from
    /// SplitMix64 seeded with `seed`, so the same spec gives the same poses everywhere.
    Random {
        /// How many poses.
        count: usize,
        /// The generator's seed.
        seed: u64,
        /// How far the eye may move, as a fraction of the scene's radius (half its bounding
        /// box's diagonal). Default 0.1.
        #[serde(default = "default_reach")]
        reach: f64,
        /// How far the view may turn (yaw; pitch up to half of it), degrees. Default 20.
        #[serde(default = "default_turn")]
        turn_degrees: f64,
    },
}

fn one() -> usize {
    1
}

fn default_reach() -> f64 {
    0.1
}

fn default_turn() -> f64 {
    20.0
}

/// A scene of the spec: a built-in name or a file (relative paths are the spec's directory's).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneSource {
    /// A built-in scene, by name.
    Builtin(String),
    /// A scene file (.toml, .gltf, .glb).
    File(PathBuf),
}

impl SceneSource {
    /// How a scene argument names it (`analyze SCENE`): the built-in's name, or the file's path
    /// (relative to the spec's directory).
    #[must_use]
    pub fn argument(&self) -> String {
        match self {
            Self::Builtin(name) => name.clone(),
            Self::File(path) => path.display().to_string(),
        }
    }
}

/// A checked spec, its values typed.
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// The scenes, with the label the spec gives each (`scenes[k]` as written).
    pub scenes: Vec<(String, SceneSource)>,
    /// The techniques; `None`: each scene's defaults (`analyze`'s).
    pub techniques: Option<Vec<Technique>>,
    /// Shadow-map sides.
    pub resolutions: Vec<u32>,
    /// Partition counts.
    pub partitions: Vec<u32>,
    /// How partitions split the depth range.
    pub splits: Splits,
    /// Lookup filters.
    pub filters: Vec<Filter>,
    /// Every lookup's bias.
    pub bias: Bias,
    /// Timing runs per cell (1: errors and footprints only matter).
    pub timing_runs: usize,
    /// The light directions.
    pub lights: Lights,
    /// The camera poses.
    pub cameras: Cameras,
}

impl Spec {
    /// Parses and checks a spec's text; relative scene paths are taken from `base` (the spec's
    /// directory). Errors name the field (`techniques[2]`).
    ///
    /// # Errors
    /// [`SweepError::Spec`] naming the field and the problem.
    pub fn parse(text: &str, base: &Path) -> Result<Self, SweepError> {
        let file: SpecFile = toml::from_str(text).map_err(|e| SweepError::Spec(e.to_string()))?;
        let field = |name: String, problem: String| SweepError::Spec(format!("{name}: {problem}"));
        let scenes = file
            .scenes
            .unwrap_or_else(|| vec![shadowlab_scene::DEFAULT_SCENE.to_string()]);
        nonempty("scenes", scenes.len())?;
        let scenes = scenes
            .into_iter()
            .map(|name| {
                let source = if shadowlab_scene::BUILTIN_SCENES.contains(&name.as_str()) {
                    SceneSource::Builtin(name.clone())
                } else {
                    SceneSource::File(base.join(&name))
                };
                (name, source)
            })
            .collect();
        let techniques = file
            .techniques
            .map(|list| {
                nonempty("techniques", list.len())?;
                list.iter()
                    .enumerate()
                    .map(|(k, s)| {
                        Technique::parse_spec(s).map_err(|e| field(format!("techniques[{k}]"), e))
                    })
                    .collect::<Result<Vec<_>, _>>()
            })
            .transpose()?;
        let resolutions = file.resolutions.unwrap_or_else(|| vec![DEFAULT_RESOLUTION]);
        nonempty("resolutions", resolutions.len())?;
        for (k, r) in resolutions.iter().enumerate() {
            if !(1..=MAX_RESOLUTION).contains(r) {
                return Err(field(
                    format!("resolutions[{k}]"),
                    format!("{r} is not a map side in 1..={MAX_RESOLUTION}"),
                ));
            }
        }
        let partitions = file.partitions.unwrap_or_else(|| vec![1]);
        nonempty("partitions", partitions.len())?;
        for (k, p) in partitions.iter().enumerate() {
            if !(1..=MAX_PARTITIONS).contains(p) {
                return Err(field(
                    format!("partitions[{k}]"),
                    format!("{p} is not a partition count in 1..={MAX_PARTITIONS}"),
                ));
            }
        }
        let splits = file
            .splits
            .map(|s| Splits::parse(&s).map_err(|e| field("splits".into(), e)))
            .transpose()?
            .unwrap_or(Splits::DEFAULT);
        let filters = match file.filters {
            None => vec![Filter::Nearest],
            Some(list) => {
                nonempty("filters", list.len())?;
                list.iter()
                    .enumerate()
                    .map(|(k, s)| Filter::parse(s).map_err(|e| field(format!("filters[{k}]"), e)))
                    .collect::<Result<Vec<_>, _>>()?
            }
        };
        let bias = file
            .bias
            .map(|s| Bias::parse(&s).map_err(|e| field("bias".into(), e)))
            .transpose()?
            .unwrap_or(Bias::DEFAULT);
        let timing_runs = file.timing_runs.unwrap_or(1);
        if !(1..=MAX_TIMING_RUNS).contains(&timing_runs) {
            return Err(field(
                "timing_runs".into(),
                format!("{timing_runs} is not in 1..={MAX_TIMING_RUNS}"),
            ));
        }
        let lights = file.lights.unwrap_or_default();
        check_lights(&lights)?;
        let cameras = file.cameras.unwrap_or_default();
        check_cameras(&cameras)?;
        Ok(Self {
            scenes,
            techniques,
            resolutions,
            partitions,
            splits,
            filters,
            bias,
            timing_runs,
            lights,
            cameras,
        })
    }
}

/// A list field that must not be empty.
fn nonempty(name: &str, len: usize) -> Result<(), SweepError> {
    if len == 0 {
        Err(SweepError::Spec(format!(
            "{name}: an empty list sweeps nothing; leave the field out for its default"
        )))
    } else {
        Ok(())
    }
}

/// A generator's count in `1..=MAX_GENERATED`.
fn count(name: &str, n: usize) -> Result<(), SweepError> {
    if (1..=MAX_GENERATED).contains(&n) {
        Ok(())
    } else {
        Err(SweepError::Spec(format!(
            "{name}: {n} is not in 1..={MAX_GENERATED}"
        )))
    }
}

fn check_lights(lights: &Lights) -> Result<(), SweepError> {
    match lights {
        Lights::Scene => Ok(()),
        Lights::Gamma { degrees, range, .. } => {
            let field = match (degrees.is_empty(), range) {
                (false, None) => "lights.degrees",
                (true, Some(range)) => {
                    count("lights.range.steps", range.steps)?;
                    "lights.range"
                }
                _ => {
                    return Err(SweepError::Spec(
                        "lights: give the angles γ as degrees = [...] or as range = { from, to, steps }, one of the two".into(),
                    ));
                }
            };
            let angles = gamma_angles(degrees, range.as_ref());
            count(field, angles.len())?;
            for (k, d) in angles.iter().enumerate() {
                if !(0.0..=90.0).contains(d) {
                    return Err(SweepError::Spec(format!(
                        "{field}: angle {k}, {d}, is not an angle in [0, 90] degrees"
                    )));
                }
            }
            Ok(())
        }
        Lights::Sphere {
            elevations,
            azimuths,
        } => {
            count("lights.elevations", elevations.len())?;
            count("lights.azimuths", *azimuths)?;
            count(
                "lights (elevations × azimuths)",
                elevations.len() * azimuths,
            )?;
            for (k, e) in elevations.iter().enumerate() {
                if !(*e > 0.0 && *e <= 90.0) {
                    return Err(SweepError::Spec(format!(
                        "lights.elevations[{k}]: {e} is not an elevation in (0, 90] degrees"
                    )));
                }
            }
            Ok(())
        }
    }
}

/// The angles γ of a `gamma` light placement, degrees: `degrees`, or `range`'s.
#[must_use]
pub fn gamma_angles(degrees: &[f64], range: Option<&AngleRange>) -> Vec<f64> {
    range.map_or_else(|| degrees.to_vec(), AngleRange::angles)
}

fn check_cameras(cameras: &Cameras) -> Result<(), SweepError> {
    match cameras {
        Cameras::Scene => Ok(()),
        Cameras::Path { poses } => {
            count("cameras.poses", poses.len())?;
            for (k, p) in poses.iter().enumerate() {
                let v = |a: [f64; 3]| glam::DVec3::from_array(a);
                shadowlab_hull::ViewPose::look_at(v(p.eye), v(p.target), v(p.up))
                    .map_err(|e| SweepError::Spec(format!("cameras.poses[{k}]: {e}")))?;
            }
            Ok(())
        }
        Cameras::Walk { frames, every } => {
            count("cameras.frames", *frames)?;
            count("cameras.every", *every)
        }
        Cameras::Random {
            count: n,
            reach,
            turn_degrees,
            ..
        } => {
            count("cameras.count", *n)?;
            if !(reach.is_finite() && (0.0..=10.0).contains(reach)) {
                return Err(SweepError::Spec(format!(
                    "cameras.reach: {reach} is not a fraction of the scene's radius in [0, 10]"
                )));
            }
            if !(0.0..=90.0).contains(turn_degrees) {
                return Err(SweepError::Spec(format!(
                    "cameras.turn_degrees: {turn_degrees} is not an angle in [0, 90]"
                )));
            }
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Spec, String> {
        Spec::parse(text, Path::new("/specs")).map_err(|e| e.to_string())
    }

    #[test]
    fn an_empty_spec_is_the_default_sweep() {
        let spec = parse("").unwrap();
        assert_eq!(spec.scenes.len(), 1);
        assert_eq!(spec.scenes[0].0, shadowlab_scene::DEFAULT_SCENE);
        assert_eq!(spec.techniques, None);
        assert_eq!(spec.resolutions, vec![DEFAULT_RESOLUTION]);
        assert_eq!((spec.lights, spec.cameras), (Lights::Scene, Cameras::Scene));
    }

    #[test]
    fn the_example_parses() {
        let spec = parse(EXAMPLE).unwrap();
        assert!(spec.techniques.is_some());
    }

    #[test]
    fn an_angle_range_is_exact_at_both_ends() {
        let range = AngleRange {
            from: 0.0,
            to: 90.0,
            steps: 7,
        };
        assert_eq!(
            range.angles(),
            vec![0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]
        );
    }

    #[test]
    fn a_file_scene_is_the_specs_directorys() {
        let spec = parse("scenes = [\"mine.gltf\", \"outdoor\"]").unwrap();
        assert_eq!(
            spec.scenes[0].1,
            SceneSource::File(PathBuf::from("/specs/mine.gltf"))
        );
        assert_eq!(spec.scenes[1].1, SceneSource::Builtin("outdoor".into()));
    }

    #[test]
    fn errors_name_the_field() {
        for (text, field) in [
            ("techniques = [\"uniform\", \"bogus\"]", "techniques[1]"),
            ("resolutions = [0]", "resolutions[0]"),
            ("partitions = [99]", "partitions[0]"),
            ("filters = []", "filters"),
            ("timing_runs = 0", "timing_runs"),
            ("colour = 3", "colour"),
            (
                "[lights]\nkind = \"gamma\"\ndegrees = [10, 91]",
                "lights.degrees: angle 1",
            ),
            (
                "[lights]\nkind = \"sphere\"\nelevations = [0]\nazimuths = 4",
                "lights.elevations[0]",
            ),
            ("[cameras]\nkind = \"walk\"\nframes = 0", "cameras.frames"),
            (
                "[cameras]\nkind = \"path\"\nposes = [{ eye = [0, 1, 0], target = [0, 1, 0] }]",
                "cameras.poses[0]",
            ),
            (
                "[lights]\nkind = \"gamma\"\nrange = { from = 0, to = 100, steps = 3 }",
                "lights.range",
            ),
            (
                "[lights]\nkind = \"gamma\"\ndegrees = [1]\nrange = { from = 0, to = 9, steps = 3 }",
                "one of the two",
            ),
            ("[cameras]\nkind = \"orbit\"", "orbit"),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.contains(field), "{text}: {e}");
        }
    }
}
