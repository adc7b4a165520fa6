//! `√(x² + y²)` correctly rounded (to nearest, ties to even), one pair or four lanes at once.
//!
//! The footprints' largest singular value takes two of these per pixel
//! ([`footprint_of`](crate::aliasing)). `f64::hypot` is the C library's, which is not correctly
//! rounded — glibc 2.36's is one ulp off on about one pair in 840 of footprint-like magnitudes
//! (docs/CONVENTIONS.md, "Machines") — so footprints' bits would depend on the C library, and it
//! takes one call per lane. Here the result is the nearest double to the exact value, the same on
//! every platform, and four lanes share each vector instruction.
//!
//! **The usual path** (both inputs within `[2⁻⁴⁵⁰, 2⁴⁵⁰]`, so nothing below overflows or loses a
//! bit to underflow): the squares are split exactly, `x² = X + X′` and `y² = Y + Y′` (Dekker's
//! two-product: T. J. Dekker, *A floating-point technique for extending the available precision*,
//! Numer. Math. 18, 1971, mul12; no fused multiply-add needed), `h = √(X + Y)` rounded, and one
//! Newton step from `h` with the residual `S − h²` (`S` the exact `x² + y²`) worked out from those
//! exact pieces gives `h + ℓ`, with `|h + ℓ − √S| < 2⁻¹⁰¹·h` (bound below). The rounding is then
//! certain when `h + (ℓ − ε)` and `h + (ℓ + ε)`, `ε =` [`RESIDUAL_BOUND`]`·h`, round to the same
//! double: `√S` lies between them and rounding is monotonic. That fails only when `√S` is within
//! about `2⁻⁹⁶·h` of a midpoint between two doubles — about one pair in 2⁴² of random ones, and
//! every exact midpoint (such as `hypot(3k, 4k) = 5k` with `5k` of 54 bits), which
//! [`nearest`] settles in exact arithmetic.
//!
//! The bound: `h = fl(√fl(X + Y))` is within `2⁻⁵¹·h` of `√S`, so the residual is at most
//! `2⁻⁵⁰·h²`; it is the sum of five terms each exact (`fl(X + Y) − fl(h·h)` by Sterbenz's lemma, the
//! two-sum error of `X + Y`, `X′`, `Y′`, and the two-product error of `h·h`) of total magnitude
//! `≤ 2⁻⁵⁰·S`, summed with an error `≤ 4·2⁻⁵³·2⁻⁵⁰·S`, which contributes `2⁻¹⁰²·h` to
//! `ℓ = residual / 2h`; the Newton step's neglected term `residual²/8h³ ≤ 2⁻¹⁰³·h`, and rounding
//! `ℓ` adds `2⁻¹⁰⁴·h`. Their sum is below `2⁻¹⁰¹·h`, a 32nd of [`RESIDUAL_BOUND`].
//!
//! **Outside that range** (a zero, a subnormal, a ratio over 2³¹, an infinity, a NaN, a huge
//! value) [`hypot`] scales the pair by a power of two into it, or answers directly: `+∞` if either
//! is infinite (even with a NaN, as IEEE 754's `hypot` does), NaN if either is NaN, the larger when
//! the smaller is zero or at most `2⁻³¹` of it (then `√S < big·(1 + 2⁻⁶³)`, which rounds to `big`),
//! and two subnormals as integers (`√(m² + n²)` of their integer significands, rounded to an integer).

use wide::f64x4;

use crate::exact_sum::{ExactSum, power_of_two};

/// The relative error allowed for `h + ℓ` in the rounding test: 32 times the proven bound, 2⁻¹⁰¹.
const RESIDUAL_BOUND: f64 = power_of_two(-96);
/// Dekker's splitting constant `2²⁷ + 1`: `a·SPLIT − (a·SPLIT − a)` is `a`'s upper 26 bits.
const SPLIT: f64 = 134_217_729.0;
/// The usual path's inputs lie in `[LEAST, GREATEST]`: their squares' exact two-product errors are
/// normal doubles (at least 2⁻¹⁰⁰⁴) and `x·SPLIT` and `x²` are far from overflow.
const LEAST: f64 = power_of_two(-450);
const GREATEST: f64 = power_of_two(450);
/// The smaller input at most this fraction of the larger leaves the larger as the rounded result.
const NEGLIGIBLE_RATIO: f64 = power_of_two(-31);

/// `√(x² + y²)` correctly rounded.
#[must_use]
pub(crate) fn hypot(x: f64, y: f64) -> f64 {
    let (x, y) = (x.abs(), y.abs());
    if x == f64::INFINITY || y == f64::INFINITY {
        return f64::INFINITY;
    }
    if x.is_nan() || y.is_nan() {
        return f64::NAN;
    }
    let (big, small) = if x >= y { (x, y) } else { (y, x) };
    if small == 0.0 {
        return big;
    }
    if big < f64::MIN_POSITIVE {
        return subnormal_hypot(big, small);
    }
    if small <= big * NEGLIGIBLE_RATIO {
        return big;
    }
    // Scale by 2^-e, e the larger one's exponent, into [1, 2): exact both ways (2^±e are doubles
    // for e in [-1022, 1023]; the smaller stays above 2^-32, a subnormal scaled up loses nothing).
    let exponent = i32::try_from(big.to_bits() >> 52).expect("an 11-bit exponent field") - 1023;
    let (down, up) = (power_of_two(-exponent), power_of_two(exponent));
    let (x, y) = (big * down, small * down);
    let [r, ..] = usual(f64x4::splat(x), f64x4::splat(y)).to_array();
    let r = if r.is_nan() { nearest(x, y) } else { r };
    // Overflows to +∞ exactly when the rounded value exceeds the largest double.
    r * up
}

/// [`hypot`] of each lane.
#[must_use]
pub(crate) fn hypot_lanes(x: f64x4, y: f64x4) -> f64x4 {
    let (x, y) = (x.abs(), y.abs());
    let within = |v: f64x4| v.simd_ge(f64x4::splat(LEAST)) & v.simd_le(f64x4::splat(GREATEST));
    let usual_lanes = within(x) & within(y);
    let r = usual(x, y);
    // A NaN lane of `r` is an uncertain rounding; a lane outside the range is answered alone.
    let certain = usual_lanes & r.simd_eq(r);
    if certain.all() {
        return r;
    }
    let (x, y, r, certain) = (
        x.to_array(),
        y.to_array(),
        r.to_array(),
        certain.to_bitmask(),
    );
    f64x4::new(std::array::from_fn(|k| {
        if certain & (1 << k) != 0 {
            r[k]
        } else {
            hypot(x[k], y[k])
        }
    }))
}

/// The usual path for inputs in `[LEAST, GREATEST]` (in either order): each lane's correctly
/// rounded `√(x² + y²)`, or NaN where the rounding test cannot decide it.
fn usual(x: f64x4, y: f64x4) -> f64x4 {
    let (xx, xx_error) = square(x);
    let (yy, yy_error) = square(y);
    let sum = xx + yy;
    let h = sum.sqrt();
    let (hh, hh_error) = square(h);
    // Knuth's two-sum: `sum_error` is exactly `xx + yy − sum`.
    let xx_part = sum - yy;
    let sum_error = (xx - xx_part) + (yy - (sum - xx_part));
    // S − h² = (sum − hh) + sum_error + xx_error + yy_error − hh_error; the first term is exact.
    let residual = (sum - hh) + (sum_error + ((xx_error + yy_error) - hh_error));
    let correction = residual / (h + h);
    let allowance = h * f64x4::splat(RESIDUAL_BOUND);
    let above = h + (correction + allowance);
    let below = h + (correction - allowance);
    above
        .simd_eq(below)
        .bitselect(above, f64x4::splat(f64::NAN))
}

/// `a·a` as the rounded product and its exact error (Dekker's mul12 for a square): exact when no
/// step overflows or underflows.
fn square(a: f64x4) -> (f64x4, f64x4) {
    let product = a * a;
    let scaled = a * f64x4::splat(SPLIT);
    let high = scaled - (scaled - a);
    let low = a - high;
    let error = ((high * high - product) + (high + high) * low) + low * low;
    (product, error)
}

/// The correctly rounded `√(x² + y²)` for `x`, `y` in `[LEAST, GREATEST]`, decided in exact
/// arithmetic: the nearest double `r` is the one with `(r − ulp⁻/2)² ≤ x² + y² ≤ (r + ulp/2)²`,
/// a tie going to the even one. Every square below is split exactly (by a fused multiply-add,
/// IEEE's on every platform), and the signs come from [`ExactSum`].
fn nearest(x: f64, y: f64) -> f64 {
    let pieces = |a: f64| {
        let product = a * a;
        [product, a.mul_add(a, -product)]
    };
    let [xx, xx_error] = pieces(x);
    let [yy, yy_error] = pieces(y);
    // The sign of (x² + y²) − m², m the midpoint of neighbours a < b: m² = a² + a·(b − a) +
    // (b − a)²/4, where b − a is a power of two, so each term is exact.
    let against_midpoint = |a: f64, b: f64| {
        let [aa, aa_error] = pieces(a);
        let gap = b - a;
        let terms = [
            xx,
            xx_error,
            yy,
            yy_error,
            -aa,
            -aa_error,
            -(a * gap),
            -(gap * gap * 0.25),
        ];
        ExactSum::of(&terms)
            .value()
            .partial_cmp(&0.0)
            .expect("finite terms")
    };
    let even = |a: f64, b: f64| if a.to_bits() & 1 == 0 { a } else { b };
    let mut r = (xx + yy).sqrt();
    loop {
        let above = r.next_up();
        match against_midpoint(r, above) {
            std::cmp::Ordering::Greater => r = above,
            std::cmp::Ordering::Equal => return even(r, above),
            std::cmp::Ordering::Less => break,
        }
    }
    loop {
        let below = r.next_down();
        match against_midpoint(below, r) {
            std::cmp::Ordering::Less => r = below,
            std::cmp::Ordering::Equal => return even(below, r),
            std::cmp::Ordering::Greater => return r,
        }
    }
}

/// `√(x² + y²)` of two subnormals (`x ≥ y > 0`), from their integer significands `m`, `n` (the
/// values are `m·2⁻¹⁰⁷⁴`): the integer nearest `√(m² + n²)` — never a tie, as `(k + ½)²` is not
/// an integer — times 2⁻¹⁰⁷⁴, which is exact below 2⁵³.
fn subnormal_hypot(x: f64, y: f64) -> f64 {
    let (m, n) = (u128::from(x.to_bits()), u128::from(y.to_bits()));
    let square = m * m + n * n;
    let root = square.isqrt();
    // √square > root + ½ ⟺ square > root² + root + ¼ ⟺ square − root² > root, for integers.
    let nearest = if square - root * root > root {
        root + 1
    } else {
        root
    };
    nearest as f64 * power_of_two(-1074)
}

#[cfg(test)]
mod tests {
    use super::*;
    use shadowlab_test_random::SplitMix;

    /// `v = significand·2^exponent` for finite positive `v`, the significand odd.
    fn parts(v: f64) -> (u128, i32) {
        let bits = v.to_bits();
        let field = i32::try_from(bits >> 52).expect("positive");
        let fraction = u128::from(bits & ((1 << 52) - 1));
        let (significand, exponent) = if field == 0 {
            (fraction, -1074)
        } else {
            (fraction | 1 << 52, field - 1075)
        };
        let zeros = significand.trailing_zeros();
        (
            significand >> zeros,
            exponent + i32::try_from(zeros).expect("small"),
        )
    }

    /// The correctly rounded `√(x² + y²)` of finite positive `x ≥ y` whose significands fit one
    /// 63-bit scale, in integer arithmetic alone and independently of the code under test:
    /// `x = m·2^e`, `y = n·2^e` with `m` in `[2⁶², 2⁶³)`; `r = ⌊√(m² + n²)⌋`, rounded at the
    /// 53rd bit or at 2⁻¹⁰⁷⁴, whichever is higher, with `r² ≠ m² + n²` as a sticky bit.
    fn oracle(x: f64, y: f64) -> f64 {
        let ((m, x_exponent), (n, y_exponent)) = (parts(x), parts(y));
        let shift = i32::try_from(m.leading_zeros()).expect("small") - 65;
        let exponent = x_exponent - shift;
        let n_shift = y_exponent - exponent;
        assert!(
            n_shift >= 0,
            "hypot({x:e}, {y:e}) is outside the oracle's reach"
        );
        let (m, n) = (m << shift, n << n_shift);
        let square = m * m + n * n;
        let root = square.isqrt();
        let exact = root * root == square;
        let length = 128 - i32::try_from(root.leading_zeros()).expect("small");
        let drop = (length - 53).max(-1074 - exponent);
        let (kept, rest) = (root >> drop, root & ((1 << drop) - 1));
        let half = 1 << (drop - 1);
        let up = rest > half || (rest == half && (!exact || kept & 1 == 1));
        // At most 54 bits, exact as a double; scaled exactly (a subnormal result is a multiple of
        // 2^-1074 by the rounding above), or overflowing to ∞.
        (kept + u128::from(up)) as f64 * power_of_two(drop + exponent)
    }

    /// The exponent of a normal positive double: `v` in `[2^e, 2^(e+1))`.
    fn exponent_of(v: f64) -> i32 {
        i32::try_from(v.to_bits() >> 52).expect("positive") - 1023
    }

    /// A random double with an exponent in `[low, high]` (normal) and a random significand.
    fn random_in(random: &mut SplitMix, low: i32, high: i32) -> f64 {
        let span = u64::try_from(high - low + 1).expect("ordered");
        let exponent = low + i32::try_from(random.next_u64() % span).expect("small");
        let field = u64::try_from(exponent + 1023).expect("normal");
        f64::from_bits(random.next_u64() >> 12 | field << 52)
    }

    /// `hypot` and each lane of `hypot_lanes` give `expected` in every order and sign.
    fn check(x: f64, y: f64, expected: f64) {
        for (a, b) in [(x, y), (y, x), (-x, y), (x, -y)] {
            assert_eq!(
                hypot(a, b).to_bits(),
                expected.to_bits(),
                "hypot({a:e}, {b:e})"
            );
            let lanes = hypot_lanes(f64x4::new([a, 1.0, b, 3.0]), f64x4::new([b, 1.0, a, 4.0]));
            let lanes = lanes.to_array();
            assert_eq!(
                [lanes[0], lanes[2]].map(f64::to_bits),
                [expected.to_bits(); 2]
            );
            assert_eq!([lanes[1], lanes[3]], [2f64.sqrt(), 5.0]);
        }
    }

    /// Random pairs — footprint-like magnitudes, every exponent range, exponents up to 8 apart —
    /// agree with the integer oracle, one at a time and in lanes beside other pairs.
    #[test]
    fn random_pairs_are_correctly_rounded() {
        let mut random = SplitMix(0x4879_706f_7400_0001);
        let mut libm_differs = 0;
        for round in 0..100_000 {
            let x = if round % 4 == 0 {
                random_in(&mut random, -1021, 1022)
            } else {
                random_in(&mut random, -8, 8)
            };
            let gap = i32::try_from(random.next_u64() % 9).expect("small");
            let below = (exponent_of(x) - gap).max(-1022);
            let y = random_in(&mut random, below, below).min(x);
            let expected = oracle(x, y);
            check(x, y, expected);
            libm_differs += usize::from(x.hypot(y) != expected);
        }
        // What this replaces: the C library's hypot is within an ulp but not always the nearest.
        assert!(
            libm_differs > 0,
            "the C library rounded every pair correctly"
        );
    }

    /// Exact midpoints between two doubles (`hypot(3k, 4k) = 5k` with `5k` odd and of 54 bits)
    /// round to the even neighbour, and values a hair from a midpoint (`hypot(a², a) = a² + ½ −
    /// 1/8a² + …`) to the nearer one; the fast rounding test defers every one of them, so these
    /// exercise the exact path.
    #[test]
    fn midpoints_and_near_midpoints_are_settled_exactly() {
        let mut random = SplitMix(0x4879_706f_7400_0002);
        for _ in 0..2_000 {
            // k odd in [2^53/5, 2^53/4): 3k and 4k are doubles, 5k an odd 54-bit integer.
            let k = ((1u64 << 53) / 5 + random.next_u64() % ((1 << 51) / 10)) | 1;
            // a in [2^26, 2^26.5): a² a double of 53 bits, a² + ½ a midpoint.
            let a = (1u64 << 26) + random.next_u64() % 19_000_000;
            for scale in [
                1.0,
                power_of_two(-700),
                power_of_two(900),
                power_of_two(-1000),
            ] {
                #[expect(clippy::cast_precision_loss, reason = "below 2^53: exact")]
                let pairs = [(3 * k, 4 * k), (a * a, a)].map(|(x, y)| (x as f64, y as f64));
                for (x, y) in pairs {
                    let (x, y) = (x * scale, y * scale);
                    let expected = oracle(x, y);
                    assert!(usual(f64x4::splat(x), f64x4::splat(y)).to_array()[0].is_nan());
                    check(x, y, expected);
                }
            }
        }
    }

    /// Zeros, subnormals, the largest doubles, a negligible second value, infinities and NaNs.
    #[test]
    fn edges_of_the_range() {
        let tiny = f64::from_bits(1);
        check(0.0, 0.0, 0.0);
        check(0.0, 2.5, 2.5);
        check(tiny, tiny, tiny);
        check(3.0 * tiny, 4.0 * tiny, 5.0 * tiny);
        check(f64::MAX, f64::MAX, f64::INFINITY);
        check(f64::MAX, 1.0, f64::MAX);
        check(1.0, power_of_two(-32), 1.0);
        check(f64::MIN_POSITIVE, tiny, f64::MIN_POSITIVE);
        let mut random = SplitMix(0x4879_706f_7400_0003);
        for _ in 0..20_000 {
            let subnormal = |random: &mut SplitMix| f64::from_bits(random.next_u64() >> 12);
            let (x, y) = (subnormal(&mut random), subnormal(&mut random));
            let (x, y) = (x.max(y), x.min(y));
            check(x, y, oracle(x, y));
            let x = random_in(&mut random, -1022, -1016);
            check(x, y, oracle(x, y));
            let x = random_in(&mut random, -1000, 1000);
            let y = x * power_of_two(-31) * random.range(0.0, 1.0);
            check(x, y, x);
        }
        for nan in [f64::NAN, -f64::NAN] {
            assert_eq!(hypot(nan, f64::INFINITY), f64::INFINITY);
            assert_eq!(hypot(f64::NEG_INFINITY, nan), f64::INFINITY);
            assert!(hypot(nan, 1.0).is_nan() && hypot(0.0, nan).is_nan());
            let lanes = hypot_lanes(
                f64x4::new([nan, 1.0, nan, 0.0]),
                f64x4::splat(f64::INFINITY),
            );
            assert_eq!(lanes.to_array(), [f64::INFINITY; 4]);
            assert!(
                hypot_lanes(f64x4::splat(nan), f64x4::splat(2.0))
                    .to_array()
                    .iter()
                    .all(|v| v.is_nan())
            );
        }
    }
}
