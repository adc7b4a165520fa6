//! Variance shadow maps: the one-sided Chebyshev (Cantelli) bound of the CAD survey's eq. 2
//! (reconstructed, formulas.md §4.2), on *shifted* moments (formulas.md §9.4).
//!
//! A VSM texel stores the first two moments of the depths under its filter kernel. The receiver at
//! depth `t` is lit with intensity `p_max(t) = σ²/(σ² + (t − μ)²)` when `t > μ`, and fully when
//! `t ≤ μ`. `σ² = M2 − M1²` cancels catastrophically when the depths are close together (f32 returns
//! exactly 0 for depths 0.95 ± 1e-4); storing moments of `x − r` for a reference `r` near the depths
//! removes most of it.
//!
//! A map whose moments a texture stores (`crate::storage`) holds the raw moments `d`, `d²` instead
//! ([`ShiftedMoments::texel_moments`], read back by [`ShiftedMoments::from_raw_moments`]), as
//! Donnelly & Lauritzen's shadow pass writes them, and keeps the variance only as well as its format
//! does.

use crate::depth_samples::Samples;
use crate::error::ParamError;

/// The first two moments of a set of depths `x` about a reference `r`:
/// `M1 = E[x − r]`, `M2 = E[(x − r)²]`.
///
/// # Guarantees
/// `r`, `M1` and `M2` are finite and `M2 ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShiftedMoments {
    reference: f64,
    m1: f64,
    m2: f64,
}

impl ShiftedMoments {
    /// Two scalars per texel: `E[x]` and `E[x²]` (as shifted moments, `M1` and `M2`).
    pub const MOMENTS_PER_TEXEL: usize = 2;

    /// From stored moments. `reference = 0` takes raw moments `E[x]`, `E[x²]`, as
    /// [`Self::from_raw_moments`] does. `Err` names `reference`, `m1` or `m2`.
    pub fn new(reference: f64, m1: f64, m2: f64) -> Result<Self, ParamError> {
        ParamError::finite("reference", reference)?;
        ParamError::finite("m1", m1)?;
        ParamError::finite("m2", m2)?;
        ParamError::require("m2", m2, m2 >= 0.0, || "at least 0".into())?;
        Ok(Self { reference, m1, m2 })
    }

    /// The moments of `depths` (equal weights, summed in order) about `reference`. `Err` names
    /// `reference` or `depths` (empty, or a value that is not finite).
    pub fn from_depths(reference: f64, depths: &[f64]) -> Result<Self, ParamError> {
        ParamError::finite("reference", reference)?;
        if depths.is_empty() {
            return Err(ParamError::OutOfDomain {
                name: "depths",
                value: 0.0,
                requirement: "non-empty".into(),
            });
        }
        let (mut s1, mut s2) = (0.0, 0.0);
        for &x in depths {
            let y = ParamError::finite("depths", x)? - reference;
            s1 += y;
            s2 += y * y;
        }
        let count = depths.len() as f64;
        Self::new(reference, s1 / count, s2 / count)
    }

    /// The moments of `depths` with one weight each (a filter kernel's taps: the weighted means
    /// `Σ wᵢ·(xᵢ − r)ᵏ / Σ wᵢ`, each clamped to the range of its terms, as in
    /// `crate::filterable`'s *Weights*), about `reference`. Unlike [`Self::from_depths`], the depths
    /// must lie in `[0, 1]`, as a shadow map stores them. `Err` names `reference`, `depths` (empty,
    /// or a value not in `[0, 1]`) or `weights` (wrong length, negative, not finite, or summing to
    /// 0).
    pub fn from_weighted_depths(
        reference: f64,
        depths: &[f64],
        weights: &[f64],
    ) -> Result<Self, ParamError> {
        ParamError::finite("reference", reference)?;
        let samples = Samples::new(depths, Some(weights))?;
        let y = |x: f64| x - reference;
        Self::new(reference, samples.mean(y), samples.mean(|x| y(x) * y(x)))
    }

    /// The raw moments one texel of depth `depth` stores, `[d, d²]` (Donnelly & Lauritzen 2006: what
    /// the shadow pass writes, before the format rounds it; `crate::storage`). No validation.
    #[must_use]
    pub fn texel_moments(depth: f64) -> [f64; 2] {
        [depth, depth * depth]
    }

    /// From blurred raw moments `[E[d], E[d²]]` as a texture holds them (`crate::storage`): the
    /// moments about reference 0, whose variance `E[d²] − E[d]²` cancels as the stored precision
    /// allows (the hazard [`Self::from_depths`] avoids by its reference). They lie in `[0, 1]` and
    /// never overflow. `Err` as [`Self::new`].
    pub fn from_raw_moments([mean, mean_square]: [f64; 2]) -> Result<Self, ParamError> {
        Self::new(0.0, mean, mean_square)
    }

    /// μ = r + M1, the mean depth.
    #[must_use]
    pub fn mean(&self) -> f64 {
        self.reference + self.m1
    }

    /// σ² = M2 − M1², clamped at 0 (rounding can make it slightly negative).
    #[must_use]
    pub fn variance(&self) -> f64 {
        (self.m2 - self.m1 * self.m1).max(0.0)
    }

    /// The lit fraction at receiver depth `t` (CAD eq. 2): 1 for `t ≤ μ`, else
    /// `σ²/(σ² + (t − μ)²)` with `σ²` raised to at least `min_variance` (the usual guard against
    /// acne where the variance vanishes). `t − μ` is formed as `(t − r) − M1`.
    /// `Err` names `t` or `min_variance` (must be finite and ≥ 0).
    pub fn lit_fraction(&self, t: f64, min_variance: f64) -> Result<f64, ParamError> {
        ParamError::finite("t", t)?;
        ParamError::finite("min_variance", min_variance)?;
        ParamError::require("min_variance", min_variance, min_variance >= 0.0, || {
            "at least 0".into()
        })?;
        let excess = (t - self.reference) - self.m1;
        if excess <= 0.0 {
            return Ok(1.0);
        }
        let variance = self.variance().max(min_variance);
        Ok(variance / (variance + excess * excess))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shifted_moments_keep_the_variance_that_raw_moments_lose() {
        // formulas.md §9.4: depths 0.95 ± 1e-4. Raw f32 moments give exactly 0; f64 raw moments
        // lose about half the digits; shifted f64 moments keep them.
        let depths = [0.95 - 1e-4, 0.95 + 1e-4];
        let exact = 1e-8;
        let shifted = ShiftedMoments::from_depths(0.95, &depths).unwrap();
        assert!((shifted.variance() - exact).abs() <= 1e-10 * exact);
        #[expect(
            clippy::cast_possible_truncation,
            reason = "the test demonstrates what f32 moments lose"
        )]
        let raw_f32: Vec<f32> = depths.iter().map(|&d| d as f32).collect();
        let m1 = (raw_f32[0] + raw_f32[1]) / 2.0;
        let m2 = (raw_f32[0] * raw_f32[0] + raw_f32[1] * raw_f32[1]) / 2.0;
        assert_eq!(m2 - m1 * m1, 0.0, "the hazard this type exists for");
    }

    #[test]
    fn weighted_moments_weigh_each_depth() {
        let depths = [0.25, 0.5, 0.5, 0.75];
        let plain = ShiftedMoments::from_depths(0.5, &depths).unwrap();
        let equal = ShiftedMoments::from_weighted_depths(0.5, &depths, &[2.0; 4]).unwrap();
        assert!((plain.m1 - equal.m1).abs() <= f64::EPSILON);
        assert!((plain.m2 - equal.m2).abs() <= f64::EPSILON);
        // Weights 3 and 1: the mean is ¾ of the way to the first depth.
        let m = ShiftedMoments::from_weighted_depths(0.5, &[0.2, 0.6], &[3.0, 1.0]).unwrap();
        assert!((m.mean() - 0.3).abs() < 1e-15, "{}", m.mean());
        assert!((m.variance() - 0.03).abs() < 1e-15, "{}", m.variance());
        let e = |r: Result<ShiftedMoments, ParamError>| r.unwrap_err().parameter();
        assert_eq!(
            e(ShiftedMoments::from_weighted_depths(0.5, &[1.5], &[1.0])),
            "depths"
        );
        assert_eq!(
            e(ShiftedMoments::from_weighted_depths(0.5, &[0.5], &[])),
            "weights"
        );
        // Raw moments are the moments about 0.
        let raw = ShiftedMoments::from_raw_moments([0.3, 0.12]).unwrap();
        assert_eq!((raw.mean(), raw.variance()), (0.3, 0.12 - 0.09));
        assert_eq!(ShiftedMoments::texel_moments(0.5), [0.5, 0.25]);
    }

    #[test]
    fn the_bound_is_one_in_front_and_sharp_for_two_points() {
        let m = ShiftedMoments::from_depths(0.5, &[0.4, 0.6]).unwrap();
        assert_eq!(m.lit_fraction(0.3, 0.0).unwrap(), 1.0);
        assert_eq!(m.lit_fraction(m.mean(), 0.0).unwrap(), 1.0);
        // A two-point distribution {μ − σ²/(t−μ) w.p. p, t w.p. 1−p} attains the bound; here the
        // mass at 0.6 is 1/2 and the bound at t = 0.6 is σ²/(σ² + σ²) = 1/2.
        let p = m.lit_fraction(0.6, 0.0).unwrap();
        assert!((p - 0.5).abs() < 1e-12, "{p}");
        assert_eq!(m.lit_fraction(f64::NAN, 0.0).unwrap_err().parameter(), "t");
        assert_eq!(
            m.lit_fraction(0.7, -1.0).unwrap_err().parameter(),
            "min_variance"
        );
        assert_eq!(
            ShiftedMoments::from_depths(0.5, &[])
                .unwrap_err()
                .parameter(),
            "depths"
        );
    }
}
