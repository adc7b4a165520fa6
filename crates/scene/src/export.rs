//! Scene export: an assembled [`Scene`] — its mesh in world space, its camera and its lights —
//! written as glTF 2.0 ([`export_glb`], [`export_gltf`]) or as OBJ ([`export_obj`]), so that
//! another renderer can draw the same frame. The functions return the file's bytes or text; the
//! caller writes them.
//!
//! # glTF
//! One node and one mesh per group of the scene's mesh (named by the group; a group without
//! triangles is not written), each a `TRIANGLES` primitive with `POSITION`, `NORMAL` and
//! `UNSIGNED_INT` indices over the vertices its triangles use (in their order in the scene's
//! mesh; vertices no triangle uses are not written), at the identity transform: positions are in
//! world space. The camera is a node with a perspective camera (`yfov`, `znear`, `zfar`, and
//! `aspectRatio` = image width / height, and the image size in its `extras` as
//! `{"shadowlab": {"image": [W, H]}}`, which the reader takes); each light a node with a `KHR_lights_punctual` light
//! (directional; spot with `outerConeAngle` = half the cone and `range` = the spot's far
//! distance; point, its node only translated to the position, with the light's `range` when it
//! has one: `KHR_lights_punctual`'s distance cutoff, which node transforms do not scale). The
//! scene's `name` is the glTF scene's name. A camera or light value that f32 cannot hold (a
//! coordinate beyond ±3.4·10³⁸, a distance that would round to 0) is an error,
//! [`ExportError::ValueOutOfF32Range`], not a file that would not read back.
//!
//! **Precision.** glTF stores f32: every position, normal, camera and light value is the f32
//! nearest the scene's f64 (node rotations are the f32 nearest the f64 quaternion of the pose;
//! a normal's coordinates may be an ulp off, so that reading the normal back and rounding it
//! again gives it back).
//! Reading the file back ([`crate::load_gltf_scene`]) gives exactly those f32 values as f64
//! positions, since the nodes' transforms are the identity; from such a re-imported scene on, the
//! mesh is a fixed point: exporting and reading it again gives the same mesh bit for bit
//! (positions, normals, triangles, groups) and the same projections, while camera and light
//! directions, re-derived from f32 rotations, agree to f32 precision (tested). What glTF does not
//! hold is lost: a spot light's near distance (the reader derives it from the bounds) and the
//! `[shadow]` settings.
//!
//! # OBJ
//! `v` and `vn` lines for every vertex in order, then per group a `g` line with the group's name
//! and its triangles as `f a//a b//b c//c`. Numbers are Rust's shortest round-trip form (`{:?}`),
//! so [`crate::load_obj`] reads back every position bit for bit. Camera and lights, which OBJ
//! has no statements for, are in a comment header, also at full precision (the header of a scene,
//! its numbers made up):
//!
//! ```text
//! # shadowlab scene "outdoor"
//! # camera eye 0.0 1.8 0.0
//! # camera forward 0.0 0.0 -1.0
//! # camera up 0.0 1.0 0.0
//! # camera fov_y 1.0471975511965976 aspect 1.3333333333333333 near 1.0 far 400.0
//! # camera image 1024 768
//! # light 0 directional to_light 0.5 0.8 0.3
//! # light 1 spot eye 1.0 2.0 3.0 forward 0.0 -1.0 0.0 up 0.0 0.0 -1.0 cone 0.5 near 1.0 far 9.0
//! # light 2 point position 0.0 2.5 -0.5 range 8.0
//! # light 3 point position 4.0 3.0 1.0
//! ```
//!
//! Vectors are world space (right-handed, y up); `fov_y` and `cone` are full angles in radians;
//! `to_light` is the unit vector toward a directional light (it travels along the negation);
//! a camera or spot looks along `forward` with `up` up; a point light's ` range R` is left out
//! when it has none (unlimited). Group names have line breaks and other control characters
//! replaced by `_`.

use std::fmt;

use base64::Engine as _;
use glam::{DMat3, DQuat, DVec3};
use serde_json::{Value, json};
use shadowlab_hull::ViewPose;

use crate::mesh::Mesh;
use crate::normals;
use crate::scene::{Scene, SceneLight};

/// Why a scene could not be exported.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum ExportError {
    /// A coordinate beyond the f32 range (±3.4·10³⁸), which glTF cannot store.
    OutOfF32Range {
        /// The vertex.
        vertex: usize,
        /// The coordinate.
        value: f64,
    },
    /// A camera or light value that glTF's f32 cannot hold: a coordinate beyond the f32 range, or
    /// a distance (`znear`, `zfar`, a light's `range`) that is not a positive finite f32 once
    /// rounded (glTF and `KHR_lights_punctual` require them > 0). Written anyway, the file would
    /// hold `null` or `0` there and not read back.
    ValueOutOfF32Range {
        /// What the value is, e.g. `light 1 position` or `camera znear`.
        what: String,
        /// The value (a coordinate of a vector).
        value: f64,
    },
    /// A directional light whose `to_light` is zero or not finite (only a hand-built
    /// [`SceneLight`] can be).
    InvalidLight {
        /// The light's index in the scene.
        index: usize,
    },
    /// A GLB file larger than its u32 length field can state (4 GiB).
    TooLarge {
        /// The bytes it would have.
        bytes: u64,
    },
}

impl fmt::Display for ExportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::OutOfF32Range { vertex, value } => write!(
                f,
                "vertex {vertex} has the coordinate {value:e}, beyond the f32 range glTF stores"
            ),
            Self::ValueOutOfF32Range { what, value } => write!(
                f,
                "{what} has the value {value:e}, which glTF's f32 cannot hold (beyond its range, \
                 or a distance that would round to 0)"
            ),
            Self::InvalidLight { index } => write!(
                f,
                "light {index} is a directional light without a direction (to_light is zero or \
                 not finite)"
            ),
            Self::TooLarge { bytes } => write!(
                f,
                "the GLB file would have {bytes} bytes, more than its length field can state \
                 (2^32 − 1)"
            ),
        }
    }
}

impl std::error::Error for ExportError {}

/// The scene as a binary glTF (`.glb`) file: the JSON chunk and one binary chunk holding the
/// buffer (glTF 2.0 §4).
///
/// # Errors
/// [`ExportError::OutOfF32Range`], [`ExportError::ValueOutOfF32Range`],
/// [`ExportError::InvalidLight`], [`ExportError::TooLarge`].
pub fn export_glb(scene: &Scene) -> Result<Vec<u8>, ExportError> {
    let (document, mut bin) = document(scene, None)?;
    let mut json = document.to_string().into_bytes();
    pad(&mut json, b' ');
    pad(&mut bin, 0);
    let total = 12 + 8 + json.len() as u64 + 8 + bin.len() as u64;
    let too_large = || ExportError::TooLarge { bytes: total };
    let length = u32::try_from(total).map_err(|_| too_large())?;
    let chunk_length = |chunk: &[u8]| u32::try_from(chunk.len()).map_err(|_| too_large());
    let mut file = Vec::with_capacity(usize::try_from(total).unwrap_or(0));
    file.extend_from_slice(b"glTF");
    file.extend_from_slice(&2_u32.to_le_bytes());
    file.extend_from_slice(&length.to_le_bytes());
    file.extend_from_slice(&chunk_length(&json)?.to_le_bytes());
    file.extend_from_slice(b"JSON");
    file.extend_from_slice(&json);
    file.extend_from_slice(&chunk_length(&bin)?.to_le_bytes());
    file.extend_from_slice(b"BIN\0");
    file.extend_from_slice(&bin);
    Ok(file)
}

/// The scene as a `.gltf` file with its buffer embedded as a base64 `data:` URI.
///
/// # Errors
/// [`ExportError::OutOfF32Range`], [`ExportError::ValueOutOfF32Range`],
/// [`ExportError::InvalidLight`].
pub fn export_gltf(scene: &Scene) -> Result<String, ExportError> {
    let (document, _) = document(scene, Some(()))?;
    Ok(document.to_string())
}

/// Pads `bytes` with `with` to a multiple of four (GLB chunks are 4-byte aligned).
fn pad(bytes: &mut Vec<u8>, with: u8) {
    while !bytes.len().is_multiple_of(4) {
        bytes.push(with);
    }
}

/// An f64 as the f32 glTF stores, as a JSON number.
#[expect(
    clippy::cast_possible_truncation,
    reason = "glTF stores f32: the value is rounded to the nearest f32, as documented"
)]
fn f32_value(value: f64) -> Value {
    json!(value as f32)
}

/// The rotation taking the node axes x, y, z to `right`, `up`, `back` (a rotation matrix's
/// columns), as the f32 `[x, y, z, w]` of a unit quaternion.
fn rotation(right: DVec3, up: DVec3, back: DVec3) -> Value {
    let q = DQuat::from_mat3(&DMat3::from_cols(right, up, back)).normalize();
    Value::Array([q.x, q.y, q.z, q.w].into_iter().map(f32_value).collect())
}

/// A point as the f32 translation glTF stores, if each coordinate is within the f32 range; else
/// [`ExportError::ValueOutOfF32Range`] naming it `what`.
fn f32_point(point: DVec3, what: &str) -> Result<Value, ExportError> {
    match to_f32(point)
        .iter()
        .zip(point.to_array())
        .find(|(f, _)| !f.is_finite())
    {
        Some((_, value)) => Err(ExportError::ValueOutOfF32Range {
            what: what.to_owned(),
            value,
        }),
        None => Ok(Value::Array(point.to_array().map(f32_value).to_vec())),
    }
}

/// A positive distance as the f32 glTF stores, if that is positive and finite; else
/// [`ExportError::ValueOutOfF32Range`] naming it `what`.
#[expect(
    clippy::cast_possible_truncation,
    reason = "glTF stores f32: the value is rounded to the nearest f32, as documented"
)]
fn f32_distance(value: f64, what: &str) -> Result<Value, ExportError> {
    let stored = value as f32;
    if stored > 0.0 && stored.is_finite() {
        Ok(json!(stored))
    } else {
        Err(ExportError::ValueOutOfF32Range {
            what: what.to_owned(),
            value,
        })
    }
}

/// A node at `pose`: its eye, and its −z along the pose's forward, its +y along its up.
fn posed_node(name: &str, pose: &ViewPose) -> Result<Value, ExportError> {
    Ok(json!({
        "name": name,
        "translation": f32_point(pose.eye(), &format!("{name} position"))?,
        "rotation": rotation(pose.right(), pose.up(), -pose.forward()),
    }))
}

/// The glTF JSON of `scene` and its buffer; the buffer is embedded as a data URI if `embed` is
/// given, else left to a GLB binary chunk.
fn document(scene: &Scene, embed: Option<()>) -> Result<(Value, Vec<u8>), ExportError> {
    let mesh = &scene.mesh;
    check_f32_range(mesh)?;
    let mut buffer = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    let mut nodes = Vec::new();
    for (group, name) in mesh.group_names().iter().enumerate() {
        let triangles: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .zip(mesh.groups())
            .filter(|(_, g)| **g as usize == group)
            .map(|(t, _)| *t)
            .collect();
        if triangles.is_empty() {
            continue;
        }
        let (vertices, local) = local_vertices(mesh.vertex_count(), &triangles);
        let positions: Vec<[f32; 3]> = vertices
            .iter()
            .map(|&v| to_f32(mesh.positions()[v]))
            .collect();
        let normals: Vec<[f32; 3]> = vertices
            .iter()
            .map(|&v| stored_normal(mesh.normals()[v]))
            .collect();
        let (min, max) = positions.iter().fold(
            ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
            |(min, max), p| {
                (
                    std::array::from_fn(|k| min[k].min(p[k])),
                    std::array::from_fn(|k| max[k].max(p[k])),
                )
            },
        );
        let accessor = accessors.len();
        let mut add = |bytes: Vec<u8>, count: usize, kind: &str, component: u32, target: u32| {
            views.push(json!({
                "buffer": 0,
                "byteOffset": buffer.len(),
                "byteLength": bytes.len(),
                "target": target,
            }));
            accessors.push(json!({
                "bufferView": views.len() - 1,
                "componentType": component,
                "count": count,
                "type": kind,
            }));
            buffer.extend_from_slice(&bytes);
        };
        const FLOAT: u32 = 5126;
        const UNSIGNED_INT: u32 = 5125;
        const ARRAY_BUFFER: u32 = 34962;
        const ELEMENT_ARRAY_BUFFER: u32 = 34963;
        let floats = |values: &[[f32; 3]]| {
            values
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect::<Vec<u8>>()
        };
        add(
            floats(&positions),
            positions.len(),
            "VEC3",
            FLOAT,
            ARRAY_BUFFER,
        );
        add(floats(&normals), normals.len(), "VEC3", FLOAT, ARRAY_BUFFER);
        let indices: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|&v| local[v as usize].to_le_bytes())
            .collect();
        add(
            indices,
            3 * triangles.len(),
            "SCALAR",
            UNSIGNED_INT,
            ELEMENT_ARRAY_BUFFER,
        );
        accessors[accessor]["min"] = json!(min);
        accessors[accessor]["max"] = json!(max);
        nodes.push(json!({ "name": name, "mesh": meshes.len() }));
        meshes.push(json!({
            "name": name,
            "primitives": [{
                "attributes": { "POSITION": accessor, "NORMAL": accessor + 1 },
                "indices": accessor + 2,
                "mode": 4,
            }],
        }));
    }
    let camera = &scene.camera;
    let mut camera_node = posed_node("camera", &camera.pose)?;
    camera_node["camera"] = json!(0);
    nodes.push(camera_node);
    let projection = &camera.projection;
    let cameras = json!([{
        "type": "perspective",
        "perspective": {
            "yfov": f32_value(projection.fov_y()),
            "znear": f32_distance(projection.near(), "camera znear")?,
            "zfar": f32_distance(projection.far(), "camera zfar")?,
            "aspectRatio": f32_value(f64::from(camera.width) / f64::from(camera.height)),
        },
        "extras": { "shadowlab": { "image": [camera.width, camera.height] } },
    }]);
    let mut lights = Vec::new();
    for (index, light) in scene.lights.iter().enumerate() {
        let name = format!("light {index}");
        let (mut node, light) = match light {
            SceneLight::Directional { to_light } => {
                let hint = if to_light.y.abs() >= to_light.x.abs().max(to_light.z.abs()) {
                    DVec3::NEG_Z
                } else {
                    DVec3::Y
                };
                // The hint is never parallel to a unit to_light: it is across its largest axis.
                let pose = ViewPose::look_to(DVec3::ZERO, -*to_light, hint)
                    .map_err(|_| ExportError::InvalidLight { index })?;
                let node = json!({
                    "name": name,
                    "rotation": rotation(pose.right(), pose.up(), -pose.forward()),
                });
                (node, json!({ "type": "directional" }))
            }
            SceneLight::Spot { pose, cone } => (
                posed_node(&name, pose)?,
                json!({
                    "type": "spot",
                    "range": f32_distance(cone.far(), &format!("{name} range (its far distance)"))?,
                    "spot": { "innerConeAngle": 0.0, "outerConeAngle": f32_value(0.5 * cone.fov_y()) },
                }),
            ),
            SceneLight::Point { position, range } => {
                // Only a translation: a point light ignores its node's rotation and scale.
                let node = json!({
                    "name": name,
                    "translation": f32_point(*position, &format!("{name} position"))?,
                });
                let mut light = json!({ "type": "point" });
                if let Some(range) = range {
                    light["range"] = f32_distance(*range, &format!("{name} range"))?;
                }
                (node, light)
            }
        };
        node["extensions"] = json!({ "KHR_lights_punctual": { "light": index } });
        nodes.push(node);
        lights.push(light);
    }
    let mut buffer_json = json!({ "byteLength": buffer.len() });
    if embed.is_some() {
        let data = base64::engine::general_purpose::STANDARD.encode(&buffer);
        buffer_json["uri"] = json!(format!("data:application/octet-stream;base64,{data}"));
    }
    let mut document = json!({
        "asset": {
            "version": "2.0",
            "generator": concat!("shadowlab-scene ", env!("CARGO_PKG_VERSION")),
        },
        "scene": 0,
        "scenes": [{ "name": scene.name, "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": meshes,
        "cameras": cameras,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [buffer_json],
    });
    if !lights.is_empty() {
        document["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        document["extensions"] = json!({ "KHR_lights_punctual": { "lights": lights } });
    }
    Ok((document, buffer))
}

/// The vertices `triangles` use, ascending, and each one's index among them (by vertex).
fn local_vertices(vertex_count: usize, triangles: &[[u32; 3]]) -> (Vec<usize>, Vec<u32>) {
    let mut used = vec![false; vertex_count];
    for &v in triangles.iter().flatten() {
        used[v as usize] = true;
    }
    let vertices: Vec<usize> = (0..vertex_count).filter(|&v| used[v]).collect();
    let mut local = vec![0_u32; vertex_count];
    for (index, &v) in vertices.iter().enumerate() {
        // At most vertex_count ≤ 2³² entries, each below it.
        local[v] = u32::try_from(index).unwrap_or(u32::MAX);
    }
    (vertices, local)
}

/// A vector as the f32 glTF stores (each coordinate rounded to the nearest f32).
#[expect(
    clippy::cast_possible_truncation,
    reason = "glTF stores f32: each coordinate is rounded to the nearest f32, as documented"
)]
fn to_f32(v: DVec3) -> [f32; 3] {
    v.to_array().map(|c| c as f32)
}

/// The f32 normal written for the unit normal `n`: of its f32 rounding and the f32 values an ulp
/// either side in each coordinate, the one nearest `n` that reading back — normalising in f64 as
/// [`crate::load_gltf`] and [`Mesh::with_normals`] do — and rounding again reproduces, so that a
/// re-exported re-import has the same normals; the f32 rounding itself if none does.
fn stored_normal(n: DVec3) -> [f32; 3] {
    let nearest = to_f32(n);
    let read_back = |q: [f32; 3]| {
        normals::unit(DVec3::from_array(q.map(f64::from)))
            .and_then(normals::unit)
            .map(to_f32)
    };
    let around = |c: f32| [c, c.next_down(), c.next_up()];
    let mut best: Option<([f32; 3], f64)> = None;
    for x in around(nearest[0]) {
        for y in around(nearest[1]) {
            for z in around(nearest[2]) {
                let q = [x, y, z];
                if read_back(q) != Some(q) {
                    continue;
                }
                let distance = (DVec3::from_array(q.map(f64::from)) - n).length();
                if best.is_none_or(|(_, d)| distance < d) {
                    best = Some((q, distance));
                }
            }
        }
    }
    best.map_or(nearest, |(q, _)| q)
}

/// [`ExportError::OutOfF32Range`] for the first coordinate whose f32 is infinite.
fn check_f32_range(mesh: &Mesh) -> Result<(), ExportError> {
    for (vertex, p) in mesh.positions().iter().enumerate() {
        if let Some(&value) = to_f32(*p)
            .iter()
            .zip(p.to_array().iter())
            .find(|(f, _)| !f.is_finite())
            .map(|(_, value)| value)
        {
            return Err(ExportError::OutOfF32Range { vertex, value });
        }
    }
    Ok(())
}

/// The scene as OBJ text, with the camera and lights in a comment header (see the [module
/// documentation](self)).
#[must_use]
pub fn export_obj(scene: &Scene) -> String {
    let vector = |v: DVec3| format!("{:?} {:?} {:?}", v.x, v.y, v.z);
    let camera = &scene.camera;
    let projection = &camera.projection;
    let mut lines = vec![
        format!("# shadowlab scene {:?}", scene.name),
        format!("# camera eye {}", vector(camera.pose.eye())),
        format!("# camera forward {}", vector(camera.pose.forward())),
        format!("# camera up {}", vector(camera.pose.up())),
        format!(
            "# camera fov_y {:?} aspect {:?} near {:?} far {:?}",
            projection.fov_y(),
            projection.aspect(),
            projection.near(),
            projection.far()
        ),
        format!("# camera image {} {}", camera.width, camera.height),
    ];
    for (index, light) in scene.lights.iter().enumerate() {
        lines.push(match light {
            SceneLight::Directional { to_light } => {
                format!("# light {index} directional to_light {}", vector(*to_light))
            }
            SceneLight::Spot { pose, cone } => format!(
                "# light {index} spot eye {} forward {} up {} cone {:?} near {:?} far {:?}",
                vector(pose.eye()),
                vector(pose.forward()),
                vector(pose.up()),
                cone.fov_y(),
                cone.near(),
                cone.far()
            ),
            SceneLight::Point { position, range } => format!(
                "# light {index} point position {}{}",
                vector(*position),
                range.map_or_else(String::new, |r| format!(" range {r:?}"))
            ),
        });
    }
    let mesh = &scene.mesh;
    lines.extend(mesh.positions().iter().map(|p| format!("v {}", vector(*p))));
    lines.extend(mesh.normals().iter().map(|n| format!("vn {}", vector(*n))));
    for (group, name) in mesh.group_names().iter().enumerate() {
        let name: String = name
            .chars()
            .map(|c| if c.is_control() { '_' } else { c })
            .collect();
        lines.push(format!("g {name}"));
        lines.extend(
            mesh.triangles()
                .iter()
                .zip(mesh.groups())
                .filter(|(_, g)| **g as usize == group)
                .map(|(triangle, _)| {
                    let [a, b, c] = triangle.map(|v| u64::from(v) + 1);
                    format!("f {a}//{a} {b}//{b} {c}//{c}")
                }),
        );
    }
    let mut text = lines.join("\n");
    text.push('\n');
    text
}
