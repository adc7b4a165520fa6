//! One cell's result: a flat row, the same in a cell file (JSON), the CSV table and the Parquet
//! table.

use std::time::Duration;

use serde::{Deserialize, Serialize};
use shadowlab_analysis::report::filter_label;
use shadowlab_analysis::study::{Measurement, Outcome};
use shadowlab_scene::Scene;

use crate::frames::light_direction;

/// One cell of a sweep, measured: what it was and what it costs and buys. Optional fields are
/// `None` where the technique is not defined for the cell's frame (`defined` false).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CellRecord {
    /// The cell's index in the sweep's enumeration (scenes × cameras × lights × settings).
    pub cell: u64,
    /// The scene's name as the spec gives it.
    pub scene: String,
    /// The camera pose's index.
    pub camera: u32,
    /// The light direction's index.
    pub light: u32,
    /// The unit vector from the eye toward the first light (a directional light's `to_light`).
    pub light_x: f64,
    /// See `light_x`.
    pub light_y: f64,
    /// See `light_x`.
    pub light_z: f64,
    /// γ, the angle between the view direction and the light direction, degrees in `[0, 90]`.
    pub gamma_deg: f64,
    /// The technique's spec (`lispsm:minimax`).
    pub technique: String,
    /// Shadow-map side.
    pub resolution: u32,
    /// Partition count.
    pub partitions: u32,
    /// The lookup filter's spec.
    pub filter: String,
    /// Whether the technique is defined for the frame.
    pub defined: bool,
    /// Why not, if not.
    pub undefined_reason: Option<String>,
    /// Pixels with a visible surface.
    pub visible: u64,
    /// Misclassified pixels.
    pub misclassified: Option<u64>,
    /// Pixels lit in the map but shadowed in truth.
    pub falsely_lit: Option<u64>,
    /// Pixels shadowed in the map but lit in truth.
    pub falsely_shadowed: Option<u64>,
    /// Texels spent over every map of every light.
    pub texels: Option<u64>,
    /// Texel footprint, pixels per texel: the largest.
    pub footprint_max: Option<f64>,
    /// Texel footprint: 99th percentile.
    pub footprint_p99: Option<f64>,
    /// Texel footprint: mean.
    pub footprint_mean: Option<f64>,
    /// Planning time, milliseconds.
    pub planning_ms: Option<f64>,
    /// Shadow-pass time, milliseconds.
    pub shadow_pass_ms: Option<f64>,
    /// Lookup time, milliseconds.
    pub lookup_ms: Option<f64>,
    /// The wall time of the cell's whole measurement (its shadows, the lookups, footprints and
    /// error attribution, every timing run; not its frame's truth), milliseconds: what the
    /// cost model's estimate is checked against.
    pub cell_ms: f64,
}

impl CellRecord {
    /// The record of `measurement`, cell `cell` of a sweep, measured in `frame` (its scene labelled
    /// `scene`, with camera pose `camera` and light placement `light`; `visible` pixels) in
    /// `cell_ms` milliseconds.
    #[must_use]
    pub fn new(
        (cell, scene, camera, light): (usize, &str, usize, usize),
        (frame, visible): (&Scene, u64),
        measurement: &Measurement,
        cell_ms: f64,
    ) -> Self {
        let (toward, gamma) = light_direction(frame);
        let setting = &measurement.setting;
        let outcome = measurement.outcome.as_ref().ok();
        let ms = |d: fn(&Outcome) -> Duration| outcome.map(|o| d(o).as_secs_f64() * 1e3);
        Self {
            cell: cell as u64,
            scene: scene.to_string(),
            camera: u32::try_from(camera).unwrap_or(u32::MAX),
            light: u32::try_from(light).unwrap_or(u32::MAX),
            light_x: toward.x,
            light_y: toward.y,
            light_z: toward.z,
            gamma_deg: gamma.to_degrees(),
            technique: setting.technique.spec(),
            resolution: setting.resolution,
            partitions: u32::try_from(setting.partitions).unwrap_or(u32::MAX),
            filter: filter_label(&setting.filter),
            defined: outcome.is_some(),
            undefined_reason: measurement.outcome.as_ref().err().cloned(),
            visible,
            misclassified: outcome.map(|o| o.errors.total()),
            falsely_lit: outcome.map(|o| o.errors.falsely_lit),
            falsely_shadowed: outcome.map(|o| o.errors.falsely_shadowed),
            texels: outcome.map(|o| o.texels),
            footprint_max: outcome.map(|o| o.footprint[0].max),
            footprint_p99: outcome.map(|o| o.footprint[0].p99),
            footprint_mean: outcome.map(|o| o.footprint[0].mean),
            planning_ms: ms(|o| o.planning),
            shadow_pass_ms: ms(|o| o.shadow_pass),
            lookup_ms: ms(|o| o.lookup),
            cell_ms,
        }
    }

    /// Misclassified pixels as a fraction of the visible ones (`None` if undefined or nothing is
    /// visible).
    #[must_use]
    pub fn misclassified_fraction(&self) -> Option<f64> {
        #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
        self.misclassified
            .filter(|_| self.visible > 0)
            .map(|m| m as f64 / self.visible as f64)
    }
}
