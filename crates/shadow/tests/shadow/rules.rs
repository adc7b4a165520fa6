//! Each warp-parameter choice computes what its source computes, in its source's units (issue 11
//! §1), checked on every built-in scene against formulas written here from the sources, and the
//! choices a user states (λ, n, the focus body) are the ones used.

use glam::{DVec3, DVec4};
use shadowlab_hull::{Tolerances, visible_body};
use shadowlab_params::{DepthRange, FrustumModel, HalfFov, LightAngle, ParameterRule, gmnpr};
use shadowlab_scene::{BUILTIN_SCENES, Scene, builtin_scene};
use shadowlab_shadow::{
    FocusPolicy, LightSetup, LogarithmicChoice, NearDistance, PlanInput, ProductionVariant,
    ShadowMapping, Technique, WarpChoice, plan, scene_input,
};

/// Agreement asked of the formulas restated here and the planned values.
const AGREEMENT: f64 = 1e-12;

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs())
}

/// The built-in scenes with a directional first light (chess-spot's is a spot).
fn directional_scenes() -> impl Iterator<Item = (Scene, PlanInput)> {
    BUILTIN_SCENES.iter().filter_map(|name| {
        let scene = builtin_scene(name).unwrap();
        let input = scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light).unwrap();
        matches!(
            input.light,
            shadowlab_shadow::LightSource::Directional { .. }
        )
        .then_some((scene, input))
    })
}

fn lispsm(choice: WarpChoice) -> Technique {
    Technique::Lispsm(choice)
}

/// A reported input of the setup's rule.
fn rule_input(setup: &LightSetup, name: &str) -> f64 {
    let warp = setup.warp.as_ref().unwrap();
    warp.inputs
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no {name} among {:?}", warp.inputs))
        .1
}

/// Claim: `lispsm` is LiSPSM §4.4's `n = (z_n + √(z_n·z_f))/sin γ` in world units, z_n and z_f the
/// camera's near and far — not the model's λ carried over, which `model` keeps (GMNPR eq. 9's λ),
/// the two apart wherever B's depth is not the model's.
#[test]
fn lispsm_is_the_papers_n_in_world_units() {
    for (scene, input) in directional_scenes() {
        let name = &scene.name;
        let setup = plan(&input, lispsm(WarpChoice::PAPER)).unwrap();
        let warp = setup.warp.as_ref().unwrap();
        let (z_n, z_f) = (
            scene.camera.projection.near(),
            scene.camera.projection.far(),
        );
        assert_eq!(
            (rule_input(&setup, "z_n"), rule_input(&setup, "z_f")),
            (z_n, z_f),
            "{name}"
        );
        let n = (z_n + (z_n * z_f).sqrt()) / setup.gamma.sin();
        assert!(
            relative(warp.near_distance, n) < AGREEMENT,
            "{name}: n {} vs {n}",
            warp.near_distance
        );
        assert!(relative(warp.lambda, n / warp.depth) < AGREEMENT, "{name}");

        let model = plan(&input, lispsm(WarpChoice::LispsmModel)).unwrap();
        let frustum = FrustumModel::new(
            DepthRange::new(z_n, z_f).unwrap(),
            HalfFov::from_radians(model.half_fov).unwrap(),
        );
        let gamma = LightAngle::from_radians(model.gamma).unwrap();
        let expected = gmnpr::lambda_lispsm(&frustum, gamma).lambda();
        let lambda = model.warp.as_ref().unwrap().lambda;
        assert!(
            relative(lambda, expected) < AGREEMENT,
            "{name}: model λ {lambda} vs {expected}"
        );
    }
}

/// Claim: `lispsm_dz` is formulas.md §2.7's `n = (z_n + √(z_n·(z_n + d·sin γ)))/sin γ` with B's own
/// depth d.
#[test]
fn lispsm_dz_uses_the_focus_bodys_own_depth() {
    for (scene, input) in directional_scenes() {
        let setup = plan(
            &input,
            lispsm(WarpChoice::Rule(ParameterRule::LispsmDeltaZ)),
        )
        .unwrap();
        let warp = setup.warp.as_ref().unwrap();
        let (z_n, sin) = (scene.camera.projection.near(), setup.gamma.sin());
        let n = (z_n + (z_n * (z_n + warp.depth * sin)).sqrt()) / sin;
        assert!(
            relative(warp.near_distance, n) < AGREEMENT,
            "{}: {} vs {n}",
            scene.name,
            warp.near_distance
        );
    }
}

/// Claim: `authors2006` is the authors' `calcNoptGeneral`: z0 the eye depth of B's nearest
/// vertex, `z1 = z0 + d·sin γ` (or the fall-back to B's eye-depth range where `z1/z0 ≤ 1`),
/// `n = d/(√(z1/z0) − 1)`, and its projection reference point over B's nearest vertex E: E moved
/// along the warp axis keeps its window x (the eye does so for the paper's rule).
#[test]
fn authors_2006_measures_from_the_focus_bodys_nearest_point() {
    let technique = lispsm(WarpChoice::Production(ProductionVariant::Authors2006));
    for (scene, input) in directional_scenes() {
        let name = &scene.name;
        let setup = plan(&input, technique).unwrap();
        let warp = setup.warp.as_ref().unwrap();
        let pose = input.eye.pose;
        let depth = |p: &DVec3| (*p - pose.eye()).dot(pose.forward());
        let nearest = setup
            .focus_body
            .iter()
            .copied()
            .min_by(|a, b| depth(a).total_cmp(&depth(b)))
            .unwrap();
        let (z0, z1) = (rule_input(&setup, "z0"), rule_input(&setup, "z1"));
        if depth(&nearest) > 0.0 {
            assert_eq!(z0, depth(&nearest), "{name}");
            assert!(
                relative(z1, z0 + warp.depth * setup.gamma.sin()) < AGREEMENT,
                "{name}"
            );
        } else {
            assert_eq!(z0, 0.1, "{name}: the fall-back's z0");
            assert!(warp.formula.contains("fall-back"), "{name}");
        }
        let n = warp.depth / ((z1 / z0).sqrt() - 1.0);
        assert!(
            relative(warp.near_distance, n) < 1e-9,
            "{name}: n {} vs {n}",
            warp.near_distance
        );

        let ShadowMapping::Projective(mapping) = setup.mapping else {
            panic!("projective")
        };
        // The warp axis in world space: light-space z.
        let axis: DVec4 = mapping.view().inverse() * DVec4::Z;
        let axis = axis.truncate();
        let x_of = |p: DVec3| setup.mapping.window(p).unwrap().x;
        let span = warp.depth;
        for s in [0.1, 0.4] {
            let moved = x_of(nearest - axis * (s * span));
            assert!(
                (moved - x_of(nearest)).abs() < 1e-9,
                "{name}: E's x {moved} vs {}",
                x_of(nearest)
            );
        }
        let paper = plan(&input, lispsm(WarpChoice::PAPER)).unwrap();
        let eye_x = |p: DVec3| paper.mapping.window(p).unwrap().x;
        let ahead = pose.eye() - axis * (0.5 * span);
        assert!(
            (eye_x(ahead) - eye_x(pose.eye() - axis * (0.2 * span))).abs() < 1e-9,
            "{name}"
        );
    }
}

/// Claim: a stated λ or n is the one used, for LiSPSM and for the logarithmic map's reference
/// point, and inspect's inputs name it.
#[test]
fn stated_warps_are_used_as_stated() {
    let scene = builtin_scene("outdoor").unwrap();
    let input = scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light).unwrap();
    let lambda = shadowlab_params::WarpParameter::from_lambda(0.3).unwrap();
    let n = NearDistance::new(25.0).unwrap();
    for technique in [
        lispsm(WarpChoice::Lambda(lambda)),
        Technique::Logarithmic(LogarithmicChoice::Lambda(lambda)),
    ] {
        let setup = plan(&input, technique).unwrap();
        assert_eq!(setup.warp.as_ref().unwrap().lambda, 0.3, "{technique}");
    }
    for technique in [
        lispsm(WarpChoice::NearDistance(n)),
        Technique::Logarithmic(LogarithmicChoice::NearDistance(n)),
    ] {
        let setup = plan(&input, technique).unwrap();
        let warp = setup.warp.as_ref().unwrap();
        assert!(
            relative(warp.near_distance, 25.0) < AGREEMENT,
            "{technique}: {}",
            warp.near_distance
        );
    }
    assert!(NearDistance::new(0.0).is_err());
    assert!(NearDistance::new(f64::NAN).is_err());
    let tiny = shadowlab_params::WarpParameter::from_lambda(1e-12).unwrap();
    assert!(
        plan(
            &input,
            Technique::Logarithmic(LogarithmicChoice::Lambda(tiny))
        )
        .is_err()
    );
}

/// Claim: the focus policies fit the map to the body they name: `view` to V's eight corners,
/// `view-scene` to V ∩ S, `light` to conv(V ∪ l) ∩ S ∩ L, which contains V ∩ S.
#[test]
fn focus_policies_fit_the_bodies_they_name() {
    let scene = builtin_scene("outdoor").unwrap();
    let at = |focus| scene_input(&scene, &scene.lights[0], None, focus).unwrap();
    let uniform = |focus| plan(&at(focus), Technique::Uniform).unwrap().focus_body;
    let view = uniform(FocusPolicy::View);
    assert_eq!(view, at(FocusPolicy::View).eye.frustum().corners().to_vec());
    let visible = visible_body(
        &at(FocusPolicy::ViewScene).eye.frustum(),
        &at(FocusPolicy::ViewScene).scene,
        &Tolerances::DEFAULT,
    )
    .unwrap()
    .unwrap();
    assert_eq!(uniform(FocusPolicy::ViewScene), visible.vertices().to_vec());
    let light = uniform(FocusPolicy::Light);
    assert_ne!(light, visible.vertices().to_vec());
    for key in ["light", "view-scene", "view"] {
        assert_eq!(FocusPolicy::parse(key).unwrap().key(), key);
    }
    assert!(FocusPolicy::parse("scene").is_err());
}

/// Claim: the logarithmic map is defined on every built-in scene with a directional or spot light,
/// the dueling frusta (where the eye lies inside B's extent along the warp axis) included, with its
/// reference point outside B.
#[test]
fn the_logarithmic_map_renders_every_built_in_scene() {
    for name in BUILTIN_SCENES {
        let scene = builtin_scene(name).unwrap();
        if matches!(scene.lights[0], shadowlab_scene::SceneLight::Point { .. }) {
            continue;
        }
        let input = scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light).unwrap();
        let setup = plan(&input, Technique::LOGARITHMIC).unwrap_or_else(|e| panic!("{name}: {e}"));
        let warp = setup.warp.as_ref().unwrap();
        assert!(warp.lambda > 0.0, "{name}: λ {}", warp.lambda);
        let eye_lambda = -rule_input(&setup, "z_max") / warp.depth;
        if name == "dueling-frusta" {
            assert!(
                eye_lambda < 0.0,
                "the eye lies inside B's extent: {eye_lambda}"
            );
        } else {
            assert_eq!(
                warp.lambda, eye_lambda,
                "{name}: the eye is the reference point"
            );
        }
    }
}

/// Claim: every named parameter spec reads back as itself, and the stated ones parse.
#[test]
fn parameter_specs_round_trip() {
    for choice in WarpChoice::named() {
        assert_eq!(WarpChoice::parse(&choice.to_string()).unwrap(), choice);
    }
    assert_eq!(
        Technique::parse("lispsm", Some("lambda=0.25"))
            .unwrap()
            .parameter()
            .as_deref(),
        Some("lambda=0.25")
    );
    assert_eq!(
        Technique::parse("logarithmic", Some("n=3"))
            .unwrap()
            .parameter()
            .as_deref(),
        Some("n=3")
    );
    assert!(Technique::parse("lispsm", Some("lambda=-1")).is_err());
    assert!(Technique::parse("lispsm", Some("lambda=x")).is_err());
    assert!(Technique::parse("psm", Some("lambda=1")).is_err());
}

/// Claim: a technique's spec (as the command line and set-up files write it) and a bias's
/// `Display` read back as the same value, bit for bit; the given set-up has a key but no spec
/// that plans it.
#[test]
fn technique_and_bias_specs_round_trip() {
    let mut techniques = vec![
        Technique::Uniform,
        Technique::UniformLimited,
        Technique::Psm,
        Technique::LOGARITHMIC,
        Technique::Logarithmic(LogarithmicChoice::Faces),
        Technique::Optimal(shadowlab_shadow::StepDirection::Paper),
        Technique::Optimal(shadowlab_shadow::StepDirection::Refitted),
        Technique::parse("lispsm", Some("lambda=0.30000000000000004")).unwrap(),
        Technique::parse("logarithmic", Some("n=1e-7")).unwrap(),
    ];
    techniques.extend(WarpChoice::named().into_iter().map(Technique::Lispsm));
    for technique in techniques {
        assert_eq!(
            Technique::parse_spec(&technique.spec()),
            Ok(technique),
            "{}",
            technique.spec()
        );
    }
    assert_eq!(
        Technique::parse("lispsm", Some("minimax")).unwrap().spec(),
        "lispsm:minimax"
    );
    assert_eq!(Technique::Given.spec(), "given");
    assert!(Technique::parse_spec("given").is_err());
    let input = directional_scenes().next().unwrap().1;
    assert!(matches!(
        plan(&input, Technique::Given),
        Err(shadowlab_shadow::ShadowError::NotDefined {
            technique: "given",
            ..
        })
    ));
    use shadowlab_shadow::{Bias, DepthComparison};
    for bias in [
        Bias::NONE,
        Bias::new(DepthComparison::Constant { offset: 0.1 + 0.2 }),
        Bias::new(DepthComparison::Constant { offset: -1e-300 }),
        Bias::DEFAULT,
        Bias::new(DepthComparison::SlopeScaled {
            constant: 0.0,
            slope: 1.0 / 3.0,
        }),
        Bias::new(DepthComparison::SecondDepth),
        Bias::new(DepthComparison::Midpoint),
        Bias::new(DepthComparison::DualDepth { max_bias: 2e-3 }),
        Bias::new(DepthComparison::ReceiverPlane { constant: 1e-5 }),
        Bias::new(DepthComparison::ReceiverPlane { constant: -0.0 }),
    ] {
        assert_eq!(Bias::parse(&bias.to_string()), Ok(bias), "{bias}");
    }
    assert_eq!(Bias::DEFAULT.to_string(), "slope:2.0,1e-5");
    assert_eq!(
        Bias::parse("receiver-plane"),
        Ok(Bias::new(DepthComparison::ReceiverPlane { constant: 0.0 }))
    );
}
