//! The draw call: vertex stage, binning, tiles.
//!
//! 1. **Vertices** (parallel over fixed chunks): transform to clip space in f64, classify against the
//!    clip volume, and snap the ones inside to the window grid. Shared vertices are snapped once, so
//!    the triangles that share an edge see identical endpoints.
//! 2. **Binning** (parallel over fixed chunks of triangles; the `bin` module): trivially reject,
//!    clip the few that cross the near or far plane or the guard band, classify (degenerate,
//!    culled, empty), and list each triangle under every tile its pixel box touches — sorted by
//!    tile within the chunk, in submission order.
//! 3. **Tiles** (parallel over groups of a few tiles, ordered by the `schedule` module): each tile
//!    walks the chunks in order and their lists for it, so it sees its triangles in submission
//!    order, and rasterizes them (`kernel`) into its own pixels through its target's sinks
//!    (`sink`, into `tile` storage); the tiles of a group take each chunk in turn, so they share
//!    its data in cache.
//!
//! No pixel is written by two threads and every tile's triangle order is the submission order, so
//! the output is bit-identical for any number of threads and any run.

use glam::{DMat4, DVec3};
use rayon::prelude::*;

use crate::bin::{BinContext, ChunkBins, EntryKind, MAX_TRIANGLES, TRIANGLE_CHUNK};
use crate::depth::{DepthCompare, DepthFormat, F32Key, ReversedF32Key, Unorm16Key, Unorm24Key};
use crate::error::RasterError;
use crate::kernel::{BLOCK, HALF, Lanes, Sink, TileKernel, rasterize};
use crate::sink::{Compare, Less};
use crate::stats::DrawStats;
use crate::target::{DepthPairTarget, DepthTarget, EyeTarget, TileTarget};
use crate::tile::{TILE_STRIDE, TargetSize, TileRect};
use crate::triangle::{CullMode, Verdict, classify};
use crate::vertex::{Viewport, WindowVertex, transform_vertices};

/// Vertices per parallel work item of the vertex stage: small enough that the bunny's 34 835
/// vertices make 17 items, which two threads share evenly (with 8192 they made 5).
const VERTEX_CHUNK: usize = 2048;
/// Triangles to draw: positions and counter-clockwise (for front faces) index triples.
#[derive(Clone, Copy, Debug)]
pub struct Triangles<'a> {
    positions: &'a [DVec3],
    triangles: &'a [[u32; 3]],
}

impl<'a> Triangles<'a> {
    /// Triangles over `positions`. Indices are checked when drawing.
    #[must_use]
    pub fn new(positions: &'a [DVec3], triangles: &'a [[u32; 3]]) -> Self {
        Self {
            positions,
            triangles,
        }
    }

    /// The vertex positions.
    #[must_use]
    pub fn positions(&self) -> &'a [DVec3] {
        self.positions
    }

    /// The index triples.
    #[must_use]
    pub fn triangles(&self) -> &'a [[u32; 3]] {
        self.triangles
    }
}

/// How a draw treats its triangles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct RasterOptions {
    /// The depth test (default: [`DepthCompare::Less`]). Ignored by depth-pair targets, which keep
    /// the two nearest.
    pub compare: DepthCompare,
    /// Which faces to discard (default: none).
    pub cull: CullMode,
}

/// One covered pixel, as [`Rasterizer::for_each_fragment`] reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment {
    /// Column, from the left.
    pub x: u32,
    /// Row, from the bottom.
    pub y: u32,
    /// Interpolated window depth in `[0, 1]`, before any storage format.
    pub depth: f64,
    /// The index of the triangle covering it.
    pub triangle: u32,
}

/// The rasterizer: options plus scratch memory reused from draw to draw.
#[derive(Debug, Default)]
pub struct Rasterizer {
    options: RasterOptions,
    window: Vec<WindowVertex>,
    codes: Vec<u8>,
    chunks: Vec<ChunkBins>,
    /// Per tile, the entries binned to it by all chunks.
    tile_entries: Vec<u32>,
}

/// Everything the tile pass needs.
struct Binned<'a> {
    size: TargetSize,
    cull: CullMode,
    window: &'a [WindowVertex],
    chunks: &'a [ChunkBins],
    /// Per tile, the entries binned to it by all chunks: what the tile groups are scheduled by.
    tile_entries: &'a [u32],
}

impl Rasterizer {
    /// A rasterizer with these options.
    #[must_use]
    pub fn new(options: RasterOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The options.
    #[must_use]
    pub fn options(&self) -> RasterOptions {
        self.options
    }

    /// Draws `mesh` transformed by `clip_from_world` (GL clip space) into a depth target.
    pub fn draw_depth(
        &mut self,
        target: &mut DepthTarget,
        mesh: Triangles<'_>,
        clip_from_world: &DMat4,
    ) -> Result<DrawStats, RasterError> {
        self.draw(target, mesh, clip_from_world)
    }

    /// Draws `mesh` into a target keeping the nearest and second-nearest depth of every pixel.
    pub fn draw_depth_pair(
        &mut self,
        target: &mut DepthPairTarget,
        mesh: Triangles<'_>,
        clip_from_world: &DMat4,
    ) -> Result<DrawStats, RasterError> {
        self.draw(target, mesh, clip_from_world)
    }

    /// Draws `mesh` into an eye target: depth and the visible triangle's index per pixel.
    pub fn draw_eye(
        &mut self,
        target: &mut EyeTarget,
        mesh: Triangles<'_>,
        clip_from_world: &DMat4,
    ) -> Result<DrawStats, RasterError> {
        self.draw(target, mesh, clip_from_world)
    }

    /// Steps 1–3 into any target. The depth test is chosen here, once per draw: `Less`, the
    /// common one, as a type of its own, so that its inner loop has no per-fragment branch.
    fn draw<T: TileTarget>(
        &mut self,
        target: &mut T,
        mesh: Triangles<'_>,
        clip_from_world: &DMat4,
    ) -> Result<DrawStats, RasterError> {
        on_pool(|| {
            let compare = self.options.compare;
            let binned = self.bin(target.target_size(), mesh, clip_from_world)?;
            let fragments = match compare {
                DepthCompare::Less => draw_tiles(target, Less, &binned),
                compare => draw_tiles(target, compare, &binned),
            };
            Ok(binned.finish(fragments))
        })
    }

    /// Calls `f` for every pixel centre covered by `mesh` on a `size` target, without a depth test:
    /// tile by tile (rows of 64 × 64 tiles from the bottom left), and within a tile in submission
    /// order, row by row. The order is the same on every run and thread count.
    pub fn for_each_fragment(
        &mut self,
        size: TargetSize,
        mesh: Triangles<'_>,
        clip_from_world: &DMat4,
        mut f: impl FnMut(Fragment),
    ) -> Result<DrawStats, RasterError> {
        let binned = self.bin(size, mesh, clip_from_world)?;
        let mut fragments = 0;
        for tile in 0..size.tile_count() {
            let mut sink = CallbackSink::new(size.tile_rect(tile), &mut f);
            fragments += binned.run(tile, std::slice::from_mut(&mut sink));
        }
        Ok(binned.finish(fragments))
    }

    /// Steps 1 and 2: vertices and binning.
    fn bin<'a>(
        &'a mut self,
        size: TargetSize,
        mesh: Triangles<'a>,
        m: &DMat4,
    ) -> Result<Binned<'a>, RasterError> {
        if !m.is_finite() {
            return Err(RasterError::NonFiniteMatrix);
        }
        if mesh.triangles.len() > MAX_TRIANGLES {
            return Err(RasterError::TooManyTriangles {
                count: mesh.triangles.len(),
            });
        }
        let viewport = Viewport::new(size.width(), size.height());
        let n = mesh.positions.len();
        self.window.resize(n, WindowVertex::default());
        self.codes.resize(n, 0);
        mesh.positions
            .par_chunks(VERTEX_CHUNK)
            .zip(self.window.par_chunks_mut(VERTEX_CHUNK))
            .zip(self.codes.par_chunks_mut(VERTEX_CHUNK))
            .with_max_len(1)
            .for_each(|((positions, window), codes)| {
                transform_vertices(m, &viewport, positions, window, codes);
            });
        let context = BinContext {
            positions: mesh.positions,
            window: &self.window,
            codes: &self.codes,
            clip_from_world: m,
            viewport,
            size,
            cull: self.options.cull,
        };
        self.chunks.resize_with(
            mesh.triangles.len().div_ceil(TRIANGLE_CHUNK),
            ChunkBins::default,
        );
        self.chunks
            .par_iter_mut()
            .zip(mesh.triangles.par_chunks(TRIANGLE_CHUNK))
            .with_max_len(1)
            .enumerate()
            .for_each(|(c, (bins, triangles))| {
                bins.refill(c * TRIANGLE_CHUNK, triangles, &context);
            });
        let chunks = &self.chunks[..];
        if let Some(error) = chunks.iter().find_map(ChunkBins::error) {
            return Err(error.clone());
        }
        self.tile_entries.clear();
        self.tile_entries.resize(size.tile_count(), 0);
        for chunk in chunks {
            for (count, entries) in self.tile_entries.iter_mut().zip(chunk.entry_counts()) {
                *count += entries;
            }
        }
        Ok(Binned {
            size,
            cull: self.options.cull,
            window: &self.window,
            chunks,
            tile_entries: &self.tile_entries,
        })
    }
}

/// Runs a draw's phases on a thread of the current rayon pool. Called from outside the pool, each
/// parallel phase would otherwise be sent to the pool separately while the calling thread sleeps,
/// and each wake-up of the caller between phases cost time the pool's threads spent idle (with
/// clears carried out by the draw instead of a parallel job of their own: 6 % of the bunny's eye
/// pass on two threads, docs/benchmarks.md). Inside a pool, `f` runs where it is.
fn on_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| f())
}

impl TileKernel for Binned<'_> {
    /// Draws a group of tiles chunk by chunk: all of a chunk's entries for the group's tiles, then
    /// the next chunk's. Each tile still sees its triangles in submission order, and the group's
    /// tiles share the window vertices of a chunk's triangles (a patch of the mesh) while they are
    /// in cache, where tile after tile would fetch them again (measured with bin entries carrying
    /// their index triples: 4 to 5 % off the dragon's passes on one thread, no change on two).
    fn run<S: Sink>(&self, first: usize, sinks: &mut [S]) -> u64 {
        let rects: Vec<TileRect> = (first..first + sinks.len())
            .map(|tile| self.size.tile_rect(tile))
            .collect();
        let mut passed = 0;
        for chunk in self.chunks {
            for (k, sink) in sinks.iter_mut().enumerate() {
                passed += self.draw_entries(chunk, first + k, &rects[k], sink);
            }
        }
        passed
    }

    /// The entries binned to the tiles (a run of early fragments counting as one).
    fn cost(&self, first: usize, count: usize) -> u64 {
        let last = (first + count).min(self.tile_entries.len());
        self.tile_entries[first..last]
            .iter()
            .map(|&entries| u64::from(entries))
            .sum()
    }
}

impl Binned<'_> {
    /// Draws a chunk's entries for tile `tile` (with pixel rectangle `rect`) into its sink.
    #[inline(always)]
    fn draw_entries<S: Sink>(
        &self,
        chunk: &ChunkBins,
        tile: usize,
        rect: &TileRect,
        sink: &mut S,
    ) -> u64 {
        let (w, h) = (i64::from(self.size.width()), i64::from(self.size.height()));
        let mut passed = 0;
        for &entry in chunk.entries(tile) {
            let (source, triangle): (&[WindowVertex], u32) = match entry.kind() {
                EntryKind::Triangle(id) => (self.window, id),
                EntryKind::Fragments(first) => {
                    for fragment in chunk.run(first) {
                        let pixel = usize::from(fragment.pixel);
                        passed += sink.fragment(pixel, fragment.z, fragment.triangle);
                    }
                    continue;
                }
                EntryKind::Piece(index) => {
                    let piece = chunk.piece(index);
                    (&piece.vertices, piece.triangle)
                }
            };
            let vertices = entry.corners().map(|v| source[v as usize]);
            if let Verdict::Draw(bounds, area) = classify(&vertices, self.cull, w, h) {
                passed += rasterize(&vertices, area, &bounds, rect, triangle, sink);
            }
        }
        passed
    }
}

impl Binned<'_> {
    fn finish(&self, fragments: u64) -> DrawStats {
        let mut stats = DrawStats::default();
        for chunk in self.chunks {
            stats.add(chunk.stats());
        }
        stats.fragments = fragments;
        stats
    }
}

/// Hands every covered pixel to a callback.
struct CallbackSink<'f, F> {
    x0: u32,
    y0: u32,
    f: &'f mut F,
}

impl<'f, F> CallbackSink<'f, F> {
    /// A sink for the tile at `rect`.
    fn new(rect: TileRect, f: &'f mut F) -> Self {
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "tile origins lie in the target"
        )]
        let (x0, y0) = (rect.x0 as u32, rect.y0 as u32);
        Self { x0, y0, f }
    }
}

impl<F: FnMut(Fragment)> Sink for CallbackSink<'_, F> {
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        triangle: u32,
    ) -> u64 {
        let mut count = 0;
        for k in (0..BLOCK).filter(|&k| uncovered[k] == 0) {
            let index = start + (k / HALF) * SPLIT + k % HALF;
            count += self.fragment(index, z[k], triangle);
        }
        count
    }

    fn fragment(&mut self, index: usize, z: f64, triangle: u32) -> u64 {
        #[expect(clippy::cast_possible_truncation, reason = "index < TILE_PIXELS")]
        let (dx, dy) = ((index % TILE_STRIDE) as u32, (index / TILE_STRIDE) as u32);
        let depth = z.clamp(0.0, 1.0);
        (self.f)(Fragment {
            x: self.x0 + dx,
            y: self.y0 + dy,
            depth,
            triangle,
        });
        1
    }
}

/// The tile pass into `target` with the depth test `compare`, compiled once per depth format so
/// that each key has its own inner loop.
fn draw_tiles<C: Compare>(target: &mut impl TileTarget, compare: C, binned: &Binned<'_>) -> u64 {
    match target.depth_format() {
        DepthFormat::F32 => target.draw_tiles::<F32Key, C>(compare, binned),
        DepthFormat::ReversedF32 => target.draw_tiles::<ReversedF32Key, C>(compare, binned),
        DepthFormat::Unorm24 => target.draw_tiles::<Unorm24Key, C>(compare, binned),
        DepthFormat::Unorm16 => target.draw_tiles::<Unorm16Key, C>(compare, binned),
    }
}
