//! An axis-aligned box.

use glam::DVec3;

use super::ShapeError;
use super::builder::MeshBuilder;
use super::parameters::positive;
use crate::mesh::Mesh;

/// A closed axis-aligned box of the given size, centred on the origin: 24 vertices (each face has
/// its own four, with the face's normal) and 12 triangles. One group, `"cuboid"`.
///
/// # Errors
/// [`ShapeError::InvalidParameter`] naming `size.x`, `size.y` or `size.z` (finite and > 0).
pub fn cuboid(size: DVec3) -> Result<Mesh, ShapeError> {
    let half_size = 0.5
        * DVec3::new(
            positive("size.x", size.x)?,
            positive("size.y", size.y)?,
            positive("size.z", size.z)?,
        );
    let mut builder = MeshBuilder::default();
    builder.cuboid(DVec3::ZERO, half_size, 0);
    builder.finish(&["cuboid"])
}
