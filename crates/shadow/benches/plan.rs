//! Criterion benchmark of planning alone — `plan_frame`, each light's partitions and windows — for
//! the planners that read the eye pass: sample distribution shadow maps (Lauritzen et al. 2011),
//! whose windows are fitted to the visible samples (`sdsm::fit`), with one map and with four
//! partitions, logarithmic and k-means splits. The built-in `outdoor` scene (1024 × 768, about
//! 403 000 visible samples), the eye pass made once beforehand; 2048² maps (the side does not
//! enter SDSM's plan). Deterministic; figures in docs/benchmarks.md with the machine and date.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::{
    Bias, Filter, FrameOptions, Lookup, PlanOptions, Technique, eye_pass, plan_frame,
};

fn plan(c: &mut Criterion) {
    let scene = builtin_scene("outdoor").expect("the built-in outdoor scene");
    let (eye, nearest_visible) = eye_pass(&scene).expect("the eye pass");
    let mut group = c.benchmark_group("plan");
    for (name, technique, partitions) in [
        ("sdsm/1", "sdsm", 1),
        ("sdsm/4", "sdsm", 4),
        ("sdsm-kmeans/4", "sdsm:kmeans", 4),
    ] {
        let (key, parameter) = technique
            .split_once(':')
            .map_or((technique, None), |(key, parameter)| (key, Some(parameter)));
        let options = FrameOptions {
            plan: PlanOptions {
                partitions,
                ..PlanOptions::new(Technique::parse(key, parameter).expect("a technique"))
            },
            resolution: 2048,
            format: DepthFormat::F32,
            lookup: Lookup::new(Bias::DEFAULT, Filter::Nearest),
            snap_texels: 0,
        };
        group.bench_function(format!("outdoor/{name}"), |b| {
            b.iter(|| {
                plan_frame(&scene, black_box(&options), nearest_visible, Some(&eye))
                    .expect("the plan")
            });
        });
    }
    group.finish();
}

criterion_group!(benches, plan);
criterion_main!(benches);
