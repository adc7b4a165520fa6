//! Loading Wavefront OBJ files into one [`Mesh`], through tobj.

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;

use crate::mesh::{MAX_VERTICES, MIN_EXTENT, Mesh, MeshError};
use crate::normals;
use crate::read::{MAX_OBJ_BYTES, read_bounded};

mod check;
mod error;

pub use error::{ObjElement, ObjError, ObjProblem};

/// Loads an OBJ file as one mesh.
///
/// - **Faces** are triangulated as fans from their first vertex (right for convex polygons, as in
///   tobj). Polylines (`l`), points (`p`), curves and surfaces are skipped: they have no area.
/// - **Groups:** each `g`/`o` name becomes a group ([`Mesh::group_names`], in order of first
///   appearance; faces before any `g`/`o` are in tobj's `"unnamed_object"`), and
///   [`Mesh::groups`] tells each triangle's. Repeated names share a group.
/// - **Vertices** are tobj's single index: one vertex per distinct (position, texture coordinate,
///   normal) triple within a group, so positions are shared between faces except across groups and
///   where the file gives a corner a different normal or texture coordinate. Positions are read as
///   f64; `v x y z w` is divided by w; vertex colours are ignored.
/// - **Normals** come from the file where its faces name them (normalised); where they do not, or a
///   file normal is zero, the vertex gets the area-weighted normal of [`Mesh::new`] (computed over
///   the loaded triangles, with the same `+z` fallback). File normals are not checked against the
///   winding.
/// - **Materials** are ignored: `mtllib` files are not opened, so a missing `.mtl` is no error.
///
/// - **Limits:** the file must be a regular file of at most [`MAX_OBJ_BYTES`]; every coordinate
///   must lie within ±[`crate::MAX_COORDINATE`], and the positions must span at least
///   [`MIN_EXTENT`] on some axis.
///
/// # Errors
/// - [`ObjError::Read`] if it cannot be read, is not a regular file (a directory, a device such
///   as `/dev/zero`, a FIFO) or is larger than [`MAX_OBJ_BYTES`];
/// - [`ObjError::Line`] naming the path and line of the first malformed statement, with an
///   [`ObjProblem`]: a number that does not parse, is not finite or is beyond
///   ±[`crate::MAX_COORDINATE`], a wrong number of values, a face index that is 0 or refers to an
///   element not defined above the line, a face with fewer than three vertices, a group mixing
///   faces with and without normals, and the rest listed there;
/// - [`ObjError::NoFaces`] for a file with no faces;
/// - [`ObjError::DegenerateExtent`] for positions spanning less than [`MIN_EXTENT`];
/// - [`ObjError::Mesh`] for more than 2³² vertices.
pub fn load_obj(path: &Path) -> Result<Mesh, ObjError> {
    let bytes = read_bounded(path, MAX_OBJ_BYTES, "an OBJ file", "MAX_OBJ_BYTES")
        .map_err(ObjError::Read)?;
    let text = std::str::from_utf8(&bytes).map_err(|error| {
        let line = 1 + bytes[..error.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        ObjError::Line {
            path: path.to_owned(),
            line,
            problem: ObjProblem::NotUtf8,
        }
    })?;
    parse_obj(text, path)
}

/// Reads OBJ text as one mesh, exactly as [`load_obj`] reads a file holding it; `path` only names
/// the text in errors (it is not opened). This is how the built-in scenes load the meshes embedded
/// in the binary.
///
/// # Errors
/// As [`load_obj`], except [`ObjError::Read`] and the UTF-8 check, which concern reading a file.
pub fn parse_obj(text: &str, path: &Path) -> Result<Mesh, ObjError> {
    let obj_error = |line, problem| ObjError::Line {
        path: path.to_owned(),
        line,
        problem,
    };
    // A byte-order mark would otherwise hide the first statement's keyword.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let summary = check::check(text).map_err(|(line, problem)| obj_error(line, problem))?;
    if summary.faces == 0 {
        return Err(ObjError::NoFaces {
            path: path.to_owned(),
        });
    }
    let models = if summary.has_polylines {
        parse(&check::without_polylines(text))
    } else {
        parse(text)
    };
    let models = models.map_err(|error| ObjError::Internal {
        path: path.to_owned(),
        message: error.to_string(),
    })?;
    let mesh = assemble(models, path)?;
    let extent = mesh.bounds().size().max_element();
    if extent < MIN_EXTENT {
        return Err(ObjError::DegenerateExtent {
            path: path.to_owned(),
            extent,
        });
    }
    Ok(mesh)
}

/// tobj's reading of checked text: triangulated, one index for positions and normals, materials
/// not loaded.
fn parse(text: &str) -> Result<Vec<tobj::Model>, tobj::LoadError> {
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) =
        tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| Ok(Default::default()))?;
    Ok(models)
}

/// Joins tobj's models (one per run of faces between `g`/`o` statements) into one mesh: groups by
/// name, file normals where every corner of a model has one, computed normals elsewhere. `path` is
/// for error messages.
fn assemble(models: Vec<tobj::Model>, path: &Path) -> Result<Mesh, ObjError> {
    let mesh_error = |source| ObjError::Mesh {
        path: path.to_owned(),
        source,
    };
    let mut positions = Vec::new();
    let mut file_normals: Vec<Option<DVec3>> = Vec::new();
    let mut triangles = Vec::new();
    let mut groups = Vec::new();
    let mut group_names: Vec<String> = Vec::new();
    let mut group_ids: HashMap<String, u32> = HashMap::new();
    for model in models.into_iter().filter(|m| !m.mesh.indices.is_empty()) {
        let mesh = model.mesh;
        let next_id = u32::try_from(group_names.len()).map_err(|_| {
            mesh_error(MeshError::TooManyGroups {
                count: group_names.len() as u64 + 1,
            })
        })?;
        let group = *group_ids.entry(model.name.clone()).or_insert_with(|| {
            group_names.push(model.name);
            next_id
        });
        let vertex_total = (positions.len() + mesh.positions.len() / 3) as u64;
        if vertex_total > MAX_VERTICES {
            return Err(mesh_error(MeshError::TooManyVertices {
                count: vertex_total,
            }));
        }
        // Below the total, which is at most 2³²: every index of this model fits a u32.
        let offset = u32::try_from(positions.len()).expect("checked against MAX_VERTICES");
        positions.extend(mesh.positions.chunks_exact(3).map(DVec3::from_slice));
        if mesh.normals.len() == mesh.positions.len() {
            let given = mesh.normals.chunks_exact(3).map(DVec3::from_slice);
            file_normals.extend(given.map(normals::unit));
        } else if mesh.normals.is_empty() {
            file_normals.resize(positions.len(), None);
        } else {
            return Err(ObjError::Internal {
                path: path.to_owned(),
                message: "a model's normals and positions differ in number".to_owned(),
            });
        }
        triangles.extend(
            mesh.indices
                .chunks_exact(3)
                .map(|c| [c[0] + offset, c[1] + offset, c[2] + offset]),
        );
        groups.resize(triangles.len(), group);
    }
    let normals = if file_normals.iter().all(Option::is_some) {
        file_normals.into_iter().flatten().collect()
    } else {
        let computed = normals::area_weighted(&positions, &triangles);
        file_normals
            .into_iter()
            .zip(computed)
            .map(|(given, computed)| given.unwrap_or(computed))
            .collect()
    };
    Mesh::with_normals(positions, normals, triangles)
        .and_then(|mesh| mesh.with_groups(groups, group_names))
        .map_err(mesh_error)
}
