//! The inner loop: one triangle's pixels within one tile, in blocks of 8 columns × 16 rows.
//!
//! An edge function at pixel centres is `E = 256·K + r` with `r` the same for every centre (the
//! vertices are on the 1/256 grid and the centres half a pixel off it), so `E ≥ 0` exactly when
//! `E >> 8 ≥ 0` (an arithmetic shift, i.e. a floor), and `E >> 8` changes by `step >> 8` per column
//! or row — an exact integer below 2^24 in magnitude. Within a block, `E >> 8` at the block's
//! corner, clamped to ±2^30 (beyond which no step within the block can change its sign), plus at
//! most 22 such steps fits an i32. So each row of a block is eight i32 lanes per edge: three adds,
//! two ORs and a sign test give the row's coverage as a bit mask, with no division and no branch per
//! pixel. The covered columns of a row of a convex triangle are contiguous, so the row's fragments
//! are the span between the mask's lowest and highest bit.
//!
//! Depth is not stepped from pixel to pixel: every pixel gets `row_depth(j) + column_depth(i)` of
//! the triangle's [`DepthPlane`] — the plane through its *unsnapped* vertices (see the `triangle`
//! module), relative to a reference point on the grid with exact integer offsets — the column parts
//! once per block, the row part once per row. So a pixel's depth bits do not depend on the block,
//! the tile or the path (blocks, narrow boxes, early fragments) that draws it.

use std::ops::RangeInclusive;

use wide::i32x8;

use crate::fixed::SUBPIXEL_BITS;
use crate::tile::{TILE_STRIDE, TileRect};
use crate::triangle::{DepthPlane, Edge, PixelBox, edges};
use crate::vertex::WindowVertex;

/// Receives the fragments of one tile, eight pixels of a row at a time.
pub(crate) trait Sink {
    /// Eight pixels in two halves: lanes `0..4` at tile indices `start..start + 4` and lanes `4..8`
    /// at `start + SPLIT..start + SPLIT + 4` — with `SPLIT` = [`HALF`], eight consecutive pixels
    /// of one row of the tile's storage (padding included); with `SPLIT` = [`TILE_STRIDE`], four
    /// pixels of a row and the four above them. Lane k is *not* covered when `uncovered[k]` is all
    /// ones (covered when zero), and has window depth `z[k]`. Returns how many covered fragments
    /// passed (were stored). Uncovered lanes must be left as they are.
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        triangle: u32,
    ) -> u64;

    /// One covered pixel at tile index `index` with window depth `z`; returns 1 if it passed.
    fn fragment(&mut self, index: usize, z: f64, triangle: u32) -> u64;
}

/// Eight lanes: one row of a block.
pub(crate) type Lanes<T> = [T; BLOCK];

/// Rasterizes everything binned to a few consecutive tiles, each into its own sink. Implemented by
/// the pipeline; called by the targets, one group of tiles per call, so that every sink type gets
/// its own compiled inner loop.
pub(crate) trait TileKernel: Sync {
    /// Draws tiles `first..first + sinks.len()`, tile `first + k` into `sinks[k]`; returns the
    /// number of fragments that passed.
    fn run<S: Sink>(&self, first: usize, sinks: &mut [S]) -> u64;

    /// A measure of the work in tiles `first..first + count`: what the scheduler orders groups by.
    fn cost(&self, first: usize, count: usize) -> u64;
}

/// Block side, in pixels: the lanes of one row.
pub(crate) const BLOCK: usize = 8;
/// [`BLOCK`] as a coordinate.
pub(crate) const BLOCK_I64: i64 = 8;
/// Block height, in pixels: the rows stepped from one clamped corner (see [`CLAMP`]). Taller than
/// wide because a triangle's box ends where it ends, not on a block boundary: with blocks of 8 rows,
/// a box of 9 rows took a second block for its last row (measured: see docs/benchmarks.md).
const BLOCK_ROWS: i64 = 16;
/// Half a block row: boxes at most this wide are drawn two rows per lane row.
pub(crate) const HALF: usize = BLOCK / 2;
/// [`HALF`] as a coordinate.
const HALF_I64: i64 = 4;
/// The column offsets of the lanes.
const COLUMNS: i32x8 = i32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
/// The column offsets of the lanes of a row pair (see [`Sink::row`]).
const PAIR_COLUMNS: i32x8 = i32x8::new([0, 1, 2, 3, 0, 1, 2, 3]);
/// The row offsets of the lanes of a row pair.
const PAIR_ROWS: i32x8 = i32x8::new([0, 0, 0, 0, 1, 1, 1, 1]);
/// Beyond this magnitude, `E >> 8` keeps its sign across a block: at most `BLOCK − 1` column and
/// `BLOCK_ROWS − 1` row steps of < 2^24 each, 22 · 2^24 < 2^30; and the clamped corner plus those
/// steps stays below 2^30 + 2^29 in magnitude, inside an i32.
const CLAMP: i64 = 1 << 30;
const _: () = assert!((BLOCK_I64 - 1 + BLOCK_ROWS - 1) << 24 < CLAMP);

/// `E >> 8` at a block corner, clamped to ±2^30.
#[inline(always)]
fn corner(e: i64) -> i32 {
    #[expect(clippy::cast_possible_truncation, reason = "clamped to ±2^30")]
    let v = (e >> SUBPIXEL_BITS).clamp(-CLAMP, CLAMP) as i32;
    v
}

/// A column or row step of `E >> 8`: a grid delta, below 2^24 in magnitude.
#[inline(always)]
fn step(s: i64) -> i32 {
    #[expect(clippy::cast_possible_truncation, reason = "a grid delta, below 2^24")]
    let v = (s >> SUBPIXEL_BITS) as i32;
    v
}

/// The coverage of one row of a block as lane masks, inverted: all ones where some edge value is
/// negative (then so is the OR of the three) or the column is outside the triangle's box; zero
/// where the centre is covered.
#[inline(always)]
fn row_uncovered(values: &[i32x8; 3], outside: i32x8) -> Lanes<u32> {
    let uncovered = (values[0] | values[1] | values[2]).is_negative() | outside;
    wide::bytemuck::cast(uncovered)
}

/// Calls `f(i, j, z)` for each pixel of a coverage mask of a box `columns` wide from row `j0` (bit
/// `r·w + c` for column `columns.start() + c` and row `j0 + r`, `w` being the box's width), row by
/// row from the bottom, with the depth the block path gives the same pixel.
#[inline(always)]
pub(crate) fn for_each_in_mask(
    mut covered: u32,
    depth: &DepthPlane,
    columns: RangeInclusive<i64>,
    j0: i64,
    mut f: impl FnMut(i64, i64, f64),
) {
    let i0 = *columns.start();
    #[expect(
        clippy::cast_sign_loss,
        clippy::cast_possible_truncation,
        reason = "a box width, at most BLOCK"
    )]
    let width = (columns.end() - i0 + 1) as u32;
    while covered != 0 {
        let bit = covered.trailing_zeros();
        covered &= covered - 1;
        let (i, j) = (i0 + i64::from(bit % width), j0 + i64::from(bit / width));
        f(i, j, depth.row_depth(j) + depth.column_depth(i));
    }
}

/// Sends the fragments of a triangle (with doubled signed area `area`, non-zero) that fall in
/// `tile` (within the triangle's pixel box) to `sink`, row by row within blocks of 8 × 16, or two
/// rows at a time for boxes at most four pixels wide. Returns the number that passed. Boxes of one
/// or two pixels take no special path here: binning draws those that lie in one tile (see
/// `pipeline::EarlyFragment`), and a per-pixel path for boxes up to four pixels, measured after
/// the two-row path came, cost 4 % of the dragon's light pass for its extra branch.
#[inline]
pub(crate) fn rasterize<S: Sink>(
    vertices: &[WindowVertex; 3],
    area: i64,
    bounds: &PixelBox,
    tile: &TileRect,
    triangle: u32,
    sink: &mut S,
) -> u64 {
    let i0 = bounds.min_i.max(tile.x0);
    let i1 = bounds.max_i.min(tile.x0 + tile.width - 1);
    let j0 = bounds.min_j.max(tile.y0);
    let j1 = bounds.max_j.min(tile.y0 + tile.height - 1);
    if i0 > i1 || j0 > j1 {
        return 0;
    }
    let edges = edges(vertices, area);
    let depth = DepthPlane::new(vertices, area);
    if i1 - i0 < HALF_I64 {
        rasterize_narrow(&edges, &depth, i0..=i1, j0..=j1, tile, triangle, sink)
    } else {
        rasterize_blocks(&edges, &depth, i0..=i1, j0..=j1, tile, triangle, sink)
    }
}

/// [`rasterize`] for a box of any width, in blocks of [`BLOCK`] columns and [`BLOCK_ROWS`] rows.
#[inline(always)]
fn rasterize_blocks<S: Sink>(
    edges: &[Edge; 3],
    depth: &DepthPlane,
    columns: RangeInclusive<i64>,
    rows: RangeInclusive<i64>,
    tile: &TileRect,
    triangle: u32,
    sink: &mut S,
) -> u64 {
    let (i0, i1, j0, j1) = (*columns.start(), *columns.end(), *rows.start(), *rows.end());
    // Per edge, the change of `E >> 8` from the block's first column to each lane's, and per row.
    let lanes = edges.map(|edge| COLUMNS * i32x8::splat(step(edge.step_i)));
    let row_steps = edges.map(|edge| i32x8::splat(step(edge.step_j)));
    let mut passed = 0;
    let mut bj = j0;
    // Blocks start at the box's first column: a triangle up to eight pixels wide takes one block
    // per sixteen rows. The tile rows' padding keeps every block row inside its tile row; lanes
    // outside the triangle's box are masked off.
    let first_block_column = i0;
    while bj <= j1 {
        let rows = (j1 - bj + 1).min(BLOCK_ROWS);
        let mut bi = first_block_column;
        while bi <= i1 {
            // Lanes outside the box's columns [i0, i1]: k − (i0 − bi) or (i1 − bi) − k is negative.
            #[expect(
                clippy::cast_possible_truncation,
                reason = "clamped to a block's width"
            )]
            let (lo, hi) = (
                (i0 - bi).clamp(-1, BLOCK_I64) as i32,
                (i1 - bi).clamp(-1, BLOCK_I64) as i32,
            );
            let outside =
                ((COLUMNS - i32x8::splat(lo)) | (i32x8::splat(hi) - COLUMNS)).is_negative();
            // `E >> 8` at the eight centres of the block's first row, per edge.
            let mut values =
                [0, 1, 2].map(|e| i32x8::splat(corner(edges[e].at(bi, bj))) + lanes[e]);
            // The column part of the depth, once per block; the row part once per row.
            let column_z = depth.column_depths(bi);
            #[expect(
                clippy::cast_sign_loss,
                clippy::cast_possible_truncation,
                reason = "the block lies inside the tile"
            )]
            let mut start = ((bj - tile.y0) as usize) * TILE_STRIDE + (bi - tile.x0) as usize;
            for r in 0..rows {
                let uncovered = row_uncovered(&values, outside);
                let row_z = depth.row_depth(bj + r);
                let mut z = [0.0; BLOCK];
                for k in 0..BLOCK {
                    z[k] = row_z + column_z[k];
                }
                passed += sink.row::<HALF>(start, &uncovered, &z, triangle);
                for (value, row_step) in values.iter_mut().zip(row_steps) {
                    *value += row_step;
                }
                start += TILE_STRIDE;
            }
            bi += BLOCK_I64;
        }
        bj += BLOCK_ROWS;
    }
    passed
}

/// [`rasterize`] for a box at most [`HALF`] columns wide, two rows per lane row (lanes `0..4` a
/// row's columns, lanes `4..8` the same columns of the row above), in blocks of 4 × 16 pixels —
/// half the lane rows a block of eight lanes would take for the narrow boxes that dense meshes are
/// made of. Each pixel gets the same coverage and the same depth (the same sum of the same row and
/// column parts) as in a block of eight.
#[inline(always)]
fn rasterize_narrow<S: Sink>(
    edges: &[Edge; 3],
    depth: &DepthPlane,
    columns: RangeInclusive<i64>,
    rows: RangeInclusive<i64>,
    tile: &TileRect,
    triangle: u32,
    sink: &mut S,
) -> u64 {
    let (i0, i1, j0, j1) = (*columns.start(), *columns.end(), *rows.start(), *rows.end());
    // Per edge, the change of `E >> 8` from the block's corner to each lane's, and per row pair.
    let lanes = edges.map(|edge| {
        PAIR_COLUMNS * i32x8::splat(step(edge.step_i)) + PAIR_ROWS * i32x8::splat(step(edge.step_j))
    });
    let pair_steps = edges.map(|edge| i32x8::splat(2 * step(edge.step_j)));
    #[expect(clippy::cast_possible_truncation, reason = "below HALF")]
    let last_column = i32x8::splat((i1 - i0) as i32);
    // Lanes right of the box, in both rows of a pair; for a last single row, also the upper half.
    let outside = (last_column - PAIR_COLUMNS).is_negative();
    let single_outside = outside | (i32x8::splat(0) - PAIR_ROWS);
    let column_z = depth.column_depths(i0);
    let mut passed = 0;
    let mut bj = j0;
    while bj <= j1 {
        let block_rows = (j1 - bj + 1).min(BLOCK_ROWS);
        // `E >> 8` at the lanes of the block's first row pair, per edge; at most 3 column and 15
        // row steps from the clamped corner, within the bound of an ordinary block.
        let mut values = [0, 1, 2].map(|e| i32x8::splat(corner(edges[e].at(i0, bj))) + lanes[e]);
        #[expect(
            clippy::cast_sign_loss,
            clippy::cast_possible_truncation,
            reason = "the block lies inside the tile"
        )]
        let mut start = ((bj - tile.y0) as usize) * TILE_STRIDE + (i0 - tile.x0) as usize;
        let mut r = 0;
        while r + 1 < block_rows {
            let uncovered = row_uncovered(&values, outside);
            let row_z = [depth.row_depth(bj + r), depth.row_depth(bj + r + 1)];
            let z: Lanes<f64> = std::array::from_fn(|k| row_z[k / HALF] + column_z[k % HALF]);
            passed += sink.row::<TILE_STRIDE>(start, &uncovered, &z, triangle);
            for (value, pair_step) in values.iter_mut().zip(pair_steps) {
                *value += pair_step;
            }
            start += 2 * TILE_STRIDE;
            r += 2;
        }
        if r < block_rows {
            // The row above may lie outside the tile's storage: the last row alone, as the first
            // half of an ordinary row.
            let uncovered = row_uncovered(&values, single_outside);
            let row_z = depth.row_depth(bj + r);
            let z: Lanes<f64> = std::array::from_fn(|k| row_z + column_z[k % HALF]);
            passed += sink.row::<HALF>(start, &uncovered, &z, triangle);
        }
        bj += BLOCK_ROWS;
    }
    passed
}

/// A sink for the tests: every covered pixel a path sends, with its depth's bits.
#[cfg(test)]
#[derive(Default)]
pub(crate) struct Recorder(pub(crate) Vec<(usize, u64)>);

#[cfg(test)]
impl Sink for Recorder {
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        _triangle: u32,
    ) -> u64 {
        for k in (0..BLOCK).filter(|&k| uncovered[k] == 0) {
            self.0
                .push((start + (k / HALF) * SPLIT + k % HALF, z[k].to_bits()));
        }
        0
    }

    fn fragment(&mut self, index: usize, z: f64, _triangle: u32) -> u64 {
        self.0.push((index, z.to_bits()));
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangle::{Verdict, classify};

    /// The shifted, clamped lane arithmetic gives the sign of the exact edge function everywhere in
    /// a block, for edges of every slope and magnitude.
    #[test]
    fn block_coverage_matches_the_exact_edge_function() {
        let values =
            (-40..40)
                .step_by(7)
                .chain([-(1 << 45) + 3, (1 << 45) - 5, -123_456_789, 987_654_321]);
        let steps = [
            0,
            1,
            -1,
            7,
            -9,
            255,
            256 * 3,
            -256 * 77,
            (1 << 32) - 256,
            -(1 << 32) + 256,
        ];
        // The largest steps a block may take: just below 2^24 after the shift.
        assert_eq!(step((1 << 32) - 256), (1 << 24) - 1);
        for e in values {
            for step_i in steps {
                for step_j in steps {
                    // Edge functions step by multiples of 256 (SUBPIXELS per pixel).
                    let (si, sj) = (step_i & !255, step_j & !255);
                    let zero = i32x8::splat(0);
                    let first_row = i32x8::splat(corner(e)) + COLUMNS * i32x8::splat(step(si));
                    let mut values = [first_row, zero, zero];
                    for r in 0..BLOCK_ROWS {
                        let uncovered = row_uncovered(&values, zero);
                        for (k, lane) in (0..8i64).zip(uncovered) {
                            let exact = e + sj * r + si * k >= 0;
                            assert_eq!(exact, lane == 0, "e {e} si {si} sj {sj} r {r} k {k}");
                        }
                        values[0] += i32x8::splat(step(sj));
                    }
                }
            }
        }
    }

    /// The narrow path (two rows per lane row) sends exactly the pixels and depths of the block
    /// path, for boxes of one to four columns and up to a whole tile's rows, anywhere in a tile.
    #[test]
    fn narrow_boxes_give_what_blocks_give() {
        let mut random = crate::test_random::XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = move |n: i64| {
            #[expect(clippy::cast_possible_wrap, reason = "below n")]
            let v = random.below(n.unsigned_abs()) as i64;
            v
        };
        let tile = TileRect {
            x0: 64,
            y0: 128,
            width: 64,
            height: 64,
        };
        let mut compared = 0;
        for _ in 0..20_000 {
            // A thin triangle in grid units: up to 4 pixels wide, up to 70 tall, anywhere, its
            // unsnapped positions off the grid by up to half a grid unit.
            let (x, y) = (256 * (60 + next(70)), 256 * (120 + next(80)));
            let v: [WindowVertex; 3] = std::array::from_fn(|_| {
                #[expect(clippy::cast_possible_truncation, reason = "small grid values")]
                let (x, y) = ((x + next(4 * 256)) as i32, (y + next(70 * 256)) as i32);
                let mut thousandths = |n| f64::from(u32::try_from(next(n)).unwrap_or(0)) / 1000.0;
                WindowVertex {
                    x,
                    y,
                    z: 0.25 + 0.5 * thousandths(1000),
                    unsnapped_x: f64::from(x) + thousandths(1001) - 0.5,
                    unsnapped_y: f64::from(y) + thousandths(1001) - 0.5,
                }
            });
            let Verdict::Draw(b, area) = classify(&v, crate::CullMode::None, 4096, 4096) else {
                continue;
            };
            let (i0, i1) = (b.min_i.max(tile.x0), b.max_i.min(tile.x0 + tile.width - 1));
            let (j0, j1) = (b.min_j.max(tile.y0), b.max_j.min(tile.y0 + tile.height - 1));
            if i0 > i1 || j0 > j1 || i1 - i0 >= HALF_I64 {
                continue;
            }
            let (edges, depth) = (edges(&v, area), DepthPlane::new(&v, area));
            let (mut narrow, mut blocks) = (Recorder::default(), Recorder::default());
            rasterize_narrow(&edges, &depth, i0..=i1, j0..=j1, &tile, 0, &mut narrow);
            rasterize_blocks(&edges, &depth, i0..=i1, j0..=j1, &tile, 0, &mut blocks);
            narrow.0.sort_unstable();
            blocks.0.sort_unstable();
            assert_eq!(narrow.0, blocks.0, "{v:?}");
            compared += usize::from(!blocks.0.is_empty());
        }
        assert!(compared > 5_000, "{compared}");
    }
}
