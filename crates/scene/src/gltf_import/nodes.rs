//! The node hierarchy of a scene (glTF 2.0 §3.5): each node's world transform, composed in f64
//! from the root down, and the cameras (§3.10) and `KHR_lights_punctual` lights its nodes carry.

use std::path::Path;

use glam::{DAffine3, DMat4, DQuat, DVec3};
use gltf::json::{self, validation::Checked};
use shadowlab_hull::ViewPose;

use super::error::{GltfError, GltfObject, GltfObjectKind, GltfProblem, GltfSkipped, GltfWarning};
use super::{GltfCamera, GltfLight, GltfLightKind};
use crate::limits::MIN_ANGLE_DEGREES;
use crate::normals;

/// A node of the scene and its world transform.
pub(super) struct Placed {
    /// The node's index.
    pub(super) node: usize,
    /// Its transform to world space: the product of its ancestors' and its own local transforms.
    pub(super) world: DAffine3,
}

/// Node `index` as an object for messages.
pub(super) fn node_object(root: &json::Root, index: usize) -> GltfObject {
    let name = root.nodes.get(index).and_then(|n| n.name.as_deref());
    GltfObject::new(GltfObjectKind::Node, index, name)
}

/// Every node of scene `scene`, depth first in the order of `scene.nodes` and of each node's
/// `children` (parents before children), with its world transform. A node reached twice (a
/// cycle, or a node with two parents) is an error: glTF 2.0 §3.5.2.
pub(super) fn walk(
    root: &json::Root,
    scene: &json::Scene,
    path: &Path,
) -> Result<Vec<Placed>, GltfError> {
    let mut visited = vec![false; root.nodes.len()];
    let mut placed = Vec::new();
    let mut stack: Vec<(usize, DAffine3)> = scene
        .nodes
        .iter()
        .rev()
        .map(|node| (node.value(), DAffine3::IDENTITY))
        .collect();
    while let Some((index, parent)) = stack.pop() {
        let error = |problem| GltfError::object(path, vec![node_object(root, index)], problem);
        let (Some(node), Some(seen)) = (root.nodes.get(index), visited.get_mut(index)) else {
            return Err(GltfError::Invalid {
                path: path.to_owned(),
                problems: vec![(format!("nodes[{index}]"), "index out of bounds".to_owned())],
            });
        };
        if *seen {
            return Err(error(GltfProblem::NodeRepeated));
        }
        *seen = true;
        let world = parent * local(node).map_err(error)?;
        if let Some(children) = &node.children {
            stack.extend(children.iter().rev().map(|child| (child.value(), world)));
        }
        placed.push(Placed { node: index, world });
    }
    Ok(placed)
}

/// A node's local transform (glTF 2.0 §3.5.3): its `matrix` (column-major, affine), or
/// T·R·S from `translation`, `rotation` (a quaternion, normalised in f64) and `scale`. Values are
/// f32 in the file and exact in f64.
fn local(node: &json::Node) -> Result<DAffine3, GltfProblem> {
    let trs_given = node.translation.is_some() || node.rotation.is_some() || node.scale.is_some();
    if let Some(matrix) = node.matrix {
        if trs_given {
            return Err(GltfProblem::Unusable {
                reason: "gives both `matrix` and translation, rotation or scale; glTF 2.0 §3.5.3 \
                         allows one of the two"
                    .to_owned(),
            });
        }
        if !matrix.iter().all(|v| v.is_finite()) {
            return Err(GltfProblem::NonFiniteTransform { property: "matrix" });
        }
        let row = [matrix[3], matrix[7], matrix[11], matrix[15]];
        if row != [0.0, 0.0, 0.0, 1.0] {
            return Err(GltfProblem::NotAffine { row });
        }
        return Ok(DAffine3::from_mat4(DMat4::from_cols_array(
            &matrix.map(f64::from),
        )));
    }
    let vector = |values: Option<[f32; 3]>, default: DVec3, property| match values {
        None => Ok(default),
        Some(v) if v.iter().all(|c| c.is_finite()) => Ok(DVec3::from_array(v.map(f64::from))),
        Some(_) => Err(GltfProblem::NonFiniteTransform { property }),
    };
    let translation = vector(node.translation, DVec3::ZERO, "translation")?;
    let scale = vector(node.scale, DVec3::ONE, "scale")?;
    let rotation = match &node.rotation {
        None => DQuat::IDENTITY,
        Some(q) => {
            if !q.0.iter().all(|c| c.is_finite()) {
                return Err(GltfProblem::NonFiniteTransform {
                    property: "rotation",
                });
            }
            let [x, y, z, w] = q.0.map(f64::from);
            let q = DQuat::from_xyzw(x, y, z, w);
            let length = q.length();
            if length == 0.0 {
                return Err(GltfProblem::ZeroRotation);
            }
            q / length
        }
    };
    Ok(DAffine3::from_scale_rotation_translation(
        scale,
        rotation,
        translation,
    ))
}

/// The pose of a camera or spot light at a node: at the node's origin, looking down its −z with
/// its +y up (glTF 2.0 §3.10.1, `KHR_lights_punctual`).
fn pose_of(world: &DAffine3) -> Result<ViewPose, GltfProblem> {
    let eye = world.translation;
    let forward = world.matrix3 * DVec3::NEG_Z;
    let up = world.matrix3 * DVec3::Y;
    ViewPose::look_to(eye, forward, up).map_err(|error| GltfProblem::Unusable {
        reason: format!("the node's world transform gives it no orientation ({error})"),
    })
}

/// The smallest field of view or cone, radians.
fn min_angle() -> f64 {
    MIN_ANGLE_DEGREES.to_radians()
}

/// `value` (f32 in the file) as f64, if `accept` holds; else [`GltfProblem::OutOfRange`].
fn checked(
    property: &'static str,
    value: f32,
    accept: impl Fn(f64) -> bool,
    requirement: impl FnOnce() -> String,
) -> Result<f64, GltfProblem> {
    let value = f64::from(value);
    if value.is_finite() && accept(value) {
        Ok(value)
    } else {
        Err(GltfProblem::OutOfRange {
            property,
            value,
            requirement: requirement(),
        })
    }
}

/// The perspective camera of `placed`'s node, if it has one; an orthographic camera is a warning.
/// `yfov` must be in [[`MIN_ANGLE_DEGREES`], 180°), `znear` > 0, a `zfar` beyond `znear`, an
/// `aspectRatio` > 0 (the far/near ratio is checked where the scene is assembled, which may
/// bring a far plane beyond the scene closer).
pub(super) fn camera(
    root: &json::Root,
    placed: &Placed,
    path: &Path,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Option<GltfCamera>, GltfError> {
    let node_object = node_object(root, placed.node);
    let Some(index) = root.nodes.get(placed.node).and_then(|n| n.camera) else {
        return Ok(None);
    };
    let index = index.value();
    let Some(json_camera) = root.cameras.get(index) else {
        return Err(GltfError::Invalid {
            path: path.to_owned(),
            problems: vec![(
                format!("nodes[{}].camera", placed.node),
                "index out of bounds".to_owned(),
            )],
        });
    };
    let camera_object = GltfObject::new(GltfObjectKind::Camera, index, json_camera.name.as_deref());
    let objects = vec![node_object.clone(), camera_object.clone()];
    let error = |problem| GltfError::object(path, objects.clone(), problem);
    let perspective = match (json_camera.type_, &json_camera.perspective) {
        (Checked::Valid(json::camera::Type::Perspective), Some(perspective)) => perspective,
        (Checked::Valid(json::camera::Type::Orthographic), _) => {
            warnings.push(GltfWarning {
                path: path.to_owned(),
                objects: objects.clone(),
                skipped: GltfSkipped::OrthographicCamera,
            });
            return Ok(None);
        }
        _ => {
            return Err(error(GltfProblem::Unusable {
                reason: "is a perspective camera without a `perspective` object".to_owned(),
            }));
        }
    };
    let pi = std::f64::consts::PI;
    let fov_y = checked(
        "yfov",
        perspective.yfov,
        |v| (min_angle()..pi).contains(&v),
        || {
            format!(
                "in [{}, π) radians ({}° = MIN_ANGLE_DEGREES, to 180°)",
                min_angle(),
                MIN_ANGLE_DEGREES
            )
        },
    )
    .map_err(error)?;
    let near =
        checked("znear", perspective.znear, |v| v > 0.0, || "> 0".to_owned()).map_err(error)?;
    let far = perspective
        .zfar
        .map(|zfar| {
            checked(
                "zfar",
                zfar,
                |v| v > near,
                || format!("beyond znear ({near})"),
            )
        })
        .transpose()
        .map_err(error)?;
    let aspect_ratio = perspective
        .aspect_ratio
        .map(|aspect| checked("aspectRatio", aspect, |v| v > 0.0, || "> 0".to_owned()))
        .transpose()
        .map_err(error)?;
    let image = shadowlab_image(json_camera.extras.as_deref()).map_err(error)?;
    let pose = pose_of(&placed.world).map_err(error)?;
    Ok(Some(GltfCamera {
        node: node_object,
        camera: camera_object,
        pose,
        fov_y,
        near,
        far,
        aspect_ratio,
        image,
    }))
}

/// The image size a camera's `extras` record under `shadowlab.image` (shadowlab's export writes
/// it: glTF cameras have an aspect ratio, not a size); `None` where the extras are absent, not an
/// object, or hold no `shadowlab` key — those are the application's.
fn shadowlab_image(
    extras: Option<&serde_json::value::RawValue>,
) -> Result<Option<[u32; 2]>, GltfProblem> {
    let Some(extras) = extras else {
        return Ok(None);
    };
    let Ok(serde_json::Value::Object(extras)) = serde_json::from_str(extras.get()) else {
        return Ok(None);
    };
    let Some(shadowlab) = extras.get("shadowlab") else {
        return Ok(None);
    };
    let image = shadowlab
        .get("image")
        .ok_or_else(|| GltfProblem::Unusable {
            reason: "has `extras.shadowlab` without an `image` [width, height]".to_owned(),
        })?;
    serde_json::from_value::<[u32; 2]>(image.clone())
        .map(Some)
        .map_err(|_| GltfProblem::Unusable {
            reason: format!(
                "has `extras.shadowlab.image` = {image}, not [width, height] in whole pixels"
            ),
        })
}

/// The `KHR_lights_punctual` light of `placed`'s node, if it has one that shadowlab represents:
/// a directional light, a point light (at the node's world position; rotation and scale are
/// ignored but for their effect on it, and `range` is taken as it is, as `KHR_lights_punctual`
/// says: light properties are unaffected by node transforms), or a spot light whose cone (twice
/// `outerConeAngle`) is below 180°. Wider spots are warnings. A `range` must be > 0.
pub(super) fn light(
    root: &json::Root,
    placed: &Placed,
    path: &Path,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Option<GltfLight>, GltfError> {
    let node_object = node_object(root, placed.node);
    let Some(index) = root
        .nodes
        .get(placed.node)
        .and_then(|n| n.extensions.as_ref())
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .map(|l| l.light.value())
    else {
        return Ok(None);
    };
    let json_light = root
        .extensions
        .as_ref()
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .and_then(|l| l.lights.get(index));
    let Some(json_light) = json_light else {
        return Err(GltfError::Invalid {
            path: path.to_owned(),
            problems: vec![(
                format!(
                    "nodes[{}].extensions.KHR_lights_punctual.light",
                    placed.node
                ),
                "index out of bounds".to_owned(),
            )],
        });
    };
    let light_object = GltfObject::new(GltfObjectKind::Light, index, json_light.name.as_deref());
    let objects = vec![node_object.clone(), light_object.clone()];
    let error = |problem| GltfError::object(path, objects.clone(), problem);
    let warn = |warnings: &mut Vec<GltfWarning>, skipped| {
        warnings.push(GltfWarning {
            path: path.to_owned(),
            objects: objects.clone(),
            skipped,
        });
    };
    use json::extensions::scene::khr_lights_punctual::Type;
    let kind = match (json_light.type_, &json_light.spot) {
        (Checked::Valid(Type::Directional), _) => {
            // The light travels along the node's −z, so the node's +z points toward it.
            let to_light = normals::unit(placed.world.matrix3 * DVec3::Z).ok_or_else(|| {
                error(GltfProblem::Unusable {
                    reason: "the node's world transform gives the light no direction".to_owned(),
                })
            })?;
            GltfLightKind::Directional { to_light }
        }
        (Checked::Valid(Type::Point), _) => GltfLightKind::Point {
            position: placed.world.translation,
            range: range(json_light).map_err(error)?,
        },
        (Checked::Valid(Type::Spot), Some(spot)) => {
            let outer = checked(
                "spot.outerConeAngle",
                spot.outer_cone_angle,
                |v| v > 0.0,
                || "> 0".to_owned(),
            )
            .map_err(error)?;
            let cone = 2.0 * outer;
            if cone >= std::f64::consts::PI {
                warn(
                    warnings,
                    GltfSkipped::WideSpot {
                        outer_cone_angle: outer,
                    },
                );
                return Ok(None);
            }
            if cone < min_angle() {
                return Err(error(GltfProblem::OutOfRange {
                    property: "spot.outerConeAngle",
                    value: outer,
                    requirement: format!(
                        "at least {} radians, half of MIN_ANGLE_DEGREES ({}°)",
                        0.5 * min_angle(),
                        MIN_ANGLE_DEGREES
                    ),
                }));
            }
            let range = range(json_light).map_err(error)?;
            let pose = pose_of(&placed.world).map_err(error)?;
            GltfLightKind::Spot { pose, cone, range }
        }
        _ => {
            return Err(error(GltfProblem::Unusable {
                reason: "is a spot light without a `spot` object".to_owned(),
            }));
        }
    };
    Ok(Some(GltfLight {
        node: node_object,
        light: light_object,
        kind,
    }))
}

/// A point or spot light's `range`, if it has one: `KHR_lights_punctual` requires it > 0 (and
/// undefined means infinite).
fn range(
    light: &json::extensions::scene::khr_lights_punctual::Light,
) -> Result<Option<f64>, GltfProblem> {
    light
        .range
        .map(|range| checked("range", range, |v| v > 0.0, || "> 0".to_owned()))
        .transpose()
}
