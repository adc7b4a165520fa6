//! Moments as a GPU stores them: the 32- and 16-bit float texture formats a filterable map is
//! rendered into and blurred in, and the rounding each write into one applies.
//!
//! An engine stores a filterable map in three steps, which a lookup that models storage follows:
//!
//! 1. **The shadow pass** writes per texel the *raw* moments of its depth (each method's
//!    `texel_moments`: [`crate::vsm::ShiftedMoments::texel_moments`] `d, d²`;
//!    [`crate::esm::ExponentialMoment::texel_moments`] `exp(c·d)`;
//!    [`crate::evsm::WarpedMoments::texel_moments`] a warp about ½ and its square;
//!    [`crate::msm::MsmMoments::texel_moments`] `d, d², d³, d⁴`), each computed in f64 from the
//!    stored depth and rounded once to the format ([`MomentFormat::round`]). The shader's own f32
//!    arithmetic, within an ulp or two of that, is not modelled.
//! 2. **The blur** reads them and writes the kernel's weighted mean, one separable pass per axis
//!    ([`MomentFormat::blur_pass`]): each pass accumulates in f32 and rounds its result to the
//!    format as it writes it to a texture of that format (named choice: *f32 blur, stored per
//!    pass*; Filament's `PostProcessManager::gaussianBlurPass` blurs horizontally into a temporary
//!    texture of the source's format, then vertically).
//! 3. **The lookup** reconstructs the lit fraction from the blurred means (each method's
//!    `from_raw_moments`), in f64.
//!
//! # Rounding (named choice: *IEEE conversion*)
//! [`MomentFormat::round`] is the IEEE 754 conversion to binary32 or binary16: to nearest, ties to
//! even, subnormals kept, and a magnitude of at least `65520` (`65504` and half an ulp, a tie that
//! goes to the even `2¹⁶`) overflowing to `±∞` in binary16 (above `f32::MAX` and half an ulp in
//! binary32). Hardware render-target conversions may differ: Direct3D 10 allows float-to-half
//! conversions to round toward zero and never to overflow to infinity (as the note in Mesa's
//! `src/gallium/auxiliary/util/u_half.h` records), which would saturate at `65504`; shadowlab
//! models the IEEE conversion.
//!
//! # Overflow (named choice: *overflow reads lit*)
//! A moment that overflows its format is `±∞` from then on: the blur's f32 sums keep it infinite
//! (every texel of one moment has the same sign, so no `∞ − ∞` arises). The reconstructions that
//! can meet one — ESM's `exp(c·d)` and the EVSM warps — read a warp whose stored means are not
//! finite as lit (bound 1): Annen et al.'s `clamp(exp(−c·t)·∞, 0, 1)` is 1; the Chebyshev bound
//! returns 1 for an infinite mean in Filament (google/filament `shaders/src/surface_shadowing.fs`,
//! `chebyshevUpperBound`: `depth <= moments.x`) and in MJP's sample (TheRealMJP/Shadows
//! `Shadows/VSM.hlsl`, `ChebyshevUpperBound`: `mean <= moments.x`); and for an infinite second
//! moment alone, where the GPU would compute `∞/∞`, 1 is the bound's limit as the variance grows.
//! That is why engines cap the exponent at the format's limit: `exp(2·c) ≤ 65504` for `c ≤ 5.54`
//! in 16 bits, 42 in 32 (MJP's `GetEVSMExponents`), in their units where the exponent acts on
//! depth in `[−1, 1]` (twice that in this crate's: `crate::evsm`, *Storage*). VSM's and MSM's
//! moments lie in `[0, 1]` and never overflow.

use crate::error::ParamError;

/// The largest finite binary16 value, `(2 − 2⁻¹⁰)·2¹⁵`.
pub const F16_MAX: f64 = 65_504.0;
/// The smallest magnitude that rounds to infinity in binary16: [`F16_MAX`] plus half its ulp (2⁵).
const F16_OVERFLOW: f64 = 65_520.0;
/// The exponent of binary16's smallest normal binade (`2⁻¹⁴`); below it the spacing stays `2⁻²⁴`.
const F16_MIN_EXPONENT: i32 = -14;
/// The fraction bits of binary16: the spacing in the binade `[2ᵉ, 2ᵉ⁺¹)` is `2ᵉ⁻¹⁰`.
const F16_FRACTION_BITS: i32 = 10;

/// A float texture format for moments.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MomentFormat {
    /// IEEE 754 binary32 channels (RG32F, RGBA32F).
    F32,
    /// IEEE 754 binary16 channels (RG16F, RGBA16F), "half float".
    F16,
}

impl MomentFormat {
    /// Every format, the wider first.
    pub const ALL: [Self; 2] = [Self::F32, Self::F16];

    /// The format's name in a filter spec: `f32`, `f16`.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::F16 => "f16",
        }
    }

    /// The format whose [`Self::key`] is `key`, if any.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.key() == key)
    }

    /// Bytes per moment: 4 for binary32, 2 for binary16.
    #[must_use]
    pub const fn bytes(self) -> u32 {
        match self {
            Self::F32 => 4,
            Self::F16 => 2,
        }
    }

    /// `x` as a texture of this format stores it (module documentation, *Rounding*): to nearest,
    /// ties to even; `±∞` beyond the format's range; NaN stays NaN.
    #[must_use]
    pub fn round(self, x: f64) -> f64 {
        match self {
            Self::F32 => f64::from(to_f32(x)),
            Self::F16 => round_to_f16(x),
        }
    }

    /// One blur pass as a GPU runs it on this format (module documentation): the weighted mean
    /// `Σ ŵᵢ·vᵢ` of `values` (moments as a texture of this format holds them), with the weights
    /// normalised in f64 (`ŵᵢ = wᵢ / Σ w`) and rounded to f32, accumulated in f32 in the order
    /// given (each product and each sum rounded to f32, no fused multiply-add), and the sum rounded
    /// to this format as the pass writes it. Infinite values stay infinite.
    ///
    /// # Errors
    /// Names `weights` (a length other than that of `values`, a value negative or not finite, a sum
    /// of 0 or overflowing) or `values` (a NaN, or infinities of both signs, whose sum is NaN).
    pub fn blur_pass(self, values: &[f64], weights: &[f64]) -> Result<f64, ParamError> {
        if weights.len() != values.len() {
            return Err(ParamError::OutOfDomain {
                name: "weights",
                value: weights.len() as f64,
                requirement: format!("one per value ({})", values.len()),
            });
        }
        let mut total = 0.0;
        for &w in weights {
            ParamError::finite("weights", w)?;
            ParamError::require("weights", w, w >= 0.0, || "at least 0".into())?;
            total += w;
        }
        ParamError::finite("weights", total)?;
        ParamError::require("weights", total, total > 0.0, || "of positive sum".into())?;
        let mut sum = 0.0f32;
        for (&v, &w) in values.iter().zip(weights) {
            sum += to_f32(w / total) * to_f32(v);
        }
        let mean = self.round(f64::from(sum));
        if mean.is_nan() {
            return Err(ParamError::NotFinite {
                name: "values",
                value: mean,
            });
        }
        Ok(mean)
    }
}

/// `x` rounded to binary32 (to nearest, ties to even; `±∞` beyond its range).
fn to_f32(x: f64) -> f32 {
    #[expect(
        clippy::cast_possible_truncation,
        reason = "rounding to binary32 is what this models"
    )]
    let rounded = x as f32;
    rounded
}

/// `x` rounded to binary16 and back, exactly (module documentation, *Rounding*): the binade of `x`
/// (at least the smallest normal one) fixes the spacing `q` of binary16 values around it, and
/// `x/q` (exact: `q` is a power of two) is rounded to an integer, ties to even.
fn round_to_f16(x: f64) -> f64 {
    if !x.is_finite() {
        return x;
    }
    if x.abs() >= F16_OVERFLOW {
        return f64::INFINITY.copysign(x);
    }
    let spacing = power_of_two(binade(x.abs()).max(F16_MIN_EXPONENT) - F16_FRACTION_BITS);
    (x / spacing).round_ties_even() * spacing
}

/// `⌊log₂ a⌋` for a finite `a > 0` of f64's normal range; −1023 for 0 and f64's subnormals (far
/// below binary16's range, where only the floor at [`F16_MIN_EXPONENT`] matters).
fn binade(a: f64) -> i32 {
    let biased = (a.to_bits() >> 52) & 0x7ff;
    i32::try_from(biased).unwrap_or(0) - 1023
}

/// `2ᵉ` exactly, for `e` in f64's normal range (here `−24..=5`).
fn power_of_two(e: i32) -> f64 {
    u64::try_from(e + 1023).map_or(0.0, |biased| f64::from_bits(biased << 52))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::esm::ExponentialMoment;
    use crate::evsm::{Evsm4Moments, Warp, WarpedMoments};
    use crate::msm::MsmMoments;
    use crate::vsm::ShiftedMoments;

    /// The spacing of binary16 values in `[1, 2)`.
    const F16_EPSILON: f64 = 1.0 / 1024.0;
    /// The smallest positive binary16 value (subnormal), `2⁻²⁴`.
    const F16_MIN_POSITIVE_SUBNORMAL: f64 = 1.0 / 16_777_216.0;
    /// The smallest positive normal binary16 value, `2⁻¹⁴`.
    const F16_MIN_POSITIVE_NORMAL: f64 = 1.0 / 16_384.0;

    #[test]
    fn half_float_rounding_at_its_boundaries() {
        let h = |x: f64| MomentFormat::F16.round(x);
        // Exact values stay.
        for x in [0.0, 1.0, -2.5, F16_MAX, -F16_MAX, F16_MIN_POSITIVE_NORMAL] {
            assert_eq!(h(x), x, "{x}");
        }
        assert!(h(-0.0).is_sign_negative(), "the sign of zero is kept");
        // Ties to even: 1 + ε/2 lies halfway between 1 (even) and 1 + ε (odd).
        assert_eq!(h(1.0 + 0.5 * F16_EPSILON), 1.0);
        assert_eq!(h(1.0 + 1.5 * F16_EPSILON), 1.0 + 2.0 * F16_EPSILON);
        assert_eq!(h(1.0 + 0.500_001 * F16_EPSILON), 1.0 + F16_EPSILON);
        // 2049 is a tie between 2048 (even) and 2050; 2051 between 2050 and 2052 (even).
        assert_eq!(h(2049.0), 2048.0);
        assert_eq!(h(2051.0), 2052.0);
        // The top: up to 65520 (exclusive) rounds down to 65504; 65520 is a tie that goes to the
        // even 2¹⁶, which overflows.
        assert_eq!(h(65_519.999), F16_MAX);
        assert_eq!(h(65_520.0), f64::INFINITY);
        assert_eq!(h(-1e6), f64::NEG_INFINITY);
        assert_eq!(h(f64::INFINITY), f64::INFINITY);
        assert!(h(f64::NAN).is_nan());
        // Subnormals: spacing 2⁻²⁴ below 2⁻¹⁴; half the smallest is a tie that goes to 0 (even),
        // a little more rounds up to it.
        assert_eq!(
            h(3.0 * F16_MIN_POSITIVE_SUBNORMAL),
            3.0 * F16_MIN_POSITIVE_SUBNORMAL
        );
        assert_eq!(h(0.5 * F16_MIN_POSITIVE_SUBNORMAL), 0.0);
        assert_eq!(
            h(0.500_001 * F16_MIN_POSITIVE_SUBNORMAL),
            F16_MIN_POSITIVE_SUBNORMAL
        );
        assert_eq!(
            h(F16_MIN_POSITIVE_NORMAL - 0.4 * F16_MIN_POSITIVE_SUBNORMAL),
            F16_MIN_POSITIVE_NORMAL
        );
        assert_eq!(h(1e-300), 0.0);
        // A value and its rounding: within half a spacing, and rounding is idempotent.
        for x in [0.1, 0.95, 0.95 * 0.95, 2.5e-3, 1234.567, 6e-5] {
            let r = h(x);
            let spacing = power_of_two(binade(x).max(F16_MIN_EXPONENT) - F16_FRACTION_BITS);
            assert!((r - x).abs() <= 0.5 * spacing, "{x} → {r}");
            assert_eq!(h(r), r);
        }
    }

    #[test]
    fn binary32_rounding_is_the_cast() {
        assert_eq!(MomentFormat::F32.round(0.1), f64::from(0.1f32));
        assert_eq!(MomentFormat::F32.round(1e39), f64::INFINITY);
        assert_eq!(MomentFormat::F32.round(F16_MAX), F16_MAX);
    }

    #[test]
    fn a_blur_pass_is_a_weighted_mean_in_f32() {
        for format in MomentFormat::ALL {
            // Equal values of one binade stay within an ulp of themselves.
            let v = format.round(0.3);
            let mean = format.blur_pass(&[v; 5], &[1.0; 5]).unwrap();
            assert!((mean - v).abs() <= 2.0 * f64::from(f32::EPSILON), "{mean}");
            // Weights are normalised: 1 and 3 weigh ¼ and ¾.
            let mean = format.blur_pass(&[0.0, 1.0], &[1.0, 3.0]).unwrap();
            assert_eq!(mean, 0.75);
            // An overflowed moment stays infinite, of its sign.
            let mean = format
                .blur_pass(&[f64::INFINITY, 2.0], &[0.5, 0.5])
                .unwrap();
            assert_eq!(mean, f64::INFINITY);
            let mean = format
                .blur_pass(&[f64::NEG_INFINITY, -2.0], &[0.5, 0.5])
                .unwrap();
            assert_eq!(mean, f64::NEG_INFINITY);
        }
        // The write rounds to the format: ⅓ in binary16.
        let third = MomentFormat::F16
            .blur_pass(&[0.0, 1.0], &[2.0, 1.0])
            .unwrap();
        assert_eq!(third, round_to_f16(1.0 / 3.0));
        // The mean of the largest finite values stays finite: the weights' f32 rounding is far
        // below half an ulp of binary16.
        let top = MomentFormat::F16
            .blur_pass(&[F16_MAX; 3], &[1.0; 3])
            .unwrap();
        assert_eq!(top, F16_MAX);
        let bad = |values: &[f64], weights: &[f64]| {
            MomentFormat::F32
                .blur_pass(values, weights)
                .unwrap_err()
                .parameter()
        };
        assert_eq!(bad(&[1.0], &[1.0, 1.0]), "weights");
        assert_eq!(bad(&[1.0, 2.0], &[0.0, 0.0]), "weights");
        assert_eq!(bad(&[1.0], &[-1.0]), "weights");
        assert_eq!(
            bad(&[f64::INFINITY, f64::NEG_INFINITY], &[1.0, 1.0]),
            "values"
        );
        assert_eq!(MomentFormat::from_key("f16"), Some(MomentFormat::F16));
        assert_eq!(MomentFormat::from_key("f64"), None);
    }

    /// How far f32 storage moves the Chebyshev bounds (VSM, EVSM2, EVSM4) from the exact ones on the
    /// test distributions: f32 keeps each raw moment to about 6·10⁻⁸ (relative), which moves the
    /// mean by up to ~2·10⁻⁷ (the bound's slope in the mean is at most `0.65/σ = 650` at the
    /// variance floor [`MIN_VARIANCE`]) and the variance `E[d²] − E[d]²` by about 6·10⁻⁸·d² (the
    /// bound moves by `p(1 − p)·δσ²/σ²`, largest where the variance is smallest): 1.4·10⁻⁴
    /// measured, for VSM.
    const F32_CHEBYSHEV_TOLERANCE: f64 = 5e-4;
    /// The same, relative, on a stack whose variance (3.4·10⁻⁶) is only 60 times f32's rounding of
    /// `E[d²]` near 0.9: about 3 % of the lit fraction.
    const F32_THIN_STACK_TOLERANCE: f64 = 0.05;
    /// The same for ESM: the stored `exp(c·d)` keeps 6·10⁻⁸ of itself, and so does the lit
    /// fraction `exp(−c·t)·E[exp(c·d)]` (1.3·10⁻⁷ measured).
    const F32_ESM_TOLERANCE: f64 = 1e-6;
    /// The same for MSM: the raw power moments of depths near 1 cancel in the Hankel determinants
    /// (the hazard the exact moments' reference avoids, formulas.md §9.4), which the bias
    /// [`MSM_ALPHA`] absorbs only in part: 1.7·10⁻³ measured on the two steps at 0.9 and 0.95.
    const F32_MSM_TOLERANCE: f64 = 5e-3;

    /// How far binary16 storage moves EVSM2's bound (4.06 % lit) for one occluder at 0.99 and a
    /// receiver at 0.995 with `c = 11.08`: binary16 stores `w ≈ 228` and `w² ≈ 5.2·10⁴` to 0.125
    /// and 32, leaving a variance of −16, clamped to 0, so the variance floor decides as for the
    /// exact single depth; the rounded mean moves the lit fraction by 2·10⁻⁴ (measured).
    const F16_EVSM_TOLERANCE: f64 = 1e-3;

    /// The variance floor of the VSM and EVSM comparisons, `(10⁻³)²` of the depth range.
    const MIN_VARIANCE: f64 = 1e-6;
    /// MSM's bias, the papers' value for 16- and 32-bit storage.
    const MSM_ALPHA: f64 = 6e-5;
    /// Filament's default exponent (`c_F = 5.54` on depths in `[−1, 1]`) in this crate's units.
    const EVSM_EXPONENT: f64 = 11.08;
    /// Annen et al.'s exponent (their 32-bit maps).
    const ESM_EXPONENT: f64 = 80.0;

    /// What a texture of `format` holds after a box blur over `depths`: each texel's raw moments
    /// rounded to the format, then one blur pass of equal weights.
    fn stored<const N: usize>(
        format: MomentFormat,
        depths: &[f64],
        texel: impl Fn(f64) -> [f64; N],
    ) -> [f64; N] {
        let texels: Vec<[f64; N]> = depths
            .iter()
            .map(|&d| texel(d).map(|m| format.round(m)))
            .collect();
        let weights = vec![1.0; depths.len()];
        std::array::from_fn(|k| {
            let values: Vec<f64> = texels.iter().map(|t| t[k]).collect();
            format.blur_pass(&values, &weights).unwrap()
        })
    }

    /// Each method's lit fraction at `t` of `depths` (equal weights): exact (f64 moments about the
    /// first depth, as a lookup takes them about its centre texel) or through a texture of
    /// `format`. In the order VSM, ESM, EVSM2, EVSM4, MSM.
    fn lit_fractions(format: Option<MomentFormat>, depths: &[f64], t: f64) -> [f64; 5] {
        let r = depths[0];
        let (c, v) = (EVSM_EXPONENT, MIN_VARIANCE);
        let Some(format) = format else {
            return [
                ShiftedMoments::from_depths(r, depths)
                    .and_then(|m| m.lit_fraction(t, v))
                    .unwrap(),
                ExponentialMoment::from_depths(ESM_EXPONENT, depths)
                    .and_then(|m| m.lit_fraction(t))
                    .unwrap(),
                WarpedMoments::from_depths(Warp::Positive, c, r, depths)
                    .and_then(|m| m.lit_fraction(t, v))
                    .unwrap(),
                Evsm4Moments::from_depths(c, c, r, depths)
                    .and_then(|m| m.lit_fraction(t, v))
                    .unwrap(),
                MsmMoments::from_depths(r, depths)
                    .and_then(|m| m.lit_fraction(t, MSM_ALPHA))
                    .unwrap(),
            ];
        };
        let warp = |warp: Warp| {
            let raw = stored(format, depths, |d| WarpedMoments::texel_moments(warp, c, d));
            WarpedMoments::from_raw_moments(warp, c, raw)
                .unwrap()
                .map_or(1.0, |m| m.lit_fraction(t, v).unwrap())
        };
        let esm = stored(format, depths, |d| {
            ExponentialMoment::texel_moments(ESM_EXPONENT, d)
        });
        [
            ShiftedMoments::from_raw_moments(stored(format, depths, ShiftedMoments::texel_moments))
                .and_then(|m| m.lit_fraction(t, v))
                .unwrap(),
            ExponentialMoment::from_raw_moments(ESM_EXPONENT, esm)
                .unwrap()
                .map_or(1.0, |m| m.lit_fraction(t).unwrap()),
            warp(Warp::Positive),
            warp(Warp::Positive).min(warp(Warp::Negative)),
            MsmMoments::from_raw_moments(stored(format, depths, MsmMoments::texel_moments))
                .and_then(|m| m.lit_fraction(t, MSM_ALPHA))
                .unwrap(),
        ]
    }

    /// Depths as a 32-bit depth map stores them.
    fn f32_depth(d: f64) -> f64 {
        MomentFormat::F32.round(d)
    }

    /// The test distributions: one step, two steps (a share at the front), a slope (midpoint rule
    /// on 25 depths, a 5 × 5 kernel's worth), each in f32 depths.
    fn distributions() -> Vec<(String, Vec<f64>)> {
        let mut cases = Vec::new();
        for d0 in [0.1, 0.5, 0.9] {
            cases.push((format!("one step at {d0}"), vec![f32_depth(d0); 9]));
        }
        for (d0, d1, front) in [
            (0.2, 0.5, 3),
            (0.45, 0.5, 5),
            (0.3, 0.31, 12),
            (0.9, 0.95, 4),
        ] {
            let mut depths = vec![f32_depth(d0); front];
            depths.resize(25, f32_depth(d1));
            cases.push((
                format!("two steps {d0}, {d1}, {front} of 25 at the front"),
                depths,
            ));
        }
        for (a, b) in [(0.2, 0.3), (0.6, 0.62)] {
            let h = (b - a) / 25.0;
            let depths = (0..25)
                .map(|i| f32_depth(a + h * (f64::from(i) + 0.5)))
                .collect();
            cases.push((format!("slope {a}..{b}"), depths));
        }
        cases
    }

    /// Claim: with f32 storage every method's lit fraction is the exact one's within its tolerance
    /// ([`F32_CHEBYSHEV_TOLERANCE`], [`F32_ESM_TOLERANCE`], [`F32_MSM_TOLERANCE`]), on every test
    /// distribution and receiver, and in `[0, 1]`.
    #[test]
    fn f32_storage_reconstructs_the_exact_lit_fractions() {
        let names = ["VSM", "ESM", "EVSM2", "EVSM4", "MSM"];
        let tolerances = [
            F32_CHEBYSHEV_TOLERANCE,
            F32_ESM_TOLERANCE,
            F32_CHEBYSHEV_TOLERANCE,
            F32_CHEBYSHEV_TOLERANCE,
            F32_MSM_TOLERANCE,
        ];
        for (name, depths) in distributions() {
            for k in 0..=40 {
                let t = 0.025 * f64::from(k);
                let exact = lit_fractions(None, &depths, t);
                let stored = lit_fractions(Some(MomentFormat::F32), &depths, t);
                for m in 0..5 {
                    let (e, s) = (exact[m], stored[m]);
                    assert!((0.0..=1.0).contains(&s), "{} {name} t = {t}: {s}", names[m]);
                    assert!(
                        (e - s).abs() <= tolerances[m],
                        "{} {name} t = {t}: exact {e}, f32 {s}",
                        names[m]
                    );
                }
            }
        }
    }

    /// Claim: VSM's variance cancels in binary16 on a distant two-depth stack. Four of 25 depths at
    /// 0.95 and the rest at 0.955 have a variance of 3.4·10⁻⁶, but binary16 keeps `E[d]` and
    /// `E[d²]` near 0.9 only to 2⁻¹¹ ≈ 4.9·10⁻⁴: their stored difference is 3.3·10⁻⁴, and a
    /// receiver at 0.965, which f32 storage shadows as the exact bound does (2.8 % lit, within
    /// [`F32_THIN_STACK_TOLERANCE`]), reads 74 % lit — a leak. (Rounding can as well cancel the
    /// variance to 0 and over-darken.)
    #[test]
    fn half_floats_lose_a_distant_stacks_variance() {
        let mut depths = vec![f32_depth(0.95); 4];
        depths.resize(25, f32_depth(0.955));
        let t = 0.965;
        let [exact, ..] = lit_fractions(None, &depths, t);
        let [f32_lit, ..] = lit_fractions(Some(MomentFormat::F32), &depths, t);
        let [f16_lit, ..] = lit_fractions(Some(MomentFormat::F16), &depths, t);
        assert!(exact < 0.03, "{exact}");
        assert!(
            (f32_lit - exact).abs() <= F32_THIN_STACK_TOLERANCE * exact,
            "{f32_lit} against {exact}"
        );
        assert!(f16_lit > 0.7, "binary16 lights the receiver: {f16_lit}");
        let [mean, mean_square] = stored(MomentFormat::F16, &depths, ShiftedMoments::texel_moments);
        let exact_variance = ShiftedMoments::from_depths(0.95, &depths)
            .unwrap()
            .variance();
        assert!(mean_square - mean * mean > 50.0 * exact_variance);
    }

    /// Claim: the EVSM warps overflow binary16 exactly above the exponent `ln 65504 ≈ 11.09` (in
    /// Filament's and MJP's units, where the exponent acts on `2d − 1`, their 5.54 against 6):
    /// at `c = 11.08` the largest stored value, `w² = exp(c)` at depth 1, is finite and a receiver
    /// behind an occluder at 0.99 is shadowed as in f64 (within [`F16_EVSM_TOLERANCE`]); at `c = 12`
    /// the squares of depths above
    /// `½ + ln(65504)/24 ≈ 0.962` overflow to `∞`, the positive warp reads lit (*overflow reads
    /// lit*), and so does EVSM2, while EVSM4 keeps its negative warp's bound. ESM's `exp(c·d)`
    /// overflows binary16 once `c·d > 11.09`: at Annen et al.'s `c = 80` every depth above 0.139.
    #[test]
    fn overflowed_moments_read_lit() {
        let f16 = MomentFormat::F16;
        for d in [0.0, 1.0] {
            for warp in [Warp::Positive, Warp::Negative] {
                for m in WarpedMoments::texel_moments(warp, EVSM_EXPONENT, d) {
                    assert!(f16.round(m).is_finite(), "{warp:?} at {d}: {m}");
                }
            }
        }
        let depths = [f32_depth(0.99); 9];
        let (t, v) = (0.995, MIN_VARIANCE);
        for (c, overflows) in [(EVSM_EXPONENT, false), (12.0, true)] {
            let exact = WarpedMoments::from_depths(Warp::Positive, c, depths[0], &depths)
                .and_then(|m| m.lit_fraction(t, v))
                .unwrap();
            assert!(exact < 0.05, "c = {c}: {exact}");
            let raw = stored(f16, &depths, |d| {
                WarpedMoments::texel_moments(Warp::Positive, c, d)
            });
            assert_eq!(raw[1].is_infinite(), overflows, "c = {c}: {raw:?}");
            let positive = WarpedMoments::from_raw_moments(Warp::Positive, c, raw).unwrap();
            assert_eq!(positive.is_none(), overflows);
            let lit = positive.map_or(1.0, |m| m.lit_fraction(t, v).unwrap());
            if overflows {
                assert_eq!(lit, 1.0);
            } else {
                assert!(
                    (lit - exact).abs() <= F16_EVSM_TOLERANCE,
                    "c = {c}: {lit} against {exact}"
                );
            }
            // The negative warp of the same depths does not overflow, and still shadows.
            let raw = stored(f16, &depths, |d| {
                WarpedMoments::texel_moments(Warp::Negative, c, d)
            });
            let negative = WarpedMoments::from_raw_moments(Warp::Negative, c, raw)
                .unwrap()
                .expect("finite");
            assert!(negative.lit_fraction(t, v).unwrap() < 0.5);
        }
        let esm = |d: f64| {
            let raw = stored(f16, &[d], |d| {
                ExponentialMoment::texel_moments(ESM_EXPONENT, d)
            });
            ExponentialMoment::from_raw_moments(ESM_EXPONENT, raw).unwrap()
        };
        assert!(esm(0.13).is_some());
        assert!(esm(0.14).is_none());
        let f32_esm = stored(MomentFormat::F32, &[1.0], |d| {
            ExponentialMoment::texel_moments(ESM_EXPONENT, d)
        });
        assert!(f32_esm[0].is_finite(), "exp(80) fits binary32");
        assert_eq!(
            WarpedMoments::from_raw_moments(Warp::Positive, 5.0, [f64::NAN, 1.0])
                .unwrap_err()
                .parameter(),
            "mean"
        );
    }
}
