//! # shadowlab-raster: an exact, deterministic CPU rasterizer
//!
//! Every number shadowlab reports comes out of this rasterizer, so it follows the GL rasterization
//! rules exactly and gives the same bits on every run and thread count.
//!
//! * **Transform** in f64 with a fixed order of operations ([`Triangles`] through a 4×4 matrix into
//!   GL clip space); homogeneous clipping against the near and far planes, and against a guard band
//!   of [`GUARD_BAND`] pixels around the viewport so that huge triangles stay exact.
//! * **Snapping** to a grid of 1/256 pixel ([`SUBPIXEL_BITS`] = 8), round to nearest.
//! * **Coverage** by integer edge functions at pixel centres `(i + ½, j + ½)` in `i64`, with the fill
//!   rule documented in the `triangle` module: a centre on an edge shared by two triangles is drawn
//!   exactly once.
//! * **Depth** interpolated linearly in screen space in f64 from the *unsnapped* window positions, as
//!   GL defines it (snapping is for coverage only), stored as a [`DepthFormat`] (f32, reversed-Z
//!   f32, 24- or 16-bit unorm), tested with a [`DepthCompare`].
//! * **Targets**: [`DepthTarget`] (shadow maps), [`DepthPairTarget`] (nearest and second-nearest
//!   depth in one pass), [`EyeTarget`] (depth and triangle id, resolved into perspective-correct
//!   world positions and normals by [`EyeTarget::resolve`]), and [`Rasterizer::for_each_fragment`]
//!   for custom per-pixel work.
//! * **Images**: [`image_out`] writes depth as EXR, 16-bit PNG and NPY (and colour as PNG);
//!   [`image_in`] reads the same depth files back, size-checked, for maps made elsewhere.
//! * **Parallel** by 64 × 64 tiles with rayon: triangles are binned to tiles and each tile is drawn
//!   by one thread in submission order.
//!
//! # Conventions
//! Window coordinates are GL's: x to the right, **y up**, pixel `(i, j)` covers
//! `[i, i+1) × [j, j+1)`, row 0 is the bottom row. Images returned by the targets are row-major with
//! row 0 at the bottom; writers of image files flip them so the top row comes first. Window depth is
//! `z_w = (z_ndc + 1)/2 ∈ [0, 1]`, 0 at the near plane, cleared to 1. Front faces are
//! counter-clockwise in window space.
//!
//! ```
//! use glam::{DMat4, DVec3};
//! use shadowlab_raster::{DepthFormat, DepthTarget, RasterOptions, Rasterizer, Triangles};
//!
//! let positions = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0), DVec3::new(-1.0, 1.0, 0.0)];
//! let triangles = [[0, 1, 2]];
//! let mut target = DepthTarget::new(8, 8, DepthFormat::F32)?;
//! let mut raster = Rasterizer::new(RasterOptions::default());
//! let stats = raster.draw_depth(&mut target, Triangles::new(&positions, &triangles), &DMat4::IDENTITY)?;
//! // The lower-left half of the square: the 28 centres strictly below the diagonal. The 8 centres on
//! // it are not drawn: in counter-clockwise order the diagonal is a right edge.
//! assert_eq!(stats.fragments, 28);
//! assert_eq!(target.depths()[0], 0.5);
//! # Ok::<(), shadowlab_raster::RasterError>(())
//! ```

mod bin;
mod clip;
mod depth;
mod error;
mod eye;
mod fixed;
pub mod image_in;
pub mod image_out;
mod kernel;
mod pipeline;
mod schedule;
mod sink;
mod stats;
mod target;
#[cfg(test)]
mod test_random;
mod tile;
mod triangle;
mod vertex;

pub use depth::{DepthCompare, DepthFormat};
pub use error::RasterError;
pub use eye::EyeImage;
pub use fixed::{GUARD_BAND, MAX_TARGET_SIZE, SUBPIXEL_BITS};
pub use pipeline::{Fragment, RasterOptions, Rasterizer, Triangles};
pub use stats::DrawStats;
pub use target::{DepthPairTarget, DepthTarget, EyeTarget, NO_TRIANGLE};
pub use tile::TargetSize;
pub use triangle::CullMode;
