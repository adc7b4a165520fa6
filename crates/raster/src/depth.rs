//! Depth formats and depth tests.
//!
//! Window depth `z ∈ [0, 1]` (GL's depth range: 0 at the near plane, 1 at the far plane) is
//! interpolated in f64 and stored in one of several formats — an accuracy knob the analyzer can turn.
//! Every format is stored as a 32-bit *key* whose unsigned order is the order of the depths it
//! represents, so one integer comparison serves every format:
//!
//! | format | stored value | key |
//! |---|---|---|
//! | [`DepthFormat::F32`] | `z` rounded to f32 | the f32's bits (non-negative floats order as integers) |
//! | [`DepthFormat::ReversedF32`] | `1 − z` rounded to f32, as reversed-Z stores it: f32's dense values near 0 go to the far plane | `u32::MAX −` its bits |
//! | [`DepthFormat::Unorm24`] | `round(z·(2²⁴ − 1))` | that integer |
//! | [`DepthFormat::Unorm16`] | `round(z·(2¹⁶ − 1))` | that integer |

/// How depth is stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthFormat {
    /// 32-bit float depth (GL's `DEPTH_COMPONENT32F`).
    #[default]
    F32,
    /// 32-bit float storing `1 − z`: the precision of a reversed-Z buffer, whose float resolution is
    /// finest at the far plane where perspective depth is coarsest.
    ReversedF32,
    /// 24-bit unsigned normalised (`DEPTH_COMPONENT24`).
    Unorm24,
    /// 16-bit unsigned normalised (`DEPTH_COMPONENT16`).
    Unorm16,
}

/// The largest 24-bit value.
const UNORM24_MAX: f64 = 16_777_215.0;
/// The largest 16-bit value.
const UNORM16_MAX: f64 = 65_535.0;

impl DepthFormat {
    /// Every format.
    pub const ALL: [Self; 4] = [Self::F32, Self::ReversedF32, Self::Unorm24, Self::Unorm16];

    /// A short stable name: `f32`, `reversed-f32`, `unorm24`, `unorm16`.
    #[must_use]
    pub fn key_name(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::ReversedF32 => "reversed-f32",
            Self::Unorm24 => "unorm24",
            Self::Unorm16 => "unorm16",
        }
    }

    /// The format named by its [`Self::key_name`].
    ///
    /// # Errors
    /// An unknown name, with the known ones.
    pub fn parse(key: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|f| f.key_name() == key)
            .ok_or_else(|| {
                let known: Vec<&str> = Self::ALL.iter().map(|f| f.key_name()).collect();
                format!("unknown depth format {key:?}; known: {}", known.join(", "))
            })
    }

    /// The key of window depth `z` (clamped to `[0, 1]`; a NaN is the far plane, 1, in every
    /// format — the formats' own conversions would disagree on it).
    #[must_use]
    pub fn encode(self, z: f64) -> u32 {
        let z = if z.is_nan() { 1.0 } else { z };
        match self {
            Self::F32 => F32Key::encode(z),
            Self::ReversedF32 => ReversedF32Key::encode(z),
            Self::Unorm24 => Unorm24Key::encode(z),
            Self::Unorm16 => Unorm16Key::encode(z),
        }
    }

    /// The window depth a key stands for, exactly as stored (so `decode(encode(z))` is `z` rounded
    /// to the format).
    #[must_use]
    pub fn decode(self, key: u32) -> f64 {
        match self {
            Self::F32 => f64::from(f32::from_bits(key)),
            Self::ReversedF32 => 1.0 - f64::from(f32::from_bits(u32::MAX - key)),
            Self::Unorm24 => f64::from(key) / UNORM24_MAX,
            Self::Unorm16 => f64::from(key) / UNORM16_MAX,
        }
    }
}

/// A depth format's encoding, as a type, so the rasterizer's inner loops are compiled once per
/// format with no per-pixel branch.
pub(crate) trait DepthKey {
    /// The key of window depth `z`, clamped to `[0, 1]`.
    fn encode(z: f64) -> u32;
}

/// [`DepthFormat::F32`].
pub(crate) struct F32Key;
/// [`DepthFormat::ReversedF32`].
pub(crate) struct ReversedF32Key;
/// [`DepthFormat::Unorm24`].
pub(crate) struct Unorm24Key;
/// [`DepthFormat::Unorm16`].
pub(crate) struct Unorm16Key;

/// The bits of 1.0f32: the largest F32 key.
const F32_ONE_BITS: i32 = 0x3f80_0000;

impl DepthKey for F32Key {
    /// Rounds to f32 first and clamps the bits: the same key as rounding `z.clamp(0, 1)` (rounding
    /// is monotone and keeps 0 and 1; every negative f32, −0 included, has the sign bit, so its bits
    /// read as a negative i32, and non-negative f32s order as their bits), in two integer
    /// operations on eight lanes where clamping in f64 took six on two halves. A depth of −0 gives
    /// key 0 here, where the f64 clamp kept −0 and its bits.
    #[inline]
    fn encode(z: f64) -> u32 {
        #[expect(
            clippy::cast_possible_truncation,
            reason = "rounding to f32 is the format"
        )]
        let bits = (z as f32).to_bits().cast_signed();
        bits.clamp(0, F32_ONE_BITS).cast_unsigned()
    }
}

impl DepthKey for ReversedF32Key {
    #[inline]
    fn encode(z: f64) -> u32 {
        #[expect(
            clippy::cast_possible_truncation,
            reason = "rounding to f32 is the format"
        )]
        let stored = (1.0 - z.clamp(0.0, 1.0)) as f32;
        u32::MAX - stored.to_bits()
    }
}

impl DepthKey for Unorm24Key {
    #[inline]
    fn encode(z: f64) -> u32 {
        unorm(z, UNORM24_MAX)
    }
}

impl DepthKey for Unorm16Key {
    #[inline]
    fn encode(z: f64) -> u32 {
        unorm(z, UNORM16_MAX)
    }
}

/// `round(z·max)` for `z` clamped to `[0, 1]`, ties up.
#[inline]
fn unorm(z: f64, max: f64) -> u32 {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "the value lies in [0, max + 0.5] with max < 2^24"
    )]
    let value = (z.clamp(0.0, 1.0) * max + 0.5) as u32;
    value
}

/// When a fragment passes the depth test, comparing its key with the stored one (GL's
/// `glDepthFunc`). With [`DepthFormat::ReversedF32`] the keys are already ordered like depths, so
/// `Less` still keeps the nearest surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthCompare {
    /// Never passes.
    Never,
    /// Passes if nearer.
    #[default]
    Less,
    /// Passes if equal.
    Equal,
    /// Passes if nearer or equal.
    LessEqual,
    /// Passes if farther.
    Greater,
    /// Passes if not equal.
    NotEqual,
    /// Passes if farther or equal.
    GreaterEqual,
    /// Always passes (the last fragment in submission order wins).
    Always,
}

impl DepthCompare {
    /// Whether a fragment with key `new` replaces the stored key `old`.
    #[inline]
    #[must_use]
    pub fn passes(self, new: u32, old: u32) -> bool {
        match self {
            Self::Never => false,
            Self::Less => new < old,
            Self::Equal => new == old,
            Self::LessEqual => new <= old,
            Self::Greater => new > old,
            Self::NotEqual => new != old,
            Self::GreaterEqual => new >= old,
            Self::Always => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rounding then clamping the bits gives what clamping then rounding gives, for depths in and
    /// around [0, 1], at the boundaries, tiny, huge and infinite.
    #[test]
    fn f32_keys_round_then_clamp_as_clamp_then_round() {
        #[expect(clippy::cast_possible_truncation, reason = "the format")]
        let reference = |z: f64| (z.clamp(0.0, 1.0) as f32).to_bits();
        let mut values = vec![
            0.0,
            1.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            1e-300,
            -1e-300,
            1.0 + f64::EPSILON,
            1.0 - f64::EPSILON / 2.0,
            1.0 + 1e-8,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut random = crate::test_random::XorShift::new(0x2545_f491_4f6c_dd1d);
        for _ in 0..200_000 {
            values.push(random.fraction() * 1.4 - 0.2);
        }
        for z in values {
            assert_eq!(F32Key::encode(z), reference(z), "{z:e}");
        }
        // −0 is the one depth where they differ: the clamp keeps it, and its bits.
        assert_eq!(F32Key::encode(-0.0), 0);
    }

    #[test]
    fn keys_are_ordered_like_depths_in_every_format() {
        for format in DepthFormat::ALL {
            let mut last = format.encode(0.0);
            for i in 1..=10_000 {
                let z = f64::from(i) / 10_000.0;
                let key = format.encode(z);
                assert!(key >= last, "{format:?} at {z}");
                last = key;
            }
            assert!(format.encode(0.0) < format.encode(1.0), "{format:?}");
        }
    }

    #[test]
    fn decoding_returns_the_stored_value() {
        for format in DepthFormat::ALL {
            // The ends are exact in every format; quarters only in the float ones.
            let exact: &[f64] = match format {
                DepthFormat::F32 | DepthFormat::ReversedF32 => &[0.0, 0.25, 0.5, 0.75, 1.0],
                DepthFormat::Unorm24 | DepthFormat::Unorm16 => &[0.0, 1.0],
            };
            for &z in exact {
                assert_eq!(format.decode(format.encode(z)), z, "{format:?} {z}");
            }
            // Re-encoding a decoded value gives the same key: the round trip is stable.
            for i in 0..1000 {
                let z = f64::from(i) / 999.0;
                let key = format.encode(z);
                assert_eq!(format.encode(format.decode(key)), key, "{format:?} {z}");
            }
        }
        assert_eq!(DepthFormat::F32.encode(1.5), DepthFormat::F32.encode(1.0));
        assert_eq!(DepthFormat::Unorm16.encode(-0.5), 0);
    }

    #[test]
    fn reversed_f32_is_finer_near_the_far_plane() {
        // Near z = 1 (where perspective depth crowds), f32 has a step of 2^-24 but 1 − z in f32 has
        // far smaller steps.
        let z = 1.0 - 1e-9;
        assert_eq!(DepthFormat::F32.decode(DepthFormat::F32.encode(z)), 1.0);
        let reversed = DepthFormat::ReversedF32.decode(DepthFormat::ReversedF32.encode(z));
        assert!((reversed - z).abs() < 1e-15);
    }

    #[test]
    fn compare_functions() {
        use DepthCompare::*;
        let table = [
            (Never, [false, false, false]),
            (Less, [true, false, false]),
            (Equal, [false, true, false]),
            (LessEqual, [true, true, false]),
            (Greater, [false, false, true]),
            (NotEqual, [true, false, true]),
            (GreaterEqual, [false, true, true]),
            (Always, [true, true, true]),
        ];
        for (compare, expected) in table {
            assert_eq!(
                [
                    compare.passes(1, 2),
                    compare.passes(2, 2),
                    compare.passes(3, 2)
                ],
                expected
            );
        }
    }
}
