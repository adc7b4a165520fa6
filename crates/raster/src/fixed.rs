//! The fixed-point window coordinates every edge decision is made in.
//!
//! Window coordinates (pixels, GL convention: x right, y up, pixel `(i, j)` covering
//! `[i, i+1) × [j, j+1)` with its centre at `(i + ½, j + ½)`) are snapped to a grid of
//! `1/2^SUBPIXEL_BITS` pixel, as GL implementations do. Snapping rounds to the nearest grid point, ties
//! to even (`f64::round_ties_even`), as Direct3D specifies and Mesa's llvmpipe does (`lrintf` in the
//! default rounding mode). Exact ties happen for dyadic inputs, e.g. a vertex at a half grid unit.
//! From then on coverage is decided in exact integer arithmetic.

/// Fractional bits of a snapped window coordinate: 8, i.e. 1/256 pixel.
pub const SUBPIXEL_BITS: u32 = 8;

/// Grid points per pixel, `2^SUBPIXEL_BITS`.
pub(crate) const SUBPIXELS: i64 = 1 << SUBPIXEL_BITS;

/// Half a pixel in grid units: pixel centres sit at `i·SUBPIXELS + HALF_PIXEL`.
pub(crate) const HALF_PIXEL: i64 = SUBPIXELS / 2;

/// The largest render target side, in pixels.
pub const MAX_TARGET_SIZE: u32 = 16384;

/// How far outside the viewport (in pixels, on every side) vertices may lie before a triangle is
/// clipped in x or y. Within it, triangles are rasterized unclipped, exactly; beyond it they are
/// clipped to it in homogeneous space. With [`MAX_TARGET_SIZE`] this keeps every snapped coordinate
/// below `2^23` grid units in magnitude, so edge-function products stay far inside `i64`.
pub const GUARD_BAND: u32 = 8192;

/// [`SUBPIXELS`] as an f64.
#[expect(clippy::cast_precision_loss, reason = "256 is exact")]
pub(crate) const SUBPIXELS_F64: f64 = SUBPIXELS as f64;

/// A window coordinate snapped to the grid; `|x| < 2^23` for coordinates inside the guard band.
#[must_use]
pub(crate) fn snap(window: f64) -> i32 {
    snapped((window * SUBPIXELS_F64).round_ties_even())
}

/// A window coordinate already scaled to grid units and rounded ([`snap`]'s last step), as an
/// integer.
#[must_use]
#[inline(always)]
pub(crate) fn snapped(grid: f64) -> i32 {
    debug_assert!(
        grid.abs() < f64::from(1u32 << 24),
        "{} outside the guard band",
        grid / SUBPIXELS_F64
    );
    #[expect(
        clippy::cast_possible_truncation,
        reason = "inside the guard band |grid| < 2^24, which i32 holds exactly"
    )]
    let snapped = grid as i32;
    snapped
}

/// The first pixel index whose centre is at or right of the grid coordinate `x`:
/// `ceil((x − ½·SUBPIXELS)/SUBPIXELS)`, by an arithmetic shift (an exact floor).
#[must_use]
pub(crate) fn first_centre_at_or_after(x: i64) -> i64 {
    (x - HALF_PIXEL + SUBPIXELS - 1) >> SUBPIXEL_BITS
}

/// The last pixel index whose centre is at or left of the grid coordinate `x`:
/// `floor((x − ½·SUBPIXELS)/SUBPIXELS)`.
#[must_use]
pub(crate) fn last_centre_at_or_before(x: i64) -> i64 {
    (x - HALF_PIXEL) >> SUBPIXEL_BITS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_are_found_exactly() {
        // Pixel 0's centre is at grid 128.
        assert_eq!(first_centre_at_or_after(128), 0);
        assert_eq!(first_centre_at_or_after(129), 1);
        assert_eq!(first_centre_at_or_after(-128), -1);
        assert_eq!(first_centre_at_or_after(-127), 0);
        assert_eq!(last_centre_at_or_before(128), 0);
        assert_eq!(last_centre_at_or_before(127), -1);
        assert_eq!(last_centre_at_or_before(383), 0);
        assert_eq!(last_centre_at_or_before(384), 1);
    }

    #[test]
    fn snapping_rounds_to_the_nearest_grid_point() {
        assert_eq!(snap(0.5), 128);
        assert_eq!(snap(1.0 / 512.0), 0); // ties go to the even grid point
        assert_eq!(snap(3.0 / 512.0), 2);
        assert_eq!(snap(-1.0 / 512.0), 0);
        assert_eq!(snap(-3.0 / 512.0), -2);
        assert_eq!(snap(1.0 / 1024.0), 0);
        assert_eq!(snap(100.25), 25664);
    }
}
