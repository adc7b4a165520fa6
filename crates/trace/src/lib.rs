//! # shadowlab-trace: exact ray casting against triangle meshes (work in progress)
