//! `shadowlab analyze`, `sweep-angle` and `temporal`: the measurements, written as reports.

use std::path::PathBuf;

use shadowlab_analysis::report::{filter_label, technique_label};
use shadowlab_analysis::{bias_sweep, report, study, sweep, temporal};
use shadowlab_raster::DepthFormat;
use shadowlab_scene::Scene;
use shadowlab_shadow::{Bias, Splits};

use crate::args::{
    ALL_TECHNIQUES, AnalyzeArgs, MemoryArgs, SWEEP_TECHNIQUES, SceneArg, StudyView, SweepArgs,
    TEMPORAL_TECHNIQUES, TemporalArgs,
};
use crate::error::CliError;
use crate::exports::{self, Exporter};
use crate::memory::{self, Workload};
use crate::output::{
    OutputDir, PICTURES, TEXT_BOUND, annotated_png_bound, png_bound, print_line, slug,
};
use crate::progress;
use crate::shadow_settings::{
    load_scene_argument, optimizer_flags, study_techniques, technique_list,
};

/// The output set of a study command: `--out`, or `out/<command>/<scene>` with the scene's name
/// made safe as a path component; checked before any work.
fn output_dir(
    out: Option<&PathBuf>,
    command: &str,
    scene: &Scene,
    estimate: u64,
) -> Result<OutputDir, CliError> {
    let target = out.cloned().unwrap_or_else(|| {
        PathBuf::from("out")
            .join(command)
            .join(slug(&scene.name, "scene"))
    });
    OutputDir::check(target, "--out", estimate)
}

pub(crate) fn analyze(args: &AnalyzeArgs) -> Result<(), CliError> {
    let scene = load_scene_argument(&args.scene)?;
    let techniques = technique_list(
        &scene,
        args.techniques.as_deref(),
        ALL_TECHNIQUES,
        &args.stated,
    )?;
    let options = study::StudyOptions {
        techniques,
        resolutions: args.resolutions.clone(),
        partitions: args.partitions.iter().map(|s| *s as usize).collect(),
        splits: args.split_scheme.unwrap_or(Splits::DEFAULT),
        filters: args.filters.clone(),
        bias: args.bias.unwrap_or(Bias::DEFAULT),
        format: DepthFormat::F32,
        map_truth: args.map_truth,
        // Pictures at the resolution closest to 1024 texels.
        pictures_at: args
            .resolutions
            .iter()
            .copied()
            .min_by_key(|r| r.abs_diff(1024)),
        optimal: optimizer_flags(&args.optimizer)?,
        focus: args.focus,
        timing_runs: args.timing_runs,
    };
    let largest_map = options
        .resolutions
        .iter()
        .copied()
        .chain(std::iter::once(options.optimal.initial_resolution))
        .max()
        .unwrap_or(0);
    let most_per_partition = options
        .techniques
        .iter()
        .map(|t| t.most_maps_per_partition())
        .max()
        .unwrap_or(1);
    let maps = (options.partitions.iter().copied().max().unwrap_or(1) * most_per_partition) as u64;
    // Per technique at the picture resolution, each picture raw and annotated, and the exports.
    let (width, height) = (scene.camera.width, scene.camera.height);
    let annotated = annotated_png_bound(width, height);
    let export_bound = if args.export {
        let combinations = study::settings(&options).len() as u64;
        exports::bound(&scene, combinations, maps, largest_map)
    } else {
        0
    };
    let estimate = TEXT_BOUND
        + PICTURES * options.techniques.len() as u64 * (png_bound(width, height, 3) + annotated)
        + export_bound;
    let out = output_dir(args.out.as_ref(), "analyze", &scene, estimate)?;
    memory::check(
        &Workload::of(
            &scene,
            true,
            largest_map,
            maps,
            "camera.image",
            "--resolutions, --partitions",
        )
        .exporting(args.export),
        args.memory.memory_budget,
    )?;
    if let Some(biases) = &args.biases {
        return sweep_biases(&scene, &options, biases, out);
    }
    let bar = progress::bar("analyze");
    let mut set = out.begin("analyze")?;
    let mut exporter = args.export.then(Exporter::new);
    let mut frame_exported = false;
    // The bar names the combination being measured.
    let result = study::run_observed(
        &scene,
        &options,
        |done, total, next| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            if let Some(setting) = next {
                bar.set_message(format!(
                    "analyze: {} {}² {} map(s) {}",
                    technique_label(setting.technique),
                    setting.resolution,
                    setting.partitions,
                    filter_label(&setting.filter)
                ));
            }
        },
        |observed| {
            let Some(exporter) = exporter.as_mut() else {
                return Ok(());
            };
            let eye = &observed.eye.image;
            if !frame_exported {
                exporter.add_scene(&mut set, &scene)?;
                exporter.add_frame(&mut set, "", eye, observed.truth)?;
                frame_exported = true;
            }
            let combination = exports::combination_dir(observed.setting);
            exporter.add_setup(
                &mut set,
                &combination,
                &scene,
                &study::frame_options(&options, observed.setting),
            )?;
            exporter.add_shadows(
                &mut set,
                &combination,
                (eye, observed.truth),
                (&observed.shadows.lights, &observed.shadows.lit),
                observed.footprints,
            )?;
            Ok::<(), Stop>(())
        },
    );
    bar.finish_and_clear();
    let study = result.map_err(|stop| match stop {
        Stop::Analysis(e) => CliError::Input(format!("{}: {e}", scene.name)),
        Stop::Output(e) => e,
    })?;
    let mut report =
        report::report(&study).map_err(|e| CliError::Failure(anyhow::anyhow!("{e}")))?;
    if let Some(exporter) = &exporter {
        report.json = exports::with_exports(&report.json, exporter.index())?;
    }
    let files = report.files();
    for (name, bytes) in &files {
        set.add(name, bytes)?;
    }
    if let Some(exporter) = exporter {
        exporter.finish(&mut set)?;
    }
    set.finish()?;
    for m in report::pareto_front(&study) {
        let o = m.outcome.as_ref().expect("defined");
        print_line(&format!(
            "{:<24} {:>5}² {} map(s) {:<10} {:>8} misclassified  {:>8.1} ms ± {:.1}",
            technique_label(m.setting.technique),
            m.setting.resolution,
            m.setting.partitions,
            filter_label(&m.setting.filter),
            o.errors.total(),
            o.time().as_secs_f64() * 1e3,
            o.time_spread.as_secs_f64() * 1e3
        ))?;
    }
    print_line(&out.path().join("report.md").display().to_string())
}

/// `analyze --biases`: the study at each bias (the default ladder if none is named), written as
/// the bias sweep's report.
fn sweep_biases(
    scene: &Scene,
    options: &study::StudyOptions,
    biases: &[Bias],
    out: OutputDir,
) -> Result<(), CliError> {
    let biases = if biases.is_empty() {
        bias_sweep::default_biases()
    } else {
        biases.to_vec()
    };
    let bar = progress::bar("bias sweep");
    let points = bias_sweep::bias_sweep(scene, options, &biases, |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let points = points.map_err(|e| CliError::Input(format!("{}: --biases: {e}", scene.name)))?;
    let mut set = out.begin("analyze")?;
    for (name, bytes) in bias_sweep::write(&scene.name, &points) {
        set.add(&name, &bytes)?;
    }
    set.finish()?;
    print_line(&out.path().join("bias-sweep.md").display().to_string())
}

/// Why `analyze` stopped: the study's error, or an output's while exporting.
enum Stop {
    Analysis(shadowlab_analysis::AnalysisError),
    Output(CliError),
}

impl From<shadowlab_analysis::AnalysisError> for Stop {
    fn from(error: shadowlab_analysis::AnalysisError) -> Self {
        Self::Analysis(error)
    }
}

impl From<CliError> for Stop {
    fn from(error: CliError) -> Self {
        Self::Output(error)
    }
}

/// The scene of `sweep-angle` and `temporal`, at the eye image size asked for.
fn study_scene(scene: &SceneArg, view: &StudyView) -> Result<Scene, CliError> {
    let mut scene = load_scene_argument(scene)?;
    if let Some((width, height)) = view.eye_size {
        (scene.camera.width, scene.camera.height) = (width, height);
    }
    Ok(scene)
}

/// The memory check of `sweep-angle` and `temporal`: one map at a time beside a study's eye buffers.
fn study_memory(scene: &Scene, view: &StudyView, memory: &MemoryArgs) -> Result<(), CliError> {
    memory::check(
        &Workload::of(
            scene,
            true,
            view.resolution,
            1,
            "--eye-size or camera.image",
            "--resolution",
        ),
        memory.memory_budget,
    )
}

pub(crate) fn sweep_angle(args: &SweepArgs) -> Result<(), CliError> {
    let scene = study_scene(&args.scene, &args.view)?;
    let techniques = study_techniques(&scene, args.techniques.as_deref(), SWEEP_TECHNIQUES)?;
    let side = if args.behind {
        sweep::Side::Behind
    } else {
        sweep::Side::Front
    };
    let angles = sweep::default_angles();
    let out = output_dir(args.out.as_ref(), "sweep", &scene, TEXT_BOUND)?;
    study_memory(&scene, &args.view, &args.memory)?;
    let bar = progress::bar("sweep");
    let result = sweep::sweep(
        &scene,
        &techniques,
        &angles,
        side,
        args.view.resolution,
        args.view.filter,
        |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    );
    bar.finish_and_clear();
    let points = result.map_err(|e| CliError::Input(format!("{}: {e}", scene.name)))?;
    let written = sweep::write(&scene.name, &args.view.filter, &points)
        .map_err(|e| CliError::Failure(anyhow::anyhow!("{e}")))?;
    out.write("sweep-angle", &written)?;
    for (name, _) in &written {
        print_line(&out.path().join(name).display().to_string())?;
    }
    Ok(())
}

pub(crate) fn temporal(args: &TemporalArgs) -> Result<(), CliError> {
    let scene = study_scene(&args.scene, &args.view)?;
    let techniques = study_techniques(&scene, args.techniques.as_deref(), TEMPORAL_TECHNIQUES)?;
    let out = output_dir(args.out.as_ref(), "temporal", &scene, TEXT_BOUND)?;
    study_memory(&scene, &args.view, &args.memory)?;
    let bar = progress::bar("temporal");
    let result = temporal::temporal(
        &scene,
        &techniques,
        args.frames as usize,
        args.view.resolution,
        args.view.filter,
        |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    );
    bar.finish_and_clear();
    let stability = result.map_err(|e| CliError::Input(format!("{}: {e}", scene.name)))?;
    let written = temporal::write(&scene.name, &args.view.filter, &stability);
    out.write("temporal", &written)?;
    for (name, _) in &written {
        print_line(&out.path().join(name).display().to_string())?;
    }
    Ok(())
}
