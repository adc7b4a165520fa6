//! The errors of [`crate::load_scene`] and [`crate::parse_scene`]: the file, and the field or the
//! line and column, with the error of the OBJ file, shape, mesh or camera behind it as its
//! `source()`.

use std::fmt;
use std::path::PathBuf;

use glam::DVec3;
use shadowlab_hull::HullError;

use crate::gltf_import::{GltfError, GltfWarning};
use crate::mesh::MeshError;
use crate::number::{Shown, ShownVector};
use crate::obj::ObjError;
use crate::procedural::ShapeError;
use crate::read::ReadError;

/// Why a scene file could not be read as a [`crate::Scene`]. Every variant names the file.
#[non_exhaustive]
#[derive(Debug)]
pub enum SceneFileError {
    /// The file could not be read: missing, not a regular file, or larger than
    /// [`crate::MAX_SCENE_FILE_BYTES`].
    Read(ReadError),
    /// The file is not valid UTF-8 (TOML is UTF-8).
    NotUtf8 {
        /// The scene file.
        path: PathBuf,
        /// The line (from 1) of the first invalid byte.
        line: usize,
    },
    /// A file that is not valid TOML, or whose TOML does not fit the scene format: a syntax
    /// error, an unknown field, a value of the wrong type (including a number out of its type's
    /// range, e.g. a negative image size), an unknown shape or light kind, a repeated key.
    Toml {
        /// The scene file.
        path: PathBuf,
        /// The line and column (both from 1, columns counting characters) where toml located the
        /// error, if it did.
        position: Option<(usize, usize)>,
        /// The field at that position (e.g. `mesh[1].shape`), if it is inside one.
        field: Option<String>,
        /// toml's message, e.g. ``unknown field `fovy`, expected one of …``.
        message: String,
    },
    /// A field whose value is out of range or inconsistent with another.
    Field {
        /// The scene file.
        path: PathBuf,
        /// The field, as a path into the file: `camera.near`, `light[0].direction`,
        /// `mesh[2].size[1]` (arrays of tables and values are indexed from 0). A value that the
        /// file does not give but that is derived from other values or from the scene is named
        /// `the default camera.far`.
        field: String,
        /// What is wrong with it.
        problem: SceneFileProblem,
    },
    /// A mesh entry's OBJ file is missing or malformed.
    Obj {
        /// The scene file.
        path: PathBuf,
        /// The entry's field, e.g. `mesh[0].obj`.
        field: String,
        /// The OBJ loader's error, naming the OBJ file (boxed: it is the largest error here).
        source: Box<ObjError>,
    },
    /// A mesh entry's shape has more triangles than [`crate::procedural::MAX_TRIANGLES`] or breaks
    /// a rule between parameters.
    Shape {
        /// The scene file.
        path: PathBuf,
        /// The entry, e.g. `mesh[3]`.
        field: String,
        /// The shape's error.
        source: ShapeError,
    },
    /// A mesh entry whose transform or copies cannot be applied (a transform that is not
    /// invertible, positions beyond [`crate::MAX_COORDINATE`], too many vertices).
    Mesh {
        /// The scene file.
        path: PathBuf,
        /// The entry or its field, e.g. `mesh[0]`, `mesh[0].copies`, `mesh`.
        field: String,
        /// The mesh's error.
        source: MeshError,
    },
    /// A glTF file (a `gltf` mesh entry's, or the scene's own) that is missing or malformed, or
    /// whose camera or light cannot be used.
    Gltf {
        /// The scene file, or the glTF file read as a scene.
        path: PathBuf,
        /// The entry's field, e.g. `mesh[0].gltf`; `None` for a glTF file read as a scene.
        field: Option<String>,
        /// The glTF reader's error, naming the glTF file and its object.
        source: Box<GltfError>,
    },
    /// The scene's glTF files hold parts that shadowlab cannot represent and would skip (a spot
    /// light of 180° or wider, lines, a skin, …): [`crate::load_scene`] refuses them so that nothing is dropped
    /// unseen; [`crate::load_scene_with_warnings`] reads the scene and returns them.
    Skipped {
        /// The scene file, or the glTF file read as a scene.
        path: PathBuf,
        /// What would be skipped.
        warnings: Vec<GltfWarning>,
    },
    /// A camera or spot light that `shadowlab-hull` rejected after this crate's checks passed:
    /// only for values that overflow (e.g. positions near ±1e308).
    Hull {
        /// The scene file.
        path: PathBuf,
        /// The camera or light, e.g. `camera`, `light[1]`.
        field: String,
        /// hull's error.
        source: HullError,
    },
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(error) => write!(f, "{error}"),
            Self::NotUtf8 { path, line } => {
                write!(f, "{}:{line}: not valid UTF-8", path.display())
            }
            Self::Toml {
                path,
                position,
                field,
                message,
            } => {
                write!(f, "{}", path.display())?;
                if let Some((line, column)) = position {
                    write!(f, ":{line}:{column}")?;
                }
                if let Some(field) = field {
                    write!(f, ": {field}")?;
                }
                write!(f, ": {message}")
            }
            Self::Field {
                path,
                field,
                problem,
            } => write!(f, "{}: {field} {problem}", path.display()),
            Self::Obj {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::Shape {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::Mesh {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::Hull {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::Gltf {
                path,
                field: Some(field),
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::Gltf {
                field: None,
                source,
                ..
            } => write!(f, "{source}"),
            Self::Skipped { path, warnings } => {
                write!(
                    f,
                    "{}: holds what shadowlab cannot represent and would skip:",
                    path.display()
                )?;
                for warning in warnings {
                    write!(f, " {warning};")?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for SceneFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Read(error) => Some(error),
            Self::Obj { source, .. } => Some(source.as_ref()),
            Self::Shape { source, .. } => Some(source),
            Self::Mesh { source, .. } => Some(source),
            Self::Hull { source, .. } => Some(source),
            Self::Gltf { source, .. } => Some(source.as_ref()),
            Self::NotUtf8 { .. }
            | Self::Toml { .. }
            | Self::Field { .. }
            | Self::Skipped { .. } => None,
        }
    }
}

/// What is wrong with one field of a scene file. Displayed after the field's name, so that
/// [`SceneFileError::Field`] reads `path: camera.fov (200) must be in (0, 180) degrees`.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum SceneFileProblem {
    /// A number that must be finite is NaN or infinite (TOML has `nan` and `inf` literals).
    NotFinite {
        /// The value given.
        value: f64,
    },
    /// A number outside its range.
    OutOfRange {
        /// The value given (integers are converted exactly).
        value: f64,
        /// The rule it breaks, with the allowed range, e.g. `"> 0"`,
        /// `"in [0.001, 180) degrees (MIN_FOV_DEGREES)"`, `"at least 3"`.
        requirement: String,
    },
    /// A number that must be below another one (`near` and `far`) is not.
    NotBelow {
        /// The value given.
        value: f64,
        /// The other field, e.g. `camera.far` or `the default camera.far`.
        other: String,
        /// The other field's value.
        other_value: f64,
    },
    /// A direction that is the zero vector.
    ZeroVector {
        /// The value given.
        value: DVec3,
    },
    /// An up vector parallel to the direction it must be orthogonalised against.
    Parallel {
        /// The value given.
        value: DVec3,
        /// The other direction, e.g. `the view direction`.
        other: &'static str,
        /// Its value.
        other_value: DVec3,
    },
    /// A point that coincides with another, so that no direction joins them (a target at the
    /// position).
    Coincident {
        /// The value given.
        value: DVec3,
        /// The other field, e.g. `camera.position`.
        other: String,
    },
    /// Two fields that exclude each other are both given.
    Conflict {
        /// The other field, e.g. `camera.direction`.
        other: String,
    },
    /// Something required is missing.
    Missing {
        /// What is needed, e.g. ``"one of `obj` and `shape`"``.
        needs: &'static str,
    },
    /// A field that the entry's kind or shape does not take (a spot light's `cone` on a
    /// directional light, a sphere's `radius` on a box).
    NotApplicable {
        /// What the entry is, e.g. `a directional light`, `shape "box"`.
        to: String,
    },
    /// An array with the wrong number of values.
    WrongLength {
        /// The values given.
        found: usize,
        /// The values expected.
        expected: usize,
    },
    /// The merged meshes span less than [`crate::MIN_EXTENT`] on every axis: a point, or
    /// denormal coordinates.
    DegenerateExtent {
        /// The largest side of the scene's bounding box.
        extent: f64,
    },
    /// A value the file does not give and whose default cannot be derived from the scene.
    NoDefault {
        /// Why, e.g. `"the scene lies behind the camera"`.
        reason: &'static str,
    },
}

impl fmt::Display for SceneFileProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { value } => write!(f, "({}) must be finite", Shown(*value)),
            Self::OutOfRange { value, requirement } => {
                write!(f, "({}) must be {requirement}", Shown(*value))
            }
            Self::NotBelow {
                value,
                other,
                other_value,
            } => write!(
                f,
                "({}) must be below {other} ({})",
                Shown(*value),
                Shown(*other_value)
            ),
            Self::ZeroVector { value } => write!(f, "{} has no direction", ShownVector(*value)),
            Self::Parallel {
                value,
                other,
                other_value,
            } => write!(
                f,
                "{} is parallel to {other} {}",
                ShownVector(*value),
                ShownVector(*other_value)
            ),
            Self::Coincident { value, other } => {
                write!(f, "{} coincides with {other}", ShownVector(*value))
            }
            Self::Conflict { other } => {
                write!(f, "and {other} exclude each other: give one of them")
            }
            Self::Missing { needs } => write!(f, "needs {needs}"),
            Self::NotApplicable { to } => write!(f, "does not apply to {to}"),
            Self::WrongLength { found, expected } => {
                write!(f, "has {found} values; it takes {expected}")
            }
            Self::DegenerateExtent { extent } => write!(
                f,
                "(the merged meshes) span {} at most on any axis; a scene must span at least {} \
                 (MIN_EXTENT) so that its extent squared stays a normal f64 number",
                Shown(*extent),
                Shown(crate::MIN_EXTENT)
            ),
            Self::NoDefault { reason } => {
                write!(f, "has no default: {reason}; give it in the file")
            }
        }
    }
}
