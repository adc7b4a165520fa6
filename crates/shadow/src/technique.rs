//! The techniques, and how LiSPSM's free parameter is chosen.

use std::fmt;

use shadowlab_params::ParameterRule;

/// A shadow-map technique: how the light's view and projection are built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Technique {
    /// The standard shadow map, focused on the body B: an orthographic (spot: perspective) fit of
    /// B in LiSPSM's light space, i.e. LiSPSM with `n = ∞`.
    Uniform,
    /// The standard shadow map with Chong and Gortler's "frustum limiting" (CG06 §6): the view
    /// frustum projected on the shadow-map plane, its convex hull, and the minimum-area rectangle
    /// around it as the map's window.
    UniformLimited,
    /// Perspective shadow maps (Stamminger & Drettakis 2002): the shadow map taken in the camera's
    /// post-perspective space, with the virtual camera shift and the near plane pushed to the
    /// nearest visible depth.
    Psm,
    /// Light space perspective shadow maps (Wimmer et al. 2004 §3) with the warp parameter chosen
    /// by a rule.
    Lispsm(WarpChoice),
    /// The ideal parameterisation of LiSPSM §4: `s = ln(z/zn)/ln(zf/zn)` along the view axis,
    /// computed exactly in software (it is not a projective map).
    Logarithmic,
    /// Chong and Gortler's scene-optimized shadow map (CG06 Algorithm 1): P chosen by gradient
    /// descent to minimise the texel footprint at the pixels near shadow boundaries of a
    /// low-resolution eye pass ([`crate::optimal`]). Needs the scene's geometry, so it is planned by
    /// [`crate::plan_light`] or [`crate::optimal::plan`], not by [`crate::plan`]. The step's
    /// direction is the paper's or the refitted objective's ([`StepDirection`]).
    Optimal(StepDirection),
}

/// Which way the scene-optimized map's descent turns `p̃_4` (CG06 Algorithm 1 step 4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum StepDirection {
    /// Against Appendix A's gradient of h with the affine rows held fixed — the paper's step.
    #[default]
    Paper,
    /// Against the gradient of the objective the line search actually compares, h with the
    /// affine rows refitted to each axis, by central differences on the unit sphere
    /// ([`crate::optimal`]): shadowlab's variant, measured against the paper's.
    Refitted,
}

impl StepDirection {
    /// Its key: `paper` or `refit`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Paper => "paper",
            Self::Refitted => "refit",
        }
    }
}

/// How LiSPSM's `n` (or λ = n/d) is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WarpChoice {
    /// A rule of the papers, as `shadowlab-params` evaluates it in the 2-D model of the view.
    Rule(ParameterRule),
    /// A production engine's choice (`shared/docs/production-variants.md`).
    Production(ProductionVariant),
}

/// The LiSPSM parameter choices that engines ship, to measure against the papers' optimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProductionVariant {
    /// Filament: `max((z0 + √(vz0·vz1))/sin γ, dzn/(2 − 3·dzn/(zf − zn)))` with hints vz0 = 1,
    /// vz1 = 100, `dzn = max(0, vz0 − zn)`; no warp when `sin γ ≤ 0.02`.
    Filament,
    /// OGRE 1.x: `(|e_z| + √(zn·zf))·0.1`, multiplied by `1 + 20·(cos γ − cos 25.8°)/(1 − cos 25.8°)`
    /// inside 25.8°.
    Ogre,
    /// The authors' 2004 code as ported in OpenSceneGraph: `zn' = zn/sin γ`,
    /// `zf' = zn' + d sin γ`, `n = (zn' + √(zn'·zf'))/sin γ`.
    Osg,
    /// The authors' 2006 code (the Δz form on B's actual depth): `n = d/(√(z1/z0) − 1)`.
    Authors2006,
    /// OpenSceneGraph's ViewDependentShadowMap: `n = tan 30°·cot² γ` in a light clip space of
    /// depth 2, at least `max(−1 − eye_y, 0.05)`; orthographic below 2°.
    OsgViewDependent,
}

impl ProductionVariant {
    /// Every variant.
    pub const ALL: [Self; 5] = [
        Self::Filament,
        Self::Ogre,
        Self::Osg,
        Self::Authors2006,
        Self::OsgViewDependent,
    ];

    /// Its key: `filament`, `ogre`, `osg`, `authors2006`, `osg_vdsm`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Filament => "filament",
            Self::Ogre => "ogre",
            Self::Osg => "osg",
            Self::Authors2006 => "authors2006",
            Self::OsgViewDependent => "osg_vdsm",
        }
    }
}

impl WarpChoice {
    /// The paper's own choice, LiSPSM's `n_opt/sin γ`.
    pub const PAPER: Self = Self::Rule(ParameterRule::Lispsm);

    /// Every choice: the rules of `shadowlab-params`, then the production variants.
    #[must_use]
    pub fn all() -> Vec<Self> {
        ParameterRule::ALL
            .into_iter()
            .map(Self::Rule)
            .chain(ProductionVariant::ALL.into_iter().map(Self::Production))
            .collect()
    }

    /// Its key: the rule's key (`lispsm`, `lispsm_dz`, `cad`, …, `minimax`) or the variant's.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Rule(rule) => rule.key(),
            Self::Production(variant) => variant.key(),
        }
    }

    /// The choice with this key.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::all().into_iter().find(|c| c.key() == key)
    }
}

impl Technique {
    /// The technique keys, in the order outputs list them.
    pub const KEYS: [&'static str; 6] = [
        "uniform",
        "uniform_limited",
        "psm",
        "lispsm",
        "logarithmic",
        "optimal",
    ];

    /// Its key: `uniform`, `uniform_limited`, `psm`, `lispsm`, `logarithmic`, `optimal`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::UniformLimited => "uniform_limited",
            Self::Psm => "psm",
            Self::Lispsm(_) => "lispsm",
            Self::Logarithmic => "logarithmic",
            Self::Optimal(_) => "optimal",
        }
    }

    /// The technique named `key`, with LiSPSM's parameter, or the scene-optimized map's step
    /// direction (`paper` or `refit`), named by `parameter` (default: the paper's). `Err` says
    /// which name is unknown and lists the known ones.
    ///
    /// # Errors
    /// An unknown technique or parameter, or a parameter given to a technique without one.
    pub fn parse(key: &str, parameter: Option<&str>) -> Result<Self, String> {
        let technique = match key {
            "uniform" => Self::Uniform,
            "uniform_limited" => Self::UniformLimited,
            "psm" => Self::Psm,
            "lispsm" => Self::Lispsm(WarpChoice::PAPER),
            "logarithmic" => Self::Logarithmic,
            "optimal" => Self::Optimal(StepDirection::Paper),
            _ => {
                return Err(format!(
                    "unknown technique {key:?}; known: {}",
                    Self::KEYS.join(", ")
                ));
            }
        };
        match (technique, parameter) {
            (_, None) => Ok(technique),
            (Self::Lispsm(_), Some(p)) => {
                WarpChoice::from_key(p).map(Self::Lispsm).ok_or_else(|| {
                    let known: Vec<_> =
                        WarpChoice::all().into_iter().map(WarpChoice::key).collect();
                    format!(
                        "unknown parameter {p:?} for lispsm; known: {}",
                        known.join(", ")
                    )
                })
            }
            (Self::Optimal(_), Some(p)) => [StepDirection::Paper, StepDirection::Refitted]
                .into_iter()
                .find(|d| d.key() == p)
                .map(Self::Optimal)
                .ok_or_else(|| format!("unknown step {p:?} for optimal; known: paper, refit")),
            (_, Some(p)) => Err(format!(
                "the parameter {p:?} applies to lispsm and optimal only, not to {key}"
            )),
        }
    }
}

impl fmt::Display for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Lispsm(choice) => write!(f, "lispsm ({})", choice.key()),
            Self::Optimal(StepDirection::Refitted) => f.write_str("optimal (refit)"),
            other => f.write_str(other.key()),
        }
    }
}
