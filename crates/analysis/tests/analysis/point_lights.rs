//! Point lights against the exact truth: the cube map's misclassified pixels shrink with its
//! resolution, their causes sum to them, and the study reports a technique that cannot serve a
//! point light as that setting's error.

use shadowlab_analysis::study::{self, StudyOptions};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::{Scene, SceneLight, builtin_scene};
use shadowlab_shadow::{Bias, Filter, FocusPolicy, Splits, Technique};

/// The chess board at a quarter of its image size under a point light where its spot light was.
fn chess_point() -> Scene {
    let mut scene = builtin_scene("chess-spot").unwrap();
    scene.camera.width /= 4;
    scene.camera.height /= 4;
    let SceneLight::Spot { pose, .. } = &scene.lights[0] else {
        panic!("chess-spot has a spot light")
    };
    scene.lights = vec![SceneLight::Point {
        position: pose.eye(),
        range: None,
    }];
    scene
}

fn options(techniques: &[&str], resolutions: Vec<u32>) -> StudyOptions {
    StudyOptions {
        techniques: techniques
            .iter()
            .map(|spec| Technique::parse_spec(spec).unwrap())
            .collect(),
        resolutions,
        partitions: vec![1],
        splits: Splits::DEFAULT,
        filters: vec![Filter::Nearest],
        bias: Bias::DEFAULT,
        format: DepthFormat::F32,
        map_truth: false,
        pictures_at: None,
        optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
        focus: FocusPolicy::Light,
        timing_runs: 1,
    }
}

/// Claim: the cube and dual-paraboloid maps of a point light misclassify fewer than half as many
/// pixels at 2048² as at 256², their causes sum to their errors, and the cube spends six maps'
/// texels at most, the paraboloid two.
#[test]
fn the_omnidirectional_maps_converge_to_the_truth() {
    for (technique, most) in [("cube", 6), ("dual-paraboloid", 2)] {
        converges(technique, most);
    }
}

fn converges(technique: &str, most_maps: u64) {
    let scene = chess_point();
    let study = study::run(
        &scene,
        &options(&[technique], vec![256, 2048]),
        |_, _, _| {},
    )
    .unwrap();
    let outcomes: Vec<_> = study
        .measurements
        .iter()
        .map(|m| m.outcome.as_ref().unwrap())
        .collect();
    for o in &outcomes {
        assert_eq!(o.causes.total(), o.errors.total(), "{:?}", o.causes);
    }
    let (coarse, fine) = (outcomes[0], outcomes[1]);
    assert!(coarse.errors.total() > 0);
    assert!(
        fine.errors.total() * 2 < coarse.errors.total(),
        "{technique}: {:?} against {:?}",
        fine.errors,
        coarse.errors
    );
    assert!(fine.texels <= most_maps * 2048 * 2048 && fine.texels >= 2048 * 2048);
}

/// Claim: a study of a technique that cannot serve the scene's point light fails before any work,
/// naming the technique, the light's kind and the techniques that serve it.
#[test]
fn a_study_refuses_techniques_that_cannot_serve_a_point_light() {
    let scene = chess_point();
    let error = study::run(
        &scene,
        &options(&["cube", "lispsm"], vec![256]),
        |_, _, _| panic!("no setting is measured"),
    )
    .unwrap_err();
    assert_eq!(
        error.to_string(),
        "lispsm cannot serve a point light; techniques for point lights: cube, dual-paraboloid, psm"
    );
}
