//! glTF files written by the tests (JSON with base64 buffers, built from their definitions):
//! transforms composed in f64, winding under mirroring, normals, sparse accessors, buffers and
//! URIs, scenes, limits, cameras and lights, and glTF files as scenes and as scene-file entries.

use std::path::Path;

use base64::Engine as _;
use glam::{DVec3, dvec3};
use serde_json::{Value, json};
use shadowlab_scene::scene_file::{DEFAULT_IMAGE, DEFAULT_SUN_DIRECTION};
use shadowlab_scene::{
    GltfError, GltfLightKind, GltfProblem, GltfSkipped, SceneFileError, SceneLight, load_gltf,
    load_gltf_scene, load_scene, load_scene_with_warnings,
};

use crate::support::ObjDir;

/// Buffer views and accessors over one buffer, for writing test files.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views.push(json!({
            "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()
        }));
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// A VEC3 FLOAT accessor.
    fn vec3(&mut self, values: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes);
        self.accessor(json!({
            "bufferView": view, "componentType": 5126, "count": values.len(), "type": "VEC3"
        }))
    }

    /// A SCALAR index accessor of `component` (5121, 5123 or 5125).
    fn indices(&mut self, values: &[u32], component: u32) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flat_map(|&v| match component {
                5121 => vec![u8::try_from(v).expect("a byte")],
                5123 => u16::try_from(v).expect("a short").to_le_bytes().to_vec(),
                _ => v.to_le_bytes().to_vec(),
            })
            .collect();
        let view = self.view(&bytes);
        self.accessor(json!({
            "bufferView": view, "componentType": component, "count": values.len(), "type": "SCALAR"
        }))
    }

    /// The document: `rest` with `asset`, the buffer (as a data URI) and the views and accessors.
    fn document(self, mut rest: Value) -> Value {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        rest["asset"] = json!({ "version": "2.0" });
        rest["buffers"] = json!([{
            "byteLength": self.bin.len(),
            "uri": format!("data:application/octet-stream;base64,{data}")
        }]);
        rest["bufferViews"] = json!(self.views);
        rest["accessors"] = json!(self.accessors);
        rest
    }
}

/// One triangle, counter-clockwise seen from +z.
const TRIANGLE: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

/// A file of one triangle mesh (mesh 0) placed by `nodes` (scene 0 holds `roots`).
fn triangle_file(nodes: Value, roots: &[usize]) -> Value {
    let mut builder = Builder::default();
    let positions = builder.vec3(&TRIANGLE);
    builder.document(json!({
        "scenes": [{ "nodes": roots }],
        "nodes": nodes,
        "meshes": [{ "name": "tri", "primitives": [{ "attributes": { "POSITION": positions } }] }],
    }))
}

fn write(dir: &ObjDir, name: &str, document: &Value) -> std::path::PathBuf {
    dir.write(name, &document.to_string())
}

fn load(document: &Value) -> Result<shadowlab_scene::GltfImport, GltfError> {
    let dir = ObjDir::new();
    load_gltf(&write(&dir, "test.gltf", document), None)
}

#[test]
fn node_transforms_compose_from_the_root_in_f64() {
    // A parent at (0.1, 2, 3) (f32 values) and a child at x = 0.2 turned 180° about y and scaled
    // by 2: world = T_parent · (T_child + R · 2p), each f32 value exact in f64 and the sums f64.
    let nodes = json!([
        { "translation": [0.1, 2.0, 3.0], "children": [1] },
        { "translation": [0.2, 0.0, 0.0], "rotation": [0.0, 1.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "mesh": 0 }
    ]);
    let import = load(&triangle_file(nodes, &[0])).expect("loads");
    let tx = f64::from(0.1_f32) + f64::from(0.2_f32);
    assert_eq!(
        import.mesh.positions(),
        [
            dvec3(tx, 2.0, 3.0),
            dvec3(tx - 2.0, 2.0, 3.0),
            dvec3(tx, 4.0, 3.0)
        ]
    );
    assert_eq!(import.mesh.group_names(), ["tri"]);
    // The same placement as a matrix (column-major).
    let nodes = json!([
        { "translation": [0.1, 2.0, 3.0], "children": [1] },
        { "matrix": [-2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, -2.0, 0.0, 0.2, 0.0, 0.0, 1.0], "mesh": 0 }
    ]);
    assert_eq!(
        load(&triangle_file(nodes, &[0])).expect("loads").mesh,
        import.mesh
    );
}

#[test]
fn a_mirroring_node_keeps_triangles_counter_clockwise_and_normals_follow_the_inverse_transpose() {
    let nodes = json!([{ "scale": [-1.0, 1.0, 1.0], "mesh": 0 }]);
    let import = load(&triangle_file(nodes, &[0])).expect("loads");
    let [a, b, c] = import.mesh.triangle_positions(0);
    assert!(
        (b - a).cross(c - a).z > 0.0,
        "still counter-clockwise from +z"
    );
    assert_eq!(import.mesh.triangles(), [[0, 2, 1]]);
    assert!(import.mesh.normals().iter().all(|n| *n == DVec3::Z));

    // A file normal (1, 1, 0)/|…| under a scale of 2 in x becomes ∝ (1/2, 1, 0).
    let mut builder = Builder::default();
    let positions = builder.vec3(&TRIANGLE);
    let normals = builder.vec3(&[[1.0, 1.0, 0.0]; 3]);
    let document = builder.document(json!({
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "scale": [2.0, 1.0, 1.0], "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": positions, "NORMAL": normals } }] }],
    }));
    let import = load(&document).expect("loads");
    let expected = dvec3(0.5, 1.0, 0.0).normalize();
    for n in import.mesh.normals() {
        assert!((*n - expected).length() < 1e-15, "{n}");
    }
}

#[test]
fn every_index_type_and_sparse_positions_are_read() {
    for component in [5121, 5123, 5125] {
        let mut builder = Builder::default();
        let positions = builder.vec3(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        let indices = builder.indices(&[0, 1, 2, 0, 2, 3], component);
        let document = builder.document(json!({
            "scenes": [{ "nodes": [0] }],
            "nodes": [{ "mesh": 0 }],
            "meshes": [{ "primitives": [{ "attributes": { "POSITION": positions }, "indices": indices }] }],
        }));
        let import = load(&document).expect("loads");
        assert_eq!(
            import.mesh.triangles(),
            [[0, 1, 2], [0, 2, 3]],
            "{component}"
        );
    }
    // A sparse accessor: vertex 1 of the base triangle replaced by (2, 0, 0); and one without a
    // buffer view: zeros but for the substituted vertices 1 and 2.
    for with_base in [true, false] {
        let mut builder = Builder::default();
        let base = builder.vec3(&TRIANGLE);
        let index_view = builder.view(&[1, 2]);
        let value_view = builder.view(
            &[[2.0_f32, 0.0, 0.0], [0.0, 1.0, 0.0]]
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect::<Vec<u8>>(),
        );
        let mut sparse = json!({
            "componentType": 5126, "count": 3, "type": "VEC3",
            "sparse": {
                "count": 2,
                "indices": { "bufferView": index_view, "componentType": 5121 },
                "values": { "bufferView": value_view }
            }
        });
        if with_base {
            sparse["bufferView"] = builder.accessors[base]["bufferView"].clone();
        }
        let positions = builder.accessor(sparse);
        let document = builder.document(json!({
            "scenes": [{ "nodes": [0] }],
            "nodes": [{ "mesh": 0 }],
            "meshes": [{ "primitives": [{ "attributes": { "POSITION": positions } }] }],
        }));
        let import = load(&document).expect("loads");
        assert_eq!(
            import.mesh.positions(),
            [DVec3::ZERO, dvec3(2.0, 0.0, 0.0), dvec3(0.0, 1.0, 0.0)]
        );
    }
}

/// The message of loading `document`, which must fail.
fn message(document: &Value) -> String {
    load(document).expect_err("an error").to_string()
}

#[test]
fn malformed_accessors_buffers_and_nodes_are_errors_naming_the_object() {
    let mut builder = Builder::default();
    let positions = builder.vec3(&TRIANGLE);
    let base = builder.document(json!({
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "name": "n", "mesh": 0 }],
        "meshes": [{ "name": "m", "primitives": [{ "attributes": { "POSITION": positions } }] }],
    }));
    let mut long = base.clone();
    long["accessors"][0]["count"] = json!(6);
    let text = message(&long);
    assert!(
        text.contains("node 0 'n': mesh 0 'm': primitive 0: accessor 0: the accessor's elements span bytes 0..72, beyond the 36 bytes there are"),
        "{text}"
    );
    let mut flat = base.clone();
    flat["accessors"][0]["type"] = json!("VEC2");
    assert!(message(&flat).contains("is VEC2 of FLOAT, but POSITION must be VEC3 of FLOAT"));
    let mut short_buffer = base.clone();
    short_buffer["buffers"][0]["byteLength"] = json!(40);
    assert!(
        message(&short_buffer).contains("buffer 0: holds 36 bytes, fewer than its byteLength 40")
    );
    let mut remote = base.clone();
    remote["buffers"][0]["uri"] = json!("https://example.com/a.bin");
    assert!(message(&remote).contains(
        "buffer 0: has the URI `https://example.com/a.bin`, whose scheme https: is not read"
    ));
    let mut projective = base.clone();
    projective["nodes"][0]["matrix"] = json!([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1]);
    assert!(
        message(&projective).contains("node 0 'n': `matrix` has the last row [0.0, 0.0, 1.0, 1.0]")
    );
    let mut both = base.clone();
    both["nodes"][0]["matrix"] = json!([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    both["nodes"][0]["scale"] = json!([1, 1, 1]);
    assert!(message(&both).contains("gives both `matrix` and translation"));
    let mut zero = base.clone();
    zero["nodes"][0]["rotation"] = json!([0, 0, 0, 0]);
    assert!(message(&zero).contains("`rotation` is the zero quaternion"));
    let mut two_parents = base.clone();
    two_parents["nodes"] = json!([{ "children": [2] }, { "children": [2] }, { "mesh": 0 }]);
    two_parents["scenes"][0]["nodes"] = json!([0, 1]);
    assert!(message(&two_parents).contains("node 2: is reached a second time"));
    let mut version = base.clone();
    version["asset"]["version"] = json!("3.0");
    assert!(message(&version).contains("asset.version is \"3.0\"; only glTF 2.0 is read"));
    let mut huge = base.clone();
    huge["accessors"][0] = json!({ "componentType": 5126, "count": 1_u64 << 40, "type": "VEC3",
        "sparse": { "count": 1, "indices": { "bufferView": 0, "componentType": 5125 }, "values": { "bufferView": 0 } } });
    assert!(message(&huge).contains("more than 100663296 (MAX_GLTF_TRIANGLES)"));
    let mut unsorted = base;
    unsorted["bufferViews"]
        .as_array_mut()
        .expect("views")
        .push(json!({ "buffer": 0, "byteOffset": 0, "byteLength": 2 }));
    unsorted["accessors"][0]["sparse"] = json!({ "count": 2,
        "indices": { "bufferView": 1, "componentType": 5121 }, "values": { "bufferView": 0 } });
    // Bytes 0 and 1 of the buffer are 0, 0: not strictly increasing.
    assert!(
        message(&unsorted).contains("sparse index 1 is 0: sparse indices must strictly increase")
    );
}

#[test]
fn external_buffers_are_read_relative_to_the_file_and_percent_decoded() {
    let dir = ObjDir::new();
    let bytes: Vec<u8> = TRIANGLE
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    std::fs::write(dir.path().join("tri angle.bin"), &bytes).expect("write the buffer");
    let mut document = triangle_file(json!([{ "mesh": 0 }]), &[0]);
    document["buffers"][0]["uri"] = json!("tri%20angle.bin");
    let path = write(&dir, "scene.gltf", &document);
    assert_eq!(
        load_gltf(&path, None).expect("loads").mesh.vertex_count(),
        3
    );
    std::fs::remove_file(dir.path().join("tri angle.bin")).expect("remove");
    let error = load_gltf(&path, None).expect_err("missing buffer");
    assert!(
        error.to_string().contains("buffer 0: ") && error.to_string().contains("tri angle.bin")
    );
}

#[test]
fn the_scene_is_the_one_asked_for_else_the_default_else_the_first() {
    let mut document = triangle_file(
        json!([{ "mesh": 0 }, { "mesh": 0, "translation": [5, 0, 0] }]),
        &[0],
    );
    document["scenes"] =
        json!([{ "nodes": [0], "name": "first" }, { "nodes": [1], "name": "second" }]);
    let dir = ObjDir::new();
    let path = write(&dir, "two.gltf", &document);
    let first = load_gltf(&path, None).expect("scene 0");
    assert_eq!(
        (first.scene, first.scene_name.as_deref()),
        (0, Some("first"))
    );
    let second = load_gltf(&path, Some(1)).expect("scene 1");
    assert_eq!(second.mesh.bounds().min.x, 5.0);
    document["scene"] = json!(1);
    let path = write(&dir, "default.gltf", &document);
    assert_eq!(load_gltf(&path, None).expect("the default").scene, 1);
    let error = load_gltf(&path, Some(2)).expect_err("no scene 2");
    assert!(
        error
            .to_string()
            .contains("there is no scene 2; the file has 2 scenes")
    );
}

/// A file of a 10 × 10 ground at y = 0 with a perspective camera, a sun, a spot and a point light
/// (range 7.5) whose node hangs from a translated, turned and scaled parent.
fn lit_file(camera: Value) -> Value {
    let mut builder = Builder::default();
    let positions = builder.vec3(&[
        [-5.0, 0.0, 5.0],
        [5.0, 0.0, 5.0],
        [5.0, 0.0, -5.0],
        [-5.0, 0.0, -5.0],
    ]);
    let indices = builder.indices(&[0, 1, 2, 0, 2, 3], 5123);
    let half = std::f32::consts::FRAC_1_SQRT_2;
    builder.document(json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "directional", "name": "sun" },
            { "type": "spot", "name": "lamp", "range": 20.0, "spot": { "outerConeAngle": 0.5 } },
            { "type": "point", "name": "bulb", "range": 7.5 }
        ] } },
        "scenes": [{ "nodes": [0, 1, 2, 3, 5], "name": "lit" }],
        "nodes": [
            { "name": "ground", "mesh": 0 },
            { "name": "eye", "camera": 0, "translation": [0.0, 2.0, 10.0] },
            // −90° about x: the node's −z points down, its +z (toward the light) along +y.
            { "name": "sun", "rotation": [-half, 0.0, 0.0, half], "extensions": { "KHR_lights_punctual": { "light": 0 } } },
            { "name": "lamp", "translation": [0.0, 8.0, 0.0], "rotation": [-half, 0.0, 0.0, half], "extensions": { "KHR_lights_punctual": { "light": 1 } } },
            { "name": "bulb", "translation": [0.1, 1.0, 0.0], "extensions": { "KHR_lights_punctual": { "light": 2 } } },
            // 180° about y and scaled by 2: the bulb's (0.1, 1, 0) becomes (−0.2, 2, 0).
            { "name": "fixture", "translation": [0.5, 3.0, -1.0], "rotation": [0.0, 1.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [4] }
        ],
        "cameras": [camera],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": positions }, "indices": indices }] }],
    }))
}

#[test]
fn cameras_and_lights_are_placed_by_their_nodes() {
    let camera = json!({ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.5, "zfar": 50.0, "aspectRatio": 1.5 } });
    let dir = ObjDir::new();
    let path = write(&dir, "lit.gltf", &lit_file(camera));
    let import = load_gltf(&path, None).expect("loads");
    let camera = &import.cameras[0];
    assert_eq!(camera.pose.eye(), dvec3(0.0, 2.0, 10.0));
    assert_eq!(camera.pose.forward(), DVec3::NEG_Z);
    assert_eq!(import.lights.len(), 3);
    match &import.lights[0].kind {
        GltfLightKind::Directional { to_light } => assert!((*to_light - DVec3::Y).length() < 1e-7),
        other => panic!("{other:?}"),
    }
    match &import.lights[1].kind {
        GltfLightKind::Spot { pose, cone, range } => {
            assert_eq!(pose.eye(), dvec3(0.0, 8.0, 0.0));
            assert!((pose.forward() - DVec3::NEG_Y).length() < 1e-7);
            assert_eq!((*cone, *range), (1.0, Some(20.0)));
        }
        other => panic!("{other:?}"),
    }
    // The point light is at its node's world origin, composed in f64 through the parent's
    // translation, rotation and scale: (0.5, 3, −1) + (−2·0.1, 2·1, 0), 0.1 the f32 nearest. Its
    // range is the file's, unscaled (KHR_lights_punctual: light properties are unaffected by node
    // transforms).
    let bulb = dvec3(0.5 - 2.0 * f64::from(0.1_f32), 5.0, -1.0);
    assert_eq!(
        import.lights[2].kind,
        GltfLightKind::Point {
            position: bulb,
            range: Some(7.5)
        }
    );
    assert_eq!(import.lights[2].node.to_string(), "node 4 'bulb'");
    assert_eq!(import.lights[2].light.to_string(), "light 2 'bulb'");
    assert_eq!(import.warnings, []);

    // As a scene: the file's camera with the default image, its three lights; the differing
    // aspect ratio is a warning, and load_scene refuses it.
    let loaded = load_gltf_scene(&path, None).expect("a scene");
    let scene = &loaded.scene;
    assert_eq!(scene.name, "lit");
    assert_eq!([scene.camera.width, scene.camera.height], DEFAULT_IMAGE);
    let projection = &scene.camera.projection;
    assert_eq!(projection.fov_y(), f64::from(0.8_f32));
    assert_eq!((projection.near(), projection.far()), (0.5, 50.0));
    assert_eq!(projection.aspect(), 1024.0 / 768.0);
    match &scene.lights[1] {
        SceneLight::Spot { cone, .. } => {
            assert_eq!((cone.fov_y(), cone.far()), (1.0, 20.0));
            assert!(cone.near() > 0.0 && cone.near() < 8.0);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        scene.lights[2],
        SceneLight::Point {
            position: bulb,
            range: Some(7.5)
        }
    );
    let kinds: Vec<_> = loaded.warnings.iter().map(|w| w.skipped.clone()).collect();
    assert_eq!(
        kinds,
        [GltfSkipped::AspectRatio {
            file: 1.5,
            width: 1024,
            height: 768
        }]
    );
    assert_eq!(load_scene_with_warnings(&path).expect("the same"), loaded);
    match load_scene(&path) {
        Err(error @ SceneFileError::Skipped { .. }) => {
            let text = error.to_string();
            assert!(
                text.contains("lit.gltf: holds what shadowlab cannot represent and would skip")
                    && text.contains("aspectRatio 1.5 not used")
                    && !text.contains("point light"),
                "{text}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_point_light_s_range_is_optional_and_must_be_positive() {
    let camera = json!({ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.5, "zfar": 50.0 } });
    let dir = ObjDir::new();
    // Without a range: unlimited (KHR_lights_punctual: an undefined range is infinite).
    let mut document = lit_file(camera.clone());
    document["extensions"]["KHR_lights_punctual"]["lights"][2]
        .as_object_mut()
        .expect("a light")
        .remove("range");
    let scene = load_gltf_scene(&write(&dir, "unlimited.gltf", &document), None)
        .expect("a scene")
        .scene;
    assert!(
        matches!(scene.lights[2], SceneLight::Point { range: None, position } if position.y == 5.0),
        "{:?}",
        scene.lights[2]
    );
    // A range must be > 0: an error naming the node, the light and the property.
    for range in [json!(0.0), json!(-3)] {
        let mut document = lit_file(camera.clone());
        document["extensions"]["KHR_lights_punctual"]["lights"][2]["range"] = range.clone();
        let error = load_gltf(&write(&dir, "bad.gltf", &document), None).expect_err("a bad range");
        let text = error.to_string();
        assert!(
            text.contains("bad.gltf: node 4 'bulb': light 2 'bulb': `range` (")
                && text.contains(") must be > 0"),
            "{range}: {text}"
        );
        assert!(
            matches!(
                &error,
                GltfError::Object {
                    problem: GltfProblem::OutOfRange {
                        property: "range",
                        ..
                    },
                    ..
                }
            ),
            "{error:?}"
        );
    }
}

#[test]
fn an_infinite_or_too_deep_projection_ends_just_beyond_the_scene() {
    let dir = ObjDir::new();
    let infinite = json!({ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.5 } });
    let scene = load_gltf_scene(&write(&dir, "a.gltf", &lit_file(infinite)), None)
        .expect("a scene")
        .scene;
    // The farthest corner of the ground's bounds lies 15 in front of the eye at z = 10.
    assert_eq!(scene.camera.projection.far(), 15.0 * 1.01);
    let deep = json!({ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 0.001, "zfar": 1e5 } });
    let loaded = load_gltf_scene(&write(&dir, "b.gltf", &lit_file(deep)), None).expect("a scene");
    assert_eq!(loaded.scene.camera.projection.far(), 15.0 * 1.01);
    assert!(loaded.warnings.iter().any(|w| w.skipped
        == GltfSkipped::FarReduced {
            zfar: 1e5,
            far: 15.0 * 1.01
        }));
    let too_deep = json!({ "type": "perspective", "perspective": { "yfov": 0.8, "znear": 1e-6, "zfar": 1e5 } });
    let error =
        load_gltf_scene(&write(&dir, "c.gltf", &lit_file(too_deep)), None).expect_err("too deep");
    assert!(
        error
            .to_string()
            .contains("node 1 'eye': camera 0: `znear`")
            && error.to_string().contains("MAX_DEPTH_RATIO"),
        "{error}"
    );
}

#[test]
fn without_camera_and_lights_a_gltf_scene_takes_the_scene_file_defaults() {
    let dir = ObjDir::new();
    let path = write(
        &dir,
        "bare.gltf",
        &triangle_file(json!([{ "mesh": 0 }]), &[0]),
    );
    let scene = load_scene(&path).expect("a scene");
    assert_eq!(scene.name, "bare");
    // The same camera and sun as a scene file with this mesh and neither [camera] nor [[light]].
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let toml =
        load_scene(&dir.write("bare.toml", "[[mesh]]\nobj = \"tri.obj\"\n")).expect("a scene");
    assert_eq!(scene.camera, toml.camera);
    assert_eq!(scene.lights, toml.lights);
    match scene.lights[0] {
        SceneLight::Directional { to_light } => {
            assert!((to_light + DEFAULT_SUN_DIRECTION.normalize()).length() < 1e-15);
        }
        SceneLight::Spot { .. } | SceneLight::Point { .. } => panic!("the default sun"),
    }
}

#[test]
fn a_scene_file_entry_reads_a_gltf_scene_with_its_transform() {
    let dir = ObjDir::new();
    let mut document = triangle_file(
        json!([{ "mesh": 0 }, { "mesh": 0, "translation": [0, 0, 5] }]),
        &[0],
    );
    document["scenes"] = json!([{ "nodes": [0] }, { "nodes": [0, 1] }]);
    write(&dir, "parts.gltf", &document);
    let path = dir.write(
        "scene.toml",
        "[[mesh]]\ngltf = \"parts.gltf\"\ngltf_scene = 1\ntranslate = [10, 0, 0]\n\n[[mesh]]\nshape = \"plane\"\nsize = [40, 40]\n",
    );
    let scene = load_scene(&path).expect("a scene");
    assert_eq!(scene.mesh.group_names(), ["parts", "plane"]);
    assert_eq!(scene.mesh.groups().iter().filter(|g| **g == 0).count(), 2);
    assert_eq!(scene.mesh.positions()[3], dvec3(10.0, 0.0, 5.0));
    for (text, fragment) in [
        (
            "[[mesh]]\ngltf = \"parts.gltf\"\nobj = \"a.obj\"\n",
            "mesh[0].obj and mesh[0].gltf exclude each other",
        ),
        (
            "[[mesh]]\nshape = \"box\"\ngltf_scene = 0\n",
            "mesh[0].gltf_scene does not apply to shape \"box\"",
        ),
        (
            "[[mesh]]\ngltf = \"parts.gltf\"\ngltf_scen = 0\n",
            "unknown field `gltf_scen`",
        ),
        (
            "[[mesh]]\ngltf = \"parts.gltf\"\nradius = 1\n",
            "mesh[0].radius does not apply to a gltf mesh",
        ),
        (
            "[[mesh]]\ngltf = \"parts.gltf\"\ngltf_scene = 7\n",
            "mesh[0].gltf: ",
        ),
        ("[[mesh]]\ngltf = \"none.glb\"\n", "none.glb"),
    ] {
        let error = load_scene(&dir.write("bad.toml", text)).expect_err(text);
        assert!(error.to_string().contains(fragment), "{text}: {error}");
    }
    let error = load_scene(&dir.write(
        "bad.toml",
        "[[mesh]]\ngltf = \"parts.gltf\"\ngltf_scene = 7\n",
    ))
    .expect_err("no scene 7");
    assert!(error.to_string().contains("there is no scene 7"), "{error}");
    assert!(Path::new(&dir.path().join("parts.gltf")).exists());
}

/// A camera's `extras.shadowlab.image` (shadowlab's export writes it) sets the image size, so an
/// aspect ratio that agrees with it is no warning; other extras are the application's and
/// ignored; a malformed or out-of-range size is an error naming the camera and the property.
#[test]
fn a_camera_s_shadowlab_extras_set_its_image() {
    let dir = ObjDir::new();
    let with_extras = |extras: Value| {
        json!({ "type": "perspective", "extras": extras,
                "perspective": { "yfov": 0.8, "znear": 0.5, "zfar": 50.0, "aspectRatio": 1.5 } })
    };
    let path = write(
        &dir,
        "sized.gltf",
        &lit_file(with_extras(json!({ "shadowlab": { "image": [96, 64] } }))),
    );
    let loaded = load_gltf_scene(&path, None).expect("a scene");
    let camera = &loaded.scene.camera;
    assert_eq!((camera.width, camera.height), (96, 64));
    assert_eq!(camera.projection.aspect(), 1.5);
    assert_eq!(loaded.warnings, []);

    let path = write(
        &dir,
        "other.gltf",
        &lit_file(with_extras(json!({ "engine": { "image": "none" } }))),
    );
    let camera = load_gltf_scene(&path, None).expect("a scene").scene.camera;
    assert_eq!([camera.width, camera.height], DEFAULT_IMAGE);

    for (extras, expected) in [
        (
            json!({ "shadowlab": { "image": [96.5, 64] } }),
            "`extras.shadowlab.image` = [96.5,64], not [width, height] in whole pixels",
        ),
        (
            json!({ "shadowlab": {} }),
            "`extras.shadowlab` without an `image`",
        ),
        (
            json!({ "shadowlab": { "image": [0, 64] } }),
            "extras.shadowlab.image",
        ),
        (
            json!({ "shadowlab": { "image": [96, 20000] } }),
            "each side in 1..=16384 pixels",
        ),
    ] {
        let path = write(&dir, "bad.gltf", &lit_file(with_extras(extras)));
        let text = load_gltf_scene(&path, None).unwrap_err().to_string();
        assert!(
            text.contains("bad.gltf") && text.contains("camera 0") && text.contains(expected),
            "{text}"
        );
    }
}
