//! Moment shadow maps: Peters & Klein, *Moment Shadow Mapping*, I3D 2015, pp. 7–14,
//! doi 10.1145/2699276.2699277 — the four power moments of the depth and the Hamburger 4MSM
//! reconstruction — on depths in `[0, 1]`, biased toward the unit interval's ends as
//! TheRealMJP/Shadows does (*Bias target* below).
//!
//! A texel stores `b = (E[d], E[d²], E[d³], E[d⁴])`. The receiver at `t = z_f` is shadowed with the
//! sharpest lower bound `G` on `P(d < z_f)` over all distributions on the real line with those four
//! moments (the Markov–Krein bound of the Hamburger moment problem); the lit fraction is `1 − G`, an
//! upper bound on `P(d ≥ z_f)` like VSM's and never above it. The paper's algorithm (Hamburger 4MSM):
//!
//! ```text
//! b' = (1 − α)·b + α·b*                      the moment bias (b* below)
//! B  = [[1, b'₁, b'₂], [b'₁, b'₂, b'₃], [b'₂, b'₃, b'₄]]    the Hankel matrix
//! solve B·c = (1, z_f, z_f²)ᵀ by a Cholesky factorisation of B
//! z₂ < z₃: the roots of c₁ + c₂·z + c₃·z² = 0
//! G = 0                                                           if z_f ≤ z₂
//!   = (z_f·z₃ − b'₁·(z_f + z₃) + b'₂) / ((z₃ − z₂)·(z_f − z₂))      if z₂ < z_f ≤ z₃
//!   = 1 − (z₂·z₃ − b'₁·(z₂ + z₃) + b'₂) / ((z_f − z₂)·(z_f − z₃))   otherwise
//! ```
//!
//! `{z_f, z₂, z₃}` with their weights is the three-point distribution with the moments `b'` that
//! has a point at the receiver; `G` sums the weights of its points in front of the receiver. A
//! two-point depth distribution is determined by its moments, so with `α → 0` the reconstruction is
//! exact for it (one step, or a receiver between two steps: lit `1 − p`).
//!
//! # Bias target (named choice: *unit-interval target*)
//! Peters & Klein work with depths in `[−1, 1]` and bias toward `(0, 0.63, 0, 0.63)`, and so does
//! the authors' demo code for Peters, Münstermann, Wetzstein & Klein, *Improved Moment Shadow Maps
//! for Translucent Occluders, Soft Shadows and Single Scattering*, JCGT 6(1), 2017 (as public ports
//! of it show: `(0, 0.628, 0, 0.628)`, `α = 6·10⁻⁵` for 16-bit storage). That target is the moment
//! vector of depths −1, 0, 1 with weights 0.315, 0.37, 0.315 — an interior point, so any `α > 0`
//! makes the Hankel matrix positive definite. Code that keeps depths in `[0, 1]`, as this crate
//! does, biases toward `b* = (½, ½, ½, ½)` instead (TheRealMJP/Shadows, `Shadows/MSM.hlsl`
//! `ComputeMSMHamburger`; [`MsmMoments::BIAS_TARGET`]): the moments of depth 0 or 1 with
//! probability ½ each. That is what this module uses. It is a boundary point (two depths), so the
//! biased Hankel matrix is positive definite (variance at least `α/4`) unless every depth is 0 or
//! 1; then `D₃₃ = 0`, which the stable form below handles exactly.
//!
//! The bias leaks light of its own. A receiver inside `(0, 1]` is lit at least `α/2`, and at
//! least `1 − α/2` at or in front of every occluder. Behind a single occluder at `d₀` the bias acts
//! much like VSM's minimum variance `α·(d₀² + (1 − d₀)²)/2`. Behind a stack of two occluders `Δ`
//! apart, the back one `g` in front of the receiver, MSM leaks less than VSM only while `α` is
//! below about `(Δ·g)²`: its leak relative to VSM's grows roughly like `α/(Δ·g)²`
//! (`tests/filterable.rs` measures it). In f64 the bias can be far smaller than the papers', which
//! has to absorb 16- and 32-bit rounding.
//!
//! # Stable form
//! * Moments about a reference `r` near the depths, `b_k = E[(d − r)^k]`, as [`crate::vsm`] does
//!   (formulas.md §9.4): the power moments of depths clustered near 0.95 cancel catastrophically in
//!   the Hankel determinants, moments about 0.95 do not. `r = 0` is the paper's raw form.
//! * The algorithm is evaluated in coordinates centred on the biased mean, where `B`'s `LDLᵀ`
//!   factorisation is `D = diag(1, m₂, D₃₃)`, `L₃₂ = m₃/m₂`, `D₃₃ = m₄ − m₂² − m₃²/m₂` with `mₖ`
//!   the biased central moments (the same bound: it does not depend on the origin of depth).
//! * The quadratic is replaced by closed forms that neither divide by `D₃₃` nor meet an infinite
//!   root. With `z` the centred receiver, `P = z·(z − L₃₂) − m₂` (the monic orthogonal polynomial of
//!   degree 2 at `z`, whose roots are the two-point nodes) and `K = P² + D₃₃·(1 + z²/m₂)`
//!   (`D₃₃·(1, z, z²)B⁻¹(1, z, z²)ᵀ`):
//!   - `P > 0`, `2z ≤ L₃₂` (receiver in front of both other points): `G = 0`, lit 1;
//!   - `P > 0`, `2z > L₃₂` (behind both): lit = the weight of the receiver's own point
//!     `= 1/((1, z, z²)B⁻¹(1, z, z²)ᵀ) = D₃₃/K`;
//!   - `P ≤ 0` (between): the reciprocal offsets `u = 1/(zᵢ − z)` of the other two points are the
//!     roots of `K·u² + Bᵤ·u + P = 0`, `Bᵤ = P·(2z − L₃₂) + D₃₃·z/m₂`, found by the stable quadratic
//!     formula, and `G = u₋²·(M₂·u₊ − M₁)/(u₊ − u₋)` with `M₁ = −z`, `M₂ = m₂ + z²` (the weight of
//!     the point in front, the paper's middle case) — or, when the front point is the nearer one,
//!     `G = 1 − D₃₃/K − u₊²·(M₂·u₋ − M₁)/(u₋ − u₊)` (one minus the weights of the receiver's and
//!     the back point), because the first form cancels there.
//!
//!   These agree with the paper's formulas wherever those are finite and are continuous in `z`
//!   where a root passes through infinity (`P = 0`). `D₃₃ = 0` (a two-point distribution) needs no
//!   special case; a receiver exactly on one of its points does, and gets the exact answer.
//! * Rounding can push moments slightly outside the set of moments of distributions on `[0, 1]`;
//!   `L₃₂` is clamped to `[2·lo, 2·hi]` and `D₃₃` to `[0, m₂·max(lo², hi²)]` (`[lo, hi]` the
//!   depth interval in centred coordinates), bounds every such distribution satisfies, so the
//!   result is always finite and in `[0, 1]`.
//!
//! # Storage (named choice: *plain float moments*)
//! [`MsmMoments::from_depths`] forms the moments in f64. A map whose moments a texture stores
//! (`crate::storage`) holds the raw power moments `d, d², d³, d⁴` ([`MsmMoments::texel_moments`]),
//! each rounded to the float format, and reads them back with [`MsmMoments::from_raw_moments`]:
//! what the paper stores at 32 bits per moment, and for 16-bit *float* storage plain half floats of
//! the same moments. That is **not the paper's 16-bit scheme**: Peters & Klein store 16 bits per
//! moment as fixed point after an optimised affine change of basis of the four moments (the
//! authors' transform is in public code, e.g. TheRealMJP/Shadows `Shadows/MSM.hlsl`
//! `GetOptimizedMoments`, which writes it to an `R16G16B16A16_UNORM` target, 32-bit float maps
//! keeping the plain moments). A fixed-point format is not among the float formats modelled, so
//! neither is that transform. `α` remains the knob that absorbs storage rounding.
//!
//! # Left out
//! Peters & Klein's depth bias (subtracting a constant from `z_f`) is the caller's, as for every
//! other lookup.

use crate::depth_samples::{Samples, unit_depth};
use crate::error::ParamError;

/// The four moments of a set of depths `d` about a reference `r`: `b_k = E[(d − r)^k]`, `k = 1..4`.
///
/// # Guarantees
/// `r ∈ [0, 1]`; every `b_k` is finite with `|b_k| ≤ 1` (depths and reference in `[0, 1]`);
/// `b₂ ≥ 0` and `b₄ ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MsmMoments {
    reference: f64,
    b: [f64; 4],
}

impl MsmMoments {
    /// Four scalars per texel: `E[d]`, `E[d²]`, `E[d³]`, `E[d⁴]`.
    pub const MOMENTS_PER_TEXEL: usize = 4;

    /// The raw moments `b*` the bias mixes in: those of depth 0 or 1 with probability ½ each
    /// (module documentation, *Bias target*).
    pub const BIAS_TARGET: [f64; 4] = [0.5; 4];

    /// From stored moments `[b₁, b₂, b₃, b₄]` about `reference` (`reference = 0`: the raw power
    /// moments the paper stores). `Err` names `reference` (in `[0, 1]`) or `moments` (a value not
    /// finite, of magnitude above 1, or `b₂` or `b₄` negative).
    pub fn new(reference: f64, moments: [f64; 4]) -> Result<Self, ParamError> {
        unit_depth("reference", reference)?;
        for (k, &b) in moments.iter().enumerate() {
            ParamError::finite("moments", b)?;
            ParamError::require("moments", b, b.abs() <= 1.0, || {
                "of magnitude at most 1 (depths and reference in [0, 1])".into()
            })?;
            if k % 2 == 1 {
                ParamError::require("moments", b, b >= 0.0, || {
                    "at least 0 (an even moment)".into()
                })?;
            }
        }
        Ok(Self {
            reference,
            b: moments,
        })
    }

    /// The moments of `depths`, all of the same weight. `Err` as [`Self::from_weighted_depths`].
    pub fn from_depths(reference: f64, depths: &[f64]) -> Result<Self, ParamError> {
        Self::build(reference, &Samples::new(depths, None)?)
    }

    /// The moments of `depths` with one weight each. `Err` names `reference`, `depths` (empty, or a
    /// value not in `[0, 1]`) or `weights` (wrong length, negative, not finite, or summing to 0).
    pub fn from_weighted_depths(
        reference: f64,
        depths: &[f64],
        weights: &[f64],
    ) -> Result<Self, ParamError> {
        Self::build(reference, &Samples::new(depths, Some(weights))?)
    }

    fn build(reference: f64, samples: &Samples<'_>) -> Result<Self, ParamError> {
        unit_depth("reference", reference)?;
        // Each mean is clamped to the range of (d − r)ᵏ over the samples (so |b_k| ≤ 1, and equal
        // depths give exactly their moments), and the powers are the same products as `b₁·b₁` in
        // the lit fraction: one depth has b₂ − b₁² = 0 exactly, and a receiver at it is lit.
        let y = |d: f64| d - reference;
        let b = [
            samples.mean(y),
            samples.mean(|d| y(d) * y(d)),
            samples.mean(|d| y(d) * y(d) * y(d)),
            samples.mean(|d| (y(d) * y(d)) * (y(d) * y(d))),
        ];
        Self::new(reference, b)
    }

    /// The raw moments one texel of depth `depth` stores, `[d, d², d³, d⁴]` (module documentation,
    /// *Storage*; the powers as MJP's shader forms them, `d²·d` and `d²·d²`), before the format
    /// rounds them. No validation.
    #[must_use]
    pub fn texel_moments(depth: f64) -> [f64; 4] {
        let square = depth * depth;
        [depth, square, square * depth, square * square]
    }

    /// From blurred raw power moments `[E[d], E[d²], E[d³], E[d⁴]]` as a texture holds them
    /// (`crate::storage`): the moments about reference 0, each clamped to `[0, 1]` first (where the
    /// raw moments of depths in `[0, 1]` lie; a blur's f32 weights can sum to a few ulps above 1,
    /// and its rounding can leave a mean an ulp outside). They never overflow. `Err` names `moments`
    /// (a value not finite).
    pub fn from_raw_moments(moments: [f64; 4]) -> Result<Self, ParamError> {
        for b in moments {
            ParamError::finite("moments", b)?;
        }
        Self::new(0.0, moments.map(|b| b.clamp(0.0, 1.0)))
    }

    /// The reference depth `r`.
    #[must_use]
    pub fn reference(&self) -> f64 {
        self.reference
    }

    /// `[b₁, b₂, b₃, b₄]`, the moments about [`Self::reference`].
    #[must_use]
    pub fn moments(&self) -> [f64; 4] {
        self.b
    }

    /// The raw power moments `[E[d], E[d²], E[d³], E[d⁴]]` (binomial expansion of `(y + r)^k`; this
    /// reintroduces the cancellation that the reference avoids, and is meant for storage).
    #[must_use]
    pub fn raw_moments(&self) -> [f64; 4] {
        let r = self.reference;
        let [b1, b2, b3, b4] = self.b;
        [
            b1 + r,
            b2 + r * (2.0 * b1 + r),
            b3 + r * (3.0 * b2 + r * (3.0 * b1 + r)),
            b4 + r * (4.0 * b3 + r * (6.0 * b2 + r * (4.0 * b1 + r))),
        ]
    }

    /// The lit fraction `1 − G` at receiver depth `t` with moment bias `α` (module documentation:
    /// the Hamburger 4MSM algorithm of Peters & Klein 2015 toward [`Self::BIAS_TARGET`], in the
    /// stable form). In `[0, 1]`; continuous in `t` and `α` wherever the biased Hankel matrix is
    /// definite. `α = 0` is the unbiased bound. With fewer than three distinct depths the matrix is
    /// then singular and the distribution determined: one depth gives the exact step, two depths
    /// their exact lit fraction up to rounding — except for a receiver on one of the depths, where
    /// the exact answer jumps and rounding picks the side. `Err` names `t` (must be finite) or
    /// `alpha` (in `[0, 1]`).
    pub fn lit_fraction(&self, t: f64, alpha: f64) -> Result<f64, ParamError> {
        ParamError::finite("t", t)?;
        ParamError::finite("alpha", alpha)?;
        ParamError::require("alpha", alpha, (0.0..=1.0).contains(&alpha), || {
            "in [0, 1]".into()
        })?;
        let r = self.reference;
        let [b1, b2, b3, b4] = self.b;
        let keep = 1.0 - alpha;
        // In y = d − r the target's points are −r and 1 − r; its mean is ½ − r.
        let mu = keep * b1 + alpha * (0.5 - r);
        // The data's moments about μ (binomial, in Horner form), the variance part kept ≥ 0.
        let e = b1 - mu;
        let d2 = (b2 - b1 * b1).max(0.0) + e * e;
        let d3 = b3 - mu * (3.0 * b2 - mu * (3.0 * b1 - mu));
        let d4 = b4 - mu * (4.0 * b3 - mu * (6.0 * b2 - mu * (4.0 * b1 - mu)));
        // The target's points about μ: the ends of the depth interval in centred coordinates.
        let (lo, hi) = (-r - mu, 1.0 - r - mu);
        let target = |k: i32| 0.5 * (lo.powi(k) + hi.powi(k));
        let m2 = keep * d2 + alpha * target(2);
        let m3 = keep * d3 + alpha * target(3);
        let m4 = keep * d4 + alpha * target(4);
        let z = (t - r) - mu;
        Ok(hamburger_lit_fraction(m2, m3, m4, lo, hi, z))
    }
}

/// `1 − G` for central moments `m₂, m₃, m₄` of a distribution on `[lo, hi]` (its mean at 0) and the
/// centred receiver `z` (module documentation, *Stable form*).
fn hamburger_lit_fraction(m2: f64, m3: f64, m4: f64, lo: f64, hi: f64, z: f64) -> f64 {
    if m2 <= 0.0 {
        // One depth (α = 0): determinate.
        return if z <= 0.0 { 1.0 } else { 0.0 };
    }
    // The two-point nodes lie in [lo, hi], and L₃₂ is their sum; D₃₃ ≤ E[w⁴] ≤ max w²·m₂.
    let l32 = (m3 / m2).clamp(2.0 * lo, 2.0 * hi);
    let d33 = (m4 - m2 * m2 - m3 * l32).clamp(0.0, m2 * lo.abs().max(hi.abs()).powi(2));
    let rho = d33 / m2;
    let p = z * (z - l32) - m2;
    // K = P² + D₃₃ + (D₃₃/m₂)·z²; the products in this order stay finite or +∞ (never 0·∞).
    let k = p * p + d33 + rho * z * z;
    if p > 0.0 {
        if 2.0 * z <= l32 {
            return 1.0;
        }
        // Behind both other points: the Christoffel weight of the receiver's point.
        return if d33 == 0.0 { 0.0 } else { d33 / k };
    }
    if k == 0.0 {
        // D₃₃ = 0 and P = 0: a two-point distribution with the receiver on one of its points.
        // Lit by the mass at or behind it: all of it at the front node, the back node's weight
        // −n₋/(n₊ − n₋) at the back one (the mean is 0).
        let half_gap = (0.25 * l32 * l32 + m2).sqrt();
        let front = 0.5 * l32 - half_gap;
        return if 2.0 * z < l32 {
            1.0
        } else {
            (-front / (2.0 * half_gap)).clamp(0.0, 1.0)
        };
    }
    // Between the nodes: K·u² + Bᵤ·u + P = 0 with P ≤ 0 < K has one root of each sign.
    let bu = p * (2.0 * z - l32) + rho * z;
    let root = (bu * bu - 4.0 * k * p).sqrt();
    let q = -0.5 * (bu + root.copysign(bu));
    let (u1, u2) = (q / k, p / q);
    let (u_front, u_back) = (u1.min(u2), u1.max(u2));
    let (m1_z, m2_z) = (-z, m2 + z * z);
    // G is the front point's weight. Its formula cancels in M₂·u₊ − M₁ when the front point is the
    // nearer one (a receiver on a node of a nearly two-point distribution: a 0·∞ form); then the
    // weights of the receiver's point (D₃₃/K) and of the back point, which do not cancel, give it.
    let g = if u_front.abs() > u_back.abs() {
        let back = u_back * u_back * (m2_z * u_front - m1_z) / (u_front - u_back);
        1.0 - d33 / k - back
    } else {
        u_front * u_front * (m2_z * u_back - m1_z) / (u_back - u_front)
    };
    (1.0 - g).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_depth_about_itself_is_a_step() {
        let m = MsmMoments::from_depths(0.3, &[0.3; 5]).unwrap();
        assert_eq!(m.moments(), [0.0; 4]);
        assert_eq!(m.lit_fraction(0.3, 0.0).unwrap(), 1.0);
        assert_eq!(m.lit_fraction(0.3 + 1e-12, 0.0).unwrap(), 0.0);
        // About another reference the moments of one depth are still exact (each mean is clamped
        // to its samples' range), and so is the step.
        let m = MsmMoments::from_weighted_depths(0.0, &[0.3; 3], &[0.1, 0.7, 0.3]).unwrap();
        assert_eq!(m.moments()[0], 0.3);
        assert_eq!(m.lit_fraction(0.3, 0.0).unwrap(), 1.0);
        assert_eq!(m.lit_fraction(0.3 + 1e-12, 0.0).unwrap(), 0.0);
    }

    #[test]
    fn raw_moments_expand_the_shifted_ones() {
        let depths = [0.1, 0.4, 0.45, 0.9];
        let shifted = MsmMoments::from_depths(0.4, &depths).unwrap().raw_moments();
        let raw = MsmMoments::from_depths(0.0, &depths).unwrap().moments();
        for (a, b) in shifted.iter().zip(raw) {
            assert!((a - b).abs() < 1e-15, "{a} {b}");
        }
    }

    #[test]
    fn raw_moments_as_stored_are_clamped_to_their_range() {
        let depths = [0.1, 0.4, 0.45, 0.9];
        let raw = MsmMoments::from_depths(0.0, &depths).unwrap().moments();
        assert_eq!(MsmMoments::from_raw_moments(raw).unwrap().moments(), raw);
        let texel = MsmMoments::texel_moments(0.5);
        assert_eq!(texel, [0.5, 0.25, 0.125, 0.0625]);
        // A blur's weights summing an ulp above 1 leave a mean of depth 1 just above 1.
        let over = MsmMoments::from_raw_moments([1.0 + 1e-7; 4]).unwrap();
        assert_eq!(over.moments(), [1.0; 4]);
        assert_eq!(over.lit_fraction(1.0, 0.0).unwrap(), 1.0);
        assert_eq!(
            MsmMoments::from_raw_moments([0.5, f64::INFINITY, 0.1, 0.1])
                .unwrap_err()
                .parameter(),
            "moments"
        );
    }

    #[test]
    fn errors_name_the_parameter() {
        assert_eq!(
            MsmMoments::new(0.5, [0.0, -0.1, 0.0, 0.1])
                .unwrap_err()
                .parameter(),
            "moments"
        );
        assert_eq!(
            MsmMoments::new(0.5, [2.0, 0.1, 0.0, 0.1])
                .unwrap_err()
                .parameter(),
            "moments"
        );
        assert_eq!(
            MsmMoments::new(1.5, [0.0; 4]).unwrap_err().parameter(),
            "reference"
        );
        let m = MsmMoments::from_depths(0.5, &[0.2, 0.6]).unwrap();
        assert_eq!(m.lit_fraction(0.5, 1.5).unwrap_err().parameter(), "alpha");
        assert_eq!(m.lit_fraction(f64::NAN, 0.1).unwrap_err().parameter(), "t");
    }
}
