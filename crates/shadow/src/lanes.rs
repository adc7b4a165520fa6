//! Four 3-vectors side by side in `wide::f64x4` lanes, with glam's `DVec3` and `DMat4` operations
//! lane by lane, each in glam's order of operations: the vocabulary of the blocks that compute a
//! per-pixel function for four pixels at once and must give each pixel's bits
//! (docs/CONVENTIONS.md, "Vector lanes"; `lookup::block` here, `aliasing::block` in the analysis
//! crate). Neither Rust nor `wide` contracts a product and a sum into a fused multiply-add.

use glam::{DMat4, DVec3};
use wide::f64x4;

/// Pixels per block.
pub const LANES: usize = 4;

/// Four 3-vectors, coordinate by coordinate: lane `k` of `x`, `y`, `z` is vector `k`.
#[derive(Clone, Copy, Debug)]
pub struct Vectors {
    /// The vectors' x coordinates.
    pub x: f64x4,
    /// The vectors' y coordinates.
    pub y: f64x4,
    /// The vectors' z coordinates.
    pub z: f64x4,
}

impl Vectors {
    /// The four vectors `v`, lane `k` holding `v[k]`.
    #[must_use]
    pub fn of(v: &[DVec3; LANES]) -> Self {
        Self {
            x: f64x4::new(v.map(|v| v.x)),
            y: f64x4::new(v.map(|v| v.y)),
            z: f64x4::new(v.map(|v| v.z)),
        }
    }

    /// `v` in every lane.
    #[must_use]
    pub fn splat(v: DVec3) -> Self {
        Self {
            x: f64x4::splat(v.x),
            y: f64x4::splat(v.y),
            z: f64x4::splat(v.z),
        }
    }

    /// `DVec3::dot`: `(x·x′ + y·y′) + z·z′`.
    #[inline(always)]
    #[must_use]
    pub fn dot(self, other: Self) -> f64x4 {
        (self.x * other.x + self.y * other.y) + self.z * other.z
    }

    /// `DVec3::length`: the square root of [`Self::dot`] with itself.
    #[inline(always)]
    #[must_use]
    pub fn length(self) -> f64x4 {
        self.dot(self).sqrt()
    }

    /// `self − other`.
    #[inline(always)]
    #[must_use]
    pub fn minus(self, other: Self) -> Self {
        Self {
            x: self.x - other.x,
            y: self.y - other.y,
            z: self.z - other.z,
        }
    }

    /// `self + other`.
    #[inline(always)]
    #[must_use]
    pub fn plus(self, other: Self) -> Self {
        Self {
            x: self.x + other.x,
            y: self.y + other.y,
            z: self.z + other.z,
        }
    }

    /// `self · s`, each vector by its lane of `s`.
    #[inline(always)]
    #[must_use]
    pub fn times(self, s: f64x4) -> Self {
        Self {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// `DVec3::cross`: `(y·z′ − y′·z, z·x′ − z′·x, x·y′ − x′·y)`.
    #[inline(always)]
    #[must_use]
    pub fn cross(self, other: Self) -> Self {
        Self {
            x: self.y * other.z - other.y * self.z,
            y: self.z * other.x - other.z * self.x,
            z: self.x * other.y - other.x * self.y,
        }
    }

    /// `m · (self, w)`, glam's `DMat4 · DVec4`: the columns times the coordinates, summed from `x`
    /// to `w` (`w` multiplies the last column and is added even where it is 0 or 1, as glam does).
    #[inline(always)]
    #[must_use]
    pub fn transformed(self, m: &DMat4, w: f64) -> [f64x4; 4] {
        let row = |i: usize| {
            let column = f64x4::splat;
            ((column(m.x_axis[i]) * self.x + column(m.y_axis[i]) * self.y)
                + column(m.z_axis[i]) * self.z)
                + column(m.w_axis[i]) * f64x4::splat(w)
        };
        [row(0), row(1), row(2), row(3)]
    }
}
