//! A capped cylinder.

use std::f64::consts::TAU;

use glam::DVec3;

use super::ShapeError;
use super::builder::MeshBuilder;
use super::parameters::{at_least, positive, triangle_budget};
use crate::mesh::Mesh;

/// A closed cylinder of the given radius and height, centred on the origin with its axis along y
/// (from y = −height/2 to +height/2): the side is `segments` quads with radial normals, each cap a
/// fan of `segments` triangles around its centre with normal ±y; `4·segments` triangles. The
/// cross-section is the regular polygon with vertices `radius·(cos φ, ·, sin φ)`, φ = 2πj/segments,
/// so the volume is exactly `segments/2 · radius² · sin(2π/segments) · height`. One group,
/// `"cylinder"`.
///
/// # Errors
/// [`ShapeError::InvalidParameter`] naming `radius` or `height` (finite and > 0) or `segments`
/// (at least 3); [`ShapeError::TooManyTriangles`].
pub fn cylinder(radius: f64, height: f64, segments: u32) -> Result<Mesh, ShapeError> {
    let radius = positive("radius", radius)?;
    let half_height = 0.5 * positive("height", height)?;
    let segments = at_least("segments", segments, 3, "at least 3")?;
    triangle_budget("cylinder", 4 * u128::from(segments))?;
    let directions: Vec<DVec3> = (0..segments)
        .map(|j| {
            let (sin_phi, cos_phi) = (TAU * f64::from(j) / f64::from(segments)).sin_cos();
            DVec3::new(cos_phi, 0.0, sin_phi)
        })
        .collect();
    let rim = |direction: DVec3, y: f64| radius * direction + DVec3::new(0.0, y, 0.0);

    let mut builder = MeshBuilder::default();
    let mut ring = |y: f64, normal: Option<DVec3>| -> Vec<u32> {
        directions
            .iter()
            .map(|&d| builder.vertex(rim(d, y), normal.unwrap_or(d)))
            .collect()
    };
    let side_top = ring(half_height, None);
    let side_bottom = ring(-half_height, None);
    let cap_top = ring(half_height, Some(DVec3::Y));
    let cap_bottom = ring(-half_height, Some(DVec3::NEG_Y));
    let top_centre = builder.vertex(DVec3::new(0.0, half_height, 0.0), DVec3::Y);
    let bottom_centre = builder.vertex(DVec3::new(0.0, -half_height, 0.0), DVec3::NEG_Y);

    // φ grows from +x toward +z, clockwise seen from +y (see `sphere`).
    let segments = segments as usize;
    for j in 0..segments {
        let k = (j + 1) % segments;
        builder.quad(
            [side_top[j], side_top[k], side_bottom[k], side_bottom[j]],
            0,
        );
        builder.triangle([top_centre, cap_top[k], cap_top[j]], 0);
        builder.triangle([bottom_centre, cap_bottom[j], cap_bottom[k]], 0);
    }
    builder.finish(&["cylinder"])
}
