//! The glTF 2.0 files of the Debian package `assimp-testmodels` committed in `data/gltf/assimp`
//! (see its README): each valid one loads with its documented geometry, each malformed one is an
//! error that names the file and the problem, and each valid file with parts shadowlab cannot
//! represent loads with a warning naming them.

use std::path::{Path, PathBuf};

use shadowlab_scene::{GltfError, GltfSkipped, load_gltf};

use crate::support::data_path;

fn sample(relative: &str) -> PathBuf {
    data_path(&format!("gltf/assimp/{relative}"))
}

/// Asserts that loading `relative` fails with a message holding the file's name and every
/// `fragment`.
fn assert_error(relative: &str, fragments: &[&str]) -> GltfError {
    let path = sample(relative);
    let error = load_gltf(&path, None).expect_err(relative);
    let message = error.to_string();
    let file = Path::new(relative).file_name().and_then(|n| n.to_str());
    assert!(
        message.contains(file.expect("a file name")),
        "{relative}: the message does not name the file: {message}"
    );
    for fragment in fragments {
        assert!(
            message.contains(fragment),
            "{relative}: `{fragment}` missing from: {message}"
        );
    }
    error
}

#[test]
fn malformed_files_are_errors_naming_the_file_and_the_problem() {
    assert_error(
        "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
        &[
            "node 1 'nodes_1'",
            "mesh 0 'Mesh'",
            "accessor 2",
            "position 0 is [-inf, -0.5, 0.5], not finite",
        ],
    );
    assert_error(
        "IndexOutOfRange/IndexOutOfRange.gltf",
        &["accessor 0", "index 0 is 255", "24 vertices"],
    );
    assert_error(
        "IndexOutOfRange/AllIndicesOutOfRange.gltf",
        &["accessor 0", "index 0 is 65535", "24 vertices"],
    );
    assert_error(
        "IncorrectVertexArrays/Cube.gltf",
        &[
            "node 1 'TruncatedCube'",
            "TRIANGLES cannot be drawn from 35 vertices",
            "multiple of 3",
        ],
    );
    let missing = assert_error(
        "MissingBin/BoxTextured.gltf",
        &["buffer 0", "BoxTextured0.bin"],
    );
    // The missing buffer is a usage error, reached through source() as the CLI does.
    let read = std::error::Error::source(&missing)
        .and_then(|e| e.downcast_ref::<shadowlab_scene::ReadError>())
        .expect("the read error as source");
    assert!(read.is_bad_input());
    assert_error(
        "RecursiveNodes/RecursiveNodes.gltf",
        &["node 0", "reached a second time", "§3.5.2"],
    );
    assert_error(
        "SchemaFailures/sceneWrongType.gltf",
        &["not a glTF 2.0 file", "\"hello\"", "line 6"],
    );
    assert_error(
        "TestNoRootNode/NoScene.gltf",
        &["invalid glTF 2.0", "scene"],
    );
    assert_error(
        "TestNoRootNode/SceneWithoutNodes.gltf",
        &["not a glTF 2.0 file", "nodes"],
    );
    for (file, fragment) in [
        ("badArray", "expected a sequence at line 44"),
        ("badNumber", "\"not a number\", expected f32 at line 132"),
        ("badObject", "\"not an object\""),
        ("badString", "integer `42`, expected a string"),
        ("badUint", "integer `-1`"),
    ] {
        assert_error(&format!("wrongTypes/{file}.gltf"), &[fragment]);
    }
    assert_error(
        "draco/2CylinderEngine.gltf",
        &["requires the extension KHR_draco_mesh_compression", "§3.12"],
    );
}

#[test]
fn an_invalid_extension_that_is_used_but_not_required_is_ignored() {
    // badExtension.gltf gives KHR_texture_transform a string instead of an object, in a material;
    // the extension is only in extensionsUsed, and glTF 2.0 §3.12 lets a loader ignore it.
    let import = load_gltf(&sample("wrongTypes/badExtension.gltf"), None).expect("loads");
    assert_eq!(import.mesh.triangle_count(), 12);
    assert!(import.warnings.is_empty());
}

#[test]
fn zero_normals_are_replaced_with_a_warning() {
    let import =
        load_gltf(&sample("BoxBadNormals-glTF-Binary/BoxBadNormals.glb"), None).expect("loads");
    assert_eq!(import.mesh.triangle_count(), 12);
    assert_eq!(import.warnings.len(), 1);
    assert_eq!(
        import.warnings[0].skipped,
        GltfSkipped::BadNormals { count: 4 }
    );
    let message = import.warnings[0].to_string();
    assert!(
        message.contains("BoxBadNormals.glb: node 1 'nodes_1': mesh 0 'Mesh': primitive 0"),
        "{message}"
    );
    for normal in import.mesh.normals() {
        assert!((normal.length() - 1.0).abs() < 1e-12, "{normal}");
    }
}

#[test]
fn the_box_loads_alike_from_gltf_glb_and_an_embedded_buffer() {
    let separate = load_gltf(&sample("BoxTextured-glTF/BoxTextured.gltf"), None).expect("gltf");
    let binary = load_gltf(&sample("BoxTextured-glTF-Binary/BoxTextured.glb"), None).expect("glb");
    let embedded =
        load_gltf(&sample("BoxTextured-glTF-Embedded/BoxTextured.gltf"), None).expect("data URI");
    assert_eq!(separate.mesh, binary.mesh);
    assert_eq!(separate.mesh, embedded.mesh);
    let mesh = &separate.mesh;
    assert_eq!(mesh.triangle_count(), 12);
    assert_eq!(mesh.group_names(), ["Mesh"]);
    // The unit box, turned by its root node's matrix (−90° about x): still a unit box.
    assert_eq!(mesh.bounds().min.to_array(), [-0.5; 3]);
    assert_eq!(mesh.bounds().max.to_array(), [0.5; 3]);
    // Counter-clockwise seen from outside: a positive volume.
    assert!((mesh.signed_volume() - 1.0).abs() < 1e-12);
}

#[test]
fn every_primitive_mode_is_drawn_or_skipped_with_a_warning() {
    // Mesh_PrimitiveMode_NN of the glTF Asset Generator: a unit square drawn with each mode,
    // without indices (00–06) and with UNSIGNED_INT (07–13), UNSIGNED_BYTE (14) and
    // UNSIGNED_SHORT (15) indices.
    let skipped = [
        (0, "POINTS"),
        (1, "LINES"),
        (2, "LINE_LOOP"),
        (3, "LINE_STRIP"),
    ];
    for number in 0..16 {
        let relative =
            format!("glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_{number:02}.gltf");
        let mode = skipped
            .iter()
            .find(|(n, _)| *n == number % 7 && number < 11)
            .map(|(_, mode)| *mode);
        match (load_gltf(&sample(&relative), None), mode) {
            (Err(error @ GltfError::NoTriangles { .. }), Some(mode)) => {
                let message = error.to_string();
                assert!(
                    message.contains("has no triangles to draw")
                        && message.contains(&format!("a {mode} primitive")),
                    "{relative}: {message}"
                );
            }
            (Ok(import), None) => {
                let mesh = &import.mesh;
                assert_eq!(mesh.triangle_count(), 2, "{relative}");
                assert!((mesh.surface_area() - 1.0).abs() < 1e-12, "{relative}");
                // Every triangle counter-clockwise seen from +z, the square's front.
                for t in 0..mesh.triangle_count() {
                    let [a, b, c] = mesh.triangle_positions(t);
                    assert!((b - a).cross(c - a).z > 0.0, "{relative}: triangle {t}");
                }
                assert!(import.warnings.is_empty(), "{relative}");
            }
            (other, mode) => panic!("{relative}: {other:?} (expected {mode:?})"),
        }
    }
}

#[test]
fn skins_morph_targets_animations_and_orthographic_cameras_are_warnings() {
    let skin = load_gltf(&sample("simple_skin/simple_skin.gltf"), None).expect("loads");
    assert_eq!(skin.mesh.triangle_count(), 8);
    let kinds: Vec<_> = skin.warnings.iter().map(|w| w.skipped.clone()).collect();
    assert_eq!(
        kinds,
        [
            GltfSkipped::Animations { count: 1 },
            GltfSkipped::Skin { skin: 0 }
        ]
    );
    assert!(
        skin.warnings[1]
            .to_string()
            .contains("simple_skin.gltf: node 0: skin 0 not applied")
    );

    let morph = load_gltf(
        &sample("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"),
        None,
    )
    .expect("loads");
    assert!(
        morph
            .warnings
            .iter()
            .any(|w| w.skipped == GltfSkipped::MorphTargets { count: 2 }
                && w.to_string().contains("mesh 0 'Cube': primitive 0"))
    );

    let cameras = load_gltf(&sample("cameras/Cameras.gltf"), None).expect("loads");
    assert_eq!(cameras.cameras.len(), 1);
    assert_eq!(cameras.warnings.len(), 1);
    assert_eq!(cameras.warnings[0].skipped, GltfSkipped::OrthographicCamera);
    assert!(cameras.warnings[0].to_string().contains("node 2: camera 1"));
    let camera = &cameras.cameras[0];
    assert_eq!(camera.fov_y, f64::from(0.7_f32));
    assert_eq!(camera.near, f64::from(0.01_f32));
    assert_eq!(camera.far, Some(100.0));
    assert_eq!(camera.aspect_ratio, Some(1.0));
    assert_eq!(camera.pose.eye().to_array(), [0.5, 0.5, 3.0]);
    assert_eq!(camera.pose.forward().to_array(), [0.0, 0.0, -1.0]);
}

#[test]
fn a_data_uri_file_with_unused_texture_coordinates_loads() {
    // issue_3269's texcoord_crash.gltf names TEXCOORD_1 where materials read TEXCOORD_0, which
    // crashed assimp; shadowlab reads no texture coordinates.
    let import = load_gltf(&sample("issue_3269/texcoord_crash.gltf"), None).expect("loads");
    assert_eq!(import.mesh.triangle_count(), 10);
    assert_eq!(import.mesh.group_count(), 5);
}
