//! Every class of bad scene file is an error that names the file and the field (or the line and
//! column of a TOML error), never a panic.

use std::path::PathBuf;

use glam::DVec3;
use shadowlab_hull::HullError;
use shadowlab_scene::{
    BuiltinSceneError, MeshError, ObjError, ObjProblem, ReadError, SceneFileError,
    SceneFileProblem, ShapeError, builtin_scene, load_scene, parse_scene,
};

use crate::support::ObjDir;

/// A valid mesh entry, for files whose error is elsewhere.
const BOX: &str = "[[mesh]]\nshape = \"box\"\n";

/// Loads `text` from `bad.toml` (next to `files`) and returns the error, its message, and the
/// path; checks that the message starts with the path.
fn scene_error_with(text: &str, files: &[(&str, &str)]) -> (SceneFileError, String, PathBuf) {
    let dir = ObjDir::new();
    for (name, contents) in files {
        dir.write(name, contents);
    }
    let path = dir.write("bad.toml", text);
    match load_scene(&path) {
        Ok(scene) => panic!("expected an error for {text:?}, got {scene:?}"),
        Err(error) => {
            let message = error.to_string();
            assert!(
                message.starts_with(&path.display().to_string()),
                "{message:?} does not name {}",
                path.display()
            );
            (error, message, path)
        }
    }
}

fn scene_error(text: &str) -> (SceneFileError, String, PathBuf) {
    scene_error_with(text, &[])
}

/// The field and problem of a [`SceneFileError::Field`]; checks that the message is
/// `path: field problem`.
fn field_error(text: &str) -> (String, SceneFileProblem) {
    match scene_error(text) {
        (
            SceneFileError::Field {
                field,
                problem,
                path: named,
            },
            message,
            path,
        ) => {
            assert_eq!(named, path);
            assert_eq!(
                message,
                format!("{}: {field} {problem}", path.display()),
                "the message names the file and the field"
            );
            (field, problem)
        }
        (other, ..) => panic!("expected a field error for {text:?}, got {other:?}"),
    }
}

/// The message of a field error, without the path.
fn field_message(text: &str) -> String {
    let (error, message, path) = scene_error(text);
    assert!(matches!(error, SceneFileError::Field { .. }), "{error:?}");
    message[path.display().to_string().len() + 2..].to_owned()
}

/// The position, field and message of a [`SceneFileError::Toml`].
fn toml_error(text: &str) -> (Option<(usize, usize)>, Option<String>, String) {
    match scene_error(text) {
        (
            SceneFileError::Toml {
                position,
                field,
                message,
                ..
            },
            ..,
        ) => (position, field, message),
        (other, ..) => panic!("expected a TOML error for {text:?}, got {other:?}"),
    }
}

#[test]
fn toml_syntax_errors_have_toml_s_line_and_column() {
    let text = "name = \"x\"\n\n[camera]\nfov = = 60\n";
    let (position, field, message) = toml_error(text);
    // toml's own report of the same text.
    let reported = toml::from_str::<toml::Table>(text).unwrap_err().to_string();
    let (line, column) = position.expect("a syntax error has a position");
    assert!(
        reported.starts_with(&format!(
            "TOML parse error at line {line}, column {column}\n"
        )),
        "{reported}"
    );
    assert_eq!((line, column), (4, 7));
    assert_eq!(field, None);
    assert!(reported.contains(&message));
    let (_, display, path) = scene_error(text);
    assert!(display.starts_with(&format!("{}:4:7: ", path.display())));
    // Repeated tables are TOML errors too, at the position toml reports.
    let text = "[camera]\nfov = 60\n[camera]\nfov = 50\n";
    let (line, column) = toml_error(text).0.expect("a position");
    let reported = toml::from_str::<toml::Table>(text).unwrap_err().to_string();
    assert!(
        reported.starts_with(&format!(
            "TOML parse error at line {line}, column {column}\n"
        )),
        "{reported}"
    );
    assert_eq!(line, 3);
}

#[test]
fn unknown_fields_are_named_by_their_path() {
    let (position, field, message) = toml_error(&format!("{BOX}[camera]\nfovy = 60\n"));
    assert_eq!(position, Some((4, 1)));
    assert_eq!(field.as_deref(), Some("camera.fovy"));
    assert!(message.contains("unknown field `fovy`"), "{message}");
    let (_, display, path) = scene_error(&format!("{BOX}[camera]\nfovy = 60\n"));
    assert!(
        display.starts_with(&format!(
            "{}:4:1: camera.fovy: unknown field",
            path.display()
        )),
        "{display}"
    );
    let (_, field, _) = toml_error(&format!(
        "{BOX}[[mesh]]\nshape = \"box\"\nsise = [1, 1, 1]\n"
    ));
    assert_eq!(field.as_deref(), Some("mesh[1].sise"));
    let (_, field, _) = toml_error(&format!("{BOX}[[light]]\ncolour = [1, 1, 1]\n"));
    assert_eq!(field.as_deref(), Some("light[0].colour"));
    let (_, field, _) = toml_error(&format!("{BOX}[shadow]\nmethod = \"lispsm\"\n"));
    assert_eq!(field.as_deref(), Some("shadow.method"));
    // Keys after a table header belong to that table.
    let (_, field, _) = toml_error(&format!("title = \"x\"\n{BOX}"));
    assert_eq!(field.as_deref(), Some("title"));
    let (_, field, _) = toml_error(&format!("{BOX}title = \"x\"\n"));
    assert_eq!(field.as_deref(), Some("mesh[0].title"));
}

#[test]
fn unknown_shapes_and_light_kinds() {
    let (position, field, message) = toml_error("[[mesh]]\nshape = \"torus\"\n");
    assert_eq!(position, Some((2, 9)));
    assert_eq!(field.as_deref(), Some("mesh[0].shape"));
    assert!(
        message.contains("torus") && message.contains("chessboard"),
        "{message}"
    );
    let (_, field, message) = toml_error(&format!("{BOX}[[light]]\nkind = \"area\"\n"));
    assert_eq!(field.as_deref(), Some("light[0].kind"));
    assert!(
        message.contains("area") && message.contains("spot") && message.contains("point"),
        "{message}"
    );
}

#[test]
fn values_of_the_wrong_type() {
    let cases = [
        ("[camera]\nfov = \"wide\"\n", "camera.fov"),
        ("[camera]\nimage = [1024, -768]\n", "camera.image[1]"),
        ("[camera]\nimage = [1024, 5000000000]\n", "camera.image[1]"),
        ("[camera]\nposition = [1, 2]\n", "camera.position"),
        ("[camera]\nfov = 1e400\n", "camera.fov"),
        ("[[light]]\n[[light]]\ncone = \"wide\"\n", "light[1].cone"),
        (
            "[[light]]\ndirection = [0, \"down\", 0]\n",
            "light[0].direction[1]",
        ),
        ("[shadow]\nresolution = -1\n", "shadow.resolution"),
    ];
    for (text, expected) in cases {
        let (position, field, _) = toml_error(&format!("{BOX}{text}"));
        assert!(position.is_some(), "{text}");
        assert_eq!(field.as_deref(), Some(expected), "{text}");
    }
    for (text, expected) in [("camera = 3\n", "camera"), ("name = 3\n", "name")] {
        let (_, field, _) = toml_error(&format!("{text}{BOX}"));
        assert_eq!(field.as_deref(), Some(expected), "{text}");
    }
    // `scale` is a number or three numbers.
    let (_, field, message) = toml_error("[[mesh]]\nshape = \"box\"\nscale = [1, 2]\n");
    assert_eq!(field.as_deref(), Some("mesh[0].scale"));
    assert!(message.contains("three numbers"), "{message}");
    let (_, field, _) = toml_error("[[mesh]]\nshape = \"box\"\nscale = [1, 2, 3, 4]\n");
    assert_eq!(field.as_deref(), Some("mesh[0].scale"));
    let (_, field, _) = toml_error("[[mesh]]\nshape = \"box\"\nscale = \"big\"\n");
    assert_eq!(field.as_deref(), Some("mesh[0].scale"));
}

#[test]
fn nan_and_infinity_are_named() {
    let cases = [
        ("[camera]\nfov = nan\n", "camera.fov"),
        ("[camera]\nnear = inf\n", "camera.near"),
        ("[camera]\nfar = -inf\n", "camera.far"),
        ("[camera]\nposition = [0, nan, 0]\n", "camera.position[1]"),
        ("[camera]\ntarget = [0, 0, inf]\n", "camera.target[2]"),
        ("[camera]\nup = [nan, 1, 0]\n", "camera.up[0]"),
        (
            "[[light]]\ndirection = [inf, -1, 0]\n",
            "light[0].direction[0]",
        ),
        ("[[light]]\nkind = \"spot\"\ncone = nan\n", "light[0].cone"),
        (
            "[[light]]\nkind = \"point\"\nposition = [0, 0, -inf]\n",
            "light[0].position[2]",
        ),
        (
            "[[light]]\nkind = \"point\"\nposition = [0, 3, 0]\nrange = nan\n",
            "light[0].range",
        ),
        (
            "[[light]]\n[[light]]\nkind = \"point\"\nposition = [0, 3, 0]\nrange = inf\n",
            "light[1].range",
        ),
    ];
    for (text, expected) in cases {
        let (field, problem) = field_error(&format!("{BOX}{text}"));
        assert_eq!(field, expected, "{text}");
        assert!(
            matches!(problem, SceneFileProblem::NotFinite { value } if !value.is_finite()),
            "{text}: {problem:?}"
        );
    }
    let mesh_cases = [
        ("translate = [0, 0, nan]", "mesh[0].translate[2]"),
        ("rotate = [inf, 0, 0]", "mesh[0].rotate[0]"),
        ("scale = nan", "mesh[0].scale"),
        ("scale = [1, 1, -inf]", "mesh[0].scale[2]"),
        ("size = [1, nan, 1]", "mesh[0].size[1]"),
    ];
    for (text, expected) in mesh_cases {
        let (field, problem) = field_error(&format!("[[mesh]]\nshape = \"box\"\n{text}\n"));
        assert_eq!(field, expected, "{text}");
        assert!(
            matches!(problem, SceneFileProblem::NotFinite { .. }),
            "{problem:?}"
        );
    }
    let (field, _) = field_error("[[mesh]]\nshape = \"sphere\"\nradius = nan\n");
    assert_eq!(field, "mesh[0].radius");
    let (field, _) = field_error(&format!(
        "{BOX}[[mesh]]\nshape = \"box\"\ncopies = 2\nstep = [nan, 0, 0]\n"
    ));
    assert_eq!(field, "mesh[1].step[0]");
}

#[test]
fn near_and_far() {
    assert_eq!(
        field_message(&format!("{BOX}[camera]\nnear = 5\nfar = 1\n")),
        "camera.near (5) must be below camera.far (1)"
    );
    assert_eq!(
        field_message(&format!("{BOX}[camera]\nnear = 2\nfar = 2\n")),
        "camera.near (2) must be below camera.far (2)"
    );
    assert_eq!(
        field_message(&format!("{BOX}[camera]\nnear = 0\n")),
        "camera.near (0) must be > 0"
    );
    assert_eq!(
        field_message(&format!("{BOX}[camera]\nfar = -1\n")),
        "camera.far (-1) must be > 0"
    );
    // A given near beyond the default far (the box reaches depth 10.5 from z = 10).
    let (field, problem) = field_error(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, -1]\nnear = 20\n"
    ));
    assert_eq!(field, "camera.near");
    assert_eq!(
        problem,
        SceneFileProblem::NotBelow {
            value: 20.0,
            other: "the default camera.far".into(),
            other_value: 1.01 * 10.5,
        }
    );
    // Looking away from the scene, far has no default.
    let (field, problem) = field_error(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, 1]\n"
    ));
    assert_eq!(field, "camera.far");
    assert!(
        matches!(problem, SceneFileProblem::NoDefault { .. }),
        "{problem:?}"
    );
    // The same rules for spot lights.
    assert_eq!(
        field_message(&format!(
            "{BOX}[[light]]\nkind = \"spot\"\nnear = 3\nfar = 2\n"
        )),
        "light[0].near (3) must be below light[0].far (2)"
    );
}

#[test]
fn fields_of_view_and_cones() {
    for fov in ["0", "180", "200", "-10", "1e-9", "0.000999"] {
        let (field, problem) = field_error(&format!("{BOX}[camera]\nfov = {fov}\n"));
        assert_eq!(field, "camera.fov");
        assert_eq!(
            problem,
            SceneFileProblem::OutOfRange {
                value: fov.parse().unwrap(),
                requirement: "in [0.001, 180) degrees (MIN_ANGLE_DEGREES)".to_owned(),
            }
        );
    }
    assert_eq!(
        field_message(&format!("{BOX}[[light]]\nkind = \"spot\"\ncone = 180\n")),
        "light[0].cone (180) must be in [0.001, 180) degrees (MIN_ANGLE_DEGREES)"
    );
}

#[test]
fn directions_without_direction() {
    let cases = [
        ("[camera]\ndirection = [0, 0, 0]\n", "camera.direction"),
        ("[camera]\nup = [0, -0.0, 0]\n", "camera.up"),
        ("[[light]]\ndirection = [0, 0, 0]\n", "light[0].direction"),
        (
            "[[light]]\nkind = \"spot\"\ndirection = [0, 0, 0]\n",
            "light[0].direction",
        ),
        (
            "[[light]]\nkind = \"spot\"\nup = [0, 0, 0]\n",
            "light[0].up",
        ),
    ];
    for (text, expected) in cases {
        let (field, problem) = field_error(&format!("{BOX}{text}"));
        assert_eq!(field, expected, "{text}");
        assert!(
            matches!(problem, SceneFileProblem::ZeroVector { value } if value == DVec3::ZERO),
            "{problem:?}"
        );
    }
    assert_eq!(
        field_message(&format!("{BOX}[[light]]\ndirection = [0, 0, 0]\n")),
        "light[0].direction [0, 0, 0] has no direction"
    );
}

#[test]
fn up_parallel_to_the_view_direction() {
    // Looking straight down with the default up.
    assert_eq!(
        field_message(&format!(
            "{BOX}[camera]\nposition = [0, 10, 0]\ntarget = [0, 0, 0]\n"
        )),
        "the default camera.up [0, 1, 0] is parallel to the view direction [0, -1, 0]"
    );
    let (field, problem) = field_error(&format!(
        "{BOX}[camera]\ndirection = [1, 0, 0]\nup = [-3, 0, 0]\n"
    ));
    assert_eq!(field, "camera.up");
    assert_eq!(
        problem,
        SceneFileProblem::Parallel {
            value: DVec3::NEG_X,
            other: "the view direction",
            other_value: DVec3::X,
        }
    );
    let (field, _) = field_error(&format!(
        "{BOX}[[light]]\nkind = \"spot\"\ndirection = [0, 0, -1]\nup = [0, 0, 2]\n"
    ));
    assert_eq!(field, "light[0].up");
}

#[test]
fn targets_at_the_position() {
    assert_eq!(
        field_message(&format!(
            "{BOX}[camera]\nposition = [1, 2, 3]\ntarget = [1, 2, 3]\n"
        )),
        "camera.target [1, 2, 3] coincides with camera.position"
    );
    // The default target is the centre of the box.
    assert_eq!(
        field_message(&format!("{BOX}[camera]\nposition = [0, 0, 0]\n")),
        "camera.position [0, 0, 0] coincides with the default camera.target (the scene's centre)"
    );
    let (field, _) = field_error(&format!(
        "{BOX}[[light]]\nkind = \"spot\"\nposition = [0, 0, 0]\n"
    ));
    assert_eq!(field, "light[0].position");
    // A target and a direction exclude each other.
    assert_eq!(
        field_message(&format!(
            "{BOX}[camera]\ntarget = [0, 0, 0]\ndirection = [0, 0, -1]\n"
        )),
        "camera.target and camera.direction exclude each other: give one of them"
    );
}

#[test]
fn sizes_counts_and_scales() {
    let cases = [
        (
            "shape = \"box\"\nsize = [1, 0, 1]",
            "mesh[0].size[1]",
            "> 0",
        ),
        (
            "shape = \"plane\"\nsize = [-2, 1]",
            "mesh[0].size[0]",
            "> 0",
        ),
        ("shape = \"sphere\"\nradius = -1", "mesh[0].radius", "> 0"),
        ("shape = \"cylinder\"\nheight = 0", "mesh[0].height", "> 0"),
        ("shape = \"lattice\"\nspacing = 0", "mesh[0].spacing", "> 0"),
        (
            "shape = \"lattice\"\nthickness = -0.1",
            "mesh[0].thickness",
            "> 0",
        ),
        (
            "shape = \"chessboard\"\nsquare_size = 0",
            "mesh[0].square_size",
            "> 0",
        ),
        (
            "shape = \"chessboard\"\nframe_width = -1",
            "mesh[0].frame_width",
            ">= 0",
        ),
        (
            "shape = \"plane\"\nsegments = 0",
            "mesh[0].segments",
            "at least 1",
        ),
        (
            "shape = \"sphere\"\nsegments = 2",
            "mesh[0].segments",
            "at least 3",
        ),
        (
            "shape = \"sphere\"\nrings = 1",
            "mesh[0].rings",
            "at least 2",
        ),
        (
            "shape = \"cylinder\"\nsegments = 2",
            "mesh[0].segments",
            "at least 3",
        ),
        ("shape = \"box\"\nscale = 0", "mesh[0].scale", "non-zero"),
        (
            "shape = \"box\"\nscale = [1, 0, 1]",
            "mesh[0].scale[1]",
            "non-zero",
        ),
        (
            "shape = \"box\"\ncopies = 0",
            "mesh[0].copies",
            "at least 1",
        ),
        (
            "[camera]\nimage = [0, 768]",
            "camera.image[0]",
            "in 1..=16384 pixels (MAX_IMAGE_SIDE)",
        ),
        (
            "[camera]\nimage = [16385, 768]",
            "camera.image[0]",
            "in 1..=16384 pixels (MAX_IMAGE_SIDE)",
        ),
        (
            "[camera]\nimage = [1024, 0]",
            "camera.image[1]",
            "in 1..=16384 pixels (MAX_IMAGE_SIDE)",
        ),
    ];
    for (text, expected, requirement) in cases {
        let text = if text.starts_with("[camera]") {
            format!("{BOX}{text}\n")
        } else {
            format!("[[mesh]]\n{text}\n")
        };
        let (field, problem) = field_error(&text);
        assert_eq!(field, expected, "{text}");
        assert!(
            matches!(&problem, SceneFileProblem::OutOfRange { requirement: r, .. } if r == requirement),
            "{text}: {problem:?}"
        );
    }
    assert_eq!(
        field_message("[[mesh]]\nshape = \"plane\"\nsize = [1, 2, 3]\n"),
        "mesh[0].size has 3 values; it takes 2"
    );
    let (field, problem) = field_error("[[mesh]]\nshape = \"box\"\nsize = [1, 2]\n");
    assert_eq!(field, "mesh[0].size");
    assert_eq!(
        problem,
        SceneFileProblem::WrongLength {
            found: 2,
            expected: 3
        }
    );
}

#[test]
fn rules_between_shape_parameters_are_procedural_errors_of_the_entry() {
    let (error, message, path) = scene_error(&format!(
        "{BOX}[[mesh]]\nshape = \"lattice\"\nspacing = 1\nthickness = 2\n"
    ));
    let SceneFileError::Shape { field, source, .. } = &error else {
        panic!("{error:?}");
    };
    assert_eq!(field, "mesh[1]");
    assert!(matches!(
        *source,
        ShapeError::InvalidParameter {
            parameter: "thickness",
            ..
        }
    ));
    assert_eq!(
        message,
        format!(
            "{}: mesh[1]: `thickness` must be less than `spacing`, got 2",
            path.display()
        )
    );
    let (error, ..) = scene_error("[[mesh]]\nshape = \"lattice\"\ncells = [0, 0, 0]\n");
    assert!(matches!(error, SceneFileError::Shape { .. }), "{error:?}");
    // Too many triangles: for one shape, and for an entry's copies together.
    let (error, ..) = scene_error("[[mesh]]\nshape = \"sphere\"\nsegments = 4294967295\n");
    assert!(
        matches!(&error, SceneFileError::Shape { field, source, .. }
            if field == "mesh[0]" && matches!(source, ShapeError::TooManyTriangles { .. })),
        "{error:?}"
    );
    let (error, message, _) =
        scene_error("[[mesh]]\nshape = \"box\"\ncopies = 4294967295\nstep = [1, 0, 0]\n");
    assert!(
        matches!(&error, SceneFileError::Shape { field, source, .. }
            if field == "mesh[0].copies" && matches!(source, ShapeError::TooManyTriangles { .. })),
        "{error:?}"
    );
    assert!(message.contains("51539607540 triangles"), "{message}");
    // A transform that overflows.
    let (error, ..) =
        scene_error("[[mesh]]\nshape = \"box\"\nsize = [10, 10, 10]\nscale = 1e308\n");
    assert!(
        matches!(&error, SceneFileError::Mesh { field, source, .. }
            if field == "mesh[0]" && matches!(source, MeshError::InvalidTransform { .. })),
        "{error:?}"
    );
    // A transform that moves positions beyond MAX_COORDINATE, named with the limit.
    let (error, message, _) = scene_error("[[mesh]]\nshape = \"box\"\nscale = 1e60\n");
    assert!(
        matches!(&error, SceneFileError::Mesh { field, source, .. }
            if field == "mesh[0]" && matches!(source, MeshError::PositionOutOfRange { .. })),
        "{error:?}"
    );
    assert!(
        message.contains("beyond ±1e40 (MAX_COORDINATE)"),
        "{message}"
    );
}

#[test]
fn obj_or_shape() {
    assert_eq!(
        field_message("[[mesh]]\nobj = \"a.obj\"\nshape = \"box\"\n"),
        "mesh[0].obj and mesh[0].shape exclude each other: give one of them"
    );
    assert_eq!(
        field_message(&format!("{BOX}[[mesh]]\nname = \"nothing\"\n")),
        "mesh[1] needs one of `obj`, `shape` and `gltf`"
    );
    assert_eq!(
        field_message("name = \"empty\"\n"),
        "mesh needs at least one `[[mesh]]` entry"
    );
    assert_eq!(
        field_message(""),
        "mesh needs at least one `[[mesh]]` entry"
    );
}

#[test]
fn fields_that_do_not_apply() {
    assert_eq!(
        field_message("[[mesh]]\nshape = \"box\"\nradius = 1\n"),
        "mesh[0].radius does not apply to shape \"box\""
    );
    assert_eq!(
        field_message("[[mesh]]\nshape = \"sphere\"\nsize = [1, 1, 1]\n"),
        "mesh[0].size does not apply to shape \"sphere\""
    );
    assert_eq!(
        field_message("[[mesh]]\nobj = \"a.obj\"\nsegments = 3\n"),
        "mesh[0].segments does not apply to an obj mesh"
    );
    for field in [
        "position = [0, 1, 0]",
        "target = [0, 0, 0]",
        "up = [0, 1, 0]",
        "cone = 30",
        "near = 1",
        "far = 2",
    ] {
        let name = field.split(' ').next().unwrap();
        assert_eq!(
            field_message(&format!("{BOX}[[light]]\n{field}\n")),
            format!("light[0].{name} does not apply to a directional light")
        );
    }
    assert_eq!(
        field_message(&format!("{BOX}[[light]]\nrange = 5\n")),
        "light[0].range does not apply to a directional light"
    );
    // A spot's reach is its far distance.
    assert_eq!(
        field_message(&format!("{BOX}[[light]]\nkind = \"spot\"\nrange = 5\n")),
        "light[0].range does not apply to a spot light (its reach is `far`)"
    );
    // A point light lights every direction: none of a directional or spot light's aim or frustum.
    for field in [
        "direction = [0, -1, 0]",
        "target = [0, 0, 0]",
        "up = [0, 1, 0]",
        "cone = 30",
        "near = 1",
        "far = 2",
    ] {
        let name = field.split(' ').next().unwrap();
        let (field, problem) = field_error(&format!(
            "{BOX}[[light]]\n[[light]]\nkind = \"point\"\nposition = [0, 3, 0]\n{field}\n"
        ));
        assert_eq!(field, format!("light[1].{name}"));
        assert_eq!(
            problem,
            SceneFileProblem::NotApplicable {
                to: "a point light".to_owned()
            }
        );
        assert_eq!(problem.to_string(), "does not apply to a point light");
    }
    assert_eq!(
        field_message("[[mesh]]\nshape = \"box\"\nstep = [1, 0, 0]\n"),
        "mesh[0].step does not apply to a single copy (set `copies`)"
    );
    assert_eq!(
        field_message("[[mesh]]\nshape = \"box\"\ncopies = 2\n"),
        "mesh[0].copies needs a `step` between the copies"
    );
}

#[test]
fn a_point_light_needs_a_position_and_a_positive_range() {
    let (field, problem) = field_error(&format!("{BOX}[[light]]\nkind = \"point\"\nrange = 4\n"));
    assert_eq!(field, "light[0].position");
    assert!(
        matches!(problem, SceneFileProblem::Missing { .. }),
        "{problem:?}"
    );
    assert_eq!(
        field_message(&format!("{BOX}[[light]]\nkind = \"point\"\n")),
        "light[0].position needs to be given for a point light, which has no default position"
    );
    for (range, shown) in [("0", "0"), ("-0.0", "-0"), ("-2.5", "-2.5")] {
        let text =
            format!("{BOX}[[light]]\nkind = \"point\"\nposition = [0, 3, 0]\nrange = {range}\n");
        let (field, problem) = field_error(&text);
        assert_eq!(field, "light[0].range", "{range}");
        assert!(
            matches!(&problem, SceneFileProblem::OutOfRange { requirement, .. } if requirement == "> 0"),
            "{range}: {problem:?}"
        );
        assert_eq!(
            field_message(&text),
            format!("light[0].range ({shown}) must be > 0")
        );
    }
    // The smallest positive range is one.
    let scene = shadowlab_scene::parse_scene(
        &format!("{BOX}[[light]]\nkind = \"point\"\nposition = [0, 3, 0]\nrange = 5e-324\n"),
        std::path::Path::new("tiny.toml"),
    )
    .expect("a positive range");
    assert_eq!(
        scene.lights,
        [shadowlab_scene::SceneLight::Point {
            position: DVec3::new(0.0, 3.0, 0.0),
            range: Some(5e-324)
        }]
    );
}

#[test]
fn obj_files_that_are_missing_or_malformed() {
    let (error, message, path) =
        scene_error("[[mesh]]\nshape = \"box\"\n[[mesh]]\nobj = \"gone.obj\"\n");
    let SceneFileError::Obj { field, source, .. } = &error else {
        panic!("{error:?}");
    };
    assert_eq!(field, "mesh[1].obj");
    let missing = path.with_file_name("gone.obj");
    assert!(matches!(&**source, ObjError::Read(ReadError::Io { path, .. }) if *path == missing));
    assert!(
        message.starts_with(&format!(
            "{}: mesh[1].obj: {}: ",
            path.display(),
            missing.display()
        )),
        "{message}"
    );
    assert!(std::error::Error::source(&error).is_some());

    let (error, message, path) = scene_error_with(
        "[[mesh]]\nobj = \"bad.obj\"\n",
        &[("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n")],
    );
    let SceneFileError::Obj { source, .. } = &error else {
        panic!("{error:?}");
    };
    let ObjError::Line { line, problem, .. } = &**source else {
        panic!("{source:?}");
    };
    assert_eq!(*line, 3);
    assert!(matches!(problem, ObjProblem::NotFinite { .. }));
    assert!(
        message.starts_with(&format!(
            "{}: mesh[0].obj: {}:3: ",
            path.display(),
            path.with_file_name("bad.obj").display()
        )),
        "{message}"
    );
}

#[test]
fn defaults_that_cannot_be_derived() {
    // The camera looks away from the scene: there is no default far plane.
    let (error, message, path) = scene_error(&format!(
        "{BOX}[camera]\nposition = [0, 0, 10]\ndirection = [0, 0, 1]\n"
    ));
    assert!(
        matches!(&error, SceneFileError::Field { field, problem: SceneFileProblem::NoDefault { .. }, .. }
            if field == "camera.far"),
        "{error:?}"
    );
    assert!(
        message.starts_with(&format!("{}: camera.far has no default: ", path.display())),
        "{message}"
    );
}

#[test]
fn values_that_overflow_are_hull_errors_of_the_camera() {
    let (error, message, path) = scene_error(&format!(
        "{BOX}[camera]\nposition = [1e308, 0, 0]\ntarget = [-1e308, 0, 0]\n"
    ));
    assert!(
        matches!(&error, SceneFileError::Hull { field, source: HullError::NonFinite { .. }, .. }
            if field == "camera"),
        "{error:?}"
    );
    assert!(message.starts_with(&format!("{}: camera: ", path.display())));
}

#[test]
fn unreadable_files_and_unknown_built_ins() {
    let dir = ObjDir::new();
    let path = dir.path().join("absent.toml");
    let error = load_scene(&path).unwrap_err();
    assert!(matches!(&error, SceneFileError::Read(ReadError::Io { path: p, .. }) if *p == path));
    let not_utf8 = dir.path().join("latin1.toml");
    std::fs::write(&not_utf8, b"\nname = \"caf\xe9\"\n").unwrap();
    assert!(matches!(
        load_scene(&not_utf8),
        Err(SceneFileError::NotUtf8 { line: 2, .. })
    ));
    let error = load_scene(dir.path()).unwrap_err();
    assert!(
        matches!(
            &error,
            SceneFileError::Read(ReadError::NotRegularFile {
                kind: "a directory",
                ..
            })
        ),
        "{error:?}"
    );
    let large = dir.path().join("large.toml");
    let size = usize::try_from(shadowlab_scene::MAX_SCENE_FILE_BYTES).unwrap() + 1;
    std::fs::write(&large, "#".repeat(size)).unwrap();
    let message = load_scene(&large).unwrap_err().to_string();
    assert!(
        message.contains("larger than 4 MiB (MAX_SCENE_FILE_BYTES)"),
        "{message}"
    );

    let error = builtin_scene("indoor").unwrap_err();
    assert!(matches!(&error, BuiltinSceneError::Unknown { name } if name == "indoor"));
    assert_eq!(
        error.to_string(),
        "there is no built-in scene `indoor`; the built-in scenes are outdoor, dueling-frusta, \
         cad-lattice, chess-spot, bunny, room-point, chess-point"
    );
}

#[test]
fn parse_scene_names_the_path_it_is_given() {
    let path = PathBuf::from("somewhere/else.toml");
    let error = parse_scene("[camera]\nfov = 0\n[[mesh]]\nshape = \"box\"\n", &path).unwrap_err();
    assert_eq!(
        error.to_string(),
        "somewhere/else.toml: camera.fov (0) must be in [0.001, 180) degrees (MIN_ANGLE_DEGREES)"
    );
}
