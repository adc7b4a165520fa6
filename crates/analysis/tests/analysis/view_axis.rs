//! The view-axis curves: with the light perpendicular to the view (LiSPSM's configuration, where
//! the 3-D frustum's warp-axis extent is the model's), the measurement on the V-fitted matrices
//! lies on the closed form of `shadowlab-params`; the logarithmic map's is constant.

use shadowlab_analysis::view_axis::{DEPTH_SAMPLES, curves};
use shadowlab_scene::{SceneLight, builtin_scene};
use shadowlab_shadow::{StepDirection, Technique, WarpChoice};

/// The agreement of issue 5's proof.
const AGREEMENT: f64 = 1e-6;

#[test]
fn at_90_degrees_the_measurement_lies_on_the_closed_form() {
    let mut scene = builtin_scene("outdoor").unwrap();
    scene.lights = vec![SceneLight::Directional {
        to_light: scene.camera.pose.up(),
    }];
    let techniques = [
        Technique::Uniform,
        Technique::Lispsm(WarpChoice::PAPER),
        Technique::LOGARITHMIC,
        Technique::Psm,
    ];
    let all = curves(&scene, &techniques).unwrap();
    assert_eq!(all.len(), techniques.len());
    for curve in &all {
        assert_eq!(curve.depths.len(), DEPTH_SAMPLES);
        if curve.technique == Technique::Psm {
            assert_eq!(curve.closed_form_deviation(), None);
            assert!(curve.fitted_to_scene.iter().all(Option::is_some));
            continue;
        }
        let (fitted, model) = curve.warp_depths.unwrap();
        assert!(
            (fitted - model).abs() < AGREEMENT * model,
            "{fitted} vs {model}"
        );
        let deviation = curve.closed_form_deviation().unwrap();
        assert!(deviation < AGREEMENT, "{:?}: {deviation}", curve.technique);
    }
    let logarithmic = &all[2].fitted_to_view;
    let first = logarithmic[0].unwrap();
    assert!(
        logarithmic
            .iter()
            .all(|v| (v.unwrap() - first).abs() < AGREEMENT * first)
    );
}

#[test]
fn the_optimized_map_has_no_view_axis_curve_and_a_scene_without_light_is_an_error() {
    let mut scene = builtin_scene("outdoor").unwrap();
    assert!(
        curves(&scene, &[Technique::Optimal(StepDirection::Paper)])
            .unwrap()
            .is_empty()
    );
    scene.lights.clear();
    assert!(curves(&scene, &[Technique::Uniform]).is_err());
}
