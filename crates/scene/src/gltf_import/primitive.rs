//! Mesh primitives (glTF 2.0 §3.7.2.1) as triangles in world space: triangle lists, strips and
//! fans, indexed or not; positions moved by the node's world transform in f64; normals from the
//! file (by the inverse transpose) or area-weighted; one group per node and primitive.

use std::path::Path;

use glam::{DAffine3, DVec3};
use gltf::json::{self, mesh::Mode, mesh::Semantic, validation::Checked};

use super::accessor::Accessors;
use super::error::{GltfError, GltfObject, GltfObjectKind, GltfProblem, GltfSkipped, GltfWarning};
use super::nodes::{Placed, node_object};
use crate::mesh::Mesh;
use crate::normals;

/// A primitive that will be drawn: which node places it, and where it is in the file.
pub(super) struct Drawn<'a> {
    /// The node and its world transform.
    pub(super) placed: &'a Placed,
    /// The mesh's index.
    pub(super) mesh: usize,
    /// The primitive's index in the mesh.
    pub(super) primitive: usize,
    /// Its mode, one of the triangle modes.
    pub(super) mode: Mode,
}

/// The name of a primitive mode, as glTF 2.0 §3.7.2.1 spells it.
fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Points => "POINTS",
        Mode::Lines => "LINES",
        Mode::LineLoop => "LINE_LOOP",
        Mode::LineStrip => "LINE_STRIP",
        Mode::Triangles => "TRIANGLES",
        Mode::TriangleStrip => "TRIANGLE_STRIP",
        Mode::TriangleFan => "TRIANGLE_FAN",
    }
}

/// The objects that name a primitive: its node, mesh and primitive.
pub(super) fn primitive_objects(root: &json::Root, drawn: &Drawn<'_>) -> Vec<GltfObject> {
    let mesh_name = root.meshes.get(drawn.mesh).and_then(|m| m.name.as_deref());
    vec![
        node_object(root, drawn.placed.node),
        GltfObject::new(GltfObjectKind::Mesh, drawn.mesh, mesh_name),
        GltfObject::new(GltfObjectKind::Primitive, drawn.primitive, None),
    ]
}

/// The primitives of `placed`'s mesh that will be drawn. Points and lines, a singular world
/// transform (the whole mesh), skins and morph targets (applied to nothing) are warnings.
pub(super) fn drawn_primitives<'a>(
    root: &json::Root,
    placed: &'a Placed,
    path: &Path,
    warnings: &mut Vec<GltfWarning>,
) -> Vec<Drawn<'a>> {
    let Some(node) = root.nodes.get(placed.node) else {
        return Vec::new();
    };
    let Some(mesh_index) = node.mesh.map(|m| m.value()) else {
        return Vec::new();
    };
    let Some(mesh) = root.meshes.get(mesh_index) else {
        return Vec::new();
    };
    let mut warn = |objects, skipped| {
        warnings.push(GltfWarning {
            path: path.to_owned(),
            objects,
            skipped,
        });
    };
    if let Some(skin) = node.skin {
        warn(
            vec![node_object(root, placed.node)],
            GltfSkipped::Skin { skin: skin.value() },
        );
    }
    let determinant = placed.world.matrix3.determinant();
    if determinant == 0.0 || !determinant.is_finite() {
        warn(
            vec![node_object(root, placed.node)],
            GltfSkipped::SingularTransform,
        );
        return Vec::new();
    }
    let mut drawn = Vec::new();
    for (index, primitive) in mesh.primitives.iter().enumerate() {
        let mode = match primitive.mode {
            Checked::Valid(mode) => mode,
            Checked::Invalid => Mode::Triangles,
        };
        let candidate = Drawn {
            placed,
            mesh: mesh_index,
            primitive: index,
            mode,
        };
        match mode {
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => {
                if let Some(targets) = primitive.targets.as_ref().filter(|t| !t.is_empty()) {
                    warn(
                        primitive_objects(root, &candidate),
                        GltfSkipped::MorphTargets {
                            count: targets.len(),
                        },
                    );
                }
                drawn.push(candidate);
            }
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => warn(
                primitive_objects(root, &candidate),
                GltfSkipped::PrimitiveMode {
                    mode: mode_name(mode),
                },
            ),
        }
    }
    drawn
}

/// The JSON of a drawn primitive.
fn json_primitive<'r>(
    root: &'r json::Root,
    drawn: &Drawn<'_>,
) -> Option<&'r json::mesh::Primitive> {
    root.meshes.get(drawn.mesh)?.primitives.get(drawn.primitive)
}

/// The accessors a drawn primitive reads: `POSITION`, `NORMAL` (if any), indices (if any).
pub(super) fn accessors_of(root: &json::Root, drawn: &Drawn<'_>) -> [Option<usize>; 3] {
    let Some(primitive) = json_primitive(root, drawn) else {
        return [None; 3];
    };
    let attribute = |semantic| {
        primitive
            .attributes
            .get(&Checked::Valid(semantic))
            .map(|a| a.value())
    };
    [
        attribute(Semantic::Positions),
        attribute(Semantic::Normals),
        primitive.indices.map(|i| i.value()),
    ]
}

/// How many triangles a primitive of `mode` makes from `count` vertices (or indices).
fn triangle_count(mode: Mode, count: usize) -> Result<usize, GltfProblem> {
    let bad = || GltfProblem::BadVertexCount {
        mode: mode_name(mode),
        count,
    };
    match mode {
        Mode::Triangles if count.is_multiple_of(3) => Ok(count / 3),
        Mode::TriangleStrip | Mode::TriangleFan if count >= 3 => Ok(count - 2),
        _ => Err(bad()),
    }
}

/// The numbers of triangles and vertices `drawn` will have, from its accessors' counts (no
/// buffer is read).
pub(super) fn planned_size(
    root: &json::Root,
    accessors: &Accessors<'_>,
    drawn: &Drawn<'_>,
    path: &Path,
) -> Result<(usize, usize), GltfError> {
    let objects = primitive_objects(root, drawn);
    let [positions, _, indices] = accessors_of(root, drawn);
    let Some(positions) = positions else {
        return Err(missing_position(path, objects));
    };
    let vertices = accessors.count(positions, &objects)?;
    let corners = match indices {
        Some(indices) => accessors.count(indices, &objects)?,
        None => vertices,
    };
    let triangles = triangle_count(drawn.mode, corners)
        .map_err(|problem| GltfError::object(path, objects, problem))?;
    Ok((triangles, vertices))
}

fn missing_position(path: &Path, objects: Vec<GltfObject>) -> GltfError {
    GltfError::object(
        path,
        objects,
        GltfProblem::Unusable {
            reason: "has no POSITION attribute".to_owned(),
        },
    )
}

/// The triangles of a primitive from its corner list, as glTF 2.0 §3.7.2.1 assembles them:
/// lists by threes; strip triangle i is (v_i, v_{i+1+i%2}, v_{i+2−i%2}); fan triangle i is
/// (v_{i+1}, v_{i+2}, v_0). All counter-clockwise for front faces.
fn assemble(mode: Mode, corners: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..corners.len().saturating_sub(2))
            .map(|i| {
                let odd = i % 2;
                [corners[i], corners[i + 1 + odd], corners[i + 2 - odd]]
            })
            .collect(),
        Mode::TriangleFan => (0..corners.len().saturating_sub(2))
            .map(|i| [corners[i + 1], corners[i + 2], corners[0]])
            .collect(),
        _ => corners
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    }
}

/// The group name of a drawn primitive: its node's name (else its mesh's, else `node N`), with
/// `/k` appended for primitive k of a mesh of several primitives.
fn group_name(root: &json::Root, drawn: &Drawn<'_>) -> String {
    let node = root.nodes.get(drawn.placed.node);
    let mesh = root.meshes.get(drawn.mesh);
    let label = node
        .and_then(|n| n.name.clone())
        .or_else(|| mesh.and_then(|m| m.name.clone()))
        .unwrap_or_else(|| format!("node {}", drawn.placed.node));
    if mesh.is_some_and(|m| m.primitives.len() > 1) {
        format!("{label}/{}", drawn.primitive)
    } else {
        label
    }
}

/// The mesh of one drawn primitive, in world space, in one group (see [`group_name`]).
pub(super) fn build(
    root: &json::Root,
    accessors: &Accessors<'_>,
    drawn: &Drawn<'_>,
    path: &Path,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Mesh, GltfError> {
    let objects = primitive_objects(root, drawn);
    let [positions_index, normals_index, indices_index] = accessors_of(root, drawn);
    let Some(positions_index) = positions_index else {
        return Err(missing_position(path, objects));
    };
    let with_accessor = |index: usize, problem| {
        let mut chain = objects.clone();
        chain.push(accessors.object(index));
        GltfError::object(path, chain, problem)
    };
    let file_positions = accessors.vec3(positions_index, "POSITION", &objects)?;
    if let Some((element, &value)) = file_positions
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
    {
        return Err(with_accessor(
            positions_index,
            GltfProblem::NonFinitePosition { element, value },
        ));
    }
    let vertices = file_positions.len();
    let file_normals = normals_index
        .map(|index| {
            let normals = accessors.vec3(index, "NORMAL", &objects)?;
            if normals.len() == vertices {
                Ok(normals)
            } else {
                Err(with_accessor(
                    index,
                    GltfProblem::AttributeCountMismatch {
                        attribute: "NORMAL",
                        count: normals.len(),
                        positions: vertices,
                    },
                ))
            }
        })
        .transpose()?;
    let corners = match indices_index {
        Some(index) => {
            let corners = accessors.indices(index, &objects)?;
            if let Some((position, &corner)) = corners
                .iter()
                .enumerate()
                .find(|(_, c)| **c as usize >= vertices)
            {
                return Err(with_accessor(
                    index,
                    GltfProblem::IndexOutOfRange {
                        position,
                        index: corner,
                        vertices,
                    },
                ));
            }
            corners
        }
        None => (0..u32::try_from(vertices).unwrap_or(u32::MAX)).collect(),
    };
    triangle_count(drawn.mode, corners.len())
        .map_err(|problem| GltfError::object(path, objects.clone(), problem))?;
    let world: &DAffine3 = &drawn.placed.world;
    let mut triangles = assemble(drawn.mode, &corners);
    if world.matrix3.determinant() < 0.0 {
        // A mirroring transform turns counter-clockwise triangles clockwise (glTF 2.0 §3.7.2.1).
        for triangle in &mut triangles {
            triangle.swap(1, 2);
        }
    }
    let positions: Vec<DVec3> = file_positions
        .iter()
        .map(|p| world.transform_point3(DVec3::from_array(p.map(f64::from))))
        .collect();
    let given: Vec<Option<DVec3>> = match &file_normals {
        Some(normals) => {
            let normal_matrix = world.matrix3.inverse().transpose();
            normals
                .iter()
                .map(|n| normals::unit(normal_matrix * DVec3::from_array(n.map(f64::from))))
                .collect()
        }
        None => vec![None; vertices],
    };
    let bad_normals = if file_normals.is_some() {
        given.iter().filter(|n| n.is_none()).count()
    } else {
        0
    };
    if bad_normals > 0 {
        let mut chain = objects.clone();
        if let Some(index) = normals_index {
            chain.push(accessors.object(index));
        }
        warnings.push(GltfWarning {
            path: path.to_owned(),
            objects: chain,
            skipped: GltfSkipped::BadNormals { count: bad_normals },
        });
    }
    let normals = if given.iter().all(Option::is_some) {
        given.into_iter().flatten().collect()
    } else {
        let computed = normals::area_weighted(&positions, &triangles);
        given
            .into_iter()
            .zip(computed)
            .map(|(given, computed)| given.unwrap_or(computed))
            .collect()
    };
    let group = vec![0; triangles.len()];
    Mesh::with_normals(positions, normals, triangles)
        .and_then(|mesh| mesh.with_groups(group, vec![group_name(root, drawn)]))
        .map_err(|error| GltfError::object(path, objects, GltfProblem::Mesh(error)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_are_assembled_as_the_specification_writes_them() {
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 2, 3, 4]),
            [[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            assemble(Mode::TriangleFan, &[0, 1, 2, 3]),
            [[1, 2, 0], [2, 3, 0]]
        );
        assert_eq!(
            assemble(Mode::Triangles, &[5, 6, 7, 8, 9, 10]),
            [[5, 6, 7], [8, 9, 10]]
        );
    }

    #[test]
    fn vertex_counts_that_a_mode_cannot_use_are_refused() {
        assert_eq!(triangle_count(Mode::Triangles, 36).ok(), Some(12));
        assert!(triangle_count(Mode::Triangles, 35).is_err());
        assert_eq!(triangle_count(Mode::TriangleStrip, 3).ok(), Some(1));
        assert!(triangle_count(Mode::TriangleFan, 2).is_err());
    }
}
