//! The camera walk of `temporal`: it starts at the scene's camera, and every frame of the default
//! walk on `outdoor` can be planned by every technique — frame 16 once failed for `optimal`, whose
//! four samples nearly on one line fit a window the focus body had no volume in.

use shadowlab_analysis::temporal::pose_at;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::optimal::{self, OptimalOptions, Readback};
use shadowlab_shadow::{FocusPolicy, scene_input};

/// Rounding of a re-orthonormalised unit vector.
const ROUNDING: f64 = 1e-14;

#[test]
fn the_walk_starts_at_the_scene_camera() {
    let scene = builtin_scene("outdoor").unwrap();
    let start = pose_at(&scene, 0).unwrap();
    let camera = scene.camera.pose;
    assert_eq!(start.eye(), camera.eye());
    // The pose is rebuilt by look_to, which re-orthonormalises: equal up to rounding.
    assert!(start.forward().distance(camera.forward()) < ROUNDING);
    assert!(start.up().distance(camera.up()) < ROUNDING);
    let moved = pose_at(&scene, 5).unwrap();
    assert!(moved.eye().distance(scene.camera.pose.eye()) > 0.0);
}

#[test]
fn a_thin_sample_window_keeps_the_initial_map() {
    let mut scene = builtin_scene("outdoor").unwrap();
    scene.camera.pose = pose_at(&scene, 16).unwrap();
    let input = scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light).unwrap();
    // The case that failed: frame 16 of the walk with a 512² initial map (the default then),
    // which sees the shadows of only a few of the thin poles.
    let options = OptimalOptions {
        initial_resolution: 512,
        ..OptimalOptions::default()
    };
    let readback = Readback::new(&scene, options.readback).unwrap();
    let planned = optimal::plan(&scene, &input, &readback, &options).unwrap();
    assert!(planned.report.samples.total() < 10, "{:?}", planned.report);
    assert_eq!(planned.report.h, None, "{:?}", planned.report);
}

/// Claim: the surface shimmer counts what stabilisation removes. Bevy's cascades keep their size
/// as the camera walks and turns, so with its snapping no still surface point changes state; with
/// the snapping off the windows slide by fractions of a texel and shadows crawl. The screen count
/// compares pixels, which see other points as the camera moves, and does not tell them apart so.
#[test]
fn snapping_removes_surface_shimmer_from_sphere_and_diagonal_fits() {
    use shadowlab_analysis::temporal::temporal;
    use shadowlab_shadow::{Engine, PresetChoices, Stabilisation, Technique};
    let mut scene = builtin_scene("outdoor").unwrap();
    scene.camera.width = 256;
    scene.camera.height = 192;
    let techniques = [
        Technique::Engine(Engine::Bevy, PresetChoices::default()),
        Technique::Engine(
            Engine::Bevy,
            PresetChoices {
                stabilisation: Stabilisation::Unsnapped,
                ..PresetChoices::default()
            },
        ),
    ];
    let runs = temporal(
        &scene,
        &techniques,
        5,
        512,
        shadowlab_shadow::Filter::Nearest,
        |_, _| {},
    )
    .unwrap();
    let surface = |technique: Technique| -> u64 {
        runs.iter()
            .find(|s| s.technique == technique && s.snap_texels == 0)
            .and_then(|s| s.surface_shimmer.clone())
            .expect("measured")
            .iter()
            .sum()
    };
    assert_eq!(surface(techniques[0]), 0, "snapped Bevy cascades crawl");
    assert!(
        surface(techniques[1]) > 0,
        "unsnapped Bevy cascades stay still"
    );
}
