//! Errors: what was wrong with the input, and where.
//!
//! [`SceneError`] is returned by every constructor and loader of this crate. Mesh data errors name
//! the offending vertex, triangle or parameter; OBJ errors name the file and the line
//! (`path:line: problem`), the problem itself being an [`ObjProblem`]; scene-file errors name the
//! file and the field (`path: camera.near (5) must be below camera.far (1)`), the problem being a
//! [`SceneFileProblem`], or the file, line and column of a TOML error.

use std::fmt;
use std::io;
use std::path::PathBuf;

use glam::DVec3;
use shadowlab_hull::HullError;

/// An error from a constructor, a loader or an operation of this crate: bad input, named.
#[non_exhaustive]
#[derive(Debug)]
pub enum SceneError {
    /// A mesh needs at least one triangle.
    NoTriangles,
    /// A vertex position has a NaN or infinite coordinate.
    NonFinitePosition {
        /// The vertex index.
        vertex: usize,
    },
    /// A given normal is zero, NaN or infinite, so it has no direction.
    InvalidNormal {
        /// The vertex index.
        vertex: usize,
    },
    /// The number of normals differs from the number of positions.
    NormalCountMismatch {
        /// Positions given.
        positions: usize,
        /// Normals given.
        normals: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle index.
        triangle: usize,
        /// The vertex index it names.
        index: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// The number of group ids differs from the number of triangles.
    GroupCountMismatch {
        /// Triangles in the mesh.
        triangles: usize,
        /// Group ids given.
        groups: usize,
    },
    /// A triangle's group id has no group name.
    GroupOutOfRange {
        /// The triangle index.
        triangle: usize,
        /// Its group id.
        group: u32,
        /// The number of group names.
        group_count: usize,
    },
    /// More vertices than a `u32` index can address (at most 2³² vertices).
    TooManyVertices {
        /// The number of vertices asked for.
        count: u64,
    },
    /// More groups than a `u32` id can address.
    TooManyGroups {
        /// The number of groups asked for.
        count: u64,
    },
    /// A transform that is not finite or not invertible, or that maps a vertex to a non-finite
    /// position or a normal to one without direction.
    InvalidTransform {
        /// What is wrong, e.g. `"not invertible"`.
        reason: &'static str,
    },
    /// A procedural parameter outside its documented range.
    InvalidParameter {
        /// The parameter, e.g. `"radius"`, `"cells[1]"`.
        parameter: &'static str,
        /// The value given (integer parameters are converted exactly).
        value: f64,
        /// The rule it breaks, e.g. `"finite and > 0"`.
        requirement: &'static str,
    },
    /// A procedural mesh with more triangles than [`crate::procedural::MAX_TRIANGLES`].
    TooManyTriangles {
        /// The mesh, e.g. `"bar_lattice"`.
        shape: &'static str,
        /// The number of triangles the parameters ask for.
        count: u128,
        /// The limit.
        max: u64,
    },
    /// A file could not be read (missing, unreadable).
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
    /// A malformed OBJ file: the file, the line, and what is wrong with it.
    Obj {
        /// The file.
        path: PathBuf,
        /// The line, counting from 1.
        line: usize,
        /// What is wrong.
        problem: ObjProblem,
    },
    /// An OBJ file that holds no faces.
    ObjWithoutFaces {
        /// The file.
        path: PathBuf,
    },
    /// tobj rejected a file that this crate's line-by-line check had accepted: a bug here, please
    /// report it with the file.
    ObjInternal {
        /// The file.
        path: PathBuf,
        /// tobj's message.
        message: String,
    },
    /// A scene file that is not valid TOML, or whose TOML does not fit the scene format: a syntax
    /// error, an unknown field, a value of the wrong type (including a number out of its type's
    /// range, e.g. a negative image size), an unknown shape or light kind, a repeated key.
    SceneToml {
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
    /// A field of a scene file whose value is out of range or inconsistent with another.
    SceneFile {
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
    /// A mesh entry of a scene file that could not be built: its OBJ file is missing or malformed,
    /// its shape has more triangles than [`crate::procedural::MAX_TRIANGLES`] or breaks a rule
    /// between parameters, or its transform overflows.
    SceneMesh {
        /// The scene file.
        path: PathBuf,
        /// The entry or its field, e.g. `mesh[0].obj`, `mesh[3]`.
        field: String,
        /// The error from the OBJ loader, the procedural shape or the transform.
        source: Box<SceneError>,
    },
    /// A camera or spot light of a scene file that `shadowlab-hull` rejected after this crate's
    /// checks passed: only for values that overflow (e.g. positions near ±1e308).
    SceneHull {
        /// The scene file.
        path: PathBuf,
        /// The camera or light, e.g. `camera`, `light[1]`.
        field: String,
        /// hull's error.
        source: HullError,
    },
    /// A built-in scene name that does not exist.
    UnknownScene {
        /// The name asked for.
        name: String,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoTriangles => f.write_str("a mesh needs at least one triangle"),
            Self::NonFinitePosition { vertex } => {
                write!(f, "position of vertex {vertex} is not finite")
            }
            Self::InvalidNormal { vertex } => {
                write!(f, "normal of vertex {vertex} is zero or not finite")
            }
            Self::NormalCountMismatch { positions, normals } => {
                write!(f, "{normals} normals for {positions} positions")
            }
            Self::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} refers to vertex {index}, \
                 but there are {vertex_count} vertices"
            ),
            Self::GroupCountMismatch { triangles, groups } => {
                write!(f, "{groups} group ids for {triangles} triangles")
            }
            Self::GroupOutOfRange {
                triangle,
                group,
                group_count,
            } => write!(
                f,
                "triangle {triangle} is in group {group}, but there are {group_count} groups"
            ),
            Self::TooManyVertices { count } => write!(
                f,
                "{count} vertices: more than u32 indices can address (2^32)"
            ),
            Self::TooManyGroups { count } => {
                write!(f, "{count} groups: more than u32 ids can address (2^32)")
            }
            Self::InvalidTransform { reason } => write!(f, "transform is {reason}"),
            Self::InvalidParameter {
                parameter,
                value,
                requirement,
            } => write!(f, "`{parameter}` must be {requirement}, got {value}"),
            Self::TooManyTriangles { shape, count, max } => write!(
                f,
                "{shape} would have {count} triangles, more than the limit of {max}"
            ),
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Obj {
                path,
                line,
                problem,
            } => write!(f, "{}:{line}: {problem}", path.display()),
            Self::ObjWithoutFaces { path } => write!(f, "{}: no faces", path.display()),
            Self::ObjInternal { path, message } => write!(
                f,
                "{}: tobj rejected the file ({message}) after shadowlab-scene's checks accepted \
                 it; this is a bug in shadowlab-scene, please report it with the file",
                path.display()
            ),
            Self::SceneToml {
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
            Self::SceneFile {
                path,
                field,
                problem,
            } => write!(f, "{}: {field} {problem}", path.display()),
            Self::SceneMesh {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::SceneHull {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::UnknownScene { name } => write!(
                f,
                "there is no built-in scene `{name}`; the built-in scenes are {}",
                crate::BUILTIN_SCENES.join(", ")
            ),
        }
    }
}

impl std::error::Error for SceneError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            Self::SceneMesh { source, .. } => Some(source.as_ref()),
            Self::SceneHull { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// What is wrong with one field of a scene file. Displayed after the field's name, so that
/// [`SceneError::SceneFile`] reads `path: camera.fov (200) must be in (0, 180) degrees`.
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
        /// The rule it breaks, e.g. `"> 0"`, `"in (0, 180) degrees"`, `"at least 3"`.
        requirement: &'static str,
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
    /// A value the file does not give and whose default cannot be derived from the scene.
    NoDefault {
        /// Why, e.g. `"the scene lies behind the camera"`.
        reason: &'static str,
    },
}

impl fmt::Display for SceneFileProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { value } => write!(f, "({value}) must be finite"),
            Self::OutOfRange { value, requirement } => {
                write!(f, "({value}) must be {requirement}")
            }
            Self::NotBelow {
                value,
                other,
                other_value,
            } => write!(f, "({value}) must be below {other} ({other_value})"),
            Self::ZeroVector { value } => write!(f, "{value} has no direction"),
            Self::Parallel {
                value,
                other,
                other_value,
            } => write!(f, "{value} is parallel to {other} {other_value}"),
            Self::Coincident { value, other } => write!(f, "{value} coincides with {other}"),
            Self::Conflict { other } => {
                write!(f, "and {other} exclude each other: give one of them")
            }
            Self::Missing { needs } => write!(f, "needs {needs}"),
            Self::NotApplicable { to } => write!(f, "does not apply to {to}"),
            Self::WrongLength { found, expected } => {
                write!(f, "has {found} values; it takes {expected}")
            }
            Self::NoDefault { reason } => {
                write!(f, "has no default: {reason}; give it in the file")
            }
        }
    }
}

/// Which kind of element an OBJ face index refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObjElement {
    /// A position (`v`).
    Position,
    /// A texture coordinate (`vt`).
    TexCoord,
    /// A normal (`vn`).
    Normal,
}

impl ObjElement {
    fn plural(self) -> &'static str {
        match self {
            Self::Position => "positions (`v`)",
            Self::TexCoord => "texture coordinates (`vt`)",
            Self::Normal => "normals (`vn`)",
        }
    }

    fn singular(self) -> &'static str {
        match self {
            Self::Position => "position",
            Self::TexCoord => "texture coordinate",
            Self::Normal => "normal",
        }
    }
}

/// What is wrong with one line of an OBJ file.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum ObjProblem {
    /// The line is not valid UTF-8.
    NotUtf8,
    /// A value that should be a number is not one.
    NotANumber {
        /// The statement, e.g. `"v"`, `"vn"`.
        keyword: &'static str,
        /// The text found.
        token: String,
    },
    /// A number that must be finite is NaN or infinite.
    NotFinite {
        /// The statement, e.g. `"v"`, `"vn"`.
        keyword: &'static str,
        /// The text found.
        token: String,
    },
    /// A statement with the wrong number of values.
    WrongValueCount {
        /// The statement, e.g. `"v"`, `"vn"`.
        keyword: &'static str,
        /// The values found.
        found: usize,
        /// What the statement takes, e.g. `"x y z, x y z w or x y z r g b"`.
        expected: &'static str,
    },
    /// A `v` statement whose weight w is zero.
    ZeroWeight,
    /// A face vertex that is not `v`, `v/vt`, `v//vn` or `v/vt/vn` with integer indices.
    MalformedFaceVertex {
        /// The text found.
        token: String,
    },
    /// A face index 0 (OBJ counts from 1; negative indices count back from the latest element).
    ZeroIndex {
        /// What the index refers to.
        element: ObjElement,
    },
    /// A face index that refers to an element not defined above the line.
    IndexOutOfRange {
        /// What the index refers to.
        element: ObjElement,
        /// The index as written.
        index: isize,
        /// How many such elements are defined above the line.
        defined: usize,
    },
    /// A face with fewer than three vertices.
    TooFewFaceVertices {
        /// The vertices found.
        found: usize,
    },
    /// Some corners of one face name a normal and others do not.
    MixedNormalsInFace,
    /// A face that names normals in a group whose first face does not, or the reverse; tobj cannot
    /// pair such normals with their vertices.
    MixedNormals {
        /// Whether this face names normals (the group's first face then does not).
        names_normals: bool,
        /// The line of the group's first face, which sets the pattern.
        first_face_line: usize,
    },
    /// Some `v` statements carry a colour and others do not; tobj rejects such files.
    MixedVertexColours {
        /// The line of the first `v` statement, which sets the pattern.
        first_vertex_line: usize,
    },
    /// A `usemtl` statement without a material name after a space.
    MissingMaterialName,
}

impl fmt::Display for ObjProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotUtf8 => f.write_str("not valid UTF-8"),
            Self::NotANumber { keyword, token } => {
                write!(f, "`{keyword}`: `{token}` is not a number")
            }
            Self::NotFinite { keyword, token } => {
                write!(f, "`{keyword}`: `{token}` is not finite")
            }
            Self::WrongValueCount {
                keyword,
                found,
                expected,
            } => write!(
                f,
                "`{keyword}` takes {expected}; found {found} value{}",
                if *found == 1 { "" } else { "s" }
            ),
            Self::ZeroWeight => f.write_str("`v`: the weight w is 0"),
            Self::MalformedFaceVertex { token } => write!(
                f,
                "face vertex `{token}` is not v, v/vt, v//vn or v/vt/vn with integer indices"
            ),
            Self::ZeroIndex { element } => write!(
                f,
                "{} index 0: OBJ indices start at 1 (negative ones count back from the latest)",
                element.singular()
            ),
            Self::IndexOutOfRange {
                element,
                index,
                defined,
            } => write!(
                f,
                "{} index {index} is out of range: {defined} {} are defined above this line",
                element.singular(),
                element.plural()
            ),
            Self::TooFewFaceVertices { found } => {
                write!(f, "a face needs at least 3 vertices, found {found}")
            }
            Self::MixedNormalsInFace => f.write_str(
                "some corners of this face name a normal and others do not: within a group, give \
                 every corner a normal (v//vn, v/vt/vn) or none",
            ),
            Self::MixedNormals {
                names_normals,
                first_face_line,
            } => write!(
                f,
                "this face {} but the group's first face (line {first_face_line}) {}: within a \
                 group, give every corner a normal (v//vn, v/vt/vn) or none",
                if *names_normals {
                    "names normals"
                } else {
                    "names no normals"
                },
                if *names_normals { "does not" } else { "does" },
            ),
            Self::MixedVertexColours { first_vertex_line } => write!(
                f,
                "`v` with and without a colour in one file (compare line {first_vertex_line}): \
                 give every vertex r g b or none"
            ),
            Self::MissingMaterialName => {
                f.write_str("`usemtl` needs a material name after a space")
            }
        }
    }
}
