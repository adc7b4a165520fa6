//! Binning: each triangle of a chunk of the submission listed under the tiles its pixel box
//! touches, in submission order; clipped pieces and the pixels of tiny triangles kept beside the
//! lists (see the `pipeline` module for where binning stands in a draw).

use glam::{DMat4, DVec3};

use crate::clip::{ClippedTriangle, clip_triangle};
use crate::error::RasterError;
use crate::kernel::for_each_in_mask;
use crate::stats::DrawStats;
use crate::tile::{TILE_SHIFT, TILE_STRIDE, TargetSize};
use crate::triangle::{CullMode, DepthPlane, Edge, PixelBox, Verdict, classify, edges};
use crate::vertex::{Viewport, WindowVertex, code, transform};

/// Triangles per parallel work item of binning, chosen as the vertex stage's chunk (17 items for the
/// bunny). Any size gives the same output.
pub(crate) const TRIANGLE_CHUNK: usize = 4096;
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
/// The most triangles a draw takes: their ids must fit an entry's index part.
pub(crate) const MAX_TRIANGLES: usize = INDEX_MASK as usize;
/// Triangles whose pixel box holds at most this many pixels, all in one tile, are rasterized while
/// binning (see [`EarlyFragment`]). Measured on the benchmark views (2 threads, best of 5 runs,
/// against no early path): 2 takes 9% off the dragon's eye pass and costs nothing elsewhere; 8
/// takes 19% off it but adds 8% to the bunny's eye pass and 5% to the dragon's light pass — the
/// early test's data-dependent branches outweigh the setup it saves once boxes cover a few pixels.
const EARLY: i64 = 2;
// A box of at most EARLY pixels is one or two pixels, as `early_coverage` requires.
const _: () = assert!(EARLY <= 2);

/// A covered pixel of a tiny triangle, found while binning.
///
/// A triangle whose pixel box holds at most [`EARLY`] pixels, all in one tile, is tested pixel by
/// pixel during binning (by the same edge test and depth as the tile pass), and only the pixels it
/// covers are binned — none at all for the many that cover no centre. Dense meshes are mostly such
/// triangles, and this spares the tile pass fetching and setting each of them up again.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EarlyFragment {
    /// Window depth, unclamped, as the tile pass would compute it.
    pub(crate) z: f64,
    /// The triangle it belongs to.
    pub(crate) triangle: u32,
    /// Index within the tile's storage.
    pub(crate) pixel: u16,
    /// Whether it is the last of its triangle's run.
    last: bool,
}

/// The triangles binned to tiles by one chunk of the submission. Kept by the [`crate::Rasterizer`] and
/// refilled by every draw, so a sequence of draws allocates its buffers once.
#[derive(Debug, Default)]
pub(crate) struct ChunkBins {
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

/// What a tile draws: a kind and an index ([`EntryKind`]); for a mesh triangle also
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
pub(crate) struct Entry {
    /// The kind in the two top bits, the index below them.
    packed: u32,
    /// The mesh triangle's vertex indices, or [`PIECE_CORNERS`] for a clipped piece; zero for a run
    /// of early fragments.
    corners: [u32; 3],
}

/// What a bin entry stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum EntryKind {
    /// A triangle of the mesh, by its id.
    Triangle(u32),
    /// A run of the chunk's early fragments, by the index of its first ([`ChunkBins::run`]).
    Fragments(usize),
    /// A clipped piece of the chunk, by its index ([`ChunkBins::piece`]).
    Piece(usize),
}

impl Entry {
    /// A triangle of the mesh with id `id` (below [`MAX_TRIANGLES`]) and vertex indices `corners`.
    fn triangle(id: u32, corners: [u32; 3]) -> Self {
        debug_assert!(id <= INDEX_MASK);
        Self {
            packed: TRIANGLE | id,
            corners,
        }
    }

    /// The run of early fragments starting at the chunk's `first`.
    fn fragments(first: usize) -> Self {
        Self {
            packed: FRAGMENTS | index_part(first),
            corners: [0; 3],
        }
    }

    /// The chunk's clipped piece `index`.
    fn piece(index: usize) -> Self {
        Self {
            packed: CLIPPED | index_part(index),
            corners: PIECE_CORNERS,
        }
    }

    /// What the entry stands for.
    #[inline(always)]
    pub(crate) fn kind(self) -> EntryKind {
        let index = self.packed & INDEX_MASK;
        match self.packed & !INDEX_MASK {
            TRIANGLE => EntryKind::Triangle(index),
            FRAGMENTS => EntryKind::Fragments(index as usize),
            _ => EntryKind::Piece(index as usize),
        }
    }

    /// The indices of its three vertices in the array its kind draws from: the mesh's window
    /// vertices for a triangle, the piece's own for a piece (unused for fragments).
    #[inline(always)]
    pub(crate) fn corners(self) -> [u32; 3] {
        self.corners
    }
}

/// An index within a chunk (of its pieces or early fragments, far fewer than `2^30`) as an entry's
/// index part.
fn index_part(index: usize) -> u32 {
    #[expect(
        clippy::cast_possible_truncation,
        reason = "a chunk's pieces and fragments are far fewer than 2^30"
    )]
    let part = index as u32;
    debug_assert!(part <= INDEX_MASK);
    part
}

/// What binning needs of the draw, the same for every chunk.
pub(crate) struct BinContext<'a> {
    pub(crate) positions: &'a [DVec3],
    pub(crate) window: &'a [WindowVertex],
    pub(crate) codes: &'a [u8],
    pub(crate) clip_from_world: &'a DMat4,
    pub(crate) viewport: Viewport,
    pub(crate) size: TargetSize,
    pub(crate) cull: CullMode,
}

impl ChunkBins {
    /// Bins triangles `first..first + triangles.len()` of the draw, replacing what the chunk held.
    pub(crate) fn refill(
        &mut self,
        first: usize,
        triangles: &[[u32; 3]],
        context: &BinContext<'_>,
    ) {
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
                reason = "ids are below MAX_TRIANGLES, checked per draw"
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
                                listed.push((tile, Entry::fragments(first)));
                            }
                        } else {
                            list_tiles(&bounds, Entry::triangle(entry, *t), size, listed);
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
                        list_tiles(&bounds, Entry::piece(p), size, listed);
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

    /// The entries binned to tile `tile`, in submission order.
    #[inline(always)]
    pub(crate) fn entries(&self, tile: usize) -> &[Entry] {
        &self.entries[self.starts[tile] as usize..self.starts[tile + 1] as usize]
    }

    /// How many entries each tile holds, tile by tile.
    pub(crate) fn entry_counts(&self) -> impl Iterator<Item = u32> + '_ {
        self.starts.windows(2).map(|range| range[1] - range[0])
    }

    /// The run of early fragments that starts at `first` (one triangle's covered pixels).
    #[inline(always)]
    pub(crate) fn run(&self, first: usize) -> impl Iterator<Item = &EarlyFragment> {
        let run = &self.fragments[first..];
        let length = run
            .iter()
            .position(|f| f.last)
            .map_or(run.len(), |last| last + 1);
        run[..length].iter()
    }

    /// Clipped piece `index`.
    #[inline(always)]
    pub(crate) fn piece(&self, index: usize) -> &ClippedTriangle {
        &self.pieces[index]
    }

    /// What binning counted of the chunk's triangles (all but the fragments).
    pub(crate) fn stats(&self) -> &DrawStats {
        &self.stats
    }

    /// The chunk's first bad input, if any.
    pub(crate) fn error(&self) -> Option<&RasterError> {
        self.error.as_ref()
    }
}

/// The tile holding all of a pixel box of at most [`EARLY`] pixels, if there is one.
fn small_box_tile(b: &PixelBox, size: TargetSize) -> Option<u32> {
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
    b: &PixelBox,
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
fn early_coverage(edges: &[Edge; 3], b: &PixelBox) -> u32 {
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
fn list_tiles(b: &PixelBox, entry: Entry, size: TargetSize, out: &mut Vec<(u32, Entry)>) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::{Recorder, rasterize};

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
            let rect = size.tile_rect(tile as usize);
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
