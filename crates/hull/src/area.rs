//! The area vector of a planar loop, accurate for every loop the exact hull makes: slivers, tiny
//! faces and huge ones.
//!
//! The area vector is `½ Σₖ (vₖ − v₀) × (vₖ₊₁ − v₀)` over the loop's fan. In plain f64 each cross
//! product has an absolute error of `~ε |a| |b|`; for a sliver, whose area is far below the product
//! of its long sides, that error tilts the normal (found by the hull fuzzer: a triangle with sides
//! 1, 1 and 4·10⁻⁷ got a normal 5·10⁻¹⁰ rad off, its third vertex 1.4·10⁻¹¹ off its plane). Here the
//! coordinates are first rescaled by a power of two (exact; coordinates below
//! [`crate::finite::ORIENTATION_FLOOR`] of the largest flushed to 0, as the predicates see them),
//! then every difference, product and sum is carried in **double-double** arithmetic (Dekker 1971;
//! Knuth's TwoSum and an FMA TwoProduct): each component's relative error is about 2⁻¹⁰⁴ of the
//! terms, so a sliver 10⁻²⁰ as wide as it is long still gets its normal to f64 precision.

use glam::DVec3;

use crate::finite::{flush_tiny, rescale_for};

/// An unevaluated sum `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct DoubleDouble {
    hi: f64,
    lo: f64,
}

impl DoubleDouble {
    const ZERO: Self = Self { hi: 0.0, lo: 0.0 };

    /// `a + b` exactly (Knuth's TwoSum).
    fn sum(a: f64, b: f64) -> Self {
        let hi = a + b;
        let b_virtual = hi - a;
        let lo = (a - (hi - b_virtual)) + (b - b_virtual);
        Self { hi, lo }
    }

    /// `a · b` exactly (TwoProduct by a fused multiply-add).
    fn product(a: f64, b: f64) -> Self {
        let hi = a * b;
        Self {
            hi,
            lo: a.mul_add(b, -hi),
        }
    }

    /// Renormalises `hi + lo` (Dekker's FastTwoSum; `|hi| ≥ |lo|`).
    fn normalised(hi: f64, lo: f64) -> Self {
        let s = hi + lo;
        Self {
            hi: s,
            lo: lo - (s - hi),
        }
    }

    fn add(self, other: Self) -> Self {
        let s = Self::sum(self.hi, other.hi);
        Self::normalised(s.hi, s.lo + self.lo + other.lo)
    }

    fn sub(self, other: Self) -> Self {
        self.add(Self {
            hi: -other.hi,
            lo: -other.lo,
        })
    }

    fn mul(self, other: Self) -> Self {
        let p = Self::product(self.hi, other.hi);
        Self::normalised(p.hi, p.lo + self.hi * other.lo + self.lo * other.hi)
    }

    fn value(self) -> f64 {
        self.hi + self.lo
    }
}

/// The unit normal of the planar loop `vertices[loop_]` (counter-clockwise around it), from its
/// area vector in double-double arithmetic on power-of-two-rescaled coordinates; NaN only for a
/// loop of zero area.
pub(crate) fn loop_normal(vertices: &[DVec3], loop_: &[usize]) -> DVec3 {
    let largest = loop_
        .iter()
        .map(|&i| vertices[i].abs().max_element())
        .fold(0.0_f64, f64::max);
    let factor = rescale_for(largest);
    let corner = |i: usize| {
        let v = vertices[loop_[i]] * factor;
        [flush_tiny(v.x), flush_tiny(v.y), flush_tiny(v.z)]
    };
    let origin = corner(0);
    let offset = |i: usize| {
        let v = corner(i);
        [0, 1, 2].map(|axis| DoubleDouble::sum(v[axis], -origin[axis]))
    };
    let mut area = [DoubleDouble::ZERO; 3];
    for k in 1..loop_.len().saturating_sub(1) {
        let (a, b) = (offset(k), offset(k + 1));
        for (axis, sum) in area.iter_mut().enumerate() {
            let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
            *sum = sum.add(a[u].mul(b[w]).sub(a[w].mul(b[u])));
        }
    }
    let area = DVec3::new(area[0].value(), area[1].value(), area[2].value());
    (area * rescale_for(area.abs().max_element())).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_sum_and_two_product_are_exact() {
        let s = DoubleDouble::sum(1.0, 1e-20);
        assert_eq!((s.hi, s.lo), (1.0, 1e-20));
        let third = 1.0 / 3.0;
        let p = DoubleDouble::product(third, 3.0);
        // 3 · fl(1/3) = 1 − 2⁻⁵⁴ exactly.
        assert_eq!(p.hi + p.lo, 1.0);
        assert_eq!(p.lo, -(2f64.powi(-54)));
    }

    #[test]
    fn a_sliver_gets_its_normal_to_f64_precision() {
        // A triangle 1.1 long and 1e-9 wide: plain f64 cross products tilt its normal by ~1e-7.
        let a = DVec3::new(0.123_456_7, 0.765_432_1, 0.314_159_2);
        let b = a + DVec3::new(0.987_654_3, 0.543_210_9, 0.111_111_1);
        let c = b + DVec3::new(0.3, -0.7, 0.2) * 1e-9;
        let vertices = [a, b, c];
        let normal = loop_normal(&vertices, &[0, 1, 2]);
        for v in vertices {
            assert!(normal.dot(v - a).abs() < 1e-15, "{}", normal.dot(v - a));
        }
        let plain = (b - a).cross(c - a).normalize();
        let worst = vertices
            .iter()
            .map(|v| plain.dot(*v - a).abs())
            .fold(0.0, f64::max);
        assert!(
            worst > 1e-13,
            "the plain normal is good here too ({worst}): a weak test"
        );
    }
}
