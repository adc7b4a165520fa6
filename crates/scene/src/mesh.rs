//! The triangle mesh: validated f64 positions, unit normals, triangles and per-triangle groups.

use glam::{DAffine3, DVec3};

use crate::bounds::Bounds;
use crate::error::SceneError;
use crate::normals;

/// The most vertices a mesh can have: every index is a `u32`.
pub(crate) const MAX_VERTICES: u64 = 1 << 32;

/// The name of the one group of a mesh built without groups.
pub const DEFAULT_GROUP_NAME: &str = "default";

/// A triangle mesh in f64: positions, unit per-vertex normals, triangles (counter-clockwise seen
/// from the side the normals face), and for each triangle the index of the group (part) it came
/// from.
///
/// # Guarantees
/// - At least one triangle; every index is in range.
/// - Every position is finite.
/// - One normal per position, finite and of unit length (to rounding).
/// - One group id per triangle, each less than [`Mesh::group_count`]; every group has a name
///   ([`Mesh::group_names`]), which need not be unique.
///
/// # Not checked
/// Degenerate (zero-area) triangles are allowed: renderers must cope with them. Whether the normals
/// given to [`Mesh::with_normals`] (or by an OBJ file) agree with the winding is the caller's
/// business; computed normals agree wherever the triangles have area. Vertices that no triangle uses are allowed, and count in
/// the bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    groups: Vec<u32>,
    group_names: Vec<String>,
    bounds: Bounds,
}

impl Mesh {
    /// A mesh with area-weighted vertex normals, all triangles in one group named
    /// [`DEFAULT_GROUP_NAME`].
    ///
    /// A vertex's normal is the normalised sum of `(b − a) × (c − a)` over its triangles
    /// `[a, b, c]` (each triangle weighted by its area); where that sum has no direction (no
    /// triangle, only zero-area triangles, or normals that cancel) it is
    /// [`crate::FALLBACK_NORMAL`], `+z`.
    ///
    /// # Errors
    /// [`SceneError::NoTriangles`], [`SceneError::NonFinitePosition`],
    /// [`SceneError::IndexOutOfRange`], [`SceneError::TooManyVertices`].
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, SceneError> {
        check_geometry(&positions, &triangles)?;
        let normals = normals::area_weighted(&positions, &triangles);
        Ok(Self::from_checked(positions, normals, triangles))
    }

    /// A mesh with the given normals, normalised; all triangles in one group named
    /// [`DEFAULT_GROUP_NAME`].
    ///
    /// # Errors
    /// As [`Mesh::new`], and [`SceneError::NormalCountMismatch`] or [`SceneError::InvalidNormal`]
    /// (a zero or non-finite normal).
    pub fn with_normals(
        positions: Vec<DVec3>,
        normals: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
    ) -> Result<Self, SceneError> {
        check_geometry(&positions, &triangles)?;
        if normals.len() != positions.len() {
            return Err(SceneError::NormalCountMismatch {
                positions: positions.len(),
                normals: normals.len(),
            });
        }
        let normals = normals
            .into_iter()
            .enumerate()
            .map(|(vertex, n)| normals::unit(n).ok_or(SceneError::InvalidNormal { vertex }))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_checked(positions, normals, triangles))
    }

    /// This mesh with its triangles assigned to named groups: `groups[t]` is the group of triangle
    /// `t`, an index into `names`.
    ///
    /// # Errors
    /// [`SceneError::GroupCountMismatch`] unless there is one id per triangle;
    /// [`SceneError::GroupOutOfRange`] for an id without a name; [`SceneError::TooManyGroups`].
    pub fn with_groups(self, groups: Vec<u32>, names: Vec<String>) -> Result<Self, SceneError> {
        if groups.len() != self.triangles.len() {
            return Err(SceneError::GroupCountMismatch {
                triangles: self.triangles.len(),
                groups: groups.len(),
            });
        }
        check_group_count(names.len())?;
        if let Some((triangle, &group)) = groups
            .iter()
            .enumerate()
            .find(|&(_, &group)| group as usize >= names.len())
        {
            return Err(SceneError::GroupOutOfRange {
                triangle,
                group,
                group_count: names.len(),
            });
        }
        Ok(Self {
            groups,
            group_names: names,
            ..self
        })
    }

    /// Builds a mesh from parts already checked; one default group.
    fn from_checked(positions: Vec<DVec3>, normals: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        let bounds = Bounds::of_points(&positions)
            .expect("a checked mesh has a triangle, so at least one vertex");
        let groups = vec![0; triangles.len()];
        Self {
            positions,
            normals,
            triangles,
            groups,
            group_names: vec![DEFAULT_GROUP_NAME.to_owned()],
            bounds,
        }
    }

    /// The vertex positions.
    #[must_use]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The unit vertex normals, one per position.
    #[must_use]
    pub fn normals(&self) -> &[DVec3] {
        &self.normals
    }

    /// The triangles, as indices into [`Mesh::positions`], counter-clockwise seen from the side the
    /// normals face.
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The group id of each triangle, an index into [`Mesh::group_names`].
    #[must_use]
    pub fn groups(&self) -> &[u32] {
        &self.groups
    }

    /// The name of each group (for OBJ files, the `g`/`o` names).
    #[must_use]
    pub fn group_names(&self) -> &[String] {
        &self.group_names
    }

    /// The number of groups.
    #[must_use]
    pub fn group_count(&self) -> usize {
        self.group_names.len()
    }

    /// The number of triangles (at least 1).
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The positions of triangle `index`'s corners.
    ///
    /// # Panics
    /// If `index ≥ triangle_count()`.
    #[must_use]
    pub fn triangle_positions(&self, index: usize) -> [DVec3; 3] {
        self.triangles[index].map(|i| self.positions[i as usize])
    }

    /// The axis-aligned bounds of all positions (finite; computed once, at construction).
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// The total area of the triangles.
    #[must_use]
    pub fn surface_area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.triangle_positions(t);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// The signed volume enclosed, `Σ a·(b × c)/6` over the triangles: positive for a closed mesh
    /// whose triangles are counter-clockwise seen from outside. It is computed relative to the
    /// bounds' centre, which changes nothing for a closed mesh and keeps rounding small far from
    /// the origin; for an open mesh it is the volume of the cones from that centre.
    #[must_use]
    pub fn signed_volume(&self) -> f64 {
        let centre = self.bounds.centre();
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.triangle_positions(t).map(|p| p - centre);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// This mesh moved by `transform`: positions are transformed as points, normals by the inverse
    /// transpose of the linear part and renormalised. A transform that mirrors (negative
    /// determinant) also reverses each triangle's winding, so triangles stay counter-clockwise seen
    /// from the side the normals face. Groups are kept.
    ///
    /// # Panics
    /// Where [`Mesh::try_transformed`] returns an error: a non-finite or non-invertible transform,
    /// or one that sends a position to infinity.
    #[must_use]
    pub fn transformed(&self, transform: &DAffine3) -> Self {
        self.try_transformed(transform)
            .unwrap_or_else(|error| panic!("Mesh::transformed: {error}"))
    }

    /// [`Mesh::transformed`], returning an error instead of panicking.
    ///
    /// # Errors
    /// [`SceneError::InvalidTransform`] if the transform is not finite, its determinant is zero (or
    /// so small that it underflows to zero, e.g. a uniform scale by 10⁻¹¹⁰) or not finite, a
    /// transformed position is not finite, or a transformed normal has no direction.
    pub fn try_transformed(&self, transform: &DAffine3) -> Result<Self, SceneError> {
        if !transform.is_finite() {
            return Err(SceneError::InvalidTransform {
                reason: "not finite",
            });
        }
        let linear = transform.matrix3;
        let determinant = linear.determinant();
        if determinant == 0.0 || !determinant.is_finite() {
            return Err(SceneError::InvalidTransform {
                reason: "not invertible (its determinant is 0, underflows to 0, or overflows)",
            });
        }
        let normal_matrix = linear.inverse().transpose();
        let positions = self
            .positions
            .iter()
            .map(|&p| {
                let q = transform.transform_point3(p);
                q.is_finite()
                    .then_some(q)
                    .ok_or(SceneError::InvalidTransform {
                        reason: "sending a vertex to a non-finite position",
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let normals = self
            .normals
            .iter()
            .map(|&n| {
                normals::unit(normal_matrix * n).ok_or(SceneError::InvalidTransform {
                    reason: "sending a normal to one without direction",
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let triangles = if determinant < 0.0 {
            self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect()
        } else {
            self.triangles.clone()
        };
        let bounds = Bounds::of_points(&positions).expect("a mesh has at least one vertex");
        Ok(Self {
            positions,
            normals,
            triangles,
            groups: self.groups.clone(),
            group_names: self.group_names.clone(),
            bounds,
        })
    }

    /// The meshes as one: vertices and triangles concatenated in order, and each mesh's groups kept
    /// apart (mesh k's group ids are offset by the group counts of meshes 0..k, and the group names
    /// concatenated), so every triangle still tells which part it came from.
    ///
    /// # Panics
    /// Where [`Mesh::try_merged`] returns an error: no meshes, or more than 2³² vertices or groups.
    #[must_use]
    pub fn merged(meshes: &[Self]) -> Self {
        Self::try_merged(meshes).unwrap_or_else(|error| panic!("Mesh::merged: {error}"))
    }

    /// [`Mesh::merged`], returning an error instead of panicking.
    ///
    /// # Errors
    /// [`SceneError::NoTriangles`] for an empty slice; [`SceneError::TooManyVertices`],
    /// [`SceneError::TooManyGroups`].
    pub fn try_merged(meshes: &[Self]) -> Result<Self, SceneError> {
        let vertex_count: u64 = meshes.iter().map(|m| m.positions.len() as u64).sum();
        if vertex_count > MAX_VERTICES {
            return Err(SceneError::TooManyVertices {
                count: vertex_count,
            });
        }
        let group_count: usize = meshes.iter().map(|m| m.group_names.len()).sum();
        check_group_count(group_count)?;
        let bounds = meshes
            .iter()
            .map(|m| m.bounds)
            .reduce(|a, b| a.union(&b))
            .ok_or(SceneError::NoTriangles)?;
        let mut merged = Self {
            positions: Vec::with_capacity(meshes.iter().map(|m| m.positions.len()).sum()),
            normals: Vec::with_capacity(meshes.iter().map(|m| m.normals.len()).sum()),
            triangles: Vec::with_capacity(meshes.iter().map(|m| m.triangles.len()).sum()),
            groups: Vec::with_capacity(meshes.iter().map(|m| m.groups.len()).sum()),
            group_names: Vec::with_capacity(group_count),
            bounds,
        };
        for mesh in meshes {
            let vertex_offset = index_u32(merged.positions.len());
            let group_offset = index_u32(merged.group_names.len());
            merged.positions.extend_from_slice(&mesh.positions);
            merged.normals.extend_from_slice(&mesh.normals);
            merged
                .triangles
                .extend(mesh.triangles.iter().map(|t| t.map(|i| i + vertex_offset)));
            merged
                .groups
                .extend(mesh.groups.iter().map(|g| g + group_offset));
            merged.group_names.extend_from_slice(&mesh.group_names);
        }
        Ok(merged)
    }
}

/// `value` as a `u32`, for offsets already checked against [`MAX_VERTICES`] and the group limit.
/// The offset of the last mesh is below the total, so it fits even when the total is 2³².
fn index_u32(value: usize) -> u32 {
    u32::try_from(value).expect("offsets are checked against the u32 limits before merging")
}

/// Checks a group count against the `u32` id limit.
fn check_group_count(count: usize) -> Result<(), SceneError> {
    if count as u64 > MAX_VERTICES {
        return Err(SceneError::TooManyGroups {
            count: count as u64,
        });
    }
    Ok(())
}

/// Checks positions and triangles: at least one triangle, finite positions, indices in range, and a
/// vertex count that `u32` indices can address.
fn check_geometry(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), SceneError> {
    if triangles.is_empty() {
        return Err(SceneError::NoTriangles);
    }
    if positions.len() as u64 > MAX_VERTICES {
        return Err(SceneError::TooManyVertices {
            count: positions.len() as u64,
        });
    }
    if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
        return Err(SceneError::NonFinitePosition { vertex });
    }
    for (triangle, corners) in triangles.iter().enumerate() {
        if let Some(&index) = corners.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(SceneError::IndexOutOfRange {
                triangle,
                index,
                vertex_count: positions.len(),
            });
        }
    }
    Ok(())
}
