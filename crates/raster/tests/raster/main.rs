//! Integration tests of the rasterizer, one binary (ripgrep's layout):
//!
//! * `coverage` — watertightness over random meshes, the fill rule on hand-built cases, exact
//!   translation by whole pixels;
//! * `clipping` — triangles crossing the near and far planes, behind the eye, and enormous ones,
//!   against an exact per-pixel reference in i128;
//! * `depth` — monotone, exact at vertices, every format, the depth pair and the eye resolve;
//! * `determinism` — identical bytes for 1, 2 and 8 threads and across runs;
//! * `golden` — exact images of small scenes (`UPDATE_GOLDEN=1` rewrites them);
//! * `errors` — bad input is an error naming the triangle, vertex or size.

mod clipping;
mod coverage;
mod depth;
mod determinism;
mod errors;
mod golden;
mod support;
