//! The extremes: γ at 0, 1e-12 and 90°, γ across φ, far/near up to 1e9.

use std::f64::consts::PI;

use glam::DVec3;
use shadowlab_params::ParameterRule;
use shadowlab_shadow::{
    FocusPolicy, LightSetup, ProductionVariant, ShadowError, Technique, WarpChoice, plan,
};

use crate::support::configuration;

/// Every technique planned from a plan input alone (the scene-optimized map needs the scene).
fn techniques() -> Vec<Technique> {
    let mut all = vec![
        Technique::Uniform,
        Technique::UniformLimited,
        Technique::Psm,
        Technique::LOGARITHMIC,
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
        FocusPolicy::Light,
    )
}

/// The authors' 2006 code, which falls back to B's eye-depth range where `z1/z0 ≤ 1` — at γ = 0
/// exactly, since `z1 = z0 + d·sin γ` — and so jumps there, as its source does.
const AUTHORS_2006: Technique =
    Technique::Lispsm(WarpChoice::Production(ProductionVariant::Authors2006));

/// Claim: at γ = 0 exactly, 1e-12 and 90°, every technique (bar GLPR below φ) gives a finite
/// mapping, and the maps at 0 and 1e-12 agree to 1e-9: the limit is reached continuously, with no
/// special case that jumps — but for the authors' 2006 code, whose own fall-back jumps at γ = 0
/// (`the_authors_2006_code_falls_back_as_written`).
#[test]
fn every_technique_is_finite_and_continuous_at_the_extreme_angles() {
    for technique in techniques() {
        let mut windows = Vec::new();
        for gamma in [0.0, 1e-12, PI / 2.0] {
            let input = at_gamma(gamma, 100.0);
            match plan(&input, technique) {
                Ok(setup) => {
                    if let Some(m) = setup.mapping.clip_from_world() {
                        assert!(m.is_finite(), "{technique} at γ = {gamma}: {m:?}");
                    }
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
        if windows.len() == 3 && technique != AUTHORS_2006 {
            for (a, b) in windows[0].iter().zip(&windows[1]) {
                assert!(
                    (*a - *b).length() < 1e-9,
                    "{technique}: γ = 0 {a} vs 1e-12 {b}"
                );
            }
        }
    }
}

/// Claim: the authors' 2006 code (OpenSceneGraph's `calcNoptGeneral`) uses `z0` = the eye depth
/// of B's nearest point and `z1 = z0 + d·sin γ` where `z1/z0 > 1`, and B's nearest and farthest
/// eye depths at γ = 0, where `z1 = z0`: a finite warp at 0 beside a nearly uniform one at 1e-12.
#[test]
fn the_authors_2006_code_falls_back_as_written() {
    for (gamma, falls_back) in [(0.0, true), (1e-12, false), (0.3, false)] {
        let input = at_gamma(gamma, 100.0);
        let setup = plan(&input, AUTHORS_2006).unwrap();
        let warp = setup.warp.unwrap();
        let value = |name: &str| {
            warp.inputs
                .iter()
                .find(|(n, _)| *n == name)
                .unwrap_or_else(|| panic!("no {name} in {:?}", warp.inputs))
                .1
        };
        let pose = input.eye.pose;
        let depths: Vec<f64> = setup
            .focus_body
            .iter()
            .map(|p| (*p - pose.eye()).dot(pose.forward()))
            .collect();
        let nearest = depths.iter().copied().fold(f64::INFINITY, f64::min);
        let farthest = depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (z0, z1) = (value("z0"), value("z1"));
        assert_eq!(z0, nearest.max(0.1), "γ = {gamma}");
        if falls_back {
            assert_eq!(z1, farthest, "γ = {gamma}");
            assert!(warp.formula.contains("fall-back"), "{}", warp.formula);
        } else {
            // sin γ of the light space the plan measured, which rounds apart from `gamma.sin()`.
            let expected = z0 + warp.depth * setup.gamma.sin();
            assert!(
                (z1 - expected).abs() <= 1e-12 * z1,
                "γ = {gamma}: z1 {z1} vs {expected}"
            );
        }
        // n = d/(√(z1/z0) − 1), printed form, against the stable one.
        let n = warp.depth / ((z1 / z0).sqrt() - 1.0);
        assert!(
            (warp.near_distance - n).abs() <= 1e-9 * n,
            "γ = {gamma}: n {} vs {n}",
            warp.near_distance
        );
    }
}

/// Claim: as γ → 0 every LiSPSM rule's warp vanishes (λ → ∞), and the logarithmic map's reference
/// point recedes to infinity, so each map tends to the uniform map's, monotonically closer at 1°,
/// 0.1°, 0.01° and 0, equal to it at 0 within rounding.
#[test]
fn every_warp_tends_to_uniform_as_gamma_vanishes() {
    let warps = ParameterRule::ALL
        .into_iter()
        .filter(|r| *r != ParameterRule::Glpr)
        .map(|r| Technique::Lispsm(WarpChoice::Rule(r)))
        .chain([Technique::LOGARITHMIC]);
    for technique in warps {
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

/// Claim: the logarithmic map is continuous across γ = φ, where the eye crosses B's near plane and
/// its reference point leaves the eye: the maps on either side differ by less than 1e-5 for angles
/// 2e-9 apart, and by about a tenth of that for angles ten times closer (a Lipschitz map, steep
/// because its reference point is then only `0.1·z_n/(z_f − z_n)·d` from B). Its λ is continuous
/// too.
#[test]
fn the_logarithmic_map_is_continuous_across_the_field_of_view_limit() {
    let phi = 30f64.to_radians();
    let input = at_gamma(phi, 100.0);
    let (e, v) = (input.eye.pose.eye(), input.eye.pose.forward());
    let gap = |step: f64| {
        let below = plan(&at_gamma(phi - step, 100.0), Technique::LOGARITHMIC).unwrap();
        let above = plan(&at_gamma(phi + step, 100.0), Technique::LOGARITHMIC).unwrap();
        let lambda = |s: &LightSetup| s.warp.as_ref().unwrap().lambda;
        let (a, b) = (lambda(&below), lambda(&above));
        assert!((a - b).abs() <= 1e-6 * a.max(b), "λ {a} vs {b}");
        probe(&below, e, v)
            .iter()
            .zip(probe(&above, e, v))
            .map(|(a, b)| (*a - b).length())
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (gap(1e-9), gap(1e-10));
    assert!(coarse < 1e-5, "{coarse}");
    assert!(fine <= 0.2 * coarse, "{fine} vs {coarse}");
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

/// A scene read from scene-file text.
fn scene(text: &str) -> shadowlab_scene::Scene {
    shadowlab_scene::parse_scene(text, std::path::Path::new("limits.toml")).expect("a valid scene")
}

/// Claim: a spot light at the eye (so the eye has no position in the spot's space) is served by
/// the maps that do not depend on the eye's position — the uniform ones, fitted to B with the
/// spot's own axes, and PSM — and refused by LiSPSM and the logarithmic map with a reason that
/// names what does serve it.
#[test]
fn a_spot_light_at_the_eye_is_served_by_the_uniform_maps() {
    let scene = scene(
        "[camera]\nposition = [0, 2, 5]\ntarget = [0, 0, 0]\n\
         [[light]]\nkind = \"spot\"\nposition = [0, 2, 5]\ntarget = [0, 0, 0]\n\
         [[mesh]]\nshape = \"box\"\n[[mesh]]\nshape = \"plane\"\nsize = [10, 10]\n",
    );
    let input = shadowlab_shadow::scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light)
        .expect("a scene box");
    for technique in [
        Technique::Uniform,
        Technique::UniformLimited,
        Technique::Psm,
    ] {
        let setup = plan(&input, technique).unwrap_or_else(|e| panic!("{technique}: {e}"));
        let centre = setup
            .mapping
            .window(DVec3::ZERO)
            .expect("the box's centre is mapped");
        assert!(
            centre.is_finite()
                && (0.0..=1.0).contains(&centre.x)
                && (0.0..=1.0).contains(&centre.y),
            "{technique}: {centre}"
        );
    }
    for technique in [
        Technique::Lispsm(WarpChoice::Rule(ParameterRule::Lispsm)),
        Technique::LOGARITHMIC,
    ] {
        match plan(&input, technique) {
            Err(ShadowError::NotDefined { reason, .. }) => assert!(
                reason.contains("uniform, uniform_limited, sdsm and psm serve such a light"),
                "{technique}: {reason}"
            ),
            other => panic!("{technique}: {other:?}"),
        }
    }
}

/// Claim: a flat scene — a ground plane alone, under a sun straight overhead or at an angle — is
/// served by every technique: the scene box is thickened on its flat axis
/// (`FLAT_SCENE_THICKNESS`), and the plane lies inside it.
#[test]
fn a_flat_scene_is_served_by_every_technique() {
    for direction in ["[0, -1, 0]", "[-1, -2, -1]"] {
        let scene = scene(&format!(
            "[[light]]\ndirection = {direction}\n[[mesh]]\nshape = \"plane\"\nsize = [10, 10]\n"
        ));
        let scene_box = shadowlab_shadow::scene_box(&scene).expect("a box");
        let size = scene_box.size();
        assert!(size.y > 0.0 && size.y <= 1e-5, "{size}");
        assert!(scene_box.min().y < 0.0 && scene_box.max().y > 0.0);
        let input =
            shadowlab_shadow::scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light)
                .expect("a scene box");
        for technique in techniques() {
            if let Ok(setup) = plan(&input, technique) {
                let centre = setup.mapping.window(DVec3::ZERO).expect("mapped");
                assert!(centre.is_finite(), "{technique} under {direction}");
            } else if !matches!(
                technique,
                Technique::Lispsm(WarpChoice::Rule(ParameterRule::Glpr))
            ) {
                panic!(
                    "{technique} under {direction}: {:?}",
                    plan(&input, technique)
                );
            }
        }
    }
}
