//! The built-in scenes: the files of `data/scenes/` and the meshes they use, embedded in the
//! binary, so that they load without the repository and exactly as from disk.

use std::fmt;
use std::path::Path;

use crate::scene::Scene;
use crate::scene_file::{self, ObjFiles, SceneFileError};

/// The names of the built-in scenes (`data/scenes/<name>.toml`; see `data/scenes/README.md`):
/// - `outdoor`: a ground with rows of poles and boxes out to the far plane of 400 and the bunny
///   near the camera, lit by a sun from the side (LiSPSM's set-up: fov 60°, near 1, far 400);
/// - `dueling-frusta`: a low sun in front of the camera, shining toward it, so that shadows
///   stretch toward the viewer (Chong and Gortler's hard case; 18° from anti-parallel);
/// - `cad-lattice`: thin bars and lattices from near 1 to far 800 (the CAD survey's and GMNPR's
///   set-up);
/// - `chess-spot`: a chess board with simple pieces under a spot light (PSM's figure 1);
/// - `bunny`: the bunny on a plane, lit from above at an angle;
/// - `room-point`: a closed room with furniture and thin objects (legs, spindles, shelves, slats,
///   a pole) around a point light that hangs below the ceiling, with the camera inside: shadows
///   in every direction, for cube maps, dual-paraboloid maps and PSM with a point light;
/// - `chess-point`: `chess-spot`'s board, pieces and camera under a point light off-centre above
///   the pieces instead of the spot.
pub const BUILTIN_SCENES: [&str; 7] = [
    "outdoor",
    "dueling-frusta",
    "cad-lattice",
    "chess-spot",
    "bunny",
    "room-point",
    "chess-point",
];

/// The built-in scene used when none is named.
pub const DEFAULT_SCENE: &str = "outdoor";

/// The built-in scene files, by name, in the order of [`BUILTIN_SCENES`].
const SCENE_FILES: [(&str, &str); 7] = [
    ("outdoor", include_str!("../../../data/scenes/outdoor.toml")),
    (
        "dueling-frusta",
        include_str!("../../../data/scenes/dueling-frusta.toml"),
    ),
    (
        "cad-lattice",
        include_str!("../../../data/scenes/cad-lattice.toml"),
    ),
    (
        "chess-spot",
        include_str!("../../../data/scenes/chess-spot.toml"),
    ),
    ("bunny", include_str!("../../../data/scenes/bunny.toml")),
    (
        "room-point",
        include_str!("../../../data/scenes/room-point.toml"),
    ),
    (
        "chess-point",
        include_str!("../../../data/scenes/chess-point.toml"),
    ),
];

/// The OBJ files the built-in scenes use, by their `obj` path as written in the scene files.
/// Only public-domain meshes are embedded (`bunny-small.obj`; see `data/meshes/README.md`).
const OBJ_FILES: [(&str, &str); 1] = [(
    "../meshes/bunny-small.obj",
    include_str!("../../../data/meshes/bunny-small.obj"),
)];

/// The directory that built-in scenes name in errors and resolve `obj` paths against.
const SCENE_DIRECTORY: &str = "data/scenes";

/// The text of a built-in scene file (`data/scenes/<name>.toml`), e.g. to start a scene of one's
/// own from; `None` for an unknown name.
#[must_use]
pub fn builtin_scene_text(name: &str) -> Option<&'static str> {
    SCENE_FILES
        .iter()
        .find(|(known, _)| *known == name)
        .map(|(_, text)| *text)
}

/// A built-in scene, read from the text embedded in the binary; it equals
/// [`crate::load_scene`] of `data/scenes/<name>.toml`. Errors would name
/// `data/scenes/<name>.toml`, but the built-ins are tested to load.
///
/// # Errors
/// [`BuiltinSceneError::Unknown`] for a name not in [`BUILTIN_SCENES`]; its message lists them.
pub fn builtin_scene(name: &str) -> Result<Scene, BuiltinSceneError> {
    let text = builtin_scene_text(name).ok_or_else(|| BuiltinSceneError::Unknown {
        name: name.to_owned(),
    })?;
    let directory = Path::new(SCENE_DIRECTORY);
    let path = directory.join(format!("{name}.toml"));
    scene_file::parse(
        text,
        &path,
        &ObjFiles::Embedded {
            directory,
            files: &OBJ_FILES,
        },
    )
    .and_then(|loaded| scene_file::strict(loaded, &path))
    .map_err(|error| BuiltinSceneError::File(Box::new(error)))
}

/// Why [`builtin_scene`] gave no scene.
#[non_exhaustive]
#[derive(Debug)]
pub enum BuiltinSceneError {
    /// A name not in [`BUILTIN_SCENES`].
    Unknown {
        /// The name asked for.
        name: String,
    },
    /// The embedded file did not load: a bug, as the built-ins are tested to load.
    File(Box<SceneFileError>),
}

impl fmt::Display for BuiltinSceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Unknown { name } => write!(
                f,
                "there is no built-in scene `{name}`; the built-in scenes are {}",
                BUILTIN_SCENES.join(", ")
            ),
            Self::File(error) => write!(f, "{error}"),
        }
    }
}

impl std::error::Error for BuiltinSceneError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Unknown { .. } => None,
            Self::File(error) => Some(error.as_ref()),
        }
    }
}
