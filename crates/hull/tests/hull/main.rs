//! Integration tests of `shadowlab-hull`, one binary (ripgrep's layout). Modules:
//! - `support`: seeded proptest configuration, input strategies, and membership tests written from
//!   the definitions (camera parameters, box bounds), independent of the crate's planes;
//! - `frusta`: frusta from parameters and from matrices in every NDC convention agree;
//! - `hull_properties`: 3-D hulls and clipping over random inputs;
//! - `focus_properties`: B, V ∩ S and the PSM near body against their definitions;
//! - `invariance`: translations and rotations move outputs alike (exactly where f64 allows);
//! - `light_space`: LiSPSM axes, γ, and the continuity of the near-parallel fallback;
//! - `planar`: 2-D hulls and minimum-area rectangles against brute force;
//! - `primitives`: planes, boxes, rays, segments, measures and lights in closed form;
//! - `extremes`: each extreme configuration of the issue as its own test;
//! - `bad_input`: every rejected input gives a clear error naming the parameter.

mod bad_input;
mod extremes;
mod focus_properties;
mod frusta;
mod hull_properties;
mod invariance;
mod light_space;
mod planar;
mod primitives;
mod support;
