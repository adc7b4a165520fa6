//! What a figure is: panels of line series on linear or logarithmic axes, described as plain data so
//! that the same description gives the SVG, the PNG and nothing else.

use crate::error::PlotError;

/// How an axis maps values to positions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Evenly spaced values.
    Linear,
    /// Evenly spaced decades; the axis range must be positive.
    Log,
}

/// One axis of a panel: its label, range and scale.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The label, with units or the quantity's symbol.
    pub label: String,
    /// The lower end of the range shown.
    pub min: f64,
    /// The upper end of the range shown.
    pub max: f64,
    /// Linear or logarithmic.
    pub scale: Scale,
}

impl Axis {
    /// A linear axis over `[min, max]`.
    #[must_use]
    pub fn linear(label: impl Into<String>, min: f64, max: f64) -> Self {
        Self {
            label: label.into(),
            min,
            max,
            scale: Scale::Linear,
        }
    }

    /// A logarithmic axis over `[min, max]`, `0 < min`.
    #[must_use]
    pub fn log(label: impl Into<String>, min: f64, max: f64) -> Self {
        Self {
            label: label.into(),
            min,
            max,
            scale: Scale::Log,
        }
    }

    /// `Err` unless `min < max`, both finite, and `min > 0` on a log axis.
    pub(crate) fn validate(&self) -> Result<(), PlotError> {
        let ok = self.min.is_finite()
            && self.max.is_finite()
            && self.min < self.max
            && (self.scale == Scale::Linear || self.min > 0.0);
        if ok {
            Ok(())
        } else {
            Err(PlotError::InvalidAxis {
                label: self.label.clone(),
                min: self.min,
                max: self.max,
            })
        }
    }

    /// The value in the axis's own linear space (log10 on a log axis); `None` where it has none.
    pub(crate) fn position_of(&self, value: f64) -> Option<f64> {
        match self.scale {
            Scale::Linear => value.is_finite().then_some(value),
            Scale::Log => (value.is_finite() && value > 0.0).then(|| value.log10()),
        }
    }

    /// The inverse of [`Self::position_of`].
    pub(crate) fn value_at(&self, value: f64) -> f64 {
        match self.scale {
            Scale::Linear => value,
            Scale::Log => 10f64.powf(value),
        }
    }
}

/// An sRGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Color(pub u8, pub u8, pub u8);

/// A qualitative palette that stays distinguishable for the common colour-vision deficiencies
/// (Okabe & Ito, *Color Universal Design*, 2008), without its yellow, which vanishes on white.
pub const PALETTE: [Color; 7] = [
    Color(0, 114, 178),   // blue
    Color(213, 94, 0),    // vermillion
    Color(0, 158, 115),   // bluish green
    Color(204, 121, 167), // reddish purple
    Color(230, 159, 0),   // orange
    Color(86, 180, 233),  // sky blue
    Color(0, 0, 0),       // black
];

/// Whether a line is drawn solid or dashed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineStyle {
    /// A continuous line.
    Solid,
    /// Long dashes.
    Dashed,
    /// Short dashes.
    Dotted,
}

/// A line through points, drawn in order. A non-finite coordinate (or a non-positive one on a log
/// axis) breaks the line; parts outside the axes are clipped.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry.
    pub label: String,
    /// The points `(x, y)`.
    pub points: Vec<(f64, f64)>,
    /// The line's colour.
    pub color: Color,
    /// The line's dash pattern.
    pub line: LineStyle,
}

impl Series {
    /// A series in the `index`-th colour of [`PALETTE`] (cycling), with the given line style.
    #[must_use]
    pub fn new(
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        index: usize,
        line: LineStyle,
    ) -> Self {
        Self {
            label: label.into(),
            points,
            color: PALETTE[index % PALETTE.len()],
            line,
        }
    }
}

/// A labelled vertical line marking a special value of x (an angle such as φ or γ_lim).
#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    /// Where the line stands.
    pub x: f64,
    /// The text written beside it.
    pub label: String,
}

/// Where a panel's legend sits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegendPosition {
    /// Top left corner of the plotting area.
    UpperLeft,
    /// Top right corner.
    UpperRight,
    /// Bottom left corner.
    LowerLeft,
    /// Bottom right corner.
    LowerRight,
}

/// One chart: axes, series, markers and a legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// The panel's caption (may be empty for a single-panel figure).
    pub title: String,
    /// The horizontal axis.
    pub x: Axis,
    /// The vertical axis.
    pub y: Axis,
    /// The lines, drawn in order and listed in the legend in order.
    pub series: Vec<Series>,
    /// Vertical marker lines.
    pub markers: Vec<Marker>,
    /// Where the legend sits.
    pub legend: LegendPosition,
}

/// A titled grid of panels.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The title over the whole figure; it should state the configuration.
    pub title: String,
    /// The panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row (at least 1).
    pub columns: usize,
    /// Width of one panel in pixels (SVG user units).
    pub panel_width: u32,
    /// Height of one panel in pixels.
    pub panel_height: u32,
}

impl Figure {
    /// A figure of one panel, 960 × 600.
    #[must_use]
    pub fn single(title: impl Into<String>, panel: Panel) -> Self {
        Self {
            title: title.into(),
            panels: vec![panel],
            columns: 1,
            panel_width: 960,
            panel_height: 600,
        }
    }

    /// `(rows, columns)` of the grid.
    pub(crate) fn grid(&self) -> (usize, usize) {
        let columns = self.columns.max(1);
        (self.panels.len().div_ceil(columns), columns)
    }

    /// `Err` for an empty figure or an invalid axis.
    pub(crate) fn validate(&self) -> Result<(), PlotError> {
        if self.panels.is_empty() || self.panel_width == 0 || self.panel_height == 0 {
            return Err(PlotError::EmptyFigure {
                title: self.title.clone(),
            });
        }
        for panel in &self.panels {
            panel.x.validate()?;
            panel.y.validate()?;
        }
        Ok(())
    }
}
