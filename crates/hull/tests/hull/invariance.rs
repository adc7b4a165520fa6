//! Translating or rotating the input moves the output alike.
//!
//! Exact comparisons use transformations that are exact in f64 on the test data: translations by
//! dyadic vectors of inputs on a dyadic grid (sums and differences are exact), and quarter-turn
//! rotations / axis permutations (which only swap and negate coordinates). For those, the exact hulls
//! (2-D and 3-D) must map bit for bit, and the minimum-area rectangle's axes and extents too (they
//! depend only on exact differences). Results that go through rounding arithmetic on absolute
//! coordinates (the rectangle's centre, the clipped body B) are compared within the validation
//! distance of [`Tolerances::DEFAULT`](shadowlab_hull::Tolerances::DEFAULT).

use std::collections::BTreeSet;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use shadowlab_hull::{
    Aabb, ConvexHull2, ConvexPolyhedron, Frustum, Light, MinAreaRect, Perspective, ViewPose,
    convex_hull_2d, focus_body,
};

use crate::support::{TOL, config};

/// Grid points `k/64` with |k| ≤ 256: exactly representable, and so are their sums with the
/// translations below.
fn grid_points_3d() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec((-256..=256_i32, -256..=256_i32, -256..=256_i32), 8..48).prop_map(|v| {
        v.into_iter()
            .map(|(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)) / 64.0)
            .collect()
    })
}

fn grid_points_2d() -> impl Strategy<Value = Vec<DVec2>> {
    prop::collection::vec((-256..=256_i32, -256..=256_i32), 3..64).prop_map(|v| {
        v.into_iter()
            .map(|(x, y)| DVec2::new(f64::from(x), f64::from(y)) / 64.0)
            .collect()
    })
}

/// A dyadic translation with small numerators.
fn dyadic_translation() -> impl Strategy<Value = DVec3> {
    (-64..=64_i32, -64..=64_i32, -64..=64_i32)
        .prop_map(|(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)) / 8.0)
}

/// The 24 rotations of the cube (signed axis permutations with determinant +1), by index.
fn cube_rotation(index: usize) -> impl Fn(DVec3) -> DVec3 {
    const PERMUTATIONS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [1, 0, 2],
        [0, 2, 1],
        [2, 1, 0],
    ];
    let perm = PERMUTATIONS[index % 6];
    let odd = index % 6 >= 3;
    let signs = index / 6; // 0..4: two free sign bits, the third fixed by det = +1
    let s0 = if signs & 1 == 0 { 1.0 } else { -1.0 };
    let s1 = if signs & 2 == 0 { 1.0 } else { -1.0 };
    let s2 = s0 * s1 * if odd { -1.0 } else { 1.0 };
    move |p: DVec3| DVec3::new(s0 * p[perm[0]], s1 * p[perm[1]], s2 * p[perm[2]])
}

/// A polyhedron, its vertices mapped by `map`, as a set of faces, each face the cyclic sequence of its
/// vertex coordinates (as bit patterns) rotated to start at its smallest.
fn face_set(body: &ConvexPolyhedron, map: impl Fn(DVec3) -> DVec3) -> BTreeSet<Vec<[u64; 3]>> {
    body.faces()
        .iter()
        .map(|f| {
            let coords: Vec<[u64; 3]> = f
                .vertices()
                .iter()
                .map(|&i| {
                    let v = map(body.vertices()[i]);
                    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
                })
                .collect();
            let start = (0..coords.len()).min_by_key(|&k| coords[k]).unwrap_or(0);
            coords[start..]
                .iter()
                .chain(&coords[..start])
                .copied()
                .collect()
        })
        .collect()
}

proptest! {
    // Seed 0x1A7A_0004: 192 grid clouds, translations and cube rotations.
    #![proptest_config(config(0x1A7A_0004, 192))]

    /// The 3-D hull of translated / rotated points is the translated / rotated hull, bit for bit.
    #[test]
    fn hull_3d_moves_exactly(points in grid_points_3d(), t in dyadic_translation(), r in 0..24_usize) {
        let Ok(hull) = ConvexPolyhedron::from_points(&points, &TOL) else {
            return Ok(()); // a flat draw: nothing to compare
        };
        let moved: Vec<DVec3> = points.iter().map(|p| *p + t).collect();
        let moved_hull = ConvexPolyhedron::from_points(&moved, &TOL).expect("solid");
        prop_assert_eq!(face_set(&moved_hull, |p| p), face_set(&hull, |p| p + t));

        let rotate = cube_rotation(r);
        let turned: Vec<DVec3> = points.iter().map(|p| rotate(*p)).collect();
        let turned_hull = ConvexPolyhedron::from_points(&turned, &TOL).expect("solid");
        prop_assert_eq!(face_set(&turned_hull, |p| p), face_set(&hull, &rotate));
        prop_assert!((turned_hull.volume() - hull.volume()).abs() <= 1e-12 * hull.volume());
    }

    /// 2-D hulls move exactly; the minimum-area rectangle keeps its axes and extents exactly under
    /// translation and its area under quarter turns, and its centre moves within the validation
    /// distance.
    #[test]
    fn planar_results_move_alike(points in grid_points_2d(), t in dyadic_translation(), quarter in 0..4_u32) {
        let t = t.truncate();
        let hull = convex_hull_2d(&points).expect("non-empty");
        let moved = convex_hull_2d(&points.iter().map(|p| *p + t).collect::<Vec<_>>()).expect("non-empty");
        let expected = match &hull {
            ConvexHull2::Polygon(p) => p.vertices().iter().map(|v| *v + t).collect::<Vec<_>>(),
            ConvexHull2::Segment(a, b) => vec![*a + t, *b + t],
            ConvexHull2::Point(a) => vec![*a + t],
        };
        let got = match &moved {
            ConvexHull2::Polygon(p) => p.vertices().to_vec(),
            ConvexHull2::Segment(a, b) => vec![*a, *b],
            ConvexHull2::Point(a) => vec![*a],
        };
        prop_assert_eq!(got, expected);

        let rect = MinAreaRect::of_hull(&hull);
        let moved_rect = MinAreaRect::of_hull(&moved);
        prop_assert_eq!(rect.axes(), moved_rect.axes());
        prop_assert_eq!(rect.half_extents(), moved_rect.half_extents());
        let slack = TOL.validation_distance(shadowlab_hull::Scale { extent: 8.0, magnitude: 16.0 });
        prop_assert!((rect.center() + t).distance(moved_rect.center()) <= slack);

        let turn = |p: DVec2| (0..quarter).fold(p, |q, _| q.perp());
        // A quarter turn: the optimum may be attained by several edges (ties pick the first edge of
        // the hull, which starts elsewhere after a turn), so compare the area and the enclosure.
        let turned_points: Vec<DVec2> = points.iter().map(|p| turn(*p)).collect();
        let turned = MinAreaRect::of_points(&turned_points).expect("non-empty");
        prop_assert!((turned.area() - rect.area()).abs() <= 1e-12 * rect.area().max(1.0));
        prop_assert_eq!(turned.validate(&turned_points, &TOL), Ok(()));
    }
}

/// B of a translated and of a quarter-turned configuration is the moved B, within the validation
/// distance (B's vertices are computed intersections, so rounding differs).
#[test]
fn focus_body_moves_alike() {
    let pose = ViewPose::look_to(
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(0.2, -0.3, -1.0),
        DVec3::Y,
    )
    .expect("valid");
    let projection = Perspective::new(1.1, 1.4, 0.25, 60.0).expect("valid");
    let scene =
        Aabb::new(DVec3::new(-20.0, -1.0, -50.0), DVec3::new(25.0, 12.0, 10.0)).expect("valid");
    let to_light = DVec3::new(0.4, 0.8, 0.3);
    let b = |pose: &ViewPose, scene: &Aabb, to_light: DVec3| {
        focus_body(
            &Frustum::perspective(pose, &projection),
            scene,
            &Light::directional(to_light).expect("valid"),
            &TOL,
        )
        .expect("valid")
        .expect("not empty")
    };
    let original = b(&pose, &scene, to_light);
    let slack = TOL.validation_distance(original.scale()) * 4.0;
    let same_set = |a: &[DVec3], b: &[DVec3]| {
        a.len() == b.len() && a.iter().all(|p| b.iter().any(|q| q.distance(*p) <= slack))
    };
    // Translation by a dyadic vector.
    let t = DVec3::new(12.5, -3.25, 7.0);
    let moved_pose = ViewPose::look_to(pose.eye() + t, pose.forward(), DVec3::Y).expect("valid");
    let moved_scene = Aabb::new(scene.min() + t, scene.max() + t).expect("valid");
    let moved = b(&moved_pose, &moved_scene, to_light);
    let expected: Vec<DVec3> = original.vertices().iter().map(|p| *p + t).collect();
    assert!(same_set(moved.vertices(), &expected));
    assert!((moved.volume() - original.volume()).abs() <= 1e-9 * original.volume());
    // A quarter turn about y: (x, y, z) → (z, y, −x).
    let turn = |p: DVec3| DVec3::new(p.z, p.y, -p.x);
    let turned_pose =
        ViewPose::look_to(turn(pose.eye()), turn(pose.forward()), DVec3::Y).expect("valid");
    let turned_scene = Aabb::from_points(&scene.corners().map(turn)).expect("valid");
    let turned = b(&turned_pose, &turned_scene, turn(to_light));
    let expected: Vec<DVec3> = original.vertices().iter().map(|p| turn(*p)).collect();
    assert!(same_set(turned.vertices(), &expected));
    assert!((turned.volume() - original.volume()).abs() <= 1e-9 * original.volume());
}
