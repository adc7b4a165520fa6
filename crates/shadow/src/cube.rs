//! The cube shadow map of a point light (Gerasimov, *Omnidirectional Shadow Mapping*, GPU Gems
//! ch. 12, 2004 — what every engine ships for point lights: Filament's, Godot's, Bevy's and
//! three.js's point-light shadows are six 90° views).
//!
//! Each face `k` of the cube is a perspective frustum from the light with a 90° field of view and
//! aspect 1, looking along its world axis, oriented as OpenGL orients its cube-map faces (OpenGL
//! 4.6 §8.13, Table 8.19: up −y for the ±x and ±z faces, +z for +y and −z for −y), so the six
//! tile every direction and meet edge to edge. A face serves the directions whose major axis is
//! its own ([`LightFace`]). What shadowlab focuses per face:
//!
//! - the face's part of B, `B_k = B ∩` (the face's pyramid from the light); a face whose part is
//!   empty, or holds no geometry, has no map (it serves no visible point);
//! - **far** = the greatest depth along the face's axis of `B_k`'s vertices, no further than the
//!   light's range;
//! - **near** = the least depth along the axis of the scene's geometry inside `B_k`
//!   (`omni::nearest`) — the cube's near plane chosen from the scene, not a constant, as large
//!   as keeps every occluder in front of it, for the depth precision the near plane decides.
//!   Geometry touching the light would put it at 0; it is kept at
//!   [`crate::omni::MIN_NEAR_FRACTION`] of far.
//!
//! Engines use one near plane for all six faces (a constant, or the light's radius); per-face
//! nears are shadowlab's focusing, named here so that the two are not confused.

use glam::DVec3;
use shadowlab_hull::{NdcDepth, Perspective, ViewPose};

use crate::error::ShadowError;
use crate::input::PlanInput;
use crate::omni::{LightFace, PointLightPlan};
use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
use crate::technique::Technique;

/// The cube's faces in OpenGL's order (+x, −x, +y, −y, +z, −z): name, view direction and the
/// up vector of its image (OpenGL 4.6 Table 8.19).
const FACES: [(&str, DVec3, DVec3); 6] = [
    ("+x", DVec3::X, DVec3::NEG_Y),
    ("-x", DVec3::NEG_X, DVec3::NEG_Y),
    ("+y", DVec3::Y, DVec3::Z),
    ("-y", DVec3::NEG_Y, DVec3::NEG_Z),
    ("+z", DVec3::Z, DVec3::NEG_Y),
    ("-z", DVec3::NEG_Z, DVec3::NEG_Y),
];

/// Plans the cube map of `input`'s point light over the scene's triangles (`positions`,
/// `triangles`): one set-up per face that serves part of B, with the face it serves.
///
/// # Errors
/// [`ShadowError::UnservedLight`] for a light that is not a point light;
/// [`ShadowError::EmptyFocusBody`] if no face holds geometry of B; geometry errors.
pub(crate) fn plan(
    input: &PlanInput,
    positions: &[DVec3],
    triangles: &[[u32; 3]],
) -> Result<Vec<(LightFace, LightSetup)>, ShadowError> {
    let plan = PointLightPlan::new(Technique::Cube, input, positions, triangles)?;
    let position = plan.position();
    let mut faces = Vec::new();
    for (name, axis, up) in FACES {
        let face = LightFace {
            name,
            light: position,
            axis,
            across: Some([axis.cross(up), up]),
        };
        let depth = |p: DVec3| axis.dot(p - position);
        // An affine depth is least at a corner of the clipped triangle.
        let least = |polygon: &[DVec3]| {
            polygon
                .iter()
                .map(|p| depth(*p))
                .fold(f64::INFINITY, f64::min)
        };
        let Some(focus) = plan.focus(&face, depth, least) else {
            continue;
        };
        let view = ViewPose::look_to(position, axis, up)?;
        let projection = Perspective::new(std::f64::consts::FRAC_PI_2, 1.0, focus.near, focus.far)?;
        let mapping = ShadowMapping::Projective(ProjectiveMapping::new(
            view.view_matrix(),
            projection.matrix(NdcDepth::NegativeOneToOne),
        ));
        faces.push((face, plan.setup(mapping, &focus)));
    }
    if faces.is_empty() {
        return Err(ShadowError::EmptyFocusBody);
    }
    Ok(faces)
}
