//! Criterion benchmark of the exact truth: one shadow ray per visible pixel and light of the
//! built-in `outdoor` scene (the LiSPSM paper's set-up) at its 1024 × 768, reported in rays per
//! second, on 1 and 2 threads; and the hierarchy's build, which a study pays once per scene.
//!
//! The eye pass is made once, outside the measurement. Everything is deterministic; there is no
//! random input.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use shadowlab_analysis::truth::{exact_truth, scene_bvh};
use shadowlab_raster::NO_TRIANGLE;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::eye_pass;

fn truth(c: &mut Criterion) {
    let scene = builtin_scene("outdoor").expect("the built-in outdoor scene");
    let (eye, _) = eye_pass(&scene).expect("the eye pass");
    let bvh = scene_bvh(&scene).expect("the scene's hierarchy");
    let visible = eye.triangle.iter().filter(|t| **t != NO_TRIANGLE).count();
    let rays = u64::try_from(visible * scene.lights.len()).expect("a ray count");

    let mut group = c.benchmark_group("exact_truth");
    group.sample_size(10);
    group.throughput(Throughput::Elements(rays));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        group.bench_with_input(
            BenchmarkId::new("outdoor_1024x768", format!("{threads}_threads")),
            &threads,
            |b, _| {
                b.iter(|| {
                    pool.install(|| exact_truth(black_box(&scene), &eye, &bvh).expect("truth"))
                });
            },
        );
    }
    group.finish();

    let mut group = c.benchmark_group("scene_bvh");
    group.sample_size(10);
    group.throughput(Throughput::Elements(scene.mesh.triangle_count() as u64));
    group.bench_function("outdoor", |b| {
        b.iter(|| scene_bvh(black_box(&scene)).expect("the scene's hierarchy"));
    });
    group.finish();
}

criterion_group!(benches, truth);
criterion_main!(benches);
