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

    /// The four vectors, `[v₀, v₁, v₂, v₃]`: the inverse of [`Vectors::of`].
    #[must_use]
    pub fn vectors(self) -> [DVec3; LANES] {
        let [x, y, z] = [self.x, self.y, self.z].map(f64x4::to_array);
        std::array::from_fn(|k| DVec3::new(x[k], y[k], z[k]))
    }

    /// Lane by lane and coordinate by coordinate, the lesser: `DVec3::min` of each lane's vectors
    /// (a NaN coordinate of either is passed over, as `f64::min` passes it over).
    #[must_use]
    pub fn min(self, other: Self) -> Self {
        Self {
            x: self.x.min(other.x),
            y: self.y.min(other.y),
            z: self.z.min(other.z),
        }
    }

    /// Lane by lane and coordinate by coordinate, the greater: `DVec3::max` of each lane's vectors
    /// (a NaN coordinate of either is passed over).
    #[must_use]
    pub fn max(self, other: Self) -> Self {
        Self {
            x: self.x.max(other.x),
            y: self.y.max(other.y),
            z: self.z.max(other.z),
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

/// The points of four homogeneous points `h` (`[x, y, z, w]`, a lane each): `h.xyz / h.w`, lane by
/// lane, as `homogeneous::point_of` divides one. Where `w` is exactly 1 in every lane — an affine
/// mapping's points — nothing is divided, as `point_of` skips the division; otherwise every lane
/// is divided, also one whose `w` is 1: `x / 1 = x`, the same bits either way.
#[inline(always)]
#[must_use]
pub fn point_of(h: [f64x4; 4]) -> Vectors {
    let [x, y, z, w] = h;
    Vectors {
        x: quotient(x, w),
        y: quotient(y, w),
        z: quotient(z, w),
    }
}

/// `x / w` lane by lane, as `homogeneous::quotient` divides one: nothing is divided where `w` is
/// exactly 1 in every lane, every lane otherwise (`x / 1 = x`, the same bits either way).
#[inline(always)]
#[must_use]
pub fn quotient(x: f64x4, w: f64x4) -> f64x4 {
    if w.to_array() == [1.0; LANES] {
        x
    } else {
        x / w
    }
}

/// The checks that a mapping in lanes gives each point's own bits (the unit tests of the
/// logarithmic and paraboloid maps).
#[cfg(test)]
pub(crate) mod check {
    use glam::{DVec2, DVec3};
    use wide::f64x4;

    use super::{LANES, Vectors};

    /// Asserts that lane `k` of `(ndc, undefined)`, four points' NDC in lanes, is `one(points[k])`
    /// to the bit, and undefined exactly where that is `None`; returns how many are defined.
    pub(crate) fn ndc(
        points: &[DVec3; LANES],
        (ndc, undefined): (Vectors, [bool; LANES]),
        one: impl Fn(DVec3) -> Option<DVec3>,
        round: usize,
    ) -> usize {
        let [x, y, z] = [ndc.x, ndc.y, ndc.z].map(f64x4::to_array);
        let mut defined = 0;
        for k in 0..LANES {
            let lanes = (!undefined[k]).then(|| [x[k], y[k], z[k]].map(f64::to_bits));
            let one = one(points[k]).map(|n| n.to_array().map(f64::to_bits));
            assert_eq!(lanes, one, "round {round}, lane {k}");
            defined += usize::from(one.is_some());
        }
        defined
    }

    /// Asserts that lane `k` of `[dx, dy]`, four derivatives in lanes along `direction`, is
    /// `one(points[k], direction[k])` to the bit wherever that is defined, and that `undefined`
    /// flags exactly the lanes where it is `None`; returns how many are defined.
    pub(crate) fn derivatives(
        (points, direction): (&[DVec3; LANES], &[DVec3; LANES]),
        ([dx, dy], undefined): ([f64x4; 2], [bool; LANES]),
        one: impl Fn(DVec3, DVec3) -> Option<DVec2>,
        round: usize,
    ) -> usize {
        let [dx, dy] = [dx, dy].map(f64x4::to_array);
        let mut defined = 0;
        for k in 0..LANES {
            let one = one(points[k], direction[k]);
            assert_eq!(undefined[k], one.is_none(), "round {round}, lane {k}");
            if let Some(one) = one {
                assert_eq!(
                    (dx[k].to_bits(), dy[k].to_bits()),
                    (one.x.to_bits(), one.y.to_bits()),
                    "round {round}, lane {k}: ({}, {}) against {one}",
                    dx[k],
                    dy[k]
                );
                defined += 1;
            }
        }
        defined
    }
}
