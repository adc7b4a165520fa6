//! `shadowlab inspect`: what a technique decides for a scene, as text or JSON.

use glam::{DMat4, DVec3};
use serde_json::{Value, json};
use shadowlab_analysis::AnalysisError;
use shadowlab_analysis::setup_file::{SetupError, setup_for};
use shadowlab_shadow::optimal::{self, OptimalOptions, OptimalReport};
use shadowlab_shadow::{
    LightSetup, ShadowError, ShadowMapping, Technique, eye_pass, plan_light, scene_input,
};

use crate::args::InspectArgs;
use crate::error::CliError;
use crate::output::{OutputFile, TEXT_BOUND, print_line};
use crate::shadow_settings::resolve;

/// A matrix as 16 numbers, row-major.
fn row_major(m: &DMat4) -> Vec<f64> {
    m.transpose().to_cols_array().to_vec()
}

fn vector(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

/// A JSON number, `null` for infinity (the uniform map's λ).
fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// The optimizer's report: samples by rule, h before and after, the accepted steps.
fn report_json(report: &OptimalReport) -> Value {
    let n = report.samples;
    json!({
        "samples": {
            "boundary": n.boundary,
            "screen_border": n.screen_border,
            "discontinuity": n.discontinuity,
            "grazing": n.grazing,
        },
        "uniform_limited_h": report.uniform_limited_h,
        "initial_h": report.initial_h,
        "h": report.h,
        "steps_degrees": report.steps_degrees,
    })
}

fn setup_json(setup: &LightSetup) -> Value {
    let (view, projection) = match setup.mapping {
        ShadowMapping::Projective(mapping) => (
            json!(row_major(&mapping.view())),
            json!(row_major(&mapping.projection())),
        ),
        ShadowMapping::Logarithmic(_) | ShadowMapping::Paraboloid(_) => (Value::Null, Value::Null),
    };
    let warp = setup.warp.as_ref();
    json!({
        "technique": setup.technique.to_string(),
        "gamma_degrees": setup.gamma.to_degrees(),
        "half_fov_degrees": setup.half_fov.to_degrees(),
        "lambda": warp.map(|w| number(w.lambda)),
        "n": warp.map(|w| number(w.near_distance)),
        "warp_depth": warp.map(|w| w.depth),
        "rule": warp.map(|w| json!({
            "formula": w.formula,
            "inputs": w.inputs.iter().map(|(name, value)| (name.to_string(), number(*value))).collect::<serde_json::Map<_, _>>(),
        })),
        "psm": setup.psm.map(|p| json!({"shift": p.shift, "near": p.near, "inverted": p.inverted, "directional": p.directional})),
        "focus_body": setup.focus_body.iter().map(|v| vector(*v)).collect::<Vec<_>>(),
        "view": view,
        "projection": projection,
    })
}

pub(crate) fn run(args: &InspectArgs) -> Result<(), CliError> {
    let resolved = resolve(&args.shadow)?;
    let scene = &resolved.scene;
    // Checked before any work; written after the set-up is printed.
    let setup_file = args
        .setup_json
        .clone()
        .map(|path| OutputFile::check(path, "--setup-json", TEXT_BOUND))
        .transpose()?;
    let (eye, nearest) =
        eye_pass(scene).map_err(|e| CliError::Failure(anyhow::anyhow!("eye pass: {e}")))?;
    let mut lights = Vec::new();
    // Per light, the optimizer's report per partition (the scene-optimized map only).
    let mut reports: Vec<Vec<OptimalReport>> = Vec::new();
    let plan = &resolved.plan;
    for (l, light) in scene.lights.iter().enumerate() {
        let failed = |e: ShadowError| {
            CliError::Input(format!(
                "{} with {}, light {l}: {e}",
                scene.name, plan.technique
            ))
        };
        if let Technique::Optimal(direction) = plan.technique {
            let input = scene_input(scene, light, nearest, plan.focus).map_err(failed)?;
            let options = OptimalOptions {
                direction,
                ..plan.optimal
            };
            let (parts, light_reports): (Vec<_>, Vec<_>) = optimal::plan_partitions(
                scene,
                &input,
                plan.splits,
                plan.partitions.max(1),
                &options,
            )
            .map_err(failed)?
            .into_iter()
            .unzip();
            lights.push(parts);
            reports.push(light_reports);
        } else {
            lights.push(
                plan_light(scene, light, plan, nearest, resolved.resolution, Some(&eye))
                    .map_err(failed)?,
            );
        }
    }
    let report_of = |l: usize, p: usize| reports.get(l).and_then(|r| r.get(p));
    if args.json {
        let value = json!({
            "scene": scene.name,
            "technique": plan.technique.to_string(),
            "focus": plan.focus.key(),
            "nearest_visible_depth": nearest,
            "lights": lights.iter().enumerate().map(|(l, parts)| json!({
                "splits": std::iter::once(parts[0].near).chain(parts.iter().map(|p| p.far)).collect::<Vec<_>>(),
                "partitions": parts.iter().enumerate().map(|(p, part)| {
                    let mut value = setup_json(&part.setup);
                    value["face"] = part.face.as_ref().map_or(Value::Null, |f| json!(f.name()));
                    if let Some(report) = report_of(l, p) {
                        value["optimizer"] = report_json(report);
                    }
                    value
                }).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        });
        return print_line(
            &serde_json::to_string_pretty(&value).map_err(|e| CliError::Failure(e.into()))?,
        );
    }
    print_line(&format!(
        "scene {}, technique {}, focus {}",
        scene.name,
        plan.technique,
        plan.focus.key()
    ))?;
    if let Some(d) = nearest {
        print_line(&format!("nearest visible eye depth {d}"))?;
    }
    for (l, parts) in lights.iter().enumerate() {
        let splits: Vec<String> = std::iter::once(parts[0].near)
            .chain(parts.iter().map(|p| p.far))
            .map(|d| format!("{d}"))
            .collect();
        print_line(&format!("light {l}: split distances {}", splits.join(", ")))?;
        for (p, part) in parts.iter().enumerate() {
            let s = &part.setup;
            let face = part.face.as_ref().map_or(String::new(), |f| {
                format!(", serving V's {} face", f.name())
            });
            print_line(&format!(
                "  part {p}: γ = {}°, φ = {}°{face}",
                s.gamma.to_degrees(),
                s.half_fov.to_degrees()
            ))?;
            if let Some(w) = &s.warp {
                print_line(&format!(
                    "    λ = {}, n = {}, warp depth d = {}",
                    w.lambda, w.near_distance, w.depth
                ))?;
                print_line(&format!("    rule: {}", w.formula))?;
                let inputs: Vec<String> = w
                    .inputs
                    .iter()
                    .map(|(name, value)| format!("{name} = {value}"))
                    .collect();
                print_line(&format!("    inputs: {}", inputs.join(", ")))?;
            }
            if let Some(report) = report_of(l, p) {
                let n = report.samples;
                print_line(&format!(
                    "    optimizer: {} samples ({} at shadow boundaries, {} on the image border, \
                     {} at depth discontinuities; {} grazed, left out of h)",
                    n.total(),
                    n.boundary,
                    n.screen_border,
                    n.discontinuity,
                    n.grazing
                ))?;
                match (report.initial_h, report.h) {
                    (Some(initial), Some(h)) => print_line(&format!(
                        "    h = {h:e} from {initial:e} (the uniform-limited window: {}), \
                         steps {:?}°",
                        report
                            .uniform_limited_h
                            .map_or("undefined".into(), |u| format!("{u:e}")),
                        report.steps_degrees
                    ))?,
                    _ => print_line(
                        "    nothing to optimize: the initial (uniform-limited) map is kept",
                    )?,
                }
            }
            if let Some(psm) = s.psm {
                print_line(&format!(
                    "    PSM: shift Δ = {}, near = {}, inverted = {}, directional = {}",
                    psm.shift, psm.near, psm.inverted, psm.directional
                ))?;
            }
            print_line(&format!(
                "    focus body B ({} vertices):",
                s.focus_body.len()
            ))?;
            for v in &s.focus_body {
                print_line(&format!("      {} {} {}", v.x, v.y, v.z))?;
            }
            match s.mapping {
                ShadowMapping::Projective(mapping) => {
                    for (name, m) in [
                        ("view", mapping.view()),
                        ("projection", mapping.projection()),
                    ] {
                        print_line(&format!("    {name} (row-major):"))?;
                        for row in row_major(&m).chunks(4) {
                            print_line(&format!(
                                "      {} {} {} {}",
                                row[0], row[1], row[2], row[3]
                            ))?;
                        }
                    }
                }
                ShadowMapping::Paraboloid(map) => {
                    let (near, far) = map.depth_range();
                    print_line(&format!(
                        "    paraboloid hemisphere (not projective), axis {}, near {near}, far {far}",
                        map.axis()
                    ))?;
                }
                ShadowMapping::Logarithmic(map) => {
                    print_line(&format!(
                        "    logarithmic map (not projective), λ = {}",
                        map.lambda()
                    ))?;
                }
            }
        }
    }
    if let Some(file) = setup_file {
        let options = resolved.frame_options();
        let setup = setup_for(scene, &options).map_err(|e| match e {
            SetupError::NotRepresentable { .. }
            | SetupError::Analysis(AnalysisError::Shadow(ShadowError::NotDefined { .. })) => {
                CliError::Input(format!("invalid --setup-json: {e}"))
            }
            other => CliError::Failure(anyhow::anyhow!("{other}")),
        })?;
        file.write(setup.to_json().as_bytes())?;
        if !args.json {
            print_line(&file.path().display().to_string())?;
        }
    }
    Ok(())
}
