//! Engines' cascades: the fits they claim (sphere and diagonal fits unchanged when the camera turns;
//! snapping moves windows in whole texels), selection by depth and by containment, blending across
//! the overlap, the fade, and every preset and SDSM variant rendering every built-in scene.

use glam::{DMat4, DQuat, DVec3};
use shadowlab_hull::{Aabb, Perspective, ViewPose};
use shadowlab_raster::NO_TRIANGLE;
use shadowlab_scene::{BUILTIN_SCENES, builtin_scene};
use shadowlab_shadow::sdsm::SdsmVariant;
use shadowlab_shadow::{
    Beyond, Bias, CullingSphere, Engine, Eye, Fade, FadeCurve, Filter, FocusPolicy, FrameOptions,
    LightMaps, LightSetup, LightSource, Lookup, MapOptions, MapSource, Partition, PartitionMap,
    PlanInput, PlanOptions, PresetChoices, Selection, SelectionRule, ShadowMapping, Stabilisation,
    Technique, eye_pass, plan_frame, render_frame, scene_eye, selection_of, served, shadows_of,
};

const RESOLUTION: u32 = 1024;

/// A camera at `eye` turned by `yaw` about world y, under a fixed sun, in a large scene box.
fn input(eye: DVec3, yaw: f64) -> PlanInput {
    let forward = DQuat::from_rotation_y(yaw) * DVec3::new(0.0, -0.3, -1.0).normalize();
    let pose = ViewPose::look_to(eye, forward, DVec3::Y).unwrap();
    PlanInput {
        eye: Eye {
            pose,
            projection: Perspective::new(60f64.to_radians(), 16.0 / 9.0, 0.5, 400.0).unwrap(),
        },
        light: LightSource::directional(DVec3::new(0.3, 1.0, 0.2)).unwrap(),
        scene: Aabb::new(
            DVec3::new(-500.0, -1.0, -500.0),
            DVec3::new(500.0, 40.0, 500.0),
        )
        .unwrap(),
        nearest_visible_depth: None,
        focus: FocusPolicy::Light,
    }
}

fn planned(engine: Engine, choices: PresetChoices, input: &PlanInput) -> Vec<Partition> {
    engine
        .plan(
            input,
            Technique::Engine(engine, choices),
            choices,
            RESOLUTION,
        )
        .unwrap()
}

/// The engine's own choices.
const SHIPPED: PresetChoices = PresetChoices {
    stabilisation: Stabilisation::Engine,
    fit: None,
    blend: None,
    select: None,
};

/// The engine's choices but its snapping.
const UNSNAPPED: PresetChoices = PresetChoices {
    stabilisation: Stabilisation::Unsnapped,
    ..SHIPPED
};

fn matrices(setup: &LightSetup) -> (DMat4, DMat4) {
    let ShadowMapping::Projective(mapping) = setup.mapping else {
        panic!("cascades are projective");
    };
    (mapping.view(), mapping.projection())
}

/// The window's width and height in world units: 2 over the projection's x and y scales.
fn window_size(setup: &LightSetup) -> (f64, f64) {
    let (_, p) = matrices(setup);
    (2.0 / p.x_axis.x, 2.0 / p.y_axis.y)
}

/// The window's left and bottom edges in the light basis.
fn window_origin(setup: &LightSetup) -> (f64, f64) {
    let (_, p) = matrices(setup);
    // X = s·x + o is −1 at the left edge: x = (−1 − o)/s.
    (
        (-1.0 - p.w_axis.x) / p.x_axis.x,
        (-1.0 - p.w_axis.y) / p.y_axis.y,
    )
}

/// Claim: the engines' sphere and diagonal fits keep their windows' size as the camera turns, and
/// so do Babylon's and Filament's cascades with such a fit chosen (`babylon:fit=sphere`,
/// `filament:fit=diagonal`); Babylon's own box of the corners does not.
#[test]
fn sphere_and_diagonal_fits_do_not_change_when_the_camera_turns() {
    let eye = DVec3::new(3.0, 5.0, 7.0);
    let chosen = |spec: &str| match Technique::parse_spec(spec).unwrap() {
        Technique::Engine(engine, choices) => (engine, choices),
        other => panic!("{spec} is {other}"),
    };
    for (engine, choices) in [
        (Engine::Bevy, SHIPPED),
        (Engine::Godot, SHIPPED),
        (Engine::ThreeJs, SHIPPED),
        (Engine::Unity, SHIPPED),
        (Engine::Unreal, SHIPPED),
        chosen("babylon:fit=sphere"),
        chosen("filament:fit=diagonal"),
    ] {
        let reference = planned(engine, choices, &input(eye, 0.0));
        for yaw in [0.3, 1.1, 2.9, -2.0] {
            let turned = planned(engine, choices, &input(eye, yaw));
            assert_eq!(turned.len(), reference.len());
            for (a, b) in reference.iter().zip(&turned) {
                let ((wa, ha), (wb, hb)) = (window_size(&a.setup), window_size(&b.setup));
                // Rotation-invariant up to rounding; Godot's edge snapping may move each edge by
                // half its 2-texel grid.
                let grid = if engine == Engine::Godot {
                    2.0 * wa / f64::from(RESOLUTION)
                } else {
                    1e-9 * wa
                };
                assert!(
                    (wa - wb).abs() <= grid && (ha - hb).abs() <= grid,
                    "{engine} yaw {yaw}: {wa}×{ha} against {wb}×{hb}"
                );
                if let (Some(sa), Some(sb)) = (a.sphere, b.sphere) {
                    assert!(
                        (sa.radius - sb.radius).abs() <= 1e-9 * sa.radius,
                        "{engine}"
                    );
                }
            }
        }
    }
    // Babylon's box of the corners turns with the camera: its size changes.
    let (a, b) = (
        planned(Engine::Babylon, SHIPPED, &input(eye, 0.0)),
        planned(Engine::Babylon, SHIPPED, &input(eye, 0.7)),
    );
    assert_ne!(window_size(&a[0].setup), window_size(&b[0].setup));
}

/// Claim: a preset's choices read back as written (`Technique::spec`), in one order whatever the
/// order given; a bad choice is refused with a message naming it.
#[test]
fn preset_choices_round_trip_and_bad_ones_are_named() {
    for (given, written) in [
        ("bevy:unsnapped", "bevy:unsnapped"),
        ("babylon:fit=sphere", "babylon:fit=sphere"),
        (
            "godot:select=containing+blend=0.25+fit=box+unsnapped",
            "godot:unsnapped+fit=box+blend=0.25+select=containing",
        ),
        ("threejs:blend=0", "threejs:blend=0"),
        ("unity:select=depth", "unity:select=depth"),
        ("filament:fit=diagonal-ceil", "filament:fit=diagonal-ceil"),
    ] {
        let technique = Technique::parse_spec(given).unwrap();
        assert_eq!(technique.spec(), written);
        assert_eq!(Technique::parse_spec(written).unwrap(), technique);
    }
    for (bad, named) in [
        ("bevy:fit=circle", "circle"),
        ("bevy:blend=1", "blend=1"),
        ("bevy:blend=-0.1", "blend=-0.1"),
        ("bevy:blend=wide", "wide"),
        ("bevy:fit=box+fit=sphere", "\"fit\" is chosen twice"),
        ("bevy:select=nearest", "nearest"),
        ("bevy:stable", "stable"),
        ("filament:blend=0.1", "filament renders one cascade"),
        ("unity:blend=0", "unity renders one cascade"),
    ] {
        let error = Technique::parse_spec(bad).unwrap_err();
        assert!(error.contains(named), "{bad}: {error}");
    }
}

/// Claim: `blend=W` sets the band in the engine's own measure — Bevy's overlap of the previous
/// far bound, Babylon's fraction of each cascade's length — and turns the blend on for engines
/// that do not blend (Godot's bands as Babylon's) or off at 0; `select=` sets the rule.
#[test]
fn preset_blend_widths_and_selection_are_the_engines_measures() {
    let choices = |spec: &str| match Technique::parse_spec(spec).unwrap() {
        Technique::Engine(_, choices) => choices,
        other => panic!("{spec} is {other}"),
    };
    let (near, far) = (0.1, 400.0);
    let starts = |engine: Engine, spec: &str| -> Vec<f64> {
        engine
            .slices(near, far, choices(spec).blend)
            .unwrap()
            .iter()
            .map(|s| s.select.0)
            .collect()
    };
    let ends = |engine: Engine| -> Vec<f64> {
        engine
            .slices(near, far, None)
            .unwrap()
            .iter()
            .map(|s| s.select.1)
            .collect()
    };
    // Bevy: cascade i starts at (1 − W)·b_{i−1}; W = 0 abuts them.
    let bevy = ends(Engine::Bevy);
    for (spec, w) in [("bevy:blend=0.5", 0.5), ("bevy:blend=0", 0.0)] {
        let got = starts(Engine::Bevy, spec);
        for i in 1..got.len() {
            assert!(
                (got[i] - (1.0 - w) * bevy[i - 1]).abs() < 1e-12,
                "{spec}: {got:?}"
            );
        }
    }
    assert!(!Engine::Bevy.selection(choices("bevy:blend=0")).blend);
    assert!(Engine::Bevy.selection(choices("bevy:blend=0.5")).blend);
    // Babylon and Godot: the last W of each cascade's own length.
    for (engine, spec) in [
        (Engine::Babylon, "babylon:blend=0.3"),
        (Engine::Godot, "godot:blend=0.3"),
    ] {
        let ends = ends(engine);
        let got = starts(engine, spec);
        let mut previous = near;
        for i in 1..got.len() {
            let expected = ends[i - 1] - 0.3 * (ends[i - 1] - previous);
            assert!((got[i] - expected).abs() < 1e-9, "{spec}: {got:?}");
            previous = ends[i - 1];
        }
        assert!(engine.selection(choices(spec)).blend, "{spec}");
    }
    assert!(!Engine::Godot.selection(choices("godot:select=depth")).blend);
    assert_eq!(
        Engine::Bevy
            .selection(choices("bevy:select=containing"))
            .rule,
        SelectionRule::Containing
    );
    assert_eq!(
        Engine::Unity.selection(choices("unity:select=depth")).rule,
        SelectionRule::Depth
    );
}

#[test]
fn snapped_windows_move_in_whole_texels_and_unsnapped_ones_do_not() {
    for engine in [
        Engine::Bevy,
        Engine::ThreeJs,
        Engine::Babylon,
        Engine::Godot,
    ] {
        let texels = if engine == Engine::Godot { 2.0 } else { 1.0 };
        let mut moved_off_grid = false;
        for step in 1..6 {
            let shift = DVec3::new(0.0137 * f64::from(step), 0.0, 0.0291 * f64::from(step));
            let (a, b) = (input(DVec3::ZERO, 0.2), input(shift, 0.2));
            for (choices, snapped) in [(SHIPPED, true), (UNSNAPPED, false)] {
                for (pa, pb) in planned(engine, choices, &a)
                    .iter()
                    .zip(&planned(engine, choices, &b))
                {
                    let (w, _) = window_size(&pa.setup);
                    let grid = texels * w / f64::from(RESOLUTION);
                    let ((xa, _), (xb, _)) = (window_origin(&pa.setup), window_origin(&pb.setup));
                    let steps = (xb - xa) / grid;
                    let whole = (steps - steps.round()).abs() < 1e-6;
                    if snapped {
                        // Babylon's box changes size as the camera moves: its centre is on the
                        // grid, its edges need not be.
                        if engine != Engine::Babylon {
                            assert!(whole, "{engine}: moved {steps} grid steps");
                        }
                        let (_, p) = matrices(&pa.setup);
                        let centre = -p.w_axis.x / p.x_axis.x;
                        let on_grid = centre / grid;
                        if engine != Engine::Godot {
                            assert!(
                                (on_grid - on_grid.round()).abs() < 1e-6,
                                "{engine}: centre {on_grid} grid steps"
                            );
                        }
                    } else {
                        moved_off_grid |= !whole;
                    }
                }
            }
        }
        assert!(
            moved_off_grid,
            "{engine}: unsnapped windows stayed on the grid"
        );
    }
}

/// Partitions at the given selection depths, each a map of nothing in particular.
fn partitions(bounds: &[(f64, f64)]) -> Vec<Partition> {
    let setup = planned(Engine::Bevy, SHIPPED, &input(DVec3::ZERO, 0.0))[0]
        .setup
        .clone();
    bounds
        .iter()
        .map(|&(near, far)| Partition {
            near,
            far,
            face: None,
            sphere: None,
            setup: setup.clone(),
        })
        .collect()
}

fn eye() -> Eye {
    Eye {
        pose: ViewPose::look_to(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).unwrap(),
        projection: Perspective::new(1.0, 1.0, 0.1, 1000.0).unwrap(),
    }
}

#[test]
fn depth_selection_picks_the_first_cascade_whose_far_lies_beyond_and_blends_the_overlap() {
    let parts = partitions(&[(0.1, 10.0), (8.0, 25.0), (20.0, 60.0)]);
    let at = |depth: f64, selection: &Selection| {
        served(
            &parts,
            |p| p,
            selection,
            &eye(),
            DVec3::new(0.0, 0.0, -depth),
        )
    };
    let plain = Selection::DEFAULT;
    let index = |depth, selection| at(depth, selection).map(|s| s.index);
    assert_eq!(index(5.0, &plain), Some(0));
    assert_eq!(
        index(9.0, &plain),
        Some(0),
        "the overlap goes to the earlier"
    );
    assert_eq!(index(10.0, &plain), Some(1));
    assert_eq!(index(80.0, &plain), Some(2), "beyond: the last");
    assert_eq!(at(9.0, &plain).unwrap().blend, None);

    let bevy = Selection {
        blend: true,
        beyond: Beyond::Lit,
        ..Selection::DEFAULT
    };
    assert_eq!(at(80.0, &bevy), None, "beyond the last cascade: lit");
    assert_eq!(at(7.9, &bevy).unwrap().blend, None);
    let blended = at(9.0, &bevy).unwrap();
    assert_eq!(blended.index, 0);
    let (next, weight) = blended.blend.unwrap();
    assert_eq!(next, 1);
    assert!((weight - 0.5).abs() < 1e-12, "(9 − 8)/(10 − 8): {weight}");
    // s = (1 − w)·s₀ + w·s₁: a shadowed earlier map and a lit later one give w.
    let lit = blended.combine(|k| if k == 0 { 0.0 } else { 1.0 });
    assert!((lit - 0.5).abs() < 1e-12);
    // Weights rise linearly across the band.
    let weights: Vec<f64> = [8.5, 9.0, 9.5]
        .iter()
        .map(|d| at(*d, &bevy).unwrap().blend.unwrap().1)
        .collect();
    assert!((weights[1] - weights[0] - (weights[2] - weights[1])).abs() < 1e-12);
}

#[test]
fn containment_selection_takes_the_first_sphere_holding_the_point() {
    let mut parts = partitions(&[(0.1, 10.0), (10.0, 50.0)]);
    parts[0].sphere = Some(CullingSphere {
        centre: DVec3::new(0.0, 0.0, -5.0),
        radius: 6.0,
    });
    parts[1].sphere = Some(CullingSphere {
        centre: DVec3::new(0.0, 0.0, -30.0),
        radius: 25.0,
    });
    let unity = Selection {
        rule: SelectionRule::Containing,
        blend: false,
        beyond: Beyond::Lit,
        fade: None,
    };
    let at = |p: DVec3| served(&parts, |p| p, &unity, &eye(), p).map(|s| s.index);
    assert_eq!(at(DVec3::new(0.0, 0.0, -9.0)), Some(0));
    // Eye depth 9, but outside the first sphere: the second serves it (by depth, the first would).
    assert_eq!(at(DVec3::new(5.0, 0.0, -9.0)), Some(1));
    assert_eq!(at(DVec3::new(0.0, 0.0, -60.0)), None);

    // Blended (a preset's `select=containing` with its blend): the band applies by eye depth after
    // the rule — in the overlap of the first map and the next, both weigh; beyond the first's far
    // end, though inside its sphere, the first serves alone.
    let mut overlapping = partitions(&[(0.1, 10.0), (8.0, 50.0)]);
    overlapping[0].sphere = Some(CullingSphere {
        centre: DVec3::new(0.0, 0.0, -5.0),
        radius: 7.0,
    });
    let blended = Selection {
        blend: true,
        ..unity
    };
    let at = |p: DVec3| served(&overlapping, |p| p, &blended, &eye(), p);
    let band = at(DVec3::new(0.0, 0.0, -9.0)).unwrap();
    assert_eq!(band.index, 0);
    let (next, weight) = band.blend.expect("blended in the band");
    assert_eq!(next, 1);
    assert!((weight - 0.5).abs() < 1e-12, "{weight}");
    let beyond = at(DVec3::new(0.0, 0.0, -11.0)).unwrap();
    assert_eq!((beyond.index, beyond.blend), (0, None));
}

#[test]
fn fades_rise_from_start_to_end() {
    let godot = Fade {
        start: 80.0,
        end: 100.0,
        curve: FadeCurve::SmoothstepDepth,
    };
    assert_eq!(godot.amount(70.0, 0.0), 0.0);
    assert_eq!(godot.amount(90.0, 0.0), 0.5);
    assert_eq!(godot.amount(120.0, 0.0), 1.0);
    let unity = Fade {
        start: 40.0,
        end: 50.0,
        curve: FadeCurve::LinearSquaredDistance,
    };
    let mid = (0.5 * (40.0f64.powi(2) + 50.0f64.powi(2))).sqrt();
    assert!((unity.amount(0.0, mid) - 0.5).abs() < 1e-12);
    assert_eq!(unity.amount(0.0, 10.0), 0.0);
}

/// A frame of four partitions by `technique`, 256² maps of f32 depths, the default bias and the
/// nearest lookup, no texel snapping.
fn four_cascades(technique: Technique) -> FrameOptions {
    FrameOptions {
        plan: PlanOptions {
            partitions: 4,
            ..PlanOptions::new(technique)
        },
        resolution: 256,
        format: shadowlab_raster::DepthFormat::F32,
        lookup: Lookup::new(Bias::DEFAULT, Filter::Nearest),
        snap_texels: 0,
    }
}

#[test]
fn every_preset_and_sdsm_variant_renders_every_builtin_scene() {
    let techniques: Vec<Technique> = Engine::ALL
        .into_iter()
        .map(|engine| Technique::Engine(engine, SHIPPED))
        .chain(SdsmVariant::ALL.into_iter().map(Technique::Sdsm))
        .collect();
    for name in BUILTIN_SCENES {
        let mut scene = builtin_scene(name).unwrap();
        if has_point_light(&scene) {
            // Cascades need a light direction: a point light is served by cube, dual-paraboloid
            // and psm alone (the omni tests).
            continue;
        }
        scene.camera.width = 96;
        scene.camera.height = 64;
        for &technique in &techniques {
            let options = four_cascades(technique);
            let frame = render_frame(&scene, &options)
                .unwrap_or_else(|e| panic!("{name} with {technique}: {e}"));
            for (light, lit) in frame.lights.iter().zip(&frame.lit) {
                assert!(!light.maps.is_empty());
                assert!(
                    lit.iter().all(|v| (0.0..=1.0).contains(v)),
                    "{name} {technique}"
                );
            }
            assert!(
                frame.lit.iter().flatten().any(|v| *v < 1.0),
                "{name} with {technique}: no shadow at all"
            );
        }
    }
}

/// Claim: each preset reads its maps with its engine's bias: the terms its doc comment derives,
/// per cascade where the engine scales them by the cascade (Godot's sphere, Unity's texel).
#[test]
fn presets_read_their_maps_with_their_engines_bias() {
    let planned_input = input(DVec3::new(3.0, 5.0, 7.0), 0.4);
    let spec = |engine: Engine, k: usize| {
        let parts = planned(engine, SHIPPED, &planned_input);
        engine.bias(&parts[k], RESOLUTION).to_string()
    };
    assert_eq!(spec(Engine::Bevy, 2), "normal:1.8+light:0.02");
    assert_eq!(spec(Engine::Babylon, 0), "constant:2.5e-5");
    assert_eq!(spec(Engine::ThreeJs, 1), "constant:-1e-6");
    for k in 0..4 {
        let parts = planned(Engine::Godot, SHIPPED, &planned_input);
        let radius = parts[k].sphere.unwrap().radius;
        let bias = Engine::Godot.bias(&parts[k], RESOLUTION);
        let light = bias.toward_light.unwrap();
        assert!((light - 0.001 * (2.0 * radius + 20.0) * 2.0).abs() < 1e-12);
        assert_eq!(bias.normal.unwrap().to_string(), "normal-lateral:2.0");
    }
    let unity = planned(Engine::Unity, SHIPPED, &planned_input);
    let (width, _) = window_size(&unity[0].setup);
    let bias = Engine::Unity.bias(&unity[0], RESOLUTION);
    assert!((bias.toward_light.unwrap() - width / f64::from(RESOLUTION)).abs() < 1e-12);
}

/// Whether `scene` has a point light.
fn has_point_light(scene: &shadowlab_scene::Scene) -> bool {
    scene
        .lights
        .iter()
        .any(|light| matches!(light, shadowlab_scene::SceneLight::Point { .. }))
}

/// Claim: a frame's lit fractions — four neighbouring pixels looked up together wherever one map
/// serves them all unblended — are each pixel's own to the bit: `served`, then `Served::combine`
/// of each serving map's `Lookup::lit_fraction`, 1 where nothing is visible or nothing serves; for
/// every preset's shipped cascades on the outdoor scene, with the nearest and the PCF lookup, each
/// with its own selection and with a fade over the whole view, so that blend bands and fades change
/// what pixels read.
#[test]
fn a_frames_lit_fractions_are_each_pixels_own() {
    let mut scene = builtin_scene("outdoor").unwrap();
    scene.camera.width = 160;
    scene.camera.height = 96;
    let view = scene_eye(&scene);
    let (eye, nearest) = eye_pass(&scene).unwrap();
    let whole_view = Fade {
        start: 0.0,
        end: 1e4,
        curve: FadeCurve::SmoothstepDepth,
    };
    let (mut blended, mut faded, mut looked_up) = (0, 0, 0);
    for engine in Engine::ALL {
        let technique = Technique::Engine(engine, SHIPPED);
        let options = four_cascades(technique);
        let planned = plan_frame(&scene, &options, nearest, Some(&eye)).unwrap();
        for (filter, fade) in [Filter::Nearest, Filter::Pcf { size: 3 }]
            .into_iter()
            .flat_map(|filter| [(filter, None), (filter, Some(whole_view))])
        {
            let lights = scene
                .lights
                .iter()
                .zip(&planned)
                .map(|(light, partitions)| {
                    let mut selection = selection_of(technique, light);
                    selection.fade = fade.or(selection.fade);
                    let map = MapOptions {
                        resolution: options.resolution,
                        format: options.format,
                        second_depth: false,
                    };
                    LightMaps {
                        light: LightSource::from_scene(light),
                        partitions: partitions
                            .iter()
                            .map(|partition| PartitionMap {
                                partition: partition.clone(),
                                source: MapSource::Render(map),
                                lookup: Lookup::new(Bias::DEFAULT, filter),
                            })
                            .collect(),
                        selection,
                    }
                })
                .collect();
            let shadows = shadows_of(&scene, &eye, lights, None).unwrap();
            for (light, lit) in shadows.lights.iter().zip(&shadows.lit) {
                for (pixel, &value) in lit.iter().enumerate() {
                    let (point, normal) = (eye.position[pixel], eye.normal[pixel]);
                    let serving = (eye.triangle[pixel] != NO_TRIANGLE)
                        .then(|| served(&light.maps, |(p, _)| p, &light.selection, &view, point))
                        .flatten();
                    let expected = serving.map_or(1.0, |serving| {
                        let lit = |k: usize| {
                            light.lookups[k].lit_fraction(&light.maps[k].1, point, normal)
                        };
                        // Where the blend or the fade changes the value.
                        if let Some((next, _)) = serving.blend {
                            blended += usize::from(lit(serving.index) != lit(next));
                        }
                        faded += usize::from(serving.fade > 0.0 && lit(serving.index) < 1.0);
                        looked_up += 1;
                        serving.combine(lit)
                    });
                    assert_eq!(
                        value.to_bits(),
                        expected.to_bits(),
                        "{engine:?}, {filter:?}, fade {fade:?}, pixel {pixel}: {value} against \
                         {expected}"
                    );
                }
            }
        }
    }
    assert!(
        blended > 50 && faded > 1000 && looked_up > 10_000,
        "{blended} blended, {faded} faded, {looked_up} looked up"
    );
}
