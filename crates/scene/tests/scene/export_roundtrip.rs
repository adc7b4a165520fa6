//! Exported scenes read back: glTF gives the f32 rounding of every position exactly, and from
//! there on the mesh is a fixed point (a re-exported re-import has the same mesh bit for bit);
//! OBJ gives every position bit for bit, with the camera and lights in its header at full
//! precision.

use std::path::Path;

use glam::DVec3;
use shadowlab_scene::{
    BUILTIN_SCENES, ExportError, Scene, SceneLight, builtin_scene, export_glb, export_gltf,
    export_obj, load_gltf_scene, load_obj, parse_scene,
};

use crate::support::ObjDir;

/// `v` rounded to f32 and back, as glTF stores it.
#[expect(
    clippy::cast_possible_truncation,
    reason = "the f32 rounding is what is being modelled"
)]
fn rounded(v: DVec3) -> DVec3 {
    DVec3::from_array(v.to_array().map(|c| f64::from(c as f32)))
}

/// A value rounded to f32 and back.
#[expect(
    clippy::cast_possible_truncation,
    reason = "the f32 rounding is what is being modelled"
)]
fn rounded_scalar(value: f64) -> f64 {
    f64::from(value as f32)
}

/// The scene read back from `bytes` written as `name` in `dir`, without a warning: the camera's
/// `extras` give its image size, so its aspect ratio is the file's.
fn read_back(dir: &ObjDir, name: &str, bytes: &[u8]) -> Scene {
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write the export");
    let loaded = load_gltf_scene(&path, None).expect("the export loads");
    assert_eq!(loaded.warnings, [], "{name}");
    loaded.scene
}

#[test]
fn a_glb_export_reads_back_as_the_f32_rounding_and_is_then_a_fixed_point() {
    let dir = ObjDir::new();
    for name in BUILTIN_SCENES {
        let scene = builtin_scene(name).expect("a built-in scene");
        let glb = export_glb(&scene).expect("exports");
        let once = read_back(&dir, "once.glb", &glb);
        assert_eq!(once.name, scene.name);
        assert_eq!(once.mesh.group_names(), scene.mesh.group_names(), "{name}");
        assert_eq!(once.mesh.groups(), scene.mesh.groups(), "{name}");
        assert_eq!(once.mesh.triangle_count(), scene.mesh.triangle_count());
        for t in 0..scene.mesh.triangle_count() {
            assert_eq!(
                once.mesh.triangle_positions(t),
                scene.mesh.triangle_positions(t).map(rounded),
                "{name}: triangle {t}"
            );
        }
        let (camera, original) = (&once.camera, &scene.camera);
        assert_eq!(camera.pose.eye(), rounded(original.pose.eye()), "{name}");
        assert!((camera.pose.forward() - original.pose.forward()).length() < 1e-6);
        assert!((camera.pose.up() - original.pose.up()).length() < 1e-6);
        assert_eq!(
            (camera.width, camera.height),
            (original.width, original.height),
            "{name}"
        );
        let (projection, source) = (&camera.projection, &original.projection);
        assert_eq!(projection.aspect(), source.aspect(), "{name}");
        assert_eq!(projection.fov_y(), rounded_scalar(source.fov_y()), "{name}");
        assert_eq!(projection.near(), rounded_scalar(source.near()), "{name}");
        assert_eq!(projection.far(), rounded_scalar(source.far()), "{name}");
        assert_eq!(once.lights.len(), scene.lights.len());
        for (light, original) in once.lights.iter().zip(&scene.lights) {
            match (light, original) {
                (
                    SceneLight::Directional { to_light },
                    SceneLight::Directional { to_light: source },
                ) => assert!((*to_light - *source).length() < 1e-6, "{name}"),
                (SceneLight::Spot { pose, cone }, SceneLight::Spot { pose: p, cone: c }) => {
                    assert_eq!(pose.eye(), rounded(p.eye()), "{name}");
                    assert!((pose.forward() - p.forward()).length() < 1e-6, "{name}");
                    assert_eq!(cone.fov_y(), rounded_scalar(c.fov_y()), "{name}");
                    assert_eq!(cone.far(), rounded_scalar(c.far()), "{name}");
                }
                (
                    SceneLight::Point { position, range },
                    SceneLight::Point {
                        position: p,
                        range: r,
                    },
                ) => {
                    assert_eq!(*position, rounded(*p), "{name}");
                    assert_eq!(*range, r.map(rounded_scalar), "{name}");
                }
                other => panic!("{name}: {other:?}"),
            }
        }
        // From the rounded scene on, the geometry is a fixed point: a second round trip gives the
        // same mesh bit for bit (positions, normals, triangles, groups) and the same projections;
        // poses, re-derived from f32 rotations, agree to f32 precision.
        let twice = read_back(&dir, "twice.glb", &export_glb(&once).expect("exports"));
        assert_eq!(twice.mesh, once.mesh, "{name}");
        assert_eq!(twice.camera.projection, once.camera.projection, "{name}");
        assert_eq!(twice.camera.pose.eye(), once.camera.pose.eye(), "{name}");
        assert!((twice.camera.pose.forward() - once.camera.pose.forward()).length() < 1e-7);
        for (light, first) in twice.lights.iter().zip(&once.lights) {
            match (light, first) {
                (SceneLight::Directional { to_light }, SceneLight::Directional { to_light: t }) => {
                    assert!((*to_light - *t).length() < 1e-7, "{name}");
                }
                (SceneLight::Spot { pose, cone }, SceneLight::Spot { pose: p, cone: c }) => {
                    assert_eq!(
                        (pose.eye(), cone.fov_y(), cone.far()),
                        (p.eye(), c.fov_y(), c.far())
                    );
                    assert!((pose.forward() - p.forward()).length() < 1e-7, "{name}");
                }
                (SceneLight::Point { .. }, SceneLight::Point { .. }) => {
                    assert_eq!(light, first, "{name}");
                }
                other => panic!("{name}: {other:?}"),
            }
        }
        // The embedded form holds the same contents: the same scene as the GLB.
        let embedded = export_gltf(&scene).expect("exports");
        assert_eq!(
            read_back(&dir, "once.gltf", embedded.as_bytes()),
            once,
            "{name}"
        );
    }
}

/// The numbers after `key` on the header line starting with `prefix`.
fn header_numbers(text: &str, prefix: &str, key: &str) -> Vec<f64> {
    let line = text
        .lines()
        .find(|line| line.starts_with(prefix))
        .unwrap_or_else(|| panic!("no header line `{prefix}`"));
    let after = line
        .split_once(&format!(" {key} "))
        .unwrap_or_else(|| panic!("no `{key}` in `{line}`"))
        .1;
    after
        .split_whitespace()
        .map_while(|word| word.parse().ok())
        .collect()
}

fn vector(numbers: &[f64]) -> DVec3 {
    DVec3::from_slice(&numbers[..3])
}

#[test]
fn an_obj_export_reads_back_bit_for_bit_with_its_camera_and_lights() {
    let dir = ObjDir::new();
    for name in BUILTIN_SCENES {
        let scene = builtin_scene(name).expect("a built-in scene");
        let text = export_obj(&scene);
        let mesh = load_obj(&dir.write("scene.obj", &text)).expect("the export loads");
        assert_eq!(mesh.triangle_count(), scene.mesh.triangle_count(), "{name}");
        for t in 0..mesh.triangle_count() {
            assert_eq!(
                mesh.triangle_positions(t),
                scene.mesh.triangle_positions(t),
                "{name}: triangle {t}"
            );
        }
        assert_eq!(mesh.group_names(), scene.mesh.group_names(), "{name}");
        crate::support::assert_unit_normals(&mesh);
        let camera = &scene.camera;
        assert_eq!(
            vector(&header_numbers(&text, "# camera eye", "eye")),
            camera.pose.eye()
        );
        assert_eq!(
            vector(&header_numbers(&text, "# camera forward", "forward")),
            camera.pose.forward()
        );
        assert_eq!(
            vector(&header_numbers(&text, "# camera up", "up")),
            camera.pose.up()
        );
        let projection = &camera.projection;
        for (key, value) in [
            ("fov_y", projection.fov_y()),
            ("aspect", projection.aspect()),
            ("near", projection.near()),
            ("far", projection.far()),
        ] {
            assert_eq!(
                header_numbers(&text, "# camera fov_y", key),
                [value],
                "{name}: {key}"
            );
        }
        for (index, light) in scene.lights.iter().enumerate() {
            let prefix = format!("# light {index} ");
            match light {
                SceneLight::Directional { to_light } => {
                    assert_eq!(
                        vector(&header_numbers(&text, &prefix, "to_light")),
                        *to_light
                    );
                }
                SceneLight::Spot { pose, cone } => {
                    assert_eq!(vector(&header_numbers(&text, &prefix, "eye")), pose.eye());
                    assert_eq!(
                        vector(&header_numbers(&text, &prefix, "forward")),
                        pose.forward()
                    );
                    assert_eq!(vector(&header_numbers(&text, &prefix, "up")), pose.up());
                    assert_eq!(header_numbers(&text, &prefix, "cone"), [cone.fov_y()]);
                    assert_eq!(header_numbers(&text, &prefix, "near"), [cone.near()]);
                    assert_eq!(header_numbers(&text, &prefix, "far"), [cone.far()]);
                }
                SceneLight::Point { position, range } => {
                    assert_eq!(
                        vector(&header_numbers(&text, &prefix, "position")),
                        *position
                    );
                    if let Some(range) = range {
                        assert_eq!(header_numbers(&text, &prefix, "range"), [*range]);
                    }
                }
            }
        }
    }
}

/// A room-sized box with a sun, a spot and two point lights, one with a range: a position and a
/// range that f32 does not hold exactly, and one that it does.
const LIT_BY_POINTS: &str = "name = \"points\"\n[[mesh]]\nshape = \"box\"\nsize = [8, 3, 10]\n\
    [[light]]\n[[light]]\nkind = \"spot\"\nposition = [0, 2.9, 0]\ndirection = [0, -1, 0]\n\
    [[light]]\nkind = \"point\"\nposition = [0.1, 2.5, -0.3]\nrange = 7.3\n\
    [[light]]\nkind = \"point\"\nposition = [-3.5, 1.25, 4]\n";

#[test]
fn point_lights_read_back_from_glb_and_gltf_as_their_f32_rounding() {
    let dir = ObjDir::new();
    let scene = parse_scene(LIT_BY_POINTS, Path::new("points.toml")).expect("a scene");
    let expected = [
        SceneLight::Point {
            position: rounded(DVec3::new(0.1, 2.5, -0.3)),
            range: Some(rounded_scalar(7.3)),
        },
        SceneLight::Point {
            position: DVec3::new(-3.5, 1.25, 4.0),
            range: None,
        },
    ];
    // The f32 rounding is not the identity here, so the test tells the two apart.
    assert_ne!(
        rounded(DVec3::new(0.1, 2.5, -0.3)),
        DVec3::new(0.1, 2.5, -0.3)
    );
    assert_ne!(rounded_scalar(7.3), 7.3);
    let glb = read_back(&dir, "points.glb", &export_glb(&scene).expect("exports"));
    assert!(matches!(glb.lights[0], SceneLight::Directional { .. }));
    assert!(matches!(glb.lights[1], SceneLight::Spot { .. }));
    assert_eq!(glb.lights[2..], expected);
    let gltf = export_gltf(&scene).expect("exports");
    assert_eq!(read_back(&dir, "points.gltf", gltf.as_bytes()), glb);
    // The point lights' nodes are translations only, and a range is written only where there is one.
    let document: serde_json::Value = serde_json::from_str(&gltf).expect("JSON");
    let lights = &document["extensions"]["KHR_lights_punctual"]["lights"];
    assert_eq!(
        lights[2],
        serde_json::json!({ "type": "point", "range": 7.3_f32 })
    );
    assert_eq!(lights[3], serde_json::json!({ "type": "point" }));
    let node = document["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .find(|node| node["name"] == "light 2")
        .expect("the node of light 2");
    assert_eq!(
        node,
        &serde_json::json!({
            "name": "light 2",
            "translation": [0.1_f32, 2.5_f32, -0.3_f32],
            "extensions": { "KHR_lights_punctual": { "light": 2 } },
        })
    );
    // A fixed point from there on.
    let twice = read_back(&dir, "twice.glb", &export_glb(&glb).expect("exports"));
    assert_eq!(twice.lights[2..], expected);
}

#[test]
fn point_lights_are_in_the_obj_header_at_full_precision() {
    let scene = parse_scene(LIT_BY_POINTS, Path::new("points.toml")).expect("a scene");
    let text = export_obj(&scene);
    assert!(
        text.lines()
            .any(|line| line == "# light 2 point position 0.1 2.5 -0.3 range 7.3"),
        "{text}"
    );
    assert!(
        text.lines()
            .any(|line| line == "# light 3 point position -3.5 1.25 4.0"),
        "{text}"
    );
    assert_eq!(
        vector(&header_numbers(&text, "# light 2 ", "position")),
        DVec3::new(0.1, 2.5, -0.3)
    );
    assert_eq!(header_numbers(&text, "# light 2 ", "range"), [7.3]);
}

#[test]
fn light_values_that_f32_cannot_hold_are_export_errors() {
    for (light, what, value) in [
        ("position = [1e39, 0, 0]", "light 0 position", 1e39),
        (
            "position = [0, 1, 0]\nrange = 1e-50",
            "light 0 range",
            1e-50,
        ),
        ("position = [0, 1, 0]\nrange = 1e39", "light 0 range", 1e39),
    ] {
        let text = format!("[[mesh]]\nshape = \"box\"\n[[light]]\nkind = \"point\"\n{light}\n");
        let scene = parse_scene(&text, Path::new("far.toml")).expect("a scene");
        let expected = ExportError::ValueOutOfF32Range {
            what: what.to_owned(),
            value,
        };
        assert_eq!(export_glb(&scene), Err(expected.clone()), "{light}");
        assert_eq!(export_gltf(&scene), Err(expected.clone()), "{light}");
        assert!(
            expected.to_string().starts_with(&format!(
                "{what} has the value {value:e}, which glTF's f32 cannot hold"
            )),
            "{expected}"
        );
        // OBJ holds every f64.
        assert!(export_obj(&scene).contains("# light 0 point position "));
    }
    // The same for a spot's far distance and a camera's position.
    let spot = parse_scene(
        "[[mesh]]\nshape = \"box\"\n[[light]]\nkind = \"spot\"\nposition = [0, 5, 0]\nfar = 1e39\n",
        Path::new("spot.toml"),
    )
    .expect("a scene");
    assert!(matches!(
        export_glb(&spot),
        Err(ExportError::ValueOutOfF32Range { what, .. }) if what == "light 0 range (its far distance)"
    ));
    let camera = parse_scene(
        "[[mesh]]\nshape = \"box\"\n[camera]\nposition = [0, 0, 1e39]\n",
        Path::new("camera.toml"),
    )
    .expect("a scene");
    assert_eq!(
        export_gltf(&camera),
        Err(ExportError::ValueOutOfF32Range {
            what: "camera position".to_owned(),
            value: 1e39
        })
    );
}
