//! Bad input: every rejected input gives an error (or, for queries, a panic) whose message names
//! the triangle, vertex or parameter.

use glam::DVec3;
use shadowlab_trace::{Bvh, MAX_COORDINATE, MIN_DIRECTION, Ray, TraceError, offset_origin};

fn square() -> Vec<DVec3> {
    vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    ]
}

#[test]
fn bad_meshes_name_the_triangle_or_vertex() {
    let error = Bvh::new(&square(), &[[0, 1, 2], [0, 2, 4]]).expect_err("index 4");
    assert_eq!(
        error,
        TraceError::IndexOutOfRange {
            triangle: 1,
            corner: 2,
            vertex: 4,
            vertex_count: 4
        }
    );
    assert_eq!(
        error.to_string(),
        "triangle 1 (corner 2) refers to vertex 4, but there are 4 vertices"
    );
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut p = square();
        p[3].y = bad;
        let error = Bvh::new(&p, &[[0, 1, 2]]).expect_err("non-finite");
        assert_eq!(error, TraceError::NonFinitePosition { vertex: 3 });
        assert_eq!(error.to_string(), "vertex 3 has a NaN or infinite position");
    }
    let mut p = square();
    p[2].z = -2.0 * MAX_COORDINATE;
    let error = Bvh::new(&p, &[[0, 1, 3]]).expect_err("too large");
    assert_eq!(
        error,
        TraceError::PositionOutOfRange {
            vertex: 2,
            value: 2.0 * MAX_COORDINATE
        }
    );
    assert!(error.to_string().starts_with("vertex 2 has coordinate"));
    // At the limit itself, accepted.
    p[2].z = -MAX_COORDINATE;
    assert!(Bvh::new(&p, &[[0, 1, 2]]).is_ok());
}

#[test]
fn bad_rays_name_the_parameter() {
    let o = DVec3::ZERO;
    let cases = [
        (
            Ray::new(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::X),
            TraceError::NonFinite {
                parameter: "origin",
            },
            "`origin` is not finite",
        ),
        (
            Ray::new(o, DVec3::new(0.0, f64::INFINITY, 0.0)),
            TraceError::NonFinite {
                parameter: "direction",
            },
            "`direction` is not finite",
        ),
        (
            Ray::new(DVec3::new(0.0, 0.0, 1e61), DVec3::X),
            TraceError::OutOfRange {
                parameter: "origin",
                value: 1e61,
            },
            "`origin` must lie within",
        ),
        (
            Ray::new(o, DVec3::ZERO),
            TraceError::DirectionOutOfRange { largest: 0.0 },
            "`direction` must have a largest component",
        ),
        (
            Ray::new(o, DVec3::new(1e-61, -1e-62, 0.0)),
            TraceError::DirectionOutOfRange { largest: 1e-61 },
            "`direction` must have a largest component",
        ),
        (
            Ray::new(o, DVec3::new(0.0, 0.0, -1e61)),
            TraceError::DirectionOutOfRange { largest: 1e61 },
            "`direction` must have a largest component",
        ),
    ];
    for (result, error, message) in cases {
        assert_eq!(result, Err(error.clone()));
        assert!(
            error.to_string().starts_with(message),
            "{error} should start with {message}"
        );
    }
    // The limits themselves are accepted.
    assert!(
        Ray::new(
            DVec3::splat(-MAX_COORDINATE),
            DVec3::new(0.0, MIN_DIRECTION, 0.0)
        )
        .is_ok()
    );
    assert!(Ray::new(o, DVec3::new(0.0, 0.0, MAX_COORDINATE)).is_ok());
}

#[test]
#[should_panic(expected = "invalid ray: `direction` must have a largest component")]
fn a_query_with_a_zero_direction_panics() {
    let bvh = Bvh::new(&square(), &[[0, 1, 2]]).expect("valid");
    let _ = bvh.closest_hit(
        &Ray {
            origin: DVec3::ZERO,
            direction: DVec3::ZERO,
        },
        0.0,
        1.0,
    );
}

#[test]
#[should_panic(expected = "invalid ray 1: `origin` is not finite")]
fn a_batch_query_names_the_bad_ray() {
    let bvh = Bvh::new(&square(), &[[0, 1, 2]]).expect("valid");
    let good = Ray::new(DVec3::Z, DVec3::NEG_Z).expect("valid");
    let bad = Ray {
        origin: DVec3::splat(f64::NAN),
        direction: DVec3::Z,
    };
    let _ = bvh.occluded_all(&[good, bad], 0.0, 1.0);
}

#[test]
#[should_panic(expected = "`t_max` is NaN")]
fn a_nan_range_panics() {
    let bvh = Bvh::new(&square(), &[[0, 1, 2]]).expect("valid");
    let _ = bvh.occluded(
        &Ray::new(DVec3::Z, DVec3::NEG_Z).expect("valid"),
        0.0,
        f64::NAN,
    );
}

#[test]
fn bad_offsets_name_the_parameter() {
    let (p, n, l) = (DVec3::ONE, DVec3::Z, DVec3::Y);
    let nan = DVec3::splat(f64::NAN);
    let cases = [
        (
            offset_origin(nan, n, l, 1.0),
            TraceError::NonFinite { parameter: "point" },
        ),
        (
            offset_origin(p, nan, l, 1.0),
            TraceError::NonFinite {
                parameter: "geometric_normal",
            },
        ),
        (
            offset_origin(p, n, nan, 1.0),
            TraceError::NonFinite {
                parameter: "toward",
            },
        ),
        (
            offset_origin(p, n, l, f64::INFINITY),
            TraceError::NonFinite {
                parameter: "magnitude",
            },
        ),
        (
            offset_origin(p, n, l, -1.0),
            TraceError::OutOfRange {
                parameter: "magnitude",
                value: -1.0,
            },
        ),
        (
            offset_origin(DVec3::new(0.0, 1e61, 0.0), n, l, 1.0),
            TraceError::OutOfRange {
                parameter: "point",
                value: 1e61,
            },
        ),
        (
            offset_origin(p, DVec3::ZERO, l, 1.0),
            TraceError::ZeroNormal,
        ),
    ];
    for (result, error) in cases {
        assert_eq!(result, Err(error.clone()));
    }
    assert_eq!(
        TraceError::ZeroNormal.to_string(),
        "`geometric_normal` has zero length"
    );
    assert_eq!(
        TraceError::NonFinite {
            parameter: "toward"
        }
        .to_string(),
        "`toward` is not finite"
    );
}
