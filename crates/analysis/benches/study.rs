//! Criterion benchmark of a whole study: the default `shadowlab analyze` on the built-in `outdoor`
//! scene (1024 × 768) — eye pass, BVH, exact truth, then every technique (uniform,
//! uniform_limited, psm, lispsm, lispsm/minimax, logarithmic, optimal) at 750², 1000², …, 2000²,
//! each rendered, looked up and measured (misclassification, per-pixel footprints) — without the
//! pictures and the writing of files. The issue bounds it by 10 s on 2 cores.
//!
//! Also the study's cheapest unit, one combination (lispsm at 2000²) on a prepared eye pass, to
//! separate the fixed cost from the per-combination one; and the same unit for a point light's
//! maps on `room-point` (the cube map, six rasterized faces with their near planes searched over
//! the scene's triangles; the dual-paraboloid map, two hemispheres cast one ray per texel), at
//! 2000². Everything is deterministic.
//!
//! And the logarithmic map's shadows at 2000² (`study::render`: planning, 4 M texel rays cast as
//! a grid, the eye pass's lookups). And the measurement's own phases for that combination, which every
//! combination of a study pays once: the per-pixel texel footprints (`study::frame_footprints`; also through the
//! logarithmic map at 2000², whose derivative is its own closed form), and their statistics
//! (`FrameFootprints::stats` of the total, perspective and projection parts, as `study::outcome`
//! takes them).
//!
//! Figures are recorded with the machine and date in docs/benchmarks.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use shadowlab_analysis::study::{self, EyePass, Setting, StudyOptions};
use shadowlab_analysis::truth::{exact_truth, scene_bvh};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::{Scene, builtin_scene};
use shadowlab_shadow::{Bias, Filter, LightSource, Splits, Technique, WarpChoice};

/// The default techniques for a directional light: every technique key but those of point lights,
/// and LiSPSM's minimax rule.
fn default_options() -> StudyOptions {
    let directional = LightSource::directional(DVec3::Y).expect("a unit vector");
    StudyOptions {
        techniques: Technique::KEYS
            .iter()
            .map(|key| Technique::parse(key, None).expect("a known key"))
            .filter(|technique| technique.check_light(&directional).is_ok())
            .chain([Technique::parse("lispsm", Some("minimax")).expect("a known rule")])
            .collect(),
        resolutions: vec![750, 1000, 1250, 1500, 1750, 2000],
        partitions: vec![1],
        splits: Splits::Uniform,
        filters: vec![Filter::Nearest],
        bias: Bias::DEFAULT,
        format: DepthFormat::F32,
        map_truth: false,
        pictures_at: None,
        optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
        focus: shadowlab_shadow::FocusPolicy::Light,
        // The benchmark times the whole study; one run per combination, as a user's quick run.
        timing_runs: 1,
    }
}

fn whole_study(c: &mut Criterion) {
    let scene = builtin_scene("outdoor").expect("the built-in outdoor scene");
    let options = default_options();
    let mut group = c.benchmark_group("study");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(60));
    group.bench_function("outdoor/default", |b| {
        b.iter(|| study::run(black_box(&scene), &options, |_, _, _| {}).expect("the study"));
    });

    group.measurement_time(Duration::from_secs(10));
    one_combination(
        &mut group,
        &scene,
        &options,
        Technique::Lispsm(WarpChoice::PAPER),
        "outdoor/one-combination",
    );
    let room = builtin_scene("room-point").expect("the built-in room-point scene");
    for (technique, name) in [
        (Technique::Cube, "room-point/cube-2000"),
        (Technique::DualParaboloid, "room-point/dual-paraboloid-2000"),
    ] {
        one_combination(&mut group, &room, &options, technique, name);
    }
    footprint_phases(&mut group, &scene, &options);
    group.finish();
}

/// The footprints of lispsm at 2000² on `scene`'s eye pass, and their three statistics; the
/// logarithmic map at the same size — its shadows (one ray per texel, swept; then the lookups)
/// and its footprints, differentiated in closed form.
fn footprint_phases(
    group: &mut BenchmarkGroup<'_, WallTime>,
    scene: &Scene,
    options: &StudyOptions,
) {
    let eye = EyePass::new(scene).expect("the eye pass");
    let bvh = scene_bvh(scene).expect("the hierarchy");
    let setting = |technique| Setting {
        technique,
        resolution: 2000,
        partitions: 1,
        filter: Filter::Nearest,
    };
    let logarithmic = setting(Technique::parse("logarithmic", None).expect("a known key"));
    group.bench_function("outdoor/logarithmic-2000", |b| {
        b.iter(|| {
            study::render(scene, options, black_box(&logarithmic), &eye, &bvh).expect("render")
        });
    });
    let shadows = study::render(scene, options, &logarithmic, &eye, &bvh).expect("render");
    group.bench_function("outdoor/footprints-logarithmic", |b| {
        b.iter(|| study::frame_footprints(scene, &eye.image, black_box(&shadows)));
    });
    let lispsm = setting(Technique::Lispsm(WarpChoice::PAPER));
    let shadows = study::render(scene, options, &lispsm, &eye, &bvh).expect("render");
    group.bench_function("outdoor/footprints", |b| {
        b.iter(|| study::frame_footprints(scene, &eye.image, black_box(&shadows)));
    });
    let footprints = study::frame_footprints(scene, &eye.image, &shadows);
    group.bench_function("outdoor/footprint-stats", |b| {
        b.iter(|| black_box(&footprints).stats());
    });
}

/// One combination of `technique` at 2000², nearest lookups, on `scene`'s prepared eye pass:
/// planned, rendered, looked up and measured.
fn one_combination(
    group: &mut BenchmarkGroup<'_, WallTime>,
    scene: &Scene,
    options: &StudyOptions,
    technique: Technique,
    name: &str,
) {
    let eye = EyePass::new(scene).expect("the eye pass");
    let bvh = scene_bvh(scene).expect("the hierarchy");
    let truth = exact_truth(scene, &eye.image, &bvh).expect("the truth");
    let setting = Setting {
        technique,
        resolution: 2000,
        partitions: 1,
        filter: Filter::Nearest,
    };
    group.bench_function(name, |b| {
        b.iter(|| {
            let shadows = study::render(scene, options, &setting, &eye, &bvh).expect("render");
            study::measure(scene, &truth, &eye.image, &shadows, setting.filter, &bvh)
                .expect("the measurement")
        });
    });
}

criterion_group!(benches, whole_study);
criterion_main!(benches);
