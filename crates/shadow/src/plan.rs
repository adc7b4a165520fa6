//! `plan`: from the eye, the light and the scene bounds to a [`LightSetup`].

use glam::{DMat4, DVec2, DVec4};
use shadowlab_hull::{Aabb2, ConvexHull2, MinAreaRect, Perspective, convex_hull_2d};
use shadowlab_params::splits::SplitScheme;
use shadowlab_params::{DepthRange, LightAngle, ParameterRule};

use crate::error::ShadowError;
use crate::faces;
use crate::focus::{focus_in_light_space, view_model};
use crate::input::PlanInput;
use crate::parameter::{self, WarpGeometry};
use crate::partition::{Partition, Region};
use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping, WarpReport};
use crate::technique::{LogarithmicChoice, Technique, WarpChoice};
use crate::warp::{self, Extents};
use crate::{logarithmic, psm};

/// Plans the shadow map of `technique` for `input`.
///
/// # Errors
/// [`ShadowError`] naming why: an empty or flat focus body, a technique not defined for the
/// configuration (GLPR for γ ≤ φ, the logarithmic map's face partitioning, which makes several
/// maps: [`plan_partitions`]), or invalid geometry. [`Technique::Optimal`] is always [`ShadowError::NotDefined`]
/// here: it needs the scene's geometry ([`crate::plan_light`], [`crate::optimal::plan`]); so is
/// [`Technique::Given`], which is read, not planned.
pub fn plan(input: &PlanInput, technique: Technique) -> Result<LightSetup, ShadowError> {
    match technique {
        Technique::Uniform | Technique::Lispsm(_) => light_space_warp(input, technique),
        Technique::UniformLimited => uniform_limited(input),
        Technique::Psm => psm::plan(input),
        Technique::Logarithmic(choice) => logarithmic::plan(input, choice),
        Technique::Optimal(_) => Err(ShadowError::NotDefined {
            technique: "optimal",
            reason:
                "the scene-optimized map needs the scene's geometry (a low-resolution eye pass \
                     and its shadows), not a plan input alone: plan it with plan_light or \
                     optimal::plan"
                    .into(),
        }),
        Technique::Sdsm(_) => Err(ShadowError::NotDefined {
            technique: "sdsm",
            reason: "sample distribution shadow maps are fitted to the eye pass's samples: plan \
                     them with plan_light and the eye image"
                .into(),
        }),
        Technique::Engine(..) => Err(ShadowError::NotDefined {
            technique: technique.key(),
            reason: "an engine's preset plans its own cascades and needs the map's size: plan it \
                     with plan_light"
                .into(),
        }),
        Technique::Cube | Technique::DualParaboloid => Err(ShadowError::NotDefined {
            technique: technique.key(),
            reason: "an omnidirectional map's near plane is the nearest geometry its light sees: \
                     plan it with plan_light and the scene"
                .into(),
        }),
        Technique::Given => Err(ShadowError::NotDefined {
            technique: "given",
            reason: "a given set-up is read from its set-up file, not planned".into(),
        }),
    }
}

/// Uniform and LiSPSM: P fitted to B in light space (LiSPSM §3.4–3.5), LiSPSM's parameter as its
/// choice computes it ([`crate::parameter`]).
fn light_space_warp(input: &PlanInput, technique: Technique) -> Result<LightSetup, ShadowError> {
    let (frame, world_points, points) = focus_in_light_space(input, technique)?;
    let (model, half_fov) = view_model(input)?;
    let gamma = LightAngle::from_radians(frame.gamma())?;
    let choice = match technique {
        Technique::Lispsm(choice) => choice,
        _ => WarpChoice::Rule(ParameterRule::Uniform),
    };
    let decision = parameter::decide(
        choice,
        &WarpGeometry {
            input,
            frame: &frame,
            world_points: &world_points,
            points: &points,
            gamma,
            model: &model,
            half_fov,
        },
    )?;
    let kappa = decision.kappa;
    let fitted = warp::fit(&points, decision.reference, kappa)?;
    Ok(LightSetup {
        technique,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(
            frame.world_to_light(),
            fitted.matrix,
        )),
        gamma: gamma.radians(),
        half_fov,
        warp: Some(WarpReport {
            lambda: 1.0 / kappa,
            near_distance: fitted.depth / kappa,
            depth: fitted.depth,
            formula: decision.formula,
            inputs: decision.inputs,
        }),
        psm: None,
        focus_body: world_points,
    })
}

/// The standard shadow map with CG06's frustum limiting: the window is the minimum-area rectangle
/// around the view frustum's projection on the shadow-map plane, clipped to B's extent there; the
/// depth range is B's.
fn uniform_limited(input: &PlanInput) -> Result<LightSetup, ShadowError> {
    let technique = Technique::UniformLimited;
    let (frame, world_points, points) = focus_in_light_space(input, technique)?;
    let (_, half_fov) = view_model(input)?;
    let extents = Extents::of(&points);
    // The view frustum's corners on the shadow-map plane (x, z); for a spot light, B's points
    // where a corner lies behind the spot.
    let corners = input.eye.frustum().corners().to_vec();
    let projected: Vec<DVec2> = match frame.light_points(&corners) {
        Some(c) => c.iter().map(|p| DVec2::new(p.x, p.z)).collect(),
        None => points.iter().map(|p| DVec2::new(p.x, p.z)).collect(),
    };
    let window = Aabb2::from_points(&[
        DVec2::new(extents.min.x, extents.min.z),
        DVec2::new(extents.max.x, extents.max.z),
    ])?;
    let hull = match convex_hull_2d(&projected)? {
        ConvexHull2::Polygon(polygon) => clip_to_box(polygon.vertices(), &window),
        _ => {
            return Err(ShadowError::FlatFocusBody {
                axis: "lateral axis",
            });
        }
    };
    let rect = MinAreaRect::of_points(&hull)?;
    let [u, v] = rect.axes();
    let (c, h) = (rect.center(), rect.half_extents());
    let depth_range = extents.max.y - extents.min.y;
    if depth_range <= 0.0 {
        return Err(ShadowError::FlatFocusBody { axis: "light axis" });
    }
    // Rows on light-space (x, y, z, 1): X along u, Y along v (both on the x–z plane), depth along −y.
    let x_row = DVec4::new(u.x, 0.0, u.y, -c.dot(u)) / h.x;
    let y_row = DVec4::new(v.x, 0.0, v.y, -c.dot(v)) / h.y;
    let z_row = DVec4::new(0.0, -2.0, 0.0, extents.max.y + extents.min.y) / depth_range;
    let projection = DMat4::from_cols(x_row, y_row, z_row, DVec4::W).transpose();
    Ok(LightSetup {
        technique,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(
            frame.world_to_light(),
            projection,
        )),
        gamma: frame.gamma(),
        half_fov,
        warp: None,
        psm: None,
        focus_body: world_points,
    })
}

/// A convex polygon clipped to an axis-aligned box (Sutherland–Hodgman, one side at a time).
fn clip_to_box(polygon: &[DVec2], window: &Aabb2) -> Vec<DVec2> {
    let (lo, hi) = (window.min(), window.max());
    // Each side as (axis, bound, keep the side where coordinate ≥ bound if `above`).
    let sides = [
        (0, lo.x, true),
        (0, hi.x, false),
        (1, lo.y, true),
        (1, hi.y, false),
    ];
    let mut out = polygon.to_vec();
    for (axis, bound, above) in sides {
        let inside = |p: DVec2| {
            if above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let input = std::mem::take(&mut out);
        for (k, &p) in input.iter().enumerate() {
            let q = input[(k + 1) % input.len()];
            if inside(p) {
                out.push(p);
            }
            if inside(p) != inside(q) {
                let t = (bound - p[axis]) / (q[axis] - p[axis]);
                out.push(p + (q - p) * t);
            }
        }
    }
    out
}

/// How the view's depth range is split for z-partitioning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Splits {
    /// Equal lengths.
    Uniform,
    /// Equal ratios (CAD eq. 5).
    Logarithmic,
    /// Zhang et al.'s practical blend with the logarithmic split's weight in `[0, 1]`.
    Practical {
        /// The logarithmic split's weight.
        weight: f64,
    },
    /// CAD eq. 19 with its δ, at the configuration's own γ.
    Adaptive {
        /// δ > 1.
        delta: f64,
    },
}

impl Splits {
    /// shadowlab's default: Zhang et al.'s practical split with weight 0.5, halfway between the
    /// uniform and the logarithmic split.
    pub const DEFAULT: Self = Self::Practical { weight: 0.5 };
}

/// z-partitioning (CAD §3.3): the view's depth range split into `count` parts by `splits`, each
/// part's sub-frustum focused and warped by `technique` on its own. One part is the unpartitioned
/// map. The logarithmic map's face partitioning ([`crate::faces`]) splits each part further, one
/// partition per face of its view that faces away from the light.
///
/// # Errors
/// As [`plan`] for any part; [`ShadowError::Parameter`] if the split scheme rejects the range or
/// count.
pub fn plan_partitions(
    input: &PlanInput,
    technique: Technique,
    splits: Splits,
    count: usize,
) -> Result<Vec<Partition>, ShadowError> {
    let bounds: Vec<(f64, f64)> = partition_inputs(input, splits, count)?
        .into_iter()
        .map(|(near, far, _)| (near, far))
        .collect();
    plan_partitions_at(input, technique, &bounds)
}

/// [`plan_partitions`] of the sub-frusta between the eye depths `bounds` (each `(near, far)`).
pub(crate) fn plan_partitions_at(
    input: &PlanInput,
    technique: Technique,
    bounds: &[(f64, f64)],
) -> Result<Vec<Partition>, ShadowError> {
    let mut partitions = Vec::new();
    for &(near, far) in bounds {
        let part = sub_frustum(input, near, far)?;
        if technique == Technique::Logarithmic(LogarithmicChoice::Faces) {
            partitions.extend(faces::plan(&part)?.into_iter().map(|face| Partition {
                near,
                far,
                face: Some(Region::ViewFace(face.region)),
                sphere: None,
                setup: face.setup,
            }));
        } else {
            partitions.push(Partition {
                near,
                far,
                face: None,
                sphere: None,
                setup: plan(&part, technique)?,
            });
        }
    }
    Ok(partitions)
}

/// `input` with the eye's projection cut to the eye depths `[near, far]`.
fn sub_frustum(input: &PlanInput, near: f64, far: f64) -> Result<PlanInput, ShadowError> {
    let projection = input.eye.projection;
    let mut part = *input;
    part.eye.projection = Perspective::new(projection.fov_y(), projection.aspect(), near, far)?;
    Ok(part)
}

/// The sub-frusta of z-partitioning: the view's depth range split into `count` parts by `splits`,
/// each as `(near, far, input)` with the eye's projection cut to `[near, far]`.
pub(crate) fn partition_inputs(
    input: &PlanInput,
    splits: Splits,
    count: usize,
) -> Result<Vec<(f64, f64, PlanInput)>, ShadowError> {
    let projection = input.eye.projection;
    let range = DepthRange::new(projection.near(), projection.far())?;
    let gamma = || {
        shadowlab_hull::light_view_angle(
            input.eye.pose.forward(),
            input.light.toward_from(input.eye.pose.eye()),
        )
    };
    let scheme = match splits {
        Splits::Uniform => SplitScheme::Uniform,
        Splits::Logarithmic => SplitScheme::Logarithmic,
        Splits::Practical { weight } => SplitScheme::Practical { weight },
        Splits::Adaptive { delta } => SplitScheme::Adaptive {
            delta,
            gamma: LightAngle::from_radians(gamma()?)?,
        },
    };
    let boundaries = scheme.boundaries(range, count)?;
    boundaries
        .windows(2)
        .map(|pair| Ok((pair[0], pair[1], sub_frustum(input, pair[0], pair[1])?)))
        .collect()
}

impl Splits {
    /// Parses `uniform`, `logarithmic`, `practical[:WEIGHT]` (default 0.5, three.js's; OGRE ships
    /// 0.95), `adaptive[:DELTA]` (default 2, CAD's recommendation with PCF).
    ///
    /// # Errors
    /// A message naming what is wrong and the accepted forms.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (name, value) = match spec.split_once(':') {
            Some((name, v)) => (
                name,
                Some(
                    v.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| format!("{v:?} in {spec:?} is not a finite number"))?,
                ),
            ),
            None => (spec, None),
        };
        match (name, value) {
            ("uniform", None) => Ok(Self::Uniform),
            ("logarithmic", None) => Ok(Self::Logarithmic),
            ("practical", weight) => {
                let weight = weight.unwrap_or(0.5);
                if (0.0..=1.0).contains(&weight) {
                    Ok(Self::Practical { weight })
                } else {
                    Err(format!("the weight in {spec:?} must lie in [0, 1]"))
                }
            }
            ("adaptive", delta) => {
                let delta = delta.unwrap_or(2.0);
                if delta > 1.0 {
                    Ok(Self::Adaptive { delta })
                } else {
                    Err(format!("δ in {spec:?} must be greater than 1"))
                }
            }
            _ => Err(format!(
                "unknown split scheme {spec:?}; known: uniform, logarithmic, practical[:WEIGHT], adaptive[:DELTA]"
            )),
        }
    }
}

/// The form [`Splits::parse`] reads: `uniform`, `logarithmic`, `practical:WEIGHT`,
/// `adaptive:DELTA` (shortest round-trip numbers).
impl std::fmt::Display for Splits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Uniform => f.write_str("uniform"),
            Self::Logarithmic => f.write_str("logarithmic"),
            Self::Practical { weight } => write!(f, "practical:{weight}"),
            Self::Adaptive { delta } => write!(f, "adaptive:{delta}"),
        }
    }
}
