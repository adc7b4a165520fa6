//! Building the tree: binned SAH splits, collapsed into 4-wide nodes as they are made.
//!
//! # Binary splits (binned surface-area heuristic)
//! Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", IEEE RT 2007: for a node
//! of `n` triangles, each triangle is represented by the centre of its bounding box; along each
//! axis where those centres spread, [`BINS`] equal bins over the centres' extent collect the
//! triangles' boxes and counts, and each of the `BINS − 1` planes between bins is scored by
//! `A(left)·b(n_left) + A(right)·b(n_right)` (A = surface area of the bins' union, `b(n) = ⌈n/4⌉`
//! the blocks of four triangles that a side's leaves need: the tree's leaves are tested four
//! triangles at a time, as in Embree's SAH for its four-triangle leaves). The best plane of the
//! three axes wins (the first on equal scores, axes in order x, y, z: determinism does not depend
//! on comparing floating-point ties any other way). Splitting costs
//! `NODE_COST + BLOCK_COST·score/A(node)`, a leaf `BLOCK_COST·b(n)`; a node becomes a leaf when
//! that is no dearer and `n ≤ MAX_LEAF_SIZE`, or when `n = 1`. (Until issue 15 the SAH counted
//! triangles, one test each; counting blocks makes fewer, fuller leaves — a third of the nodes on
//! the bunny and the dragon. No answer depends on the tree: see the `bvh` module.)
//!
//! Planes next to empty bins are not scored: a plane whose left neighbour bin is empty splits
//! the triangles as the plane before it does, with the same score to the bit, and the first of
//! equal scores wins, so only the first plane after each non-empty bin can win. This makes the
//! sweep cost `O(min(n, BINS))` per axis instead of `O(BINS)`, which is what small nodes (most
//! nodes) spend their time on; the chosen plane is the same.
//!
//! Nodes whose centres all coincide are split in the middle of their list (or made a leaf). From
//! depth [`SAH_DEPTH_LIMIT`] on, nodes are split at the median centre along their widest axis, so
//! the binary depth never exceeds [`MAX_DEPTH`] = `SAH_DEPTH_LIMIT + 32` (at most 2³² triangles)
//! whatever the input: the recursion, and the traversal stack, stay shallow.
//!
//! # Data
//! The build moves the triangles' boxes themselves, not indices into them, so that binning and
//! partitioning read memory in order: a [`Prim`] is its box as two four-lane vectors (x, y, z and
//! a spare lane holding the triangle's index), 64 bytes, on which a union or a centre is a couple
//! of AVX instructions. Partitioning a node gathers the bounds and centre bounds of both sides in
//! the same pass, so no pass is spent on a node's bounds. A thread's bins are reused from node to
//! node: a bit mask per axis records the non-empty bins, which lists the planes to score and the
//! bins to empty again. Binning a node of at least [`PARALLEL_BINNING`] triangles is split into
//! chunks of [`BINNING_CHUNK`] binned in parallel; bins combine by min, max and integer addition,
//! which are exact, so the bins — and the tree — are the same for any split and thread count. The
//! leaves' blocks are written in parallel, each in its place.
//!
//! # Collapse to four children
//! Each binary inner node takes the place of a 4-wide node: while it has fewer than four
//! children, its inner child of largest surface area (the first on ties) is replaced by that
//! child's two children. Nodes are stored in depth-first order, parent first. The collapse is done
//! top-down as the splits are made (a child is split when it is chosen for expansion or becomes a
//! child of its own 4-wide node), which gives the tree the binary build followed by a bottom-up
//! collapse would give, without building the binary tree.
//!
//! # Determinism
//! Every choice depends only on the input: binning (whatever its chunks), scoring and the in-place
//! partition are the same sequential definitions, and the children of a large 4-wide node are
//! built in parallel into their own node lists, appended in lane order. The resulting tree, and the
//! order of triangles in its leaves, is the same for any thread count.

use std::cell::RefCell;

use glam::DVec3;
use rayon::prelude::*;
use wide::f64x4;

use crate::triangle::{BLOCK, TriangleBlock, TriangleVertices};

/// Bins per axis in the binned SAH (at most 32: a node's non-empty bins are the bits of a `u32`).
const BINS: usize = 32;
const _: () = assert!(BINS <= 32);
/// The index of the last bin, as an f64.
#[expect(clippy::cast_precision_loss, reason = "BINS is 32")]
const LAST_BIN: f64 = (BINS - 1) as f64;
/// The largest leaf, in triangles.
const MAX_LEAF_SIZE: usize = 8;
/// SAH cost of visiting a 4-wide node (four box tests at once), relative to [`BLOCK_COST`].
const NODE_COST: f64 = 1.0;
/// SAH cost of testing a ray against one block of four triangles (four tests at once).
const BLOCK_COST: f64 = 1.0;
/// Binary depth below which the SAH chooses splits; deeper nodes split at the median.
const SAH_DEPTH_LIMIT: usize = 64;
/// The largest possible depth of the binary tree (and so of the 4-wide one): the SAH part, then
/// at most 32 median halvings of at most 2³² triangles.
pub(crate) const MAX_DEPTH: usize = SAH_DEPTH_LIMIT + 32;
/// 4-wide nodes (and binary splits) of at least this many triangles build their children in
/// parallel; the tree is the sequential build's whatever the value. Measured (docs/benchmarks.md,
/// "The BVH build's parallel threshold"): against 4 096, which built a mesh of a few thousand
/// triangles on one thread, 1 024 builds it faster on two — a third in criterion's back-to-back
/// loop, less and noisily from a pool whose second worker sleeps — for 3 % more on the bunny.
const PARALLEL_THRESHOLD: usize = 1024;
/// Nodes of at least this many triangles are binned in parallel chunks.
const PARALLEL_BINNING: usize = 1 << 15;
/// Triangles per parallel work item when binning a large node.
const BINNING_CHUNK: usize = 1 << 13;

/// Four f64 lanes: x, y, z and a spare lane that pads the vector to 256 bits, so that box
/// operations compile to single AVX instructions. The spare lane is not geometry: whatever it
/// holds, nothing reads it as a coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lanes(pub(crate) [f64; 4]);

impl Lanes {
    fn splat(value: f64) -> Self {
        Self([value; 4])
    }

    /// Lane by lane `a < b ? a : b`: for the finite coordinates of boxes the same values as
    /// `f64::min` (up to the sign of a zero, which no comparison sees), in one instruction.
    ///
    /// Written as `wide`'s `fast_min` (x86's `minpd`, which is defined as that select), not as the
    /// select itself: LLVM turns a select between a bin's stored box and a triangle's box, stored
    /// back, into a masked store (`vmaskmovpd`), slow on AMD's Zen 1: the whole build took a third
    /// longer there (docs/benchmarks.md, "Masked stores").
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Self(
            f64x4::from(self.0)
                .fast_min(f64x4::from(other.0))
                .to_array(),
        )
    }

    /// Lane by lane `a > b ? a : b` (see [`Lanes::min`]; `maxpd`).
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Self(
            f64x4::from(self.0)
                .fast_max(f64x4::from(other.0))
                .to_array(),
        )
    }

    /// Lanes 0 to 2 as a point.
    fn point(self) -> DVec3 {
        DVec3::new(self.0[0], self.0[1], self.0[2])
    }

    #[inline(always)]
    fn add(self, other: Self) -> Self {
        Self(std::array::from_fn(|k| self.0[k] + other.0[k]))
    }

    #[inline(always)]
    fn sub(self, other: Self) -> Self {
        Self(std::array::from_fn(|k| self.0[k] - other.0[k]))
    }

    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        Self(std::array::from_fn(|k| self.0[k] * other.0[k]))
    }
}

/// An axis-aligned box (coordinates in lanes 0 to 2); empty when `lo > hi` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Aabb {
    pub(crate) lo: Lanes,
    pub(crate) hi: Lanes,
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    const EMPTY: Self = Self {
        lo: Lanes([f64::INFINITY; 4]),
        hi: Lanes([f64::NEG_INFINITY; 4]),
    };

    #[inline(always)]
    fn union(self, other: Self) -> Self {
        Self {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    #[inline(always)]
    fn grow(&mut self, p: Lanes) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    /// Half the surface area (the SAH only compares ratios); 0 for an empty box.
    fn half_area(&self) -> f64 {
        let d = self.hi.sub(self.lo).max(Lanes::splat(0.0)).0;
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }

    /// The centre, `(lo + hi)·0.5`.
    #[inline(always)]
    fn center(&self) -> Lanes {
        self.lo.add(self.hi).mul(Lanes::splat(0.5))
    }
}

/// A triangle as the build sees it: its bounding box, whose spare lanes hold the triangle's index
/// in the mesh (exactly: every `u32` is an f64), so that one triangle fills 64 bytes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Prim {
    bounds: Aabb,
}

impl Prim {
    pub(crate) fn new(lo: DVec3, hi: DVec3, id: u32) -> Self {
        let id = f64::from(id);
        Self {
            bounds: Aabb {
                lo: Lanes([lo.x, lo.y, lo.z, id]),
                hi: Lanes([hi.x, hi.y, hi.z, id]),
            },
        }
    }

    /// The triangle's index in the mesh.
    pub(crate) fn id(&self) -> u32 {
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "the spare lane holds a u32 exactly"
        )]
        let id = self.bounds.lo.0[3] as u32;
        id
    }
}

/// What a node's split and leaf decisions read of its triangles: their bounds and the bounds of
/// their boxes' centres.
#[derive(Clone, Copy)]
struct Extent {
    bounds: Aabb,
    centers: Aabb,
}

impl Extent {
    const EMPTY: Self = Self {
        bounds: Aabb::EMPTY,
        centers: Aabb::EMPTY,
    };

    fn add(&mut self, prim: &Prim) {
        self.bounds = self.bounds.union(prim.bounds);
        self.centers.grow(prim.bounds.center());
    }

    fn union(self, other: Self) -> Self {
        Self {
            bounds: self.bounds.union(other.bounds),
            centers: self.centers.union(other.centers),
        }
    }

    fn of(prims: &[Prim]) -> Self {
        let mut extent = Self::EMPTY;
        for prim in prims {
            extent.add(prim);
        }
        extent
    }
}

/// How a node's triangles are divided between its two children.
#[derive(Clone, Copy)]
enum Split {
    /// By bin along `axis`: bins `< bin` go left (the bins of [`Binning::best_split`]).
    Binned {
        axis: usize,
        lo: f64,
        scale: f64,
        bin: usize,
    },
    /// At the median centre along the widest centre axis ([`median_split`]).
    Median,
    /// In the middle of the list (all centres coincide).
    Middle,
}

/// A contiguous range of the build order with its extent and binary depth, and what becomes of it:
/// split (`split` is `Some`) or a leaf.
struct Range<'a> {
    prims: &'a mut [Prim],
    start: usize,
    extent: Extent,
    depth: usize,
    split: Option<Split>,
}

impl<'a> Range<'a> {
    fn new(prims: &'a mut [Prim], start: usize, extent: Extent, depth: usize) -> Self {
        let split = decide(prims, &extent, depth);
        Self {
            prims,
            start,
            extent,
            depth,
            split,
        }
    }

    /// Divides the range as decided: its two children, each with its own decision.
    fn divide(self) -> [Range<'a>; 2] {
        let split = self.split.expect("an inner range");
        let n = self.prims.len();
        let (mid, left, right) = match split {
            Split::Binned {
                axis,
                lo,
                scale,
                bin,
            } => partition(self.prims, |b| bin_of(b.center().0[axis], lo, scale) < bin),
            Split::Median => {
                let mid = median_split(self.prims, &self.extent.centers);
                let (l, r) = self.prims.split_at(mid);
                (mid, Extent::of(l), Extent::of(r))
            }
            Split::Middle => {
                let mid = n / 2;
                let (l, r) = self.prims.split_at(mid);
                (mid, Extent::of(l), Extent::of(r))
            }
        };
        let (l, r) = self.prims.split_at_mut(mid);
        let depth = self.depth + 1;
        if n >= PARALLEL_THRESHOLD {
            let (l, r) = rayon::join(
                || Range::new(l, self.start, left, depth),
                || Range::new(r, self.start + mid, right, depth),
            );
            [l, r]
        } else {
            [
                Range::new(l, self.start, left, depth),
                Range::new(r, self.start + mid, right, depth),
            ]
        }
    }
}

/// The bin of a centre coordinate `c` along an axis whose centres start at `lo`, with
/// `scale = BINS/extent`: `⌊(c − lo)·scale⌋`, at most `BINS − 1` ([`bin_index`] of the product).
#[inline(always)]
fn bin_of(c: f64, lo: f64, scale: f64) -> usize {
    bin_index((c - lo) * scale)
}

/// `⌊t⌋`, at most `BINS − 1`, for `t = (c − lo)·scale` (in `[0, BINS]` up to rounding; NaN, from
/// an axis without extent, gives 0).
#[inline(always)]
fn bin_index(t: f64) -> usize {
    // Clamped as floats first (NaN to 0), so that the conversion needs no saturation.
    let t = if t < LAST_BIN { t } else { LAST_BIN };
    let t = if t > 0.0 { t } else { 0.0 };
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "t lies in [0, BINS − 1]"
    )]
    let bin = t as u32 as usize;
    bin
}

/// [`bin_index`] of the first three lanes.
#[inline(always)]
fn bin_indices(t: Lanes) -> [usize; 3] {
    [bin_index(t.0[0]), bin_index(t.0[1]), bin_index(t.0[2])]
}

/// Per axis and bin, the union of the boxes of the triangles whose centres fall in it, and their
/// number (the empty box and 0 for an empty bin).
#[derive(Clone)]
struct Bins {
    boxes: [[Aabb; BINS]; 3],
    counts: [[u32; BINS]; 3],
    /// Per axis, bit `k` set when bin `k` is not empty.
    filled: [u32; 3],
}

thread_local! {
    /// The bins of the nodes a thread bins alone, reused from node to node (no work is spawned
    /// while they are borrowed).
    static SCRATCH: RefCell<Bins> = const { RefCell::new(Bins::EMPTY) };
}

impl Bins {
    const EMPTY: Self = Self {
        boxes: [[Aabb::EMPTY; BINS]; 3],
        counts: [[0; BINS]; 3],
        filled: [0; 3],
    };

    /// Empties the bins that are not empty.
    fn clear(&mut self) {
        for axis in 0..3 {
            for k in bits(self.filled[axis]) {
                self.boxes[axis][k] = Aabb::EMPTY;
                self.counts[axis][k] = 0;
            }
        }
        self.filled = [0; 3];
    }

    #[inline(always)]
    fn add(&mut self, axis: usize, k: usize, bounds: Aabb, count: u32) {
        self.boxes[axis][k] = self.boxes[axis][k].union(bounds);
        self.counts[axis][k] += count;
        self.filled[axis] |= 1 << k;
    }

    /// Both bin sets together (exact: min, max and integer addition).
    fn merge(mut self, other: &Self) -> Self {
        for axis in 0..3 {
            for k in bits(other.filled[axis]) {
                self.add(axis, k, other.boxes[axis][k], other.counts[axis][k]);
            }
        }
        self
    }
}

/// The positions of the set bits of `mask`, in increasing order.
fn bits(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            k
        })
    })
}

/// The binning of one node: the axes along which its centres spread, and per axis the origin and
/// scale of the bins.
struct Binning {
    axes: [usize; 3],
    count: usize,
    lo: Lanes,
    scale: Lanes,
}

impl Binning {
    fn new(centers: &Aabb) -> Self {
        let extent = centers.hi.sub(centers.lo).0;
        let mut axes = [0; 3];
        let mut count = 0;
        for (axis, &e) in extent[..3].iter().enumerate() {
            if e > 0.0 {
                axes[count] = axis;
                count += 1;
            }
        }
        #[expect(clippy::cast_precision_loss, reason = "BINS is 32")]
        let scale = Lanes(extent.map(|e| BINS as f64 / e));
        Self {
            axes,
            count,
            lo: centers.lo,
            scale,
        }
    }

    fn axes(&self) -> &[usize] {
        &self.axes[..self.count]
    }

    /// Adds `prims` to cleared `bins`. Every axis is binned (an axis without extent puts every
    /// triangle in its bin 0), so that the loop has no branches; only [`Binning::axes`] are scored.
    fn bin(&self, prims: &[Prim], bins: &mut Bins) {
        for prim in prims {
            let k = bin_indices(prim.bounds.center().sub(self.lo).mul(self.scale));
            for (axis, &k) in k.iter().enumerate() {
                bins.add(axis, k, prim.bounds, 1);
            }
        }
    }

    /// The best binned split of `bins`: `(score, axis, first bin of the right side)`.
    fn best_split(&self, bins: &Bins) -> Option<(f64, usize, usize)> {
        let mut best: Option<(f64, usize, usize)> = None;
        for &axis in self.axes() {
            let (boxes, counts) = (&bins.boxes[axis], &bins.counts[axis]);
            // The non-empty bins, in order: only the plane just after each can win (module docs).
            let mut filled = [0; BINS];
            let mut count = 0;
            for k in bits(bins.filled[axis]) {
                filled[count] = k;
                count += 1;
            }
            let filled = &filled[..count];
            // Right-to-left sweep: area and count of the filled bins j.. for every j ≥ 1.
            let mut right = [(0.0, 0_u32); BINS];
            let mut acc = (Aabb::EMPTY, 0);
            for j in (1..count).rev() {
                let k = filled[j];
                acc = (acc.0.union(boxes[k]), acc.1 + counts[k]);
                right[j] = (acc.0.half_area(), acc.1);
            }
            let mut left = (Aabb::EMPTY, 0);
            for j in 1..count {
                let k = filled[j - 1];
                left = (left.0.union(boxes[k]), left.1 + counts[k]);
                let (right_area, right_count) = right[j];
                let score = left.0.half_area() * blocks(left.1) + right_area * blocks(right_count);
                if best.is_none_or(|(b, _, _)| score < b) {
                    best = Some((score, axis, k + 1));
                }
            }
        }
        best
    }
}

/// The number of [`TriangleBlock`]s that hold `n` triangles, as the SAH counts them.
fn blocks(n: u32) -> f64 {
    #[expect(clippy::cast_possible_truncation, reason = "BLOCK is 4")]
    const PER_BLOCK: u32 = BLOCK as u32;
    f64::from(n.div_ceil(PER_BLOCK))
}

/// What becomes of a range of `prims` with this extent at this binary depth: `None` for a leaf.
fn decide(prims: &[Prim], extent: &Extent, depth: usize) -> Option<Split> {
    let n = prims.len();
    if n == 1 {
        return None;
    }
    if depth >= SAH_DEPTH_LIMIT {
        return (n > MAX_LEAF_SIZE).then_some(Split::Median);
    }
    let binning = Binning::new(&extent.centers);
    if binning.count == 0 {
        // All centres coincide: no plane separates them.
        return (n > MAX_LEAF_SIZE).then_some(Split::Middle);
    }
    let best = if n >= PARALLEL_BINNING {
        let bins = prims
            .par_chunks(BINNING_CHUNK)
            .map(|chunk| {
                let mut bins = Bins::EMPTY;
                binning.bin(chunk, &mut bins);
                bins
            })
            .reduce(|| Bins::EMPTY, |a, b| a.merge(&b));
        binning.best_split(&bins)
    } else {
        SCRATCH.with_borrow_mut(|bins| {
            bins.clear();
            binning.bin(prims, bins);
            binning.best_split(bins)
        })
    };
    let (score, axis, bin) = best.expect("centres spread on an axis");
    let leaf_cost = BLOCK_COST * blocks(u32::try_from(n).expect("triangle count fits u32"));
    let split_cost = NODE_COST + BLOCK_COST * score / extent.bounds.half_area();
    if n <= MAX_LEAF_SIZE && leaf_cost <= split_cost {
        return None;
    }
    Some(Split::Binned {
        axis,
        lo: binning.lo.0[axis],
        scale: binning.scale.0[axis],
        bin,
    })
}

/// Moves the entries for which `left` holds to the front (order within each side is the
/// deterministic result of the swaps); returns how many there are, and the extents of both sides.
fn partition(prims: &mut [Prim], left: impl Fn(&Aabb) -> bool) -> (usize, Extent, Extent) {
    let mut left_extent = Extent::EMPTY;
    let mut right_extent = Extent::EMPTY;
    let mut first = 0;
    let mut last = prims.len();
    // Every entry is examined once: kept at `first`, or swapped to `last − 1`.
    while first < last {
        let prim = prims[first];
        if left(&prim.bounds) {
            left_extent.add(&prim);
            first += 1;
        } else {
            right_extent.add(&prim);
            last -= 1;
            prims.swap(first, last);
        }
    }
    (first, left_extent, right_extent)
}

/// Sorts the median split of `prims` along the widest centre axis: entries before `len/2` have
/// centres ≤ those after (ties by triangle index). Returns the split position.
fn median_split(prims: &mut [Prim], centers: &Aabb) -> usize {
    let [x, y, z, _] = centers.hi.sub(centers.lo).0;
    let axis = if x >= y && x >= z {
        0
    } else if y >= z {
        1
    } else {
        2
    };
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |a, b| {
        a.bounds.center().0[axis]
            .total_cmp(&b.bounds.center().0[axis])
            .then(a.id().cmp(&b.id()))
    });
    mid
}

/// A 4-wide node: the boxes of up to four children, lane by lane, and what each child is.
///
/// A lane is an inner node (`count == 0`, `child` = its node index), a leaf (`count > 0`
/// triangles from `child` on in leaf order), or unused (`count == 0`, `child == u32::MAX`, and an
/// empty box `lo = +∞, hi = −∞`, which no ray enters).
///
/// The boxes are stored in f32, each bound rounded outward ([`round_down`], [`round_up`]), so a
/// node is 128 bytes, two cache lines, where f64 bounds made it 224: random rays spend most of
/// their time waiting for nodes (docs/benchmarks.md, "f32 node boxes"). A stored box contains the
/// build's f64 box, and the box test is monotone in the bounds (the `bvh` module), so a ray enters
/// every box it would have entered: answers do not change, only a few more boxes are visited.
#[derive(Clone, Debug, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Node4 {
    /// Lower bounds per axis, per lane, rounded down.
    lo: [[f32; 4]; 3],
    /// Upper bounds per axis, per lane, rounded up.
    hi: [[f32; 4]; 3],
    /// Node index or first triangle.
    pub(crate) child: [u32; 4],
    /// Triangle count of a leaf lane; 0 otherwise.
    pub(crate) count: [u32; 4],
}

/// The largest f32 at most `x` (−∞ below f32's range).
fn round_down(x: f64) -> f32 {
    #[expect(clippy::cast_possible_truncation, reason = "rounded outward next")]
    let near = x as f32;
    if f64::from(near) > x {
        near.next_down()
    } else {
        near
    }
}

/// The smallest f32 at least `x` (+∞ above f32's range).
fn round_up(x: f64) -> f32 {
    #[expect(clippy::cast_possible_truncation, reason = "rounded outward next")]
    let near = x as f32;
    if f64::from(near) < x {
        near.next_up()
    } else {
        near
    }
}

impl Node4 {
    /// The node with four unused lanes.
    pub(crate) const EMPTY: Self = Self {
        lo: [[f32::INFINITY; 4]; 3],
        hi: [[f32::NEG_INFINITY; 4]; 3],
        child: [u32::MAX; 4],
        count: [0; 4],
    };

    /// Sets `lane` to the box `bounds`, rounded outward, and the leaf or node `child` with
    /// `count` triangles.
    pub(crate) fn set(&mut self, lane: usize, bounds: &Aabb, child: usize, count: usize) {
        for axis in 0..3 {
            self.lo[axis][lane] = round_down(bounds.lo.0[axis]);
            self.hi[axis][lane] = round_up(bounds.hi.0[axis]);
        }
        self.child[lane] = u32::try_from(child).expect("index fits u32");
        self.count[lane] = u32::try_from(count).expect("leaf size fits u32");
    }

    /// The four lanes' lower bounds on `axis` (exactly the stored f32 values).
    #[inline(always)]
    pub(crate) fn lower(&self, axis: usize) -> [f64; 4] {
        self.lo[axis].map(f64::from)
    }

    /// The four lanes' upper bounds on `axis`.
    #[inline(always)]
    pub(crate) fn upper(&self, axis: usize) -> [f64; 4] {
        self.hi[axis].map(f64::from)
    }
}

/// The 4-wide tree: nodes in depth-first order (root first), its depth, and the exact bounding
/// box `(lo, hi)` of the triangles (`None` without triangles).
pub(crate) struct Tree {
    pub(crate) nodes: Vec<Node4>,
    pub(crate) depth: usize,
    pub(crate) bounds: Option<(DVec3, DVec3)>,
}

/// Builds the tree over `prims`, permuting them into leaf order.
pub(crate) fn build(prims: &mut [Prim]) -> Tree {
    if prims.is_empty() {
        return Tree {
            nodes: Vec::new(),
            depth: 0,
            bounds: None,
        };
    }
    let extent = prims
        .par_chunks(BINNING_CHUNK)
        .map(Extent::of)
        .reduce(|| Extent::EMPTY, Extent::union);
    let root = Range::new(prims, 0, extent, 0);
    let bounds = Some((root.extent.bounds.lo.point(), root.extent.bounds.hi.point()));
    let mut nodes = Vec::new();
    let depth = if root.split.is_some() {
        subtree(root, &mut nodes)
    } else {
        let mut node = Node4::EMPTY;
        node.set(0, &root.extent.bounds, 0, root.prims.len());
        nodes.push(node);
        1
    };
    Tree {
        nodes,
        depth,
        bounds,
    }
}

/// Appends the 4-wide subtree of an inner range to `nodes` (its root first, at `nodes.len()`);
/// returns its depth in 4-wide nodes.
fn subtree(range: Range<'_>, nodes: &mut Vec<Node4>) -> usize {
    let n = range.prims.len();
    let mut lanes: Vec<Range<'_>> = Vec::with_capacity(4);
    lanes.extend(range.divide());
    while lanes.len() < 4 {
        let mut widest: Option<(usize, f64)> = None;
        for (k, lane) in lanes.iter().enumerate() {
            if lane.split.is_some() {
                let area = lane.extent.bounds.half_area();
                if widest.is_none_or(|(_, a)| area > a) {
                    widest = Some((k, area));
                }
            }
        }
        let Some((k, _)) = widest else {
            break;
        };
        let divided = lanes.remove(k).divide();
        lanes.splice(k..k, divided);
    }
    let index = nodes.len();
    let mut node = Node4::EMPTY;
    for (lane, range) in lanes.iter().enumerate() {
        if range.split.is_none() {
            node.set(lane, &range.extent.bounds, range.start, range.prims.len());
        }
    }
    nodes.push(node);
    let mut depth = 0;
    if n >= PARALLEL_THRESHOLD {
        // Each inner child's subtree in a list of its own (indices relative to its root),
        // appended in lane order: the layout of the sequential build.
        let built: Vec<(usize, Aabb, Vec<Node4>, usize)> = lanes
            .into_par_iter()
            .enumerate()
            .filter(|(_, range)| range.split.is_some())
            .map(|(lane, range)| {
                let bounds = range.extent.bounds;
                let mut own = Vec::new();
                let depth = subtree(range, &mut own);
                (lane, bounds, own, depth)
            })
            .collect();
        for (lane, bounds, own, own_depth) in built {
            let base = nodes.len();
            nodes[index].set(lane, &bounds, base, 0);
            let offset = u32::try_from(base).expect("node count fits u32");
            nodes.extend(own.into_iter().map(|mut node| {
                for k in 0..4 {
                    if node.count[k] == 0 && node.child[k] != u32::MAX {
                        node.child[k] += offset;
                    }
                }
                node
            }));
            depth = depth.max(own_depth);
        }
    } else {
        for (lane, range) in lanes.into_iter().enumerate() {
            if range.split.is_some() {
                let (bounds, child) = (range.extent.bounds, nodes.len());
                nodes[index].set(lane, &bounds, child, 0);
                depth = depth.max(subtree(range, nodes));
            }
        }
    }
    depth + 1
}

/// Stores the leaves' triangles in blocks of [`BLOCK`], in the order of the leaves in `nodes`
/// (depth first, lanes in order), and points each leaf lane at its first block. `prims` is the
/// build's leaf order; `vertices` gives a triangle's vertices from its index.
pub(crate) fn leaf_blocks(
    nodes: &mut [Node4],
    prims: &[Prim],
    vertices: impl Fn(u32) -> TriangleVertices + Sync,
) -> Vec<TriangleBlock> {
    // (first triangle in `prims`, triangle count, block within the leaf) of every block.
    let mut work = Vec::new();
    for node in nodes.iter_mut() {
        for lane in 0..4 {
            let count = node.count[lane] as usize;
            if count > 0 {
                let start = node.child[lane] as usize;
                node.child[lane] = u32::try_from(work.len()).expect("block count fits u32");
                work.extend((0..count.div_ceil(BLOCK)).map(|b| (start, count, b)));
            }
        }
    }
    let mut blocks = Vec::new();
    work.par_iter()
        .map(|&(start, count, b)| {
            // Spare lanes repeat the leaf's last triangle.
            let slot = |k: usize| &prims[start + (b * BLOCK + k).min(count - 1)];
            let triangles: [TriangleVertices; BLOCK] =
                std::array::from_fn(|k| vertices(slot(k).id()));
            TriangleBlock {
                p: std::array::from_fn(|c| std::array::from_fn(|k| triangles[k][c])),
                id: std::array::from_fn(|k| slot(k).id()),
            }
        })
        .collect_into_vec(&mut blocks);
    blocks
}

#[cfg(test)]
mod tests {
    use super::{round_down, round_up};

    /// The f32 bounds are the nearest ones outward: exact values stay, others move to the
    /// neighbouring f32 on the outer side, and beyond f32's range a bound becomes infinite.
    #[test]
    fn node_bounds_round_outward_to_the_nearest_f32() {
        let third = 1.0 / 3.0;
        let (down, up) = (round_down(third), round_up(third));
        assert!(f64::from(down) < third && third < f64::from(up));
        assert_eq!(down.next_up(), up);
        for exact in [
            0.0,
            -0.0,
            1.5,
            -(2f64.powi(-140)),
            f64::from(f32::MAX),
            f64::INFINITY,
        ] {
            assert_eq!(f64::from(round_down(exact)), exact);
            assert_eq!(f64::from(round_up(exact)), exact);
        }
        // The trace crate accepts coordinates up to 2^200, past f32's largest value.
        let huge = 2f64.powi(200);
        assert_eq!(round_down(huge), f32::MAX);
        assert_eq!(round_up(huge), f32::INFINITY);
        assert_eq!(round_down(-huge), f32::NEG_INFINITY);
        assert_eq!(round_up(-huge), -f32::MAX);
        // And down to tiny ones, below f32's smallest subnormal.
        let tiny = 2f64.powi(-200);
        assert_eq!(round_down(tiny), 0.0);
        assert_eq!(round_up(tiny), f32::from_bits(1));
        assert_eq!(round_down(-tiny), -f32::from_bits(1));
        assert!(round_up(-tiny) == 0.0);
    }
}
