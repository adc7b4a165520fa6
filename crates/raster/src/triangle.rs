//! Triangle setup: orientation and culling, integer edge functions with the fill rule folded in,
//! the pixel bounding box, and the depth plane.
//!
//! # Edge functions and the fill rule
//! With the triangle made counter-clockwise in window space (y up), the edge from `a` to `b` has
//! `E(P) = (b_x − a_x)(P_y − a_y) − (b_y − a_y)(P_x − a_x)`, positive on the triangle's side. It is
//! evaluated exactly, in `i64` grid units, at pixel centres. A centre is covered when every `E > 0`;
//! a centre exactly on an edge (`E = 0`) is covered only if the edge is a *left* edge (running down,
//! `b_y < a_y`) or a *bottom* edge (horizontal, running in +x). These are GL's window coordinates
//! with row 0 at the bottom; stored with row 0 first, as GL stores framebuffers, this is the
//! "top-left" rule of D3D and of Mesa's llvmpipe rendering into a framebuffer object. Two triangles
//! sharing an edge see it with opposite directions, so a centre on it is covered by exactly one of
//! them. The `≥ 0`/`> 0` distinction is folded into a constant: `E − (included ? 0 : 1) ≥ 0`.
//!
//! # Depth
//! Coverage uses the snapped vertices; depth does not. A pixel's depth is the plane through the
//! vertices' *unsnapped* window positions and their depths, evaluated at the pixel centre, as GL
//! defines it (interpolating from the snapped positions put it off the exact plane by up to half a
//! grid unit times the plane's gradient). Only slivers so thin that the unsnapped plane would carry
//! the centres they cover far beyond their vertices' depths take the plane through the snapped
//! positions ([`MAX_DEPTH_EXTRAPOLATION`]).
//! Either way the depth is evaluated as `row_depth(j) + column_depth(i)` from a reference point on
//! the grid, with exact integer offsets, so it is a function of the triangle and the pixel alone:
//! every path that draws a pixel (blocks, narrow boxes, early fragments) gives it the same bits.

use crate::fixed::{HALF_PIXEL, SUBPIXELS, first_centre_at_or_after, last_centre_at_or_before};
use crate::vertex::WindowVertex;

/// Which faces are discarded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CullMode {
    /// Draw every non-degenerate triangle.
    #[default]
    None,
    /// Discard back faces: clockwise in window space (y up), GL's default front face being CCW.
    Back,
    /// Discard front faces (counter-clockwise in window space).
    Front,
}

/// What setup decided about a triangle before rasterizing it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// Zero area in grid units: never drawn.
    Degenerate,
    /// Discarded by the cull mode.
    Culled,
    /// Its bounding box holds no pixel centre of the target.
    Empty,
    /// To be rasterized over the given pixel bounding box (inclusive); with twice its signed area in
    /// grid units², which the depth plane takes instead of computing it again.
    Draw(PixelBox, i64),
}

/// An inclusive rectangle of pixel indices.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PixelBox {
    pub(crate) min_i: i64,
    pub(crate) max_i: i64,
    pub(crate) min_j: i64,
    pub(crate) max_j: i64,
}

/// Twice the signed area in grid units², positive for counter-clockwise (y up).
#[inline]
fn doubled_area(v: &[WindowVertex; 3]) -> i64 {
    let (x0, y0) = (i64::from(v[0].x), i64::from(v[0].y));
    (i64::from(v[1].x) - x0) * (i64::from(v[2].y) - y0)
        - (i64::from(v[2].x) - x0) * (i64::from(v[1].y) - y0)
}

/// Orientation, culling and the pixel bounding box clipped to a `width × height` target.
#[inline]
pub(crate) fn classify(v: &[WindowVertex; 3], cull: CullMode, width: i64, height: i64) -> Verdict {
    let area = doubled_area(v);
    if area == 0 {
        return Verdict::Degenerate;
    }
    match cull {
        CullMode::Back if area < 0 => return Verdict::Culled,
        CullMode::Front if area > 0 => return Verdict::Culled,
        _ => {}
    }
    let (min_x, max_x) = min_max(v[0].x, v[1].x, v[2].x);
    let (min_y, max_y) = min_max(v[0].y, v[1].y, v[2].y);
    let b = PixelBox {
        min_i: first_centre_at_or_after(min_x).max(0),
        max_i: last_centre_at_or_before(max_x).min(width - 1),
        min_j: first_centre_at_or_after(min_y).max(0),
        max_j: last_centre_at_or_before(max_y).min(height - 1),
    };
    if b.min_i > b.max_i || b.min_j > b.max_j {
        Verdict::Empty
    } else {
        Verdict::Draw(b, area)
    }
}

#[inline]
fn min_max(a: i32, b: i32, c: i32) -> (i64, i64) {
    (i64::from(a.min(b).min(c)), i64::from(a.max(b).max(c)))
}

/// One edge function at pixel centres: `E(i, j) = step_i·i + step_j·j + offset`, covered when ≥ 0
/// (the fill rule is in `offset`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Edge {
    pub(crate) step_i: i64,
    pub(crate) step_j: i64,
    pub(crate) offset: i64,
}

impl Edge {
    fn new(a: WindowVertex, b: WindowVertex) -> Self {
        let (ax, ay) = (i64::from(a.x), i64::from(a.y));
        let (dx, dy) = (i64::from(b.x) - ax, i64::from(b.y) - ay);
        // Bitwise, not short-circuit: the sign of dy is as good as random, and `||` compiled to
        // a branch on it, which mispredicted often (see the commit introducing this line).
        let included = (dy < 0) | ((dy == 0) & (dx > 0));
        Self {
            step_i: -dy * SUBPIXELS,
            step_j: dx * SUBPIXELS,
            offset: dx * (HALF_PIXEL - ay) - dy * (HALF_PIXEL - ax) - i64::from(!included),
        }
    }

    /// The value at pixel `(i, j)`.
    #[inline]
    pub(crate) fn at(&self, i: i64, j: i64) -> i64 {
        self.step_i * i + self.step_j * j + self.offset
    }
}

/// The edge functions of a triangle, given its doubled signed area (non-zero): those of its
/// vertices in counter-clockwise order (y up), `v[0]` first.
#[inline]
pub(crate) fn edges(v: &[WindowVertex; 3], area: i64) -> [Edge; 3] {
    debug_assert_eq!(area, doubled_area(v));
    debug_assert_ne!(area, 0);
    let [a, b, c] = if area > 0 {
        [v[0], v[1], v[2]]
    } else {
        [v[0], v[2], v[1]]
    };
    [Edge::new(a, b), Edge::new(b, c), Edge::new(c, a)]
}

/// The depth gradient `(dz/dx, dz/dy)` per grid unit of the plane through the *snapped* positions
/// of a triangle, from its snapped edge vectors from the first vertex `[b_x, b_y, c_x, c_y]`, the
/// depth differences `b_z`, `c_z` and its doubled signed area `b_x·c_y − c_x·b_y` (non-zero): for
/// the slivers [`MAX_DEPTH_EXTRAPOLATION`] describes.
#[inline(always)]
fn snapped_gradient(deltas: [i32; 4], bz: f64, cz: f64, area: i64) -> (f64, f64) {
    #[expect(
        clippy::cast_precision_loss,
        reason = "a doubled area below 2^49 grid units², exact in f64"
    )]
    let inverse_area = 1.0 / area as f64;
    // Grid deltas are below 2^25 in magnitude: exact in f64.
    let [bx, by, cx, cy] = deltas.map(f64::from);
    (
        (bz * cy - cz * by) * inverse_area,
        (cz * bx - bz * cx) * inverse_area,
    )
}

/// How far beyond its vertices' depths the plane through the unsnapped vertices may carry a
/// covered pixel centre, in window depth, before [`DepthPlane::new`] takes the plane through the
/// snapped vertices instead.
///
/// Covered centres lie inside the *snapped* triangle, whose vertices are at most half a grid unit
/// (per axis) from the unsnapped ones. So a covered centre is `Q + d` with `Q` in the unsnapped
/// triangle and `|d|∞ ≤ ½`, and the unsnapped plane's depth there differs from its depth at `Q`,
/// which lies between the vertices' depths, by at most `½·(|∂z/∂x| + |∂z/∂y|)` (per grid unit).
/// The unsnapped plane is used when that bound is at most this. With vertex depths in `[0, 1]`,
/// only slivers exceed it: `|∂z/∂x| + |∂z/∂y| > 1/32` per grid unit needs the triangle to be
/// narrower than `32·√2` grid units (a sixth of a pixel) across its depth gradient. A sliver that
/// snapping turned over, or whose unsnapped area vanishes (an infinite or NaN gradient), could carry
/// its centres' depths arbitrarily far from its vertices'; the snapped plane keeps every covered
/// centre within them. On the bunny's 2048² light pass, 6 of 87 518 triangle setups fall back.
const MAX_DEPTH_EXTRAPOLATION: f64 = 1.0 / 64.0;

/// Window depth as a linear function of the window position (GL interpolates z linearly in
/// screen space), relative to the first vertex so that nearby pixels keep full precision.
///
/// The plane is the one through the *unsnapped* window positions (see [`MAX_DEPTH_EXTRAPOLATION`]
/// for the slivers that take the snapped positions instead): GL defines depth by the primitive's
/// vertices, and snapping them to the 1/256-pixel grid, which coverage needs, would tilt and shift
/// the plane by up to half a grid unit times its gradient. It is written relative to the first
/// vertex's *snapped* position, with the depth the plane has there (not the vertex's own depth), so
/// that every pixel centre's offset from the reference is an exact integer in grid units (see
/// [`Self::column_depths`] for why that matters) while the reference stays within half a grid unit
/// of the triangle, where the plane is known to full precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DepthPlane {
    /// The reference point: the first vertex's grid coordinates, and the plane's depth there.
    origin_x: i64,
    origin_y: i64,
    origin_z: f64,
    /// Depth change per grid unit in x and y.
    dz_dx: f64,
    dz_dy: f64,
}

impl DepthPlane {
    /// The plane through a triangle, given its snapped doubled signed area (non-zero). The plane
    /// does not depend on the order of the vertices beyond the first, the reference: `[a, b, c]` and
    /// `[a, c, b]` give the same bits (every difference and product only changes sign).
    #[inline]
    pub(crate) fn new(v: &[WindowVertex; 3], area: i64) -> Self {
        let [a, b, c] = *v;
        let (bz, cz) = (b.z - a.z, c.z - a.z);
        let (origin_x, origin_y) = (i64::from(a.x), i64::from(a.y));
        // Unsnapped grid coordinates are below 2^24 in magnitude: their differences are within
        // 2^-28 grid units of the exact ones.
        let (bx, by) = (b.unsnapped_x - a.unsnapped_x, b.unsnapped_y - a.unsnapped_y);
        let (cx, cy) = (c.unsnapped_x - a.unsnapped_x, c.unsnapped_y - a.unsnapped_y);
        let inverse_area = 1.0 / (bx * cy - cx * by);
        let (dz_dx, dz_dy) = (
            (bz * cy - cz * by) * inverse_area,
            (cz * bx - bz * cx) * inverse_area,
        );
        // False for an infinite or NaN gradient (a vanishing unsnapped area) too.
        let extrapolation_bounded = dz_dx.abs() + dz_dy.abs() <= 2.0 * MAX_DEPTH_EXTRAPOLATION;
        if !extrapolation_bounded {
            let snapped_deltas = [b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y];
            let (dz_dx, dz_dy) = snapped_gradient(snapped_deltas, bz, cz, area);
            return Self {
                origin_x,
                origin_y,
                origin_z: a.z,
                dz_dx,
                dz_dy,
            };
        }
        // From the unsnapped vertex to its snapped position: at most half a grid unit, and exact
        // (a float minus its nearest integer).
        let (to_snapped_x, to_snapped_y) = (
            f64::from(a.x) - a.unsnapped_x,
            f64::from(a.y) - a.unsnapped_y,
        );
        Self {
            origin_x,
            origin_y,
            origin_z: a.z + (dz_dx * to_snapped_x + dz_dy * to_snapped_y),
            dz_dx,
            dz_dy,
        }
    }

    /// The part of the depth that depends on the row: `z0 + dz_dy·y_offset(j)`, with `y_offset` the
    /// exact grid distance from the reference point to row `j`'s centres.
    #[inline(always)]
    pub(crate) fn row_depth(&self, j: i64) -> f64 {
        self.origin_z + self.dz_dy * (j * SUBPIXELS + HALF_PIXEL - self.origin_y) as f64
    }

    /// The part of the depth that depends on the column, `dz_dx·x_offset`, for the eight columns
    /// from `i`, `x_offset` being the exact grid distance from the reference point to the column's
    /// centres. A pixel's depth is `row_depth(j) + column_depths(..)[k]`, which depends on the
    /// triangle alone, never on the tile. The offsets of the eight columns are formed by adding
    /// multiples of `SUBPIXELS` to the first in f64, which is exact (integers below 2^53), so they
    /// are the same numbers however a row is split into blocks.
    #[inline(always)]
    pub(crate) fn column_depths(&self, i: i64) -> [f64; 8] {
        const STEPS: [f64; 8] = [0.0, 256.0, 512.0, 768.0, 1024.0, 1280.0, 1536.0, 1792.0];
        let first = (i * SUBPIXELS + HALF_PIXEL - self.origin_x) as f64;
        let mut depths = [0.0; 8];
        for k in 0..8 {
            depths[k] = self.dz_dx * (first + STEPS[k]);
        }
        depths
    }

    /// The column part of the depth of column `i` alone: the same number as its lane in
    /// [`Self::column_depths`] (the same product of the same exact offset).
    #[inline(always)]
    pub(crate) fn column_depth(&self, i: i64) -> f64 {
        self.dz_dx * (i * SUBPIXELS + HALF_PIXEL - self.origin_x) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plane through the snapped positions, as [`DepthPlane::new`] builds it for slivers.
    fn snapped_plane(v: &[WindowVertex; 3], area: i64) -> DepthPlane {
        let [a, b, c] = *v;
        let deltas = [b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y];
        let (dz_dx, dz_dy) = snapped_gradient(deltas, b.z - a.z, c.z - a.z, area);
        DepthPlane {
            origin_x: i64::from(a.x),
            origin_y: i64::from(a.y),
            origin_z: a.z,
            dz_dx,
            dz_dy,
        }
    }

    /// The plane's depth at window position `(x, y)` in grid units.
    fn depth_at(plane: &DepthPlane, x: f64, y: f64) -> f64 {
        #[expect(clippy::cast_precision_loss, reason = "grid coordinates, exact in f64")]
        let (origin_x, origin_y) = (plane.origin_x as f64, plane.origin_y as f64);
        plane.origin_z + plane.dz_dx * (x - origin_x) + plane.dz_dy * (y - origin_y)
    }

    /// A window vertex at unsnapped grid position `(x, y)`, snapped as the vertex stage snaps.
    fn vertex(x: f64, y: f64, z: f64) -> WindowVertex {
        WindowVertex {
            x: crate::fixed::snapped(x.round_ties_even()),
            y: crate::fixed::snapped(y.round_ties_even()),
            z,
            unsnapped_x: x,
            unsnapped_y: y,
        }
    }

    /// The plane passes through the unsnapped vertices at their depths (to rounding), for
    /// triangles of every size and shape off the grid, and does not depend on their winding; for
    /// vertices on the grid it is the plane through the snapped ones, bit for bit (the same
    /// numbers in the same operations).
    #[test]
    fn the_plane_goes_through_the_unsnapped_vertices() {
        let mut random = crate::test_random::XorShift::new(0x51ab_7e3d_00c4_9a61);
        let (mut unsnapped, mut on_grid) = (0, 0);
        for k in 0..20_000 {
            let scale = [300.0, 5000.0, 2e6][k % 3];
            let mut coordinate = || 4096.0 * 256.0 + scale * (random.fraction() - 0.5);
            let mut v: [WindowVertex; 3] =
                std::array::from_fn(|_| vertex(coordinate(), coordinate(), 0.0));
            for corner in &mut v {
                corner.z = random.fraction();
            }
            if k % 2 == 1 {
                v = v.map(|c| vertex(f64::from(c.x), f64::from(c.y), c.z));
            }
            let area = doubled_area(&v);
            if area == 0 {
                continue;
            }
            let plane = DepthPlane::new(&v, area);
            assert_eq!(plane, DepthPlane::new(&[v[0], v[2], v[1]], -area), "{v:?}");
            if k % 2 == 1 {
                assert_eq!(plane, snapped_plane(&v, area), "on the grid: {v:?}");
                on_grid += 1;
            } else if plane != snapped_plane(&v, area) {
                unsnapped += 1;
                for c in v {
                    let z = depth_at(&plane, c.unsnapped_x, c.unsnapped_y);
                    assert!((z - c.z).abs() < 1e-12, "{z} vs {} of {v:?}", c.z);
                }
            }
        }
        assert!(
            unsnapped > 9_000 && on_grid > 9_000,
            "{unsnapped} {on_grid}"
        );
    }

    /// A sliver that snapping turns over, or whose unsnapped area vanishes, takes the snapped
    /// plane, which keeps its depths finite and its vertices' depths at the snapped vertices; of
    /// two triangles whose unsnapped gradients lie just below and just above the threshold, the
    /// first takes the unsnapped plane and the second the snapped one.
    #[test]
    fn slivers_take_the_snapped_plane() {
        // Snapped: (1000, 1000), (3560, 1000), (6120, 1001), counter-clockwise.
        let sliver = |last_y: f64| {
            [
                vertex(1000.0, 1000.3, 0.2),
                vertex(3560.0, 1000.45, 0.9),
                vertex(6120.0, 1000.0 + last_y, 0.3),
            ]
        };
        // Unsnapped doubled areas −128 (turned over), 2560e-6 (vanishing).
        for last_y in [0.55, 0.6 + 1e-6] {
            let v = sliver(last_y);
            let area = doubled_area(&v);
            assert!(area > 0, "counter-clockwise when snapped");
            let plane = DepthPlane::new(&v, area);
            assert_eq!(plane, snapped_plane(&v, area), "{last_y}");
            for c in v {
                let z = depth_at(&plane, f64::from(c.x), f64::from(c.y));
                assert!((z - c.z).abs() < 1e-12, "{z} vs {}", c.z);
            }
        }
        // Depth changing by `factor·32·MAX_DEPTH_EXTRAPOLATION` over 16 grid units in y, none in
        // x: a gradient `|∂z/∂y|` of `factor` times `2·MAX_DEPTH_EXTRAPOLATION`, the threshold.
        for (factor, unsnapped) in [(0.999, true), (1.001, false)] {
            let v = [
                vertex(1000.0, 1000.3, 0.1),
                vertex(3560.0, 1000.3, 0.1),
                vertex(
                    1000.0,
                    1016.3,
                    0.1 + factor * 32.0 * MAX_DEPTH_EXTRAPOLATION,
                ),
            ];
            let area = doubled_area(&v);
            let snapped = DepthPlane::new(&v, area) == snapped_plane(&v, area);
            assert_eq!(snapped, !unsnapped, "factor {factor}");
        }
    }
}
