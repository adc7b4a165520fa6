//! Aliasing along the view axis: the perspective error `dp/ds = (1/z)·dz/ds` measured on the
//! matrices a technique builds for the scene's camera and first light
//! (`shadowlab_shadow::measure::view_axis_error`), plotted over the closed form of
//! `shadowlab-params` (LiSPSM eq. 3 generalised: GMNPR eq. 2, CAD eq. 12; [`FrustumModel::view_axis_error`]).
//!
//! The closed forms assume the map fitted to the view frustum (B = V). Each technique is therefore
//! planned twice: fitted to V, where the measurement must lie on the closed form (issue 5's proof,
//! here on the scene's own configuration), and fitted to the scene's focus body B = conv(V ∪ l) ∩ S
//! as it renders — the difference is what focusing on the scene changes.
//!
//! Closed forms exist for the uniform map and LiSPSM with any parameter (a warp λ) and for the
//! logarithmic map (constant: `ln(f/n)` at 90°, `ln(1 + 1/λ)` at other angles; LiSPSM §4,
//! formulas.md §2.9);
//! PSM and the scene-optimized map have none, and spot lights, whose map is fitted in the spot's
//! normalized device space, are not of the model: their curves carry the measurements only.

use shadowlab_params::{DepthRange, FrustumModel, HalfFov, LightAngle, WarpParameter};
use shadowlab_scene::{Scene, SceneLight};
use shadowlab_shadow::{
    FocusPolicy, LightSetup, PlanInput, ShadowError, ShadowMapping, Technique, measure, plan,
    scene_eye, scene_input,
};

use crate::error::AnalysisError;

/// Depths sampled between the camera's near and far planes (geometrically spaced).
pub const DEPTH_SAMPLES: usize = 48;

/// One technique's error along the view axis.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisCurve {
    /// The technique.
    pub technique: Technique,
    /// Eye depths, from the near to the far plane.
    pub depths: Vec<f64>,
    /// The closed form at each depth for the map fitted to V; `None` where the technique has none.
    pub closed_form: Vec<Option<f64>>,
    /// Measured on the map fitted to V; `None` where the technique is not defined or the point is
    /// not mapped.
    pub fitted_to_view: Vec<Option<f64>>,
    /// Measured on the map fitted to the scene's focus body (what renders).
    pub fitted_to_scene: Vec<Option<f64>>,
    /// `(d fitted, d of the model)`: the warp-axis extent of the 3-D view frustum the map was
    /// fitted to, and of the model's 2-D cut of it by the light–view plane; `None` without a
    /// closed form. Where the two differ (an image that is not square, the light off the image
    /// plane's axes) the closed form and the measurement differ by about as much.
    pub warp_depths: Option<(f64, f64)>,
}

impl AxisCurve {
    /// The largest relative difference between the closed form and the measurement on the map
    /// fitted to V, over the depths where both exist; `None` if there are none.
    #[must_use]
    pub fn closed_form_deviation(&self) -> Option<f64> {
        self.closed_form
            .iter()
            .zip(&self.fitted_to_view)
            .filter_map(|(c, m)| Some((c.as_ref()?, m.as_ref()?)))
            .map(|(c, m)| (m - c).abs() / c.abs())
            .reduce(f64::max)
    }
}

/// The error along the view axis of `scene`'s camera for the first light, per technique.
///
/// # Errors
/// [`AnalysisError::Shadow`] for a scene without lights or with an invalid box, or if planning
/// fails other than by the technique not being defined.
pub fn curves(scene: &Scene, techniques: &[Technique]) -> Result<Vec<AxisCurve>, AnalysisError> {
    let light = scene
        .lights
        .first()
        .ok_or_else(|| ShadowError::NotDefined {
            technique: "view axis",
            reason: "the scene has no light".into(),
        })?;
    let eye = scene_eye(scene);
    let (view_input, scene_input) = (
        scene_input(scene, light, None, FocusPolicy::View)?,
        scene_input(scene, light, None, FocusPolicy::Light)?,
    );
    let projection = eye.projection;
    let range = DepthRange::new(projection.near(), projection.far()).map_err(ShadowError::from)?;
    #[expect(clippy::cast_precision_loss, reason = "a small sample index")]
    let depths: Vec<f64> = (0..DEPTH_SAMPLES)
        .map(|k| range.geometric_lerp(k as f64 / (DEPTH_SAMPLES - 1) as f64))
        .collect();
    let directional = matches!(light, SceneLight::Directional { .. });
    let mut out = Vec::with_capacity(techniques.len());
    for &technique in techniques {
        if matches!(
            technique,
            Technique::Optimal(_)
                | Technique::Sdsm(_)
                | Technique::Engine(..)
                | Technique::Cube
                | Technique::DualParaboloid
        ) {
            // Planned from the scene's or the eye pass's samples, as cascades for a map size, or
            // with near planes at the scene's geometry, not from a plan input: no V-fitted
            // counterpart.
            continue;
        }
        let planned = |input: &PlanInput| match plan(input, technique) {
            Ok(setup) => Ok(Some(setup)),
            Err(e) if e.undefined_reason().is_some() => Ok(None),
            Err(e) => Err(AnalysisError::from(e)),
        };
        let (view_setup, scene_setup) = (planned(&view_input)?, planned(&scene_input)?);
        let measured = |setup: &Option<LightSetup>| -> Vec<Option<f64>> {
            depths
                .iter()
                .map(|&t| {
                    setup
                        .as_ref()
                        .and_then(|s| measure::view_axis_error(&s.mapping, &eye, t))
                })
                .collect()
        };
        let closed_form = depths
            .iter()
            .map(|&t| {
                let setup = view_setup.as_ref().filter(|_| directional)?;
                closed_form(technique, setup, range, t)
            })
            .collect();
        let warp_depths = view_setup
            .as_ref()
            .filter(|_| directional)
            .and_then(|setup| {
                let model = FrustumModel::new(range, HalfFov::from_radians(setup.half_fov).ok()?);
                let gamma = LightAngle::from_radians(setup.gamma).ok()?;
                Some((setup.warp.as_ref()?.depth, model.warp_depth(gamma)))
            });
        out.push(AxisCurve {
            technique,
            warp_depths,
            closed_form,
            fitted_to_view: measured(&view_setup),
            fitted_to_scene: measured(&scene_setup),
            depths: depths.clone(),
        });
    }
    Ok(out)
}

/// The closed-form `dp/ds` at eye depth `t` of the map `setup` (fitted to V) of `technique`.
fn closed_form(technique: Technique, setup: &LightSetup, range: DepthRange, t: f64) -> Option<f64> {
    let model = FrustumModel::new(range, HalfFov::from_radians(setup.half_fov).ok()?);
    let gamma = LightAngle::from_radians(setup.gamma).ok()?;
    match technique {
        Technique::Uniform | Technique::UniformLimited | Technique::Lispsm(_) => {
            let warp = WarpParameter::from_lambda(setup.warp.as_ref()?.lambda).ok()?;
            model.view_axis_error(gamma, warp, t).ok()
        }
        // LiSPSM §4: the ideal parameterisation's constant error — ln(f/n) at 90°, ln(1 + 1/λ)
        // for the warp-axis extent it is fitted to at other angles (formulas.md §2.9) — where its
        // reference point is the eye; elsewhere `LogarithmicMap::view_axis_error`.
        Technique::Logarithmic(_) => match &setup.mapping {
            ShadowMapping::Logarithmic(map) => Some(map.view_axis_error(setup.gamma.sin(), t)),
            ShadowMapping::Projective(_) | ShadowMapping::Paraboloid(_) => None,
        },
        Technique::Psm
        | Technique::Optimal(_)
        | Technique::Given
        | Technique::Sdsm(_)
        | Technique::Cube
        | Technique::DualParaboloid
        | Technique::Engine(..) => None,
    }
}
