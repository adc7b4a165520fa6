//! Point lights against the exact truth: the cube and paraboloid maps' misclassified pixels shrink
//! with their resolution and their causes sum to them, the range bounds truth and maps, and a study
//! refuses a technique that cannot serve a point light before any work.

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

/// Claim: a point light's range bounds what it lights: the truth marks the visible points beyond
/// it as outside the light (not counted as misclassified), none within it, and every cube face's
/// far plane lies within the range.
#[test]
fn a_point_lights_range_bounds_the_truth_and_the_maps() {
    let mut scene = chess_point();
    let SceneLight::Point { position, .. } = scene.lights[0] else {
        unreachable!("chess_point has a point light")
    };
    let (eye, _) = shadowlab_shadow::eye_pass(&scene).unwrap();
    // Halfway between the nearest and the farthest visible point.
    let distances = eye
        .triangle
        .iter()
        .zip(&eye.position)
        .filter(|(t, _)| **t != shadowlab_raster::NO_TRIANGLE)
        .map(|(_, p)| (*p - position).length());
    let (near, far) = distances.fold((f64::INFINITY, 0.0_f64), |(lo, hi), d| {
        (lo.min(d), hi.max(d))
    });
    let range = 0.5 * (near + far);
    scene.lights[0] = SceneLight::Point {
        position,
        range: Some(range),
    };
    let bvh = shadowlab_analysis::truth::scene_bvh(&scene).unwrap();
    let truth = shadowlab_analysis::truth::exact_truth(&scene, &eye, &bvh).unwrap();
    let (mut beyond, mut within) = (0, 0);
    for (pixel, &triangle) in eye.triangle.iter().enumerate() {
        if triangle == shadowlab_raster::NO_TRIANGLE {
            continue;
        }
        let far = (eye.position[pixel] - position).length() > range;
        assert_eq!(truth.outside_cone[0][pixel], far, "pixel {pixel}");
        if far {
            beyond += 1;
        } else {
            within += 1;
        }
    }
    assert!(
        beyond > 100 && within > 100,
        "{beyond} beyond, {within} within"
    );
    let partitions = shadowlab_shadow::plan_light(
        &scene,
        &scene.lights[0],
        &shadowlab_shadow::PlanOptions::new(Technique::Cube),
        None,
        256,
        None,
    )
    .unwrap();
    for partition in &partitions {
        let shadowlab_shadow::ShadowMapping::Projective(mapping) = &partition.setup.mapping else {
            panic!("a cube face is projective")
        };
        // GL's projection: far = m32/(m22 + 1).
        let (a, b) = (mapping.projection().z_axis.z, mapping.projection().w_axis.z);
        assert!(b / (a + 1.0) <= range * (1.0 + 1e-12));
    }
}
