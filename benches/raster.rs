//! The rasterizer on real meshes, in the views of issue 4 and of the peer harness
//! (`shared/tools/peers/gl_depth_bench.py`): the light pass (orthographic, depth only, 2048² and
//! 4096²) and the eye pass (perspective, 1024×768), clear + draw, f32 depth, depth test less, no
//! culling — on 1 and 2 threads. Setup (loading, allocation) is outside the timing.
//!
//! The Stanford bunny is in data/meshes; the dragon is used when data/meshes/dragon.obj exists
//! (`data/meshes/fetch-dragon.sh` makes it) and reported as absent otherwise. Figures are recorded in
//! docs/benchmarks.md.

use std::hint::black_box;
use std::path::Path;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use shadowlab_raster::{DepthFormat, DepthTarget, RasterOptions, Rasterizer, Triangles};
use shadowlab_scene::benchmark::BenchmarkView;

fn meshes() -> Vec<(&'static str, shadowlab_scene::Mesh)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/meshes");
    let mut out = Vec::new();
    for name in ["bunny", "dragon"] {
        let path = dir.join(format!("{name}.obj"));
        if path.exists() {
            out.push((
                name,
                shadowlab_scene::load_obj(&path).expect("benchmark mesh loads"),
            ));
        } else {
            eprintln!(
                "{} is absent: run data/meshes/fetch-dragon.sh to benchmark it",
                path.display()
            );
        }
    }
    out
}

fn passes(c: &mut Criterion) {
    let mut group = c.benchmark_group("raster");
    group.sample_size(20);
    for (name, mesh) in meshes() {
        let view = BenchmarkView::new(&mesh.bounds(), 1024, 768);
        let triangles = Triangles::new(mesh.positions(), mesh.triangles());
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            for (pass, width, height, m) in [
                ("light-2048", 2048, 2048, view.light),
                ("light-4096", 4096, 4096, view.light),
                ("eye-1024x768", 1024, 768, view.eye),
            ] {
                let mut target = DepthTarget::new(width, height, DepthFormat::F32).expect("target");
                let mut raster = Rasterizer::new(RasterOptions::default());
                group.throughput(Throughput::Elements(triangles.triangles().len() as u64));
                let id = BenchmarkId::new(format!("{name}/{pass}"), format!("{threads}-threads"));
                group.bench_function(id, |b| {
                    b.iter(|| {
                        pool.install(|| {
                            target.clear(1.0);
                            raster
                                .draw_depth(&mut target, black_box(triangles), &m)
                                .expect("draw")
                        })
                    });
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, passes);
criterion_main!(benches);
