//! Errors of the rasterizer: bad input, named.

use std::fmt;

/// Why a draw (or a target) could not be made.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum RasterError {
    /// A target side is 0 or larger than [`crate::MAX_TARGET_SIZE`].
    TargetSize {
        /// `"width"` or `"height"`.
        name: &'static str,
        /// The size given.
        value: u32,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle's index.
        triangle: usize,
        /// The bad vertex index.
        vertex: u32,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// A vertex position, or its transformed position, is NaN or infinite.
    NonFiniteVertex {
        /// The vertex's index.
        vertex: usize,
    },
    /// A matrix entry is NaN or infinite.
    NonFiniteMatrix,
    /// A mesh has more triangles than the rasterizer can number (`2^30`, the top two bits of a bin
    /// entry marking its kind).
    TooManyTriangles {
        /// The count given.
        count: usize,
    },
    /// An image's values do not match its size.
    ImageSize {
        /// Width given.
        width: u32,
        /// Height given.
        height: u32,
        /// Number of values given.
        values: usize,
    },
    /// An image could not be encoded (a bug to report).
    Encode(String),
    /// The normals given to resolve an eye pass do not match the positions.
    NormalCount {
        /// Number of normals.
        normals: usize,
        /// Number of positions.
        positions: usize,
    },
}

impl fmt::Display for RasterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TargetSize { name, value } => write!(
                f,
                "target {name} must be between 1 and {}, got {value}",
                crate::MAX_TARGET_SIZE
            ),
            Self::IndexOutOfRange {
                triangle,
                vertex,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} refers to vertex {vertex}, but there are {vertex_count} vertices"
            ),
            Self::NonFiniteVertex { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite position")
            }
            Self::NonFiniteMatrix => write!(f, "the transform matrix has a NaN or infinite entry"),
            Self::TooManyTriangles { count } => {
                write!(
                    f,
                    "{count} triangles are more than the rasterizer can number"
                )
            }
            Self::ImageSize {
                width,
                height,
                values,
            } => {
                write!(f, "{values} values do not make a {width}×{height} image")
            }
            Self::Encode(message) => write!(f, "image encoding failed (please report): {message}"),
            Self::NormalCount { normals, positions } => {
                write!(f, "{normals} normals given for {positions} positions")
            }
        }
    }
}

impl std::error::Error for RasterError {}
