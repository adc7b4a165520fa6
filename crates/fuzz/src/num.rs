//! Numbers and vectors decoded from fuzz bytes, biased toward the values that break geometry code:
//! NaN, ±∞, ±0, the extremes of f64, subnormals, powers of two near the rasterizer's limits, and
//! plain small values so that most inputs still reach past the finiteness checks.

use arbitrary::Arbitrary;
use glam::{DMat4, DVec2, DVec3, DVec4};

/// The values tried by [`Num::Special`].
const SPECIALS: [f64; 24] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    5e-324,
    -5e-324,
    f64::EPSILON,
    1e-300,
    1e300,
    // The rasterizer's guard band and its fixed-point limits, in pixels of a small target.
    8192.0,
    1_073_741_824.0,
    2_147_483_648.0,
    9_007_199_254_740_992.0,
    1.0 - f64::EPSILON / 2.0,
    1.0 + f64::EPSILON,
    -8192.5,
];

/// One f64.
#[derive(Clone, Copy, Debug, Arbitrary)]
pub(crate) enum Num {
    /// `k / 8`: small exact values, coincident points and grid-aligned edges.
    Small(i8),
    /// A value in `[-2, 2]` on a fine grid.
    Unit(i16),
    /// `m · 2^e`: any magnitude from subnormal to overflow.
    Scaled(i32, i16),
    /// One of [`SPECIALS`].
    Special(u8),
    /// Any bit pattern.
    Bits(u64),
}

impl Num {
    /// The value.
    pub(crate) fn get(self) -> f64 {
        match self {
            Self::Small(k) => f64::from(k) / 8.0,
            Self::Unit(k) => f64::from(k) / 16384.0,
            Self::Scaled(m, e) => f64::from(m) * 2f64.powi(i32::from(e % 1100)),
            Self::Special(k) => SPECIALS[usize::from(k) % SPECIALS.len()],
            Self::Bits(bits) => f64::from_bits(bits),
        }
    }
}

/// A 2-D vector.
#[derive(Clone, Copy, Debug, Arbitrary)]
pub(crate) struct V2(Num, Num);

impl V2 {
    /// The vector.
    pub(crate) fn get(self) -> DVec2 {
        DVec2::new(self.0.get(), self.1.get())
    }
}

/// A 3-D vector.
#[derive(Clone, Copy, Debug, Arbitrary)]
pub(crate) struct V3(Num, Num, Num);

impl V3 {
    /// The vector.
    pub(crate) fn get(self) -> DVec3 {
        DVec3::new(self.0.get(), self.1.get(), self.2.get())
    }
}

/// A 4×4 matrix: either sixteen arbitrary entries or a structured one (so that most inputs map
/// something onto the target).
#[derive(Clone, Copy, Debug, Arbitrary)]
pub(crate) enum Matrix {
    /// The identity.
    Identity,
    /// A scale and translation (an orthographic projection).
    ScaleTranslate(V3, V3),
    /// A GL perspective projection `(fov_y, aspect, near, far)` times a translation, written out so
    /// that no constructor's assertions stand between the numbers and the rasterizer.
    Perspective(Num, Num, Num, Num, V3),
    /// A perspective projection with its last row replaced.
    ProjectiveRow(Num, Num, Num, Num, V3),
    /// Sixteen entries, column by column.
    Raw([Num; 16]),
}

impl Matrix {
    /// The matrix.
    pub(crate) fn get(self) -> DMat4 {
        match self {
            Self::Identity => DMat4::IDENTITY,
            Self::ScaleTranslate(scale, translation) => {
                DMat4::from_translation(translation.get()) * DMat4::from_scale(scale.get())
            }
            Self::Perspective(fov, aspect, near, far, translation) => {
                perspective(fov.get(), aspect.get(), near.get(), far.get())
                    * DMat4::from_translation(translation.get())
            }
            Self::ProjectiveRow(a, b, c, d, translation) => {
                let mut m = DMat4::from_translation(translation.get());
                let row = DVec4::new(a.get(), b.get(), c.get(), d.get());
                m.x_axis.w = row.x;
                m.y_axis.w = row.y;
                m.z_axis.w = row.z;
                m.w_axis.w = row.w;
                m
            }
            Self::Raw(entries) => DMat4::from_cols_array(&entries.map(Num::get)),
        }
    }
}

/// GL's perspective matrix, without checks: any of the inputs may be zero, negative or non-finite.
fn perspective(fov_y: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    let depth = near - far;
    DMat4::from_cols(
        DVec4::new(f / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, f, 0.0, 0.0),
        DVec4::new(0.0, 0.0, (far + near) / depth, -1.0),
        DVec4::new(0.0, 0.0, 2.0 * far * near / depth, 0.0),
    )
}
