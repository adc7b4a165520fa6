//! Integration tests of `shadowlab-shadow`, one binary (ripgrep's layout):
//! - `biases`: the light's direction and texel size a map gives at a point, the engines' receiver
//!   offsets measured against them, the bias spec's round trips and errors;
//! - `cascades`: engines' cascades: rotation-invariant fits, snapping in whole texels, selection
//!   by depth and by containment, blending, fades, every preset on every built-in scene;
//! - `closed_forms`: every technique's matrices, fitted to B = V, have the aliasing the closed forms
//!   of `shadowlab-params` predict (LiSPSM eq. 3, CAD eq. 12 / GMNPR eq. 2, the logarithmic
//!   constant, PSM shifted by Δ = LiSPSM with n = zn + Δ);
//! - `faces`: Lloyd et al.'s face partitioning tiles the view, covers what it serves, reduces to
//!   the plain map for the overhead light;
//! - `given`: maps given as depths make the maps they were rendered as; given depths are stored
//!   in their format; each partition is read with its own lookup;
//! - `golden`: every built-in scene × technique, hashed; identical on 1, 2 and 8 threads;
//! - `lookups`: rendered maps looked up: shadows where geometry puts them, biases against acne,
//!   filters only at edges, seeded disks;
//! - `limits`: γ → 0, γ = φ, γ = 90°, far/near up to 1e9: finite, continuous, tending to uniform;
//! - `omni`: point lights: the cube's faces serve what their maps hold, its near planes are the
//!   nearest geometry, techniques that cannot serve a light say so;
//! - `optimal`: the scene-optimized map's objective, gradient, descent and plans (CG06);
//! - `pictures`: the annotated eye and light views hold the raw ones pixel for pixel;
//! - `rules`: each warp-parameter choice computes what its source computes, in its units; stated
//!   λ, n and focus bodies are used as stated;
//! - `sdsm`: sample distribution maps hold every sample in the window that serves it, tightly;
//!   log splits have equal ratios; k-means is deterministic; empty partitions merge;
//! - `snap`: texel snapping translates the window onto the grid and nothing else;
//! - `support`: seeded configurations.

mod biases;
mod cascades;
mod closed_forms;
mod faces;
mod given;
mod golden;
mod limits;
mod lookups;
mod omni;
mod optimal;
mod pictures;
mod rules;
mod sdsm;
mod snap;
mod support;
