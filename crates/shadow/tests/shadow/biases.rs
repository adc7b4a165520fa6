//! Biases as engines apply them: the light's direction and the texel size a map gives at a point,
//! the receiver offsets (normal, normal × sin θ, lateral, toward the light) measured against them,
//! and the `--bias` spec's terms, round trips and errors.

use glam::{DMat3, DMat4, DVec3};
use shadowlab_hull::{Aabb, NdcDepth, Orthographic, Perspective, ViewPose};
use shadowlab_raster::DepthFormat;
use shadowlab_shadow::{
    Bias, DepthComparison, Eye, FocusPolicy, LightSetup, LightSource, LightTexel, NormalOffset,
    PlanInput, ProjectiveMapping, ShadowMap, ShadowMapping, Technique, WarpChoice, plan,
};

/// Side of the hand-made maps, in texels.
const SIDE: u32 = 256;

/// A map of `SIDE²` empty texels through `view` and `projection`.
fn map_of(view: DMat4, projection: DMat4) -> ShadowMap {
    map_of_setup(LightSetup {
        technique: Technique::Given,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(view, projection)),
        gamma: 0.0,
        half_fov: 0.0,
        warp: None,
        psm: None,
        focus_body: Vec::new(),
    })
}

fn map_of_setup(setup: LightSetup) -> ShadowMap {
    let texels = SIDE as usize * SIDE as usize;
    ShadowMap::from_depths(setup, SIDE, DepthFormat::F32, vec![1.0; texels], None).unwrap()
}

/// An orthographic map 30 wide and 20 high (world units) looking from `from` at the origin, and
/// the unit vector toward its light.
fn orthographic(from: DVec3) -> (ShadowMap, DVec3) {
    let pose = ViewPose::look_at(from, DVec3::ZERO, DVec3::Y).unwrap();
    let box_ = Orthographic::new(-15.0, 15.0, -10.0, 10.0, 1.0, 60.0).unwrap();
    let map = map_of(pose.view_matrix(), box_.matrix(NdcDepth::NegativeOneToOne));
    (map, -pose.forward())
}

/// A spot light's perspective map: 50° cone from `position` toward the origin.
fn spot(position: DVec3) -> (ShadowMap, ViewPose, Perspective) {
    let pose = ViewPose::look_at(position, DVec3::ZERO, DVec3::Y).unwrap();
    let cone = Perspective::new(50f64.to_radians(), 1.0, 0.5, 60.0).unwrap();
    let map = map_of(pose.view_matrix(), cone.matrix(NdcDepth::NegativeOneToOne));
    (map, pose, cone)
}

/// Points around the origin, on and above the ground.
fn points() -> impl Iterator<Item = DVec3> {
    (0..27).map(|k| {
        let c = |d: i32| f64::from(d - 1) * 4.5;
        DVec3::new(c(k % 3), 0.5 + c(k / 3 % 3).abs(), c(k / 9)) + DVec3::new(0.3, 0.0, -0.7)
    })
}

/// Normals toward, across and away from various lights.
fn normals() -> [DVec3; 6] {
    [
        DVec3::Y,
        DVec3::new(0.3, 1.0, -0.2).normalize(),
        DVec3::X,
        DVec3::new(-0.6, 0.2, 0.77).normalize(),
        DVec3::NEG_Y,
        DVec3::new(0.1, -0.4, 0.9).normalize(),
    ]
}

fn assert_close(a: DVec3, b: DVec3, tolerance: f64, what: &str) {
    assert!(
        (a - b).length() <= tolerance * b.length().max(1.0),
        "{what}: {a} against {b}, {:e} apart",
        (a - b).length()
    );
}

/// Claim: on an orthographic map of 30 × 20 world units and 256² texels, `L` is the unit vector
/// against the view direction and `t` = 30/256 everywhere (the larger texel side), to 1e-9.
#[test]
fn an_orthographic_map_gives_its_direction_and_texel_size() {
    for from in [
        DVec3::new(0.0, 20.0, 0.001),
        DVec3::new(7.0, 18.0, -4.0),
        DVec3::new(-12.0, 3.0, 9.0),
    ] {
        let (map, toward) = orthographic(from);
        for p in points() {
            let frame = LightTexel::at(&map, p).unwrap();
            assert_close(frame.toward_light, toward, 1e-9, "L");
            let t = 30.0 / f64::from(SIDE);
            assert!(
                (frame.texel - t).abs() <= 1e-9 * t,
                "t {} against {t}",
                frame.texel
            );
        }
    }
}

/// The analytic texel size of `cone` at view-space point `q`: the longer of the steps `a`, `b`
/// perpendicular to the ray to `q` that move the window one texel along x (y fixed) or along y,
/// from the perspective projection's derivatives.
fn spot_texel(cone: &Perspective, q: DVec3) -> f64 {
    let c = 1.0 / cone.tan_half_fov_y();
    let d = -q.z;
    // window x = (1 + c·q.x/d)/2 (aspect 1), y likewise; gradients in view space.
    let gx = DVec3::new(0.5 * c / d, 0.0, 0.5 * c * q.x / (d * d));
    let gy = DVec3::new(0.0, 0.5 * c / d, 0.5 * c * q.y / (d * d));
    let l = -q.normalize();
    let rows = DMat3::from_cols(gx, gy, l).transpose();
    let inverse = rows.inverse();
    let side = f64::from(SIDE);
    let a = inverse * DVec3::new(1.0 / side, 0.0, 0.0);
    let b = inverse * DVec3::new(0.0, 1.0 / side, 0.0);
    a.length().max(b.length())
}

/// Claim: on a spot light's perspective map `L` is the unit vector toward the spot's position, and
/// `t` the texel's size at the point, perpendicular to the ray (analytic from the projection's
/// derivatives; on the axis 2·d·tan(fov/2)/256), to 1e-8.
#[test]
fn a_spot_map_gives_the_direction_to_the_spot_and_its_texel_size() {
    let position = DVec3::new(6.0, 15.0, 4.0);
    let (map, pose, cone) = spot(position);
    for p in points() {
        let frame = LightTexel::at(&map, p).unwrap();
        assert_close(
            frame.toward_light,
            (position - p).normalize(),
            1e-8,
            "L toward the spot",
        );
        let q = pose.view_matrix().transform_point3(p);
        let t = spot_texel(&cone, q);
        assert!(
            (frame.texel - t).abs() <= 1e-8 * t,
            "t {} against {t} at {p}",
            frame.texel
        );
    }
    let on_axis = position + pose.forward() * 12.0;
    let t = 2.0 * 12.0 * cone.tan_half_fov_y() / f64::from(SIDE);
    let frame = LightTexel::at(&map, on_axis).unwrap();
    assert!(
        (frame.texel - t).abs() <= 1e-8 * t,
        "{} against {t}",
        frame.texel
    );
}

/// Claim: planned maps (uniform, PSM, LiSPSM, logarithmic for a directional light; uniform and
/// LiSPSM for a spot) give `L` as the light itself does (`LightSource::toward_from`), to 1e-6:
/// each map's window x, y stay fixed along the light's rays and its depth grows away from the
/// light, PSM's post-perspective maps included.
#[test]
fn planned_maps_give_the_lights_direction() {
    let pose = ViewPose::look_at(DVec3::new(0.0, 12.0, 25.0), DVec3::ZERO, DVec3::Y).unwrap();
    let projection = Perspective::new(50f64.to_radians(), 4.0 / 3.0, 1.0, 80.0).unwrap();
    let scene = Aabb::new(DVec3::new(-20.0, -1.0, -20.0), DVec3::new(20.0, 6.0, 20.0)).unwrap();
    let input = |light| PlanInput {
        eye: Eye { pose, projection },
        light,
        scene,
        nearest_visible_depth: None,
        focus: FocusPolicy::Light,
    };
    let spot_pose = ViewPose::look_at(DVec3::new(6.0, 25.0, 4.0), DVec3::ZERO, DVec3::Y).unwrap();
    let cone = Perspective::new(90f64.to_radians(), 1.0, 1.0, 80.0).unwrap();
    let cases = [
        (
            LightSource::directional(DVec3::new(-0.3, 1.0, 0.2)).unwrap(),
            vec![
                Technique::Uniform,
                Technique::Psm,
                Technique::Lispsm(WarpChoice::PAPER),
                Technique::LOGARITHMIC,
            ],
        ),
        (
            LightSource::directional(DVec3::new(0.2, 0.5, -1.0)).unwrap(),
            vec![Technique::Psm, Technique::Lispsm(WarpChoice::PAPER)],
        ),
        (
            LightSource::Spot {
                pose: spot_pose,
                cone,
            },
            vec![Technique::Uniform, Technique::Lispsm(WarpChoice::PAPER)],
        ),
    ];
    for (light, techniques) in cases {
        for technique in techniques {
            let map = map_of_setup(plan(&input(light), technique).unwrap());
            for p in points() {
                let frame = LightTexel::at(&map, p)
                    .unwrap_or_else(|| panic!("{technique}: no frame at {p}"));
                assert_close(
                    frame.toward_light,
                    light.toward_from(p),
                    1e-6,
                    &format!("{technique} at {p}"),
                );
                assert!(frame.texel > 0.0 && frame.texel.is_finite());
            }
        }
    }
}

/// Claim: `normal:K` moves the receiver by exactly K texels (K·t) along its unit normal, whatever
/// its angle to the light; `light:D` moves it D toward the light; together they add. Checked on
/// the orthographic map, where t = 30/256 is known.
#[test]
fn normal_and_light_offsets_move_the_receiver_by_their_lengths() {
    let (map, toward) = orthographic(DVec3::new(7.0, 18.0, -4.0));
    let t = 30.0 / f64::from(SIDE);
    let normal = Bias::NONE.with_normal(NormalOffset::Plain { texels: 1.0 });
    let light = Bias::NONE.with_toward_light(0.02);
    let both = Bias::NONE
        .with_normal(NormalOffset::Plain { texels: 1.8 })
        .with_toward_light(0.02);
    for p in points() {
        for n in normals() {
            assert_close(normal.receiver(&map, p, n) - p, n * t, 1e-9, "normal:1");
            // The normal is normalized first.
            assert_close(normal.receiver(&map, p, n * 3.0) - p, n * t, 1e-9, "3n");
            assert_close(light.receiver(&map, p, n) - p, toward * 0.02, 1e-9, "light");
            assert_close(
                both.receiver(&map, p, n) - p,
                n * (1.8 * t) + toward * 0.02,
                1e-9,
                "both",
            );
        }
    }
}

/// Claim: `normal-sine:K` is K·t·sin θ along n: zero where n ∥ L, K·t where n ⟂ L or faces away;
/// `normal-lateral:K` is perpendicular to L, K·t·sin θ long on faces toward the light, and scaled by
/// (1 + n·L) on faces away (Godot's `BIAS_FUNC`); `normal-versine:K` is K·t·(1 − cos θ) along n,
/// zero where n ∥ L and K·t on faces away (Unity's inset, on the receiver).
#[test]
fn the_angle_scaled_normal_offsets_follow_their_engines() {
    let (map, toward) = orthographic(DVec3::new(-12.0, 3.0, 9.0));
    let t = 30.0 / f64::from(SIDE);
    let k = 2.0;
    let sine = Bias::NONE.with_normal(NormalOffset::Sine { texels: k });
    let lateral = Bias::NONE.with_normal(NormalOffset::Lateral { texels: k });
    let versine = Bias::NONE.with_normal(NormalOffset::Versine { texels: k });
    for p in points() {
        assert!((versine.receiver(&map, p, toward) - p).length() <= 1e-7 * t);
        assert!(
            (sine.receiver(&map, p, toward) - p).length() <= 1e-7 * t,
            "n ∥ L moves {}",
            (sine.receiver(&map, p, toward) - p).length()
        );
        assert!((lateral.receiver(&map, p, toward) - p).length() <= 1e-7 * t);
        let across = toward.any_orthonormal_vector();
        assert_close(
            sine.receiver(&map, p, across) - p,
            across * (k * t),
            1e-9,
            "n ⟂ L",
        );
        assert_close(
            sine.receiver(&map, p, -toward) - p,
            -toward * (k * t),
            1e-9,
            "n = −L",
        );
        for n in normals() {
            let cos = n.dot(toward);
            let sin = (1.0 - cos * cos).sqrt();
            let moved = sine.receiver(&map, p, n) - p;
            let expected = if cos > 0.0 { sin } else { 1.0 };
            assert_close(moved, n * (k * t * expected), 1e-8, "normal-sine");
            let moved = versine.receiver(&map, p, n) - p;
            let expected = 1.0 - cos.max(0.0);
            assert_close(moved, n * (k * t * expected), 1e-8, "normal-versine");
            let moved = lateral.receiver(&map, p, n) - p;
            assert!(
                moved.dot(toward).abs() <= 1e-9 * k * t,
                "lateral offset {moved} not perpendicular to L"
            );
            let expected = k * t * sin * if cos >= 0.0 { 1.0 } else { 1.0 + cos };
            assert!(
                (moved.length() - expected).abs() <= 1e-8 * k * t,
                "lateral length {} against {expected}",
                moved.length()
            );
        }
    }
}

/// Claim: without offsets, with a zero normal (for the normal offset), and where the map has no
/// `L` (a point behind the spot), the receiver is not moved: the point itself, bit for bit. A zero
/// normal still leaves the offset toward the light.
#[test]
fn degenerate_receivers_are_not_moved() {
    let position = DVec3::new(6.0, 15.0, 4.0);
    let (map, pose, _) = spot(position);
    let all = Bias::DEFAULT
        .with_normal(NormalOffset::Lateral { texels: 2.0 })
        .with_toward_light(0.1);
    let behind = position - pose.forward() * 3.0;
    assert_eq!(LightTexel::at(&map, behind), None);
    assert_eq!(all.receiver(&map, behind, DVec3::Y), behind);
    let p = DVec3::new(0.3, 0.5, -0.7);
    assert_eq!(Bias::DEFAULT.receiver(&map, p, DVec3::Y), p);
    let normal_only = Bias::NONE.with_normal(NormalOffset::Plain { texels: 1.0 });
    assert_eq!(normal_only.receiver(&map, p, DVec3::ZERO), p);
    assert_eq!(normal_only.receiver(&map, p, DVec3::NAN), p);
    let moved = all.receiver(&map, p, DVec3::ZERO) - p;
    assert_close(moved, (position - p).normalize() * 0.1, 1e-8, "light only");
}

/// Every comparison, normal offset and light offset the specs can write, with awkward numbers.
fn comparisons() -> Vec<DepthComparison> {
    vec![
        DepthComparison::None,
        DepthComparison::Constant { offset: 0.1 + 0.2 },
        DepthComparison::Constant { offset: -1e-300 },
        DepthComparison::SlopeScaled {
            constant: 1e-5,
            slope: 2.0,
        },
        DepthComparison::SlopeScaled {
            constant: 0.0,
            slope: 1.0 / 3.0,
        },
        DepthComparison::SecondDepth,
        DepthComparison::Midpoint,
        DepthComparison::DualDepth { max_bias: 2e-3 },
        DepthComparison::ReceiverPlane { constant: 0.0 },
        DepthComparison::ReceiverPlane { constant: 1e-5 },
        DepthComparison::ReceiverPlane { constant: -0.0 },
    ]
}

/// Claim: every combination of comparison, normal offset (none or each kind) and light offset
/// (none or some) reads back from its `Display` bit for bit; the second-depth family still needs
/// second depths; terms given in any order read as their canonical spec.
#[test]
fn every_bias_spec_round_trips() {
    let normals = [
        None,
        Some(NormalOffset::Plain { texels: 1.8 }),
        Some(NormalOffset::Sine { texels: 0.5 }),
        Some(NormalOffset::Lateral { texels: 0.1 + 0.2 }),
        Some(NormalOffset::Versine { texels: 1.0 }),
        Some(NormalOffset::Plain { texels: 0.0 }),
    ];
    let lights = [None, Some(0.02), Some(1e-300), Some(0.0)];
    let mut count = 0;
    for comparison in comparisons() {
        for normal in normals {
            for toward_light in lights {
                let bias = Bias {
                    comparison,
                    normal,
                    toward_light,
                };
                let spec = bias.to_string();
                let read = Bias::parse(&spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
                assert_eq!(format!("{read:?}"), format!("{bias:?}"), "{spec}");
                assert_eq!(read, bias, "{spec}");
                assert_eq!(
                    bias.needs_second_depth(),
                    matches!(
                        comparison,
                        DepthComparison::SecondDepth
                            | DepthComparison::Midpoint
                            | DepthComparison::DualDepth { .. }
                    )
                );
                count += 1;
            }
        }
    }
    assert_eq!(count, comparisons().len() * normals.len() * lights.len());
    assert_eq!(count, 11 * 6 * 4);
    assert_eq!(Bias::DEFAULT.to_string(), "slope:2.0,1e-5");
    for (spec, expected, canonical) in [
        (
            "slope:2,1e-5+normal:1",
            Bias::DEFAULT.with_normal(NormalOffset::Plain { texels: 1.0 }),
            "slope:2.0,1e-5+normal:1.0",
        ),
        (
            "constant:1e-4+normal-sine:0.5+light:0.02",
            Bias::new(DepthComparison::Constant { offset: 1e-4 })
                .with_normal(NormalOffset::Sine { texels: 0.5 })
                .with_toward_light(0.02),
            "constant:0.0001+normal-sine:0.5+light:0.02",
        ),
        (
            "receiver-plane",
            Bias::new(DepthComparison::ReceiverPlane { constant: 0.0 }),
            "receiver-plane:0.0",
        ),
        (
            "receiver-plane:1e-5+normal:1.8",
            Bias::new(DepthComparison::ReceiverPlane { constant: 1e-5 })
                .with_normal(NormalOffset::Plain { texels: 1.8 }),
            "receiver-plane:1e-5+normal:1.8",
        ),
        (
            "light:0.02 + normal-lateral:2 + midpoint",
            Bias::new(DepthComparison::Midpoint)
                .with_normal(NormalOffset::Lateral { texels: 2.0 })
                .with_toward_light(0.02),
            "midpoint+normal-lateral:2.0+light:0.02",
        ),
        (
            "normal:1",
            Bias::NONE.with_normal(NormalOffset::Plain { texels: 1.0 }),
            "normal:1.0",
        ),
        (
            "none+light:3",
            Bias::NONE.with_toward_light(3.0),
            "light:3.0",
        ),
        (
            "constant:1e+2",
            Bias::new(DepthComparison::Constant { offset: 100.0 }),
            "constant:100.0",
        ),
        ("none", Bias::NONE, "none"),
    ] {
        let read = Bias::parse(spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
        assert_eq!(read, expected, "{spec}");
        assert_eq!(read.to_string(), canonical, "{spec}");
    }
}

/// Claim: a bad spec is refused with a message naming the bad term (or the two terms of one
/// kind) and listing the known forms.
#[test]
fn bad_bias_specs_name_the_bad_term() {
    for (spec, named) in [
        ("constant:1e-4+slope:2", "\"slope:2\""),
        ("constant:1e-4+slope:2", "\"constant:1e-4\""),
        ("normal:1+normal-sine:1", "\"normal-sine:1\""),
        ("light:1+normal:1+light:2", "\"light:2\""),
        ("receiver-plane+none", "\"none\""),
        ("bogus", "\"bogus\""),
        ("slope:2+bogus:1", "\"bogus:1\""),
        ("normal", "\"normal\""),
        ("normal:x", "\"x\""),
        ("light:nan", "\"nan\""),
        ("normal-lateral:-1", "\"normal-lateral:-1\""),
        ("light:-0.5", "\"light:-0.5\""),
        ("receiver-plane:1,2", "\"receiver-plane:1,2\""),
        ("slope:2+", "\"slope:2+\""),
        ("+normal:1", "\"+normal:1\""),
    ] {
        let error = Bias::parse(spec).expect_err(spec);
        assert!(error.contains(named), "{spec}: {error}");
    }
    for spec in [
        "constant:1e-4+slope:2",
        "bogus",
        "normal",
        "receiver-plane:1,2",
        "slope:2+",
    ] {
        let error = Bias::parse(spec).unwrap_err();
        for form in [
            "receiver-plane[:CONSTANT]",
            "normal-sine:TEXELS",
            "normal-lateral:TEXELS",
            "light:DISTANCE",
            "dual-depth:MAX",
        ] {
            assert!(error.contains(form), "{spec}: {error} lacks {form}");
        }
    }
    assert!(
        Bias::parse("normal:1+normal-sine:1")
            .unwrap_err()
            .contains("normal offsets")
    );
    assert!(
        Bias::parse("normal-lateral:-1")
            .unwrap_err()
            .contains("at least 0")
    );
    assert!(
        Bias::parse("light:nan")
            .unwrap_err()
            .contains("not a finite number")
    );
}
