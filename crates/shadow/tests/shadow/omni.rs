//! Point lights: the cube map's faces tile the light's directions and hold every visible point they
//! serve, each face's near plane is the nearest geometry it sees, and techniques that cannot serve a
//! point light say so.

use glam::DVec3;
use shadowlab_hull::{ConvexPolyhedron, Tolerances};
use shadowlab_raster::NO_TRIANGLE;
use shadowlab_scene::{Scene, SceneLight, builtin_scene};
use shadowlab_shadow::paraboloid::ParaboloidMap;
use shadowlab_shadow::{
    Bias, FrameOptions, Lookup, PlanOptions, Region, Selection, ShadowError, ShadowMapping,
    Technique, plan_light, render_frame, scene_eye, served,
};

/// `name`, small, lit by one point light at `position`.
fn point_lit(name: &str, position: DVec3, range: Option<f64>) -> Scene {
    let mut scene = builtin_scene(name).unwrap();
    (scene.camera.width, scene.camera.height) = (96, 72);
    scene.lights = vec![SceneLight::Point { position, range }];
    scene
}

/// The chess board under a point light above it, and the outdoor scene with a point light among
/// its objects (inside the scene box, so that B holds the light and every face has a part).
fn scenes() -> Vec<Scene> {
    let chess = builtin_scene("chess-spot").unwrap();
    let SceneLight::Spot { pose, .. } = &chess.lights[0] else {
        panic!("chess-spot has a spot light")
    };
    let outdoor = builtin_scene("outdoor").unwrap();
    let centre = outdoor.bounds();
    let inside = (centre.min + centre.max) * 0.5 + DVec3::new(0.3, 0.0, 0.2);
    vec![
        point_lit("chess-spot", pose.eye(), None),
        point_lit("outdoor", inside, None),
    ]
}

fn options(technique: Technique) -> FrameOptions {
    FrameOptions {
        plan: PlanOptions::new(technique),
        resolution: 256,
        format: shadowlab_raster::DepthFormat::F32,
        lookup: Lookup::new(Bias::DEFAULT, shadowlab_shadow::Filter::Nearest),
        snap_texels: 0,
    }
}

/// Claim: every visible point is served by the cube face whose axis is its direction's major
/// axis (by the hemisphere on its side, for the dual paraboloid), and lies inside that face's map
/// (window x, y in [0, 1] — within the disk for a paraboloid — depth in [0, 1]).
#[test]
fn omnidirectional_faces_serve_every_visible_point_inside_their_maps() {
    for (scene, technique) in scenes()
        .into_iter()
        .flat_map(|s| [(s.clone(), Technique::Cube), (s, Technique::DualParaboloid)])
    {
        let frame = render_frame(&scene, &options(technique)).unwrap();
        let light = &frame.lights[0];
        let SceneLight::Point { position, .. } = scene.lights[0] else {
            unreachable!()
        };
        let eye = scene_eye(&scene);
        let mut seen = 0;
        for (pixel, &triangle) in frame.eye.triangle.iter().enumerate() {
            if triangle == NO_TRIANGLE {
                continue;
            }
            let world = frame.eye.position[pixel];
            let s = served(&light.maps, |(p, _)| p, &Selection::DEFAULT, &eye, world).unwrap();
            let (partition, map) = &light.maps[s.index];
            let Some(Region::LightFace(face)) = &partition.face else {
                panic!("a cube face serves {world}")
            };
            let d = world - position;
            let major = if technique == Technique::Cube {
                d.abs().max_element()
            } else {
                0.0
            };
            assert!(
                face.axis.dot(d) >= major * (1.0 - 1e-12),
                "{}: {world} served by {} ({d})",
                scene.name,
                face.name
            );
            let w = map.setup.mapping.window(world).unwrap();
            let slack = 1e-9;
            let disk = (w.truncate() * 2.0 - glam::DVec2::ONE).length();
            assert!(
                technique == Technique::Cube || disk <= 1.0 + slack,
                "{}: {world} off the disk ({disk})",
                scene.name
            );
            assert!(
                (-slack..=1.0 + slack).contains(&w.x)
                    && (-slack..=1.0 + slack).contains(&w.y)
                    && (-slack..=1.0 + slack).contains(&w.z),
                "{}: {world} at {w} in face {}",
                scene.name,
                face.name
            );
            seen += 1;
        }
        assert!(seen > 1000, "{}", scene.name);
    }
}

/// Claim: each face's near plane lies at or before every mesh vertex inside its part of B, so no
/// occluder there is clipped, and is chosen from the scene: further than the floor kept for
/// geometry touching the light.
#[test]
fn cube_near_planes_are_the_nearest_geometry_each_face_sees() {
    for scene in scenes() {
        let partitions = plan_light(
            &scene,
            &scene.lights[0],
            &PlanOptions::new(Technique::Cube),
            None,
            256,
            None,
        )
        .unwrap();
        assert!(!partitions.is_empty(), "{}", scene.name);
        for partition in &partitions {
            let Some(Region::LightFace(face)) = &partition.face else {
                panic!("cube partitions are light faces")
            };
            let part =
                ConvexPolyhedron::from_points(&partition.setup.focus_body, &Tolerances::DEFAULT)
                    .unwrap();
            let depth = |p: DVec3| face.axis.dot(p - face.light);
            let ShadowMapping::Projective(mapping) = &partition.setup.mapping else {
                panic!("a cube face is projective")
            };
            // GL's projection: m22 = −(f + n)/(f − n), m32 = −2fn/(f − n) ⇒ n = m32/(m22 − 1),
            // f = m32/(m22 + 1).
            let (a, b) = (mapping.projection().z_axis.z, mapping.projection().w_axis.z);
            let (near, far) = (b / (a - 1.0), b / (a + 1.0));
            assert!(
                near > far * shadowlab_shadow::MIN_NEAR_FRACTION * 1.5,
                "{}",
                scene.name
            );
            let tolerance = 1e-9 * far;
            let inside: Vec<f64> = scene
                .mesh
                .positions()
                .iter()
                .filter(|p| part.contains(**p, tolerance))
                .map(|p| depth(*p))
                .collect();
            for d in &inside {
                assert!(
                    *d >= near - tolerance,
                    "{}: a vertex of face {}'s part of B at depth {d} lies before its near plane {near}",
                    scene.name,
                    face.name
                );
            }
        }
    }
}

/// Claim: the techniques that need a light direction refuse a point light, naming the technique,
/// the light's kind and the techniques that serve it; the omnidirectional maps refuse a directional
/// light.
#[test]
fn techniques_that_cannot_serve_a_light_say_so() {
    let scene = &scenes()[0];
    for technique in [
        "uniform",
        "lispsm",
        "logarithmic",
        "optimal",
        "sdsm",
        "bevy",
    ] {
        let technique = Technique::parse_spec(technique).unwrap();
        let error = plan_light(
            scene,
            &scene.lights[0],
            &PlanOptions::new(technique),
            None,
            256,
            None,
        )
        .unwrap_err();
        assert_eq!(
            error,
            ShadowError::UnservedLight {
                technique: technique.key(),
                light: "point",
                serving: Technique::POINT_LIGHT_TECHNIQUES,
            }
        );
        assert!(error.to_string().contains("cube, dual-paraboloid, psm"));
    }
    let outdoor = builtin_scene("outdoor").unwrap();
    for technique in [Technique::Cube, Technique::DualParaboloid] {
        let error = plan_light(
            &outdoor,
            &outdoor.lights[0],
            &PlanOptions::new(technique),
            None,
            256,
            None,
        )
        .unwrap_err();
        assert!(
            matches!(
                error,
                ShadowError::UnservedLight {
                    light: "directional",
                    ..
                }
            ),
            "{error}"
        );
    }
}

/// Claim: the paraboloid's texel ray runs from the near to the far distance along the direction
/// the forward map sends back to the texel, and its closed-form derivative matches central
/// differences.
#[test]
fn the_paraboloid_inverts_and_differentiates_exactly() {
    let light = DVec3::new(0.5, 2.0, -1.0);
    for axis in [DVec3::Y, DVec3::NEG_Y, DVec3::new(0.6, 0.0, 0.8), DVec3::X] {
        let map = ParaboloidMap::new(light, axis, 0.25, 9.0);
        for (x, y) in [
            (0.0, 0.0),
            (0.3, -0.2),
            (-0.7, 0.7),
            (0.999, 0.0),
            (0.1, 0.6),
        ] {
            let (from, to) = map.texel_ray(x, y).unwrap();
            assert!(((from - light).length() - 0.25).abs() < 1e-12);
            assert!(((to - light).length() - 9.0).abs() < 1e-12);
            for (point, depth) in [(from, -1.0), (to, 1.0), ((from + to) * 0.5, 0.0)] {
                let ndc = map.ndc(point).unwrap();
                assert!(
                    (ndc.x - x).abs() < 1e-12 && (ndc.y - y).abs() < 1e-12,
                    "{ndc}"
                );
                let expected = if depth == 0.0 {
                    2.0 * ((point - light).length() - 0.25) / 8.75 - 1.0
                } else {
                    depth
                };
                assert!((ndc.z - expected).abs() < 1e-12, "{ndc} {expected}");
            }
            let point = (from + to) * 0.5;
            for direction in [DVec3::X, DVec3::Y, DVec3::new(0.3, -0.4, 0.5)] {
                let h = 1e-5;
                let at = |t: f64| map.ndc(point + direction * t).unwrap().truncate();
                let numeric = (at(h) - at(-h)) / (2.0 * h);
                let exact = map.ndc_derivative(point, direction).unwrap();
                assert!(
                    (numeric - exact).length() < 1e-7 * (1.0 + exact.length()),
                    "{numeric} {exact}"
                );
            }
        }
        assert!(map.texel_ray(0.8, 0.8).is_none(), "outside the disk");
        assert!(map.ndc(light - axis).is_none(), "the opposite pole");
    }
}

/// Claim: PSM serves a point light as one map in the camera's post-perspective space (§4): an
/// ordinary point light in front of the viewer, and the *inverted* one behind it (the plane
/// through the eye perpendicular to the view separates them), each holding every visible point
/// in its window.
#[test]
fn psm_serves_a_point_light_in_front_of_and_behind_the_viewer() {
    let chess = builtin_scene("chess-spot").unwrap();
    let SceneLight::Spot { pose, .. } = &chess.lights[0] else {
        panic!("chess-spot has a spot light")
    };
    let camera = &chess.camera.pose;
    // The spot's own position, and a point light behind the camera, above it.
    let behind = camera.eye() - camera.forward() * 3.0 + DVec3::Y * 4.0;
    for (position, inverted) in [(pose.eye(), false), (behind, true)] {
        let scene = point_lit("chess-spot", position, None);
        let in_front = (position - camera.eye()).dot(camera.forward()) > 0.0;
        assert_eq!(in_front, !inverted, "the configuration");
        let frame = render_frame(&scene, &options(Technique::Psm)).unwrap();
        let (_, map) = &frame.lights[0].maps[0];
        let report = map.setup.psm.unwrap();
        assert_eq!(report.inverted, inverted, "{position}");
        let mut seen = 0;
        for (pixel, &triangle) in frame.eye.triangle.iter().enumerate() {
            if triangle == NO_TRIANGLE {
                continue;
            }
            let w = map.setup.mapping.window(frame.eye.position[pixel]).unwrap();
            let slack = 1e-9;
            assert!(
                w.x > -slack && w.x < 1.0 + slack && w.y > -slack && w.y < 1.0 + slack,
                "{position}: {w}"
            );
            seen += 1;
        }
        assert!(seen > 1000);
    }
}

/// Claim: texel snapping leaves a cube face as it is (its grid is fixed to the light and the
/// world's axes; a shifted face would leave gaps between faces) and a paraboloid hemisphere too.
#[test]
fn snapping_leaves_the_omnidirectional_maps_alone() {
    let scene = &scenes()[1];
    for technique in [Technique::Cube, Technique::DualParaboloid] {
        let partitions = plan_light(
            scene,
            &scene.lights[0],
            &PlanOptions::new(technique),
            None,
            512,
            None,
        )
        .unwrap();
        for partition in &partitions {
            assert_eq!(
                shadowlab_shadow::snap_to_texels(&partition.setup, 512, 1),
                partition.setup
            );
        }
    }
}
