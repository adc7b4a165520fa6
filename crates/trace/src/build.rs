//! Building the tree: a binary tree by binned SAH, collapsed into a 4-wide tree.
//!
//! # Binary build (binned surface-area heuristic)
//! Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", IEEE RT 2007: for a node
//! of `n` triangles, each triangle is represented by the centre of its bounding box; along each
//! axis where those centres spread, [`BINS`] equal bins over the centres' extent collect the
//! triangles' boxes and counts, and each of the `BINS − 1` planes between bins is scored by
//! `A(left)·n_left + A(right)·n_right` (A = surface area of the bins' union). The best plane of
//! the three axes wins (the first on equal scores, axes in order x, y, z: determinism does not
//! depend on comparing floating-point ties any other way). Splitting costs
//! `NODE_COST + TRIANGLE_COST·score/A(node)`, a leaf `TRIANGLE_COST·n`; a node becomes a leaf
//! when that is no dearer and `n ≤ MAX_LEAF_SIZE`, or when `n = 1`.
//!
//! Nodes whose centres all coincide are split in the middle of their list (or made a leaf). From
//! depth [`SAH_DEPTH_LIMIT`] on, nodes are split at the median centre along their widest axis, so
//! the binary depth never exceeds [`MAX_DEPTH`] = `SAH_DEPTH_LIMIT + 32` (at most 2³² triangles)
//! whatever the input: the recursion, and the traversal stack, stay shallow.
//!
//! # Determinism
//! Every choice depends only on the input: binning, scoring and the in-place partition run
//! sequentially per node, and the two halves of a large node are built by `rayon::join` into
//! disjoint parts of the index list. The resulting tree, and the order of triangles in its leaves,
//! is the same for any thread count.
//!
//! # Collapse to four children
//! Each binary inner node takes the place of a 4-wide node: while it has fewer than four
//! children, its inner child of largest surface area (the first on ties) is replaced by that
//! child's two children. Nodes are stored in depth-first order, parent first.

use glam::DVec3;

/// Bins per axis in the binned SAH.
const BINS: usize = 32;
/// The largest leaf, in triangles.
const MAX_LEAF_SIZE: usize = 8;
/// SAH cost of visiting a 4-wide node's box, relative to [`TRIANGLE_COST`].
const NODE_COST: f64 = 1.0;
/// SAH cost of one ray–triangle test.
const TRIANGLE_COST: f64 = 1.0;
/// Binary depth below which the SAH chooses splits; deeper nodes split at the median.
const SAH_DEPTH_LIMIT: usize = 64;
/// The largest possible depth of the binary tree (and so of the 4-wide one): the SAH part, then
/// at most 32 median halvings of at most 2³² triangles.
pub(crate) const MAX_DEPTH: usize = SAH_DEPTH_LIMIT + 32;
/// Nodes of at least this many triangles build their two halves in parallel.
const PARALLEL_THRESHOLD: usize = 4096;

/// An axis-aligned box; empty when `lo > hi` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Aabb {
    pub(crate) lo: DVec3,
    pub(crate) hi: DVec3,
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    pub(crate) const EMPTY: Self = Self {
        lo: DVec3::INFINITY,
        hi: DVec3::NEG_INFINITY,
    };

    pub(crate) fn union(self, other: Self) -> Self {
        Self {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    fn grow(&mut self, p: DVec3) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    /// Half the surface area (the SAH only compares ratios); 0 for an empty box.
    pub(crate) fn half_area(&self) -> f64 {
        let d = (self.hi - self.lo).max(DVec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    fn center(&self) -> DVec3 {
        (self.lo + self.hi) * 0.5
    }
}

/// A node of the binary tree under construction.
pub(crate) enum BuildNode {
    /// Triangles `start..start + count` of the build order.
    Leaf {
        bounds: Aabb,
        start: usize,
        count: usize,
    },
    /// Two subtrees.
    Inner {
        bounds: Aabb,
        children: Box<[BuildNode; 2]>,
    },
}

impl BuildNode {
    pub(crate) fn bounds(&self) -> Aabb {
        match self {
            Self::Leaf { bounds, .. } | Self::Inner { bounds, .. } => *bounds,
        }
    }
}

/// What the recursion reads: each triangle's box and the box's centre, by triangle.
struct Primitives<'a> {
    boxes: &'a [Aabb],
    centers: &'a [DVec3],
}

/// Builds the binary tree over `order` (indices into `boxes`), permuting `order` into leaf order.
pub(crate) fn build_binary(boxes: &[Aabb], order: &mut [u32]) -> Option<BuildNode> {
    if order.is_empty() {
        return None;
    }
    let centers: Vec<DVec3> = boxes.iter().map(Aabb::center).collect();
    let primitives = Primitives {
        boxes,
        centers: &centers,
    };
    Some(build_node(&primitives, order, 0, 0))
}

/// The bin of a centre coordinate `c` along an axis whose centres start at `lo`, with
/// `scale = BINS/extent`: `⌊(c − lo)·scale⌋`, at most `BINS − 1`.
#[inline]
fn bin_of(c: f64, lo: f64, scale: f64) -> usize {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "the float-to-int cast saturates: (c − lo)·scale lies in [0, BINS] and is clamped"
    )]
    let bin = ((c - lo) * scale) as usize;
    bin.min(BINS - 1)
}

/// The best binned split of a node: `(score, axis, first bin of the right side)`.
fn best_split(p: &Primitives<'_>, order: &[u32], centers: Aabb) -> Option<(f64, usize, usize)> {
    let extent = centers.hi - centers.lo;
    // The axes along which the centres spread, in order.
    let mut axes = [0; 3];
    let mut count = 0;
    for axis in 0..3 {
        if extent[axis] > 0.0 {
            axes[count] = axis;
            count += 1;
        }
    }
    let axes = &axes[..count];
    #[expect(clippy::cast_precision_loss, reason = "BINS is 32")]
    let scale = extent.map(|e| BINS as f64 / e);
    // One pass over the triangles fills the bins of every axis.
    let mut bins = [[(Aabb::EMPTY, 0_usize); BINS]; 3];
    for &i in order {
        let (bounds, center) = (p.boxes[i as usize], p.centers[i as usize]);
        for &axis in axes {
            let bin = &mut bins[axis][bin_of(center[axis], centers.lo[axis], scale[axis])];
            bin.0 = bin.0.union(bounds);
            bin.1 += 1;
        }
    }
    let mut best: Option<(f64, usize, usize)> = None;
    for &axis in axes {
        let bins = &bins[axis];
        // Right-to-left sweep: area and count of bins k.. for every k.
        let mut right = [(0.0, 0_usize); BINS];
        let mut acc = (Aabb::EMPTY, 0);
        for k in (1..BINS).rev() {
            acc = (acc.0.union(bins[k].0), acc.1 + bins[k].1);
            right[k] = (acc.0.half_area(), acc.1);
        }
        let mut left = (Aabb::EMPTY, 0);
        for k in 1..BINS {
            left = (left.0.union(bins[k - 1].0), left.1 + bins[k - 1].1);
            let (right_area, right_count) = right[k];
            if left.1 == 0 || right_count == 0 {
                continue;
            }
            #[expect(clippy::cast_precision_loss, reason = "counts below 2^32 are exact")]
            let score = left.0.half_area() * left.1 as f64 + right_area * right_count as f64;
            if best.is_none_or(|(b, _, _)| score < b) {
                best = Some((score, axis, k));
            }
        }
    }
    best
}

/// Moves the entries for which `left` holds to the front (order within each side is the
/// deterministic result of the swaps); returns how many there are.
fn partition(order: &mut [u32], left: impl Fn(u32) -> bool) -> usize {
    let mut first = 0;
    let mut last = order.len();
    while first < last {
        if left(order[first]) {
            first += 1;
        } else {
            last -= 1;
            order.swap(first, last);
        }
    }
    first
}

/// Sorts the median split of `order` along the widest centre axis: entries before `len/2` have
/// centres ≤ those after (ties by triangle index). Returns the split position.
fn median_split(p: &Primitives<'_>, order: &mut [u32], centers: Aabb) -> usize {
    let extent = centers.hi - centers.lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        p.centers[a as usize][axis]
            .total_cmp(&p.centers[b as usize][axis])
            .then(a.cmp(&b))
    });
    mid
}

fn build_node(p: &Primitives<'_>, order: &mut [u32], start: usize, depth: usize) -> BuildNode {
    let mut bounds = Aabb::EMPTY;
    let mut centers = Aabb::EMPTY;
    for &i in order.iter() {
        bounds = bounds.union(p.boxes[i as usize]);
        centers.grow(p.centers[i as usize]);
    }
    let n = order.len();
    let leaf = BuildNode::Leaf {
        bounds,
        start,
        count: n,
    };
    if n == 1 {
        return leaf;
    }
    let mid = if depth >= SAH_DEPTH_LIMIT {
        if n <= MAX_LEAF_SIZE {
            return leaf;
        }
        median_split(p, order, centers)
    } else if let Some((score, axis, split)) = best_split(p, order, centers) {
        #[expect(clippy::cast_precision_loss, reason = "counts below 2^32 are exact")]
        let leaf_cost = TRIANGLE_COST * n as f64;
        let split_cost = NODE_COST + TRIANGLE_COST * score / bounds.half_area();
        if n <= MAX_LEAF_SIZE && leaf_cost <= split_cost {
            return leaf;
        }
        #[expect(clippy::cast_precision_loss, reason = "BINS is 32")]
        let scale = BINS as f64 / (centers.hi[axis] - centers.lo[axis]);
        let lo = centers.lo[axis];
        // The same bins as `best_split` (the same operations on the same values).
        partition(order, |i| {
            bin_of(p.centers[i as usize][axis], lo, scale) < split
        })
    } else {
        // All centres coincide: no plane separates them.
        if n <= MAX_LEAF_SIZE {
            return leaf;
        }
        n / 2
    };
    let (left, right) = order.split_at_mut(mid);
    let (left, right) = if n >= PARALLEL_THRESHOLD {
        rayon::join(
            || build_node(p, left, start, depth + 1),
            || build_node(p, right, start + mid, depth + 1),
        )
    } else {
        (
            build_node(p, left, start, depth + 1),
            build_node(p, right, start + mid, depth + 1),
        )
    };
    BuildNode::Inner {
        bounds,
        children: Box::new([left, right]),
    }
}

/// A 4-wide node: the boxes of up to four children, lane by lane, and what each child is.
///
/// A lane is an inner node (`count == 0`, `child` = its node index), a leaf (`count > 0`
/// triangles from `child` on in leaf order), or unused (`count == 0`, `child == u32::MAX`, and an
/// empty box `lo = +∞, hi = −∞`, which no ray enters).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Node4 {
    /// Lower bounds per axis, per lane.
    pub(crate) lo: [[f64; 4]; 3],
    /// Upper bounds per axis, per lane.
    pub(crate) hi: [[f64; 4]; 3],
    /// Node index or first triangle.
    pub(crate) child: [u32; 4],
    /// Triangle count of a leaf lane; 0 otherwise.
    pub(crate) count: [u32; 4],
}

/// The 4-wide tree, flattened: nodes in depth-first order (root first), and its depth.
pub(crate) struct Flattened {
    pub(crate) nodes: Vec<Node4>,
    pub(crate) depth: usize,
}

/// Collapses the binary tree into 4-wide nodes.
pub(crate) fn flatten(root: &BuildNode) -> Flattened {
    let mut nodes = Vec::new();
    let depth = match root {
        BuildNode::Leaf { .. } => {
            nodes.push(node4(&[root], &[]));
            1
        }
        BuildNode::Inner { children, .. } => flatten_inner(children, &mut nodes),
    };
    Flattened { nodes, depth }
}

/// Packs up to four children into a node; `inner` holds the node index of each inner child (in
/// the order of the inner children in `children`).
fn node4(children: &[&BuildNode], inner: &[u32]) -> Node4 {
    let mut node = Node4 {
        lo: [[f64::INFINITY; 4]; 3],
        hi: [[f64::NEG_INFINITY; 4]; 3],
        child: [u32::MAX; 4],
        count: [0; 4],
    };
    let mut inner = inner.iter();
    for (lane, child) in children.iter().enumerate() {
        let bounds = child.bounds();
        for axis in 0..3 {
            node.lo[axis][lane] = bounds.lo[axis];
            node.hi[axis][lane] = bounds.hi[axis];
        }
        match child {
            BuildNode::Leaf { start, count, .. } => {
                node.child[lane] = u32::try_from(*start).expect("triangle count fits u32");
                node.count[lane] = u32::try_from(*count).expect("leaf size fits u32");
            }
            BuildNode::Inner { .. } => {
                node.child[lane] = *inner.next().expect("one index per inner child");
            }
        }
    }
    node
}

/// Flattens the inner node with these two children, and its subtree; returns the subtree's depth
/// in 4-wide nodes.
fn flatten_inner(children: &[BuildNode; 2], nodes: &mut Vec<Node4>) -> usize {
    let mut lanes: Vec<&BuildNode> = children.iter().collect();
    while lanes.len() < 4 {
        let mut widest: Option<(usize, f64, &[BuildNode; 2])> = None;
        for (k, lane) in lanes.iter().enumerate() {
            if let BuildNode::Inner { bounds, children } = lane {
                let area = bounds.half_area();
                if widest.is_none_or(|(_, a, _)| area > a) {
                    widest = Some((k, area, children));
                }
            }
        }
        let Some((k, _, grandchildren)) = widest else {
            break;
        };
        lanes.splice(k..=k, grandchildren.iter());
    }
    let index = nodes.len();
    // Placeholder, replaced once the children's indices are known.
    nodes.push(node4(&[], &[]));
    let mut inner = Vec::new();
    let mut depth = 0;
    for lane in &lanes {
        if let BuildNode::Inner { children, .. } = lane {
            inner.push(u32::try_from(nodes.len()).expect("node count fits u32"));
            depth = depth.max(flatten_inner(children, nodes));
        }
    }
    nodes[index] = node4(&lanes, &inner);
    depth + 1
}
