//! The focus bodies: the points a shadow map must cover.
//!
//! - [`focus_body`]: **B = conv(V ∪ l) ∩ S ∩ L** (PSM §4.1's H; LiSPSM §3.3). V is the view frustum,
//!   l the light (for a directional light, at infinity: conv(V ∪ l) is V swept toward the light), S
//!   the scene bounds, L the spot frustum (all space for directional and point lights). B holds every
//!   point of S ∩ L that lies between the light and V, i.e. every potential occluder of a visible
//!   point.
//! - [`visible_body`]: the tighter **V ∩ S**, the receivers.
//! - [`psm_near_body`]: **conv((V ∩ S) ∪ l) ∩ S ∩ L**, the occluders of points that are both visible
//!   and inside the scene. PSM pushes the view's near plane as far as possible (§6: "the near plane of
//!   the view be as far as possible") and shifts the virtual camera back until the focus region lies
//!   in front of it (§4.2, formulas.md §3.3: `Δ = max(0, n − min_{h∈H} (h − e)·v)`); both need only
//!   the minimum eye depth of the region that can matter, which [`eye_depth_range`] gives. Using
//!   V ∩ S instead of V is our reading of "the points that matter": receivers outside the scene
//!   bounds cannot exist, so their occluders need not be covered. It is contained in B.
//!
//! All three are computed by clipping the scene box by half-spaces, so their faces lie exactly on the
//! planes of S, V, L and the extrusion (see [`crate::extrude`]). An empty body is `None`.

use glam::DVec3;

use crate::aabb::Aabb;
use crate::camera::ViewPose;
use crate::error::HullError;
use crate::extrude::extrusion_planes;
use crate::frustum::Frustum;
use crate::light::Light;
use crate::polyhedron::ConvexPolyhedron;
use crate::tolerance::Tolerances;

/// B = conv(V ∪ l) ∩ S ∩ L; `None` if empty (e.g. the view sees nothing of the scene and nothing in
/// the scene lies between the light and the view).
///
/// # Errors
/// [`HullError::ZeroSizeBox`] if `scene` is flat; [`HullError::DegeneratePoints`] if `view` is flat
/// within the snap distance.
pub fn focus_body(
    view: &Frustum,
    scene: &Aabb,
    light: &Light,
    tolerances: &Tolerances,
) -> Result<Option<ConvexPolyhedron>, HullError> {
    let v = ConvexPolyhedron::from_frustum(view, tolerances)?;
    occluders_of(&v, scene, light, tolerances)
}

/// V ∩ S; `None` if the view sees no part of the scene bounds.
///
/// # Errors
/// As [`focus_body`].
pub fn visible_body(
    view: &Frustum,
    scene: &Aabb,
    tolerances: &Tolerances,
) -> Result<Option<ConvexPolyhedron>, HullError> {
    let s = ConvexPolyhedron::from_aabb(scene, tolerances)?;
    let v = ConvexPolyhedron::from_frustum(view, tolerances)?;
    Ok(v.intersect(&s, tolerances))
}

/// conv((V ∩ S) ∪ l) ∩ S ∩ L, the body whose nearest eye depth PSM's near plane and virtual camera
/// shift follow; `None` if V ∩ S is empty.
///
/// PSM wants the view's near plane as far as possible (§6) and shifts the virtual camera back until
/// the focus region lies in front of it (§4.2; formulas.md §3.3:
/// `Δ = max(0, n − min_{h∈H} (h − e)·v)`). Our reading of the region that matters: the occluders of
/// points that are both visible and inside the scene bounds, i.e. B with V replaced by V ∩ S (it lies
/// in B). Its nearest eye depth is `eye_depth_range(body, pose).0`.
///
/// # Errors
/// As [`focus_body`].
pub fn psm_near_body(
    view: &Frustum,
    scene: &Aabb,
    light: &Light,
    tolerances: &Tolerances,
) -> Result<Option<ConvexPolyhedron>, HullError> {
    match visible_body(view, scene, tolerances)? {
        Some(visible) => occluders_of(&visible, scene, light, tolerances),
        None => Ok(None),
    }
}

/// `(min, max)` eye depth `(x − eye)·forward` over the body: its extent along the view direction.
#[must_use]
pub fn eye_depth_range(body: &ConvexPolyhedron, pose: &ViewPose) -> (f64, f64) {
    let eye: DVec3 = pose.eye();
    body.vertices()
        .iter()
        .map(|v| (*v - eye).dot(pose.forward()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        })
}

/// conv(receivers ∪ l) ∩ S ∩ L.
fn occluders_of(
    receivers: &ConvexPolyhedron,
    scene: &Aabb,
    light: &Light,
    tolerances: &Tolerances,
) -> Result<Option<ConvexPolyhedron>, HullError> {
    let s = ConvexPolyhedron::from_aabb(scene, tolerances)?;
    let planes = extrusion_planes(receivers, light.source(), None, tolerances);
    let body = s.intersect_planes(&planes, tolerances);
    Ok(match (body, light.frustum()) {
        (Some(b), Some(spot)) => b.intersect_frustum(spot, tolerances),
        (body, _) => body,
    })
}
