//! The bounding-volume hierarchy and its queries.
//!
//! # Traversal
//! A stack of `(child, triangle count, entry parameter)`. At a 4-wide node the ray's parameter
//! interval is computed for all four child boxes ([`PreparedRay::slab`], lane by lane); children
//! whose interval meets `[t_min, t_best]` are pushed farthest first, so the nearest is visited
//! next (closest hit; one or two entered children, the common cases, without sorting) — any
//! order serves the any-hit query, which stops at the first hit. A popped entry whose entry
//! parameter exceeds the current best is skipped. A leaf's triangles are tested four at a time
//! (`triangle::intersect_block`, the same bits as one at a time). The batch queries trace runs of
//! coherent rays together (the `packet` module), each ray keeping its own best and its own tests,
//! so that the argument below holds for each ray of a packet.
//!
//! # Why the traversal finds what brute force finds
//! Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013 (<https://jcgt.org/published/0002/02/02/>),
//! makes the slab test conservative by widening its far parameter by a few ulps. Here the boxes
//! are widened in space instead, by enough to cover the triangle test as well:
//!
//! Let `u = ε/2`, `M` the mesh's largest absolute coordinate ([`Bvh::magnitude`]), and
//! `R = M + |o|∞` for a ray from `o`: every vertex and every box plane lies within `R` of `o` in
//! each coordinate.
//!
//! 1. The watertight test (see `triangle`) decides exactly for sheared vertices that carry
//!    rounding: `fl(fl(p − o)[kx] − fl(Sx·fl(p − o)[kz]))` differs from its exact value by at most
//!    `(u + γ₃ + u(2 + u + γ₃))·R < 7u·R`, since `|Sx|, |Sy| ≤ 1`. A reported hit is therefore a
//!    point `Q` of the exact triangle such that the exact ray, at the parameter where it reaches
//!    `Q`'s coordinate along `kz`, is within `7u·R` of `Q` along `kx` and `ky`: the exact ray meets
//!    the triangle's box grown by `7u·R`.
//! 2. Boxes are grown by `e = BOX_PADDING_ULPS·ε·R = 16u·R` (computed with one rounding, then
//!    rounded outward). Each slab parameter `fl(fl(plane − shifted origin)·fl(1/d))` has relative
//!    error at most `γ₃ ≈ 3u`, i.e. absolute error at most `3u·(R + e)/|d_axis|`, less than the
//!    `(e − 7u·R)/|d_axis| > 8.9u·R/|d_axis|` by which the grown box's slab exceeds the `7u·R`
//!    box's. So the computed interval of a grown box contains the exact interval of the `7u·R`
//!    box: the box test never rejects a box that holds a watertight hit.
//! 3. A triangle's reported `t` is clamped into the computed interval of its own grown box (from
//!    its f64 vertices). The nodes store their boxes in f32, each bound rounded outward, so every
//!    stored box above the triangle contains the triangle's box. Every step of the slab
//!    computation is monotone in the box's bounds, so that interval lies in the interval of every
//!    stored box above it. (Monotone also with an infinite inverse: as the entry plane moves
//!    outward, its product goes from +∞ through NaN, which the comparisons ignore, to −∞; and the
//!    exit plane's the other way.) The traversal visits every box whose interval meets
//!    `[t_min, t_best]`; hence it sees every triangle whose reported `t` could win.
//!
//! With ties broken by triangle index, the result is a function of the ray and the mesh alone:
//! the same as a loop over all triangles ([`Bvh::intersect_triangle`]), whatever the tree.

mod grid;
mod packet;

pub use grid::GRID_CHUNK;

use std::fmt;

use glam::DVec3;
use rayon::prelude::*;

use crate::build::{self, Node4, Prim};
use crate::error::TraceError;
use crate::ray::{Hit, MAX_COORDINATE, PreparedRay, Ray};
use crate::triangle::{self, TriangleBlock, TriangleVertices};
use packet::{PACKET, Packet, PacketStack};

/// Rays per parallel work item in the batch queries. The split of a batch into work items depends
/// on this constant only; each ray's result depends on nothing but the ray, so the output is
/// identical for any thread count either way.
pub const RAY_CHUNK: usize = 1024;

/// Triangles per parallel work item of the exact zero-area test in [`Bvh::new`].
const DEGENERACY_CHUNK: usize = 4096;

/// A stack entry: a node (`count == 0`) or a leaf's first triangle and count, and the parameter
/// at which the ray enters its box.
#[derive(Clone, Copy)]
struct Entry {
    child: u32,
    count: u32,
    near: f64,
}

/// The traversal stack; batch queries reuse one per work item.
type Stack = Vec<Entry>;

/// A new, empty traversal stack, sized for typical trees (it grows if needed).
fn new_stack() -> Stack {
    Vec::with_capacity(64)
}

/// Shape of a built tree, for reports and benchmarks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BvhStats {
    /// Triangles given to [`Bvh::new`].
    pub triangles: usize,
    /// Of those, the zero-area ones (not stored, never hit).
    pub degenerate: usize,
    /// 4-wide nodes.
    pub nodes: usize,
    /// Leaves.
    pub leaves: usize,
    /// The largest leaf, in triangles.
    pub max_leaf_size: usize,
    /// Depth in 4-wide nodes (1 for a single node; 0 without triangles).
    pub depth: usize,
}

/// A bounding-volume hierarchy over a triangle mesh: 4-wide nodes built by binned SAH, the
/// watertight ray–triangle test, exact agreement with brute force.
///
/// # Guarantees
/// * **Watertight:** a ray through a shared edge or vertex of a mesh is reported by at least one
///   of the triangles there, unless the surface folds over along the ray there (a silhouette),
///   where the ray only grazes it (see the crate documentation for the tie rule).
/// * **Brute-force equal:** [`Bvh::closest_hit`] returns the hit of smallest `t` among
///   [`Bvh::intersect_triangle`] over all triangles, the smallest triangle index among equal `t`;
///   [`Bvh::occluded`] is true exactly when one of them hits. Never approximately: the same bits.
/// * **Deterministic:** the tree, and every answer, is the same for any thread count and run.
/// * **Zero-area triangles** (exactly collinear vertices, decided with exact predicates) are not
///   stored and never hit; [`Bvh::degenerate_triangles`] lists them. A mesh that needs them to be
///   closed (zero-area triangles filling T-junctions) may therefore leak within rounding distance
///   of them: the shear can open them into slivers that no other triangle covers.
#[derive(Clone, PartialEq)]
pub struct Bvh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// 4-wide nodes, depth first, root first; empty without triangles. A leaf lane's `child` is
    /// its first block.
    nodes: Vec<Node4>,
    /// The stored triangles in blocks of four, leaf by leaf.
    blocks: Vec<TriangleBlock>,
    /// Indices of the zero-area triangles, ascending.
    degenerate: Vec<u32>,
    /// The exact bounding box of the stored triangles (the nodes' boxes are rounded outward).
    bounds: Option<(DVec3, DVec3)>,
    /// The largest absolute coordinate of a stored triangle's vertex.
    magnitude: f64,
    depth: usize,
}

impl fmt::Debug for Bvh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Bvh")
            .field("stats", &self.stats())
            .field("magnitude", &self.magnitude)
            .finish_non_exhaustive()
    }
}

/// Whether the triangle has zero area, exactly: its edge cross product vanishes iff all three of
/// its projections onto the coordinate planes are collinear.
fn is_degenerate(p: [DVec3; 3]) -> bool {
    let flat = |i: usize, j: usize| {
        let c = |q: DVec3| robust::Coord { x: q[i], y: q[j] };
        robust::orient2d(c(p[0]), c(p[1]), c(p[2])) == 0.0
    };
    flat(0, 1) && flat(1, 2) && flat(2, 0)
}

fn vertices(p: [DVec3; 3]) -> TriangleVertices {
    [
        p[0].x, p[0].y, p[0].z, p[1].x, p[1].y, p[1].z, p[2].x, p[2].y, p[2].z,
    ]
}

/// Panics with the error's message if `t_min` or `t_max` is NaN.
fn check_range(t_min: f64, t_max: f64) {
    for (parameter, value) in [("t_min", t_min), ("t_max", t_max)] {
        if value.is_nan() {
            panic!("{}", TraceError::NanRange { parameter });
        }
    }
}

impl Bvh {
    /// Builds the hierarchy over `triangles` (index triples into `positions`). The inputs are
    /// copied; indices of triangles in [`Hit`]s refer to `triangles`.
    ///
    /// Build: binned SAH with 32 bins per axis counting blocks of four triangles, leaves of at most
    /// 8 triangles, a binary tree collapsed to 4 children per node (details in the `build`
    /// module). Parallel (rayon) for large nodes; the tree is identical for any thread count.
    ///
    /// # Errors
    /// [`TraceError::TooManyTriangles`] beyond `u32::MAX` triangles;
    /// [`TraceError::NonFinitePosition`] or [`TraceError::PositionOutOfRange`] (beyond
    /// [`MAX_COORDINATE`]) naming the first bad vertex; [`TraceError::IndexOutOfRange`] naming the
    /// first triangle (and corner) with a bad index.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<Self, TraceError> {
        if u32::try_from(triangles.len()).is_err() {
            return Err(TraceError::TooManyTriangles {
                count: triangles.len(),
            });
        }
        let out_of_range = |p: &DVec3| !p.is_finite() || p.abs().max_element() > MAX_COORDINATE;
        if let Some(vertex) = positions.par_iter().position_first(out_of_range) {
            let p = positions[vertex];
            return Err(if p.is_finite() {
                TraceError::PositionOutOfRange {
                    vertex,
                    value: p.abs().max_element(),
                }
            } else {
                TraceError::NonFinitePosition { vertex }
            });
        }
        let bad_index = |vertex: &u32| *vertex as usize >= positions.len();
        if let Some(triangle) = triangles
            .par_iter()
            .position_first(|corners| corners.iter().any(bad_index))
        {
            let corner = triangles[triangle]
                .iter()
                .position(bad_index)
                .expect("a bad corner");
            return Err(TraceError::IndexOutOfRange {
                triangle,
                corner,
                vertex: triangles[triangle][corner],
                vertex_count: positions.len(),
            });
        }
        let corners = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        let flags: Vec<bool> = triangles
            .par_iter()
            .with_min_len(DEGENERACY_CHUNK)
            .map(|t| is_degenerate(corners(t)))
            .collect();
        let mut degenerate = Vec::new();
        let mut order = Vec::new();
        for (i, &flat) in flags.iter().enumerate() {
            let i = u32::try_from(i).expect("checked above");
            if flat {
                degenerate.push(i);
            } else {
                order.push(i);
            }
        }
        let mut prims: Vec<Prim> = order
            .par_iter()
            .map(|&id| {
                let [a, b, c] = corners(&triangles[id as usize]);
                Prim::new(a.min(b).min(c), a.max(b).max(c), id)
            })
            .collect();
        let build::Tree {
            mut nodes,
            depth,
            bounds,
        } = build::build(&mut prims);
        // The box holds every stored vertex and is bounded by them: its largest absolute
        // coordinate is theirs.
        let magnitude = bounds.map_or(0.0, |(lo, hi)| lo.abs().max(hi.abs()).max_element());
        debug_assert!(depth <= build::MAX_DEPTH);
        let blocks = build::leaf_blocks(&mut nodes, &prims, |id| {
            vertices(corners(&triangles[id as usize]))
        });
        Ok(Self {
            positions: positions.to_vec(),
            triangles: triangles.to_vec(),
            nodes,
            blocks,
            degenerate,
            bounds,
            magnitude,
            depth,
        })
    }

    /// The number of triangles given to [`Bvh::new`], zero-area ones included.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The indices of the zero-area triangles, ascending. They are not stored and never hit.
    #[must_use]
    pub fn degenerate_triangles(&self) -> &[u32] {
        &self.degenerate
    }

    /// The largest absolute coordinate of a vertex of a stored (non-degenerate) triangle; 0 when
    /// there is none. Boxes are padded in proportion to it, and it is a valid `magnitude` for
    /// [`crate::offset_origin`] of any point on the mesh.
    #[must_use]
    pub fn magnitude(&self) -> f64 {
        self.magnitude
    }

    /// The bounding box `(lo, hi)` of the stored triangles; `None` when there is none.
    #[must_use]
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.bounds
    }

    /// The shape of the tree.
    #[must_use]
    pub fn stats(&self) -> BvhStats {
        let mut leaves = 0;
        let mut max_leaf_size = 0;
        for node in &self.nodes {
            for &count in &node.count {
                if count > 0 {
                    leaves += 1;
                    max_leaf_size = max_leaf_size.max(count as usize);
                }
            }
        }
        BvhStats {
            triangles: self.triangles.len(),
            degenerate: self.degenerate.len(),
            nodes: self.nodes.len(),
            leaves,
            max_leaf_size,
            depth: self.depth,
        }
    }

    /// The vertices of triangle `triangle`.
    ///
    /// # Panics
    /// If `triangle` is not an index of the triangles given to [`Bvh::new`].
    #[must_use]
    pub fn triangle(&self, triangle: u32) -> [DVec3; 3] {
        self.triangles[triangle as usize].map(|v| self.positions[v as usize])
    }

    /// The hit's point from its barycentric coordinates: `(1 − u − v)·p0 + u·p1 + v·p2`, evaluated
    /// in that order. It lies within `4.4·ε·m` of the triangle's plane, `m` being the triangle's
    /// largest absolute coordinate (the weights sum to 1 within `2u`, and the sum rounds by at most
    /// `γ₃·m` per coordinate), so it satisfies the precondition of [`crate::offset_origin`] with
    /// `magnitude = m` or [`Bvh::magnitude`]. Prefer it to `ray.at(hit.t)`, whose error grows
    /// with `t` and with the ray's obliquity.
    ///
    /// # Panics
    /// If `hit.triangle` is not an index of the triangles given to [`Bvh::new`].
    #[must_use]
    pub fn hit_point(&self, hit: &Hit) -> DVec3 {
        let [p0, p1, p2] = self.triangle(hit.triangle);
        p0 * (1.0 - hit.u - hit.v) + p1 * hit.u + p2 * hit.v
    }

    /// The triangle's geometric normal `(p1 − p0) × (p2 − p0)`, not normalised: counter-clockwise
    /// vertices seen from where it points. Zero (or tiny) for zero-area triangles.
    ///
    /// # Panics
    /// If `triangle` is not an index of the triangles given to [`Bvh::new`].
    #[must_use]
    pub fn geometric_normal(&self, triangle: u32) -> DVec3 {
        let [p0, p1, p2] = self.triangle(triangle);
        (p1 - p0).cross(p2 - p0)
    }

    /// The ray set up against this mesh; panics with the error's message if it is invalid.
    fn prepare(&self, ray: &Ray) -> PreparedRay {
        PreparedRay::new(ray, self.magnitude).unwrap_or_else(|e| panic!("invalid ray: {e}"))
    }

    /// The crate's ray–triangle test against one triangle, exactly as the traversal applies it:
    /// the hit with `t` in the open interval `(t_min, t_max)`, if any. Zero-area triangles never
    /// hit. This is the reference the tree agrees with (a loop over all triangles).
    ///
    /// # Panics
    /// If the ray is invalid ([`Ray::validate`]), `t_min` or `t_max` is NaN, or `triangle` is not
    /// an index of the triangles given to [`Bvh::new`].
    #[must_use]
    pub fn intersect_triangle(
        &self,
        ray: &Ray,
        triangle: u32,
        t_min: f64,
        t_max: f64,
    ) -> Option<Hit> {
        check_range(t_min, t_max);
        let ray = self.prepare(ray);
        let corners = self.triangle(triangle);
        if self.degenerate.binary_search(&triangle).is_ok() {
            return None;
        }
        let stored = vertices(corners);
        let (t, u, v) = match ray.kz {
            0 => triangle::intersect::<0>(&ray, &stored)?,
            1 => triangle::intersect::<1>(&ray, &stored)?,
            _ => triangle::intersect::<2>(&ray, &stored)?,
        };
        (t_min < t && t < t_max).then_some(Hit { t, triangle, u, v })
    }

    /// The nearest hit with `t` in the open interval `(t_min, t_max)`; on equal `t`, the one of
    /// smallest triangle index. Use `t_max = f64::INFINITY` for an unbounded ray.
    ///
    /// # Panics
    /// If the ray is invalid ([`Ray::validate`]) or `t_min` or `t_max` is NaN.
    #[must_use]
    pub fn closest_hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        check_range(t_min, t_max);
        self.closest_prepared(&self.prepare(ray), t_min, t_max, &mut new_stack())
    }

    /// Whether any triangle is hit with `t` in the open interval `(t_min, t_max)`: for a shadow
    /// ray from `p` toward a point light `l`, `Ray { origin: p, direction: l − p }` with `(0, 1)`.
    ///
    /// # Panics
    /// If the ray is invalid ([`Ray::validate`]) or `t_min` or `t_max` is NaN.
    #[must_use]
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        check_range(t_min, t_max);
        self.occluded_prepared(&self.prepare(ray), t_min, t_max, &mut new_stack())
    }

    /// [`Bvh::closest_hit`] for every ray, in parallel (rayon, [`RAY_CHUNK`] rays per work item);
    /// the output is identical for any thread count. Runs of consecutive rays that share their
    /// direction signs are traced together, a few at a time (the `packet` module): order a
    /// coherent batch so that neighbouring rays are next to each other (a shadow map's rays row by
    /// row, say). Every answer is the single query's, bit for bit, whatever the order.
    ///
    /// # Panics
    /// If a ray is invalid (the message names its index) or `t_min` or `t_max` is NaN.
    #[must_use]
    pub fn closest_hits(&self, rays: &[Ray], t_min: f64, t_max: f64) -> Vec<Option<Hit>> {
        check_range(t_min, t_max);
        self.batch(rays, |prepared, out| {
            self.closest_item(prepared, t_min, t_max, out);
        })
    }

    /// [`Bvh::occluded`] for every ray, in parallel (rayon, [`RAY_CHUNK`] rays per work item); the
    /// output is identical for any thread count. Coherent runs of rays are traced together, as in
    /// [`Bvh::closest_hits`].
    ///
    /// # Panics
    /// If a ray is invalid (the message names its index) or `t_min` or `t_max` is NaN.
    #[must_use]
    pub fn occluded_all(&self, rays: &[Ray], t_min: f64, t_max: f64) -> Vec<bool> {
        check_range(t_min, t_max);
        self.batch(rays, |prepared, out| {
            Self::item(
                prepared,
                |ray, stack| self.occluded_prepared(ray, t_min, t_max, stack),
                |rays, packet, stack, out| {
                    self.occluded_packet(rays, packet, t_min, t_max, stack, out);
                },
                out,
            );
        })
    }

    /// Casts `rays` in parallel work items of [`RAY_CHUNK`] rays, each set up and answered by
    /// `item` into its place.
    fn batch<T: Clone + Default + Send>(
        &self,
        rays: &[Ray],
        item: impl Fn(&[PreparedRay], &mut [T]) + Sync,
    ) -> Vec<T> {
        // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers"): a 2048² grid's
        // answers are 160 MB of `Option<Hit>`.
        let mut out: Vec<T> = rayon::iter::repeat_n(T::default(), rays.len()).collect();
        out.par_chunks_mut(RAY_CHUNK)
            .zip(rays.par_chunks(RAY_CHUNK))
            .enumerate()
            .for_each(|(chunk, (out, rays))| {
                // All of the work item's rays first: their loads overlap.
                let prepared: Vec<PreparedRay> = rays
                    .iter()
                    .enumerate()
                    .map(|(i, ray)| {
                        PreparedRay::new(ray, self.magnitude).unwrap_or_else(|e| {
                            panic!("invalid ray {}: {e}", chunk * RAY_CHUNK + i)
                        })
                    })
                    .collect();
                item(&prepared, out);
            });
        out
    }

    /// One work item's rays, set up: in packets of [`PACKET`] consecutive rays where they form
    /// one (`packet`), one by one otherwise (`single`).
    fn item<T>(
        prepared: &[PreparedRay],
        single: impl Fn(&PreparedRay, &mut Stack) -> T,
        packet: impl Fn(&[PreparedRay], &Packet, &mut PacketStack, &mut [T]),
        out: &mut [T],
    ) {
        let mut stack = new_stack();
        let mut packet_stack = PacketStack::new();
        let mut set_up = Packet::default();
        for (out, rays) in out.chunks_mut(PACKET).zip(prepared.chunks(PACKET)) {
            if set_up.set(rays) {
                packet(rays, &set_up, &mut packet_stack, out);
            } else {
                for (out, ray) in out.iter_mut().zip(rays) {
                    *out = single(ray, &mut stack);
                }
            }
        }
    }

    /// [`Bvh::closest_hits`] of one work item's rays, set up, into `out`.
    fn closest_item(
        &self,
        prepared: &[PreparedRay],
        t_min: f64,
        t_max: f64,
        out: &mut [Option<Hit>],
    ) {
        Self::item(
            prepared,
            |ray, stack| self.closest_prepared(ray, t_min, t_max, stack),
            |rays, packet, stack, out| self.closest_packet(rays, packet, t_min, t_max, stack, out),
            out,
        );
    }

    fn closest_prepared(
        &self,
        ray: &PreparedRay,
        t_min: f64,
        t_max: f64,
        stack: &mut Stack,
    ) -> Option<Hit> {
        match ray.kz {
            0 => self.closest::<0>(ray, t_min, t_max, stack),
            1 => self.closest::<1>(ray, t_min, t_max, stack),
            _ => self.closest::<2>(ray, t_min, t_max, stack),
        }
    }

    fn occluded_prepared(
        &self,
        ray: &PreparedRay,
        t_min: f64,
        t_max: f64,
        stack: &mut Stack,
    ) -> bool {
        match ray.kz {
            0 => self.occluded_kz::<0>(ray, t_min, t_max, stack),
            1 => self.occluded_kz::<1>(ray, t_min, t_max, stack),
            _ => self.occluded_kz::<2>(ray, t_min, t_max, stack),
        }
    }

    /// The blocks of the leaf whose first block is `first` and which holds `count` triangles.
    #[inline(always)]
    fn leaf(&self, first: u32, count: u32) -> &[TriangleBlock] {
        let first = first as usize;
        &self.blocks[first..first + (count as usize).div_ceil(triangle::BLOCK)]
    }

    /// The parameter intervals of a node's four child boxes, clipped to `[t_lo, t_hi]`: lanes
    /// with `near <= far` are entered. Lane by lane the same operations as [`PreparedRay::slab`].
    #[inline(always)]
    fn children(ray: &PreparedRay, node: &Node4, t_lo: f64, t_hi: f64) -> ([f64; 4], [f64; 4]) {
        let mut near = [t_lo; 4];
        let mut far = [t_hi; 4];
        for axis in 0..3 {
            let (entry, exit) = if ray.negative[axis] {
                (node.upper(axis), node.lower(axis))
            } else {
                (node.lower(axis), node.upper(axis))
            };
            let (near_origin, far_origin) = (ray.near_origin[axis], ray.far_origin[axis]);
            let inverse = ray.inverse[axis];
            for lane in 0..4 {
                let t_entry = (entry[lane] - near_origin) * inverse;
                let t_exit = (exit[lane] - far_origin) * inverse;
                near[lane] = if t_entry > near[lane] {
                    t_entry
                } else {
                    near[lane]
                };
                far[lane] = if t_exit < far[lane] {
                    t_exit
                } else {
                    far[lane]
                };
            }
        }
        (near, far)
    }

    fn closest<const KZ: usize>(
        &self,
        ray: &PreparedRay,
        t_min: f64,
        t_max: f64,
        stack: &mut Stack,
    ) -> Option<Hit> {
        if self.nodes.is_empty() {
            return None;
        }
        // The best so far: a hit must have t < best_t, or t == best_t and a smaller index. With
        // no hit yet, best_id = 0 makes t == t_max fail: the interval is open.
        let mut best_t = t_max;
        let mut best_id = 0_u32;
        let mut best_uv = None;
        stack.clear();
        stack.push(Entry {
            child: 0,
            count: 0,
            near: t_min,
        });
        while let Some(entry) = stack.pop() {
            if entry.near > best_t {
                continue;
            }
            if entry.count > 0 {
                for block in self.leaf(entry.child, entry.count) {
                    triangle::intersect_block::<KZ>(ray, block, |k, t, u, v| {
                        let id = block.id[k];
                        if t_min < t && (t < best_t || (t == best_t && id < best_id)) {
                            best_t = t;
                            best_id = id;
                            best_uv = Some((u, v));
                        }
                        false
                    });
                }
                continue;
            }
            let node = &self.nodes[entry.child as usize];
            let (near, far) = Self::children(ray, node, t_min, best_t);
            let mut mask = 0_u32;
            for lane in 0..4 {
                mask |= u32::from(near[lane] <= far[lane]) << lane;
            }
            let entry_of = |lane: usize| Entry {
                child: node.child[lane],
                count: node.count[lane],
                near: near[lane],
            };
            match mask.count_ones() {
                0 => {}
                1 => stack.push(entry_of(mask.trailing_zeros() as usize)),
                2 => {
                    let a = mask.trailing_zeros() as usize;
                    let b = (mask & (mask - 1)).trailing_zeros() as usize;
                    // The nearer last (popped first); the first lane on ties.
                    let (first, second) = if near[b] < near[a] { (b, a) } else { (a, b) };
                    stack.push(entry_of(second));
                    stack.push(entry_of(first));
                }
                _ => {
                    // Entered lanes, sorted by entry parameter, nearest last (popped first).
                    let mut order = [(0.0, 0_usize); 4];
                    let mut entered = 0;
                    for (lane, &lane_near) in near.iter().enumerate() {
                        if mask & (1 << lane) != 0 {
                            let mut k = entered;
                            while k > 0 && order[k - 1].0 < lane_near {
                                order[k] = order[k - 1];
                                k -= 1;
                            }
                            order[k] = (lane_near, lane);
                            entered += 1;
                        }
                    }
                    for &(_, lane) in &order[..entered] {
                        stack.push(entry_of(lane));
                    }
                }
            }
        }
        best_uv.map(|(u, v)| Hit {
            t: best_t,
            triangle: best_id,
            u,
            v,
        })
    }

    fn occluded_kz<const KZ: usize>(
        &self,
        ray: &PreparedRay,
        t_min: f64,
        t_max: f64,
        stack: &mut Stack,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        stack.clear();
        stack.push(Entry {
            child: 0,
            count: 0,
            near: t_min,
        });
        while let Some(entry) = stack.pop() {
            if entry.count > 0 {
                for block in self.leaf(entry.child, entry.count) {
                    if triangle::intersect_block::<KZ>(ray, block, |_, t, _, _| {
                        t_min < t && t < t_max
                    }) {
                        return true;
                    }
                }
                continue;
            }
            let node = &self.nodes[entry.child as usize];
            let (near, far) = Self::children(ray, node, t_min, t_max);
            for lane in 0..4 {
                if near[lane] <= far[lane] {
                    stack.push(Entry {
                        child: node.child[lane],
                        count: node.count[lane],
                        near: near[lane],
                    });
                }
            }
        }
        false
    }
}
