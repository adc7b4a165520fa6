//! Exponential variance shadow maps (EVSM): the exponential depth warps of Lauritzen & McCool,
//! *Layered Variance Shadow Maps*, Graphics Interface 2008, with the one-sided
//! Chebyshev (Cantelli) bound of variance shadow maps (Donnelly & Lauritzen 2006; Lauritzen,
//! *Summed-Area Variance Shadow Maps*, GPU Gems 3 ch. 8, 2007; the CAD survey's eq. 2,
//! formulas.md §4.2) applied to each warped depth.
//!
//! A warp is an increasing function `w` of depth, so `P(d ≥ t) = P(w(d) ≥ w(t))` and the Cantelli
//! bound on the warped depths is again an upper bound on the lit fraction:
//!
//! ```text
//! w₊(d) = exp(c₊·d),   w₋(d) = −exp(−c₋·d)
//! p(t) = 1                          if w(t) ≤ E[w]
//!      = σ_w² / (σ_w² + (w(t) − E[w])²)   else,   σ_w² = E[w²] − E[w]²
//! EVSM2: p₊(t)             (2 moments: E[w₊], E[w₊²])
//! EVSM4: min(p₊(t), p₋(t))  (4 moments: E[w₊], E[w₊²], E[w₋], E[w₋²])
//! ```
//!
//! The convex positive warp moves a receiver behind its occluders far from them relative to the
//! occluders' own spread, which is what shrinks VSM's leak (for a two-occluder stack the bound
//! provably drops: [`Evsm2Moments`]). The concave negative warp errs the other way; each bound is
//! valid, so their minimum is, and it is never worse than either.
//!
//! # Stable form: scaled and shifted warps
//! The Cantelli bound is unchanged when the warped value is replaced by `a·w + b` with `a > 0`. This
//! module stores moments of
//!
//! ```text
//! u₊(d) = exp(c₊·(d − r)) − 1  = expm1(c₊·(d − r))
//! u₋(d) = 1 − exp(−c₋·(d − r)) = −expm1(−c₋·(d − r))
//! ```
//!
//! about a reference depth `r ∈ [0, 1]` (`u = (w − w(r))/|w(r)|`): the scaling keeps `u²` finite for
//! every exponent up to [`MAX_EXPONENT`] and the shift removes most of the cancellation in
//! `E[u²] − E[u]²` when `r` is near the depths — the EVSM counterpart of [`crate::vsm`]'s shifted
//! moments (formulas.md §9.4). `expm1` keeps `u` accurate when `c·(d − r)` is small. The shift has
//! one hazard of its own: `u₊` rounds to −1 once `c₊·(r − d) > 37` (`e⁻³⁷` is below half an ulp of
//! 1), and `u₋` to 1 once `c₋·(d − r) > 37`, so a reference far above every depth (below, for the
//! negative warp) loses them: keep `r` within the depths (their mean is a good choice). The GPU's
//! raw moments are `E[exp(c₊·d)] = exp(c₊·r)·(1 + M1)` and
//! `E[exp(2c₊·d)] = exp(2c₊·r)·(1 + 2·M1 + M2)` (likewise for the negative warp with `exp(−c₋·r)`
//! and `1 − M1`).
//!
//! # Minimum variance: in depth units, carried through the warp
//! As in VSM a minimum variance keeps the bound from collapsing where the filtered depths are all
//! equal (acne). Here it is given in depth² units, like [`crate::vsm`]'s, and carried into each warp
//! by the warp's slope at the receiver (the first-order "delta method"): `σ_u,min = |u'(t)|·σ_min`,
//! with `u₊'(t) = c₊·exp(c₊·(t − r))` and `u₋'(t) = c₋·exp(−c₋·(t − r))`. So the knob means the same
//! thing for every exponent, and as `c → 0` EVSM2 tends to VSM with the same `min_variance`. Because
//! the positive warp's slope grows as fast as the gap `u₊(t) − M1`, a floor keeps `p₊` at least
//! `1/(1 + (c₊·σ_min)⁻²)` however far behind the receiver is (Filament's relative floor does the
//! same); the negative warp has no such limit. Filament's floor `0.002·w²` per warp (below) is this
//! rule with `min_variance = 0.002/c²` in our units (its receiver-slope term, and its
//! light-bleeding reduction, are left to callers).
//!
//! # Domain: depths in `[0, 1]`, warped directly (named choice: *unit-interval warp*)
//! Depths are in `[0, 1]` and the exponents act on them directly, as in Lauritzen & McCool. Filament
//! (google/filament, `shaders/src/surface_main.vs`: `depth = depth * 2.0 - 1.0` before the warp;
//! `shaders/src/surface_shadowing.fs` `evaluateEVSM`; `shaders/src/surface_depth_main.fs`) first maps
//! depth to `[−1, 1]` and uses one exponent `c_F` for both warps (`pw = exp(c·depth)`,
//! `nw = −1/pw`). Because of the scale invariance above that is the same bound as ours with
//! `c₊ = c₋ = 2·c_F`: Filament's default `c_F = 5.54`, the fp16 limit (42 for fp32;
//! `filament/include/filament/Options.h`, `VsmShadowOptions::exponent`), is `c = 11.08` here (84
//! for fp32). Its centring at mid-depth only changes what overflows in 16- and 32-bit storage.
//!
//! # Storage: raw warps about ½ (named choice: *centred raw warps*)
//! The moments above are formed in f64 from the depths. A map whose moments a texture stores
//! (`crate::storage`) holds what the engines' shadow pass writes: the raw warps centred on mid-depth,
//! `w₊ = exp(c₊·(d − ½))`, `w₋ = −exp(−c₋·(d − ½))`, and their squares
//! ([`WarpedMoments::texel_moments`]) — Filament's and MJP's `WarpDepth` (TheRealMJP/Shadows,
//! `Shadows/VSM.hlsl`: `depth = 2.0f * depth - 1.0f`, then `exp(c_F·depth)`, `−exp(−c_F·depth)`),
//! with `c = 2·c_F`. The largest stored value is `w² = exp(c)` (the positive warp at `d = 1`, the
//! negative one at `d = 0`), so binary16 holds exponents up to `ln 65504 ≈ 11.09` here (MJP's and
//! Filament's 5.54 in theirs) and binary32 up to 88.7 (MJP's 42, 84 here, keeps a margin); above,
//! the squares of the depths farthest from ½ overflow to `∞` and those texels' warp reads lit
//! (`crate::storage`, *overflow reads lit*). Lauritzen & McCool's uncentred `exp(c·d)` would
//! overflow at half the exponent. [`WarpedMoments::from_raw_moments`]
//! reads the blurred raw moments back as moments about `r = ½`.

use crate::depth_samples::{Samples, unit_depth};
use crate::error::ParamError;

/// The largest exponent accepted: `⌊ln(f64::MAX)/2⌋ = 354`. With depths and reference in `[0, 1]`,
/// `|c·(d − r)| ≤ c`, so `u² ≤ exp(2c) ≤ exp(708)` stays finite.
pub const MAX_EXPONENT: f64 = 354.0;

/// The depth the raw warps a texel stores are centred on: `w₊ = exp(c·(d − ½))`,
/// `w₋ = −exp(−c·(d − ½))` (module documentation, *Storage*).
pub const RAW_REFERENCE: f64 = 0.5;

/// Which of the two exponential warps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Warp {
    /// `w₊(d) = exp(c·d)`, stored as `u₊ = expm1(c·(d − r))`.
    Positive,
    /// `w₋(d) = −exp(−c·d)`, stored as `u₋ = −expm1(−c·(d − r))`.
    Negative,
}

impl Warp {
    /// The stored warped value `u(d)` for exponent `c` about reference `r` (module documentation).
    /// Increasing in `d`; `u(r) = 0`. No validation: `c`, `r` and `d` are used as given.
    #[must_use]
    pub fn apply(self, exponent: f64, reference: f64, depth: f64) -> f64 {
        let x = exponent * (depth - reference);
        match self {
            Self::Positive => x.exp_m1(),
            Self::Negative => -(-x).exp_m1(),
        }
    }

    /// The raw warped depth a texel stores (module documentation, *Storage*):
    /// `w₊ = exp(c·(d − ½))`, `w₋ = −exp(−c·(d − ½))`. No validation.
    #[must_use]
    pub fn raw(self, exponent: f64, depth: f64) -> f64 {
        let x = exponent * (depth - RAW_REFERENCE);
        match self {
            Self::Positive => x.exp(),
            Self::Negative => -(-x).exp(),
        }
    }

    /// The raw warp at [`RAW_REFERENCE`]: `w₊(½) = 1`, `w₋(½) = −1`.
    const fn raw_at_reference(self) -> f64 {
        match self {
            Self::Positive => 1.0,
            Self::Negative => -1.0,
        }
    }
}

/// The first two moments of one warp of the depths: `M1 = E[u]`, `M2 = E[u²]` with `u` the
/// scaled, shifted warp of the module documentation.
///
/// # Guarantees
/// `0 < c ≤ MAX_EXPONENT`; `r ∈ [0, 1]`; `M1`, `M2` finite; `M2 ≥ 0`; `M1 ≥ −1` for the positive
/// warp and `M1 ≤ 1` for the negative one (the ranges of `u₊ > −1` and `u₋ < 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WarpedMoments {
    warp: Warp,
    exponent: f64,
    reference: f64,
    m1: f64,
    m2: f64,
}

impl WarpedMoments {
    /// From stored moments. `Err` names `exponent` (must be finite, `> 0` and at most
    /// [`MAX_EXPONENT`]), `reference` (in `[0, 1]`), `m1` or `m2`.
    pub fn new(
        warp: Warp,
        exponent: f64,
        reference: f64,
        m1: f64,
        m2: f64,
    ) -> Result<Self, ParamError> {
        check_exponent(exponent)?;
        unit_depth("reference", reference)?;
        ParamError::finite("m1", m1)?;
        ParamError::finite("m2", m2)?;
        ParamError::require("m2", m2, m2 >= 0.0, || "at least 0".into())?;
        match warp {
            Warp::Positive => {
                ParamError::require("m1", m1, m1 >= -1.0, || "at least −1".into())?;
            }
            Warp::Negative => {
                ParamError::require("m1", m1, m1 <= 1.0, || "at most 1".into())?;
            }
        }
        Ok(Self {
            warp,
            exponent,
            reference,
            m1,
            m2,
        })
    }

    /// The moments of `depths`, all of the same weight. `Err` as [`Self::from_weighted_depths`].
    pub fn from_depths(
        warp: Warp,
        exponent: f64,
        reference: f64,
        depths: &[f64],
    ) -> Result<Self, ParamError> {
        Self::build(warp, exponent, reference, &Samples::new(depths, None)?)
    }

    /// The moments of `depths` with one weight each, about `reference` (keep it within the depths:
    /// module documentation, *Stable form*). `Err` names `exponent`, `reference`, `depths`
    /// (empty, or a value not in `[0, 1]`) or `weights` (wrong length, negative, not finite, or
    /// summing to 0).
    pub fn from_weighted_depths(
        warp: Warp,
        exponent: f64,
        reference: f64,
        depths: &[f64],
        weights: &[f64],
    ) -> Result<Self, ParamError> {
        Self::build(
            warp,
            exponent,
            reference,
            &Samples::new(depths, Some(weights))?,
        )
    }

    fn build(
        warp: Warp,
        exponent: f64,
        reference: f64,
        samples: &Samples<'_>,
    ) -> Result<Self, ParamError> {
        check_exponent(exponent)?;
        unit_depth("reference", reference)?;
        let u = |d: f64| warp.apply(exponent, reference, d);
        // Means clamped to the samples' range: M1 of one depth is exactly u(d), so a receiver at
        // that depth is lit, and M1 stays in u's range (> −1, resp. < 1).
        let m1 = samples.mean(u);
        let m2 = samples.mean(|d| u(d) * u(d));
        Self::new(warp, exponent, reference, m1, m2)
    }

    /// The raw moments one texel of depth `depth` stores for this warp, `[w, w²]` with `w` the raw
    /// warp about ½ ([`Warp::raw`]; module documentation, *Storage*), before the format rounds
    /// them. No validation.
    #[must_use]
    pub fn texel_moments(warp: Warp, exponent: f64, depth: f64) -> [f64; 2] {
        let w = warp.raw(exponent, depth);
        [w, w * w]
    }

    /// From blurred raw moments `[E[w], E[w²]]` of `warp` about ½ as a texture holds them
    /// (`crate::storage`), or `None` when either is infinite (it overflowed its format: the warp
    /// carries no bound and reads lit — `crate::storage`, *overflow reads lit*). The raw moments
    /// become the scaled, shifted ones about `r = ½` as the module documentation relates them
    /// (`u = w − w(½)`, `w(½) = ±1`): `M1 = E[w] ∓ 1`, `M2 = E[w²] ∓ 2·E[w] + 1`, the latter kept at
    /// least 0 (rounding can push it below; the variance `M2 − M1² = E[w²] − E[w]²` is clamped at 0
    /// anyway). `Err` names `exponent`, `mean` (NaN) or `m1` (a mean of the wrong sign).
    pub fn from_raw_moments(
        warp: Warp,
        exponent: f64,
        [mean, mean_square]: [f64; 2],
    ) -> Result<Option<Self>, ParamError> {
        check_exponent(exponent)?;
        for value in [mean, mean_square] {
            if value.is_nan() {
                return Err(ParamError::NotFinite {
                    name: "mean",
                    value,
                });
            }
        }
        if mean.is_infinite() || mean_square.is_infinite() {
            return Ok(None);
        }
        let at = warp.raw_at_reference();
        let m1 = mean - at;
        let m2 = (mean_square - 2.0 * at * mean + 1.0).max(0.0);
        Self::new(warp, exponent, RAW_REFERENCE, m1, m2).map(Some)
    }

    /// Which warp.
    #[must_use]
    pub fn warp(&self) -> Warp {
        self.warp
    }

    /// The exponent `c`.
    #[must_use]
    pub fn exponent(&self) -> f64 {
        self.exponent
    }

    /// The reference depth `r`.
    #[must_use]
    pub fn reference(&self) -> f64 {
        self.reference
    }

    /// `M1 = E[u]`.
    #[must_use]
    pub fn m1(&self) -> f64 {
        self.m1
    }

    /// `M2 = E[u²]`.
    #[must_use]
    pub fn m2(&self) -> f64 {
        self.m2
    }

    /// `σ_u² = M2 − M1²`, clamped at 0 (rounding can make it slightly negative).
    #[must_use]
    pub fn variance(&self) -> f64 {
        (self.m2 - self.m1 * self.m1).max(0.0)
    }

    /// The Cantelli bound on this warp at receiver depth `t`: 1 if `u(t) ≤ M1`, else
    /// `σ²/(σ² + (u(t) − M1)²)` with `σ² = max(σ_u², (u'(t))²·min_variance)` (module documentation:
    /// `min_variance` is in depth² units). In `[0, 1]`, never NaN: it is evaluated as
    /// `1/(1 + k²)` with `k = (u(t) − M1)/σ`, each ratio formed so that no `∞/∞` arises for
    /// receivers far outside `[0, 1]`. `Err` names `t` (must be finite) or `min_variance` (finite,
    /// `≥ 0`).
    pub fn lit_fraction(&self, t: f64, min_variance: f64) -> Result<f64, ParamError> {
        ParamError::finite("t", t)?;
        check_min_variance(min_variance)?;
        let c = self.exponent;
        // c ≤ 354 and t − r finite: x is finite or ±∞, never NaN.
        let x = c * (t - self.reference);
        let min_sd = min_variance.sqrt();
        let sd = self.variance().sqrt();
        let (excess, k_min) = match self.warp {
            Warp::Positive => {
                let excess = x.exp_m1() - self.m1;
                if excess <= 0.0 {
                    return Ok(1.0);
                }
                // k_min = excess/(c·eˣ·σ_min). For x > 700, eˣ and the excess overflow together;
                // divide both by eˣ first: excess·e⁻ˣ = 1 − (1 + M1)·e⁻ˣ (1 + M1 ≥ 0).
                let k_min = if min_sd == 0.0 {
                    f64::INFINITY
                } else if x <= 700.0 {
                    excess / (c * x.exp() * min_sd)
                } else {
                    (1.0 - (1.0 + self.m1) * (-x).exp()) / (c * min_sd)
                };
                (excess, k_min)
            }
            Warp::Negative => {
                let excess = -(-x).exp_m1() - self.m1;
                if excess <= 0.0 {
                    return Ok(1.0);
                }
                // excess > 0 needs e⁻ˣ < 1 − M1, so e⁻ˣ is finite here; it underflows to 0 for a
                // receiver far behind, where k_min = +∞ is the right limit.
                let k_min = if min_sd == 0.0 {
                    f64::INFINITY
                } else {
                    excess / (c * (-x).exp() * min_sd)
                };
                (excess, k_min)
            }
        };
        let k = (excess / sd).min(k_min).max(0.0);
        let lit = 1.0 / (1.0 + k * k);
        debug_assert!((0.0..=1.0).contains(&lit), "{lit}");
        Ok(lit)
    }
}

/// EVSM with two moments: the positive warp only, `E[u₊]` and `E[u₊²]`.
///
/// For a two-occluder stack (`d₀ < d₁`) and a receiver behind both (`t > d₁`), the positive warp's
/// bound is never above VSM's: the Cantelli bound of a two-point distribution falls with
/// `(w(t) − w(d₁))/(w(d₁) − w(d₀))`, and a convex increasing `w` makes that ratio at least the
/// unwarped `(t − d₁)/(d₁ − d₀)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evsm2Moments {
    positive: WarpedMoments,
}

impl Evsm2Moments {
    /// Two scalars per texel: `E[w₊]`, `E[w₊²]`.
    pub const MOMENTS_PER_TEXEL: usize = 2;

    /// From stored moments of `u₊` about `reference` ([`WarpedMoments::new`] with
    /// [`Warp::Positive`]; the same errors).
    pub fn new(exponent: f64, reference: f64, m1: f64, m2: f64) -> Result<Self, ParamError> {
        WarpedMoments::new(Warp::Positive, exponent, reference, m1, m2)
            .map(|positive| Self { positive })
    }

    /// The moments of `depths`, all of the same weight ([`WarpedMoments::from_depths`]).
    pub fn from_depths(exponent: f64, reference: f64, depths: &[f64]) -> Result<Self, ParamError> {
        WarpedMoments::from_depths(Warp::Positive, exponent, reference, depths)
            .map(|positive| Self { positive })
    }

    /// The moments of `depths` with one weight each ([`WarpedMoments::from_weighted_depths`]).
    pub fn from_weighted_depths(
        exponent: f64,
        reference: f64,
        depths: &[f64],
        weights: &[f64],
    ) -> Result<Self, ParamError> {
        WarpedMoments::from_weighted_depths(Warp::Positive, exponent, reference, depths, weights)
            .map(|positive| Self { positive })
    }

    /// The positive warp's moments.
    #[must_use]
    pub fn positive(&self) -> &WarpedMoments {
        &self.positive
    }

    /// The lit fraction `p₊(t)` (module documentation; [`WarpedMoments::lit_fraction`]).
    pub fn lit_fraction(&self, t: f64, min_variance: f64) -> Result<f64, ParamError> {
        self.positive.lit_fraction(t, min_variance)
    }
}

/// EVSM with four moments: both warps, lit fraction `min(p₊(t), p₋(t))`.
///
/// # Guarantees
/// [`Self::positive`] holds a [`Warp::Positive`] warp and [`Self::negative`] a [`Warp::Negative`]
/// one. Their exponents and references may differ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evsm4Moments {
    positive: WarpedMoments,
    negative: WarpedMoments,
}

impl Evsm4Moments {
    /// Four scalars per texel: `E[w₊]`, `E[w₊²]`, `E[w₋]`, `E[w₋²]`.
    pub const MOMENTS_PER_TEXEL: usize = 4;

    /// From the two warps' moments. `Err` names `positive` or `negative` when that argument holds
    /// the other warp.
    pub fn new(positive: WarpedMoments, negative: WarpedMoments) -> Result<Self, ParamError> {
        let wrong = |name, m: WarpedMoments, requirement: &str| ParamError::OutOfDomain {
            name,
            value: m.exponent,
            requirement: requirement.into(),
        };
        if positive.warp != Warp::Positive {
            return Err(wrong(
                "positive",
                positive,
                "the moments of a positive warp",
            ));
        }
        if negative.warp != Warp::Negative {
            return Err(wrong(
                "negative",
                negative,
                "the moments of a negative warp",
            ));
        }
        Ok(Self { positive, negative })
    }

    /// The moments of `depths`, all of the same weight, both warps about one `reference`.
    /// `Err` names `positive_exponent` or `negative_exponent` for a bad exponent, otherwise as
    /// [`WarpedMoments::from_weighted_depths`].
    pub fn from_depths(
        positive_exponent: f64,
        negative_exponent: f64,
        reference: f64,
        depths: &[f64],
    ) -> Result<Self, ParamError> {
        Self::build(
            positive_exponent,
            negative_exponent,
            reference,
            &Samples::new(depths, None)?,
        )
    }

    /// The moments of `depths` with one weight each, both warps about one `reference`. Errors as
    /// [`Self::from_depths`].
    pub fn from_weighted_depths(
        positive_exponent: f64,
        negative_exponent: f64,
        reference: f64,
        depths: &[f64],
        weights: &[f64],
    ) -> Result<Self, ParamError> {
        Self::build(
            positive_exponent,
            negative_exponent,
            reference,
            &Samples::new(depths, Some(weights))?,
        )
    }

    fn build(
        positive_exponent: f64,
        negative_exponent: f64,
        reference: f64,
        samples: &Samples<'_>,
    ) -> Result<Self, ParamError> {
        let rename = |name| {
            move |e: ParamError| match e {
                ParamError::NotFinite {
                    name: "exponent",
                    value,
                } => ParamError::NotFinite { name, value },
                ParamError::OutOfDomain {
                    name: "exponent",
                    value,
                    requirement,
                } => ParamError::OutOfDomain {
                    name,
                    value,
                    requirement,
                },
                other => other,
            }
        };
        Ok(Self {
            positive: WarpedMoments::build(Warp::Positive, positive_exponent, reference, samples)
                .map_err(rename("positive_exponent"))?,
            negative: WarpedMoments::build(Warp::Negative, negative_exponent, reference, samples)
                .map_err(rename("negative_exponent"))?,
        })
    }

    /// The positive warp's moments.
    #[must_use]
    pub fn positive(&self) -> &WarpedMoments {
        &self.positive
    }

    /// The negative warp's moments.
    #[must_use]
    pub fn negative(&self) -> &WarpedMoments {
        &self.negative
    }

    /// The lit fraction `min(p₊(t), p₋(t))`, both with the same `min_variance` in depth² units
    /// (module documentation). Errors as [`WarpedMoments::lit_fraction`].
    pub fn lit_fraction(&self, t: f64, min_variance: f64) -> Result<f64, ParamError> {
        Ok(self
            .positive
            .lit_fraction(t, min_variance)?
            .min(self.negative.lit_fraction(t, min_variance)?))
    }
}

fn check_exponent(exponent: f64) -> Result<f64, ParamError> {
    ParamError::finite("exponent", exponent)?;
    ParamError::require(
        "exponent",
        exponent,
        exponent > 0.0 && exponent <= MAX_EXPONENT,
        || format!("greater than 0 and at most {MAX_EXPONENT}"),
    )
}

fn check_min_variance(min_variance: f64) -> Result<f64, ParamError> {
    ParamError::finite("min_variance", min_variance)?;
    ParamError::require("min_variance", min_variance, min_variance >= 0.0, || {
        "at least 0".into()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vsm::ShiftedMoments;

    #[test]
    fn one_depth_is_shadowed_behind_and_lit_in_front() {
        let m = Evsm4Moments::from_depths(40.0, 20.0, 0.5, &[0.6; 4]).unwrap();
        assert_eq!(m.lit_fraction(0.6, 0.0).unwrap(), 1.0);
        assert_eq!(m.lit_fraction(0.2, 0.0).unwrap(), 1.0);
        assert_eq!(m.lit_fraction(0.6 + 1e-9, 0.0).unwrap(), 0.0);
        // With a floor the bound is the Cantelli value of that floor, carried by the slope.
        let (t, var) = (0.61, 1e-6);
        let p = m.positive().lit_fraction(t, var).unwrap();
        let slope = 40.0 * (40.0f64 * (t - 0.5)).exp();
        let gap = (40.0f64 * (t - 0.5)).exp_m1() - (40.0f64 * 0.1).exp_m1();
        let expected = slope * slope * var / (slope * slope * var + gap * gap);
        assert!((p - expected).abs() < 1e-12, "{p} {expected}");
    }

    #[test]
    fn a_small_exponent_is_vsm() {
        let depths = [0.30, 0.32, 0.5, 0.55, 0.7];
        let vsm = ShiftedMoments::from_depths(0.45, &depths).unwrap();
        let evsm = Evsm2Moments::from_depths(1e-6, 0.45, &depths).unwrap();
        for t in [0.2, 0.46, 0.5, 0.6, 0.9] {
            for min_variance in [0.0, 1e-3] {
                let a = vsm.lit_fraction(t, min_variance).unwrap();
                let b = evsm.lit_fraction(t, min_variance).unwrap();
                assert!((a - b).abs() < 1e-5, "t = {t}: VSM {a}, EVSM2 {b}");
            }
        }
    }

    #[test]
    fn raw_moments_about_a_half_are_the_shifted_moments_about_a_half() {
        let depths = [0.3, 0.32, 0.5, 0.55, 0.7];
        for warp in [Warp::Positive, Warp::Negative] {
            let shifted = WarpedMoments::from_depths(warp, 11.08, RAW_REFERENCE, &depths).unwrap();
            let texels: Vec<[f64; 2]> = depths
                .iter()
                .map(|&d| WarpedMoments::texel_moments(warp, 11.08, d))
                .collect();
            let mean = |k: usize| texels.iter().map(|t| t[k]).sum::<f64>() / 5.0;
            let raw = WarpedMoments::from_raw_moments(warp, 11.08, [mean(0), mean(1)])
                .unwrap()
                .expect("finite");
            assert!((raw.m1() - shifted.m1()).abs() < 1e-14, "{warp:?}");
            assert!(
                (raw.variance() - shifted.variance()).abs() < 1e-13,
                "{warp:?}"
            );
            for t in [0.2, 0.5, 0.6, 0.75] {
                let (a, b) = (
                    raw.lit_fraction(t, 1e-6).unwrap(),
                    shifted.lit_fraction(t, 1e-6).unwrap(),
                );
                assert!((a - b).abs() < 1e-12, "{warp:?} at {t}: {a} {b}");
            }
        }
        // An overflowed moment carries no bound.
        let overflowed = [f64::INFINITY, f64::INFINITY];
        assert!(
            WarpedMoments::from_raw_moments(Warp::Positive, 12.0, overflowed)
                .unwrap()
                .is_none()
        );
    }

    #[test]
    fn receivers_far_outside_give_limits_not_nan() {
        let m =
            Evsm4Moments::from_depths(MAX_EXPONENT, MAX_EXPONENT, 0.0, &[0.0, 0.5, 1.0]).unwrap();
        for t in [-f64::MAX, -1e300, -1.0, 2.0, 1e300, f64::MAX] {
            for min_variance in [0.0, 1e-12, 1.0, 1e300] {
                let p = m.positive().lit_fraction(t, min_variance).unwrap();
                let n = m.negative().lit_fraction(t, min_variance).unwrap();
                assert!(
                    (0.0..=1.0).contains(&p) && (0.0..=1.0).contains(&n),
                    "{t}: {p} {n}"
                );
            }
        }
        assert_eq!(m.lit_fraction(-1e300, 0.0).unwrap(), 1.0);
        assert_eq!(m.positive().lit_fraction(1e300, 0.0).unwrap(), 0.0);
        // With a floor the positive warp keeps 1/(1 + (c·σ_min)⁻²) however far the receiver is.
        let floor = 1.0 / (1.0 + (MAX_EXPONENT * 1e-3f64).powi(-2));
        let far = m.positive().lit_fraction(1e300, 1e-6).unwrap();
        assert!((far - floor).abs() < 1e-12, "{far} {floor}");
    }

    #[test]
    fn errors_name_the_parameter() {
        let e = |r: Result<Evsm4Moments, ParamError>| r.unwrap_err().parameter();
        assert_eq!(
            e(Evsm4Moments::from_depths(0.0, 1.0, 0.5, &[0.5])),
            "positive_exponent"
        );
        assert_eq!(
            e(Evsm4Moments::from_depths(1.0, 355.0, 0.5, &[0.5])),
            "negative_exponent"
        );
        assert_eq!(
            e(Evsm4Moments::from_depths(1.0, 1.0, -0.1, &[0.5])),
            "reference"
        );
        assert_eq!(
            e(Evsm4Moments::from_depths(1.0, 1.0, 0.5, &[1.1])),
            "depths"
        );
        let p = WarpedMoments::new(Warp::Positive, 5.0, 0.5, 0.1, 0.1).unwrap();
        assert_eq!(e(Evsm4Moments::new(p, p)), "negative");
        assert_eq!(
            WarpedMoments::new(Warp::Positive, 5.0, 0.5, -1.5, 0.1)
                .unwrap_err()
                .parameter(),
            "m1"
        );
        assert_eq!(
            WarpedMoments::new(Warp::Negative, 5.0, 0.5, 0.0, -0.1)
                .unwrap_err()
                .parameter(),
            "m2"
        );
        assert_eq!(
            p.lit_fraction(0.5, -1.0).unwrap_err().parameter(),
            "min_variance"
        );
        assert_eq!(p.lit_fraction(f64::NAN, 0.0).unwrap_err().parameter(), "t");
    }
}
