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

/// The vertices in counter-clockwise order (y up), given the doubled signed area (non-zero).
#[inline]
pub(crate) fn counter_clockwise(v: &[WindowVertex; 3], area: i64) -> [WindowVertex; 3] {
    debug_assert_eq!(area, doubled_area(v));
    debug_assert_ne!(area, 0);
    if area > 0 { *v } else { [v[0], v[2], v[1]] }
}

/// The edge functions of a counter-clockwise triangle.
#[inline]
pub(crate) fn edges(v: &[WindowVertex; 3]) -> [Edge; 3] {
    [
        Edge::new(v[0], v[1]),
        Edge::new(v[1], v[2]),
        Edge::new(v[2], v[0]),
    ]
}

/// Window depth as a linear function of the window position (GL interpolates z linearly in
/// screen space), relative to the first vertex so that nearby pixels keep full precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DepthPlane {
    /// The reference vertex's grid coordinates and depth.
    origin_x: i64,
    origin_y: i64,
    origin_z: f64,
    /// Depth change per grid unit in x and y.
    dz_dx: f64,
    dz_dy: f64,
}

impl DepthPlane {
    /// The plane through a counter-clockwise triangle, given its doubled area (non-zero; either
    /// sign, its magnitude is used).
    #[inline]
    pub(crate) fn new(v: &[WindowVertex; 3], area: i64) -> Self {
        let [a, b, c] = *v;
        #[expect(
            clippy::cast_precision_loss,
            reason = "a doubled area below 2^49 grid units², exact in f64"
        )]
        let area = area.abs() as f64;
        let (ax, ay) = (i64::from(a.x), i64::from(a.y));
        // Grid deltas are below 2^25 in magnitude: exact in f64.
        let (bx, by) = (f64::from(b.x - a.x), f64::from(b.y - a.y));
        let (cx, cy) = (f64::from(c.x - a.x), f64::from(c.y - a.y));
        let (bz, cz) = (b.z - a.z, c.z - a.z);
        let inverse_area = 1.0 / area;
        Self {
            origin_x: ax,
            origin_y: ay,
            origin_z: a.z,
            dz_dx: (bz * cy - cz * by) * inverse_area,
            dz_dy: (cz * bx - bz * cx) * inverse_area,
        }
    }

    /// The part of the depth that depends on the row: `z0 + dz_dy·y_offset(j)`, with `y_offset` the
    /// exact grid distance from the reference vertex to row `j`'s centres.
    #[inline(always)]
    pub(crate) fn row_depth(&self, j: i64) -> f64 {
        self.origin_z + self.dz_dy * (j * SUBPIXELS + HALF_PIXEL - self.origin_y) as f64
    }

    /// The part of the depth that depends on the column, `dz_dx·x_offset`, for the eight columns
    /// from `i`, `x_offset` being the exact grid distance from the reference vertex to the column's
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
