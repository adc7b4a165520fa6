//! The extremes: γ at 0, 1e-12 and 90°, γ across φ, far/near up to 1e9.

use std::f64::consts::PI;

use glam::DVec3;
use shadowlab_params::ParameterRule;
use shadowlab_shadow::{
    FocusPolicy, LightSetup, ProductionVariant, ShadowError, Technique, WarpChoice, plan,
};

use crate::support::configuration;

/// Every technique but the logarithmic map (which is not defined for γ ≤ φ).
fn techniques() -> Vec<Technique> {
    let mut all = vec![
        Technique::Uniform,
        Technique::UniformLimited,
        Technique::Psm,
    ];
    all.extend(
        ParameterRule::ALL
            .into_iter()
            .map(|r| Technique::Lispsm(WarpChoice::Rule(r))),
    );
    all.extend(
        ProductionVariant::ALL
            .into_iter()
            .map(|v| Technique::Lispsm(WarpChoice::Production(v))),
    );
    all
}

/// Window coordinates of a few points inside the view, through a setup.
fn probe(setup: &LightSetup, eye: DVec3, forward: DVec3) -> Vec<DVec3> {
    [2.0, 5.0, 20.0, 60.0]
        .into_iter()
        .map(|t| setup.mapping.window(eye + forward * t).expect("mapped"))
        .collect()
}

fn at_gamma(gamma: f64, far: f64) -> shadowlab_shadow::PlanInput {
    configuration(
        DVec3::new(1.0, 2.0, 3.0),
        0.3,
        -0.2,
        60.0,
        1.0,
        far,
        gamma,
        true,
        true,
        FocusPolicy::Scene,
    )
}

/// Claim: at γ = 0 exactly, 1e-12 and 90°, every technique (bar GLPR below φ) gives a finite
/// mapping, and the maps at 0 and 1e-12 agree to 1e-9: the limit is reached continuously, with no
/// special case that jumps.
#[test]
fn every_technique_is_finite_and_continuous_at_the_extreme_angles() {
    for technique in techniques() {
        let mut windows = Vec::new();
        for gamma in [0.0, 1e-12, PI / 2.0] {
            let input = at_gamma(gamma, 100.0);
            match plan(&input, technique) {
                Ok(setup) => {
                    let m = setup.mapping.clip_from_world().expect("projective");
                    assert!(m.is_finite(), "{technique} at γ = {gamma}: {m:?}");
                    let w = probe(&setup, input.eye.pose.eye(), input.eye.pose.forward());
                    assert!(
                        w.iter().all(|p| p.is_finite()),
                        "{technique} at γ = {gamma}"
                    );
                    windows.push(w);
                }
                Err(ShadowError::NotDefined { .. })
                    if technique == Technique::Lispsm(WarpChoice::Rule(ParameterRule::Glpr))
                        && gamma < PI / 2.0 => {}
                Err(e) => panic!("{technique} at γ = {gamma}: {e}"),
            }
        }
        if windows.len() == 3 {
            for (a, b) in windows[0].iter().zip(&windows[1]) {
                assert!(
                    (*a - *b).length() < 1e-9,
                    "{technique}: γ = 0 {a} vs 1e-12 {b}"
                );
            }
        }
    }
}

/// Claim: as γ → 0 every LiSPSM rule's warp vanishes (λ → ∞) and its map tends to the uniform
/// map's, monotonically closer at 1°, 0.1°, 0.01° and 0.
#[test]
fn lispsm_tends_to_uniform_as_gamma_vanishes() {
    for rule in ParameterRule::ALL
        .into_iter()
        .filter(|r| *r != ParameterRule::Glpr)
    {
        let technique = Technique::Lispsm(WarpChoice::Rule(rule));
        let mut previous = f64::INFINITY;
        for degrees in [1.0f64, 0.1, 0.01, 0.0] {
            let input = at_gamma(degrees.to_radians(), 100.0);
            let warped = plan(&input, technique).unwrap();
            let uniform = plan(&input, Technique::Uniform).unwrap();
            let (e, v) = (input.eye.pose.eye(), input.eye.pose.forward());
            let gap = probe(&warped, e, v)
                .iter()
                .zip(probe(&uniform, e, v))
                .map(|(a, b)| (*a - b).length())
                .fold(0.0, f64::max);
            assert!(
                gap <= previous,
                "{technique} at {degrees}°: {gap} after {previous}"
            );
            previous = gap;
        }
        assert!(
            previous < 1e-12,
            "{technique} at γ = 0 differs from uniform by {previous}"
        );
    }
}

/// Claim: across γ = φ (the narrow/wide switch of the model and the field-of-view limit) the
/// rules defined on both sides give maps within 1e-6 of each other for angles 1e-9 apart.
#[test]
fn the_warp_is_continuous_across_the_field_of_view_limit() {
    let phi = 30f64.to_radians();
    for rule in ParameterRule::ALL
        .into_iter()
        .filter(|r| *r != ParameterRule::Glpr)
    {
        let technique = Technique::Lispsm(WarpChoice::Rule(rule));
        let below = plan(&at_gamma(phi - 1e-9, 100.0), technique).unwrap();
        let above = plan(&at_gamma(phi + 1e-9, 100.0), technique).unwrap();
        let input = at_gamma(phi, 100.0);
        let (e, v) = (input.eye.pose.eye(), input.eye.pose.forward());
        for (a, b) in probe(&below, e, v).iter().zip(probe(&above, e, v)) {
            assert!((*a - b).length() < 1e-6, "{technique}: {a} vs {b}");
        }
    }
}

/// Claim: with far/near up to 1e9 every technique still gives finite maps whose probes are inside
/// the map.
#[test]
fn huge_depth_ranges_stay_finite() {
    for far in [1e6, 1e9] {
        for technique in techniques() {
            let input = at_gamma(0.7, far);
            match plan(&input, technique) {
                Ok(setup) => {
                    let w = probe(&setup, input.eye.pose.eye(), input.eye.pose.forward());
                    for p in &w {
                        assert!(p.is_finite(), "{technique}, far {far}: {p}");
                        assert!(
                            p.x >= -1e-9 && p.x <= 1.0 + 1e-9 && p.y >= -1e-9 && p.y <= 1.0 + 1e-9,
                            "{technique}, far {far}: {p} off the map"
                        );
                    }
                }
                Err(ShadowError::NotDefined { .. })
                    if technique == Technique::Lispsm(WarpChoice::Rule(ParameterRule::Glpr)) => {}
                Err(e) => panic!("{technique}, far {far}: {e}"),
            }
        }
    }
}
