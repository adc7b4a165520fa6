//! B, V ∩ S and the PSM near body over random cameras, scenes and lights, checked against their
//! definitions (membership in V from the camera parameters, in S from the box bounds, in L from the
//! spot parameters), not against the planes the crate computed.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_hull::{eye_depth_range, focus_body, psm_near_body, visible_body};

use crate::support::{
    Camera, LightCase, TOL, body_samples, camera, config, light_case, scene_box, slack_for,
};

/// Points to test "B ⊇ V ∩ S ∩ L" with: points of V, and points of V moved toward the light (which
/// are in B whenever they are in S ∩ L, since they lie between the light and V).
fn probe_points(view: &Camera, light: &LightCase, fractions: &[[f64; 4]]) -> Vec<DVec3> {
    let mut points = Vec::new();
    for f in fractions {
        let q = view.point([f[0], f[1], f[2]]);
        points.push(q);
        let toward = match light {
            LightCase::Directional(u) => *u * (200.0 * f[3]),
            LightCase::Point(l) => (*l - q) * f[3],
            LightCase::Spot(c) => (c.pose.eye() - q) * f[3],
        };
        points.push(q + toward);
    }
    points
}

proptest! {
    // Seed 0x5EED_B0D1 ("seed body"): 256 random configurations of camera, scene box and light.
    #![proptest_config(config(0x5EED_B0D1, 256))]

    /// B contains every sampled point of V ∩ S ∩ L (and of its extension toward the light); every
    /// vertex and sampled point of B lies in S and L and reaches V moving away from the light. B is
    /// convex, so checking its vertices proves the second property for all of B.
    #[test]
    fn focus_body_matches_its_definition(
        view in camera(),
        scene in scene_box(),
        light in light_case(),
        fractions in prop::collection::vec(
            (0.0..1.0_f64, 0.0..1.0_f64, 0.0..1.0_f64, 0.0..1.0_f64).prop_map(|(a, b, c, d)| [a, b, c, d]),
            24,
        ),
        weights in prop::collection::vec(prop::collection::vec(0.0..1.0_f64, 1..12), 8),
    ) {
        let frustum = view.frustum();
        let b = focus_body(&frustum, &scene, &light.light(), &TOL).expect("valid input");
        let slack = slack_for(&[frustum.corners(), &scene.corners(), &[light.light().position().unwrap_or(DVec3::ZERO)]]);
        let probes = probe_points(&view, &light, &fractions);
        match &b {
            None => {
                for p in &probes {
                    prop_assert!(
                        !(scene.contains(*p, -slack) && light.in_light_frustum(*p, -slack)
                            && light.reaches_view(&view, *p, -slack)),
                        "B is empty but {p} is in it by definition"
                    );
                }
            }
            Some(body) => {
                prop_assert_eq!(body.validate(&TOL), Ok(()));
                for p in &probes {
                    if scene.contains(*p, 0.0) && light.in_light_frustum(*p, 0.0)
                        && light.reaches_view(&view, *p, 0.0)
                    {
                        prop_assert!(body.contains(*p, slack), "{p} in V∩S∩L (extended) but not in B");
                    }
                }
                for p in body_samples(body, &weights) {
                    prop_assert!(scene.contains(p, slack), "{p} of B is outside S");
                    prop_assert!(light.in_light_frustum(p, slack), "{p} of B is outside L");
                    prop_assert!(light.reaches_view(&view, p, slack), "{p} of B does not reach V");
                }
            }
        }
    }

    /// V ∩ S contains the sampled points of V that are in S, and lies in both; the PSM near body
    /// contains V ∩ S, lies in B, and its nearest eye depth is at least B's.
    #[test]
    fn visible_and_psm_near_bodies(
        view in camera(),
        scene in scene_box(),
        light in light_case(),
        fractions in prop::collection::vec(
            (0.0..1.0_f64, 0.0..1.0_f64, 0.0..1.0_f64).prop_map(|(a, b, c)| [a, b, c]),
            24,
        ),
    ) {
        let frustum = view.frustum();
        let slack = slack_for(&[frustum.corners(), &scene.corners(), &[light.light().position().unwrap_or(DVec3::ZERO)]]);
        let visible = visible_body(&frustum, &scene, &TOL).expect("valid input");
        let near_body = psm_near_body(&frustum, &scene, &light.light(), &TOL).expect("valid input");
        let b = focus_body(&frustum, &scene, &light.light(), &TOL).expect("valid input");
        for f in &fractions {
            let p = view.point(*f);
            if scene.contains(p, -slack) {
                let v = visible.as_ref().expect("a point of V ∩ S exists");
                prop_assert!(v.contains(p, slack));
            }
        }
        if let Some(v) = &visible {
            prop_assert_eq!(v.validate(&TOL), Ok(()));
            for p in v.vertices() {
                prop_assert!(scene.contains(*p, slack) && view.contains(*p, slack));
            }
        }
        if let Some(near_body) = &near_body {
            prop_assert_eq!(near_body.validate(&TOL), Ok(()));
            let b = b.as_ref().expect("the PSM near body lies in B");
            for p in near_body.vertices() {
                prop_assert!(b.contains(*p, slack), "{p} of the PSM near body is outside B");
            }
            if let Some(v) = &visible {
                let in_l = |p: &DVec3| light.in_light_frustum(*p, -slack);
                for p in v.vertices().iter().filter(|p| in_l(p)) {
                    prop_assert!(near_body.contains(*p, slack));
                }
            }
            let (near_min, _) = eye_depth_range(near_body, &view.pose);
            let (b_min, _) = eye_depth_range(b, &view.pose);
            prop_assert!(near_min >= b_min - slack);
        }
    }
}

proptest! {
    // Seed 0x5EED_5CA1: 128 configurations moved to a random place (up to 10⁷ from the origin) and
    // size (10⁻⁶ … 10⁶).
    #![proptest_config(config(0x5EED_5CA1, 128))]

    /// B at any scale and place: valid, and its vertices satisfy the definition.
    #[test]
    fn focus_body_at_any_scale_and_place(
        view in camera(),
        scene in scene_box(),
        light in light_case(),
        log_scale in -6.0..6.0_f64,
        log_offset in -3.0..7.0_f64,
        direction in crate::support::unit_vector(),
    ) {
        let scale = 10f64.powf(log_scale);
        let offset = direction * 10f64.powf(log_offset);
        let at = |p: DVec3| offset + p * scale;
        let moved_view = Camera {
            pose: shadowlab_hull::ViewPose::look_to(at(view.pose.eye()), view.pose.forward(), view.pose.up())
                .expect("valid"),
            projection: shadowlab_hull::Perspective::new(
                view.projection.fov_y(),
                view.projection.aspect(),
                view.projection.near() * scale,
                view.projection.far() * scale,
            )
            .expect("valid"),
        };
        let moved_scene = shadowlab_hull::Aabb::new(at(scene.min()), at(scene.max())).expect("valid");
        let moved_light = match &light {
            LightCase::Directional(u) => LightCase::Directional(*u),
            LightCase::Point(p) => LightCase::Point(at(*p)),
            LightCase::Spot(c) => LightCase::Spot(Camera {
                pose: shadowlab_hull::ViewPose::look_to(at(c.pose.eye()), c.pose.forward(), c.pose.up())
                    .expect("valid"),
                projection: shadowlab_hull::Perspective::new(
                    c.projection.fov_y(),
                    c.projection.aspect(),
                    c.projection.near() * scale,
                    c.projection.far() * scale,
                )
                .expect("valid"),
            }),
        };
        crate::support::checked_focus_body(&moved_view, &moved_scene, &moved_light);
    }
}
