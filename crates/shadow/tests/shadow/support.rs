//! Configurations for the tests: a camera and a directional light at a chosen angle γ, the light in
//! the camera's vertical plane (so that φ is half the vertical field of view, as in the 2-D model).

use glam::{DQuat, DVec3};
use proptest::test_runner::{Config, RngSeed};
use shadowlab_hull::{Aabb, Perspective, ViewPose};
use shadowlab_shadow::{Eye, FocusPolicy, LightSource, PlanInput};

/// The seed of every property in this crate's tests.
pub(crate) const SEED: u64 = 0x5348_4144_4f57_5348; // "SHADOWSH"

pub(crate) fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        failure_persistence: None,
        ..Config::default()
    }
}

/// A camera with its orientation given by yaw and pitch (radians) and roll, and a directional
/// light at angle `gamma` from the view direction, tilted toward the camera's up (`above`) or
/// down, shining from in front (`facing`) or from behind.
#[expect(clippy::too_many_arguments, reason = "one test configuration")]
pub(crate) fn configuration(
    eye: DVec3,
    yaw: f64,
    pitch: f64,
    fov_y_degrees: f64,
    near: f64,
    far: f64,
    gamma: f64,
    above: bool,
    facing: bool,
    focus: FocusPolicy,
) -> PlanInput {
    let rotation = DQuat::from_rotation_y(yaw) * DQuat::from_rotation_x(pitch);
    let forward = rotation * DVec3::NEG_Z;
    let up = rotation * DVec3::Y;
    let pose = ViewPose::look_to(eye, forward, up).expect("a valid pose");
    let projection = Perspective::new(fov_y_degrees.to_radians(), 4.0 / 3.0, near, far)
        .expect("a valid projection");
    let tilt = if above { 1.0 } else { -1.0 };
    let along = if facing { 1.0 } else { -1.0 };
    // γ is the smallest angle between the view direction and the light vector (toward the light).
    let to_light = forward * (along * gamma.cos()) + up * (tilt * gamma.sin());
    let light = LightSource::directional(to_light).expect("a unit light");
    let reach = 2.0 * far;
    PlanInput {
        eye: Eye { pose, projection },
        light,
        scene: Aabb::new(eye - DVec3::splat(reach), eye + DVec3::splat(reach)).expect("a box"),
        nearest_visible_depth: None,
        focus,
    }
}

/// Relative difference.
pub(crate) fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs())
}
