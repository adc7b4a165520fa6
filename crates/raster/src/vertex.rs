//! The vertex stage: world position → clip space (f64, fixed operation order), the clip test, and
//! for vertices inside the clip volume the window position snapped to the fixed-point grid.
//!
//! Clip space is GL's: a point is inside when `−w ≤ z ≤ w` (near and far planes) and, for x and y,
//! inside the guard band `|x| ≤ g_x·w`, `|y| ≤ g_y·w` with `g = 1 + 2·GUARD_BAND/size`. Window
//! coordinates are `x_w = (x/w)·W/2 + W/2`, `y_w = (y/w)·H/2 + H/2` (y up, GL) and depth
//! `z_w = (z/w)/2 + 1/2`, the quotients formed as products with `1/w`.

use glam::{DMat4, DVec3, DVec4};

use crate::fixed::{GUARD_BAND, snap};

/// Bits of a vertex's clip code: which planes of the clip volume it lies outside of.
pub(crate) mod code {
    /// Left of the guard band.
    pub(crate) const LEFT: u8 = 1;
    /// Right of the guard band.
    pub(crate) const RIGHT: u8 = 2;
    /// Below the guard band.
    pub(crate) const BOTTOM: u8 = 4;
    /// Above the guard band.
    pub(crate) const TOP: u8 = 8;
    /// In front of the near plane (`z < −w`), which includes points behind the eye.
    pub(crate) const NEAR: u8 = 16;
    /// Beyond the far plane (`z > w`).
    pub(crate) const FAR: u8 = 32;
    /// A coordinate is NaN or infinite: the vertex cannot be drawn at all.
    pub(crate) const NOT_FINITE: u8 = 128;
}

/// A vertex inside the clip volume, in window space: x and y on the fixed-point grid, depth in f64.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct WindowVertex {
    /// x in grid units.
    pub(crate) x: i32,
    /// y in grid units.
    pub(crate) y: i32,
    /// Window depth in `[0, 1]`.
    pub(crate) z: f64,
}

/// The viewport: the target's size and the guard-band factors derived from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Viewport {
    half_width: f64,
    half_height: f64,
    guard_x: f64,
    guard_y: f64,
}

impl Viewport {
    pub(crate) fn new(width: u32, height: u32) -> Self {
        let (w, h) = (f64::from(width), f64::from(height));
        Self {
            half_width: w / 2.0,
            half_height: h / 2.0,
            guard_x: 1.0 + 2.0 * f64::from(GUARD_BAND) / w,
            guard_y: 1.0 + 2.0 * f64::from(GUARD_BAND) / h,
        }
    }

    /// The guard-band factors `(g_x, g_y)`.
    pub(crate) fn guard(&self) -> (f64, f64) {
        (self.guard_x, self.guard_y)
    }

    /// The clip code of a clip-space point.
    pub(crate) fn clip_code(&self, c: DVec4) -> u8 {
        if !(c.x.is_finite() && c.y.is_finite() && c.z.is_finite() && c.w.is_finite()) {
            return code::NOT_FINITE;
        }
        let (gx, gy) = (self.guard_x * c.w, self.guard_y * c.w);
        let mut bits = 0;
        if c.x < -gx {
            bits |= code::LEFT;
        }
        if c.x > gx {
            bits |= code::RIGHT;
        }
        if c.y < -gy {
            bits |= code::BOTTOM;
        }
        if c.y > gy {
            bits |= code::TOP;
        }
        // w ≤ 0 is never inside (for a GL projection it means behind the eye, where z < −w holds
        // anyway); testing it keeps a degenerate (0, 0, 0, 0) from reaching the divide.
        if c.z < -c.w || c.w <= 0.0 {
            bits |= code::NEAR;
        }
        if c.z > c.w {
            bits |= code::FAR;
        }
        bits
    }

    /// The window vertex of a clip-space point inside the clip volume (`w > 0`).
    pub(crate) fn window_vertex(&self, c: DVec4) -> WindowVertex {
        // One division and three products instead of three divisions: each coordinate is then
        // within an ulp of the correctly rounded quotient (1e-13 pixel), far below the 1/256-pixel
        // grid it is snapped to, and it is the same on every machine.
        let inverse_w = 1.0 / c.w;
        let x = (c.x * inverse_w) * self.half_width + self.half_width;
        let y = (c.y * inverse_w) * self.half_height + self.half_height;
        let z = ((c.z * inverse_w) * 0.5 + 0.5).clamp(0.0, 1.0);
        WindowVertex {
            x: snap(x),
            y: snap(y),
            z,
        }
    }
}

/// `M·(p, 1)` in f64 with a fixed order of operations (each row summed left to right, no fused
/// multiply-add), so the result does not depend on the target's SIMD or on glam's implementation.
#[inline]
pub(crate) fn transform(m: &DMat4, p: DVec3) -> DVec4 {
    let (c0, c1, c2, c3) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
    DVec4::new(
        c0.x * p.x + c1.x * p.y + c2.x * p.z + c3.x,
        c0.y * p.x + c1.y * p.y + c2.y * p.z + c3.y,
        c0.z * p.x + c1.z * p.y + c2.z * p.z + c3.z,
        c0.w * p.x + c1.w * p.y + c2.w * p.z + c3.w,
    )
}
