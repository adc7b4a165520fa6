//! `shadowlab evaluate`: an engine's own shadow set-up (a set-up file) against the exact truth.

use std::path::PathBuf;

use shadowlab_analysis::evaluate::evaluate_observed;
use shadowlab_analysis::report::{self, technique_label};
use shadowlab_analysis::setup_file::load_setup;
use shadowlab_analysis::temporal::Stability;

use crate::args::EvaluateArgs;
use crate::error::CliError;
use crate::exports::{self, Exporter};
use crate::memory::{self, Workload};
use crate::output::{
    OutputDir, PICTURES, TEXT_BOUND, annotated_png_bound, png_bound, print_line, slug,
};
use crate::progress;
use crate::shadow_settings::load_scene_argument;

/// The report's machine-readable results, which list the exports.
const RESULTS_JSON: &str = "results.json";

pub(crate) fn run(args: &EvaluateArgs) -> Result<(), CliError> {
    let scene = load_scene_argument(&args.scene)?;
    let setup = load_setup(&args.setup)?;
    let frames = setup.frames.len() as u64;
    // Per frame the report and its pictures (each raw and annotated), and the exports.
    let (width, height) = (scene.camera.width, scene.camera.height);
    let maps = setup.most_maps() as u64;
    let export_bound = if args.export {
        exports::bound(&scene, frames, maps, setup.largest_map())
    } else {
        0
    };
    let estimate = frames
        .saturating_mul(
            TEXT_BOUND
                + PICTURES * (png_bound(width, height, 3) + annotated_png_bound(width, height)),
        )
        .saturating_add(export_bound);
    let target = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out/evaluate").join(slug(&scene.name, "scene")));
    let out = OutputDir::check(target, "--out", estimate)?;
    memory::check(
        &Workload::of(
            &scene,
            true,
            setup.largest_map(),
            maps,
            "camera.image",
            "the set-up's map_size",
        )
        .exporting(args.export),
        args.memory.memory_budget,
    )?;
    let mut set = out.begin("evaluate")?;
    let mut exporter = args.export.then(Exporter::new);
    let mut first_report = None;
    // Each frame's results.json, held back while exporting.
    let mut results = Vec::new();
    let bar = progress::bar("evaluate");
    bar.set_length(frames);
    let stability = evaluate_observed(&scene, &setup, true, |study, frame| {
        bar.set_position(frame.index as u64 + 1);
        let prefix = if frames > 1 {
            format!("frame-{:04}/", frame.index)
        } else {
            String::new()
        };
        let report =
            report::report(&study).map_err(|e| CliError::Failure(anyhow::anyhow!("{e}")))?;
        for (name, bytes) in report.files() {
            // With exports, results.json is written last, listing them all.
            if exporter.is_some() && name == RESULTS_JSON {
                results.push((format!("{prefix}{name}"), bytes));
            } else {
                set.add(&format!("{prefix}{name}"), &bytes)?;
            }
        }
        if let Some(exporter) = exporter.as_mut() {
            if frame.index == 0 {
                exporter.add_scene(&mut set, &scene)?;
            }
            exporter.add_frame(&mut set, &prefix, frame.eye, &study.truth)?;
            let combination = exports::combination_dir(&study.measurements[0].setting);
            exporter.add_shadows(
                &mut set,
                &format!("{prefix}{combination}"),
                (frame.eye, &study.truth),
                (&frame.shadows.lights, &frame.shadows.lit),
                frame.footprints,
            )?;
        }
        if frame.index == 0 {
            first_report = study.measurements.into_iter().next();
        }
        Ok::<(), CliError>(())
    });
    bar.finish_and_clear();
    let stability = stability?;
    if let Some(stability) = &stability {
        set.add("shimmer.csv", shimmer_csv(stability).as_bytes())?;
    }
    if let Some(exporter) = exporter {
        for (name, json) in &results {
            let json = String::from_utf8_lossy(json);
            set.add(
                name,
                exports::with_exports(&json, exporter.index())?.as_bytes(),
            )?;
        }
        exporter.finish(&mut set)?;
    }
    set.finish()?;
    if let Some(m) = first_report
        && let Ok(o) = &m.outcome
    {
        print_line(&format!(
            "{:<24} {:>5}² {} map(s) {:>8} misclassified ({} falsely lit, {} falsely shadowed; \
             {})",
            technique_label(m.setting.technique),
            m.setting.resolution,
            m.setting.partitions,
            o.errors.total(),
            o.errors.falsely_lit,
            o.errors.falsely_shadowed,
            o.causes
        ))?;
    }
    if let Some(Stability {
        shimmer: Ok(counts),
        surface_shimmer: None,
        ..
    }) = &stability
    {
        let total: u64 = counts.iter().sum();
        print_line(&format!(
            "shimmer: {total} pixels over {} frame pairs",
            counts.len()
        ))?;
    }
    print_line(&out.path().display().to_string())
}

/// The shimmering pixels between consecutive frames (first light), one row per pair.
fn shimmer_csv(stability: &Stability) -> String {
    let mut csv = String::from("frame,shimmering_pixels\n");
    match &stability.shimmer {
        Ok(counts) => {
            for (k, count) in counts.iter().enumerate() {
                csv.push_str(&format!("{},{count}\n", k + 1));
            }
        }
        Err(reason) => csv.push_str(&format!("# not defined: {reason}\n")),
    }
    csv
}
