//! A flat rectangle: the ground.

use glam::DVec3;

use super::ShapeError;
use super::builder::MeshBuilder;
use super::parameters::{at_least, positive, triangle_budget};
use crate::mesh::Mesh;

/// A rectangle of `size_x × size_z` in the plane y = 0, centred on the origin and facing +y,
/// divided into `segments × segments` equal quads (two triangles each) that share their vertices.
/// One group, `"plane"`.
///
/// # Errors
/// [`ShapeError::InvalidParameter`] naming `size_x` or `size_z` (finite and > 0) or `segments`
/// (at least 1); [`ShapeError::TooManyTriangles`].
pub fn plane(size_x: f64, size_z: f64, segments: u32) -> Result<Mesh, ShapeError> {
    let size = DVec3::new(
        positive("size_x", size_x)?,
        0.0,
        positive("size_z", size_z)?,
    );
    let segments = at_least("segments", segments, 1, "at least 1")?;
    let n = u128::from(segments);
    triangle_budget("plane", 2 * n * n)?;
    let mut builder = MeshBuilder::default();
    let steps = f64::from(segments);
    let mut rows = Vec::with_capacity(segments as usize + 1);
    for i in 0..=segments {
        let row: Vec<u32> = (0..=segments)
            .map(|j| {
                let t = DVec3::new(f64::from(i) / steps, 0.0, f64::from(j) / steps);
                builder.vertex(size * (t - 0.5 * DVec3::new(1.0, 0.0, 1.0)), DVec3::Y)
            })
            .collect();
        rows.push(row);
    }
    for i in 0..segments as usize {
        for j in 0..segments as usize {
            // +z then +x is counter-clockwise seen from +y.
            builder.quad(
                [
                    rows[i][j],
                    rows[i][j + 1],
                    rows[i + 1][j + 1],
                    rows[i + 1][j],
                ],
                0,
            );
        }
    }
    builder.finish(&["plane"])
}
