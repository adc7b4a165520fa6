//! Extrusion toward a light: the convex hull of a body and a point light's position, and the sweep of
//! a body along the direction toward a directional light (PSM §4.1's M, LiSPSM §3.3's "convex hull
//! of the view frustum and the light position (which is at infinity for a directional light)").
//!
//! # Algorithm
//! Both are intersections of half-spaces read off the body's faces and edges, then clipped out of a
//! bounding box (so faces keep exact planes and no 3-D hull is needed):
//! - **point light at `l`**: conv(body ∪ {l}) is bounded by the faces that do not see `l`
//!   (`n·l + d ≤ 0`) and, for each horizon edge `a → b` (between a face that sees `l` and one that
//!   does not), the plane through `a`, `b`, `l` with normal `(b − a) × (l − a)`. If no face sees `l`,
//!   the hull is the body.
//! - **directional light, unit `u` toward it, length `T`**: body ⊕ {t·u : 0 ≤ t ≤ T} is bounded by the
//!   faces with `n·u ≤ 0`, the faces with `n·u > 0` moved out by `T·(n·u)`, and for each silhouette
//!   edge `a → b` the plane through `a` containing `u`, normal `(b − a) × u`.
//!
//! A silhouette plane whose edge is parallel to `l − a` or `u` (sine below
//! [`Tolerances::relative`]) is skipped: its two faces bound the extrusion there within the snap
//! distance.

use glam::DVec3;

use crate::aabb::Aabb;
use crate::error::HullError;
use crate::finite::{finite, finite_vec, unit_vec};
use crate::light::{Light, Source};
use crate::plane::Plane;
use crate::polyhedron::ConvexPolyhedron;
use crate::tolerance::Tolerances;

/// The half-spaces whose intersection is the extrusion of `body` toward `source`; with
/// `sweep_length = None` a directional extrusion is unbounded toward the light.
pub(crate) fn extrusion_planes(
    body: &ConvexPolyhedron,
    source: Source,
    sweep_length: Option<f64>,
    tolerances: &Tolerances,
) -> Vec<Plane> {
    let faces = body.faces();
    let sees: Vec<bool> = faces
        .iter()
        .map(|f| match source {
            Source::Position(l) => f.plane().signed_distance(l) > 0.0,
            Source::Direction(u) => f.plane().normal().dot(u) > 0.0,
        })
        .collect();
    let mut planes = Vec::with_capacity(faces.len() * 2);
    for (face, &seen) in faces.iter().zip(&sees) {
        let plane = face.plane();
        match (seen, source, sweep_length) {
            (false, _, _) => planes.push(*plane),
            (true, Source::Direction(u), Some(length)) => {
                let offset = plane.offset() - length * plane.normal().dot(u);
                planes.push(Plane::from_unit_normal_offset(plane.normal(), offset));
            }
            (true, _, _) => {}
        }
    }
    let mut edges: Vec<(usize, usize, usize)> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let l = face.vertices();
        for k in 0..l.len() {
            edges.push((l[k], l[(k + 1) % l.len()], f));
        }
    }
    edges.sort_unstable();
    let vertices = body.vertices();
    for &(a, b, f) in &edges {
        if !sees[f] {
            continue;
        }
        let Ok(i) = edges.binary_search_by(|e| (e.0, e.1).cmp(&(b, a))) else {
            continue;
        };
        if sees[edges[i].2] {
            continue;
        }
        let (pa, pb) = (vertices[a], vertices[b]);
        let toward = match source {
            Source::Position(l) => l - pa,
            Source::Direction(u) => u,
        };
        let normal = (pb - pa).cross(toward);
        if normal.length() <= tolerances.relative * (pb - pa).length() * toward.length() {
            continue;
        }
        planes.push(Plane::from_unit_normal_point(normal.normalize(), pa));
    }
    planes
}

impl ConvexPolyhedron {
    /// conv(self ∪ {point}): the body extended toward a point light (PSM §4.1's M). It is the box
    /// bounding both clipped by the faces that do not see `point` and, for each horizon edge `a → b`,
    /// the plane through `a`, `b` and `point`; the body itself if no face sees `point`.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `point`; [`HullError::Internal`] on a numerical failure (a bug).
    pub fn hull_with_point(
        &self,
        point: DVec3,
        tolerances: &Tolerances,
    ) -> Result<Self, HullError> {
        let point = finite_vec(point, "point")?;
        let planes = extrusion_planes(self, Source::Position(point), None, tolerances);
        let bounds = Aabb::of_finite_points(self.vertices().iter().copied().chain([point]));
        clip_box(&bounds, &planes, tolerances, "hull_with_point")
    }

    /// self ⊕ {t·u : 0 ≤ t ≤ length}, `u` = `to_light` normalised: the body swept toward a directional
    /// light. It is the box bounding the sweep clipped by the faces with `n·u ≤ 0`, the faces with
    /// `n·u > 0` moved out by `length·(n·u)`, and for each silhouette edge `a → b` the plane through it
    /// containing `u`.
    ///
    /// # Errors
    /// [`HullError::NonFinite`]/[`HullError::ZeroVector`] naming `to_light`; [`HullError::NonFinite`]
    /// or [`HullError::NotPositive`] naming `length` (zero is accepted and gives the body itself);
    /// [`HullError::Overflow`] if the swept body reaches beyond f64's range;
    /// [`HullError::Internal`] on a numerical failure (a bug).
    pub fn sweep(
        &self,
        to_light: DVec3,
        length: f64,
        tolerances: &Tolerances,
    ) -> Result<Self, HullError> {
        let u = unit_vec(to_light, "to_light")?;
        let length = finite(length, "length")?;
        if length < 0.0 {
            return Err(HullError::NotPositive {
                parameter: "length",
                value: length,
            });
        }
        let planes = extrusion_planes(self, Source::Direction(u), Some(length), tolerances);
        let bounds = Aabb::of_computed_points(
            self.vertices().iter().flat_map(|&v| [v, v + u * length]),
            "sweep",
        )?;
        clip_box(&bounds, &planes, tolerances, "sweep")
    }

    /// The body extruded toward `light`: for a point or spot light the hull with its position
    /// ([`ConvexPolyhedron::hull_with_point`]); for a directional light the sweep toward it up to the
    /// scene bounds, i.e. with the length after which the swept body has passed the whole of `scene`
    /// (`max over S of s·u − min over the body of x·u`, at least 0).
    ///
    /// # Errors
    /// As [`ConvexPolyhedron::hull_with_point`] and [`ConvexPolyhedron::sweep`].
    pub fn extrude_toward_light(
        &self,
        light: &Light,
        scene: &Aabb,
        tolerances: &Tolerances,
    ) -> Result<Self, HullError> {
        match light.source() {
            Source::Position(l) => self.hull_with_point(l, tolerances),
            Source::Direction(u) => {
                let scene_far = scene
                    .corners()
                    .iter()
                    .map(|c| c.dot(u))
                    .fold(f64::NEG_INFINITY, f64::max);
                let (body_near, _) = self.extent_along(u);
                self.sweep(u, (scene_far - body_near).max(0.0), tolerances)
            }
        }
    }
}

/// The box `bounds` clipped by `planes`; the box contains the result, so it cannot be empty.
fn clip_box(
    bounds: &Aabb,
    planes: &[Plane],
    tolerances: &Tolerances,
    operation: &'static str,
) -> Result<ConvexPolyhedron, HullError> {
    ConvexPolyhedron::from_aabb(bounds, tolerances)
        .ok()
        .and_then(|b| b.intersect_planes(planes, tolerances))
        .ok_or(HullError::Internal { operation })
}
