//! The dual-paraboloid shadow map of a point light (Brabec, Annen & Seidel, *Shadow Mapping for
//! Hemispherical and Omnidirectional Light Sources*, CGI 2002, §3).
//!
//! Each hemisphere of directions from the light is mapped onto the unit disk by the paraboloid
//! `f(x, y) = ½ − ½(x² + y²)`: a unit direction `d = (d_x, d_y, d_z)` in the hemisphere's frame
//! (`d_z ≥ 0`) lands at `(x, y) = (d_x, d_y)/(1 + d_z)` (§3, eq. 3), and back at
//! `d = (2x, 2y, 1 − x² − y²)/(1 + x² + y²)`. Depth is the distance from the light, linear between
//! a near and a far distance (§3.2: `(|p − l| − near)/(far − near)`).
//!
//! Engines render the map by transforming *vertices* through the paraboloid and rasterizing
//! straight edges between them — wrong for any triangle whose edges the paraboloid bends, which
//! is the dual-paraboloid map's best-known artifact (Brabec et al. §4: "the tessellation of the
//! scene must be fine enough"). shadowlab makes the map exactly instead: one ray per texel centre
//! through the inverse mapping ([`crate::ShadowMap::cast`]), like the logarithmic map, so what is
//! measured is the parameterisation's own aliasing, not the tessellation's.
//!
//! The hemispheres are fixed to the light's frame, as Brabec et al. orient them; a point light of
//! a scene has no frame of its own, so shadowlab gives it the world's: the front hemisphere looks
//! down (`−y`, toward the floor a ceiling light hangs over), the back one up — fixed, so the maps'
//! texel grids do not move as the camera does (a camera-dependent axis would make every frame's
//! grid a new one: shimmer). shadowlab's focusing, named: each hemisphere's near distance is the
//! nearest geometry of its part of B and its far distance the furthest vertex of that part (no
//! further than the light's range).

use glam::DVec3;

use crate::error::ShadowError;
use crate::input::PlanInput;
use crate::omni::{LightFace, PointLightPlan};
pub use crate::paraboloid_map::{LanesAt, ParaboloidMap};
use crate::setup::{LightSetup, ShadowMapping};
use crate::technique::Technique;

/// The front hemisphere's axis: down, the world's −y (module docs).
pub const FRONT: DVec3 = DVec3::NEG_Y;

/// Plans the dual-paraboloid map of `input`'s point light over the scene's triangles: one set-up
/// per hemisphere that holds geometry of B, with the hemisphere it serves.
///
/// # Errors
/// [`ShadowError::UnservedLight`] for a light that is not a point light;
/// [`ShadowError::EmptyFocusBody`] if neither hemisphere holds geometry of B; geometry errors.
pub(crate) fn plan(
    input: &PlanInput,
    positions: &[DVec3],
    triangles: &[[u32; 3]],
) -> Result<Vec<(LightFace, LightSetup)>, ShadowError> {
    let plan = PointLightPlan::new(Technique::DualParaboloid, input, positions, triangles)?;
    let position = plan.position();
    let mut hemispheres = Vec::new();
    for (name, axis) in [("front", FRONT), ("back", -FRONT)] {
        let face = LightFace {
            name,
            light: position,
            axis,
            across: None,
        };
        let Some(focus) = plan.focus(
            &face,
            |p| (p - position).length(),
            |polygon| distance_to_polygon(position, polygon),
        ) else {
            continue;
        };
        let map = ParaboloidMap::new(position, axis, focus.near, focus.far);
        hemispheres.push((face, plan.setup(ShadowMapping::Paraboloid(map), &focus)));
    }
    if hemispheres.is_empty() {
        return Err(ShadowError::EmptyFocusBody);
    }
    Ok(hemispheres)
}

/// The distance from `point` to the convex planar `polygon` (its corners in order; none: ∞): to
/// its plane where the point projects inside it, else to its nearest edge.
fn distance_to_polygon(point: DVec3, polygon: &[DVec3]) -> f64 {
    let to_segment = |a: DVec3, b: DVec3| {
        let ab = b - a;
        let length2 = ab.length_squared();
        let t = if length2 > 0.0 {
            ((point - a).dot(ab) / length2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a + ab * t - point).length()
    };
    let edges = polygon.len();
    let nearest_edge = (0..edges)
        .map(|k| to_segment(polygon[k], polygon[(k + 1) % edges]))
        .fold(f64::INFINITY, f64::min);
    if edges < 3 {
        return nearest_edge;
    }
    // The plane through the corners (Newell's normal, robust for any convex polygon).
    let normal = (0..edges)
        .map(|k| polygon[k].cross(polygon[(k + 1) % edges]))
        .sum::<DVec3>();
    let Some(normal) = normal.try_normalize() else {
        return nearest_edge;
    };
    let height = (point - polygon[0]).dot(normal);
    let projected = point - normal * height;
    let inside = (0..edges).all(|k| {
        let (a, b) = (polygon[k], polygon[(k + 1) % edges]);
        (b - a).cross(projected - a).dot(normal) >= 0.0
    });
    if inside { height.abs() } else { nearest_edge }
}
