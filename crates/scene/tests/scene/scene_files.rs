//! Scene files that load: the documented defaults, the camera and lights as written, the transform
//! order on known points, copies, groups, OBJ paths relative to the file, and shadow settings.

use std::f64::consts::PI;

use glam::DVec3;
use shadowlab_scene::{Scene, SceneLight, ShadowSettings, load_scene, parse_scene, procedural};

use crate::support::{ObjDir, assert_close};

/// Loads `text` as `scene.toml` in a temporary directory that also holds `files`.
fn load_with(text: &str, files: &[(&str, &str)]) -> Scene {
    let dir = ObjDir::new();
    for (name, contents) in files {
        dir.write(name, contents);
    }
    let path = dir.write("scene.toml", text);
    load_scene(&path).unwrap_or_else(|error| panic!("{error}"))
}

fn load(text: &str) -> Scene {
    load_with(text, &[])
}

/// Asserts that two vectors agree to `relative` of the larger length.
fn assert_vec_close(actual: DVec3, expected: DVec3, relative: f64, what: &str) {
    let error = (actual - expected).length();
    assert!(
        error <= relative * expected.length().max(actual.length()),
        "{what}: {actual} differs from {expected} by {error}"
    );
}

/// A box of size 2 × 4 × 6 about the origin: the bounds' centre is 0 and R = √56 / 2.
const BOX: &str = "[[mesh]]\nshape = \"box\"\nsize = [2, 4, 6]\n";

#[test]
fn a_minimal_file_gets_the_documented_defaults() {
    let scene = load(BOX);
    assert_eq!(scene.name, "scene", "the file's stem");
    assert_eq!(scene.mesh.group_names(), ["box"]);
    assert_eq!(scene.mesh.triangle_count(), 12);
    assert_eq!(scene.bounds().max, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(scene.shadow, ShadowSettings::default());

    let camera = &scene.camera;
    assert_eq!((camera.width, camera.height), (1024, 768));
    assert_close(camera.projection.fov_y(), PI / 3.0, 1e-15, "fov");
    assert_close(camera.projection.aspect(), 4.0 / 3.0, 1e-15, "aspect");
    // The bounding sphere (radius R) just fits the 60° vertical field (the narrower one at 4:3):
    // the eye is at distance R / sin 30° = 2R from the centre, along (0, 1, 2)/√5.
    let radius = 56_f64.sqrt() / 2.0;
    let from = DVec3::new(0.0, 1.0, 2.0) / 5_f64.sqrt();
    assert_vec_close(camera.pose.eye(), 2.0 * radius * from, 1e-15, "eye");
    assert_vec_close(camera.pose.forward(), -from, 1e-15, "looks at the centre");
    assert!(camera.pose.up().y > 0.0 && camera.pose.up().dot(from).abs() < 1e-15);
    // Corner depths along the view direction are 2R ± max |corner·from| = 2R ± (2 + 2·3)/√5.
    let reach = 8.0 / 5_f64.sqrt();
    assert_close(
        camera.projection.far(),
        1.01 * (2.0 * radius + reach),
        1e-14,
        "far",
    );
    assert_close(
        camera.projection.near(),
        0.99 * (2.0 * radius - reach),
        1e-14,
        "near",
    );

    // The default sun travels along (−1, −2, −1).
    assert_eq!(scene.lights.len(), 1);
    let SceneLight::Directional { to_light } = scene.lights[0] else {
        panic!("the default light is directional: {:?}", scene.lights[0]);
    };
    assert_vec_close(
        to_light,
        DVec3::new(1.0, 2.0, 1.0) / 6_f64.sqrt(),
        1e-15,
        "sun",
    );
    assert_eq!(scene.lights[0].light().to_light(), Some(to_light));
}

#[test]
fn a_light_without_fields_is_the_default_sun() {
    let defaulted = load(BOX);
    let explicit = load(&format!(
        "{BOX}[[light]]\n[[light]]\nkind = \"directional\"\ndirection = [-1, -2, -1]\n"
    ));
    assert_eq!(explicit.lights, vec![defaulted.lights[0].clone(); 2]);
}

#[test]
fn the_light_direction_is_the_direction_light_travels() {
    let scene = load(&format!(
        "{BOX}[[light]]\ndirection = [0, -5, 0]\n[[light]]\ndirection = [3, 0, -4]\n"
    ));
    let to_light: Vec<DVec3> = scene
        .lights
        .iter()
        .map(|light| light.light().to_light().expect("directional"))
        .collect();
    assert_eq!(to_light, [DVec3::Y, DVec3::new(-0.6, 0.0, 0.8)]);
}

#[test]
fn the_camera_as_written() {
    let scene = load(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ntarget = [0, 0, -5]\nup = [1, 1, 0]\n\
         fov = 90\nnear = 0.5\nfar = 50\nimage = [640, 480]\n"
    ));
    let camera = &scene.camera;
    assert_eq!(camera.pose.eye(), DVec3::new(0.0, 0.0, 10.0));
    assert_eq!(camera.pose.forward(), DVec3::NEG_Z);
    assert_vec_close(
        camera.pose.up(),
        DVec3::new(1.0, 1.0, 0.0) / 2_f64.sqrt(),
        1e-15,
        "up",
    );
    assert_close(camera.projection.fov_y(), PI / 2.0, 1e-15, "fov");
    assert_eq!(
        (camera.projection.near(), camera.projection.far()),
        (0.5, 50.0)
    );
    assert_eq!((camera.width, camera.height), (640, 480));
    assert_eq!(camera.projection.aspect(), 4.0 / 3.0);
    // `direction` instead of `target`; integers are numbers.
    let scene = load(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, -2]\n"
    ));
    assert_eq!(scene.camera.pose.forward(), DVec3::NEG_Z);
}

#[test]
fn default_depth_ranges_enclose_the_scene() {
    // A camera at z = 10 looking down −z at a box reaching z = ±3: depths 7 to 13.
    let outside = load(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, -1]\n"
    ));
    assert_close(outside.camera.projection.far(), 1.01 * 13.0, 1e-15, "far");
    assert_close(outside.camera.projection.near(), 0.99 * 7.0, 1e-15, "near");
    // Inside the box, the nearest corner is behind the eye: near = far / 1000.
    let inside = load(&format!(
        "{BOX}[camera]\nposition = [0, 0, 0]\ndirection = [0, 0, -1]\n"
    ));
    assert_close(inside.camera.projection.far(), 1.01 * 3.0, 1e-15, "far");
    assert_close(
        inside.camera.projection.near(),
        1.01 * 3.0 / 1000.0,
        1e-15,
        "near",
    );
    // A given far nearer than the scene: the derived near falls back to far / 1000.
    let short = load(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, -1]\nfar = 5\n"
    ));
    assert_eq!(short.camera.projection.far(), 5.0);
    assert_eq!(short.camera.projection.near(), 5.0 / 1000.0);
    // A given near keeps the derived far.
    let near = load(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, -1]\nnear = 2\n"
    ));
    assert_eq!(near.camera.projection.near(), 2.0);
    assert_close(near.camera.projection.far(), 1.01 * 13.0, 1e-15, "far");
}

#[test]
fn a_spot_light_with_defaults() {
    let scene = load(&format!("{BOX}[[light]]\nkind = \"spot\"\n"));
    let SceneLight::Spot { pose, cone } = &scene.lights[0] else {
        panic!("a spot light: {:?}", scene.lights[0]);
    };
    // Where the default sun is, at R / sin 30° = 2R from the centre, shining at the centre.
    let radius = 56_f64.sqrt() / 2.0;
    let toward = DVec3::new(1.0, 2.0, 1.0) / 6_f64.sqrt();
    assert_vec_close(pose.eye(), 2.0 * radius * toward, 1e-15, "position");
    assert_vec_close(pose.forward(), -toward, 1e-15, "direction");
    // It travels mostly along −y, so its up vector is −z orthogonalised.
    assert!(pose.up().z < 0.0 && pose.up().dot(pose.forward()).abs() < 1e-15);
    assert_close(cone.fov_y(), PI / 3.0, 1e-15, "cone");
    assert_eq!(cone.aspect(), 1.0);
    // Depths: 2R ± max |corner·toward| = 2R ± (1 + 4 + 3)/√6.
    let reach = 8.0 / 6_f64.sqrt();
    assert_close(cone.far(), 1.01 * (2.0 * radius + reach), 1e-14, "far");
    assert_close(cone.near(), 0.99 * (2.0 * radius - reach), 1e-14, "near");
    // hull's light: a spot at that position whose frustum holds the whole box.
    let light = scene.lights[0].light();
    assert_eq!(light.position(), Some(pose.eye()));
    let frustum = light.frustum().expect("a spot light has a frustum");
    for corner in frustum.corners() {
        assert!(corner.is_finite());
    }
    for &p in scene.mesh.positions() {
        assert!(frustum.contains(p, 1e-12), "{p} outside the spot's frustum");
    }
}

#[test]
fn a_spot_light_as_written() {
    let scene = load(&format!(
        "{BOX}[[light]]\nkind = \"spot\"\nposition = [10, 0, 0]\ndirection = [-1, 0, 0]\n\
         up = [0, 0, 1]\ncone = 40\nnear = 3\nfar = 30\n"
    ));
    let SceneLight::Spot { pose, cone } = &scene.lights[0] else {
        panic!("a spot light");
    };
    assert_eq!(pose.eye(), DVec3::new(10.0, 0.0, 0.0));
    assert_eq!(pose.forward(), DVec3::NEG_X);
    assert_eq!(pose.up(), DVec3::Z);
    assert_close(cone.fov_y(), 40_f64.to_radians(), 1e-15, "cone");
    assert_eq!((cone.near(), cone.far()), (3.0, 30.0));
    // A spot travelling mostly sideways gets +y as its up vector.
    let sideways = load(&format!(
        "{BOX}[[light]]\nkind = \"spot\"\nposition = [10, 1, 0]\ntarget = [0, 0, 0]\n"
    ));
    let SceneLight::Spot { pose, .. } = &sideways.lights[0] else {
        panic!("a spot light");
    };
    assert!(pose.up().y > 0.99);
}

#[test]
fn a_point_light_as_written_with_and_without_range() {
    let scene = load(&format!(
        "{BOX}[[light]]\nkind = \"point\"\nposition = [0.5, 2.5, -1]\nrange = 7.25\n\
         [[light]]\nkind = \"point\"\nposition = [-3, 1e3, 0]\n"
    ));
    assert_eq!(
        scene.lights,
        [
            SceneLight::Point {
                position: DVec3::new(0.5, 2.5, -1.0),
                range: Some(7.25),
            },
            SceneLight::Point {
                position: DVec3::new(-3.0, 1000.0, 0.0),
                range: None,
            },
        ]
    );
    // hull's light: a point light there, with no direction and no frustum (it lights all space).
    let light = scene.lights[0].light();
    assert_eq!(light.position(), Some(DVec3::new(0.5, 2.5, -1.0)));
    assert_eq!(light.to_light(), None);
    assert!(light.frustum().is_none());
    // Next to other kinds, in file order.
    let mixed = load(&format!(
        "{BOX}[[light]]\nkind = \"spot\"\n[[light]]\nkind = \"point\"\nposition = [0, 9, 0]\n\
         [[light]]\n"
    ));
    assert!(matches!(
        mixed.lights[..],
        [
            SceneLight::Spot { .. },
            SceneLight::Point { range: None, .. },
            SceneLight::Directional { .. }
        ]
    ));
}

/// One triangle with a corner at (1, 2, 3) and one at the origin.
const TRIANGLE_OBJ: &str = "v 1 2 3\nv 0 0 0\nv 1 0 0\nf 1 2 3\n";

/// The positions of an OBJ entry with the given transform fields.
fn transformed(fields: &str) -> Vec<DVec3> {
    let scene = load_with(
        &format!("[[mesh]]\nobj = \"tri.obj\"\n{fields}"),
        &[("tri.obj", TRIANGLE_OBJ)],
    );
    scene.mesh.positions().to_vec()
}

#[test]
fn rotations_follow_the_right_hand_rule_about_world_axes() {
    let p = |fields: &str| transformed(fields)[0];
    assert_eq!(p(""), DVec3::new(1.0, 2.0, 3.0));
    // About x: y turns toward z. About y: z toward x. About z: x toward y. Exact at 90°.
    assert_eq!(p("rotate = [90, 0, 0]"), DVec3::new(1.0, -3.0, 2.0));
    assert_eq!(p("rotate = [0, 90, 0]"), DVec3::new(3.0, 2.0, -1.0));
    assert_eq!(p("rotate = [0, 0, 90]"), DVec3::new(-2.0, 1.0, 3.0));
    assert_eq!(p("rotate = [0, 0, -270]"), DVec3::new(-2.0, 1.0, 3.0));
    assert_eq!(p("rotate = [180, 0, 0]"), DVec3::new(1.0, -2.0, -3.0));
    assert_eq!(p("rotate = [0, 720, 0]"), DVec3::new(1.0, 2.0, 3.0));
    // Other angles: about z by 30°, (1, 2) turns to (cos 30° − 2 sin 30°, sin 30° + 2 cos 30°).
    let (sin, cos) = 30_f64.to_radians().sin_cos();
    assert_vec_close(
        p("rotate = [0, 0, 30]"),
        DVec3::new(cos - 2.0 * sin, sin + 2.0 * cos, 3.0),
        1e-15,
        "30° about z",
    );
}

#[test]
fn scale_then_rotate_x_y_z_then_translate_then_step() {
    // (1, 2, 3) scaled to (2, 6, 12); about x by 90° → (2, −12, 6); about y → (6, −12, −2);
    // about z → (12, 6, −2); translated → (22, 26, 28).
    let positions = transformed(
        "scale = [2, 3, 4]\nrotate = [90, 90, 90]\ntranslate = [10, 20, 30]\n\
         copies = 3\nstep = [0, 0, -5]\n",
    );
    assert_eq!(positions.len(), 9, "three copies of three vertices");
    for (k, copy) in [0.0, 1.0, 2.0].into_iter().zip(positions.chunks(3)) {
        let step = DVec3::new(0.0, 0.0, -5.0) * k;
        assert_eq!(
            copy[..2],
            [
                DVec3::new(22.0, 26.0, 28.0) + step,
                DVec3::new(10.0, 20.0, 30.0) + step
            ]
        );
    }
    // A uniform scale, as an integer.
    assert_eq!(transformed("scale = 2")[0], DVec3::new(2.0, 4.0, 6.0));
}

#[test]
fn a_mirroring_scale_keeps_closed_shapes_outward() {
    let scene = load("[[mesh]]\nshape = \"box\"\nscale = [-1, 2, 3]\n");
    assert!(scene.mesh.signed_volume() > 0.0);
    assert_close(scene.mesh.signed_volume(), 6.0, 1e-15, "volume");
}

#[test]
fn each_entry_is_one_named_group() {
    let scene = load_with(
        "[[mesh]]\nshape = \"chessboard\"\nframe_width = 0.1\n\
         [[mesh]]\nobj = \"tri.obj\"\n\
         [[mesh]]\nshape = \"lattice\"\nname = \"scaffold\"\ncopies = 2\nstep = [5, 0, 0]\n",
        &[("tri.obj", TRIANGLE_OBJ)],
    );
    assert_eq!(
        scene.mesh.group_names(),
        ["chessboard", "tri", "scaffold"],
        "defaults: the shape, the OBJ file's stem; or the entry's name"
    );
    let board = procedural::chess_board(0.125, 0.1)
        .unwrap()
        .triangle_count();
    let lattice = procedural::bar_lattice([4; 3], 0.25, 0.025)
        .unwrap()
        .triangle_count();
    let mut expected = vec![0; board];
    expected.push(1);
    expected.resize(board + 1 + 2 * lattice, 2);
    assert_eq!(scene.mesh.groups(), expected);
}

#[test]
fn obj_paths_are_relative_to_the_scene_file() {
    let dir = ObjDir::new();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    dir.write("sub/tri.obj", TRIANGLE_OBJ);
    let path = dir.write("sub/scene.toml", "[[mesh]]\nobj = \"tri.obj\"\n");
    let scene = load_scene(&path).unwrap();
    assert_eq!(scene.mesh.positions()[0], DVec3::new(1.0, 2.0, 3.0));
    // parse_scene reads the same text the same way, resolving against the given path.
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(parse_scene(&text, &path).unwrap(), scene);
}

#[test]
fn procedural_shapes_take_their_parameters_and_defaults() {
    let scene = load(
        "[[mesh]]\nshape = \"plane\"\n\
         [[mesh]]\nshape = \"plane\"\nsize = [4, 2]\nsegments = 3\n\
         [[mesh]]\nshape = \"sphere\"\n\
         [[mesh]]\nshape = \"sphere\"\nradius = 2\nsegments = 5\nrings = 3\n\
         [[mesh]]\nshape = \"cylinder\"\n\
         [[mesh]]\nshape = \"cylinder\"\nradius = 2\nheight = 3\nsegments = 7\n\
         [[mesh]]\nshape = \"box\"\n\
         [[mesh]]\nshape = \"lattice\"\ncells = [1, 0, 2]\nspacing = 2\nthickness = 0.5\n\
         [[mesh]]\nshape = \"chessboard\"\nsquare_size = 2\n",
    );
    let expected = [
        procedural::plane(1.0, 1.0, 1),
        procedural::plane(4.0, 2.0, 3),
        procedural::sphere(0.5, 32, 16),
        procedural::sphere(2.0, 5, 3),
        procedural::cylinder(0.5, 1.0, 32),
        procedural::cylinder(2.0, 3.0, 7),
        procedural::cuboid(DVec3::ONE),
        procedural::bar_lattice([1, 0, 2], 2.0, 0.5),
        procedural::chess_board(2.0, 0.0),
    ]
    .map(Result::unwrap);
    let mut offset = 0;
    for (group, mesh) in expected.iter().enumerate() {
        for t in 0..mesh.triangle_count() {
            assert_eq!(
                scene.mesh.triangle_positions(offset + t),
                mesh.triangle_positions(t),
                "entry {group}, triangle {t}"
            );
            assert_eq!(scene.mesh.groups()[offset + t] as usize, group);
        }
        offset += mesh.triangle_count();
    }
    assert_eq!(offset, scene.mesh.triangle_count());
}

#[test]
fn name_and_shadow_settings_are_passed_on() {
    let scene = load(&format!(
        "name = \"mine\"\n{BOX}[shadow]\ntechnique = \"lispsm\"\nparameter = \"n_opt\"\n\
         resolution = 2048\npartitions = 4\nsplit_scheme = \"practical\"\nbias = \"slope\"\n\
         filter = \"pcf\"\nlambda = 0.25\nn = 3\nfocus = \"view\"\n\
         optimal_readback = \"35x35\"\noptimal_initial = 512\noptimal_iterations = 2\n\
         optimal_border = 0.1\n"
    ));
    assert_eq!(scene.name, "mine");
    assert_eq!(
        scene.shadow,
        ShadowSettings {
            technique: Some("lispsm".into()),
            parameter: Some("n_opt".into()),
            lambda: Some(0.25),
            n: Some(3.0),
            focus: Some("view".into()),
            resolution: Some(2048),
            partitions: Some(4),
            split_scheme: Some("practical".into()),
            bias: Some("slope".into()),
            filter: Some("pcf".into()),
            optimal_readback: Some("35x35".into()),
            optimal_initial: Some(512),
            optimal_iterations: Some(2),
            optimal_border: Some(0.1),
        }
    );
    let not_finite = parse_scene(
        &format!("{BOX}[shadow]\nlambda = nan\n"),
        std::path::Path::new("nan.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        not_finite.contains("nan.toml") && not_finite.contains("shadow.lambda"),
        "{not_finite}"
    );
    let partial = load(&format!("{BOX}[shadow]\nsplits = 3\n"));
    assert_eq!(
        partial.shadow,
        ShadowSettings {
            partitions: Some(3),
            ..ShadowSettings::default()
        }
    );
}

#[test]
fn the_view_projection_matrix_maps_the_target_to_the_centre() {
    let scene = load(&format!(
        "{BOX}[camera]\nposition = [3, 4, 10]\ntarget = [0, 1, 0]\nnear = 1\nfar = 20\n"
    ));
    let m = scene
        .camera
        .view_projection(shadowlab_hull::NdcDepth::NegativeOneToOne);
    let clip = m * DVec3::new(0.0, 1.0, 0.0).extend(1.0);
    let ndc = clip.truncate() / clip.w;
    assert!(ndc.x.abs() < 1e-15 && ndc.y.abs() < 1e-15, "{ndc}");
    assert!(ndc.z > -1.0 && ndc.z < 1.0);
}
