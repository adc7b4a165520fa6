//! Errors of figure rendering and table writing.

use std::fmt;

/// Why a figure or table could not be produced.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum PlotError {
    /// An axis range that cannot be drawn (empty, not finite, or not positive on a log axis).
    InvalidAxis {
        /// The axis's label.
        label: String,
        /// Its lower end.
        min: f64,
        /// Its upper end.
        max: f64,
    },
    /// A figure with no panels or zero size.
    EmptyFigure {
        /// The figure's title.
        title: String,
    },
    /// A table row whose length differs from the number of columns.
    RowLength {
        /// The number of columns.
        expected: usize,
        /// The row's length.
        found: usize,
    },
    /// An image whose pixels do not fill its sides, or with a side of zero.
    ImageSize {
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
        /// The pixels given.
        pixels: usize,
    },
    /// A colour bar that cannot be drawn (beyond its range, which is an [`Self::InvalidAxis`]).
    ColourBar {
        /// The bar's label.
        label: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// The chart library or the SVG renderer failed; this is a bug to report.
    Render(String),
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidAxis { label, min, max } => {
                write!(f, "axis \"{label}\" cannot show the range [{min}, {max}]")
            }
            Self::EmptyFigure { title } => write!(f, "figure \"{title}\" has nothing to draw"),
            Self::RowLength { expected, found } => {
                write!(f, "table row has {found} values for {expected} columns")
            }
            Self::ImageSize {
                width,
                height,
                pixels,
            } => write!(
                f,
                "an image of {width} × {height} pixels cannot hold {pixels} pixels"
            ),
            Self::ColourBar { label, reason } => write!(f, "colour bar \"{label}\": {reason}"),
            Self::Render(message) => {
                write!(f, "internal rendering error (please report): {message}")
            }
        }
    }
}

impl std::error::Error for PlotError {}
