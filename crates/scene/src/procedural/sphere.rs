//! A UV sphere.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::ShapeError;
use super::builder::MeshBuilder;
use super::parameters::{at_least, positive, triangle_budget};
use crate::mesh::Mesh;

/// A closed UV sphere of the given radius, centred on the origin with its poles on the y axis:
/// `rings` bands of latitude (polar angle θ = πk/rings) and `segments` of longitude
/// (φ = 2πj/segments), one vertex at each pole, `2·segments·(rings − 1)` triangles. Every vertex
/// lies on the sphere (to rounding) and its normal is its exact radial direction. One group,
/// `"sphere"`.
///
/// The vertex at (θ, φ) is `radius·(sin θ cos φ, cos θ, sin θ sin φ)`.
///
/// # Errors
/// [`ShapeError::InvalidParameter`] naming `radius` (finite and > 0), `segments` (at least 3) or
/// `rings` (at least 2); [`ShapeError::TooManyTriangles`].
pub fn sphere(radius: f64, segments: u32, rings: u32) -> Result<Mesh, ShapeError> {
    let radius = positive("radius", radius)?;
    let segments = at_least("segments", segments, 3, "at least 3")?;
    let rings = at_least("rings", rings, 2, "at least 2")?;
    triangle_budget("sphere", 2 * u128::from(segments) * (u128::from(rings) - 1))?;
    let mut builder = MeshBuilder::default();
    let north = builder.vertex(radius * DVec3::Y, DVec3::Y);
    let circles: Vec<Vec<u32>> = (1..rings)
        .map(|k| {
            let (sin_theta, cos_theta) = (PI * f64::from(k) / f64::from(rings)).sin_cos();
            (0..segments)
                .map(|j| {
                    let (sin_phi, cos_phi) = (TAU * f64::from(j) / f64::from(segments)).sin_cos();
                    let direction = DVec3::new(sin_theta * cos_phi, cos_theta, sin_theta * sin_phi);
                    builder.vertex(radius * direction, direction)
                })
                .collect()
        })
        .collect();
    let south = builder.vertex(radius * DVec3::NEG_Y, DVec3::NEG_Y);

    // φ grows from +x toward +z, which is clockwise seen from +y; so, seen from outside, a band's
    // quad [upper j, upper j+1, lower j+1, lower j] is counter-clockwise.
    let segments = segments as usize;
    let next = |j: usize| (j + 1) % segments;
    let (first, last) = (&circles[0], &circles[circles.len() - 1]);
    for j in 0..segments {
        builder.triangle([north, first[next(j)], first[j]], 0);
        builder.triangle([last[j], last[next(j)], south], 0);
    }
    for band in circles.windows(2) {
        let (upper, lower) = (&band[0], &band[1]);
        for j in 0..segments {
            builder.quad([upper[j], upper[next(j)], lower[next(j)], lower[j]], 0);
        }
    }
    builder.finish(&["sphere"])
}
