//! The limits of a scene's camera and lights that every reader applies (scene files and glTF
//! files alike): the deepest depth range, the narrowest angle, the largest image. Each is where
//! shadowlab stops working in f64, or the rasterizer's limit, with the measurement that set it.

/// The largest far/near ratio of a camera or spot light whose near and far the file gives:
/// 10⁶. Every technique was tried at 2·10⁷ (near 10⁻⁶, far 20 on a unit box on a plane) and
/// works; at 2·10¹⁰ PSM's post-perspective focus body is flat to f64 ("no hull with an
/// interior"), at 2·10³¹ the light-space fits overflow. The papers' ratios are 100 to 800.
pub const MAX_DEPTH_RATIO: f64 = 1e6;

/// The smallest field of view or spot cone, in degrees: 0.001°. The focus body of a narrower
/// view stops having an interior in f64 (at 10⁻⁸° on a unit box PSM's hull is flat; 10⁻⁶° still
/// works for every technique, so this leaves a factor of 1000).
pub const MIN_ANGLE_DEGREES: f64 = 1e-3;

/// The largest image side, in pixels: the rasterizer's largest target side
/// (`shadowlab_raster::MAX_TARGET_SIZE`, 16384; the command-line tool asserts the two agree), so
/// that a scene's camera always has an eye pass.
pub const MAX_IMAGE_SIDE: u32 = 16384;
