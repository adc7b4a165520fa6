//! 2-D hulls and minimum-area rectangles against brute force.

use glam::DVec2;
use proptest::prelude::*;
use shadowlab_hull::{Aabb2, ConvexHull2, MinAreaRect, convex_hull_2d};

use crate::support::{TOL, config};

/// Points at a random scale and offset, some clouds stretched and rotated into thin shapes.
fn points_2d() -> impl Strategy<Value = Vec<DVec2>> {
    (
        prop::collection::vec((-1.0..1.0_f64, -1.0..1.0_f64), 3..80),
        -3.0..3.0_f64,
        0.001..1.0_f64,
        0.0..std::f64::consts::TAU,
        (-10.0..10.0_f64, -10.0..10.0_f64),
    )
        .prop_map(|(raw, log_scale, squash, angle, (ox, oy))| {
            let scale = 10f64.powf(log_scale);
            let rotation = DVec2::from_angle(angle);
            raw.into_iter()
                .map(|(x, y)| {
                    (rotation.rotate(DVec2::new(x, y * squash)) + DVec2::new(ox, oy)) * scale
                })
                .collect()
        })
}

/// The rectangle aligned with direction `u` enclosing `points`: its area.
fn aligned_area(points: &[DVec2], u: DVec2) -> f64 {
    let v = u.perp();
    let (mut a0, mut a1, mut b0, mut b1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in points {
        a0 = a0.min(p.dot(u));
        a1 = a1.max(p.dot(u));
        b0 = b0.min(p.dot(v));
        b1 = b1.max(p.dot(v));
    }
    (a1 - a0) * (b1 - b0)
}

proptest! {
    // Seed 0x2D2D_0006: 256 random planar clouds.
    #![proptest_config(config(0x2D2D_0006, 256))]

    /// The hull contains every point exactly and its vertices are input points; the rectangle contains
    /// every point and is no larger than the rectangle aligned with any hull edge (brute force) or the
    /// axis-aligned box.
    #[test]
    fn min_area_rectangle_is_minimal(points in points_2d()) {
        let hull = convex_hull_2d(&points).expect("non-empty");
        let ConvexHull2::Polygon(polygon) = &hull else {
            return Err(TestCaseError::fail("random clouds span an area"));
        };
        prop_assert_eq!(polygon.validate(), Ok(()));
        prop_assert_eq!(polygon.validate_contains(&points), Ok(()));
        for v in polygon.vertices() {
            prop_assert!(points.contains(v));
        }
        let rect = MinAreaRect::of_hull(&hull);
        prop_assert_eq!(rect.validate(&points, &TOL), Ok(()));
        let relative = 1e-9;
        let n = polygon.vertices().len();
        let brute = (0..n)
            .map(|k| {
                let e = polygon.vertices()[(k + 1) % n] - polygon.vertices()[k];
                aligned_area(&points, e.normalize())
            })
            .fold(f64::INFINITY, f64::min);
        prop_assert!(rect.area() <= brute * (1.0 + relative), "{} > brute force {}", rect.area(), brute);
        prop_assert!(rect.area() >= brute * (1.0 - relative));
        let aabb = Aabb2::from_points(&points).expect("non-empty");
        prop_assert!(rect.area() <= aabb.area() * (1.0 + relative));
        prop_assert!(rect.area() >= polygon.area() * (1.0 - relative));
    }
}

#[test]
fn degenerate_planar_inputs() {
    let p = DVec2::new(0.25, -3.0);
    assert_eq!(convex_hull_2d(&[p, p, p]), Ok(ConvexHull2::Point(p)));
    let rect = MinAreaRect::of_points(&[p, p]).expect("non-empty");
    assert_eq!(rect.area(), 0.0);
    assert_eq!(rect.center(), p);

    let line: Vec<DVec2> = (0..10)
        .map(|k| DVec2::new(1.0, 2.0) * f64::from(k))
        .chain([DVec2::new(4.0, 8.0)])
        .collect();
    assert_eq!(
        convex_hull_2d(&line),
        Ok(ConvexHull2::Segment(DVec2::ZERO, DVec2::new(9.0, 18.0)))
    );
    let rect = MinAreaRect::of_points(&line).expect("non-empty");
    assert_eq!(rect.half_extents().y, 0.0);
    assert_eq!(rect.validate(&line, &TOL), Ok(()));

    // Collinear points on the hull boundary are not vertices; duplicates are harmless.
    let square = [
        DVec2::ZERO,
        DVec2::new(0.5, 0.0),
        DVec2::X,
        DVec2::ONE,
        DVec2::Y,
        DVec2::ONE,
        DVec2::new(0.5, 0.5),
    ];
    let ConvexHull2::Polygon(polygon) = convex_hull_2d(&square).expect("non-empty") else {
        panic!("a square spans an area");
    };
    assert_eq!(
        polygon.vertices(),
        &[DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]
    );
    let rect = MinAreaRect::of_points(&square).expect("non-empty");
    assert!((rect.area() - 1.0).abs() <= 1e-15);
}

/// A rotated rectangle's points give back that rectangle.
#[test]
fn recovers_a_rotated_rectangle() {
    let axis = DVec2::from_angle(0.3);
    let center = DVec2::new(100.0, -50.0);
    let corners: Vec<DVec2> = [(-3.0, -1.0), (3.0, -1.0), (3.0, 1.0), (-3.0, 1.0)]
        .into_iter()
        .map(|(a, b)| center + axis * a + axis.perp() * b)
        .collect();
    let mut points = corners.clone();
    points.extend(corners.iter().map(|c| center + (*c - center) * 0.5));
    let rect = MinAreaRect::of_points(&points).expect("non-empty");
    assert!((rect.area() - 12.0).abs() <= 1e-9);
    assert!(rect.center().distance(center) <= 1e-9);
}
