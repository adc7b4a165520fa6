//! A glTF file as a scene by itself: its mesh, its first perspective camera and its lights, with
//! the defaults of scene files where the file gives none (see [`crate::load_gltf_scene`]).

use std::path::Path;

use shadowlab_hull::Perspective;

use super::checks::Checker;
use super::error::SceneFileError;
use super::raw::RawCamera;
use super::view::{self, corner_depths, default_far, default_near};
use super::{DEFAULT_IMAGE, LoadedScene, MAX_DEPTH_RATIO, MAX_IMAGE_SIDE};
use crate::gltf_import::{
    GltfCamera, GltfError, GltfImport, GltfLight, GltfLightKind, GltfProblem, GltfSkipped,
    GltfWarning,
};
use crate::scene::{Camera, Scene, SceneLight, ShadowSettings};

/// The scene of `import`, read from `path`.
pub(super) fn scene(import: GltfImport, path: &Path) -> Result<LoadedScene, SceneFileError> {
    let checker = Checker::new(path);
    let mut warnings = import.warnings;
    let camera = match import.cameras.first() {
        Some(camera) => camera_of(camera, &import.mesh.bounds(), path, &mut warnings)?,
        None => view::camera(checker, &RawCamera::default(), &import.mesh.bounds())?,
    };
    let lights = view::lights_or_default_sun(checker, &import.lights, |_, light| {
        light_of(light, &import.mesh.bounds(), path)
    })?;
    Ok(LoadedScene {
        scene: Scene {
            name: view::scene_name(import.scene_name, path),
            camera,
            lights,
            mesh: import.mesh,
            shadow: ShadowSettings::default(),
        },
        warnings,
    })
}

/// A [`SceneFileError::Gltf`] for a problem of a camera or light of the file.
fn object_error(
    path: &Path,
    objects: Vec<crate::GltfObject>,
    problem: GltfProblem,
) -> SceneFileError {
    SceneFileError::Gltf {
        path: path.to_owned(),
        field: None,
        source: Box::new(GltfError::object(path, objects, problem)),
    }
}

/// The eye of a glTF camera: its pose, `yfov`, `znear`; `zfar`, or for an infinite projection
/// the scene files' default far plane (just beyond the scene's bounds); the image the camera's
/// `extras` record (shadowlab's export), else [`DEFAULT_IMAGE`], whose aspect replaces `aspectRatio` (a warning where they differ at f32
/// precision). A `zfar` more than [`MAX_DEPTH_RATIO`] times `znear` is brought in to the default
/// far plane, with a warning, if that is close enough.
fn camera_of(
    camera: &GltfCamera,
    bounds: &crate::Bounds,
    path: &Path,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Camera, SceneFileError> {
    let objects = vec![camera.node.clone(), camera.camera.clone()];
    let [width, height] = camera.image.unwrap_or(DEFAULT_IMAGE);
    if let Some(side) = [width, height]
        .into_iter()
        .find(|side| !(1..=MAX_IMAGE_SIDE).contains(side))
    {
        return Err(object_error(
            path,
            objects,
            GltfProblem::OutOfRange {
                property: "extras.shadowlab.image",
                value: f64::from(side),
                requirement: format!("each side in 1..={MAX_IMAGE_SIDE} pixels (MAX_IMAGE_SIDE)"),
            },
        ));
    }
    let aspect = f64::from(width) / f64::from(height);
    let (_, farthest) = corner_depths(bounds, &camera.pose);
    let derived = default_far(farthest).filter(|&far| far > camera.near);
    let far = match (camera.far, derived) {
        (Some(zfar), _) if zfar / camera.near <= MAX_DEPTH_RATIO => zfar,
        (Some(zfar), Some(far)) if far < zfar && far / camera.near <= MAX_DEPTH_RATIO => {
            warnings.push(GltfWarning {
                path: path.to_owned(),
                objects: objects.clone(),
                skipped: GltfSkipped::FarReduced { zfar, far },
            });
            far
        }
        (None, Some(far)) if far / camera.near <= MAX_DEPTH_RATIO => far,
        (None, None) => {
            return Err(object_error(
                path,
                objects,
                GltfProblem::Unusable {
                    reason: "has an infinite projection and the scene lies behind it, so no far \
                             plane can be derived"
                        .to_owned(),
                },
            ));
        }
        (zfar, far) => {
            let far = zfar.or(far).unwrap_or(f64::INFINITY);
            return Err(object_error(
                path,
                objects,
                GltfProblem::OutOfRange {
                    property: "znear",
                    value: camera.near,
                    requirement: format!(
                        "at least 1/{MAX_DEPTH_RATIO:e} (MAX_DEPTH_RATIO) of the far distance {}",
                        crate::number::Shown(far)
                    ),
                },
            ));
        }
    };
    if let Some(file) = camera.aspect_ratio {
        #[expect(
            clippy::cast_possible_truncation,
            reason = "the file's aspect ratio is an f32; the image's is compared at that precision"
        )]
        let same = file as f32 == aspect as f32;
        if !same {
            warnings.push(GltfWarning {
                path: path.to_owned(),
                objects: objects.clone(),
                skipped: GltfSkipped::AspectRatio {
                    file,
                    width,
                    height,
                },
            });
        }
    }
    let projection = Perspective::new(camera.fov_y, aspect, camera.near, far).map_err(|error| {
        object_error(
            path,
            objects,
            GltfProblem::Unusable {
                reason: error.to_string(),
            },
        )
    })?;
    Ok(Camera {
        pose: camera.pose,
        projection,
        width,
        height,
    })
}

/// A scene light of a glTF light. A point light is its position and `range` as they are. A spot
/// light's far distance is its `range`, or the scene files' default (just beyond the scene's
/// bounds); its near distance is the scene files' default for that far distance
/// (`KHR_lights_punctual` has no near distance).
fn light_of(
    light: &GltfLight,
    bounds: &crate::Bounds,
    path: &Path,
) -> Result<SceneLight, SceneFileError> {
    match &light.kind {
        GltfLightKind::Directional { to_light } => Ok(SceneLight::Directional {
            to_light: *to_light,
        }),
        GltfLightKind::Point { position, range } => Ok(SceneLight::Point {
            position: *position,
            range: *range,
        }),
        GltfLightKind::Spot { pose, cone, range } => {
            let objects = vec![light.node.clone(), light.light.clone()];
            let (nearest, farthest) = corner_depths(bounds, pose);
            let far = range.or_else(|| default_far(farthest)).ok_or_else(|| {
                object_error(
                    path,
                    objects.clone(),
                    GltfProblem::Unusable {
                        reason: "has no range and the scene lies behind it, so no far distance \
                                 can be derived"
                            .to_owned(),
                    },
                )
            })?;
            let near = default_near(nearest, far);
            let cone = Perspective::new(*cone, 1.0, near, far).map_err(|error| {
                object_error(
                    path,
                    objects,
                    GltfProblem::Unusable {
                        reason: error.to_string(),
                    },
                )
            })?;
            Ok(SceneLight::Spot { pose: *pose, cone })
        }
    }
}
