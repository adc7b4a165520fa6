//! Scene files: a TOML description of the meshes, the camera, the lights and the suggested shadow
//! settings of an experiment, read into a [`Scene`] ([`load_scene`], [`parse_scene`]).
//!
//! Only geometry is required: at least one `[[mesh]]`. Every other field has the default stated
//! below. Unknown fields are errors everywhere (a misspelt `fovy` is reported, not ignored), as
//! are fields that do not apply (a `radius` on a box, a `cone` on a directional light).
//!
//! ```toml
//! name = "example"                   # default: the file's stem
//!
//! [camera]
//! position = [0.0, 1.8, 0.0]
//! target = [0.0, 1.0, -50.0]         # or `direction = [...]`
//! fov = 60.0                         # vertical, degrees
//! near = 1.0
//! far = 400.0
//! image = [1024, 768]
//!
//! [[light]]
//! kind = "directional"
//! direction = [-1.0, -0.7, 0.0]      # the direction the light TRAVELS
//!
//! [[mesh]]
//! shape = "plane"
//! size = [1200.0, 1200.0]
//!
//! [[mesh]]
//! obj = "../meshes/bunny-small.obj"  # relative to this file's directory
//! name = "bunny"
//! scale = 0.15
//! rotate = [0.0, 90.0, 0.0]
//! translate = [1.5, 0.0, -6.0]
//!
//! [shadow]
//! technique = "lispsm"
//! ```
//!
//! # Conventions
//! World space is `shadowlab-hull`'s: right-handed, **y up**; a camera looks down its eye-space
//! −z. Angles in the file are in **degrees**; [`Scene`] holds radians. Vectors are arrays of
//! three numbers; integers are accepted where numbers are expected. `nan` and `inf`, which TOML
//! allows, are errors in every field.
//!
//! The defaults that depend on the scene use its bounds (the axis-aligned box of the merged
//! mesh, [`Scene::bounds`]): their centre c and R, half their diagonal (the radius of the
//! bounding sphere about c).
//!
//! # `[camera]` (optional table)
//! | field | meaning | default |
//! |---|---|---|
//! | `position` | the eye | c + d·(0, 1, 2)/√5 with d = R / sin φ, φ the smaller of the vertical and horizontal half fields of view: the bounding sphere just fits the view, seen from the +z side and 26.6° above |
//! | `target` | a point the camera looks at | c |
//! | `direction` | the view direction instead of `target` (give at most one of the two) | `target − position` |
//! | `up` | roughly up; orthogonalised against the view direction, must not be parallel to it | `[0, 1, 0]` |
//! | `fov` | the vertical field of view, degrees, in [0.001, 180) ([`MIN_ANGLE_DEGREES`]) | 60 |
//! | `near`, `far` | the clip distances along the view direction, 0 < near < far ≤ 10⁶·near ([`MAX_DEPTH_RATIO`]) | from the depths of the bounds' eight corners along the view direction: far = 1.01 × the farthest; near = the larger of 0.99 × the nearest and far / 1000 (or far / 1000 if that is not below a given far) |
//! | `image` | `[width, height]` in pixels, each in 1..=16384 ([`MAX_IMAGE_SIDE`]); the aspect ratio is width / height | `[1024, 768]` |
//!
//! # `[[light]]` (zero or more)
//! A scene without lights gets the **default sun**: a directional light travelling along
//! `(−1, −2, −1)` (from the upper right behind a camera on the +z side, 54.7° above the ground).
//!
//! `kind = "directional"` (the default):
//! | field | meaning | default |
//! |---|---|---|
//! | `direction` | the direction the light **travels**, from the light into the scene (engine convention) | `[-1, -2, -1]` |
//!
//! It takes none of the other fields (`position`, `cone`, `range`, …).
//!
//! **Direction convention.** The file gives the direction light *travels*, as engines and most
//! scene formats do. [`SceneLight::Directional`] holds hull's `to_light`, the unit vector from the
//! scene *toward* the light: `to_light = −normalize(direction)`. `direction = [0, -1, 0]` is a sun
//! straight overhead, whose `to_light` is `+y`.
//!
//! `kind = "spot"`:
//! | field | meaning | default |
//! |---|---|---|
//! | `position` | the light | c + d·(1, 2, 1)/√6 with d = R / sin(cone/2): where the default sun is, just far enough for the cone to hold the bounding sphere |
//! | `target` | a point the light shines at | c |
//! | `direction` | the direction it travels instead of `target` (at most one of the two) | `target − position` |
//! | `up` | orients the light's image; must not be parallel to the direction | +y, or −z if y is the direction's largest component (ties included) |
//! | `cone` | the full cone angle, degrees, in [0.001, 180) ([`MIN_ANGLE_DEGREES`]): the light frustum is the perspective frustum with this vertical field of view and aspect 1 | 60 |
//! | `near`, `far` | along the direction, as the camera's | as the camera's, from the spot's position and direction |
//!
//! A spot's reach is its `far`: it takes no `range` (an error naming `light[i].range`).
//!
//! `kind = "point"`: an omnidirectional light ([`SceneLight::Point`]), which lights every
//! direction, so it takes no `direction`, `target`, `up`, `cone`, `near` or `far` (each an
//! error naming the field, as a `cone` on a directional light is):
//! | field | meaning | default |
//! |---|---|---|
//! | `position` | the light; **required** (`light[i].position needs to be given …`) | |
//! | `range` | the distance beyond which it lights nothing, finite and > 0: `KHR_lights_punctual`'s `range` ("a distance cutoff at which the light's intensity may be considered to have reached zero"; engines must ignore the light beyond it) | unlimited |
//!
//! # `[[mesh]]` (one or more)
//! Each entry is an OBJ file, a glTF file or a procedural shape: give exactly one of `obj`,
//! `gltf` and `shape`.
//! | field | meaning | default |
//! |---|---|---|
//! | `obj` | an OBJ file (see [`crate::load_obj`]), relative to the scene file's directory | |
//! | `gltf` | a `.gltf` or `.glb` file (see [`crate::load_gltf`]), relative to the scene file's directory: the triangles of one of its scenes in the file's world space; its cameras and lights are not read (the scene file gives them) | |
//! | `gltf_scene` | with `gltf` only: the index of the glTF scene | the file's default scene, else scene 0 |
//! | `shape` | `"plane"`, `"box"`, `"sphere"`, `"cylinder"`, `"lattice"` or `"chessboard"`, with the parameters below | |
//! | `name` | the entry's group name in [`Scene::mesh`] | the OBJ or glTF file's stem, or the shape's name |
//! | `scale` | a number, or `[sx, sy, sz]`; each finite and non-zero (negative mirrors, and the winding is kept outward) | 1 |
//! | `rotate` | `[a, b, c]` degrees: about the world x axis by a, then y by b, then z by c, each counter-clockwise seen from the positive axis (right-hand rule); R = Rz(c)·Ry(b)·Rx(a), exact at multiples of 90° | `[0, 0, 0]` |
//! | `translate` | `[x, y, z]` | `[0, 0, 0]` |
//! | `copies` | how many copies of the entry, ≥ 1 | 1 |
//! | `step` | copy k (from 0) is moved by k·`step` after the transform; required if `copies` > 1, not allowed otherwise | |
//!
//! A point p of the shape or file becomes `translate + R·(scale ∘ p) + k·step`: scale first, then
//! rotate, then translate, then the copy's step. All of an entry's triangles (every copy, every
//! OBJ group or glTF node, a chess board's colours, a lattice's axes) form **one group** named
//! `name`, so group k of [`Scene::mesh`] is entry k. What a glTF file holds that shadowlab
//! cannot represent (lines, skins, …) is a warning: [`load_scene`] refuses it,
//! [`load_scene_with_warnings`] returns it.
//!
//! Shapes and their parameters ([`crate::procedural`]; all centred on the origin, flat ones in the
//! plane y = 0 facing +y, round ones with their axis along y; by default each fits about the unit
//! cube):
//! | shape | parameters (default) |
//! |---|---|
//! | `plane` | `size = [x, z]` (`[1, 1]`), `segments` ≥ 1 per side (1) |
//! | `box` | `size = [x, y, z]` (`[1, 1, 1]`) |
//! | `sphere` | `radius` (0.5), `segments` ≥ 3 (32), `rings` ≥ 2 (16) |
//! | `cylinder` | `radius` (0.5), `height` (1), `segments` ≥ 3 (32) |
//! | `lattice` | `cells = [nx, ny, nz]` (`[4, 4, 4]`), `spacing` (0.25), `thickness` < spacing (0.025): [`crate::procedural::bar_lattice`] |
//! | `chessboard` | `square_size` (0.125), `frame_width` ≥ 0 (0): [`crate::procedural::chess_board`] |
//!
//! Sizes, radii, heights, spacings and thicknesses must be finite and > 0. No mesh (one shape, or
//! an entry's copies together) may exceed [`crate::procedural::MAX_TRIANGLES`] triangles; every
//! transformed position must lie within ±[`crate::MAX_COORDINATE`], and the merged meshes must
//! span at least [`crate::MIN_EXTENT`] on some axis (a flat scene, a ground plane alone, is
//! fine).
//!
//! # `[shadow]` (optional table)
//! Suggestions for the shadow technique, passed on as [`ShadowSettings`]; the `shadow` crate and
//! the command-line tool check them (numbers must be finite here). All optional, each named as
//! its command-line flag is: `technique`, `parameter`, `focus`, `split_scheme`, `bias`, `filter`,
//! `optimal_readback` (`"WxH"`) (strings); `lambda`, `n`, `optimal_border` (numbers);
//! `resolution`, `splits`, `optimal_initial`, `optimal_iterations` (non-negative integers). At
//! most one of `parameter`, `lambda` and `n`.
//!
//! # Errors
//! Every error is a [`SceneFileError`] naming the file. A file that is not a regular file or is
//! larger than [`crate::MAX_SCENE_FILE_BYTES`] is refused before it is read
//! ([`SceneFileError::Read`]). TOML errors (syntax, unknown fields, wrong types, unknown shapes or
//! light kinds, numbers out of their integer type) are [`SceneFileError::Toml`] with toml's line
//! and column and the field there; values out of range or inconsistent are
//! [`SceneFileError::Field`] naming the field by its path (`camera.near`, `light[0].range`,
//! `mesh[2].size[1]`) and the allowed range, e.g.
//! `outdoor.toml: camera.near (5) must be below camera.far (1)`; meshes that cannot be built are
//! [`SceneFileError::Obj`], [`SceneFileError::Gltf`], [`SceneFileError::Shape`] or
//! [`SceneFileError::Mesh`], whose `source()` is the OBJ or glTF loader's, the shape's or the
//! mesh's error. Numbers in messages are
//! shortest round-trip, in scientific notation when very small or large (`1e-300`). Meshes are
//! built first (the other defaults need their bounds), then the camera, then the lights. Nothing
//! panics on any input.

mod checks;
mod error;
mod gltf_scene;
mod meshes;
mod raw;
mod toml_error;
mod view;

use std::path::Path;

use glam::DVec3;

use crate::gltf_import::{GltfWarning, is_gltf_path, load_gltf};
use crate::read::{MAX_SCENE_FILE_BYTES, read_bounded};
#[cfg(doc)]
use crate::scene::SceneLight;
use crate::scene::{Scene, ShadowSettings};

use self::checks::{Checker, field};
use self::raw::{RawScene, RawShadow};

pub use self::error::{SceneFileError, SceneFileProblem};

/// The camera's default vertical field of view, in degrees.
pub const DEFAULT_FOV_DEGREES: f64 = 60.0;

/// The camera's default image size, `[width, height]` in pixels.
pub const DEFAULT_IMAGE: [u32; 2] = [1024, 768];

/// The camera's default up vector.
pub const DEFAULT_UP: DVec3 = DVec3::Y;

/// The direction from the scene's centre toward the default camera position (normalised when
/// used): the +z side, 26.6° above the horizontal.
pub const DEFAULT_VIEW_FROM: DVec3 = DVec3::new(0.0, 1.0, 2.0);

/// The direction the default sun travels (normalised when used); `to_light` is its negation.
pub const DEFAULT_SUN_DIRECTION: DVec3 = DVec3::new(-1.0, -2.0, -1.0);

/// A spot light's default full cone angle, in degrees.
pub const DEFAULT_CONE_DEGREES: f64 = 60.0;

/// The relative margin by which default near and far planes clear the scene's bounds, so that a
/// renderer's rounding cannot clip the nearest or farthest geometry.
pub const DEPTH_MARGIN: f64 = 0.01;

/// The largest far/near ratio of default near planes: near is at least far / 1000.
pub const MAX_FAR_NEAR_RATIO: f64 = 1000.0;

pub use crate::limits::{MAX_DEPTH_RATIO, MAX_IMAGE_SIDE, MIN_ANGLE_DEGREES};

/// Where the `obj` and `gltf` paths of a scene's mesh entries are read from.
pub(crate) enum ObjFiles<'a> {
    /// From disk, relative to this directory (the scene file's).
    Relative(&'a Path),
    /// From text embedded in the binary, looked up by the `obj` string as written; `directory`
    /// only names them in errors.
    Embedded {
        directory: &'a Path,
        files: &'a [(&'a str, &'a str)],
    },
}

/// A scene with the warnings of the glTF files it was read from: what they hold that shadowlab
/// cannot represent and skipped (or replaced). A caller shows the warnings to the user.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The warnings, in the order they were met; empty for a scene without glTF files.
    pub warnings: Vec<GltfWarning>,
}

/// Reads a scene: a scene file (TOML; `obj` and `gltf` paths relative to its directory), or a
/// `.gltf` or `.glb` file as a scene by itself ([`load_gltf_scene`] of its default scene), by
/// the path's extension ([`crate::is_gltf_path`]).
///
/// It refuses what would be read with warnings ([`SceneFileError::Skipped`]), so that no caller
/// loses a mesh, light or camera without being told; [`load_scene_with_warnings`] reads such
/// scenes and returns the warnings.
///
/// # Errors
/// As [`load_scene_with_warnings`], and [`SceneFileError::Skipped`] listing the warnings.
pub fn load_scene(path: &Path) -> Result<Scene, SceneFileError> {
    strict(load_scene_with_warnings(path)?, path)
}

/// [`load_scene`], returning the warnings of its glTF files instead of refusing them.
///
/// # Errors
/// For a glTF path, as [`load_gltf_scene`]. For a scene file: [`SceneFileError::Read`] if the
/// file cannot be read, is not a regular file or is larger than [`MAX_SCENE_FILE_BYTES`];
/// [`SceneFileError::NotUtf8`]; otherwise as [`parse_scene`], but for
/// [`SceneFileError::Skipped`].
pub fn load_scene_with_warnings(path: &Path) -> Result<LoadedScene, SceneFileError> {
    if is_gltf_path(path) {
        return load_gltf_scene(path, None);
    }
    let bytes = read_bounded(
        path,
        MAX_SCENE_FILE_BYTES,
        "a scene file",
        "MAX_SCENE_FILE_BYTES",
    )
    .map_err(SceneFileError::Read)?;
    let text = std::str::from_utf8(&bytes).map_err(|error| SceneFileError::NotUtf8 {
        path: path.to_owned(),
        line: 1 + bytes[..error.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
    })?;
    let directory = path.parent().unwrap_or(Path::new(""));
    parse(text, path, &ObjFiles::Relative(directory))
}

/// Reads scene `scene` of a `.gltf` or `.glb` file (its default scene for `None`, see
/// [`crate::load_gltf`]) as a scene by itself:
/// - **mesh**: the scene's triangles in world space, one group per node and primitive;
/// - **camera**: the first perspective camera met (nodes depth first, in file order), its `yfov`,
///   `znear` and pose; its far distance is `zfar`, or for an infinite projection (no `zfar`)
///   the default of scene files (1.01 × the depth of the farthest corner of the scene's bounds);
///   a `zfar` beyond [`MAX_DEPTH_RATIO`] × `znear` is brought in to that default, with a
///   warning, if that suffices. The image is [`DEFAULT_IMAGE`], and its width / height is the
///   aspect (the file's `aspectRatio`, if it differs, is a warning). Without a perspective
///   camera: the default camera of scene files (framing the bounds);
/// - **lights**: the directional, point and spot lights; a point light's `range` is its range
///   (unlimited without one); a spot's far distance is its `range`, or the
///   scene files' default, and its near distance the scene files' default for that far distance
///   (`KHR_lights_punctual` gives none). Without lights: the default sun of scene files;
/// - **name**: the glTF scene's `name`, else the file's stem; **shadow** settings: none.
///
/// # Errors
/// [`SceneFileError::Gltf`] with the [`crate::GltfError`] of reading the file or of its camera
/// or lights; [`SceneFileError::Field`] or [`SceneFileError::Hull`] if the default camera or
/// sun cannot be placed (bounds near the f64 range).
pub fn load_gltf_scene(path: &Path, scene: Option<usize>) -> Result<LoadedScene, SceneFileError> {
    let import = load_gltf(path, scene).map_err(|error| SceneFileError::Gltf {
        path: path.to_owned(),
        field: None,
        source: Box::new(error),
    })?;
    gltf_scene::scene(import, path)
}

/// The scene of `loaded` if it has no warnings, else [`SceneFileError::Skipped`].
pub(crate) fn strict(loaded: LoadedScene, path: &Path) -> Result<Scene, SceneFileError> {
    if loaded.warnings.is_empty() {
        Ok(loaded.scene)
    } else {
        Err(SceneFileError::Skipped {
            path: path.to_owned(),
            warnings: loaded.warnings,
        })
    }
}

/// Reads scene-file text as if it were the file `path`: errors name `path`, the scene's default
/// name is its stem, and `obj` paths are relative to its directory (the text is not read from
/// `path`).
///
/// # Errors
/// - [`SceneFileError::Toml`]: not TOML, or not the format (unknown field, wrong type, unknown
///   `shape` or `kind`), with the line, column and field;
/// - [`SceneFileError::Field`]: a value out of range or inconsistent, naming the field (see the
///   [module documentation](self) for every rule);
/// - [`SceneFileError::Obj`], [`SceneFileError::Shape`], [`SceneFileError::Mesh`]: an OBJ file
///   that is missing or malformed, a shape with too many triangles or inconsistent parameters, a
///   transform that overflows;
/// - [`SceneFileError::Hull`]: a camera or light that overflows `shadowlab-hull`'s checks;
/// - [`SceneFileError::Gltf`]: a `gltf` mesh entry's file that is missing or malformed;
/// - [`SceneFileError::Skipped`]: a `gltf` mesh entry's file holds parts that would be skipped
///   (as [`load_scene`]; [`load_scene_with_warnings`] accepts them).
pub fn parse_scene(text: &str, path: &Path) -> Result<Scene, SceneFileError> {
    let directory = path.parent().unwrap_or(Path::new(""));
    strict(parse(text, path, &ObjFiles::Relative(directory))?, path)
}

/// Scene-file text as a scene, with the OBJ and glTF files read from `obj_files`.
pub(crate) fn parse(
    text: &str,
    path: &Path,
    obj_files: &ObjFiles<'_>,
) -> Result<LoadedScene, SceneFileError> {
    let raw: RawScene =
        toml::from_str(text).map_err(|error| toml_error::scene_toml_error(path, text, &error))?;
    let checker = Checker::new(path);
    let mut warnings = Vec::new();
    let mesh = meshes::scene_mesh(checker, &raw.mesh, obj_files, &mut warnings)?;
    let bounds = mesh.bounds();
    let camera = view::camera(checker, &raw.camera, &bounds)?;
    let lights = view::lights_or_default_sun(checker, &raw.light, |index, light| {
        view::light(checker, index, light, &bounds)
    })?;
    Ok(LoadedScene {
        scene: Scene {
            name: view::scene_name(raw.name, path),
            camera,
            lights,
            mesh,
            shadow: shadow_settings(checker, raw.shadow)?,
        },
        warnings,
    })
}

/// The `[shadow]` table as it is, but for its numbers, which must be finite.
fn shadow_settings(checker: Checker<'_>, raw: RawShadow) -> Result<ShadowSettings, SceneFileError> {
    let finite = |name: &str, value: Option<f64>| {
        value
            .map(|v| checker.finite(&field("shadow", name), v))
            .transpose()
    };
    Ok(ShadowSettings {
        lambda: finite("lambda", raw.lambda)?,
        n: finite("n", raw.n)?,
        optimal_border: finite("optimal_border", raw.optimal_border)?,
        technique: raw.technique,
        parameter: raw.parameter,
        resolution: raw.resolution,
        partitions: raw.partitions,
        split_scheme: raw.split_scheme,
        bias: raw.bias,
        filter: raw.filter,
        focus: raw.focus,
        optimal_readback: raw.optimal_readback,
        optimal_initial: raw.optimal_initial,
        optimal_iterations: raw.optimal_iterations,
    })
}
