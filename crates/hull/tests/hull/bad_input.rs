//! Every rejected input is a clear `Err` naming the bad parameter, never a NaN or a panic.

use glam::{DMat4, DVec2, DVec3};
use shadowlab_hull::{
    Aabb, ConvexPolyhedron, Degeneracy, Frustum, HullError, Light, LightSpace, MinAreaRect,
    NdcDepth, Orthographic, Perspective, Plane, Ray, ViewPose, convex_hull_2d, focus_body,
};

use crate::support::TOL;

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

fn pose() -> ViewPose {
    ViewPose::look_to(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).expect("valid")
}

#[test]
fn non_finite_values_are_named() {
    let non_finite = |parameter| HullError::NonFinite { parameter };
    assert_eq!(
        ViewPose::look_to(DVec3::splat(NAN), DVec3::NEG_Z, DVec3::Y),
        Err(non_finite("eye"))
    );
    assert_eq!(
        ViewPose::look_to(DVec3::ZERO, DVec3::new(0.0, INF, 1.0), DVec3::Y),
        Err(non_finite("forward"))
    );
    assert_eq!(
        Perspective::new(NAN, 1.0, 1.0, 2.0),
        Err(non_finite("fov_y"))
    );
    assert_eq!(Perspective::new(1.0, 1.0, 1.0, INF), Err(non_finite("far")));
    assert_eq!(
        Orthographic::new(0.0, 1.0, 0.0, 1.0, NAN, 1.0),
        Err(non_finite("near"))
    );
    assert_eq!(
        Aabb::new(DVec3::new(0.0, NAN, 0.0), DVec3::ONE),
        Err(non_finite("min"))
    );
    assert_eq!(
        Light::directional(DVec3::new(INF, 0.0, 0.0)),
        Err(non_finite("to_light"))
    );
    assert_eq!(
        Light::point(DVec3::splat(-INF)),
        Err(non_finite("position"))
    );
    assert_eq!(
        ConvexPolyhedron::from_points(
            &[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.0, 0.0, NAN)],
            &TOL
        ),
        Err(non_finite("points"))
    );
    assert_eq!(
        convex_hull_2d(&[DVec2::ZERO, DVec2::new(NAN, 1.0)]),
        Err(non_finite("points"))
    );
    assert_eq!(
        MinAreaRect::of_points(&[DVec2::new(INF, 1.0)]),
        Err(non_finite("points"))
    );
    assert_eq!(
        Frustum::from_view_projection(
            DMat4::from_diagonal(glam::DVec4::new(1.0, NAN, 1.0, 1.0)),
            NdcDepth::NegativeOneToOne
        ),
        Err(non_finite("view_projection"))
    );
    assert_eq!(
        Plane::from_point_normal(DVec3::ZERO, DVec3::splat(NAN)),
        Err(non_finite("normal"))
    );
    assert_eq!(
        Ray::new(DVec3::splat(INF), DVec3::X),
        Err(non_finite("origin"))
    );
    assert_eq!(
        LightSpace::new(&pose(), DVec3::splat(NAN)),
        Err(non_finite("to_light"))
    );
    let body =
        ConvexPolyhedron::from_aabb(&Aabb::new(DVec3::ZERO, DVec3::ONE).expect("valid"), &TOL)
            .expect("solid");
    assert_eq!(
        body.hull_with_point(DVec3::splat(NAN), &TOL),
        Err(non_finite("point"))
    );
    assert_eq!(body.sweep(DVec3::X, NAN, &TOL), Err(non_finite("length")));
}

#[test]
fn zero_size_and_inverted_boxes() {
    let flat = Aabb::new(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)).expect("a flat box is a value");
    assert_eq!(
        ConvexPolyhedron::from_aabb(&flat, &TOL),
        Err(HullError::ZeroSizeBox { axis: 1 })
    );
    let view = Frustum::perspective(
        &pose(),
        &Perspective::new(1.0, 1.0, 0.1, 10.0).expect("valid"),
    );
    let light = Light::directional(DVec3::Y).expect("valid");
    assert_eq!(
        focus_body(&view, &flat, &light, &TOL),
        Err(HullError::ZeroSizeBox { axis: 1 })
    );
    assert_eq!(
        Aabb::new(DVec3::ONE, DVec3::ZERO),
        Err(HullError::InvertedBox { axis: 0 })
    );
}

#[test]
fn projection_ranges() {
    for fov in [0.0, -0.1, std::f64::consts::PI, 4.0] {
        assert_eq!(
            Perspective::new(fov, 1.0, 0.1, 10.0),
            Err(HullError::FieldOfViewOutOfRange { fov_y: fov })
        );
    }
    assert_eq!(
        Perspective::new(1.0, 1.0, 10.0, 10.0),
        Err(HullError::EmptyRange {
            parameter: "near/far",
            lo: 10.0,
            hi: 10.0
        })
    );
    assert_eq!(
        Perspective::new(1.0, 1.0, 20.0, 10.0),
        Err(HullError::EmptyRange {
            parameter: "near/far",
            lo: 20.0,
            hi: 10.0
        })
    );
    assert_eq!(
        Perspective::new(1.0, 1.0, 0.0, 10.0),
        Err(HullError::NotPositive {
            parameter: "near",
            value: 0.0
        })
    );
    assert_eq!(
        Perspective::new(1.0, -2.0, 1.0, 10.0),
        Err(HullError::NotPositive {
            parameter: "aspect",
            value: -2.0
        })
    );
    assert_eq!(
        Orthographic::new(1.0, 1.0, 0.0, 1.0, 0.0, 1.0),
        Err(HullError::EmptyRange {
            parameter: "left/right",
            lo: 1.0,
            hi: 1.0
        })
    );
}

#[test]
fn degenerate_vectors_and_matrices() {
    assert_eq!(
        ViewPose::look_to(DVec3::ZERO, DVec3::ZERO, DVec3::Y),
        Err(HullError::ZeroVector {
            parameter: "forward"
        })
    );
    assert_eq!(
        ViewPose::look_to(DVec3::ZERO, DVec3::Y, DVec3::Y * 3.0),
        Err(HullError::ParallelVectors {
            parameter: "forward/up_hint"
        })
    );
    assert_eq!(
        Light::directional(DVec3::ZERO),
        Err(HullError::ZeroVector {
            parameter: "to_light"
        })
    );
    assert_eq!(
        Frustum::from_view_projection(DMat4::ZERO, NdcDepth::ZeroToOne),
        Err(HullError::SingularMatrix {
            parameter: "view_projection"
        })
    );
    // An infinite far plane (OpenGL): the far corners unproject to infinity.
    let infinite = DMat4::from_cols(
        glam::DVec4::new(1.0, 0.0, 0.0, 0.0),
        glam::DVec4::new(0.0, 1.0, 0.0, 0.0),
        glam::DVec4::new(0.0, 0.0, -1.0, -1.0),
        glam::DVec4::new(0.0, 0.0, -0.2, 0.0),
    );
    assert_eq!(
        Frustum::from_view_projection(infinite, NdcDepth::NegativeOneToOne),
        Err(HullError::UnboundedFrustum)
    );
    assert_eq!(
        LightSpace::with_parallel_sin(&pose(), DVec3::Y, 0.0),
        Err(HullError::OutOfRange {
            parameter: "parallel_sin",
            value: 0.0,
            min: 0.0,
            max: LightSpace::MAX_PARALLEL_SIN
        })
    );
    assert_eq!(
        Light::point(DVec3::ONE)
            .expect("valid")
            .light_vector(DVec3::ONE),
        Err(HullError::ZeroVector {
            parameter: "reference"
        })
    );
    assert_eq!(
        convex_hull_2d(&[]),
        Err(HullError::DegeneratePoints {
            degeneracy: Degeneracy::Empty
        })
    );
}

/// The messages name the parameter.
#[test]
fn messages_name_the_parameter() {
    let message = Perspective::new(1.0, 1.0, 5.0, 1.0)
        .expect_err("near ≥ far")
        .to_string();
    assert!(message.contains("near/far"), "{message}");
    let message = Perspective::new(0.0, 1.0, 1.0, 5.0)
        .expect_err("fov")
        .to_string();
    assert!(message.contains("fov_y"), "{message}");
    let message = Aabb::new(DVec3::splat(NAN), DVec3::ONE)
        .expect_err("NaN")
        .to_string();
    assert!(message.contains("min"), "{message}");
}
