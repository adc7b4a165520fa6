//! `[camera]` and `[[light]]`: poses, projections, and the defaults derived from the scene's
//! bounds (see the module documentation of [`crate::scene_file`] for the rules).

use std::path::Path;

use glam::DVec3;
use shadowlab_hull::{HullError, Perspective, ViewPose};

use super::checks::{Checker, field, named};
use super::error::{SceneFileError, SceneFileProblem};
use super::raw::{LightKind, RawCamera, RawLight};
use super::{
    DEFAULT_CONE_DEGREES, DEFAULT_FOV_DEGREES, DEFAULT_IMAGE, DEFAULT_SUN_DIRECTION, DEFAULT_UP,
    DEFAULT_VIEW_FROM, DEPTH_MARGIN, MAX_DEPTH_RATIO, MAX_FAR_NEAR_RATIO,
};
use crate::bounds::Bounds;
use crate::normals;
use crate::number::Shown;
use crate::scene::{Camera, SceneLight};

/// The camera of `[camera]`, with defaults derived from the scene's bounds.
pub(super) fn camera(
    checker: Checker<'_>,
    raw: &RawCamera,
    bounds: &Bounds,
) -> Result<Camera, SceneFileError> {
    let fov_y = match raw.fov {
        Some(degrees) => checker.angle("camera.fov", degrees)?,
        None => DEFAULT_FOV_DEGREES.to_radians(),
    };
    let [width, height] = match raw.image {
        Some(image) => {
            for (index, &size) in image.iter().enumerate() {
                checker.image_side(&format!("camera.image[{index}]"), size)?;
            }
            image
        }
        None => DEFAULT_IMAGE,
    };
    let aspect = f64::from(width) / f64::from(height);
    let up = match raw.up {
        Some(up) => checker.direction("camera.up", up)?,
        None => DEFAULT_UP,
    };
    checker.at_most_one(
        ("camera.target", raw.target.is_some()),
        ("camera.direction", raw.direction.is_some()),
    )?;
    let position = match raw.position {
        Some(position) => checker.vector("camera.position", position)?,
        None => {
            // The bounding sphere must fit the narrower of the vertical and horizontal fields.
            let half_fov_y = 0.5 * fov_y;
            let half_fov_x = (aspect * half_fov_y.tan()).atan();
            let half_angle = half_fov_y.min(half_fov_x);
            default_viewpoint(
                checker,
                "camera.position",
                bounds,
                DEFAULT_VIEW_FROM,
                half_angle,
            )?
        }
    };
    let aim = Aim {
        prefix: "camera",
        position,
        position_given: raw.position.is_some(),
        target: raw.target,
        direction: raw.direction,
    };
    let forward = aim.forward(checker, bounds)?;
    let pose = pose(
        checker,
        &aim,
        forward,
        (up, raw.up.is_some()),
        "the view direction",
    )?;
    let (near, far) = depth_range(checker, "camera", (raw.near, raw.far), bounds, &pose)?;
    let projection =
        Perspective::new(fov_y, aspect, near, far).map_err(|e| checker.hull_error("camera", e))?;
    Ok(Camera {
        pose,
        projection,
        width,
        height,
    })
}

/// The light that a scene without `[[light]]` entries gets: a directional light travelling along
/// [`DEFAULT_SUN_DIRECTION`], exactly as a `[[light]]` without fields.
fn default_sun(checker: Checker<'_>) -> Result<SceneLight, SceneFileError> {
    directional(checker, "light", DEFAULT_SUN_DIRECTION.to_array())
}

/// The lights of a scene read from `lights` by `read` (with each one's index), or where there are
/// none, [`default_sun`].
pub(super) fn lights_or_default_sun<T>(
    checker: Checker<'_>,
    lights: &[T],
    mut read: impl FnMut(usize, &T) -> Result<SceneLight, SceneFileError>,
) -> Result<Vec<SceneLight>, SceneFileError> {
    if lights.is_empty() {
        Ok(vec![default_sun(checker)?])
    } else {
        lights
            .iter()
            .enumerate()
            .map(|(index, light)| read(index, light))
            .collect()
    }
}

/// A scene's name: `name` as given, else the stem of the file it was read from.
pub(super) fn scene_name(name: Option<String>, path: &Path) -> String {
    name.unwrap_or_else(|| {
        let stem = path.file_stem().unwrap_or_default();
        stem.to_string_lossy().into_owned()
    })
}

/// A directional light travelling along `direction` (the field `prefix.direction`).
fn directional(
    checker: Checker<'_>,
    prefix: &str,
    direction: [f64; 3],
) -> Result<SceneLight, SceneFileError> {
    let direction = checker.direction(&field(prefix, "direction"), direction)?;
    Ok(SceneLight::Directional {
        to_light: -direction,
    })
}

/// The light of `[[light]]` entry `index`. A field that the entry's kind does not take is an
/// error naming it, so that a `cone` on a directional light or a `range` on a spot is reported
/// rather than ignored.
pub(super) fn light(
    checker: Checker<'_>,
    index: usize,
    raw: &RawLight,
    bounds: &Bounds,
) -> Result<SceneLight, SceneFileError> {
    let prefix = format!("light[{index}]");
    let kind = raw.kind.unwrap_or_default();
    let given = [
        ("direction", raw.direction.is_some()),
        ("position", raw.position.is_some()),
        ("target", raw.target.is_some()),
        ("up", raw.up.is_some()),
        ("cone", raw.cone.is_some()),
        ("near", raw.near.is_some()),
        ("far", raw.far.is_some()),
        ("range", raw.range.is_some()),
    ];
    let (takes, to): (&[&str], _) = match kind {
        LightKind::Directional => (&["direction"], "a directional light"),
        LightKind::Spot => (
            &[
                "direction",
                "position",
                "target",
                "up",
                "cone",
                "near",
                "far",
            ],
            "a spot light (its reach is `far`)",
        ),
        LightKind::Point => (&["position", "range"], "a point light"),
    };
    if let Some((name, _)) = given
        .iter()
        .find(|(name, given)| *given && !takes.contains(name))
    {
        return Err(checker.error(
            field(&prefix, name),
            SceneFileProblem::NotApplicable { to: to.to_owned() },
        ));
    }
    match kind {
        LightKind::Directional => {
            let direction = raw.direction.unwrap_or(DEFAULT_SUN_DIRECTION.to_array());
            directional(checker, &prefix, direction)
        }
        LightKind::Spot => spot(checker, &prefix, raw, bounds),
        LightKind::Point => point(checker, &prefix, raw),
    }
}

/// A point light (`kind = "point"`): its `position`, required, and its `range`, if given, finite
/// and > 0 (`KHR_lights_punctual`'s `range`: the distance beyond which it lights nothing).
fn point(checker: Checker<'_>, prefix: &str, raw: &RawLight) -> Result<SceneLight, SceneFileError> {
    let position_field = field(prefix, "position");
    let Some(position) = raw.position else {
        return Err(checker.error(
            position_field,
            SceneFileProblem::Missing {
                needs: "to be given for a point light, which has no default position",
            },
        ));
    };
    let position = checker.vector(&position_field, position)?;
    let range = raw
        .range
        .map(|range| checker.positive(&field(prefix, "range"), range))
        .transpose()?;
    Ok(SceneLight::Point { position, range })
}

/// A spot light (`kind = "spot"`).
fn spot(
    checker: Checker<'_>,
    prefix: &str,
    raw: &RawLight,
    bounds: &Bounds,
) -> Result<SceneLight, SceneFileError> {
    let cone = match raw.cone {
        Some(degrees) => checker.angle(&field(prefix, "cone"), degrees)?,
        None => DEFAULT_CONE_DEGREES.to_radians(),
    };
    let up = raw
        .up
        .map(|up| checker.direction(&field(prefix, "up"), up))
        .transpose()?;
    checker.at_most_one(
        (&field(prefix, "target"), raw.target.is_some()),
        (&field(prefix, "direction"), raw.direction.is_some()),
    )?;
    let position = match raw.position {
        Some(position) => checker.vector(&field(prefix, "position"), position)?,
        None => default_viewpoint(
            checker,
            &field(prefix, "position"),
            bounds,
            -DEFAULT_SUN_DIRECTION,
            0.5 * cone,
        )?,
    };
    let aim = Aim {
        prefix,
        position,
        position_given: raw.position.is_some(),
        target: raw.target,
        direction: raw.direction,
    };
    let forward = aim.forward(checker, bounds)?;
    let up = (up.unwrap_or_else(|| spot_up(forward)), raw.up.is_some());
    let pose = pose(checker, &aim, forward, up, "the light direction")?;
    let (near, far) = depth_range(checker, prefix, (raw.near, raw.far), bounds, &pose)?;
    let cone = Perspective::new(cone, 1.0, near, far).map_err(|e| checker.hull_error(prefix, e))?;
    Ok(SceneLight::Spot { pose, cone })
}

/// A spot light's default up vector: +y, or −z when the light travels mostly along ±y (its
/// largest absolute component, ties included, is y), so that it is never parallel to the light.
fn spot_up(forward: DVec3) -> DVec3 {
    let size = forward.abs();
    if size.y >= size.x && size.y >= size.z {
        DVec3::NEG_Z
    } else {
        DVec3::Y
    }
}

/// Where a camera or spot light is and where it looks, as the file gives it.
struct Aim<'a> {
    /// `camera` or `light[i]`.
    prefix: &'a str,
    position: DVec3,
    position_given: bool,
    target: Option<[f64; 3]>,
    direction: Option<[f64; 3]>,
}

impl Aim<'_> {
    /// The view (or light) direction: `direction` normalised, or `target − position` (not
    /// normalised) with the target defaulting to the centre of the scene's bounds.
    fn forward(&self, checker: Checker<'_>, bounds: &Bounds) -> Result<DVec3, SceneFileError> {
        if let Some(direction) = self.direction {
            return checker.direction(&field(self.prefix, "direction"), direction);
        }
        let target = match self.target {
            Some(target) => checker.vector(&field(self.prefix, "target"), target)?,
            None => bounds.centre(),
        };
        let forward = target - self.position;
        if forward != DVec3::ZERO {
            return Ok(forward);
        }
        let position = named(field(self.prefix, "position"), self.position_given);
        Err(if self.target.is_some() {
            checker.error(
                field(self.prefix, "target"),
                SceneFileProblem::Coincident {
                    value: target,
                    other: position,
                },
            )
        } else {
            checker.error(
                position,
                SceneFileProblem::Coincident {
                    value: self.position,
                    other: format!(
                        "the default {} (the scene's centre)",
                        field(self.prefix, "target")
                    ),
                },
            )
        })
    }
}

/// The pose at `aim.position` looking along `forward`; an up vector parallel to `forward` is named
/// with `other`, the name of the direction.
fn pose(
    checker: Checker<'_>,
    aim: &Aim<'_>,
    forward: DVec3,
    (up, up_given): (DVec3, bool),
    other: &'static str,
) -> Result<ViewPose, SceneFileError> {
    ViewPose::look_to(aim.position, forward, up).map_err(|error| match error {
        HullError::ParallelVectors { .. } => checker.error(
            named(field(aim.prefix, "up"), up_given),
            SceneFileProblem::Parallel {
                value: up,
                other,
                other_value: normals::unit(forward).unwrap_or(forward),
            },
        ),
        other => checker.hull_error(aim.prefix, other),
    })
}

/// A default position: the centre c of the scene's bounds plus `distance · normalize(from)`, with
/// `distance = R / sin(half_angle)`, R half the bounds' diagonal: from there the bounding sphere
/// just fills a cone of that half angle around the direction toward c. R > 0: a scene spans at
/// least [`crate::MIN_EXTENT`].
fn default_viewpoint(
    checker: Checker<'_>,
    field: &str,
    bounds: &Bounds,
    from: DVec3,
    half_angle: f64,
) -> Result<DVec3, SceneFileError> {
    let radius = 0.5 * bounds.diagonal();
    let position = bounds.centre() + from.normalize() * (radius / half_angle.sin());
    if position.is_finite() {
        Ok(position)
    } else {
        Err(checker.error(
            field,
            SceneFileProblem::NoDefault {
                reason: "the scene's bounds are too large to place it",
            },
        ))
    }
}

/// The near and far distances of a camera or spot light (`prefix`) at `pose`, from the file or
/// derived from the depths of the corners of the scene's bounds along the view direction:
/// far = farthest·(1 + [`DEPTH_MARGIN`]), near = max(nearest·(1 − [`DEPTH_MARGIN`]),
/// far / [`MAX_FAR_NEAR_RATIO`]); a derived near that is not below a given far is
/// far / [`MAX_FAR_NEAR_RATIO`]. A given near must be at least far / [`MAX_DEPTH_RATIO`].
fn depth_range(
    checker: Checker<'_>,
    prefix: &str,
    (near, far): (Option<f64>, Option<f64>),
    bounds: &Bounds,
    pose: &ViewPose,
) -> Result<(f64, f64), SceneFileError> {
    let near_field = field(prefix, "near");
    let far_field = field(prefix, "far");
    let given_near = near.map(|n| checker.positive(&near_field, n)).transpose()?;
    let given_far = far.map(|f| checker.positive(&far_field, f)).transpose()?;
    let (nearest, farthest) = corner_depths(bounds, pose);
    let far = match given_far {
        Some(far) => far,
        None => default_far(farthest).ok_or_else(|| {
            checker.error(
                far_field.clone(),
                SceneFileProblem::NoDefault {
                    reason: "the scene's bounds lie behind it, or are too far away",
                },
            )
        })?,
    };
    let near = given_near.unwrap_or_else(|| default_near(nearest, far));
    if near >= far {
        return Err(checker.error(
            near_field,
            SceneFileProblem::NotBelow {
                value: near,
                other: named(far_field, given_far.is_some()),
                other_value: far,
            },
        ));
    }
    if far / near > MAX_DEPTH_RATIO {
        return Err(checker.error(
            near_field,
            SceneFileProblem::OutOfRange {
                value: near,
                requirement: format!(
                    "at least {} / {} (MAX_DEPTH_RATIO) = {}",
                    named(far_field, given_far.is_some()),
                    Shown(MAX_DEPTH_RATIO),
                    Shown(far / MAX_DEPTH_RATIO)
                ),
            },
        ));
    }
    Ok((near, far))
}

/// The smallest and largest depth of the corners of the scene's bounds along `pose`'s view
/// direction (negative behind it).
pub(super) fn corner_depths(bounds: &Bounds, pose: &ViewPose) -> (f64, f64) {
    let depths = corners(bounds).map(|corner| (corner - pose.eye()).dot(pose.forward()));
    let nearest = depths.iter().copied().fold(f64::INFINITY, f64::min);
    let farthest = depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (nearest, farthest)
}

/// The default far distance for the farthest corner depth: farthest·(1 + [`DEPTH_MARGIN`]);
/// `None` if that is not positive and finite (the scene lies behind, or is too far away).
pub(super) fn default_far(farthest: f64) -> Option<f64> {
    let far = farthest * (1.0 + DEPTH_MARGIN);
    (far > 0.0 && far.is_finite()).then_some(far)
}

/// The default near distance for the nearest corner depth and the far distance:
/// max(nearest·(1 − [`DEPTH_MARGIN`]), far / [`MAX_FAR_NEAR_RATIO`]), or far /
/// [`MAX_FAR_NEAR_RATIO`] if that is not below far.
pub(super) fn default_near(nearest: f64, far: f64) -> f64 {
    let loose = far / MAX_FAR_NEAR_RATIO;
    let tight = (nearest * (1.0 - DEPTH_MARGIN)).max(loose);
    if tight < far { tight } else { loose }
}

/// The eight corners of a box.
fn corners(bounds: &Bounds) -> [DVec3; 8] {
    let (min, max) = (bounds.min, bounds.max);
    std::array::from_fn(|k| {
        DVec3::new(
            if k & 1 == 0 { min.x } else { max.x },
            if k & 2 == 0 { min.y } else { max.y },
            if k & 4 == 0 { min.z } else { max.z },
        )
    })
}
