//! The one configuration all figures share.

use shadowlab_params::{DepthRange, FrustumModel, HalfFov, ParamError};

/// The view frustum of the 2-D model and the partition settings the figures use.
///
/// The default is the papers' configuration: `n = 1`, `f = 100`, a 60° field of view (φ = 30°),
/// four partitions, the CAD survey's δ = 2 and the practical split's λ = 0.5.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveConfig {
    model: FrustumModel,
    fov_degrees: f64,
    partitions: usize,
    adaptive_delta: f64,
    practical_weight: f64,
}

impl Default for CurveConfig {
    fn default() -> Self {
        Self::new(1.0, 100.0, 60.0).expect("the papers' configuration is valid")
    }
}

impl CurveConfig {
    /// Depth range `[near, far]` and full field of view in degrees, with the default partition
    /// settings. `Err` names `near`, `far` or `fov`.
    pub fn new(near: f64, far: f64, fov_degrees: f64) -> Result<Self, ParamError> {
        let model = FrustumModel::new(
            DepthRange::new(near, far)?,
            HalfFov::from_full_fov_degrees(fov_degrees)?,
        );
        Ok(Self {
            model,
            fov_degrees,
            partitions: 4,
            adaptive_delta: 2.0,
            practical_weight: 0.5,
        })
    }

    /// The 2-D view-frustum model.
    #[must_use]
    pub fn model(&self) -> &FrustumModel {
        &self.model
    }

    /// The eye depth range.
    #[must_use]
    pub fn range(&self) -> DepthRange {
        self.model.range()
    }

    /// The number of partitions of the `partitions` figure.
    #[must_use]
    pub fn partitions(&self) -> usize {
        self.partitions
    }

    /// δ of CAD eq. 19 in the `partitions` figure.
    #[must_use]
    pub fn adaptive_delta(&self) -> f64 {
        self.adaptive_delta
    }

    /// λ of the practical split in the `partitions` figure.
    #[must_use]
    pub fn practical_weight(&self) -> f64 {
        self.practical_weight
    }

    /// "n = 1, f = 100, fov = 60° (φ = 30°)", for titles.
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "n = {}, f = {}, fov = {}° (φ = {}°)",
            self.range().near(),
            self.range().far(),
            self.fov_degrees,
            self.fov_degrees / 2.0
        )
    }
}
