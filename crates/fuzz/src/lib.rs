//! # shadowlab-fuzz: the fuzz targets, callable on stable
//!
//! Each function takes the fuzzer's bytes and feeds them to one reader or operation of shadowlab;
//! it returns normally whatever the input, and **panics only on a bug**: a panic, hang or abort in
//! the code under test, or a broken guarantee the harness checks (named in each function's
//! documentation). Errors returned as `Result` are the correct answer to bad input.
//!
//! cargo-fuzz's targets (`fuzz/fuzz_targets/*.rs`, nightly, outside the workspace) are one-line
//! calls into these functions, and `tests/corpus.rs` replays the committed corpus
//! (`fuzz/corpus/<target>/`) through them on the stable toolchain. See `docs/fuzzing.md`.
//!
//! ```
//! shadowlab_fuzz::cli(b"analyze\0--techniques\0lispsm:n=2\0--resolution\x0064");
//! shadowlab_fuzz::obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
//! shadowlab_fuzz::raster(&[0xff; 64]);
//! ```

mod hull;
mod num;
mod raster;
mod text;

/// The OBJ reader: the bytes (invalid UTF-8 replaced, as a lossy read would) through
/// `shadowlab_scene::parse_obj`. A mesh it returns must keep `Mesh`'s guarantees: a triangle,
/// finite positions, one unit normal per position, indices and group ids in range.
pub fn obj(data: &[u8]) {
    text::obj(data);
}

/// The scene reader: the bytes (lossy UTF-8) through `shadowlab_scene::parse_scene`, named as a
/// file in a directory that does not exist, so relative `obj` paths fail as missing files (absolute
/// ones are read). A scene it returns must keep the mesh's guarantees, have a light whose
/// `SceneLight::light` does not panic, and an image of at least one pixel with aspect
/// width / height.
pub fn scene(data: &[u8]) {
    text::scene(data);
}

/// The command line: the bytes split at NUL into arguments (any other bytes, not necessarily
/// UTF-8), after the program name `shadowlab`, through `shadowlab::check_arguments`, which parses
/// them as the binary does without running anything.
pub fn cli(data: &[u8]) {
    text::cli(data);
}

/// The rasterizer: the bytes decoded (with `arbitrary`) into a target (depth, depth pair, eye with
/// its resolve, or fragment callback) of at most 160 × 160 pixels, a format, compare and cull mode,
/// and draws of arbitrary positions, index triples and matrices (NaN, infinite, huge, subnormal,
/// degenerate, projective). Checked: `DrawStats` counts every triangle once; stored depths lie in
/// `[0, 1]`; the depth pair's nearest is not behind its second; triangle ids and fragments lie in
/// range; the depth images encode.
///
/// `EyeTarget::resolve` requires the mesh and matrix the target was drawn with, so it runs only
/// after a single draw.
pub fn raster(data: &[u8]) {
    raster::raster(data);
}

/// hull's operations: the bytes decoded into a start body (3-D hull of arbitrary points, a box, or
/// a frustum from camera parameters or any matrix) and up to 16 operations on it — clips by planes,
/// intersections with boxes, frusta and other hulls, extrusion toward point and directional lights
/// and sweeps, the focus bodies, light space, queries — plus the 2-D hull and minimum-area
/// rectangle of arbitrary points. Checked: every body returned validates, every polygon validates
/// and contains its points exactly, light space validates, ray intervals are ordered.
///
/// `Tolerances` are a caller's settings, not data: the harness uses the default and two other
/// valid values, never NaN or negative ones.
pub fn hull(data: &[u8]) {
    hull::hull(data);
}
