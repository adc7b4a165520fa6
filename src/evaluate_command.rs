//! `shadowlab evaluate`: an engine's own shadow set-up (a set-up file) against the exact truth.

use std::path::PathBuf;

use shadowlab_analysis::evaluate::evaluate;
use shadowlab_analysis::report::{self, technique_label};
use shadowlab_analysis::setup_file::{SetupError, load_setup};
use shadowlab_analysis::temporal::Stability;

use crate::args::EvaluateArgs;
use crate::error::CliError;
use crate::memory::{self, Workload};
use crate::output::{OutputDir, TEXT_BOUND, png_bound, print_line, slug};
use crate::progress;
use crate::shadow_settings::load_scene_argument;

/// A set-up file's error: an input error naming the file and the field (exit 2), unless the
/// operating system failed to read a file that is there (exit 1), as for scene files.
fn setup_error(error: &SetupError) -> CliError {
    CliError::from_input_file(error)
}

pub(crate) fn run(args: &EvaluateArgs) -> Result<(), CliError> {
    let scene = load_scene_argument(&args.scene)?;
    let setup = load_setup(&args.setup).map_err(|e| setup_error(&e))?;
    let frames = setup.frames.len() as u64;
    // Per frame the report and its pictures: three raw and three annotated.
    let (width, height) = (scene.camera.width, scene.camera.height);
    let annotated = png_bound(
        (width + 2 * shadowlab_plot::MARGIN).max(1200),
        height + 320,
        4,
    );
    let estimate =
        frames.saturating_mul(TEXT_BOUND + 3 * (png_bound(width, height, 3) + annotated));
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
            setup.most_maps() as u64,
            "camera.image",
            "the set-up's map_size",
        ),
        args.memory.memory_budget,
    )?;
    let mut set = out.begin("evaluate")?;
    let mut written: Result<(), CliError> = Ok(());
    let mut first_report = None;
    let bar = progress::bar("evaluate");
    bar.set_length(frames);
    let stability = evaluate(&scene, &setup, true, |k, study| {
        bar.set_position(k as u64 + 1);
        if written.is_err() {
            return;
        }
        let prefix = if frames > 1 {
            format!("frame-{k:04}/")
        } else {
            String::new()
        };
        written = report::report(&study)
            .map_err(|e| CliError::Failure(anyhow::anyhow!("{e}")))
            .and_then(|report| {
                for (name, bytes) in report.files() {
                    set.add(&format!("{prefix}{name}"), &bytes)?;
                }
                Ok(())
            });
        if k == 0 {
            first_report = study.measurements.into_iter().next();
        }
    });
    bar.finish_and_clear();
    let stability = stability.map_err(|e| setup_error(&e))?;
    written?;
    if let Some(stability) = &stability {
        set.add("shimmer.csv", shimmer_csv(stability).as_bytes())?;
    }
    set.finish()?;
    if let Some(m) = first_report
        && let Ok(o) = &m.outcome
    {
        print_line(&format!(
            "{:<24} {:>5}² {} map(s) {:>8} misclassified ({} falsely lit, {} falsely shadowed)",
            technique_label(m.setting.technique),
            m.setting.resolution,
            m.setting.partitions,
            o.errors.total(),
            o.errors.falsely_lit,
            o.errors.falsely_shadowed
        ))?;
    }
    if let Some(Stability {
        shimmer: Ok(counts),
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
