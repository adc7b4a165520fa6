//! Misclassification: zero for a uniform map whose texel edges fall on the shadow's edges, counted
//! and pictured as documented.

use glam::DVec3;
use shadowlab_analysis::classify::{
    BACKGROUND, CORRECT_LIT, CORRECT_SHADOW, FALSELY_LIT, FALSELY_SHADOWED, Misclassification,
    difference_image, misclassification,
};
use shadowlab_analysis::truth::{Truth, exact_truth, scene_bvh};
use shadowlab_hull::ViewPose;
use shadowlab_raster::{DepthFormat, EyeImage, NO_TRIANGLE, Triangles};
use shadowlab_scene::Scene;
use shadowlab_shadow::{Bias, Filter, LightSetup, Lookup, MapOptions, ShadowMap, eye_pass};

use crate::support::{box_over_ground, camera, on_threads, orthographic, scene, split_mix64, sun};

/// Texels per side of the aligned map: over the 16-unit window, a texel is 1/4 unit, so the box's
/// edges at ±2 fall on texel edges 24 and 40.
const ALIGNED_RESOLUTION: u32 = 64;

/// A uniform map straight down over `[−8 + shift, 8 + shift]²` (x across, −z up the map): window
/// x = (x + 8 − shift)/16 and y = (8 − z − shift)/16, computed exactly for these values.
fn straight_down(shift: f64) -> LightSetup {
    let pose = ViewPose::look_to(DVec3::new(0.0, 10.0, 0.0), DVec3::NEG_Y, DVec3::NEG_Z).unwrap();
    orthographic(&pose, 8.0, shift)
}

/// The lit fractions of every pixel of `eye` under `setup`'s map of `scene` (1 where nothing is
/// visible, as `Frame::lit` has them).
fn look_up(scene: &Scene, eye: &EyeImage, setup: &LightSetup) -> Vec<f64> {
    let options = MapOptions {
        resolution: ALIGNED_RESOLUTION,
        format: DepthFormat::F32,
        second_depth: false,
    };
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let map = ShadowMap::render(setup, mesh, options).unwrap();
    let lookup = Lookup::new(Bias::DEFAULT, Filter::Nearest);
    (0..eye.triangle.len())
        .map(|p| {
            if eye.triangle[p] == NO_TRIANGLE {
                1.0
            } else {
                lookup.lit_fraction(&map, eye.position[p], eye.normal[p])
            }
        })
        .collect()
}

/// Claim: a uniform map whose texel edges fall exactly on the edges of the box's shadow (sun
/// straight down, window chosen by hand) misclassifies no pixel — although hundreds of visible
/// ground points lie within one texel of the shadow's edge on either side — while the same map
/// shifted by 0.3 texel misclassifies many, both ways. (The box's sides, parallel to the light,
/// are lit in truth — their rays pass just outside the box — and by the default slope-scaled bias,
/// which is at its cap there.)
#[test]
fn an_aligned_uniform_map_misclassifies_nothing() {
    // Seen from the +x, +z side, under the floating box: the ground under it and its shadow's
    // edges are visible through the gap.
    let camera = camera(
        DVec3::new(10.0, 6.0, 11.0),
        DVec3::new(-1.0, 1.0, -1.0),
        55.0,
        320,
        240,
    );
    let scene = scene(camera, vec![sun(DVec3::Y)], &box_over_ground());
    let (eye, _) = eye_pass(&scene).unwrap();
    let truth = exact_truth(&scene, &eye, &scene_bvh(&scene).unwrap()).unwrap();

    let aligned = misclassification(&truth, &[look_up(&scene, &eye, &straight_down(0.0))]);
    assert_eq!(aligned.total(), 0, "{aligned:?}");

    // The test has teeth: ground points close to the shadow's edge, on both sides.
    let texel = 16.0 / f64::from(ALIGNED_RESOLUTION);
    let (mut inside, mut outside) = (0, 0);
    for (p, lit) in truth.lit[0].iter().enumerate() {
        let point = eye.position[p];
        let Some(lit) = lit else { continue };
        let to_edge = (point.x.abs() - 2.0).max(point.z.abs() - 2.0);
        if point.y == 0.0 && to_edge.abs() < texel {
            if *lit {
                outside += 1;
            } else {
                inside += 1;
            }
        }
    }
    assert!(
        inside > 100 && outside > 100,
        "{inside} inside, {outside} outside"
    );
    assert_eq!(
        aligned.visible,
        truth.lit[0].iter().flatten().count() as u64
    );

    let shifted = misclassification(
        &truth,
        &[look_up(&scene, &eye, &straight_down(0.3 * texel))],
    );
    assert!(
        shifted.falsely_lit > 20 && shifted.falsely_shadowed > 20,
        "{shifted:?}"
    );
}

/// A truth of one light over four pixels: nothing, lit, shadowed, outside the cone.
fn four_pixels() -> Truth {
    Truth {
        lit: vec![vec![None, Some(true), Some(false), Some(false)]],
        outside_cone: vec![vec![false, false, false, true]],
    }
}

/// Claim: pairs are counted as documented — lit at a fraction of at least ½, nothing judged where
/// nothing is visible or outside a cone — and summed over lights; the percentage is of the judged
/// pairs.
#[test]
fn misclassification_counts_as_documented() {
    let truth = four_pixels();
    let count = |lit: [f64; 4]| misclassification(&truth, &[lit.to_vec()]);
    assert_eq!(
        count([0.0, 1.0, 0.0, 1.0]),
        Misclassification {
            visible: 2,
            falsely_lit: 0,
            falsely_shadowed: 0
        }
    );
    assert_eq!(
        count([1.0, 0.49, 0.5, 0.0]),
        Misclassification {
            visible: 2,
            falsely_lit: 1,
            falsely_shadowed: 1
        }
    );
    assert_eq!(count([1.0, 0.49, 0.5, 0.0]).percentage(), 100.0);
    assert_eq!(count([1.0, 0.5, 0.25, 1.0]).percentage(), 0.0);
    assert_eq!(Misclassification::default().percentage(), 0.0);

    let two = Truth {
        lit: [four_pixels().lit, four_pixels().lit].concat(),
        outside_cone: [four_pixels().outside_cone, four_pixels().outside_cone].concat(),
    };
    let wrong = misclassification(&two, &[vec![1.0, 1.0, 1.0, 1.0], vec![0.0; 4]]);
    assert_eq!(
        wrong,
        Misclassification {
            visible: 4,
            falsely_lit: 1,
            falsely_shadowed: 1
        }
    );
    assert_eq!(wrong.total(), 2);
    assert_eq!(wrong.percentage(), 50.0);
}

/// Claim: the difference image colours each pixel by the documented precedence (falsely lit over
/// falsely shadowed over correct), with the background where nothing is visible.
#[test]
fn the_difference_image_uses_the_documented_colours() {
    let truth = Truth {
        lit: vec![
            vec![
                None,
                Some(true),
                Some(false),
                Some(true),
                Some(false),
                Some(false),
            ],
            vec![
                None,
                Some(false),
                Some(true),
                Some(false),
                Some(false),
                Some(true),
            ],
        ],
        outside_cone: vec![
            vec![false; 6],
            vec![false, false, false, false, false, true],
        ],
    };
    let lit = [
        vec![1.0, 0.0, 1.0, 1.0, 0.0, 0.0],
        vec![1.0, 0.0, 1.0, 0.0, 0.0, 1.0],
    ];
    let eye = EyeImage {
        width: 3,
        height: 2,
        depth: vec![1.0; 6],
        triangle: vec![NO_TRIANGLE, 0, 0, 0, 0, 0],
        position: vec![DVec3::ZERO; 6],
        normal: vec![DVec3::Y; 6],
    };
    assert_eq!(
        difference_image(&truth, &lit, &eye),
        [
            BACKGROUND,
            FALSELY_SHADOWED,
            FALSELY_LIT,
            CORRECT_LIT,
            CORRECT_SHADOW,
            CORRECT_SHADOW
        ]
    );
    let colours = [
        FALSELY_LIT,
        FALSELY_SHADOWED,
        CORRECT_LIT,
        CORRECT_SHADOW,
        BACKGROUND,
    ];
    for (k, a) in colours.iter().enumerate() {
        assert!(colours[k + 1..].iter().all(|b| a != b), "distinct colours");
    }
}

/// Claim: the counts are the direct tally of every judged pair, on 1 and 3 threads, for two lights
/// over more pixels than one work item takes (and a partial last one): pixels seeing nothing,
/// pixels outside a light's cone, and all four agreements of truth and lookup.
#[test]
fn counts_are_the_direct_tally_on_any_thread_count() {
    let mut next = split_mix64(16);
    let pixels = 3 * (1 << 14) + 1234;
    let mut truth = Truth {
        lit: Vec::new(),
        outside_cone: Vec::new(),
    };
    let mut lit = Vec::new();
    for _ in 0..2 {
        truth.lit.push(
            (0..pixels)
                .map(|_| match next() % 5 {
                    0 => None,
                    r => Some(r % 2 == 0),
                })
                .collect(),
        );
        truth
            .outside_cone
            .push((0..pixels).map(|_| next().is_multiple_of(7)).collect());
        lit.push(
            (0..pixels)
                .map(|_| (next() % 3) as f64 / 2.0)
                .collect::<Vec<f64>>(),
        );
    }
    let mut tally = Misclassification::default();
    for (light, fractions) in lit.iter().enumerate() {
        for (pixel, fraction) in fractions.iter().enumerate() {
            let (Some(truly_lit), false) =
                (truth.lit[light][pixel], truth.outside_cone[light][pixel])
            else {
                continue;
            };
            let judged_lit = *fraction >= shadowlab_analysis::truth::LIT_THRESHOLD;
            tally.visible += 1;
            tally.falsely_lit += u64::from(judged_lit && !truly_lit);
            tally.falsely_shadowed += u64::from(!judged_lit && truly_lit);
        }
    }
    assert!(tally.falsely_lit > 0 && tally.falsely_shadowed > 0);
    for threads in [1, 3] {
        assert_eq!(
            on_threads(threads, || misclassification(&truth, &lit)),
            tally
        );
    }
}
