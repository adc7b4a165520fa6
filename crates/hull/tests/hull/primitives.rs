//! Planes, boxes, rays, segments, bodies' measures and lights: small closed-form checks.

use glam::{DAffine3, DQuat, DVec3};
use shadowlab_hull::{
    Aabb, ConvexPolyhedron, Light, Perspective, Plane, Ray, Segment, ViewPose, eye_depth_range,
};

use crate::support::TOL;

fn unit_box() -> Aabb {
    Aabb::new(DVec3::new(-1.0, 0.0, 2.0), DVec3::new(3.0, 2.0, 3.0)).expect("valid")
}

#[test]
fn planes_are_outward_half_spaces() {
    let plane = Plane::from_point_normal(DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.0, 0.0, 5.0))
        .expect("valid");
    assert_eq!(plane.normal(), DVec3::Z);
    assert_eq!(plane.offset(), -2.0);
    assert!(plane.contains(DVec3::ZERO, 0.0));
    assert!(!plane.contains(DVec3::new(0.0, 0.0, 3.0), 0.5));
    assert_eq!(
        plane.project(DVec3::new(1.0, 2.0, 7.0)),
        DVec3::new(1.0, 2.0, 2.0)
    );
    assert_eq!(plane.flipped().signed_distance(DVec3::ZERO), 2.0);
    // Counter-clockwise seen from +z: the normal is +z, the half-space below.
    let ccw = Plane::from_points(DVec3::ZERO, DVec3::X, DVec3::Y).expect("valid");
    assert_eq!(ccw.normal(), DVec3::Z);
    assert!(Plane::from_points(DVec3::ZERO, DVec3::X, DVec3::X * 2.0).is_err());
}

#[test]
fn boxes() {
    let b = unit_box();
    assert_eq!(b.size(), DVec3::new(4.0, 2.0, 1.0));
    assert_eq!(b.center(), DVec3::new(1.0, 1.0, 2.5));
    let corners = b.corners();
    assert_eq!(corners[0], b.min());
    assert_eq!(corners[7], b.max());
    assert_eq!(corners[5], DVec3::new(3.0, 0.0, 3.0));
    for plane in b.planes() {
        for c in corners {
            assert!(plane.signed_distance(c) <= 0.0);
        }
        assert_eq!(
            corners
                .iter()
                .filter(|c| plane.signed_distance(**c) == 0.0)
                .count(),
            4
        );
    }
    let turned = b
        .transformed_bounds(&DAffine3::from_quat(DQuat::from_rotation_z(
            std::f64::consts::FRAC_PI_2,
        )))
        .expect("in range");
    // A box near f64's largest value, doubled, overflows: an error, not infinite bounds.
    let huge = Aabb::new(DVec3::splat(1e308), DVec3::splat(1.5e308)).expect("a box");
    assert_eq!(
        huge.transformed_bounds(&DAffine3::from_scale(DVec3::splat(2.0))),
        Err(shadowlab_hull::HullError::Overflow {
            operation: "transformed_bounds"
        })
    );
    assert!((turned.size() - DVec3::new(2.0, 4.0, 1.0)).length() <= 1e-12);
    let body = ConvexPolyhedron::from_aabb(&b, &TOL).expect("solid");
    assert_eq!(body.validate(&TOL), Ok(()));
    assert_eq!(body.volume(), 8.0);
    assert_eq!(body.centroid(), b.center());
    assert_eq!(body.bounds(), b);
    assert_eq!(body.edge_count(), 12);
    assert_eq!(body.extent_along(DVec3::X), (-1.0, 3.0));
}

#[test]
fn rays_and_segments() {
    let body = ConvexPolyhedron::from_aabb(&unit_box(), &TOL).expect("solid");
    let ray = Ray::new(DVec3::new(-5.0, 1.0, 2.5), DVec3::X * 2.0).expect("valid");
    assert_eq!(ray.direction(), DVec3::X);
    assert_eq!(body.ray_interval(&ray), Some((4.0, 8.0)));
    assert_eq!(ray.at(4.0), DVec3::new(-1.0, 1.0, 2.5));
    let away = Ray::new(DVec3::new(-5.0, 1.0, 2.5), DVec3::NEG_X).expect("valid");
    assert_eq!(body.ray_interval(&away), None);
    let plane = Plane::from_point_normal(DVec3::X, DVec3::X).expect("valid");
    assert_eq!(ray.intersect_plane(&plane), Some(6.0));
    assert_eq!(away.intersect_plane(&plane), None);
    let segment = Segment::new(DVec3::ZERO, DVec3::X * 4.0).expect("valid");
    assert_eq!(segment.intersect_plane(&plane), Some(0.25));
    assert_eq!(segment.at(0.25), DVec3::X);
    assert_eq!(
        Segment::new(DVec3::ZERO, DVec3::X * 0.5)
            .expect("valid")
            .intersect_plane(&plane),
        None
    );
}

#[test]
fn lights_and_depths() {
    let sun = Light::directional(DVec3::new(0.0, 3.0, 4.0)).expect("valid");
    let to_light = sun.to_light().expect("directional");
    assert!(to_light.distance(DVec3::new(0.0, 0.6, 0.8)) <= 1e-15);
    assert_eq!(sun.position(), None);
    assert!(sun.frustum().is_none());
    assert_eq!(sun.light_vector(DVec3::ZERO), Ok(to_light));
    let lamp = Light::point(DVec3::new(0.0, 10.0, 0.0)).expect("valid");
    assert_eq!(lamp.light_vector(DVec3::new(0.0, 5.0, 0.0)), Ok(DVec3::Y));
    let pose =
        ViewPose::look_to(DVec3::new(0.0, 10.0, 0.0), DVec3::NEG_Y, DVec3::Z).expect("valid");
    let spot = Light::spot(
        &pose,
        &Perspective::new(1.0, 1.0, 1.0, 20.0).expect("valid"),
    );
    assert_eq!(spot.position(), Some(pose.eye()));
    assert!(
        spot.light_vector(DVec3::ZERO)
            .expect("valid")
            .distance(DVec3::Y)
            <= 1e-15
    );
    let body = ConvexPolyhedron::from_aabb(&unit_box(), &TOL).expect("solid");
    let camera =
        ViewPose::look_to(DVec3::new(1.0, 1.0, 10.0), DVec3::NEG_Z, DVec3::Y).expect("valid");
    assert_eq!(eye_depth_range(&body, &camera), (7.0, 8.0));
}
