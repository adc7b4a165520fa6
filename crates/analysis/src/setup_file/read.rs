//! Reading a set-up file into a [`Setup`]: the JSON checked field by field, every matrix
//! converted once into the library's convention, depth images located (they are read when a frame
//! is evaluated, so that a long file's images are never all in memory).

use std::path::{Path, PathBuf};

use glam::{DMat3, DMat4, DVec3};
use serde::de::DeserializeOwned;
use shadowlab_hull::{Perspective, ViewPose};
use shadowlab_raster::{DepthFormat, MAX_TARGET_SIZE};
use shadowlab_scene::read_bounded;
use shadowlab_scene::scene_file::{MAX_DEPTH_RATIO, MAX_IMAGE_SIDE};
use shadowlab_shadow::{Bias, Filter, Lookup, Technique};

use super::error::SetupError;
use super::file::{
    CameraEntry, Conventions, FORMAT, FrameEntry, Handedness, MatrixOrder, NdcDepthRange, NdcY,
    PartitionEntry, Preamble, SetupFile, VERSION,
};

/// The largest set-up file read: 64 MiB, some forty thousand partitions. A set-up file holds
/// matrices, not maps; the bound only stops a wrong path early.
pub const MAX_SETUP_FILE_BYTES: u64 = 64 << 20;

/// The most frames a set-up file holds (as `temporal --frames`).
pub const MAX_SETUP_FRAMES: usize = 10_000;

/// The most partitions of one light (as `--splits`).
pub const MAX_SETUP_PARTITIONS: usize = 16;

/// How far a frame's camera may be from a symmetric perspective view: the cosines between its
/// recovered axes (right, up, forward) and between its depth row and its view direction. f32
/// matrices (ε = 6·10⁻⁸) keep them within about 10⁻⁷; a projection off-centre by one pixel of
/// 1024 (a jittered one) shows 2·10⁻³.
pub const CAMERA_TOLERANCE: f64 = 1e-5;

/// What a depth image may hold beyond 8 bytes per texel (an f64 sample, the largest any reader
/// takes): headers and offset tables. A depth image of a map of side `s` is read up to
/// `8·s² + DEPTH_IMAGE_SLACK_BYTES` bytes.
pub const DEPTH_IMAGE_SLACK_BYTES: u64 = 1 << 20;

/// A set-up, read and checked: every matrix in the library's convention (column vectors, GL clip
/// space with NDC depth in `[−1, 1]` and y up, the scene's right-handed world).
#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    /// The file it was read from (for messages; depth images are relative to its directory).
    pub path: PathBuf,
    /// The technique that planned it, as the file says; [`Technique::Given`] if it does not.
    pub technique: Technique,
    /// The file's `source`, if any.
    pub source: Option<String>,
    /// The frames, in order.
    pub frames: Vec<SetupFrame>,
}

impl Setup {
    /// The largest map side of any partition (for memory estimates).
    #[must_use]
    pub fn largest_map(&self) -> u32 {
        self.partitions().map(|p| p.map_size).max().unwrap_or(0)
    }

    /// The most maps one frame holds, over all its lights (a frame's maps are held together).
    #[must_use]
    pub fn most_maps(&self) -> usize {
        self.frames
            .iter()
            .map(|f| f.lights.iter().map(Vec::len).sum())
            .max()
            .unwrap_or(0)
    }

    fn partitions(&self) -> impl Iterator<Item = &SetupPartition> {
        self.frames.iter().flat_map(|f| f.lights.iter().flatten())
    }
}

/// One frame of a set-up.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupFrame {
    /// The frame's camera; `None`: the scene's own.
    pub camera: Option<FrameCamera>,
    /// Per light (in the scene's order), its partitions, ordered by `near`.
    pub lights: Vec<Vec<SetupPartition>>,
}

/// A frame's camera: the pose and projection its matrices describe, and the matrices' product,
/// which the eye pass is drawn through (so the same matrices give the same image).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameCamera {
    /// Where it is and looks.
    pub pose: ViewPose,
    /// Its symmetric perspective projection.
    pub projection: Perspective,
    /// Its image size, width × height; `None`: the scene camera's.
    pub size: Option<(u32, u32)>,
    /// World → GL clip space, `projection · view` as given (converted).
    pub clip_from_world: DMat4,
}

/// One partition of a light's shadow, checked and converted.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupPartition {
    /// Its JSON path (`frames[0].lights[0].partitions[1]`), for messages.
    pub field: String,
    /// The eye depth where it starts serving.
    pub near: f64,
    /// The eye depth where it ends.
    pub far: f64,
    /// World → the light's view space.
    pub view: DMat4,
    /// The light's view space → GL clip space of the map.
    pub projection: DMat4,
    /// Side of the square map.
    pub map_size: u32,
    /// How depth is stored.
    pub format: DepthFormat,
    /// Bias and filter.
    pub lookup: Lookup,
    /// The map's nearest depths as an image, looked up instead of rendering.
    pub depth_image: Option<DepthImage>,
    /// Its second-nearest depths (given exactly when the bias reads them and `depth_image` is
    /// given).
    pub second_depth_image: Option<DepthImage>,
}

/// A depth image a partition names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DepthImage {
    /// Its JSON path (`…partitions[0].depth_image`), for messages.
    pub field: String,
    /// The file: the name given, joined to the set-up file's directory.
    pub path: PathBuf,
    /// Its kind, from its extension.
    pub kind: ImageKind,
    /// Whether it holds `1 − z` (the file's NDC depth is reversed, as its depth buffer was).
    pub reversed: bool,
}

/// The kinds of depth image read (`shadowlab_raster::image_in`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageKind {
    /// `.exr`: one f32 channel, top row first.
    Exr,
    /// `.npy`: f32 or f64, row 0 at the bottom.
    Npy,
    /// `.png`: 16-bit greyscale, top row first; unorm16 maps only.
    Png16,
}

/// Reads and checks the set-up file `path` ([`parse_setup`]).
///
/// # Errors
/// [`SetupError::Read`] if the file is missing, special or larger than
/// [`MAX_SETUP_FILE_BYTES`]; [`SetupError::NotUtf8`]; as [`parse_setup`].
pub fn load_setup(path: &Path) -> Result<Setup, SetupError> {
    let bytes = read_bounded(
        path,
        MAX_SETUP_FILE_BYTES,
        "a set-up file",
        "MAX_SETUP_FILE_BYTES",
    )
    .map_err(SetupError::Read)?;
    let text = String::from_utf8(bytes).map_err(|_| SetupError::NotUtf8 {
        path: path.to_owned(),
    })?;
    parse_setup(&text, path)
}

/// Checks the set-up `text` of the file `path` (named in every error; depth images are found
/// relative to its directory) and converts it into the library's convention.
///
/// # Errors
/// [`SetupError::Json`] for text that is not JSON of the format (with the JSON path, line and
/// column); [`SetupError::Field`] for another format or version, a technique shadowlab does not
/// know, no frames or partitions, partitions out of order, an empty or inverted depth range, a
/// singular matrix, a camera that is not a symmetric perspective view, a map size, depth format,
/// bias or filter out of range, a depth image of an unknown kind or missing its second depths.
pub fn parse_setup(text: &str, path: &Path) -> Result<Setup, SetupError> {
    let preamble: Preamble = deserialize(text, path)?;
    let field = |field: &str, problem: String| SetupError::Field {
        path: path.to_owned(),
        field: field.into(),
        problem,
    };
    if preamble.format != FORMAT {
        return Err(field(
            "format",
            format!(
                "{:?} is not a set-up file's format, {FORMAT:?}",
                preamble.format
            ),
        ));
    }
    if preamble.version != VERSION {
        return Err(field(
            "version",
            format!(
                "version {} is not one this shadowlab reads; it reads version {VERSION}",
                preamble.version
            ),
        ));
    }
    let file: SetupFile = deserialize(text, path)?;
    convert(&file, path)
}

/// `T` from `text`, its error naming the JSON path.
fn deserialize<T: DeserializeOwned>(text: &str, path: &Path) -> Result<T, SetupError> {
    let json = |field: String, error: &serde_json::Error| SetupError::Json {
        path: path.to_owned(),
        field,
        message: error.to_string(),
    };
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let value = serde_path_to_error::deserialize(&mut deserializer)
        .map_err(|e| json(e.path().to_string(), e.inner()))?;
    deserializer.end().map_err(|e| json(".".into(), &e))?;
    Ok(value)
}

/// The checked, converted set-up of `file`, read from `path`.
fn convert(file: &SetupFile, path: &Path) -> Result<Setup, SetupError> {
    let problem = |field: &str, problem: String| SetupError::Field {
        path: path.to_owned(),
        field: field.into(),
        problem,
    };
    let technique = match &file.technique {
        None => Technique::Given,
        Some(spec) => Technique::parse_spec(spec).map_err(|e| {
            problem(
                "technique",
                format!("{e}; a set-up made elsewhere leaves technique out"),
            )
        })?,
    };
    if file.frames.is_empty() || file.frames.len() > MAX_SETUP_FRAMES {
        return Err(problem(
            "frames",
            format!(
                "{} frames; a set-up has 1 to {MAX_SETUP_FRAMES}",
                file.frames.len()
            ),
        ));
    }
    let reader = Reader {
        path,
        base: path.parent().unwrap_or(Path::new("")),
        conventions: file.conventions,
    };
    let frames = file
        .frames
        .iter()
        .enumerate()
        .map(|(k, frame)| reader.frame(k, frame))
        .collect::<Result<_, _>>()?;
    Ok(Setup {
        path: path.to_owned(),
        technique,
        source: file.source.clone(),
        frames,
    })
}

/// What reading a frame needs: the file, its directory, its conventions.
struct Reader<'a> {
    path: &'a Path,
    base: &'a Path,
    conventions: Conventions,
}

impl Reader<'_> {
    fn problem(&self, field: &str, problem: String) -> SetupError {
        SetupError::Field {
            path: self.path.to_owned(),
            field: field.into(),
            problem,
        }
    }

    fn frame(&self, k: usize, entry: &FrameEntry) -> Result<SetupFrame, SetupError> {
        let camera = entry
            .camera
            .as_ref()
            .map(|c| self.camera(&format!("frames[{k}].camera"), c))
            .transpose()?;
        let lights = entry
            .lights
            .iter()
            .enumerate()
            .map(|(l, light)| {
                let field = format!("frames[{k}].lights[{l}].partitions");
                let count = light.partitions.len();
                if count == 0 || count > MAX_SETUP_PARTITIONS {
                    return Err(self.problem(
                        &field,
                        format!("{count} partitions; a light has 1 to {MAX_SETUP_PARTITIONS} maps"),
                    ));
                }
                let partitions: Vec<SetupPartition> = light
                    .partitions
                    .iter()
                    .enumerate()
                    .map(|(p, partition)| self.partition(&format!("{field}[{p}]"), partition))
                    .collect::<Result<_, _>>()?;
                for pair in partitions.windows(2) {
                    if pair[1].near <= pair[0].near {
                        return Err(self.problem(
                            &format!("{}.near", pair[1].field),
                            format!(
                                "{} is not beyond the previous partition's near, {}: \
                                 partitions are ordered by near, and a pixel is served by the \
                                 last whose near is at most its eye depth",
                                pair[1].near, pair[0].near
                            ),
                        ));
                    }
                }
                Ok(partitions)
            })
            .collect::<Result<_, _>>()?;
        Ok(SetupFrame { camera, lights })
    }

    fn camera(&self, field: &str, entry: &CameraEntry) -> Result<FrameCamera, SetupError> {
        let view = self.world_to_scene(matrix(self.conventions.matrix_order, &entry.view));
        let projection = self.to_gl_clip(matrix(self.conventions.matrix_order, &entry.projection));
        let clip_from_world = projection * view;
        let size = match (entry.width, entry.height) {
            (None, None) => None,
            (Some(width), Some(height)) => {
                for (name, side) in [("width", width), ("height", height)] {
                    if !(1..=MAX_IMAGE_SIDE).contains(&side) {
                        return Err(self.problem(
                            &format!("{field}.{name}"),
                            format!("{side} is not an image side in 1..={MAX_IMAGE_SIDE}"),
                        ));
                    }
                }
                Some((width, height))
            }
            (Some(_), None) | (None, Some(_)) => {
                return Err(self.problem(
                    field,
                    "gives one of width and height: give both, or neither for the scene \
                     camera's image size"
                        .into(),
                ));
            }
        };
        let (pose, projection) = decompose(&clip_from_world)
            .map_err(|problem| self.problem(field, format!("projection · view {problem}")))?;
        Ok(FrameCamera {
            pose,
            projection,
            size,
            clip_from_world,
        })
    }

    fn partition(&self, field: &str, entry: &PartitionEntry) -> Result<SetupPartition, SetupError> {
        let (near, far) = (entry.near, entry.far);
        if near < 0.0 {
            return Err(self.problem(
                &format!("{field}.near"),
                format!("{near} is negative; eye depths are at least 0"),
            ));
        }
        if far <= near {
            return Err(self.problem(
                &format!("{field}.far"),
                format!("{far} is not beyond near, {near}"),
            ));
        }
        let order = self.conventions.matrix_order;
        let view = self.world_to_scene(matrix(order, &entry.view));
        let projection = self.to_gl_clip(matrix(order, &entry.projection));
        let determinant = (projection * view).determinant();
        if !(view.is_finite() && projection.is_finite())
            || determinant == 0.0
            || !determinant.is_finite()
        {
            return Err(self.problem(
                &format!("{field}.projection"),
                format!(
                    "projection · view has determinant {determinant}: a map's matrices must \
                     map the world one to one onto clip space, in finite numbers"
                ),
            ));
        }
        if !(1..=MAX_TARGET_SIZE).contains(&entry.map_size) {
            return Err(self.problem(
                &format!("{field}.map_size"),
                format!(
                    "{} is not a map side in 1..={MAX_TARGET_SIZE}",
                    entry.map_size
                ),
            ));
        }
        let format = DepthFormat::ALL
            .into_iter()
            .find(|f| f.key_name() == entry.depth_format)
            .ok_or_else(|| {
                self.problem(
                    &format!("{field}.depth_format"),
                    format!(
                        "unknown depth format {:?}; known: f32, reversed-f32, unorm24, unorm16",
                        entry.depth_format
                    ),
                )
            })?;
        let bias =
            Bias::parse(&entry.bias).map_err(|e| self.problem(&format!("{field}.bias"), e))?;
        let filter = Filter::parse(&entry.filter)
            .map_err(|e| self.problem(&format!("{field}.filter"), e))?;
        let image = |name: &str, given: &Option<String>| {
            given
                .as_deref()
                .map(|file| self.image(&format!("{field}.{name}"), file, format))
                .transpose()
        };
        let depth_image = image("depth_image", &entry.depth_image)?;
        let second_depth_image = image("second_depth_image", &entry.second_depth_image)?;
        match (&depth_image, &second_depth_image, bias.needs_second_depth()) {
            (None, Some(second), _) => {
                return Err(self.problem(
                    &second.field,
                    "is given without depth_image: the second-nearest depths go with the \
                     nearest"
                        .into(),
                ));
            }
            (Some(first), None, true) => {
                return Err(self.problem(
                    &first.field,
                    format!(
                        "the bias {bias} reads second-nearest depths: give second_depth_image \
                         beside depth_image"
                    ),
                ));
            }
            (_, Some(second), false) => {
                return Err(self.problem(
                    &second.field,
                    format!(
                        "the bias {bias} reads no second-nearest depths (only second-depth, \
                         midpoint and dual-depth do)"
                    ),
                ));
            }
            _ => {}
        }
        Ok(SetupPartition {
            field: field.into(),
            near,
            far,
            view,
            projection,
            map_size: entry.map_size,
            format,
            lookup: Lookup::new(bias, filter),
            depth_image,
            second_depth_image,
        })
    }

    fn image(
        &self,
        field: &str,
        name: &str,
        format: DepthFormat,
    ) -> Result<DepthImage, SetupError> {
        let path = self.base.join(name);
        let extension = Path::new(name)
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let kind = match extension.as_deref() {
            Some("exr") => ImageKind::Exr,
            Some("npy") => ImageKind::Npy,
            Some("png") if format == DepthFormat::Unorm16 => ImageKind::Png16,
            Some("png") => {
                return Err(self.problem(
                    field,
                    format!(
                        "{name:?}: a 16-bit PNG holds unorm16 depths exactly, and this map is \
                         {}: give it as EXR or NPY",
                        format.key_name()
                    ),
                ));
            }
            _ => {
                return Err(self.problem(
                    field,
                    format!("{name:?} is not named .exr, .npy or .png, the depth images read"),
                ));
            }
        };
        Ok(DepthImage {
            field: field.into(),
            path,
            kind,
            reversed: self.conventions.ndc_depth == NdcDepthRange::ReversedZeroToOne,
        })
    }

    /// A view matrix of the file's world as one of the scene's: for a left-handed file,
    /// `V·diag(1, 1, −1, 1)` (its third column negated, which is exact).
    fn world_to_scene(&self, view: DMat4) -> DMat4 {
        match self.conventions.world {
            Handedness::RightHanded => view,
            Handedness::LeftHanded => {
                let mut view = view;
                view.z_axis = -view.z_axis;
                view
            }
        }
    }

    /// A projection of the file's clip space as one into GL's: depth rows `2z − w` (`[0, 1]`) or
    /// `w − 2z` (reversed), y negated for y down. The library's own conventions change nothing.
    fn to_gl_clip(&self, projection: DMat4) -> DMat4 {
        let mut rows = projection.transpose();
        match self.conventions.ndc_depth {
            NdcDepthRange::NegativeOneToOne => {}
            NdcDepthRange::ZeroToOne => rows.z_axis = rows.z_axis * 2.0 - rows.w_axis,
            NdcDepthRange::ReversedZeroToOne => rows.z_axis = rows.w_axis - rows.z_axis * 2.0,
        }
        if self.conventions.ndc_y == NdcY::Down {
            rows.y_axis = -rows.y_axis;
        }
        rows.transpose()
    }
}

/// The matrix whose 16 numbers are `m` in `order`.
fn matrix(order: MatrixOrder, m: &[f64; 16]) -> DMat4 {
    let columns = DMat4::from_cols_array(m);
    match order {
        MatrixOrder::ColumnMajor => columns,
        MatrixOrder::RowMajor => columns.transpose(),
    }
}

/// The camera of a world → GL clip matrix `M = P·V` with `P` a symmetric perspective projection
/// and `V` a right-handed rigid view. With `M`'s rows `r₀…r₃` scaled so that `|r₃.xyz| = 1`:
/// `r₃ = (f, −f·e)` (w is the eye depth along the view direction f), `r₀ = c_x·(right, …)`,
/// `r₁ = c_y·(up, …)`, `r₂.xyz = −a·f`; the eye e solves `r₀, r₁, r₃ · (e, 1) = 0`, then
/// `b = r₂·(e, 1)`, near `= b/(a − 1)`, far `= b/(a + 1)` (GL's `a = (f+n)/(n−f)`,
/// `b = 2fn/(n−f)`), `fov_y = 2·atan(1/c_y)`, aspect `= c_y/c_x`. `Err` says what does not fit:
/// axes further than [`CAMERA_TOLERANCE`] from orthogonal, a mirrored frame, a far plane beyond
/// `MAX_DEPTH_RATIO` times the near one (as scene files' cameras).
fn decompose(m: &DMat4) -> Result<(ViewPose, Perspective), String> {
    let rows = m.transpose();
    let scale = rows.w_axis.truncate().length();
    if !(scale > 0.0 && scale.is_finite()) {
        return Err(
            "has no w row: it is not a perspective camera's (an orthographic camera is \
                    not modelled)"
                .into(),
        );
    }
    let [r0, r1, r2, r3] = [rows.x_axis, rows.y_axis, rows.z_axis, rows.w_axis].map(|r| r / scale);
    let forward = r3.truncate();
    let (cx, cy) = (r0.truncate().length(), r1.truncate().length());
    let (right, up) = (r0.truncate() / cx, r1.truncate() / cy);
    let depth_row = r2.truncate();
    let off_axis = depth_row - forward * depth_row.dot(forward);
    let cosines = [
        ("its x row and its view direction", right.dot(forward)),
        ("its y row and its view direction", up.dot(forward)),
        ("its x and y rows", right.dot(up)),
        (
            "its depth row and its view direction (sine)",
            off_axis.length() / depth_row.length(),
        ),
    ];
    for (what, cosine) in cosines {
        // A NaN (a zero row) fails too.
        if cosine.is_nan() || cosine.abs() > CAMERA_TOLERANCE {
            return Err(format!(
                "is not a symmetric perspective view: {what} are {cosine:e} from orthogonal, more \
                 than CAMERA_TOLERANCE = {CAMERA_TOLERANCE:e} (an off-centre or jittered \
                 projection, or a skewed one)"
            ));
        }
    }
    if right.cross(up).dot(forward) >= 0.0 {
        return Err(
            "is mirrored: its x, y and view axes form a left-handed frame in the scene's \
                    world — check conventions.world and conventions.ndc_y"
                .into(),
        );
    }
    let axes = DMat3::from_cols(r0.truncate(), r1.truncate(), r3.truncate()).transpose();
    let eye: DVec3 = -(axes.inverse() * DVec3::new(r0.w, r1.w, r3.w));
    if !eye.is_finite() {
        return Err("has no finite eye position".into());
    }
    let a = -depth_row.dot(forward);
    let b = r2.w + depth_row.dot(eye);
    let (near, far) = (b / (a - 1.0), b / (a + 1.0));
    // An infinite far plane (a = −1) comes back as a huge or negative far after rounding.
    if !(far > near && far / near <= MAX_DEPTH_RATIO) {
        return Err(format!(
            "is not a perspective projection with a finite far plane: near {near}, far {far} \
             (scene files' cameras reach at most MAX_DEPTH_RATIO = {MAX_DEPTH_RATIO:e} times \
             their near)"
        ));
    }
    let pose = ViewPose::look_to(eye, forward, up).map_err(|e| format!("has no pose: {e}"))?;
    let projection =
        Perspective::new(2.0 * (1.0 / cy).atan(), cy / cx, near, far).map_err(|e| {
            format!(
                "is not a perspective projection with a finite far plane (near {near}, far {far}): \
             {e}"
            )
        })?;
    Ok((pose, projection))
}
