//! The scene-optimized map (CG06 Algorithm 1): h against the composite map it is defined by, its
//! gradient against finite differences and the degree-2 homogeneity, known optima, the built-in
//! scenes planned, rendered and looked up, and determinism on any thread count.

use glam::{DMat2, DMat4, DVec2, DVec3, DVec4};
use proptest::prelude::*;
use shadowlab_hull::{NdcDepth, Perspective};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::{Mesh, Scene, builtin_scene};
use shadowlab_shadow::optimal::{
    self, LINE_SEARCH_DEGREES, LightPoint, Objective, OptimalOptions, Problem, Readback, Rows,
    Sample,
};
use shadowlab_shadow::{
    Bias, Filter, FocusPolicy, FrameOptions, Lookup, PlanInput, PlanOptions, ShadowError,
    ShadowMapping, Splits, StepDirection, Technique, plan, plan_light, render_frame,
};

use crate::support::{config, configuration, relative};

/// The agreement the brief asks of the gradient with central differences.
const GRADIENT_AGREEMENT: f64 = 1e-6;

/// A reduced 3-vector from three numbers in `[−1, 1]`.
fn vector() -> impl Strategy<Value = DVec3> {
    prop::array::uniform3(-1.0..1.0f64).prop_map(DVec3::from_array)
}

/// A random objective in reduced coordinates and rows with every sample in front: `p̃_4` a unit
/// axis, samples at distances 1–20 along it with a lateral spread, `p̃_1, p̃_2` near the plane
/// ⟂ `p̃_4`, slopes and `w_q` over a few decades.
fn objective_and_rows() -> impl Strategy<Value = (Objective, Rows)> {
    (
        vector().prop_filter("a direction", |v| v.length() > 0.3),
        vector(),
        vector(),
        prop::array::uniform3(vector()),
        prop::collection::vec(
            (
                vector(),
                1.0..20.0f64,
                -1.0..1.0f64,
                prop::array::uniform2(-3.0..3.0f64),
            ),
            1..12,
        ),
    )
        .prop_map(|(axis, p1, p2, columns, raw)| {
            let p4 = axis.normalize();
            let rows = Rows {
                p1: p1 - p4 * p1.dot(p4) + p4 * 0.1,
                p2: p2 - p4 * p2.dot(p4) - p4 * 0.2,
                p4,
            };
            let samples = raw
                .into_iter()
                .map(|(lateral, distance, decades, [s1, s2])| Sample {
                    point: p4 * distance + (lateral - p4 * lateral.dot(p4)) * distance * 0.5,
                    w_q: 10f64.powf(decades),
                    depth_slope: DVec2::new(s1, s2) * 1e-2,
                })
                .collect();
            (Objective::new(columns, samples), rows)
        })
}

/// `rows` with `p̃_4` replaced.
fn with_axis(rows: &Rows, p4: DVec3) -> Rows {
    Rows { p4, ..*rows }
}

/// An independent reference for h (eqs. 3–6): the composite map `(x1, x2) ↦ u(x1, x2, x3(x1, x2))`
/// differentiated by central differences and its 2×2 Jacobian inverted explicitly, for one sample
/// given by a full `Q⁻¹` (4×4, light at the origin) and a screen point with its depth slope.
fn reference_h(inverse_q: &DMat4, rows: &Rows, x_s: DVec3, slope: DVec2) -> f64 {
    let u = |x1: f64, x2: f64| {
        let x3 = x_s.z + slope.x * (x1 - x_s.x) + slope.y * (x2 - x_s.y);
        let x_l = (*inverse_q * DVec4::new(x1, x2, x3, 1.0)).truncate();
        DVec2::new(rows.p1.dot(x_l), rows.p2.dot(x_l)) / rows.p4.dot(x_l)
    };
    let step = 1e-4;
    let d1 = (u(x_s.x + step, x_s.y) - u(x_s.x - step, x_s.y)) / (2.0 * step);
    let d2 = (u(x_s.x, x_s.y + step) - u(x_s.x, x_s.y - step)) / (2.0 * step);
    let inverse = DMat2::from_cols(d1, d2).inverse();
    inverse.x_axis.length_squared() + inverse.y_axis.length_squared()
}

proptest! {
    #![proptest_config(config(64))]

    /// Claim: the closed form of h (eq. 5 folded into eq. 4, summed as eq. 6) is `‖J⁻¹‖²_F` of the
    /// composite map from screen to shadow map on the visible surface, differentiated numerically
    /// and inverted explicitly (formulas.md §6.3–6.5), to 1e-6.
    #[test]
    fn h_is_the_squared_norm_of_the_inverse_jacobian(
        q in prop::array::uniform4(prop::array::uniform4(-1.0..1.0f64)),
        x_s in prop::array::uniform3(-1.0..1.0f64),
        slope in prop::array::uniform2(-1.0..1.0f64),
        (_, rows) in objective_and_rows(),
    ) {
        // Q⁻¹ near the identity plus a translation that puts the point in front of the rows' axis.
        let inverse_q = DMat4::from_cols_array_2d(&q) * 0.3 + DMat4::IDENTITY;
        let x_s = DVec3::from_array(x_s);
        let slope = DVec2::from_array(slope);
        let full = inverse_q * x_s.extend(1.0);
        prop_assume!(full.w > 0.1);
        // X_l has a 1 in the light's entry; Q X_l = w_q x_s.
        let (point, w_q) = (full.truncate() / full.w, 1.0 / full.w);
        prop_assume!(rows.p4.dot(point) > 0.1);
        let columns = [0, 1, 2].map(|j| inverse_q.col(j).truncate());
        let objective = Objective::new(columns, vec![Sample { point, w_q, depth_slope: slope }]);
        let closed = objective.value(&rows).unwrap();
        let reference = reference_h(&inverse_q, &rows, x_s, slope);
        prop_assert!(relative(closed, reference) < 1e-6, "eq. 6 {closed} vs numerical {reference}");
    }

    /// Claim: the gradient of h with respect to `p̃_4` (App. A assembled as in formulas.md §6.6)
    /// agrees with central differences of h to a relative 1e-6.
    #[test]
    fn the_gradient_matches_central_differences((objective, rows) in objective_and_rows()) {
        let (h, gradient) = objective.gradient(&rows).unwrap();
        prop_assert_eq!(h, objective.value(&rows).unwrap());
        let step = 1e-6;
        let numerical = DVec3::from_array([DVec3::X, DVec3::Y, DVec3::Z].map(|e| {
            let plus = objective.value(&with_axis(&rows, rows.p4 + e * step)).unwrap();
            let minus = objective.value(&with_axis(&rows, rows.p4 - e * step)).unwrap();
            (plus - minus) / (2.0 * step)
        }));
        prop_assert!((gradient - numerical).length() <= GRADIENT_AGREEMENT * gradient.length(),
            "App. A {gradient} vs differences {numerical}");
    }

    /// Claim: with rows 1 and 2 fixed, h is homogeneous of degree 2 in `p̃_4`, so `p̃_4·∇h = 2h`
    /// (formulas.md §6.6), for any scale of `p̃_4`.
    #[test]
    fn the_gradient_is_homogeneous_of_degree_two(
        (objective, rows) in objective_and_rows(),
        scale in 0.01..100.0f64,
    ) {
        let rows = with_axis(&rows, rows.p4 * scale);
        let (h, gradient) = objective.gradient(&rows).unwrap();
        prop_assert!(relative(rows.p4.dot(gradient), 2.0 * h) < 1e-12,
            "p̃_4·∇h = {} vs 2h = {}", rows.p4.dot(gradient), 2.0 * h);
    }
}

/// Claim: a sample behind P's projection centre, or a P that maps its surface onto a line, has no h.
#[test]
fn h_is_undefined_behind_the_light_and_on_a_line() {
    let sample = Sample {
        point: DVec3::new(0.0, 0.0, -5.0),
        w_q: 5.0,
        depth_slope: DVec2::ZERO,
    };
    let objective = Objective::new([DVec3::X, DVec3::Y, DVec3::Z], vec![sample]);
    let rows = Rows {
        p1: DVec3::X,
        p2: DVec3::Y,
        p4: DVec3::NEG_Z,
    };
    assert!(objective.value(&rows).is_some());
    assert_eq!(objective.value(&with_axis(&rows, DVec3::Z)), None);
    assert_eq!(
        objective.value(&Rows {
            p2: DVec3::X,
            ..rows
        }),
        None
    );
}

/// A camera at the origin looking down −z (square pixels, 640 × 480), and samples on a symmetric
/// grid of the plane facing it at distance 10 whose screen positions form a square — the light is
/// the camera itself (`Origin`), or a directional light along the view (`Infinity`, the plane then
/// being the light's image plane). With P's axis along the view, the map from screen to shadow map
/// is affine (one Jacobian for every sample), which attains the lower bound `h ≥ N·A/2` of
/// `‖J⁻¹‖²_F ≥ 2/det J` and of the harmonic mean over a fixed image area: the optimum.
fn facing_plane(light: LightPoint) -> (Objective, Vec<DVec3>, DVec3) {
    let (width, height) = (640.0, 480.0);
    let projection = Perspective::new(50f64.to_radians(), width / height, 1.0, 100.0)
        .unwrap()
        .matrix(NdcDepth::NegativeOneToOne);
    let viewport = DMat4::from_cols(
        DVec4::new(width / 2.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, height / 2.0, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 0.5, 0.0),
        DVec4::new(width / 2.0, height / 2.0, 0.5, 1.0),
    );
    // Light space: the camera's eye space (Origin); for Infinity, y toward the light (the light
    // shines down −y onto the plane y = −10, seen by the camera looking down −y).
    // Light space for Infinity is scaled as the pipeline scales it: the samples' half-diagonal is 1.
    let to_eye = match light {
        LightPoint::Origin => DMat4::IDENTITY,
        LightPoint::Infinity => {
            DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2)
                * DMat4::from_scale(DVec3::splat(4.0 * std::f64::consts::SQRT_2))
        }
    };
    let screen = viewport * projection * to_eye;
    let inverse_q = screen.inverse();
    let columns = [0, 1, 2].map(|j| light.reduce(inverse_q.col(j)));
    let mut points = Vec::new();
    let steps = 8i32;
    for a in -steps..=steps {
        for b in -steps..=steps {
            let (x, y) = (f64::from(a) * 0.5, f64::from(b) * 0.5);
            let eye_point = DVec3::new(x, y, -10.0);
            points.push(to_eye.inverse().transform_point3(eye_point));
        }
    }
    let samples = points
        .iter()
        .map(|p| Sample {
            point: light.reduce(p.extend(1.0)),
            w_q: (screen * p.extend(1.0)).w,
            depth_slope: DVec2::ZERO,
        })
        .collect::<Vec<_>>();
    let cover = samples.iter().map(|s| s.point).collect();
    let axis = match light {
        LightPoint::Origin => DVec3::NEG_Z,
        LightPoint::Infinity => DVec3::Z,
    };
    (Objective::new(columns, samples), cover, axis)
}

/// The angle between two directions, degrees.
fn degrees_between(a: DVec3, b: DVec3) -> f64 {
    a.angle_between(b).to_degrees()
}

/// Claim (a known answer): where the map along the view is optimal — the facing plane above — the
/// descent does not move `p̃_4` at all (every rotation of the line search, the smallest 3°
/// included, is worse), for a spot light and for a directional one. Started 10° off that axis it
/// never raises h and never moves further off — but it does not come back either: Appendix A's
/// gradient holds rows 1 and 2 fixed, the refit of the affine part then changes them, and here the
/// paper's direction points away from the optimum, so the line search rejects every candidate
/// (measured; see the module's deviations).
#[test]
fn the_papers_step_keeps_a_known_optimum_but_does_not_return_to_it() {
    let options = OptimalOptions::default();
    for light in [LightPoint::Origin, LightPoint::Infinity] {
        let (objective, cover, axis) = facing_plane(light);
        let kept = optimal::descend(&objective, light, &cover, axis, &options).unwrap();
        assert_eq!(kept.steps_degrees, Vec::<f64>::new(), "{light:?}");
        assert_eq!(kept.rows.p4, axis);
        assert_eq!(kept.h, kept.initial_h);
        // The rows map the samples' square onto the bordered square: J is the same everywhere.
        let (_, gradient) = objective.gradient(&kept.rows).unwrap();
        let tangential = gradient - axis * axis.dot(gradient);
        assert!(
            tangential.length() < 1e-9 * gradient.length(),
            "{light:?}: {tangential}"
        );

        let tilt = glam::DQuat::from_axis_angle(DVec3::X, 10f64.to_radians());
        let start = tilt * axis;
        let back = optimal::descend(&objective, light, &cover, start, &options).unwrap();
        assert!(
            back.h <= back.initial_h,
            "{light:?}: {} vs {}",
            back.h,
            back.initial_h
        );
        assert!(
            back.steps_degrees
                .iter()
                .all(|s| LINE_SEARCH_DEGREES.contains(s))
        );
        let off = degrees_between(back.rows.p4, axis);
        assert!(
            off <= 10.0 + 1e-9,
            "{light:?}: ended {off}° off the optimum"
        );
        assert!(
            back.h > kept.h,
            "{light:?}: {} below the optimum {}",
            back.h,
            kept.h
        );
    }
}

/// Claim: where the paper's step fails — the facing plane started 10° off its optimal axis — the
/// refitted objective's direction (`optimal:refit`) comes back: h falls, and the axis ends within
/// 3° of the optimum, for a spot light and a directional one.
#[test]
fn the_refitted_step_returns_to_the_known_optimum() {
    let options = OptimalOptions {
        direction: StepDirection::Refitted,
        ..OptimalOptions::default()
    };
    for light in [LightPoint::Origin, LightPoint::Infinity] {
        let (objective, cover, axis) = facing_plane(light);
        let kept = optimal::descend(&objective, light, &cover, axis, &options).unwrap();
        assert_eq!(kept.steps_degrees, Vec::<f64>::new(), "{light:?}");
        let start = glam::DQuat::from_axis_angle(DVec3::X, 10f64.to_radians()) * axis;
        let back = optimal::descend(&objective, light, &cover, start, &options).unwrap();
        assert!(
            back.h < back.initial_h,
            "{light:?}: {} vs {}",
            back.h,
            back.initial_h
        );
        let off = degrees_between(back.rows.p4, axis);
        assert!(off < 3.0, "{light:?}: ended {off}° off the optimum");
        assert!(
            back.h >= kept.h,
            "{light:?}: {} below the optimum {}",
            back.h,
            kept.h
        );
    }
}

/// Claim: on the built-in scenes the refitted step ends no higher than the paper's (measured:
/// 0–28 % lower h; formulas in the module docs), from the same start and samples.
#[test]
fn the_refitted_step_is_no_worse_than_the_papers_on_the_built_in_scenes() {
    let paper = OptimalOptions::default();
    let refit = OptimalOptions {
        direction: StepDirection::Refitted,
        ..paper
    };
    for name in ["outdoor", "dueling-frusta", "chess-spot", "bunny"] {
        let scene = builtin_scene(name).unwrap();
        let input = scene_input(&scene);
        let readback = Readback::new(&scene, READBACK).unwrap();
        let problem = Problem::new(&scene, &input, &readback, &paper).unwrap();
        let (by_paper, by_refit) = (
            problem.solve(&paper).unwrap(),
            problem.solve(&refit).unwrap(),
        );
        let (h_paper, h_refit) = (by_paper.report.h.unwrap(), by_refit.report.h.unwrap());
        assert!(
            h_refit <= h_paper,
            "{name}: refit {h_refit} > paper {h_paper}"
        );
        assert_eq!(
            by_refit.setup.technique,
            Technique::Optimal(StepDirection::Refitted)
        );
    }
}

/// The plan input of a scene's first light, focused on B.
fn scene_input(scene: &Scene) -> PlanInput {
    shadowlab_shadow::scene_input(scene, &scene.lights[0], None, FocusPolicy::Light).unwrap()
}

/// The reduced rows of a planned map's P, scaled so that `|p̃_4| = 1`.
fn planned_rows(problem: &Problem, mapping: &ShadowMapping) -> Rows {
    let ShadowMapping::Projective(mapping) = mapping else {
        panic!("the optimized map is projective");
    };
    assert_eq!(mapping.view(), problem.view());
    let projection = mapping.projection();
    let [p1, p2, p4] = [0, 1, 3].map(|i| problem.light().reduce(projection.row(i)));
    let norm = p4.length();
    Rows {
        p1: p1 / norm,
        p2: p2 / norm,
        p4: p4 / norm,
    }
}

/// Claim: on the built-in scenes of CG06's kind (`outdoor`, `dueling-frusta`) the optimizer finds
/// samples by every rule it needs, lowers h below its start and far below the uniform-limited map's
/// own window, and builds a P whose rows are the ones it optimized, which holds every sample inside
/// the bordered region and every vertex of the body it fitted in front of the light and within the
/// depth range; the gradient of the real objective agrees with differences too.
#[test]
fn the_built_in_scenes_are_optimized() {
    let options = OptimalOptions::default();
    for name in ["outdoor", "dueling-frusta"] {
        let scene = builtin_scene(name).unwrap();
        let input = scene_input(&scene);
        let readback = Readback::new(&scene, options.readback).unwrap();
        let problem = Problem::new(&scene, &input, &readback, &options).unwrap();
        let counts = problem.counts();
        assert!(counts.boundary > 10, "{name}: {counts:?}");
        assert_eq!(problem.cover().len(), counts.total());
        assert_eq!(
            problem.objective().samples().len(),
            counts.total() - counts.grazing
        );

        let optimized = problem.solve(&options).unwrap();
        let report = &optimized.report;
        let (initial, h) = (report.initial_h.unwrap(), report.h.unwrap());
        assert!(h <= initial, "{name}: h {h} > initial {initial}");
        assert!(initial < report.uniform_limited_h.unwrap());
        assert_eq!(
            optimized.setup.technique,
            Technique::Optimal(StepDirection::Paper)
        );
        assert_eq!(optimized.setup.warp, None);

        let rows = planned_rows(&problem, &optimized.setup.mapping);
        let recomputed = problem.objective().value(&rows).unwrap();
        assert!(
            relative(recomputed, h) < 1e-12,
            "{name}: {recomputed} vs {h}"
        );
        let limit = 1.0 - 2.0 * options.border + 1e-9;
        for x in problem.cover() {
            let u = DVec2::new(rows.p1.dot(*x), rows.p2.dot(*x)) / rows.p4.dot(*x);
            assert!(u.abs().max_element() <= limit, "{name}: sample at {u}");
        }
        for v in &optimized.setup.focus_body {
            let window = optimized.setup.mapping.window(*v).expect("in front");
            assert!((-1e-9..=1.0 + 1e-9).contains(&window.z), "{name}: {window}");
        }

        let (_, gradient) = problem
            .objective()
            .gradient(&problem.initial_rows())
            .unwrap();
        let step = 1e-7;
        let numerical = DVec3::from_array([DVec3::X, DVec3::Y, DVec3::Z].map(|e| {
            let rows = problem.initial_rows();
            let at = |s: f64| {
                problem
                    .objective()
                    .value(&with_axis(&rows, rows.p4 + e * s))
                    .unwrap()
            };
            (at(step) - at(-step)) / (2.0 * step)
        }));
        assert!(
            (gradient - numerical).length() <= GRADIENT_AGREEMENT * gradient.length(),
            "{name}: {gradient} vs {numerical}"
        );
    }
}

/// Claim: `render_frame` renders and looks up the optimized maps of the built-in scenes like any
/// other technique's — also z-partitioned, each partition optimized on its own samples — and every
/// depth and lit fraction is finite.
#[test]
fn optimized_frames_render_and_look_up() {
    for (name, partitions) in [("outdoor", 1), ("dueling-frusta", 1), ("dueling-frusta", 2)] {
        let mut scene = builtin_scene(name).unwrap();
        (scene.camera.width, scene.camera.height) = (160, 120);
        let options = FrameOptions {
            plan: PlanOptions {
                partitions,
                splits: Splits::Logarithmic,
                ..PlanOptions::new(Technique::Optimal(StepDirection::Paper))
            },
            resolution: 256,
            format: DepthFormat::F32,
            lookup: Lookup::new(Bias::DEFAULT, Filter::Pcf { size: 3 }),
            snap_texels: 0,
        };
        let frame = render_frame(&scene, &options).unwrap();
        let maps = &frame.lights[0].maps;
        assert_eq!(maps.len(), partitions);
        for (partition, map) in maps {
            assert_eq!(
                partition.setup.technique,
                Technique::Optimal(StepDirection::Paper)
            );
            assert!(map.nearest.iter().all(|d| d.is_finite()));
            // Something was drawn into the map.
            assert!(map.nearest.iter().any(|d| *d < 1.0), "{name}");
        }
        let lit = &frame.lit[0];
        assert!(lit.iter().all(|v| (0.0..=1.0).contains(v)));
        assert!(lit.iter().any(|v| *v < 1.0), "{name}: no shadow at all");
    }
}

/// Claim: the optimizer is deterministic: the same scene gives the same P (and report) bit for bit
/// on 1, 2 and 8 threads.
#[test]
fn optimization_is_identical_on_any_thread_count() {
    for name in ["outdoor", "dueling-frusta", "chess-spot"] {
        let scene = builtin_scene(name).unwrap();
        let input = scene_input(&scene);
        let options = OptimalOptions::default();
        let runs: Vec<_> = [1, 2, 8]
            .into_iter()
            .map(|threads| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| {
                        let readback = Readback::new(&scene, options.readback).unwrap();
                        optimal::plan(&scene, &input, &readback, &options).unwrap()
                    })
            })
            .collect();
        assert_eq!(runs[0], runs[1], "{name}");
        assert_eq!(runs[0], runs[2], "{name}");
    }
}

/// Claim: `optimal` is a technique like the others by name, and `plan` refuses it with the reason
/// (it needs the scene), while `plan_light` plans it.
#[test]
fn optimal_is_a_technique_planned_from_the_scene() {
    assert_eq!(
        Technique::parse("optimal", None),
        Ok(Technique::Optimal(StepDirection::Paper))
    );
    assert_eq!(
        Technique::parse("optimal", Some("refit")),
        Ok(Technique::Optimal(StepDirection::Refitted))
    );
    assert!(Technique::parse("optimal", Some("steepest")).is_err());
    assert_eq!(
        Technique::Optimal(StepDirection::Refitted).to_string(),
        "optimal (refit)"
    );
    assert!(Technique::KEYS.contains(&"optimal"));
    assert_eq!(
        Technique::Optimal(StepDirection::Paper).to_string(),
        "optimal"
    );
    assert!(Technique::parse("optimal", Some("cad")).is_err());
    let scene = builtin_scene("outdoor").unwrap();
    let input = scene_input(&scene);
    match plan(&input, Technique::Optimal(StepDirection::Paper)) {
        Err(ShadowError::NotDefined { technique, reason }) => {
            assert_eq!(technique, "optimal");
            assert!(reason.contains("scene's geometry"), "{reason}");
        }
        other => panic!("expected NotDefined, got {other:?}"),
    }
    let parts = plan_light(
        &scene,
        &scene.lights[0],
        &PlanOptions::new(Technique::Optimal(StepDirection::Paper)),
        None,
        256,
        None,
    )
    .unwrap();
    assert_eq!(parts.len(), 1);
    assert_eq!(
        parts[0].setup.technique,
        Technique::Optimal(StepDirection::Paper)
    );
}

/// Claim: invalid options and a plan input whose eye is not the scene's camera are refused with a
/// reason; a configuration with no shadow boundary in view keeps the initial map and says so.
#[test]
fn bad_options_are_refused_and_no_samples_keep_the_initial_map() {
    let scene = builtin_scene("outdoor").unwrap();
    let input = scene_input(&scene);
    let readback = Readback::new(&scene, READBACK).unwrap();
    let bad = OptimalOptions {
        border: 0.5,
        ..OptimalOptions::default()
    };
    assert!(matches!(
        optimal::plan(&scene, &input, &readback, &bad),
        Err(ShadowError::NotDefined { .. })
    ));
    let mut moved = input;
    moved.eye = configuration(
        DVec3::ZERO,
        0.0,
        0.0,
        60.0,
        1.0,
        100.0,
        1.0,
        true,
        true,
        FocusPolicy::Light,
    )
    .eye;
    assert!(matches!(
        optimal::plan(&scene, &moved, &readback, &OptimalOptions::default()),
        Err(ShadowError::NotDefined { .. })
    ));

    // The ground alone: nothing casts a shadow, so there is no sample.
    let mut ground = scene.clone();
    let triangles = (scene.mesh.triangles().iter().zip(scene.mesh.groups()))
        .filter(|&(_, &group)| group == 0)
        .map(|(triangle, _)| *triangle)
        .collect();
    ground.mesh = Mesh::new(scene.mesh.positions().to_vec(), triangles).unwrap();
    let ground_input = scene_input(&ground);
    let readback = Readback::new(&ground, READBACK).unwrap();
    let optimized = optimal::plan(
        &ground,
        &ground_input,
        &readback,
        &OptimalOptions::default(),
    )
    .unwrap();
    let initial = plan(&ground_input, Technique::UniformLimited).unwrap();
    assert_eq!(optimized.report.h, None);
    assert_eq!(optimized.setup.mapping, initial.mapping);
    assert_eq!(
        optimized.setup.technique,
        Technique::Optimal(StepDirection::Paper)
    );
}

/// The paper's readback size, spelt out once for the tests.
const READBACK: (u32, u32) = optimal::READBACK_SIZE;

/// Claim: the optimizer's settings given to `plan_light` (read-back size, initial map, iterations,
/// border) are the ones the optimizer runs with, and the step direction is the technique's, not
/// the settings'.
#[test]
fn plan_light_plans_with_the_given_optimizer_settings() {
    let mut scene = builtin_scene("dueling-frusta").unwrap();
    (scene.camera.width, scene.camera.height) = (160, 120);
    let settings = OptimalOptions {
        readback: (40, 30),
        initial_resolution: 128,
        iterations: 1,
        border: 0.1,
        direction: StepDirection::Refitted,
    };
    let light = &scene.lights[0];
    let planned = plan_light(
        &scene,
        light,
        &PlanOptions {
            optimal: settings,
            ..PlanOptions::new(Technique::Optimal(StepDirection::Paper))
        },
        None,
        256,
        None,
    )
    .unwrap();
    let input = scene_input(&scene);
    let direct = |options: &OptimalOptions| -> Vec<_> {
        optimal::plan_partitions(&scene, &input, Splits::Uniform, 1, options)
            .unwrap()
            .into_iter()
            .map(|(partition, _)| partition)
            .collect()
    };
    let paper = OptimalOptions {
        direction: StepDirection::Paper,
        ..settings
    };
    assert_eq!(planned, direct(&paper));
    // The settings matter: the defaults plan another map.
    assert_ne!(planned, direct(&OptimalOptions::default()));
}
