//! A lattice of thin bars: the hard case of thin geometry for shadow maps.

use glam::DVec3;

use super::ShapeError;
use super::builder::MeshBuilder;
use super::parameters::{positive, triangle_budget};
use crate::mesh::Mesh;

/// The group names of [`bar_lattice`]: group `a` holds the bars along axis `a`.
pub const BAR_LATTICE_GROUPS: [&str; 3] = ["bars along x", "bars along y", "bars along z"];

/// A 3-D grid of thin square bars, like scaffolding or the trusses of a CAD model: the thin
/// geometry that shadow maps alias worst (the CAD survey's and GMNPR's thin-bar set-ups).
///
/// The lattice has `cells[a]` cells of size `spacing` along axis `a`, so `cells[a] + 1` nodes at
/// `(i − cells[a]/2)·spacing`, centred on the origin. Along every axis with at least one cell, a
/// bar runs through each line of nodes: a closed box of cross-section `thickness × thickness`,
/// centred on the line, extending `thickness/2` past the end nodes so that the lattice's corners
/// are filled. Bars cross (and overlap) at the nodes; each is closed on its own (bars that end in
/// the same corner share the corner's edges). Axes with zero
/// cells have no bars, so `[n, 0, m]` is a flat grating in the plane y = 0 and `[n, 0, 0]` a single
/// bar. Each bar has 24 vertices and 12 triangles; the bars along axis a are group a
/// ([`BAR_LATTICE_GROUPS`]). The bounds are `±(cells·spacing/2 + thickness/2)` on each axis.
///
/// # Errors
/// [`ShapeError::InvalidParameter`] naming `spacing` (finite and > 0), `thickness` (finite, > 0
/// and less than `spacing`, so that the bars stay apart) or `cells` (at least one non-zero);
/// [`ShapeError::TooManyTriangles`].
pub fn bar_lattice(cells: [u32; 3], spacing: f64, thickness: f64) -> Result<Mesh, ShapeError> {
    let spacing = positive("spacing", spacing)?;
    let thickness = positive("thickness", thickness)?;
    if thickness >= spacing {
        return Err(ShapeError::InvalidParameter {
            parameter: "thickness",
            value: thickness,
            requirement: "less than `spacing`",
        });
    }
    if cells == [0; 3] {
        return Err(ShapeError::InvalidParameter {
            parameter: "cells",
            value: 0.0,
            requirement: "non-zero on at least one axis",
        });
    }
    let nodes = cells.map(|c| u128::from(c) + 1);
    let bar_count: u128 = (0..3)
        .filter(|&a| cells[a] > 0)
        .map(|a| nodes[(a + 1) % 3] * nodes[(a + 2) % 3])
        .sum();
    triangle_budget("bar_lattice", 12 * bar_count)?;

    let half_extent = DVec3::from_array(cells.map(f64::from)) * (0.5 * spacing);
    let node = |axis: usize, i: u32| -half_extent[axis] + f64::from(i) * spacing;
    let mut builder = MeshBuilder::default();
    for axis in 0..3 {
        if cells[axis] == 0 {
            continue;
        }
        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut half_size = DVec3::splat(0.5 * thickness);
        half_size[axis] = half_extent[axis] + 0.5 * thickness;
        for i in 0..=cells[b] {
            for j in 0..=cells[c] {
                let mut centre = DVec3::ZERO;
                centre[b] = node(b, i);
                centre[c] = node(c, j);
                let group = u32::try_from(axis).expect("three axes");
                builder.cuboid(centre, half_size, group);
            }
        }
    }
    builder.finish(&BAR_LATTICE_GROUPS)
}
