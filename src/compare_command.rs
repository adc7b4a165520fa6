//! `shadowlab compare`: one scene, several techniques, one labelled picture.

use anyhow::Context;
use shadowlab_raster::{DepthFormat, NO_TRIANGLE};
use shadowlab_shadow::{Bias, Filter, FrameOptions, Lookup, PlanOptions, render_frame, view};
use tiny_skia::{Color, Pixmap, PixmapPaint, Transform};

use crate::args::{COMPARE_TECHNIQUES, CompareArgs};
use crate::error::CliError;
use crate::memory::{self, Workload};
use crate::output::{OutputFile, png_bound, print_line};
use crate::progress;
use crate::shadow_settings::{load_scene_argument, optimizer_flags, technique_list};

/// Height of a picture's label, in pixels.
const LABEL_HEIGHT: u32 = 30;
/// Space between pictures.
const GAP: u32 = 6;

pub(crate) fn run(args: &CompareArgs) -> Result<(), CliError> {
    let scene = load_scene_argument(&args.scene)?;
    let (width, height) = (scene.camera.width, scene.camera.height);
    let [cx, cy, cw, ch] = args.crop.unwrap_or([0, 0, width, height]);
    if cx + cw > width || cy + ch > height {
        return Err(CliError::Input(format!(
            "invalid --crop: {cw}x{ch} at ({cx}, {cy}) does not fit the {width}x{height} image"
        )));
    }
    let techniques = technique_list(
        &scene,
        args.techniques.as_deref(),
        COMPARE_TECHNIQUES,
        &args.stated,
    )?;
    let optimal = optimizer_flags(&args.optimizer)?;
    let columns = args
        .columns
        .min(u32::try_from(techniques.len()).unwrap_or(1))
        .max(1);
    let rows = u32::try_from(techniques.len())
        .unwrap_or(1)
        .div_ceil(columns);
    let (tile_w, tile_h) = (cw, ch + LABEL_HEIGHT);
    let mut canvas = Pixmap::new(
        columns * tile_w + (columns + 1) * GAP,
        rows * tile_h + (rows + 1) * GAP,
    )
    .ok_or_else(|| CliError::Input("invalid --crop: the picture would be empty".into()))?;
    let out = OutputFile::check(
        args.out.clone(),
        "--out",
        png_bound(canvas.width(), canvas.height(), 4),
    )?;
    memory::check(
        &Workload::of(
            &scene,
            false,
            args.resolution,
            1,
            "camera.image",
            "--resolution",
        ),
        args.memory.memory_budget,
    )?;
    canvas.fill(Color::WHITE);
    for (k, technique) in techniques.iter().enumerate() {
        let options = FrameOptions {
            plan: PlanOptions {
                focus: args.focus,
                optimal,
                ..PlanOptions::new(*technique)
            },
            resolution: args.resolution,
            format: DepthFormat::F32,
            lookup: Lookup::new(Bias::DEFAULT, Filter::Nearest),
            snap_texels: 0,
        };
        let k = u32::try_from(k).unwrap_or(0);
        let (x, y) = (
            GAP + (k % columns) * (tile_w + GAP),
            GAP + (k / columns) * (tile_h + GAP),
        );
        let spinner = progress::spinner(&format!("compare: {technique}"));
        let frame = render_frame(&scene, &options);
        spinner.finish_and_clear();
        let label = match frame {
            Ok(frame) => {
                let shaded = view::shade(&frame, &scene);
                let mut tile = Pixmap::new(cw, ch).expect("a non-empty crop");
                let pixels = tile.pixels_mut();
                for v in 0..ch {
                    for u in 0..cw {
                        // The frame's rows are bottom-up.
                        let [r, g, b] = shaded[((height - 1 - (cy + v)) * width + cx + u) as usize];
                        pixels[(v * cw + u) as usize] =
                            tiny_skia::ColorU8::from_rgba(r, g, b, 255).premultiply();
                    }
                }
                draw(&mut canvas, &tile, x, y)?;
                let visible = frame
                    .eye
                    .triangle
                    .iter()
                    .filter(|t| **t != NO_TRIANGLE)
                    .count()
                    .max(1);
                let shadowed: f64 = frame
                    .eye
                    .triangle
                    .iter()
                    .zip(&frame.lit[0])
                    .filter(|(t, _)| **t != NO_TRIANGLE)
                    .map(|(_, l)| 1.0 - l)
                    .sum();
                #[expect(clippy::cast_precision_loss, reason = "a pixel count")]
                let share = 100.0 * shadowed / visible as f64;
                print_line(&format!(
                    "{technique}: {share:.2} % of the visible pixels in shadow, shadow pass {:.1} ms",
                    frame.timings.shadow_pass.as_secs_f64() * 1e3
                ))?;
                format!("{technique}")
            }
            Err(e) if e.undefined_reason().is_some() => {
                print_line(&format!("{technique}: not defined for this scene ({e})"))?;
                format!("{technique}: not defined here")
            }
            Err(e) => {
                return Err(CliError::Input(format!(
                    "{} with {technique}: {e}",
                    scene.name
                )));
            }
        };
        let text = label_pixmap(&label, tile_w)?;
        draw(&mut canvas, &text, x, y + ch)?;
    }
    let png = canvas.encode_png().context("cannot encode the picture")?;
    out.write(&png)?;
    print_line(&out.path().display().to_string())
}

/// A label as a picture, rendered from SVG with the figures' embedded font.
fn label_pixmap(text: &str, width: u32) -> Result<Pixmap, CliError> {
    let escaped = text
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{LABEL_HEIGHT}"><text x="{}" y="21" font-family="DejaVu Sans" font-size="15" text-anchor="middle" fill="rgb(34,34,34)">{escaped}</text></svg>"#,
        width / 2
    );
    let png = shadowlab_plot::render_png(&svg)
        .map_err(|e| CliError::Failure(anyhow::anyhow!("label: {e}")))?;
    let pixmap = Pixmap::decode_png(&png).context("cannot decode a label")?;
    debug_assert_eq!((pixmap.width(), pixmap.height()), (width, LABEL_HEIGHT));
    Ok(pixmap)
}

/// Draws `picture` onto `canvas` with its top left at `(x, y)`.
fn draw(canvas: &mut Pixmap, picture: &Pixmap, x: u32, y: u32) -> Result<(), CliError> {
    let position = |v: u32| {
        i32::try_from(v)
            .map_err(|_| CliError::Input("invalid --crop: the picture is too large".into()))
    };
    canvas.draw_pixmap(
        position(x)?,
        position(y)?,
        picture.as_ref(),
        &PixmapPaint::default(),
        Transform::identity(),
        None,
    );
    Ok(())
}
