//! The filterable maps (ESM, EVSM2, EVSM4, MSM, beside VSM) against their closed forms and the exact
//! lit fraction, as issue 16 §1 asks: one step, two steps, a slope; results bounded in `[0, 1]`;
//! VSM's leak on a two-occluder stack, and when EVSM and MSM leak less there; continuity in the
//! knobs. Each test names its claim and its tolerance; property tests use the fixed seed [`SEED`].
//!
//! "Exact" is the filtered binary test (PCF) of the same depths: the weighted share of depths at or
//! behind the receiver, `Σ wᵢ [t ≤ dᵢ] / Σ wᵢ` (a receiver at an occluder's depth is lit, as in every
//! module). VSM, EVSM and MSM with `α = 0` return upper bounds on it; MSM with `α > 0` returns an
//! upper bound on the exact lit fraction of the *biased* distribution (the data mixed with depth 0
//! or 1 with probability ½ each, weight `α`).

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use shadowlab_params::esm::ExponentialMoment;
use shadowlab_params::evsm::{Evsm2Moments, Evsm4Moments, MAX_EXPONENT, Warp, WarpedMoments};
use shadowlab_params::msm::MsmMoments;
use shadowlab_params::vsm::ShiftedMoments;

/// The seed of every property in this file (an arbitrary constant, fixed so that runs repeat).
const SEED: u64 = 0x4649_4c54_4552_4142; // "FILTERAB"

/// Two closed forms of the same quantity in f64, evaluated by different routes.
const CLOSED_FORM_TOLERANCE: f64 = 1e-12;
/// How far below the exact lit fraction an upper bound may come out: rounding in the moments
/// (the warped variance of EVSM at large exponents, MSM's Hankel determinants).
const BOUND_SLACK: f64 = 1e-9;
/// A moment computed by the midpoint rule on [`SLOPE_SAMPLES`] depths against the continuous
/// uniform distribution's closed form: the rule's error, about `(c·h)²/24` relative.
const QUADRATURE_TOLERANCE: f64 = 2e-5;
/// Depths per slope.
const SLOPE_SAMPLES: usize = 4000;

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        failure_persistence: None,
        ..Config::default()
    }
}

#[track_caller]
fn assert_close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    let error = (actual - expected).abs();
    assert!(
        error <= tolerance * expected.abs().max(1.0),
        "{what}: got {actual:.15e}, expected {expected:.15e} (error {error:.2e} > {tolerance:.0e})"
    );
}

/// The exact lit fraction `Σ wᵢ [t ≤ dᵢ] / Σ wᵢ`.
fn exact_lit(depths: &[f64], weights: &[f64], t: f64) -> f64 {
    let total: f64 = weights.iter().sum();
    let lit: f64 = depths
        .iter()
        .zip(weights)
        .filter(|&(&d, _)| t <= d)
        .map(|(_, &w)| w)
        .sum();
    lit / total
}

/// The exact lit fraction of the biased distribution `(1 − α)·data + α·{0, 1 with ½ each}`.
fn exact_biased_lit(depths: &[f64], weights: &[f64], t: f64, alpha: f64) -> f64 {
    let target = if t <= 0.0 {
        1.0
    } else if t <= 1.0 {
        0.5
    } else {
        0.0
    };
    (1.0 - alpha) * exact_lit(depths, weights, t) + alpha * target
}

/// The Cantelli bound `σ²/(σ² + (t − μ)²)` for `t > μ`, else 1.
fn cantelli(mean: f64, variance: f64, t: f64) -> f64 {
    if t <= mean {
        1.0
    } else {
        variance / (variance + (t - mean) * (t - mean))
    }
}

/// The Cantelli bound of the biased distribution MSM reconstructs (mean and variance of the
/// mixture): MSM's bound, using four moments instead of two, is never above it.
fn biased_cantelli(depths: &[f64], weights: &[f64], t: f64, alpha: f64) -> f64 {
    let total: f64 = weights.iter().sum();
    let mean_of = |f: &dyn Fn(f64) -> f64| -> f64 {
        depths
            .iter()
            .zip(weights)
            .map(|(&d, &w)| w * f(d))
            .sum::<f64>()
            / total
    };
    let data_mean = mean_of(&|d| d);
    let mean = (1.0 - alpha) * data_mean + alpha * 0.5;
    let variance = (1.0 - alpha) * mean_of(&|d| (d - mean) * (d - mean))
        + alpha * 0.5 * (mean * mean + (1.0 - mean) * (1.0 - mean));
    cantelli(mean, variance, t)
}

/// Peters & Klein's Hamburger 4MSM transcribed directly in raw coordinates (Cholesky of the Hankel
/// matrix, the quadratic, the three cases), as the independent reference for [`MsmMoments`]'s
/// stable form. Returns the lit fraction `1 − G`.
fn paper_msm(raw: [f64; 4], alpha: f64, zf: f64) -> f64 {
    let [b1, b2, b3, b4] = raw.map(|b| (1.0 - alpha) * b + alpha * 0.5);
    // B = L·D·Lᵀ with L = [[1,0,0],[b1,1,0],[b2,l32,1]], D = diag(1, d22, d33).
    let d22 = b2 - b1 * b1;
    let l32 = (b3 - b1 * b2) / d22;
    let d33 = (b4 - b2 * b2) - l32 * l32 * d22;
    // Forward substitution, scaling, back substitution for B·c = (1, zf, zf²).
    let y1 = zf - b1;
    let y2 = zf * zf - b2 - l32 * y1;
    let c3 = y2 / d33;
    let c2 = y1 / d22 - l32 * c3;
    let c1 = 1.0 - b1 * c2 - b2 * c3;
    let root = (c2 * c2 - 4.0 * c1 * c3).max(0.0).sqrt();
    let (r1, r2) = ((-c2 - root) / (2.0 * c3), (-c2 + root) / (2.0 * c3));
    let (z2, z3) = (r1.min(r2), r1.max(r2));
    let g = if zf <= z2 {
        0.0
    } else if zf <= z3 {
        (zf * z3 - b1 * (zf + z3) + b2) / ((z3 - z2) * (zf - z2))
    } else {
        1.0 - (z2 * z3 - b1 * (z2 + z3) + b2) / ((zf - z2) * (zf - z3))
    };
    1.0 - g
}

/// `n` depths, a share `p` of them at `d0` and the rest at `d1` (equal weights).
fn two_steps(d0: f64, d1: f64, p: f64, n: usize) -> Vec<f64> {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "p·n is a small non-negative count by construction"
    )]
    let front = (p * n as f64).round() as usize;
    let mut depths = vec![d0; front];
    depths.resize(n, d1);
    depths
}

/// Midpoint-rule depths of the uniform distribution on `[a, b]`.
fn slope(a: f64, b: f64) -> Vec<f64> {
    let h = (b - a) / SLOPE_SAMPLES as f64;
    (0..SLOPE_SAMPLES)
        .map(|i| a + h * (i as f64 + 0.5))
        .collect()
}

/// Claim: one step (all depths at `d0`). ESM is `exp(−c·(t − d0))` behind it, exactly; VSM, EVSM2
/// and EVSM4 without a floor are the exact step; with a floor, the Cantelli value of the floor
/// carried by each warp's slope. MSM about `r = d0` with `α = 0` is the exact step; with `α > 0`
/// it is lit at least `1 − α/2` in front and at most the biased Cantelli bound behind (the bias acts
/// like a minimum variance `α·((d0² + (1 − d0)²)/2)`), at least `α/2` (the mass the bias puts at 1).
#[test]
fn one_step() {
    for d0 in [0.1, 0.5, 0.9] {
        let depths = [d0; 6];
        let weights = [1.0; 6];
        let fronts = [0.0, d0 - 0.05, d0];
        let behinds = [d0 + 1e-6, d0 + 1e-3, d0 + 0.05, 1.0, 1.5];
        for c in [2.0, 80.0, 3000.0] {
            let esm = ExponentialMoment::from_depths(c, &depths).unwrap();
            assert_eq!(esm.mean_depth(), d0);
            for t in fronts {
                assert_eq!(esm.lit_fraction(t).unwrap(), 1.0);
            }
            for t in behinds {
                let expected = (-c * (t - d0)).exp();
                assert_close(
                    esm.lit_fraction(t).unwrap(),
                    expected,
                    CLOSED_FORM_TOLERANCE,
                    "ESM",
                );
            }
        }
        let vsm = ShiftedMoments::from_depths(d0, &depths).unwrap();
        for (c_pos, c_neg) in [
            (5.0, 5.0),
            (11.08, 11.08),
            (40.0, 10.0),
            (MAX_EXPONENT, 84.0),
        ] {
            let evsm = Evsm4Moments::from_depths(c_pos, c_neg, d0, &depths).unwrap();
            for t in fronts {
                assert_eq!(evsm.lit_fraction(t, 0.0).unwrap(), 1.0);
                assert_eq!(vsm.lit_fraction(t, 0.0).unwrap(), 1.0);
            }
            for t in behinds {
                assert_eq!(
                    evsm.lit_fraction(t, 0.0).unwrap(),
                    0.0,
                    "c = {c_pos}, t = {t}"
                );
                assert_eq!(vsm.lit_fraction(t, 0.0).unwrap(), 0.0);
                // A floor of 1e-6 depth²: the warped floor is (u'(t))²·1e-6.
                let var = 1e-6;
                let p = evsm.positive().lit_fraction(t, var).unwrap();
                let n = evsm.negative().lit_fraction(t, var).unwrap();
                let slope_p = c_pos * (c_pos * (t - d0)).exp();
                let gap_p = (c_pos * (t - d0)).exp_m1();
                let slope_n = c_neg * (-c_neg * (t - d0)).exp();
                let gap_n = -(-c_neg * (t - d0)).exp_m1();
                let expected_p = 1.0 / (1.0 + (gap_p / slope_p).powi(2) / var);
                let expected_n = 1.0 / (1.0 + (gap_n / slope_n).powi(2) / var);
                assert_close(p, expected_p, 1e-9, "EVSM positive warp with a floor");
                assert_close(n, expected_n, 1e-9, "EVSM negative warp with a floor");
            }
        }
        let msm = MsmMoments::from_depths(d0, &depths).unwrap();
        for t in fronts {
            assert_eq!(msm.lit_fraction(t, 0.0).unwrap(), 1.0);
        }
        for t in behinds {
            assert_eq!(msm.lit_fraction(t, 0.0).unwrap(), 0.0);
        }
        for alpha in [1e-6, 1e-4, 1e-2] {
            for t in fronts.into_iter().filter(|&t| t > 0.0) {
                let lit = msm.lit_fraction(t, alpha).unwrap();
                assert!(
                    lit >= 1.0 - alpha / 2.0 - BOUND_SLACK && lit <= 1.0,
                    "{lit}"
                );
            }
            for t in behinds.into_iter().filter(|&t| t <= 1.0) {
                let lit = msm.lit_fraction(t, alpha).unwrap();
                let above = biased_cantelli(&depths, &weights, t, alpha);
                assert!(
                    lit >= alpha / 2.0 - BOUND_SLACK && lit <= above + BOUND_SLACK,
                    "d0 = {d0}, α = {alpha}, t = {t}: {lit} not in [{}, {above}]",
                    alpha / 2.0
                );
            }
        }
    }
}

/// Claim: two steps, a share `p` at `d0` and `1 − p` at `d1`. ESM equals
/// `min(1, p·e^{−c(t−d0)} + (1 − p)·e^{−c(t−d1)})` (too light between the steps: ESM's leak); VSM,
/// EVSM2 and EVSM4 equal their Cantelli closed forms on the (warped) two-point distribution and are
/// at least the exact lit fraction; MSM is exact as `α → 0` (a two-point distribution is determined
/// by its moments: lit `1 − p` between the steps, 0 behind) and stays within its rigorous bracket
/// for `α > 0`.
#[test]
fn two_steps_against_closed_forms() {
    for (d0, d1) in [(0.2, 0.6), (0.45, 0.5), (0.1, 0.95)] {
        for p in [0.25, 0.5, 0.75] {
            let depths = two_steps(d0, d1, p, 20);
            let weights = vec![1.0; depths.len()];
            let mid = 0.5 * (d0 + d1);
            let ts = [d0 - 0.05, d0, mid, d1, d1 + 0.02, 1.0];
            for c in [5.0, 40.0, 200.0] {
                let esm = ExponentialMoment::from_depths(c, &depths).unwrap();
                for t in ts {
                    let expected =
                        (p * (-c * (t - d0)).exp() + (1.0 - p) * (-c * (t - d1)).exp()).min(1.0);
                    assert_close(esm.lit_fraction(t).unwrap(), expected, 1e-11, "ESM");
                }
            }
            let vsm = ShiftedMoments::from_depths(mid, &depths).unwrap();
            let (mean, var) = (p * d0 + (1.0 - p) * d1, p * (1.0 - p) * (d1 - d0).powi(2));
            for t in ts {
                let lit = vsm.lit_fraction(t, 0.0).unwrap();
                assert_close(lit, cantelli(mean, var, t), CLOSED_FORM_TOLERANCE, "VSM");
                assert!(lit >= exact_lit(&depths, &weights, t) - BOUND_SLACK);
            }
            for c in [5.0, 11.08, 40.0] {
                let evsm = Evsm4Moments::from_depths(c, c, mid, &depths).unwrap();
                // Closed forms on the raw warps w₊ = e^{c·d}, w₋ = −e^{−c·d}, scaled by e^{∓c·mid}.
                let warped = |w: &dyn Fn(f64) -> f64, t: f64| {
                    let (w0, w1) = (w(d0), w(d1));
                    let m = p * w0 + (1.0 - p) * w1;
                    cantelli(m, p * (1.0 - p) * (w1 - w0).powi(2), w(t))
                };
                for t in ts {
                    let positive = warped(&|d| (c * (d - mid)).exp(), t);
                    let negative = warped(&|d| -(-c * (d - mid)).exp(), t);
                    let e2 = evsm.positive().lit_fraction(t, 0.0).unwrap();
                    let e4 = evsm.lit_fraction(t, 0.0).unwrap();
                    assert_close(e2, positive, 1e-10, "EVSM2");
                    assert_close(e4, positive.min(negative), 1e-10, "EVSM4");
                    assert!(e4 >= exact_lit(&depths, &weights, t) - BOUND_SLACK);
                }
            }
            let msm = MsmMoments::from_depths(mid, &depths).unwrap();
            // Exact as α → 0, away from the steps themselves (where the exact answer jumps).
            for (t, exact) in [(d0 - 0.05, 1.0), (mid, 1.0 - p), (d1 + 0.02, 0.0)] {
                let mut last_error = f64::INFINITY;
                for alpha in [1e-3, 1e-5, 1e-7, 1e-9] {
                    let error = (msm.lit_fraction(t, alpha).unwrap() - exact).abs();
                    assert!(error <= last_error + 1e-12, "not converging at α = {alpha}");
                    last_error = error;
                }
                assert!(last_error <= 1e-3, "{d0} {d1} {p} t = {t}: {last_error}");
                assert_close(msm.lit_fraction(t, 0.0).unwrap(), exact, 1e-9, "MSM α = 0");
            }
            for alpha in [1e-6, 1e-4, 1e-2] {
                for t in ts {
                    let lit = msm.lit_fraction(t, alpha).unwrap();
                    let below = exact_biased_lit(&depths, &weights, t, alpha);
                    let above = biased_cantelli(&depths, &weights, t, alpha);
                    assert!(
                        lit >= below - BOUND_SLACK && lit <= above + BOUND_SLACK,
                        "{d0} {d1} {p} α = {alpha} t = {t}: {lit} not in [{below}, {above}]"
                    );
                }
            }
        }
    }
}

/// Claim: a slope, depths uniform on `[a, b]` (by the midpoint rule on [`SLOPE_SAMPLES`] depths).
/// ESM, VSM and EVSM match their closed forms for the continuous uniform distribution to the
/// rule's error ([`QUADRATURE_TOLERANCE`]); MSM built from the depths matches MSM built from the
/// uniform distribution's exact moments, and for `α = 0` lies between the exact lit fraction
/// `(b − t)/(b − a)` and VSM's bound.
#[test]
fn slope_against_closed_forms() {
    for (a, b) in [(0.2, 0.7), (0.5, 0.52), (0.0, 1.0)] {
        let depths = slope(a, b);
        let r = 0.5 * (a + b);
        let ts: Vec<f64> = (0..=24)
            .map(|i| a - 0.1 + (b - a + 0.2) * f64::from(i) / 24.0)
            .collect();
        // E[e^{k·(d − r)}] of the uniform distribution.
        let exp_mean = |k: f64| ((k * (b - r)).exp() - (k * (a - r)).exp()) / (k * (b - a));
        for c in [5.0, 40.0, 200.0] {
            let esm = ExponentialMoment::from_depths(c, &depths).unwrap();
            for &t in &ts {
                let expected = (exp_mean(c) * (-c * (t - r)).exp()).min(1.0);
                let lit = esm.lit_fraction(t).unwrap();
                assert_close(lit, expected, QUADRATURE_TOLERANCE, "ESM slope");
            }
        }
        let vsm = ShiftedMoments::from_depths(r, &depths).unwrap();
        let (mean, var) = (r, (b - a) * (b - a) / 12.0);
        for &t in &ts {
            let lit = vsm.lit_fraction(t, 0.0).unwrap();
            assert_close(
                lit,
                cantelli(mean, var, t),
                QUADRATURE_TOLERANCE,
                "VSM slope",
            );
        }
        for c in [5.0, 40.0] {
            let evsm = Evsm4Moments::from_depths(c, c, r, &depths).unwrap();
            let (e1, e2) = (exp_mean(c), exp_mean(2.0 * c));
            let positive = Evsm2Moments::new(c, r, e1 - 1.0, e2 - 2.0 * e1 + 1.0).unwrap();
            let (n1, n2) = (exp_mean(-c), exp_mean(-2.0 * c));
            let negative =
                WarpedMoments::new(Warp::Negative, c, r, 1.0 - n1, 1.0 - 2.0 * n1 + n2).unwrap();
            for &t in &ts {
                for (built, closed, what) in [
                    (evsm.positive(), positive.positive(), "EVSM positive slope"),
                    (evsm.negative(), &negative, "EVSM negative slope"),
                ] {
                    let lit = built.lit_fraction(t, 0.0).unwrap();
                    let expected = closed.lit_fraction(t, 0.0).unwrap();
                    assert_close(lit, expected, QUADRATURE_TOLERANCE, what);
                }
            }
        }
        let exact_moments: [f64; 4] = [1, 2, 3, 4]
            .map(|k| ((b - r).powi(k + 1) - (a - r).powi(k + 1)) / (f64::from(k + 1) * (b - a)));
        let closed = MsmMoments::new(r, exact_moments).unwrap();
        let built = MsmMoments::from_depths(r, &depths).unwrap();
        for &t in &ts {
            for alpha in [0.0, 1e-4] {
                let lit = built.lit_fraction(t, alpha).unwrap();
                let expected = closed.lit_fraction(t, alpha).unwrap();
                assert_close(lit, expected, QUADRATURE_TOLERANCE, "MSM slope");
            }
            let lit = closed.lit_fraction(t, 0.0).unwrap();
            let exact = ((b - t) / (b - a)).clamp(0.0, 1.0);
            let vsm = cantelli(mean, var, t);
            assert!(
                exact - BOUND_SLACK <= lit && lit <= vsm + BOUND_SLACK,
                "[{a}, {b}] t = {t}: {exact} ≤ {lit} ≤ {vsm}"
            );
        }
    }
}

/// The lit fraction of a two-occluder stack under VSM in closed form: a share `p` at `d0`, `1 − p`
/// at `d1 = d0 + Δ`, receiver at `t = d1 + g`. With `ρ = g/Δ`,
/// `p(1 − p)/(p(1 − p) + (ρ + p)²)`, increasing in `Δ/g` from 0 to `1 − p`.
fn vsm_stack_leak(p: f64, spread: f64, gap: f64) -> f64 {
    let rho = gap / spread;
    p * (1.0 - p) / (p * (1.0 - p) + (rho + p) * (rho + p))
}

/// Claim: VSM's known leak on a two-occluder stack (receiver behind both, exact lit 0) equals the
/// closed form [`vsm_stack_leak`], grows as the occluders' separation `Δ` grows relative to the
/// receiver's distance `g` behind the back one, and tends to `1 − p` as that ratio grows. EVSM2
/// and EVSM4 leak less for every exponent (a convex warp; [`Evsm2Moments`]). MSM leaks less while
/// its bias is at most `(Δ·g)²` — the ratio of MSM's leak to VSM's grows about like `α/(Δ·g)²`
/// (see [`a_large_msm_bias_leaks_more_than_vsm_right_behind_the_stack`]); `α = 0` leaks nothing.
#[test]
fn vsm_leaks_on_a_two_occluder_stack_and_the_others_leak_less() {
    for (p, gap) in [0.25, 0.5, 0.75]
        .into_iter()
        .flat_map(|p| [0.005, 0.02, 0.1].map(|g| (p, g)))
    {
        let mut last = 0.0;
        for spread in [0.01, 0.05, 0.1, 0.2, 0.4, 0.6] {
            let d0 = 0.3;
            let d1 = d0 + spread;
            let t = d1 + gap;
            let depths = two_steps(d0, d1, p, 20);
            let vsm = ShiftedMoments::from_depths(0.5 * (d0 + d1), &depths)
                .unwrap()
                .lit_fraction(t, 0.0)
                .unwrap();
            assert_close(
                vsm,
                vsm_stack_leak(p, spread, gap),
                CLOSED_FORM_TOLERANCE,
                "VSM leak",
            );
            assert!(vsm > last, "the leak grows with the separation");
            last = vsm;
            for c in [1.0, 5.0, 11.08, 40.0, 84.0] {
                let evsm = Evsm4Moments::from_depths(c, c, 0.5 * (d0 + d1), &depths).unwrap();
                let e2 = evsm.positive().lit_fraction(t, 0.0).unwrap();
                let e4 = evsm.lit_fraction(t, 0.0).unwrap();
                assert!(
                    e2 < vsm && e4 <= e2,
                    "c = {c}: EVSM2 {e2}, EVSM4 {e4}, VSM {vsm}"
                );
            }
            let msm = MsmMoments::from_depths(0.5 * (d0 + d1), &depths).unwrap();
            let scale = (spread * gap).powi(2);
            assert!(msm.lit_fraction(t, 0.0).unwrap() <= 1e-12);
            for alpha in [scale / 100.0, scale] {
                let lit = msm.lit_fraction(t, alpha).unwrap();
                assert!(lit < vsm, "α = {alpha}: MSM {lit}, VSM {vsm}");
            }
        }
        assert_close(
            vsm_stack_leak(p, 1e12, 1.0),
            1.0 - p,
            1e-9,
            "the leak's limit",
        );
    }
}

/// Claim (a caution, not a virtue): MSM's bias leaks, and right behind a thin stack a bias large
/// beside `(Δ·g)²` leaks *more* than VSM — here `α = 10⁻³` (and even `10⁻⁵` behind a stack 0.01
/// deep), a hundredth of a depth unit behind the back occluder — while `α = (Δ·g)²/100` leaks
/// a tenth of VSM's or less.
#[test]
fn a_large_msm_bias_leaks_more_than_vsm_right_behind_the_stack() {
    let depths = two_steps(0.45, 0.5, 0.25, 20);
    let t = 0.51;
    let vsm = ShiftedMoments::from_depths(0.475, &depths)
        .unwrap()
        .lit_fraction(t, 0.0)
        .unwrap();
    let msm = MsmMoments::from_depths(0.475, &depths).unwrap();
    assert!(msm.lit_fraction(t, 1e-3).unwrap() > vsm + 0.05);
    assert!(
        msm.lit_fraction(t, (0.05f64 * 0.01).powi(2) / 100.0)
            .unwrap()
            < vsm / 10.0
    );
    let thin = two_steps(0.3, 0.31, 0.5, 20);
    let t = 0.33;
    let vsm = ShiftedMoments::from_depths(0.3, &thin)
        .unwrap()
        .lit_fraction(t, 0.0)
        .unwrap();
    let msm = MsmMoments::from_depths(0.3, &thin).unwrap();
    assert!(msm.lit_fraction(t, 1e-5).unwrap() > vsm);
}

/// Claim: MSM's stable form is the paper's algorithm: on well-conditioned moments it agrees with
/// the direct transcription [`paper_msm`] to rounding, for receivers in front of, between and
/// behind the reconstructed points, and outside `[0, 1]`.
#[test]
fn msm_stable_form_is_the_papers_algorithm() {
    let sets: [&[f64]; 4] = [
        &[0.2, 0.2, 0.5, 0.7, 0.71],
        &[0.1, 0.35, 0.9],
        &[0.0, 0.4, 0.6, 1.0],
        &[0.3, 0.31, 0.32, 0.8, 0.8, 0.8, 0.95],
    ];
    for depths in sets {
        let raw = MsmMoments::from_depths(0.0, depths).unwrap().moments();
        for reference in [0.0, 0.5, depths[0]] {
            let m = MsmMoments::from_depths(reference, depths).unwrap();
            // α = 1 is the target alone, a two-point distribution: singular for the paper's
            // division by D₃₃, exact below.
            for alpha in [0.0, 1e-6, 1e-3, 0.1, 0.9] {
                for i in 0..=60 {
                    let t = -0.25 + 1.5 * f64::from(i) / 60.0;
                    let ours = m.lit_fraction(t, alpha).unwrap();
                    let paper = paper_msm(raw, alpha, t);
                    assert_close(ours, paper, 1e-10, "stable form against the paper");
                }
            }
        }
    }
}

/// Claim: with `α = 1` MSM sees only the bias target, depth 0 or 1 with probability ½ each — a
/// two-point distribution (`D₃₃ = 0`) — and returns its exact lit fraction: 1 in front of depth 0,
/// ½ between, 0 behind depth 1. (On a step itself the exact lit fraction jumps, and rounding of the
/// receiver's centred depth decides the side; those receivers are left out.)
#[test]
fn msm_with_full_bias_is_the_targets_exact_step() {
    let m = MsmMoments::from_depths(0.3, &[0.3, 0.7, 0.9]).unwrap();
    for (t, expected) in [
        (-0.5, 1.0),
        (-1e-9, 1.0),
        (1e-9, 0.5),
        (0.5, 0.5),
        (1.0 - 1e-9, 0.5),
        (1.0 + 1e-9, 0.0),
        (2.0, 0.0),
    ] {
        assert_close(m.lit_fraction(t, 1.0).unwrap(), expected, 1e-12, "α = 1");
    }
}

/// Claim: MSM on depths clustered within 10⁻⁴ of 0.95 keeps its accuracy when the moments are taken
/// about the cluster (formulas.md §9.4's hazard, for four moments): it equals, to 10⁻⁹, MSM of the
/// same configuration scaled up 2500 times (the bound is affine invariant), while the raw power
/// moments of the paper (reference 0) lose it in f64.
#[test]
fn msm_moments_about_the_depths_keep_what_raw_moments_lose() {
    let scale = 2500.0;
    let cluster = [0.95 - 1e-4, 0.95, 0.95 + 1e-4];
    let spread: Vec<f64> = cluster.iter().map(|d| 0.5 + (d - 0.95) * scale).collect();
    let shifted = MsmMoments::from_depths(0.95, &cluster).unwrap();
    let raw = MsmMoments::from_depths(0.0, &cluster).unwrap();
    let reference = MsmMoments::from_depths(0.5, &spread).unwrap();
    for t in [0.95 - 5e-5, 0.95 + 5e-5, 0.95 + 2e-4] {
        let expected = reference
            .lit_fraction(0.5 + (t - 0.95) * scale, 0.0)
            .unwrap();
        assert_close(
            shifted.lit_fraction(t, 0.0).unwrap(),
            expected,
            1e-9,
            "MSM about 0.95",
        );
    }
    let lost = raw.lit_fraction(0.95 - 5e-5, 0.0).unwrap();
    let kept = shifted.lit_fraction(0.95 - 5e-5, 0.0).unwrap();
    assert!(
        (lost - kept).abs() > 0.05,
        "the hazard this form exists for: {lost} {kept}"
    );
}

/// Claim: MSM is continuous in the receiver depth across its case boundaries (where a reconstructed
/// point passes through infinity): on a sweep with steps of 10⁻⁵ no jump exceeds 10⁻², far below
/// what a wrong branch would give.
#[test]
fn msm_is_continuous_in_the_receiver_depth() {
    let sets: [&[f64]; 3] = [&[0.3, 0.6], &[0.2, 0.25, 0.8], &[0.1, 0.5, 0.5, 0.9, 0.95]];
    for depths in sets {
        let m = MsmMoments::from_depths(0.5, depths).unwrap();
        for alpha in [1e-3, 1e-2, 0.3] {
            let mut last = m.lit_fraction(-0.1, alpha).unwrap();
            for i in 1..=120_000 {
                let t = -0.1 + f64::from(i) * 1e-5;
                let lit = m.lit_fraction(t, alpha).unwrap();
                assert!(
                    (lit - last).abs() <= 1e-2,
                    "{depths:?} α = {alpha}: jump at t = {t}"
                );
                last = lit;
            }
        }
    }
}

/// Depth samples: 1 to 10 depths in `[0, 1]`, with the ends and repeated values likely, and
/// weights in `[0, 1]` with at least one positive.
fn samples() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    let depth = prop_oneof![
        3 => 0.0f64..=1.0,
        1 => Just(0.0),
        1 => Just(1.0),
        1 => Just(0.5),
    ];
    prop::collection::vec((depth, 0.0f64..=1.0), 1..=10).prop_map(|pairs| {
        let (depths, mut weights): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
        weights[0] = weights[0].max(0.5);
        (depths, weights)
    })
}

/// Receivers: inside `[0, 1]` mostly, near it, and far outside.
fn receiver() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -0.2f64..=1.2,
        1 => prop::sample::select(vec![-f64::MAX, -1e300, -3.0, 0.0, 1.0, 3.0, 1e300, f64::MAX]),
    ]
}

/// An exponent log-uniform in `[10⁻³, MAX_EXPONENT]`.
fn exponent() -> impl Strategy<Value = f64> {
    (-3.0f64..=MAX_EXPONENT.log10()).prop_map(|e| 10f64.powf(e).min(MAX_EXPONENT))
}

/// A knob that is 0 or log-uniform in `[10⁻¹², high]`.
fn zero_or_log(high: f64) -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 3 => (-12.0f64..=high.log10()).prop_map(|e| 10f64.powf(e))]
}

/// The weighted mean depth, the reference that keeps the moments well conditioned.
fn mean_depth(depths: &[f64], weights: &[f64]) -> f64 {
    let total: f64 = weights.iter().sum();
    let mean: f64 = depths.iter().zip(weights).map(|(d, w)| d * w).sum::<f64>() / total;
    mean.clamp(0.0, 1.0)
}

/// Every method's lit fraction at `t`, in the order ESM, EVSM2, EVSM4, MSM, VSM.
fn all_lit_fractions(
    (depths, weights): (&[f64], &[f64]),
    reference: f64,
    (c, alpha, min_variance): (f64, f64, f64),
    t: f64,
) -> [f64; 5] {
    let esm = ExponentialMoment::from_weighted_depths(c, depths, weights).unwrap();
    let evsm = Evsm4Moments::from_weighted_depths(c, c, reference, depths, weights).unwrap();
    let msm = MsmMoments::from_weighted_depths(reference, depths, weights).unwrap();
    // VSM has no weighted constructor: its stored moments, weighted here.
    let total: f64 = weights.iter().sum();
    let shifted_mean = |k: i32| -> f64 {
        let sum: f64 = depths
            .iter()
            .zip(weights)
            .map(|(d, w)| w * (d - reference).powi(k))
            .sum();
        sum / total
    };
    let vsm = ShiftedMoments::new(reference, shifted_mean(1), shifted_mean(2))
        .unwrap()
        .lit_fraction(t, min_variance)
        .unwrap();
    [
        esm.lit_fraction(t).unwrap(),
        evsm.positive().lit_fraction(t, min_variance).unwrap(),
        evsm.lit_fraction(t, min_variance).unwrap(),
        msm.lit_fraction(t, alpha).unwrap(),
        vsm,
    ]
}

/// One configuration for the continuity property: depths, weights, reference, exponent, receiver.
struct Case<'a> {
    depths: &'a [f64],
    weights: &'a [f64],
    reference: f64,
    exponent: f64,
    t: f64,
}

/// The knobs whose continuity is checked.
#[derive(Clone, Copy, Debug)]
enum Knob {
    EsmExponent,
    Evsm2Exponent,
    Evsm4Exponent,
    Evsm2MinVariance,
    Evsm4MinVariance,
    MsmBias,
}

impl Knob {
    const ALL: [Self; 6] = [
        Self::EsmExponent,
        Self::Evsm2Exponent,
        Self::Evsm4Exponent,
        Self::Evsm2MinVariance,
        Self::Evsm4MinVariance,
        Self::MsmBias,
    ];

    /// The lit fraction of `case` with this knob set to `value` (the others as in `case`, no floor).
    fn lit(self, case: &Case<'_>, value: f64) -> f64 {
        let (d, w, r, c, t) = (
            case.depths,
            case.weights,
            case.reference,
            case.exponent,
            case.t,
        );
        let evsm2 = |c| Evsm2Moments::from_weighted_depths(c, r, d, w).unwrap();
        let evsm4 = |c| Evsm4Moments::from_weighted_depths(c, c, r, d, w).unwrap();
        match self {
            Self::EsmExponent => ExponentialMoment::from_weighted_depths(value, d, w)
                .unwrap()
                .lit_fraction(t),
            Self::Evsm2Exponent => evsm2(value).lit_fraction(t, 0.0),
            Self::Evsm4Exponent => evsm4(value).lit_fraction(t, 0.0),
            Self::Evsm2MinVariance => evsm2(c).lit_fraction(t, value),
            Self::Evsm4MinVariance => evsm4(c).lit_fraction(t, value),
            Self::MsmBias => MsmMoments::from_weighted_depths(r, d, w)
                .unwrap()
                .lit_fraction(t, value),
        }
        .unwrap()
    }
}

proptest! {
    #![proptest_config(config(2048))]

    /// Claim: every method's lit fraction is a number in `[0, 1]`, for any depths, weights,
    /// reference, knobs and finite receiver, the extremes included; EVSM4 is never above EVSM2.
    #[test]
    fn lit_fractions_are_bounded(
        (depths, weights) in samples(),
        reference in prop_oneof![0.0f64..=1.0, Just(0.0), Just(1.0)],
        c in exponent(),
        alpha in prop_oneof![
            Just(0.0),
            Just(1.0),
            0.0f64..=1.0,
            (-9.0f64..0.0).prop_map(|e| 10f64.powf(e)),
        ],
        min_variance in zero_or_log(1.0),
        t in receiver(),
    ) {
        let knobs = (c, alpha, min_variance);
        let lits = all_lit_fractions((&depths, &weights), reference, knobs, t);
        for (lit, name) in lits.iter().zip(["ESM", "EVSM2", "EVSM4", "MSM", "VSM"]) {
            prop_assert!((0.0..=1.0).contains(lit), "{name}: {lit}");
        }
        prop_assert!(lits[2] <= lits[1]);
    }

    /// Claim: VSM, EVSM2 and EVSM4 without a floor are upper bounds on the exact lit fraction
    /// (Cantelli on an increasing warp); MSM with a bias `α > 0` lies between the exact lit fraction
    /// of the biased distribution and that distribution's Cantelli bound (it is the sharpest upper
    /// bound given four moments, VSM's the sharpest given two). Moments about the mean depth.
    #[test]
    fn the_bounds_hold(
        (depths, weights) in samples(),
        c in exponent(),
        alpha in (-6.0f64..=0.0).prop_map(|e| 10f64.powf(e)),
        t in -0.2f64..=1.2,
    ) {
        let reference = mean_depth(&depths, &weights);
        let lits = all_lit_fractions((&depths, &weights), reference, (c, alpha, 0.0), t);
        let exact = exact_lit(&depths, &weights, t);
        for (lit, name) in [(lits[1], "EVSM2"), (lits[2], "EVSM4"), (lits[4], "VSM")] {
            prop_assert!(lit >= exact - BOUND_SLACK, "{name}: {lit} < exact {exact}");
        }
        let below = exact_biased_lit(&depths, &weights, t, alpha);
        let above = biased_cantelli(&depths, &weights, t, alpha);
        prop_assert!(lits[3] >= below - BOUND_SLACK && lits[3] <= above + BOUND_SLACK,
            "MSM {} not in [{below}, {above}]", lits[3]);
    }

    /// Claim: continuity in the knobs — the exponent `c` (ESM, EVSM), the minimum variance (EVSM)
    /// and the bias `α ≥ 10⁻⁶` (MSM). A relative step of 10⁻⁸ changes the lit fraction by at most a
    /// hundredth of what a step of 10⁻⁴ does (a jump would not shrink), or by less than 10⁻¹⁰.
    #[test]
    fn continuous_in_the_knobs(
        (depths, weights) in samples(),
        c in exponent(),
        alpha in (-6.0f64..=0.0).prop_map(|e| 10f64.powf(e)),
        min_variance in (-12.0f64..=-1.0).prop_map(|e| 10f64.powf(e)),
        t in -0.2f64..=1.2,
    ) {
        let reference = mean_depth(&depths, &weights);
        let case = Case { depths: &depths, weights: &weights, reference, exponent: c, t };
        for knob in Knob::ALL {
            let k = match knob {
                Knob::EsmExponent | Knob::Evsm2Exponent | Knob::Evsm4Exponent => c,
                Knob::Evsm2MinVariance | Knob::Evsm4MinVariance => min_variance,
                Knob::MsmBias => alpha,
            };
            // Steps down from the knob, so that knobs at their upper limit (c, α) move too.
            let base = knob.lit(&case, k);
            let coarse = (knob.lit(&case, k * (1.0 - 1e-4)) - base).abs();
            let fine = (knob.lit(&case, k * (1.0 - 1e-8)) - base).abs();
            prop_assert!(fine <= 1e-2 * coarse + 1e-10, "{knob:?} = {k}: {fine} vs {coarse}");
        }
    }
}
