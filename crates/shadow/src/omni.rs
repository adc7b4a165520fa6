//! What the omnidirectional maps of a point light share ([`crate::cube`], [`crate::paraboloid`]):
//! the part of the light's directions a map serves ([`LightFace`]), and the nearest geometry a
//! map must keep in front of its near plane — chosen from the scene, not a constant.

use glam::DVec3;
use rayon::prelude::*;
use shadowlab_hull::{ConvexPolyhedron, Plane};

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
pub(crate) fn nearest(
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
