//! z-partitioning: where to split the eye's depth range `[n, f]` into k shadow maps (cascades).
//!
//! * uniform: `n + (f − n) i/k`;
//! * logarithmic, "self-similar" (CAD eq. 5; Lloyd et al. 2006): `n (f/n)^(i/k)`, every partition
//!   with the same ratio `(f/n)^(1/k)`, which is optimal whenever a partition's maximum error grows
//!   with its ratio alone (formulas.md §4.5);
//! * practical (Zhang et al.'s parallel-split scheme, GPU Gems 3 ch. 10):
//!   `λ·n(f/n)^(i/k) + (1 − λ)·(n + (f − n) i/k)`, divided by k, not k + 1 (formulas.md §7);
//! * adaptive (CAD eq. 19; formulas.md §4.8): a per-boundary blend, weighted by the light angle,
//!   between the logarithmic split and the "limit" split in which every partition but the first has
//!   ratio δ.
//!
//! Every scheme returns `k + 1` boundaries, strictly increasing, with `b_0 = n` and `b_k = f` exactly.

use std::f64::consts::FRAC_PI_2;

use crate::domain::{DepthRange, LightAngle};
use crate::error::ParamError;

/// How to split a depth range into partitions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SplitScheme {
    /// Equal lengths: `b_i = n + (f − n) i/k`.
    Uniform,
    /// Equal ratios (CAD eq. 5): `b_i = n (f/n)^(i/k)`.
    Logarithmic,
    /// The practical blend `b_i = λ·n(f/n)^(i/k) + (1 − λ)·(n + (f − n) i/k)` (Zhang et al.);
    /// `weight = λ ∈ [0, 1]`, 1 being logarithmic. OGRE ships 0.95, three.js 0.5.
    Practical {
        /// λ, the weight of the logarithmic split, in `[0, 1]`.
        weight: f64,
    },
    /// CAD eq. 19: with `β = γ/(π/2)`, `b_k = f` and, for `i = k, …, 2`,
    /// `b_{i−1} = β·n(f/n)^((i−1)/k) + (1 − β)·b_i/δ`. The paper recommends `δ ≤ 4` without PCF and
    /// `δ ≤ 2` with it.
    ///
    /// Clamp (formulas.md §9.8): the boundaries are strictly increasing with `b_1 > n` exactly when
    /// `δ ≤ (f/n)^(1/k)` (by induction, `b_i ≥ n(f/n)^(i/k)` then), so δ is clamped to that ratio
    /// ([`SplitScheme::effective_delta`]); at the clamp the limit split is the logarithmic one.
    Adaptive {
        /// δ > 1, the ratio of the limit split's partitions.
        delta: f64,
        /// γ, the angle between light and view directions.
        gamma: LightAngle,
    },
}

impl SplitScheme {
    /// A short stable name: `uniform`, `logarithmic`, `practical`, `adaptive`.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Logarithmic => "logarithmic",
            Self::Practical { .. } => "practical",
            Self::Adaptive { .. } => "adaptive",
        }
    }

    /// For [`Self::Adaptive`], the δ actually used for `k` partitions: `min(δ, (f/n)^(1/k))`; `None`
    /// for the other schemes.
    #[must_use]
    pub fn effective_delta(&self, range: DepthRange, partitions: usize) -> Option<f64> {
        match *self {
            Self::Adaptive { delta, .. } if partitions > 0 => {
                Some(delta.min(range.geometric_lerp(1.0 / partitions as f64) / range.near()))
            }
            _ => None,
        }
    }

    /// The `k + 1` boundaries `n = b_0 < b_1 < … < b_k = f` for `k = partitions`.
    ///
    /// `Err` names `partitions` (k = 0, or too many for the range to stay strictly increasing in
    /// f64), `weight` (outside `[0, 1]`) or `delta` (not a finite number > 1).
    pub fn boundaries(&self, range: DepthRange, partitions: usize) -> Result<Vec<f64>, ParamError> {
        let k = partitions;
        if k == 0 {
            return Err(ParamError::OutOfDomain {
                name: "partitions",
                value: 0.0,
                requirement: "at least 1".into(),
            });
        }
        let fraction = |i: usize| i as f64 / k as f64;
        let logarithmic = |i: usize| range.geometric_lerp(fraction(i));
        let mut b: Vec<f64> = match *self {
            Self::Uniform => (0..=k).map(|i| range.lerp(fraction(i))).collect(),
            Self::Logarithmic => (0..=k).map(logarithmic).collect(),
            Self::Practical { weight } => {
                ParamError::require("weight", weight, (0.0..=1.0).contains(&weight), || {
                    "in [0, 1]".into()
                })?;
                (0..=k)
                    .map(|i| weight * logarithmic(i) + (1.0 - weight) * range.lerp(fraction(i)))
                    .collect()
            }
            Self::Adaptive { delta, gamma } => {
                ParamError::finite("delta", delta)?;
                ParamError::require("delta", delta, delta > 1.0, || "greater than 1".into())?;
                let delta = self.effective_delta(range, k).unwrap_or(delta);
                let beta = gamma.radians() / FRAC_PI_2;
                let mut b = vec![range.far(); k + 1];
                for i in (2..=k).rev() {
                    b[i - 1] = beta * logarithmic(i - 1) + (1.0 - beta) * b[i] / delta;
                }
                b
            }
        };
        b[0] = range.near();
        b[k] = range.far();
        if b.windows(2).all(|w| w[0] < w[1]) {
            Ok(b)
        } else {
            Err(ParamError::TooManyPartitions {
                count: k,
                ratio: range.ratio(),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_parameters_are_named() {
        let r = DepthRange::new(1.0, 100.0).unwrap();
        let g = LightAngle::PERPENDICULAR;
        let cases = [
            (SplitScheme::Uniform, 0, "partitions"),
            (SplitScheme::Practical { weight: 1.5 }, 3, "weight"),
            (SplitScheme::Practical { weight: f64::NAN }, 3, "weight"),
            (
                SplitScheme::Adaptive {
                    delta: 1.0,
                    gamma: g,
                },
                3,
                "delta",
            ),
            (
                SplitScheme::Adaptive {
                    delta: f64::INFINITY,
                    gamma: g,
                },
                3,
                "delta",
            ),
        ];
        for (scheme, k, name) in cases {
            assert_eq!(scheme.boundaries(r, k).unwrap_err().parameter(), name);
        }
    }

    #[test]
    fn a_range_too_thin_for_the_partitions_is_an_error() {
        let r = DepthRange::new(1.0, 1.0 + 1e-15).unwrap();
        let err = SplitScheme::Logarithmic.boundaries(r, 100).unwrap_err();
        assert_eq!(err.parameter(), "partitions");
        assert_eq!(
            SplitScheme::Logarithmic.boundaries(r, 1).unwrap(),
            vec![1.0, 1.0 + 1e-15]
        );
    }

    #[test]
    fn delta_is_clamped_to_the_logarithmic_ratio() {
        let r = DepthRange::new(1.0, 100.0).unwrap();
        let parallel = LightAngle::from_degrees(0.0).unwrap();
        let adaptive = SplitScheme::Adaptive {
            delta: 50.0,
            gamma: parallel,
        };
        let delta = adaptive.effective_delta(r, 3).unwrap();
        assert!((delta - 100f64.cbrt()).abs() < 1e-13);
        let b = adaptive.boundaries(r, 3).unwrap();
        let log = SplitScheme::Logarithmic.boundaries(r, 3).unwrap();
        for (x, y) in b.iter().zip(&log) {
            assert!((x - y).abs() <= 1e-12 * y, "{b:?} {log:?}");
        }
    }
}
