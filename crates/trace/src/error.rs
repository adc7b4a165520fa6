//! Errors: what went wrong and which parameter, triangle or vertex was bad.

use std::fmt;

/// Why a [`crate::Bvh`], a [`crate::Ray`] or an offset origin could not be made.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum TraceError {
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle's index.
        triangle: usize,
        /// Which of its three corners (0, 1 or 2).
        corner: usize,
        /// The bad vertex index.
        vertex: u32,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// A vertex position has a NaN or infinite coordinate.
    NonFinitePosition {
        /// The vertex's index.
        vertex: usize,
    },
    /// A vertex position has a coordinate larger in magnitude than [`crate::MAX_COORDINATE`].
    PositionOutOfRange {
        /// The vertex's index.
        vertex: usize,
        /// The offending coordinate.
        value: f64,
    },
    /// More triangles than a `u32` can number (a [`crate::Hit`] names its triangle by a `u32`).
    TooManyTriangles {
        /// The count given.
        count: usize,
    },
    /// A parameter (`"origin"`, `"direction"`, `"point"`, `"geometric_normal"`, `"toward"`,
    /// `"magnitude"`) is NaN or infinite, or has a NaN or infinite coordinate.
    NonFinite {
        /// The parameter.
        parameter: &'static str,
    },
    /// A parameter (`"origin"`, `"point"`, `"magnitude"`) lies outside
    /// [−[`crate::MAX_COORDINATE`], [`crate::MAX_COORDINATE`]], or a `magnitude` is negative.
    OutOfRange {
        /// The parameter.
        parameter: &'static str,
        /// The offending value (for a vector, its coordinate of largest magnitude, as a magnitude).
        value: f64,
    },
    /// A ray direction whose largest component (in magnitude) lies outside
    /// [[`crate::MIN_DIRECTION`], [`crate::MAX_COORDINATE`]]; zero directions are reported here.
    DirectionOutOfRange {
        /// The largest absolute component of the direction.
        largest: f64,
    },
    /// A geometric normal of zero length.
    ZeroNormal,
    /// A ray parameter bound (`"t_min"` or `"t_max"`) is NaN.
    NanRange {
        /// The parameter.
        parameter: &'static str,
    },
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::IndexOutOfRange {
                triangle,
                corner,
                vertex,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} (corner {corner}) refers to vertex {vertex}, but there are \
                 {vertex_count} vertices"
            ),
            Self::NonFinitePosition { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite position")
            }
            Self::PositionOutOfRange { vertex, value } => write!(
                f,
                "vertex {vertex} has coordinate {value}, beyond ±{:e} (MAX_COORDINATE)",
                crate::MAX_COORDINATE
            ),
            Self::TooManyTriangles { count } => write!(
                f,
                "{count} triangles are more than a u32 triangle index can number"
            ),
            Self::NonFinite { parameter } => write!(f, "`{parameter}` is not finite"),
            Self::OutOfRange { parameter, value } => write!(
                f,
                "`{parameter}` must lie within [0, {:e}] in magnitude (MAX_COORDINATE), \
                 got {value}",
                crate::MAX_COORDINATE
            ),
            Self::DirectionOutOfRange { largest } => write!(
                f,
                "`direction` must have a largest component in [{:e}, {:e}] in magnitude, \
                 got {largest}",
                crate::MIN_DIRECTION,
                crate::MAX_COORDINATE
            ),
            Self::ZeroNormal => f.write_str("`geometric_normal` has zero length"),
            Self::NanRange { parameter } => write!(f, "`{parameter}` is NaN"),
        }
    }
}

impl std::error::Error for TraceError {}
