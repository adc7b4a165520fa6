//! The vertex stage: world position → clip space (f64, fixed operation order), the clip test, and
//! for vertices inside the clip volume the window position, both snapped to the fixed-point grid
//! and as it was before snapping.
//!
//! Clip space is GL's: a point is inside when `−w ≤ z ≤ w` (near and far planes) and, for x and y,
//! inside the guard band `|x| ≤ g_x·w`, `|y| ≤ g_y·w` with `g = 1 + 2·GUARD_BAND/size`. Window
//! coordinates are `x_w = (x/w)·W/2 + W/2`, `y_w = (y/w)·H/2 + H/2` (y up, GL) and depth
//! `z_w = (z/w)/2 + 1/2`, the quotients formed as products with `1/w`.
//!
//! A window vertex keeps both positions because they serve different ends: coverage is decided on
//! the snapped grid (exact, so shared edges stay watertight), while depth is interpolated from the
//! unsnapped position, as GL defines it. Interpolating it from the snapped one moved the whole plane
//! by up to half a grid unit times its gradient: up to 6e-6 in window depth on the steep planes of
//! tests/raster/exact_depth.rs, and a wrong 16-bit value at two thirds of a grazing ground plane's
//! texels.

use glam::{DMat4, DVec3, DVec4};
use wide::{f64x4, i64x4};

use crate::fixed::{GUARD_BAND, SUBPIXELS_F64, snap, snapped};

/// The smallest clip-space w a vertex inside the clip volume has: the smallest normal f64, whose
/// reciprocal is finite. A vertex of smaller w (zero, negative, or subnormal — found by the raster
/// fuzzer: w = 1e-320 gave an infinite window position) is outside the near plane, and a clipped
/// polygon with one is dropped.
pub(crate) const MIN_W: f64 = f64::MIN_POSITIVE;

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

/// A vertex inside the clip volume, in window space: x and y on the fixed-point grid (for
/// coverage) and before snapping (for depth), depth in f64.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct WindowVertex {
    /// x in grid units, snapped: the nearest integer to `unsnapped_x`, ties to even.
    pub(crate) x: i32,
    /// y in grid units, snapped.
    pub(crate) y: i32,
    /// Window depth in `[0, 1]`.
    pub(crate) z: f64,
    /// x in grid units before snapping (the window x times [`crate::fixed::SUBPIXELS`], exactly).
    pub(crate) unsnapped_x: f64,
    /// y in grid units before snapping.
    pub(crate) unsnapped_y: f64,
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
        // w below MIN_W is never inside (for a GL projection w ≤ 0 means behind the eye, where
        // z < −w holds anyway); testing it keeps a degenerate (0, 0, 0, 0), and a w whose
        // reciprocal overflows, from reaching the divide.
        if c.z < -c.w || c.w < MIN_W {
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
            unsnapped_x: x * SUBPIXELS_F64,
            unsnapped_y: y * SUBPIXELS_F64,
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

/// The vertex stage for a run of vertices: `codes[k]` is the clip code of `positions[k]`
/// transformed by `m`, and where it is 0, `window[k]` its window vertex; elsewhere `window[k]` is
/// left as it is. The same numbers as [`transform`], [`Viewport::clip_code`] and
/// [`Viewport::window_vertex`] vertex by vertex, computed four vertices at a time in f64 lanes:
/// each lane performs the same IEEE operations in the same order (products and sums, no fused
/// multiply-add; one correctly rounded division; rounding ties to even), so the results are
/// bit-identical. Scalar, the stage took about 94 instructions per vertex and 10 % of the dragon
/// light pass's time on one thread.
pub(crate) fn transform_vertices(
    m: &DMat4,
    viewport: &Viewport,
    positions: &[DVec3],
    window: &mut [WindowVertex],
    codes: &mut [u8],
) {
    debug_assert!(positions.len() == window.len() && positions.len() == codes.len());
    let mut positions = positions.chunks_exact(4);
    let mut window = window.chunks_exact_mut(4);
    let mut codes = codes.chunks_exact_mut(4);
    for ((p, w), c) in (&mut positions).zip(&mut window).zip(&mut codes) {
        let (quad_codes, [x, y, z, unsnapped_x, unsnapped_y]) = viewport.quad(m, p);
        for k in 0..4 {
            c[k] = quad_codes[k];
            if c[k] == 0 {
                w[k] = WindowVertex {
                    x: snapped(x[k]),
                    y: snapped(y[k]),
                    z: z[k].clamp(0.0, 1.0),
                    unsnapped_x: unsnapped_x[k],
                    unsnapped_y: unsnapped_y[k],
                };
            }
        }
    }
    let tail = positions
        .remainder()
        .iter()
        .zip(window.into_remainder())
        .zip(codes.into_remainder());
    for ((p, w), c) in tail {
        let clip = transform(m, *p);
        *c = viewport.clip_code(clip);
        if *c == 0 {
            *w = viewport.window_vertex(clip);
        }
    }
}

impl Viewport {
    /// The clip codes of four points and, meaningful where the code is 0, their window x and y in
    /// grid units rounded to the grid (for [`snapped`]), their window depth before clamping, and
    /// their window x and y in grid units before rounding.
    #[inline(always)]
    fn quad(&self, m: &DMat4, p: &[DVec3]) -> ([u8; 4], [[f64; 4]; 5]) {
        let lanes = |f: fn(&DVec3) -> f64| f64x4::new([f(&p[0]), f(&p[1]), f(&p[2]), f(&p[3])]);
        let (px, py, pz) = (lanes(|p| p.x), lanes(|p| p.y), lanes(|p| p.z));
        // `transform`, lane-wise: each row summed left to right.
        let row = |a: f64, b: f64, c: f64, d: f64| {
            f64x4::splat(a) * px + f64x4::splat(b) * py + f64x4::splat(c) * pz + f64x4::splat(d)
        };
        let (c0, c1, c2, c3) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
        let x = row(c0.x, c1.x, c2.x, c3.x);
        let y = row(c0.y, c1.y, c2.y, c3.y);
        let z = row(c0.z, c1.z, c2.z, c3.z);
        let w = row(c0.w, c1.w, c2.w, c3.w);
        // `clip_code`, lane-wise: the comparisons as lane masks, each selecting its bit.
        let finite = x.is_finite() & y.is_finite() & z.is_finite() & w.is_finite();
        let (gx, gy) = (
            f64x4::splat(self.guard_x) * w,
            f64x4::splat(self.guard_y) * w,
        );
        let bit = |mask: f64x4, bit: u8| {
            wide::bytemuck::cast::<f64x4, i64x4>(mask) & i64x4::splat(i64::from(bit))
        };
        let bits = bit(x.simd_lt(-gx), code::LEFT)
            | bit(x.simd_gt(gx), code::RIGHT)
            | bit(y.simd_lt(-gy), code::BOTTOM)
            | bit(y.simd_gt(gy), code::TOP)
            | bit(z.simd_lt(-w) | w.simd_lt(f64x4::splat(MIN_W)), code::NEAR)
            | bit(z.simd_gt(w), code::FAR);
        let finite = wide::bytemuck::cast::<f64x4, i64x4>(finite);
        let not_finite = i64x4::splat(i64::from(code::NOT_FINITE));
        let codes = ((bits & finite) | (not_finite & !finite)).to_array();
        // `window_vertex`, lane-wise: garbage (never stored) in lanes outside the clip volume.
        let inverse_w = f64x4::ONE / w;
        let (half_width, half_height) = (
            f64x4::splat(self.half_width),
            f64x4::splat(self.half_height),
        );
        let grid = f64x4::splat(SUBPIXELS_F64);
        let unsnapped_x = ((x * inverse_w) * half_width + half_width) * grid;
        let unsnapped_y = ((y * inverse_w) * half_height + half_height) * grid;
        let wz = (z * inverse_w) * f64x4::HALF + f64x4::HALF;
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "a code is at most NOT_FINITE"
        )]
        let codes = codes.map(|c| c as u8);
        (
            codes,
            [
                unsnapped_x.round_ties_even().to_array(),
                unsnapped_y.round_ties_even().to_array(),
                wz.to_array(),
                unsnapped_x.to_array(),
                unsnapped_y.to_array(),
            ],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The four-lane vertex stage gives the same codes and window vertices (snapped and unsnapped)
    /// as the scalar functions, bit for bit, for points inside, on and outside every plane and the
    /// guard band, behind the eye, at `w = 0`, and with non-finite coordinates; and leaves the
    /// window vertices of points outside untouched.
    #[test]
    fn four_lanes_match_the_scalar_stage() {
        let mut random = crate::test_random::XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = move || random.fraction();
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
        ];
        let mut positions = Vec::new();
        for k in 0..20_000 {
            let scale = [1.0, 3.0, 50.0, 1e4][k % 4];
            let mut p = DVec3::new(
                (next() - 0.5) * scale,
                (next() - 0.5) * scale,
                (next() - 0.5) * scale,
            );
            if k % 97 == 0 {
                p.x = special[k / 97 % special.len()];
            }
            if k % 89 == 0 {
                p.z = special[k / 89 % special.len()];
            }
            positions.push(p);
        }
        // A GL perspective projection (45°-ish field of view, near 0.1, far 20) of a shifted
        // scene, and an orthographic one, column by column.
        let (f, aspect, near, far) = (2.0, 1.3, 0.1, 20.0);
        let perspective = DMat4::from_cols_array(&[
            f / aspect,
            0.0,
            0.0,
            0.0,
            0.0,
            f,
            0.0,
            0.0,
            0.0,
            0.0,
            (far + near) / (near - far),
            -1.0,
            0.0,
            0.0,
            2.0 * far * near / (near - far),
            0.0,
        ]) * DMat4::from_translation(DVec3::new(0.1, -0.2, -3.0));
        let orthographic = DMat4::from_scale(DVec3::new(1.0, 1.0, -0.5));
        // A matrix whose rows give w = 0 exactly for points on the plane x = 0.
        let mut flat = perspective;
        flat.x_axis.w = 1.0;
        flat.y_axis.w = 0.0;
        flat.z_axis.w = 0.0;
        flat.w_axis.w = 0.0;
        let sentinel = WindowVertex {
            x: 7,
            y: -7,
            z: 0.25,
            unsnapped_x: 7.25,
            unsnapped_y: -7.25,
        };
        let (mut seen, mut inside) = (0, 0);
        for m in [perspective, orthographic, flat] {
            for (width, height) in [(1024, 768), (2048, 2048), (3, 5)] {
                let viewport = Viewport::new(width, height);
                // Lengths that leave every tail length.
                for n in [positions.len(), positions.len() - 1, 6, 3] {
                    let mut window = vec![sentinel; n];
                    let mut codes = vec![0; n];
                    transform_vertices(&m, &viewport, &positions[..n], &mut window, &mut codes);
                    for (k, p) in positions[..n].iter().enumerate() {
                        let clip = transform(&m, *p);
                        let code = viewport.clip_code(clip);
                        assert_eq!(codes[k], code, "{p:?}");
                        seen |= code;
                        inside += usize::from(code == 0);
                        let expected = if code == 0 {
                            viewport.window_vertex(clip)
                        } else {
                            sentinel
                        };
                        assert_eq!(window[k].x, expected.x, "{p:?}");
                        assert_eq!(window[k].y, expected.y, "{p:?}");
                        assert_eq!(window[k].z.to_bits(), expected.z.to_bits(), "{p:?}");
                        let unsnapped =
                            |v: &WindowVertex| (v.unsnapped_x.to_bits(), v.unsnapped_y.to_bits());
                        assert_eq!(unsnapped(&window[k]), unsnapped(&expected), "{p:?}");
                    }
                }
            }
        }
        // Every bit of the clip code came up, and many points were inside.
        assert_eq!(seen, 0b1011_1111, "{seen:#b}");
        assert!(inside > 10_000, "{inside}");
    }
}
