//! Numbers in messages: short, and exact.
//!
//! Rust's `{}` of an `f64` prints the shortest decimal that reads back to the same bits, but never
//! in scientific notation: `1e-300` becomes 300 zeros. Messages show values through [`Shown`]
//! instead: plain where that is short, scientific (`{:e}`, also shortest round-trip) elsewhere.

use std::fmt;

use glam::DVec3;

/// Magnitudes from here up to [`PLAIN_BELOW`] are written plainly (`0.001`, `1024`, `5`).
const PLAIN_FROM: f64 = 1e-4;

/// Magnitudes from here up are written in scientific notation (`1e16`).
const PLAIN_BELOW: f64 = 1e16;

/// An `f64` as a message shows it: the shortest round-trip form, plain for 0 and magnitudes in
/// [10⁻⁴, 10¹⁶), scientific otherwise (`1e-300`, `2.5e20`); NaN and infinities as Rust writes them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shown(pub(crate) f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let magnitude = self.0.abs();
        if self.0 == 0.0 || !self.0.is_finite() || (PLAIN_FROM..PLAIN_BELOW).contains(&magnitude) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// A vector as a message shows it: `[x, y, z]`, each coordinate [`Shown`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShownVector(pub(crate) DVec3);

impl fmt::Display for ShownVector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let DVec3 { x, y, z } = self.0;
        write!(f, "[{}, {}, {}]", Shown(x), Shown(y), Shown(z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_and_large_magnitudes_are_scientific_and_round_trip() {
        assert_eq!(Shown(1e-300).to_string(), "1e-300");
        assert_eq!(Shown(-2.5e20).to_string(), "-2.5e20");
        assert_eq!(Shown(5.0).to_string(), "5");
        assert_eq!(Shown(0.001).to_string(), "0.001");
        assert_eq!(Shown(0.0).to_string(), "0");
        assert_eq!(Shown(f64::NAN).to_string(), "NaN");
        for value in [1e-300, 0.1 + 0.2, 1e308, 123_456.789, f64::MIN_POSITIVE] {
            assert_eq!(Shown(value).to_string().parse::<f64>(), Ok(value));
        }
        assert_eq!(
            ShownVector(DVec3::new(1e-310, 0.5, -3.0)).to_string(),
            "[1e-310, 0.5, -3]"
        );
    }
}
