//! The extreme configurations of the issue, one explicit test each.

use glam::DVec3;
use shadowlab_hull::{
    Aabb, ConvexPolyhedron, Degeneracy, HullError, LightSpace, Tolerances, focus_body,
};

use crate::support::{LightCase, TOL, checked_focus_body, make_camera};

fn scene() -> Aabb {
    Aabb::new(DVec3::new(-30.0, -2.0, -60.0), DVec3::new(30.0, 15.0, 10.0)).expect("valid")
}

fn camera_looking(forward: DVec3) -> crate::support::Camera {
    make_camera(
        DVec3::new(0.0, 3.0, 5.0),
        forward,
        DVec3::new(0.1, 1.0, 0.05),
        1.0,
        1.5,
        0.3,
        40.0,
    )
}

#[test]
fn light_exactly_parallel_and_anti_parallel_to_the_view() {
    for forward in [DVec3::NEG_Z, DVec3::new(0.3, -0.4, -0.8).normalize()] {
        let view = camera_looking(forward);
        for to_light in [forward, -forward] {
            let b = checked_focus_body(&view, &scene(), &LightCase::Directional(to_light))
                .expect("the camera sees the scene");
            assert_eq!(b.validate(&TOL), Ok(()));
            let ls = LightSpace::new(&view.pose, to_light).expect("valid");
            assert_eq!(ls.validate(), Ok(()));
            assert_eq!(ls.gamma(), 0.0);
        }
        // A spot light on the view axis, looking back at the camera and looking along with it.
        for sign in [1.0, -1.0] {
            let spot = make_camera(
                view.pose.eye() + forward * (20.0 - 30.0 * sign),
                forward * sign,
                DVec3::Y,
                1.2,
                1.0,
                0.5,
                200.0,
            );
            checked_focus_body(&view, &scene(), &LightCase::Spot(spot));
        }
    }
}

#[test]
fn light_within_a_nanoradian_of_parallel() {
    let view = camera_looking(DVec3::NEG_Z);
    for base in [DVec3::NEG_Z, DVec3::Z] {
        for axis in [DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0).normalize()] {
            let to_light = glam::DQuat::from_axis_angle(axis, 1e-9) * base;
            checked_focus_body(&view, &scene(), &LightCase::Directional(to_light))
                .expect("not empty");
            let ls = LightSpace::new(&view.pose, to_light).expect("valid");
            assert_eq!(ls.validate(), Ok(()));
            assert!(ls.gamma() > 0.0 && ls.gamma() < 2e-9);
        }
    }
}

#[test]
fn camera_inside_and_outside_the_scene_box() {
    let inside = camera_looking(DVec3::new(0.2, -0.3, -1.0));
    let outside = make_camera(
        DVec3::new(0.0, 40.0, 80.0),
        DVec3::new(0.0, -0.5, -1.0),
        DVec3::Y,
        0.8,
        1.0,
        1.0,
        300.0,
    );
    let away = make_camera(
        DVec3::new(0.0, 5.0, 40.0),
        DVec3::Z,
        DVec3::Y,
        0.8,
        1.0,
        1.0,
        300.0,
    );
    for light in [
        LightCase::Directional(DVec3::new(0.3, 1.0, 0.4).normalize()),
        LightCase::Point(DVec3::new(5.0, 30.0, -10.0)),
    ] {
        assert!(checked_focus_body(&inside, &scene(), &light).is_some());
        assert!(checked_focus_body(&outside, &scene(), &light).is_some());
        // Looking away from the scene: the only occluders are between the light and V.
        checked_focus_body(&away, &scene(), &light);
    }
}

#[test]
fn empty_focus_body() {
    // The scene is behind the camera and the light is in front: nothing in S lies between the light
    // and V.
    let view = make_camera(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, 1.0, 1.0, 1.0, 100.0);
    let behind =
        Aabb::new(DVec3::new(-5.0, -5.0, 10.0), DVec3::new(5.0, 5.0, 20.0)).expect("valid");
    let light = LightCase::Directional(DVec3::NEG_Z);
    assert!(checked_focus_body(&view, &behind, &light).is_none());
    // With the light behind the scene, the scene's points now lie between the light and V.
    let light = LightCase::Directional(DVec3::Z);
    assert!(checked_focus_body(&view, &behind, &light).is_some());
    // A point light in front of the camera, scene behind: empty too.
    let light = LightCase::Point(DVec3::new(0.0, 0.0, -300.0));
    assert!(checked_focus_body(&view, &behind, &light).is_none());
}

#[test]
fn near_plane_toward_zero() {
    for near in [1e-3, 1e-6, 1e-9, 1e-12] {
        let view = make_camera(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(0.0, -0.2, -1.0),
            DVec3::Y,
            1.0,
            1.3,
            near,
            50.0,
        );
        let body = ConvexPolyhedron::from_frustum(&view.frustum(), &TOL).expect("solid");
        assert_eq!(body.validate(&TOL), Ok(()));
        // Below the snap distance the near face collapses onto the apex: a pyramid.
        let snap = TOL.snap_distance(view.frustum().scale());
        let expected = if near * 1.3 > snap { 8 } else { 5 };
        assert_eq!(body.vertices().len(), expected, "near = {near}");
        let b = checked_focus_body(
            &view,
            &scene(),
            &LightCase::Directional(DVec3::new(0.2, 1.0, 0.5).normalize()),
        )
        .expect("not empty");
        assert_eq!(b.validate(&TOL), Ok(()));
    }
}

#[test]
fn huge_and_tiny_coordinates() {
    for (offset, scale) in [
        (1e7, 1.0),
        (1e7, 1e-2),
        (1e-7, 1e-7),
        (0.0, 1e-7),
        (0.0, 1e7),
    ] {
        let at = |p: DVec3| DVec3::splat(offset) + p * scale;
        let view = make_camera(
            at(DVec3::new(0.0, 3.0, 5.0)),
            DVec3::new(0.2, -0.3, -1.0),
            DVec3::Y,
            1.0,
            1.5,
            0.3 * scale,
            40.0 * scale,
        );
        let scene = Aabb::new(
            at(DVec3::new(-30.0, -2.0, -60.0)),
            at(DVec3::new(30.0, 15.0, 10.0)),
        )
        .expect("valid");
        for light in [
            LightCase::Directional(DVec3::new(0.3, 1.0, 0.4).normalize()),
            LightCase::Point(at(DVec3::new(5.0, 30.0, -10.0))),
        ] {
            let b = checked_focus_body(&view, &scene, &light).expect("not empty");
            let reference = checked_focus_body(
                &make_camera(
                    DVec3::new(0.0, 3.0, 5.0),
                    DVec3::new(0.2, -0.3, -1.0),
                    DVec3::Y,
                    1.0,
                    1.5,
                    0.3,
                    40.0,
                ),
                &Aabb::new(DVec3::new(-30.0, -2.0, -60.0), DVec3::new(30.0, 15.0, 10.0))
                    .expect("valid"),
                &match light {
                    LightCase::Point(_) => LightCase::Point(DVec3::new(5.0, 30.0, -10.0)),
                    other => other,
                },
            )
            .expect("not empty");
            let ratio = b.volume() / (reference.volume() * scale.powi(3));
            assert!(
                (ratio - 1.0).abs() <= 1e-6,
                "volume ratio {ratio} at offset {offset}, scale {scale}"
            );
        }
        // 3-D hulls of clouds at that place and size.
        let cloud: Vec<DVec3> = (0..40)
            .map(|k| {
                let t = f64::from(k);
                at(DVec3::new(
                    (t * 1.7).sin(),
                    (t * 2.3).cos(),
                    (t * 0.9).sin() * (t * 0.4).cos(),
                ) * 10.0)
            })
            .collect();
        let hull = ConvexPolyhedron::from_points(&cloud, &TOL).expect("solid");
        assert_eq!(hull.validate(&TOL), Ok(()));
        assert_eq!(hull.validate_contains(&cloud, &TOL), Ok(()));
    }
}

#[test]
fn coplanar_collinear_and_duplicated_points() {
    let degenerate = |points: &[DVec3]| match ConvexPolyhedron::from_points(points, &TOL) {
        Err(HullError::DegeneratePoints { degeneracy }) => degeneracy,
        other => panic!("expected a degenerate outcome, got {other:?}"),
    };
    assert_eq!(degenerate(&[]), Degeneracy::Empty);
    assert_eq!(degenerate(&[DVec3::ONE; 7]), Degeneracy::Coincident);
    let line: Vec<DVec3> = (0..9)
        .map(|k| DVec3::new(1.0, -2.0, 0.5) * f64::from(k) + DVec3::X)
        .collect();
    assert_eq!(degenerate(&line), Degeneracy::Collinear);
    let plane: Vec<DVec3> = (0..30)
        .map(|k| {
            let t = f64::from(k);
            DVec3::new(t.sin(), t.cos() * 2.0, 0.0) + DVec3::new(0.0, 0.0, 1e7)
        })
        .collect();
    assert_eq!(degenerate(&plane), Degeneracy::Coplanar);
    // Nearly coplanar within the snap distance is coplanar too.
    let mut thin = plane.clone();
    thin.push(DVec3::new(0.1, 0.1, 1e7 + 1e-12));
    assert_eq!(degenerate(&thin), Degeneracy::Coplanar);

    // Cube corners, each three times plus near-duplicates, plus the 3×3×3 grid (collinear and
    // coplanar points on the boundary): the hull is the cube, 8 vertices, 6 square faces.
    let mut points = Vec::new();
    for x in [-1, 0, 1] {
        for y in [-1, 0, 1] {
            for z in [-1, 0, 1] {
                let p = DVec3::new(f64::from(x), f64::from(y), f64::from(z));
                points.extend([p, p, p + DVec3::splat(1e-13)]);
            }
        }
    }
    let cube = ConvexPolyhedron::from_points(&points, &TOL).expect("solid");
    assert_eq!(cube.validate(&TOL), Ok(()));
    assert_eq!(cube.vertices().len(), 8);
    assert_eq!(cube.faces().len(), 6);
    assert!(cube.faces().iter().all(|f| f.vertices().len() == 4));
    assert!((cube.volume() - 8.0).abs() <= 1e-12);
    assert!(cube.centroid().length() <= 1e-12);
    assert_eq!(cube.validate_contains(&points, &TOL), Ok(()));
}

#[test]
fn point_light_inside_the_view_and_the_scene() {
    let view = camera_looking(DVec3::NEG_Z);
    // Inside V: conv(V ∪ l) = V.
    let l = view.pose.eye() + DVec3::NEG_Z * 10.0;
    let b = checked_focus_body(&view, &scene(), &LightCase::Point(l)).expect("not empty");
    let v = ConvexPolyhedron::from_frustum(&view.frustum(), &TOL).expect("solid");
    let hull = v.hull_with_point(l, &TOL).expect("valid");
    assert!((hull.volume() - v.volume()).abs() <= 1e-9 * v.volume());
    assert!(b.volume() <= v.volume() * (1.0 + 1e-9));
    // Behind the camera, inside the scene.
    checked_focus_body(
        &view,
        &scene(),
        &LightCase::Point(view.pose.eye() + DVec3::new(0.0, 2.0, 3.0)),
    )
    .expect("not empty");
}

/// The extrusions against the exact 3-D hull of the corners (an independent construction).
#[test]
fn extrusions_match_exact_hulls() {
    let view = camera_looking(DVec3::new(0.2, -0.3, -1.0).normalize());
    let v = ConvexPolyhedron::from_frustum(&view.frustum(), &TOL).expect("solid");
    let l = DVec3::new(4.0, 30.0, 12.0);
    let by_planes = v.hull_with_point(l, &TOL).expect("valid");
    let mut points = v.vertices().to_vec();
    points.push(l);
    let exact = ConvexPolyhedron::from_points(&points, &TOL).expect("solid");
    assert!((by_planes.volume() - exact.volume()).abs() <= 1e-9 * exact.volume());
    let u = DVec3::new(0.3, 1.0, -0.2).normalize();
    let swept = v.sweep(u, 25.0, &TOL).expect("valid");
    let mut points = v.vertices().to_vec();
    points.extend(v.vertices().iter().map(|p| *p + u * 25.0));
    let exact = ConvexPolyhedron::from_points(&points, &TOL).expect("solid");
    assert!((swept.volume() - exact.volume()).abs() <= 1e-9 * exact.volume());
    assert_eq!(swept.validate(&TOL), Ok(()));
    // Extruding up to the scene bounds, then cutting by S, gives B.
    let light = shadowlab_hull::Light::directional(u).expect("valid");
    let extruded = v
        .extrude_toward_light(&light, &scene(), &TOL)
        .expect("valid");
    let cut = extruded.intersect_aabb(&scene(), &TOL).expect("not empty");
    let b = focus_body(&view.frustum(), &scene(), &light, &TOL)
        .expect("valid")
        .expect("not empty");
    assert!((cut.volume() - b.volume()).abs() <= 1e-9 * b.volume());
}

/// Coarser tolerances are honoured too (they are parameters, not constants).
#[test]
fn custom_tolerances() {
    let coarse = Tolerances {
        relative: 1e-6,
        ..Tolerances::DEFAULT
    };
    let view = make_camera(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, 1.0, 1.0, 1e-5, 10.0);
    let body = ConvexPolyhedron::from_frustum(&view.frustum(), &coarse).expect("solid");
    assert_eq!(body.vertices().len(), 5);
    assert_eq!(body.validate(&coarse), Ok(()));
}
