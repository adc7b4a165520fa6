//! Property tests (seeded, see `support::SEED`): transforms, merging and normals over random
//! meshes, and the procedural shapes over random parameters.

use glam::{DAffine3, DQuat, DVec3};
use proptest::prelude::*;
use shadowlab_scene::{Mesh, ObjError, load_obj, procedural};

use crate::procedural::{assert_bars_closed, assert_closed_convex};
use crate::support::{ObjDir, assert_close, assert_unit_normals, config, first_open_edge};

/// A coordinate spread over many orders of magnitude, of either sign.
fn coordinate() -> impl Strategy<Value = f64> {
    (-1.0..1.0_f64, -20..20_i32).prop_map(|(m, e)| m * 10_f64.powi(e))
}

fn point() -> impl Strategy<Value = DVec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A random triangle soup of 3–30 vertices (degenerate triangles included).
fn mesh() -> impl Strategy<Value = Mesh> {
    prop::collection::vec(point(), 3..30).prop_flat_map(|positions| {
        let n = u32::try_from(positions.len()).expect("small");
        prop::collection::vec([0..n, 0..n, 0..n], 1..40).prop_map(move |triangles| {
            Mesh::new(positions.clone(), triangles).expect("valid by construction")
        })
    })
}

/// A rigid motion with a uniform scale: rotation, scale in [1/8, 8], translation.
fn similarity() -> impl Strategy<Value = (DQuat, f64, DVec3)> {
    (
        (
            -1.0..1.0_f64,
            -1.0..1.0_f64,
            -1.0..1.0_f64,
            0.0..std::f64::consts::TAU,
        ),
        -3..=3_i32,
        (-1e3..1e3_f64, -1e3..1e3_f64, -1e3..1e3_f64),
    )
        .prop_map(|((x, y, z, angle), exponent, (tx, ty, tz))| {
            let axis = DVec3::new(x, y, z).try_normalize().unwrap_or(DVec3::Y);
            (
                DQuat::from_axis_angle(axis, angle),
                2_f64.powi(exponent),
                DVec3::new(tx, ty, tz),
            )
        })
}

/// A well-formed OBJ line (in a file that starts with three `v`, a `vt` and a `vn`); its faces name
/// normals if `normals`, so that a file's faces agree.
fn valid_obj_line(normals: bool) -> impl Strategy<Value = String> {
    let number = || prop::sample::select(vec!["0", "1", "-2.5", "1e3", "-1e-3", "0.25"]);
    let corner = (
        prop::sample::select(vec!["1", "2", "3", "-1", "-2", "-3"]),
        prop::sample::select(if normals {
            vec!["//1", "/-1/1"]
        } else {
            vec!["", "/1"]
        }),
    );
    prop_oneof![
        3 => (number(), number(), number()).prop_map(|(x, y, z)| format!("v {x} {y} {z}")),
        4 => (prop::collection::vec(corner.0, 3..6), corner.1).prop_map(|(corners, suffix)| {
            let corners: Vec<String> = corners.iter().map(|c| format!("{c}{suffix}")).collect();
            format!("f {}", corners.join(" "))
        }),
        1 => (number(), number(), number()).prop_map(|(x, y, z)| format!("vn {x} {y} {z}")),
        1 => prop::sample::select(vec!["g a", "o b", "g", "usemtl m", "s off", "l 1 2 3", "# c"])
            .prop_map(str::to_owned),
    ]
}

/// One OBJ line built from keywords and values that are mostly not well-formed.
fn junk_obj_line() -> impl Strategy<Value = String> {
    let keyword = prop::sample::select(vec![
        "v", "vt", "vn", "f", "l", "g", "usemtl", "mtllib", "#", "p",
    ]);
    let value = prop::sample::select(vec![
        "0",
        "1",
        "-1",
        "-4",
        "1e308",
        "1e-320",
        "nan",
        "inf",
        "x",
        "1/1",
        "2/1/1",
        "3//1",
        "1/2/3/4",
        "/1",
        "0/0",
        "1//",
        "+2",
        "9223372036854775807",
        "-9223372036854775808",
        "#",
    ]);
    (keyword, prop::collection::vec(value, 0..8))
        .prop_map(|(keyword, values)| format!("{keyword} {}", values.join(" ")))
}

/// Mostly well-formed OBJ text, with an occasional malformed line.
fn obj_lines() -> impl Strategy<Value = Vec<String>> {
    any::<bool>().prop_flat_map(|normals| {
        prop::collection::vec(
            prop_oneof![30 => valid_obj_line(normals), 1 => junk_obj_line()],
            0..40,
        )
    })
}

proptest! {
    #![proptest_config(config(64))]

    /// Normals are unit, one per vertex; scaling a mesh by a power of two (exact) changes no bit of
    /// them; merging keeps every triangle's positions.
    #[test]
    fn normals_and_merging(mesh in mesh(), other in mesh(), exponent in -60..60_i32) {
        assert_unit_normals(&mesh);
        prop_assert_eq!(mesh.normals().len(), mesh.vertex_count());
        let scale = 2_f64.powi(exponent);
        let scaled = Mesh::new(
            mesh.positions().iter().map(|&p| p * scale).collect(),
            mesh.triangles().to_vec(),
        ).unwrap();
        prop_assert_eq!(scaled.normals(), mesh.normals());
        let merged = Mesh::merged(&[mesh.clone(), other.clone()]);
        prop_assert_eq!(merged.triangle_count(), mesh.triangle_count() + other.triangle_count());
        for t in 0..other.triangle_count() {
            prop_assert_eq!(
                merged.triangle_positions(mesh.triangle_count() + t),
                other.triangle_positions(t)
            );
        }
        prop_assert_eq!(&merged.normals()[mesh.vertex_count()..], other.normals());
        prop_assert!(merged.bounds().contains(mesh.bounds().min));
        prop_assert!(merged.bounds().contains(other.bounds().max));
    }

    /// A similarity transform moves every position as a point, rotates every normal (by the same
    /// rotation, whatever the scale), and scales volume and area by s³ and s².
    #[test]
    fn similarity_transforms((rotation, scale, translation) in similarity(),
                             radius in 0.1..10.0_f64, segments in 3..24_u32) {
        let shape = procedural::cylinder(radius, 2.0 * radius, segments).unwrap();
        let transform =
            DAffine3::from_scale_rotation_translation(DVec3::splat(scale), rotation, translation);
        let moved = shape.transformed(&transform);
        for (p, q) in shape.positions().iter().zip(moved.positions()) {
            prop_assert_eq!(*q, transform.transform_point3(*p));
        }
        for (n, m) in shape.normals().iter().zip(moved.normals()) {
            prop_assert!((rotation * *n - *m).length() < 1e-14);
        }
        assert_unit_normals(&moved);
        assert_close(moved.signed_volume(), shape.signed_volume() * scale.powi(3), 1e-10, "volume");
        assert_close(moved.surface_area(), shape.surface_area() * scale.powi(2), 1e-10, "area");
        prop_assert!(first_open_edge(&moved).is_none());
    }

    /// Closed procedural shapes stay closed, convex-outward and of positive volume for any
    /// parameters in range.
    #[test]
    fn procedural_shapes(radius in 1e-3..1e3_f64, height in 1e-3..1e3_f64,
                         segments in 3..40_u32, rings in 2..20_u32,
                         size in (1e-3..1e3_f64, 1e-3..1e3_f64, 1e-3..1e3_f64)) {
        assert_closed_convex(&procedural::sphere(radius, segments, rings).unwrap(), "sphere");
        assert_closed_convex(&procedural::cylinder(radius, height, segments).unwrap(), "cylinder");
        let cuboid = procedural::cuboid(DVec3::new(size.0, size.1, size.2)).unwrap();
        assert_closed_convex(&cuboid, "cuboid");
        assert_close(cuboid.signed_volume(), size.0 * size.1 * size.2, 1e-14, "cuboid volume");
    }

    /// Lattices of any shape are sets of closed bars with the documented bounds.
    #[test]
    fn bar_lattices(cells in [0..4_u32, 0..4_u32, 0..4_u32], spacing in 1e-2..1e2_f64,
                    fraction in 0.01..0.99_f64) {
        prop_assume!(cells != [0; 3]);
        let thickness = spacing * fraction;
        let lattice = procedural::bar_lattice(cells, spacing, thickness).unwrap();
        assert_bars_closed(&lattice, &format!("{cells:?}"));
        prop_assert!(lattice.signed_volume() > 0.0);
        let half = DVec3::from_array(cells.map(f64::from)) * (0.5 * spacing) + 0.5 * thickness;
        prop_assert!((lattice.bounds().max - half).abs().max_element() <= 1e-12 * spacing);
        prop_assert!((lattice.bounds().min + half).abs().max_element() <= 1e-12 * spacing);
    }
}

proptest! {
    #![proptest_config(config(256))]

    /// Random OBJ text, mostly well-formed, never panics (in debug builds, with overflow checks)
    /// and never reaches tobj with something tobj rejects: the result is a valid mesh or an error
    /// that names a line, or says there are no faces.
    #[test]
    fn obj_text_never_panics(lines in obj_lines()) {
        let dir = ObjDir::new();
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n{}\n", lines.join("\n"));
        let path = dir.write("random.obj", &text);
        match load_obj(&path) {
            Ok(mesh) => {
                assert_unit_normals(&mesh);
                prop_assert!(mesh.positions().iter().all(|p| p.is_finite()));
            }
            Err(ObjError::Line { line, .. }) => prop_assert!(line >= 1 && line <= lines.len() + 5),
            Err(ObjError::NoFaces { .. }) => {}
            Err(other) => prop_assert!(false, "unexpected error {other}"),
        }
    }
}

/// Values that may replace a number of a scene file: out of range, not finite, huge, tiny, of the
/// wrong type, or plain.
const SCENE_VALUES: [&str; 16] = [
    "0",
    "-1",
    "2",
    "0.5",
    "90",
    "180",
    "nan",
    "-inf",
    "1e300",
    "1e-300",
    "-0.0",
    "4294967295",
    "4294967296",
    "\"x\"",
    "[0, 0, 0]",
    "true",
];

/// Lines that may be inserted into a scene file: headers, and fields that may or may not belong
/// where they land.
const SCENE_LINES: [&str; 20] = [
    "[[mesh]]",
    "[[light]]",
    "[camera]",
    "[shadow]",
    "kind = \"spot\"",
    "shape = \"lattice\"",
    "shape = \"sphere\"",
    "obj = \"missing.obj\"",
    "direction = [0, -1, 0]",
    "up = [0, 1, 0]",
    "target = [0, 0, 0]",
    "position = [0, 0, 0]",
    "copies = 3",
    "step = [1, 0, 0]",
    "near = 5",
    "far = 2",
    "cone = 200",
    "radius = 1",
    "scale = -1",
    "technique = \"lispsm\"",
];

/// One edit of a scene file's text; positions are fractions of the length.
#[derive(Clone, Debug)]
enum Edit {
    /// Delete 1 to 6 characters.
    Delete(f64, usize),
    /// Replace the number (with its sign) at or after a position by one of [`SCENE_VALUES`].
    ReplaceNumber(f64, usize),
    /// Insert one of [`SCENE_LINES`] before a line.
    InsertLine(f64, usize),
    /// Duplicate (true) or delete a line.
    Line(f64, bool),
}

fn edit() -> impl Strategy<Value = Edit> {
    let at = || 0.0..1.0_f64;
    prop_oneof![
        1 => (at(), 1..=6_usize).prop_map(|(at, n)| Edit::Delete(at, n)),
        4 => (at(), 0..SCENE_VALUES.len()).prop_map(|(at, v)| Edit::ReplaceNumber(at, v)),
        2 => (at(), 0..SCENE_LINES.len()).prop_map(|(at, l)| Edit::InsertLine(at, l)),
        1 => (at(), any::<bool>()).prop_map(|(at, duplicate)| Edit::Line(at, duplicate)),
    ]
}

/// `text` with `edit` applied. Built-in files are ASCII, so byte positions are character
/// positions.
fn apply(text: &str, edit: &Edit) -> String {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "a fraction in [0, 1) of a length that fits usize"
    )]
    let position = |at: f64, len: usize| ((at * len as f64) as usize).min(len);
    let mut text = text.to_owned();
    let mut lines: Vec<&str> = text.lines().collect();
    let line = |at: f64| position(at, lines.len()).min(lines.len().saturating_sub(1));
    match *edit {
        Edit::Delete(at, n) => {
            let start = position(at, text.len());
            text.replace_range(start..(start + n).min(text.len()), "");
        }
        Edit::ReplaceNumber(at, value) => {
            let from = position(at, text.len());
            if let Some(offset) = text[from..].find(|c: char| c.is_ascii_digit()) {
                let digits = from + offset;
                let start = if text[..digits].ends_with('-') {
                    digits - 1
                } else {
                    digits
                };
                let end = text[digits..]
                    .find(|c: char| !(c.is_ascii_digit() || c == '.'))
                    .map_or(text.len(), |length| digits + length);
                text.replace_range(start..end, SCENE_VALUES[value]);
            }
        }
        Edit::InsertLine(at, inserted) => {
            let index = line(at);
            lines.insert(index, SCENE_LINES[inserted]);
            text = lines.join("\n");
        }
        Edit::Line(at, duplicate) => {
            let index = line(at);
            if duplicate {
                lines.insert(index, lines[index]);
            } else {
                lines.remove(index);
            }
            text = lines.join("\n");
        }
    }
    text
}

proptest! {
    #![proptest_config(config(256))]

    /// Mangled versions of the built-in scene files never panic: each is a scene whose camera and
    /// lights are valid, or an error whose message names the file.
    #[test]
    fn mangled_scene_files_never_panic(
        scene in 0..shadowlab_scene::BUILTIN_SCENES.len(),
        edits in prop::collection::vec(edit(), 1..4),
    ) {
        let name = shadowlab_scene::BUILTIN_SCENES[scene];
        let path = crate::support::data_path(&format!("scenes/{name}.toml"));
        let text = edits.iter().fold(
            shadowlab_scene::builtin_scene_text(name).unwrap().to_owned(),
            |text, edit| apply(&text, edit),
        );
        match shadowlab_scene::parse_scene(&text, &path) {
            Ok(scene) => {
                prop_assert!(!scene.lights.is_empty());
                let projection = scene.camera.projection;
                prop_assert!(0.0 < projection.near() && projection.near() < projection.far());
                prop_assert!(scene.camera.width > 0 && scene.camera.height > 0);
                prop_assert!(scene.bounds().min.is_finite() && scene.bounds().max.is_finite());
                for light in &scene.lights {
                    let _ = light.light();
                }
            }
            Err(error) => {
                let message = error.to_string();
                prop_assert!(
                    message.starts_with(&path.display().to_string()),
                    "{} does not name the file", message
                );
            }
        }
    }
}
