//! Integration tests of the rasterizer, one binary (ripgrep's layout):
//!
//! * `coverage` — watertightness over random meshes, the fill rule on hand-built cases, exact
//!   translation by whole pixels;
//! * `clipping` — triangles crossing the near and far planes, behind the eye, and enormous ones,
//!   against an exact per-pixel reference in i128;
//! * `depth` — monotone, exact at vertices, every format, the depth pair and the eye resolve;
//! * `exact_depth` — depth at every covered pixel against the exact plane through the clip-space
//!   vertices, in every format, on tilted planes and ground planes;
//! * `determinism` — identical bytes for 1, 2 and 8 threads and across runs;
//! * `golden` — exact images of small scenes (`UPDATE_GOLDEN=1` rewrites them);
//! * `errors` — bad input is an error naming the triangle, vertex or size.

mod clipping;
mod coverage;
mod depth;
mod determinism;
mod errors;
mod exact_depth;
mod golden;
mod support;
