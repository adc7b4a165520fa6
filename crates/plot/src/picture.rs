//! Raster pictures that explain themselves: an image (a rendered view, a per-pixel measurement)
//! under a title and a subtitle, with a colour bar (quantity, unit, scale, the bar's range and the
//! values the image holds) and a legend of colour swatches below it.
//!
//! The annotations are drawn as SVG and rasterised by resvg with the embedded font, like the
//! figures; the image is then copied into its place pixel for pixel, so it is neither resampled
//! nor re-encoded through a lossy path, and the whole PNG is byte-identical across runs and
//! machines. The SVG is an intermediate only: it holds the annotations and an empty slot, not the
//! image.
//!
//! # Layout
//! Top to bottom, in pixels: a margin of [`MARGIN`], the title and the subtitle, the image at one
//! pixel per pixel (centred, in a thin grey frame), then the colour bar (its label with the
//! scale, the bar with markers ▼ at the least and greatest value of the image, tick labels, and
//! the values' range in words), then the legend's swatches in rows. The canvas is as wide as the
//! widest of the image and the texts, and at least [`MIN_WIDTH`].

use std::fmt::Write as _;

use crate::error::PlotError;
use crate::figure::{Color, Scale};
use crate::font::{FAMILY, text_width};
use crate::render::{encode_png, format_tick, rasterise};

/// The margin around everything, in pixels.
pub const MARGIN: u32 = 14;
/// The least width of a picture, in pixels: room for a colour bar and its labels.
pub const MIN_WIDTH: u32 = 480;
/// The colour bar's greatest length, in pixels.
const BAR_LENGTH: f64 = 640.0;
/// The colour bar's thickness, in pixels.
const BAR_HEIGHT: f64 = 16.0;
/// Font sizes (SVG `font-size`, pixels).
const TITLE_FONT: f64 = 18.0;
const SUBTITLE_FONT: f64 = 13.0;
const KEY_FONT: f64 = 13.0;
const TICK_FONT: f64 = 12.0;
/// A line of text is this many times its font size high.
const LINE: f64 = 1.45;
/// Side of a legend swatch, and the gaps after it and between entries.
const SWATCH: f64 = 14.0;
const SWATCH_GAP: f64 = 6.0;
const ENTRY_GAP: f64 = 20.0;
/// Gaps between the header, the image and the key.
const GAP: f64 = 10.0;
/// Colours of the text, the frame and the swatches' borders.
const INK: &str = "rgb(30,30,30)";
const FRAME: &str = "rgb(150,150,150)";

/// An 8-bit sRGB image, stored top row first.
///
/// # Guarantees
/// At least one pixel, and `width × height` of them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<[u8; 3]>,
}

impl Image {
    /// An image whose `pixels` run row by row from the top.
    ///
    /// # Errors
    /// [`PlotError::ImageSize`] if a side is zero or `pixels` does not hold `width × height`.
    pub fn top_down(width: u32, height: u32, pixels: Vec<[u8; 3]>) -> Result<Self, PlotError> {
        let expected = u64::from(width) * u64::from(height);
        if width == 0 || height == 0 || pixels.len() as u64 != expected {
            return Err(PlotError::ImageSize {
                width,
                height,
                pixels: pixels.len(),
            });
        }
        Ok(Self {
            width,
            height,
            pixels,
        })
    }

    /// An image whose `pixels` run row by row from the bottom (as the eye image's do).
    ///
    /// # Errors
    /// As [`Self::top_down`].
    pub fn bottom_up(width: u32, height: u32, pixels: &[[u8; 3]]) -> Result<Self, PlotError> {
        let expected = u64::from(width) * u64::from(height);
        if width == 0 || height == 0 || pixels.len() as u64 != expected {
            return Err(PlotError::ImageSize {
                width,
                height,
                pixels: pixels.len(),
            });
        }
        let mut rows = Vec::with_capacity(pixels.len());
        for row in pixels.chunks(width as usize).rev() {
            rows.extend_from_slice(row);
        }
        Self::top_down(width, height, rows)
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, top row first.
    #[must_use]
    pub fn pixels(&self) -> &[[u8; 3]] {
        &self.pixels
    }
}

/// One entry of a legend: a colour and what it means.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Swatch {
    /// The colour, exactly as the image uses it.
    pub color: Color,
    /// What a pixel of that colour means.
    pub label: String,
}

/// How a heat map's colours read as values.
#[derive(Clone, Debug, PartialEq)]
pub struct ColourBar {
    /// The quantity and its unit, e.g. `texel footprint on screen (pixels per texel)`; the scale
    /// is added when drawn.
    pub label: String,
    /// Linear or logarithmic.
    pub scale: Scale,
    /// The value at the first colour.
    pub low: f64,
    /// The value at the last colour.
    pub high: f64,
    /// The colour map's control points, evenly spaced from `low` (first) to `high` (last) along
    /// the scale and interpolated linearly in sRGB between them, as an SVG gradient is. Values
    /// beyond the ends take the end colours (said under the bar).
    pub stops: Vec<Color>,
    /// The least and greatest value the image holds (`None`: it holds none), marked on the bar
    /// and written under it.
    pub range: Option<(f64, f64)>,
}

impl ColourBar {
    /// `Err` unless the range can be drawn on the scale and there are at least two stops.
    fn validate(&self) -> Result<(), PlotError> {
        let axis = crate::figure::Axis {
            label: self.label.clone(),
            min: self.low,
            max: self.high,
            scale: self.scale,
        };
        axis.validate()?;
        if self.stops.len() < 2 {
            return Err(PlotError::ColourBar {
                label: self.label.clone(),
                reason: "a colour bar needs at least two colours",
            });
        }
        if let Some((least, greatest)) = self.range
            && !(least.is_finite() && greatest.is_finite() && least <= greatest)
        {
            return Err(PlotError::ColourBar {
                label: self.label.clone(),
                reason: "the values' range must be finite, least first",
            });
        }
        Ok(())
    }

    /// Where `value` sits along the bar, in `[0, 1]` (clamped).
    fn fraction(&self, value: f64) -> f64 {
        let f = match self.scale {
            Scale::Linear => (value - self.low) / (self.high - self.low),
            Scale::Log => {
                if value <= 0.0 {
                    0.0
                } else {
                    (value / self.low).ln() / (self.high / self.low).ln()
                }
            }
        };
        f.clamp(0.0, 1.0)
    }

    /// The labelled values: every power of ten inside a log bar (its ends where there are fewer
    /// than two), five evenly spaced values on a linear one.
    fn ticks(&self) -> Vec<f64> {
        match self.scale {
            Scale::Log => {
                let first = self.low.log10().ceil();
                let last = self.high.log10().floor();
                let mut ticks = Vec::new();
                let mut exponent = first;
                while exponent <= last {
                    ticks.push(10f64.powf(exponent));
                    exponent += 1.0;
                }
                if ticks.len() < 2 {
                    ticks = vec![self.low, self.high];
                }
                ticks
            }
            Scale::Linear => (0..5)
                .map(|k| self.low + f64::from(k) / 4.0 * (self.high - self.low))
                .collect(),
        }
    }

    /// The line over the bar: quantity, unit and scale.
    fn heading(&self) -> String {
        let scale = match self.scale {
            Scale::Linear => "linear scale",
            Scale::Log => "log scale",
        };
        format!("{} — {scale}", self.label)
    }

    /// The line under the bar: the values the image holds, and what the ends mean.
    fn range_text(&self) -> String {
        let ends = format!(
            "the bar spans {} to {}; values beyond take the end colours",
            format_tick(self.low),
            format_tick(self.high)
        );
        match self.range {
            Some((least, greatest)) => format!(
                "▼ values in this picture: {} to {}; {ends}",
                format_value(least),
                format_value(greatest)
            ),
            None => format!("no values in this picture; {ends}"),
        }
    }
}

/// A picture: an image under a title, with its colour bar and legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    /// The first line: what the picture shows (scene, technique).
    pub title: String,
    /// The second line: the settings it was made with (may be empty).
    pub subtitle: String,
    /// The image, drawn at one pixel per pixel.
    pub image: Image,
    /// How its colours read as values, for a heat map.
    pub colour_bar: Option<ColourBar>,
    /// What its colours mean, for a picture of classes (and a heat map's "no value" colour).
    pub legend: Vec<Swatch>,
}

/// An axis-aligned rectangle in the picture's pixels: left, top, width, height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rect {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) width: f64,
    pub(crate) height: f64,
}

/// A picture laid out: the SVG of its annotations and where its parts are.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Composition {
    /// The annotations, with an empty slot for the image.
    pub(crate) svg: String,
    /// Where the image's top-left pixel goes.
    pub(crate) image_at: (u32, u32),
    /// The colour bar's gradient.
    pub(crate) bar: Option<Rect>,
    /// The legend's swatches, in order.
    pub(crate) swatches: Vec<Rect>,
}

/// `text` safe inside SVG (XML) text and attribute values.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // XML 1.0 has no place for other control characters; they would make the SVG invalid.
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A value with three significant digits: plain decimals from 1e-3 to 1e5, exponent form outside.
#[must_use]
pub fn format_value(value: f64) -> String {
    if !value.is_finite() {
        return format!("{value}");
    }
    let magnitude = value.abs();
    if magnitude == 0.0 {
        return "0".into();
    }
    if (1e-3..1e5).contains(&magnitude) {
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "a decimal count in 0..=5"
        )]
        let decimals = (2.0 - magnitude.log10().floor()).max(0.0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{value:.2e}")
    }
}

fn text(svg: &mut String, x: f64, y: f64, size: f64, anchor: &str, content: &str) {
    writeln!(
        svg,
        r#"<text x="{x:.2}" y="{y:.2}" font-family="{FAMILY}" font-size="{size}" fill="{INK}" text-anchor="{anchor}">{}</text>"#,
        escape(content)
    )
    .expect("writing to a string");
}

fn colour(c: Color) -> String {
    format!("rgb({},{},{})", c.0, c.1, c.2)
}

/// Lays `picture` out.
pub(crate) fn compose(picture: &Picture) -> Result<Composition, PlotError> {
    if let Some(bar) = &picture.colour_bar {
        bar.validate()?;
    }
    let margin = f64::from(MARGIN);
    let image_w = f64::from(picture.image.width);
    let image_h = f64::from(picture.image.height);
    // The widest line decides the canvas.
    let mut widest = image_w.max(f64::from(MIN_WIDTH) - 2.0 * margin);
    widest = widest.max(text_width(&picture.title, TITLE_FONT)?);
    widest = widest.max(text_width(&picture.subtitle, SUBTITLE_FONT)?);
    if let Some(bar) = &picture.colour_bar {
        widest = widest.max(text_width(&bar.heading(), KEY_FONT)?);
        widest = widest.max(text_width(&bar.range_text(), KEY_FONT)?);
    }
    let entries: Vec<f64> = picture
        .legend
        .iter()
        .map(|s| Ok(SWATCH + SWATCH_GAP + text_width(&s.label, KEY_FONT)?))
        .collect::<Result<_, PlotError>>()?;
    widest = entries.iter().copied().fold(widest, f64::max);
    let content = widest.ceil();
    let width = content + 2.0 * margin;

    let mut svg = String::new();
    let mut y = margin;
    let mut body = String::new();
    if !picture.title.is_empty() {
        text(
            &mut body,
            margin,
            y + TITLE_FONT,
            TITLE_FONT,
            "start",
            &picture.title,
        );
        y += (TITLE_FONT * LINE).round();
    }
    if !picture.subtitle.is_empty() {
        text(
            &mut body,
            margin,
            y + SUBTITLE_FONT,
            SUBTITLE_FONT,
            "start",
            &picture.subtitle,
        );
        y += (SUBTITLE_FONT * LINE).round();
    }
    y += GAP;
    let image_x = margin + ((content - image_w) / 2.0).floor();
    writeln!(
        body,
        r#"<rect x="{:.1}" y="{:.1}" width="{}" height="{}" fill="none" stroke="{FRAME}" stroke-width="1"/>"#,
        image_x - 0.5,
        y - 0.5,
        image_w + 1.0,
        image_h + 1.0
    )
    .expect("writing to a string");
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "whole, non-negative pixel positions"
    )]
    let image_at = (image_x as u32, y as u32);
    y += image_h + GAP + 4.0;

    let mut bar_rect = None;
    if let Some(bar) = &picture.colour_bar {
        text(
            &mut body,
            margin,
            y + KEY_FONT,
            KEY_FONT,
            "start",
            &bar.heading(),
        );
        y += (KEY_FONT * LINE).round();
        let length = content.min(BAR_LENGTH);
        // The markers sit over the bar, pointing down at the values.
        let marker = 7.0;
        if let Some((least, greatest)) = bar.range {
            for value in [least, greatest] {
                let x = margin + bar.fraction(value) * length;
                writeln!(
                    body,
                    r#"<path d="M {:.2} {:.2} L {:.2} {:.2} L {:.2} {:.2} Z" fill="{INK}"/>"#,
                    x - marker / 2.0,
                    y,
                    x + marker / 2.0,
                    y,
                    x,
                    y + marker
                )
                .expect("writing to a string");
            }
        }
        y += marker + 1.0;
        let rect = Rect {
            x: margin,
            y,
            width: length,
            height: BAR_HEIGHT,
        };
        let last = bar.stops.len() - 1;
        writeln!(
            svg,
            r#"<defs><linearGradient id="bar" x1="0" y1="0" x2="1" y2="0">"#
        )
        .expect("writing to a string");
        for (k, stop) in bar.stops.iter().enumerate() {
            #[expect(clippy::cast_precision_loss, reason = "a handful of stops")]
            let offset = k as f64 / last as f64;
            writeln!(
                svg,
                r#"<stop offset="{offset}" stop-color="{}"/>"#,
                colour(*stop)
            )
            .expect("writing to a string");
        }
        writeln!(svg, "</linearGradient></defs>").expect("writing to a string");
        writeln!(
            body,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="url(#bar)"/>"#,
            rect.x, rect.y, rect.width, rect.height
        )
        .expect("writing to a string");
        writeln!(
            body,
            r#"<rect x="{:.1}" y="{:.1}" width="{}" height="{}" fill="none" stroke="{FRAME}" stroke-width="1"/>"#,
            rect.x - 0.5,
            rect.y - 0.5,
            rect.width + 1.0,
            rect.height + 1.0
        )
        .expect("writing to a string");
        y += BAR_HEIGHT;
        for tick in bar.ticks() {
            let x = margin + bar.fraction(tick) * length;
            writeln!(
                body,
                r#"<line x1="{x:.2}" y1="{y}" x2="{x:.2}" y2="{}" stroke="{INK}" stroke-width="1"/>"#,
                y + 5.0
            )
            .expect("writing to a string");
            let label = format_tick(tick);
            let half = text_width(&label, TICK_FONT)? / 2.0;
            // Labels at the ends stay inside the canvas.
            let at = x.clamp(half + 1.0, width - half - 1.0);
            text(
                &mut body,
                at,
                y + 6.0 + TICK_FONT,
                TICK_FONT,
                "middle",
                &label,
            );
        }
        y += 6.0 + (TICK_FONT * LINE).round();
        text(
            &mut body,
            margin,
            y + KEY_FONT,
            KEY_FONT,
            "start",
            &bar.range_text(),
        );
        y += (KEY_FONT * LINE).round() + GAP / 2.0;
        bar_rect = Some(rect);
    }

    let mut swatches = Vec::new();
    let row = (KEY_FONT * LINE).round();
    let mut x = margin;
    for (swatch, entry) in picture.legend.iter().zip(&entries) {
        if x > margin && x + entry > margin + content {
            x = margin;
            y += row;
        }
        let rect = Rect {
            x,
            y: y + ((row - SWATCH) / 2.0).floor(),
            width: SWATCH,
            height: SWATCH,
        };
        writeln!(
            body,
            r#"<rect x="{}" y="{}" width="{SWATCH}" height="{SWATCH}" fill="{}" stroke="{FRAME}" stroke-width="1"/>"#,
            rect.x,
            rect.y,
            colour(swatch.color)
        )
        .expect("writing to a string");
        text(
            &mut body,
            x + SWATCH + SWATCH_GAP,
            y + KEY_FONT,
            KEY_FONT,
            "start",
            &swatch.label,
        );
        swatches.push(rect);
        x += entry + ENTRY_GAP;
    }
    if !picture.legend.is_empty() {
        y += row;
    }
    let height = (y + margin).ceil();
    let document = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\">\n{svg}<rect width=\"{width}\" height=\"{height}\" \
         fill=\"white\"/>\n{body}</svg>\n"
    );
    Ok(Composition {
        svg: document,
        image_at,
        bar: bar_rect,
        swatches,
    })
}

/// The picture as PNG bytes (8-bit RGBA, opaque): the annotations rasterised from SVG with the
/// embedded font, the image copied into its slot pixel for pixel. Byte-identical across runs and
/// machines.
///
/// # Errors
/// [`PlotError::InvalidAxis`] or [`PlotError::ColourBar`] for a colour bar that cannot be drawn;
/// [`PlotError::Render`] if the SVG renderer fails (a bug).
pub fn render_picture(picture: &Picture) -> Result<Vec<u8>, PlotError> {
    let composition = compose(picture)?;
    let mut pixmap = rasterise(&composition.svg)?;
    let (x0, y0) = composition.image_at;
    let canvas = pixmap.width() as usize;
    let image = &picture.image;
    let pixels = pixmap.pixels_mut();
    for (row, line) in image.pixels.chunks(image.width as usize).enumerate() {
        let start = (y0 as usize + row) * canvas + x0 as usize;
        for (target, [r, g, b]) in pixels[start..start + line.len()].iter_mut().zip(line) {
            *target = resvg::tiny_skia::ColorU8::from_rgba(*r, *g, *b, 255).premultiply();
        }
    }
    encode_png(&pixmap)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A picture of `width × height` pixels coloured by position, with a bar and two swatches.
    fn picture(width: u32, height: u32) -> Picture {
        let pixels = (0..width * height)
            .map(|k| [(k % 251) as u8, (k / 251 % 251) as u8, 200])
            .collect();
        Picture {
            title: "scene <a & b> — \"technique\"".into(),
            subtitle: "1024² map, filter nearest".into(),
            image: Image::top_down(width, height, pixels).unwrap(),
            colour_bar: Some(ColourBar {
                label: "footprint (pixels per texel)".into(),
                scale: Scale::Log,
                low: 0.1,
                high: 100.0,
                stops: vec![Color(0, 0, 0), Color(255, 0, 0), Color(255, 255, 255)],
                range: Some((0.5, 20.0)),
            }),
            legend: vec![
                Swatch {
                    color: Color(213, 94, 0),
                    label: "falsely lit".into(),
                },
                Swatch {
                    color: Color(0, 114, 178),
                    label: "falsely shadowed".into(),
                },
            ],
        }
    }

    fn decode(png: &[u8]) -> resvg::tiny_skia::Pixmap {
        resvg::tiny_skia::Pixmap::decode_png(png).expect("a PNG")
    }

    fn at(pixmap: &resvg::tiny_skia::Pixmap, x: f64, y: f64) -> [u8; 3] {
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "positions inside the canvas"
        )]
        let p = pixmap
            .pixel(x as u32, y as u32)
            .expect("inside")
            .demultiply();
        [p.red(), p.green(), p.blue()]
    }

    /// Claim: the image lands in its slot unchanged, pixel for pixel, and the same picture gives
    /// the same bytes twice.
    #[test]
    fn the_image_is_copied_exactly_and_the_bytes_repeat() {
        let p = picture(300, 40);
        let png = render_picture(&p).unwrap();
        assert_eq!(png, render_picture(&p).unwrap());
        let pixmap = decode(&png);
        let (x0, y0) = compose(&p).unwrap().image_at;
        for (k, expected) in p.image.pixels().iter().enumerate() {
            let (x, y) = (k % 300, k / 300);
            #[expect(clippy::cast_precision_loss, reason = "small positions")]
            let got = at(&pixmap, (x0 as usize + x) as f64, (y0 as usize + y) as f64);
            assert_eq!(got, *expected, "pixel {x}, {y}");
        }
        assert!(pixmap.width() >= MIN_WIDTH);
    }

    /// Claim: bottom-up rows are turned over; a wrong pixel count is an error.
    #[test]
    fn rows_from_the_bottom_are_turned_over() {
        let image = Image::bottom_up(2, 2, &[[1; 3], [2; 3], [3; 3], [4; 3]]).unwrap();
        assert_eq!(image.pixels(), &[[3; 3], [4; 3], [1; 3], [2; 3]]);
        assert!(matches!(
            Image::top_down(2, 2, vec![[0; 3]; 3]),
            Err(PlotError::ImageSize { pixels: 3, .. })
        ));
        assert!(Image::bottom_up(0, 0, &[]).is_err());
    }

    /// Claim: the bar runs from the first stop on the left to the last on the right through the
    /// middle one, and each swatch shows its colour.
    #[test]
    fn the_bar_and_the_swatches_show_their_colours() {
        let p = picture(200, 30);
        let composition = compose(&p).unwrap();
        let pixmap = decode(&render_picture(&p).unwrap());
        let bar = composition.bar.unwrap();
        let mid_y = bar.y + bar.height / 2.0;
        let near = |a: [u8; 3], b: [u8; 3]| a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= 3);
        let left = at(&pixmap, bar.x + 0.5, mid_y);
        let middle = at(&pixmap, bar.x + bar.width / 2.0, mid_y);
        let right = at(&pixmap, bar.x + bar.width - 0.5, mid_y);
        assert!(near(left, [0, 0, 0]), "{left:?}");
        assert!(near(middle, [255, 0, 0]), "{middle:?}");
        assert!(near(right, [255, 255, 255]), "{right:?}");
        assert_eq!(composition.swatches.len(), 2);
        for (rect, swatch) in composition.swatches.iter().zip(&p.legend) {
            let got = at(
                &pixmap,
                rect.x + rect.width / 2.0,
                rect.y + rect.height / 2.0,
            );
            let Color(r, g, b) = swatch.color;
            assert_eq!(got, [r, g, b], "{}", swatch.label);
        }
    }

    /// Claim: text from input is escaped (an unescaped `<` would not parse), and the canvas grows
    /// to hold a long title.
    #[test]
    fn titles_are_escaped_and_fit() {
        let mut p = picture(10, 10);
        let svg = compose(&p).unwrap().svg;
        assert!(
            svg.contains("scene &lt;a &amp; b&gt; — &quot;technique&quot;"),
            "{svg}"
        );
        p.title = "x".repeat(200);
        let composition = compose(&p).unwrap();
        let pixmap = decode(&render_picture(&p).unwrap());
        let expected = text_width(&p.title, TITLE_FONT).unwrap() + 2.0 * f64::from(MARGIN);
        assert!(f64::from(pixmap.width()) >= expected, "{}", pixmap.width());
        assert!(composition.image_at.0 > 0);
    }

    /// Claim: log ticks fall on the decades inside the bar; ranges that cannot be drawn are
    /// errors naming the bar.
    #[test]
    fn ticks_and_bad_bars() {
        let p = picture(10, 10);
        let bar = p.colour_bar.clone().unwrap();
        assert_eq!(bar.ticks(), vec![0.1, 1.0, 10.0, 100.0]);
        let narrow = ColourBar {
            low: 2.0,
            high: 5.0,
            ..bar.clone()
        };
        assert_eq!(narrow.ticks(), vec![2.0, 5.0]);
        for broken in [
            ColourBar {
                low: 0.0,
                ..bar.clone()
            },
            ColourBar {
                stops: vec![Color(0, 0, 0)],
                ..bar.clone()
            },
            ColourBar {
                range: Some((3.0, f64::NAN)),
                ..bar.clone()
            },
        ] {
            let mut q = p.clone();
            q.colour_bar = Some(broken);
            assert!(render_picture(&q).is_err());
        }
    }

    #[test]
    fn values_have_three_significant_digits() {
        assert_eq!(format_value(57.23), "57.2");
        assert_eq!(format_value(0.034_34), "0.0343");
        assert_eq!(format_value(1234.4), "1234");
        assert_eq!(format_value(1.5), "1.50");
        assert_eq!(format_value(2.5e6), "2.50e6");
        assert_eq!(format_value(0.0), "0");
    }
}
