//! The inner loop: one triangle's pixels within one tile, in blocks of 8 × 8.
//!
//! An edge function at pixel centres is `E = 256·K + r` with `r` the same for every centre (the
//! vertices are on the 1/256 grid and the centres half a pixel off it), so `E ≥ 0` exactly when
//! `E >> 8 ≥ 0` (an arithmetic shift, i.e. a floor), and `E >> 8` changes by `step >> 8` per column
//! or row — an exact integer below 2^24 in magnitude. Within a block, `E >> 8` at the block's
//! corner, clamped to ±2^30 (beyond which no step within the block can change its sign), plus at
//! most 14 such steps fits an i32. So each row of a block is eight i32 lanes per edge: three adds,
//! two ORs and a sign test give the row's coverage as a bit mask, with no division and no branch per
//! pixel. The covered columns of a row of a convex triangle are contiguous, so the row's fragments
//! are the span between the mask's lowest and highest bit.

use crate::fixed::SUBPIXEL_BITS;
use crate::target::TILE_STRIDE;
use crate::triangle::{PixelBox, Setup};

/// Receives the fragments of one tile, eight pixels of a row at a time.
pub(crate) trait Sink {
    /// The eight pixels at tile indices `start..start + 8` (within one row of the tile's storage,
    /// padding included): lane k is *not* covered when `uncovered[k]` is all ones (covered when zero), and
    /// has window depth `z[k]`. Returns how many covered fragments passed (were stored). Uncovered
    /// lanes must be left as they are.
    fn row(&mut self, start: usize, uncovered: &Lanes<u32>, z: &Lanes<f64>, triangle: u32) -> u64;

    /// One covered pixel at tile index `index` with window depth `z`; returns 1 if it passed.
    fn fragment(&mut self, index: usize, z: f64, triangle: u32) -> u64;
}

/// Eight lanes: one row of a block.
pub(crate) type Lanes<T> = [T; BLOCK];

/// Rasterizes everything binned to one tile into a sink. Implemented by the pipeline; called by
/// the targets, one tile per call, so that every sink type gets its own compiled inner loop.
pub(crate) trait TileKernel: Sync {
    /// Draws tile `tile`; returns the number of fragments that passed.
    fn run<S: Sink>(&self, tile: usize, sink: &mut S) -> u64;
}

/// The pixel rectangle of a tile: first column and row, and size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TileRect {
    pub(crate) x0: i64,
    pub(crate) y0: i64,
    pub(crate) width: i64,
    pub(crate) height: i64,
}

/// Pixel boxes of at most this many pixels (within the tile) are tested pixel by pixel: cheaper than
/// setting up a block for the one or two centres a tiny triangle can cover.
const SMALL: i64 = 4;

/// Block side, in pixels: the lanes of one row.
pub(crate) const BLOCK: usize = 8;
/// [`BLOCK`] as a coordinate.
const BLOCK_I64: i64 = 8;
/// The column offsets of the lanes.
const COLUMNS: [i32; BLOCK] = [0, 1, 2, 3, 4, 5, 6, 7];
/// Beyond this magnitude, `E >> 8` keeps its sign across a block (at most 14 steps of < 2^24).
const CLAMP: i64 = 1 << 30;

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
/// negative (the OR of the three has its sign bit set, spread by an arithmetic shift) or the column
/// is outside the triangle's box; zero where the centre is covered.
#[inline(always)]
fn row_uncovered(edges: [i32; 3], lanes: &[Lanes<i32>; 3], outside: &Lanes<u32>) -> Lanes<u32> {
    // Plain indexed loops over fixed-size arrays: LLVM turns these into single vector
    // instructions, which it does not reliably do for `array::map` or `from_fn`.
    let mut uncovered = [0u32; BLOCK];
    for k in 0..BLOCK {
        let v = (edges[0] + lanes[0][k]) | (edges[1] + lanes[1][k]) | (edges[2] + lanes[2][k]);
        #[expect(clippy::cast_sign_loss, reason = "the sign, spread to every bit")]
        let sign = (v >> 31) as u32;
        uncovered[k] = sign | outside[k];
    }
    uncovered
}

/// Sends the fragments of a set-up triangle that fall in `tile` (within the triangle's pixel box) to
/// `sink`, row by row within 8 × 8 blocks. Returns the number that passed.
#[inline]
pub(crate) fn rasterize<S: Sink>(
    setup: &Setup,
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
    let edges = setup.edges;
    if (i1 - i0 + 1) * (j1 - j0 + 1) <= SMALL {
        let mut passed = 0;
        for j in j0..=j1 {
            for i in i0..=i1 {
                if (edges[0].at(i, j) | edges[1].at(i, j) | edges[2].at(i, j)) >= 0 {
                    #[expect(
                        clippy::cast_sign_loss,
                        clippy::cast_possible_truncation,
                        reason = "the pixel lies inside the tile"
                    )]
                    let index = ((j - tile.y0) as usize) * TILE_STRIDE + (i - tile.x0) as usize;
                    let z = setup.row_depth(j) + setup.column_depth(i);
                    passed += sink.fragment(index, z, triangle);
                }
            }
        }
        return passed;
    }
    let mut lanes = [[0i32; BLOCK]; 3];
    for (lane, edge) in lanes.iter_mut().zip(&edges) {
        let per_column = step(edge.step_i);
        for k in 0..BLOCK {
            lane[k] = COLUMNS[k] * per_column;
        }
    }
    let row_steps = [
        step(edges[0].step_j),
        step(edges[1].step_j),
        step(edges[2].step_j),
    ];
    let mut passed = 0;
    let mut bj = j0;
    // Blocks start at the box's first column: a triangle up to eight pixels wide takes one block
    // per eight rows. The tile rows' padding keeps every block row inside its tile row; lanes
    // outside the triangle's box are masked off.
    let first_block_column = i0;
    while bj <= j1 {
        let rows = (j1 - bj + 1).min(BLOCK_I64);
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
            let mut outside = [0u32; BLOCK];
            for k in 0..BLOCK {
                #[expect(clippy::cast_sign_loss, reason = "the sign, spread to every bit")]
                let sign = (((COLUMNS[k] - lo) | (hi - COLUMNS[k])) >> 31) as u32;
                outside[k] = sign;
            }
            let mut corners = [
                corner(edges[0].at(bi, bj)),
                corner(edges[1].at(bi, bj)),
                corner(edges[2].at(bi, bj)),
            ];
            // The column part of the depth, once per block; the row part once per row.
            let column_z = setup.column_depths(bi);
            #[expect(
                clippy::cast_sign_loss,
                clippy::cast_possible_truncation,
                reason = "the block lies inside the tile"
            )]
            let mut start = ((bj - tile.y0) as usize) * TILE_STRIDE + (bi - tile.x0) as usize;
            for r in 0..rows {
                let uncovered = row_uncovered(corners, &lanes, &outside);
                let row_z = setup.row_depth(bj + r);
                let mut z = [0.0; BLOCK];
                for k in 0..BLOCK {
                    z[k] = row_z + column_z[k];
                }
                passed += sink.row(start, &uncovered, &z, triangle);
                for k in 0..3 {
                    corners[k] += row_steps[k];
                }
                start += TILE_STRIDE;
            }
            bi += BLOCK_I64;
        }
        bj += BLOCK_I64;
    }
    passed
}

#[cfg(test)]
mod tests {
    use super::*;

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
        for e in values {
            for step_i in steps {
                for step_j in steps {
                    // Edge functions step by multiples of 256 (SUBPIXELS per pixel).
                    let (si, sj) = (step_i & !255, step_j & !255);
                    let lanes = [COLUMNS.map(|k| k * step(si)), [0; BLOCK], [0; BLOCK]];
                    let mut edges = [corner(e), 0, 0];
                    for r in 0..8i64 {
                        let uncovered = row_uncovered(edges, &lanes, &[0; BLOCK]);
                        for (k, lane) in (0..8i64).zip(uncovered) {
                            let exact = e + sj * r + si * k >= 0;
                            assert_eq!(exact, lane == 0, "e {e} si {si} sj {sj} r {r} k {k}");
                        }
                        edges[0] += step(sj);
                    }
                }
            }
        }
    }
}
