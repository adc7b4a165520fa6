//! Procedural meshes: the shapes of shadow-map test scenes, built exactly from their parameters.
//!
//! Every function validates its parameters and returns [`ShapeError::InvalidParameter`] naming the
//! first bad one, or [`ShapeError::TooManyTriangles`] past [`MAX_TRIANGLES`].
//!
//! # Conventions
//! - **y is up** (the world is right-handed, as in `shadowlab-hull`); every shape is centred on the
//!   origin: flat shapes lie in the plane y = 0 facing +y, round ones have their axis along y.
//! - Triangles are counter-clockwise seen from outside (from +y for flat shapes), and the normals
//!   face outward. Closed shapes ([`cuboid`], [`sphere`], [`cylinder`], each bar of
//!   [`bar_lattice`]) are watertight: every edge is shared by exactly two triangles that traverse
//!   it in opposite directions (comparing corners by position, as vertices are split where normals
//!   are discontinuous).
//! - Normals are exact where the shape has them: face normals on flat faces (vertices are split at
//!   sharp edges), the radial direction on spheres and cylinder sides.
//! - Vertices that must coincide are computed by the same expression, so they are bit-identical.

mod bar_lattice;
mod builder;
mod chess_board;
mod cuboid;
mod cylinder;
mod error;
mod parameters;
mod plane;
mod sphere;

pub use bar_lattice::{BAR_LATTICE_GROUPS, bar_lattice};
pub use chess_board::{CHESS_DARK, CHESS_FRAME, CHESS_LIGHT, chess_board};
pub use cuboid::cuboid;
pub use cylinder::cylinder;
pub use error::ShapeError;
pub use plane::plane;
pub use sphere::sphere;

/// The most triangles a procedural mesh may have: 2²⁴ = 16 777 216 (about 20 times the Stanford
/// dragon), so that a mistyped parameter fails at once instead of exhausting memory.
pub const MAX_TRIANGLES: u64 = 1 << 24;
