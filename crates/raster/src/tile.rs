//! Tile storage: a target's pixels kept tile by tile (each tile a contiguous block, rows within
//! it, padded), so that each tile can be written by one thread with no sharing, and clears that are
//! carried out only where a draw writes. Readers get ordinary row-major images with row 0 at the
//! bottom (GL's window convention — image writers flip it).

use std::borrow::Cow;

use rayon::prelude::*;

use crate::depth::DepthFormat;
use crate::error::RasterError;
use crate::fixed::MAX_TARGET_SIZE;

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
/// by chunk (see `TileKernel::run`).
pub(crate) const TILE_GROUP: usize = 4;

/// The pixel rectangle of a tile: first column and row, and size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TileRect {
    pub(crate) x0: i64,
    pub(crate) y0: i64,
    pub(crate) width: i64,
    pub(crate) height: i64,
}

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

    /// The pixel rectangle of tile `t`.
    pub(crate) fn tile_rect(&self, t: usize) -> TileRect {
        let (tx, ty) = (t % self.tiles_x, t / self.tiles_x);
        let (x0, y0) = (tx * TILE_SIZE, ty * TILE_SIZE);
        let width = (self.width as usize - x0).min(TILE_SIZE);
        let height = (self.height as usize - y0).min(TILE_SIZE);
        #[expect(
            clippy::cast_possible_wrap,
            reason = "sizes are at most MAX_TARGET_SIZE"
        )]
        let rect = TileRect {
            x0: x0 as i64,
            y0: y0 as i64,
            width: width as i64,
            height: height as i64,
        };
        rect
    }

    fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Converts tiled storage to a row-major image (row 0 at the bottom) of `value` of each stored
    /// value, leaving out the padding; tiles marked in `cleared` read as `clear_value` whatever they
    /// store. Bands of one tile row in parallel: each output value depends on its own pixel alone.
    fn untile<T: Copy + Sync, U: Copy + Default + Send>(
        &self,
        tiled: &[T],
        cleared: &[bool],
        clear_value: T,
        value: impl Fn(T) -> U + Sync,
    ) -> Vec<U> {
        let w = self.width as usize;
        // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers").
        let mut out: Vec<U> = rayon::iter::repeat_n(U::default(), self.pixel_count()).collect();
        out.par_chunks_mut(w * TILE_SIZE)
            .enumerate()
            .for_each(|(ty, band)| {
                for (dy, row) in band.chunks_mut(w).enumerate() {
                    let in_tile_row = dy * TILE_STRIDE;
                    for (tx, span) in row.chunks_mut(TILE_SIZE).enumerate() {
                        let tile = ty * self.tiles_x + tx;
                        if cleared[tile] {
                            span.fill(value(clear_value));
                        } else {
                            let start = tile * TILE_PIXELS + in_tile_row;
                            let stored = &tiled[start..start + span.len()];
                            for (out, &stored) in span.iter_mut().zip(stored) {
                                *out = value(stored);
                            }
                        }
                    }
                }
            });
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
pub(crate) struct TiledPlane {
    values: Vec<u32>,
    /// The value of the last clear.
    clear_value: u32,
    /// Per tile: whether it holds the last clear, not written to `values` yet.
    cleared: Vec<bool>,
}

impl TiledPlane {
    /// A plane of `size`'s tiles, cleared to `value`.
    pub(crate) fn new(size: TargetSize, value: u32) -> Self {
        Self {
            // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers").
            values: rayon::iter::repeat_n(0, size.tile_count() * TILE_PIXELS).collect(),
            clear_value: value,
            cleared: vec![true; size.tile_count()],
        }
    }

    /// Sets every pixel to `value` (carried out where the next draws write).
    pub(crate) fn clear(&mut self, value: u32) {
        self.clear_value = value;
        self.cleared.fill(true);
    }

    /// The stored values with the cleared tiles filled in.
    fn resolved(&self) -> Cow<'_, [u32]> {
        if !self.cleared.contains(&true) {
            return Cow::Borrowed(&self.values);
        }
        let mut values = self.values.clone();
        for (tile, &cleared) in values.chunks_mut(TILE_PIXELS).zip(&self.cleared) {
            if cleared {
                tile.fill(self.clear_value);
            }
        }
        Cow::Owned(values)
    }

    /// The values as a row-major image (row 0 at the bottom).
    pub(crate) fn untile(&self, size: TargetSize) -> Vec<u32> {
        self.image(size, |v| v)
    }

    /// `value` of each pixel's value, as a row-major image (row 0 at the bottom).
    pub(crate) fn image<U: Copy + Default + Send>(
        &self,
        size: TargetSize,
        value: impl Fn(u32) -> U + Sync,
    ) -> Vec<U> {
        size.untile(&self.values, &self.cleared, self.clear_value, value)
    }

    /// The window depths of the keys of `format` each pixel holds, as a row-major image (row 0 at
    /// the bottom): [`Self::image`] of [`DepthFormat::decode`], with the format's decoding chosen
    /// once rather than per pixel.
    pub(crate) fn depths(&self, size: TargetSize, format: DepthFormat) -> Vec<f64> {
        match format {
            DepthFormat::F32 => self.image(size, |k| DepthFormat::F32.decode(k)),
            DepthFormat::ReversedF32 => self.image(size, |k| DepthFormat::ReversedF32.decode(k)),
            DepthFormat::Unorm24 => self.image(size, |k| DepthFormat::Unorm24.decode(k)),
            DepthFormat::Unorm16 => self.image(size, |k| DepthFormat::Unorm16.decode(k)),
        }
    }

    /// The groups of [`TILE_GROUP`] tiles a draw writes in parallel, in storage order.
    pub(crate) fn groups_mut(&mut self) -> impl Iterator<Item = PlaneGroup<'_>> {
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
pub(crate) struct PlaneGroup<'a> {
    values: &'a mut [u32],
    cleared: &'a mut [bool],
    clear_value: u32,
}

/// The storage of one group of tiles as a draw receives it: one plane's ([`PlaneGroup`]) or two
/// planes' in step (a pair of groups).
pub(crate) trait TileGroup: Send {
    /// One tile's storage.
    type Tile;

    /// Writes the pending clear into the group's tiles that the draw writes (`drawn(k)` for the
    /// group's `k`-th), and returns every tile's storage, in order.
    fn tiles(self, drawn: &impl Fn(usize) -> bool) -> impl Iterator<Item = Self::Tile>;
}

impl<'a> TileGroup for PlaneGroup<'a> {
    type Tile = &'a mut [u32];

    fn tiles(self, drawn: &impl Fn(usize) -> bool) -> impl Iterator<Item = &'a mut [u32]> {
        for (k, (tile, cleared)) in self
            .values
            .chunks_mut(TILE_PIXELS)
            .zip(self.cleared.iter_mut())
            .enumerate()
        {
            if *cleared && drawn(k) {
                tile.fill(self.clear_value);
                *cleared = false;
            }
        }
        self.values.chunks_mut(TILE_PIXELS)
    }
}

impl<A: TileGroup, B: TileGroup> TileGroup for (A, B) {
    type Tile = (A::Tile, B::Tile);

    fn tiles(self, drawn: &impl Fn(usize) -> bool) -> impl Iterator<Item = Self::Tile> {
        let (a, b) = self;
        a.tiles(drawn).zip(b.tiles(drawn))
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

    /// A draw fills the pending clear into the tiles it writes and no others; a pair of planes
    /// gets the same tiles filled in both.
    #[test]
    fn a_draw_fills_the_pending_clear_only_where_it_writes() {
        let size = TargetSize::new(64 * 5, 64).expect("a valid size");
        let (mut a, mut b) = (TiledPlane::new(size, 3), TiledPlane::new(size, 4));
        let written = |k: usize| k == 1;
        for group in a.groups_mut().zip(b.groups_mut()) {
            for (ta, tb) in group.tiles(&written) {
                assert_eq!((ta.len(), tb.len()), (TILE_PIXELS, TILE_PIXELS));
            }
        }
        // Tile 1 of each group of four: tiles 1 and 5 (absent: the target has five tiles).
        assert_eq!(a.cleared, [true, false, true, true, true]);
        assert_eq!(b.cleared, a.cleared);
        assert!(
            a.values[TILE_PIXELS..2 * TILE_PIXELS]
                .iter()
                .all(|&v| v == 3)
        );
        assert!(
            b.values[TILE_PIXELS..2 * TILE_PIXELS]
                .iter()
                .all(|&v| v == 4)
        );
        assert!(a.values[..TILE_PIXELS].iter().all(|&v| v == 0));
    }
}
