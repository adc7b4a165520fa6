//! Render targets. Pixels are stored tile by tile (each tile a contiguous block, rows within it),
//! so each tile can be written by one thread with no sharing; the accessors return ordinary
//! row-major images with row 0 at the bottom (GL's window convention — image writers flip it).

use crate::depth::{DepthCompare, DepthFormat, DepthKey};
use crate::error::RasterError;
use crate::fixed::MAX_TARGET_SIZE;
use crate::kernel::{BLOCK, HALF, Lanes, Sink, TileKernel};

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

    /// Converts tiled storage to a row-major image (row 0 at the bottom), leaving out the padding;
    /// tiles marked in `cleared` read as `clear_value` whatever they store.
    fn untile<T: Copy + Default>(&self, tiled: &[T], cleared: &[bool], clear_value: T) -> Vec<T> {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut out = vec![T::default(); self.pixel_count()];
        for (y, row) in out.chunks_mut(w).enumerate().take(h) {
            let ty = y / TILE_SIZE;
            let in_tile_row = (y % TILE_SIZE) * TILE_STRIDE;
            for (tx, span) in row.chunks_mut(TILE_SIZE).enumerate() {
                let tile = ty * self.tiles_x + tx;
                if cleared[tile] {
                    span.fill(clear_value);
                } else {
                    let start = tile * TILE_PIXELS + in_tile_row;
                    span.copy_from_slice(&tiled[start..start + span.len()]);
                }
            }
        }
        out
    }
}

/// One value per pixel, stored tile by tile, with clears carried out only where a draw writes.
///
/// A clear only records its value and marks every tile as holding it; a draw fills a marked tile
/// just before drawing into it, while the tile is in that thread's cache, and tiles no triangle
/// touches are never written at all (readers see the clear value there), as tile-based GPUs
/// clear. That spares a separate pass over the whole target (a 2048² target is 19 MB with its
/// padding, of which a mesh often touches a quarter), and, for a caller outside the rayon pool, a
/// separate parallel job whose hand-over cost more than the fill itself on small targets
/// (docs/benchmarks.md).
#[derive(Clone, Debug)]
struct TiledPlane {
    values: Vec<u32>,
    /// The value of the last clear.
    clear_value: u32,
    /// Per tile: whether it holds the last clear, not written to `values` yet.
    cleared: Vec<bool>,
}

impl TiledPlane {
    /// A plane of `size`'s tiles, cleared to `value`.
    fn new(size: TargetSize, value: u32) -> Self {
        Self {
            values: vec![0; size.tile_count() * TILE_PIXELS],
            clear_value: value,
            cleared: vec![true; size.tile_count()],
        }
    }

    /// Sets every pixel to `value` (carried out where the next draws write).
    fn clear(&mut self, value: u32) {
        self.clear_value = value;
        self.cleared.fill(true);
    }

    /// The stored values with the cleared tiles filled in.
    fn resolved(&self) -> std::borrow::Cow<'_, [u32]> {
        if !self.cleared.contains(&true) {
            return std::borrow::Cow::Borrowed(&self.values);
        }
        let mut values = self.values.clone();
        for (tile, &cleared) in values.chunks_mut(TILE_PIXELS).zip(&self.cleared) {
            if cleared {
                tile.fill(self.clear_value);
            }
        }
        std::borrow::Cow::Owned(values)
    }

    /// The values as a row-major image (row 0 at the bottom).
    fn untile(&self, size: TargetSize) -> Vec<u32> {
        size.untile(&self.values, &self.cleared, self.clear_value)
    }

    /// The groups of [`TILE_GROUP`] tiles a draw writes in parallel.
    fn groups_mut(&mut self) -> impl Iterator<Item = PlaneGroup<'_>> {
        let clear_value = self.clear_value;
        self.values
            .chunks_mut(TILE_PIXELS * TILE_GROUP)
            .zip(self.cleared.chunks_mut(TILE_GROUP))
            .map(move |(values, cleared)| PlaneGroup {
                values,
                cleared,
                clear_value,
            })
    }
}

/// Equal when every pixel holds the same value, whether its tile was cleared lazily or not.
impl PartialEq for TiledPlane {
    fn eq(&self, other: &Self) -> bool {
        self.resolved() == other.resolved()
    }
}

/// One group's tiles of a [`TiledPlane`], as a draw gets them.
struct PlaneGroup<'a> {
    values: &'a mut [u32],
    cleared: &'a mut [bool],
    clear_value: u32,
}

impl<'a> PlaneGroup<'a> {
    /// Writes the pending clear into the group's tiles that `kernel` draws into (tile `first + k`
    /// being the group's `k`-th), and returns the tiles' storage.
    fn prepare(self, kernel: &impl TileKernel, first: usize) -> std::slice::ChunksMut<'a, u32> {
        for (k, (tile, cleared)) in self
            .values
            .chunks_mut(TILE_PIXELS)
            .zip(self.cleared.iter_mut())
            .enumerate()
        {
            if *cleared && kernel.cost(first + k, 1) > 0 {
                tile.fill(self.clear_value);
                *cleared = false;
            }
        }
        self.values.chunks_mut(TILE_PIXELS)
    }
}

/// A depth-only target: the shadow map.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthTarget {
    size: TargetSize,
    format: DepthFormat,
    keys: TiledPlane,
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
            keys: TiledPlane::new(size, format.encode(1.0)),
        })
    }

    /// Sets every pixel to window depth `depth` (clamped to `[0, 1]`; NaN: the far plane). Takes no
    /// time: the next draw fills each tile as it draws it.
    pub fn clear(&mut self, depth: f64) {
        self.keys.clear(self.format.encode(depth));
    }

    /// The stored keys, row-major with row 0 at the bottom (see [`DepthFormat`] for what a key is).
    #[must_use]
    pub fn keys(&self) -> Vec<u32> {
        self.keys.untile(self.size)
    }

    /// Window depths in `[0, 1]` exactly as stored, row-major with row 0 at the bottom.
    #[must_use]
    pub fn depths(&self) -> Vec<f64> {
        let format = self.format;
        self.keys().into_iter().map(|k| format.decode(k)).collect()
    }
}

/// A target the tile pass draws into: what the draw call needs of each of the three.
pub(crate) trait TileTarget: Send {
    /// The target's size.
    fn target_size(&self) -> TargetSize;

    /// The depth format it stores.
    fn depth_format(&self) -> DepthFormat;

    /// Runs `kernel` on every group of [`TILE_GROUP`] tiles in parallel, with a sink per tile
    /// writing into that tile only; returns the number of fragments that passed. `compare` is the
    /// depth test (a depth-pair target keeps the two nearest and ignores it).
    fn draw_tiles<K: DepthKey, R: TileKernel>(&mut self, compare: DepthCompare, kernel: &R) -> u64;
}

impl TileTarget for DepthTarget {
    fn target_size(&self) -> TargetSize {
        self.size
    }

    fn depth_format(&self) -> DepthFormat {
        self.format
    }

    fn draw_tiles<K: DepthKey, R: TileKernel>(&mut self, compare: DepthCompare, kernel: &R) -> u64 {
        draw_costliest_first(
            self.keys.groups_mut().collect(),
            |g| kernel.cost(g * TILE_GROUP, TILE_GROUP),
            |g, keys| {
                let tiles = keys.prepare(kernel, g * TILE_GROUP);
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
            },
        )
    }
}

/// The nearest and second-nearest depth in one pass: what the second-depth, midpoint and
/// dual-depth biases need. The depth test is fixed: nearer keys win.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthPairTarget {
    size: TargetSize,
    format: DepthFormat,
    nearest: TiledPlane,
    second: TiledPlane,
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
            nearest: TiledPlane::new(size, far),
            second: TiledPlane::new(size, far),
        })
    }

    /// Sets both depths of every pixel to the far plane (carried out by the next draw).
    pub fn clear(&mut self) {
        let far = self.format.encode(1.0);
        self.nearest.clear(far);
        self.second.clear(far);
    }

    /// Nearest depths, row-major with row 0 at the bottom.
    #[must_use]
    pub fn nearest(&self) -> Vec<f64> {
        let format = self.format;
        self.nearest
            .untile(self.size)
            .into_iter()
            .map(|k| format.decode(k))
            .collect()
    }

    /// Second-nearest depths (1 where fewer than two surfaces cover the pixel).
    #[must_use]
    pub fn second(&self) -> Vec<f64> {
        let format = self.format;
        self.second
            .untile(self.size)
            .into_iter()
            .map(|k| format.decode(k))
            .collect()
    }
}

impl TileTarget for DepthPairTarget {
    fn target_size(&self) -> TargetSize {
        self.size
    }

    fn depth_format(&self) -> DepthFormat {
        self.format
    }

    fn draw_tiles<K: DepthKey, R: TileKernel>(&mut self, _: DepthCompare, kernel: &R) -> u64 {
        draw_costliest_first(
            self.nearest
                .groups_mut()
                .zip(self.second.groups_mut())
                .collect(),
            |g| kernel.cost(g * TILE_GROUP, TILE_GROUP),
            |g, (nearest, second)| {
                let mut sinks: Vec<_> = nearest
                    .prepare(kernel, g * TILE_GROUP)
                    .zip(second.prepare(kernel, g * TILE_GROUP))
                    .map(|(nearest, second)| PairSink::<K> {
                        nearest,
                        second,
                        key: std::marker::PhantomData,
                    })
                    .collect();
                kernel.run(g * TILE_GROUP, &mut sinks)
            },
        )
    }
}

/// The eye pass: depth and the id of the visible triangle per pixel, from which
/// [`crate::EyeTarget::resolve`] computes perspective-correct positions and normals.
#[derive(Clone, Debug, PartialEq)]
pub struct EyeTarget {
    size: TargetSize,
    format: DepthFormat,
    keys: TiledPlane,
    triangles: TiledPlane,
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
            keys: TiledPlane::new(size, format.encode(1.0)),
            triangles: TiledPlane::new(size, NO_TRIANGLE),
        })
    }

    /// Clears depth to the far plane and the triangle ids to [`NO_TRIANGLE`] (carried out by the
    /// next draw).
    pub fn clear(&mut self) {
        self.keys.clear(self.format.encode(1.0));
        self.triangles.clear(NO_TRIANGLE);
    }

    /// Window depths as stored, row-major with row 0 at the bottom.
    #[must_use]
    pub fn depths(&self) -> Vec<f64> {
        let format = self.format;
        self.keys
            .untile(self.size)
            .into_iter()
            .map(|k| format.decode(k))
            .collect()
    }

    /// The visible triangle of each pixel ([`NO_TRIANGLE`] where none), row-major, row 0 at the
    /// bottom.
    #[must_use]
    pub fn triangles(&self) -> Vec<u32> {
        self.triangles.untile(self.size)
    }
}

impl TileTarget for EyeTarget {
    fn target_size(&self) -> TargetSize {
        self.size
    }

    fn depth_format(&self) -> DepthFormat {
        self.format
    }

    fn draw_tiles<K: DepthKey, R: TileKernel>(&mut self, compare: DepthCompare, kernel: &R) -> u64 {
        draw_costliest_first(
            self.keys
                .groups_mut()
                .zip(self.triangles.groups_mut())
                .collect(),
            |g| kernel.cost(g * TILE_GROUP, TILE_GROUP),
            |g, (keys, triangles)| {
                let tiles = keys
                    .prepare(kernel, g * TILE_GROUP)
                    .zip(triangles.prepare(kernel, g * TILE_GROUP));
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
            },
        )
    }
}

/// Draws every group of tiles on the pool's threads, the costliest first, each thread taking the
/// next group as it finishes one; returns the sum of `draw`'s results (fragments that passed).
///
/// Groups differ wildly in cost (most are empty, a few hold most of a mesh). Rayon's halving of an
/// index range left one thread with a costly group to finish while the other idled: on the bunny's
/// eye pass the tile pass kept two threads 92–97 % busy. Taking groups in order of decreasing cost
/// from one shared counter leaves at most a cheap group's time at the end. Which thread draws a
/// group does not change what is drawn into it, and the sum is of integers, so the result does not
/// depend on the schedule.
fn draw_costliest_first<G: Send>(
    groups: Vec<G>,
    cost: impl Fn(usize) -> u64,
    draw: impl Fn(usize, G) -> u64 + Sync,
) -> u64 {
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
    let mut order: Vec<(u64, usize)> = (0..groups.len()).map(|g| (cost(g), g)).collect();
    // Decreasing cost, ties in group order.
    order.sort_unstable_by_key(|&(c, g)| (std::cmp::Reverse(c), g));
    let mut groups: Vec<Option<G>> = groups.into_iter().map(Some).collect();
    let queue: Vec<(usize, Mutex<Option<G>>)> = order
        .iter()
        .map(|&(_, g)| (g, Mutex::new(groups[g].take())))
        .collect();
    let next = AtomicUsize::new(0);
    let passed = AtomicU64::new(0);
    let worker = || {
        let mut mine = 0;
        while let Some((g, slot)) = queue.get(next.fetch_add(1, Ordering::Relaxed)) {
            let group = slot
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .take();
            if let Some(group) = group {
                mine += draw(*g, group);
            }
        }
        passed.fetch_add(mine, Ordering::Relaxed);
    };
    rayon::scope(|scope| {
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(|_| worker());
        }
        worker();
    });
    passed.into_inner()
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

/// The eight stored values of a block row whose second half lies `SPLIT` after its first (see
/// [`Sink::row`]): one load when the halves are adjacent, two otherwise.
#[inline(always)]
fn load<const SPLIT: usize>(values: &[u32], start: usize) -> Lanes<u32> {
    let mut lanes = [0; BLOCK];
    if SPLIT == HALF {
        lanes.copy_from_slice(&values[start..start + BLOCK]);
    } else {
        lanes[..HALF].copy_from_slice(&values[start..start + HALF]);
        lanes[HALF..].copy_from_slice(&values[start + SPLIT..start + SPLIT + HALF]);
    }
    lanes
}

/// Stores what [`load`] loaded.
#[inline(always)]
fn store<const SPLIT: usize>(values: &mut [u32], start: usize, lanes: &Lanes<u32>) {
    if SPLIT == HALF {
        values[start..start + BLOCK].copy_from_slice(lanes);
    } else {
        values[start..start + HALF].copy_from_slice(&lanes[..HALF]);
        values[start + SPLIT..start + SPLIT + HALF].copy_from_slice(&lanes[HALF..]);
    }
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
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        _triangle: u32,
    ) -> u64 {
        let mut keys = load::<SPLIT>(self.keys, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (merged, pass) = self.compare.merge(uncovered[k], key, keys[k]);
            keys[k] = merged;
            passed += pass & 1;
        }
        store::<SPLIT>(self.keys, start, &keys);
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
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        _triangle: u32,
    ) -> u64 {
        let mut nearest = load::<SPLIT>(self.nearest, start);
        let mut second = load::<SPLIT>(self.second, start);
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
        store::<SPLIT>(self.nearest, start, &nearest);
        store::<SPLIT>(self.second, start, &second);
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
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        triangle: u32,
    ) -> u64 {
        let mut keys = load::<SPLIT>(self.keys, start);
        let mut ids = load::<SPLIT>(self.triangles, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (merged, pass) = self.compare.merge(uncovered[k], key, keys[k]);
            keys[k] = merged;
            ids[k] = select(pass, triangle, ids[k]);
            passed += u64::from(pass & 1);
        }
        store::<SPLIT>(self.keys, start, &keys);
        store::<SPLIT>(self.triangles, start, &ids);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A clear not yet carried out reads, and compares, as the value it will write, tile by tile.
    #[test]
    fn a_pending_clear_reads_and_compares_as_done() {
        let size = TargetSize::new(130, 3).expect("a valid size");
        let mut pending = TiledPlane::new(size, 7);
        assert_eq!(pending.untile(size), vec![7; 390]);
        let mut done = pending.clone();
        done.values.fill(7);
        done.cleared.fill(false);
        assert_eq!(done.untile(size), vec![7; 390]);
        assert_eq!(pending, done);
        assert_eq!(done, pending);
        pending.clear(8);
        assert_ne!(pending, done);
        // Tile 1 written, tiles 0 and 2 still cleared: each reads as what it holds.
        pending.cleared[1] = false;
        pending.values[TILE_PIXELS..2 * TILE_PIXELS].fill(9);
        let image = pending.untile(size);
        assert_eq!(&image[..64], &[8; 64]);
        assert_eq!(&image[64..128], &[9; 64]);
        assert_eq!(&image[128..130], &[8; 2]);
        done.values.fill(8);
        done.values[TILE_PIXELS..2 * TILE_PIXELS].fill(9);
        assert_eq!(pending, done);
    }

    /// Every group is drawn once, whatever its cost and however many threads share the work.
    #[test]
    fn every_group_is_drawn_once_costliest_first() {
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool");
            let mut drawn = vec![0u32; 37];
            let total = pool.install(|| {
                let groups: Vec<&mut u32> = drawn.iter_mut().collect();
                draw_costliest_first(
                    groups,
                    |g| (g as u64 * 7) % 5,
                    |g, count| {
                        *count += 1;
                        g as u64
                    },
                )
            });
            assert_eq!(drawn, vec![1; 37], "{threads} threads");
            assert_eq!(total, (0..37).sum::<u64>());
        }
    }
}
