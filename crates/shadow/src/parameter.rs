//! LiSPSM's free parameter, computed as each source computes it, in the source's own units.
//!
//! A warp is fitted to B in light space ([`crate::warp`]): P's near plane at B's largest z, its
//! projection reference point `n` beyond it. What differs between the choices is `n` (or λ = n/d,
//! d being B's extent along the warp axis) and, for the authors' 2006 code, where the reference
//! point sits laterally:
//!
//! | choice | n | source |
//! |---|---|---|
//! | `lispsm` | `(z_n + √(z_n·z_f))/sin γ`, z_n and z_f the camera's near and far | LiSPSM §4.4; formulas.md §2.6 |
//! | `lispsm_dz` | `(z_n + √(z_n·(z_n + d·sin γ)))/sin γ` | LiSPSM §4.4 (Δz); formulas.md §2.7 |
//! | `authors2006` | `d/(√(z1/z0) − 1)`, z0 the eye depth of B's nearest point, `z1 = z0 + d·sin γ` | the authors' 2006 `calcNoptGeneral` (OpenSceneGraph's `LightSpacePerspectiveShadowMap.cpp`) |
//! | `cad`, `cad_eq17`, `cad_sin2`, `gmnpr`, `glpr`, `minimax`, `uniform` | `λ·d`, λ unit-free in the 2-D model of the view | CAD eq. 16, GMNPR eqs. 7–8, GMNPR §3, formulas.md §5.8 |
//! | `model` | `λ·d`, λ = GMNPR eq. 9 (LiSPSM's n over the model's depth) | shadowlab's own transfer |
//! | engines (`filament`, `ogre`, `osg`, `osg_vdsm`) | as `production-variants.md` gives them | each engine's source |
//! | `lambda=L`, `n=N` | as stated | the user |
//!
//! For a spot light everything is measured after the spot's perspective transform, where its rays
//! are parallel (LiSPSM §3.4): z_n and z_f are the distances from the eye to the view axis's near
//! and far points there, d is B's extent there.

use glam::DVec3;
use shadowlab_params::{FrustumModel, LightAngle, ParameterRule, lispsm};

use crate::error::ShadowError;
use crate::frame::LightFrame;
use crate::input::PlanInput;
use crate::technique::{ProductionVariant, WarpChoice};
use crate::warp::{Extents, Reference};

/// What a choice decided, and from what.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct WarpDecision {
    /// κ = d/n = 1/λ; 0 for the uniform map.
    pub(crate) kappa: f64,
    /// Where P's projection reference point sits across the warp axis.
    pub(crate) reference: Reference,
    /// The formula and its source, in words.
    pub(crate) formula: String,
    /// The inputs the formula used, by name (angles in degrees).
    pub(crate) inputs: Vec<(&'static str, f64)>,
}

/// The geometry every choice computes from.
pub(crate) struct WarpGeometry<'a> {
    pub(crate) input: &'a PlanInput,
    pub(crate) frame: &'a LightFrame,
    /// B's vertices in world space and, in the same order, in light space.
    pub(crate) world_points: &'a [DVec3],
    pub(crate) points: &'a [DVec3],
    pub(crate) gamma: LightAngle,
    /// The 2-D model of the view the unit-free rules work in, and φ.
    pub(crate) model: &'a FrustumModel,
    pub(crate) half_fov: f64,
}

impl WarpGeometry<'_> {
    fn extents(&self) -> Extents {
        Extents::of(self.points)
    }

    /// d, B's extent along the warp axis.
    fn depth(&self) -> f64 {
        let e = self.extents();
        e.max.z - e.min.z
    }

    /// The camera's near and far distances in light space.
    fn view_range(&self) -> Result<(f64, f64), ShadowError> {
        self.frame
            .view_range(&self.input.eye)
            .ok_or_else(|| ShadowError::NotDefined {
                technique: "lispsm",
                reason: "the view axis's near or far point lies behind the spot light's plane, \
                         so LiSPSM's z_n and z_f have no value in its space"
                    .into(),
            })
    }

    /// The inputs every choice reports.
    fn common(&self) -> [(&'static str, f64); 2] {
        [("gamma_degrees", self.gamma.degrees()), ("d", self.depth())]
    }
}

/// κ for `n`: `d/n`, 0 (uniform) where n is infinite, not positive or not a number.
fn kappa_of(depth: f64, n: f64) -> f64 {
    if n.is_finite() && n > 0.0 {
        depth / n
    } else {
        0.0
    }
}

/// `n = (z_n + √(z_n·z_f))/sin γ`, infinite at γ = 0.
fn paper_n(z_n: f64, z_f: f64, gamma: LightAngle) -> f64 {
    if gamma.is_parallel() {
        f64::INFINITY
    } else {
        (z_n + z_n.sqrt() * z_f.sqrt()) / gamma.sin()
    }
}

/// The decision of `choice` for `geometry`.
///
/// # Errors
/// [`ShadowError::NotDefined`] for GLPR at γ ≤ φ, and for `lispsm`/`lispsm_dz` where a spot light
/// puts the view axis's ends behind its plane.
pub(crate) fn decide(
    choice: WarpChoice,
    geometry: &WarpGeometry<'_>,
) -> Result<WarpDecision, ShadowError> {
    let depth = geometry.depth();
    let gamma = geometry.gamma;
    let [angle, d] = geometry.common();
    let at_eye = Reference::EYE;
    let decision = match choice {
        WarpChoice::Rule(ParameterRule::Lispsm) => {
            let (z_n, z_f) = geometry.view_range()?;
            WarpDecision {
                kappa: kappa_of(depth, paper_n(z_n, z_f, gamma)),
                reference: at_eye,
                formula: "n = (z_n + √(z_n·z_f))/sin γ, z_n and z_f the camera's near and far \
                          (LiSPSM §4.4; formulas.md §2.6)"
                    .into(),
                inputs: vec![("z_n", z_n), ("z_f", z_f), angle, d],
            }
        }
        WarpChoice::Rule(ParameterRule::LispsmDeltaZ) => {
            let (z_n, _) = geometry.view_range()?;
            let n = lispsm::n_delta_z(z_n, depth, gamma)?;
            WarpDecision {
                kappa: kappa_of(depth, n),
                reference: at_eye,
                formula: "n = (z_n + √(z_n·(z_n + d·sin γ)))/sin γ, z_n the camera's near, d B's \
                          depth along the warp axis (LiSPSM §4.4, the Δz variant; formulas.md §2.7)"
                    .into(),
                inputs: vec![("z_n", z_n), angle, d],
            }
        }
        WarpChoice::Rule(rule) => {
            let warp = rule
                .warp(geometry.model, gamma)
                .ok_or_else(|| ShadowError::NotDefined {
                    technique: "lispsm",
                    reason: format!(
                        "the {} parameter needs γ > φ (γ = {:.4}°, φ = {:.4}°)",
                        rule.key(),
                        gamma.degrees(),
                        geometry.half_fov.to_degrees()
                    ),
                })?;
            WarpDecision {
                kappa: warp.inverse_lambda(),
                reference: at_eye,
                formula: model_formula(rule),
                inputs: model_inputs(geometry, angle, d),
            }
        }
        WarpChoice::LispsmModel => WarpDecision {
            kappa: ParameterRule::Lispsm
                .warp(geometry.model, gamma)
                .map_or(0.0, |w| w.inverse_lambda()),
            reference: at_eye,
            formula:
                "λ = (z_n + √(z_n·z_f))/(sin γ·d_model), d_model the 2-D model's depth (GMNPR \
                      eq. 9), used with B's depth: n = λ·d — shadowlab's own transfer of LiSPSM's \
                      parameter"
                    .into(),
            inputs: model_inputs(geometry, angle, d),
        },
        WarpChoice::Lambda(warp) => WarpDecision {
            kappa: warp.inverse_lambda(),
            reference: at_eye,
            formula: "λ as stated".into(),
            inputs: vec![angle, d],
        },
        WarpChoice::NearDistance(n) => WarpDecision {
            kappa: kappa_of(depth, n.get()),
            reference: at_eye,
            formula: "n as stated".into(),
            inputs: vec![angle, d],
        },
        WarpChoice::Production(variant) => production(variant, geometry)?,
    };
    Ok(decision)
}

fn model_formula(rule: ParameterRule) -> String {
    match rule {
        ParameterRule::Uniform => "λ = ∞: the uniform map".into(),
        other => format!(
            "λ of {} in the 2-D model of the view (unit-free), used with B's depth: n = λ·d",
            other.label()
        ),
    }
}

/// The 2-D model's inputs: the eye's near and far, φ.
fn model_inputs(
    geometry: &WarpGeometry<'_>,
    angle: (&'static str, f64),
    d: (&'static str, f64),
) -> Vec<(&'static str, f64)> {
    let range = geometry.model.range();
    vec![
        ("near", range.near()),
        ("far", range.far()),
        ("phi_degrees", geometry.half_fov.to_degrees()),
        angle,
        d,
    ]
}

/// Below this angle OSG's view-dependent shadow map is plainly orthographic (production-variants.md).
const OSG_VDSM_ORTHOGRAPHIC_BELOW_DEGREES: f64 = 2.0;
/// Filament switches the warp off when `sin γ` is at most this.
const FILAMENT_NO_WARP_SIN: f64 = 0.02;
/// Filament's "virtual" near and far hints, in metres.
const FILAMENT_NEAR_HINT: f64 = 1.0;
const FILAMENT_FAR_HINT: f64 = 100.0;
/// OGRE's default optimisation factor and the angle inside which it strengthens the warp.
const OGRE_FACTOR: f64 = 0.1;
const OGRE_BOOST_RADIANS: f64 = 0.451;
const OGRE_BOOST_MAX: f64 = 20.0;
/// The authors' 2006 code's fall-back depths (world units) where `z1/z0 ≤ 1`: z0 at least this,
/// z1 at least z0 plus this.
const AUTHORS2006_FALLBACK_DEPTH: f64 = 0.1;

/// An engine's choice (production-variants.md), with B's depth d along the warp axis. Where an
/// engine divides by `sin γ = 0` (and so would produce NaN or infinity), the uniform map (κ = 0) is
/// taken.
fn production(
    variant: ProductionVariant,
    geometry: &WarpGeometry<'_>,
) -> Result<WarpDecision, ShadowError> {
    let eye = &geometry.input.eye;
    let (zn, zf) = (eye.projection.near(), eye.projection.far());
    let gamma = geometry.gamma;
    let sin = gamma.sin();
    let extents = geometry.extents();
    let depth = geometry.depth();
    let [angle, d] = geometry.common();
    let at_eye = Reference::EYE;
    // Filament's z0: the eye depth where the view axis meets P's near plane (light-space z = z_max;
    // the eye is the light-space origin and the view direction has z component −sin γ), at least
    // the near plane.
    let axis_z0 = if sin > 0.0 {
        (-extents.max.z / sin).max(zn)
    } else {
        zn
    };
    let decision = match variant {
        ProductionVariant::Filament => {
            let dzn = (FILAMENT_NEAR_HINT - zn).max(0.0);
            let ratio = 3.0 * dzn / (zf - zn);
            let n = if sin <= FILAMENT_NO_WARP_SIN || ratio >= 2.0 {
                f64::INFINITY
            } else {
                ((axis_z0 + (FILAMENT_NEAR_HINT * FILAMENT_FAR_HINT).sqrt()) / sin)
                    .max(dzn / (2.0 - ratio))
            };
            WarpDecision {
                kappa: kappa_of(depth, n),
                reference: at_eye,
                formula: "n = max((z0 + √(vz0·vz1))/sin γ, dzn/(2 − 3·dzn/(z_f − z_n))), vz0 = 1, \
                          vz1 = 100, dzn = max(0, vz0 − z_n); uniform when sin γ ≤ 0.02 (Filament \
                          ShadowMap.cpp; production-variants.md)"
                    .into(),
                inputs: vec![("z0", axis_z0), ("z_n", zn), ("z_f", zf), angle, d],
            }
        }
        ProductionVariant::Ogre => {
            let e_z = extents.max.z.abs();
            let cos = gamma.cos();
            let cos_boost = OGRE_BOOST_RADIANS.cos();
            let boost = if cos > cos_boost {
                1.0 + OGRE_BOOST_MAX * (cos - cos_boost) / (1.0 - cos_boost)
            } else {
                1.0
            };
            WarpDecision {
                kappa: kappa_of(depth, (e_z + (zn * zf).sqrt()) * OGRE_FACTOR * boost),
                reference: at_eye,
                formula: "n = (|e_z| + √(z_n·z_f))·0.1, times 1 + 20·(cos γ − cos 25.8°)/(1 − cos \
                          25.8°) inside 25.8° (OGRE OgreShadowCameraSetupLiSPSM.cpp; \
                          production-variants.md)"
                    .into(),
                inputs: vec![("e_z", e_z), ("z_n", zn), ("z_f", zf), angle, d],
            }
        }
        ProductionVariant::Osg => {
            let n = if sin == 0.0 {
                f64::INFINITY
            } else {
                let zn_prime = zn / sin;
                let zf_prime = zn_prime + depth * sin;
                (zn_prime + (zn_prime * zf_prime).sqrt()) / sin
            };
            WarpDecision {
                kappa: kappa_of(depth, n),
                reference: at_eye,
                formula:
                    "n = (z_n' + √(z_n'·z_f'))/sin γ, z_n' = z_n/sin γ, z_f' = z_n' + d·sin γ \
                          (the authors' 2004 code, as kept in OpenSceneGraph's \
                          LightSpacePerspectiveShadowMap.cpp)"
                        .into(),
                inputs: vec![("z_n", zn), angle, d],
            }
        }
        ProductionVariant::Authors2006 => authors_2006(geometry, angle, d)?,
        ProductionVariant::OsgViewDependent => {
            let n = if gamma.degrees() < OSG_VDSM_ORTHOGRAPHIC_BELOW_DEGREES {
                f64::INFINITY
            } else {
                // In a light clip space of depth 2 spanning B along the warp axis; the eye's
                // position there is −1 at P's near plane (z_max) and +1 at its far plane.
                let eye_y = 2.0 * extents.max.z / depth - 1.0;
                let cot = gamma.cos() / sin;
                let n_clip = (30f64.to_radians().tan() * cot * cot).max((-1.0 - eye_y).max(0.05));
                n_clip * depth / 2.0
            };
            WarpDecision {
                kappa: kappa_of(depth, n),
                reference: at_eye,
                formula: "n = tan 30°·cot² γ in a light clip space of depth 2, at least max(−1 − \
                          eye_y, 0.05); uniform below 2° (OpenSceneGraph ViewDependentShadowMap.cpp)".into(),
                inputs: vec![angle, d],
            }
        }
    };
    Ok(decision)
}

/// The authors' 2006 `calcNoptGeneral`, as OpenSceneGraph's `LightSpacePerspectiveShadowMap.cpp`
/// carries it (read, not copied): E is B's point nearest the camera (largest eye-space z), z0 its
/// eye depth; z1 the eye depth of the point d further along the warp axis, `z0 + d·sin γ` (for a
/// spot light shadowlab takes the same expression with d and γ of the spot's space; the code maps
/// that point back to eye space instead). Where `z1/z0 ≤ 1` the code falls back to B's nearest and
/// farthest eye depths, z0 at least 0.1 and z1 at least z0 + 0.1. Then `n = d/(√(z1/z0) − 1)`, in
/// the stable form `d·(z0 + √(z0·z1))/(z1 − z0)` (formulas.md §9.2). P's projection reference point
/// sits over E (`Cstart = (e_ls.x, e_ls.y, B.zMax)`), not over the eye.
fn authors_2006(
    geometry: &WarpGeometry<'_>,
    angle: (&'static str, f64),
    d: (&'static str, f64),
) -> Result<WarpDecision, ShadowError> {
    let pose = geometry.input.eye.pose;
    let eye_depth = |p: &DVec3| (*p - pose.eye()).dot(pose.forward());
    let (nearest, z_near) = geometry
        .world_points
        .iter()
        .map(eye_depth)
        .enumerate()
        .fold((0, f64::INFINITY), |(k, z), (i, depth)| {
            if depth < z { (i, depth) } else { (k, z) }
        });
    let z_far = geometry
        .world_points
        .iter()
        .map(eye_depth)
        .fold(f64::NEG_INFINITY, f64::max);
    let depth = geometry.depth();
    let mut z0 = z_near;
    let mut z1 = z0 + depth * geometry.gamma.sin();
    // z1/z0 ≤ 1, with z0 ≤ 0 read as the code's intent (its division gives ≤ 1 or ∞ there).
    let fell_back = z0 <= 0.0 || z1 <= z0;
    if fell_back {
        z0 = if z_near > 0.0 {
            z_near
        } else {
            AUTHORS2006_FALLBACK_DEPTH
        };
        z1 = if z_far > z0 {
            z_far
        } else {
            z0 + AUTHORS2006_FALLBACK_DEPTH
        };
    }
    let n = lispsm::n_general(depth, z0, z1)?;
    let e = geometry.points[nearest];
    Ok(WarpDecision {
        kappa: kappa_of(depth, n),
        reference: Reference {
            x: e.x,
            y: Some(e.y),
        },
        formula: String::from(if fell_back {
            "n = d/(√(z1/z0) − 1), z0 and z1 B's nearest and farthest eye depths (the code's \
             fall-back where z1/z0 ≤ 1; z0 ≥ 0.1, z1 ≥ z0 + 0.1); reference point over B's nearest \
             point (the authors' 2006 calcNoptGeneral, as in OpenSceneGraph's \
             LightSpacePerspectiveShadowMap.cpp)"
        } else {
            "n = d/(√(z1/z0) − 1), z0 the eye depth of B's nearest point, z1 = z0 + d·sin γ; \
             reference point over B's nearest point (the authors' 2006 calcNoptGeneral, as in \
             OpenSceneGraph's LightSpacePerspectiveShadowMap.cpp)"
        }),
        inputs: vec![("z0", z0), ("z1", z1), angle, d],
    })
}
