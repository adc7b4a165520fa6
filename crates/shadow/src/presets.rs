//! Engines' shadow set-ups by name: each preset reproduces an engine's defaults — cascade count,
//! split rule and its parameters, fit, snapping, blending, selection and fade — from the engine's
//! source, cited per item (file and symbol; `docs/engine-sources.md` has the formulas and the
//! commits read). `--technique bevy` plans a light as Bevy would.
//!
//! What every preset shares, shadowlab's choices (named in `docs/what-engines-ship.md`):
//! - scene units are taken as metres, so the engines' distances (Bevy's 150, Godot's 100, Unity's
//!   50) apply as they are;
//! - each cascade's map is the study's resolution (the engines' own sizes are in [`Engine::map`]),
//!   its depth format the study's;
//! - a spot light gets one perspective map, fitted as shadowlab's `uniform` (engines render a spot
//!   into one perspective map; their fits of it are not reproduced);
//! - blending engines fit the next cascade from the start of the blend band, so both maps cover it
//!   (Bevy does so itself; for Babylon and Unreal, named **band coverage**).
//!
//! # Choices ([`PresetChoices`], `ENGINE:CHOICE+…`)
//! A preset's fit, blend width and selection rule can be chosen otherwise, each a knob beside
//! `unsnapped`; everything else stays the engine's. They shape a directional light's cascades (a
//! spot light's one map does not change):
//! - `fit=F` ([`CascadeFit`]): every cascade fitted so, snapped as the engine snaps. Filament's
//!   default is no cascade fit but LiSPSM per cascade; with `fit=F` it gets that fit and no
//!   snapping (its 2-texel snap belongs to its `stable` mode, not reproduced).
//! - `blend=W`, `W ∈ [0, 1)`, in the engine's own measure: Bevy's `overlap_proportion` (cascade
//!   `i` starts at `(1 − W)·b_{i−1}`), Babylon's `cascadeBlendPercentage` and Unreal's
//!   `CascadeTransitionFraction` (the last `W` of each cascade's length). Godot and three.js do not
//!   blend by default; with `blend=W` they get Babylon's band, linear over the last `W` of each
//!   cascade — shadowlab's **linear band** (Godot's own `blend_splits` smoothstep and three.js's
//!   `fade` are not reproduced). `blend=0` turns blending off. Filament and Unity have one cascade:
//!   nothing to blend, and `blend` is refused.
//! - `select=depth|containing` ([`SelectionRule`]): the cascade picked by eye depth or by the
//!   first map holding the point (culling sphere, else window); a blend band then applies by eye
//!   depth after either rule.

use shadowlab_params::DepthRange;
use shadowlab_params::splits::SplitScheme;

use crate::bias::{Bias, DepthComparison, NormalOffset};
use crate::cascade_fit::{CascadeFit, Snap};
use crate::cascades::{self, CascadeSlice};
use crate::error::ShadowError;
use crate::input::{LightSource, PlanInput};
use crate::partition::Partition;
use crate::plan::{plan, plan_partitions_at};
use crate::selection::{Beyond, Fade, FadeCurve, Selection, SelectionRule};
use crate::setup::ShadowMapping;
use crate::technique::{
    BlendWidth, Engine, PresetChoices, ProductionVariant, Stabilisation, Technique, WarpChoice,
};

/// The map an engine allocates by default, for the docs' memory table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EngineMap {
    /// Side of one cascade's map, texels (`None`: the engine has no default).
    pub side: Option<u32>,
    /// Bits per depth texel.
    pub depth_bits: u32,
}

impl Engine {
    /// Its default map: Bevy `DirectionalLightShadowMap` 2048, Depth32Float; Filament `mapSize`
    /// 1024, DEPTH16; Godot's 4096 atlas of 4 → 2048, 16-bit; Babylon none (a constructor
    /// argument), 32-bit; three.js CSM `shadowMapSize` 2048, 32-bit (unverified per release); Unity
    /// URP 2048 for its one cascade, 16-bit; Unreal `r.Shadow.MaxCSMResolution` 2048 (unverified).
    #[must_use]
    pub fn map(self) -> EngineMap {
        let (side, depth_bits) = match self {
            Self::Bevy => (Some(2048), 32),
            Self::Filament => (Some(1024), 16),
            Self::Godot | Self::Unity => (Some(2048), 16),
            Self::Babylon => (None, 32),
            Self::ThreeJs | Self::Unreal => (Some(2048), 32),
        };
        EngineMap { side, depth_bits }
    }

    /// How many cascades it gives a directional light (a spot light gets one map).
    #[must_use]
    pub fn cascades(self) -> usize {
        match self {
            Self::Bevy => BEVY_CASCADES.unsigned_abs() as usize,
            Self::Godot => GODOT_SPLITS.len() + 1,
            Self::Babylon => BABYLON_CASCADES,
            Self::ThreeJs => THREEJS_CASCADES.unsigned_abs() as usize,
            Self::Unreal => UNREAL_CASCADES as usize,
            Self::Filament | Self::Unity => 1,
        }
    }

    /// Whether `choices` apply to it: a blend width needs more than one cascade.
    ///
    /// # Errors
    /// The choice that does not apply, and why.
    pub fn check(self, choices: PresetChoices) -> Result<(), String> {
        if choices.blend.is_some() && self.cascades() == 1 {
            return Err(format!(
                "{self} renders one cascade: there is nothing to blend (blend=W applies to \
                 bevy, godot, babylon, threejs and unreal)"
            ));
        }
        Ok(())
    }

    /// How its cascades are chosen, blended and faded for a directional light, with `choices`'
    /// selection rule and blend width where given.
    #[must_use]
    pub fn selection(self, choices: PresetChoices) -> Selection {
        let engine = self.engine_selection();
        Selection {
            rule: choices.select.unwrap_or(engine.rule),
            blend: choices.blend.map_or(engine.blend, |w| w.get() > 0.0),
            ..engine
        }
    }

    /// How its cascades are chosen, blended and faded as the engine ships it.
    fn engine_selection(self) -> Selection {
        let depth = |blend, beyond, fade| Selection {
            rule: SelectionRule::Depth,
            blend,
            beyond,
            fade,
        };
        match self {
            // `get_cascade_index`, `fetch_directional_shadow`: linear blend over the overlap,
            // unshadowed beyond the last cascade.
            Self::Bevy => depth(true, Beyond::Lit, None),
            // `getShadowCascade`: the cascade count clamps to the last; no blending.
            Self::Filament => depth(false, Beyond::Last, None),
            // Split offsets, `blend_splits` off; the shadow fades out by smoothstep from 0.8 to
            // 1.0 of the maximum distance.
            Self::Godot => depth(
                false,
                Beyond::Lit,
                Some(Fade {
                    start: 0.8 * GODOT_MAX_DISTANCE,
                    end: GODOT_MAX_DISTANCE,
                    curve: FadeCurve::SmoothstepDepth,
                }),
            ),
            // `cascadeBlendPercentage` 0.1: linear over the last tenth of each cascade.
            Self::Babylon => depth(true, Beyond::Lit, None),
            // `lights_fragment_begin`: intervals of linear depth; `fade` off.
            Self::ThreeJs => depth(false, Beyond::Lit, None),
            // `ComputeCascadeIndex` by culling sphere; the last cascade fades over the last
            // `m_CascadeBorder` (0.2) of the shadow distance, linear in squared distance.
            Self::Unity => Selection {
                rule: SelectionRule::Containing,
                blend: false,
                beyond: Beyond::Lit,
                fade: Some(Fade {
                    start: (1.0 - UNITY_CASCADE_BORDER) * UNITY_SHADOW_DISTANCE,
                    end: UNITY_SHADOW_DISTANCE,
                    curve: FadeCurve::LinearSquaredDistance,
                }),
            },
            // `CascadeTransitionFraction` 0.1 (unverified); its distance fade-out is not
            // reproduced (its curve is not documented).
            Self::Unreal => depth(true, Beyond::Lit, None),
        }
    }

    /// The cascades of a camera whose view runs from eye depth `near` to `far`, with the blend
    /// width `blend` where given (module docs).
    ///
    /// # Errors
    /// A parameter error for a depth range the split rules reject.
    pub fn slices(
        self,
        near: f64,
        far: f64,
        blend: Option<BlendWidth>,
    ) -> Result<Vec<CascadeSlice>, ShadowError> {
        let width = |engine: f64| blend.map_or(engine, BlendWidth::get);
        let slices = match self {
            Self::Bevy => return Ok(bevy_slices(width(BEVY_OVERLAP))),
            // One cascade over the camera's [zn, zf] (`shadowCascades` = 1, `shadowFar` 0).
            Self::Filament => unbanded(&[near, far]),
            Self::Godot => {
                let max = GODOT_MAX_DISTANCE.min(far);
                let mut bounds = vec![near];
                bounds.extend(GODOT_SPLITS.iter().map(|s| near + s * (max - near)));
                bounds.push(max);
                unbanded(&bounds)
            }
            Self::Babylon => band(unbanded(&babylon_bounds(near, far)?), width(BABYLON_BLEND)),
            Self::ThreeJs => threejs_slices(near, far)?,
            // One cascade, `m_ShadowCascadeCount` = 1, to the shadow distance.
            Self::Unity => unbanded(&[near, UNITY_SHADOW_DISTANCE.max(near)]),
            Self::Unreal => {
                let distance = UNREAL_SHADOW_DISTANCE.max(near);
                let count = f64::from(UNREAL_CASCADES);
                let total = UNREAL_EXPONENT.powf(count) - 1.0;
                let bounds: Vec<f64> = (0..=UNREAL_CASCADES)
                    .map(|i| {
                        near + (distance - near) * (UNREAL_EXPONENT.powi(i.cast_signed()) - 1.0)
                            / total
                    })
                    .collect();
                band(unbanded(&bounds), width(UNREAL_TRANSITION))
            }
        };
        // The engines that do not blend: shadowlab's linear band, if a width is chosen.
        Ok(match (self, blend) {
            (Self::Godot | Self::ThreeJs, Some(width)) => band(slices, width.get()),
            _ => slices,
        })
    }

    /// Its cascade fit and snapping with `choices`' fit where given (module docs), and no
    /// snapping if they say `unsnapped`; `None` for Filament's LiSPSM cascades.
    #[must_use]
    pub fn fit(self, choices: PresetChoices) -> Option<(CascadeFit, Snap)> {
        let (fit, snap) = match (self.engine_fit(), choices.fit) {
            (Some((_, snap)), Some(fit)) => (fit, snap),
            (None, Some(fit)) => (fit, Snap::Off),
            (Some(engine), None) => engine,
            (None, None) => return None,
        };
        Some(match choices.stabilisation {
            Stabilisation::Engine => (fit, snap),
            Stabilisation::Unsnapped => (fit, Snap::Off),
        })
    }

    /// Its cascade fit and snapping as the engine ships them.
    fn engine_fit(self) -> Option<(CascadeFit, Snap)> {
        let (fit, snap) = match self {
            // `calculate_cascade`: ceil'd diagonal square, centre floored to one texel.
            Self::Bevy => (
                CascadeFit::Diagonal { ceil: true },
                Snap::CentreFloor { texels: 1 },
            ),
            // Non-stable by default: the LiSPSM plan of the slice (see [`Self::plan`]).
            Self::Filament => return None,
            // Sphere with a one-texel border, edges rounded to 2 texels.
            Self::Godot => (
                CascadeFit::Sphere { texel_border: true },
                Snap::EdgesRound { texels: 2 },
            ),
            // `stabilizeCascades` off: the corners' box; the origin rounded to a whole texel.
            Self::Babylon => (CascadeFit::CornerBox, Snap::CentreRound { texels: 1 }),
            // Diagonal square, no rounding; centre floored to one texel.
            Self::ThreeJs => (
                CascadeFit::Diagonal { ceil: false },
                Snap::CentreFloor { texels: 1 },
            ),
            // Culling sphere (native, unverified); snapping unverified, so none.
            Self::Unity => (
                CascadeFit::Sphere {
                    texel_border: false,
                },
                Snap::Off,
            ),
            // Sphere bounds and a one-texel snap, both unverified.
            Self::Unreal => (
                CascadeFit::Sphere {
                    texel_border: false,
                },
                Snap::CentreRound { texels: 1 },
            ),
        };
        Some((fit, snap))
    }

    /// Its default bias for the map of `partition` (one of its cascades, `resolution` texels a
    /// side), as the receiver-side terms of [`Bias`] write it; `t` is the cascade's texel, its
    /// window's width over `resolution`:
    /// - Bevy (`sample_cascade`): `normal:1.8+light:0.02` — `shadow_normal_bias` 1.8 texels along
    ///   n, `shadow_depth_bias` 0.02 world units toward the light; no depth-comparison offset.
    /// - Filament (`ShadowOptions`): polygon offset slope 2.0, constant 0.5 units of its DEPTH16 map
    ///   (0.5/65535 in window depth) → `slope:2,7.6e-6`; `normalBias` 1.0 → `normal-sine:0.5`;
    ///   `constantBias` 1 mm "by which shadows are moved away from the occluders" → `light:0.001`.
    /// - Godot (`update_light_buffers`, `BIAS_FUNC`): `normal-lateral:2` (`shadow_normal_bias` 2);
    ///   toward the light `shadow_bias/100 · (2r + pancake) · 2.0` = `0.001·(2r + 20)·2` with r the
    ///   cascade's sphere radius (its border included) and 2.0 the Soft Low filter's radius scale.
    /// - Babylon (`bias` 0.00005 added to the caster's NDC z): `constant:2.5e-5` (half of it in
    ///   window depth, on the receiver's side: the same test); `normalBias` 0.
    /// - three.js CSM (`shadowBias` 1e−6 added to the receiver's depth, `shadowCoord.z += bias`):
    ///   `constant:-1e-6` — a receiver pushed away from the light, which acnes.
    /// - Unity URP (`GetShadowBias`, `ApplyShadowBias`): caster pushed 1 texel away from the light
    ///   and inset 1 texel × (1 − n·L), plus hardware depth bias 1 unit (16-bit: 1/65535) and slope
    ///   2.5 → `slope:2.5,1.5e-5+normal-versine:1+light:t`, the caster's offsets applied to the
    ///   receiver (shadowlab's receiver-side equivalent, named in [`NormalOffset::Versine`]).
    /// - Unreal: its bias units are not public (`r.Shadow.CSMDepthBias` 10, slope 3, receiver 0.9
    ///   unverified): shadowlab's default, [`Bias::DEFAULT`], named so in the docs.
    #[must_use]
    pub fn bias(self, partition: &Partition, resolution: u32) -> Bias {
        let texel = match partition.setup.mapping {
            ShadowMapping::Projective(mapping) => {
                2.0 / mapping.projection().x_axis.x.abs() / f64::from(resolution)
            }
            ShadowMapping::Logarithmic(_) | ShadowMapping::Paraboloid(_) => 0.0,
        };
        let slope = |slope, units: f64| {
            Bias::new(DepthComparison::SlopeScaled {
                constant: units / SIXTEEN_BIT_UNITS,
                slope,
            })
        };
        match self {
            Self::Bevy => Bias::NONE
                .with_normal(NormalOffset::Plain { texels: 1.8 })
                .with_toward_light(0.02),
            Self::Filament => slope(2.0, 0.5)
                .with_normal(NormalOffset::Sine { texels: 0.5 })
                .with_toward_light(0.001),
            Self::Godot => {
                let radius = partition.sphere.map_or(0.0, |s| s.radius);
                Bias::NONE
                    .with_normal(NormalOffset::Lateral { texels: 2.0 })
                    .with_toward_light(0.1 / 100.0 * (2.0 * radius + GODOT_PANCAKE) * 2.0)
            }
            Self::Babylon => Bias::new(DepthComparison::Constant { offset: 2.5e-5 }),
            Self::ThreeJs => Bias::new(DepthComparison::Constant { offset: -1e-6 }),
            Self::Unity => slope(2.5, 1.0)
                .with_normal(NormalOffset::Versine { texels: 1.0 })
                .with_toward_light(texel),
            Self::Unreal => Bias::DEFAULT,
        }
    }

    /// Plans `input`'s light as the engine does with `choices`, labelled `technique`, for maps of
    /// `resolution` texels: a directional light's cascades ([`crate::cascades`], or for Filament
    /// without a chosen fit its LiSPSM map of each cascade with Filament's parameter), a spot
    /// light's one map fitted as `uniform`.
    ///
    /// # Errors
    /// As [`crate::cascades::plan`] and [`crate::plan`].
    pub fn plan(
        self,
        input: &PlanInput,
        technique: Technique,
        choices: PresetChoices,
        resolution: u32,
    ) -> Result<Vec<Partition>, ShadowError> {
        let projection = input.eye.projection;
        let (near, far) = (projection.near(), projection.far());
        let labelled = |mut partitions: Vec<Partition>| {
            for p in &mut partitions {
                p.setup.technique = technique;
            }
            partitions
        };
        if let LightSource::Spot { .. } = input.light {
            return Ok(labelled(vec![Partition {
                near,
                far,
                face: None,
                sphere: None,
                setup: plan(input, Technique::Uniform)?,
            }]));
        }
        let slices = self.slices(near, far, choices.blend)?;
        match self.fit(choices) {
            Some(fit) => cascades::plan(input, technique, &slices, fit, resolution),
            None => {
                // Filament: `applyLISPSM` on each cascade's focused light frustum.
                let bounds: Vec<(f64, f64)> = slices.iter().map(|s| s.slice).collect();
                let lispsm = Technique::Lispsm(WarpChoice::Production(ProductionVariant::Filament));
                plan_partitions_at(input, lispsm, &bounds).map(labelled)
            }
        }
    }
}

/// Bevy `CascadeShadowConfigBuilder::default`: 4 cascades, `minimum_distance` 0.1,
/// `first_cascade_far_bound` 10, `maximum_distance` 150, `overlap_proportion` 0.2.
const BEVY_CASCADES: i32 = 4;
const BEVY_MINIMUM: f64 = 0.1;
const BEVY_FIRST_FAR: f64 = 10.0;
const BEVY_MAXIMUM: f64 = 150.0;
const BEVY_OVERLAP: f64 = 0.2;

/// Bevy's cascades (`calculate_cascade_bounds`, `build_directional_light_cascades`): far bounds
/// `b_i = first·(max/first)^(i/(N − 1))`; cascade 0 starts at `minimum_distance`, cascade `i > 0`
/// at `(1 − overlap)·b_{i−1}`. They do not depend on the camera's near and far.
fn bevy_slices(overlap: f64) -> Vec<CascadeSlice> {
    let far = |i: i32| {
        BEVY_FIRST_FAR
            * (BEVY_MAXIMUM / BEVY_FIRST_FAR).powf(f64::from(i) / f64::from(BEVY_CASCADES - 1))
    };
    (0..BEVY_CASCADES)
        .map(|i| {
            let near = if i == 0 {
                BEVY_MINIMUM
            } else {
                (1.0 - overlap) * far(i - 1)
            };
            CascadeSlice {
                select: (near, far(i)),
                slice: (near, far(i)),
            }
        })
        .collect()
}

/// Godot's `directional_shadow_max_distance` default, 100.
const GODOT_MAX_DISTANCE: f64 = 100.0;
/// Godot's `pancake_size` default, 20: how far its light frustum reaches toward the light beyond
/// the sphere.
const GODOT_PANCAKE: f64 = 20.0;
/// The steps of a 16-bit depth buffer, GL's `r` for polygon-offset units.
const SIXTEEN_BIT_UNITS: f64 = 65_535.0;
/// Godot's `directional_shadow_split_1/2/3`: 0.1, 0.2, 0.5 of the range.
const GODOT_SPLITS: [f64; 3] = [0.1, 0.2, 0.5];

/// Babylon `DEFAULT_CASCADES_COUNT` 4, `lambda` 0.5, `cascadeBlendPercentage` 0.1.
const BABYLON_CASCADES: usize = 4;
const BABYLON_LAMBDA: f64 = 0.5;
const BABYLON_BLEND: f64 = 0.1;

/// Babylon `_splitFrustum`: `d_i = λ(log − uni) + uni` at `p = (i + 1)/N` over `[minZ, maxZ]` (the
/// camera's, `shadowMaxZ` defaulting to the camera's far) — Zhang's practical split with weight λ.
fn babylon_bounds(near: f64, far: f64) -> Result<Vec<f64>, ShadowError> {
    Ok(SplitScheme::Practical {
        weight: BABYLON_LAMBDA,
    }
    .boundaries(DepthRange::new(near, far)?, BABYLON_CASCADES)?)
}

/// Cascades from `bounds`, each selected for and fitted to its own interval.
fn unbanded(bounds: &[f64]) -> Vec<CascadeSlice> {
    bounds
        .windows(2)
        .map(|pair| CascadeSlice {
            select: (pair[0], pair[1]),
            slice: (pair[0], pair[1]),
        })
        .collect()
}

/// `slices` with a blend band over the last `fraction` of each cascade's own length: cascade
/// `i + 1` is selected, and its map fitted, from `b_{i+1} − fraction·(b_{i+1} − b_i)` (band
/// coverage), so the two overlap across the band; selection and slice depths each so.
fn band(mut slices: Vec<CascadeSlice>, fraction: f64) -> Vec<CascadeSlice> {
    let widened = |(start, end): (f64, f64), (previous, _): (f64, f64)| {
        (start - fraction * (start - previous), end)
    };
    for i in (1..slices.len()).rev() {
        let previous = slices[i - 1];
        slices[i].select = widened(slices[i].select, previous.select);
        slices[i].slice = widened(slices[i].slice, previous.slice);
    }
    slices
}

/// three.js CSM: 3 cascades, `mode` 'practical' (λ 0.5, hard-coded), `maxFar` 100000.
const THREEJS_CASCADES: i32 = 3;
const THREEJS_LAMBDA: f64 = 0.5;
const THREEJS_MAX_FAR: f64 = 100_000.0;

/// three.js CSM `getBreaks` and `CSMFrustum.split`: breaks `b_i = lerp(u_i, l_i, ½)` with
/// `u_i = (n + (f − n)i/N)/f`, `l_i = n(f/n)^(i/N)/f` (fractions of f); cascade i's map is fitted
/// to the slice at eye depths `n + (f − n)·b` while the shader selects it on `depth/(f − n) ∈
/// [b_i, b_{i+1})` — the two meanings of a break that the source has, both kept.
fn threejs_slices(near: f64, far: f64) -> Result<Vec<CascadeSlice>, ShadowError> {
    let f = far.min(THREEJS_MAX_FAR);
    DepthRange::new(near, f)?;
    let n = near;
    let count = f64::from(THREEJS_CASCADES);
    let mut breaks = vec![0.0];
    for i in 1..THREEJS_CASCADES {
        let i = f64::from(i);
        let uniform = (n + (f - n) * i / count) / f;
        let log = n * (f / n).powf(i / count) / f;
        breaks.push(uniform + (log - uniform) * THREEJS_LAMBDA);
    }
    breaks.push(1.0);
    Ok(breaks
        .windows(2)
        .map(|b| CascadeSlice {
            select: ((f - n) * b[0], (f - n) * b[1]),
            slice: (n + (f - n) * b[0], n + (f - n) * b[1]),
        })
        .collect())
}

/// Unity URP `m_ShadowDistance` 50 and `m_CascadeBorder` 0.2.
const UNITY_SHADOW_DISTANCE: f64 = 50.0;
const UNITY_CASCADE_BORDER: f64 = 0.2;

/// Unreal (unverified): `DynamicShadowCascades` 3, `CascadeDistributionExponent` 3,
/// `DynamicShadowDistanceMovableLight` 20000 cm, `CascadeTransitionFraction` 0.1; splits
/// `z_i = near + (D − near)(e^i − 1)/(e^N − 1)`.
const UNREAL_CASCADES: u32 = 3;
const UNREAL_EXPONENT: f64 = 3.0;
const UNREAL_SHADOW_DISTANCE: f64 = 200.0;
const UNREAL_TRANSITION: f64 = 0.1;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bevy_bounds_are_its_defaults() {
        let far: Vec<f64> = bevy_slices(BEVY_OVERLAP)
            .iter()
            .map(|s| s.select.1)
            .collect();
        let expected = [10.0, 24.662_120_743_304_7, 60.822_019_955_734, 150.0];
        for (a, b) in far.iter().zip(expected) {
            assert!((a - b).abs() < 1e-9, "{far:?}");
        }
        assert_eq!(bevy_slices(BEVY_OVERLAP)[1].select.0, 8.0);
    }

    #[test]
    fn godot_bounds_with_near_0_05() {
        let slices = Engine::Godot.slices(0.05, 4000.0, None).unwrap();
        let far: Vec<f64> = slices.iter().map(|s| s.select.1).collect();
        let expected = [10.045, 20.04, 50.025, 100.0];
        for (a, b) in far.iter().zip(expected) {
            assert!((a - b).abs() < 1e-12, "{far:?}");
        }
    }

    #[test]
    fn unreal_bounds_are_a_geometric_series() {
        let slices = Engine::Unreal
            .slices(0.0_f64.max(1.0), 1000.0, None)
            .unwrap();
        // (3^i − 1)/(3^3 − 1): 2/26, 8/26 of 199 after the near of 1.
        assert!((slices[0].select.1 - (1.0 + 199.0 * 2.0 / 26.0)).abs() < 1e-12);
        assert!((slices[1].select.1 - (1.0 + 199.0 * 8.0 / 26.0)).abs() < 1e-12);
        assert_eq!(slices[2].select.1, 200.0);
        // The band: cascade 1 starts a tenth of cascade 0's length before its far end.
        let f0 = slices[0].select.1;
        assert!((slices[1].select.0 - (f0 - 0.1 * (f0 - 1.0))).abs() < 1e-12);
    }
}
