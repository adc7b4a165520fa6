//! The light swept from parallel to perpendicular to the view: how each technique's error and
//! aliasing behave on the way to γ = 0, where every technique must fall back to the uniform map
//! and none may jump or produce NaN.

use glam::DVec3;
use shadowlab_hull::ViewPose;
use shadowlab_scene::{Scene, SceneLight};
use shadowlab_shadow::{Bias, Filter, Technique};
use shadowlab_trace::Bvh;

use crate::classify::Misclassification;
use crate::error::AnalysisError;
use crate::study::{EyePass, Setting, StudyOptions, measure, render};
use crate::truth::exact_truth;

/// The angles of a default sweep, in radians: exactly 0, points within 1e-6 rad of it, then degrees
/// up to 90.
#[must_use]
pub fn default_angles() -> Vec<f64> {
    let mut angles = vec![0.0, 1e-9, 1e-6];
    angles.extend(
        [
            0.1, 0.25, 0.5, 1.0, 2.0, 3.0, 5.0, 7.5, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0,
            60.0, 70.0, 80.0, 90.0,
        ]
        .iter()
        .map(|d: &f64| d.to_radians()),
    );
    angles
}

/// Which side the light comes from as γ → 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// In front of the viewer, shining toward it: the dueling frusta.
    Front,
    /// Behind the viewer, shining along the view.
    Behind,
}

/// The directional light at angle `gamma` from the view direction of the camera `pose`: in the
/// plane of the view direction and the scene's up (+y) — or the camera's up when the view is
/// vertical — tilted up.
#[must_use]
pub fn light_at(pose: &ViewPose, gamma: f64, side: Side) -> DVec3 {
    let v = pose.forward();
    let up = DVec3::Y - v * DVec3::Y.dot(v);
    let up = if up.length() > 1e-6 {
        up.normalize()
    } else {
        pose.up()
    };
    let along = match side {
        Side::Front => v,
        Side::Behind => -v,
    };
    // to_light: from the scene toward the light.
    (along * gamma.cos() + up * gamma.sin()).normalize()
}

/// One technique at one angle.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepPoint {
    /// γ, radians.
    pub gamma: f64,
    /// The technique.
    pub technique: Technique,
    /// Misclassified pixels and the largest texel footprint (pixels per texel), or why the
    /// technique is not defined there.
    pub outcome: Result<(Misclassification, f64), String>,
}

/// A scene's first light (`first`) moved to lie along `to_light` from the `eye`: a point light at
/// its own distance from the eye (its range kept), so that γ is the angle between the view and
/// the direction from the eye to it; any other light replaced by a directional one along
/// `to_light`.
#[must_use]
pub fn swept_light(first: Option<&SceneLight>, eye: DVec3, to_light: DVec3) -> SceneLight {
    match first {
        Some(&SceneLight::Point { position, range }) => SceneLight::Point {
            position: eye + to_light * (position - eye).length(),
            range,
        },
        _ => SceneLight::Directional { to_light },
    }
}

/// Sweeps the scene's first light over `angles` for every technique, at one resolution and
/// filter: a point light moved around the eye at its own distance (its range kept), any other
/// replaced by a directional light.
///
/// # Errors
/// Truth and rendering errors other than a technique not being defined.
pub fn sweep(
    scene: &Scene,
    techniques: &[Technique],
    angles: &[f64],
    side: Side,
    resolution: u32,
    filter: Filter,
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<SweepPoint>, AnalysisError> {
    let bvh = Bvh::new(scene.mesh.positions(), scene.mesh.triangles())?;
    let options = StudyOptions {
        techniques: techniques.to_vec(),
        resolutions: vec![resolution],
        partitions: vec![1],
        splits: shadowlab_shadow::Splits::Uniform,
        filters: vec![filter],
        bias: Bias::DEFAULT,
        format: shadowlab_raster::DepthFormat::F32,
        map_truth: false,
        pictures_at: None,
        optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
        focus: shadowlab_shadow::FocusPolicy::Light,
        // Sweeps report errors and footprints, no times.
        timing_runs: 1,
    };
    let mut points = Vec::new();
    let total = angles.len() * techniques.len();
    for gamma in angles {
        let mut lit_scene = scene.clone();
        let pose = &scene.camera.pose;
        lit_scene.lights = vec![swept_light(
            scene.lights.first(),
            pose.eye(),
            light_at(pose, *gamma, side),
        )];
        let eye = EyePass::new(&lit_scene)?;
        let truth = exact_truth(&lit_scene, &eye.image, &bvh)?;
        for technique in techniques {
            let setting = Setting {
                technique: *technique,
                resolution,
                partitions: 1,
                filter,
            };
            let outcome = match render(&lit_scene, &options, &setting, &eye, &bvh) {
                Ok(shadows) => {
                    let o = measure(&lit_scene, &truth, &eye.image, &shadows, filter, &bvh)?;
                    Ok((o.errors, o.footprint[0].p99))
                }
                Err(e) => match e.undefined_reason() {
                    Some(reason) => Err(reason),
                    None => return Err(e.into()),
                },
            };
            points.push(SweepPoint {
                gamma: *gamma,
                technique: *technique,
                outcome,
            });
            progress(points.len(), total);
        }
    }
    Ok(points)
}

/// The sweep written out: `sweep.csv` (every point), `sweep.md` (the angles near 0 side by side, to
/// read the continuity, naming the lookups' `filter`), and `sweep.svg`/`sweep.png` (misclassified pixels
/// and the 99th-percentile texel footprint against γ).
///
/// # Errors
/// [`AnalysisError::Plot`] if the figure cannot be drawn.
pub fn write(
    scene: &str,
    filter: &Filter,
    points: &[SweepPoint],
) -> Result<Vec<(String, Vec<u8>)>, AnalysisError> {
    use std::fmt::Write as _;
    let label = crate::report::technique_label;
    let filter = crate::labels::filter_label(filter);
    let scene_field = crate::report::csv_field(scene);
    let mut csv = String::from(
        "scene,technique,gamma_rad,gamma_deg,defined,misclassified,falsely_lit,falsely_shadowed,footprint_p99\n",
    );
    for p in points {
        match &p.outcome {
            Ok((e, p99)) => writeln!(
                csv,
                "{scene_field},{},{:?},{:?},true,{},{},{},{:?}",
                label(p.technique),
                p.gamma,
                p.gamma.to_degrees(),
                e.total(),
                e.falsely_lit,
                e.falsely_shadowed,
                p99
            ),
            Err(_) => writeln!(
                csv,
                "{scene_field},{},{:?},{:?},false,,,,",
                label(p.technique),
                p.gamma,
                p.gamma.to_degrees()
            ),
        }
        .expect("writing to a string");
    }
    let techniques: Vec<Technique> = points.iter().fold(Vec::new(), |mut acc, p| {
        if !acc.contains(&p.technique) {
            acc.push(p.technique);
        }
        acc
    });
    let mut md = format!(
        "# Light swept toward the view direction: `{scene}`\n\nMisclassified pixels (99th percentile of the texel footprint, pixels per texel — the maximum sits at silhouettes and near-grazing surfaces, where any map's footprint grows without bound) at the smallest angles, where every technique must reach the uniform map continuously. A jump between larger angles can be physical: the light crossing the plane of a large surface (the ground) changes which side of it is lit. Every map is looked up with `{filter}`.\n\n| technique | γ = 0 | 1e-9 rad | 1e-6 rad | 0.1° | 1° | 10° | 90° |\n|---|---:|---:|---:|---:|---:|---:|---:|\n"
    );
    let near = [
        0.0,
        1e-9,
        1e-6,
        0.1f64.to_radians(),
        1f64.to_radians(),
        10f64.to_radians(),
        90f64.to_radians(),
    ];
    for t in &techniques {
        let cells: Vec<String> = near
            .iter()
            .map(|g| {
                points
                    .iter()
                    .find(|p| p.technique == *t && (p.gamma - g).abs() <= 1e-12 * g.max(1.0))
                    .map_or("—".into(), |p| match &p.outcome {
                        Ok((e, p99)) => format!("{} ({p99:.2})", e.total()),
                        Err(_) => "not defined".into(),
                    })
            })
            .collect();
        writeln!(md, "| {} | {} |", label(*t), cells.join(" | ")).expect("writing to a string");
    }
    md.push_str("\n![Misclassified pixels and texel footprint against γ](sweep.png)\n");
    let series = |value: fn(&(Misclassification, f64)) -> f64| -> Vec<shadowlab_plot::Series> {
        techniques
            .iter()
            .enumerate()
            .map(|(k, t)| {
                let line: Vec<(f64, f64)> = points
                    .iter()
                    .filter(|p| p.technique == *t)
                    .map(|p| {
                        (
                            p.gamma.to_degrees(),
                            p.outcome.as_ref().map_or(f64::NAN, |o| value(o).max(0.5)),
                        )
                    })
                    .collect();
                shadowlab_plot::Series::new(
                    label(*t),
                    line,
                    k,
                    if k < 7 {
                        shadowlab_plot::LineStyle::Solid
                    } else {
                        shadowlab_plot::LineStyle::Dashed
                    },
                )
            })
            .collect()
    };
    #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
    let errors = series(|(e, _)| e.total() as f64);
    let footprint = series(|(_, p99)| *p99);
    let range = |s: &[shadowlab_plot::Series]| {
        let values = s
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .filter(|v| v.is_finite());
        let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
        if lo.is_finite() {
            ((lo * 0.5).max(1e-3), (hi * 2.0).max(1.0))
        } else {
            (0.5, 10.0)
        }
    };
    let (e_lo, e_hi) = range(&errors);
    let (f_lo, f_hi) = range(&footprint);
    let panel = |title: &str, y: shadowlab_plot::Axis, series| shadowlab_plot::Panel {
        title: title.into(),
        x: shadowlab_plot::Axis::linear("γ, angle between light and view (degrees)", 0.0, 90.0),
        y,
        series,
        markers: Vec::new(),
        legend: shadowlab_plot::LegendPosition::UpperRight,
    };
    let figure = shadowlab_plot::Figure {
        title: format!("{scene}: the light swept from parallel to perpendicular to the view"),
        panels: vec![
            panel(
                "misclassified pixels",
                shadowlab_plot::Axis::log("misclassified pixels", e_lo, e_hi),
                errors,
            ),
            panel(
                "texel footprint, 99th percentile",
                shadowlab_plot::Axis::log("pixels per texel", f_lo, f_hi),
                footprint,
            ),
        ],
        columns: 2,
        panel_width: 720,
        panel_height: 520,
    };
    let svg = shadowlab_plot::render_svg(&figure)?;
    let png = shadowlab_plot::render_png(&svg)?;
    Ok(vec![
        ("sweep.csv".into(), csv.into_bytes()),
        ("sweep.md".into(), md.into_bytes()),
        ("sweep.svg".into(), svg.into_bytes()),
        ("sweep.png".into(), png),
    ])
}
