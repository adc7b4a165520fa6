//! Drawing a [`Figure`] as SVG with plotters, and rasterising that SVG to PNG with resvg. The PNG is
//! rendered from the very SVG that is written, so the two never differ; both are byte-identical
//! across runs and machines because the only font is embedded and nothing reads the clock.

use std::borrow::Cow;
use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::clip::visible_runs;
use crate::error::PlotError;
use crate::figure::{Color as SeriesColor, Figure, LegendPosition, LineStyle, Panel, Scale};
use crate::font::{self, CHART_FAMILY};

/// plotters places everything on whole pixels; the SVG is therefore drawn on a canvas this many
/// times larger than its nominal size (every length below is multiplied by it) and declares the
/// nominal size with a `viewBox`, so lines sit on a grid of 1/4 pixel instead of 1.
const SUPERSAMPLE: u32 = 4;
/// Height of the figure title band, in nominal pixels.
const TITLE_HEIGHT: u32 = 44;
/// Font sizes, in nominal pixels.
const TITLE_FONT: u32 = 20;
const PANEL_TITLE_FONT: u32 = 16;
const AXIS_LABEL_FONT: u32 = 15;
const TICK_FONT: u32 = 12;
const LEGEND_FONT: u32 = 12;
/// Margins around a panel and the sizes of its label areas, in nominal pixels.
const PANEL_MARGIN: u32 = 14;
const X_LABEL_AREA: u32 = 48;
const Y_LABEL_AREA: u32 = 72;
/// Line widths, in nominal pixels.
const SERIES_WIDTH: u32 = 2;
const GRID_WIDTH: u32 = 1;
/// Dash and gap lengths of [`LineStyle::Dashed`] and [`LineStyle::Dotted`] and of marker lines.
const DASH: (u32, u32) = (10, 6);
const DOT: (u32, u32) = (3, 4);
const MARKER_DASH: (u32, u32) = (4, 4);
/// Length of a legend's line sample.
const LEGEND_SAMPLE: i32 = 26;
/// Heights of marker labels, as fractions of the frame from the bottom, used in turn.
const MARKER_LABEL_LEVELS: [f64; 4] = [0.97, 0.92, 0.87, 0.82];

/// A length in nominal pixels on the supersampled canvas.
fn px(nominal: u32) -> u32 {
    nominal * SUPERSAMPLE
}

/// The figure as an SVG document of its nominal size (`columns × panel_width` by
/// `rows × panel_height` plus the title band).
pub fn render_svg(figure: &Figure) -> Result<String, PlotError> {
    figure.validate()?;
    font::register_for_layout()?;
    let (rows, columns) = figure.grid();
    let width = figure.panel_width * u32::try_from(columns).map_err(render_error)?;
    let height = figure.panel_height * u32::try_from(rows).map_err(render_error)? + TITLE_HEIGHT;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (px(width), px(height))).into_drawing_area();
        root.fill(&WHITE).map_err(render_error)?;
        let (title, body) = root.split_vertically(px(TITLE_HEIGHT));
        let centre = Pos::new(HPos::Center, VPos::Center);
        let style = (CHART_FAMILY, px(TITLE_FONT))
            .into_font()
            .color(&BLACK)
            .pos(centre);
        let at = (
            i32::try_from(px(width) / 2).map_err(render_error)?,
            i32::try_from(px(TITLE_HEIGHT) / 2).map_err(render_error)?,
        );
        title
            .draw(&Text::new(figure.title.as_str(), at, style))
            .map_err(render_error)?;
        for (panel, area) in figure.panels.iter().zip(body.split_evenly((rows, columns))) {
            draw_panel(&area, panel)?;
        }
        root.present().map_err(render_error)?;
    }
    let canvas = format!("<svg width=\"{}\" height=\"{}\"", px(width), px(height));
    let nominal = format!("<svg width=\"{width}\" height=\"{height}\"");
    if !svg.starts_with(&canvas) {
        return Err(PlotError::Render(
            "unexpected SVG header from plotters".into(),
        ));
    }
    Ok(svg.replacen(&canvas, &nominal, 1))
}

/// The SVG rasterised at one pixel per SVG unit, as PNG bytes: 8-bit RGBA, the same pixels as
/// tiny-skia's own encoder, compressed with the `png` crate's fast setting.
pub fn render_png(svg: &str) -> Result<Vec<u8>, PlotError> {
    encode_png(&rasterise(svg)?)
}

/// A rendered pixmap as PNG bytes: 8-bit RGBA, each pixel demultiplied as
/// `tiny_skia::Pixmap::encode_png` does it, compressed with the `png` crate's fast setting and
/// adaptive filter — the settings of the raw pictures (`shadowlab_raster::image_out`). The same
/// pixels as tiny-skia's own encoder, whose default compression took most of a report's drawing
/// time (docs/benchmarks.md); deterministic.
pub(crate) fn encode_png(pixmap: &resvg::tiny_skia::Pixmap) -> Result<Vec<u8>, PlotError> {
    // Demultiplying leaves an opaque pixel as it is: an opaque pixmap (every annotated picture,
    // whose canvas is painted white first) is encoded from its own bytes, not from a copy.
    let opaque = pixmap.pixels().iter().all(|pixel| pixel.alpha() == u8::MAX);
    let demultiplied: Cow<'_, [u8]> = if opaque {
        Cow::Borrowed(pixmap.data())
    } else {
        Cow::Owned(pixmap.clone().take_demultiplied())
    };
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, pixmap.width(), pixmap.height());
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(render_error)?;
    writer
        .write_image_data(&demultiplied)
        .map_err(render_error)?;
    writer.finish().map_err(render_error)?;
    Ok(bytes)
}

/// The SVG rasterised at one pixel per SVG unit, with the embedded font as every family.
pub(crate) fn rasterise(svg: &str) -> Result<resvg::tiny_skia::Pixmap, PlotError> {
    let mut options = resvg::usvg::Options {
        fontdb: font::database(),
        ..resvg::usvg::Options::default()
    };
    options.font_family = font::FAMILY.to_owned();
    let tree = resvg::usvg::Tree::from_str(svg, &options).map_err(render_error)?;
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| PlotError::Render("zero-sized figure".into()))?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

pub(crate) fn render_error(error: impl std::fmt::Display) -> PlotError {
    PlotError::Render(error.to_string())
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
) -> Result<(), PlotError> {
    let x: Range<f64> = panel.x.min..panel.x.max;
    let y: Range<f64> = panel.y.min..panel.y.max;
    match (panel.x.scale, panel.y.scale) {
        (Scale::Linear, Scale::Linear) => draw_in(area, panel, x, y),
        (Scale::Linear, Scale::Log) => draw_in(area, panel, x, y.log_scale()),
        (Scale::Log, Scale::Linear) => draw_in(area, panel, x.log_scale(), y),
        (Scale::Log, Scale::Log) => draw_in(area, panel, x.log_scale(), y.log_scale()),
    }
}

fn draw_in<DB, X, Y>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    x: X,
    y: Y,
) -> Result<(), PlotError>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (CHART_FAMILY, px(PANEL_TITLE_FONT)))
        .margin(px(PANEL_MARGIN))
        .x_label_area_size(px(X_LABEL_AREA))
        .y_label_area_size(px(Y_LABEL_AREA))
        .build_cartesian_2d(x, y)
        .map_err(render_error)?;
    let tick_label = |v: &f64| format_tick(*v);
    chart
        .configure_mesh()
        .x_desc(&panel.x.label)
        .y_desc(&panel.y.label)
        .axis_desc_style((CHART_FAMILY, px(AXIS_LABEL_FONT)))
        .label_style((CHART_FAMILY, px(TICK_FONT)))
        .x_label_formatter(&tick_label)
        .y_label_formatter(&tick_label)
        .set_all_tick_mark_size(px(4))
        .axis_style(BLACK.stroke_width(px(GRID_WIDTH)))
        .light_line_style(RGBColor(238, 238, 238).stroke_width(px(GRID_WIDTH)))
        .bold_line_style(RGBColor(205, 205, 205).stroke_width(px(GRID_WIDTH)))
        .draw()
        .map_err(render_error)?;

    for (index, marker) in panel.markers.iter().enumerate() {
        let (y0, y1) = (panel.y.min, panel.y.max);
        let gray = RGBColor(110, 110, 110);
        chart
            .draw_series(DashedLineSeries::new(
                [(marker.x, y0), (marker.x, y1)],
                px(MARKER_DASH.0),
                px(MARKER_DASH.1),
                gray.stroke_width(px(GRID_WIDTH)),
            ))
            .map_err(render_error)?;
        // Labels of neighbouring markers are staggered down the frame so they do not overlap.
        let level = MARKER_LABEL_LEVELS[index % MARKER_LABEL_LEVELS.len()];
        let (low, high) = (
            panel.y.position_of(y0).unwrap_or(y0),
            panel.y.position_of(y1).unwrap_or(y1),
        );
        let text_y = panel.y.value_at(low + level * (high - low));
        chart
            .draw_series(std::iter::once(Text::new(
                format!(" {}", marker.label),
                (marker.x, text_y),
                (CHART_FAMILY, px(LEGEND_FONT)).into_font().color(&gray),
            )))
            .map_err(render_error)?;
    }

    for series in &panel.series {
        let style = rgb(series.color).stroke_width(px(SERIES_WIDTH));
        let line = series.line;
        let runs = visible_runs(&series.points, &panel.x, &panel.y);
        // An empty first run still carries the legend entry of a series that is out of range.
        let mut runs = runs.into_iter();
        let first = runs.next().unwrap_or_default();
        draw_run(&mut chart, first, line, style)?
            .label(&series.label)
            .legend(move |(x, y)| legend_sample(x, y, line, style));
        for run in runs {
            draw_run(&mut chart, run, line, style)?;
        }
    }

    chart
        .configure_series_labels()
        .position(match panel.legend {
            LegendPosition::UpperLeft => SeriesLabelPosition::UpperLeft,
            LegendPosition::UpperRight => SeriesLabelPosition::UpperRight,
            LegendPosition::LowerLeft => SeriesLabelPosition::LowerLeft,
            LegendPosition::LowerRight => SeriesLabelPosition::LowerRight,
        })
        .label_font((CHART_FAMILY, px(LEGEND_FONT)))
        .margin(px(10))
        .legend_area_size(px(32))
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(160, 160, 160))
        .draw()
        .map_err(render_error)?;
    Ok(())
}

type Annotation<'a, 'b, DB> = plotters::chart::SeriesAnno<'a, DB>;

fn draw_run<'a, 'b, DB, X, Y>(
    chart: &'b mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    run: Vec<(f64, f64)>,
    line: LineStyle,
    style: ShapeStyle,
) -> Result<&'b mut Annotation<'a, 'b, DB>, PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let result = match line {
        LineStyle::Solid => chart.draw_series(LineSeries::new(run, style)),
        LineStyle::Dashed => {
            chart.draw_series(DashedLineSeries::new(run, px(DASH.0), px(DASH.1), style))
        }
        LineStyle::Dotted => {
            chart.draw_series(DashedLineSeries::new(run, px(DOT.0), px(DOT.1), style))
        }
    };
    result.map_err(render_error)
}

/// The legend's sample of a line, dashed like the line.
fn legend_sample<DB: DrawingBackend>(
    x: i32,
    y: i32,
    line: LineStyle,
    style: ShapeStyle,
) -> DynElement<'static, DB, (i32, i32)> {
    let length = LEGEND_SAMPLE * i32::try_from(SUPERSAMPLE).unwrap_or(1);
    let points = vec![(x, y), (x + length, y)];
    match line {
        LineStyle::Solid => PathElement::new(points, style).into_dyn(),
        LineStyle::Dashed => {
            DashedPathElement::new(points, px(DASH.0), px(DASH.1), style).into_dyn()
        }
        LineStyle::Dotted => DashedPathElement::new(points, px(DOT.0), px(DOT.1), style).into_dyn(),
    }
}

fn rgb(color: SeriesColor) -> RGBColor {
    RGBColor(color.0, color.1, color.2)
}

/// A tick label: plain decimals (at most four places, trailing zeros dropped) between 1e-3 and
/// 1e5, a short exponent form outside.
pub(crate) fn format_tick(value: f64) -> String {
    if value == 0.0 {
        return "0".into();
    }
    let magnitude = value.abs();
    if (1e-3..1e5).contains(&magnitude) {
        let text = format!("{value:.4}");
        let text = text.trim_end_matches('0').trim_end_matches('.');
        text.to_owned()
    } else {
        let text = format!("{value:e}");
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Claim: [`encode_png`] stores what tiny-skia's own encoder stores, pixel for pixel (both
    /// decoded), for every opacity — demultiplied alike — and a rendered figure; and it is
    /// deterministic.
    #[test]
    fn the_encoder_keeps_tiny_skias_pixels() {
        use resvg::tiny_skia::{Pixmap, PremultipliedColorU8};
        let (width, height) = (97, 61);
        let mut pixmap = Pixmap::new(width, height).expect("a pixmap");
        for (k, pixel) in pixmap.pixels_mut().iter_mut().enumerate() {
            let alpha = u8::try_from(k * 37 % 256).expect("a byte");
            let channel =
                |m: usize| u8::try_from(k * m % (usize::from(alpha) + 1)).expect("a byte");
            *pixel = PremultipliedColorU8::from_rgba(channel(7), channel(13), channel(29), alpha)
                .expect("premultiplied");
        }
        let figure = rasterise(
            "<svg width=\"40\" height=\"30\" xmlns=\"http://www.w3.org/2000/svg\">\
             <circle cx=\"20\" cy=\"15\" r=\"9\" fill=\"#c04020\" fill-opacity=\"0.6\"/></svg>",
        )
        .expect("a figure");
        // On white, as the annotated pictures are: opaque, encoded from its own bytes.
        let opaque = rasterise(
            "<svg width=\"40\" height=\"30\" xmlns=\"http://www.w3.org/2000/svg\">\
             <rect width=\"40\" height=\"30\" fill=\"white\"/>\
             <circle cx=\"20\" cy=\"15\" r=\"9\" fill=\"#c04020\" fill-opacity=\"0.6\"/></svg>",
        )
        .expect("a figure");
        assert!(opaque.pixels().iter().all(|pixel| pixel.alpha() == u8::MAX));
        for pixmap in [pixmap, figure, opaque] {
            let ours = encode_png(&pixmap).expect("encoded");
            let theirs = pixmap.encode_png().expect("encoded");
            let decoded = |png: &[u8]| Pixmap::decode_png(png).expect("a PNG").data().to_vec();
            assert_eq!(decoded(&ours), decoded(&theirs));
            assert_eq!(ours, encode_png(&pixmap).expect("encoded"));
        }
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(format_tick(10.0), "10");
        assert_eq!(format_tick(0.05), "0.05");
        assert_eq!(format_tick(12.5), "12.5");
        assert_eq!(format_tick(1e6), "1e6");
        assert_eq!(format_tick(2.5e-4), "2.5e-4");
        assert_eq!(format_tick(0.0), "0");
        assert_eq!(format_tick(-30.0), "-30");
    }
}
