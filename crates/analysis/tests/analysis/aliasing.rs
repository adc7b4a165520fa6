//! The footprint against closed forms: a tilted plane under an orthographic map (by hand, and by
//! an independent construction at every pixel of a rendered plane), the 1-D error of
//! `shadowlab_shadow::measure` on the view axis (at γ = 90°, and with `sin γ·cos α/cos β` at any
//! γ), for projective and logarithmic maps; the statistics; determinism.

use std::f64::consts::PI;

use glam::{DAffine3, DMat2, DQuat, DVec2, DVec3};
use proptest::prelude::*;
use shadowlab_analysis::aliasing::{
    AliasingStats, Footprint, GRAZING_COS, footprint, footprints, stats, stats_of_each,
    texel_jacobian,
};
use shadowlab_hull::{Aabb, NdcDepth, Perspective, ViewPose};
use shadowlab_params::ParameterRule;
use shadowlab_scene::{Camera, Scene, SceneLight, procedural};
use shadowlab_shadow::{
    Eye, FocusPolicy, LightSetup, LightSource, PlanInput, ShadowError, Technique, WarpChoice,
    eye_pass, measure, plan,
};

use crate::support::{camera, config, on_threads, orthographic, relative, scene, split_mix64, sun};

/// Agreement asked of the footprint and the closed forms.
const AGREEMENT: f64 = 1e-6;

/// Claim: a plane tilted by ψ = 60° under a straight-down orthographic map of texel τ = 1/4, seen
/// head-on from distance D = 10 at the centre of a 101-pixel-high image with a 40° field of view,
/// shows a texel over `τ/(cos ψ·D·δ)` pixels (δ = 2 tan 20°/101, a pixel at unit distance): the
/// texel's shaft lands on the plane over `τ/cos ψ` along the tilt. The projection part is
/// `cos α/cos β = 1/cos ψ`, the perspective part `τ/(D·δ)`.
#[test]
fn a_tilted_plane_has_the_closed_form_footprint() {
    let light = ViewPose::look_to(DVec3::new(0.0, 10.0, 0.0), DVec3::NEG_Y, DVec3::NEG_Z).unwrap();
    let setup = orthographic(&light, 8.0, 0.0);
    let (tau, resolution) = (0.25, 64);
    let psi = 60f64.to_radians();
    let normal = DVec3::new(0.0, psi.cos(), psi.sin());
    let point = DVec3::new(0.3, 0.2, -0.1);
    let distance = 10.0;
    let camera = camera(point + normal * distance, point, 40.0, 101, 101);
    let delta = 2.0 * 20f64.to_radians().tan() / 101.0;

    let f = footprint(&setup, resolution, &camera, point, normal).unwrap();
    let expected = tau / (psi.cos() * distance * delta);
    assert!(
        relative(f.total, expected) < AGREEMENT,
        "{f:?} vs {expected}"
    );
    assert!(relative(f.projection, 1.0 / psi.cos()) < AGREEMENT, "{f:?}");
    assert!(
        relative(f.perspective, tau / (distance * delta)) < AGREEMENT,
        "{f:?}"
    );
    // The normal's orientation does not matter.
    assert_eq!(
        footprint(&setup, resolution, &camera, point, -normal),
        Some(f)
    );
}

/// Claim: a plane edge-on to the light (`cos β` below `GRAZING_COS`) has no footprint, however the
/// rounding comes out; just above the bound it has the closed form of the tilted plane
/// (`τ/(cos ψ·D·δ)`, here with `cos ψ` the bound doubled).
#[test]
fn planes_grazed_by_the_light_have_no_footprint() {
    let light = ViewPose::look_to(DVec3::new(0.0, 10.0, 0.0), DVec3::NEG_Y, DVec3::NEG_Z).unwrap();
    let setup = orthographic(&light, 8.0, 0.0);
    let (tau, resolution, distance) = (0.25, 64, 10.0);
    let point = DVec3::new(0.3, 0.2, -0.1);
    let delta = 2.0 * 20f64.to_radians().tan() / 101.0;
    for cos_psi in [0.0, 1e-12, 0.5 * GRAZING_COS, 2.0 * GRAZING_COS] {
        let sin_psi = (1.0 - cos_psi * cos_psi).sqrt();
        let normal = DVec3::new(0.0, cos_psi, sin_psi);
        let camera = camera(point + normal * distance, point, 40.0, 101, 101);
        let f = footprint(&setup, resolution, &camera, point, normal);
        if cos_psi < GRAZING_COS {
            assert_eq!(f, None, "cos ψ = {cos_psi}");
        } else {
            let expected = tau / (cos_psi * distance * delta);
            let total = f.expect("a footprint above the bound").total;
            assert!(
                relative(total, expected) < AGREEMENT,
                "{total} vs {expected}"
            );
        }
    }
}

/// The largest singular value of `g`, from the eigenvalues of `gᵀg`.
fn largest_singular_value(g: DMat2) -> f64 {
    let trace = g.x_axis.length_squared() + g.y_axis.length_squared();
    let det = g.determinant();
    (0.5 * (trace + (trace * trace - 4.0 * det * det).max(0.0).sqrt())).sqrt()
}

/// The footprint of an orthographic map seen from `light` with texel `tau`, on the plane through
/// `point` with unit normal `n`, seen by `camera`, built without the crate's chain rule: a texel
/// step along the map's axis `a` lands on the plane as `τ·(a − ℓ(a·n)/(ℓ·n))` (the axis projected
/// along the light's rays `ℓ`), and a world step `d` moves the window point by the derivative of
/// the camera's projection matrix.
fn oblique_projection_footprint(
    light: &ViewPose,
    tau: f64,
    camera: &Camera,
    point: DVec3,
    n: DVec3,
) -> Footprint {
    let l = light.forward();
    let on_plane = |a: DVec3| (a - l * (a.dot(n) / l.dot(n))) * tau;
    let m = camera.view_projection(NdcDepth::NegativeOneToOne);
    let (w, h) = (f64::from(camera.width), f64::from(camera.height));
    let screen = |d: DVec3| {
        let (p, dp) = (m * point.extend(1.0), m * d.extend(0.0));
        let along = |k: usize| (dp[k] * p.w - p[k] * dp.w) / (p.w * p.w);
        DVec2::new(along(0) * w / 2.0, along(1) * h / 2.0)
    };
    let g = DMat2::from_cols(
        screen(on_plane(light.right())),
        screen(on_plane(light.up())),
    );
    let to_eye = camera.pose.eye() - point;
    let projection = (n.dot(to_eye).abs() / to_eye.length()) / n.dot(l).abs();
    let total = largest_singular_value(g);
    Footprint {
        total,
        perspective: total / projection,
        projection,
    }
}

/// Claim: at every pixel of a rendered plane — tilted about two axes, under an oblique
/// orthographic map, seen obliquely — `footprints` agrees to 1e-6 with the footprint built
/// independently by projecting texel steps along the light onto the plane and through the camera's
/// matrix; and with [`footprint`] at the pixel's point.
#[test]
fn footprints_of_a_rendered_plane_match_an_independent_construction() {
    let rotation = DQuat::from_rotation_x(0.5) * DQuat::from_rotation_z(-0.3);
    let normal = rotation * DVec3::Y;
    let plane = procedural::plane(12.0, 12.0, 2)
        .unwrap()
        .transformed(&DAffine3::from_quat(rotation));
    let to_light = DVec3::new(0.5, 1.0, -0.35).normalize();
    let light = ViewPose::look_to(to_light * 20.0, -to_light, DVec3::Z).unwrap();
    let (half, resolution) = (10.0, 256);
    let tau = 2.0 * half / f64::from(resolution);
    let setup = orthographic(&light, half, 0.0);
    let camera = camera(
        DVec3::new(-7.0, 6.0, 9.0),
        DVec3::new(0.5, -0.5, 0.0),
        50.0,
        64,
        48,
    );
    let scene = scene(camera.clone(), vec![sun(to_light)], &[plane]);
    let (eye, _) = eye_pass(&scene).unwrap();
    let all: Vec<_> = footprints(&setup, resolution, &eye, &camera)
        .each_pixel()
        .collect();
    let mut compared = 0;
    for (p, f) in all.iter().enumerate() {
        let Some(f) = f else {
            continue;
        };
        let point = eye.position[p];
        let expected = oblique_projection_footprint(&light, tau, &camera, point, normal);
        assert!(
            relative(f.total, expected.total) < AGREEMENT
                && relative(f.projection, expected.projection) < AGREEMENT
                && relative(f.perspective, expected.perspective) < AGREEMENT,
            "pixel {p}: {f:?} vs {expected:?}"
        );
        let direct = footprint(&setup, resolution, &camera, point, eye.normal[p]).unwrap();
        assert_eq!(direct, *f);
        compared += 1;
    }
    assert!(compared > 1500, "{compared} pixels compared");
    // The plane is seen at varying angles and depths: the footprint varies.
    let totals = stats(all.iter().flatten().map(|f| f.total));
    assert!(
        totals.max
            > 1.5
                * all
                    .iter()
                    .flatten()
                    .map(|f| f.total)
                    .fold(f64::INFINITY, f64::min)
    );
}

/// A camera of `width × height` pixels (aspect 4/3) and a directional light at angle γ from its
/// view direction in its vertical plane (toward its up if `above`, from in front if `facing`).
#[expect(clippy::too_many_arguments, reason = "one test configuration")]
fn configuration(
    yaw: f64,
    pitch: f64,
    fov_y_degrees: f64,
    near: f64,
    far: f64,
    gamma: f64,
    above: bool,
    facing: bool,
) -> (Camera, PlanInput) {
    let rotation = DQuat::from_rotation_y(yaw) * DQuat::from_rotation_x(pitch);
    let pose = ViewPose::look_to(
        DVec3::new(3.0, 2.0, -1.0),
        rotation * DVec3::NEG_Z,
        rotation * DVec3::Y,
    )
    .unwrap();
    let projection = Perspective::new(fov_y_degrees.to_radians(), 4.0 / 3.0, near, far).unwrap();
    let tilt = if above { 1.0 } else { -1.0 };
    let along = if facing { 1.0 } else { -1.0 };
    let to_light = pose.forward() * (along * gamma.cos()) + pose.up() * (tilt * gamma.sin());
    let reach = 2.0 * far;
    let input = PlanInput {
        eye: Eye { pose, projection },
        light: LightSource::directional(to_light).unwrap(),
        scene: Aabb::new(
            pose.eye() - DVec3::splat(reach),
            pose.eye() + DVec3::splat(reach),
        )
        .unwrap(),
        nearest_visible_depth: None,
        focus: FocusPolicy::View,
    };
    let camera = Camera {
        pose,
        projection,
        width: 1024,
        height: 768,
    };
    (camera, input)
}

/// The techniques whose map axes follow the light–view plane: uniform, LiSPSM with every rule,
/// logarithmic.
fn light_space_techniques() -> Vec<Technique> {
    ParameterRule::ALL
        .into_iter()
        .map(|r| Technique::Lispsm(WarpChoice::Rule(r)))
        .chain([Technique::Uniform, Technique::LOGARITHMIC])
        .collect()
}

/// Pixels per texel along the map's warp axis (y), and across it (x): the columns of `J⁻¹`.
fn along_axes(j: DMat2) -> (f64, f64) {
    let inverse = j.inverse();
    (inverse.y_axis.length(), inverse.x_axis.length())
}

/// Claim: in LiSPSM's configuration (§4.1, Fig. 4) — light perpendicular to the view, a surface on
/// the view axis whose normal halves the angle between the eye's and the light's rays, so
/// cos α = cos β — a texel covers along the warp axis exactly `view_axis_error·H/(2 tan φ·res)`
/// pixels, CAD's m_z of `measure`'s dp/ds, to 1e-6, at every depth and for every light-space
/// technique; the projection part is 1; and the total is the larger of the warp and lateral
/// extents (`J` is diagonal there).
#[test]
fn at_90_degrees_the_footprint_is_the_measured_view_axis_error() {
    let (camera, input) = configuration(0.3, -0.2, 45.0, 1.0, 100.0, PI / 2.0, true, true);
    let (v, l) = (camera.pose.forward(), input.light.toward_from(DVec3::ZERO));
    let normal = (l - v).normalize();
    let resolution = 2048;
    let pixels_per_texel = f64::from(camera.height)
        / (2.0 * camera.projection.tan_half_fov_y() * f64::from(resolution));
    for technique in light_space_techniques() {
        let setup = plan(&input, technique).unwrap();
        for k in 0..=8 {
            let z = 100f64.powf(f64::from(k) / 8.0);
            let point = camera.pose.eye() + v * z;
            let j = texel_jacobian(&setup, resolution, &camera, point, normal).unwrap();
            let (warp, lateral) = along_axes(j);
            let dp_ds = measure::view_axis_error(&setup.mapping, &input.eye, z).unwrap();
            let expected = dp_ds * pixels_per_texel;
            assert!(
                relative(warp, expected) < AGREEMENT,
                "{technique} at z = {z}: {warp} vs {expected}"
            );
            let f = footprint(&setup, resolution, &camera, point, normal).unwrap();
            assert!((f.projection - 1.0).abs() < 1e-9, "{f:?}");
            assert!(relative(f.total, warp.max(lateral)) < AGREEMENT, "{f:?}");
            assert!(relative(f.perspective, f.total) < AGREEMENT);
        }
    }
}

proptest! {
    #![proptest_config(config(32))]

    /// Claim: at any γ from 3° to 90°, for any normal in the light–view plane facing the eye (not
    /// edge-on to the light), on the view axis, a texel covers along the warp axis
    /// `view_axis_error·sin γ·(cos α/cos β)·H/(2 tan φ·res)` pixels to 1e-6 — the 1-D error times
    /// the projection factor and the shaft's width across the light — for every light-space
    /// technique defined there, and the footprint's projection part is that `cos α/cos β`.
    #[test]
    fn on_the_view_axis_the_footprint_is_the_one_dimensional_error(
        yaw in -PI..PI, pitch in -1.2..1.2f64,
        fov in 20.0..100.0f64, near in 0.1..5.0f64, decades in 0.5..3.0f64,
        gamma_degrees in 3.0..90.0f64, above in any::<bool>(), facing in any::<bool>(),
        tilt in -1.3..1.3f64, depth in 0.0..1.0f64,
    ) {
        let far = near * 10f64.powf(decades);
        let gamma = gamma_degrees.to_radians();
        let (camera, input) = configuration(yaw, pitch, fov, near, far, gamma, above, facing);
        let (v, up) = (camera.pose.forward(), camera.pose.up());
        let l = input.light.toward_from(DVec3::ZERO);
        let normal = -v * tilt.cos() + up * tilt.sin();
        let (cos_alpha, cos_beta) = (tilt.cos(), normal.dot(l).abs());
        prop_assume!(cos_beta > 0.05);
        let resolution = 1024;
        let pixels_per_texel = f64::from(camera.height)
            / (2.0 * camera.projection.tan_half_fov_y() * f64::from(resolution));
        let z = near * (far / near).powf(depth);
        let point = camera.pose.eye() + v * z;
        for technique in light_space_techniques() {
            let setup = match plan(&input, technique) {
                Ok(setup) => setup,
                Err(ShadowError::NotDefined { .. }) => continue,
                Err(e) => return Err(TestCaseError::fail(format!("{technique}: {e}"))),
            };
            let j = texel_jacobian(&setup, resolution, &camera, point, normal).unwrap();
            let dp_ds = measure::view_axis_error(&setup.mapping, &input.eye, z).unwrap();
            let expected = dp_ds * gamma.sin() * cos_alpha / cos_beta * pixels_per_texel;
            let (warp, _) = along_axes(j);
            prop_assert!(relative(warp, expected) < AGREEMENT,
                "{technique} at z = {z}: {warp} vs {expected}");
            let f = footprint(&setup, resolution, &camera, point, normal).unwrap();
            prop_assert!(relative(f.projection, cos_alpha / cos_beta) < AGREEMENT, "{f:?}");
        }
    }
}

/// Claim: the statistics are exact on known values — maximum, nearest-rank 99th percentile
/// (the ⌈0.99·n⌉-th smallest), mean (the exact sum rounded once, over the count) — leave NaN out,
/// do not depend on the order of the values, and are all 0 for no values.
#[test]
fn statistics_have_the_documented_values() {
    let values: Vec<f64> = (1..=100).map(f64::from).collect();
    let s = stats(values.iter().rev().copied().chain([f64::NAN]));
    assert_eq!((s.max, s.p99, s.mean, s.count), (100.0, 99.0, 50.5, 100));
    let s = stats((1..=201).map(f64::from));
    // ⌈0.99·201⌉ = 199.
    assert_eq!((s.max, s.p99, s.count), (201.0, 199.0, 201));
    let s = stats([7.5].into_iter());
    assert_eq!((s.max, s.p99, s.mean, s.count), (7.5, 7.5, 7.5, 1));
    let s = stats(std::iter::empty());
    assert_eq!((s.max, s.p99, s.mean, s.count), (0.0, 0.0, 0.0, 0));
    // Order does not change a bit of the mean.
    let tenths: Vec<f64> = (0..1000).map(|k| 0.1 * f64::from(k % 37) + 1e-3).collect();
    let forward = stats(tenths.iter().copied());
    let backward = stats(tenths.iter().rev().copied());
    assert_eq!(forward.mean.to_bits(), backward.mean.to_bits());
    // The sum is exact: a sorted sum of these loses the ones against 1e16 (mean 0, not 0.5).
    let s = stats([-1e16, 1.0, 1.0, 1e16].into_iter());
    assert_eq!(s.mean, 0.5);
    // Negative values, both zeros and infinities sort as `f64::total_cmp` sorts them.
    let mixed = [
        3.0,
        -0.0,
        0.0,
        -2.5,
        f64::INFINITY,
        -1e300,
        1e-300,
        f64::NEG_INFINITY,
        7.0,
    ];
    let mut reference = mixed.to_vec();
    reference.sort_by(f64::total_cmp);
    let s = stats(mixed.into_iter().cycle().take(900));
    assert_eq!((s.max, s.p99, s.count), (f64::INFINITY, f64::INFINITY, 900));
    let s = stats(mixed.into_iter().filter(|v| v.is_finite()));
    assert_eq!(s.max.to_bits(), reference[7].to_bits());
    assert_eq!(s.p99.to_bits(), reference[7].to_bits());
    let s = stats([-0.0, 0.0].into_iter());
    assert_eq!(s.max.to_bits(), 0.0f64.to_bits());
}

/// The nearest-rank 99th percentile and the maximum of `values` by sorting them (`total_cmp`).
fn sorted_p99_and_max(values: &[f64]) -> (f64, f64) {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let rank = (99 * sorted.len()).div_ceil(100);
    (sorted[rank - 1], sorted[sorted.len() - 1])
}

/// Claim: the percentile the statistics select (a radix selection over chunks of values) is the
/// one a full sort gives, bit for bit, on 1 and 3 threads — for sets small enough to be selected
/// directly and large ones that take several bucketing passes, values spread over many binades or
/// crowded into a few texels' worth of one, duplicates, all values equal, both signs and zeros,
/// subnormals and infinities; the maximum too.
#[test]
fn the_selected_percentile_is_the_sorted_one() {
    let mut next = split_mix64(15);
    let mut sets: Vec<Vec<f64>> = Vec::new();
    for n in [1, 99, 100, 101, 4096, 4097, 16_385, 65_536, 65_537, 200_003] {
        // Spread: any finite double of either sign, by its bits.
        sets.push(
            (0..n)
                .map(|_| f64::from_bits(next() & !(0x7ff << 52) | ((next() % 2047) << 52)))
                .collect(),
        );
        // Crowded: 4 096 distinct values near 300, each many times, and a few outliers.
        sets.push(
            (0..n)
                .map(|k| match k % 997 {
                    0 => f64::INFINITY,
                    1 => -0.0,
                    2 => 0.0,
                    3 => f64::MIN_POSITIVE / 8.0,
                    _ => 300.0 + f64::from((next() % 4096) as u32) * 1e-9,
                })
                .collect(),
        );
        // All equal.
        sets.push(vec![7.25; n]);
    }
    for values in &sets {
        let (p99, max) = sorted_p99_and_max(values);
        for threads in [1, 3] {
            let s = on_threads(threads, || stats(values.iter().copied()));
            assert_eq!(s.p99.to_bits(), p99.to_bits(), "{} values", values.len());
            assert_eq!(s.max.to_bits(), max.to_bits(), "{} values", values.len());
            assert_eq!(s.count, values.len() as u64);
        }
    }
}

/// Claim: `stats_of_each` summarises each of its values as `stats` does that value alone — the
/// maximum, the selected percentile, the exact mean and the count, bit for bit — whatever the
/// others are: items across several chunks, each value missing (`None`) or NaN at its own items.
#[test]
fn each_value_is_summarised_as_alone() {
    let mut next = split_mix64(31);
    for n in [0, 1, 16_385, 40_000] {
        let items: Vec<[Option<f64>; 3]> = (0..n)
            .map(|_| {
                std::array::from_fn(|_| match next() % 10 {
                    0 => None,
                    1 => Some(f64::NAN),
                    _ => Some(f64::from_bits(next() >> 2)),
                })
            })
            .collect();
        let each = stats_of_each(&items, |item| *item);
        for (k, summary) in each.iter().enumerate() {
            let alone = stats(items.iter().filter_map(|item| item[k]));
            let bits = |s: &AliasingStats| [s.max, s.p99, s.mean].map(f64::to_bits);
            assert_eq!(bits(summary), bits(&alone), "value {k} of {n} items");
            assert_eq!(summary.count, alone.count, "value {k} of {n} items");
        }
    }
}

/// A ground with a box under the sun, seen from above it.
fn ground_with_a_box() -> Scene {
    scene(
        camera(
            DVec3::new(0.0, 3.0, 10.0),
            DVec3::new(0.0, 0.0, -20.0),
            60.0,
            160,
            120,
        ),
        vec![sun(DVec3::new(-0.3, 1.0, 0.2))],
        &[
            procedural::plane(80.0, 80.0, 4).unwrap(),
            procedural::cuboid(DVec3::splat(2.0))
                .unwrap()
                .transformed(&DAffine3::from_translation(DVec3::new(1.0, 1.0, -8.0))),
        ],
    )
}

/// `technique`'s set-up of `scene`'s first light.
fn setup_of(scene: &Scene, technique: Technique) -> LightSetup {
    let partitions = shadowlab_shadow::plan_light(
        scene,
        &scene.lights[0],
        &shadowlab_shadow::PlanOptions::new(technique),
        None,
        256,
        None,
    )
    .unwrap_or_else(|e| panic!("{technique}: {e}"));
    partitions[0].setup.clone()
}

/// Claim: the footprints of a LiSPSM map and a logarithmic one of a ground with a box are
/// identical on 1, 2 and 3 threads, and defined at nearly every visible pixel.
#[test]
fn footprints_are_the_same_on_any_thread_count() {
    let scene = ground_with_a_box();
    let (eye, _) = eye_pass(&scene).unwrap();
    let visible = eye
        .triangle
        .iter()
        .filter(|t| **t != shadowlab_raster::NO_TRIANGLE)
        .count();
    for technique in [Technique::Lispsm(WarpChoice::PAPER), Technique::LOGARITHMIC] {
        let setup = &setup_of(&scene, technique);
        let run = |threads| {
            on_threads(threads, || {
                let all = footprints(setup, 1024, &eye, &scene.camera);
                all.each_pixel().collect::<Vec<_>>()
            })
        };
        let one = run(1);
        assert_eq!(one, run(2));
        assert_eq!(one, run(3));
        let defined = one.iter().flatten().count();
        assert!(
            defined * 100 >= visible * 99,
            "{technique}: {defined} of {visible}"
        );
    }
}

/// Claim: `footprints`, which measures four neighbouring pixels side by side, gives every pixel
/// the bits of `footprint` at that pixel alone, through a LiSPSM map and a logarithmic one under
/// the sun, and a paraboloid hemisphere of a point light above the box.
#[test]
fn footprints_are_each_pixels_footprint_to_the_bit() {
    let sunlit = ground_with_a_box();
    let mut lamp = sunlit.clone();
    lamp.lights = vec![SceneLight::Point {
        position: DVec3::new(-2.0, 6.0, -6.0),
        range: None,
    }];
    for (scene, technique) in [
        (&sunlit, Technique::Lispsm(WarpChoice::PAPER)),
        (&sunlit, Technique::LOGARITHMIC),
        (&lamp, Technique::DualParaboloid),
    ] {
        let (eye, _) = eye_pass(scene).unwrap();
        let setup = setup_of(scene, technique);
        let frame = footprints(&setup, 1000, &eye, &scene.camera);
        let all: Vec<_> = frame.each_pixel().collect();
        assert_eq!(all.len(), eye.triangle.len(), "{technique}: one per pixel");
        let mut defined = 0;
        for (p, measured) in all.iter().enumerate() {
            let alone = (eye.triangle[p] != shadowlab_raster::NO_TRIANGLE)
                .then(|| footprint(&setup, 1000, &scene.camera, eye.position[p], eye.normal[p]))
                .flatten();
            let bits = |f: &Option<Footprint>| {
                f.map(|f| [f.total, f.perspective, f.projection].map(f64::to_bits))
            };
            assert_eq!(bits(measured), bits(&alone), "{technique}, pixel {p}");
            defined += usize::from(alone.is_some());
        }
        assert!(defined > 10_000, "{technique}: {defined}");
        // The statistics of the three parts, as `stats` of each part of the defined footprints.
        let parts: [fn(&Footprint) -> f64; 3] = [|f| f.total, |f| f.perspective, |f| f.projection];
        for (summary, part) in frame.stats().iter().zip(parts) {
            let alone = stats(all.iter().flatten().map(part));
            let bits = |s: &AliasingStats| [s.max, s.p99, s.mean].map(f64::to_bits);
            assert_eq!(bits(summary), bits(&alone), "{technique}");
            assert_eq!(summary.count, alone.count, "{technique}");
        }
    }
}
