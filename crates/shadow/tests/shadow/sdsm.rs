//! Sample distribution shadow maps (`sdsm`): every sample lies in the window of the partition that
//! serves it; the partitions span exactly the samples' depth range; the logarithmic splits have
//! equal ratios; the windows are tight; k-means is deterministic and keeps each sample nearest its
//! own partition's centre; the edge cases fail with their errors.

use std::f64::consts::PI;

use glam::{DMat4, DVec3};
use proptest::prelude::*;
use shadowlab_hull::{Aabb, HullError, Perspective, ViewPose};
use shadowlab_params::ParamError;
use shadowlab_raster::NO_TRIANGLE;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::sdsm::{self, FLAT_FRACTION, SdsmVariant};
use shadowlab_shadow::{
    FocusPolicy, LightSource, Partition, PlanInput, Selection, ShadowError, ShadowMapping,
    eye_pass, scene_input,
};

use crate::support::{config, configuration};

/// Tolerance, in window units, beyond the rounding a window's side is allowed
/// ([`rounding`]): how near a sample must come to a side to touch it.
const TOUCH: f64 = 1e-9;

/// The eye depth `(p − e)·v` of `world`, as the lookups compute it.
fn depth(input: &PlanInput, world: DVec3) -> f64 {
    (world - input.eye.pose.eye()).dot(input.eye.pose.forward())
}

/// The world point at `(u, w)` across the view (each in `[−1, 1]`, the frustum's sides) and a
/// fraction `t` of the way from near to far, geometrically.
fn in_view(input: &PlanInput, (u, w, t): (f64, f64, f64)) -> DVec3 {
    let (pose, projection) = (input.eye.pose, input.eye.projection);
    let d = projection.near() * (projection.far() / projection.near()).powf(t);
    let tan_y = projection.tan_half_fov_y();
    let tan_x = tan_y * projection.aspect();
    pose.eye() + pose.forward() * d + pose.right() * (u * d * tan_x) + pose.up() * (w * d * tan_y)
}

fn projection(partition: &Partition) -> (DMat4, DMat4) {
    match partition.setup.mapping {
        ShadowMapping::Projective(mapping) => (mapping.view(), mapping.projection()),
        ShadowMapping::Logarithmic(_) | ShadowMapping::Paraboloid(_) => {
            panic!("an SDSM map is projective")
        }
    }
}

/// Per map axis (x, y, depth): the window's size in light units and the rounding its coordinates
/// carry in window units — 256 ulps of the largest magnitude behind them (the world point's, the
/// eye's, the window's own light coordinates) over the size.
fn rounding(partition: &Partition, world_magnitude: f64) -> [(f64, f64); 3] {
    let (_, projection) = projection(partition);
    // Map axis m runs along light axis x, z, y; its row is (… a at that axis …, b).
    [0, 2, 1].map(|light_axis| {
        let m = match light_axis {
            0 => 0,
            2 => 1,
            _ => 2,
        };
        let a = projection.col(light_axis)[m];
        let b = projection.col(3)[m];
        let size = 2.0 / a.abs();
        let magnitude = (b / a).abs() + 0.5 * size + world_magnitude;
        (size, 256.0 * f64::EPSILON * magnitude / size)
    })
}

/// The claims every plan makes about `samples` (those of them the light lights): each lies in the
/// window of the partition that serves it — `[0, 1)` across, `[0, 1]` in depth; the first near and
/// the last far are the smallest and largest eye depth, exactly; the partitions are nearest first
/// and none is empty; and each window is tight — across the map some sample touches each side (or
/// the axis is flat, widened to `FLAT_FRACTION` of the window's largest extent about the samples'
/// middle), and in depth some sample touches the far side. Returns the served samples per
/// partition.
fn check(input: &PlanInput, partitions: &[Partition], samples: &[DVec3]) -> Vec<Vec<DVec3>> {
    assert!(!partitions.is_empty());
    let depths: Vec<f64> = samples.iter().map(|p| depth(input, *p)).collect();
    let min = depths.iter().copied().fold(f64::INFINITY, f64::min);
    let max = depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(partitions[0].near, min, "first near");
    assert_eq!(partitions[partitions.len() - 1].far, max, "last far");
    for pair in partitions.windows(2) {
        assert!(pair[0].near < pair[1].near, "nearest first");
        assert_eq!(pair[0].far, pair[1].near, "contiguous");
    }
    let mut served = vec![Vec::new(); partitions.len()];
    for (world, d) in samples.iter().zip(&depths) {
        let k =
            shadowlab_shadow::served(partitions, |p| p, &Selection::DEFAULT, &input.eye, *world)
                .expect("the last partition serves beyond")
                .index;
        let at = partitions[k].setup.mapping.window(*world).unwrap();
        assert!(
            (0.0..1.0).contains(&at.x) && (0.0..1.0).contains(&at.y) && (0.0..=1.0).contains(&at.z),
            "sample {world} (depth {d}) of partition {k} at window {at}"
        );
        served[k].push(*world);
    }
    let world_magnitude = samples
        .iter()
        .chain([&input.eye.pose.eye()])
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    for (k, (partition, served)) in partitions.iter().zip(&served).enumerate() {
        assert!(!served.is_empty(), "partition {k} serves no sample");
        let windows: Vec<DVec3> = served
            .iter()
            .map(|p| partition.setup.mapping.window(*p).unwrap())
            .collect();
        let low = windows.iter().fold(DVec3::INFINITY, |a, b| a.min(*b));
        let high = windows.iter().fold(DVec3::NEG_INFINITY, |a, b| a.max(*b));
        let axes = rounding(partition, world_magnitude);
        let largest = axes.iter().map(|(size, _)| *size).fold(0.0, f64::max);
        for (m, (size, round)) in axes.into_iter().enumerate().take(2) {
            let tol = TOUCH + round;
            let flat = ((size / (FLAT_FRACTION * largest)) - 1.0).abs() < 1e-3;
            if flat {
                assert!(
                    (low[m] + high[m] - 1.0).abs() <= 2.0 * tol,
                    "partition {k}, axis {m}: flat axis not centred: {low} {high}"
                );
            } else {
                assert!(
                    low[m] <= tol && high[m] >= 1.0 - tol,
                    "partition {k}, axis {m}: not tight: {low} {high} (tolerance {tol})"
                );
            }
        }
        assert!(
            high.z >= 1.0 - TOUCH - axes[2].1,
            "partition {k}: the farthest sample is at depth {}",
            high.z
        );
    }
    served
}

/// The window depth of the scene box's corner nearest the light, per partition: 0 where the map
/// reaches S's nearest point toward the light ([caster reach]).
fn reach_depths(input: &PlanInput, partitions: &[Partition]) -> Vec<f64> {
    partitions
        .iter()
        .map(|p| {
            input
                .scene
                .corners()
                .iter()
                .map(|c| p.setup.mapping.window(*c).unwrap().z)
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

proptest! {
    #![proptest_config(config(64))]

    /// Claim: for seeded clouds of samples in the view (any camera orientation, far/near 10 to
    /// 10⁴, a directional light at any angle, above or below, in front or behind), both variants
    /// and 1–7 partitions: the claims of `check`, the logarithmic splits from the variant's
    /// boundaries (equal ratios, merged where empty), and each map's depth reaching S's nearest
    /// point toward the light exactly.
    #[test]
    fn every_sample_lies_in_the_window_that_serves_it(
        yaw in -PI..PI, pitch in -1.2..1.2f64, fov in 20.0..100.0f64,
        near in 0.05..5.0f64, decades in 1.0..4.0f64,
        gamma in 0.01..1.57f64, above in any::<bool>(), facing in any::<bool>(),
        cloud in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, 0.0..1.0f64), 1..200),
        count in 1usize..8, kmeans in any::<bool>(),
    ) {
        let input = configuration(
            DVec3::new(3.0, 2.0, -1.0), yaw, pitch, fov, near, near * 10f64.powf(decades),
            gamma, above, facing, FocusPolicy::Light,
        );
        let samples: Vec<DVec3> = cloud.iter().map(|c| in_view(&input, *c)).collect();
        let variant = if kmeans { SdsmVariant::Kmeans } else { SdsmVariant::Log };
        let partitions = sdsm::plan(&input, &samples, variant, count).unwrap();
        prop_assert!(partitions.len() <= count);
        check(&input, &partitions, &samples);
        let depths: Vec<f64> = samples.iter().map(|p| depth(&input, *p)).collect();
        let boundaries = variant.boundaries(&depths, count).unwrap();
        for p in &partitions {
            prop_assert!(boundaries.contains(&p.near) && boundaries.contains(&p.far));
        }
        for (k, d) in reach_depths(&input, &partitions).into_iter().enumerate() {
            let tol = TOUCH + rounding(&partitions[k], 2.0 * input.eye.projection.far() + 10.0)[2].1;
            prop_assert!(d.abs() <= tol, "partition {}: S's nearest corner at depth {}", k, d);
        }
    }

    /// Claim: k-means ends at a fixed point of Lloyd's iteration: over seeded clouds with depths
    /// anywhere in the view and 2–7 partitions, every sample is nearer the mean depth of its own
    /// partition than that of any other (to 1e-12 of its depth).
    #[test]
    fn kmeans_ends_with_each_sample_nearest_its_centre(
        cloud in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, 0.0..1.0f64), 2..300),
        count in 2usize..8,
    ) {
        let input = test_input();
        let samples: Vec<DVec3> = cloud.iter().map(|c| in_view(&input, *c)).collect();
        let partitions = sdsm::plan(&input, &samples, SdsmVariant::Kmeans, count).unwrap();
        let served = check(&input, &partitions, &samples);
        assert_nearest_centres(&input, &served);
    }

    /// Claim: the logarithmic split of any depths has the smallest and largest depth at its ends,
    /// exactly, and equal ratios between neighbouring splits (to 1e-12): `min·(max/min)^(i/k)`.
    #[test]
    fn log_splits_have_equal_ratios(
        depths in prop::collection::vec(1e-3..1e5f64, 2..50), count in 1usize..10,
    ) {
        let b = SdsmVariant::Log.boundaries(&depths, count).unwrap();
        let min = depths.iter().copied().fold(f64::INFINITY, f64::min);
        let max = depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        prop_assert_eq!(b.len(), count + 1);
        prop_assert_eq!(b[0], min);
        prop_assert_eq!(b[count], max);
        let ratio = (max / min).powf(1.0 / count as f64);
        for pair in b.windows(2) {
            prop_assert!((pair[1] / pair[0] / ratio - 1.0).abs() <= 1e-12, "{:?}", b);
        }
    }
}

/// The depths of three tight clusters (around 2, 20 and 60, ±1 %) and their world points on the
/// view axis of `input`'s camera, with seeded sideways offsets.
fn clustered(input: &PlanInput) -> Vec<DVec3> {
    // A fixed linear congruential sequence (Knuth's MMIX constants), seed 14.
    let mut state: u64 = 14;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut samples = Vec::new();
    for centre in [2.0_f64, 20.0, 60.0] {
        for _ in 0..40 {
            let d = centre * (0.99 + 0.02 * next());
            let t = (d / input.eye.projection.near()).ln()
                / (input.eye.projection.far() / input.eye.projection.near()).ln();
            samples.push(in_view(input, (next() - 0.5, next() - 0.5, t)));
        }
    }
    samples
}

fn test_input() -> PlanInput {
    configuration(
        DVec3::new(0.0, 1.0, 0.0),
        0.3,
        -0.2,
        60.0,
        0.5,
        100.0,
        0.7,
        true,
        true,
        FocusPolicy::Light,
    )
}

/// Every served sample is nearer the mean depth of its own partition than that of any other, to
/// 1e-12 of its depth.
fn assert_nearest_centres(input: &PlanInput, served: &[Vec<DVec3>]) {
    let centres: Vec<f64> = served
        .iter()
        .map(|s| s.iter().map(|p| depth(input, *p)).sum::<f64>() / s.len() as f64)
        .collect();
    for (k, s) in served.iter().enumerate() {
        for p in s {
            let d = depth(input, *p);
            for (j, c) in centres.iter().enumerate() {
                assert!(
                    (d - centres[k]).abs() <= (d - c).abs() + 1e-12 * d,
                    "depth {d} of partition {k} (centre {}) is nearer centre {j} ({c})",
                    centres[k]
                );
            }
        }
    }
}

/// Claim: k-means on three tight clusters of depths puts one cluster in each of three partitions,
/// and every sample is nearer the mean depth of its own partition than that of any other; the
/// logarithmic split of the same samples does not separate them so (the test can tell them apart).
#[test]
fn kmeans_keeps_each_sample_nearest_its_partitions_centre() {
    let input = test_input();
    let samples = clustered(&input);
    let partitions = sdsm::plan(&input, &samples, SdsmVariant::Kmeans, 3).unwrap();
    let served = check(&input, &partitions, &samples);
    assert_eq!(partitions.len(), 3);
    for (k, s) in served.iter().enumerate() {
        assert_eq!(s.len(), 40, "partition {k} holds one cluster");
    }
    assert_nearest_centres(&input, &served);
    let log = sdsm::plan(&input, &samples, SdsmVariant::Log, 3).unwrap();
    let log_served = check(&input, &log, &samples);
    assert!(
        log_served.iter().any(|s| s.len() != 40),
        "the log split separates the clusters too"
    );
}

/// Claim: k-means (and the log split) plans the same partitions twice, and for the samples in
/// reverse order: nothing depends on state or on the samples' order.
#[test]
fn plans_are_deterministic_and_independent_of_sample_order() {
    let input = test_input();
    let samples = clustered(&input);
    let mut reversed = samples.clone();
    reversed.reverse();
    for variant in SdsmVariant::ALL {
        for count in [1, 2, 4, 7] {
            let once = sdsm::plan(&input, &samples, variant, count).unwrap();
            assert_eq!(once, sdsm::plan(&input, &samples, variant, count).unwrap());
            assert_eq!(
                once,
                sdsm::plan(&input, &reversed, variant, count).unwrap(),
                "{variant} {count}"
            );
        }
    }
}

/// Claim: a split interval with no sample is merged into its nearer neighbour — the log split of
/// [1, 100] in four has empty second and third parts for samples near 1 and near 100 — and samples
/// all at one depth make one partition.
#[test]
fn empty_partitions_are_merged() {
    let input = test_input();
    let samples: Vec<DVec3> = [1.0, 1.05, 1.1, 40.0, 90.0, 100.0]
        .iter()
        .map(|d| {
            input.eye.pose.eye() + input.eye.pose.forward() * *d + DVec3::new(0.0, 0.01 * d, 0.0)
        })
        .collect();
    let depths: Vec<f64> = samples.iter().map(|p| depth(&input, *p)).collect();
    let b = SdsmVariant::Log.boundaries(&depths, 4).unwrap();
    let partitions = sdsm::plan(&input, &samples, SdsmVariant::Log, 4).unwrap();
    check(&input, &partitions, &samples);
    // [1, 3.16) holds three, [3.16, 10) and [10, 31.6) none, [31.6, 100] three.
    let spans: Vec<(f64, f64)> = partitions.iter().map(|p| (p.near, p.far)).collect();
    assert_eq!(spans, vec![(b[0], b[3]), (b[3], b[4])]);

    let same = vec![input.eye.pose.eye() + input.eye.pose.forward() * 5.0; 3];
    for variant in SdsmVariant::ALL {
        let partitions = sdsm::plan(&input, &same, variant, 3).unwrap();
        assert_eq!(partitions.len(), 1, "{variant}");
        check(&input, &partitions, &same);
    }
}

/// Claim: a sample exactly on a split belongs to the farther partition, as `served` reads it, and
/// lies in its window: a camera at the origin looking down −z (so that a point's eye depth is −z,
/// exactly) with samples at 1, at 100 and on each logarithmic split between, each split's sample
/// farther to the side than the one before.
#[test]
fn a_sample_on_a_split_belongs_to_the_farther_partition() {
    let input = configuration(
        DVec3::ZERO,
        0.0,
        0.0,
        60.0,
        0.5,
        200.0,
        0.7,
        true,
        true,
        FocusPolicy::Light,
    );
    assert_eq!(input.eye.pose.forward(), DVec3::NEG_Z);
    let count = 4;
    let splits = SdsmVariant::Log.boundaries(&[1.0, 100.0], count).unwrap();
    let samples: Vec<DVec3> = splits
        .iter()
        .map(|d| DVec3::new(0.2 * d, 0.0, -d))
        .collect();
    let partitions = sdsm::plan(&input, &samples, SdsmVariant::Log, count).unwrap();
    assert_eq!(partitions.len(), count);
    let served = check(&input, &partitions, &samples);
    for (k, partition) in partitions.iter().enumerate() {
        assert_eq!(partition.near, splits[k]);
        assert!(served[k].contains(&samples[k]), "partition {k}");
    }
}

/// Claim: samples on one light ray (flat across the map) and a single sample get a window of
/// `FLAT_FRACTION` of its largest extent on the flat axes, with the samples at its middle.
#[test]
fn flat_sample_sets_get_a_minimal_window() {
    let input = test_input();
    let LightSource::Directional { to_light } = input.light else {
        panic!("a directional light")
    };
    let base = input.eye.pose.eye() + input.eye.pose.forward() * 10.0;
    let ray: Vec<DVec3> = [0.0, 0.5, 1.0]
        .iter()
        .map(|t| base + to_light * *t)
        .collect();
    for samples in [ray, vec![base]] {
        let partitions = sdsm::plan(&input, &samples, SdsmVariant::Log, 1).unwrap();
        check(&input, &partitions, &samples);
        for p in &samples {
            let at = partitions[0].setup.mapping.window(*p).unwrap();
            assert!(
                (at.x - 0.5).abs() < 1e-6 && (at.y - 0.5).abs() < 1e-6,
                "{at}"
            );
        }
    }
}

/// Claim: the eye pass of `outdoor` (a directional light) and of `chess-spot` (a spot light, whose
/// cone holds only part of the view) plan maps that hold every visible sample the light lights,
/// for both variants and 1–4 partitions.
#[test]
fn built_in_scenes_plan_from_their_eye_pass() {
    for name in ["outdoor", "chess-spot"] {
        let mut scene = builtin_scene(name).unwrap();
        (scene.camera.width, scene.camera.height) = (96, 72);
        let (eye, nearest) = eye_pass(&scene).unwrap();
        let visible: Vec<DVec3> = eye
            .triangle
            .iter()
            .zip(&eye.position)
            .filter(|(t, _)| **t != NO_TRIANGLE)
            .map(|(_, p)| *p)
            .collect();
        assert!(visible.len() > 1000, "{name}");
        let input = scene_input(&scene, &scene.lights[0], nearest, FocusPolicy::Light).unwrap();
        let lit: Vec<DVec3> = match input.light {
            LightSource::Spot { pose, cone } => visible
                .iter()
                .copied()
                .filter(|p| {
                    (-input.light.toward_from(*p)).dot(pose.forward()) >= (0.5 * cone.fov_y()).cos()
                })
                .collect(),
            LightSource::Directional { .. } => visible.clone(),
            LightSource::Point { .. } => unreachable!("{name} has no point light"),
        };
        assert!(!lit.is_empty(), "{name}");
        for variant in SdsmVariant::ALL {
            for count in 1..=4 {
                let partitions = sdsm::plan(&input, &visible, variant, count)
                    .unwrap_or_else(|e| panic!("{name} {variant} {count}: {e}"));
                check(&input, &partitions, &lit);
            }
        }
    }
}

/// Claim: each edge case fails with its own error — no partitions, no samples, a sample that is
/// not finite, a sample behind the eye, a spot light that lights none of the samples, a sample at
/// the spot light's position.
#[test]
fn edge_cases_fail_with_their_errors() {
    let input = test_input();
    let samples = clustered(&input);
    match sdsm::plan(&input, &samples, SdsmVariant::Log, 0) {
        Err(ShadowError::Parameter(ParamError::OutOfDomain { name, .. })) => {
            assert_eq!(name, "partitions");
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        sdsm::plan(&input, &[], SdsmVariant::Log, 2),
        Err(ShadowError::NoSamples)
    );
    assert!(matches!(
        sdsm::plan(
            &input,
            &[DVec3::new(f64::NAN, 0.0, 0.0)],
            SdsmVariant::Kmeans,
            2
        ),
        Err(ShadowError::Geometry(HullError::NonFinite { .. }))
    ));
    let behind = input.eye.pose.eye() - input.eye.pose.forward();
    assert!(matches!(
        sdsm::plan(&input, &[samples[0], behind], SdsmVariant::Log, 2),
        Err(ShadowError::NotDefined {
            technique: "sdsm",
            ..
        })
    ));

    // A spot light above the view's samples, pointing away from them, then at them.
    let position = DVec3::new(0.0, 30.0, 0.0);
    let cone = Perspective::new(40f64.to_radians(), 1.0, 1.0, 200.0).unwrap();
    let spot = |forward: DVec3| PlanInput {
        light: LightSource::Spot {
            pose: ViewPose::look_to(position, forward, DVec3::X).unwrap(),
            cone,
        },
        scene: Aabb::new(DVec3::splat(-300.0), DVec3::splat(300.0)).unwrap(),
        ..input
    };
    assert_eq!(
        sdsm::plan(&spot(DVec3::Y), &samples, SdsmVariant::Log, 2),
        Err(ShadowError::NoSamples)
    );
    let down = spot(DVec3::NEG_Y);
    let below = position + DVec3::new(0.0, -40.0, 0.0);
    let samples_below: Vec<DVec3> = [0.0, 1.0, -1.0]
        .iter()
        .map(|x| below + DVec3::new(*x, 0.0, *x))
        .collect();
    let partitions = sdsm::plan(&down, &samples_below, SdsmVariant::Log, 2).unwrap();
    check(&down, &partitions, &samples_below);
    assert_eq!(
        sdsm::plan(&down, &[samples_below[0], position], SdsmVariant::Log, 2),
        Err(ShadowError::LightInsideFocusBody)
    );
}

/// Claim: each variant's key parses back to it and displays as it; an unknown key is refused with
/// the known ones.
#[test]
fn variants_round_trip_through_their_keys() {
    assert_eq!(SdsmVariant::default(), SdsmVariant::Log);
    for variant in SdsmVariant::ALL {
        assert_eq!(SdsmVariant::parse(variant.key()), Ok(variant));
        assert_eq!(SdsmVariant::parse(&variant.to_string()), Ok(variant));
    }
    let err = SdsmVariant::parse("adaptive").unwrap_err();
    assert!(err.contains("log, kmeans"), "{err}");
}
