//! The draw call: vertex stage, binning, tiles.
//!
//! 1. **Vertices** (parallel over fixed chunks): transform to clip space in f64, classify against the
//!    clip volume, and snap the ones inside to the window grid. Shared vertices are snapped once, so
//!    the triangles that share an edge see identical endpoints.
//! 2. **Binning** (parallel over fixed chunks of triangles): trivially reject, clip the few that
//!    cross the near or far plane or the guard band, classify (degenerate, culled, empty), and list
//!    each triangle under every tile its pixel box touches — sorted by tile within the chunk, in
//!    submission order.
//! 3. **Tiles** (parallel over groups of a few tiles): each tile walks the chunks in order and their
//!    lists for it, so it sees its triangles in submission order, and rasterizes them into its own
//!    pixels; the tiles of a group take each chunk in turn, so they share its data in cache.
//!
//! No pixel is written by two threads and every tile's triangle order is the submission order, so
//! the output is bit-identical for any number of threads and any run.

use glam::{DMat4, DVec3};
use rayon::prelude::*;

use crate::clip::{ClippedTriangle, clip_triangle};
use crate::depth::{DepthCompare, DepthFormat, F32Key, ReversedF32Key, Unorm16Key, Unorm24Key};
use crate::error::RasterError;
use crate::kernel::{BLOCK, HALF, Lanes, Sink, TileKernel, TileRect, for_each_in_mask, rasterize};
use crate::target::{
    DepthPairTarget, DepthTarget, EyeTarget, TILE_SHIFT, TILE_STRIDE, TargetSize, TileTarget,
};
use crate::triangle::{CullMode, DepthPlane, Edge, Verdict, classify, edges};
use crate::vertex::{Viewport, WindowVertex, code, transform, transform_vertices};

/// Vertices per parallel work item of the vertex stage: small enough that the bunny's 34 835
/// vertices make 17 items, which two threads share evenly (with 8192 they made 5).
const VERTEX_CHUNK: usize = 2048;
/// Triangles per parallel work item of binning, chosen the same way (17 items for the bunny). Any
/// size gives the same output.
const TRIANGLE_CHUNK: usize = 4096;
/// The two top bits of a bin entry say what the rest indexes: a triangle of the mesh, a clipped
/// piece of the chunk, or a run of the chunk's early fragments.
const KIND_SHIFT: u32 = 30;
/// An entry's kind: a triangle of the mesh (so triangle ids must stay below `2^30`).
const TRIANGLE: u32 = 0;
/// An entry's kind: a run of [`EarlyFragment`]s, by the index of its first.
const FRAGMENTS: u32 = 1 << KIND_SHIFT;
/// An entry's kind: a clipped piece.
const CLIPPED: u32 = 2 << KIND_SHIFT;
/// The corners of a clipped piece's entry: indices into its own three vertices, so that the tile
/// pass loads the vertices of pieces and of mesh triangles alike (see [`Entry`]).
const PIECE_CORNERS: [u32; 3] = [0, 1, 2];
/// The index part of an entry.
const INDEX_MASK: u32 = (1 << KIND_SHIFT) - 1;
/// Triangles whose pixel box holds at most this many pixels, all in one tile, are rasterized while
/// binning (see [`EarlyFragment`]). Measured on the benchmark views (2 threads, best of 5 runs,
/// against no early path): 2 takes 9% off the dragon's eye pass and costs nothing elsewhere; 8
/// takes 19% off it but adds 8% to the bunny's eye pass and 5% to the dragon's light pass — the
/// early test's data-dependent branches outweigh the setup it saves once boxes cover a few pixels.
const EARLY: i64 = 2;
// A box of at most EARLY pixels is one or two pixels, as `early_coverage` requires.
const _: () = assert!(EARLY <= 2);

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

/// What happened to the triangles of a draw. Every triangle is counted exactly once among
/// `drawn`, `degenerate`, `culled`, `empty`, `outside` and `clipped`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawStats {
    /// Triangles submitted.
    pub triangles: u64,
    /// Rasterized without clipping.
    pub drawn: u64,
    /// Zero area after snapping (never drawn).
    pub degenerate: u64,
    /// Discarded by the cull mode.
    pub culled: u64,
    /// Inside the clip volume but covering no pixel centre's bounding box.
    pub empty: u64,
    /// Entirely outside one plane of the clip volume.
    pub outside: u64,
    /// Crossing the near or far plane or the guard band, and clipped.
    pub clipped: u64,
    /// Pieces the clipped triangles were cut into that were rasterized.
    pub clipped_pieces: u64,
    /// Fragments that passed the depth test (or, for [`Rasterizer::for_each_fragment`], all covered
    /// pixels).
    pub fragments: u64,
}

impl DrawStats {
    fn add(&mut self, other: &Self) {
        self.triangles += other.triangles;
        self.drawn += other.drawn;
        self.degenerate += other.degenerate;
        self.culled += other.culled;
        self.empty += other.empty;
        self.outside += other.outside;
        self.clipped += other.clipped;
        self.clipped_pieces += other.clipped_pieces;
        self.fragments += other.fragments;
    }
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

/// A covered pixel of a tiny triangle, found while binning.
///
/// A triangle whose pixel box holds at most [`EARLY`] pixels, all in one tile, is tested pixel by
/// pixel during binning (by the same edge test and depth as the tile pass), and only the pixels it
/// covers are binned — none at all for the many that cover no centre. Dense meshes are mostly such
/// triangles, and this spares the tile pass fetching and setting each of them up again.
#[derive(Clone, Copy, Debug)]
struct EarlyFragment {
    /// Window depth, unclamped, as the tile pass would compute it.
    z: f64,
    /// The triangle it belongs to.
    triangle: u32,
    /// Index within the tile's storage.
    pixel: u16,
    /// Whether it is the last of its triangle's run.
    last: bool,
}

/// The triangles binned to tiles by one chunk of the submission. Kept by the [`Rasterizer`] and
/// refilled by every draw, so a sequence of draws allocates its buffers once.
#[derive(Debug, Default)]
struct ChunkBins {
    /// Entries grouped by tile.
    entries: Vec<Entry>,
    /// `entries[starts[t]..starts[t + 1]]` are tile t's.
    starts: Vec<u32>,
    /// The clipped pieces this chunk made.
    pieces: Vec<ClippedTriangle>,
    /// The runs of early fragments this chunk found.
    fragments: Vec<EarlyFragment>,
    stats: DrawStats,
    /// The first bad input of the chunk, if any.
    error: Option<RasterError>,
    /// Scratch: `(tile, entry)` pairs in submission order, before sorting.
    listed: Vec<(u32, Entry)>,
    /// Scratch: the next free slot of each tile while sorting.
    cursor: Vec<u32>,
}

/// What a tile draws: a kind (the two top bits of `entry`) and an index; for a mesh triangle also
/// its index triple, copied while binning (which reads it anyway) so that the tile pass need not
/// fetch it from the mesh, where a tile's triangles lie scattered: that fetch missed the cache often
/// enough to take 9 % of the dragon light pass's tile time.
///
/// A clipped piece's corners are [`PIECE_CORNERS`], indices into its own vertices, so the tile pass
/// picks the vertex array (the mesh's or the piece's) and loads three vertices from it the same way
/// for both kinds. Picking the three vertices themselves instead made the compiler carry a pointer
/// per field of each vertex past the choice: about 10 instructions per triangle setup in the tile
/// pass with window vertices of three fields (1 % of the instructions of the bunny's 2048² light
/// pass, callgrind), and about 50 with the five a vertex has once depth uses its unsnapped position.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    entry: u32,
    /// The mesh triangle's vertex indices, or [`PIECE_CORNERS`] for a clipped piece; zero for a run
    /// of early fragments.
    corners: [u32; 3],
}

impl Entry {
    /// An entry of a run of early fragments.
    fn fragments(entry: u32) -> Self {
        Self {
            entry,
            corners: [0; 3],
        }
    }
}

/// What binning needs of the draw, the same for every chunk.
struct BinContext<'a> {
    positions: &'a [DVec3],
    window: &'a [WindowVertex],
    codes: &'a [u8],
    clip_from_world: &'a DMat4,
    viewport: Viewport,
    size: TargetSize,
    cull: CullMode,
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

    /// Steps 1–3 into any target, with the tile pass compiled once per depth format so that each
    /// key has its own inner loop.
    fn draw<T: TileTarget>(
        &mut self,
        target: &mut T,
        mesh: Triangles<'_>,
        clip_from_world: &DMat4,
    ) -> Result<DrawStats, RasterError> {
        on_pool(|| {
            let compare = self.options.compare;
            let binned = self.bin(target.target_size(), mesh, clip_from_world)?;
            let fragments = match target.depth_format() {
                DepthFormat::F32 => target.draw_tiles::<F32Key, _>(compare, &binned),
                DepthFormat::ReversedF32 => {
                    target.draw_tiles::<ReversedF32Key, _>(compare, &binned)
                }
                DepthFormat::Unorm24 => target.draw_tiles::<Unorm24Key, _>(compare, &binned),
                DepthFormat::Unorm16 => target.draw_tiles::<Unorm16Key, _>(compare, &binned),
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
            let (x0, y0, _, _) = size.tile_rect(tile);
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "tile origins lie in the target"
            )]
            let mut sink = CallbackSink {
                x0: x0 as u32,
                y0: y0 as u32,
                f: &mut f,
            };
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
        if mesh.triangles.len() > INDEX_MASK as usize {
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
        if let Some(error) = chunks.iter().find_map(|c| c.error.clone()) {
            return Err(error);
        }
        self.tile_entries.clear();
        self.tile_entries.resize(size.tile_count(), 0);
        for chunk in chunks {
            for (count, range) in self.tile_entries.iter_mut().zip(chunk.starts.windows(2)) {
                *count += range[1] - range[0];
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

impl ChunkBins {
    /// Bins triangles `first..first + triangles.len()` of the draw, replacing what the chunk held.
    fn refill(&mut self, first: usize, triangles: &[[u32; 3]], context: &BinContext<'_>) {
        let BinContext {
            positions,
            window,
            codes,
            clip_from_world: m,
            ref viewport,
            size,
            cull,
        } = *context;
        let (width, height) = (i64::from(size.width()), i64::from(size.height()));
        let mut stats = DrawStats::default();
        let mut error = None;
        let Self {
            entries,
            starts,
            pieces,
            fragments,
            listed,
            cursor,
            ..
        } = self;
        entries.clear();
        starts.clear();
        cursor.clear();
        pieces.clear();
        fragments.clear();
        listed.clear();
        let n = positions.len();
        for (k, t) in triangles.iter().enumerate() {
            let id = first + k;
            if let Some(&vertex) = t.iter().find(|&&v| v as usize >= n) {
                error = Some(RasterError::IndexOutOfRange {
                    triangle: id,
                    vertex,
                    vertex_count: n,
                });
                break;
            }
            let [a, b, c] = t.map(|v| v as usize);
            let (ca, cb, cc) = (codes[a], codes[b], codes[c]);
            if (ca | cb | cc) & code::NOT_FINITE != 0 {
                let bad = [a, b, c]
                    .into_iter()
                    .find(|&v| codes[v] & code::NOT_FINITE != 0);
                error = Some(RasterError::NonFiniteVertex {
                    vertex: bad.unwrap_or(a),
                });
                break;
            }
            stats.triangles += 1;
            #[expect(
                clippy::cast_possible_truncation,
                reason = "ids are at most INDEX_MASK, checked per draw"
            )]
            let entry = id as u32;
            if ca | cb | cc == 0 {
                let vertices = [window[a], window[b], window[c]];
                match classify(&vertices, cull, width, height) {
                    Verdict::Degenerate => stats.degenerate += 1,
                    Verdict::Culled => stats.culled += 1,
                    Verdict::Empty => stats.empty += 1,
                    Verdict::Draw(bounds, area) => {
                        stats.drawn += 1;
                        if let Some(tile) = small_box_tile(&bounds, size) {
                            let first = fragments.len();
                            find_early_fragments(&vertices, area, &bounds, entry, fragments);
                            if fragments.len() > first {
                                let last = fragments.len() - 1;
                                fragments[last].last = true;
                                #[expect(
                                    clippy::cast_possible_truncation,
                                    reason = "a chunk's fragments are far fewer than 2^30"
                                )]
                                let run = FRAGMENTS | first as u32;
                                listed.push((tile, Entry::fragments(run)));
                            }
                        } else {
                            let entry = Entry {
                                entry: TRIANGLE | entry,
                                corners: *t,
                            };
                            list_tiles(&bounds, entry, size, listed);
                        }
                    }
                }
            } else if ca & cb & cc != 0 {
                stats.outside += 1;
            } else {
                stats.clipped += 1;
                let clip = [
                    transform(m, positions[a]),
                    transform(m, positions[b]),
                    transform(m, positions[c]),
                ];
                let before = pieces.len();
                clip_triangle(clip, ca | cb | cc, entry, viewport, pieces);
                for (p, piece) in pieces.iter().enumerate().skip(before) {
                    if let Verdict::Draw(bounds, _) = classify(&piece.vertices, cull, width, height)
                    {
                        stats.clipped_pieces += 1;
                        #[expect(
                            clippy::cast_possible_truncation,
                            reason = "pieces per chunk < 2^30"
                        )]
                        let piece_entry = CLIPPED | p as u32;
                        let entry = Entry {
                            entry: piece_entry,
                            corners: PIECE_CORNERS,
                        };
                        list_tiles(&bounds, entry, size, listed);
                    }
                }
            }
        }
        // Counting sort by tile; stable, so each tile keeps submission order.
        let tiles = size.tile_count();
        starts.resize(tiles + 1, 0);
        for &(tile, _) in listed.iter() {
            starts[tile as usize + 1] += 1;
        }
        for t in 0..tiles {
            starts[t + 1] += starts[t];
        }
        cursor.extend_from_slice(starts);
        entries.resize(listed.len(), Entry::default());
        for &(tile, entry) in listed.iter() {
            let slot = &mut cursor[tile as usize];
            entries[*slot as usize] = entry;
            *slot += 1;
        }
        self.stats = stats;
        self.error = error;
    }
}

/// The tile holding all of a pixel box of at most [`EARLY`] pixels, if there is one.
fn small_box_tile(b: &crate::triangle::PixelBox, size: TargetSize) -> Option<u32> {
    let small = (b.max_i - b.min_i + 1) * (b.max_j - b.min_j + 1) <= EARLY;
    let (tx, ty) = (b.min_i >> TILE_SHIFT, b.min_j >> TILE_SHIFT);
    let one_tile = tx == b.max_i >> TILE_SHIFT && ty == b.max_j >> TILE_SHIFT;
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "tile coordinates are small and non-negative"
    )]
    let tile = (ty as usize * size.tiles_x() + tx as usize) as u32;
    (small && one_tile).then_some(tile)
}

/// Appends the covered pixels of a tiny triangle (see [`EarlyFragment`]) to `out`. The depth
/// plane is set up only if some centre is covered, which most such triangles do not.
fn find_early_fragments(
    vertices: &[WindowVertex; 3],
    area: i64,
    b: &crate::triangle::PixelBox,
    triangle: u32,
    out: &mut Vec<EarlyFragment>,
) {
    let covered = early_coverage(&edges(vertices, area), b);
    if covered == 0 {
        return;
    }
    let depth = DepthPlane::new(vertices, area);
    let tile_mask = (1 << TILE_SHIFT) - 1;
    for_each_in_mask(covered, &depth, b.min_i..=b.max_i, b.min_j, |i, j, z| {
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "an index within a tile, below TILE_PIXELS"
        )]
        let pixel = ((j & tile_mask) as usize * TILE_STRIDE + (i & tile_mask) as usize) as u16;
        out.push(EarlyFragment {
            z,
            triangle,
            pixel,
            last: false,
        });
    });
}

/// The covered centres of a box of one or two pixels (bit 0 for its first pixel, bit 1 for the
/// second, right of or above it, as [`for_each_in_mask`] reads them), by the exact edge functions
/// in scalar arithmetic: for two points, lanes cost more than they save.
#[inline(always)]
fn early_coverage(edges: &[Edge; 3], b: &crate::triangle::PixelBox) -> u32 {
    let first = edges.map(|e| e.at(b.min_i, b.min_j));
    let wide = b.max_i > b.min_i;
    let two = wide || b.max_j > b.min_j;
    let second: [i64; 3] = std::array::from_fn(|k| {
        first[k]
            + if wide {
                edges[k].step_i
            } else {
                edges[k].step_j
            }
    });
    let inside = |v: [i64; 3]| (v[0] | v[1] | v[2]) >= 0;
    u32::from(inside(first)) | (u32::from(two && inside(second)) << 1)
}

/// Lists `entry` under every tile the pixel box touches.
fn list_tiles(
    b: &crate::triangle::PixelBox,
    entry: Entry,
    size: TargetSize,
    out: &mut Vec<(u32, Entry)>,
) {
    let tiles_x = size.tiles_x();
    for ty in b.min_j >> TILE_SHIFT..=b.max_j >> TILE_SHIFT {
        for tx in b.min_i >> TILE_SHIFT..=b.max_i >> TILE_SHIFT {
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "tile coordinates are small and non-negative"
            )]
            let t = (ty as usize * tiles_x + tx as usize) as u32;
            out.push((t, entry));
        }
    }
}

impl TileKernel for Binned<'_> {
    /// Draws a group of tiles chunk by chunk: all of a chunk's entries for the group's tiles, then
    /// the next chunk's. Each tile still sees its triangles in submission order, and the group's
    /// tiles share the window vertices of a chunk's triangles (a patch of the mesh) while they are
    /// in cache, where tile after tile would fetch them again (measured with bin entries carrying
    /// their index triples: 4 to 5 % off the dragon's passes on one thread, no change on two).
    fn run<S: Sink>(&self, first: usize, sinks: &mut [S]) -> u64 {
        let rects: Vec<TileRect> = (first..first + sinks.len())
            .map(|tile| {
                let (x0, y0, width, height) = self.size.tile_rect(tile);
                TileRect {
                    x0,
                    y0,
                    width,
                    height,
                }
            })
            .collect();
        let mut passed = 0;
        for chunk in self.chunks {
            for (k, sink) in sinks.iter_mut().enumerate() {
                let tile = first + k;
                let range = chunk.starts[tile] as usize..chunk.starts[tile + 1] as usize;
                passed += self.draw_entries(chunk, &chunk.entries[range], &rects[k], sink);
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
    /// Draws some of a chunk's entries for one tile into its sink.
    #[inline(always)]
    fn draw_entries<S: Sink>(
        &self,
        chunk: &ChunkBins,
        entries: &[Entry],
        rect: &TileRect,
        sink: &mut S,
    ) -> u64 {
        let (w, h) = (i64::from(self.size.width()), i64::from(self.size.height()));
        let mut passed = 0;
        for &Entry { entry, corners } in entries {
            let index = (entry & INDEX_MASK) as usize;
            let (source, triangle): (&[WindowVertex], u32) = match entry & !INDEX_MASK {
                TRIANGLE => (self.window, entry),
                FRAGMENTS => {
                    for fragment in &chunk.fragments[index..] {
                        let pixel = usize::from(fragment.pixel);
                        passed += sink.fragment(pixel, fragment.z, fragment.triangle);
                        if fragment.last {
                            break;
                        }
                    }
                    continue;
                }
                _ => {
                    let piece = &chunk.pieces[index];
                    (&piece.vertices, piece.triangle)
                }
            };
            let vertices = corners.map(|v| source[v as usize]);
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
            stats.add(&chunk.stats);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Recorder;
    use crate::triangle::PixelBox;

    /// The early fragments binning finds for a tiny triangle are the pixels, with the same depth
    /// bits, that the tile pass draws for it, for triangles off the grid (unsnapped positions up to
    /// half a grid unit from the snapped ones) anywhere in a tile, on and across its borders.
    #[test]
    fn early_fragments_are_what_the_tile_pass_draws() {
        let mut random = crate::test_random::XorShift::new(0x3c6e_f372_fe94_f82b);
        let mut next = move |n: u64| {
            #[expect(clippy::cast_possible_wrap, reason = "below n")]
            let v = random.below(n) as i64;
            v
        };
        let size = TargetSize::new(256, 256).unwrap();
        let mut compared = 0;
        for _ in 0..50_000 {
            // Within three pixels of a point near the tile corner (64, 64).
            let (x, y) = (256 * 62 + next(256 * 4), 256 * 62 + next(256 * 4));
            let v: [WindowVertex; 3] = std::array::from_fn(|_| {
                #[expect(clippy::cast_possible_truncation, reason = "small grid values")]
                let (x, y) = ((x + next(3 * 256)) as i32, (y + next(3 * 256)) as i32);
                #[expect(clippy::cast_precision_loss, reason = "below 1001")]
                let mut off_grid = || next(1001) as f64 / 1000.0 - 0.5;
                WindowVertex {
                    x,
                    y,
                    z: 0.5 + off_grid(),
                    unsnapped_x: f64::from(x) + off_grid(),
                    unsnapped_y: f64::from(y) + off_grid(),
                }
            });
            let Verdict::Draw(bounds, area) = classify(&v, CullMode::None, 256, 256) else {
                continue;
            };
            let Some(tile) = small_box_tile(&bounds, size) else {
                continue;
            };
            let mut early = Vec::new();
            find_early_fragments(&v, area, &bounds, 0, &mut early);
            let mut early: Vec<(usize, u64)> = early
                .iter()
                .map(|f| (usize::from(f.pixel), f.z.to_bits()))
                .collect();
            let (x0, y0, width, height) = size.tile_rect(tile as usize);
            let rect = TileRect {
                x0,
                y0,
                width,
                height,
            };
            let mut drawn = Recorder::default();
            rasterize(&v, area, &bounds, &rect, 0, &mut drawn);
            early.sort_unstable();
            drawn.0.sort_unstable();
            assert_eq!(early, drawn.0, "{v:?}");
            compared += usize::from(!early.is_empty());
        }
        assert!(compared > 2_000, "{compared}");
    }

    /// The scalar test of one- and two-pixel boxes agrees with the edge functions evaluated at
    /// each centre, for edges of every slope and boxes on and off the triangles.
    #[test]
    fn early_coverage_matches_the_small_box_test() {
        let mut random = crate::test_random::XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = move |range: i64| {
            #[expect(clippy::cast_possible_wrap, reason = "below 2^63")]
            let v = random.below(2 * range.unsigned_abs() + 1) as i64 - range;
            v
        };
        let mut covered = 0;
        for k in 0..50_000 {
            let range = if k % 2 == 0 { 256 * 6 } else { 256 * 3000 };
            let v: [WindowVertex; 3] = std::array::from_fn(|_| {
                #[expect(clippy::cast_possible_truncation, reason = "inside the guard band")]
                let (x, y) = (
                    (256 * 10 + next(range)) as i32,
                    (256 * 10 + next(range)) as i32,
                );
                WindowVertex {
                    x,
                    y,
                    z: 0.5,
                    unsnapped_x: f64::from(x),
                    unsnapped_y: f64::from(y),
                }
            });
            let area = (i64::from(v[1].x) - i64::from(v[0].x))
                * (i64::from(v[2].y) - i64::from(v[0].y))
                - (i64::from(v[2].x) - i64::from(v[0].x)) * (i64::from(v[1].y) - i64::from(v[0].y));
            if area == 0 {
                continue;
            }
            let e = edges(&v, area);
            let (i, j) = (10 + next(3), 10 + next(3));
            for (w, h) in [(1, 1), (2, 1), (1, 2)] {
                let b = PixelBox {
                    min_i: i,
                    max_i: i + w - 1,
                    min_j: j,
                    max_j: j + h - 1,
                };
                let centres = [(b.min_i, b.min_j), (b.max_i, b.max_j)];
                let inside = |(i, j)| e.iter().all(|edge| edge.at(i, j) >= 0);
                let exact = u32::from(inside(centres[0]))
                    | (u32::from(w * h == 2 && inside(centres[1])) << 1);
                assert_eq!(early_coverage(&e, &b), exact, "{v:?} {b:?}");
                covered += u32::from(exact != 0);
            }
        }
        assert!(covered > 1000, "{covered}");
    }
}
