//! Criterion benchmarks of the BVH: build time, and rays per second for closest-hit and any-hit
//! queries with coherent and random rays: the batch queries on 1 and 2 threads, and one ray at a
//! time (`closest_hit`, `occluded` in a loop) on 1 thread; and the grids swept
//! (`closest-grid`: [`Bvh::closest_hits_grid`]) on 1 and 2 threads.
//!
//! Meshes: the small bunny (`data/meshes/bunny-small.obj`, 3 674 triangles: the one whose 2048²
//! grid is swept, at 1 141 rays per triangle), the Stanford bunny (`data/meshes/bunny.obj`, 69 666
//! triangles) and, when present, the dragon (`data/meshes/dragon.obj`, 871 414 triangles; made by
//! `data/meshes/fetch-dragon.sh`, reported as absent otherwise). They are read by the small OBJ
//! reader below (`v` and `f` only), so the benchmark depends on nothing but this crate.
//!
//! Rays (fixed by a SplitMix64 seed):
//! - *coherent*: a 256 × 256 orthographic grid over the mesh's bounding sphere, all parallel to
//!   one oblique direction, as a directional light's shadow map casts them (65 536 rays);
//! - *grid2048*: the same at 2048 × 2048, a full-size shadow map (4 194 304 rays, row by row);
//! - *random*: from uniform points on a sphere of twice the bounding radius toward uniform points
//!   in the bounding box: every ray starts outside and most cross the mesh (65 536 rays).
//!
//! Run with `cargo bench -p shadowlab-trace`. The side-by-side run against Intel Embree on larger
//! ray sets (the same random rays among them) is `benches/embree.sh`; docs/benchmarks.md ("Ray
//! casting against Intel Embree 4.4") records it with the machine and date.

use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use rayon::iter::ParallelIterator;
use shadowlab_trace::{Bvh, Ray};

/// A mesh read from an OBJ file: positions and index triples.
struct Mesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

/// Reads `v x y z` and `f i j k …` statements (fans for polygons; `i/t/n` forms and negative
/// indices accepted); everything else is skipped. Panics with the line on malformed input: the
/// benchmark meshes are known to be well formed.
fn read_obj(path: &Path) -> Mesh {
    let text = std::fs::read_to_string(path).expect("benchmark mesh is readable");
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words
                    .take(3)
                    .map(|w| w.parse().expect("a coordinate"))
                    .collect();
                assert_eq!(
                    c.len(),
                    3,
                    "line {}: a vertex needs 3 coordinates",
                    number + 1
                );
                positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let corners: Vec<u32> = words
                    .map(|w| {
                        let index: i64 = w
                            .split('/')
                            .next()
                            .and_then(|i| i.parse().ok())
                            .expect("a vertex index");
                        let count = i64::try_from(positions.len()).expect("vertex count");
                        let index = if index < 0 { count + index } else { index - 1 };
                        u32::try_from(index).expect("index in range")
                    })
                    .collect();
                for k in 1..corners.len().saturating_sub(1) {
                    triangles.push([corners[0], corners[k], corners[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Mesh {
        positions,
        triangles,
    }
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    let dir: PathBuf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/meshes");
    let mut out = Vec::new();
    for name in ["bunny-small", "bunny", "dragon"] {
        let path = dir.join(format!("{name}.obj"));
        if path.exists() {
            out.push((name, read_obj(&path)));
        } else {
            eprintln!(
                "{} is absent: run data/meshes/fetch-dragon.sh to benchmark it",
                path.display()
            );
        }
    }
    out
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, seedable generator for benchmark inputs.
struct SplitMix64(u64);

impl SplitMix64 {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        #[expect(
            clippy::cast_precision_loss,
            reason = "53 random bits fit an f64 exactly"
        )]
        let unit = (z >> 11) as f64 / (1_u64 << 53) as f64;
        unit
    }

    /// A uniform unit vector (Marsaglia's method via the cylinder projection).
    fn direction(&mut self) -> DVec3 {
        let z = 2.0 * self.unit() - 1.0;
        let a = std::f64::consts::TAU * self.unit();
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * a.cos(), r * a.sin(), z)
    }
}

/// Side of the coherent grid, and the number of random rays (its square).
const GRID: usize = 256;
/// Side of the shadow-map-sized grid.
const MAP_GRID: usize = 2048;

/// A `side × side` orthographic grid of parallel rays, row by row.
fn grid_rays(lo: DVec3, hi: DVec3, side: usize) -> Vec<Ray> {
    let center = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let direction = DVec3::new(-0.3, -1.0, -0.45).normalize();
    let across = direction.cross(DVec3::Z).normalize();
    let up = across.cross(direction);
    let mut rays = Vec::with_capacity(side * side);
    for j in 0..side {
        for i in 0..side {
            #[expect(clippy::cast_precision_loss, reason = "grid indices are small")]
            let (x, y) = (
                (i as f64 + 0.5) / side as f64 * 2.0 - 1.0,
                (j as f64 + 0.5) / side as f64 * 2.0 - 1.0,
            );
            let origin = center - direction * (2.0 * radius) + (across * x + up * y) * radius;
            rays.push(Ray::new(origin, direction).expect("valid ray"));
        }
    }
    rays
}

/// The random batch (seed 0x7ACE_0001): `GRID²` rays.
fn random_rays(lo: DVec3, hi: DVec3) -> Vec<Ray> {
    let mut rng = SplitMix64(0x7ACE_0001);
    let center = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    (0..GRID * GRID)
        .map(|_| {
            let origin = center + rng.direction() * (2.0 * radius);
            let target = lo + (hi - lo) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
            Ray::new(origin, target - origin).expect("valid ray")
        })
        .collect()
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    group.sample_size(10);
    for (name, mesh) in meshes() {
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            group.throughput(Throughput::Elements(mesh.triangles.len() as u64));
            group.bench_function(BenchmarkId::new(name, format!("{threads}-threads")), |b| {
                b.iter(|| {
                    pool.install(|| {
                        Bvh::new(black_box(&mesh.positions), black_box(&mesh.triangles))
                            .expect("valid mesh")
                    })
                });
            });
        }
    }
    group.finish();
}

fn queries(c: &mut Criterion) {
    let mut group = c.benchmark_group("rays");
    group.sample_size(10);
    for (name, mesh) in meshes() {
        let bvh = Bvh::new(&mesh.positions, &mesh.triangles).expect("valid mesh");
        let (lo, hi) = bvh.bounds().expect("triangles");
        eprintln!("{name}: {:?}", bvh.stats());
        for (kind, rays, row_len) in [
            ("coherent", grid_rays(lo, hi, GRID), Some(GRID)),
            ("grid2048", grid_rays(lo, hi, MAP_GRID), Some(MAP_GRID)),
            ("random", random_rays(lo, hi), None),
        ] {
            let hits = bvh
                .closest_hits(&rays, 0.0, f64::INFINITY)
                .iter()
                .filter(|h| h.is_some())
                .count();
            eprintln!("{name}/{kind}: {hits} of {} rays hit", rays.len());
            group.throughput(Throughput::Elements(rays.len() as u64));
            let id = |query: &str, threads: usize| {
                BenchmarkId::new(
                    format!("{name}/{kind}/{query}"),
                    format!("{threads}-threads"),
                )
            };
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("thread pool");
                group.bench_function(id("closest", threads), |b| {
                    b.iter(|| {
                        pool.install(|| bvh.closest_hits(black_box(&rays), 0.0, f64::INFINITY))
                    });
                });
                group.bench_function(id("occluded", threads), |b| {
                    b.iter(|| {
                        pool.install(|| bvh.occluded_all(black_box(&rays), 0.0, f64::INFINITY))
                    });
                });
                // The grids by the sweep (`Bvh::closest_hits_grid`), answers into a new buffer
                // filled by the workers, as `closest_hits` makes its own.
                if let Some(row_len) = row_len {
                    group.bench_function(id("closest-grid", threads), |b| {
                        b.iter(|| {
                            pool.install(|| {
                                let mut out: Vec<_> =
                                    rayon::iter::repeat_n(None, rays.len()).collect();
                                bvh.closest_hits_grid(
                                    row_len,
                                    |j, row| {
                                        row.copy_from_slice(
                                            &black_box(&rays)[j * row_len..(j + 1) * row_len],
                                        );
                                    },
                                    0.0,
                                    f64::INFINITY,
                                    &mut out,
                                    |_, hits, out| out.copy_from_slice(hits),
                                )
                                .expect("valid rays");
                                out
                            })
                        });
                    });
                }
            }
            group.bench_function(id("closest-single", 1), |b| {
                b.iter(|| {
                    black_box(&rays)
                        .iter()
                        .filter(|ray| bvh.closest_hit(ray, 0.0, f64::INFINITY).is_some())
                        .count()
                });
            });
            group.bench_function(id("occluded-single", 1), |b| {
                b.iter(|| {
                    black_box(&rays)
                        .iter()
                        .filter(|ray| bvh.occluded(ray, 0.0, f64::INFINITY))
                        .count()
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, build, queries);
criterion_main!(benches);
