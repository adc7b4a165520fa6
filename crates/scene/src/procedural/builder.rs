//! Accumulates the vertices, triangles and groups of a procedural mesh.

use glam::DVec3;

use super::ShapeError;
use crate::mesh::Mesh;

/// A mesh under construction. Procedural shapes check their triangle budget first, so the vertex
/// count always fits a `u32`.
#[derive(Default)]
pub(super) struct MeshBuilder {
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    groups: Vec<u32>,
}

impl MeshBuilder {
    /// Adds a vertex and returns its index.
    pub(super) fn vertex(&mut self, position: DVec3, normal: DVec3) -> u32 {
        let index = u32::try_from(self.positions.len())
            .expect("procedural shapes check their size before building");
        self.positions.push(position);
        self.normals.push(normal);
        index
    }

    /// Adds a triangle, counter-clockwise seen from outside.
    pub(super) fn triangle(&mut self, corners: [u32; 3], group: u32) {
        self.triangles.push(corners);
        self.groups.push(group);
    }

    /// Adds the quad `[a, b, c, d]` (counter-clockwise seen from outside) as the triangles
    /// `[a, b, c]` and `[a, c, d]`.
    pub(super) fn quad(&mut self, [a, b, c, d]: [u32; 4], group: u32) {
        self.triangle([a, b, c], group);
        self.triangle([a, c, d], group);
    }

    /// Adds a closed axis-aligned box with flat faces (4 vertices per face, 12 triangles).
    pub(super) fn cuboid(&mut self, centre: DVec3, half_size: DVec3, group: u32) {
        // For each face: its outward axis, and two tangent axes u, v with u × v = outward, so that
        // the corners (−u, −v), (+u, −v), (+u, +v), (−u, +v) run counter-clockwise seen from
        // outside.
        const FACES: [(DVec3, DVec3, DVec3); 6] = [
            (DVec3::X, DVec3::Y, DVec3::Z),
            (DVec3::NEG_X, DVec3::Z, DVec3::Y),
            (DVec3::Y, DVec3::Z, DVec3::X),
            (DVec3::NEG_Y, DVec3::X, DVec3::Z),
            (DVec3::Z, DVec3::X, DVec3::Y),
            (DVec3::NEG_Z, DVec3::Y, DVec3::X),
        ];
        for (outward, u, v) in FACES {
            let corner = |su: f64, sv: f64| centre + half_size * (outward + su * u + sv * v);
            let quad = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(su, sv)| self.vertex(corner(su, sv), outward));
            self.quad(quad, group);
        }
    }

    /// The finished mesh, with the given group names.
    ///
    /// # Errors
    /// [`ShapeError::Mesh`] if a vertex lies beyond ±[`crate::MAX_COORDINATE`] (a size too large).
    pub(super) fn finish(self, group_names: &[&str]) -> Result<Mesh, ShapeError> {
        let mesh = Mesh::with_normals(self.positions, self.normals, self.triangles)?.with_groups(
            self.groups,
            group_names.iter().map(|&name| name.to_owned()).collect(),
        )?;
        Ok(mesh)
    }
}
