//! The same draw gives the same bytes on 1, 2 and 8 threads, and on every run.

use glam::{DMat4, DVec3};
use shadowlab_raster::{
    CullMode, DepthFormat, DepthPairTarget, DepthTarget, EyeTarget, RasterOptions, Rasterizer,
    TargetSize, Triangles,
};

use crate::support::{Rng, fnv1a};

/// A soup of 30 000 random triangles in perspective: overlapping, of every size, some crossing the
/// near or far plane, some behind the eye or beyond the far plane, so every stage (clipping, binning across many tiles and
/// chunks, the depth test between overlapping triangles) takes part. Fixed seed.
fn soup() -> (Vec<DVec3>, Vec<[u32; 3]>, DMat4) {
    let mut rng = Rng::new(0x00de_7e41);
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 0..30_000u32 {
        let centre = DVec3::new(
            rng.unit() * 20.0 - 10.0,
            rng.unit() * 20.0 - 10.0,
            -rng.unit() * 50.0 + 6.0,
        );
        let size = if t % 100 == 0 {
            8.0
        } else {
            0.05 + rng.unit() * 0.6
        };
        for _ in 0..3 {
            positions.push(
                centre + DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * size,
            );
        }
        triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
    }
    let view = glam::dcamera::rh::view::look_at_mat4(
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(0.0, 0.0, -10.0),
        DVec3::Y,
    );
    let projection = glam::dcamera::rh::proj::opengl::perspective(1.2, 1.5, 0.5, 40.0);
    (positions, triangles, projection * view)
}

/// Everything a draw produces, hashed.
fn render_all(positions: &[DVec3], triangles: &[[u32; 3]], m: &DMat4) -> Vec<u64> {
    let mesh = Triangles::new(positions, triangles);
    let (w, h) = (300u32, 200u32);
    let mut hashes = Vec::new();
    for format in DepthFormat::ALL {
        let mut depth = DepthTarget::new(w, h, format).unwrap();
        let stats = Rasterizer::new(RasterOptions::default())
            .draw_depth(&mut depth, mesh, m)
            .unwrap();
        hashes.push(fnv1a(depth.keys().iter().flat_map(|k| k.to_le_bytes())));
        hashes.push(stats.fragments);
    }
    let mut pair = DepthPairTarget::new(w, h, DepthFormat::F32).unwrap();
    Rasterizer::new(RasterOptions {
        cull: CullMode::Back,
        ..RasterOptions::default()
    })
    .draw_depth_pair(&mut pair, mesh, m)
    .unwrap();
    hashes.push(fnv1a(
        pair.nearest()
            .iter()
            .chain(&pair.second())
            .flat_map(|z| z.to_le_bytes()),
    ));
    let mut eye = EyeTarget::new(w, h, DepthFormat::Unorm24).unwrap();
    Rasterizer::new(RasterOptions::default())
        .draw_eye(&mut eye, mesh, m)
        .unwrap();
    hashes.push(fnv1a(eye.triangles().iter().flat_map(|t| t.to_le_bytes())));
    let normals = vec![DVec3::Z; positions.len()];
    let image = eye.resolve(mesh, &normals, m).unwrap();
    hashes.push(fnv1a(
        image
            .position
            .iter()
            .flat_map(|p| p.to_array())
            .flat_map(f64::to_le_bytes),
    ));
    let mut sequence = Vec::new();
    Rasterizer::new(RasterOptions::default())
        .for_each_fragment(TargetSize::new(w, h).unwrap(), mesh, m, |f| {
            sequence.extend(f.x.to_le_bytes());
            sequence.extend(f.y.to_le_bytes());
            sequence.extend(f.triangle.to_le_bytes());
            sequence.extend(f.depth.to_le_bytes());
        })
        .unwrap();
    hashes.push(fnv1a(sequence));
    hashes
}

#[test]
fn identical_bytes_on_1_2_and_8_threads_and_across_runs() {
    let (positions, triangles, m) = soup();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| render_all(&positions, &triangles, &m))
    };
    let one = run(1);
    assert_eq!(one, run(2), "2 threads");
    assert_eq!(one, run(8), "8 threads");
    assert_eq!(one, run(8), "a second run");
    // The soup did exercise clipping.
    let mut target = DepthTarget::new(300, 200, DepthFormat::F32).unwrap();
    let stats = Rasterizer::new(RasterOptions::default())
        .draw_depth(&mut target, Triangles::new(&positions, &triangles), &m)
        .unwrap();
    assert!(
        stats.clipped > 100 && stats.outside > 1000 && stats.fragments > 10_000,
        "{stats:?}"
    );
    assert_eq!(
        stats.triangles,
        stats.drawn + stats.degenerate + stats.culled + stats.empty + stats.outside + stats.clipped
    );
}
