//! The named rules for choosing the warp parameter, side by side: each technique of the papers (and
//! the minimax of formulas.md §5.8) as a function from the light angle to λ in the 2-D model of
//! [`crate::model`]. This is what `shadowlab params` and the `max-error-vs-angle` figure tabulate.

use crate::cad::{self, Falloff};
use crate::domain::{LightAngle, WarpParameter};
use crate::gmnpr;
use crate::lispsm;
use crate::model::FrustumModel;

/// A rule that picks the warp parameter λ from the light angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ParameterRule {
    /// The uniform (standard, focused) shadow map: λ = ∞.
    Uniform,
    /// LiSPSM §4.4: `n'_opt = (n + √(fn))/sin γ` (GMNPR eq. 9 as λ).
    Lispsm,
    /// LiSPSM's Δz variant: `n' = (n + √(n (n + d sin γ)))/sin γ`, `d` the model's warp depth.
    LispsmDeltaZ,
    /// CAD eq. 16 with the given fall-back curve `r(γ)`.
    Cad(Falloff),
    /// GMNPR eq. 8.
    Gmnpr,
    /// GLPR (GMNPR §3): F linear in z; defined only for γ > φ.
    Glpr,
    /// The L∞ optimum of the model, `max(λ_equal-error, μ/(1 − 2μ))` (formulas.md §5.8).
    Minimax,
}

impl ParameterRule {
    /// Every rule, in the order outputs list them.
    pub const ALL: [Self; 9] = [
        Self::Uniform,
        Self::Lispsm,
        Self::LispsmDeltaZ,
        Self::Cad(Falloff::Eq18),
        Self::Cad(Falloff::Eq17),
        Self::Cad(Falloff::SinSquared),
        Self::Gmnpr,
        Self::Glpr,
        Self::Minimax,
    ];

    /// A short stable name: `uniform`, `lispsm`, `lispsm_dz`, `cad` (eq. 18), `cad_eq17`,
    /// `cad_sin2`, `gmnpr`, `glpr`, `minimax`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Lispsm => "lispsm",
            Self::LispsmDeltaZ => "lispsm_dz",
            Self::Cad(Falloff::Eq18) => "cad",
            Self::Cad(Falloff::Eq17) => "cad_eq17",
            Self::Cad(Falloff::SinSquared) => "cad_sin2",
            Self::Gmnpr => "gmnpr",
            Self::Glpr => "glpr",
            Self::Minimax => "minimax",
        }
    }

    /// A human-readable name that says which formula is used.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Lispsm => "LiSPSM n_opt/sin γ",
            Self::LispsmDeltaZ => "LiSPSM Δz",
            Self::Cad(Falloff::Eq18) => "CAD eq. 16, r eq. 18",
            Self::Cad(Falloff::Eq17) => "CAD eq. 16, r eq. 17",
            Self::Cad(Falloff::SinSquared) => "CAD eq. 16, r sin²",
            Self::Gmnpr => "GMNPR eq. 8",
            Self::Glpr => "GLPR",
            Self::Minimax => "minimax (§5.8)",
        }
    }

    /// The rule named by [`Self::key`].
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|rule| rule.key() == key)
    }

    /// λ at angle γ for the model, or `None` where the rule has no valid parameter (GLPR at
    /// `γ ≤ φ`). Every rule but GLPR gives the uniform map at `γ = 0`.
    #[must_use]
    pub fn warp(self, model: &FrustumModel, gamma: LightAngle) -> Option<WarpParameter> {
        match self {
            Self::Uniform => Some(WarpParameter::UNIFORM),
            Self::Lispsm => Some(gmnpr::lambda_lispsm(model, gamma)),
            Self::LispsmDeltaZ => {
                let depth = model.warp_depth(gamma);
                let n = lispsm::n_delta_z(model.range().near(), depth, gamma).ok()?;
                Some(WarpParameter::from_positive(n / depth))
            }
            Self::Cad(falloff) => Some(cad::warp(model, gamma, falloff)),
            Self::Gmnpr => Some(gmnpr::lambda_gmnpr(model, gamma)),
            Self::Glpr => gmnpr::lambda_glpr(model, gamma),
            Self::Minimax => Some(gmnpr::lambda_minimax(model, gamma)),
        }
    }
}

/// A rule's parameter and the error it buys, at one angle, in the 2-D model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RuleEvaluation {
    /// λ = n'/d; `UNIFORM` when the rule gives the uniform map.
    pub warp: WarpParameter,
    /// P's near distance `n' = λ·d` for the model's warp depth `d`; `f64::INFINITY` for the
    /// uniform map.
    pub near_distance: f64,
    /// `max over z ∈ [n, f]` of GMNPR's F ([`gmnpr::max_error`]); `f64::INFINITY` at `γ = 0`,
    /// where every rule's error is unbounded.
    pub max_error: f64,
}

impl ParameterRule {
    /// λ, n' and the maximum error at angle γ; `None` where the rule is not defined.
    #[must_use]
    pub fn evaluate(self, model: &FrustumModel, gamma: LightAngle) -> Option<RuleEvaluation> {
        let warp = self.warp(model, gamma)?;
        Some(RuleEvaluation {
            warp,
            near_distance: warp.near_distance(model.warp_depth(gamma)),
            max_error: gmnpr::max_error(model, gamma, warp),
        })
    }
}
