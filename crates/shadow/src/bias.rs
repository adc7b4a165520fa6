//! Biases as engines apply them: a depth comparison (CAD Table 1, slope scaling, receiver-plane
//! depth bias), plus offsets that move the receiver in world space before it is projected into the
//! map (along its normal, toward the light).
//!
//! # The light's direction and the texel size at a point
//! The receiver offsets need `L`, the unit vector toward the light, and `t`, the world size of one
//! texel, at the receiver. Both come from the map alone ([`LightTexel::at`]): with `∇x`, `∇y`, `∇z`
//! the world gradients of the map's window coordinates at the point (central differences),
//! - `L = ±(∇x × ∇y)/|∇x × ∇y|`, the direction along which the window's `(x, y)` stays fixed (the
//!   light's ray through the point), signed so that window depth decreases toward the light
//!   (`∇z · L < 0`);
//! - `t = max(|∇y × L|, |∇x × L|) / (resolution · |∇x × ∇y|)`, the larger of the world lengths of
//!   the steps `a`, `b ⟂ L` that move the window by one texel along x (`∇x·a = 1/resolution`,
//!   `∇y·a = 0`) and along y. For an orthographic map `t = max(width, height)/resolution`; for a
//!   perspective map it is the texel's width at the point's distance, in the plane facing the light.

use std::fmt;

use glam::{DMat2, DVec2, DVec3};
use shadowlab_params::bias::DepthBias;

use crate::map::ShadowMap;

/// A receiver's depth slope per texel is capped here: a surface seen edge-on by the light would
/// otherwise get an unbounded bias.
pub(crate) const MAX_SLOPE: f64 = 1.0;
/// Step along the surface for the slope, relative to the point's distance from the origin (or 1).
pub(crate) const SLOPE_STEP: f64 = 1e-5;
/// Step of the central differences for the window gradients of [`LightTexel::at`], relative to
/// the point's distance from the origin (or 1), as [`SLOPE_STEP`].
const GRADIENT_STEP: f64 = 1e-5;
/// `∇x` and `∇y` closer to parallel than this (`|∇x × ∇y| ≤ PARALLEL_GRADIENTS·|∇x|·|∇y|`) leave
/// the light's direction undefined: the map is degenerate at the point.
const PARALLEL_GRADIENTS: f64 = 1e-9;
/// Window depth changing along the light's ray by less than this (`|∇z · (∇x × ∇y)| ≤
/// FLAT_DEPTH·|∇z|·|∇x × ∇y|`) leaves the side the light is on undefined.
const FLAT_DEPTH: f64 = 1e-9;

/// How a receiver's window depth is compared with the stored depth (it is lit when its depth is
/// at most the offset stored depth). Depths are GL window depths of the map, `[0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthComparison {
    /// No offset: the raw test, which acnes.
    None,
    /// Williams' constant offset, in window-depth units (CAD Table 1a).
    Constant {
        /// The offset.
        offset: f64,
    },
    /// A constant plus `slope` times the receiver's depth slope per texel (the larger of
    /// `|∂z/∂x|`, `|∂z/∂y|` over the map), as `glPolygonOffset(factor, units)` does.
    SlopeScaled {
        /// The constant part, in window-depth units.
        constant: f64,
        /// The factor on the slope.
        slope: f64,
    },
    /// The second-nearest depth (Wang & Molnar, CAD Table 1b); needs a map with second depths.
    SecondDepth,
    /// The midpoint of the two nearest depths (Woo, CAD Table 1c); needs second depths.
    Midpoint,
    /// The midpoint capped at `max_bias` (CAD Table 1d); needs second depths.
    DualDepth {
        /// The cap, in window-depth units.
        max_bias: f64,
    },
    /// Receiver plane depth bias (Isidoro, "Shadow Mapping: GPU-based Tips and Techniques", GDC
    /// 2006): the receiver's window depth is extrapolated on its own plane to each tap,
    /// `z_tap = z + (∂z/∂u)·du + (∂z/∂v)·dv`, with `(∂z/∂u, ∂z/∂v)` the receiver plane's
    /// window-depth gradient per texel (each component capped at ±1), and compared with the stored
    /// depth plus `constant`: lit when `z_tap ≤ z_stored + constant`. `(du, dv)` is the tap's offset
    /// from the point in texels: the kernel offset for PCF and the disk (Isidoro compares at the
    /// tap position), and for the nearest filter the offset from the point to the centre of the
    /// texel it reads (where the stored depth was sampled). A texel holding nothing (depth 1)
    /// lights the receiver; a surface seen edge-on by the light gets no extrapolation.
    ReceiverPlane {
        /// The constant added to the stored depth, in window-depth units.
        constant: f64,
    },
}

impl DepthComparison {
    /// Whether the map must hold second-nearest depths.
    #[must_use]
    pub fn needs_second_depth(&self) -> bool {
        matches!(
            self,
            Self::SecondDepth | Self::Midpoint | Self::DualDepth { .. }
        )
    }

    /// The term's name in a spec: `none`, `constant`, `slope`, `second-depth`, `midpoint`,
    /// `dual-depth`, `receiver-plane`.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Constant { .. } => "constant",
            Self::SlopeScaled { .. } => "slope",
            Self::SecondDepth => "second-depth",
            Self::Midpoint => "midpoint",
            Self::DualDepth { .. } => "dual-depth",
            Self::ReceiverPlane { .. } => "receiver-plane",
        }
    }
}

impl fmt::Display for DepthComparison {
    /// The term [`Bias::parse`] reads back: `none`, `constant:O`, `slope:F,C`, `second-depth`,
    /// `midpoint`, `dual-depth:MAX`, `receiver-plane:C`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Constant { offset } => write!(f, "constant:{offset:?}"),
            Self::SlopeScaled { constant, slope } => write!(f, "slope:{slope:?},{constant:?}"),
            Self::DualDepth { max_bias } => write!(f, "dual-depth:{max_bias:?}"),
            Self::ReceiverPlane { constant } => write!(f, "receiver-plane:{constant:?}"),
            Self::None | Self::SecondDepth | Self::Midpoint => f.write_str(self.key()),
        }
    }
}

/// How far a receiver is moved along its unit normal `n` before it is projected into the map, in
/// texels: `texels` times `t`, the world size of one texel of the map at the point
/// ([`LightTexel`]), scaled by the receiver's angle to the light as each engine does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NormalOffset {
    /// `p' = p + texels·t·n`, not scaled by the angle: Bevy, `shadows.wgsl` `sample_cascade`
    /// (`shadow_normal_bias` 1.8 by default). Spec `normal:K`.
    Plain {
        /// The offset in texels.
        texels: f64,
    },
    /// `p' = p + texels·t·sinθ·n`, `sinθ = √(1 − sat(n·L)²)`: Filament,
    /// `surface_shadowing.glsl` `computeLightSpacePosition`. Filament applies its
    /// `ShadowOptions::normalBias` as `0.5 × normalBias` texels (`ShadowMap.cpp`), so its default
    /// `normalBias` 1.0 is `normal-sine:0.5`. Spec `normal-sine:K`.
    Sine {
        /// The offset in texels.
        texels: f64,
    },
    /// Godot 4, `scene_forward_clustered.glsl` `BIAS_FUNC`: `base = n·(1 − max(0, L·(−n)))`,
    /// `nb = base·texels·t`, `nb −= L·(L·nb)`, `p' = p + nb` — the part of the offset across the
    /// light's ray, of length `texels·t·sinθ` on faces toward the light. (Godot's
    /// `shadow_normal_bias` is in texels too; 2.0 for directional lights by default.) Spec
    /// `normal-lateral:K`.
    Lateral {
        /// The offset in texels.
        texels: f64,
    },
    /// `p' = p + texels·t·(1 − sat(n·L))·n`: Unity URP, `Shadows.hlsl` `ApplyShadowBias`, which
    /// insets the *caster* by this much along −n (`normalBias` 1 texel by default); shadowlab moves
    /// the receiver out along +n instead (its receiver-side equivalent, named **versine offset**:
    /// 1 − cos θ is θ's versine). Spec `normal-versine:K`.
    Versine {
        /// The offset in texels.
        texels: f64,
    },
}

impl NormalOffset {
    /// The term's name in a spec: `normal`, `normal-sine`, `normal-lateral`, `normal-versine`.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Self::Plain { .. } => "normal",
            Self::Sine { .. } => "normal-sine",
            Self::Lateral { .. } => "normal-lateral",
            Self::Versine { .. } => "normal-versine",
        }
    }

    /// The offset in texels.
    #[must_use]
    pub fn texels(&self) -> f64 {
        match *self {
            Self::Plain { texels }
            | Self::Sine { texels }
            | Self::Lateral { texels }
            | Self::Versine { texels } => texels,
        }
    }

    /// The world offset of a receiver with unit normal `normal`, where the map's texel is `texel`
    /// world units wide and `toward_light` is the unit vector toward the light.
    #[must_use]
    pub fn offset(&self, normal: DVec3, toward_light: DVec3, texel: f64) -> DVec3 {
        let length = self.texels() * texel;
        match self {
            Self::Plain { .. } => normal * length,
            Self::Sine { .. } => {
                let cos = normal.dot(toward_light).clamp(0.0, 1.0);
                normal * (length * (1.0 - cos * cos).max(0.0).sqrt())
            }
            Self::Lateral { .. } => {
                let base = normal * (1.0 - toward_light.dot(-normal).max(0.0));
                let offset = base * length;
                offset - toward_light * toward_light.dot(offset)
            }
            Self::Versine { .. } => {
                normal * (length * (1.0 - normal.dot(toward_light).clamp(0.0, 1.0)))
            }
        }
    }
}

impl fmt::Display for NormalOffset {
    /// The term [`Bias::parse`] reads back: `normal:K`, `normal-sine:K`, `normal-lateral:K`,
    /// `normal-versine:K`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{:?}", self.key(), self.texels())
    }
}

/// A bias as engines combine it: a depth comparison, and optional offsets that move the receiver
/// in world space before it is projected into the map (normal first, then toward the light, both
/// computed at the unmoved point). The filters read the moved point's window position and depth;
/// VSM ignores the comparison but not the offsets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bias {
    /// How the receiver's depth is compared with the stored one.
    pub comparison: DepthComparison,
    /// The receiver's offset along its normal, if any.
    pub normal: Option<NormalOffset>,
    /// The receiver's offset toward the light, in world units (`light:D`): `p' = p + D·L`, as
    /// Bevy's `shadow_depth_bias` (`shadows.wgsl` `sample_cascade`) and Godot's scaled
    /// `shadow_bias` (`scene_forward_clustered.glsl` `BIAS_FUNC`) move it.
    pub toward_light: Option<f64>,
}

impl From<DepthComparison> for Bias {
    fn from(comparison: DepthComparison) -> Self {
        Self::new(comparison)
    }
}

/// The unit vector toward the light and the world size of one texel at a point, as the map itself
/// gives them (see the module's documentation for the formulas).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightTexel {
    /// `L`, the unit vector toward the light.
    pub toward_light: DVec3,
    /// `t`, the larger of the world lengths of one texel step along the map's x and y, in the
    /// plane perpendicular to `L`.
    pub texel: f64,
}

impl LightTexel {
    /// `L` and `t` at `world`, from central differences of `map`'s window coordinates over a step
    /// of `GRADIENT_STEP` (1e-5) times the point's distance from the origin (or 1). `None` where the
    /// map does not define them: a sample behind the map's projection centre, window x and y
    /// (nearly) dependent, or depth (nearly) constant along the light's ray.
    #[must_use]
    pub fn at(map: &ShadowMap, world: DVec3) -> Option<Self> {
        let step = GRADIENT_STEP * world.length().max(1.0);
        // Column k: the derivative of the window (x, y, z) along world axis k.
        let mut columns = [DVec3::ZERO; 3];
        for (k, column) in columns.iter_mut().enumerate() {
            let axis = DVec3::AXES[k];
            let (ahead, behind) = (world + axis * step, world - axis * step);
            let change = map.setup.mapping.window(ahead)? - map.setup.mapping.window(behind)?;
            *column = change / (ahead[k] - behind[k]);
        }
        let gradient = |row: usize| DVec3::new(columns[0][row], columns[1][row], columns[2][row]);
        let (gx, gy, gz) = (gradient(0), gradient(1), gradient(2));
        let across = gx.cross(gy);
        let area = across.length();
        if !area.is_finite() || area <= PARALLEL_GRADIENTS * gx.length() * gy.length() {
            return None;
        }
        let along = gz.dot(across);
        if !along.is_finite() || along.abs() <= FLAT_DEPTH * gz.length() * area {
            return None;
        }
        let toward_light = across * (-along.signum() / area);
        let side = f64::from(map.resolution);
        let texel = gx
            .cross(toward_light)
            .length()
            .max(gy.cross(toward_light).length())
            / (side * area);
        texel.is_finite().then_some(Self {
            toward_light,
            texel,
        })
    }
}

impl Bias {
    /// The default of `shadowlab render`: slope-scaled, factor 2 and constant 1e-5 (window depth),
    /// no receiver offsets.
    pub const DEFAULT: Self = Self::new(DepthComparison::SlopeScaled {
        constant: 1e-5,
        slope: 2.0,
    });

    /// The raw test: no comparison offset, no receiver offsets.
    pub const NONE: Self = Self::new(DepthComparison::None);

    /// `comparison` alone, without receiver offsets.
    #[must_use]
    pub const fn new(comparison: DepthComparison) -> Self {
        Self {
            comparison,
            normal: None,
            toward_light: None,
        }
    }

    /// This bias with the normal offset `normal`.
    #[must_use]
    pub const fn with_normal(self, normal: NormalOffset) -> Self {
        Self {
            normal: Some(normal),
            ..self
        }
    }

    /// This bias with the receiver moved `distance` world units toward the light.
    #[must_use]
    pub const fn with_toward_light(self, distance: f64) -> Self {
        Self {
            toward_light: Some(distance),
            ..self
        }
    }

    /// Whether the map must hold second-nearest depths.
    #[must_use]
    pub fn needs_second_depth(&self) -> bool {
        self.comparison.needs_second_depth()
    }

    /// Whether the bias moves the receiver before projecting it.
    #[must_use]
    pub fn moves_receiver(&self) -> bool {
        self.normal.is_some() || self.toward_light.is_some()
    }

    /// Where the receiver at `world` with normal `normal` is looked up: `world` moved by the
    /// normal offset and the offset toward the light, both with `L` and `t` of `map` at `world`
    /// ([`LightTexel::at`]). The point itself, bit for bit, without offsets or where `L` and `t`
    /// are undefined (a point behind the map's projection centre, a degenerate map); without the
    /// normal offset where the normal is zero or not finite (it is normalized otherwise).
    #[must_use]
    pub fn receiver(&self, map: &ShadowMap, world: DVec3, normal: DVec3) -> DVec3 {
        if !self.moves_receiver() {
            return world;
        }
        let Some(LightTexel {
            toward_light,
            texel,
        }) = LightTexel::at(map, world)
        else {
            return world;
        };
        let unit = normal.normalize_or_zero();
        let along_normal = match self.normal {
            Some(offset) if unit != DVec3::ZERO => offset.offset(unit, toward_light, texel),
            _ => DVec3::ZERO,
        };
        let along_light = toward_light * self.toward_light.unwrap_or(0.0);
        world + along_normal + along_light
    }
}

impl fmt::Display for Bias {
    /// The spec [`Bias::parse`] reads back, terms in the order comparison, normal offset, offset
    /// toward the light, numbers in Rust's shortest round-trip form (so the parsed bias is the same
    /// bit for bit): `slope:2.0,1e-5`, `constant:0.0001+normal-sine:0.5+light:0.02`. The
    /// comparison `none` is written only when there is no other term.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut terms = Vec::with_capacity(3);
        if self.comparison != DepthComparison::None || !self.moves_receiver() {
            terms.push(self.comparison.to_string());
        }
        if let Some(normal) = self.normal {
            terms.push(normal.to_string());
        }
        if let Some(distance) = self.toward_light {
            terms.push(format!("light:{distance:?}"));
        }
        f.write_str(&terms.join("+"))
    }
}

/// The forms [`Bias::parse`] accepts, for its messages.
const KNOWN_TERMS: &str = "none, constant:OFFSET, slope:FACTOR[,CONSTANT], second-depth, \
    midpoint, dual-depth:MAX, receiver-plane[:CONSTANT] (depth comparisons, window-depth units); \
    normal:TEXELS, normal-sine:TEXELS, normal-lateral:TEXELS, normal-versine:TEXELS (normal \
    offsets); light:DISTANCE \
    (world units); joined by +, at most one of each kind";

/// The kinds of term, at most one each in a spec.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Comparison,
    Normal,
    Light,
}

impl Kind {
    fn of(name: &str) -> Option<Self> {
        match name {
            "none" | "constant" | "slope" | "second-depth" | "midpoint" | "dual-depth"
            | "receiver-plane" => Some(Self::Comparison),
            "normal" | "normal-sine" | "normal-lateral" | "normal-versine" => Some(Self::Normal),
            "light" => Some(Self::Light),
            _ => None,
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Self::Comparison => "depth comparisons",
            Self::Normal => "normal offsets",
            Self::Light => "offsets toward the light",
        }
    }
}

/// One term of a spec.
enum Term {
    Comparison(DepthComparison),
    Normal(NormalOffset),
    Light(f64),
}

impl Bias {
    /// Parses terms joined by `+`, at most one of each kind: a depth comparison (`none`,
    /// `constant:OFFSET`, `slope:FACTOR[,CONSTANT]`, `second-depth`, `midpoint`, `dual-depth:MAX`,
    /// `receiver-plane[:CONSTANT]`; window-depth units; `none` if absent), a normal offset
    /// (`normal:K`, `normal-sine:K`, `normal-lateral:K`; texels) and an offset toward the light
    /// (`light:D`; world units). Examples: `slope:2,1e-5+normal:1`,
    /// `constant:1e-4+normal-sine:0.5+light:0.02`, `receiver-plane`. A `+` starts a new term only
    /// before a letter, so `constant:1e+2` is one term; spaces around terms are ignored.
    ///
    /// # Errors
    /// A message naming the bad term and the accepted forms: an unknown term, a number that is not
    /// finite, a slope factor, cap, normal offset or light distance below 0, two terms of one kind.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let mut bias = Self::NONE;
        let mut seen: Vec<(Kind, &str)> = Vec::with_capacity(3);
        for term in split_terms(spec) {
            let term = term.trim();
            if term.is_empty() {
                return Err(format!(
                    "an empty term in bias {spec:?}; known: {KNOWN_TERMS}"
                ));
            }
            let name = term.split_once(':').map_or(term, |(name, _)| name);
            let Some(kind) = Kind::of(name) else {
                return Err(format!("unknown bias term {term:?}; known: {KNOWN_TERMS}"));
            };
            if let Some((_, first)) = seen.iter().find(|(k, _)| *k == kind) {
                return Err(format!(
                    "{first:?} and {term:?} in {spec:?} are both {}: give at most one; known: \
                     {KNOWN_TERMS}",
                    kind.describe()
                ));
            }
            seen.push((kind, term));
            match parse_term(term).map_err(|e| format!("{e}; known: {KNOWN_TERMS}"))? {
                Term::Comparison(comparison) => bias.comparison = comparison,
                Term::Normal(normal) => bias.normal = Some(normal),
                Term::Light(distance) => bias.toward_light = Some(distance),
            }
        }
        Ok(bias)
    }
}

/// The terms of a spec: split at each `+` followed by a letter (spaces between allowed) or by
/// nothing, so that exponents like `1e+2` stay in their number.
fn split_terms(spec: &str) -> Vec<&str> {
    let mut terms = Vec::new();
    let mut start = 0;
    for (at, c) in spec.char_indices() {
        if c != '+' {
            continue;
        }
        let next = spec[at + 1..].trim_start().chars().next();
        if next.is_none_or(|n| n.is_ascii_alphabetic()) {
            terms.push(&spec[start..at]);
            start = at + 1;
        }
    }
    terms.push(&spec[start..]);
    terms
}

/// One term of a spec, its kind known (the caller adds the known forms to the message).
fn parse_term(term: &str) -> Result<Term, String> {
    let (name, n) = spec_numbers(term, 2)?;
    let non_negative = |v: f64, what: &str| {
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(format!("{what} in {term:?} must be at least 0"))
        }
    };
    let comparison = |c| Ok(Term::Comparison(c));
    match (name, n.as_slice()) {
        ("none", []) => comparison(DepthComparison::None),
        ("constant", [offset]) => comparison(DepthComparison::Constant { offset: *offset }),
        ("slope", [slope]) => comparison(DepthComparison::SlopeScaled {
            constant: 0.0,
            slope: non_negative(*slope, "the factor")?,
        }),
        ("slope", [slope, constant]) => comparison(DepthComparison::SlopeScaled {
            constant: *constant,
            slope: non_negative(*slope, "the factor")?,
        }),
        ("second-depth", []) => comparison(DepthComparison::SecondDepth),
        ("midpoint", []) => comparison(DepthComparison::Midpoint),
        ("dual-depth", [max]) => comparison(DepthComparison::DualDepth {
            max_bias: non_negative(*max, "the cap")?,
        }),
        ("receiver-plane", []) => comparison(DepthComparison::ReceiverPlane { constant: 0.0 }),
        ("receiver-plane", [constant]) => comparison(DepthComparison::ReceiverPlane {
            constant: *constant,
        }),
        ("normal", [k]) => Ok(Term::Normal(NormalOffset::Plain {
            texels: non_negative(*k, "the normal offset")?,
        })),
        ("normal-sine", [k]) => Ok(Term::Normal(NormalOffset::Sine {
            texels: non_negative(*k, "the normal offset")?,
        })),
        ("normal-lateral", [k]) => Ok(Term::Normal(NormalOffset::Lateral {
            texels: non_negative(*k, "the normal offset")?,
        })),
        ("normal-versine", [k]) => Ok(Term::Normal(NormalOffset::Versine {
            texels: non_negative(*k, "the normal offset")?,
        })),
        ("light", [d]) => Ok(Term::Light(non_negative(*d, "the distance")?)),
        _ => Err(format!(
            "bias term {term:?} has the wrong numbers for {name:?}"
        )),
    }
}

/// A depth comparison ready for one lookup: the receiver's slope (or plane gradient) is found at
/// most once per lookup, not once per tap. A lookup of several taps finds the slope up front
/// ([`Self::lit`]); one of a single tap only when the tap's decision depends on it
/// ([`Self::lit_only_tap`]). (Deferring it for several taps measured slower: PCF 3×3 in the lookup
/// bench, docs/benchmarks.md.)
pub(crate) struct Comparison<'a> {
    comparison: DepthComparison,
    /// The receiver's point and window position, and its normal, for a deferred [`depth_slope`]:
    /// borrowed from the lookup, not copied. (A copy read the pair back just after the lookup had
    /// stored it, in wider loads than its stores: a store-forwarding stall, docs/benchmarks.md,
    /// "The receiver borrowed".)
    receiver: (&'a (DVec3, DVec3), &'a DVec3),
    /// Whether the slope is deferred to [`Self::lit_only_tap`].
    deferred: bool,
    /// The capped slope, for [`DepthComparison::SlopeScaled`] (0 while deferred).
    slope: f64,
    /// The capped gradient per texel, for [`DepthComparison::ReceiverPlane`].
    gradient: DVec2,
}

impl<'a> Comparison<'a> {
    /// `comparison` for the receiver `at = (world, window)` with `normal`: its point and its window
    /// position through `map` (`map.setup.mapping.window(world)`, which the caller has at hand),
    /// read by one tap (`one_tap`: through [`Self::lit_only_tap`]) or several (through
    /// [`Self::lit`]).
    pub(crate) fn new(
        comparison: DepthComparison,
        map: &ShadowMap,
        at: &'a (DVec3, DVec3),
        normal: &'a DVec3,
        one_tap: bool,
    ) -> Self {
        let deferred = one_tap && matches!(comparison, DepthComparison::SlopeScaled { .. });
        let (slope, gradient) = match comparison {
            DepthComparison::SlopeScaled { .. } if !deferred => {
                (depth_slope(map, *at, *normal), DVec2::ZERO)
            }
            DepthComparison::ReceiverPlane { .. } => {
                let gradient = depth_gradient(map, *at, *normal)
                    .filter(|g| g.is_finite())
                    .map_or(DVec2::ZERO, |g| {
                        g.clamp(DVec2::splat(-MAX_SLOPE), DVec2::splat(MAX_SLOPE))
                    });
                (0.0, gradient)
            }
            _ => (0.0, DVec2::ZERO),
        };
        Self {
            comparison,
            receiver: (at, normal),
            deferred,
            slope,
            gradient,
        }
    }

    /// [`Self::lit`] for a lookup's only tap, finding a deferred slope only where the decision
    /// depends on it. The slope-scaled limit `(z₁ + constant) + factor·slope` never falls below
    /// `z₁ + constant` when the factor is not negative (the slope is capped to `[0, MAX_SLOPE]`,
    /// and rounding is monotone), so a receiver at or in front of `z₁ + constant` is lit whatever
    /// its slope: the same decision as [`Self::lit`]'s with the slope found up front.
    pub(crate) fn lit_only_tap(
        &self,
        map: &ShadowMap,
        (i, j): (u32, u32),
        receiver: f64,
        offset: DVec2,
    ) -> bool {
        if let (true, DepthComparison::SlopeScaled { constant, slope }) =
            (self.deferred, self.comparison)
        {
            let base = map.depth(i, j) + constant;
            if lit_whatever_the_slope(base, slope, receiver) {
                return true;
            }
            // Lit's limit, with the slope found now.
            let capped = depth_slope(map, *self.receiver.0, *self.receiver.1);
            return receiver <= base + slope * capped;
        }
        self.lit(map, (i, j), receiver, offset)
    }

    /// Whether the receiver at window depth `receiver` is lit through texel `(i, j)`, read by a tap
    /// `offset` texels from the point.
    pub(crate) fn lit(
        &self,
        map: &ShadowMap,
        (i, j): (u32, u32),
        receiver: f64,
        offset: DVec2,
    ) -> bool {
        let z1 = map.depth(i, j);
        let second = || {
            let z2 = map.second_depth(i, j).unwrap_or(1.0);
            // A second depth at the far plane means no second surface.
            if z2 >= 1.0 { f64::INFINITY } else { z2.max(z1) }
        };
        let limit = match self.comparison {
            DepthComparison::None => z1,
            DepthComparison::Constant { offset } => z1 + offset,
            DepthComparison::SlopeScaled { constant, slope } => {
                debug_assert!(!self.deferred, "a deferred slope is read by lit_only_tap");
                z1 + constant + slope * self.slope
            }
            DepthComparison::SecondDepth => table_1(DepthBias::SecondDepth, z1, second()),
            DepthComparison::Midpoint => table_1(DepthBias::Midpoint, z1, second()),
            DepthComparison::DualDepth { max_bias } => {
                table_1(DepthBias::DualDepth { max_bias }, z1, second())
            }
            DepthComparison::ReceiverPlane { constant } => {
                if z1 >= 1.0 {
                    return true;
                }
                let at_tap = receiver + self.gradient.x * offset.x + self.gradient.y * offset.y;
                return at_tap <= z1 + constant;
            }
        };
        receiver <= limit
    }

    /// Whether the taps' offsets matter (only the receiver plane reads them).
    pub(crate) fn reads_offsets(&self) -> bool {
        matches!(self.comparison, DepthComparison::ReceiverPlane { .. })
    }
}

/// Whether a slope-scaled comparison lights the receiver at window depth `receiver` whatever its
/// slope: its limit `base + factor·slope` (`base = z₁ + constant`, the slope capped to
/// `[0, MAX_SLOPE]`) never falls below `base` when `factor` is not negative, as rounding is
/// monotone; so a receiver at or in front of `base` is lit ([`Comparison::lit_only_tap`]).
pub(crate) fn lit_whatever_the_slope(base: f64, factor: f64, receiver: f64) -> bool {
    factor >= 0.0 && receiver <= base
}

/// CAD eq. 1 through `shadowlab-params`; an empty texel (z1 at the far plane) lights everything.
fn table_1(bias: DepthBias, z1: f64, z2: f64) -> f64 {
    bias.z_map(z1, z2).unwrap_or(f64::INFINITY)
}

/// The receiver's window-depth slope per texel: the larger of `|∂z/∂x|`, `|∂z/∂y|` of
/// [`depth_gradient`], capped at [`MAX_SLOPE`] (which is also the slope where the gradient is
/// undefined).
pub(crate) fn depth_slope(map: &ShadowMap, at: (DVec3, DVec3), normal: DVec3) -> f64 {
    depth_gradient(map, at, normal).map_or(MAX_SLOPE, |gradient| {
        gradient.x.abs().max(gradient.y.abs()).min(MAX_SLOPE)
    })
}

/// The window-depth gradient per texel `(∂z/∂x, ∂z/∂y)` of the surface plane through `world`
/// (whose window position is `window`) with `normal`, seen through the map: two steps along the
/// plane, and the inverse of their Jacobian in texels. `None` where the plane is seen edge-on (the
/// Jacobian is singular) or a step lies behind the map's projection centre.
fn depth_gradient(
    map: &ShadowMap,
    (world, window): (DVec3, DVec3),
    normal: DVec3,
) -> Option<DVec2> {
    let (t1, t2) = normal.any_orthonormal_pair();
    let step = SLOPE_STEP * world.length().max(1.0);
    let side = f64::from(map.resolution);
    let in_texels = |w: DVec3| DVec3::new(w.x * side, w.y * side, w.z);
    let at = |p: DVec3| map.setup.mapping.window(p).map(in_texels);
    let (p0, p1, p2) = (
        in_texels(window),
        at(world + t1 * step)?,
        at(world + t2 * step)?,
    );
    let (d1, d2) = (p1 - p0, p2 - p0);
    let jacobian = DMat2::from_cols(DVec2::new(d1.x, d1.y), DVec2::new(d2.x, d2.y));
    let determinant = jacobian.determinant();
    if determinant.abs() <= f64::EPSILON * d1.truncate().length() * d2.truncate().length() {
        return None;
    }
    // (∂z/∂x, ∂z/∂y) J = (dz1, dz2).
    Some(jacobian.transpose().inverse() * DVec2::new(d1.z, d2.z))
}

/// The numbers after `name:` in a spec like `slope:2,1e-5`, at most `max` of them.
pub(crate) fn spec_numbers(spec: &str, max: usize) -> Result<(&str, Vec<f64>), String> {
    let (name, rest) = spec.split_once(':').unwrap_or((spec, ""));
    let numbers: Vec<f64> = rest
        .split(',')
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("{s:?} in {spec:?} is not a finite number"))
        })
        .collect::<Result<_, _>>()?;
    if numbers.len() > max {
        return Err(format!(
            "{spec:?} takes at most {max} numbers after {name:?}"
        ));
    }
    Ok((name, numbers))
}
