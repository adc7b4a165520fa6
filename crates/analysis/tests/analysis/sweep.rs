//! The logarithmic map swept across γ = φ, where the eye crosses B's near plane and the map's
//! reference point leaves the eye, and down to γ = 0: its misclassified pixels change no more
//! there than a small angle step explains elsewhere (issue 11 §2).

use shadowlab_analysis::sweep::{Side, light_at, sweep};
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::{LogarithmicChoice, Technique, scene_eye};

/// Misclassified pixels at each angle, in order.
fn errors_at(scene: &shadowlab_scene::Scene, technique: Technique, angles: &[f64]) -> Vec<u64> {
    sweep(
        scene,
        &[technique],
        angles,
        Side::Front,
        256,
        shadowlab_shadow::Filter::Nearest,
        |_, _| {},
    )
    .unwrap()
    .iter()
    .map(|p| {
        let (m, _) = p
            .outcome
            .as_ref()
            .unwrap_or_else(|e| panic!("{technique}: {e}"));
        m.falsely_lit + m.falsely_shadowed
    })
    .collect()
}

/// Claim: across φ (steps of 0.1°, from φ − 0.5° to φ + 0.5°) the change in misclassified
/// pixels between neighbouring angles at φ is at most twice the largest change between
/// neighbours away from φ, plus 0.2 % of the image — no jump — for the default reference rule and
/// for face partitioning; and as γ → 0 (1°, 0.1°, 0.01°, 0) the misclassified pixels settle
/// (the last two steps change by no more than 0.2 % of the image).
#[test]
fn the_logarithmic_maps_errors_are_continuous_across_phi_and_at_zero() {
    let mut scene = builtin_scene("outdoor").unwrap();
    (scene.camera.width, scene.camera.height) = (160, 120);
    let pixels = f64::from(scene.camera.width * scene.camera.height);
    let eye = scene_eye(&scene);
    let phi = eye.half_fov_toward(light_at(&scene.camera.pose, 0.5, Side::Front));
    let step = 0.1f64.to_radians();
    let angles: Vec<f64> = (-5..=5).map(|k| phi + f64::from(k) * step).collect();
    let slack = 0.002 * pixels;
    for technique in [
        Technique::LOGARITHMIC,
        Technique::Logarithmic(LogarithmicChoice::Faces),
    ] {
        let errors = errors_at(&scene, technique, &angles);
        let changes: Vec<f64> = errors
            .windows(2)
            .map(|w| {
                (f64::from(u32::try_from(w[1]).unwrap()) - f64::from(u32::try_from(w[0]).unwrap()))
                    .abs()
            })
            .collect();
        // Changes 4 and 5 straddle φ (angles 5 = φ).
        let elsewhere = changes
            .iter()
            .enumerate()
            .filter(|(k, _)| *k != 4 && *k != 5)
            .map(|(_, c)| *c)
            .fold(0.0, f64::max);
        for k in [4, 5] {
            assert!(
                changes[k] <= 2.0 * elsewhere + slack,
                "{technique}: {errors:?} jumps by {} at φ (elsewhere at most {elsewhere})",
                changes[k]
            );
        }
        let near_zero = errors_at(
            &scene,
            technique,
            &[1f64.to_radians(), 0.1f64.to_radians(), 1e-4, 0.0],
        );
        for w in near_zero.windows(2).skip(1) {
            let change = (f64::from(u32::try_from(w[1]).unwrap())
                - f64::from(u32::try_from(w[0]).unwrap()))
            .abs();
            assert!(change <= slack, "{technique}: {near_zero:?} near γ = 0");
        }
    }
}
