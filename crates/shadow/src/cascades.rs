//! Cascaded shadow maps as engines build them: each cascade an orthographic map of one slice of the
//! view frustum, in a light basis fixed by the light's direction alone, fitted to the slice by an
//! engine's rule ([`CascadeFit`]) and stabilised by snapping its window to the texel grid
//! ([`Snap`]). The engines' own parameters are in [`crate::presets`]; their sources in
//! `docs/engine-sources.md`.
//!
//! Two choices are shadowlab's, named here and in the docs:
//! - **light roll**: the basis looks along −L with world +y as up (world +z when L is within
//!   [`PARALLEL_TO_UP`] of ±y) — Babylon's `LookAtLH` up vector; Bevy and Godot take the light
//!   node's rotation, which a scene does not state. The roll turns the texel grid about L; the
//!   fits are invariant to it except [`CascadeFit::CornerBox`].
//! - **caster extension**: a cascade's depth range runs from its slice's farthest corner (away
//!   from the light) to the nearer of its slice's nearest corner and the scene box's nearest
//!   corner toward the light, so every caster between the light and the slice is in the map.
//!   Engines keep a tighter range and clamp the casters in front of it to the near plane (Bevy's
//!   `UNCLIPPED_DEPTH_ORTHO`, Godot's pancaking, Filament's and Babylon's depth clamp): the same
//!   nearest-surface test, with less depth precision here in fixed-point formats.

use glam::{DMat4, DVec3, DVec4};
use shadowlab_hull::{Frustum, Perspective, ViewPose};

use crate::cascade_fit::{CascadeFit, Snap};
use crate::error::ShadowError;
use crate::input::{LightSource, PlanInput};
use crate::partition::CullingSphere;
use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
use crate::technique::Technique;

/// Within this of parallel to world y (|L·y|), the light basis takes world z as up.
pub const PARALLEL_TO_UP: f64 = 1.0 - 1e-9;

/// The part of the view one cascade covers, as eye depths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CascadeSlice {
    /// The eye depths the cascade is selected for (its partition's `near`, `far`).
    pub select: (f64, f64),
    /// The eye depths of the view frustum's slice its map is fitted to.
    pub slice: (f64, f64),
}

/// One cascade's window in the light basis: `x ∈ [min.x, max.x]`, `y ∈ [min.y, max.y]`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Window {
    min: [f64; 2],
    max: [f64; 2],
}

/// The light basis: world → a view looking along −L (rotation only, origin at the world origin).
///
/// # Errors
/// A geometry error for a light direction that is not a direction.
pub fn light_basis(to_light: DVec3) -> Result<DMat4, ShadowError> {
    let up = if to_light.y.abs() > PARALLEL_TO_UP {
        DVec3::Z
    } else {
        DVec3::Y
    };
    Ok(ViewPose::look_to(DVec3::ZERO, -to_light, up)?.view_matrix())
}

/// The cascades of a directional light: one orthographic map per slice, fitted by `fit`, snapped
/// by `snap` on a `resolution`-texel map, each labelled `technique`, with its culling sphere when
/// the fit is a sphere. The partitions' `near`, `far` are the slices' selection depths.
///
/// # Errors
/// [`ShadowError::NotDefined`] for a spot light (engines give a spot one perspective map: plan it
/// as the uniform map instead); geometry errors for a slice the camera cannot have.
pub fn plan(
    input: &PlanInput,
    technique: Technique,
    slices: &[CascadeSlice],
    (fit, snap): (CascadeFit, Snap),
    resolution: u32,
) -> Result<Vec<crate::partition::Partition>, ShadowError> {
    let LightSource::Directional { to_light } = input.light else {
        return Err(ShadowError::NotDefined {
            technique: technique.key(),
            reason: "cascades are fitted for a directional light".into(),
        });
    };
    let basis = light_basis(to_light)?;
    let scene_nearest = input
        .scene
        .corners()
        .iter()
        .map(|c| -(basis.transform_point3(*c)).z)
        .fold(f64::INFINITY, f64::min);
    let projection = input.eye.projection;
    slices
        .iter()
        .map(|cascade| {
            let (near, far) = cascade.slice;
            let part = Perspective::new(projection.fov_y(), projection.aspect(), near, far)?;
            let world = *Frustum::perspective(&input.eye.pose, &part).corners();
            let corners = world.map(|c| basis.transform_point3(c));
            let (mut window, sphere) = fitted(fit, &world, &corners, resolution);
            window = snapped(window, snap, resolution);
            // View-space z is negative in front: distances from the light basis's plane are −z.
            let distances = corners.map(|c| -c.z);
            let slice_far = distances.into_iter().fold(f64::NEG_INFINITY, f64::max);
            let slice_near = distances.into_iter().fold(f64::INFINITY, f64::min);
            let depth_near = slice_near.min(scene_nearest);
            let projection = orthographic(window, depth_near, slice_far);
            Ok(crate::partition::Partition {
                near: cascade.select.0,
                far: cascade.select.1,
                face: None,
                sphere,
                setup: LightSetup {
                    technique,
                    mapping: ShadowMapping::Projective(ProjectiveMapping::new(basis, projection)),
                    gamma: shadowlab_hull::light_view_angle(input.eye.pose.forward(), to_light)?,
                    half_fov: input.eye.half_fov_toward(to_light),
                    warp: None,
                    psm: None,
                    focus_body: world.to_vec(),
                },
            })
        })
        .collect()
}

/// GL's orthographic projection (`glOrtho`) of `window` between the distances `near` and `far`
/// along the basis's −z: `X = (2x − (r + l))/(r − l)`, likewise Y, `Z = (−2z − (f + n))/(f − n)`.
fn orthographic(window: Window, near: f64, far: f64) -> DMat4 {
    let ([l, b], [r, t]) = (window.min, window.max);
    DMat4::from_cols(
        DVec4::new(2.0 / (r - l), 0.0, 0.0, 0.0),
        DVec4::new(0.0, 2.0 / (t - b), 0.0, 0.0),
        DVec4::new(0.0, 0.0, -2.0 / (far - near), 0.0),
        DVec4::new(
            -(r + l) / (r - l),
            -(t + b) / (t - b),
            -(far + near) / (far - near),
            1.0,
        ),
    )
}

/// `fit`'s window of a slice with `world` corners (`corners` in the light basis), and its culling
/// sphere for a sphere fit.
fn fitted(
    fit: CascadeFit,
    world: &[DVec3; 8],
    corners: &[DVec3; 8],
    resolution: u32,
) -> (Window, Option<CullingSphere>) {
    let lo = corners.iter().fold(DVec3::INFINITY, |a, c| a.min(*c));
    let hi = corners.iter().fold(DVec3::NEG_INFINITY, |a, c| a.max(*c));
    let square = |centre: [f64; 2], half: f64| Window {
        min: [centre[0] - half, centre[1] - half],
        max: [centre[0] + half, centre[1] + half],
    };
    match fit {
        CascadeFit::Diagonal { ceil } => {
            // shadowlab_hull's corner order: bit 0 right, bit 1 top, bit 2 far; so c₇ (right, top,
            // far) lies across the body from c₀ and across the far face from c₄.
            let body = (world[0] - world[7]).length();
            let face = (world[4] - world[7]).length();
            let side = if ceil {
                body.max(face).ceil()
            } else {
                body.max(face)
            };
            let centre = (lo + hi) * 0.5;
            (square([centre.x, centre.y], 0.5 * side), None)
        }
        CascadeFit::CornerBox => (
            Window {
                min: [lo.x, lo.y],
                max: [hi.x, hi.y],
            },
            None,
        ),
        CascadeFit::Sphere { texel_border } => {
            let centre = world.iter().copied().sum::<DVec3>() / 8.0;
            let radius = world
                .iter()
                .map(|c| (*c - centre).length())
                .fold(0.0, f64::max);
            let size = f64::from(resolution);
            let radius = if texel_border && resolution > 2 {
                radius * size / (size - 2.0)
            } else {
                radius
            };
            let light_centre = corners.iter().copied().sum::<DVec3>() / 8.0;
            (
                square([light_centre.x, light_centre.y], radius),
                Some(CullingSphere { centre, radius }),
            )
        }
    }
}

/// `window` moved onto the texel grid as `snap` says.
fn snapped(window: Window, snap: Snap, resolution: u32) -> Window {
    let size = f64::from(resolution);
    let texel = |axis: usize| (window.max[axis] - window.min[axis]) / size;
    let mut out = window;
    for axis in 0..2 {
        match snap {
            Snap::Off => {}
            Snap::CentreFloor { texels } | Snap::CentreRound { texels } => {
                let grid = texel(axis) * f64::from(texels);
                let centre = 0.5 * (window.min[axis] + window.max[axis]);
                let half = 0.5 * (window.max[axis] - window.min[axis]);
                let moved = if matches!(snap, Snap::CentreFloor { .. }) {
                    (centre / grid).floor() * grid
                } else {
                    (centre / grid).round() * grid
                };
                out.min[axis] = moved - half;
                out.max[axis] = moved + half;
            }
            Snap::EdgesRound { texels } => {
                let grid = texel(axis) * f64::from(texels);
                out.min[axis] = (window.min[axis] / grid).round() * grid;
                out.max[axis] = (window.max[axis] / grid).round() * grid;
            }
        }
    }
    out
}
