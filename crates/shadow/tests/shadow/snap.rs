//! Texel snapping: the world origin lands on a corner of the snapping grid, the window moves by at
//! most half a grid step, every point moves alike, and a camera moved sideways by less than a texel
//! gives the same snapped map window when the fitted window's size does not change.

use glam::DVec3;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::{FocusPolicy, PlanInput, Technique, plan, scene_input, snap_to_texels};

/// Tolerance of NDC coordinates computed through a 4×4 matrix product of magnitude ~1.
const NDC_EPS: f64 = 1e-9;

fn outdoor_input() -> PlanInput {
    let scene = builtin_scene("outdoor").unwrap();
    scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light).unwrap()
}

/// Claim: after snapping to a `texels`-texel grid the origin's window position is a multiple of
/// the grid step, the shift is at most half a step on each axis, and every other point is shifted
/// by exactly the same window offset (a pure translation of the window).
#[test]
fn the_origin_lands_on_the_grid_and_the_window_only_translates() {
    let input = outdoor_input();
    for technique in [Technique::Uniform, Technique::UniformLimited] {
        let setup = plan(&input, technique).unwrap();
        for (resolution, texels) in [(1024, 1), (2048, 2), (750, 1)] {
            let snapped = snap_to_texels(&setup, resolution, texels);
            let step = f64::from(texels) / f64::from(resolution);
            let origin = snapped.mapping.window(DVec3::ZERO).unwrap();
            let before = setup.mapping.window(DVec3::ZERO).unwrap();
            for axis in 0..2 {
                let cells = origin[axis] / step;
                assert!(
                    (cells - cells.round()).abs() < NDC_EPS / step,
                    "{technique:?}: {cells}"
                );
                assert!((origin[axis] - before[axis]).abs() <= step / 2.0 + NDC_EPS);
            }
            let shift = origin - before;
            for point in [DVec3::new(10.0, 0.0, -50.0), DVec3::new(-3.0, 2.0, -200.0)] {
                let moved =
                    snapped.mapping.window(point).unwrap() - setup.mapping.window(point).unwrap();
                assert!(
                    (moved - shift).abs().max_element() < NDC_EPS,
                    "{technique:?}: {moved} vs {shift}"
                );
            }
        }
    }
}

/// Claim: snapping to 0 texels, or a map that is not projective, changes nothing.
#[test]
fn zero_texels_and_the_logarithmic_map_are_left_alone() {
    let input = outdoor_input();
    let uniform = plan(&input, Technique::Uniform).unwrap();
    assert_eq!(snap_to_texels(&uniform, 1024, 0), uniform);
    let logarithmic = plan(&input, Technique::LOGARITHMIC).unwrap();
    assert_eq!(snap_to_texels(&logarithmic, 1024, 1), logarithmic);
}
