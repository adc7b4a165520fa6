//! `shadowlab render`: one scene, one technique, the pictures.

use std::path::PathBuf;

use shadowlab_analysis::report::filter_label;
use shadowlab_analysis::study::{Setting, footprints_of};
use shadowlab_analysis::truth::{exact_truth, scene_bvh};
use shadowlab_raster::image_out;
use shadowlab_scene::Scene;
use shadowlab_shadow::{Frame, FrameOptions, Technique, render_frame, scene_eye, view};

use crate::args::RenderArgs;
use crate::error::CliError;
use crate::exports::{self, Exporter};
use crate::memory::{self, Workload};
use crate::output::{OutputDir, annotated_png_bound, png_bound, print_line, slug};
use crate::progress;
use crate::shadow_settings::resolve;

pub(crate) fn run(args: &RenderArgs) -> Result<(), CliError> {
    let resolved = resolve(&args.shadow)?;
    let scene = &resolved.scene;
    let technique = resolved.plan.technique;
    let options = resolved.frame_options();
    let target = args.out.clone().unwrap_or_else(|| {
        PathBuf::from("out/render").join(slug(
            &format!("{}-{}", scene.name, technique.key()),
            "render",
        ))
    });
    let maps = u64::try_from(resolved.plan.partitions * technique.most_maps_per_partition())
        .unwrap_or(u64::MAX);
    let setting = Setting {
        technique,
        resolution: resolved.resolution,
        partitions: resolved.plan.partitions,
        filter: resolved.lookup.filter,
    };
    let export_bound = if args.export {
        exports::bound(scene, 1, maps, resolved.resolution)
    } else {
        0
    };
    // Raw and annotated: the eye view, and per map its depth (16-bit) and its light view.
    let (width, height, side) = (scene.camera.width, scene.camera.height, resolved.resolution);
    let estimate = png_bound(width, height, 3)
        + annotated_png_bound(width, height)
        + maps.saturating_mul(png_bound(side, side, 2 + 3) + annotated_png_bound(side, side))
        + export_bound;
    // Memory before disk: a run that cannot fit in memory is refused whatever the disk holds.
    memory::check(
        &Workload::of(
            scene,
            false,
            resolved.resolution,
            maps,
            "camera.image",
            "--resolution, --partitions",
        )
        .exporting(args.export),
        args.memory.memory_budget,
    )?;
    let out = OutputDir::check(target, "--out", estimate)?;
    let spinner = progress::spinner(&format!("render: {technique} {}²", resolved.resolution));
    let frame = render_frame(scene, &options);
    spinner.finish_and_clear();
    let frame =
        frame.map_err(|e| CliError::Input(format!("{} with {technique}: {e}", scene.name)))?;
    let image_failure =
        |e: shadowlab_raster::RasterError| CliError::Failure(anyhow::anyhow!("{e}"));
    let picture_failure = |e: shadowlab_plot::PlotError| CliError::Failure(anyhow::anyhow!("{e}"));
    let faces = frame.lights.first().map_or(0, |light| light.maps.len());
    let settings = settings_line(scene, &options, faces);
    let mut files = vec![
        (
            "eye.png".to_string(),
            image_out::rgb_png(&view::shade(&frame, scene), width, height)
                .map_err(image_failure)?,
        ),
        (
            "pictures/eye.png".to_string(),
            view::eye_picture(&frame, scene, &settings).map_err(picture_failure)?,
        ),
    ];
    let eye = scene_eye(scene);
    let single = frame.lights.len() == 1 && frame.lights[0].maps.len() == 1;
    for (l, shadow) in frame.lights.iter().enumerate() {
        for (p, (partition, map)) in shadow.maps.iter().enumerate() {
            let side = map.resolution;
            let suffix = format!("light{l}-part{p}");
            files.push((
                format!("shadowmap-{suffix}.png"),
                image_out::depth_png16(&map.nearest, side, side).map_err(image_failure)?,
            ));
            let name = if single {
                "lightview.png".to_string()
            } else {
                format!("lightview-{suffix}.png")
            };
            files.push((
                format!("pictures/{name}"),
                view::light_view_picture(map, &eye, &scene.name, &settings)
                    .map_err(picture_failure)?,
            ));
            files.push((
                name,
                image_out::rgb_png(&view::light_view(map, &eye), side, side)
                    .map_err(image_failure)?,
            ));
            let setup = &map.setup;
            let warp = setup.warp.as_ref().map_or(String::new(), |w| {
                format!(", λ = {:.6}, n' = {:.6}", w.lambda, w.near_distance)
            });
            print_line(&format!(
                "light {l}, part {p} (eye depths {:.4}–{:.4}): {}, γ = {:.4}°{warp}",
                partition.near,
                partition.far,
                setup.technique,
                setup.gamma.to_degrees()
            ))?;
        }
    }
    let visible = frame
        .eye
        .triangle
        .iter()
        .filter(|t| **t != shadowlab_raster::NO_TRIANGLE)
        .count();
    for (l, lit) in frame.lit.iter().enumerate() {
        let shadowed: f64 = frame
            .eye
            .triangle
            .iter()
            .zip(lit)
            .filter(|(t, _)| **t != shadowlab_raster::NO_TRIANGLE)
            .map(|(_, v)| 1.0 - v)
            .sum();
        #[expect(clippy::cast_precision_loss, reason = "a pixel count")]
        let share = shadowed / visible.max(1) as f64;
        print_line(&format!(
            "light {l}: {:.2} % of the visible pixels in shadow",
            100.0 * share
        ))?;
    }
    let t = frame.timings;
    print_line(&format!(
        "time: eye pass {:.2} ms, planning {:.3} ms, shadow pass {:.2} ms, lookup {:.2} ms",
        t.eye_pass.as_secs_f64() * 1e3,
        t.planning.as_secs_f64() * 1e3,
        t.shadow_pass.as_secs_f64() * 1e3,
        t.lookup.as_secs_f64() * 1e3
    ))?;
    let mut set = out.begin("render")?;
    for (name, bytes) in &files {
        set.add(name, bytes)?;
    }
    if args.export {
        export(
            &mut set,
            scene,
            (&frame, &options),
            &exports::combination_dir(&setting),
        )?;
    }
    set.finish()?;
    for (file, _) in &files {
        print_line(&out.path().join(file).display().to_string())?;
    }
    if args.export {
        print_line(&out.path().join(exports::EXPORT_DIR).display().to_string())?;
    }
    Ok(())
}

/// The settings a frame was made with, as one line under its pictures' titles.
/// `faces` is how many maps the first light's partitions made (a point light's cube faces or
/// paraboloid hemispheres).
fn settings_line(scene: &Scene, options: &FrameOptions, faces: usize) -> String {
    let partitions = match (options.plan.technique, options.plan.partitions) {
        (Technique::Cube, _) => format!("{faces} cube faces per light"),
        (Technique::DualParaboloid, _) => format!("{faces} paraboloid hemispheres per light"),
        (_, 1) => "1 map per light".to_owned(),
        (_, k) => format!("{k} maps per light ({} splits)", options.plan.splits),
    };
    format!(
        "{}² shadow map, {partitions}, filter {}, bias {}, format {}, focus {}; {}×{} eye image",
        options.resolution,
        filter_label(&options.lookup.filter),
        options.lookup.bias,
        options.format.key_name(),
        options.plan.focus.key(),
        scene.camera.width,
        scene.camera.height
    )
}

/// The frame's per-pixel results (`--export`): eye pass, exact truth, lookups, footprints, maps.
fn export(
    set: &mut crate::output::OutputSet<'_>,
    scene: &Scene,
    (frame, options): (&Frame, &FrameOptions),
    combination: &str,
) -> Result<(), CliError> {
    let spinner = progress::spinner("render: the exact truth for --export");
    let truth = scene_bvh(scene).and_then(|bvh| exact_truth(scene, &frame.eye, &bvh));
    spinner.finish_and_clear();
    let truth = truth.map_err(|e| CliError::Input(format!("{}: {e}", scene.name)))?;
    let footprints = footprints_of(scene, &frame.eye, &frame.lights);
    let mut exporter = Exporter::new();
    exporter.add_scene(set, scene)?;
    exporter.add_frame(set, "", &frame.eye, &truth)?;
    exporter.add_setup(set, combination, scene, options)?;
    exporter.add_shadows(
        set,
        combination,
        (&frame.eye, &truth),
        (&frame.lights, &frame.lit),
        &footprints,
    )?;
    exporter.finish(set)
}
