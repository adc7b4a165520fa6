//! The render targets a draw writes: [`DepthTarget`] (the shadow map), [`DepthPairTarget`] (the two
//! nearest depths) and [`EyeTarget`] (depth and the visible triangle). Each keeps its planes as
//! tiled storage (`tile`) and gives the tile pass a sink per tile (`sink`); the accessors return
//! ordinary row-major images with row 0 at the bottom.

use crate::depth::{DepthFormat, DepthKey};
use crate::error::RasterError;
use crate::kernel::{Sink, TileKernel};
use crate::schedule::costliest_first;
use crate::sink::{Compare, DepthSink, EyeSink, PairSink};
use crate::tile::{TILE_GROUP, TargetSize, TileGroup, TiledPlane};

/// The triangle id stored where no triangle covers a pixel.
pub const NO_TRIANGLE: u32 = u32::MAX;

/// A depth-only target: the shadow map.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthTarget {
    size: TargetSize,
    format: DepthFormat,
    keys: TiledPlane,
}

impl DepthTarget {
    /// The target's size.
    #[must_use]
    pub fn size(&self) -> TargetSize {
        self.size
    }

    /// The depth format it stores.
    #[must_use]
    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// A `width × height` depth target storing `format`, cleared to the far plane (depth 1).
    pub fn new(width: u32, height: u32, format: DepthFormat) -> Result<Self, RasterError> {
        let size = TargetSize::new(width, height)?;
        Ok(Self {
            size,
            format,
            keys: TiledPlane::new(size, format.encode(1.0)),
        })
    }

    /// Sets every pixel to window depth `depth` (clamped to `[0, 1]`; NaN: the far plane). Takes no
    /// time: the next draw fills each tile as it draws it.
    pub fn clear(&mut self, depth: f64) {
        self.keys.clear(self.format.encode(depth));
    }

    /// The stored keys, row-major with row 0 at the bottom (see [`DepthFormat`] for what a key is).
    #[must_use]
    pub fn keys(&self) -> Vec<u32> {
        self.keys.untile(self.size)
    }

    /// Window depths in `[0, 1]` exactly as stored, row-major with row 0 at the bottom.
    #[must_use]
    pub fn depths(&self) -> Vec<f64> {
        self.keys.depths(self.size, self.format)
    }
}

/// A target the tile pass draws into: what the draw call needs of each of the three.
pub(crate) trait TileTarget: Send {
    /// The target's size.
    fn target_size(&self) -> TargetSize;

    /// The depth format it stores.
    fn depth_format(&self) -> DepthFormat;

    /// Runs `kernel` on every group of [`TILE_GROUP`] tiles in parallel, with a sink per tile
    /// writing keys `K` into that tile only; returns the number of fragments that passed. `compare`
    /// is the depth test (a depth-pair target keeps the two nearest and ignores it).
    fn draw_tiles<K: DepthKey, C: Compare>(&mut self, compare: C, kernel: &impl TileKernel) -> u64;
}

impl TileTarget for DepthTarget {
    fn target_size(&self) -> TargetSize {
        self.size
    }

    fn depth_format(&self) -> DepthFormat {
        self.format
    }

    fn draw_tiles<K: DepthKey, C: Compare>(&mut self, compare: C, kernel: &impl TileKernel) -> u64 {
        draw_groups(self.keys.groups_mut(), kernel, |keys| {
            DepthSink::<K, C>::new(keys, compare)
        })
    }
}

/// The nearest and second-nearest depth in one pass: what the second-depth, midpoint and
/// dual-depth biases need. The depth test is fixed: nearer keys win.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthPairTarget {
    size: TargetSize,
    format: DepthFormat,
    nearest: TiledPlane,
    second: TiledPlane,
}

impl DepthPairTarget {
    /// The target's size.
    #[must_use]
    pub fn size(&self) -> TargetSize {
        self.size
    }

    /// The depth format it stores.
    #[must_use]
    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// A `width × height` target of depth pairs, both cleared to the far plane.
    pub fn new(width: u32, height: u32, format: DepthFormat) -> Result<Self, RasterError> {
        let size = TargetSize::new(width, height)?;
        let far = format.encode(1.0);
        Ok(Self {
            size,
            format,
            nearest: TiledPlane::new(size, far),
            second: TiledPlane::new(size, far),
        })
    }

    /// Sets both depths of every pixel to the far plane (carried out by the next draw).
    pub fn clear(&mut self) {
        let far = self.format.encode(1.0);
        self.nearest.clear(far);
        self.second.clear(far);
    }

    /// Nearest depths, row-major with row 0 at the bottom.
    #[must_use]
    pub fn nearest(&self) -> Vec<f64> {
        self.nearest.depths(self.size, self.format)
    }

    /// Second-nearest depths (1 where fewer than two surfaces cover the pixel).
    #[must_use]
    pub fn second(&self) -> Vec<f64> {
        self.second.depths(self.size, self.format)
    }
}

impl TileTarget for DepthPairTarget {
    fn target_size(&self) -> TargetSize {
        self.size
    }

    fn depth_format(&self) -> DepthFormat {
        self.format
    }

    fn draw_tiles<K: DepthKey, C: Compare>(&mut self, _: C, kernel: &impl TileKernel) -> u64 {
        let groups = self.nearest.groups_mut().zip(self.second.groups_mut());
        draw_groups(groups, kernel, |(nearest, second)| {
            PairSink::<K>::new(nearest, second)
        })
    }
}

/// The eye pass: depth and the id of the visible triangle per pixel, from which
/// [`crate::EyeTarget::resolve`] computes perspective-correct positions and normals.
#[derive(Clone, Debug, PartialEq)]
pub struct EyeTarget {
    size: TargetSize,
    format: DepthFormat,
    keys: TiledPlane,
    triangles: TiledPlane,
}

impl EyeTarget {
    /// The target's size.
    #[must_use]
    pub fn size(&self) -> TargetSize {
        self.size
    }

    /// The depth format it stores.
    #[must_use]
    pub fn format(&self) -> DepthFormat {
        self.format
    }

    /// A `width × height` eye target, cleared (depth 1, no triangle).
    pub fn new(width: u32, height: u32, format: DepthFormat) -> Result<Self, RasterError> {
        let size = TargetSize::new(width, height)?;
        Ok(Self {
            size,
            format,
            keys: TiledPlane::new(size, format.encode(1.0)),
            triangles: TiledPlane::new(size, NO_TRIANGLE),
        })
    }

    /// Clears depth to the far plane and the triangle ids to [`NO_TRIANGLE`] (carried out by the
    /// next draw).
    pub fn clear(&mut self) {
        self.keys.clear(self.format.encode(1.0));
        self.triangles.clear(NO_TRIANGLE);
    }

    /// Window depths as stored, row-major with row 0 at the bottom.
    #[must_use]
    pub fn depths(&self) -> Vec<f64> {
        self.keys.depths(self.size, self.format)
    }

    /// The visible triangle of each pixel ([`NO_TRIANGLE`] where none), row-major, row 0 at the
    /// bottom.
    #[must_use]
    pub fn triangles(&self) -> Vec<u32> {
        self.triangles.untile(self.size)
    }
}

impl TileTarget for EyeTarget {
    fn target_size(&self) -> TargetSize {
        self.size
    }

    fn depth_format(&self) -> DepthFormat {
        self.format
    }

    fn draw_tiles<K: DepthKey, C: Compare>(&mut self, compare: C, kernel: &impl TileKernel) -> u64 {
        let groups = self.keys.groups_mut().zip(self.triangles.groups_mut());
        draw_groups(groups, kernel, |(keys, triangles)| {
            EyeSink::<K, C>::new(keys, triangles, compare)
        })
    }
}

/// Runs `kernel` on every group of tiles, scheduled costliest first ([`costliest_first`]), each
/// tile through the sink `sink` makes of its storage; the pending clear is written only into the
/// tiles the kernel draws into. Returns the number of fragments that passed.
fn draw_groups<G: TileGroup, S: Sink>(
    groups: impl Iterator<Item = G>,
    kernel: &impl TileKernel,
    sink: impl Fn(G::Tile) -> S + Sync,
) -> u64 {
    costliest_first(
        groups.collect(),
        |g| kernel.cost(g * TILE_GROUP, TILE_GROUP),
        |g, group| {
            let first = g * TILE_GROUP;
            let drawn = |k| kernel.cost(first + k, 1) > 0;
            let mut sinks: Vec<S> = group.tiles(&drawn).map(&sink).collect();
            kernel.run(first, &mut sinks)
        },
    )
}
