//! The exact sum of many `f64` values, rounded once.
//!
//! A long fixed-point accumulator — Kulisch's "long accumulator"; the "small superaccumulator" of
//! R. M. Neal, *Fast exact summation using small and large superaccumulators*, arXiv:1505.05571
//! (2015), §2 — wide enough to hold every finite double exactly: the binary digits from 2⁻¹⁰⁷⁴
//! (the least subnormal) up, in base-2³² digits kept in `i64`s so that a digit absorbs 2³⁰
//! additions before its carry must be passed on. Each value adds its 53-bit significand, shifted,
//! into three digits — or, where [`ExactSum::of`] finds a block of values whose exponents lie
//! within a few binades, the block's significands are first summed as shifted integers in vector
//! lanes and the total added once. The accumulated integer is exact, so the total does not depend
//! on the order of the values, nor on how a parallel sum splits and merges them, and is rounded to
//! the nearest double (ties to even) once, at the end. That makes a mean independent of the order
//! the values arrive in without sorting them, and more accurate than any ordered sum (whose error
//! grows with the count).

/// Base-2³² digits: 2046 bit positions of finite doubles (2⁻¹⁰⁷⁴ up to the top of the largest
/// significand), plus room for the carries of up to 2⁶⁴ values: ⌈(2046 + 53 + 64)/32⌉ = 68, and a
/// digit of margin for the three digits one value touches.
const DIGITS: usize = 69;
/// Bits per digit.
const DIGIT_BITS: u32 = 32;
/// Additions after which the digits' carries are passed on: each addition changes a digit by less
/// than 2³², so a digit in `[0, 2³²)` stays within `i64` for fewer than 2³¹ of them.
const ADDITIONS_PER_CARRY: u32 = 1 << 30;
/// The exponent of the accumulator's lowest bit: the least subnormal, 2⁻¹⁰⁷⁴.
const LOWEST_EXPONENT: i32 = -1074;
/// Values per block of [`ExactSum::of`]'s integer sums: the 32-bit halves of at most 2¹³ terms
/// sum to less than 2⁴⁵, within a `u64`.
const NARROW_BLOCK: usize = 1 << 13;
/// The widest spread of positions whose values [`ExactSum::of`] sums as integers: a significand
/// (below 2⁵³) shifted by at most this stays below 2⁶⁴.
const NARROW_SPAN: u64 = 11;
/// The low 32 bits of a `u64`.
const LOW_HALF: u64 = (1 << 32) - 1;

/// A finite double's significand and the position of its lowest bit, from its `bits`: the value
/// is `±significand·2^(position − 1074)`. Subnormals have biased exponent 0 and no hidden bit,
/// and share the position of the least normal binade.
fn significand_and_position(bits: u64) -> (u64, u64) {
    let biased = (bits >> 52) & 0x7ff;
    let fraction = bits & ((1 << 52) - 1);
    // Without a branch, so that a loop over values runs in vector lanes.
    let normal = u64::from(biased != 0);
    (fraction | normal << 52, biased - normal)
}

/// An exact sum of doubles; [`ExactSum::value`] rounds it to the nearest double.
#[derive(Clone, Debug)]
pub(crate) struct ExactSum {
    /// `Σ digits[k]·2^(32k − 1074)`; after [`ExactSum::carry`], every digit but the last lies in
    /// `[0, 2³²)` and the last holds the sign.
    digits: [i64; DIGITS],
    /// Additions since the last carry.
    pending: u32,
    /// Whether +∞, −∞ or NaN was added.
    positive_infinity: bool,
    negative_infinity: bool,
    nan: bool,
}

impl Default for ExactSum {
    fn default() -> Self {
        Self::new()
    }
}

impl ExactSum {
    /// The empty sum, 0.
    #[must_use]
    pub(crate) fn new() -> Self {
        Self {
            digits: [0; DIGITS],
            pending: 0,
            positive_infinity: false,
            negative_infinity: false,
            nan: false,
        }
    }

    /// The sum of `values`, a block of [`NARROW_BLOCK`] at a time: a block of finite values whose
    /// positions (the exponents of their significands' lowest bits) lie within [`NARROW_SPAN`] of
    /// each other is summed as integers — each significand shifted to the block's lowest
    /// position, in vector lanes, with no carries through memory — and added once; any other
    /// block value by value ([`Self::add`]). Either way the sum is exact, so which way a block
    /// goes does not show in the result.
    #[must_use]
    pub(crate) fn of(values: &[f64]) -> Self {
        let mut sum = Self::new();
        for block in values.chunks(NARROW_BLOCK) {
            let (mut lowest, mut highest, mut finite) = (u64::MAX, 0, true);
            for value in block {
                let bits = value.to_bits();
                finite &= (bits >> 52) & 0x7ff != 0x7ff;
                let (_, position) = significand_and_position(bits);
                lowest = lowest.min(position);
                highest = highest.max(position);
            }
            if finite && highest - lowest <= NARROW_SPAN {
                // Each term is below 2⁶⁴: its two 32-bit halves are summed apart, by sign, in
                // `u64`s (below 2⁴⁵ after a block), which the compiler keeps in vector lanes.
                let [
                    mut positive_low,
                    mut positive_high,
                    mut negative_low,
                    mut negative_high,
                ] = [0_u64; 4];
                for value in block {
                    let bits = value.to_bits();
                    let (significand, position) = significand_and_position(bits);
                    let term = significand << (position - lowest);
                    let negative = (bits >> 63).wrapping_neg();
                    let (low, high) = (term & LOW_HALF, term >> 32);
                    positive_low += low & !negative;
                    positive_high += high & !negative;
                    negative_low += low & negative;
                    negative_high += high & negative;
                }
                let whole = |low: u64, high: u64| (i128::from(high) << 32) + i128::from(low);
                let total = whole(positive_low, positive_high) - whole(negative_low, negative_high);
                sum.add_integer(total, lowest);
            } else {
                for &value in block {
                    sum.add(value);
                }
            }
        }
        sum
    }

    /// Adds `integer·2^(position − 1074)` exactly, for a finite double's position (at most 2045):
    /// the integer's four 32-bit limbs, shifted, touch five digits, each by less than 2³² at most
    /// twice.
    fn add_integer(&mut self, integer: i128, position: u64) {
        let magnitude = integer.unsigned_abs();
        let negative = integer < 0;
        #[expect(clippy::cast_possible_truncation, reason = "a position below 2046")]
        let (digit, shift) = (
            (position / u64::from(DIGIT_BITS)) as usize,
            (position % u64::from(DIGIT_BITS)) as u32,
        );
        let low_mask = (1_u64 << DIGIT_BITS) - 1;
        for k in 0..4 {
            #[expect(clippy::cast_possible_truncation, reason = "masked to 32 bits")]
            let limb = (magnitude >> (DIGIT_BITS * k)) as u64 & low_mask;
            let part = limb << shift;
            let k = k as usize;
            #[expect(clippy::cast_possible_wrap, reason = "each piece is below 2^32")]
            for (index, piece) in [
                (digit + k, part & low_mask),
                (digit + k + 1, part >> DIGIT_BITS),
            ] {
                if negative {
                    self.digits[index] -= piece as i64;
                } else {
                    self.digits[index] += piece as i64;
                }
            }
        }
        self.pending += 2;
        if self.pending >= ADDITIONS_PER_CARRY {
            self.carry();
        }
    }

    /// Adds `value` exactly.
    pub(crate) fn add(&mut self, value: f64) {
        if !value.is_finite() {
            if value.is_nan() {
                self.nan = true;
            } else if value > 0.0 {
                self.positive_infinity = true;
            } else {
                self.negative_infinity = true;
            }
            return;
        }
        let bits = value.to_bits();
        let (significand, position) = significand_and_position(bits);
        #[expect(clippy::cast_possible_truncation, reason = "a position below 2046")]
        let (digit, shift) = (
            (position / u64::from(DIGIT_BITS)) as usize,
            (position % u64::from(DIGIT_BITS)) as u32,
        );
        let shifted = u128::from(significand) << shift;
        let low_mask = (1u128 << DIGIT_BITS) - 1;
        #[expect(clippy::cast_possible_truncation, reason = "each part is below 2^32")]
        let parts = [
            (shifted & low_mask) as i64,
            ((shifted >> DIGIT_BITS) & low_mask) as i64,
            (shifted >> (2 * DIGIT_BITS)) as i64,
        ];
        let negative = bits >> 63 == 1;
        for (k, part) in parts.into_iter().enumerate() {
            if negative {
                self.digits[digit + k] -= part;
            } else {
                self.digits[digit + k] += part;
            }
        }
        self.pending += 1;
        if self.pending >= ADDITIONS_PER_CARRY {
            self.carry();
        }
    }

    /// Adds another sum exactly.
    #[must_use]
    pub(crate) fn merged(mut self, mut other: Self) -> Self {
        self.carry();
        other.carry();
        for (digit, theirs) in self.digits.iter_mut().zip(other.digits) {
            *digit += theirs;
        }
        self.pending = 1;
        self.carry();
        self.positive_infinity |= other.positive_infinity;
        self.negative_infinity |= other.negative_infinity;
        self.nan |= other.nan;
        self
    }

    /// Passes every digit's carry to the next, leaving digits in `[0, 2³²)` but the last.
    fn carry(&mut self) {
        for k in 0..DIGITS - 1 {
            let carry = self.digits[k] >> DIGIT_BITS;
            self.digits[k] -= carry << DIGIT_BITS;
            self.digits[k + 1] += carry;
        }
        self.pending = 0;
    }

    /// The sum rounded to the nearest double, ties to even; ±∞ beyond the largest finite double
    /// (or if an infinity was added), NaN if a NaN or infinities of both signs were added.
    #[must_use]
    pub(crate) fn value(&self) -> f64 {
        match (self.nan, self.positive_infinity, self.negative_infinity) {
            (true, _, _) | (_, true, true) => return f64::NAN,
            (_, true, false) => return f64::INFINITY,
            (_, false, true) => return f64::NEG_INFINITY,
            _ => {}
        }
        let mut digits = self.clone();
        digits.carry();
        let negative = digits.digits[DIGITS - 1] < 0;
        if negative {
            for digit in &mut digits.digits {
                *digit = -*digit;
            }
            digits.carry();
        }
        let magnitude = |k: usize| {
            #[expect(clippy::cast_sign_loss, reason = "carried digits lie in [0, 2^32)")]
            let digit = digits.digits[k] as u128;
            digit
        };
        let Some(top) = (0..DIGITS).rev().find(|&k| digits.digits[k] != 0) else {
            return 0.0;
        };
        let rounded = if top < 2 {
            // Below 2⁶⁴ units of 2⁻¹⁰⁷⁴: converted whole (to nearest, ties to even), then scaled
            // exactly — a subnormal result has fewer than 53 bits and is converted exactly.
            #[expect(
                clippy::cast_precision_loss,
                reason = "rounded to nearest, as intended"
            )]
            let whole = ((magnitude(1) << DIGIT_BITS) | magnitude(0)) as f64;
            whole * power_of_two(LOWEST_EXPONENT)
        } else {
            // The top three digits (at least 65 significant bits), with a sticky bit for anything
            // nonzero below them: rounding that to 53 bits rounds the whole sum correctly. The
            // result is at least 2⁶⁴·2⁻¹⁰⁷⁴, a normal double, so the scaling is exact.
            let head = (magnitude(top) << (2 * DIGIT_BITS))
                | (magnitude(top - 1) << DIGIT_BITS)
                | magnitude(top - 2);
            let sticky = u128::from(digits.digits[..top - 2].iter().any(|&d| d != 0));
            #[expect(
                clippy::cast_precision_loss,
                reason = "rounded to nearest, as intended"
            )]
            let head = (head | sticky) as f64;
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_possible_wrap,
                reason = "top < 69"
            )]
            let exponent = (top as i32 - 2) * DIGIT_BITS as i32 + LOWEST_EXPONENT;
            scale(head, exponent)
        };
        if negative { -rounded } else { rounded }
    }
}

/// `2^exponent` for `−1074 ≤ exponent ≤ 1023`, built from its bits.
pub(crate) const fn power_of_two(exponent: i32) -> f64 {
    debug_assert!(LOWEST_EXPONENT <= exponent && exponent <= 1023);
    #[expect(clippy::cast_sign_loss, reason = "checked non-negative")]
    let bits = if exponent >= -1022 {
        ((exponent + 1023) as u64) << 52
    } else {
        1 << (exponent - LOWEST_EXPONENT)
    };
    f64::from_bits(bits)
}

/// `value·2^exponent` for a `value` whose product is a normal double or overflows: exact, or ∞.
fn scale(value: f64, exponent: i32) -> f64 {
    if exponent > 1023 {
        value * power_of_two(1023) * power_of_two(exponent - 1023)
    } else {
        value * power_of_two(exponent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shadowlab_test_random::SplitMix;

    /// Sums that no ordered f64 sum gets right come out exact.
    #[test]
    fn cancellation_and_tiny_terms_are_exact() {
        assert_eq!(ExactSum::of(&[1e300, 1.0, -1e300]).value(), 1.0);
        assert_eq!(ExactSum::of(&[1.0, 1e-300, -1.0]).value(), 1e-300);
        let tiny = f64::from_bits(1);
        assert_eq!(ExactSum::of(&[tiny, tiny, tiny]).value(), 3.0 * tiny);
        assert_eq!(
            ExactSum::of(&[f64::MAX, f64::MAX, -f64::MAX]).value(),
            f64::MAX
        );
        assert_eq!(ExactSum::of(&[f64::MAX, f64::MAX]).value(), f64::INFINITY);
        assert_eq!(
            ExactSum::of(&[-f64::MAX, -f64::MAX]).value(),
            f64::NEG_INFINITY
        );
        assert_eq!(ExactSum::of(&[0.0; 0]).value().to_bits(), 0.0f64.to_bits());
        assert_eq!(ExactSum::of(&[0.1; 10]).value(), 1.0);
        // Ties to even: 2⁵³ + 1 is halfway between 2⁵³ and 2⁵³ + 2.
        let big = 2f64.powi(53);
        assert_eq!(ExactSum::of(&[big, 1.0]).value(), big);
        assert_eq!(ExactSum::of(&[big, 1.0, 1e-300]).value(), big + 2.0);
        assert_eq!(ExactSum::of(&[big + 2.0, 1.0]).value(), big + 4.0);
    }

    /// Infinities and NaN give what IEEE addition gives.
    #[test]
    fn infinities_and_nan() {
        assert_eq!(ExactSum::of(&[1.0, f64::INFINITY]).value(), f64::INFINITY);
        assert_eq!(
            ExactSum::of(&[f64::NEG_INFINITY, 1.0]).value(),
            f64::NEG_INFINITY
        );
        assert!(
            ExactSum::of(&[f64::INFINITY, f64::NEG_INFINITY])
                .value()
                .is_nan()
        );
        assert!(ExactSum::of(&[1.0, f64::NAN]).value().is_nan());
    }

    /// Random integers of up to 53 bits times one power of two anywhere in the range of doubles
    /// (every value exact): the sum is the exact integer sum rounded once, whatever the order and
    /// however the values are split and merged.
    #[test]
    fn matches_the_exact_integer_sum_in_any_order_and_split() {
        let mut random = SplitMix(0x5eed_0000_0000_0015);
        let mut compared = 0;
        for round in 0..2000 {
            let count = 1 + usize::try_from(random.next_u64() % 300).expect("small");
            // From the least subnormal's exponent to where 300 values of 53 bits still fit.
            let exponent = i32::try_from(random.next_u64() % 2035).expect("small") - 1074;
            let bits = 1 + random.next_u64() % 53;
            let integers: Vec<i64> = (0..count)
                .map(|_| {
                    let magnitude =
                        i64::try_from(random.next_u64() >> (64 - bits)).expect("53 bits");
                    if random.next_u64() & 1 == 0 {
                        magnitude
                    } else {
                        -magnitude
                    }
                })
                .collect();
            let exact: i128 = integers.iter().map(|&m| i128::from(m)).sum();
            // A sum of more than 53 bits in the subnormal range would be rounded twice below.
            let length = 128 - exact.unsigned_abs().leading_zeros();
            if length > 53 && exponent + i32::try_from(length).expect("small") <= -1022 {
                continue;
            }
            #[expect(
                clippy::cast_precision_loss,
                reason = "exact below 2^53; else rounded once"
            )]
            let (values, expected): (Vec<f64>, f64) = (
                integers
                    .iter()
                    .map(|&m| m as f64 * power_of_two(exponent))
                    .collect(),
                exact as f64 * power_of_two(exponent),
            );
            let sum = ExactSum::of(&values).value();
            assert_eq!(
                sum.to_bits(),
                expected.to_bits(),
                "round {round}: {integers:?} 2^{exponent}"
            );
            let reversed: Vec<f64> = values.iter().rev().copied().collect();
            assert_eq!(ExactSum::of(&reversed).value().to_bits(), sum.to_bits());
            let split = usize::try_from(random.next_u64()).expect("64-bit") % (count + 1);
            let merged = ExactSum::of(&values[..split]).merged(ExactSum::of(&values[split..]));
            assert_eq!(merged.value().to_bits(), sum.to_bits());
            compared += 1;
        }
        assert!(compared > 1500, "{compared}");
    }

    /// The accumulator after its carries: the one representation of its integer.
    fn carried(sum: &ExactSum) -> ([i64; DIGITS], [bool; 3]) {
        let mut sum = sum.clone();
        sum.carry();
        (
            sum.digits,
            [sum.positive_infinity, sum.negative_infinity, sum.nan],
        )
    }

    /// `of`'s integer sums of narrow blocks hold exactly what adding the values one by one holds:
    /// blocks narrower and wider than the span, of both signs, with zeros, subnormals, infinities
    /// and NaN among them, lengths around the block size.
    #[test]
    fn integer_blocks_hold_what_value_by_value_holds() {
        let mut random = SplitMix(0x5eed_0000_0000_0126);
        for round in 0..48 {
            let length = [
                1,
                7,
                NARROW_BLOCK - 1,
                NARROW_BLOCK,
                NARROW_BLOCK + 1,
                20_000,
            ][round % 6];
            let width = [0, 5, NARROW_SPAN, NARROW_SPAN + 1, 60, 2045][(round / 6) % 6];
            let lowest = random.next_u64() % (2046 - width);
            let values: Vec<f64> = (0..length)
                .map(|_| {
                    let position = lowest + random.next_u64() % (width + 1);
                    let fraction = random.next_u64() >> 12;
                    let sign = random.next_u64() & (1 << 63);
                    // The position's own binade (a subnormal at 0; a few exact zeros there too).
                    let biased = if position == 0 { 0 } else { position + 1 };
                    let value = f64::from_bits(sign | (biased << 52) | fraction);
                    match random.next_u64() % 1000 {
                        0 if round >= 24 => f64::INFINITY,
                        1 if round >= 24 => f64::NEG_INFINITY,
                        2 if round >= 40 => f64::NAN,
                        3 => 0.0,
                        4 => -0.0,
                        _ => value,
                    }
                })
                .collect();
            let mut one_by_one = ExactSum::new();
            for &value in &values {
                one_by_one.add(value);
            }
            let summed = ExactSum::of(&values);
            assert_eq!(carried(&summed), carried(&one_by_one), "round {round}");
            let same = summed.value().to_bits() == one_by_one.value().to_bits()
                || summed.value().is_nan() && one_by_one.value().is_nan();
            assert!(same, "round {round}");
        }
    }

    /// Carries passed on mid-sum change nothing: a sum past the carry interval equals its count
    /// times the value.
    #[test]
    fn carries_are_passed_on_without_loss() {
        let mut sum = ExactSum::new();
        sum.pending = ADDITIONS_PER_CARRY - 3;
        for _ in 0..6 {
            sum.add(f64::MAX / 8.0);
        }
        assert_eq!(sum.value(), f64::MAX / 8.0 * 6.0);
    }
}
