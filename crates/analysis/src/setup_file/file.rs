//! The set-up file as it is written: plain data in the file's own conventions, one type per JSON
//! object, every object closed to unknown fields. `docs/setup-format.md` is its reference.

use serde::{Deserialize, Serialize};

/// The value of the top-level `format` field.
pub const FORMAT: &str = "shadowlab-setup";

/// The format version this library reads and writes.
pub const VERSION: u32 = 1;

/// A whole set-up file: what every light's shadow maps were for one or more frames.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetupFile {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// Who wrote it and from what, for people (not read).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// The shadowlab technique that planned it (`lispsm:minimax`, as the command line writes it);
    /// it labels the measurements. Absent for a set-up made elsewhere (an engine's), which is
    /// labelled `given`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub technique: Option<String>,
    /// How the matrices of the file are to be read.
    pub conventions: Conventions,
    /// The frames, in order (shimmer is counted between consecutive ones).
    pub frames: Vec<FrameEntry>,
}

/// How the file's matrices are written: read once, when the file is read, into the library's
/// convention (column vectors, GL clip space with NDC depth in `[−1, 1]` and y up, a right-handed
/// world).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Conventions {
    /// The order of a matrix's 16 numbers.
    pub matrix_order: MatrixOrder,
    /// The NDC depth range the projections produce.
    pub ndc_depth: NdcDepthRange,
    /// Which way NDC y points.
    pub ndc_y: NdcY,
    /// The handedness of the world the view matrices take points from.
    pub world: Handedness,
}

impl Conventions {
    /// The library's own: row-major (as `inspect` prints), `[−1, 1]`, y up, right-handed. Files in
    /// these conventions are read without arithmetic on their numbers.
    pub const LIBRARY: Self = Self {
        matrix_order: MatrixOrder::RowMajor,
        ndc_depth: NdcDepthRange::NegativeOneToOne,
        ndc_y: NdcY::Up,
        world: Handedness::RightHanded,
    };
}

/// The order of a matrix's 16 numbers. Matrices act on column vectors, `clip = P·V·(x, y, z, 1)`;
/// an engine whose matrices act on row vectors (`v·M`, DirectXMath, Unity's shaders' `mul(v, M)`)
/// holds the transpose, so its row-major storage is this matrix's `column-major` order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MatrixOrder {
    /// Row by row: `m[0..4]` is the first row.
    RowMajor,
    /// Column by column (GL, glam, GLM): `m[0..4]` is the first column.
    ColumnMajor,
}

/// The NDC depth range of the file's projections.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NdcDepthRange {
    /// OpenGL: near → −1, far → 1.
    NegativeOneToOne,
    /// Direct3D, Vulkan, Metal: near → 0, far → 1.
    ZeroToOne,
    /// Reversed Z: near → 1, far → 0 (depth images then hold `1 − z`, as such a depth buffer
    /// does).
    ReversedZeroToOne,
}

/// Which way NDC y points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NdcY {
    /// GL, Direct3D, Metal: +y is the top of the image.
    Up,
    /// Vulkan: +y is the bottom of the image.
    Down,
}

/// The handedness of the file's world coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Handedness {
    /// The scene's own coordinates.
    RightHanded,
    /// The scene's coordinates with z negated, `(x, y, −z)`: a left-handed, y-up engine's
    /// (Unity's, for one) view of the same scene.
    LeftHanded,
}

/// One frame: the camera (optional) and every light's partitions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameEntry {
    /// The camera of this frame; absent: the scene's own camera.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraEntry>,
    /// One entry per light of the scene, in the scene's order.
    pub lights: Vec<LightEntry>,
}

/// A frame's camera as an engine holds it: its view and projection matrices (a symmetric
/// perspective projection with a finite far plane), and its image size.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraEntry {
    /// World → eye space.
    pub view: [f64; 16],
    /// Eye → clip space.
    pub projection: [f64; 16],
    /// The image width in pixels; absent: the scene camera's (give both or neither).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<u32>,
    /// The image height in pixels; absent: the scene camera's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<u32>,
}

/// One light's shadow: its partitions, nearest first.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightEntry {
    /// The partitions (one for an unpartitioned map), ordered by `near`.
    pub partitions: Vec<PartitionEntry>,
}

/// One shadow map: the eye depths it serves, its matrices, how it is stored and read, and
/// optionally its depths as an image.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartitionEntry {
    /// The eye depth where the partition starts serving.
    pub near: f64,
    /// The eye depth where it ends.
    pub far: f64,
    /// World → the light's view space.
    pub view: [f64; 16],
    /// The light's view space → clip space of the map.
    pub projection: [f64; 16],
    /// Side of the square map, in texels.
    pub map_size: u32,
    /// How depth is stored: `f32`, `reversed-f32`, `unorm24`, `unorm16`.
    pub depth_format: String,
    /// The bias, as the command line writes it (`slope:2,1e-5`).
    pub bias: String,
    /// The filter, as the command line writes it (`pcf:3`).
    pub filter: String,
    /// The map's depths as an image (EXR, NPY or 16-bit PNG; a path relative to the set-up file),
    /// looked up as it is instead of rendering the matrices.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth_image: Option<String>,
    /// The second-nearest depths, for the `second-depth`, `midpoint` and `dual-depth` biases.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second_depth_image: Option<String>,
}

/// The top two fields alone, read first so that another format or version is named as such
/// rather than as unknown fields.
#[derive(Deserialize)]
pub(super) struct Preamble {
    pub(super) format: String,
    pub(super) version: u32,
}
