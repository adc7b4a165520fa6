//! The filterable shadow maps side by side: what each stores per texel, and the depth samples their
//! moments are built from.
//!
//! | method | module | type | moments per texel |
//! |---|---|---|---|
//! | VSM, Donnelly & Lauritzen 2006 (the CAD survey's eq. 2) | [`crate::vsm`] | [`crate::vsm::ShiftedMoments`] | 2 |
//! | ESM, Annen et al. 2008 | [`crate::esm`] | [`crate::esm::ExponentialMoment`] | 1 |
//! | EVSM with two moments, Lauritzen & McCool 2008 | [`crate::evsm`] | [`crate::evsm::Evsm2Moments`] | 2 |
//! | EVSM with four moments, Lauritzen & McCool 2008 | [`crate::evsm`] | [`crate::evsm::Evsm4Moments`] | 4 |
//! | MSM, Peters & Klein 2015 (Hamburger 4MSM) | [`crate::msm`] | [`crate::msm::MsmMoments`] | 4 |
//!
//! Every one of them replaces the binary shadow test of one depth by a function of a few moments
//! of the depths under the filter kernel, so the map can be filtered (box, Gaussian, mipmaps,
//! summed-area tables) *before* the test. The price is that the moments do not determine the depth
//! distribution: each method reconstructs a lit fraction that errs in its own way. VSM, EVSM and
//! MSM return upper bounds on the lit fraction (MSM's of the distribution its bias `α` mixes in),
//! so they leak light; ESM tends to the exact value as its exponent grows only for a receiver
//! behind every occluder, and leaks elsewhere.
//!
//! # Domain
//! Depths `d` and receiver depths `t` are light-space depths normalised to `[0, 1]`, as stored in a
//! shadow map (0 at the near plane, 1 at the far plane). The constructors of ESM, EVSM and MSM
//! reject depths and references outside `[0, 1]`; the exponent limit
//! ([`crate::evsm::MAX_EXPONENT`]) and MSM's bias target are stated for that interval. Receiver
//! depths may be any finite number (a receiver outside the map's range is answered by the same
//! formula, never by a NaN).
//!
//! # Weights
//! `from_weighted_depths` takes one non-negative weight per depth (a filter kernel's taps); the
//! moments are the weighted means `Σ wᵢ f(dᵢ) / Σ wᵢ`. `from_depths` gives every depth the same
//! weight.
//!
//! # Storage
//! `from_depths` and `from_weighted_depths` form the moments in f64, about a reference near the
//! depths where the method takes one: what a map that keeps its moments exactly reads. What an
//! engine stores instead — per texel the raw moments `texel_moments` of its depth, rounded to a 32-
//! or 16-bit float format, blurred in that format, read back by `from_raw_moments` — is modelled by
//! [`crate::storage`].

/// A filterable shadow-map method, without its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FilterableMethod {
    /// Variance shadow maps: `E[d]`, `E[d²]` and the Cantelli bound ([`crate::vsm`]).
    Vsm,
    /// Exponential shadow maps: `E[exp(c·d)]` ([`crate::esm`]).
    Esm,
    /// Exponential variance shadow maps with the positive warp only ([`crate::evsm::Evsm2Moments`]).
    Evsm2,
    /// Exponential variance shadow maps with both warps ([`crate::evsm::Evsm4Moments`]).
    Evsm4,
    /// Moment shadow maps, the Hamburger 4MSM reconstruction ([`crate::msm`]).
    Msm,
}

impl FilterableMethod {
    /// Every method, in the order of the table above (VSM first).
    pub const ALL: [Self; 5] = [Self::Vsm, Self::Esm, Self::Evsm2, Self::Evsm4, Self::Msm];

    /// The name of the method as a filter: `vsm`, `esm`, `evsm2`, `evsm4`, `msm`.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Self::Vsm => "vsm",
            Self::Esm => "esm",
            Self::Evsm2 => "evsm2",
            Self::Evsm4 => "evsm4",
            Self::Msm => "msm",
        }
    }

    /// The method whose [`Self::key`] is `key`, if any.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.key() == key)
    }

    /// The number of scalar moments each texel stores: 1 for ESM, 2 for VSM and EVSM2, 4 for EVSM4
    /// and MSM. Bytes per texel are this times the bytes of the storage format (2 for 16-bit, 4 for
    /// 32-bit channels: [`crate::storage::MomentFormat::bytes`]).
    #[must_use]
    pub const fn moments_per_texel(self) -> usize {
        match self {
            Self::Vsm => crate::vsm::ShiftedMoments::MOMENTS_PER_TEXEL,
            Self::Esm => crate::esm::ExponentialMoment::MOMENTS_PER_TEXEL,
            Self::Evsm2 => crate::evsm::Evsm2Moments::MOMENTS_PER_TEXEL,
            Self::Evsm4 => crate::evsm::Evsm4Moments::MOMENTS_PER_TEXEL,
            Self::Msm => crate::msm::MsmMoments::MOMENTS_PER_TEXEL,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_round_trip_and_memory_is_as_the_issue_states() {
        for m in FilterableMethod::ALL {
            assert_eq!(FilterableMethod::from_key(m.key()), Some(m));
        }
        assert_eq!(FilterableMethod::from_key("pcf"), None);
        let per_texel: Vec<usize> = FilterableMethod::ALL
            .iter()
            .map(|m| m.moments_per_texel())
            .collect();
        assert_eq!(per_texel, [2, 1, 2, 4, 4]);
    }
}
