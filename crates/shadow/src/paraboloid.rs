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

use glam::{DVec2, DVec3};

use crate::error::ShadowError;
use crate::input::PlanInput;
use crate::omni::{LightFace, PointLightPlan};
use crate::setup::{LightSetup, ShadowMapping};
use crate::technique::Technique;

/// The front hemisphere's axis: down, the world's −y (module docs).
pub const FRONT: DVec3 = DVec3::NEG_Y;

/// One hemisphere's paraboloid map: the light, the hemisphere's frame and its depth range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParaboloidMap {
    light: DVec3,
    /// The frame's axes in world space: `x` and `y` across the map, `z` the hemisphere's axis.
    axes: [DVec3; 3],
    near: f64,
    far: f64,
}

impl ParaboloidMap {
    /// The map of the hemisphere around `axis` (unit) from `light`, depths from `near` to `far`.
    /// Its image's up is world +y projected across the axis, or −z where the axis lies along ±y.
    #[must_use]
    pub fn new(light: DVec3, axis: DVec3, near: f64, far: f64) -> Self {
        let hint = if axis.y.abs() >= axis.x.abs().max(axis.z.abs()) {
            DVec3::NEG_Z
        } else {
            DVec3::Y
        };
        let x = hint.cross(axis).normalize();
        let y = axis.cross(x);
        Self {
            light,
            axes: [x, y, axis],
            near,
            far,
        }
    }

    /// The light's position.
    #[must_use]
    pub fn light(&self) -> DVec3 {
        self.light
    }

    /// The hemisphere's axis.
    #[must_use]
    pub fn axis(&self) -> DVec3 {
        self.axes[2]
    }

    /// The near and far distances.
    #[must_use]
    pub fn depth_range(&self) -> (f64, f64) {
        (self.near, self.far)
    }

    /// Normalized device coordinates of `world`: the paraboloid's `(x, y)` and the distance's
    /// `2(r − near)/(far − near) − 1`; `None` at the light and at the opposite pole (`d_z = −1`),
    /// where the paraboloid has no image.
    #[inline]
    #[must_use]
    pub fn ndc(&self, world: DVec3) -> Option<DVec3> {
        let d = world - self.light;
        let r = d.length();
        let [x, y, z] = self.axes;
        let denominator = r + z.dot(d);
        if r == 0.0 || denominator <= 0.0 {
            return None;
        }
        Some(DVec3::new(
            x.dot(d) / denominator,
            y.dot(d) / denominator,
            self.ndc_of_distance(r),
        ))
    }

    /// The NDC depth of a point at distance `r` from the light.
    fn ndc_of_distance(&self, r: f64) -> f64 {
        2.0 * (r - self.near) / (self.far - self.near) - 1.0
    }

    /// The NDC depth of `world` (its distance from the light).
    #[must_use]
    pub fn ndc_depth(&self, world: DVec3) -> f64 {
        self.ndc_of_distance((world - self.light).length())
    }

    /// The ray of the texel centre at NDC `(x, y)`: from the near to the far distance along the
    /// direction the paraboloid maps there; `None` outside the unit disk, which no direction of
    /// the hemisphere reaches.
    #[must_use]
    pub fn texel_ray(&self, x: f64, y: f64) -> Option<(DVec3, DVec3)> {
        let s = x * x + y * y;
        if s > 1.0 {
            return None;
        }
        let [ax, ay, az] = self.axes;
        let direction = (ax * (2.0 * x) + ay * (2.0 * y) + az * (1.0 - s)) / (1.0 + s);
        Some((
            self.light + direction * self.near,
            self.light + direction * self.far,
        ))
    }

    /// The derivative of NDC `(x, y)` at `world` along `direction` (closed form: the unit
    /// direction `n = d/r` moves by `(δ − n(n·δ))/r`, and `x = n_x/(1 + n_z)`); `None` where
    /// [`Self::ndc`] is.
    #[must_use]
    pub fn ndc_derivative(&self, world: DVec3, direction: DVec3) -> Option<DVec2> {
        let d = world - self.light;
        let r = d.length();
        if r == 0.0 {
            return None;
        }
        let n = d / r;
        let dn = (direction - n * n.dot(direction)) / r;
        let [x, y, z] = self.axes;
        let (nz, dnz) = (z.dot(n), z.dot(dn));
        let denominator = 1.0 + nz;
        if denominator <= 0.0 {
            return None;
        }
        let along = |axis: DVec3| {
            (axis.dot(dn) * denominator - axis.dot(n) * dnz) / (denominator * denominator)
        };
        Some(DVec2::new(along(x), along(y)))
    }
}

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
