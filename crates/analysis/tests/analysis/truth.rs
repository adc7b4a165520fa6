//! Truth on hand-built cases (under the box or beside it, surfaces facing away, a spot's cone and
//! its segment), against the high-resolution map truth, on any thread count, and its errors.

use glam::DVec3;
use shadowlab_analysis::AnalysisError;
use shadowlab_analysis::classify::disagreement;
use shadowlab_analysis::truth::{Truth, exact_truth, map_truth, scene_bvh};
use shadowlab_hull::{Perspective, ViewPose};
use shadowlab_raster::{DepthFormat, NO_TRIANGLE, Triangles};
use shadowlab_scene::{Mesh, SceneLight, procedural};
use shadowlab_shadow::{
    Bias, Filter, Lookup, MapOptions, PlanOptions, ShadowMap, Technique, eye_pass, plan_light,
};
use shadowlab_trace::Bvh;

use crate::support::{box_over_ground, camera, eye_image, on_threads, scene, sun};

/// A camera that sees the box-over-ground scene from above and aside (its image is not used with
/// the hand-built eye images; it only positions the view).
fn overview() -> shadowlab_scene::Camera {
    camera(
        DVec3::new(12.0, 9.0, 14.0),
        DVec3::new(-1.0, 0.5, -1.0),
        50.0,
        160,
        120,
    )
}

/// Claim: with the sun straight above, ground points under the box are in shadow and those beside
/// it lit, and the box's top is lit; with the sun at 45° toward +x the shadow moves to
/// x ∈ [−7, −1], exactly where the box's bottom face projects.
#[test]
fn under_the_box_is_shadowed_and_beside_it_lit() {
    let meshes = box_over_ground();
    let cases = [
        (
            DVec3::Y,
            vec![
                (DVec3::new(0.3, 0.0, 0.2), false),
                (DVec3::new(1.5, 0.0, -1.2), false),
                (DVec3::new(-1.9, 0.0, 1.7), false),
                (DVec3::new(2.1, 0.0, 0.3), true),
                (DVec3::new(3.0, 0.0, 0.1), true),
                (DVec3::new(-6.0, 0.0, 5.0), true),
                (DVec3::new(0.4, 5.0, -0.3), true),
            ],
        ),
        (
            DVec3::new(1.0, 1.0, 0.0),
            vec![
                (DVec3::new(-4.0, 0.0, 0.3), false),
                (DVec3::new(-1.1, 0.0, 1.9), false),
                (DVec3::new(-6.9, 0.0, -1.9), false),
                (DVec3::new(-0.9, 0.0, 0.3), true),
                (DVec3::new(0.3, 0.0, 0.2), true),
                (DVec3::new(-7.1, 0.0, 0.2), true),
                (DVec3::new(-4.0, 0.0, 2.1), true),
            ],
        ),
    ];
    for (to_light, points) in cases {
        let scene = scene(overview(), vec![sun(to_light)], &meshes);
        let positions: Vec<DVec3> = points.iter().map(|(p, _)| *p).collect();
        let eye = eye_image(&scene.mesh, &positions);
        let truth = exact_truth(&scene, &eye, &scene_bvh(&scene).unwrap()).unwrap();
        for (k, (point, lit)) in points.iter().enumerate() {
            assert_eq!(truth.lit[0][k], Some(*lit), "{point} under {to_light}");
            assert!(!truth.outside_cone[0][k]);
        }
    }
}

/// Claim: only occlusion shadows. A point on the box's underside faces away from the sun and is
/// in shadow (its ray starts inside the box and leaves through the top); a point on the underside
/// of an open quad faces away too but nothing blocks it, so it is lit — as the shadow map's lookup
/// says for both, which compares depths and never looks at orientation.
#[test]
fn facing_away_shadows_only_through_occlusion_as_the_lookup_does() {
    let [ground, block] = box_over_ground();
    // An open quad at y = 2 over x, z ∈ [4, 6], wound to face down (−y).
    let quad = Mesh::new(
        vec![
            DVec3::new(4.0, 2.0, 4.0),
            DVec3::new(6.0, 2.0, 4.0),
            DVec3::new(6.0, 2.0, 6.0),
            DVec3::new(4.0, 2.0, 6.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    assert!(quad.normals()[0].y < 0.0);
    let scene = scene(overview(), vec![sun(DVec3::Y)], &[ground, block, quad]);
    let points = [
        (DVec3::new(0.7, 3.0, -0.4), false), // the box's underside
        (DVec3::new(5.3, 2.0, 4.6), true),   // the open quad's underside
        (DVec3::new(5.3, 0.0, 4.6), false),  // the ground under the quad
        (DVec3::new(0.4, 5.0, -0.3), true),  // the box's top
    ];
    let positions: Vec<DVec3> = points.iter().map(|(p, _)| *p).collect();
    let eye = eye_image(&scene.mesh, &positions);
    let truth = exact_truth(&scene, &eye, &scene_bvh(&scene).unwrap()).unwrap();

    let setup = &plan_light(
        &scene,
        &scene.lights[0],
        &PlanOptions::new(Technique::Uniform),
        None,
        256,
        None,
    )
    .unwrap()[0]
        .setup;
    let options = MapOptions {
        resolution: 1024,
        format: DepthFormat::F32,
        second_depth: false,
    };
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let map = ShadowMap::render(setup, mesh, options).unwrap();
    let lookup = Lookup::new(Bias::DEFAULT, Filter::Nearest);
    for (k, (point, lit)) in points.iter().enumerate() {
        assert_eq!(truth.lit[0][k], Some(*lit), "truth at {point}");
        let looked_up = lookup.lit_fraction(&map, *point, eye.normal[k]);
        assert_eq!(looked_up == 1.0, *lit, "lookup at {point}");
    }
}

/// Claim: a spot light lights the points inside its cone that nothing between them and the light
/// blocks; points outside the cone are unlit and marked; a quad *behind* the spot (above it) does
/// not shadow, because the shadow ray ends at the light.
#[test]
fn a_spot_lights_its_cone_up_to_itself() {
    let ground = procedural::plane(40.0, 40.0, 1).unwrap();
    let block = procedural::cuboid(DVec3::splat(2.0))
        .unwrap()
        .transformed(&glam::DAffine3::from_translation(DVec3::new(0.0, 5.0, 0.0)));
    let lid =
        procedural::plane(10.0, 10.0, 1)
            .unwrap()
            .transformed(&glam::DAffine3::from_translation(DVec3::new(
                0.0, 12.0, 0.0,
            )));
    let spot = SceneLight::Spot {
        pose: ViewPose::look_to(DVec3::new(0.0, 10.0, 0.0), DVec3::NEG_Y, DVec3::Z).unwrap(),
        cone: Perspective::new(60f64.to_radians(), 1.0, 1.0, 30.0).unwrap(),
    };
    let scene = scene(overview(), vec![spot], &[ground, block, lid]);
    // The box (y ∈ [4, 6], |x|, |z| ≤ 1) shades the ground out to 1·10/4 = 2.5 along x; the cone's
    // half angle of 30° reaches 10·tan 30° ≈ 5.77 on the ground.
    let points = [
        (DVec3::new(0.3, 0.0, 0.2), Some(false), false),
        (DVec3::new(2.0, 0.0, 0.3), Some(false), false),
        (DVec3::new(3.0, 0.0, 0.4), Some(true), false),
        (DVec3::new(5.0, 0.0, 0.5), Some(true), false),
        (DVec3::new(-2.2, 0.0, -4.9), Some(true), false),
        (DVec3::new(6.5, 0.0, 0.3), Some(false), true),
        (DVec3::new(-4.5, 0.0, -4.5), Some(false), true),
    ];
    let positions: Vec<DVec3> = points.iter().map(|(p, ..)| *p).collect();
    let eye = eye_image(&scene.mesh, &positions);
    let truth = exact_truth(&scene, &eye, &scene_bvh(&scene).unwrap()).unwrap();
    for (k, (point, lit, outside)) in points.iter().enumerate() {
        assert_eq!(truth.lit[0][k], *lit, "lit at {point}");
        assert_eq!(
            truth.outside_cone[0][k], *outside,
            "outside the cone at {point}"
        );
    }
}

/// The box-over-ground scene under an oblique sun, seen from above and aside.
fn oblique_scene() -> shadowlab_scene::Scene {
    scene(
        camera(
            DVec3::new(-11.0, 8.0, -13.0),
            DVec3::new(-1.0, 0.5, -1.0),
            50.0,
            160,
            120,
        ),
        vec![sun(DVec3::new(0.4, 1.0, 0.3))],
        &box_over_ground(),
    )
}

/// Whether some pixel within `reach` pixels (Chebyshev) of `pixel` has another truth value.
fn near_an_edge(truth: &[Option<bool>], width: usize, pixel: usize, reach: usize) -> bool {
    let height = truth.len() / width;
    let (i, j) = (pixel % width, pixel / width);
    let rows = j.saturating_sub(reach)..=(j + reach).min(height - 1);
    rows.into_iter().any(|r| {
        (i.saturating_sub(reach)..=(i + reach).min(width - 1))
            .any(|c| truth[r * width + c] != truth[pixel])
    })
}

/// Claim: Chong and Gortler's map truth (a 4096² uniform map, texels about 1/20 of a pixel on the
/// ground) agrees with the exact truth except within two pixels of a shadow edge or silhouette,
/// and on fewer than 1 % of the pixels.
#[test]
fn exact_and_map_truth_differ_only_at_shadow_edges() {
    let scene = oblique_scene();
    let (eye, _) = eye_pass(&scene).unwrap();
    let exact = exact_truth(&scene, &eye, &scene_bvh(&scene).unwrap()).unwrap();
    let fine = map_truth(&scene, &eye, 4096).unwrap();
    let apart = disagreement(&exact, &fine);
    let shadowed = exact.lit[0].iter().filter(|t| **t == Some(false)).count();
    let lit = exact.lit[0].iter().filter(|t| **t == Some(true)).count();
    assert!(
        shadowed > 1000 && lit > 5000,
        "{shadowed} shadowed, {lit} lit"
    );
    assert_eq!(apart.visible, (shadowed + lit) as u64);
    assert!(
        apart.percentage() < 1.0,
        "{apart:?}: {} %",
        apart.percentage()
    );
    let width = eye.width as usize;
    for (pixel, (a, b)) in exact.lit[0].iter().zip(&fine.lit[0]).enumerate() {
        if a != b {
            assert!(
                near_an_edge(&exact.lit[0], width, pixel, 2),
                "pixel {pixel} ({}, {}): exact {a:?}, map {b:?}, far from any edge",
                pixel % width,
                pixel / width
            );
        }
    }
    // A coarse map disagrees more: the measure can tell maps apart.
    let coarse = map_truth(&scene, &eye, 64).unwrap();
    assert!(disagreement(&exact, &coarse).total() > apart.total());
}

/// Claim: the exact and the map truth are identical on 1, 2 and 3 threads.
#[test]
fn truth_is_the_same_on_any_thread_count() {
    let scene = oblique_scene();
    let (eye, _) = eye_pass(&scene).unwrap();
    let bvh = scene_bvh(&scene).unwrap();
    let run = |threads: usize| -> (Truth, Truth) {
        on_threads(threads, || {
            (
                exact_truth(&scene, &eye, &bvh).unwrap(),
                map_truth(&scene, &eye, 512).unwrap(),
            )
        })
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(3));
}

/// Claim: an eye image or a hierarchy of another mesh is an error naming what does not fit, and so
/// is a visible zero-area triangle (it has no normal to offset the shadow ray along).
#[test]
fn inputs_that_do_not_belong_together_are_errors() {
    let scene = oblique_scene();
    let bvh = scene_bvh(&scene).unwrap();
    let mut eye = eye_image(&scene.mesh, &[DVec3::new(3.0, 0.0, 3.0)]);
    let count = scene.mesh.triangle_count();

    eye.triangle[0] = 99;
    assert_eq!(
        exact_truth(&scene, &eye, &bvh),
        Err(AnalysisError::TriangleOutOfRange {
            pixel: 0,
            triangle: 99,
            triangles: count
        })
    );
    eye.triangle[0] = NO_TRIANGLE;
    eye.normal.push(DVec3::Y);
    assert!(matches!(
        map_truth(&scene, &eye, 64),
        Err(AnalysisError::EyeImageSize { .. })
    ));
    eye.normal.pop();
    let other = Bvh::new(&[DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]]).unwrap();
    assert_eq!(
        exact_truth(&scene, &eye, &other),
        Err(AnalysisError::BvhMismatch {
            bvh: 1,
            mesh: count
        })
    );

    // A visible zero-area triangle.
    let flat = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let degenerate = crate::support::scene(overview(), vec![sun(DVec3::Y)], &[flat]);
    let mut eye = eye_image(&scene.mesh, &[DVec3::new(3.0, 0.0, 3.0)]);
    eye.triangle[0] = 0;
    assert!(matches!(
        exact_truth(&degenerate, &eye, &scene_bvh(&degenerate).unwrap()),
        Err(AnalysisError::ShadowRay {
            light: 0,
            pixel: 0,
            ..
        })
    ));
}
