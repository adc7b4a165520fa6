//! The errors and warnings of [`crate::load_gltf`]: the file, the glTF objects (node, mesh,
//! primitive, accessor, camera, light, each with its index and name) and what is wrong or was
//! skipped.

use std::fmt;
use std::path::PathBuf;

use crate::mesh::MeshError;
use crate::number::Shown;
use crate::read::ReadError;

/// The kinds of glTF objects an error or warning can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GltfObjectKind {
    /// An entry of `scenes`.
    Scene,
    /// An entry of `nodes`.
    Node,
    /// An entry of `meshes`.
    Mesh,
    /// An entry of a mesh's `primitives`.
    Primitive,
    /// An entry of `accessors`.
    Accessor,
    /// An entry of `bufferViews`.
    BufferView,
    /// An entry of `buffers`.
    Buffer,
    /// An entry of `cameras`.
    Camera,
    /// An entry of `KHR_lights_punctual`'s `lights`.
    Light,
    /// An entry of `skins`.
    Skin,
}

impl GltfObjectKind {
    fn word(self) -> &'static str {
        match self {
            Self::Scene => "scene",
            Self::Node => "node",
            Self::Mesh => "mesh",
            Self::Primitive => "primitive",
            Self::Accessor => "accessor",
            Self::BufferView => "bufferView",
            Self::Buffer => "buffer",
            Self::Camera => "camera",
            Self::Light => "light",
            Self::Skin => "skin",
        }
    }
}

/// One glTF object: its kind, its index in its array and its name, if the file gives one.
/// Displayed as `node 3 'Wheel'`, or `primitive 0` without a name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GltfObject {
    /// What it is.
    pub kind: GltfObjectKind,
    /// Its index in its array (`nodes[3]` is node 3).
    pub index: usize,
    /// Its `name`, if any.
    pub name: Option<String>,
}

impl GltfObject {
    pub(crate) fn new(kind: GltfObjectKind, index: usize, name: Option<&str>) -> Self {
        Self {
            kind,
            index,
            name: name.map(str::to_owned),
        }
    }
}

impl fmt::Display for GltfObject {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.kind.word(), self.index)?;
        match &self.name {
            Some(name) => write!(f, " '{name}'"),
            None => Ok(()),
        }
    }
}

/// A chain of objects, outermost first, as `node 1 'Wheel': mesh 0: primitive 2`.
struct Objects<'a>(&'a [GltfObject]);

impl fmt::Display for Objects<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for object in self.0 {
            write!(f, "{object}: ")?;
        }
        Ok(())
    }
}

/// Why a glTF file could not be read as a scene.
#[non_exhaustive]
#[derive(Debug)]
pub enum GltfError {
    /// The file, or an external buffer it names, could not be read: missing, not a regular
    /// file, or larger than [`crate::MAX_GLTF_BYTES`].
    Read(ReadError),
    /// Not a glTF 2.0 file: a GLB container that breaks glTF 2.0 §4, JSON that does not parse, or
    /// JSON that does not fit the schema (a value of the wrong type, a missing required
    /// property), with serde_json's line and column.
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The file parses but breaks rules of the glTF 2.0 schema that `gltf`'s validation checks
    /// (an index out of range, a camera without its projection, a stride out of range).
    Invalid {
        /// The file.
        path: PathBuf,
        /// Each problem: the JSON path (`meshes[0].primitives[0].indices`) and what is wrong.
        problems: Vec<(String, String)>,
    },
    /// The file requires extensions (`extensionsRequired`) that shadowlab does not read, e.g.
    /// `KHR_draco_mesh_compression`; glTF 2.0 §3.12 forbids loading it without them.
    UnsupportedExtensions {
        /// The file.
        path: PathBuf,
        /// The extensions.
        extensions: Vec<String>,
    },
    /// A problem in one object of the file (a node, primitive, accessor, buffer, camera or
    /// light), named with the objects that lead to it.
    Object {
        /// The file.
        path: PathBuf,
        /// The objects, outermost first: e.g. the node, its mesh, the primitive, the accessor.
        objects: Vec<GltfObject>,
        /// What is wrong.
        problem: GltfProblem,
    },
    /// The scene asked for does not exist, or the file has no scene.
    NoScene {
        /// The file.
        path: PathBuf,
        /// The scene index asked for, if one was.
        asked: Option<usize>,
        /// The number of scenes in the file.
        scenes: usize,
    },
    /// The scene has no triangles to draw: no node with a triangle mesh, or only primitives that
    /// were skipped.
    NoTriangles {
        /// The file.
        path: PathBuf,
        /// The scene.
        scene: usize,
        /// What was skipped (points, lines, …).
        skipped: Vec<GltfWarning>,
    },
    /// The scene's positions span less than [`crate::MIN_EXTENT`] on every axis.
    DegenerateExtent {
        /// The file.
        path: PathBuf,
        /// The largest side of the positions' bounding box.
        extent: f64,
    },
    /// The scene, with every mesh instanced by its nodes, has more triangles or vertices than
    /// [`crate::MAX_GLTF_TRIANGLES`] allows (or an accessor more elements), or its buffers
    /// declare more than [`crate::MAX_GLTF_BYTES`].
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What is too large, e.g. `"triangles"`.
        what: &'static str,
        /// How many there would be, at least.
        count: u64,
        /// The limit.
        limit: u64,
    },
}

impl GltfError {
    pub(crate) fn object(
        path: impl Into<PathBuf>,
        objects: Vec<GltfObject>,
        problem: GltfProblem,
    ) -> Self {
        Self::Object {
            path: path.into(),
            objects,
            problem,
        }
    }
}

impl fmt::Display for GltfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(error) => write!(f, "{error}"),
            Self::Format { path, message } => {
                write!(f, "{}: not a glTF 2.0 file: {message}", path.display())
            }
            Self::Invalid { path, problems } => {
                write!(f, "{}: invalid glTF 2.0:", path.display())?;
                for (json_path, problem) in problems {
                    write!(f, " {json_path}: {problem};")?;
                }
                Ok(())
            }
            Self::UnsupportedExtensions { path, extensions } => write!(
                f,
                "{}: requires the extension{} {}, which shadowlab does not read (of the \
                 extensions only KHR_lights_punctual is read; glTF 2.0 §3.12 forbids loading a \
                 file without its required extensions)",
                path.display(),
                if extensions.len() == 1 { "" } else { "s" },
                extensions.join(", ")
            ),
            Self::Object {
                path,
                objects,
                problem,
            } => write!(f, "{}: {}{problem}", path.display(), Objects(objects)),
            Self::NoScene {
                path,
                asked: Some(asked),
                scenes,
            } => write!(
                f,
                "{}: there is no scene {asked}; the file has {scenes} scene{}",
                path.display(),
                if *scenes == 1 { "" } else { "s" }
            ),
            Self::NoScene {
                path, asked: None, ..
            } => write!(
                f,
                "{}: the file has no scene (glTF 2.0 §3.5.1: a file without scenes is a library \
                 of objects, not a scene to draw)",
                path.display()
            ),
            Self::NoTriangles {
                path,
                scene,
                skipped,
            } => {
                write!(
                    f,
                    "{}: scene {scene} has no triangles to draw",
                    path.display()
                )?;
                for warning in skipped {
                    write!(f, "; {}{}", Objects(&warning.objects), warning.skipped)?;
                }
                Ok(())
            }
            Self::DegenerateExtent { path, extent } => write!(
                f,
                "{}: the positions span {} at most on any axis; a scene must span at least {} \
                 (MIN_EXTENT) so that its extent squared stays a normal f64 number",
                path.display(),
                Shown(*extent),
                Shown(crate::MIN_EXTENT)
            ),
            Self::TooLarge {
                path,
                what,
                count,
                limit,
            } => write!(
                f,
                "{}: the scene would have at least {count} {what}, more than {limit} \
                 ({}), the most read from one file",
                path.display(),
                if what.starts_with("bytes") {
                    "MAX_GLTF_BYTES"
                } else {
                    "MAX_GLTF_TRIANGLES"
                }
            ),
        }
    }
}

impl std::error::Error for GltfError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Read(error) => Some(error),
            Self::Object {
                problem: GltfProblem::Mesh(error),
                ..
            } => Some(error),
            Self::Object {
                problem: GltfProblem::BufferFile(error),
                ..
            } => Some(error),
            _ => None,
        }
    }
}

/// What is wrong with one object of a glTF file.
#[non_exhaustive]
#[derive(Debug)]
pub enum GltfProblem {
    /// A node with two parents, or in a cycle: glTF 2.0 §3.5.2 makes the node hierarchy a set of
    /// disjoint strict trees.
    NodeRepeated,
    /// A node's `matrix` whose last row is not `0 0 0 1`: glTF 2.0 §3.5.3 requires an affine
    /// (TRS-decomposable) transform.
    NotAffine {
        /// The last row of the matrix.
        row: [f32; 4],
    },
    /// A node's `matrix`, `translation`, `rotation` or `scale` with a NaN or infinite value.
    NonFiniteTransform {
        /// The property, e.g. `"rotation"`.
        property: &'static str,
    },
    /// A node's `rotation` quaternion of length zero, which is no rotation.
    ZeroRotation,
    /// A buffer that cannot be had: no `uri` outside the GLB binary chunk, a URI scheme other
    /// than a relative path or a `data:` URI, a `data:` URI that is not valid base64.
    BufferSource {
        /// What is wrong, e.g. `"the URI scheme http: is not read"`.
        reason: String,
    },
    /// An external buffer file that could not be read.
    BufferFile(ReadError),
    /// A buffer whose data is shorter than its `byteLength`.
    BufferTooShort {
        /// The `byteLength`.
        declared: u64,
        /// The bytes there are.
        found: u64,
    },
    /// A byte range (of a buffer view in its buffer, or of an accessor in its buffer view)
    /// that does not fit.
    OutOfBounds {
        /// What the range is, e.g. `"the accessor's elements"`.
        what: &'static str,
        /// Its first byte.
        start: u64,
        /// One past its last byte.
        end: u64,
        /// The length of what it must fit in.
        length: u64,
    },
    /// An accessor of the wrong type for its use (glTF 2.0 §3.7.2.1): e.g. a `POSITION` that is
    /// not `VEC3` of `FLOAT`, or indices that are not `SCALAR` unsigned integers.
    WrongAccessorType {
        /// What the accessor is used as, e.g. `"POSITION"`.
        used_as: &'static str,
        /// What it must be.
        expected: &'static str,
        /// What it is, e.g. `"VEC2 of FLOAT"`.
        found: String,
    },
    /// An accessor with `count` 0 (the schema's minimum is 1).
    EmptyAccessor,
    /// A buffer view's `byteStride` smaller than one element.
    StrideTooSmall {
        /// The stride.
        stride: u64,
        /// The element size in bytes.
        element: u64,
    },
    /// A sparse accessor's indices that do not strictly increase or reach past its count
    /// (glTF 2.0 §3.6.2.3).
    BadSparseIndex {
        /// The position among the sparse indices.
        position: usize,
        /// The index found there.
        index: u64,
    },
    /// A position with a NaN or infinite coordinate.
    NonFinitePosition {
        /// The element of the accessor.
        element: usize,
        /// Its coordinates.
        value: [f32; 3],
    },
    /// A vertex index that names no vertex of the primitive.
    IndexOutOfRange {
        /// The position among the indices.
        position: usize,
        /// The index.
        index: u32,
        /// The primitive's vertex count.
        vertices: usize,
    },
    /// Attributes of one primitive with different counts (glTF 2.0 §3.7.2.1 requires them
    /// equal).
    AttributeCountMismatch {
        /// The attribute, e.g. `"NORMAL"`.
        attribute: &'static str,
        /// Its count.
        count: usize,
        /// `POSITION`'s count.
        positions: usize,
    },
    /// A vertex or index count that the primitive's mode cannot use: not a multiple of 3 for
    /// `TRIANGLES`, fewer than 3 for strips and fans (glTF 2.0 §3.7.2.1).
    BadVertexCount {
        /// The mode, e.g. `"TRIANGLES"`.
        mode: &'static str,
        /// The count of vertices (or indices, for an indexed primitive).
        count: usize,
    },
    /// A camera or light value out of the range shadowlab (or the glTF schema) accepts.
    OutOfRange {
        /// The property, e.g. `"yfov"`.
        property: &'static str,
        /// Its value.
        value: f64,
        /// The range, e.g. `"in [1.7e-5, π) radians"`.
        requirement: String,
    },
    /// A camera or light whose derived pose or range is unusable (e.g. a far plane derived from
    /// the scene's bounds that is not beyond the camera's `znear`).
    Unusable {
        /// Why.
        reason: String,
    },
    /// The mesh of a node breaks a rule of [`crate::Mesh`] (a world position beyond
    /// [`crate::MAX_COORDINATE`]).
    Mesh(MeshError),
}

impl fmt::Display for GltfProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NodeRepeated => f.write_str(
                "is reached a second time: the node hierarchy must be disjoint trees, without \
                 cycles or nodes with two parents (glTF 2.0 §3.5.2)",
            ),
            Self::NotAffine { row } => write!(
                f,
                "`matrix` has the last row {row:?}, not [0, 0, 0, 1]: a node's transform must \
                 be affine (glTF 2.0 §3.5.3)"
            ),
            Self::NonFiniteTransform { property } => {
                write!(f, "`{property}` has a value that is not finite")
            }
            Self::ZeroRotation => f.write_str("`rotation` is the zero quaternion, no rotation"),
            Self::BufferSource { reason } => f.write_str(reason),
            Self::BufferFile(error) => write!(f, "{error}"),
            Self::BufferTooShort { declared, found } => write!(
                f,
                "holds {found} bytes, fewer than its byteLength {declared}"
            ),
            Self::OutOfBounds {
                what,
                start,
                end,
                length,
            } => write!(
                f,
                "{what} span bytes {start}..{end}, beyond the {length} bytes there are"
            ),
            Self::WrongAccessorType {
                used_as,
                expected,
                found,
            } => write!(
                f,
                "is {found}, but {used_as} must be {expected} (glTF 2.0 §3.7.2.1)"
            ),
            Self::EmptyAccessor => {
                f.write_str("has count 0; an accessor holds at least one element")
            }
            Self::StrideTooSmall { stride, element } => write!(
                f,
                "byteStride {stride} is smaller than an element ({element} bytes)"
            ),
            Self::BadSparseIndex { position, index } => write!(
                f,
                "sparse index {position} is {index}: sparse indices must strictly increase and \
                 stay below the accessor's count (glTF 2.0 §3.6.2.3)"
            ),
            Self::NonFinitePosition { element, value } => {
                write!(f, "position {element} is {value:?}, not finite")
            }
            Self::IndexOutOfRange {
                position,
                index,
                vertices,
            } => write!(
                f,
                "index {position} is {index}, but the primitive has {vertices} vertices"
            ),
            Self::AttributeCountMismatch {
                attribute,
                count,
                positions,
            } => write!(
                f,
                "{attribute} has {count} elements but POSITION has {positions}; a primitive's \
                 attributes must have one count (glTF 2.0 §3.7.2.1)"
            ),
            Self::BadVertexCount { mode, count } => write!(
                f,
                "{mode} cannot be drawn from {count} {}: {} (glTF 2.0 §3.7.2.1)",
                if *count == 1 { "vertex" } else { "vertices" },
                if *mode == "TRIANGLES" {
                    "the count must be a multiple of 3"
                } else {
                    "it needs at least 3"
                }
            ),
            Self::OutOfRange {
                property,
                value,
                requirement,
            } => write!(f, "`{property}` ({}) must be {requirement}", Shown(*value)),
            Self::Unusable { reason } => f.write_str(reason),
            Self::Mesh(error) => write!(f, "{error}"),
        }
    }
}

/// Something in a glTF file that shadowlab cannot represent and skipped (or replaced), named
/// with the objects it belongs to. The file is read all the same; a caller shows the warnings
/// to the user (their `Display` is one line each, naming the file).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfWarning {
    /// The file.
    pub path: PathBuf,
    /// The objects, outermost first (empty for the file as a whole).
    pub objects: Vec<GltfObject>,
    /// What was skipped or replaced.
    pub skipped: GltfSkipped,
}

impl fmt::Display for GltfWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: {}{}",
            self.path.display(),
            Objects(&self.objects),
            self.skipped
        )
    }
}

/// What a [`GltfWarning`] says was skipped or replaced.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum GltfSkipped {
    /// A primitive of points or lines: no surface, no shadow.
    PrimitiveMode {
        /// The mode, e.g. `"LINE_STRIP"`.
        mode: &'static str,
    },
    /// A spot light whose cone is wider than a perspective shadow map can cover.
    WideSpot {
        /// `outerConeAngle`, radians.
        outer_cone_angle: f64,
    },
    /// An orthographic camera: shadowlab's eye is a perspective camera.
    OrthographicCamera,
    /// Morph targets, not applied: the primitive's base shape is drawn.
    MorphTargets {
        /// How many targets.
        count: usize,
    },
    /// A skin, not applied: the mesh is drawn as stored, placed by its node's transform.
    Skin {
        /// The skin's index.
        skin: usize,
    },
    /// Animations, not applied: nodes are placed by their transforms as stored.
    Animations {
        /// How many animations.
        count: usize,
    },
    /// A mesh node whose world transform is singular (a zero scale): its mesh has no area and is
    /// not drawn.
    SingularTransform,
    /// Normals that are zero or not finite, replaced by computed (area-weighted) ones.
    BadNormals {
        /// How many.
        count: usize,
    },
    /// The camera's `zfar`, brought in to the far side of the scene's bounds because `zfar /
    /// znear` exceeds [`MAX_DEPTH_RATIO`](crate::scene_file::MAX_DEPTH_RATIO); nothing lies beyond the new far
    /// plane, so the image is the same.
    FarReduced {
        /// The file's `zfar`.
        zfar: f64,
        /// The far distance used.
        far: f64,
    },
    /// The camera's `aspectRatio`, which the image size overrides.
    AspectRatio {
        /// The file's aspect ratio.
        file: f64,
        /// The image's width.
        width: u32,
        /// The image's height.
        height: u32,
    },
}

impl fmt::Display for GltfSkipped {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PrimitiveMode { mode } => write!(
                f,
                "skipped: a {mode} primitive has no surface to cast or receive shadows"
            ),
            Self::WideSpot { outer_cone_angle } => write!(
                f,
                "spot light skipped: its cone of {}° is not below 180°, which a perspective \
                 shadow map needs",
                Shown(2.0 * outer_cone_angle.to_degrees())
            ),
            Self::OrthographicCamera => {
                f.write_str("orthographic camera skipped: shadowlab's eye is a perspective camera")
            }
            Self::MorphTargets { count } => write!(
                f,
                "{count} morph target{} not applied: the base shape is drawn",
                if *count == 1 { "" } else { "s" }
            ),
            Self::Skin { skin } => write!(
                f,
                "skin {skin} not applied: the mesh is drawn as stored, placed by its node's \
                 transform"
            ),
            Self::Animations { count } => write!(
                f,
                "{count} animation{} not applied: nodes are placed by their transforms as stored",
                if *count == 1 { "" } else { "s" }
            ),
            Self::SingularTransform => f.write_str(
                "skipped: the node's world transform is singular (a zero scale), so its mesh has \
                 no area",
            ),
            Self::BadNormals { count } => write!(
                f,
                "{count} normal{} zero or not finite, replaced by area-weighted ones",
                if *count == 1 { " is" } else { "s are" }
            ),
            Self::FarReduced { zfar, far } => write!(
                f,
                "zfar {} reduced to {}, just beyond the scene: zfar/znear may be at most {} \
                 (MAX_DEPTH_RATIO)",
                Shown(*zfar),
                Shown(*far),
                Shown(crate::limits::MAX_DEPTH_RATIO)
            ),
            Self::AspectRatio {
                file,
                width,
                height,
            } => write!(
                f,
                "aspectRatio {} not used: the image, {width}×{height}, sets the aspect",
                Shown(*file)
            ),
        }
    }
}
