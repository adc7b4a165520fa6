//! # shadowlab-scene: triangle meshes for shadow-map experiments
//!
//! A [`Mesh`] is a validated triangle mesh in f64: finite positions, unit per-vertex normals,
//! triangles counter-clockwise seen from the side the normals face, and a group (part) id per
//! triangle. Meshes come from OBJ files ([`load_obj`], through tobj, with errors that name the file
//! and line), from glTF 2.0 files ([`load_gltf`]: one scene's triangles in world space, with its
//! cameras and lights; [`load_gltf_scene`] makes a [`Scene`] of it) or from [`procedural`] shapes
//! (plane, box, sphere, cylinder, a lattice of thin bars, a chess board), and can be moved
//! ([`Mesh::transformed`]) and combined ([`Mesh::merged`]). A [`Scene`] is written for other
//! renderers by [`export_glb`], [`export_gltf`] (glTF stores f32) and [`export_obj`] (every f64).
//!
//! ```
//! use glam::{DAffine3, DVec3};
//! use shadowlab_scene::{Mesh, procedural};
//!
//! let ground = procedural::plane(20.0, 20.0, 1)?;
//! let ball = procedural::sphere(1.0, 32, 16)?
//!     .transformed(&DAffine3::from_translation(DVec3::new(0.0, 1.5, 0.0)));
//! let scene = Mesh::merged(&[ground, ball]);
//! assert_eq!(scene.triangle_count(), 2 + 2 * 32 * 15);
//! assert_eq!(scene.group_names(), ["plane", "sphere"]);
//! assert!(scene.bounds().contains(DVec3::new(0.0, 2.5, 0.0)));
//! # Ok::<(), shadowlab_scene::ShapeError>(())
//! ```
//!
//! ```
//! use shadowlab_scene::{SceneLight, builtin_scene, DEFAULT_SCENE};
//!
//! let scene = builtin_scene(DEFAULT_SCENE)?;
//! assert_eq!(scene.camera.projection.far(), 400.0);
//! assert!(matches!(scene.lights[0], SceneLight::Directional { .. }));
//! assert!(scene.bounds().contains(scene.camera.pose.eye()));
//! # Ok::<(), shadowlab_scene::BuiltinSceneError>(())
//! ```
//!
//! # Conventions
//! - **Space:** right-handed, **y up** (as in `shadowlab-hull`); procedural shapes are centred on
//!   the origin. Units are whatever the caller's are.
//! - **Winding:** triangles are counter-clockwise seen from the side their normals face; for closed
//!   procedural shapes that is outside, and their signed volume ([`Mesh::signed_volume`]) is
//!   positive.
//! - **Normals** are unit vectors per vertex. [`Mesh::new`] computes them area-weighted; a vertex
//!   without a direction (only zero-area triangles, or none) gets [`FALLBACK_NORMAL`], +z.
//! - **Degenerate triangles** (zero area) are allowed: rasterizers must cope. NaN or infinite
//!   positions and out-of-range indices are errors.
//! - **Groups:** every triangle has a group id indexing [`Mesh::group_names`]; [`Mesh::merged`]
//!   keeps the parts apart by offsetting ids.
//! - **Lights:** a scene file gives the direction a directional light **travels**;
//!   [`SceneLight::Directional`] holds hull's `to_light`, its negation, normalised. Scene-file
//!   angles are degrees; [`Scene`] holds radians.
//! - **Errors** are one type per module, each naming what was wrong and where, and composed by
//!   `source()`: [`MeshError`] (vertex, triangle, group), [`ShapeError`] (parameter),
//!   [`ReadError`] (a file missing, special or too large: [`MAX_OBJ_BYTES`],
//!   [`MAX_SCENE_FILE_BYTES`]), [`ObjError`] (file and line), [`SceneFileError`] (file and field,
//!   its source the OBJ, glTF, shape or mesh error behind it), [`GltfError`] (file and glTF
//!   object) and [`BuiltinSceneError`]; what a glTF file holds that shadowlab cannot represent is
//!   a [`GltfWarning`] ([`load_scene_with_warnings`]). Nothing panics
//!   on bad input except [`Mesh::transformed`] and [`Mesh::merged`], the documented panicking
//!   forms of [`Mesh::try_transformed`] and
//!   [`Mesh::try_merged`], and [`SceneLight::light`] on a hand-built zero or non-finite
//!   `to_light` or non-finite point-light `position`.
//! - **Determinism:** no randomness and no hash-order dependence; the same input gives
//!   bit-identical meshes.

#![deny(missing_docs)]

pub mod benchmark;
mod bounds;
mod builtin;
pub mod export;
pub mod gltf_import;
mod limits;
mod mesh;
mod normals;
mod number;
mod obj;
pub mod procedural;
mod read;
mod scene;
pub mod scene_file;

pub use bounds::Bounds;
pub use builtin::{
    BUILTIN_SCENES, BuiltinSceneError, DEFAULT_SCENE, builtin_scene, builtin_scene_text,
};
pub use export::{ExportError, export_glb, export_gltf, export_obj};
pub use gltf_import::{
    GltfCamera, GltfError, GltfImport, GltfLight, GltfLightKind, GltfObject, GltfObjectKind,
    GltfProblem, GltfSkipped, GltfWarning, MAX_GLTF_BYTES, MAX_GLTF_TRIANGLES, is_gltf_path,
    load_gltf, parse_gltf,
};
pub use mesh::{DEFAULT_GROUP_NAME, MAX_COORDINATE, MIN_EXTENT, Mesh, MeshError};
pub use normals::FALLBACK_NORMAL;
pub use obj::{ObjElement, ObjError, ObjProblem, load_obj, parse_obj};
pub use procedural::ShapeError;
pub use read::{MAX_OBJ_BYTES, MAX_SCENE_FILE_BYTES, ReadError, read_bounded};
pub use scene::{Camera, Scene, SceneLight, ShadowSettings};
pub use scene_file::{
    LoadedScene, SceneFileError, SceneFileProblem, load_gltf_scene, load_scene,
    load_scene_with_warnings, parse_scene,
};
