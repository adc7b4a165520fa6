//! shadowlab's side of the ray-casting comparison with Intel Embree (`benches/embree.sh`; Embree's
//! side is `benches/embree_bench.cpp`).
//!
//! Two steps, so that both programs read the very same numbers from the same files:
//!
//! * `ray_bench write MESH.obj DIR` reads the mesh (`shadowlab_scene::load_obj`), rounds its
//!   positions to f32, makes three ray sets with origins and directions rounded to f32, and writes
//!   them to `DIR` (formats below). Nothing is timed.
//! * `ray_bench time DIR [--threads 1,2] [--runs R] [--warmup W] [--hits]` reads them back (f32
//!   widened to f64, exactly), and per thread count, in a rayon pool of that size, times
//!   `Bvh::new` and the batch queries `closest_hits` and `occluded_all` over each ray set (mode
//!   `batch`), and the grid set's closest hits again through `closest_hits_grid` (mode `rows`: row
//!   by row, as the logarithmic shadow map casts them, its answers checked against the batch's):
//!   `W` untimed runs, then `R` timed ones. It prints one JSON object (every timed run, in ms);
//!   with `--hits` it writes the answers per ray for the agreement check.
//!
//! # Ray sets
//! Built from the mesh's bounds (centre `c`, radius `R` = half the diagonal) and the benchmark
//! views of `shadowlab_scene::benchmark::BenchmarkView`; every ray runs over `t ∈ (0, t_max)`, a
//! bound that covers the whole mesh:
//! * `camera`: one ray per pixel centre of the eye view, 1024×768 (perspective, 45°), from the
//!   near plane to the far plane (`t_max = 1`: the far plane lies at `4R` from the eye, the mesh
//!   within `3.2R`). Coherent.
//! * `random`: 2²⁰ rays, as `crates/trace/benches/trace.rs` makes them (SplitMix64, seed
//!   `0x7ACE_0001`, so its first 65 536 rays are that bench's): from uniform points on the sphere
//!   of radius `2R` about `c` toward uniform points in the bounding box. `|direction| ≥ R` and the
//!   mesh lies within `3R` of every origin, so `t_max = 4` covers it. Incoherent.
//! * `grid`: 2048² parallel rays, one per texel centre of the light view (orthographic, box `±R`)
//!   from its near plane to its far plane, as the logarithmic shadow map casts its texel rays for a
//!   directional light (`t_max = 1`: the slab between the planes holds the bounding sphere).
//!
//! The pixel sets are ordered in 4×4 tiles (rows of tiles from the bottom, row-major inside a
//! tile), so that 16 consecutive rays — one Embree packet — are a tile; shadowlab's batches take
//! the same rays in the same order.
//!
//! # Files (little-endian)
//! * `mesh.bin`: `u32` vertex count `V`, `u32` triangle count `T`, `V × 3 f32` positions,
//!   `T × 3 u32` indices.
//! * `rays-SET.bin`: `u32` count `N`, `f32 t_max`, `N × 6 f32` (origin, direction).
//! * with `--hits`, `shadowlab-SET.closest` (`N i32`: the closest hit's triangle index, −1 for a
//!   miss) and `shadowlab-SET.anyhit` (`N u8`: 1 if occluded); the answers do not depend on the
//!   thread count.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail, ensure};
use clap::{Parser, Subcommand};
use glam::{DMat4, DVec3, DVec4, Vec3};
use serde_json::json;
use shadowlab_scene::benchmark::BenchmarkView;
use shadowlab_trace::{Bvh, Hit, Ray};

/// The ray sets, in the order they are written, read, timed and reported.
const SETS: [&str; 3] = ["camera", "random", "grid"];
/// The eye view's size in pixels (as the raster benchmark's eye pass).
const EYE: (u32, u32) = (1024, 768);
/// The light view's side in texels (as the raster benchmark's light pass).
const LIGHT: u32 = 2048;
/// Rays of the random set.
const RANDOM_RAYS: usize = 1 << 20;
/// The random set's seed, the one `crates/trace/benches/trace.rs` uses.
const RANDOM_SEED: u64 = 0x7ACE_0001;
/// The side of the square tiles the pixel sets are ordered in: a tile is one 16-wide packet.
const TILE: u32 = 4;

#[derive(Parser)]
#[command(about = "shadowlab's side of benches/embree.sh: writes the inputs, times the queries")]
struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Writes the mesh (f32) and the three ray sets (f32) to DIR.
    Write {
        /// The OBJ mesh.
        mesh: PathBuf,
        /// Where `mesh.bin` and `rays-SET.bin` go (created if missing).
        dir: PathBuf,
    },
    /// Times the build and the queries on the inputs in DIR; prints JSON.
    Time {
        /// The folder `write` filled.
        dir: PathBuf,
        /// Rayon pool sizes, comma-separated.
        #[arg(long, value_delimiter = ',', default_value = "1,2")]
        threads: Vec<usize>,
        /// Timed runs of each measurement.
        #[arg(long, default_value_t = 3)]
        runs: usize,
        /// Untimed runs before them.
        #[arg(long, default_value_t = 1)]
        warmup: usize,
        /// Also writes the answers per ray (`shadowlab-SET.closest`, `.anyhit`) to DIR.
        #[arg(long)]
        hits: bool,
    },
}

fn main() -> Result<()> {
    match Args::parse().command {
        Command::Write { mesh, dir } => write_inputs(&mesh, &dir),
        Command::Time {
            dir,
            threads,
            runs,
            warmup,
            hits,
        } => time(&dir, &threads, runs, warmup, hits),
    }
}

fn write_inputs(mesh_path: &Path, dir: &Path) -> Result<()> {
    let mesh = shadowlab_scene::load_obj(mesh_path)
        .with_context(|| format!("reading {}", mesh_path.display()))?;
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut out = Writer::create(&dir.join("mesh.bin"))?;
    out.u32(len_u32(mesh.positions().len())?)?;
    out.u32(len_u32(mesh.triangles().len())?)?;
    for &p in mesh.positions() {
        out.vec3(p.as_vec3())?;
    }
    for t in mesh.triangles() {
        for &i in t {
            out.u32(i)?;
        }
    }
    out.finish()?;
    let bounds = mesh.bounds();
    let view = BenchmarkView::new(&bounds, EYE.0, EYE.1);
    let sets = [
        ("camera", pixel_rays(view.eye, EYE.0, EYE.1), 1.0),
        ("random", random_rays(bounds.min, bounds.max), 4.0),
        ("grid", pixel_rays(view.light, LIGHT, LIGHT), 1.0),
    ];
    for (set, rays, t_max) in sets {
        let mut out = Writer::create(&dir.join(format!("rays-{set}.bin")))?;
        out.u32(len_u32(rays.len())?)?;
        out.f32(t_max)?;
        for (origin, direction) in rays {
            out.vec3(origin.as_vec3())?;
            out.vec3(direction.as_vec3())?;
        }
        out.finish()?;
    }
    Ok(())
}

/// One ray per pixel centre of a `width × height` view with clip matrix `clip_from_world`, from
/// the near plane (NDC z = −1) to the far plane (z = 1), in 4×4 tiles: rows of tiles from the
/// bottom, row-major inside a tile. Both sides must be multiples of the tile.
fn pixel_rays(clip_from_world: DMat4, width: u32, height: u32) -> Vec<(DVec3, DVec3)> {
    assert!(
        width.is_multiple_of(TILE) && height.is_multiple_of(TILE),
        "whole tiles"
    );
    let world_from_clip = clip_from_world.inverse();
    let unproject = |x: f64, y: f64, z: f64| {
        let p = world_from_clip * DVec4::new(x, y, z, 1.0);
        p.truncate() / p.w
    };
    let ndc = |i: u32, n: u32| (f64::from(i) + 0.5) / f64::from(n) * 2.0 - 1.0;
    let mut rays = Vec::with_capacity(width as usize * height as usize);
    for tile_y in (0..height).step_by(TILE as usize) {
        for tile_x in (0..width).step_by(TILE as usize) {
            for y in tile_y..tile_y + TILE {
                for x in tile_x..tile_x + TILE {
                    let (nx, ny) = (ndc(x, width), ndc(y, height));
                    let near = unproject(nx, ny, -1.0);
                    let far = unproject(nx, ny, 1.0);
                    rays.push((near, far - near));
                }
            }
        }
    }
    rays
}

/// SplitMix64 (Steele, Lea & Flood 2014), exactly as `crates/trace/benches/trace.rs` uses it.
struct SplitMix64(u64);

impl SplitMix64 {
    /// A uniform number in `[0, 1)` with 53 random bits.
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

/// The random set: from the sphere of radius `2R` about the box's centre toward uniform points in
/// the box `lo..hi`.
fn random_rays(lo: DVec3, hi: DVec3) -> Vec<(DVec3, DVec3)> {
    let mut rng = SplitMix64(RANDOM_SEED);
    let center = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    (0..RANDOM_RAYS)
        .map(|_| {
            let origin = center + rng.direction() * (2.0 * radius);
            let target = lo + (hi - lo) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
            (origin, target - origin)
        })
        .collect()
}

fn len_u32(len: usize) -> Result<u32> {
    u32::try_from(len).context("more than u32::MAX items")
}

/// A buffered little-endian writer.
struct Writer {
    out: BufWriter<File>,
    path: PathBuf,
}

impl Writer {
    fn create(path: &Path) -> Result<Self> {
        let file = File::create(path).with_context(|| format!("creating {}", path.display()))?;
        Ok(Self {
            out: BufWriter::new(file),
            path: path.to_owned(),
        })
    }

    fn bytes(&mut self, bytes: &[u8]) -> Result<()> {
        self.out
            .write_all(bytes)
            .with_context(|| format!("writing {}", self.path.display()))
    }

    fn u32(&mut self, x: u32) -> Result<()> {
        self.bytes(&x.to_le_bytes())
    }

    fn f32(&mut self, x: f32) -> Result<()> {
        self.bytes(&x.to_le_bytes())
    }

    fn vec3(&mut self, v: Vec3) -> Result<()> {
        for x in v.to_array() {
            self.f32(x)?;
        }
        Ok(())
    }

    fn finish(mut self) -> Result<()> {
        self.out
            .flush()
            .with_context(|| format!("writing {}", self.path.display()))
    }
}

/// A whole input file, read as little-endian words.
struct Reader {
    bytes: Vec<u8>,
    at: usize,
    path: PathBuf,
}

impl Reader {
    fn open(path: &Path) -> Result<Self> {
        let mut bytes = Vec::new();
        BufReader::new(File::open(path).with_context(|| format!("opening {}", path.display()))?)
            .read_to_end(&mut bytes)
            .with_context(|| format!("reading {}", path.display()))?;
        Ok(Self {
            bytes,
            at: 0,
            path: path.to_owned(),
        })
    }

    fn word(&mut self) -> Result<[u8; 4]> {
        let Some(word) = self.bytes.get(self.at..self.at + 4) else {
            bail!("{} ends early", self.path.display());
        };
        self.at += 4;
        Ok(word.try_into().expect("four bytes"))
    }

    fn u32(&mut self) -> Result<u32> {
        Ok(u32::from_le_bytes(self.word()?))
    }

    fn f32(&mut self) -> Result<f64> {
        Ok(f64::from(f32::from_le_bytes(self.word()?)))
    }

    fn dvec3(&mut self) -> Result<DVec3> {
        Ok(DVec3::new(self.f32()?, self.f32()?, self.f32()?))
    }

    fn end(&self) -> Result<()> {
        ensure!(
            self.at == self.bytes.len(),
            "{} is longer than its counts say",
            self.path.display()
        );
        Ok(())
    }
}

/// A ray set read back: its rays (f32 values, widened) and `t_max`.
struct RaySet {
    name: &'static str,
    rays: Vec<Ray>,
    t_max: f64,
}

/// What `write` wrote, read back.
struct Inputs {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    sets: Vec<RaySet>,
}

fn read_inputs(dir: &Path) -> Result<Inputs> {
    let mut mesh = Reader::open(&dir.join("mesh.bin"))?;
    let (vertices, triangles) = (mesh.u32()?, mesh.u32()?);
    let positions = (0..vertices)
        .map(|_| mesh.dvec3())
        .collect::<Result<Vec<_>>>()?;
    let triangles = (0..triangles)
        .map(|_| Ok([mesh.u32()?, mesh.u32()?, mesh.u32()?]))
        .collect::<Result<Vec<_>>>()?;
    mesh.end()?;
    let mut sets = Vec::new();
    for name in SETS {
        let mut file = Reader::open(&dir.join(format!("rays-{name}.bin")))?;
        let count = file.u32()?;
        let t_max = file.f32()?;
        let rays = (0..count)
            .map(|_| Ok(Ray::new(file.dvec3()?, file.dvec3()?)?))
            .collect::<Result<Vec<_>>>()?;
        file.end()?;
        sets.push(RaySet { name, rays, t_max });
    }
    Ok(Inputs {
        positions,
        triangles,
        sets,
    })
}

/// `warmup` untimed calls of `f`, then the times of `runs` calls, in ms; and the last result.
fn timed<T>(warmup: usize, runs: usize, mut f: impl FnMut() -> T) -> (Vec<f64>, T) {
    for _ in 0..warmup {
        drop(f());
    }
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let start = Instant::now();
        let result = f();
        times.push(start.elapsed().as_secs_f64() * 1e3);
        last = Some(result);
    }
    (times, last.expect("at least one timed run"))
}

fn time(dir: &Path, threads: &[usize], runs: usize, warmup: usize, hits: bool) -> Result<()> {
    ensure!(runs > 0, "--runs must be at least 1");
    ensure!(
        !threads.is_empty() && !threads.contains(&0),
        "--threads takes positive counts"
    );
    let Inputs {
        positions,
        triangles,
        sets,
    } = read_inputs(dir)?;
    let mut records = Vec::new();
    let mut hit_counts = serde_json::Map::new();
    let mut degenerate = None;
    for (k, &n) in threads.iter().enumerate() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build()?;
        let (ms, bvh) = timed(warmup, runs, || {
            pool.install(|| Bvh::new(&positions, &triangles))
        });
        let bvh = bvh?;
        degenerate = Some(bvh.stats().degenerate);
        records.push(json!({"what": "build", "threads": n, "ms": ms}));
        for set in &sets {
            let (ms, closest) = timed(warmup, runs, || {
                pool.install(|| bvh.closest_hits(&set.rays, 0.0, set.t_max))
            });
            let rays = set.rays.len();
            records.push(json!({"what": "closest", "set": set.name, "mode": "batch",
                "threads": n, "rays": rays, "ms": ms}));
            if set.name == "grid" {
                let ms = time_grid_rows(&pool, &bvh, set, (warmup, runs), &closest)?;
                records.push(json!({"what": "closest", "set": set.name, "mode": "rows",
                    "threads": n, "rays": rays, "ms": ms}));
            }
            let (ms, occluded) = timed(warmup, runs, || {
                pool.install(|| bvh.occluded_all(&set.rays, 0.0, set.t_max))
            });
            records.push(json!({"what": "anyhit", "set": set.name, "mode": "batch",
                "threads": n, "rays": rays, "ms": ms}));
            // The answers are the same for every pool size: record them once.
            if k == 0 {
                let closest: Vec<i32> = closest
                    .iter()
                    .map(|h| h.map_or(Ok(-1), |h| i32::try_from(h.triangle)))
                    .collect::<Result<_, _>>()?;
                let occluded_count = occluded.iter().filter(|&&o| o).count();
                let closest_count = closest.iter().filter(|&&t| t >= 0).count();
                hit_counts.insert(
                    set.name.into(),
                    json!({"closest": closest_count, "anyhit": occluded_count}),
                );
                if hits {
                    write_hits(dir, set.name, &closest, &occluded)?;
                }
            }
        }
    }
    let ray_counts: serde_json::Map<_, _> = sets
        .iter()
        .map(|s| (s.name.to_owned(), json!(s.rays.len())))
        .collect();
    let report = json!({
        "side": "shadowlab",
        "precision": "f64, exact (watertight)",
        "triangles": triangles.len(),
        "degenerate": degenerate,
        "rays": ray_counts,
        "hits": hit_counts,
        "warmup": warmup,
        "records": records,
    });
    let mut stdout = std::io::stdout().lock();
    serde_json::to_writer(&mut stdout, &report)?;
    writeln!(stdout)?;
    Ok(())
}

/// The `grid` set's closest hits timed through [`Bvh::closest_hits_grid`], as the logarithmic
/// shadow map casts its texel rays: row by row (the rays put in row order once, untimed; each row
/// copied in by the row callback, the answers copied out), swept triangle by triangle where the
/// grid has at least `RAYS_PER_TRIANGLE` (64) rays per triangle, through the tree otherwise. Its
/// answers must be `batch`'s, bit for bit (an error otherwise).
fn time_grid_rows(
    pool: &rayon::ThreadPool,
    bvh: &Bvh,
    set: &RaySet,
    (warmup, runs): (usize, usize),
    batch: &[Option<Hit>],
) -> Result<Vec<f64>> {
    let side = LIGHT as usize;
    ensure!(
        set.rays.len() == side * side,
        "the grid set holds {side}² rays"
    );
    // Pixel (x, y)'s place in the tile order of `pixel_rays`.
    let tile = TILE as usize;
    let tiled = |x: usize, y: usize| {
        ((y / tile) * (side / tile) + x / tile) * tile * tile + (y % tile) * tile + x % tile
    };
    let in_rows: Vec<Ray> = (0..side * side)
        .map(|k| set.rays[tiled(k % side, k / side)])
        .collect();
    let mut answers = vec![None; side * side];
    let (ms, result) = timed(warmup, runs, || {
        pool.install(|| {
            bvh.closest_hits_grid(
                side,
                |j, rays| rays.copy_from_slice(&in_rows[j * side..(j + 1) * side]),
                0.0,
                set.t_max,
                &mut answers,
                |_, hits, out| out.copy_from_slice(hits),
            )
        })
    });
    result?;
    let differing = (0..side * side)
        .filter(|&k| answers[k] != batch[tiled(k % side, k / side)])
        .count();
    ensure!(
        differing == 0,
        "closest_hits_grid answered {differing} rays differently from closest_hits"
    );
    Ok(ms)
}

fn write_hits(dir: &Path, set: &str, closest: &[i32], occluded: &[bool]) -> Result<()> {
    let mut out = Writer::create(&dir.join(format!("shadowlab-{set}.closest")))?;
    for &t in closest {
        out.bytes(&t.to_le_bytes())?;
    }
    out.finish()?;
    let mut out = Writer::create(&dir.join(format!("shadowlab-{set}.anyhit")))?;
    for &o in occluded {
        out.bytes(&[u8::from(o)])?;
    }
    out.finish()
}
