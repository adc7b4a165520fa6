//! Exponential shadow maps: Annen, Mertens, Seidel, Flerackers & Kautz, *Exponential Shadow Maps*,
//! Graphics Interface 2008.
//!
//! The binary test `H(d − t)` of an occluder at depth `d` and a receiver at depth `t` is replaced by
//! `exp(−c·(t − d))`, which tends to it for `t > d` as the exponent `c` grows and factors into a
//! receiver term and an occluder term. The map stores the occluder term `exp(c·d)`, filtered; the
//! receiver is lit with
//!
//! ```text
//! lit(t) = clamp(exp(−c·t) · E[exp(c·d)], 0, 1)
//! ```
//!
//! (the paper's filtered shadow function, clamped to `[0, 1]` as implementations do). It is exact —
//! it equals the filtered binary test — only when `c → ∞` *and* the receiver lies behind every
//! occluder under the kernel; a receiver in front of part of the kernel (`d₀ < t < d₁`) sees
//! `exp(c·(d₁ − t))` terms larger than 1 and is lit too much, which is ESM's characteristic leak at
//! contact and at depth discontinuities.
//!
//! # Stable form: log space
//! `exp(c·d)` overflows f64 once `c·d > 709` and f32 once `c·d > 88.7`; the paper's GPU form is
//! limited to modest `c` for that reason. This module keeps the filtered moment as its *exponential
//! mean depth*
//!
//! ```text
//! d̄ = (1/c)·ln E[exp(c·d)],   lit(t) = exp(−c·max(t − d̄, 0))
//! ```
//!
//! which is the same function (`exp(−c·t)·E[exp(c·d)] = exp(c·(d̄ − t))`, and the clamp at 1
//! becomes the `max` with 0), computed by log-sum-exp: with normalised weights `ŵᵢ` and `p` the
//! sample with the largest `c·dᵢ + ln ŵᵢ`,
//!
//! ```text
//! d̄ = d_p + (ln ŵ_p + ln Σᵢ exp(c·(dᵢ − d_p) + ln ŵᵢ − ln ŵ_p)) / c
//! ```
//!
//! Every exponential there has an argument `≤ 0` and the sum lies in `[1, n]`, so nothing
//! overflows, nothing underflows into a logarithm of 0, for any `c > 0`, and `d̄` is exact for one
//! depth (`d̄ = d₀`). This is the log-space filtering of Salvi's ESM variant (ShaderX⁶, 2008),
//! done exactly. Stored values about another reference `r` (`E[exp(c·(d − r))]`, the form a GPU
//! stores with `r = 0`) are accepted by [`ExponentialMoment::new`].
//!
//! # Storage: the paper's raw moment
//! A map whose moment a texture stores (`crate::storage`) holds what Annen et al.'s shadow pass
//! writes, `exp(c·d)` about depth 0 ([`ExponentialMoment::texel_moments`]), not Salvi's log-space
//! form, and reads it back with [`ExponentialMoment::from_raw_moments`]. It overflows binary16 for
//! `c·d > 11.09` and binary32 for `c·d > 88.72`; an overflowed texel reads lit.

use crate::depth_samples::{Samples, unit_depth};
use crate::error::ParamError;

/// The filtered ESM moment for an exponent `c`, held as the exponential mean depth
/// `d̄ = (1/c)·ln E[exp(c·d)]`.
///
/// # Guarantees
/// `c` is finite and `> 0`; `d̄` is finite. Built from depths, `min dᵢ ≤ d̄ ≤ max dᵢ` over the
/// depths of positive weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExponentialMoment {
    exponent: f64,
    mean_depth: f64,
}

impl ExponentialMoment {
    /// One scalar per texel: `E[exp(c·d)]`.
    pub const MOMENTS_PER_TEXEL: usize = 1;

    /// From a stored moment `moment = E[exp(c·(d − r))]` about a reference depth `r ∈ [0, 1]`
    /// (`r = 0`: the moment as the paper stores it). `Err` names `exponent` (must be finite and
    /// `> 0`), `reference` or `moment` (must be finite and `> 0`).
    pub fn new(exponent: f64, reference: f64, moment: f64) -> Result<Self, ParamError> {
        let exponent = check_exponent(exponent)?;
        unit_depth("reference", reference)?;
        ParamError::finite("moment", moment)?;
        ParamError::require("moment", moment, moment > 0.0, || "greater than 0".into())?;
        Ok(Self {
            exponent,
            mean_depth: reference + moment.ln() / exponent,
        })
    }

    /// The moment of `depths`, all of the same weight. `Err` as [`Self::from_weighted_depths`].
    pub fn from_depths(exponent: f64, depths: &[f64]) -> Result<Self, ParamError> {
        Self::build(exponent, &Samples::new(depths, None)?)
    }

    /// The moment of `depths` with one weight each (the filter kernel), by log-sum-exp (module
    /// documentation). `Err` names `exponent`, `depths` (empty, or a value not
    /// in `[0, 1]`) or `weights` (wrong length, negative, not finite, or summing to 0).
    pub fn from_weighted_depths(
        exponent: f64,
        depths: &[f64],
        weights: &[f64],
    ) -> Result<Self, ParamError> {
        Self::build(exponent, &Samples::new(depths, Some(weights))?)
    }

    fn build(exponent: f64, samples: &Samples<'_>) -> Result<Self, ParamError> {
        let exponent = check_exponent(exponent)?;
        // Log-sum-exp of c·dᵢ + ln ŵᵢ about its largest term p: every exponential has an argument
        // ≤ 0 and the sum is ≥ 1 (term p itself). Logarithms of the weights, not ŵᵢ = wᵢ/W, so that
        // a tiny weight does not underflow to 0 and lose its depth.
        let log_total = samples.total().ln();
        let log_weight = |w: f64| w.ln() - log_total;
        let (pivot, pivot_log_weight) = samples
            .iter()
            .filter(|&(_, w)| w > 0.0)
            .map(|(d, w)| (d, log_weight(w)))
            // Ordered by dᵢ + ln ŵᵢ / c (the same order as c·dᵢ + ln ŵᵢ, without overflow).
            .fold((0.0, f64::NEG_INFINITY), |best, (d, lw)| {
                if d + lw / exponent > best.0 + best.1 / exponent {
                    (d, lw)
                } else {
                    best
                }
            });
        let sum: f64 = samples
            .iter()
            .map(|(d, w)| (exponent * (d - pivot) + (log_weight(w) - pivot_log_weight)).exp())
            .sum();
        // The exponential mean lies between the least and greatest depth of positive weight; the
        // clamp removes rounding only.
        let (low, high) = samples
            .iter()
            .filter(|&(_, w)| w > 0.0)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (d, _)| {
                (lo.min(d), hi.max(d))
            });
        Ok(Self {
            exponent,
            mean_depth: (pivot + (pivot_log_weight + sum.ln()) / exponent).clamp(low, high),
        })
    }

    /// The raw moment one texel of depth `depth` stores, `[exp(c·d)]`: the occluder term as Annen et
    /// al. store it (about depth 0, not in log space; `crate::storage`), before the format rounds
    /// it. It overflows binary16 once `c·d > ln 65504 ≈ 11.09` and binary32 once `c·d > 88.72`.
    /// No validation.
    #[must_use]
    pub fn texel_moments(exponent: f64, depth: f64) -> [f64; 1] {
        [(exponent * depth).exp()]
    }

    /// From a blurred raw moment `[E[exp(c·d)]]` as a texture holds it (`crate::storage`): the
    /// moment about reference 0 ([`Self::new`]), or `None` when it is `+∞` (it overflowed its
    /// format: no exponential mean is recorded, and the texel reads lit — `crate::storage`,
    /// *overflow reads lit*). `Err` names `exponent` or `moment`
    /// (NaN, `−∞`, or not above 0).
    pub fn from_raw_moments(exponent: f64, [moment]: [f64; 1]) -> Result<Option<Self>, ParamError> {
        let exponent = check_exponent(exponent)?;
        if moment == f64::INFINITY {
            return Ok(None);
        }
        Self::new(exponent, 0.0, moment).map(Some)
    }

    /// The exponent `c`.
    #[must_use]
    pub fn exponent(&self) -> f64 {
        self.exponent
    }

    /// `d̄ = (1/c)·ln E[exp(c·d)]`, the exponential mean ("soft maximum") of the depths.
    #[must_use]
    pub fn mean_depth(&self) -> f64 {
        self.mean_depth
    }

    /// The stored moment about a reference `r`, `E[exp(c·(d − r))] = exp(c·(d̄ − r))` (it may
    /// overflow to `+∞` or underflow to 0 for large `c`; the type itself never does).
    #[must_use]
    pub fn moment_about(&self, reference: f64) -> f64 {
        (self.exponent * (self.mean_depth - reference)).exp()
    }

    /// The lit fraction at receiver depth `t`: `clamp(exp(−c·t)·E[exp(c·d)], 0, 1)
    /// = exp(−c·max(t − d̄, 0))` (Annen et al. 2008, the filtered exponential test; module
    /// documentation). In `[0, 1]`; 1 for `t ≤ d̄`. `Err` names `t` (must be finite).
    pub fn lit_fraction(&self, t: f64) -> Result<f64, ParamError> {
        ParamError::finite("t", t)?;
        let excess = t - self.mean_depth;
        Ok(if excess <= 0.0 {
            1.0
        } else {
            (-self.exponent * excess).exp()
        })
    }
}

fn check_exponent(exponent: f64) -> Result<f64, ParamError> {
    ParamError::finite("exponent", exponent)?;
    ParamError::require("exponent", exponent, exponent > 0.0, || {
        "greater than 0".into()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_depth_is_its_own_mean_and_the_test_is_exponential_behind_it() {
        let m = ExponentialMoment::from_depths(80.0, &[0.4, 0.4, 0.4]).unwrap();
        assert_eq!(m.mean_depth(), 0.4);
        assert_eq!(m.lit_fraction(0.4).unwrap(), 1.0);
        assert_eq!(m.lit_fraction(0.1).unwrap(), 1.0);
        let lit = m.lit_fraction(0.45).unwrap();
        assert!((lit - (-80.0f64 * 0.05).exp()).abs() < 1e-15, "{lit}");
    }

    #[test]
    fn no_overflow_where_the_raw_moment_would_overflow() {
        // c·d = 5000: exp overflows f64 by far, the log form does not care.
        let m = ExponentialMoment::from_weighted_depths(5000.0, &[0.9, 1.0], &[1.0, 1.0]).unwrap();
        let expected = 1.0 + (0.5f64.ln() + (1.0 + (-500.0f64).exp()).ln()) / 5000.0;
        assert!((m.mean_depth() - expected).abs() < 1e-15);
        assert_eq!(m.lit_fraction(0.95).unwrap(), 1.0);
        assert!(m.lit_fraction(1.0).unwrap() > 0.49);
        assert!(m.moment_about(0.0).is_infinite());
        // The stored form about r = 1 is finite and gives the same map.
        let stored = ExponentialMoment::new(5000.0, 1.0, m.moment_about(1.0)).unwrap();
        assert!((stored.mean_depth() - m.mean_depth()).abs() < 1e-15);
    }

    #[test]
    fn errors_name_the_parameter() {
        assert_eq!(
            ExponentialMoment::from_depths(0.0, &[0.5])
                .unwrap_err()
                .parameter(),
            "exponent"
        );
        assert_eq!(
            ExponentialMoment::new(10.0, 0.5, 0.0)
                .unwrap_err()
                .parameter(),
            "moment"
        );
        assert_eq!(
            ExponentialMoment::new(10.0, 2.0, 1.0)
                .unwrap_err()
                .parameter(),
            "reference"
        );
        let m = ExponentialMoment::from_depths(10.0, &[0.5]).unwrap();
        assert_eq!(m.lit_fraction(f64::INFINITY).unwrap_err().parameter(), "t");
        assert_eq!(m.lit_fraction(1e300).unwrap(), 0.0);
    }
}
