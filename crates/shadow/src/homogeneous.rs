//! Homogeneous coordinates divided back, without the division where it changes nothing.
//!
//! Through an affine or orthographic mapping — a directional light's light space, an orthographic
//! shadow map — the matrix's last row is exactly `(0, 0, 0, 1)`, so a point's `w` is exactly
//! `0·x + 0·y + 0·z + 1·1 = 1` and the divisions by it return their dividends unchanged. Skipping
//! them then gives the same bits (`x / 1 = x` for every `x`, signed zeros and NaN included) and
//! spares the divider, the slowest unit on the lookups', footprints' and cast maps' paths
//! (docs/benchmarks.md); a `w` that is not exactly 1 is divided by as before.

use glam::{DVec3, DVec4};

/// `x / w`, returning `x` itself where `w` is exactly 1 (module docs).
#[inline]
#[must_use]
pub fn quotient(x: f64, w: f64) -> f64 {
    if w == 1.0 { x } else { x / w }
}

/// `v / w`, returning `v` itself where `w` is exactly 1 (module docs).
#[inline]
#[must_use]
pub fn divided(v: DVec3, w: f64) -> DVec3 {
    if w == 1.0 { v } else { v / w }
}

/// The point of homogeneous `h`: `h.xyz / h.w` through [`divided`].
#[inline]
#[must_use]
pub fn point_of(h: DVec4) -> DVec3 {
    divided(h.truncate(), h.w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dividing by an exact 1 is skipped and by anything else is not: the same bits as the
    /// division in both cases, signed zeros and NaN included.
    #[test]
    fn the_skipped_division_gives_the_divisions_bits() {
        let values = [
            0.0,
            -0.0,
            1.5,
            -3.25e-300,
            7.0e300,
            f64::INFINITY,
            f64::NAN,
            0.1,
        ];
        for w in [
            1.0,
            2.0,
            0.75,
            -1.0,
            1.0 + f64::EPSILON,
            1.0 - f64::EPSILON / 2.0,
        ] {
            for x in values {
                assert_eq!(quotient(x, w).to_bits(), (x / w).to_bits(), "{x} / {w}");
                let v = DVec3::new(x, -x, 0.5 * x);
                let expected = v / w;
                let got = point_of(v.extend(w));
                assert_eq!(
                    [got.x, got.y, got.z].map(f64::to_bits),
                    [expected.x, expected.y, expected.z].map(f64::to_bits),
                    "{v} / {w}"
                );
            }
        }
    }
}
