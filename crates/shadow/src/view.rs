//! Pictures of a frame: the shaded eye view, and the light's view of a shadow map with the view
//! frustum and the focus body outlined, as the papers draw them — raw ([`shade`], [`light_view`]:
//! one pixel per pixel, nothing drawn on them) and annotated ([`eye_picture`],
//! [`light_view_picture`]: the same pixels under a title naming scene and technique and a line of
//! settings, the light view with the legend of its colours; drawn by `shadowlab-plot`).

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use shadowlab_hull::{ConvexHull2, convex_hull_2d};
use shadowlab_plot::{Color as PlotColor, Image, Picture, PlotError, Swatch, render_picture};
use shadowlab_raster::{EyeImage, NO_TRIANGLE};
use shadowlab_scene::Scene;
use tiny_skia::{Color, LineCap, Paint, PathBuilder, Pixmap, Stroke, Transform};

use crate::input::Eye;
use crate::map::ShadowMap;
use crate::render::{Frame, LightShadow};

/// Albedos of the mesh groups, in turn (linear, 0–1): muted, distinguishable, printable.
const PALETTE: [[f64; 3]; 8] = [
    [0.72, 0.70, 0.64],
    [0.80, 0.48, 0.32],
    [0.36, 0.56, 0.78],
    [0.56, 0.72, 0.40],
    [0.86, 0.74, 0.36],
    [0.62, 0.46, 0.72],
    [0.40, 0.70, 0.70],
    [0.84, 0.56, 0.64],
];
/// The background where no surface is seen.
const SKY: [f64; 3] = [0.83, 0.88, 0.94];
/// Light reaching every surface (no shadow test).
const AMBIENT: f64 = 0.28;
/// The direct light's strength, split among the lights.
const DIRECT: f64 = 0.85;
/// Samples along each frustum edge (the logarithmic map bends them).
const EDGE_SAMPLES: u32 = 48;
/// The light view's outline of the view frustum's edges.
pub const FRUSTUM_COLOUR: [u8; 3] = [215, 40, 40];
/// The light view's outline of the focus body B.
pub const FOCUS_BODY_COLOUR: [u8; 3] = [40, 90, 220];
/// The light view's grey at half the depth range, for its legend.
const MID_DEPTH_GREY: [u8; 3] = [175, 175, 175];

/// The eye view shaded with its shadows: per-group albedo × (ambient + Σ direct·cos·lit), the
/// normal turned toward the eye; 8-bit sRGB, row 0 at the bottom.
#[must_use]
pub fn shade(frame: &Frame, scene: &Scene) -> Vec<[u8; 3]> {
    shade_eye(&frame.eye, &frame.lights, &frame.lit, scene)
}

/// [`shade`] for an eye pass and the shadows made for it apart (a study's
/// [`crate::render_shadows`]): `lights` and `lit` as [`crate::Shadows`] holds them.
#[must_use]
pub fn shade_eye(
    image: &EyeImage,
    lights: &[LightShadow],
    lit: &[Vec<f64>],
    scene: &Scene,
) -> Vec<[u8; 3]> {
    let eye = scene.camera.pose.eye();
    let groups = scene.mesh.groups();
    let direct = DIRECT / lights.len().max(1) as f64;
    // In parallel, in pixel order.
    (0..image.triangle.len())
        .into_par_iter()
        .map(|pixel| {
            let triangle = image.triangle[pixel];
            if triangle == NO_TRIANGLE {
                return to_srgb8(SKY);
            }
            let position = image.position[pixel];
            let mut normal = image.normal[pixel];
            if normal.dot(eye - position) < 0.0 {
                normal = -normal;
            }
            let light: f64 = lights
                .iter()
                .zip(lit)
                .map(|(shadow, lit)| {
                    let toward = shadow.light.toward_from(position);
                    let reached = if shadow.light.reaches(position) {
                        1.0
                    } else {
                        0.0
                    };
                    direct * normal.dot(toward).max(0.0) * lit[pixel] * reached
                })
                .sum();
            let albedo = PALETTE[groups[triangle as usize] as usize % PALETTE.len()];
            to_srgb8(albedo.map(|a| a * (AMBIENT + light)))
        })
        .collect()
}

/// The shadow map as the light sees it: stored depth as grey (near dark, empty white), the view
/// frustum's edges in red and the outline of the focus body B in blue, drawn through the map's
/// own mapping (so the logarithmic map bends them). 8-bit sRGB, `resolution²`, row 0 at the bottom.
#[must_use]
pub fn light_view(map: &ShadowMap, eye: &Eye) -> Vec<[u8; 3]> {
    let side = map.resolution;
    let mut pixmap = Pixmap::new(side, side).expect("a non-empty map");
    for (k, pixel) in pixmap.pixels_mut().iter_mut().enumerate() {
        // Pixmaps are top-down; the map's rows bottom-up.
        let (i, j) = (k % side as usize, side as usize - 1 - k / side as usize);
        let depth = map.nearest[j * side as usize + i];
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "in [0, 255]"
        )]
        let grey = (depth.clamp(0.0, 1.0).powf(0.6) * 235.0 + 20.0).round() as u8;
        *pixel = tiny_skia::ColorU8::from_rgba(grey, grey, grey, 255).premultiply();
    }
    let to_pixel = |world: DVec3| {
        map.setup
            .mapping
            .window(world)
            .map(|w| DVec2::new(w.x * f64::from(side), (1.0 - w.y) * f64::from(side)))
    };
    let width = (f64::from(side) / 256.0).max(1.0);
    // B's outline: the convex hull of its vertices on the map.
    let outline: Vec<DVec2> = map
        .setup
        .focus_body
        .iter()
        .filter_map(|p| to_pixel(*p))
        .collect();
    if let Ok(ConvexHull2::Polygon(polygon)) = convex_hull_2d(&outline) {
        let mut closed = polygon.vertices().to_vec();
        closed.push(closed[0]);
        stroke(
            &mut pixmap,
            &[closed],
            Color::from_rgba8(
                FOCUS_BODY_COLOUR[0],
                FOCUS_BODY_COLOUR[1],
                FOCUS_BODY_COLOUR[2],
                255,
            ),
            width * 1.5,
        );
    }
    // The view frustum's twelve edges: corners whose indices differ in one bit.
    let corners = eye.frustum().corners().to_owned();
    let mut edges = Vec::new();
    for a in 0..8usize {
        for bit in [1, 2, 4] {
            let b = a | bit;
            if b != a {
                let line: Vec<DVec2> = (0..=EDGE_SAMPLES)
                    .filter_map(|s| {
                        let t = f64::from(s) / f64::from(EDGE_SAMPLES);
                        to_pixel(corners[a].lerp(corners[b], t))
                    })
                    .collect();
                edges.push(line);
            }
        }
    }
    stroke(
        &mut pixmap,
        &edges,
        Color::from_rgba8(FRUSTUM_COLOUR[0], FRUSTUM_COLOUR[1], FRUSTUM_COLOUR[2], 255),
        width,
    );
    let rows: Vec<[u8; 3]> = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue()]
        })
        .collect();
    // Back to bottom-up rows.
    rows.chunks(side as usize)
        .rev()
        .flatten()
        .copied()
        .collect()
}

/// The technique of a frame's first map (every map of a frame has the same).
fn technique(lights: &[LightShadow]) -> String {
    lights.first().and_then(|l| l.maps.first()).map_or_else(
        || "no light".to_owned(),
        |(_, map)| map.setup.technique.to_string(),
    )
}

fn swatch(colour: [u8; 3], label: &str) -> Swatch {
    Swatch {
        color: PlotColor(colour[0], colour[1], colour[2]),
        label: label.to_owned(),
    }
}

/// [`shade`] as an annotated PNG: titled with the scene and the technique, `settings` (the
/// options the frame was made with, as the caller names them) under the title, and the sky's
/// colour in the legend.
///
/// # Errors
/// `shadowlab-plot`'s, if the picture cannot be drawn (a bug).
pub fn eye_picture(frame: &Frame, scene: &Scene, settings: &str) -> Result<Vec<u8>, PlotError> {
    let pixels = shade(frame, scene);
    render_picture(&Picture {
        title: format!(
            "{} — {}: the view with its shadows",
            scene.name,
            technique(&frame.lights)
        ),
        subtitle: settings.to_owned(),
        image: Image::bottom_up(frame.eye.width, frame.eye.height, &pixels)?,
        colour_bar: None,
        legend: vec![swatch(to_srgb8(SKY), "nothing seen (sky)")],
    })
}

/// [`light_view`] as an annotated PNG: titled with the scene (`scene`, its name) and the map's
/// technique, `settings` under the title, and the legend of its colours (the frustum, B, the
/// depth grey).
///
/// # Errors
/// `shadowlab-plot`'s, if the picture cannot be drawn (a bug).
pub fn light_view_picture(
    map: &ShadowMap,
    eye: &Eye,
    scene: &str,
    settings: &str,
) -> Result<Vec<u8>, PlotError> {
    let pixels = light_view(map, eye);
    render_picture(&Picture {
        title: format!(
            "{scene} — {}: the shadow map as the light sees it",
            map.setup.technique
        ),
        subtitle: settings.to_owned(),
        image: Image::bottom_up(map.resolution, map.resolution, &pixels)?,
        colour_bar: None,
        legend: vec![
            swatch(FRUSTUM_COLOUR, "the view frustum's edges"),
            swatch(FOCUS_BODY_COLOUR, "the outline of the focus body B"),
            swatch(
                MID_DEPTH_GREY,
                "stored depth: darker nearer the light, white where nothing is",
            ),
        ],
    })
}

/// Strokes polylines (of at least two points) onto the pixmap.
fn stroke(pixmap: &mut Pixmap, lines: &[Vec<DVec2>], color: Color, width: f64) {
    let mut builder = PathBuilder::new();
    for line in lines.iter().filter(|l| l.len() >= 2) {
        #[expect(clippy::cast_possible_truncation, reason = "pixel coordinates")]
        let point = |p: DVec2| (p.x as f32, p.y as f32);
        let (x, y) = point(line[0]);
        builder.move_to(x, y);
        for p in &line[1..] {
            let (x, y) = point(*p);
            builder.line_to(x, y);
        }
    }
    let Some(path) = builder.finish() else {
        return;
    };
    let mut paint = Paint::default();
    paint.set_color(color);
    paint.anti_alias = true;
    #[expect(clippy::cast_possible_truncation, reason = "a line width in pixels")]
    let stroke = Stroke {
        width: width as f32,
        line_cap: LineCap::Round,
        ..Stroke::default()
    };
    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
}

/// Linear 0–1 values to 8-bit sRGB (the standard transfer function).
fn to_srgb8(linear: [f64; 3]) -> [u8; 3] {
    linear.map(|v| {
        let v = v.clamp(0.0, 1.0);
        let s = if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "in [0, 255]"
        )]
        let byte = (s * 255.0).round() as u8;
        byte
    })
}
