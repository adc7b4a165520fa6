//! The targets that read text: OBJ files, scene files and the command line.

use std::ffi::OsString;
use std::path::Path;

use shadowlab_scene::{Mesh, Scene, parse_obj, parse_scene};

/// What errors name the fuzzed OBJ text by.
const OBJ_PATH: &str = "fuzz.obj";

/// What errors name the fuzzed scene text by. Its directory does not exist, so a relative `obj`
/// path of the scene resolves to nothing and fails as a missing file; absolute paths are read.
const SCENE_PATH: &str = "/nonexistent-shadowlab-fuzz/fuzz.toml";

/// See [`crate::obj`].
pub(crate) fn obj(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Ok(mesh) = parse_obj(&text, Path::new(OBJ_PATH)) {
        check_mesh(&mesh);
    }
}

/// See [`crate::scene`].
pub(crate) fn scene(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Ok(scene) = parse_scene(&text, Path::new(SCENE_PATH)) {
        check_scene(&scene);
    }
}

/// See [`crate::cli`].
pub(crate) fn cli(data: &[u8]) {
    let arguments =
        std::iter::once(OsString::from("shadowlab")).chain(data.split(|&b| b == 0).map(os_string));
    // Err is the message a user would see; only a panic is a failure.
    let _ = shadowlab::check_arguments(arguments);
}

/// One argument as the operating system would pass it: any bytes but NUL.
#[cfg(unix)]
fn os_string(bytes: &[u8]) -> OsString {
    use std::os::unix::ffi::OsStringExt;
    OsString::from_vec(bytes.to_vec())
}

/// One argument; where arguments are not bytes, the bytes read as UTF-8.
#[cfg(not(unix))]
fn os_string(bytes: &[u8]) -> OsString {
    OsString::from(String::from_utf8_lossy(bytes).into_owned())
}

/// The guarantees `Mesh` documents.
fn check_mesh(mesh: &Mesh) {
    let (positions, normals) = (mesh.positions(), mesh.normals());
    assert!(mesh.triangle_count() > 0, "a mesh has a triangle");
    assert!(
        positions.iter().all(|p| p.is_finite()),
        "positions are finite"
    );
    assert_eq!(normals.len(), positions.len(), "one normal per position");
    for normal in normals {
        assert!(
            normal.is_finite() && (normal.length() - 1.0).abs() < 1e-9,
            "normals are unit: {normal}"
        );
    }
    let vertex_count = positions.len();
    for triangle in mesh.triangles() {
        assert!(
            triangle.iter().all(|&i| (i as usize) < vertex_count),
            "indices are in range: {triangle:?} of {vertex_count}"
        );
    }
    assert_eq!(
        mesh.groups().len(),
        mesh.triangle_count(),
        "a group per triangle"
    );
    assert_eq!(mesh.group_names().len(), mesh.group_count());
    assert!(
        mesh.groups()
            .iter()
            .all(|&g| (g as usize) < mesh.group_count()),
        "group ids are in range"
    );
}

/// The guarantees `Scene` documents for a scene read from a file.
fn check_scene(scene: &Scene) {
    check_mesh(&scene.mesh);
    assert!(!scene.lights.is_empty(), "a scene has a light");
    for light in &scene.lights {
        // Panics on a zero or non-finite direction, which a scene file's light never is.
        let _ = light.light();
    }
    let camera = &scene.camera;
    assert!(
        camera.width >= 1 && camera.height >= 1,
        "the image has pixels"
    );
    assert_eq!(
        camera.projection.aspect(),
        f64::from(camera.width) / f64::from(camera.height),
        "aspect = width / height"
    );
}
