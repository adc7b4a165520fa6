//! The triangle mesh: validated f64 positions, unit normals, triangles and per-triangle groups.

use glam::{DAffine3, DVec3};

use crate::bounds::Bounds;
use crate::normals;

mod error;

pub use error::MeshError;

/// The most vertices a mesh can have: every index is a `u32`.
pub(crate) const MAX_VERTICES: u64 = 1 << 32;

/// The largest coordinate magnitude of a mesh's positions: 10⁴⁰. Differences and squared extents of
/// such coordinates stay finite and normal in f64 (squares up to about 10⁸¹), and the ray caster's
/// range (`shadowlab_trace::MAX_COORDINATE`, 2²⁰⁰ ≈ 1.6·10⁶⁰) leaves 10²⁰ of room for the eye,
/// the lights and the planes derived from the scene. Every technique was tried on a box and sphere
/// at this scale; at 10⁶⁰ the exact truth's rays leave the ray caster's range.
pub const MAX_COORDINATE: f64 = 1e40;

/// The smallest largest extent (the largest side of the bounding box) of a mesh read from an OBJ
/// file or of a scene: 10⁻⁴⁰, the reciprocal of [`MAX_COORDINATE`], so that squared extents stay
/// normal f64 numbers (about 10⁻⁸⁰, far above the smallest normal, 2.2·10⁻³⁰⁸). Every technique was
/// tried on a scene of this size; a mesh of denormal coordinates has no extent the planners can
/// measure. [`Mesh`] itself allows any extent, a single point included.
pub const MIN_EXTENT: f64 = 1e-40;

/// The name of the one group of a mesh built without groups.
pub const DEFAULT_GROUP_NAME: &str = "default";

/// A triangle mesh in f64: positions, unit per-vertex normals, triangles (counter-clockwise seen
/// from the side the normals face), and for each triangle the index of the group (part) it came
/// from.
///
/// # Guarantees
/// - At least one triangle; every index is in range.
/// - Every position is finite, each coordinate within ±[`MAX_COORDINATE`].
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
    /// [`MeshError::NoTriangles`], [`MeshError::NonFinitePosition`],
    /// [`MeshError::PositionOutOfRange`], [`MeshError::IndexOutOfRange`],
    /// [`MeshError::TooManyVertices`].
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        check_geometry(&positions, &triangles)?;
        let normals = normals::area_weighted(&positions, &triangles);
        Ok(Self::from_checked(positions, normals, triangles))
    }

    /// A mesh with the given normals, normalised; all triangles in one group named
    /// [`DEFAULT_GROUP_NAME`].
    ///
    /// # Errors
    /// As [`Mesh::new`], and [`MeshError::NormalCountMismatch`] or [`MeshError::InvalidNormal`]
    /// (a zero or non-finite normal).
    pub fn with_normals(
        positions: Vec<DVec3>,
        normals: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
    ) -> Result<Self, MeshError> {
        check_geometry(&positions, &triangles)?;
        if normals.len() != positions.len() {
            return Err(MeshError::NormalCountMismatch {
                positions: positions.len(),
                normals: normals.len(),
            });
        }
        let normals = normals
            .into_iter()
            .enumerate()
            .map(|(vertex, n)| normals::unit(n).ok_or(MeshError::InvalidNormal { vertex }))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_checked(positions, normals, triangles))
    }

    /// This mesh with its triangles assigned to named groups: `groups[t]` is the group of triangle
    /// `t`, an index into `names`.
    ///
    /// # Errors
    /// [`MeshError::GroupCountMismatch`] unless there is one id per triangle;
    /// [`MeshError::GroupOutOfRange`] for an id without a name; [`MeshError::TooManyGroups`].
    pub fn with_groups(self, groups: Vec<u32>, names: Vec<String>) -> Result<Self, MeshError> {
        if groups.len() != self.triangles.len() {
            return Err(MeshError::GroupCountMismatch {
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
            return Err(MeshError::GroupOutOfRange {
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
    /// [`MeshError::InvalidTransform`] if the transform is not finite, its determinant is zero (or
    /// so small that it underflows to zero, e.g. a uniform scale by 10⁻¹¹⁰) or not finite, a
    /// transformed position is not finite, or a transformed normal has no direction;
    /// [`MeshError::PositionOutOfRange`] if a transformed position lies beyond
    /// ±[`MAX_COORDINATE`].
    pub fn try_transformed(&self, transform: &DAffine3) -> Result<Self, MeshError> {
        if !transform.is_finite() {
            return Err(MeshError::InvalidTransform {
                reason: "not finite",
            });
        }
        let linear = transform.matrix3;
        let determinant = linear.determinant();
        if determinant == 0.0 || !determinant.is_finite() {
            return Err(MeshError::InvalidTransform {
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
                    .ok_or(MeshError::InvalidTransform {
                        reason: "sending a vertex to a non-finite position",
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        check_range(&positions)?;
        let normals = self
            .normals
            .iter()
            .map(|&n| {
                normals::unit(normal_matrix * n).ok_or(MeshError::InvalidTransform {
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
    /// [`MeshError::NoTriangles`] for an empty slice; [`MeshError::TooManyVertices`],
    /// [`MeshError::TooManyGroups`].
    pub fn try_merged(meshes: &[Self]) -> Result<Self, MeshError> {
        let vertex_count: u64 = meshes.iter().map(|m| m.positions.len() as u64).sum();
        if vertex_count > MAX_VERTICES {
            return Err(MeshError::TooManyVertices {
                count: vertex_count,
            });
        }
        let group_count: usize = meshes.iter().map(|m| m.group_names.len()).sum();
        check_group_count(group_count)?;
        let bounds = meshes
            .iter()
            .map(|m| m.bounds)
            .reduce(|a, b| a.union(&b))
            .ok_or(MeshError::NoTriangles)?;
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
fn check_group_count(count: usize) -> Result<(), MeshError> {
    if count as u64 > MAX_VERTICES {
        return Err(MeshError::TooManyGroups {
            count: count as u64,
        });
    }
    Ok(())
}

/// Checks positions and triangles: at least one triangle, finite positions, indices in range, and a
/// vertex count that `u32` indices can address.
fn check_geometry(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), MeshError> {
    if triangles.is_empty() {
        return Err(MeshError::NoTriangles);
    }
    if positions.len() as u64 > MAX_VERTICES {
        return Err(MeshError::TooManyVertices {
            count: positions.len() as u64,
        });
    }
    if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
        return Err(MeshError::NonFinitePosition { vertex });
    }
    check_range(positions)?;
    for (triangle, corners) in triangles.iter().enumerate() {
        if let Some(&index) = corners.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(MeshError::IndexOutOfRange {
                triangle,
                index,
                vertex_count: positions.len(),
            });
        }
    }
    Ok(())
}

/// Checks that every coordinate lies within ±[`MAX_COORDINATE`].
fn check_range(positions: &[DVec3]) -> Result<(), MeshError> {
    match positions
        .iter()
        .enumerate()
        .find(|(_, p)| p.abs().max_element() > MAX_COORDINATE)
    {
        Some((vertex, p)) => Err(MeshError::PositionOutOfRange {
            vertex,
            value: if p.x.abs() > MAX_COORDINATE {
                p.x
            } else if p.y.abs() > MAX_COORDINATE {
                p.y
            } else {
                p.z
            },
        }),
        None => Ok(()),
    }
}
