//! Attribution: scenes built so that each cause occurs alone (acne, peter-panning, aliasing, a
//! seam in a blend band, a seam at a hard boundary), the five counts summing to the
//! misclassified pairs on every built-in scene, and the same causes on one and two threads.

use std::f64::consts::FRAC_1_SQRT_2;

use glam::{DAffine3, DVec3};
use shadowlab_analysis::attribution::{Attribution, Cause, Causes, attribute};
use shadowlab_analysis::classify::{Misclassification, misclassification};
use shadowlab_analysis::study::{self, StudyOptions};
use shadowlab_analysis::truth::{Truth, exact_truth, scene_bvh};
use shadowlab_hull::ViewPose;
use shadowlab_raster::{DepthFormat, EyeImage, NO_TRIANGLE};
use shadowlab_scene::{BUILTIN_SCENES, Mesh, Scene, builtin_scene, procedural};
use shadowlab_shadow::{
    Beyond, Bias, DepthComparison, Filter, FocusPolicy, LightMaps, LightSetup, LightSource, Lookup,
    MapOptions, MapSource, Partition, PartitionMap, Selection, SelectionRule, Shadows, Splits,
    Technique, eye_pass, scene_eye, served, shadows_of,
};
use shadowlab_trace::Bvh;

use crate::support::{camera, on_threads, orthographic, scene, sun};

/// A scene's eye pass, hierarchy and exact truth.
struct Judged {
    scene: Scene,
    eye: EyeImage,
    bvh: Bvh,
    truth: Truth,
}

impl Judged {
    fn new(scene: Scene) -> Self {
        let (eye, _) = eye_pass(&scene).unwrap();
        let bvh = scene_bvh(&scene).unwrap();
        let truth = exact_truth(&scene, &eye, &bvh).unwrap();
        Self {
            scene,
            eye,
            bvh,
            truth,
        }
    }

    /// The shadows of the first light from maps of `resolution` texels over `partitions` (eye
    /// depths and set-up each), read with `lookup` and chosen by eye depth, blended if `blend`.
    fn shadows(
        &self,
        partitions: &[(f64, f64, LightSetup)],
        resolution: u32,
        lookup: &Lookup,
        blend: bool,
    ) -> Shadows {
        let light = LightMaps {
            light: LightSource::from_scene(&self.scene.lights[0]),
            partitions: partitions
                .iter()
                .map(|(near, far, setup)| PartitionMap {
                    partition: Partition {
                        near: *near,
                        far: *far,
                        face: None,
                        sphere: None,
                        setup: setup.clone(),
                    },
                    source: MapSource::Render(MapOptions {
                        resolution,
                        format: DepthFormat::F32,
                        second_depth: false,
                    }),
                    lookup: lookup.clone(),
                })
                .collect(),
            selection: Selection {
                rule: SelectionRule::Depth,
                blend,
                beyond: Beyond::Last,
                fade: None,
            },
        };
        shadows_of(&self.scene, &self.eye, vec![light], Some(&self.bvh)).unwrap()
    }

    /// The misclassified pairs of `shadows` and their attribution (read with `filter`).
    fn attribute(&self, shadows: &Shadows, filter: Filter) -> (Misclassification, Attribution) {
        let attribution = attribute(
            &self.scene,
            &self.eye,
            &self.truth,
            (&shadows.lights, &shadows.lit),
            |_, _| filter,
            &self.bvh,
        )
        .unwrap();
        (misclassification(&self.truth, &shadows.lit), attribution)
    }
}

/// Causes with only `cause` set to `n`.
fn only(n: u64, set: impl FnOnce(&mut Causes) -> &mut u64) -> Causes {
    let mut causes = Causes::default();
    *set(&mut causes) = n;
    causes
}

/// Claim: a lone plane lit at a grazing angle and read without bias is falsely shadowed only by
/// its own depth: every misclassified pixel is acne, and there are many — in the uniform map, in
/// LiSPSM's and PSM's (projective: the texel's ray unprojected) and in the logarithmic map (its
/// texel ray); with the default slope-scaled bias the uniform map's acne is gone.
#[test]
fn a_lone_plane_without_bias_has_only_acne() {
    let plane = procedural::plane(40.0, 40.0, 4).unwrap();
    let camera = camera(
        DVec3::new(0.0, 6.0, 14.0),
        DVec3::new(0.0, 0.0, 0.0),
        50.0,
        160,
        120,
    );
    // 8° above the ground.
    let scene = scene(
        camera,
        vec![sun(DVec3::new(1.0, 0.14, 0.3))],
        std::slice::from_ref(&plane),
    );
    let study = |technique, bias| {
        let options = StudyOptions {
            techniques: vec![technique],
            resolutions: vec![256],
            partitions: vec![1],
            splits: Splits::Uniform,
            filters: vec![Filter::Nearest],
            bias,
            format: DepthFormat::F32,
            map_truth: false,
            pictures_at: None,
            optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
            focus: FocusPolicy::Light,
            timing_runs: 1,
        };
        let study = study::run(&scene, &options, |_, _, _| {}).unwrap();
        study.measurements[0].outcome.clone().unwrap()
    };
    for key in ["uniform", "lispsm", "psm", "logarithmic"] {
        let raw = study(Technique::parse(key, None).unwrap(), Bias::NONE);
        assert_eq!(raw.errors.falsely_lit, 0, "{key}: {:?}", raw.errors);
        assert!(raw.errors.falsely_shadowed > 500, "{key}: {:?}", raw.errors);
        assert_eq!(
            raw.causes,
            only(raw.errors.total(), |c| &mut c.acne),
            "{key}: {:?}",
            raw.errors
        );
    }
    let biased = study(Technique::Uniform, Bias::DEFAULT);
    assert_eq!(biased.causes.acne, 0, "{:?}", biased.causes);
}

/// A sun 45° above the ground toward +x, `(1, 1, 0)/√2`.
fn diagonal_sun() -> DVec3 {
    DVec3::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0)
}

/// Claim: a box resting on a plane, under a sun at 45°, its map aligned so that the box's shadow
/// edges fall on texel edges, read with a constant bias larger than the box's height along the
/// light: its whole visible shadow on the ground is lit by the bias, and every misclassified
/// pixel is peter-panning. Without the bias nothing is misclassified, so the alignment leaves no
/// edge texel in error.
#[test]
fn a_resting_box_under_a_large_bias_has_only_peter_panning() {
    let ground = procedural::plane(40.0, 40.0, 1).unwrap();
    let block = procedural::cuboid(DVec3::new(2.0, 2.0, 2.0))
        .unwrap()
        .transformed(&DAffine3::from_translation(DVec3::new(0.0, 1.0, 0.0)));
    // From above the box's +x side, in the plane z = 0: the box's −x and ±z faces, which face
    // away or lie parallel to the light, are hidden; its shadow on the ground (x ∈ [−3, −1],
    // z ∈ [−1, 1]) is seen past it.
    let camera = camera(
        DVec3::new(3.0, 12.0, 0.0),
        DVec3::new(-2.0, 0.0, 0.0),
        50.0,
        200,
        150,
    );
    let judged = Judged::new(scene(camera, vec![sun(diagonal_sun())], &[ground, block]));
    // The map's y axis is `up`, its x axis ±z. Texels of 1/16 over a window of half-width 8: the
    // shadow's sides z = ±1 lie on texel edges as they are; its far end, the ground point
    // (−3, 0, 0) at up-coordinate 3/√2, is moved onto the texel edge at 2.125 by moving the
    // light along `up`.
    let up = DVec3::new(-FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0);
    let along = 3.0 * FRAC_1_SQRT_2 - 2.125;
    let pose = ViewPose::look_to(diagonal_sun() * 20.0 + up * along, -diagonal_sun(), up).unwrap();
    let setup = orthographic(&pose, 8.0, 0.0);
    let partitions = [(0.0, 1000.0, setup)];

    // The box stands 2√2 ≈ 2.83 above the ground along the light: 0.073 in window depth (depths
    // 1 to 40); a bias of 0.1 lights all of its shadow.
    let biased = Lookup::new(
        Bias::new(DepthComparison::Constant { offset: 0.1 }),
        Filter::Nearest,
    );
    let shadows = judged.shadows(&partitions, 256, &biased, false);
    let (errors, attribution) = judged.attribute(&shadows, Filter::Nearest);
    assert_eq!(errors.falsely_shadowed, 0, "{errors:?}");
    assert!(errors.falsely_lit > 200, "{errors:?}");
    assert_eq!(
        attribution.counts,
        only(errors.total(), |c| &mut c.peter_panning)
    );

    // The design: with no bias at all the aligned map lights no point in shadow — every texel of
    // the shadow holds the box.
    let unbiased = Lookup::new(Bias::NONE, Filter::Nearest);
    let shadows = judged.shadows(&partitions, 256, &unbiased, false);
    let (errors, _) = judged.attribute(&shadows, Filter::Nearest);
    assert_eq!(errors.falsely_lit, 0, "{errors:?}");
}

/// The sun straight down.
fn overhead_sun() -> DVec3 {
    DVec3::Y
}

/// A map straight down over `[−8 + shift, 8 + shift]²` (x across, −z up the map), depths 1 to
/// 40 from y = 10: the ground (y = 0) at window depth 9/39 and the strip (y = 6) at 3/39, which
/// f32 both rounds up — so no surface facing this light shadows itself unbiased.
fn straight_down(shift: f64) -> LightSetup {
    let pose = ViewPose::look_to(DVec3::new(0.0, 10.0, 0.0), DVec3::NEG_Y, DVec3::NEG_Z).unwrap();
    orthographic(&pose, 8.0, shift)
}

/// A 16 × 16 ground and, 6 above it, a strip x ∈ [−0.5, 0.5], z ∈ [−3, 3] (facing up), under the
/// overhead sun, seen from the +x, +z side below the strip, looking along it.
fn strip_scene() -> Judged {
    let ground = procedural::plane(16.0, 16.0, 1).unwrap();
    let strip = procedural::plane(1.0, 6.0, 1)
        .unwrap()
        .transformed(&DAffine3::from_translation(DVec3::new(0.0, 6.0, 0.0)));
    let camera = camera(
        DVec3::new(3.0, 4.0, 9.0),
        DVec3::new(0.0, 0.0, -1.0),
        55.0,
        240,
        180,
    );
    let judged = Judged::new(scene(camera, vec![sun(overhead_sun())], &[ground, strip]));
    // The premise of `straight_down`: both surfaces' depths round up in f32.
    let setup = straight_down(0.0);
    for point in [DVec3::new(1.0, 0.0, 2.0), DVec3::new(0.2, 6.0, -1.0)] {
        let z = setup.mapping.window(point).unwrap().z;
        #[expect(clippy::cast_possible_truncation, reason = "f32 storage, on purpose")]
        let stored = f64::from(z as f32);
        assert!(stored > z + 1e-10, "{point}: {z} is stored as {stored}");
    }
    judged
}

/// The lookup of the strip tests: a small constant bias.
fn small_bias() -> Lookup {
    Lookup::new(
        Bias::new(DepthComparison::Constant { offset: 1e-5 }),
        Filter::Nearest,
    )
}

/// Claim: a thin strip far above the ground, straight under the sun, in a coarse map whose texels
/// straddle its shadow's edges, with a bias that leaves no acne: pixels are misclassified both
/// ways along the edges, and every one is aliasing.
#[test]
fn a_thin_strip_in_a_coarse_map_has_only_aliasing() {
    let judged = strip_scene();
    // Texels of 0.5, shifted by 0.3 of one: no shadow edge on a texel edge.
    let partitions = [(0.0, 1000.0, straight_down(0.15))];
    let shadows = judged.shadows(&partitions, 32, &small_bias(), false);
    let (errors, attribution) = judged.attribute(&shadows, Filter::Nearest);
    assert!(
        errors.falsely_lit > 20 && errors.falsely_shadowed > 20,
        "{errors:?}"
    );
    assert_eq!(
        attribution.counts,
        only(errors.total(), |c| &mut c.aliasing)
    );
    // Per pixel, as counted.
    let per_pixel = attribution.per_pixel[0].iter().flatten().count() as u64;
    assert_eq!(per_pixel, errors.total());

    // Aligned (edges on texel edges), the same map misclassifies nothing.
    let aligned = judged.shadows(
        &[(0.0, 1000.0, straight_down(0.0))],
        32,
        &small_bias(),
        false,
    );
    let (errors, _) = judged.attribute(&aligned, Filter::Nearest);
    assert_eq!(errors.total(), 0, "{errors:?}");
}

/// The least and greatest eye depth of the strip's shadow's corners on the ground.
fn shadow_depths(judged: &Judged) -> (f64, f64) {
    let view = scene_eye(&judged.scene);
    [(-0.5, -3.0), (-0.5, 3.0), (0.5, -3.0), (0.5, 3.0)]
        .into_iter()
        .map(|(x, z)| (DVec3::new(x, 0.0, z) - view.pose.eye()).dot(view.pose.forward()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        })
}

/// Claim: two partitions blended over a band of eye depths that holds the strip's whole shadow —
/// the first an aligned map that errs nowhere, the second the misaligned one, which serves alone
/// only beyond the shadow, where it errs nowhere either — err only in the band, where the second
/// map weighs more; every misclassified pixel is a blend band's seam.
#[test]
fn a_misaligned_map_blended_in_errs_only_at_the_seam() {
    let judged = strip_scene();
    let (near, far) = shadow_depths(&judged);
    let partitions = [
        (0.0, far + 0.5, straight_down(0.0)),
        (near - 0.5, 1000.0, straight_down(0.15)),
    ];
    let shadows = judged.shadows(&partitions, 32, &small_bias(), true);
    let (errors, attribution) = judged.attribute(&shadows, Filter::Nearest);
    assert!(errors.total() > 20, "{errors:?}");
    assert_eq!(
        attribution.counts,
        only(errors.total(), |c| &mut c.seam_band)
    );

    // Without the blend the first map serves the shadow: nothing is misclassified.
    let shadows = judged.shadows(&partitions, 32, &small_bias(), false);
    let (errors, _) = judged.attribute(&shadows, Filter::Nearest);
    assert_eq!(errors.total(), 0, "{errors:?}");
}

/// The largest of `widths` for which every pixel served by the second of `partitions(width)` has
/// a 4-neighbour served by another, and how many pixels it serves.
fn thinnest_band(
    judged: &Judged,
    widths: &[f64],
    partitions: impl Fn(f64) -> Vec<(f64, f64, LightSetup)>,
) -> (f64, usize) {
    let view = scene_eye(&judged.scene);
    let eye = &judged.eye;
    let width = eye.width as usize;
    for band in widths {
        let shadows = judged.shadows(&partitions(*band), 32, &small_bias(), false);
        let light = &shadows.lights[0];
        let index = |p: usize| {
            (eye.triangle[p] != NO_TRIANGLE)
                .then(|| {
                    served(
                        &light.maps,
                        |(p, _)| p,
                        &light.selection,
                        &view,
                        eye.position[p],
                    )
                })
                .flatten()
                .map(|s| s.index)
        };
        let banded: Vec<usize> = (0..eye.triangle.len())
            .filter(|p| index(*p) == Some(1))
            .collect();
        let at_seam = banded.iter().all(|&p| {
            let (x, y) = (p % width, p / width);
            [
                (x > 0).then(|| p - 1),
                (x + 1 < width).then(|| p + 1),
                (y > 0).then(|| p - width),
                (p + width < eye.triangle.len()).then(|| p + width),
            ]
            .into_iter()
            .flatten()
            .any(|n| index(n).is_some_and(|k| k != 1))
        });
        if at_seam {
            return (*band, banded.len());
        }
    }
    panic!("no band of {widths:?} is thin enough");
}

/// Claim: a misaligned map serving a band of eye depths across the strip's shadow, so thin that
/// each of its pixels has a neighbour served by the aligned maps on either side: its errors are
/// boundary seams; widened, the same map's errors inside the band are aliasing.
#[test]
fn a_misaligned_map_in_a_thin_band_errs_only_at_the_seam() {
    let judged = strip_scene();
    let (near, far) = shadow_depths(&judged);
    let start = 0.5 * (near + far);
    let partitions = |width: f64| {
        vec![
            (0.0, start, straight_down(0.0)),
            (start, start + width, straight_down(0.15)),
            (start + width, 1000.0, straight_down(0.0)),
        ]
    };
    let (band, banded) = thinnest_band(&judged, &[0.2, 0.1, 0.05, 0.02], partitions);
    assert!(banded > 50, "{banded} pixels in a band {band} deep");
    let shadows = judged.shadows(&partitions(band), 32, &small_bias(), false);
    let (errors, attribution) = judged.attribute(&shadows, Filter::Nearest);
    assert!(errors.total() > 0, "{errors:?}");
    assert_eq!(
        attribution.counts,
        only(errors.total(), |c| &mut c.seam_boundary)
    );

    let wide = judged.shadows(&partitions(0.4 * (far - near)), 32, &small_bias(), false);
    let (errors, attribution) = judged.attribute(&wide, Filter::Nearest);
    assert!(
        attribution.counts.aliasing > 0 && attribution.counts.seam_boundary > 0,
        "{errors:?}: {:?}",
        attribution.counts
    );
    assert_eq!(attribution.counts.total(), errors.total());
}

/// The built-in scenes at a quarter of their image size, for speed.
fn quarter(name: &str) -> Scene {
    let mut scene = builtin_scene(name).unwrap();
    scene.camera.width /= 4;
    scene.camera.height /= 4;
    scene
}

/// Claim: on every built-in scene, for uniform and LiSPSM with one and three maps, nearest and
/// PCF, an engine's blended cascades, and PSM and the logarithmic map (one map each) — for the
/// point lights' scenes the cube, dual-paraboloid and PSM maps, nearest and PCF — the five causes
/// sum to the misclassified pixels, and each occurs somewhere.
#[test]
fn the_causes_sum_to_the_misclassified_pixels_on_every_built_in_scene() {
    let options =
        |techniques: &[&str], partitions: Vec<usize>, filters: Vec<Filter>| StudyOptions {
            techniques: techniques
                .iter()
                .map(|key| Technique::parse(key, None).unwrap())
                .collect(),
            resolutions: vec![512],
            partitions,
            splits: Splits::Practical { weight: 0.5 },
            filters,
            bias: Bias::DEFAULT,
            format: DepthFormat::F32,
            map_truth: false,
            pictures_at: None,
            optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
            focus: FocusPolicy::Light,
            timing_runs: 1,
        };
    let studies = [
        options(
            &["uniform", "lispsm", "bevy"],
            vec![1, 3],
            vec![Filter::Nearest, Filter::Pcf { size: 3 }],
        ),
        options(&["psm", "logarithmic"], vec![1], vec![Filter::Nearest]),
    ];
    // A point light's maps: the cube's six faces and the paraboloid's two hemispheres meet at
    // seams of their own.
    let point_studies = [options(
        &["cube", "dual-paraboloid", "psm"],
        vec![1],
        vec![Filter::Nearest, Filter::Pcf { size: 3 }],
    )];
    let mut seen = Causes::default();
    for name in BUILTIN_SCENES {
        let scene = quarter(name);
        let point = matches!(scene.lights[0], shadowlab_scene::SceneLight::Point { .. });
        for options in if point {
            &point_studies[..]
        } else {
            &studies[..]
        } {
            let study = study::run(&scene, options, |_, _, _| {}).unwrap();
            for m in &study.measurements {
                let Ok(o) = &m.outcome else { continue };
                assert_eq!(
                    o.causes.total(),
                    o.errors.total(),
                    "{name}, {:?}: {:?} against {:?}",
                    m.setting,
                    o.causes,
                    o.errors
                );
                seen += o.causes;
            }
        }
    }
    // Every cause occurs somewhere among them.
    assert!(
        Cause::ALL.iter().all(|&cause| seen.of(cause) > 0),
        "{seen:?}"
    );
}

/// Claim: the attribution — every pair's cause — is the same on one thread and on two.
#[test]
fn attribution_is_identical_on_any_thread_count() {
    let scene = quarter("outdoor");
    let (eye, nearest) = eye_pass(&scene).unwrap();
    let bvh = scene_bvh(&scene).unwrap();
    let truth = exact_truth(&scene, &eye, &bvh).unwrap();
    let options = shadowlab_shadow::FrameOptions {
        plan: shadowlab_shadow::PlanOptions {
            partitions: 3,
            ..shadowlab_shadow::PlanOptions::new(Technique::parse("lispsm", None).unwrap())
        },
        resolution: 256,
        format: DepthFormat::F32,
        lookup: Lookup::new(Bias::DEFAULT, Filter::Pcf { size: 3 }),
        snap_texels: 0,
    };
    let shadows =
        shadowlab_shadow::render_shadows(&scene, &options, &eye, nearest, Some(&bvh)).unwrap();
    let run = || {
        attribute(
            &scene,
            &eye,
            &truth,
            (&shadows.lights, &shadows.lit),
            |_, _| Filter::Pcf { size: 3 },
            &bvh,
        )
        .unwrap()
    };
    let one = on_threads(1, run);
    let two = on_threads(2, run);
    assert!(one.counts.total() > 0, "{:?}", one.counts);
    assert_eq!(one, two);
}

/// Claim: a hierarchy of another mesh is refused.
#[test]
fn a_hierarchy_of_another_mesh_is_refused() {
    let judged = strip_scene();
    let shadows = judged.shadows(
        &[(0.0, 1000.0, straight_down(0.0))],
        32,
        &small_bias(),
        false,
    );
    let other: Mesh = procedural::plane(1.0, 1.0, 1).unwrap();
    let bvh = Bvh::new(other.positions(), other.triangles()).unwrap();
    let refused = attribute(
        &judged.scene,
        &judged.eye,
        &judged.truth,
        (&shadows.lights, &shadows.lit),
        |_, _| Filter::Nearest,
        &bvh,
    );
    assert!(refused.is_err());
}
