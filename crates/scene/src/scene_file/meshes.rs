//! `[[mesh]]`: OBJ files and procedural shapes, their transforms and copies, merged into one mesh
//! with one group per entry.

use std::path::Path;

use glam::{DAffine3, DMat3, DVec3};

use super::ObjFiles;
use super::checks::{Checker, field};
use super::error::{SceneFileError, SceneFileProblem};
use super::raw::{RawMesh, RawScale, ShapeKind};
use crate::gltf_import::{GltfError, GltfImport, GltfWarning, load_gltf};
use crate::mesh::{MIN_EXTENT, Mesh};
use crate::obj::{ObjError, load_obj, parse_obj};
use crate::procedural::{self, MAX_TRIANGLES, ShapeError};
use crate::read::ReadError;

/// Default `size` of a plane, `[x, z]`.
const PLANE_SIZE: [f64; 2] = [1.0, 1.0];
/// Default `segments` of a plane.
const PLANE_SEGMENTS: u32 = 1;
/// Default `size` of a box.
const BOX_SIZE: [f64; 3] = [1.0, 1.0, 1.0];
/// Default `radius` of a sphere or cylinder.
const RADIUS: f64 = 0.5;
/// Default `height` of a cylinder.
const CYLINDER_HEIGHT: f64 = 1.0;
/// Default `segments` of a sphere or cylinder.
const ROUND_SEGMENTS: u32 = 32;
/// Default `rings` of a sphere.
const SPHERE_RINGS: u32 = 16;
/// Default `cells` of a lattice.
const LATTICE_CELLS: [u32; 3] = [4, 4, 4];
/// Default `spacing` of a lattice.
const LATTICE_SPACING: f64 = 0.25;
/// Default `thickness` of a lattice's bars.
const LATTICE_THICKNESS: f64 = 0.025;
/// Default `square_size` of a chess board.
const CHESS_SQUARE_SIZE: f64 = 0.125;
/// Default `frame_width` of a chess board.
const CHESS_FRAME_WIDTH: f64 = 0.0;

/// Every entry built and merged: group k of the result is entry k. The merged mesh must span at
/// least [`MIN_EXTENT`].
pub(super) fn scene_mesh(
    checker: Checker<'_>,
    entries: &[RawMesh],
    obj_files: &ObjFiles<'_>,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Mesh, SceneFileError> {
    if entries.is_empty() {
        return Err(checker.error(
            "mesh",
            SceneFileProblem::Missing {
                needs: "at least one `[[mesh]]` entry",
            },
        ));
    }
    let meshes = entries
        .iter()
        .enumerate()
        .map(|(index, entry)| mesh_entry(checker, index, entry, obj_files, warnings))
        .collect::<Result<Vec<_>, _>>()?;
    let mesh = Mesh::try_merged(&meshes).map_err(|error| checker.mesh_error("mesh", error))?;
    let extent = mesh.bounds().size().max_element();
    if extent < MIN_EXTENT {
        return Err(checker.error("mesh", SceneFileProblem::DegenerateExtent { extent }));
    }
    Ok(mesh)
}

/// Entry `index`: its mesh in one group named by the entry, transformed and copied; the
/// warnings of a glTF file are added to `warnings`.
fn mesh_entry(
    checker: Checker<'_>,
    index: usize,
    raw: &RawMesh,
    obj_files: &ObjFiles<'_>,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Mesh, SceneFileError> {
    let prefix = format!("mesh[{index}]");
    let sources: Vec<&str> = [
        ("obj", raw.obj.is_some()),
        ("shape", raw.shape.is_some()),
        ("gltf", raw.gltf.is_some()),
    ]
    .into_iter()
    .filter_map(|(name, given)| given.then_some(name))
    .collect();
    if let [first, second, ..] = sources[..] {
        return Err(checker.error(
            field(&prefix, first),
            SceneFileProblem::Conflict {
                other: field(&prefix, second),
            },
        ));
    }
    if raw.gltf_scene.is_some() && raw.gltf.is_none() {
        return Err(checker.error(
            field(&prefix, "gltf_scene"),
            SceneFileProblem::NotApplicable {
                to: match raw.shape {
                    Some(shape) => format!("shape \"{}\"", shape.name()),
                    None => "an entry without `gltf`".to_owned(),
                },
            },
        ));
    }
    let (mesh, default_name) = match (&raw.obj, raw.shape, &raw.gltf) {
        (Some(obj), _, _) => {
            not_applicable(checker, &prefix, raw, &[], "an obj mesh")?;
            let mesh = obj_files
                .load(obj)
                .map_err(|error| checker.obj_error(field(&prefix, "obj"), error))?;
            (mesh, stem(obj))
        }
        (None, Some(shape), _) => {
            let to = format!("shape \"{}\"", shape.name());
            not_applicable(checker, &prefix, raw, shape.parameters(), &to)?;
            (
                build_shape(checker, &prefix, shape, raw)?,
                shape.name().to_owned(),
            )
        }
        (None, None, Some(gltf)) => {
            not_applicable(checker, &prefix, raw, &[], "a gltf mesh")?;
            let import = obj_files
                .load_gltf(gltf, raw.gltf_scene)
                .map_err(|error| checker.gltf_error(field(&prefix, "gltf"), error))?;
            warnings.extend(import.warnings);
            (import.mesh, stem(gltf))
        }
        (None, None, None) => {
            return Err(checker.error(
                prefix,
                SceneFileProblem::Missing {
                    needs: "one of `obj`, `shape` and `gltf`",
                },
            ));
        }
    };
    let name = raw.name.clone().unwrap_or(default_name);
    let mesh = one_group(checker, &prefix, mesh, &name)?;
    let mesh = match transform(checker, &prefix, raw)? {
        Some(transform) => mesh
            .try_transformed(&transform)
            .map_err(|error| checker.mesh_error(&prefix, error))?,
        None => mesh,
    };
    copies(checker, &prefix, raw, mesh, &name)
}

/// The stem of a file named in an entry: its default group name.
fn stem(file: &str) -> String {
    let stem = Path::new(file).file_stem().unwrap_or_default();
    stem.to_string_lossy().into_owned()
}

/// An error for the first shape parameter the entry gives that is not in `allowed`.
fn not_applicable(
    checker: Checker<'_>,
    prefix: &str,
    raw: &RawMesh,
    allowed: &[&str],
    to: &str,
) -> Result<(), SceneFileError> {
    match raw
        .parameters()
        .into_iter()
        .find(|name| !allowed.contains(name))
    {
        Some(name) => Err(checker.error(
            field(prefix, name),
            SceneFileProblem::NotApplicable { to: to.to_owned() },
        )),
        None => Ok(()),
    }
}

/// `mesh` with all its triangles in one group named `name`.
fn one_group(
    checker: Checker<'_>,
    prefix: &str,
    mesh: Mesh,
    name: &str,
) -> Result<Mesh, SceneFileError> {
    let groups = vec![0; mesh.triangle_count()];
    mesh.with_groups(groups, vec![name.to_owned()])
        .map_err(|error| checker.mesh_error(prefix, error))
}

/// The procedural mesh of a `shape` entry, its parameters checked and named here; rules between
/// parameters and the triangle budget are `procedural`'s, wrapped as [`SceneFileError::Shape`].
fn build_shape(
    checker: Checker<'_>,
    prefix: &str,
    shape: ShapeKind,
    raw: &RawMesh,
) -> Result<Mesh, SceneFileError> {
    let positive = |name: &str, value: Option<f64>, default: f64| {
        value.map_or(Ok(default), |v| checker.positive(&field(prefix, name), v))
    };
    let segments = |default: u32, minimum: u32, requirement: &'static str| {
        raw.segments.map_or(Ok(default), |v| {
            checker.at_least(&field(prefix, "segments"), v, minimum, requirement)
        })
    };
    let mesh = match shape {
        ShapeKind::Plane => {
            let [x, z] = sizes(checker, prefix, raw.size.as_deref(), PLANE_SIZE)?;
            procedural::plane(x, z, segments(PLANE_SEGMENTS, 1, "at least 1")?)
        }
        ShapeKind::Cuboid => {
            let size = sizes(checker, prefix, raw.size.as_deref(), BOX_SIZE)?;
            procedural::cuboid(DVec3::from_array(size))
        }
        ShapeKind::Sphere => procedural::sphere(
            positive("radius", raw.radius, RADIUS)?,
            segments(ROUND_SEGMENTS, 3, "at least 3")?,
            raw.rings.map_or(Ok(SPHERE_RINGS), |v| {
                checker.at_least(&field(prefix, "rings"), v, 2, "at least 2")
            })?,
        ),
        ShapeKind::Cylinder => procedural::cylinder(
            positive("radius", raw.radius, RADIUS)?,
            positive("height", raw.height, CYLINDER_HEIGHT)?,
            segments(ROUND_SEGMENTS, 3, "at least 3")?,
        ),
        ShapeKind::Lattice => procedural::bar_lattice(
            raw.cells.unwrap_or(LATTICE_CELLS),
            positive("spacing", raw.spacing, LATTICE_SPACING)?,
            positive("thickness", raw.thickness, LATTICE_THICKNESS)?,
        ),
        ShapeKind::Chessboard => procedural::chess_board(
            positive("square_size", raw.square_size, CHESS_SQUARE_SIZE)?,
            raw.frame_width.map_or(Ok(CHESS_FRAME_WIDTH), |v| {
                checker.non_negative(&field(prefix, "frame_width"), v)
            })?,
        ),
    };
    mesh.map_err(|error| checker.shape_error(prefix, error))
}

/// The `size` array of a plane (N = 2) or box (N = 3): N positive values, named `size[i]`.
fn sizes<const N: usize>(
    checker: Checker<'_>,
    prefix: &str,
    size: Option<&[f64]>,
    default: [f64; N],
) -> Result<[f64; N], SceneFileError> {
    let Some(size) = size else {
        return Ok(default);
    };
    let size_field = field(prefix, "size");
    let values: [f64; N] = size.try_into().map_err(|_| {
        checker.error(
            &size_field,
            SceneFileProblem::WrongLength {
                found: size.len(),
                expected: N,
            },
        )
    })?;
    for (index, &value) in values.iter().enumerate() {
        checker.positive(&format!("{size_field}[{index}]"), value)?;
    }
    Ok(values)
}

/// The entry's transform `p ↦ translate + R·(scale ∘ p)` with `R = Rz·Ry·Rx` (see
/// [`rotation`]); `None` if the entry gives none of `translate`, `rotate` and `scale`, so that
/// such meshes keep their exact positions and normals.
fn transform(
    checker: Checker<'_>,
    prefix: &str,
    raw: &RawMesh,
) -> Result<Option<DAffine3>, SceneFileError> {
    if raw.translate.is_none() && raw.rotate.is_none() && raw.scale.is_none() {
        return Ok(None);
    }
    let translation = match raw.translate {
        Some(translate) => checker.vector(&field(prefix, "translate"), translate)?,
        None => DVec3::ZERO,
    };
    let rotation = match raw.rotate {
        Some(degrees) => rotation(checker.vector(&field(prefix, "rotate"), degrees)?),
        None => DMat3::IDENTITY,
    };
    let scale_field = field(prefix, "scale");
    let scale = match raw.scale {
        None => DVec3::ONE,
        Some(RawScale::Uniform(scale)) => DVec3::splat(checker.non_zero(&scale_field, scale)?),
        Some(RawScale::PerAxis(scales)) => {
            let mut checked = [0.0; 3];
            for (index, (out, &scale)) in checked.iter_mut().zip(&scales).enumerate() {
                *out = checker.non_zero(&format!("{scale_field}[{index}]"), scale)?;
            }
            DVec3::from_array(checked)
        }
    };
    Ok(Some(DAffine3::from_mat3_translation(
        rotation * DMat3::from_diagonal(scale),
        translation,
    )))
}

/// The rotation of `rotate = [a, b, c]` (degrees): about the world x axis by a, then about y by b,
/// then about z by c, each counter-clockwise seen from the positive axis (right-hand rule):
/// `Rz(c)·Ry(b)·Rx(a)`. Multiples of 90° give exact matrices of 0 and ±1.
fn rotation(degrees: DVec3) -> DMat3 {
    let (sin_x, cos_x) = sin_cos_degrees(degrees.x);
    let (sin_y, cos_y) = sin_cos_degrees(degrees.y);
    let (sin_z, cos_z) = sin_cos_degrees(degrees.z);
    let about_x = DMat3::from_cols(
        DVec3::X,
        DVec3::new(0.0, cos_x, sin_x),
        DVec3::new(0.0, -sin_x, cos_x),
    );
    let about_y = DMat3::from_cols(
        DVec3::new(cos_y, 0.0, -sin_y),
        DVec3::Y,
        DVec3::new(sin_y, 0.0, cos_y),
    );
    let about_z = DMat3::from_cols(
        DVec3::new(cos_z, sin_z, 0.0),
        DVec3::new(-sin_z, cos_z, 0.0),
        DVec3::Z,
    );
    about_z * about_y * about_x
}

/// `(sin, cos)` of an angle in degrees, exact at multiples of 90°: the angle is reduced exactly to
/// `r + 90°·q` with |r| ≤ 45° (`%` is exact, and so is the subtraction, by Sterbenz's lemma), and
/// the quadrant q swaps and negates the sine and cosine of r.
fn sin_cos_degrees(degrees: f64) -> (f64, f64) {
    let reduced = degrees % 360.0;
    let quadrant = (reduced / 90.0).round();
    let (sin, cos) = (reduced - 90.0 * quadrant).to_radians().sin_cos();
    let turns = quadrant.rem_euclid(4.0);
    if turns == 0.0 {
        (sin, cos)
    } else if turns == 1.0 {
        (cos, -sin)
    } else if turns == 2.0 {
        (-sin, -cos)
    } else {
        (-cos, sin)
    }
}

/// `copies` copies of `mesh`, copy k moved by k·`step`, in one group named `name`.
fn copies(
    checker: Checker<'_>,
    prefix: &str,
    raw: &RawMesh,
    mesh: Mesh,
    name: &str,
) -> Result<Mesh, SceneFileError> {
    let copies_field = field(prefix, "copies");
    let count = match raw.copies {
        Some(count) => checker.at_least(&copies_field, count, 1, "at least 1")?,
        None => 1,
    };
    let step = match (count, raw.step) {
        (1, None) => return Ok(mesh),
        (1, Some(_)) => {
            return Err(checker.error(
                field(prefix, "step"),
                SceneFileProblem::NotApplicable {
                    to: "a single copy (set `copies`)".to_owned(),
                },
            ));
        }
        (_, None) => {
            return Err(checker.error(
                copies_field,
                SceneFileProblem::Missing {
                    needs: "a `step` between the copies",
                },
            ));
        }
        (_, Some(step)) => checker.vector(&field(prefix, "step"), step)?,
    };
    let triangles = u128::from(count) * mesh.triangle_count() as u128;
    if triangles > u128::from(MAX_TRIANGLES) {
        return Err(checker.shape_error(
            copies_field,
            ShapeError::TooManyTriangles {
                shape: "the copies",
                count: triangles,
                max: MAX_TRIANGLES,
            },
        ));
    }
    let moved = (1..count)
        .map(|k| mesh.try_transformed(&DAffine3::from_translation(f64::from(k) * step)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|error| checker.mesh_error(prefix, error))?;
    let all: Vec<Mesh> = std::iter::once(mesh).chain(moved).collect();
    let merged = Mesh::try_merged(&all).map_err(|error| checker.mesh_error(prefix, error))?;
    one_group(checker, prefix, merged, name)
}

impl ObjFiles<'_> {
    /// Scene `scene` of an entry's `gltf` path. Embedded files are text; no built-in scene uses
    /// a glTF file, so an embedded lookup is always a missing file.
    fn load_gltf(&self, gltf: &str, scene: Option<usize>) -> Result<GltfImport, GltfError> {
        match self {
            Self::Relative(directory) => load_gltf(&directory.join(gltf), scene),
            Self::Embedded { directory, .. } => Err(GltfError::Read(ReadError::Io {
                path: directory.join(gltf),
                source: std::io::Error::new(
                    std::io::ErrorKind::NotFound,
                    "no glTF file is embedded in the binary",
                ),
            })),
        }
    }

    /// The mesh of an entry's `obj` path.
    fn load(&self, obj: &str) -> Result<Mesh, ObjError> {
        match self {
            Self::Relative(directory) => load_obj(&directory.join(obj)),
            Self::Embedded { directory, files } => {
                let path = directory.join(obj);
                match files.iter().find(|(name, _)| *name == obj) {
                    Some((_, text)) => parse_obj(text, &path),
                    None => Err(ObjError::Read(ReadError::Io {
                        path,
                        source: std::io::Error::new(
                            std::io::ErrorKind::NotFound,
                            "no such mesh is embedded in the binary",
                        ),
                    })),
                }
            }
        }
    }
}
