//! Perspective shadow maps (Stamminger & Drettakis, SIGGRAPH 2002): the shadow map is taken in the
//! camera's post-perspective space (PPS), where perspective aliasing is already undone.
//!
//! 1. **Near plane and virtual camera** (PSM §4.2, §6; formulas.md §3.3): the near distance `n` is
//!    pushed to the nearest visible depth (read back from an eye depth pass, which here costs
//!    nothing), then the camera moves back by `Δ = max(0, n − min_{h∈H} (h − e)·v)`, keeping `n`,
//!    with `far' = f + Δ`, so that every point of H — the occluders of the visible part of the scene,
//!    `hull::psm_near_body` — lies in front of its near plane.
//! 2. **The light in PPS** (formulas.md §3.2): `L = M·(l, 0)` for a directional light, `M·(p, 1)` for
//!    a spot. A directional light in front of the viewer (`w' > 0`) becomes a point light on the
//!    infinity plane `z = (f' + n')/(f' − n')`; behind the viewer (`w' < 0`) an *inverted* point
//!    light whose rays converge; parallel to the image plane (`w' = 0`) it stays directional.
//! 3. **The light's projection**, one construction for all three cases. Let `c` be the point of H
//!    (in PPS) nearest the light point `L.xyz/w'` (any point of H for a directional light). There
//!    the light travels along `a = normalise(w'·c − L.xyz)`: away from an ordinary point light,
//!    toward an inverted one, along the direction of a directional one — continuous through
//!    `w' = 0`. In LiSPSM's light space built around `a` (hull's `LightSpace`, with PPS's view
//!    direction +z) and centred on `c`, the light sits on the y axis at `(0, s, 0, w')`,
//!    `s = |w'·c − L.xyz|`; the projective map `w ↦ 1 − (w'/s)·y` sends it to infinity along +y,
//!    after which every light ray is parallel to y and the map is an orthographic fit of H, depth
//!    growing along the light's travel. Because `c` is H's nearest point to the light, the plane
//!    through the light perpendicular to `a` has all of H on one side (the projection theorem), so
//!    `w ≥ 1` on H: one projection covers H however close the light comes, even in the dueling
//!    frusta, where H reaches almost to the light point. For an inverted light the map keeps the
//!    surface *furthest* from the PPS light point — PSM's reversed depth test — with the ordinary
//!    `Less` test.

use glam::{DMat3, DMat4, DVec3, DVec4};
use shadowlab_hull::{
    ConvexPolyhedron, LightSpace, NdcDepth, Perspective, Tolerances, ViewPose, psm_near_body,
    visible_body,
};

use crate::error::ShadowError;
use crate::focus::view_model;
use crate::input::{FocusPolicy, PlanInput};
use crate::setup::{LightSetup, ProjectiveMapping, PsmReport, ShadowMapping};
use crate::technique::Technique;
use crate::warp;

/// `|w'|` at most this fraction of `|L|` counts as a light parallel to the image plane (reported
/// as directional in PPS; the construction itself needs no threshold).
pub const DIRECTIONAL_W: f64 = 1e-12;

/// Plans PSM with the virtual camera shift H requires.
pub(crate) fn plan(input: &PlanInput) -> Result<LightSetup, ShadowError> {
    plan_with_shift(input, None)
}

/// Plans PSM; `shift` forces the virtual camera's shift Δ (at least what H requires is used when
/// it is `None`). With `Some(Δ)` and B = V (FocusPolicy::View) this is the configuration of
/// formulas.md §3.3's equivalence: PSM shifted by Δ equals LiSPSM with `n = zn + Δ`.
///
/// # Errors
/// As [`crate::plan`]; [`ShadowError::LightInsideFocusBody`] if one projection from the light cannot
/// cover H (the light at H's centre in PPS, or H spanning half of the light's directions).
pub fn plan_with_shift(input: &PlanInput, shift: Option<f64>) -> Result<LightSetup, ShadowError> {
    let eye = &input.eye;
    let (pose, projection) = (eye.pose, eye.projection);
    let frustum = eye.frustum();
    let body: Vec<DVec3> = match input.focus {
        FocusPolicy::View => frustum.corners().to_vec(),
        FocusPolicy::Light => psm_near_body(
            &frustum,
            &input.scene,
            &input.light.hull_light(),
            &Tolerances::DEFAULT,
        )?
        .ok_or(ShadowError::EmptyFocusBody)?
        .vertices()
        .to_vec(),
        FocusPolicy::ViewScene => visible_body(&frustum, &input.scene, &Tolerances::DEFAULT)?
            .ok_or(ShadowError::EmptyFocusBody)?
            .vertices()
            .to_vec(),
    };
    let (e, v) = (pose.eye(), pose.forward());
    let near = input
        .nearest_visible_depth
        .map_or(projection.near(), |d| d.max(projection.near()));
    let nearest = body
        .iter()
        .map(|h| (*h - e).dot(v))
        .fold(f64::INFINITY, f64::min);
    let shift = shift.unwrap_or_else(|| (near - nearest).max(0.0));
    let virtual_pose = ViewPose::look_to(e - v * shift, v, pose.up())?;
    let virtual_projection = Perspective::new(
        projection.fov_y(),
        projection.aspect(),
        near,
        projection.far() + shift,
    )?;
    let to_pps = virtual_projection.matrix(NdcDepth::NegativeOneToOne);
    let view = virtual_pose.view_matrix();
    let m = to_pps * view;
    let pps: Vec<DVec3> = body
        .iter()
        .map(|h| {
            let q = m * h.extend(1.0);
            q.truncate() / q.w
        })
        .collect();
    let light = m * input.light.homogeneous();
    let directional = light.w.abs() <= DIRECTIONAL_W * light.truncate().length();
    let centre = if light.w == 0.0 {
        pps.iter().copied().sum::<DVec3>() / pps.len() as f64
    } else {
        nearest_point(&pps, light.truncate() / light.w)?
    };
    let travel = centre * light.w - light.truncate();
    let s = travel.length();
    if s <= 0.0 {
        return Err(ShadowError::LightInsideFocusBody);
    }
    // PPS's "camera" looks along +z (near plane −1, far plane +1), up +y.
    let pps_pose = ViewPose::look_to(centre, DVec3::Z, DVec3::Y)?;
    let space = LightSpace::new(&pps_pose, -travel / s)?;
    let rotation = DMat3::from_cols(space.x_axis(), space.y_axis(), space.z_axis()).transpose();
    let to_light_space = DMat4::from_mat3(rotation) * DMat4::from_translation(-centre);
    // w ↦ 1 − (w'/s)·y: the light, at (0, s, 0, w') in this frame, goes to infinity along +y.
    let straighten = DMat4::from_cols(
        DVec4::X,
        DVec4::new(0.0, 1.0, 0.0, -light.w / s),
        DVec4::Z,
        DVec4::W,
    );
    let to_parallel = straighten * to_light_space;
    let mut straight = Vec::with_capacity(pps.len());
    for p in &pps {
        let q = to_parallel * p.extend(1.0);
        if q.w <= 0.0 {
            return Err(ShadowError::LightInsideFocusBody);
        }
        straight.push(q.truncate() / q.w);
    }
    let fitted = warp::fit(&straight, warp::Reference::EYE, 0.0)?;
    let (_, half_fov) = view_model(input)?;
    let gamma = shadowlab_hull::light_view_angle(v, input.light.toward_from(e))?;
    Ok(LightSetup {
        technique: Technique::Psm,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(
            view,
            fitted.matrix * to_parallel * to_pps,
        )),
        gamma,
        half_fov,
        warp: None,
        psm: Some(PsmReport {
            shift,
            near,
            inverted: light.w < 0.0 && !directional,
            directional,
        }),
        focus_body: body,
    })
}

/// The point of the convex hull of `points` nearest `target`: the nearest point over every face
/// (the target's projection, where it falls inside the face) and every edge.
///
/// # Errors
/// [`ShadowError::LightInsideFocusBody`] if `target` lies inside the hull (it is on the inner side
/// of every face plane).
fn nearest_point(points: &[DVec3], target: DVec3) -> Result<DVec3, ShadowError> {
    let hull = ConvexPolyhedron::from_points(points, &Tolerances::DEFAULT)?;
    let vertices = hull.vertices();
    if hull
        .faces()
        .iter()
        .all(|f| f.plane().signed_distance(target) <= 0.0)
    {
        return Err(ShadowError::LightInsideFocusBody);
    }
    let mut best = vertices[0];
    let mut consider = |p: DVec3| {
        if p.distance_squared(target) < best.distance_squared(target) {
            best = p;
        }
    };
    for face in hull.faces() {
        let plane = face.plane();
        let loop_ = face.vertices();
        let projected = plane.project(target);
        // Inside the (convex, counter-clockwise) face: left of every edge.
        let inside = (0..loop_.len()).all(|k| {
            let (a, b) = (vertices[loop_[k]], vertices[loop_[(k + 1) % loop_.len()]]);
            (b - a).cross(projected - a).dot(plane.normal()) >= 0.0
        });
        if inside {
            consider(projected);
        }
        for k in 0..loop_.len() {
            let (a, b) = (vertices[loop_[k]], vertices[loop_[(k + 1) % loop_.len()]]);
            let t = ((target - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            consider(a + (b - a) * t);
        }
    }
    Ok(best)
}
