//! The hull target: convex hulls of arbitrary point sets, then a sequence of clips, intersections
//! and extrusions, the focus bodies, light space and the 2-D hull and rectangle.

use arbitrary::{Arbitrary, Unstructured};
use glam::{DVec2, DVec3};
use shadowlab_hull::{
    Aabb, Aabb2, ConvexHull2, ConvexPolyhedron, Frustum, Light, LightSpace, MinAreaRect, NdcDepth,
    Orthographic, Perspective, Plane, Ray, Tolerances, ViewPose, convex_hull_2d, eye_depth_range,
    focus_body, light_view_angle, psm_near_body, visible_body,
};

use crate::num::{Matrix, Num, V2, V3};

/// At most this many operations run on one body, so each input stays fast.
const MAX_OPERATIONS: usize = 16;

/// The tolerances tried: the default and two others of the documented kind (`relative` a small
/// positive fraction, `validation_factor` above 2). Tolerances are plain caller-chosen settings,
/// not input data, so NaN or negative ones are not tried.
const TOLERANCES: [Tolerances; 3] = [
    Tolerances::DEFAULT,
    Tolerances {
        relative: 1e-6,
        rounding_ulps: 64.0,
        validation_factor: 16.0,
    },
    Tolerances {
        relative: 1e-13,
        rounding_ulps: 4.0,
        validation_factor: 4.0,
    },
];

/// A camera pose.
#[derive(Clone, Copy, Debug, Arbitrary)]
struct Pose {
    eye: V3,
    forward: V3,
    up: V3,
}

impl Pose {
    fn get(self) -> Option<ViewPose> {
        ViewPose::look_to(self.eye.get(), self.forward.get(), self.up.get()).ok()
    }
}

/// A frustum, from camera parameters or from any matrix.
#[derive(Clone, Copy, Debug, Arbitrary)]
enum FrustumSpec {
    Perspective {
        pose: Pose,
        fov: Num,
        aspect: Num,
        near: Num,
        far: Num,
    },
    Orthographic {
        pose: Pose,
        sides: [Num; 6],
    },
    Matrix {
        matrix: Matrix,
        ndc: u8,
    },
}

impl FrustumSpec {
    /// The frustum and, for camera parameters, its pose.
    fn get(self) -> Option<(Frustum, Option<ViewPose>)> {
        match self {
            Self::Perspective {
                pose,
                fov,
                aspect,
                near,
                far,
            } => {
                let pose = pose.get()?;
                let projection =
                    Perspective::new(fov.get(), aspect.get(), near.get(), far.get()).ok()?;
                Some((Frustum::perspective(&pose, &projection), Some(pose)))
            }
            Self::Orthographic { pose, sides } => {
                let pose = pose.get()?;
                let [l, r, b, t, n, f] = sides.map(Num::get);
                let projection = Orthographic::new(l, r, b, t, n, f).ok()?;
                Some((Frustum::orthographic(&pose, &projection), Some(pose)))
            }
            Self::Matrix { matrix, ndc } => {
                let ndc = [
                    NdcDepth::NegativeOneToOne,
                    NdcDepth::ZeroToOne,
                    NdcDepth::ReversedZeroToOne,
                ][usize::from(ndc) % 3];
                Some((Frustum::from_view_projection(matrix.get(), ndc).ok()?, None))
            }
        }
    }
}

/// A light.
#[derive(Clone, Copy, Debug, Arbitrary)]
enum LightSpec {
    Directional(V3),
    Point(V3),
    Spot {
        pose: Pose,
        cone: Num,
        near: Num,
        far: Num,
    },
}

impl LightSpec {
    fn get(self) -> Option<Light> {
        match self {
            Self::Directional(to_light) => Light::directional(to_light.get()).ok(),
            Self::Point(position) => Light::point(position.get()).ok(),
            Self::Spot {
                pose,
                cone,
                near,
                far,
            } => {
                let pose = pose.get()?;
                let cone = Perspective::new(cone.get(), 1.0, near.get(), far.get()).ok()?;
                Some(Light::spot(&pose, &cone))
            }
        }
    }
}

/// The body operations start from.
#[derive(Debug, Arbitrary)]
enum Start {
    Points(Vec<V3>),
    Box(V3, V3),
    Frustum(FrustumSpec),
}

/// One operation on the current body (or, for the focus bodies, a new body replacing it).
#[derive(Debug, Arbitrary)]
enum Operation {
    Clip {
        point: V3,
        normal: V3,
    },
    ClipThrough(V3, V3, V3),
    IntersectBox(V3, V3),
    IntersectFrustum(Box<FrustumSpec>),
    IntersectHull(Vec<V3>),
    HullWithPoint(V3),
    Sweep {
        to_light: V3,
        length: Num,
    },
    Extrude {
        light: LightSpec,
        min: V3,
        max: V3,
    },
    Focus {
        view: Box<FrustumSpec>,
        min: V3,
        max: V3,
        light: LightSpec,
        which: u8,
    },
    LightSpace {
        pose: Pose,
        to_light: V3,
        parallel_sin: Option<Num>,
    },
    Query {
        origin: V3,
        direction: V3,
        point: V3,
        tolerance: Num,
    },
}

/// One fuzz input.
#[derive(Debug, Arbitrary)]
struct Input {
    tolerances: u8,
    start: Start,
    operations: Vec<Operation>,
    points_2d: Vec<V2>,
}

/// See [`crate::hull`].
pub(crate) fn hull(data: &[u8]) {
    let Ok(input) = Input::arbitrary_take_rest(Unstructured::new(data)) else {
        return;
    };
    let tolerances = &TOLERANCES[usize::from(input.tolerances) % TOLERANCES.len()];
    let points_2d = points_2d(&input.points_2d);
    plane_hulls(&points_2d, tolerances);
    let start = match &input.start {
        Start::Points(points) => {
            let points = points_3d(points);
            let _ = Aabb::from_points(&points);
            ConvexPolyhedron::from_points(&points, tolerances).ok()
        }
        Start::Box(min, max) => Aabb::new(min.get(), max.get())
            .ok()
            .and_then(|aabb| ConvexPolyhedron::from_aabb(&aabb, tolerances).ok()),
        Start::Frustum(spec) => spec
            .get()
            .and_then(|(frustum, _)| ConvexPolyhedron::from_frustum(&frustum, tolerances).ok()),
    };
    let Some(mut body) = start else {
        return;
    };
    check_body(&body, tolerances);
    for operation in input.operations.iter().take(MAX_OPERATIONS) {
        if let Some(next) = apply(&body, operation, tolerances) {
            check_body(&next, tolerances);
            body = next;
        }
    }
}

/// The body `operation` makes of `body`, if any.
fn apply(
    body: &ConvexPolyhedron,
    operation: &Operation,
    tolerances: &Tolerances,
) -> Option<ConvexPolyhedron> {
    match operation {
        Operation::Clip { point, normal } => {
            let plane = Plane::from_point_normal(point.get(), normal.get()).ok()?;
            body.clip(&plane, tolerances)
        }
        Operation::ClipThrough(a, b, c) => {
            let plane = Plane::from_points(a.get(), b.get(), c.get()).ok()?;
            body.clip(&plane, tolerances)
        }
        Operation::IntersectBox(min, max) => {
            let aabb = Aabb::new(min.get(), max.get()).ok()?;
            body.intersect_aabb(&aabb, tolerances)
        }
        Operation::IntersectFrustum(spec) => {
            let (frustum, _) = spec.get()?;
            body.intersect_frustum(&frustum, tolerances)
        }
        Operation::IntersectHull(points) => {
            let points = points_3d(points);
            let other = ConvexPolyhedron::from_points(&points, tolerances).ok()?;
            check_body(&other, tolerances);
            body.intersect(&other, tolerances)
        }
        Operation::HullWithPoint(point) => body.hull_with_point(point.get(), tolerances).ok(),
        Operation::Sweep { to_light, length } => {
            body.sweep(to_light.get(), length.get(), tolerances).ok()
        }
        Operation::Extrude { light, min, max } => {
            let light = light.get()?;
            let scene = Aabb::new(min.get(), max.get()).ok()?;
            body.extrude_toward_light(&light, &scene, tolerances).ok()
        }
        Operation::Focus {
            view,
            min,
            max,
            light,
            which,
        } => {
            let (view, pose) = view.get()?;
            let scene = Aabb::new(min.get(), max.get()).ok()?;
            let light = light.get()?;
            let focus = match which % 3 {
                0 => focus_body(&view, &scene, &light, tolerances),
                1 => visible_body(&view, &scene, tolerances),
                _ => psm_near_body(&view, &scene, &light, tolerances),
            };
            let focus = focus.ok()??;
            if let Some(pose) = pose {
                let _ = eye_depth_range(&focus, &pose);
                if let Some(to_light) = light.to_light() {
                    let _ = light_view_angle(pose.forward(), to_light);
                }
            }
            Some(focus)
        }
        Operation::LightSpace {
            pose,
            to_light,
            parallel_sin,
        } => {
            let pose = pose.get()?;
            let space = match parallel_sin {
                None => LightSpace::new(&pose, to_light.get()),
                Some(s) => LightSpace::with_parallel_sin(&pose, to_light.get(), s.get()),
            }
            .ok()?;
            assert_eq!(space.validate(), Ok(()), "light space invalid: {space:?}");
            let _ = body.bounds_in(&space.world_to_light(pose.eye()));
            None
        }
        Operation::Query {
            origin,
            direction,
            point,
            tolerance,
        } => {
            let _ = (body.volume(), body.centroid(), body.vertex_mean());
            let _ = (body.bounds(), body.edge_count(), body.scale());
            let _ = body.extent_along(direction.get());
            let _ = body.contains(point.get(), tolerance.get());
            if let Ok(ray) = Ray::new(origin.get(), direction.get())
                && let Some((t0, t1)) = body.ray_interval(&ray)
            {
                assert!(0.0 <= t0 && t0 <= t1, "ray interval [{t0}, {t1}]");
            }
            None
        }
    }
}

/// Coordinates below this fraction of a point set's largest are flushed to zero before a hull is
/// taken, so that the checks of exact containment hold: the hulls' predicates themselves flush
/// below 2^-300 of the largest (shadowlab-hull's `ORIENTATION_FLOOR`, the fix for what this target
/// found), and without this flush a point set spanning more than that range fails
/// `validate_contains` by up to the flushed magnitude (open, docs/fuzzing.md).
const SMALLEST_RELATIVE: f64 = f64::from_bits((1023 - 256) << 52); // 2^-256

/// The largest finite absolute coordinate of `coordinates` times [`SMALLEST_RELATIVE`].
fn flush_limit(coordinates: impl Iterator<Item = f64>) -> f64 {
    coordinates
        .map(f64::abs)
        .filter(|c| c.is_finite())
        .fold(0.0, f64::max)
        * SMALLEST_RELATIVE
}

/// A 2-D point set, tiny coordinates flushed to zero.
fn points_2d(points: &[V2]) -> Vec<DVec2> {
    let points: Vec<DVec2> = points.iter().map(|p| p.get()).collect();
    let limit = DVec2::splat(flush_limit(points.iter().flat_map(|p| p.to_array())));
    points
        .into_iter()
        .map(|p| DVec2::select(p.abs().cmplt(limit), DVec2::ZERO, p))
        .collect()
}

/// A 3-D point set, tiny coordinates flushed to zero.
fn points_3d(points: &[V3]) -> Vec<DVec3> {
    let points: Vec<DVec3> = points.iter().map(|p| p.get()).collect();
    let limit = DVec3::splat(flush_limit(points.iter().flat_map(|p| p.to_array())));
    points
        .into_iter()
        .map(|p| DVec3::select(p.abs().cmplt(limit), DVec3::ZERO, p))
        .collect()
}

/// Every body the crate returns validates (its documented guarantee).
fn check_body(body: &ConvexPolyhedron, tolerances: &Tolerances) {
    assert_eq!(body.validate(tolerances), Ok(()), "invalid body: {body:?}");
}

/// The 2-D hull, its bounds and the minimum-area rectangle of `points`.
fn plane_hulls(points: &[DVec2], tolerances: &Tolerances) {
    let _ = Aabb2::from_points(points);
    let Ok(hull) = convex_hull_2d(points) else {
        return;
    };
    if let ConvexHull2::Polygon(polygon) = &hull {
        assert_eq!(polygon.validate(), Ok(()), "invalid polygon: {polygon:?}");
        assert_eq!(
            polygon.validate_contains(points),
            Ok(()),
            "the hull misses a point: {polygon:?}"
        );
        let _ = polygon.area();
    }
    let rectangle = MinAreaRect::of_hull(&hull);
    let _ = (rectangle.area(), rectangle.corners());
    let _ = rectangle.validate(points, tolerances);
}
