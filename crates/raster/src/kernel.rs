//! The inner loop: one triangle's pixels within one tile, as spans of covered pixels per row.
//!
//! For each row the exact range of columns whose centres every edge function covers is found by
//! integer division (the edge functions are linear in the column), so the depth loop runs only over
//! covered pixels and has no coverage test in it.

use crate::fixed::SUBPIXELS;
use crate::target::TILE_SIZE;
use crate::triangle::{PixelBox, Setup};

/// Receives the fragments of one tile, a span of one row at a time.
pub(crate) trait Sink {
    /// A covered span of `count` pixels starting at tile index `start` (row-major, `TILE_SIZE` per
    /// row). The depth of its `k`-th pixel is `row_z + dz_dx·(x_offset + k·SUBPIXELS)`, the form in
    /// which the setup defines it (see [`Setup::depth_row`]). Returns how many fragments passed.
    fn span(&mut self, start: usize, count: usize, depth: SpanDepth, triangle: u32) -> u64;
}

/// The depth along a span: `z(k) = row_z + dz_dx·(x_offset + k·SUBPIXELS)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SpanDepth {
    pub(crate) row_z: f64,
    pub(crate) dz_dx: f64,
    pub(crate) x_offset: f64,
}

impl SpanDepth {
    /// The depth of the span's `k`-th pixel. `x_offset + k·SUBPIXELS` is an integer below 2^53, so
    /// it is exact however it is formed, and every pixel's depth depends on the triangle alone.
    #[inline(always)]
    pub(crate) fn at(&self, k: u32) -> f64 {
        self.row_z + self.dz_dx * (self.x_offset + f64::from(k) * SUBPIXELS as f64)
    }
}

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

/// The boundary an edge puts on a row's span, followed from row to row.
///
/// For an edge whose function grows to the right (`step > 0`) the boundary is the span's first
/// column `k = min{k ≥ 0 : E(k) ≥ 0}` (`len` if none); for one that shrinks (`step < 0`) it is the
/// last column `k = max{k < len : E(k) ≥ 0}` (`−1` if none). `value` is `E(k)`. Moving to the next
/// row adds `step_j` to it and walks `k` until the definition holds again: as many steps as the
/// boundary moves, so a triangle costs O(rows + columns) additions and no division per row.
#[derive(Clone, Copy, Debug)]
struct Boundary {
    step_i: i64,
    step_j: i64,
    column: i64,
    value: i64,
}

impl Boundary {
    /// The boundary in the first row, where the edge function is `e` at column 0; exact (integer
    /// division).
    #[inline(always)]
    fn new(e: i64, step_i: i64, step_j: i64, len: i64) -> Self {
        let column = if step_i > 0 {
            if e >= 0 {
                0
            } else {
                ((-e + step_i - 1) / step_i).min(len)
            }
        } else if step_i < 0 {
            if e < 0 {
                -1
            } else {
                (e / -step_i).min(len - 1)
            }
        } else {
            0
        };
        Self {
            step_i,
            step_j,
            column,
            value: e + step_i * column,
        }
    }

    /// Moves to the next row.
    #[inline(always)]
    fn next_row(&mut self, len: i64) {
        self.value += self.step_j;
        let step = self.step_i;
        if step > 0 {
            if self.value < 0 {
                while self.value < 0 && self.column < len {
                    self.column += 1;
                    self.value += step;
                }
            } else {
                while self.column > 0 && self.value - step >= 0 {
                    self.column -= 1;
                    self.value -= step;
                }
            }
        } else if step < 0 {
            if self.value < 0 {
                while self.value < 0 && self.column >= 0 {
                    self.column -= 1;
                    self.value -= step;
                }
            } else {
                while self.column < len - 1 && self.value + step >= 0 {
                    self.column += 1;
                    self.value += step;
                }
            }
        }
    }

    /// The row's columns `lo..=hi` allowed by this edge; `lo > hi` if none.
    #[inline(always)]
    fn span(&self, len: i64) -> (i64, i64) {
        if self.step_i > 0 {
            (self.column, len - 1)
        } else if self.step_i < 0 {
            (0, self.column)
        } else if self.value >= 0 {
            (0, len - 1)
        } else {
            (1, 0)
        }
    }
}

/// Triangles at most this many columns wide (within the tile) find each row's span by testing
/// every column at once, as a bit mask; wider ones follow their boundaries from row to row.
const NARROW: i64 = 8;
/// [`NARROW`] as a lane count.
const NARROW_LANES: usize = 8;
/// The column offsets of the lanes.
const COLUMNS: [i32; NARROW_LANES] = [0, 1, 2, 3, 4, 5, 6, 7];
/// The mask bit of each lane.
const LANE_BITS: [u32; NARROW_LANES] = [1, 2, 4, 8, 16, 32, 64, 128];

/// `e >> 8` clamped to `±2^30`: the sign of the edge function, in a form that stays exact when up to
/// `NARROW` column steps (each below 2^24 in magnitude) are added in i32.
#[inline(always)]
fn shifted(e: i64) -> i32 {
    const LIMIT: i64 = 1 << 30;
    #[expect(clippy::cast_possible_truncation, reason = "clamped to ±2^30")]
    let v = (e >> crate::fixed::SUBPIXEL_BITS).clamp(-LIMIT, LIMIT) as i32;
    v
}

/// Sends the fragments of a set-up triangle that fall in `tile` (within the triangle's pixel box) to
/// `sink`, a covered span per row. Returns the number that passed.
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
    let len = i1 - i0 + 1;
    let [e0, e1, e2] = setup.edges;
    let (mut a, mut b, mut c) = (e0.at(i0, j0), e1.at(i0, j0), e2.at(i0, j0));
    let emit = |j: i64, lo: i64, hi: i64, sink: &mut S| {
        let (row_z, x_offset) = setup.depth_row(i0 + lo, j);
        let depth = SpanDepth {
            row_z,
            dz_dx: setup.dz_dx(),
            x_offset,
        };
        #[expect(
            clippy::cast_sign_loss,
            clippy::cast_possible_truncation,
            reason = "the span lies inside the tile"
        )]
        let (start, count) = (
            ((j - tile.y0) as usize) * TILE_SIZE + (i0 + lo - tile.x0) as usize,
            (hi - lo + 1) as usize,
        );
        sink.span(start, count, depth, triangle)
    };
    let mut passed = 0;
    let mut j = j0;
    if len <= NARROW {
        // All columns of a row at once, as a bit mask. An edge function at pixel centres is
        // E = 256·K + r with r fixed, so E ≥ 0 exactly when E >> 8 ≥ 0, and E >> 8 changes by
        // step_i/256 per column. Clamped to ±2^30 (beyond which the sign cannot change within
        // NARROW columns) it fits an i32 lane, eight to a vector. The covered columns of a row of
        // a convex triangle are contiguous.
        let lanes = |step: i64| -> [i32; NARROW_LANES] {
            #[expect(
                clippy::cast_possible_truncation,
                reason = "a column step of E >> 8 is a grid delta, below 2^24 in magnitude"
            )]
            let per_column = (step >> crate::fixed::SUBPIXEL_BITS) as i32;
            let mut lanes = COLUMNS;
            for lane in &mut lanes {
                *lane *= per_column;
            }
            lanes
        };
        let (la, lb, lc) = (lanes(e0.step_i), lanes(e1.step_i), lanes(e2.step_i));
        let valid = (1u32 << len) - 1;
        loop {
            let (sa, sb, sc) = (shifted(a), shifted(b), shifted(c));
            // Bit k set when every edge is ≥ 0 at column k: the OR of the three has its sign bit
            // clear. Written as lane operations and a reduction so that it compiles to vector code.
            let mut bits = [0u32; NARROW_LANES];
            for k in 0..NARROW_LANES {
                let covered = (sa + la[k]) | (sb + lb[k]) | (sc + lc[k]);
                #[expect(clippy::cast_sign_loss, reason = "reinterpreting the sign mask")]
                let outside = (covered >> 31) as u32;
                bits[k] = !outside & LANE_BITS[k];
            }
            let mut mask = bits.iter().fold(0, |m, b| m | b);
            mask &= valid;
            if mask != 0 {
                let lo = i64::from(mask.trailing_zeros());
                let hi = i64::from(31 - mask.leading_zeros());
                passed += emit(j, lo, hi, sink);
            }
            if j == j1 {
                break;
            }
            j += 1;
            a += e0.step_j;
            b += e1.step_j;
            c += e2.step_j;
        }
    } else {
        let mut edges = [
            Boundary::new(a, e0.step_i, e0.step_j, len),
            Boundary::new(b, e1.step_i, e1.step_j, len),
            Boundary::new(c, e2.step_i, e2.step_j, len),
        ];
        loop {
            let (lo0, hi0) = edges[0].span(len);
            let (lo1, hi1) = edges[1].span(len);
            let (lo2, hi2) = edges[2].span(len);
            let (lo, hi) = (lo0.max(lo1).max(lo2), hi0.min(hi1).min(hi2));
            if lo <= hi {
                passed += emit(j, lo, hi, sink);
            }
            if j == j1 {
                break;
            }
            j += 1;
            edges[0].next_row(len);
            edges[1].next_row(len);
            edges[2].next_row(len);
        }
    }
    passed
}

#[cfg(test)]
mod tests {
    use super::Boundary;

    /// Followed row by row, the spans agree with testing every pixel, for edges of every slope and
    /// magnitude.
    #[test]
    fn spans_match_the_per_pixel_test() {
        let values = (-40..40)
            .step_by(3)
            .chain([-(1 << 40) + 3, (1 << 40) - 5, -123_456_789]);
        let steps = [
            -9,
            -3,
            -1,
            0,
            1,
            2,
            7,
            256,
            -256,
            65_536 * 3,
            -(1 << 30) + 1,
        ];
        for e in values {
            for step_i in steps {
                for step_j in steps {
                    for len in [1, 2, 5, 64] {
                        let mut edge = Boundary::new(e, step_i, step_j, len);
                        for row in 0..20 {
                            let (lo, hi) = edge.span(len);
                            for k in 0..len {
                                let value = e + step_j * row + step_i * k;
                                assert_eq!(
                                    value >= 0,
                                    lo <= k && k <= hi,
                                    "e {e} step_i {step_i} step_j {step_j} len {len} row {row} k {k}"
                                );
                            }
                            edge.next_row(len);
                        }
                    }
                }
            }
        }
    }
}
