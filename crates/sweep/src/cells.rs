//! A sweep's cells: every frame (scene × camera pose × light placement) times every combination
//! of its study (technique × resolution × partitions × filter), numbered in that order, each with
//! an estimated cost.

use shadowlab_analysis::study::{self, DEFAULT_TECHNIQUES, Setting, StudyOptions};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::{Scene, SceneLight};
use shadowlab_shadow::optimal::OptimalOptions;
use shadowlab_shadow::{FocusPolicy, LightSource, Technique};

use crate::error::SweepError;
use crate::frames::{
    CameraPose, LightPlacement, camera_poses, light_placements, pose_and_lights, posed,
};
use crate::spec::Spec;

/// One frame of the sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Index into the spec's scenes.
    pub scene: usize,
    /// Index into the spec's camera poses.
    pub camera: usize,
    /// Index into the spec's light placements.
    pub light: usize,
    /// The camera pose.
    pub pose: CameraPose,
    /// The light placement.
    pub placement: LightPlacement,
}

/// One cell: a frame and a combination.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// Its number in the sweep (the order of enumeration).
    pub index: usize,
    /// Index into [`Plan::frames`].
    pub frame: usize,
    /// The combination.
    pub setting: Setting,
    /// Its estimated cost ([`cell_cost`]), nanoseconds on the machine the model was fitted on.
    pub cost: f64,
}

/// A spec made concrete: its scenes loaded, its frames and cells enumerated.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The scenes, with the label the spec gives each.
    pub scenes: Vec<(String, Scene)>,
    /// Each scene's study options (techniques defaulted per scene).
    pub options: Vec<StudyOptions>,
    /// Every frame, scene by scene, camera by camera, light by light.
    pub frames: Vec<Frame>,
    /// Every cell, frame by frame.
    pub cells: Vec<Cell>,
    /// Each frame's estimated truth cost ([`frame_cost`]).
    pub frame_costs: Vec<f64>,
}

/// The cost model of the estimates, nanoseconds on one thread of the machine of docs/cluster.md
/// (release build), fitted there to `outdoor` at 512² to 2048² with uniform, LiSPSM and the
/// logarithmic map (within 10 % of every cell): a frame's truth costs [`TRUTH_NS_PER_PIXEL`] per eye pixel; a cell
/// [`CELL_NS_PER_PIXEL`] per eye pixel (lookups, footprints, attribution) and, per timing run,
/// [`MAP_NS_PER_TEXEL`] per texel of its maps — [`RAY_NS_PER_TEXEL`] for the logarithmic map,
/// which casts one exact ray per texel.
pub const TRUTH_NS_PER_PIXEL: f64 = 170.0;
/// See [`TRUTH_NS_PER_PIXEL`].
pub const CELL_NS_PER_PIXEL: f64 = 75.0;
/// See [`TRUTH_NS_PER_PIXEL`].
pub const MAP_NS_PER_TEXEL: f64 = 6.0;
/// See [`TRUTH_NS_PER_PIXEL`].
pub const RAY_NS_PER_TEXEL: f64 = 80.0;

/// The most cells a sweep may have (its plan holds every cell in memory, about 200 bytes each).
pub const MAX_CELLS: usize = 10_000_000;

/// A frame's estimated truth cost: its eye pixels at [`TRUTH_NS_PER_PIXEL`].
#[must_use]
pub fn frame_cost(scene: &Scene) -> f64 {
    f64::from(scene.camera.width) * f64::from(scene.camera.height) * TRUTH_NS_PER_PIXEL
}

/// A cell's estimated cost: eye pixels at [`CELL_NS_PER_PIXEL`] plus, per timing run, its maps'
/// texels (side² × partitions × maps per partition) at [`MAP_NS_PER_TEXEL`] or, for the
/// logarithmic map, [`RAY_NS_PER_TEXEL`].
#[must_use]
pub fn cell_cost(scene: &Scene, setting: &Setting, timing_runs: usize) -> f64 {
    let pixels = f64::from(scene.camera.width) * f64::from(scene.camera.height);
    #[expect(clippy::cast_precision_loss, reason = "small counts")]
    let maps = (setting.partitions * setting.technique.most_maps_per_partition()) as f64;
    let texels = f64::from(setting.resolution).powi(2) * maps;
    let per_texel = if matches!(setting.technique, Technique::Logarithmic(_)) {
        RAY_NS_PER_TEXEL
    } else {
        MAP_NS_PER_TEXEL
    };
    #[expect(clippy::cast_precision_loss, reason = "small counts")]
    let runs = timing_runs as f64;
    pixels * CELL_NS_PER_PIXEL + texels * per_texel * runs
}

/// The study options of one scene of the spec: its techniques (the spec's, or the scene's
/// defaults as `analyze` takes them) and the spec's lists; no pictures, no map truth.
#[must_use]
pub fn scene_options(spec: &Spec, scene: &Scene) -> StudyOptions {
    StudyOptions {
        techniques: spec
            .techniques
            .clone()
            .unwrap_or_else(|| study::default_techniques(scene, DEFAULT_TECHNIQUES)),
        resolutions: spec.resolutions.clone(),
        partitions: spec.partitions.iter().map(|p| *p as usize).collect(),
        splits: spec.splits,
        filters: spec.filters.clone(),
        bias: spec.bias,
        format: DepthFormat::F32,
        map_truth: false,
        pictures_at: None,
        optimal: OptimalOptions::default(),
        focus: FocusPolicy::default(),
        timing_runs: spec.timing_runs,
    }
}

impl Plan {
    /// The plan of `spec` over its loaded `scenes` (in the spec's order, with their labels).
    ///
    /// # Errors
    /// [`SweepError::Scene`] if a pose is degenerate or a technique does not serve a scene's light
    /// (naming both); [`SweepError::Spec`] if the sweep has more than [`MAX_CELLS`] cells.
    pub fn new(spec: &Spec, scenes: Vec<(String, Scene)>) -> Result<Self, SweepError> {
        let poses = camera_poses(&spec.cameras)?;
        let placements = light_placements(&spec.lights);
        let options: Vec<StudyOptions> = scenes
            .iter()
            .map(|(_, scene)| scene_options(spec, scene))
            .collect();
        // Each scene's combinations and their costs, the same in every frame of it.
        let combinations: Vec<Vec<(Setting, f64)>> = scenes
            .iter()
            .zip(&options)
            .map(|((_, scene), o)| {
                study::settings(o)
                    .into_iter()
                    .map(|setting| {
                        let cost = cell_cost(scene, &setting, spec.timing_runs);
                        (setting, cost)
                    })
                    .collect()
            })
            .collect();
        let count = combinations.iter().fold(0usize, |n, c| {
            n.saturating_add((poses.len() * placements.len()).saturating_mul(c.len()))
        });
        if count > MAX_CELLS {
            return Err(SweepError::Spec(format!(
                "the sweep has {count} cells, more than {MAX_CELLS}: split it into several specs"
            )));
        }
        let mut frames = Vec::new();
        let mut cells = Vec::with_capacity(count);
        let mut frame_costs = Vec::new();
        for (s, (label, scene)) in scenes.iter().enumerate() {
            for (c, pose) in poses.iter().enumerate() {
                for (l, placement) in placements.iter().enumerate() {
                    // The frame's lights only: a frame's scene is made when it is measured.
                    let (_, lights) = pose_and_lights(scene, *pose, *placement)?;
                    check_lights(label, &lights, &options[s].techniques)?;
                    let frame = frames.len();
                    for (setting, cost) in &combinations[s] {
                        cells.push(Cell {
                            index: cells.len(),
                            frame,
                            setting: setting.clone(),
                            cost: *cost,
                        });
                    }
                    frame_costs.push(frame_cost(scene));
                    frames.push(Frame {
                        scene: s,
                        camera: c,
                        light: l,
                        pose: *pose,
                        placement: *placement,
                    });
                }
            }
        }
        Ok(Self {
            scenes,
            options,
            frames,
            cells,
            frame_costs,
        })
    }

    /// The posed scene of frame `frame`.
    ///
    /// # Errors
    /// As [`posed`] (a plan's frames were posed once already, so none in practice).
    pub fn frame_scene(&self, frame: usize) -> Result<Scene, SweepError> {
        let f = &self.frames[frame];
        posed(&self.scenes[f.scene].1, f.pose, f.placement)
    }

    /// The estimated total cost: every cell and every frame's truth once.
    #[must_use]
    pub fn total_cost(&self) -> f64 {
        self.cells.iter().map(|c| c.cost).sum::<f64>() + self.frame_costs.iter().sum::<f64>()
    }
}

/// Refuses a technique that cannot serve a frame's light (a cube map for a directional light).
fn check_lights(
    label: &str,
    lights: &[SceneLight],
    techniques: &[Technique],
) -> Result<(), SweepError> {
    for (k, light) in lights.iter().enumerate() {
        let source = LightSource::from_scene(light);
        for technique in techniques {
            technique.check_light(&source).map_err(|e| {
                SweepError::Scene(format!(
                    "techniques: {} does not serve scene {label}'s light[{k}]: {e}",
                    technique.spec()
                ))
            })?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::shard::{assign, loads};

    fn example_plan() -> Plan {
        let spec = Spec::parse(crate::EXAMPLE, Path::new(".")).unwrap();
        let scenes = spec
            .scenes
            .iter()
            .map(|(label, _)| {
                (
                    label.clone(),
                    shadowlab_scene::builtin_scene(label).unwrap(),
                )
            })
            .collect();
        Plan::new(&spec, scenes).unwrap()
    }

    #[test]
    fn cells_are_numbered_frame_by_frame() {
        let plan = example_plan();
        // 2 scenes × 1 camera × 3 lights; 4 techniques × 2 sides each.
        assert_eq!((plan.frames.len(), plan.cells.len()), (6, 48));
        for (k, cell) in plan.cells.iter().enumerate() {
            assert_eq!((cell.index, cell.frame), (k, k / 8));
            assert!(cell.cost > 0.0);
        }
    }

    #[test]
    fn every_cell_has_one_shard_and_the_loads_are_balanced() {
        let plan = example_plan();
        let largest = plan.cells.iter().map(|c| c.cost).fold(0.0, f64::max)
            + plan.frame_costs.iter().copied().fold(0.0, f64::max);
        for count in [1, 2, 3, 4, 7, 48, 60] {
            let assignment = assign(&plan, count).unwrap();
            assert_eq!(assignment, assign(&plan, count).unwrap(), "deterministic");
            assert!(assignment.iter().all(|s| *s < count));
            let loads = loads(&plan, &assignment, count);
            let busy: Vec<f64> = loads.iter().copied().filter(|l| *l > 0.0).collect();
            assert_eq!(
                busy.len(),
                count.min(plan.cells.len()),
                "{count}: every shard has work"
            );
            let (lo, hi) = busy
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(*v), h.max(*v)));
            // Longest processing time first: the most loaded shard was the least loaded when it
            // took its last cell, so it exceeds any other by at most one cell and one truth.
            assert!(hi - lo <= largest, "{count}: loads {lo}..{hi}");
        }
    }

    #[test]
    fn too_many_cells_are_refused() {
        let text = "resolutions = [256, 512]\n[cameras]\nkind = \"walk\"\nframes = 100000\n[lights]\nkind = \"sphere\"\nelevations = [10.0, 20.0, 30.0, 40.0, 50.0]\nazimuths = 100";
        let spec = Spec::parse(text, Path::new(".")).unwrap();
        let scenes = vec![(
            "outdoor".into(),
            shadowlab_scene::builtin_scene("outdoor").unwrap(),
        )];
        let e = Plan::new(&spec, scenes).unwrap_err().to_string();
        assert!(e.contains("split it"), "{e}");
    }
}
