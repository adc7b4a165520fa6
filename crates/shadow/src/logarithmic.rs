//! The logarithmic parameterisation (LiSPSM §4; Lloyd et al., *Logarithmic perspective shadow
//! maps*, ACM TOG 27(4), 2008), evaluated exactly in software.
//!
//! In LiSPSM's light space (viewer looking down −z, y toward the light), with `τ = (z_max − z)/d`
//! the position through B's extent `d` along the warp axis, the map is
//!
//! ```text
//! Y = 2·ln(1 + τ/λ)/ln(1 + 1/λ) − 1        the warp axis, logarithmic
//! X = (2x/w − (l + r))/(r − l),  w = 1 + τ/λ   lateral: perspective from the same point, as P's
//! depth = linear in y, growing away from the light
//! ```
//!
//! with its reference point at distance `n' = λ·d` beyond B's near plane along the warp axis. At
//! the eye's position, `λ = −z_max/d` (the eye is the light-space origin), the view axis, whose eye
//! depth `t` has light-space `z = −t sin γ`, gets `1 + τ/λ = t sin γ/(−z_max)`, so `s = (Y + 1)/2`
//! is `ln(t/t0)/ln(1 + 1/λ)` and the perspective aliasing `dp/ds = (1/t)·dt/ds = ln(1 + 1/λ)` is the
//! same at every depth: for `γ = 90°` and B = V, `ln(zf/zn)` (formulas.md §2.9), the constant the
//! paper predicts. The map is not projective, so no rasterizer can draw it: the shadow map is
//! made by casting one ray per texel along the light ([`LogarithmicMap::texel_ray`]).
//!
//! The eye can serve as the reference point only where it lies beyond B's near plane (`z_max < 0`;
//! for B = V, `γ > φ`). [`reference_lambda`] is the rule that chooses λ everywhere else too
//! ([`LogarithmicChoice::Eye`]); `lambda=L` and `n=N` state it. Everything is written in `κ = 1/λ`
//! (`Y = 2·ln(1 + κτ)/ln(1 + κ) − 1`, `w = 1 + κτ`), so `κ = 0` is the uniform map exactly, the
//! limit the rule reaches as γ → 0.

use glam::DVec3;

use shadowlab_params::{FrustumModel, LightAngle, gmnpr};

use crate::error::ShadowError;
use crate::focus::{focus_points, view_model};
use crate::frame::LightFrame;
use crate::input::PlanInput;
use crate::setup::{LightSetup, ShadowMapping, WarpReport};
use crate::technique::{LogarithmicChoice, Technique};
use crate::warp::Extents;

pub use crate::logarithmic_map::{LanesAt, LogarithmicMap, TexelRow};

/// The smallest λ of a logarithmic map: a reference point within a billionth of B's depth of its
/// near plane would all but sit on B (a third of the map's rows would cover B's first 1e-6 of
/// depth). A stated λ below it is refused.
pub const MIN_LAMBDA: f64 = 1e-9;

/// How near [`reference_lambda`] lets the reference point come to B's near plane, as a fraction
/// of the eye's own distance in the papers' ideal case (γ = 90°, B = V: `λ = z_n/(z_f − z_n)`).
/// Where the eye approaches B's near plane (γ → φ for B = V) the eye's λ tends to 0 and the map
/// would crowd its rows onto that plane; the floor keeps its error within `ln(1 + 10·z_f/z_n)`
/// there and the map's change per radian of γ bounded. On the built-in scenes the eye's λ is at
/// least 2.8 times the floor (cad-lattice), so the floor leaves them alone.
pub const REFERENCE_FLOOR_FRACTION: f64 = 0.1;

/// λ of shadowlab's reference rule ([`LogarithmicChoice::Eye`]) for B with near plane `z_max`
/// and depth `depth` along the warp axis (the eye at the light-space origin):
///
/// `λ = max(λ_eye, λ_fall(γ), λ_floor)`, `λ_eye = −z_max/d`,
/// `λ_fall(γ) = max(0, λ_mm(γ) − λ_mm(φ))` for `γ < φ`, 0 above,
/// `λ_floor = 0.1·z_n/(z_f − z_n)` ([`REFERENCE_FLOOR_FRACTION`], z_n and z_f the view's),
///
/// with `λ_mm` the L∞-optimal λ of a perspective warp in the 2-D model of the view (formulas.md
/// §5.8, `shadowlab_params::gmnpr::lambda_minimax`): where the eye lies inside B's extent the
/// reference point is placed where the best perspective warp would put its projection centre
/// (the lateral mapping of both is the same perspective from that point), less that λ's value at
/// φ, so that λ is continuous where the eye crosses B's near plane (γ = φ for B = V); it grows to
/// infinity as γ → 0, so the map tends to the uniform one. Wherever the eye lies beyond B's near
/// plane by more than `λ_floor·d` and `γ ≥ φ` — every built-in scene but the dueling frusta, and
/// B = V at 90° for any depth range — this is the eye's λ, the logarithmic map of LiSPSM §4 and
/// Lloyd et al. shadowlab's own rule: neither paper defines the map where the eye lies inside B's
/// extent (measured against stated λ in docs/benchmarks.md).
#[must_use]
pub fn reference_lambda(z_max: f64, depth: f64, model: &FrustumModel, gamma: LightAngle) -> f64 {
    let eye = -z_max / depth;
    let phi = model.half_fov().radians();
    let fall = match LightAngle::from_radians(phi) {
        Ok(at_phi) if gamma.radians() < phi => {
            let minimax = |angle| gmnpr::lambda_minimax(model, angle).lambda();
            (minimax(gamma) - minimax(at_phi)).max(0.0)
        }
        _ => 0.0,
    };
    let range = model.range();
    let floor = REFERENCE_FLOOR_FRACTION * range.near() / range.length();
    eye.max(fall).max(floor).max(MIN_LAMBDA)
}

/// How a logarithmic map's reference point is placed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ReferenceRule {
    /// shadowlab's rule, [`reference_lambda`].
    Rule,
    /// The eye, where it lies beyond B's near plane (a face partition's side face always has it
    /// there), at least [`MIN_LAMBDA`].
    Eye,
    /// Infinitely far: the uniform map (a face partition's end face).
    Uniform,
    /// λ as stated.
    Lambda(f64),
    /// n' as stated.
    NearDistance(f64),
}

/// Plans the logarithmic map for `input`, its reference point chosen by `choice`.
///
/// # Errors
/// [`ShadowError::NotDefined`] for face partitioning (several maps: [`crate::plan_partitions`]) or
/// a stated λ below [`MIN_LAMBDA`]; as [`crate::plan`] otherwise.
pub(crate) fn plan(
    input: &PlanInput,
    choice: LogarithmicChoice,
) -> Result<LightSetup, ShadowError> {
    let technique = Technique::Logarithmic(choice);
    let reference = match choice {
        LogarithmicChoice::Eye => ReferenceRule::Rule,
        LogarithmicChoice::Lambda(warp) => ReferenceRule::Lambda(warp.lambda()),
        LogarithmicChoice::NearDistance(n) => ReferenceRule::NearDistance(n.get()),
        LogarithmicChoice::Faces => {
            return Err(ShadowError::NotDefined {
                technique: technique.key(),
                reason: "face partitioning makes one map per face of the view frustum: plan it \
                         with plan_partitions or plan_light"
                    .into(),
            });
        }
    };
    let frame = LightFrame::new(&input.eye, &input.light, technique.key())?;
    let (model, half_fov) = view_model(input)?;
    let gamma = LightAngle::from_radians(frame.gamma())?;
    plan_in(
        technique,
        &frame,
        focus_points(input)?,
        reference,
        &model,
        gamma,
        half_fov,
    )
}

/// The logarithmic map of the body with vertices `world_points` in light space `frame`, its
/// reference point placed by `reference`.
///
/// # Errors
/// [`ShadowError::NotDefined`] for a stated λ below [`MIN_LAMBDA`];
/// [`ShadowError::FlatFocusBody`] for a body flat along an axis of the map;
/// [`ShadowError::LightInsideFocusBody`] for a point behind a spot light.
pub(crate) fn plan_in(
    technique: Technique,
    frame: &LightFrame,
    world_points: Vec<DVec3>,
    reference: ReferenceRule,
    model: &FrustumModel,
    gamma: LightAngle,
    half_fov: f64,
) -> Result<LightSetup, ShadowError> {
    let points = frame
        .light_points(&world_points)
        .ok_or(ShadowError::LightInsideFocusBody)?;
    let extents = Extents::of(&points);
    let depth = extents.max.z - extents.min.z;
    if depth <= 0.0 {
        return Err(ShadowError::FlatFocusBody { axis: "warp axis" });
    }
    let common = [("gamma_degrees", gamma.degrees()), ("d", depth)];
    let eye = -extents.max.z / depth;
    let (lambda, formula, inputs) = match reference {
        ReferenceRule::Rule => (
            reference_lambda(extents.max.z, depth, model, gamma),
            "λ = max(−z_max/d, λ_mm(γ) − λ_mm(φ) below φ, 0.1·z_n/(z_f − z_n)): the reference \
             point at the eye where it lies beyond B's near plane, else held outside B where the \
             model's minimax perspective warp (formulas.md §5.8) would put its centre, growing \
             to the uniform map as γ → 0 — shadowlab's own rule",
            vec![
                ("z_max", extents.max.z),
                ("z_n", model.range().near()),
                ("z_f", model.range().far()),
                ("phi_degrees", half_fov.to_degrees()),
                common[0],
                common[1],
            ],
        ),
        ReferenceRule::Eye => (
            eye.max(MIN_LAMBDA),
            "λ = −z_max/d: the reference point at the eye (Lloyd et al.'s face partitioning, a \
             side face)",
            vec![("z_max", extents.max.z), common[0], common[1]],
        ),
        ReferenceRule::Uniform => (
            f64::INFINITY,
            "λ = ∞: a uniform map (Lloyd et al.'s face partitioning, an end face)",
            common.to_vec(),
        ),
        ReferenceRule::Lambda(lambda) => (lambda, "λ as stated", common.to_vec()),
        ReferenceRule::NearDistance(n) => (n / depth, "n as stated", common.to_vec()),
    };
    if lambda < MIN_LAMBDA {
        return Err(ShadowError::NotDefined {
            technique: technique.key(),
            reason: format!(
                "λ = {lambda:e} puts the logarithm's reference point on B; it must be at least \
                 {MIN_LAMBDA:e}"
            ),
        });
    }
    let kappa = 1.0 / lambda;
    let (left, right) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, r), p| {
            let w = 1.0 + kappa * (extents.max.z - p.z) / depth;
            (l.min(p.x / w), r.max(p.x / w))
        });
    if right <= left || extents.max.y <= extents.min.y {
        return Err(ShadowError::FlatFocusBody {
            axis: "lateral axis",
        });
    }
    let world_to_light = frame.world_to_light();
    let map = LogarithmicMap {
        world_to_light,
        light_to_world: world_to_light.inverse(),
        z_max: extents.max.z,
        depth,
        kappa,
        log_range: kappa.ln_1p(),
        left,
        right,
        y_min: extents.min.y,
        y_max: extents.max.y,
    };
    Ok(LightSetup {
        technique,
        mapping: ShadowMapping::Logarithmic(map),
        gamma: gamma.radians(),
        half_fov,
        warp: Some(WarpReport {
            lambda,
            near_distance: lambda * depth,
            depth,
            formula: formula.into(),
            inputs,
        }),
        psm: None,
        focus_body: world_points,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use glam::{DMat4, DVec2};
    use shadowlab_test_random::SplitMix;

    /// Relative agreement asked of the closed-form derivative against Richardson-extrapolated
    /// central differences (whose own error is of order 1e-10 at these steps).
    const AGREEMENT: f64 = 1e-6;

    /// The closed-form derivative matches differences of `ndc`, for λ from 1e-6 to 1e6, a spot
    /// light's projective light space and every direction.
    #[test]
    fn the_derivative_matches_differences_of_the_map() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            #[expect(clippy::cast_precision_loss, reason = "a random fraction")]
            let v = (state >> 11) as f64 / (1u64 << 53) as f64;
            v
        };
        let spot = glam::dcamera::rh::proj::opengl::perspective(1.0, 1.0, 0.5, 50.0)
            * glam::dcamera::rh::view::look_at_mat4(
                DVec3::new(1.0, 8.0, 2.0),
                DVec3::ZERO,
                DVec3::Z,
            );
        let mut compared = 0;
        for (k, lambda) in [1e-6, 1e-3, 0.3, 1.0, 7.0, 1e3, 1e6]
            .into_iter()
            .enumerate()
        {
            let world_to_light = if k % 2 == 0 { spot } else { DMat4::IDENTITY };
            let map = LogarithmicMap {
                world_to_light,
                light_to_world: world_to_light.inverse(),
                z_max: -2.0,
                depth: 2.0 / lambda,
                kappa: 1.0 / lambda,
                log_range: (1.0 / lambda).ln_1p(),
                left: -1.5,
                right: 2.5,
                y_min: -3.0,
                y_max: 3.0,
            };
            for _ in 0..600 {
                let p = DVec3::new(4.0 * next() - 2.0, 4.0 * next() - 2.0, -2.0 - 6.0 * next());
                let t = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                let Some(analytic) = map.ndc_derivative(p, t) else {
                    continue;
                };
                let h = 1e-4 * p.length();
                let at = |s: f64| map.ndc(p + t * s).map(|n| DVec2::new(n.x, n.y));
                let central = |h: f64| Some((at(h)? - at(-h)?) / (2.0 * h));
                let (Some(full), Some(half)) = (central(h), central(0.5 * h)) else {
                    continue;
                };
                let numeric = (half * 4.0 - full) / 3.0;
                let scale = numeric.abs().max_element().max(1e-300);
                assert!(
                    (analytic - numeric).abs().max_element() <= AGREEMENT * scale,
                    "λ {lambda} at {p} along {t}: {analytic} vs {numeric}"
                );
                compared += 1;
            }
        }
        assert!(compared > 1000, "{compared}");
    }

    /// Round `round`'s map for the lane tests: a spot light's projective light space, the identity
    /// or a random affine one (`w` exactly 1) in turn; κ = 0 among the λ; random depth and extents.
    pub(crate) fn random_map(random: &mut SplitMix, round: usize) -> LogarithmicMap {
        let spot = glam::dcamera::rh::proj::opengl::perspective(1.0, 1.0, 0.5, 50.0)
            * glam::dcamera::rh::view::look_at_mat4(
                DVec3::new(1.0, 8.0, 2.0),
                DVec3::ZERO,
                DVec3::Z,
            );
        let lambda = [f64::INFINITY, 1e-3, 0.3, 1.0, 7.0, 1e3][round % 6];
        let kappa = 1.0 / lambda;
        let world_to_light = match round % 4 {
            0 | 2 => spot,
            1 => DMat4::IDENTITY,
            _ => {
                let column = |random: &mut SplitMix, w: f64| random.vector(2.0).extend(w);
                DMat4::from_cols(
                    column(random, 0.0),
                    column(random, 0.0),
                    column(random, 0.0),
                    column(random, 1.0),
                )
            }
        };
        LogarithmicMap {
            world_to_light,
            light_to_world: world_to_light.inverse(),
            z_max: -2.0,
            depth: 2.0 * random.range(0.1, 10.0),
            kappa,
            log_range: kappa.ln_1p(),
            left: random.range(-2.0, -1.0),
            right: random.range(1.0, 3.0),
            y_min: -3.0,
            y_max: 3.0,
        }
    }

    /// Four points side by side ([`LogarithmicMap::ndc_lanes`], [`LogarithmicMap::ndc_depth_lanes`],
    /// [`LogarithmicMap::at_lanes`]) give each point's NDC, depth and derivative to the bit, and
    /// are undefined exactly where they are `None`: spot and directional light spaces, κ = 0
    /// among the λ, points behind the spot light and on the eye's side of the reference point
    /// among defined ones.
    #[test]
    fn four_points_side_by_side_are_each_point_alone() {
        use crate::lanes::{LANES, Vectors, check};

        let mut random = SplitMix(0x5eed_0000_0000_1095);
        let (mut defined, mut undefined, mut mapped) = (0, 0, 0);
        for round in 0..3000_usize {
            let map = random_map(&mut random, round);
            let points: [DVec3; LANES] = std::array::from_fn(|_| random.vector(20.0));
            let directions: [[DVec3; LANES]; 3] =
                std::array::from_fn(|_| std::array::from_fn(|_| random.vector(1.0)));
            mapped += check::ndc(
                &points,
                map.ndc_lanes(Vectors::of(&points)),
                |p| map.ndc(p),
                round,
            );
            // The depth alone, in every coordinate.
            let (depth, depth_undefined) = map.ndc_depth_lanes(Vectors::of(&points));
            let depths = Vectors {
                x: depth,
                y: depth,
                z: depth,
            };
            check::ndc(
                &points,
                (depths, depth_undefined),
                |p| map.ndc_depth(p).map(DVec3::splat),
                round,
            );
            let at = map.at_lanes(Vectors::of(&points));
            for direction in &directions {
                let found = check::derivatives(
                    (&points, direction),
                    (at.ndc_derivative(Vectors::of(direction)), at.undefined()),
                    |p, d| map.ndc_derivative(p, d),
                    round,
                );
                defined += found;
                undefined += LANES - found;
            }
        }
        assert!(
            defined > 10_000 && undefined > 2_000,
            "{defined} {undefined}"
        );
        assert!(mapped > 3_000, "{mapped}");
    }

    /// A row's texel rays four at a time ([`TexelRow::rays`]) are each texel's [`TexelRow::ray`]
    /// to the bit — origin its first point, direction `to − from` — under spot, identity and
    /// random affine light spaces, in rows of 1 to 11 texels (whole blocks of four and the rest).
    #[test]
    fn a_rows_rays_four_at_a_time_are_each_texels_ray() {
        use shadowlab_trace::Ray;

        let mut random = SplitMix(0x5eed_0000_0000_7e15);
        let unset = Ray {
            origin: DVec3::NAN,
            direction: DVec3::NAN,
        };
        for round in 0..2000_usize {
            let map = random_map(&mut random, round);
            let row = map.texel_row(random.range(-1.0, 1.0));
            let xs: Vec<f64> = (0..1 + round % 11)
                .map(|_| random.range(-1.0, 1.0))
                .collect();
            let mut rays = vec![unset; xs.len()];
            row.rays(&xs, &mut rays);
            for (k, (ray, &x)) in rays.iter().zip(&xs).enumerate() {
                let (from, to) = row.ray(x);
                let bits = |v: DVec3| v.to_array().map(f64::to_bits);
                assert_eq!(bits(ray.origin), bits(from), "round {round}, texel {k}");
                assert_eq!(
                    bits(ray.direction),
                    bits(to - from),
                    "round {round}, texel {k}"
                );
            }
        }
    }
}
