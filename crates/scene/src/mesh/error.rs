//! The errors of [`crate::Mesh`]'s constructors and operations: bad mesh data, naming the vertex,
//! triangle or group.

use std::fmt;

use crate::number::Shown;

/// Why a mesh could not be built, moved or merged.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum MeshError {
    /// A mesh needs at least one triangle.
    NoTriangles,
    /// A vertex position has a NaN or infinite coordinate.
    NonFinitePosition {
        /// The vertex index.
        vertex: usize,
    },
    /// A vertex position has a coordinate beyond ±[`crate::MAX_COORDINATE`].
    PositionOutOfRange {
        /// The vertex index.
        vertex: usize,
        /// The coordinate.
        value: f64,
    },
    /// A given normal is zero, NaN or infinite, so it has no direction.
    InvalidNormal {
        /// The vertex index.
        vertex: usize,
    },
    /// The number of normals differs from the number of positions.
    NormalCountMismatch {
        /// Positions given.
        positions: usize,
        /// Normals given.
        normals: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle index.
        triangle: usize,
        /// The vertex index it names.
        index: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// The number of group ids differs from the number of triangles.
    GroupCountMismatch {
        /// Triangles in the mesh.
        triangles: usize,
        /// Group ids given.
        groups: usize,
    },
    /// A triangle's group id has no group name.
    GroupOutOfRange {
        /// The triangle index.
        triangle: usize,
        /// Its group id.
        group: u32,
        /// The number of group names.
        group_count: usize,
    },
    /// More vertices than a `u32` index can address (at most 2³² vertices).
    TooManyVertices {
        /// The number of vertices asked for.
        count: u64,
    },
    /// More groups than a `u32` id can address.
    TooManyGroups {
        /// The number of groups asked for.
        count: u64,
    },
    /// A transform that is not finite or not invertible, or that maps a normal to one without
    /// direction (a position it moves out of range is [`MeshError::PositionOutOfRange`]).
    InvalidTransform {
        /// What is wrong, e.g. `"not invertible"`.
        reason: &'static str,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoTriangles => f.write_str("a mesh needs at least one triangle"),
            Self::NonFinitePosition { vertex } => {
                write!(f, "position of vertex {vertex} is not finite")
            }
            Self::PositionOutOfRange { vertex, value } => write!(
                f,
                "vertex {vertex} has coordinate {}, beyond ±{} (MAX_COORDINATE)",
                Shown(*value),
                Shown(crate::MAX_COORDINATE)
            ),
            Self::InvalidNormal { vertex } => {
                write!(f, "normal of vertex {vertex} is zero or not finite")
            }
            Self::NormalCountMismatch { positions, normals } => {
                write!(f, "{normals} normals for {positions} positions")
            }
            Self::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} refers to vertex {index}, \
                 but there are {vertex_count} vertices"
            ),
            Self::GroupCountMismatch { triangles, groups } => {
                write!(f, "{groups} group ids for {triangles} triangles")
            }
            Self::GroupOutOfRange {
                triangle,
                group,
                group_count,
            } => write!(
                f,
                "triangle {triangle} is in group {group}, but there are {group_count} groups"
            ),
            Self::TooManyVertices { count } => write!(
                f,
                "{count} vertices: more than u32 indices can address (2^32)"
            ),
            Self::TooManyGroups { count } => {
                write!(f, "{count} groups: more than u32 ids can address (2^32)")
            }
            Self::InvalidTransform { reason } => write!(f, "transform is {reason}"),
        }
    }
}

impl std::error::Error for MeshError {}
