//! The techniques, and how LiSPSM's free parameter is chosen.

use std::fmt;

use shadowlab_params::{ParameterRule, WarpParameter};

use crate::cascade_fit::CascadeFit;
use crate::error::ShadowError;
use crate::input::LightSource;
use crate::selection::SelectionRule;

/// A shadow-map technique: how the light's view and projection are built.
#[derive(Clone, Copy, Debug, PartialEq)]
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
    /// computed exactly in software (it is not a projective map), with its reference point chosen
    /// as [`LogarithmicChoice`] says.
    Logarithmic(LogarithmicChoice),
    /// Chong and Gortler's scene-optimized shadow map (CG06 Algorithm 1): P chosen by gradient
    /// descent to minimise the texel footprint at the pixels near shadow boundaries of a
    /// low-resolution eye pass ([`crate::optimal`]). Needs the scene's geometry, so it is planned by
    /// [`crate::plan_light`] or [`crate::optimal::plan`], not by [`crate::plan`]. The step's
    /// direction is the paper's or the refitted objective's ([`StepDirection`]).
    Optimal(StepDirection),
    /// A light set-up given from outside rather than planned: matrices read from a set-up file
    /// (`shadowlab_analysis::setup_file`), as an engine dumped them. It has no planning of its own,
    /// so [`crate::plan`] refuses it; it labels the measurements of such a set-up (key `given`).
    Given,
    /// Sample distribution shadow maps (Lauritzen, Salvi & Lefohn, I3D 2011; [`crate::sdsm`]): the
    /// partitions and each one's window taken from the eye pass's visible samples, split as the
    /// variant says (`sdsm`, `sdsm:kmeans`). Needs the eye pass, so it is planned by
    /// [`crate::plan_light`] with the eye image, not by [`crate::plan`].
    Sdsm(SdsmVariant),
    /// The omnidirectional cube shadow map of a point light (Gerasimov, *Omnidirectional Shadow
    /// Mapping*, GPU Gems ch. 12, 2004; every engine's point-light shadow): six 90° perspective
    /// frusta from the light along ±x, ±y, ±z, each kept for the part of B its face sees, its near
    /// plane at the nearest geometry it sees ([`crate::cube`]).
    Cube,
    /// The dual-paraboloid map of a point light (Brabec, Annen & Seidel, *Shadow Mapping for
    /// Hemispherical and Omnidirectional Light Sources*, CGI 2002): two hemispheres, each mapped
    /// by the paraboloid `(x, y) = (d_x, d_y)/(1 + d_z)` of the unit direction `d`, depth the
    /// distance from the light; made exactly, one ray per texel ([`crate::paraboloid`]).
    DualParaboloid,
    /// An engine's default shadows ([`crate::presets`]): its cascades, fit, snapping, blending,
    /// selection and bias, keyed by the engine's name; `ENGINE:CHOICE+…` with some of them
    /// chosen otherwise ([`PresetChoices`]: `bevy:unsnapped`, `babylon:fit=sphere+blend=0.2`).
    Engine(Engine, PresetChoices),
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

/// How LiSPSM's `n` (or λ = n/d) is chosen. Each choice computes what its source computes, in the
/// source's own units (the crate's `parameter` module); `inspect` prints the inputs and the formula.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WarpChoice {
    /// A rule of the papers. `lispsm` and `lispsm_dz` give `n` in world units from the camera's
    /// near and far (and B's own depth d), as LiSPSM §4.4 writes them; the rules defined by a
    /// unit-free λ in the 2-D model of the view (CAD eq. 16, GMNPR eq. 8, GLPR, the minimax, and
    /// uniform) keep that λ and use it with B's depth, `n = λ·d`.
    Rule(ParameterRule),
    /// shadowlab's own transfer of LiSPSM's parameter: GMNPR eq. 9's λ (the paper's `n_opt/sin γ`
    /// over the 2-D model's depth) used with B's actual depth. Equal to `lispsm` when B = V in the
    /// light–view plane; apart elsewhere (what every LiSPSM map used before `lispsm` meant the
    /// paper's n).
    LispsmModel,
    /// A production engine's choice (`shared/docs/production-variants.md`).
    Production(ProductionVariant),
    /// λ as the user states it (`--lambda`, `lispsm:lambda=L`); ∞ is the uniform map.
    Lambda(WarpParameter),
    /// The warp near distance n as the user states it, in light-space units (world units for a
    /// directional light; `--n`, `lispsm:n=N`); ∞ is the uniform map.
    NearDistance(NearDistance),
}

/// A warp near distance the user stated: positive, possibly infinite (the uniform map).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct NearDistance(f64);

impl NearDistance {
    /// `n ∈ (0, ∞]`.
    ///
    /// # Errors
    /// A message naming `n` and its range.
    pub fn new(n: f64) -> Result<Self, String> {
        if n > 0.0 {
            Ok(Self(n))
        } else {
            Err(format!(
                "n = {n} must be greater than 0 (inf means the uniform map)"
            ))
        }
    }

    /// The distance.
    #[must_use]
    pub fn get(self) -> f64 {
        self.0
    }
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
    /// The authors' 2004 code (the excerpt kept in OpenSceneGraph's
    /// `LightSpacePerspectiveShadowMap.cpp`): `zn' = zn/sin γ` with zn the camera's near,
    /// `zf' = zn' + d sin γ`, `n = (zn' + √(zn'·zf'))/sin γ`. (OSG's own port measures its near
    /// distance in the light's clip space, which this does not reproduce.)
    Osg,
    /// The authors' 2006 code, `calcNoptGeneral` as OpenSceneGraph's
    /// `LightSpacePerspectiveShadowMap.cpp` carries it: `n = d/(√(z1/z0) − 1)` with z0 the eye
    /// depth of B's nearest point and `z1 = z0 + d sin γ`; where `z1/z0 ≤ 1`, z0 and z1 are B's
    /// nearest and farthest eye depths (z0 at least 0.1, z1 at least z0 + 0.1). Its projection
    /// reference point lies over B's nearest point, not over the eye.
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

    /// Every named choice: the rules of `shadowlab-params`, shadowlab's model transfer, then the
    /// production variants (the stated λ and n are not named).
    #[must_use]
    pub fn named() -> Vec<Self> {
        ParameterRule::ALL
            .into_iter()
            .map(Self::Rule)
            .chain([Self::LispsmModel])
            .chain(ProductionVariant::ALL.into_iter().map(Self::Production))
            .collect()
    }

    /// The choice a parameter spec names: a rule's key (`lispsm`, `lispsm_dz`, `cad`, …,
    /// `minimax`), `model`, an engine's key, `lambda=L` or `n=N`.
    ///
    /// # Errors
    /// An unknown name or a bad number, with the known names.
    pub fn parse(spec: &str) -> Result<Self, String> {
        match stated_warp(spec)? {
            Some(Stated::Lambda(warp)) => return Ok(Self::Lambda(warp)),
            Some(Stated::NearDistance(n)) => return Ok(Self::NearDistance(n)),
            None => {}
        }
        Self::named()
            .into_iter()
            .find(|c| c.to_string() == spec)
            .ok_or_else(|| {
                let known: Vec<String> = Self::named().iter().map(ToString::to_string).collect();
                format!(
                    "unknown parameter {spec:?} for lispsm; known: {}, lambda=L, n=N",
                    known.join(", ")
                )
            })
    }
}

impl fmt::Display for WarpChoice {
    /// The spec [`Self::parse`] reads back.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Rule(rule) => f.write_str(rule.key()),
            Self::LispsmModel => f.write_str("model"),
            Self::Production(variant) => f.write_str(variant.key()),
            Self::Lambda(warp) => write!(f, "lambda={}", warp.lambda()),
            Self::NearDistance(n) => write!(f, "n={}", n.get()),
        }
    }
}

/// How the logarithmic map's reference point — the point its logarithm is measured from, at
/// `n' = λ·d` beyond B's near plane along the warp axis — is chosen ([`crate::logarithmic`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum LogarithmicChoice {
    /// shadowlab's rule: at the eye (LiSPSM §4, Lloyd et al. 2008), which is where the map's error
    /// is the same at every depth, wherever the eye lies at least a small margin beyond B's near
    /// plane; elsewhere held outside B by a floor that grows to infinity (the uniform map) as
    /// γ → 0 ([`crate::logarithmic::reference_lambda`]).
    #[default]
    Eye,
    /// λ as the user states it; ∞ is the uniform map.
    Lambda(WarpParameter),
    /// n', the reference point's distance beyond B's near plane, as the user states it.
    NearDistance(NearDistance),
    /// Lloyd et al.'s face partitioning (EGSR 2006 §5.2; TOG 2008): the view frustum split by the
    /// faces of V that face away from the light, each part with its own map whose logarithm is
    /// measured from the eye ([`crate::faces`]).
    Faces,
}

impl LogarithmicChoice {
    /// The choice a parameter spec names: `eye`, `faces`, `lambda=L` or `n=N`.
    ///
    /// # Errors
    /// An unknown name or a bad number.
    pub fn parse(spec: &str) -> Result<Self, String> {
        match stated_warp(spec)? {
            Some(Stated::Lambda(warp)) => return Ok(Self::Lambda(warp)),
            Some(Stated::NearDistance(n)) => return Ok(Self::NearDistance(n)),
            None => {}
        }
        match spec {
            "eye" => Ok(Self::Eye),
            "faces" => Ok(Self::Faces),
            _ => Err(format!(
                "unknown parameter {spec:?} for logarithmic; known: eye, faces, lambda=L, n=N"
            )),
        }
    }
}

impl fmt::Display for LogarithmicChoice {
    /// The spec [`Self::parse`] reads back.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Eye => f.write_str("eye"),
            Self::Faces => f.write_str("faces"),
            Self::Lambda(warp) => write!(f, "lambda={}", warp.lambda()),
            Self::NearDistance(n) => write!(f, "n={}", n.get()),
        }
    }
}

/// A warp stated in a parameter spec.
enum Stated {
    Lambda(WarpParameter),
    NearDistance(NearDistance),
}

/// The warp `lambda=L` or `n=N` states, `None` for any other spec.
fn stated_warp(spec: &str) -> Result<Option<Stated>, String> {
    if let Some(value) = stated(spec, "lambda")? {
        return WarpParameter::from_lambda(value)
            .map(|w| Some(Stated::Lambda(w)))
            .map_err(|e| e.to_string());
    }
    stated(spec, "n")?
        .map(|value| NearDistance::new(value).map(Stated::NearDistance))
        .transpose()
}

/// The number after `name=` in `spec`, `None` if `spec` does not start so.
fn stated(spec: &str, name: &str) -> Result<Option<f64>, String> {
    let Some(value) = spec
        .strip_prefix(name)
        .and_then(|rest| rest.strip_prefix('='))
    else {
        return Ok(None);
    };
    value
        .trim()
        .parse::<f64>()
        .ok()
        .filter(|v| !v.is_nan())
        .map(Some)
        .ok_or_else(|| {
            format!("{value:?} in {spec:?} is not a number: {name} takes a number > 0, or inf (the uniform map)")
        })
}

impl Technique {
    /// The technique keys, in the order outputs list them.
    pub const KEYS: [&'static str; 9] = [
        "uniform",
        "uniform_limited",
        "psm",
        "lispsm",
        "logarithmic",
        "optimal",
        "sdsm",
        "cube",
        "dual-paraboloid",
    ];

    /// The techniques that serve a point light, as an error message lists them.
    pub const POINT_LIGHT_TECHNIQUES: &'static str = "cube, dual-paraboloid, psm";

    /// The techniques that serve a directional or spot light, as an error message lists them.
    pub const DIRECTED_LIGHT_TECHNIQUES: &'static str = "every technique but cube and \
                                                         dual-paraboloid";

    /// Whether it can serve `light`: a point light lights every direction, so only the
    /// omnidirectional maps and PSM (which sees the light as one point in post-perspective space,
    /// §4) serve it — and a set-up given from outside, which is whatever it is; the omnidirectional
    /// maps serve point lights only.
    ///
    /// # Errors
    /// [`ShadowError::UnservedLight`] naming the technique, the light's kind and what serves it.
    pub fn check_light(self, light: &LightSource) -> Result<(), ShadowError> {
        let point = matches!(light, LightSource::Point { .. });
        let serves = match self {
            Self::Psm | Self::Given => true,
            Self::Cube | Self::DualParaboloid => point,
            _ => !point,
        };
        if serves {
            Ok(())
        } else if point {
            Err(Self::unserved_point_light(self.key()))
        } else {
            Err(ShadowError::UnservedLight {
                technique: self.key(),
                light: light.kind(),
                serving: Self::DIRECTED_LIGHT_TECHNIQUES,
            })
        }
    }

    /// The most maps one partition of it makes: six cube faces, two paraboloid hemispheres, one
    /// map per face of the view for the logarithmic map's face partitioning (six at most), one
    /// otherwise — what a memory or output estimate multiplies the partitions by.
    #[must_use]
    pub fn most_maps_per_partition(self) -> usize {
        match self {
            Self::Cube | Self::Logarithmic(LogarithmicChoice::Faces) => 6,
            Self::DualParaboloid => 2,
            _ => 1,
        }
    }

    /// The error of the technique keyed `technique` given a point light.
    pub(crate) fn unserved_point_light(technique: &'static str) -> ShadowError {
        ShadowError::UnservedLight {
            technique,
            light: "point",
            serving: Self::POINT_LIGHT_TECHNIQUES,
        }
    }

    /// The logarithmic map with shadowlab's reference rule.
    pub const LOGARITHMIC: Self = Self::Logarithmic(LogarithmicChoice::Eye);

    /// Its key: `uniform`, `uniform_limited`, `psm`, `lispsm`, `logarithmic`, `optimal`, or
    /// `given` for a set-up read from a file (not one of [`Self::KEYS`]: nothing plans it).
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::UniformLimited => "uniform_limited",
            Self::Psm => "psm",
            Self::Lispsm(_) => "lispsm",
            Self::Logarithmic(_) => "logarithmic",
            Self::Optimal(_) => "optimal",
            Self::Given => "given",
            Self::Sdsm(_) => "sdsm",
            Self::Cube => "cube",
            Self::DualParaboloid => "dual-paraboloid",
            Self::Engine(engine, _) => engine.key(),
        }
    }

    /// The spec [`Self::parse_spec`] reads back: the key, then `:` and the parameter where it has
    /// one other than the default (`lispsm:minimax`, `logarithmic:faces`, `optimal:refit`), as
    /// the command line's technique lists write it.
    #[must_use]
    pub fn spec(self) -> String {
        match self.parameter() {
            Some(parameter) => format!("{}:{parameter}", self.key()),
            None => self.key().into(),
        }
    }

    /// The technique a spec names: `KEY` or `KEY:PARAMETER`, read by [`Self::parse`].
    ///
    /// # Errors
    /// As [`Self::parse`].
    pub fn parse_spec(spec: &str) -> Result<Self, String> {
        match spec.split_once(':') {
            Some((key, parameter)) => Self::parse(key, Some(parameter)),
            None => Self::parse(spec, None),
        }
    }

    /// Its parameter spec where it has one other than the default (`minimax`, `lambda=0.3`,
    /// `faces`, `refit`), `None` for the default.
    #[must_use]
    pub fn parameter(self) -> Option<String> {
        match self {
            Self::Lispsm(choice) if choice != WarpChoice::PAPER => Some(choice.to_string()),
            Self::Logarithmic(choice) if choice != LogarithmicChoice::Eye => {
                Some(choice.to_string())
            }
            Self::Optimal(StepDirection::Refitted) => Some(StepDirection::Refitted.key().into()),
            Self::Engine(_, choices) if choices != PresetChoices::default() => {
                Some(choices.to_string())
            }
            Self::Sdsm(variant) if variant != SdsmVariant::Log => Some(variant.to_string()),
            _ => None,
        }
    }

    /// The technique named `key` with the parameter named by `parameter` (default: the paper's):
    /// LiSPSM's ([`WarpChoice::parse`]), the logarithmic map's reference
    /// ([`LogarithmicChoice::parse`]), or the scene-optimized map's step direction (`paper` or
    /// `refit`). `Err` says which name is unknown and lists the known ones.
    ///
    /// # Errors
    /// An unknown technique or parameter, or a parameter given to a technique without one.
    pub fn parse(key: &str, parameter: Option<&str>) -> Result<Self, String> {
        let technique = match key {
            "uniform" => Self::Uniform,
            "uniform_limited" => Self::UniformLimited,
            "psm" => Self::Psm,
            "lispsm" => Self::Lispsm(WarpChoice::PAPER),
            "logarithmic" => Self::LOGARITHMIC,
            "optimal" => Self::Optimal(StepDirection::Paper),
            "sdsm" => Self::Sdsm(SdsmVariant::Log),
            "cube" => Self::Cube,
            "dual-paraboloid" => Self::DualParaboloid,
            _ => match Engine::from_key(key) {
                Some(engine) => Self::Engine(engine, PresetChoices::default()),
                None => {
                    let engines: Vec<&str> = Engine::ALL.iter().map(|e| e.key()).collect();
                    return Err(format!(
                        "unknown technique {key:?}; known: {}, and the engines' presets {}",
                        Self::KEYS.join(", "),
                        engines.join(", ")
                    ));
                }
            },
        };
        match (technique, parameter) {
            (_, None) => Ok(technique),
            (Self::Lispsm(_), Some(p)) => WarpChoice::parse(p).map(Self::Lispsm),
            (Self::Logarithmic(_), Some(p)) => LogarithmicChoice::parse(p).map(Self::Logarithmic),
            (Self::Optimal(_), Some(p)) => [StepDirection::Paper, StepDirection::Refitted]
                .into_iter()
                .find(|d| d.key() == p)
                .map(Self::Optimal)
                .ok_or_else(|| format!("unknown step {p:?} for optimal; known: paper, refit")),
            (Self::Sdsm(_), Some(p)) => SdsmVariant::parse(p).map(Self::Sdsm),
            (Self::Engine(engine, _), Some(p)) => {
                let choices = PresetChoices::parse(p)
                    .map_err(|e| format!("{e} (in the {key} preset's {p:?})"))?;
                engine.check(choices)?;
                Ok(Self::Engine(engine, choices))
            }
            (_, Some(p)) => Err(format!(
                "the parameter {p:?} applies to lispsm, logarithmic, optimal, sdsm and the \
                 engines' presets only, not to {key}"
            )),
        }
    }
}

impl fmt::Display for Technique {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self, self.parameter()) {
            (Self::Lispsm(_), None) => f.write_str("lispsm (lispsm)"),
            (_, Some(parameter)) => write!(f, "{} ({parameter})", self.key()),
            (_, None) => f.write_str(self.key()),
        }
    }
}

/// An engine whose default directional shadows a preset reproduces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Engine {
    /// Bevy (`crates/bevy_light/src/cascade.rs`, `crates/bevy_pbr/src/render/shadows.wgsl`).
    Bevy,
    /// Filament (`LightManager.h` `ShadowOptions`, `ShadowMap.cpp`, `ShadowMapManager.cpp`).
    Filament,
    /// Godot 4 (`renderer_scene_cull.cpp` `_light_instance_setup_directional_shadow`).
    Godot,
    /// Babylon.js `CascadedShadowGenerator` (`cascadedShadowGenerator.ts`).
    Babylon,
    /// three.js's CSM addon (`examples/jsm/csm/CSM.js`, `CSMFrustum.js`, `CSMShader.js`).
    ThreeJs,
    /// Unity URP (`UniversalRenderPipelineAsset.cs`, `ShadowUtils.cs`, `Shadows.hlsl`).
    Unity,
    /// Unreal Engine's documented defaults: its source is not public, so every item is
    /// unverified (`docs/engine-sources.md` §7).
    Unreal,
}

/// Whether a preset keeps its engine's stabilisation (texel snapping).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Stabilisation {
    /// As the engine ships it.
    #[default]
    Engine,
    /// Snapping off (`ENGINE:unsnapped`): the same cascades, windows where the fit puts them.
    Unsnapped,
}

/// What a preset does otherwise than its engine ships it, written after the engine's name as
/// `+`-joined choices (`bevy:unsnapped`, `godot:fit=box+blend=0.1+select=containing`); the
/// default changes nothing. [`crate::presets`] says what each means for each engine.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PresetChoices {
    /// `unsnapped`: no texel snapping.
    pub stabilisation: Stabilisation,
    /// `fit=F` ([`CascadeFit::key`]): every cascade's window fitted so.
    pub fit: Option<CascadeFit>,
    /// `blend=W`: the blend band's width (0: no blending).
    pub blend: Option<BlendWidth>,
    /// `select=depth` or `select=containing`: the rule that picks a point's cascade.
    pub select: Option<SelectionRule>,
}

impl PresetChoices {
    /// The choices `spec` writes: `+`-joined `unsnapped`, `fit=F`, `blend=W`, `select=R`, each at
    /// most once.
    ///
    /// # Errors
    /// An unknown or repeated choice, or a value out of its range, named.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let mut choices = Self::default();
        let mut seen: Vec<&str> = Vec::new();
        for term in spec.split('+').map(str::trim) {
            let (name, value) = term.split_once('=').unwrap_or((term, ""));
            if seen.contains(&name) {
                return Err(format!("{name:?} is chosen twice"));
            }
            seen.push(name);
            match (name, value) {
                ("unsnapped", "") => choices.stabilisation = Stabilisation::Unsnapped,
                ("fit", fit) => choices.fit = Some(CascadeFit::parse(fit)?),
                ("blend", width) => {
                    let width = width.parse::<f64>().map_err(|_| {
                        format!("blend={width:?} is not a number: the blend width is in [0, 1)")
                    })?;
                    choices.blend = Some(BlendWidth::new(width)?);
                }
                ("select", rule) => choices.select = Some(SelectionRule::parse(rule)?),
                _ => {
                    return Err(format!(
                        "unknown preset choice {term:?}; known: unsnapped, fit=F, blend=W, \
                         select=depth|containing"
                    ));
                }
            }
        }
        Ok(choices)
    }
}

/// `unsnapped+fit=F+blend=W+select=R`, the choices made, in that order: what [`PresetChoices::parse`]
/// reads back.
impl fmt::Display for PresetChoices {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut terms = Vec::new();
        if self.stabilisation == Stabilisation::Unsnapped {
            terms.push("unsnapped".to_owned());
        }
        if let Some(fit) = self.fit {
            terms.push(format!("fit={fit}"));
        }
        if let Some(width) = self.blend {
            terms.push(format!("blend={}", width.get()));
        }
        if let Some(rule) = self.select {
            terms.push(format!("select={}", rule.key()));
        }
        f.write_str(&terms.join("+"))
    }
}

/// A blend band's width, as a preset's engine measures it ([`crate::presets`]): in `[0, 1)`, 0
/// for no blending.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct BlendWidth(f64);

impl BlendWidth {
    /// `width ∈ [0, 1)`.
    ///
    /// # Errors
    /// A message naming the width and its range.
    pub fn new(width: f64) -> Result<Self, String> {
        if (0.0..1.0).contains(&width) {
            Ok(Self(width))
        } else {
            Err(format!(
                "blend={width} is out of range: the blend width is in [0, 1), 0 for none"
            ))
        }
    }

    /// The width.
    #[must_use]
    pub fn get(self) -> f64 {
        self.0
    }
}

impl Engine {
    /// Every engine, in the order outputs list them.
    pub const ALL: [Self; 7] = [
        Self::Bevy,
        Self::Filament,
        Self::Godot,
        Self::Babylon,
        Self::ThreeJs,
        Self::Unity,
        Self::Unreal,
    ];

    /// Its key, the technique's name: `bevy`, `filament`, `godot`, `babylon`, `threejs`, `unity`,
    /// `unreal`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Bevy => "bevy",
            Self::Filament => "filament",
            Self::Godot => "godot",
            Self::Babylon => "babylon",
            Self::ThreeJs => "threejs",
            Self::Unity => "unity",
            Self::Unreal => "unreal",
        }
    }

    /// The engine named `key`.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.key() == key)
    }
}

impl fmt::Display for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// How the visible depth range is split into partitions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SdsmVariant {
    /// The logarithmic split of the samples' tight depth range `[min, max]`:
    /// `min·(max/min)^(i/k)` (the sample's `LogPartitionFromRange`; CAD eq. 5 on the visible range).
    #[default]
    Log,
    /// k-means clustering of the samples' eye depths ([`crate::sdsm`]'s exact k-means); the splits
    /// are the midpoints between neighbouring cluster centres.
    Kmeans,
}

impl SdsmVariant {
    /// Every variant.
    pub const ALL: [Self; 2] = [Self::Log, Self::Kmeans];

    /// Its key: `log` or `kmeans`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Log => "log",
            Self::Kmeans => "kmeans",
        }
    }

    /// The variant named `key`.
    ///
    /// # Errors
    /// An unknown key, with the known ones.
    pub fn parse(key: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|v| v.key() == key)
            .ok_or_else(|| format!("unknown SDSM variant {key:?}; known: log, kmeans"))
    }
}

impl fmt::Display for SdsmVariant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}
