//! Set-ups evaluated: the set-up written for a technique measures what analyzing the technique
//! measures, bit for bit but for the times; maps given as images shadowlab wrote measure what
//! rendering measures; a map pushed farther by a known amount lights exactly the pixels the
//! lookup's rule says; shimmer over a camera walk is `temporal`'s.

use std::path::Path;
use std::time::Duration;

use shadowlab_analysis::classify::misclassification;
use shadowlab_analysis::evaluate::evaluate;
use shadowlab_analysis::report::report;
use shadowlab_analysis::setup_file::{
    CameraEntry, NdcDepthRange, Setup, SetupError, SetupFile, load_setup, parse_setup, setup_for,
};
use shadowlab_analysis::study::{self, Outcome, StudyOptions};
use shadowlab_analysis::temporal::{Stability, pose_at, temporal};
use shadowlab_raster::DepthFormat;
use shadowlab_raster::image_out::{depth_exr, depth_npy, depth_png16};
use shadowlab_scene::Scene;
use shadowlab_shadow::optimal::OptimalOptions;
use shadowlab_shadow::{
    Bias, DepthComparison, Filter, FocusPolicy, FrameOptions, Lookup, PlanOptions, Prefilter,
    ShadowMap, Splits, StepDirection, Technique, WarpChoice, eye_pass, render_shadows,
};

use crate::setup_file::small_outdoor;
use crate::support::on_threads;

/// One combination: technique, partitions, filter, bias and format, at 256² maps.
#[derive(Clone, Copy)]
struct Case {
    technique: Technique,
    partitions: usize,
    filter: Filter,
    bias: Bias,
    format: DepthFormat,
}

const RESOLUTION: u32 = 256;
const SPLITS: Splits = Splits::Practical { weight: 0.5 };

/// The optimizer with a smaller initial map, for speed.
fn optimal() -> OptimalOptions {
    OptimalOptions {
        initial_resolution: 256,
        ..OptimalOptions::default()
    }
}

impl Case {
    fn new(technique: Technique) -> Self {
        Self {
            technique,
            partitions: 1,
            filter: Filter::Nearest,
            bias: Bias::DEFAULT,
            format: DepthFormat::F32,
        }
    }

    fn frame_options(self) -> FrameOptions {
        FrameOptions {
            plan: PlanOptions {
                technique: self.technique,
                partitions: self.partitions,
                splits: SPLITS,
                focus: FocusPolicy::Light,
                optimal: optimal(),
            },
            resolution: RESOLUTION,
            format: self.format,
            lookup: Lookup::new(self.bias, self.filter),
            snap_texels: 0,
        }
    }

    fn study_options(self) -> StudyOptions {
        StudyOptions {
            techniques: vec![self.technique],
            resolutions: vec![RESOLUTION],
            partitions: vec![self.partitions],
            splits: SPLITS,
            filters: vec![self.filter],
            bias: self.bias,
            format: self.format,
            map_truth: false,
            pictures_at: Some(RESOLUTION),
            optimal: optimal(),
            focus: FocusPolicy::Light,
            timing_runs: 1,
        }
    }
}

/// `outcome` with its times zeroed.
fn untimed(outcome: &Outcome) -> Outcome {
    Outcome {
        planning: Duration::ZERO,
        shadow_pass: Duration::ZERO,
        lookup: Duration::ZERO,
        attribution: Duration::ZERO,
        footprints: Duration::ZERO,
        time_spread: Duration::ZERO,
        ..outcome.clone()
    }
}

/// Every frame's study and the stability of `setup` evaluated on `scene`.
fn evaluated(
    scene: &Scene,
    setup: &Setup,
    pictures: bool,
) -> (Vec<study::Study>, Option<Stability>) {
    let mut studies = Vec::new();
    let stability = evaluate(scene, setup, pictures, |k, study| {
        assert_eq!(k, studies.len());
        studies.push(study);
    })
    .unwrap();
    (studies, stability)
}

/// The single frame's outcome of `setup` on `scene`.
fn outcome_of(scene: &Scene, setup: &Setup) -> Outcome {
    let (studies, stability) = evaluated(scene, setup, false);
    assert!(stability.is_none());
    untimed(studies[0].measurements[0].outcome.as_ref().unwrap())
}

fn read(file: &SetupFile) -> Setup {
    parse_setup(&file.to_json(), Path::new("setup.json")).unwrap()
}

/// Claim: for uniform, LiSPSM, PSM, a three-map practical split and the scene-optimized map —
/// with filters, biases (one reading second depths) and depth formats varied — the written set-up
/// evaluates to analyze's measurement bit for bit (counts, footprint statistics, setting,
/// pictures) but for the times.
#[test]
fn a_written_set_up_measures_what_analyzing_the_technique_measures() {
    let scene = small_outdoor();
    let cases = [
        Case::new(Technique::Uniform),
        Case {
            filter: Filter::Pcf { size: 3 },
            format: DepthFormat::Unorm24,
            ..Case::new(Technique::Lispsm(WarpChoice::PAPER))
        },
        Case {
            bias: Bias::new(DepthComparison::Midpoint),
            filter: Filter::Disk {
                taps: 8,
                radius: 1.5,
                seed: 7,
            },
            ..Case::new(Technique::Psm)
        },
        Case {
            partitions: 3,
            filter: Filter::Vsm {
                size: 3,
                min_variance: 1e-6,
                prefilter: Prefilter::default(),
            },
            format: DepthFormat::ReversedF32,
            ..Case::new(Technique::Lispsm(WarpChoice::PAPER))
        },
        Case {
            partitions: 2,
            ..Case::new(Technique::Optimal(StepDirection::Paper))
        },
    ];
    for case in cases {
        let analyzed = study::run(&scene, &case.study_options(), |_, _, _| {}).unwrap();
        let file = setup_for(&scene, &case.frame_options()).unwrap();
        let setup = read(&file);
        assert_eq!(setup.frames[0].lights[0].len(), case.partitions);
        let (studies, _) = evaluated(&scene, &setup, true);
        let (expected, got) = (&analyzed.measurements[0], &studies[0].measurements[0]);
        let label = case.technique.spec();
        assert_eq!(got.setting, expected.setting, "{label}");
        assert_eq!(
            untimed(got.outcome.as_ref().unwrap()),
            untimed(expected.outcome.as_ref().unwrap()),
            "{label}"
        );
        assert!(got.outcome.as_ref().unwrap().errors.total() > 0, "{label}");
        let study = &studies[0];
        assert_eq!(
            (study.width, study.height, study.visible),
            (analyzed.width, analyzed.height, analyzed.visible)
        );
        assert_eq!(study.truth, analyzed.truth, "{label}");
        assert_eq!(study.pictures, analyzed.pictures, "{label}");
    }
}

/// Claim: an engine's set-up (no technique named) is labelled `given`, and the report writer
/// writes its study as it writes analyze's.
#[test]
fn a_set_up_made_elsewhere_is_reported_as_given() {
    let scene = small_outdoor();
    let mut file = setup_for(&scene, &Case::new(Technique::Uniform).frame_options()).unwrap();
    file.technique = None;
    let setup = read(&file);
    assert_eq!(setup.technique, Technique::Given);
    let (studies, _) = evaluated(&scene, &setup, false);
    let written = report(&studies[0]).unwrap();
    assert!(
        written.markdown.contains("| resolution | given |"),
        "{}",
        written.markdown
    );
    assert!(
        written.csv.contains(",given,256,1,nearest,true,"),
        "{}",
        written.csv
    );
}

/// Claim: the evaluation is the same on one thread and on two.
#[test]
fn the_evaluation_is_the_same_on_any_thread_count() {
    let scene = small_outdoor();
    let case = Case {
        partitions: 2,
        filter: Filter::Pcf { size: 3 },
        ..Case::new(Technique::Lispsm(WarpChoice::PAPER))
    };
    let setup = read(&setup_for(&scene, &case.frame_options()).unwrap());
    let one = on_threads(1, || outcome_of(&scene, &setup));
    let two = on_threads(2, || outcome_of(&scene, &setup));
    assert_eq!(one, two);
}

/// The maps `case` renders for the scene's frame, per light (as `render_shadows` makes them).
fn rendered_maps(scene: &Scene, case: Case) -> Vec<Vec<ShadowMap>> {
    let (eye, nearest) = eye_pass(scene).unwrap();
    render_shadows(scene, &case.frame_options(), &eye, nearest, None)
        .unwrap()
        .lights
        .into_iter()
        .map(|light| light.maps.into_iter().map(|(_, map)| map).collect())
        .collect()
}

/// Writes a map's depths (side given) as an image file's bytes.
type Writer = dyn Fn(&[f64], u32) -> Vec<u8>;

/// `file` with each partition's depth image written into `dir` by `write` (and its second depths,
/// where the map has them), then read from there.
fn with_images(
    dir: &Path,
    mut file: SetupFile,
    maps: &[Vec<ShadowMap>],
    extension: &str,
    write: impl Fn(&[f64], u32) -> Vec<u8>,
) -> Setup {
    for (l, light) in file.frames[0].lights.iter_mut().enumerate() {
        for (p, partition) in light.partitions.iter_mut().enumerate() {
            let map = &maps[l][p];
            let name = format!("maps/l{l}-p{p}.{extension}");
            std::fs::create_dir_all(dir.join("maps")).unwrap();
            std::fs::write(dir.join(&name), write(&map.nearest, map.resolution)).unwrap();
            partition.depth_image = Some(name);
            if let Some(second) = &map.second {
                let name = format!("maps/l{l}-p{p}-second.npy");
                std::fs::write(
                    dir.join(&name),
                    depth_npy(second, map.resolution, map.resolution).unwrap(),
                )
                .unwrap();
                partition.second_depth_image = Some(name);
            }
        }
    }
    let path = dir.join("setup.json");
    std::fs::write(&path, file.to_json()).unwrap();
    load_setup(&path).unwrap()
}

/// Claim: the maps shadowlab renders, written as EXR, NPY or (unorm16) 16-bit PNG and given as
/// the partitions' depth images, measure exactly what rendering them measures — second depths and
/// two partitions included.
#[test]
fn maps_shadowlab_wrote_measure_what_rendering_measures() {
    let scene = small_outdoor();
    let dir = tempfile::tempdir().unwrap();
    let exr = |d: &[f64], side: u32| depth_exr(d, side, side).unwrap();
    let npy = |d: &[f64], side: u32| depth_npy(d, side, side).unwrap();
    let png = |d: &[f64], side: u32| depth_png16(d, side, side).unwrap();
    let cases: [(Case, &str, &Writer); 3] = [
        (
            Case {
                partitions: 2,
                ..Case::new(Technique::Lispsm(WarpChoice::PAPER))
            },
            "exr",
            &exr,
        ),
        (
            Case {
                bias: Bias::new(DepthComparison::Midpoint),
                ..Case::new(Technique::Psm)
            },
            "npy",
            &npy,
        ),
        (
            Case {
                format: DepthFormat::Unorm16,
                bias: Bias::new(DepthComparison::Constant { offset: 2e-4 }),
                ..Case::new(Technique::Uniform)
            },
            "png",
            &png,
        ),
    ];
    for (k, (case, extension, write)) in cases.into_iter().enumerate() {
        let file = setup_for(&scene, &case.frame_options()).unwrap();
        let rendered = outcome_of(&scene, &read(&file));
        let maps = rendered_maps(&scene, case);
        let case_dir = dir.path().join(k.to_string());
        let given = with_images(&case_dir, file, &maps, extension, write);
        assert!(given.frames[0].lights[0][0].depth_image.is_some());
        assert_eq!(outcome_of(&scene, &given), rendered, "{extension}");
    }
}

/// Claim: a map whose depths are pushed by δ (clamped to [0, 1], stored as f32) is looked up by
/// the rule `receiver ≤ stored + offset` exactly: the misclassification is the one that rule
/// gives pixel by pixel, and pushing farther (δ > 0) makes more pixels falsely lit and none more
/// falsely shadowed, pushing nearer the reverse.
#[test]
fn a_perturbed_map_misclassifies_as_its_rule_predicts() {
    let scene = small_outdoor();
    let offset = 1e-4;
    let case = Case {
        bias: Bias::new(DepthComparison::Constant { offset }),
        ..Case::new(Technique::Lispsm(WarpChoice::PAPER))
    };
    let file = setup_for(&scene, &case.frame_options()).unwrap();
    let (studies, _) = evaluated(&scene, &read(&file), false);
    let baseline = studies[0].measurements[0].outcome.as_ref().unwrap().errors;
    let truth = &studies[0].truth;
    let map = &rendered_maps(&scene, case)[0][0];
    let (eye, _) = eye_pass(&scene).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for delta in [3e-3, -3e-3] {
        #[expect(clippy::cast_possible_truncation, reason = "the image holds f32")]
        let pushed: Vec<f64> = map
            .nearest
            .iter()
            .map(|z| f64::from((z + delta).clamp(0.0, 1.0) as f32))
            .collect();
        let moved = ShadowMap {
            nearest: pushed.clone(),
            ..map.clone()
        };
        // The rule, pixel by pixel: lit where nothing is visible, where the map does not reach,
        // or where the receiver's depth is at most the pushed depth plus the offset.
        let predicted: Vec<f64> = eye
            .position
            .iter()
            .map(|&point| {
                let lit = map.setup.mapping.window(point).is_none_or(|window| {
                    map.texel_of(window)
                        .is_none_or(|(i, j)| window.z <= moved.depth(i, j) + offset)
                });
                if lit { 1.0 } else { 0.0 }
            })
            .collect();
        let expected = misclassification(truth, &[predicted]);
        let exr = |d: &[f64], side: u32| depth_exr(d, side, side).unwrap();
        let given = with_images(
            &dir.path().join(format!("{delta}")),
            file.clone(),
            &[vec![moved]],
            "exr",
            exr,
        );
        let got = outcome_of(&scene, &given).errors;
        assert_eq!(got, expected, "δ = {delta}");
        if delta > 0.0 {
            assert!(
                got.falsely_lit > baseline.falsely_lit,
                "{got:?} {baseline:?}"
            );
            assert!(got.falsely_shadowed <= baseline.falsely_shadowed);
        } else {
            assert!(
                got.falsely_shadowed > baseline.falsely_shadowed,
                "{got:?} {baseline:?}"
            );
            assert!(got.falsely_lit <= baseline.falsely_lit);
        }
    }
}

/// Claim: with a reversed NDC depth range, depth images hold `1 − z` as a reversed-Z buffer does;
/// given so, they measure what rendering the same file's matrices measures.
#[test]
fn reversed_depth_images_hold_one_minus_z() {
    let scene = small_outdoor();
    let case = Case {
        format: DepthFormat::ReversedF32,
        ..Case::new(Technique::Uniform)
    };
    let mut file = setup_for(&scene, &case.frame_options()).unwrap();
    file.conventions.ndc_depth = NdcDepthRange::ReversedZeroToOne;
    for partition in &mut file.frames[0].lights[0].partitions {
        // z_reversed = (w − z_gl)/2: the depth row becomes (row w − row z)/2.
        let p = &mut partition.projection;
        for c in 0..4 {
            p[8 + c] = (p[12 + c] - p[8 + c]) * 0.5;
        }
    }
    let setup = read(&file);
    let rendered = outcome_of(&scene, &setup);
    // The maps of the file's own (converted) matrices, which rendering it draws.
    let partition = &setup.frames[0].lights[0][0];
    let light_setup = shadowlab_shadow::LightSetup {
        technique: Technique::Given,
        mapping: shadowlab_shadow::ShadowMapping::Projective(
            shadowlab_shadow::ProjectiveMapping::new(partition.view, partition.projection),
        ),
        gamma: 0.0,
        half_fov: 0.0,
        warp: None,
        psm: None,
        focus_body: Vec::new(),
    };
    let map = ShadowMap::render(
        &light_setup,
        shadowlab_raster::Triangles::new(scene.mesh.positions(), scene.mesh.triangles()),
        shadowlab_shadow::MapOptions {
            resolution: RESOLUTION,
            format: DepthFormat::ReversedF32,
            second_depth: false,
        },
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let reversed = |d: &[f64], side: u32| {
        let stored: Vec<f64> = d.iter().map(|z| 1.0 - z).collect();
        depth_exr(&stored, side, side).unwrap()
    };
    let given = with_images(dir.path(), file, &[vec![map]], "exr", reversed);
    assert!(
        given.frames[0].lights[0][0]
            .depth_image
            .as_ref()
            .unwrap()
            .reversed
    );
    assert_eq!(outcome_of(&scene, &given), rendered);
}

/// The error of evaluating `setup` on `scene`.
fn evaluation_error(scene: &Scene, setup: &Setup) -> String {
    evaluate(scene, setup, false, |_, _| {})
        .unwrap_err()
        .to_string()
}

/// Claim: images of another size, with values that are not depths, or missing are refused with
/// the set-up file, the field and the image named; so is a frame with another number of lights.
#[test]
fn bad_images_and_frames_are_refused_by_field() {
    let scene = small_outdoor();
    let case = Case::new(Technique::Uniform);
    let file = setup_for(&scene, &case.frame_options()).unwrap();
    let maps = rendered_maps(&scene, case);
    let dir = tempfile::tempdir().unwrap();
    let field = "frames[0].lights[0].partitions[0].depth_image";

    let small = |d: &[f64], _: u32| depth_exr(&d[..4], 2, 2).unwrap();
    let setup = with_images(&dir.path().join("size"), file.clone(), &maps, "exr", small);
    let message = evaluation_error(&scene, &setup);
    assert!(
        message.contains(&format!("setup.json: {field}: ")),
        "{message}"
    );
    assert!(
        message.contains("l0-p0.exr: the EXR image is 2×2 but the map is 256×256"),
        "{message}"
    );

    let beyond = |d: &[f64], side: u32| {
        let mut d = d.to_vec();
        d[3 * 256 + 5] = 1.5;
        depth_npy(&d, side, side).unwrap()
    };
    let setup = with_images(
        &dir.path().join("beyond"),
        file.clone(),
        &maps,
        "npy",
        beyond,
    );
    let message = evaluation_error(&scene, &setup);
    assert!(
        message.contains("texel (5, 3) (column, row from the bottom) holds 1.5"),
        "{message}"
    );

    let setup = with_images(
        &dir.path().join("gone"),
        file.clone(),
        &maps,
        "exr",
        |d, s| depth_exr(d, s, s).unwrap(),
    );
    std::fs::remove_dir_all(dir.path().join("gone/maps")).unwrap();
    let error = evaluate(&scene, &setup, false, |_, _| {}).unwrap_err();
    let SetupError::ImageRead { source, .. } = &error else {
        panic!("{error}");
    };
    assert!(source.is_bad_input(), "{error}");

    let mut two = file.clone();
    let light = two.frames[0].lights[0].clone();
    two.frames[0].lights.push(light);
    let message = evaluation_error(&scene, &read(&two));
    assert!(
        message.contains("frames[0].lights: 2 lights for a scene with 1"),
        "{message}"
    );
}

/// Claim: over a camera walk, each frame's set-up written with its camera evaluates to the
/// shimmer `temporal` counts, frame pair by frame pair; frames of another image size are refused.
#[test]
fn shimmer_over_a_walk_is_temporals() {
    let scene = small_outdoor();
    let frames = 4;
    let expected = temporal(
        &scene,
        &[Technique::Uniform],
        frames,
        RESOLUTION,
        Filter::Nearest,
        |_, _| {},
    )
    .unwrap();
    let options = FrameOptions {
        lookup: Lookup::new(Bias::DEFAULT, Filter::Nearest),
        ..Case::new(Technique::Uniform).frame_options()
    };
    let mut file: Option<SetupFile> = None;
    for k in 0..frames {
        let mut moved = scene.clone();
        moved.camera.pose = pose_at(&scene, k).unwrap();
        let mut frame = setup_for(&moved, &options).unwrap().frames.remove(0);
        frame.camera = Some(CameraEntry::of(&moved.camera));
        match &mut file {
            None => {
                let mut first = setup_for(&moved, &options).unwrap();
                first.frames = vec![frame];
                file = Some(first);
            }
            Some(file) => file.frames.push(frame),
        }
    }
    let mut file = file.unwrap();
    let setup = read(&file);
    let (studies, stability) = evaluated(&scene, &setup, false);
    assert_eq!(studies.len(), frames);
    let stability = stability.unwrap();
    let counts = stability.shimmer.unwrap();
    assert_eq!(Ok(counts.clone()), expected[0].shimmer, "snapping off");
    assert!(counts.iter().any(|c| *c > 0), "{counts:?}");
    assert_eq!(
        (stability.technique, stability.snap_texels),
        (Technique::Uniform, 0)
    );

    file.frames[1].camera.as_mut().unwrap().width = Some(80);
    file.frames[1].camera.as_mut().unwrap().height = Some(60);
    let message = evaluation_error(&scene, &read(&file));
    assert!(
        message.contains("frames[1].camera: an image of 80×60 after frame 0's 160×120"),
        "{message}"
    );
}
