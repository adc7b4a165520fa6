//! The errors of [`crate::load_obj`] and [`crate::parse_obj`]: the file, the line, and what is
//! wrong with it.

use std::fmt;
use std::path::PathBuf;

use crate::mesh::MeshError;
use crate::number::Shown;
use crate::read::ReadError;

/// Why an OBJ file could not be read as a mesh.
#[non_exhaustive]
#[derive(Debug)]
pub enum ObjError {
    /// The file could not be read: missing, not a regular file, or larger than
    /// [`crate::MAX_OBJ_BYTES`].
    Read(ReadError),
    /// A malformed statement: the file, the line, and what is wrong with it.
    Line {
        /// The file.
        path: PathBuf,
        /// The line, counting from 1.
        line: usize,
        /// What is wrong.
        problem: ObjProblem,
    },
    /// A file that holds no faces.
    NoFaces {
        /// The file.
        path: PathBuf,
    },
    /// A file whose positions span less than [`crate::MIN_EXTENT`] on every axis (a point, or
    /// denormal coordinates): no shadow map or view can be fitted to it.
    DegenerateExtent {
        /// The file.
        path: PathBuf,
        /// The largest side of the positions' bounding box.
        extent: f64,
    },
    /// The file's mesh breaks a rule of [`crate::Mesh`] (more than 2³² vertices or groups).
    Mesh {
        /// The file.
        path: PathBuf,
        /// The mesh's error.
        source: MeshError,
    },
    /// tobj rejected a file that this crate's line-by-line check had accepted: a bug here, please
    /// report it with the file.
    Internal {
        /// The file.
        path: PathBuf,
        /// tobj's message.
        message: String,
    },
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(error) => write!(f, "{error}"),
            Self::Line {
                path,
                line,
                problem,
            } => write!(f, "{}:{line}: {problem}", path.display()),
            Self::NoFaces { path } => write!(f, "{}: no faces", path.display()),
            Self::DegenerateExtent { path, extent } => write!(
                f,
                "{}: the positions span {} at most on any axis; a mesh must span at least {} \
                 (MIN_EXTENT) so that its extent squared stays a normal f64 number",
                path.display(),
                Shown(*extent),
                Shown(crate::MIN_EXTENT)
            ),
            Self::Mesh { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Internal { path, message } => write!(
                f,
                "{}: tobj rejected the file ({message}) after shadowlab-scene's checks accepted \
                 it; this is a bug in shadowlab-scene, please report it with the file",
                path.display()
            ),
        }
    }
}

impl std::error::Error for ObjError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Read(error) => Some(error),
            Self::Mesh { source, .. } => Some(source),
            Self::Line { .. }
            | Self::NoFaces { .. }
            | Self::DegenerateExtent { .. }
            | Self::Internal { .. } => None,
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
    /// A coordinate (after the division by w) beyond ±[`crate::MAX_COORDINATE`].
    CoordinateOutOfRange {
        /// The text found (`x/w` for a weighted position).
        token: String,
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
            Self::CoordinateOutOfRange { token } => write!(
                f,
                "`v`: `{token}` is beyond ±{} (MAX_COORDINATE), the largest coordinate magnitude \
                 read, so that the mesh's extent and its square stay finite in f64",
                Shown(crate::MAX_COORDINATE)
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
