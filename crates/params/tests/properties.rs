//! Property tests of the params crate, one claim each, over the whole domain: depth ratios
//! `f/n` log-uniform in `[1 + 1e-6, 1e9]`, half fields of view from 5° to 75°, light angles across
//! both branches of the model. Each property names its claim and its tolerance; every run uses the
//! fixed seed [`SEED`] so results are reproducible (proptest's `RngSeed::Fixed`).

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use shadowlab_params::cad::{self, Falloff};
use shadowlab_params::splits::SplitScheme;
use shadowlab_params::{
    DepthRange, FrustumModel, HalfFov, LightAngle, ModelCase, ParameterRule, WarpParameter, gmnpr,
    lispsm, logarithmic,
};

/// The seed of every property in this file (an arbitrary constant, fixed so that runs repeat).
const SEED: u64 = 0x5348_4144_4f57_4c41; // "SHADOWLA"

/// Equal error at near and far, as the issue asks.
const EQUAL_ERROR_TOLERANCE: f64 = 1e-12;
/// Identities between two closed forms of the same quantity.
const IDENTITY_TOLERANCE: f64 = 1e-12;
/// How much lower a perturbed parameter's maximum error may be before the minimax claim fails:
/// rounding in the error evaluations, a few ulps.
const MINIMAX_SLACK: f64 = 1e-12;
/// Central differences with a relative step of [`FD_STEP`] against a closed-form derivative.
const FD_TOLERANCE: f64 = 1e-6;
/// Relative step of the central differences.
const FD_STEP: f64 = 1e-5;
/// The relative variation of F over a grid below which its minimum's location is lost in rounding.
const RESOLVABLE_VARIATION: f64 = 1e-9;

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        failure_persistence: None,
        ..Config::default()
    }
}

fn relative_error(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(f64::MIN_POSITIVE)
}

/// `n` log-uniform in [1e-3, 1e3] and `f/n − 1` log-uniform in [1e-6, 1e9].
fn depth_range() -> impl Strategy<Value = DepthRange> {
    (-3.0f64..3.0, -6.0f64..9.0).prop_map(|(log_near, log_excess)| {
        let near = 10f64.powf(log_near);
        DepthRange::new(near, near * (1.0 + 10f64.powf(log_excess))).unwrap()
    })
}

fn frustum_model() -> impl Strategy<Value = FrustumModel> {
    (depth_range(), 5.0f64..75.0).prop_map(|(range, half_fov_degrees)| {
        FrustumModel::new(
            range,
            HalfFov::from_radians(half_fov_degrees.to_radians()).unwrap(),
        )
    })
}

/// An angle a fraction `t ∈ [0, 1]` of the way from `low` to `high` radians.
fn angle_between(low: f64, high: f64, t: f64) -> LightAngle {
    LightAngle::from_radians((low + (high - low) * t).clamp(low, high)).unwrap()
}

/// A model and an angle in its wide branch, `[φ, π/2]`.
fn wide_case() -> impl Strategy<Value = (FrustumModel, LightAngle)> {
    (frustum_model(), 0.0f64..=1.0).prop_map(|(m, t)| {
        let gamma = angle_between(m.half_fov().radians(), std::f64::consts::FRAC_PI_2, t);
        (m, gamma)
    })
}

/// A model and an angle in its narrow branch where equal error is possible, `(θ_0, φ)`.
fn narrow_equal_error_case() -> impl Strategy<Value = (FrustumModel, LightAngle)> {
    (frustum_model(), 0.001f64..0.999).prop_map(|(m, t)| {
        let low = gmnpr::theta0(&m).radians();
        (m, angle_between(low, m.half_fov().radians(), t))
    })
}

/// A model and any angle in `(0, π/2]`, spread log-uniformly near 0 as well.
fn any_case() -> impl Strategy<Value = (FrustumModel, LightAngle)> {
    (frustum_model(), prop_oneof![0.0f64..=1.0, -12.0f64..0.0]).prop_map(|(m, u)| {
        let half_pi = std::f64::consts::FRAC_PI_2;
        let gamma = if u >= 0.0 {
            angle_between(1e-9, half_pi, u)
        } else {
            angle_between(0.0, half_pi, 10f64.powf(u))
        };
        (m, gamma)
    })
}

/// The maximum of F over a dense grid of `GRID` depths, log-spaced over `[n, f]` with both ends
/// included: the brute-force reference for the minimax claims.
fn brute_force_max_error(m: &FrustumModel, gamma: LightAngle, warp: WarpParameter) -> f64 {
    const GRID: usize = 257;
    (0..GRID)
        .map(|i| {
            let z = m.range().geometric_lerp(i as f64 / (GRID - 1) as f64);
            gmnpr::error(m, gamma, warp, z).unwrap()
        })
        .fold(0.0, f64::max)
}

/// Factors by which the minimax parameter is perturbed, from tiny to large, both ways.
const PERTURBATIONS: [f64; 14] = [
    1e-4, 1e-2, 0.1, 0.5, 0.9, 0.99, 0.999_999, 1.000_001, 1.01, 1.1, 2.0, 10.0, 1e2, 1e4,
];

fn scaled(warp: WarpParameter, factor: f64) -> WarpParameter {
    WarpParameter::from_lambda(warp.lambda() * factor).unwrap()
}

proptest! {
    #![proptest_config(config(512))]

    /// Claim: at n_opt = zn + √(zn zf) LiSPSM's eq. 3 has the same error at zn and zf.
    #[test]
    fn lispsm_n_opt_equalises_near_and_far(range in depth_range()) {
        let n = lispsm::n_opt(range);
        let near = lispsm::dp_ds(range, n, range.near()).unwrap();
        let far = lispsm::dp_ds(range, n, range.far()).unwrap();
        prop_assert!(relative_error(near, far) <= EQUAL_ERROR_TOLERANCE, "{near} {far}");
        let closed = lispsm::max_error_at_n_opt(range);
        prop_assert!(relative_error(near, closed) <= EQUAL_ERROR_TOLERANCE, "{near} {closed}");
        // Its one interior minimum is at √(zn zf) (formulas.md §2.5).
        let minimum = lispsm::error_minimum_depth(range, n).unwrap().unwrap();
        let mean = range.geometric_mean();
        prop_assert!(relative_error(minimum, mean) <= IDENTITY_TOLERANCE, "{minimum} {mean}");
    }

    /// Claim: λ1 (wide) equalises F(n) and F(f); so does n'_1 for the CAD survey's m_z.
    #[test]
    fn wide_branch_parameters_equalise_near_and_far((m, gamma) in wide_case()) {
        let warp = WarpParameter::from_lambda(gmnpr::lambda1(&m, gamma)).unwrap();
        let (n, f) = (m.range().near(), m.range().far());
        let near = gmnpr::error(&m, gamma, warp, n).unwrap();
        let far = gmnpr::error(&m, gamma, warp, f).unwrap();
        prop_assert!(relative_error(near, far) <= EQUAL_ERROR_TOLERANCE, "F: {near} {far}");
        let n1 = cad::n1(&m, gamma);
        let near = cad::m_z(&m, gamma, n1, n, 1.0).unwrap();
        let far = cad::m_z(&m, gamma, n1, f, 1.0).unwrap();
        prop_assert!(relative_error(near, far) <= EQUAL_ERROR_TOLERANCE, "m_z: {near} {far}");
    }

    /// Claim: λ2 (narrow, above θ_0) equalises F(n) and F(f); so does n'_2 for m_z.
    #[test]
    fn narrow_branch_parameters_equalise_near_and_far((m, gamma) in narrow_equal_error_case()) {
        let lambda = gmnpr::lambda_equal_error(&m, gamma);
        prop_assume!(lambda >= f64::MIN_POSITIVE);
        let warp = WarpParameter::from_lambda(lambda).unwrap();
        let (n, f) = (m.range().near(), m.range().far());
        let near = gmnpr::error(&m, gamma, warp, n).unwrap();
        let far = gmnpr::error(&m, gamma, warp, f).unwrap();
        prop_assert!(relative_error(near, far) <= EQUAL_ERROR_TOLERANCE, "F: {near} {far}");
        let n2 = cad::n2(&m, gamma);
        let near = cad::m_z(&m, gamma, n2, n, 1.0).unwrap();
        let far = cad::m_z(&m, gamma, n2, f, 1.0).unwrap();
        prop_assert!(relative_error(near, far) <= EQUAL_ERROR_TOLERANCE, "m_z: {near} {far}");
    }

    /// Claim: the minimax λ of formulas.md §5.8 is the L∞ optimum on a dense z grid: no
    /// perturbation, from 1e-6 to 1e4 relative, and no λ on a log grid spanning eight decades
    /// around it, has a lower maximum error. Covers both branches and the angles below θ1.
    #[test]
    fn minimax_cannot_be_improved((m, gamma) in any_case()) {
        let best = gmnpr::lambda_minimax(&m, gamma);
        let best_error = brute_force_max_error(&m, gamma, best);
        prop_assert!(best_error.is_finite());
        let floor = best_error * (1.0 - MINIMAX_SLACK);
        for factor in PERTURBATIONS {
            let other = brute_force_max_error(&m, gamma, scaled(best, factor));
            prop_assert!(other >= floor, "factor {factor}: {other} < {best_error}");
        }
        for i in 0..=64 {
            let factor = 10f64.powf(-4.0 + 8.0 * f64::from(i) / 64.0);
            let other = brute_force_max_error(&m, gamma, scaled(best, factor));
            prop_assert!(other >= floor, "scan {factor}: {other} < {best_error}");
        }
        let uniform = brute_force_max_error(&m, gamma, WarpParameter::UNIFORM);
        prop_assert!(uniform >= floor);
    }

    /// Claim: below θ1 neither GMNPR's λ2* nor the equal-error λ2 is the minimax: the minimax λ
    /// has a strictly lower maximum error (formulas.md §5.8, OCR note 13).
    #[test]
    fn below_theta1_gmnpr_is_not_minimax(m in frustum_model(), t in 0.01f64..0.99) {
        let theta1 = gmnpr::theta1(&m).radians().min(m.half_fov().radians());
        let gamma = angle_between(0.0, theta1, t);
        prop_assume!(!gamma.is_parallel());
        let best = brute_force_max_error(&m, gamma, gmnpr::lambda_minimax(&m, gamma));
        let star = gmnpr::lambda2_star(&m, gamma).unwrap();
        let gmnpr_error = brute_force_max_error(&m, gamma, star);
        prop_assert!(gmnpr_error > best * (1.0 + 1e-9), "λ2*: {gmnpr_error} vs {best}");
        let lambda2 = gmnpr::lambda2(&m, gamma);
        if lambda2 >= f64::MIN_POSITIVE {
            let equal = WarpParameter::from_lambda(lambda2).unwrap();
            let equal_error = brute_force_max_error(&m, gamma, equal);
            prop_assert!(equal_error > best * (1.0 + 1e-9), "λ2: {equal_error} vs {best}");
        }
    }

    /// Claim: the equal-error parameters put F's one interior minimum at z* = √(nf), the printed
    /// ϕ(λ, θ) of eq. 2 (F's minimiser, formulas.md §5.7) says so too, and F is convex in z. The
    /// brute-force location of the minimum is checked where F varies by more than
    /// [`RESOLVABLE_VARIATION`] over the range (for f/n → 1 it is flat to rounding).
    #[test]
    fn equal_error_minimum_sits_at_the_geometric_mean((m, gamma) in prop_oneof![wide_case(), narrow_equal_error_case()]) {
        let lambda = gmnpr::lambda_equal_error(&m, gamma);
        prop_assume!(lambda >= f64::MIN_POSITIVE);
        let warp = WarpParameter::from_lambda(lambda).unwrap();
        let mean = m.range().geometric_mean();
        let phi = gmnpr::phi(&m, gamma, lambda).unwrap();
        prop_assert!(relative_error(phi, mean) <= 1e-9, "ϕ = {phi}, √(nf) = {mean}");
        // Brute force: the grid minimum is next to √(nf), and second differences are ≥ 0.
        const GRID: usize = 401;
        let z: Vec<f64> = (0..GRID).map(|i| m.range().geometric_lerp(i as f64 / (GRID - 1) as f64)).collect();
        let e: Vec<f64> = z.iter().map(|&z| gmnpr::error(&m, gamma, warp, z).unwrap()).collect();
        let argmin = (0..GRID).min_by(|&a, &b| e[a].total_cmp(&e[b])).unwrap();
        let (low, high) = (z[argmin.saturating_sub(1)], z[(argmin + 1).min(GRID - 1)]);
        if e[0] > e[argmin] * (1.0 + RESOLVABLE_VARIATION) {
            prop_assert!(low <= mean && mean <= high, "{low} {mean} {high}");
        }
        for i in 1..GRID - 1 {
            // Convexity in z on a log grid: F(z_i) ≤ the chord between its neighbours.
            let w = (z[i] - z[i - 1]) / (z[i + 1] - z[i - 1]);
            let chord = (1.0 - w) * e[i - 1] + w * e[i + 1];
            prop_assert!(e[i] <= chord * (1.0 + 1e-12), "not convex at {}", z[i]);
        }
    }

    /// Claim: the stable F equals eq. 2 as printed, ψ(λ,θ)(z + ϕ(λ,θ))²/z, on both branches.
    #[test]
    fn stable_error_matches_the_printed_equation_2((m, gamma) in any_case(), log_lambda in -3.0f64..3.0, t in 0.0f64..=1.0) {
        let lambda = 10f64.powf(log_lambda);
        let warp = WarpParameter::from_lambda(lambda).unwrap();
        let z = m.range().geometric_lerp(t);
        let psi = gmnpr::psi(&m, gamma, lambda).unwrap();
        let phi = gmnpr::phi(&m, gamma, lambda).unwrap();
        let printed = psi * (z + phi) * (z + phi) / z;
        let stable = gmnpr::error(&m, gamma, warp, z).unwrap();
        // The printed form cancels in z + ϕ; allow for that: its error is eps·(|z| + |ϕ| terms).
        let terms = z.abs() + phi.abs() + m.range().far() * (1.0 + lambda) * 4.0;
        let tolerance = 64.0 * f64::EPSILON * terms / (z + phi).abs() + 1e-12;
        prop_assert!(relative_error(stable, printed) <= tolerance, "{stable} {printed}");
    }

    /// Claim: λ = n'/(f' − n') links the CAD and GMNPR forms: CAD eq. 13 as printed, divided by
    /// eq. 11's f' − n', equals GMNPR eq. 4 as printed (with `T = tan φ/tan θ`), and both equal
    /// the crate's stable evaluation, to the rounding of the terms that cancel in the printed forms.
    #[test]
    fn cad_and_gmnpr_parameters_are_the_same((m, gamma) in any_case()) {
        let r = m.range();
        let (n, f, root) = (r.near(), r.far(), r.geometric_mean());
        let (a, b) = (m.near_half_height(), m.far_half_height());
        let (sin, cos) = (gamma.sin(), gamma.cos());
        let t = m.half_fov().tan() * cos / sin;
        let (cad_printed, gmnpr_printed, terms) = match m.case(gamma) {
            ModelCase::Wide => (
                (n + root) * sin - a * cos,
                (n + root - n * t) / (f - n + (f + n) * t),
                ((n + root) * sin + a * cos, (n + root + n * t) / (f - n + (f + n) * t)),
            ),
            ModelCase::Narrow => (
                (f + root) * sin - b * cos,
                (f + root) / (2.0 * f) / t - 0.5,
                ((f + root) * sin + b * cos, (f + root) / (2.0 * f) / t + 0.5),
            ),
        };
        let depth = cad::f_prime(&m, gamma, 1.0).unwrap() - 1.0;
        let stable = gmnpr::lambda_equal_error(&m, gamma);
        let tolerance = |scale: f64| IDENTITY_TOLERANCE * scale.abs() / stable.abs().max(f64::MIN_POSITIVE) + IDENTITY_TOLERANCE;
        prop_assert!(relative_error(cad_printed / depth, stable) <= tolerance(terms.0 / depth), "CAD {} {stable}", cad_printed / depth);
        prop_assert!(relative_error(gmnpr_printed, stable) <= tolerance(terms.1), "GMNPR {gmnpr_printed} {stable}");
    }

    /// Claim: the authors' 2006 form d/(√(z1/z0) − 1) equals the Δz variant when z1 = z0 + d sin γ.
    #[test]
    fn the_2006_form_equals_the_delta_z_variant(log_z0 in -3.0f64..3.0, log_d in -3.0f64..6.0, t in 0.0f64..=1.0) {
        let (z0, depth) = (10f64.powf(log_z0), 10f64.powf(log_d));
        let gamma = angle_between(1e-6, std::f64::consts::FRAC_PI_2, t);
        let z1 = z0 + depth * gamma.sin();
        let general = lispsm::n_general(depth, z0, z1).unwrap();
        let delta_z = lispsm::n_delta_z(z0, depth, gamma).unwrap();
        // z1 is rounded; its error relative to z1 − z0 bounds the disagreement.
        let tolerance = IDENTITY_TOLERANCE + 4.0 * f64::EPSILON * z1 / (z1 - z0);
        prop_assert!(relative_error(general, delta_z) <= tolerance, "{general} {delta_z}");
    }

    /// Claim: eq. 3 tends to the uniform map as n → ∞ (exactly at n = ∞) and is PSM at n = zn.
    #[test]
    fn lispsm_limits_are_uniform_and_psm(range in depth_range(), t in 0.0f64..=1.0) {
        let z = range.lerp(t);
        let uniform = lispsm::uniform_dp_ds(range, z).unwrap();
        prop_assert_eq!(lispsm::dp_ds(range, f64::INFINITY, z).unwrap(), uniform);
        let far_n = lispsm::dp_ds(range, 1e9 * range.far(), z).unwrap();
        prop_assert!(relative_error(far_n, uniform) <= 1e-8, "{far_n} {uniform}");
        let psm = lispsm::psm_dp_ds(range, z).unwrap();
        let at_zn = lispsm::dp_ds(range, range.near(), z).unwrap();
        prop_assert!(relative_error(at_zn, psm) <= IDENTITY_TOLERANCE, "{at_zn} {psm}");
        prop_assert!(relative_error(lispsm::dp_dt(range, range.near(), z).unwrap(), 1.0) <= IDENTITY_TOLERANCE);
    }

    /// Claim: the closed-form ds/dz agrees with central differences of s(z), for LiSPSM at any n
    /// and for the logarithmic map, and both map [zn, zf] onto [0, 1] exactly.
    #[test]
    fn closed_form_slopes_match_finite_differences(range in depth_range(), log_n in -1.0f64..4.0, t in 0.05f64..0.95) {
        let n = range.near() * 10f64.powf(log_n);
        let z = range.lerp(t);
        let h = FD_STEP * range.length();
        let (lo, hi) = (z - h, z + h);
        prop_assume!(range.contains(lo) && range.contains(hi) && lo < hi);
        // Truncation error O(h²) plus the rounding of s (≤ 1) amplified by 1/(2h s').
        let tolerance = |slope: f64| FD_TOLERANCE + 4.0 * f64::EPSILON / ((hi - lo) * slope);
        let fd = (lispsm::s(range, n, hi).unwrap() - lispsm::s(range, n, lo).unwrap()) / (hi - lo);
        let exact = lispsm::ds_dz(range, n, z).unwrap();
        prop_assert!(relative_error(fd, exact) <= tolerance(exact), "LiSPSM {fd} {exact}");
        let fd = (logarithmic::s(range, hi).unwrap() - logarithmic::s(range, lo).unwrap()) / (hi - lo);
        let exact = logarithmic::ds_dz(range, z).unwrap();
        prop_assert!(relative_error(fd, exact) <= tolerance(exact), "log {fd} {exact}");
        prop_assert_eq!(lispsm::s(range, n, range.near()).unwrap(), 0.0);
        prop_assert_eq!(lispsm::s(range, n, range.far()).unwrap(), 1.0);
        prop_assert_eq!(logarithmic::s(range, range.near()).unwrap(), 0.0);
        prop_assert_eq!(logarithmic::s(range, range.far()).unwrap(), 1.0);
        let back = logarithmic::depth(range, logarithmic::s(range, z).unwrap()).unwrap();
        prop_assert!(relative_error(back, z) <= 1e-12 * range.log_ratio().max(1.0), "{back} {z}");
    }

    /// Claim: every split scheme is strictly increasing with exact endpoints; eq. 5 has equal
    /// ratios; eq. 19 at γ = π/2 is eq. 5.
    #[test]
    fn split_schemes_are_well_formed(range in depth_range(), k in 1usize..9, weight in 0.0f64..=1.0, delta in 1.01f64..8.0, t in 0.0f64..=1.0) {
        let gamma = angle_between(0.0, std::f64::consts::FRAC_PI_2, t);
        let schemes = [
            SplitScheme::Uniform,
            SplitScheme::Logarithmic,
            SplitScheme::Practical { weight },
            SplitScheme::Adaptive { delta, gamma },
        ];
        for scheme in schemes {
            let b = scheme.boundaries(range, k).unwrap();
            prop_assert_eq!(b.len(), k + 1);
            prop_assert_eq!((b[0], b[k]), (range.near(), range.far()));
            prop_assert!(b.windows(2).all(|w| w[0] < w[1]), "{:?}: {:?}", scheme, b);
        }
        let log = SplitScheme::Logarithmic.boundaries(range, k).unwrap();
        let ratio = log[1] / log[0];
        for w in log.windows(2) {
            prop_assert!(relative_error(w[1] / w[0], ratio) <= IDENTITY_TOLERANCE * range.log_ratio().max(1.0));
        }
        let perpendicular = SplitScheme::Adaptive { delta, gamma: LightAngle::PERPENDICULAR };
        prop_assert_eq!(perpendicular.boundaries(range, k).unwrap(), log);
    }
}

/// The singular places of the domain, visited exactly: f/n from 1 + 1e-9 to 1e12, γ at 0, 1e-12,
/// around φ, θ_0, θ1 and γ_lim, and at π/2.
fn extreme_configurations() -> Vec<(FrustumModel, LightAngle)> {
    let mut out = Vec::new();
    for ratio in [
        1.0 + 1e-9,
        1.0 + 1e-6,
        1.5,
        2.618,
        100.0,
        800.0,
        1e6,
        1e9,
        1e12,
    ] {
        for half_fov in [1e-3, 5.0, 30.0, 60.0, 89.0] {
            let range = DepthRange::new(1.0, ratio).unwrap();
            let m = FrustumModel::new(
                range,
                HalfFov::from_radians(f64::to_radians(half_fov)).unwrap(),
            );
            let phi = m.half_fov().radians();
            let mut angles = vec![
                0.0,
                1e-12,
                1e-9,
                std::f64::consts::FRAC_PI_2 - 1e-12,
                std::f64::consts::FRAC_PI_2,
            ];
            for special in [
                phi,
                gmnpr::theta0(&m).radians(),
                gmnpr::theta1(&m).radians(),
                cad::gamma_lim(&m).radians(),
            ] {
                for offset in [-1e-9, -1e-12, 0.0, 1e-12, 1e-9] {
                    angles.push(special + offset);
                }
            }
            for a in angles {
                if let Ok(gamma) = LightAngle::from_radians(a) {
                    out.push((m, gamma));
                }
            }
        }
    }
    out
}

/// Claim: no NaN anywhere in the domain, the extremes included; infinities only where documented
/// (parameters and errors at γ = 0 exactly, raw λ2 at γ = π/2).
#[test]
fn no_nan_or_infinity_in_the_domain() {
    let mut checked = 0;
    for (m, gamma) in extreme_configurations() {
        let at = format!(
            "f/n = {}, φ = {}, γ = {:e}",
            m.range().ratio(),
            m.half_fov().radians(),
            gamma.radians()
        );
        let parallel = gamma.is_parallel();
        for rule in ParameterRule::ALL {
            let Some(warp) = rule.warp(&m, gamma) else {
                assert!(
                    rule == ParameterRule::Glpr && gamma.radians() <= m.half_fov().radians(),
                    "{} undefined at {at}",
                    rule.key()
                );
                continue;
            };
            assert!(!warp.lambda().is_nan(), "{} at {at}", rule.key());
            assert!(
                warp.lambda().is_finite() || parallel || rule == ParameterRule::Uniform,
                "{} infinite at {at}",
                rule.key()
            );
            let max = gmnpr::max_error(&m, gamma, warp);
            assert!(
                max.is_finite() != parallel,
                "{} max error {max} at {at}",
                rule.key()
            );
            for t in [0.0, 0.5, 1.0] {
                let e = gmnpr::error(&m, gamma, warp, m.range().lerp(t)).unwrap();
                assert!(
                    e.is_finite() != parallel && e > 0.0,
                    "{} error {e} at {at}",
                    rule.key()
                );
            }
            checked += 1;
        }
        let raw = [
            gmnpr::lambda1(&m, gamma),
            gmnpr::lambda_equal_error(&m, gamma),
            gmnpr::mu(&m, gamma),
            gmnpr::nu(&m, gamma),
            cad::n1(&m, gamma),
            cad::n2(&m, gamma),
            m.warp_depth(gamma),
        ];
        assert!(raw.iter().all(|x| x.is_finite()), "{raw:?} at {at}");
        assert!(!gmnpr::lambda2(&m, gamma).is_nan(), "λ2 at {at}");
        assert!(
            !gmnpr::lambda_near_minimizer(&m, gamma).is_nan(),
            "μ/(1−2μ) at {at}"
        );
        for falloff in Falloff::ALL {
            let n = cad::n_prime(&m, gamma, falloff);
            assert!(n > 0.0 && (n.is_finite() != parallel), "n' {n} at {at}");
        }
        let n = lispsm::n_opt_general(m.range(), gamma);
        assert!(n.is_finite() != parallel, "n_opt/sin γ at {at}");
    }
    assert!(checked > 1000, "only {checked} configurations");
}

/// Claim: every parameter tends to the uniform map as γ → 0 — λ grows without bound, like 1/γ —
/// and is the uniform map at γ = 0 exactly (GLPR excepted: undefined below φ).
#[test]
fn parameters_tend_to_uniform_as_the_light_becomes_parallel() {
    let m = FrustumModel::new(
        DepthRange::new(1.0, 100.0).unwrap(),
        HalfFov::from_full_fov_degrees(60.0).unwrap(),
    );
    let parallel = LightAngle::from_radians(0.0).unwrap();
    for rule in ParameterRule::ALL {
        if rule == ParameterRule::Glpr {
            assert!(rule.warp(&m, parallel).is_none());
            continue;
        }
        assert!(
            rule.warp(&m, parallel).unwrap().is_uniform(),
            "{}",
            rule.key()
        );
        if rule == ParameterRule::Uniform {
            continue;
        }
        let mut last = 0.0;
        for k in 1..=12 {
            let gamma = LightAngle::from_radians(10f64.powi(-k)).unwrap();
            let lambda = rule.warp(&m, gamma).unwrap().lambda();
            assert!(lambda > last, "{} not increasing at 1e-{k}", rule.key());
            last = lambda;
        }
        assert!(last > 1e10, "{}: {last}", rule.key());
    }
}

#[test]
fn named_identities() {
    for far in [1.0 + 1e-6, 2.0, 100.0, 800.0, 1e9] {
        for fov in [10.0, 60.0, 120.0] {
            let m = FrustumModel::new(
                DepthRange::new(1.0, far).unwrap(),
                HalfFov::from_full_fov_degrees(fov).unwrap(),
            );
            let perpendicular = LightAngle::PERPENDICULAR;
            // n'_1(π/2) = n_opt, exactly (cos γ = 0 there).
            assert_eq!(cad::n1(&m, perpendicular), lispsm::n_opt(m.range()));
            // λ_LiSPSM(π/2) = λ1(π/2).
            let l = gmnpr::lambda_lispsm(&m, perpendicular).lambda();
            assert!(relative_error(l, gmnpr::lambda1(&m, perpendicular)) <= IDENTITY_TOLERANCE);
            // λ2*(φ) = λ1(φ), and λ1(φ) = λ2(φ) (continuity at φ).
            let phi = LightAngle::from_radians(m.half_fov().radians()).unwrap();
            let star = gmnpr::lambda2_star(&m, phi).unwrap().lambda();
            assert!(
                relative_error(star, gmnpr::lambda1(&m, phi)) <= IDENTITY_TOLERANCE,
                "{star}"
            );
            let two = gmnpr::lambda2(&m, phi);
            assert!(
                relative_error(two, gmnpr::lambda1(&m, phi)) <= 1e-10,
                "{two}"
            );
            // The model's two branches meet at φ.
            assert!(
                relative_error(m.warp_depth(phi), 2.0 * m.far_half_height() * phi.cos())
                    <= IDENTITY_TOLERANCE
            );
            // GLPR: F ∝ z (ϕ = 0) wherever it is defined.
            let gamma = LightAngle::from_radians(
                (m.half_fov().radians() + std::f64::consts::FRAC_PI_2) / 2.0,
            )
            .unwrap();
            let glpr = gmnpr::lambda_glpr(&m, gamma).unwrap();
            let phi_value = gmnpr::phi(&m, gamma, glpr.lambda()).unwrap();
            assert!(phi_value.abs() <= 1e-9 * far, "ϕ(λ_GLPR) = {phi_value}");
            // CAD eq. 16 is continuous at γ_lim.
            let limit = cad::gamma_lim(&m);
            assert!(limit.radians() > m.half_fov().radians());
            for falloff in Falloff::ALL {
                let just_below = LightAngle::from_radians(limit.radians() * (1.0 - 1e-12)).unwrap();
                let a = cad::n_prime(&m, just_below, falloff);
                assert!(
                    relative_error(a, cad::n1(&m, limit)) <= 1e-9,
                    "{falloff:?} {a}"
                );
            }
        }
    }
}

/// Claim: at angles far below any practical one (1e-300 rad) nothing is NaN; a parameter or error
/// whose exact value exceeds f64::MAX rounds to +∞, which means "uniform" for a parameter.
#[test]
fn vanishing_angles_overflow_to_uniform_never_to_nan() {
    for (m, _) in extreme_configurations() {
        let gamma = LightAngle::from_radians(1e-300).unwrap();
        for rule in ParameterRule::ALL {
            if let Some(warp) = rule.warp(&m, gamma) {
                assert!(!warp.lambda().is_nan(), "{}", rule.key());
                assert!(
                    !gmnpr::max_error(&m, gamma, warp).is_nan(),
                    "{}",
                    rule.key()
                );
            }
        }
    }
}
