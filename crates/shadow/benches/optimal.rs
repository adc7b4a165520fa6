//! Criterion benchmarks of the scene-optimized map (CG06 Algorithm 1), per light and frame, on the
//! built-in scenes of the paper's kind (`outdoor`, `dueling-frusta`):
//! - `readback`: the 70 × 70 eye pass (step 1), shared by every light and partition of a frame;
//! - `problem`: the initial uniform-limited map, its lookups and the samples (steps 2–3);
//! - `solve`: the descent (step 4) and the depth row — the optimizer proper, which the issue bounds
//!   by 1 ms per light per frame (the paper: 6.96 ms for four lights on 2006 hardware);
//! - `plan`: steps 2–4 together, what a frame pays per light after the readback.
//!
//! Figures are recorded with the machine and date in docs/benchmarks.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::optimal::{self, OptimalOptions, Problem, Readback};
use shadowlab_shadow::{FocusPolicy, scene_input};

fn optimizer(c: &mut Criterion) {
    let options = OptimalOptions::default();
    let mut group = c.benchmark_group("optimal");
    for name in ["outdoor", "dueling-frusta"] {
        let scene = builtin_scene(name).expect("a built-in scene");
        let input = scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light)
            .expect("the scene's plan input");
        group.bench_function(format!("readback/{name}"), |b| {
            b.iter(|| Readback::new(black_box(&scene), options.readback).expect("readback"));
        });
        let readback = Readback::new(&scene, options.readback).expect("readback");
        group.bench_function(format!("problem/{name}"), |b| {
            b.iter(|| {
                Problem::new(&scene, black_box(&input), &readback, &options).expect("samples")
            });
        });
        let problem = Problem::new(&scene, &input, &readback, &options).expect("samples");
        group.bench_function(format!("solve/{name}"), |b| {
            b.iter(|| black_box(&problem).solve(&options).expect("optimized"));
        });
        group.bench_function(format!("plan/{name}"), |b| {
            b.iter(|| optimal::plan(&scene, black_box(&input), &readback, &options).expect("plan"));
        });
    }
    group.finish();
}

criterion_group!(benches, optimizer);
criterion_main!(benches);
