//! Render targets. Pixels are stored tile by tile (each tile a contiguous block, rows within it),
//! so each tile can be written by one thread with no sharing; the accessors return ordinary
//! row-major images with row 0 at the bottom (GL's window convention — image writers flip it).

use crate::depth::{DepthCompare, DepthFormat, DepthKey};
use crate::error::RasterError;
use crate::fixed::MAX_TARGET_SIZE;
use crate::kernel::{BLOCK, Lanes, Sink, TileKernel};

/// Tile side in pixels, `2^TILE_SHIFT`.
pub(crate) const TILE_SIZE: usize = 1 << TILE_SHIFT;
/// log2 of the tile side.
pub(crate) const TILE_SHIFT: u32 = 6;
/// Stored values per tile row: the tile's 64 pixels and 8 of padding, so that a run of eight
/// pixels starting at any column of the tile stays inside its row (the padding is never covered).
pub(crate) const TILE_STRIDE: usize = TILE_SIZE + 8;
/// Stored values per tile.
pub(crate) const TILE_PIXELS: usize = TILE_STRIDE * TILE_SIZE;

/// Consecutive tiles (in storage order: along a row of tiles) drawn by one parallel job, chunk
/// by chunk (see [`TileKernel::run`]).
pub(crate) const TILE_GROUP: usize = 4;

/// Tiles cleared per parallel job.
const CLEAR_TILES_PER_JOB: usize = 64;

/// The triangle id stored where no triangle covers a pixel.
pub const NO_TRIANGLE: u32 = u32::MAX;

/// The size of a target and its tiling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TargetSize {
    width: u32,
    height: u32,
    tiles_x: usize,
    tiles_y: usize,
}

impl TargetSize {
    /// A `width × height` target; `Err` if a side is 0 or above [`MAX_TARGET_SIZE`].
    pub fn new(width: u32, height: u32) -> Result<Self, RasterError> {
        for (name, value) in [("width", width), ("height", height)] {
            if value == 0 || value > MAX_TARGET_SIZE {
                return Err(RasterError::TargetSize { name, value });
            }
        }
        Ok(Self {
            width,
            height,
            tiles_x: (width as usize).div_ceil(TILE_SIZE),
            tiles_y: (height as usize).div_ceil(TILE_SIZE),
        })
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Number of tiles.
    pub(crate) fn tile_count(&self) -> usize {
        self.tiles_x * self.tiles_y
    }

    /// Tiles per row.
    pub(crate) fn tiles_x(&self) -> usize {
        self.tiles_x
    }

    /// The pixel rectangle of tile `t`: `(first column, first row, columns, rows)`.
    pub(crate) fn tile_rect(&self, t: usize) -> (i64, i64, i64, i64) {
        let (tx, ty) = (t % self.tiles_x, t / self.tiles_x);
        let (x0, y0) = (tx * TILE_SIZE, ty * TILE_SIZE);
        let w = (self.width as usize - x0).min(TILE_SIZE);
        let h = (self.height as usize - y0).min(TILE_SIZE);
        #[expect(
            clippy::cast_possible_wrap,
            reason = "sizes are at most MAX_TARGET_SIZE"
        )]
        let rect = (x0 as i64, y0 as i64, w as i64, h as i64);
        rect
    }

    fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Converts tiled storage to a row-major image (row 0 at the bottom), leaving out the padding.
    fn untile<T: Copy + Default>(&self, tiled: &[T]) -> Vec<T> {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut out = vec![T::default(); self.pixel_count()];
        for (y, row) in out.chunks_mut(w).enumerate().take(h) {
            let ty = y / TILE_SIZE;
            let in_tile_row = (y % TILE_SIZE) * TILE_STRIDE;
            for (tx, span) in row.chunks_mut(TILE_SIZE).enumerate() {
                let start = (ty * self.tiles_x + tx) * TILE_PIXELS + in_tile_row;
                span.copy_from_slice(&tiled[start..start + span.len()]);
            }
        }
        out
    }
}

/// A depth-only target: the shadow map.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthTarget {
    size: TargetSize,
    format: DepthFormat,
    keys: Vec<u32>,
}

impl DepthTarget {
    /// The target's size.
    #[must_use]
    pub fn size(&self) -> TargetSize {
        self.size
    }

    /// The depth format it stores.
    #[must_use]
    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// A `width × height` depth target storing `format`, cleared to the far plane (depth 1).
    pub fn new(width: u32, height: u32, format: DepthFormat) -> Result<Self, RasterError> {
        let size = TargetSize::new(width, height)?;
        Ok(Self {
            size,
            format,
            keys: vec![format.encode(1.0); size.tile_count() * TILE_PIXELS],
        })
    }

    /// Sets every pixel to window depth `depth` (clamped to `[0, 1]`), in parallel.
    pub fn clear(&mut self, depth: f64) {
        fill(&mut self.keys, self.format.encode(depth));
    }

    /// The stored keys, row-major with row 0 at the bottom (see [`DepthFormat`] for what a key is).
    #[must_use]
    pub fn keys(&self) -> Vec<u32> {
        self.size.untile(&self.keys)
    }

    /// Window depths in `[0, 1]` exactly as stored, row-major with row 0 at the bottom.
    #[must_use]
    pub fn depths(&self) -> Vec<f64> {
        let format = self.format;
        self.keys().into_iter().map(|k| format.decode(k)).collect()
    }
}

impl DepthTarget {
    /// Runs `kernel` on every group of [`TILE_GROUP`] tiles in parallel, with a sink per tile
    /// writing into that tile only; returns the number of fragments that passed.
    pub(crate) fn draw_tiles<K: DepthKey, R: TileKernel>(
        &mut self,
        compare: DepthCompare,
        kernel: &R,
    ) -> u64 {
        use rayon::prelude::*;
        self.keys
            .par_chunks_mut(TILE_PIXELS * TILE_GROUP)
            // One group per job: tiles differ wildly in cost (most are empty), and rayon's adaptive
            // splitting alone leaves one thread with most of the work when the caller is itself a
            // pool thread (its job never counts as stolen, so it is split less).
            .with_max_len(1)
            .enumerate()
            .map(|(g, keys)| {
                let tiles = keys.chunks_mut(TILE_PIXELS);
                // The common test gets its own loop, without a per-fragment branch.
                if compare == DepthCompare::Less {
                    let mut sinks: Vec<_> = tiles
                        .map(|keys| DepthSink::<K, Less> {
                            keys,
                            compare: Less,
                            key: std::marker::PhantomData,
                        })
                        .collect();
                    kernel.run(g * TILE_GROUP, &mut sinks)
                } else {
                    let mut sinks: Vec<_> = tiles
                        .map(|keys| DepthSink::<K, DepthCompare> {
                            keys,
                            compare,
                            key: std::marker::PhantomData,
                        })
                        .collect();
                    kernel.run(g * TILE_GROUP, &mut sinks)
                }
            })
            .sum()
    }
}

/// The nearest and second-nearest depth in one pass: what the second-depth, midpoint and
/// dual-depth biases need. The depth test is fixed: nearer keys win.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthPairTarget {
    size: TargetSize,
    format: DepthFormat,
    nearest: Vec<u32>,
    second: Vec<u32>,
}

impl DepthPairTarget {
    /// The target's size.
    #[must_use]
    pub fn size(&self) -> TargetSize {
        self.size
    }

    /// The depth format it stores.
    #[must_use]
    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// A `width × height` target of depth pairs, both cleared to the far plane.
    pub fn new(width: u32, height: u32, format: DepthFormat) -> Result<Self, RasterError> {
        let size = TargetSize::new(width, height)?;
        let far = format.encode(1.0);
        Ok(Self {
            size,
            format,
            nearest: vec![far; size.tile_count() * TILE_PIXELS],
            second: vec![far; size.tile_count() * TILE_PIXELS],
        })
    }

    /// Sets both depths of every pixel to the far plane.
    pub fn clear(&mut self) {
        let far = self.format.encode(1.0);
        fill(&mut self.nearest, far);
        fill(&mut self.second, far);
    }

    /// Nearest depths, row-major with row 0 at the bottom.
    #[must_use]
    pub fn nearest(&self) -> Vec<f64> {
        let format = self.format;
        self.size
            .untile(&self.nearest)
            .into_iter()
            .map(|k| format.decode(k))
            .collect()
    }

    /// Second-nearest depths (1 where fewer than two surfaces cover the pixel).
    #[must_use]
    pub fn second(&self) -> Vec<f64> {
        let format = self.format;
        self.size
            .untile(&self.second)
            .into_iter()
            .map(|k| format.decode(k))
            .collect()
    }
}

impl DepthPairTarget {
    /// Runs `kernel` on every group of [`TILE_GROUP`] tiles in parallel, with a sink per tile
    /// writing into that tile only; returns the number of fragments that passed.
    pub(crate) fn draw_tiles<K: DepthKey, R: TileKernel>(&mut self, kernel: &R) -> u64 {
        use rayon::prelude::*;
        self.nearest
            .par_chunks_mut(TILE_PIXELS * TILE_GROUP)
            .zip(self.second.par_chunks_mut(TILE_PIXELS * TILE_GROUP))
            .with_max_len(1)
            .enumerate()
            .map(|(g, (nearest, second))| {
                let mut sinks: Vec<_> = nearest
                    .chunks_mut(TILE_PIXELS)
                    .zip(second.chunks_mut(TILE_PIXELS))
                    .map(|(nearest, second)| PairSink::<K> {
                        nearest,
                        second,
                        key: std::marker::PhantomData,
                    })
                    .collect();
                kernel.run(g * TILE_GROUP, &mut sinks)
            })
            .sum()
    }
}

/// The eye pass: depth and the id of the visible triangle per pixel, from which
/// [`crate::EyeTarget::resolve`] computes perspective-correct positions and normals.
#[derive(Clone, Debug, PartialEq)]
pub struct EyeTarget {
    size: TargetSize,
    format: DepthFormat,
    keys: Vec<u32>,
    triangles: Vec<u32>,
}

impl EyeTarget {
    /// The target's size.
    #[must_use]
    pub fn size(&self) -> TargetSize {
        self.size
    }

    /// The depth format it stores.
    #[must_use]
    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// A `width × height` eye target, cleared (depth 1, no triangle).
    pub fn new(width: u32, height: u32, format: DepthFormat) -> Result<Self, RasterError> {
        let size = TargetSize::new(width, height)?;
        Ok(Self {
            size,
            format,
            keys: vec![format.encode(1.0); size.tile_count() * TILE_PIXELS],
            triangles: vec![NO_TRIANGLE; size.tile_count() * TILE_PIXELS],
        })
    }

    /// Clears depth to the far plane and the triangle ids to [`NO_TRIANGLE`].
    pub fn clear(&mut self) {
        fill(&mut self.keys, self.format.encode(1.0));
        fill(&mut self.triangles, NO_TRIANGLE);
    }

    /// Window depths as stored, row-major with row 0 at the bottom.
    #[must_use]
    pub fn depths(&self) -> Vec<f64> {
        let format = self.format;
        self.size
            .untile(&self.keys)
            .into_iter()
            .map(|k| format.decode(k))
            .collect()
    }

    /// The visible triangle of each pixel ([`NO_TRIANGLE`] where none), row-major, row 0 at the
    /// bottom.
    #[must_use]
    pub fn triangles(&self) -> Vec<u32> {
        self.size.untile(&self.triangles)
    }
}

impl EyeTarget {
    /// Runs `kernel` on every group of [`TILE_GROUP`] tiles in parallel, with a sink per tile
    /// writing into that tile only; returns the number of fragments that passed.
    pub(crate) fn draw_tiles<K: DepthKey, R: TileKernel>(
        &mut self,
        compare: DepthCompare,
        kernel: &R,
    ) -> u64 {
        use rayon::prelude::*;
        self.keys
            .par_chunks_mut(TILE_PIXELS * TILE_GROUP)
            .zip(self.triangles.par_chunks_mut(TILE_PIXELS * TILE_GROUP))
            .with_max_len(1)
            .enumerate()
            .map(|(g, (keys, triangles))| {
                let tiles = keys
                    .chunks_mut(TILE_PIXELS)
                    .zip(triangles.chunks_mut(TILE_PIXELS));
                if compare == DepthCompare::Less {
                    let mut sinks: Vec<_> = tiles
                        .map(|(keys, triangles)| EyeSink::<K, Less> {
                            keys,
                            triangles,
                            compare: Less,
                            key: std::marker::PhantomData,
                        })
                        .collect();
                    kernel.run(g * TILE_GROUP, &mut sinks)
                } else {
                    let mut sinks: Vec<_> = tiles
                        .map(|(keys, triangles)| EyeSink::<K, DepthCompare> {
                            keys,
                            triangles,
                            compare,
                            key: std::marker::PhantomData,
                        })
                        .collect();
                    kernel.run(g * TILE_GROUP, &mut sinks)
                }
            })
            .sum()
    }
}

fn fill(values: &mut [u32], value: u32) {
    use rayon::prelude::*;
    // Equal work per tile: 64 tiles (1 MiB) per job keeps the job overhead negligible and still
    // splits a 2048² target into 16 jobs, whoever calls.
    values
        .par_chunks_mut(TILE_PIXELS)
        .with_max_len(CLEAR_TILES_PER_JOB)
        .for_each(|tile| tile.fill(value));
}

/// A depth comparison as a type, so the common `Less` compiles without a per-fragment branch.
pub(crate) trait Compare {
    fn passes(&self, new: u32, old: u32) -> bool;

    /// The stored value after a fragment with key `new`, uncovered where `uncovered` is all ones,
    /// meets `old`; and all ones if the fragment passed (zero otherwise).
    #[inline(always)]
    fn merge(&self, uncovered: u32, new: u32, old: u32) -> (u32, u32) {
        let pass = !uncovered & mask(self.passes(new, old));
        (select(pass, new, old), pass)
    }
}

/// `new < old`.
pub(crate) struct Less;

impl Compare for Less {
    #[inline(always)]
    fn passes(&self, new: u32, old: u32) -> bool {
        new < old
    }

    /// `min(new | uncovered, old)`: an uncovered lane offers the largest key, which never wins; a
    /// fragment passed exactly where the value changed.
    #[inline(always)]
    fn merge(&self, uncovered: u32, new: u32, old: u32) -> (u32, u32) {
        let merged = (new | uncovered).min(old);
        (merged, mask(merged != old))
    }
}

impl Compare for DepthCompare {
    #[inline(always)]
    fn passes(&self, new: u32, old: u32) -> bool {
        DepthCompare::passes(*self, new, old)
    }
}

/// Writes depth keys through the depth test.
struct DepthSink<'a, K, C> {
    keys: &'a mut [u32],
    compare: C,
    key: std::marker::PhantomData<K>,
}

/// The eight keys of a block row.
#[inline(always)]
fn lanes(values: &mut [u32], start: usize) -> &mut Lanes<u32> {
    (&mut values[start..start + BLOCK])
        .try_into()
        .expect("a block row lies inside the tile")
}

/// All ones where `pass`, zero otherwise (written as a select of constants, which compiles to a
/// vector compare; going through `u32::from(bool)` makes LLVM shuffle single bits).
#[inline(always)]
fn mask(pass: bool) -> u32 {
    if pass { u32::MAX } else { 0 }
}

/// `new` where `pass` (all ones), `old` elsewhere: a select, not a branch — whether a fragment
/// passes is as good as random, and a mispredicted branch costs more than the whole test.
#[inline(always)]
fn select(pass: u32, new: u32, old: u32) -> u32 {
    (new & pass) | (old & !pass)
}

impl<K: DepthKey, C: Compare> Sink for DepthSink<'_, K, C> {
    #[inline(always)]
    fn row(&mut self, start: usize, uncovered: &Lanes<u32>, z: &Lanes<f64>, _triangle: u32) -> u64 {
        let keys = lanes(self.keys, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (merged, pass) = self.compare.merge(uncovered[k], key, keys[k]);
            keys[k] = merged;
            passed += pass & 1;
        }
        u64::from(passed)
    }

    #[inline(always)]
    fn fragment(&mut self, index: usize, z: f64, _triangle: u32) -> u64 {
        let key = K::encode(z);
        let old = &mut self.keys[index];
        let (merged, pass) = self.compare.merge(0, key, *old);
        *old = merged;
        u64::from(pass & 1)
    }
}

/// Keeps the two nearest keys.
struct PairSink<'a, K> {
    nearest: &'a mut [u32],
    second: &'a mut [u32],
    key: std::marker::PhantomData<K>,
}

impl<K: DepthKey> Sink for PairSink<'_, K> {
    #[inline(always)]
    fn row(&mut self, start: usize, uncovered: &Lanes<u32>, z: &Lanes<f64>, _triangle: u32) -> u64 {
        let nearest = lanes(self.nearest, start);
        let second = lanes(self.second, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (near, next) = (nearest[k], second[k]);
            let nearer = !uncovered[k] & mask(key < near);
            let between = !uncovered[k] & !nearer & mask(key < next);
            nearest[k] = select(nearer, key, near);
            second[k] = select(nearer, near, select(between, key, next));
            passed += u64::from((nearer | between) & 1);
        }
        passed
    }

    #[inline(always)]
    fn fragment(&mut self, index: usize, z: f64, _triangle: u32) -> u64 {
        let key = K::encode(z);
        let (near, next) = (self.nearest[index], self.second[index]);
        if key < near {
            self.second[index] = near;
            self.nearest[index] = key;
            1
        } else if key < next {
            self.second[index] = key;
            1
        } else {
            0
        }
    }
}

/// Writes depth keys and triangle ids through the depth test.
struct EyeSink<'a, K, C> {
    keys: &'a mut [u32],
    triangles: &'a mut [u32],
    compare: C,
    key: std::marker::PhantomData<K>,
}

impl<K: DepthKey, C: Compare> Sink for EyeSink<'_, K, C> {
    #[inline(always)]
    fn row(&mut self, start: usize, uncovered: &Lanes<u32>, z: &Lanes<f64>, triangle: u32) -> u64 {
        let keys = lanes(self.keys, start);
        let ids = lanes(self.triangles, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (merged, pass) = self.compare.merge(uncovered[k], key, keys[k]);
            keys[k] = merged;
            ids[k] = select(pass, triangle, ids[k]);
            passed += u64::from(pass & 1);
        }
        passed
    }

    #[inline(always)]
    fn fragment(&mut self, index: usize, z: f64, triangle: u32) -> u64 {
        let key = K::encode(z);
        let (merged, pass) = self.compare.merge(0, key, self.keys[index]);
        self.keys[index] = merged;
        self.triangles[index] = select(pass, triangle, self.triangles[index]);
        u64::from(pass & 1)
    }
}
