//! glTF 2.0 import: the triangle meshes of one scene of a `.gltf` or `.glb` file in world space,
//! its perspective cameras and its `KHR_lights_punctual` directional, point and spot lights
//! ([`load_gltf`], [`parse_gltf`]).
//!
//! The JSON is parsed and checked against the schema by the `gltf` crate (`gltf::json` and its
//! validation); the GLB container (glTF 2.0 §4), buffers (§3.6.1), accessors (§3.6.2), node
//! transforms (§3.5) and primitives (§3.7.2) are read here, every byte range checked, so that
//! any malformed file is a [`GltfError`] naming the file and the object (node, mesh, primitive,
//! accessor, buffer, camera or light, with its index and name), never a panic.
//!
//! # What is read
//! - **The scene**: the one asked for, else the file's `scene`, else scene 0 (glTF 2.0 §3.5.1
//!   leaves the choice to the loader when `scene` is undefined); a file without scenes is an
//!   error. Every node reachable from the scene's root nodes is visited depth first, parents
//!   before children, in the order of `scene.nodes` and `children`; a node reached twice (a
//!   cycle, or two parents) is an error (§3.5.2).
//! - **Transforms**: a node's `matrix` (which must be affine) or its `translation`, `rotation`
//!   and `scale` (the quaternion normalised), composed from the root down in f64: the f32 values
//!   of the file are exact in f64, and so every world position is the f64 product, not an f32
//!   one.
//! - **Triangles**: primitives of mode `TRIANGLES`, `TRIANGLE_STRIP` and `TRIANGLE_FAN` (strips
//!   and fans converted as §3.7.2.1 defines them), indexed by `UNSIGNED_BYTE`, `UNSIGNED_SHORT`
//!   or `UNSIGNED_INT` or not indexed; sparse accessors are applied. A node whose world transform
//!   mirrors (negative determinant) has its triangles' winding reversed, so that front faces stay
//!   counter-clockwise (§3.7.2.1). A mesh used by several nodes is drawn once per node.
//! - **Normals**: the primitive's `NORMAL`, moved by the inverse transpose of the node's
//!   transform and normalised; where it is absent, zero or not finite, area-weighted normals of
//!   the primitive's world triangles, as [`crate::Mesh::new`] computes them (zero or non-finite
//!   ones are a warning).
//! - **Groups**: one per drawn primitive, in visiting order, named by the node (its name, else its
//!   mesh's name, else `node N`), with `/k` for primitive k of a mesh of several primitives.
//! - **Cameras**: perspective cameras (§3.10), at their node's origin looking down its −z with
//!   its +y up, in visiting order ([`GltfCamera`]).
//! - **Lights**: `KHR_lights_punctual` directional lights (travelling along the node's −z),
//!   point lights (at the node's origin in world space, its rotation and scale ignored but for
//!   their effect on that position) and spot lights (at the node's origin, shining down its −z;
//!   the cone is twice `outerConeAngle`) ([`GltfLight`]). A point or spot light's `range` is
//!   read as it is: `KHR_lights_punctual` leaves light properties unaffected by node transforms
//!   (no scaling), and an undefined range is infinite. Colour, intensity and `innerConeAngle`
//!   are not used: shadowlab measures shadows, not shading.
//! - **Not read**: materials, textures, images (never opened), and any buffer no drawn primitive
//!   uses. Such parts are checked only by the schema validation.
//!
//! # What is skipped, with a warning
//! Each is a [`GltfWarning`] in [`GltfImport::warnings`], naming the file and the objects:
//! points and lines; spot lights whose cone is 180° or wider; orthographic
//! cameras; morph targets (the base shape is drawn); skins (the mesh is drawn as stored, placed
//! by its node); animations (nodes are placed by their transforms as stored); meshes of nodes
//! with a singular world transform (a zero scale: no area); zero or non-finite normals
//! (replaced).
//!
//! # What is an error
//! Besides a malformed file: a required extension other than `KHR_lights_punctual` (e.g.
//! `KHR_draco_mesh_compression`, `EXT_meshopt_compression`, `KHR_mesh_quantization`, glTF 2.0
//! §3.12); a `POSITION` with a NaN or infinite value; indices out of range; a vertex count the mode
//! cannot use; camera and light values out of range (`yfov` in [0.001°, 180°), `znear` > 0,
//! `zfar` beyond `znear`, `aspectRatio`, `range` and `outerConeAngle` > 0); a scene without
//! triangles; world positions
//! beyond ±[`crate::MAX_COORDINATE`] or spanning less than [`crate::MIN_EXTENT`]; more than
//! [`MAX_GLTF_TRIANGLES`].
//!
//! Two schema rules are relaxed: `POSITION` accessors without `min` and `max` are read (the bounds
//! are computed from the data), and alignment rules are not checked (reading does not depend on
//! them).
//!
//! # Limits
//! The `.gltf` or `.glb` file and each buffer file must be regular files of at most
//! [`MAX_GLTF_BYTES`], and the buffers read must together declare at most [`MAX_GLTF_BYTES`]
//! (checked before any is read). URIs are `data:` URIs (base64) or paths relative to the glTF
//! file (percent-decoded); other schemes and absolute paths are refused.

mod accessor;
mod buffers;
mod container;
mod error;
mod nodes;
mod primitive;

use std::path::Path;

use glam::DVec3;
use shadowlab_hull::ViewPose;

use crate::mesh::{MIN_EXTENT, Mesh};
use crate::read::read_bounded;

use self::accessor::Accessors;
use self::primitive::Drawn;

pub use self::error::{
    GltfError, GltfObject, GltfObjectKind, GltfProblem, GltfSkipped, GltfWarning,
};

/// The largest `.gltf` or `.glb` file read, and the most bytes its buffers may declare together:
/// 1 GiB, as [`crate::MAX_OBJ_BYTES`] for OBJ files (binary geometry is some three times denser
/// than OBJ text).
pub const MAX_GLTF_BYTES: u64 = 1 << 30;

/// The most triangles a glTF scene may have, with every mesh drawn once per node that uses it:
/// 2²⁵ = 33 554 432 (about 40 times the Stanford dragon). Instancing lets a small file describe
/// any number of triangles; this bound stops it before memory runs out. The scene may have at most
/// three times as many vertices, and no accessor read more elements than that.
pub const MAX_GLTF_TRIANGLES: u64 = 1 << 25;

/// A perspective camera of a glTF scene (glTF 2.0 §3.10), placed by its node.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfCamera {
    /// The node that places it.
    pub node: GltfObject,
    /// The camera object.
    pub camera: GltfObject,
    /// At the node's origin, looking down the node's −z, with the node's +y as up.
    pub pose: ViewPose,
    /// `yfov`: the vertical field of view, radians, in [0.001°, 180°).
    pub fov_y: f64,
    /// `znear`, > 0.
    pub near: f64,
    /// `zfar`; `None` for an infinite projection (§3.10.3).
    pub far: Option<f64>,
    /// `aspectRatio`, if the file gives one (> 0).
    pub aspect_ratio: Option<f64>,
    /// The image size in pixels, `[width, height]`, if the camera's `extras` record one as
    /// shadowlab's export writes it: `{"shadowlab": {"image": [W, H]}}` (other extras are the
    /// application's and ignored; the range is checked where the scene is assembled).
    pub image: Option<[u32; 2]>,
}

/// A `KHR_lights_punctual` light of a glTF scene that shadowlab represents, placed by its node.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfLight {
    /// The node that places it.
    pub node: GltfObject,
    /// The light object.
    pub light: GltfObject,
    /// What kind of light, where and which way.
    pub kind: GltfLightKind,
}

/// The kinds of [`GltfLight`].
#[derive(Clone, Debug, PartialEq)]
pub enum GltfLightKind {
    /// A directional light: it travels along its node's −z.
    Directional {
        /// The unit vector toward the light (hull's convention): the node's +z in world space.
        to_light: DVec3,
    },
    /// A point light at its node's origin, lighting every direction.
    Point {
        /// The node's origin in world space: its world transform's translation, composed in f64
        /// from the root down.
        position: DVec3,
        /// `range`, beyond which it gives no light (`KHR_lights_punctual`: "a distance cutoff at
        /// which the light's intensity may be considered to have reached zero", > 0, unaffected
        /// by the node's scale); `None` for unbounded.
        range: Option<f64>,
    },
    /// A spot light at its node's origin, shining down the node's −z.
    Spot {
        /// The pose: position, direction of travel, and the node's +y as up.
        pose: ViewPose,
        /// The full cone angle, twice `outerConeAngle`, radians, below π.
        cone: f64,
        /// `range`, beyond which it gives no light; `None` for unbounded.
        range: Option<f64>,
    },
}

/// One scene of a glTF file: its triangles in world space, cameras, lights and what was skipped.
///
/// # Guarantees
/// `mesh` spans at least [`crate::MIN_EXTENT`]; it has one group per drawn primitive (see the
/// [module documentation](self)).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfImport {
    /// The index of the scene read.
    pub scene: usize,
    /// That scene's `name`, if it has one.
    pub scene_name: Option<String>,
    /// Every drawn primitive, in world space, merged.
    pub mesh: Mesh,
    /// The perspective cameras, in visiting order.
    pub cameras: Vec<GltfCamera>,
    /// The directional, point and spot lights, in visiting order.
    pub lights: Vec<GltfLight>,
    /// What was skipped or replaced, in the order it was met.
    pub warnings: Vec<GltfWarning>,
}

/// Whether `path` names a glTF file by its extension: `.gltf` or `.glb`, in any case.
#[must_use]
pub fn is_gltf_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Loads scene `scene` of a `.gltf` or `.glb` file (the default scene for `None`; see the
/// [module documentation](self)); external buffers are read relative to the file's directory.
///
/// # Errors
/// [`GltfError::Read`] if the file cannot be read, is not a regular file or is larger than
/// [`MAX_GLTF_BYTES`]; otherwise as [`parse_gltf`].
pub fn load_gltf(path: &Path, scene: Option<usize>) -> Result<GltfImport, GltfError> {
    let bytes = read_bounded(path, MAX_GLTF_BYTES, "a glTF file", "MAX_GLTF_BYTES")
        .map_err(GltfError::Read)?;
    parse_gltf(&bytes, path, scene)
}

/// Reads the contents of a `.gltf` or `.glb` file as [`load_gltf`] reads the file `path`: errors
/// name `path`, and external buffers are read relative to its directory (`bytes` is not read
/// from `path`).
///
/// # Errors
/// - [`GltfError::Format`]: not GLB or JSON, not the glTF 2.0 schema, or another version;
/// - [`GltfError::UnsupportedExtensions`], [`GltfError::Invalid`] (schema validation);
/// - [`GltfError::NoScene`], [`GltfError::NoTriangles`], [`GltfError::DegenerateExtent`],
///   [`GltfError::TooLarge`];
/// - [`GltfError::Object`] naming the object and the [`GltfProblem`]: buffers that cannot be had
///   or are too short, byte ranges out of bounds, accessors of the wrong type, bad indices,
///   non-finite positions, bad transforms, camera and light values out of range.
pub fn parse_gltf(
    bytes: &[u8],
    path: &Path,
    scene: Option<usize>,
) -> Result<GltfImport, GltfError> {
    let document = container::parse(bytes, path)?;
    let root = &document.root;
    let scene_index = match scene.or(root.scene.map(|s| s.value())) {
        Some(index) => index,
        None if !root.scenes.is_empty() => 0,
        None => {
            return Err(GltfError::NoScene {
                path: path.to_owned(),
                asked: None,
                scenes: 0,
            });
        }
    };
    let Some(json_scene) = root.scenes.get(scene_index) else {
        return Err(GltfError::NoScene {
            path: path.to_owned(),
            asked: Some(scene_index),
            scenes: root.scenes.len(),
        });
    };
    let mut warnings = Vec::new();
    if !root.animations.is_empty() {
        warnings.push(GltfWarning {
            path: path.to_owned(),
            objects: Vec::new(),
            skipped: GltfSkipped::Animations {
                count: root.animations.len(),
            },
        });
    }
    let placed = nodes::walk(root, json_scene, path)?;
    let mut cameras = Vec::new();
    let mut lights = Vec::new();
    let mut drawn: Vec<Drawn<'_>> = Vec::new();
    for node in &placed {
        cameras.extend(nodes::camera(root, node, path, &mut warnings)?);
        lights.extend(nodes::light(root, node, path, &mut warnings)?);
        drawn.extend(primitive::drawn_primitives(root, node, path, &mut warnings));
    }
    if drawn.is_empty() {
        return Err(GltfError::NoTriangles {
            path: path.to_owned(),
            scene: scene_index,
            skipped: warnings,
        });
    }
    let mesh = meshes(root, document.bin, &drawn, path, &mut warnings)?;
    Ok(GltfImport {
        scene: scene_index,
        scene_name: json_scene.name.clone(),
        mesh,
        cameras,
        lights,
        warnings,
    })
}

/// The drawn primitives as one mesh: their buffers loaded, their sizes checked against
/// [`MAX_GLTF_TRIANGLES`] before any is read, then each built and all merged.
fn meshes(
    root: &gltf::json::Root,
    bin: Option<&[u8]>,
    drawn: &[Drawn<'_>],
    path: &Path,
    warnings: &mut Vec<GltfWarning>,
) -> Result<Mesh, GltfError> {
    let probe = buffers::BufferData::new();
    let unloaded = Accessors {
        root,
        buffers: &probe,
        path,
    };
    let mut needed = vec![false; root.buffers.len()];
    for primitive in drawn {
        for accessor in primitive::accessors_of(root, primitive)
            .into_iter()
            .flatten()
        {
            for buffer in unloaded.buffers_of(accessor) {
                if let Some(flag) = needed.get_mut(buffer) {
                    *flag = true;
                }
            }
        }
    }
    let (mut triangles, mut vertices) = (0_u64, 0_u64);
    for primitive in drawn {
        let (more_triangles, more_vertices) =
            primitive::planned_size(root, &unloaded, primitive, path)?;
        triangles += more_triangles as u64;
        vertices += more_vertices as u64;
        for (what, count, limit) in [
            ("triangles", triangles, MAX_GLTF_TRIANGLES),
            ("vertices", vertices, 3 * MAX_GLTF_TRIANGLES),
        ] {
            if count > limit {
                return Err(GltfError::TooLarge {
                    path: path.to_owned(),
                    what,
                    count,
                    limit,
                });
            }
        }
    }
    let data = buffers::load(root, bin, &needed, path)?;
    let accessors = Accessors {
        root,
        buffers: &data,
        path,
    };
    let parts = drawn
        .iter()
        .map(|primitive| primitive::build(root, &accessors, primitive, path, warnings))
        .collect::<Result<Vec<_>, _>>()?;
    let mesh = Mesh::try_merged(&parts).map_err(|error| GltfError::Object {
        path: path.to_owned(),
        objects: Vec::new(),
        problem: GltfProblem::Mesh(error),
    })?;
    let extent = mesh.bounds().size().max_element();
    if extent < MIN_EXTENT {
        return Err(GltfError::DegenerateExtent {
            path: path.to_owned(),
            extent,
        });
    }
    Ok(mesh)
}
