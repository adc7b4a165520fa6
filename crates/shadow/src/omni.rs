//! What the omnidirectional maps of a point light share ([`crate::cube`], [`crate::paraboloid`]):
//! the part of the light's directions a map serves ([`LightFace`]), and the nearest geometry a
//! map must keep in front of its near plane — chosen from the scene, not a constant.

use glam::DVec3;
use rayon::prelude::*;
use shadowlab_hull::{ConvexPolyhedron, Plane, Tolerances};

use crate::error::ShadowError;
use crate::focus::{focus_polyhedron, view_model};
use crate::input::{LightSource, PlanInput};
use crate::setup::{LightSetup, ShadowMapping};
use crate::technique::Technique;

/// The least near distance of a face, as a fraction of its far distance: where geometry touches
/// the light, the near plane cannot reach it, and what lies nearer is left out of the map.
pub const MIN_NEAR_FRACTION: f64 = 1e-5;

/// What every face of a point light's omnidirectional map is planned from: the light, its range,
/// the focus body B, and the view's γ and φ (which the set-ups report).
pub(crate) struct PointLightPlan<'a> {
    technique: Technique,
    position: DVec3,
    range: Option<f64>,
    body: ConvexPolyhedron,
    gamma: f64,
    half_fov: f64,
    positions: &'a [DVec3],
    triangles: &'a [[u32; 3]],
}

/// A face's focus: its part of B and its near and far distances.
pub(crate) struct FaceFocus {
    /// B ∩ the face's directions.
    pub(crate) part: ConvexPolyhedron,
    /// The near distance: the nearest geometry in the part, floored at [`MIN_NEAR_FRACTION`] of
    /// the far.
    pub(crate) near: f64,
    /// The far distance: the part's farthest vertex, no farther than the range.
    pub(crate) far: f64,
}

impl<'a> PointLightPlan<'a> {
    /// The plan of `technique` for `input`'s point light over the scene's triangles.
    ///
    /// # Errors
    /// [`ShadowError::UnservedLight`] for a light that is not a point light; B's and γ's errors.
    pub(crate) fn new(
        technique: Technique,
        input: &PlanInput,
        positions: &'a [DVec3],
        triangles: &'a [[u32; 3]],
    ) -> Result<Self, ShadowError> {
        let LightSource::Point { position, range } = input.light else {
            return Err(ShadowError::UnservedLight {
                technique: technique.key(),
                light: input.light.kind(),
                serving: Technique::DIRECTED_LIGHT_TECHNIQUES,
            });
        };
        let eye = input.eye.pose;
        Ok(Self {
            technique,
            position,
            range,
            body: focus_polyhedron(input)?,
            gamma: shadowlab_hull::light_view_angle(
                eye.forward(),
                input.light.toward_from(eye.eye()),
            )?,
            half_fov: view_model(input)?.1,
            positions,
            triangles,
        })
    }

    /// The light's position.
    pub(crate) fn position(&self) -> DVec3 {
        self.position
    }

    /// `face`'s focus, its distances measured by `depth` (of a point; the far is the greatest
    /// over the part's vertices, so `depth` must be convex) and `nearest_of` (the least depth over
    /// a clipped triangle's polygon); `None` if the face's part of B is empty or holds no geometry
    /// before its far end — such a face serves no visible point.
    pub(crate) fn focus(
        &self,
        face: &LightFace,
        depth: impl Fn(DVec3) -> f64,
        nearest_of: impl Fn(&[DVec3]) -> f64 + Sync,
    ) -> Option<FaceFocus> {
        let part = self
            .body
            .intersect_planes(&face.planes(), &Tolerances::DEFAULT)?;
        let far = part
            .vertices()
            .iter()
            .map(|v| depth(*v))
            .fold(0.0, f64::max);
        let far = self.range.map_or(far, |range| far.min(range));
        let nearest = nearest(&part, self.positions, self.triangles, nearest_of)?;
        (far > 0.0 && nearest < far).then(|| FaceFocus {
            near: nearest.max(far * MIN_NEAR_FRACTION),
            far,
            part,
        })
    }

    /// The set-up of one face: its mapping, and its part of B's vertices.
    pub(crate) fn setup(&self, mapping: ShadowMapping, focus: &FaceFocus) -> LightSetup {
        LightSetup {
            technique: self.technique,
            mapping,
            gamma: self.gamma,
            half_fov: self.half_fov,
            warp: None,
            psm: None,
            focus_body: focus.part.vertices().to_vec(),
        }
    }
}

/// The part of a point light's directions one of its maps serves: a face of its cube (the
/// directions whose largest component, in absolute value, lies along the face's axis) or a
/// hemisphere of its dual-paraboloid map (the directions on the axis's side).
#[derive(Clone, Debug, PartialEq)]
pub struct LightFace {
    /// `+x`, `-x`, `+y`, `-y`, `+z`, `-z` for a cube face; `front` or `back` for a hemisphere.
    pub name: &'static str,
    /// The light's position.
    pub light: DVec3,
    /// The face's axis, unit.
    pub axis: DVec3,
    /// A cube face's two axes across it (unit, perpendicular to `axis`); `None` for a hemisphere.
    pub across: Option<[DVec3; 2]>,
}

impl LightFace {
    /// How far inside the face the direction from the light to `world` lies, as a difference of
    /// direction cosines: `(a·d − max(|b·d|, |c·d|))/|d|` for a cube face (positive where `a` is the
    /// direction's major axis, zero on the cube's edges between faces), `a·d/|d|` for a hemisphere;
    /// 0 at the light itself. Of a light's faces, the one with the greatest value serves `world`.
    #[must_use]
    pub fn inside(&self, world: DVec3) -> f64 {
        let d = world - self.light;
        let length = d.length();
        if length == 0.0 {
            return 0.0;
        }
        let along = self.axis.dot(d);
        let lateral = self
            .across
            .map_or(0.0, |[b, c]| b.dot(d).abs().max(c.dot(d).abs()));
        (along - lateral) / length
    }

    /// The planes through the light that bound the face's directions (outward normals): for a cube
    /// face, `(b − a)·d ≤ 0`, `(−b − a)·d ≤ 0` and likewise for `c`; for a hemisphere, `−a·d ≤ 0`.
    pub(crate) fn planes(&self) -> Vec<Plane> {
        let a = self.axis;
        let normals = match self.across {
            Some([b, c]) => vec![b - a, -b - a, c - a, -c - a],
            None => vec![-a],
        };
        normals
            .into_iter()
            .map(|n| Plane::from_point_normal(self.light, n).expect("finite, non-zero normals"))
            .collect()
    }
}

/// The least of `measure` over the scene's triangles (`positions`, `triangles`) clipped to `body`,
/// `measure` taking a clipped triangle's corners (a convex polygon, never empty); `None` if no
/// triangle reaches into `body`. Triangles outside `body`'s bounding box are skipped before
/// clipping. The least value is the same in any order, so the parallel search is deterministic.
fn nearest(
    body: &ConvexPolyhedron,
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    measure: impl Fn(&[DVec3]) -> f64 + Sync,
) -> Option<f64> {
    let bounds = body.bounds();
    let planes: Vec<Plane> = body.planes().copied().collect();
    let least = triangles
        .par_iter()
        .map(|triangle| {
            let corners = triangle.map(|k| positions[k as usize]);
            let low = corners[0].min(corners[1]).min(corners[2]);
            let high = corners[0].max(corners[1]).max(corners[2]);
            if low.cmpgt(bounds.max()).any() || high.cmplt(bounds.min()).any() {
                return f64::INFINITY;
            }
            let polygon = clip_polygon(corners.to_vec(), &planes);
            if polygon.is_empty() {
                return f64::INFINITY;
            }
            measure(&polygon)
        })
        .reduce(|| f64::INFINITY, f64::min);
    least.is_finite().then_some(least)
}

/// `polygon` (convex, planar) clipped to the inner sides of `planes` (Sutherland–Hodgman): the
/// corners that remain, possibly none.
fn clip_polygon(mut polygon: Vec<DVec3>, planes: &[Plane]) -> Vec<DVec3> {
    for plane in planes {
        if polygon.is_empty() {
            break;
        }
        let mut kept = Vec::with_capacity(polygon.len() + 1);
        for k in 0..polygon.len() {
            let (p, q) = (polygon[k], polygon[(k + 1) % polygon.len()]);
            let (dp, dq) = (plane.signed_distance(p), plane.signed_distance(q));
            if dp <= 0.0 {
                kept.push(p);
            }
            if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
                kept.push(p + (q - p) * (dp / (dp - dq)));
            }
        }
        polygon = kept;
    }
    polygon
}
