//! The study's pictures as files: raw ones pixel for pixel, annotated ones holding the raw pixels
//! under a title naming scene, technique and settings, the difference image's legend agreeing
//! with the counted misclassifications, and every byte the same on any thread count.

use shadowlab_analysis::images::{CauseCounts, ClassCounts};
use shadowlab_analysis::pictures::{self, PictureKind};
use shadowlab_analysis::study::{self, Study, StudyOptions};
use shadowlab_raster::DepthFormat;
use shadowlab_shadow::{Bias, Filter, FocusPolicy, Splits, Technique};

use crate::support::on_threads;

/// The outdoor scene at 96 × 72, uniform and LiSPSM at 128².
fn tiny_study() -> Study {
    let mut scene = shadowlab_scene::builtin_scene("outdoor").expect("the built-in scene");
    (scene.camera.width, scene.camera.height) = (96, 72);
    let options = StudyOptions {
        techniques: vec![
            Technique::Uniform,
            Technique::parse("lispsm", None).unwrap(),
        ],
        resolutions: vec![128],
        partitions: vec![1],
        splits: Splits::Uniform,
        filters: vec![Filter::Nearest],
        bias: Bias::DEFAULT,
        format: DepthFormat::F32,
        map_truth: false,
        pictures_at: Some(128),
        optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
        focus: FocusPolicy::Light,
        timing_runs: 1,
    };
    study::run(&scene, &options, |_, _, _| {}).expect("the study")
}

/// A PNG's pixels, top row first.
fn decode(png: &[u8]) -> (u32, u32, Vec<[u8; 3]>) {
    let pixmap = tiny_skia::Pixmap::decode_png(png).expect("a PNG");
    let pixels = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue()]
        })
        .collect();
    (pixmap.width(), pixmap.height(), pixels)
}

/// Where `inner` lies inside `outer` pixel for pixel, if anywhere.
fn find(outer: &(u32, u32, Vec<[u8; 3]>), inner: &(u32, u32, Vec<[u8; 3]>)) -> Option<(u32, u32)> {
    let (ow, oh, o) = outer;
    let (iw, ih, i) = inner;
    let (ow, iw) = (*ow as usize, *iw as usize);
    for y in 0..=(*oh - *ih) as usize {
        for x in 0..=(ow - iw) {
            let matches =
                (0..*ih as usize).all(|row| o[(y + row) * ow + x..][..iw] == i[row * iw..][..iw]);
            if matches {
                return Some((u32::try_from(x).unwrap(), u32::try_from(y).unwrap()));
            }
        }
    }
    None
}

/// Claim: each technique has its four raw pictures (the eye image's size, its top row first)
/// and four annotated ones that hold the raw pixels unchanged inside a larger canvas.
#[test]
fn annotated_pictures_hold_the_raw_ones() {
    let study = tiny_study();
    let files = pictures::files(&study).unwrap();
    assert_eq!(files.len(), 2 * 8);
    for p in &study.pictures {
        for kind in PictureKind::ALL {
            let raw_path = kind.raw_path(p.setting.technique);
            let annotated_path = kind.annotated_path(p.setting.technique);
            let get = |path: &str| {
                let (_, bytes) = files.iter().find(|(name, _)| name == path).unwrap();
                decode(bytes)
            };
            let raw = get(&raw_path);
            assert_eq!((raw.0, raw.1), (study.width, study.height), "{raw_path}");
            let bottom_up: Vec<[u8; 3]> = raw
                .2
                .chunks(study.width as usize)
                .rev()
                .flatten()
                .copied()
                .collect();
            let source = match kind {
                PictureKind::Eye => &p.eye,
                PictureKind::Difference => &p.difference,
                PictureKind::Causes => &p.causes,
                PictureKind::Heatmap => &p.heatmap,
            };
            assert_eq!(&bottom_up, source, "{raw_path}");
            let annotated = get(&annotated_path);
            assert!(
                annotated.0 > raw.0 && annotated.1 > raw.1,
                "{annotated_path}"
            );
            let at = find(&annotated, &raw);
            assert!(at.is_some(), "{annotated_path} does not hold {raw_path}");
        }
    }
    let stems: Vec<&str> = files.iter().map(|(name, _)| name.as_str()).collect();
    assert!(stems.contains(&"images/heatmap-lispsm.png"), "{stems:?}");
    assert!(
        stems.contains(&"pictures/difference-uniform.png"),
        "{stems:?}"
    );
    assert!(
        stems.contains(&"images/difference-causes-uniform.png"),
        "{stems:?}"
    );
}

/// Claim: titles name scene, technique and what is shown; the settings line names resolution,
/// maps, filter, bias, focus and the eye image.
#[test]
fn titles_name_scene_technique_and_settings() {
    let study = tiny_study();
    let setting = &study.pictures[1].setting;
    assert_eq!(
        pictures::title(&study, setting, PictureKind::Heatmap),
        "outdoor — lispsm: texel footprint on screen"
    );
    assert_eq!(
        pictures::settings(&study, setting),
        "128² shadow map, 1 map(s) per light, filter nearest, bias slope:2.0,1e-5, focus light; \
         96×72 eye image"
    );
    let picture = pictures::annotated(&study, &study.pictures[1], PictureKind::Difference).unwrap();
    assert_eq!(picture.legend.len(), 5);
    assert!(picture.colour_bar.is_none());
    let causes = pictures::annotated(&study, &study.pictures[1], PictureKind::Causes).unwrap();
    // Five causes, the two seams apart, then correct lit, correct in shadow, nothing visible.
    assert_eq!(causes.legend.len(), 8);
    for (swatch, start) in causes.legend.iter().zip([
        "acne",
        "peter-panning",
        "seam: in a blend band",
        "seam: at a",
    ]) {
        assert!(swatch.label.starts_with(start), "{:?}", swatch.label);
    }
    assert!(causes.colour_bar.is_none());
    let heat = pictures::annotated(&study, &study.pictures[1], PictureKind::Heatmap).unwrap();
    let bar = heat.colour_bar.expect("a colour bar");
    assert_eq!((bar.low, bar.high), (0.1, 100.0));
    assert_eq!(bar.range, study.pictures[1].footprint_range);
    assert!(
        bar.range
            .is_some_and(|(low, high)| 0.0 < low && low <= high)
    );
}

/// Claim: with one light, the difference image's falsely lit and falsely shadowed pixels are the
/// study's counts, the causes picture's classes are its counts per cause, and each picture's
/// classes cover every pixel.
#[test]
fn the_legend_counts_agree_with_the_measurement() {
    let study = tiny_study();
    for p in &study.pictures {
        let counts = ClassCounts::of(&p.difference);
        let measured = study
            .measurements
            .iter()
            .find(|m| m.setting == p.setting)
            .and_then(|m| m.outcome.as_ref().ok())
            .expect("measured");
        assert_eq!(counts.falsely_lit, measured.errors.falsely_lit);
        assert_eq!(counts.falsely_shadowed, measured.errors.falsely_shadowed);
        let all: u64 = counts.classes().iter().map(|c| c.2).sum();
        assert_eq!(all, u64::from(study.width * study.height));
        assert_eq!(
            counts.background,
            u64::from(study.width * study.height) - study.visible
        );
        let causes = CauseCounts::of(&p.causes);
        assert_eq!(causes.first, measured.causes);
        let all: u64 = causes.classes().iter().map(|c| c.2).sum();
        assert_eq!(all, u64::from(study.width * study.height));
        assert_eq!(
            (causes.correct_lit, causes.correct_shadow, causes.background),
            (counts.correct_lit, counts.correct_shadow, counts.background)
        );
    }
}

/// Claim: every picture file, raw and annotated, is byte-identical on one and on two threads.
#[test]
fn pictures_are_identical_on_any_thread_count() {
    let one = on_threads(1, || pictures::files(&tiny_study()).unwrap());
    let two = on_threads(2, || pictures::files(&tiny_study()).unwrap());
    assert_eq!(one, two);
}
