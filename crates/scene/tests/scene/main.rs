//! Integration tests of `shadowlab-scene`, one binary (ripgrep's layout). Modules:
//! - `support`: the seeded proptest configuration, OBJ files in a temporary directory, and mesh
//!   checks written from their definitions (closed and consistently oriented by edge counting);
//! - `mesh`: construction, validation, normals, bounds, groups, transforms and merging;
//! - `obj_loading`: well-formed OBJ files of every supported shape load as written;
//! - `obj_errors`: every class of malformed file is an error naming the file and the line;
//! - `procedural`: each shape is closed, outward, of the analytic volume and area, and bounded;
//! - `properties`: property tests over random meshes, transforms, shape parameters, OBJ text and
//!   mangled scene files;
//! - `data_meshes`: the meshes committed in data/meshes load with their documented counts;
//! - `scene_files`: scene files load with the documented defaults, transforms, lights and groups;
//! - `scene_errors`: every class of bad scene file is an error naming the file and the field;
//! - `builtin_scenes`: the built-in scenes equal data/scenes on disk and are set up as documented;
//! - `gltf_samples`: the glTF 2.0 files of data/gltf/assimp (every malformed one of the package is
//!   an error naming the file and the problem, unsupported parts are warnings);
//! - `gltf_files`: glTF files written by the tests: transforms, winding, normals, sparse
//!   accessors, buffers, scenes, limits, cameras and lights, glTF scenes and scene-file entries;
//! - `export_roundtrip`: exported scenes read back (glTF: the f32 rounding, then a fixed point;
//!   OBJ: bit for bit).

mod builtin_scenes;
mod data_meshes;
mod export_roundtrip;
mod gltf_files;
mod gltf_samples;
mod mesh;
mod obj_errors;
mod obj_loading;
mod procedural;
mod properties;
mod scene_errors;
mod scene_files;
mod support;
