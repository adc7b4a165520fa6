//! Deterministic charts and tables for shadowlab: a figure is plain data ([`Figure`]: panels of line
//! series on linear or log axes, with labelled marker lines), drawn to SVG by plotters and
//! rasterised to PNG by resvg from that same SVG, with one embedded font. The same figure gives the
//! same bytes on every run and machine; tables are CSV at full f64 precision. A [`Picture`] is a
//! raster image (a view, a heat map) with a title, a colour bar and a legend, drawn the same way
//! around the image's own pixels.
//!
//! Why these libraries: plotters lays out axes, ticks and legends; resvg renders anti-aliased,
//! deterministic pixels (with tiny-skia) without system fonts. Nothing here knows about shadows.

mod clip;
mod error;
mod figure;
mod font;
mod picture;
mod render;
mod table;

pub use error::PlotError;
pub use figure::{
    Axis, Color, Figure, LegendPosition, LineStyle, Marker, PALETTE, Panel, Scale, Series,
};
pub use picture::{
    ColourBar, Image, MARGIN, MIN_WIDTH, Picture, Swatch, format_value, render_picture,
};
pub use render::{render_png, render_svg};
pub use table::Table;
