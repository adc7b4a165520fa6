//! The errors of [`crate::procedural`]: a parameter out of range, or a shape too large.

use std::fmt;

use crate::mesh::MeshError;
use crate::number::Shown;

/// Why a procedural shape could not be built.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeError {
    /// A parameter outside its documented range.
    InvalidParameter {
        /// The parameter, e.g. `"radius"`, `"cells[1]"`.
        parameter: &'static str,
        /// The value given (integer parameters are converted exactly).
        value: f64,
        /// The rule it breaks, e.g. `"finite and > 0"`.
        requirement: &'static str,
    },
    /// A mesh with more triangles than [`crate::procedural::MAX_TRIANGLES`].
    TooManyTriangles {
        /// The mesh, e.g. `"bar_lattice"`.
        shape: &'static str,
        /// The number of triangles the parameters ask for.
        count: u128,
        /// The limit.
        max: u64,
    },
    /// The shape's vertices are out of the mesh's range (a size beyond
    /// [`crate::MAX_COORDINATE`]).
    Mesh(MeshError),
}

impl fmt::Display for ShapeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidParameter {
                parameter,
                value,
                requirement,
            } => write!(
                f,
                "`{parameter}` must be {requirement}, got {}",
                Shown(*value)
            ),
            Self::TooManyTriangles { shape, count, max } => write!(
                f,
                "{shape} would have {count} triangles, more than the limit of {max} (MAX_TRIANGLES)"
            ),
            Self::Mesh(error) => write!(f, "{error}"),
        }
    }
}

impl std::error::Error for ShapeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Mesh(error) => Some(error),
            Self::InvalidParameter { .. } | Self::TooManyTriangles { .. } => None,
        }
    }
}

impl From<MeshError> for ShapeError {
    fn from(error: MeshError) -> Self {
        Self::Mesh(error)
    }
}
