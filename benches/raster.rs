//! The rasterizer on real meshes, in the views of issue 4 and of the peer harness
//! (`shared/tools/peers/gl_depth_bench.py`): the light pass (orthographic, depth only, 2048² and
//! 4096²) and the eye pass (perspective, 1024×768), clear + draw, f32 depth, depth test less, no
//! culling — on 1 and 2 threads. Setup (loading, allocation) is outside the timing.
//!
//! `image_out`: the PNG writers on one thread — a 1024×768 colour picture of flat bands and edges,
//! about as compressible as the pictures `analyze` writes (four per technique), and a 2048² 16-bit
//! depth preview of a smooth ramp.
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

fn image_out(c: &mut Criterion) {
    use shadowlab_raster::image_out::{depth_png16, rgb_png};
    let mut group = c.benchmark_group("image_out");
    group.sample_size(20);
    let (width, height) = (1024u32, 768u32);
    // Bands of a few colours with a diagonal edge: about as compressible as the pictures.
    let palette = [
        [40u8, 40, 48],
        [200, 190, 170],
        [90, 140, 60],
        [230, 60, 40],
    ];
    let picture: Vec<[u8; 3]> = (0..height)
        .flat_map(|y| {
            (0..width).map(move |x| palette[((x / 64 + y / 48 + (x + y) / 300) % 4) as usize])
        })
        .collect();
    group.throughput(Throughput::Elements(u64::from(width * height)));
    group.bench_function("rgb_png/1024x768", |b| {
        b.iter(|| rgb_png(black_box(&picture), width, height).expect("encode"));
    });
    let side = 2048u32;
    let depths: Vec<f64> = (0..side * side)
        .map(|k| f64::from(k % side + k / side) / f64::from(2 * side))
        .collect();
    group.throughput(Throughput::Elements(u64::from(side * side)));
    group.bench_function("depth_png16/2048", |b| {
        b.iter(|| depth_png16(black_box(&depths), side, side).expect("encode"));
    });
    group.finish();
}

criterion_group!(benches, passes, image_out);
criterion_main!(benches);
