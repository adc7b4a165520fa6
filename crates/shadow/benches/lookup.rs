//! Criterion benchmark of the lookup path: every visible pixel of a built-in scene (`outdoor`,
//! 1024 × 768; `room-point`) looked up in its light's maps — the serving map chosen (`served`:
//! depth or containment, blend band, fade), the bias applied, the filter read. Timed is
//! everything `render_shadows` does but plan and render the maps: its whole time less its own
//! planning and shadow-pass phases (`iter_custom`), the eye pass made once beforehand. (Its
//! lookup phase alone, `Timings::lookup`, would not do: before the serving rule, each pixel's
//! eye depth was computed outside every phase.)
//!
//! Cases, all with shadowlab's default bias: on `outdoor` at 2048² per map, LiSPSM with one
//! map, nearest and 3×3 PCF; LiSPSM with four practical partitions (λ = 0.5), nearest; and
//! Bevy's preset (four blended cascades read with its normal offset), where the technique
//! exists; on `room-point` (a point light) at 512², the cube's six faces and the dual
//! paraboloid's two hemispheres, nearest. The file compiles against older commits of the crate
//! as well, so the same cases measure the lookup before and after a change
//! (docs/benchmarks.md). Everything is deterministic.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::{
    Bias, Filter, FrameOptions, Lookup, PlanOptions, Splits, Technique, eye_pass, render_shadows,
};

/// The side of every map of `outdoor`.
const RESOLUTION: u32 = 2048;
/// The side of every map of `room-point`: smaller, so that its cast paraboloid hemispheres, made
/// for every timed lookup but not timed, keep the benchmark short.
const POINT_RESOLUTION: u32 = 512;

/// One case: its name, technique, partitions and filter.
type Case = (&'static str, Technique, usize, Filter);

fn lookup(c: &mut Criterion) {
    let lispsm = Technique::parse("lispsm", None).expect("lispsm");
    let mut outdoor: Vec<Case> = vec![
        ("lispsm/1/nearest", lispsm, 1, Filter::Nearest),
        ("lispsm/1/pcf3", lispsm, 1, Filter::Pcf { size: 3 }),
        ("lispsm/4/nearest", lispsm, 4, Filter::Nearest),
    ];
    // Older commits have no presets: the case is left out there.
    if let Ok(bevy) = Technique::parse("bevy", None) {
        outdoor.push(("bevy/nearest", bevy, 4, Filter::Nearest));
    }
    // A point light's maps: six cube faces, two paraboloid hemispheres.
    let room_point: Vec<Case> = ["cube", "dual-paraboloid"]
        .into_iter()
        .filter_map(|key| Some((key, Technique::parse(key, None).ok()?, 1, Filter::Nearest)))
        .collect();
    let mut group = c.benchmark_group("lookup");
    group.sample_size(20);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(4));
    for (scene_name, resolution, cases) in [
        ("outdoor", RESOLUTION, outdoor),
        ("room-point", POINT_RESOLUTION, room_point),
    ] {
        let scene = builtin_scene(scene_name).expect("a built-in scene");
        let (eye, nearest_visible) = eye_pass(&scene).expect("the eye pass");
        for (name, technique, partitions, filter) in cases {
            let options = FrameOptions {
                plan: PlanOptions {
                    partitions,
                    splits: Splits::Practical { weight: 0.5 },
                    ..PlanOptions::new(technique)
                },
                resolution,
                format: DepthFormat::F32,
                lookup: Lookup::new(Bias::DEFAULT, filter),
                snap_texels: 0,
            };
            group.bench_function(format!("{scene_name}/{name}"), |b| {
                b.iter_custom(|iterations| {
                    (0..iterations)
                        .map(|_| {
                            let start = Instant::now();
                            let shadows =
                                render_shadows(&scene, &options, &eye, nearest_visible, None)
                                    .expect("the shadows");
                            let whole = start.elapsed();
                            let timings = shadows.timings;
                            whole.saturating_sub(timings.planning + timings.shadow_pass)
                        })
                        .sum()
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, lookup);
criterion_main!(benches);
