//! What every technique plans from: the focus body B of the input's policy, in world space and
//! in light space, and the 2-D model of the view that the unit-free parameter rules work in.

use glam::DVec3;
use shadowlab_hull::{ConvexPolyhedron, Tolerances, focus_body, visible_body};
use shadowlab_params::{DepthRange, FrustumModel, HalfFov};

use crate::error::ShadowError;
use crate::frame::LightFrame;
use crate::input::{FocusPolicy, PlanInput};
use crate::technique::Technique;

/// The vertices of the focus body B of `input`'s policy, in world space (the view frustum's
/// corners in their order for [`FocusPolicy::View`]).
pub(crate) fn focus_points(input: &PlanInput) -> Result<Vec<DVec3>, ShadowError> {
    match input.focus {
        FocusPolicy::View => Ok(input.eye.frustum().corners().to_vec()),
        FocusPolicy::Light | FocusPolicy::ViewScene => {
            Ok(focus_polyhedron(input)?.vertices().to_vec())
        }
    }
}

/// The focus body B of `input`'s policy as a polyhedron (world space).
pub(crate) fn focus_polyhedron(input: &PlanInput) -> Result<ConvexPolyhedron, ShadowError> {
    let frustum = input.eye.frustum();
    match input.focus {
        FocusPolicy::View => Ok(ConvexPolyhedron::from_frustum(
            &frustum,
            &Tolerances::DEFAULT,
        )?),
        FocusPolicy::Light => focus_body(
            &frustum,
            &input.scene,
            &input.light.hull_light(),
            &Tolerances::DEFAULT,
        )?
        .ok_or(ShadowError::EmptyFocusBody),
        FocusPolicy::ViewScene => visible_body(&frustum, &input.scene, &Tolerances::DEFAULT)?
            .ok_or(ShadowError::EmptyFocusBody),
    }
}

/// `input`'s light frame for `technique`, the vertices of its focus body B (world) and the same
/// vertices in light space: where every light-space technique starts.
pub(crate) fn focus_in_light_space(
    input: &PlanInput,
    technique: Technique,
) -> Result<(LightFrame, Vec<DVec3>, Vec<DVec3>), ShadowError> {
    let frame = LightFrame::new(&input.eye, &input.light, technique.key())?;
    let world_points = focus_points(input)?;
    let points = frame
        .light_points(&world_points)
        .ok_or(ShadowError::LightInsideFocusBody)?;
    Ok((frame, world_points, points))
}

/// The 2-D model of the view the parameter rules work in: the eye's depth range and φ toward the
/// light.
pub(crate) fn view_model(input: &PlanInput) -> Result<(FrustumModel, f64), ShadowError> {
    let eye = &input.eye;
    let toward = input.light.toward_from(eye.pose.eye());
    let half_fov = eye.half_fov_toward(toward);
    let model = FrustumModel::new(
        DepthRange::new(eye.projection.near(), eye.projection.far())?,
        HalfFov::from_radians(half_fov)?,
    );
    Ok((model, half_fov))
}
