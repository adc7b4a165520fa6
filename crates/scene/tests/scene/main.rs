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
//! - `builtin_scenes`: the built-in scenes equal data/scenes on disk and are set up as documented.

mod builtin_scenes;
mod data_meshes;
mod mesh;
mod obj_errors;
mod obj_loading;
mod procedural;
mod properties;
mod scene_errors;
mod scene_files;
mod support;
