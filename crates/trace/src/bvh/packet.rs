//! Packet traversal: up to [`PACKET`] rays through the tree together, for coherent batches.
//!
//! # The packet's box test
//! After Boulos, Wald, Shirley et al., "Geometric and Arithmetic Culling Methods for Entire Ray
//! Packets" (University of Utah UUCS-06-010, 2006) and Wald, Boulos & Shirley, "Ray Tracing
//! Deformable Scenes Using Dynamic Bounding Volume Hierarchies" (ACM TOG 26(1), 2007): instead of
//! testing every ray against a node's boxes, the packet tests the boxes once with interval
//! arithmetic over its rays, which bounds every ray's slab interval. Here the bound is made exact
//! for the rounded computation each ray would perform:
//!
//! A ray's entry parameter on an axis is `fl(fl(E − n)·i)` (entry plane `E`, its shifted origin
//! `n`, its inverse direction `i`; [`PreparedRay::slab`]). When every ray of the packet has the
//! same direction sign on the axis and a finite inverse, `fl(E − n)` lies between `fl(E − n₊)` and
//! `fl(E − n₋)` (`n₋`, `n₊` the extremes of the rays' `n`; rounding is monotone), and the product
//! of a value and an inverse in `[i₋, i₊]` is smallest at a corner of that rectangle. With the
//! signs fixed, the corner is on the side `a = fl(E − n*)`, `n* = n₊` for a positive direction and
//! `n₋` for a negative one, so `min(fl(a·i₋), fl(a·i₊))` is at most every ray's entry parameter;
//! likewise `max(fl(b·i₋), fl(b·i₊))` with `b = fl(X − f*)` at least every ray's exit parameter.
//! Hence the packet's interval contains the interval of each ray, clipped to the packet's
//! `[t_min, max best]`: a box that any ray enters, the packet enters. No value is NaN (finite
//! inverses; an empty lane's infinite plane gives an infinite product of the right sign).
//!
//! # What each ray tests
//! When the packet enters a leaf, each ray's own slab test of the leaf's box
//! ([`PreparedRay::slab`] with the ray's `[t_min, best]`, lane by lane the same operations; done
//! with the bests of that moment, which only shrink afterwards) decides whether the ray tests the
//! leaf's triangles, with the one-ray test. So every ray enters every box its own traversal would
//! enter (the bound above), and tests every triangle whose hit could win: by the argument of the
//! `bvh` module, each ray's answer is the brute-force answer, to the bit, whichever rays share its
//! packet and in whatever order the packet visits the tree.
//!
//! Rays whose direction signs differ, or with a zero direction component (an infinite inverse),
//! do not form a packet: the batch casts them one by one.

use crate::build::Node4;
use crate::ray::{Hit, PreparedRay};
use crate::triangle::{self, TriangleBlock};

use super::Bvh;

/// The largest number of rays traversed together.
pub(crate) const PACKET: usize = 8;

/// One f64 per ray of a packet.
type Lanes = [f64; PACKET];

/// Up to [`PACKET`] rays set up together: their slab set-up side by side for their own box tests,
/// and the bounds on it for the packet's box test (module documentation). Lanes beyond the
/// packet's rays repeat its first ray, which changes no bound.
#[derive(Default)]
pub(crate) struct Packet {
    len: usize,
    /// The direction sign per axis, shared by all rays.
    negative: [bool; 3],
    /// Per axis, each ray's [`PreparedRay`] `near_origin`, `far_origin` and `inverse`.
    near_origin: [Lanes; 3],
    far_origin: [Lanes; 3],
    inverse: [Lanes; 3],
    /// Per axis, the extreme shifted origins for entry and exit parameters (`n*`, `f*`).
    near_extreme: [f64; 3],
    far_extreme: [f64; 3],
    /// Per axis, the smallest and largest inverse direction.
    inverse_lo: [f64; 3],
    inverse_hi: [f64; 3],
}

/// `a < b ? a : b` (no NaN reaches it).
#[inline(always)]
fn min(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// `a > b ? a : b` (no NaN reaches it).
#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

impl Packet {
    /// Sets the packet up for `rays` (at least one, at most [`PACKET`]); `false`, leaving it in
    /// no useful state, if they do not share their direction signs or have an infinite inverse.
    pub(crate) fn set(&mut self, rays: &[PreparedRay]) -> bool {
        debug_assert!((1..=PACKET).contains(&rays.len()));
        self.len = rays.len();
        let negative = rays[0].negative;
        self.negative = negative;
        for i in 0..PACKET {
            let ray = rays.get(i).unwrap_or(&rays[0]);
            if ray.negative != negative {
                return false;
            }
            for axis in 0..3 {
                self.near_origin[axis][i] = ray.near_origin[axis];
                self.far_origin[axis][i] = ray.far_origin[axis];
                self.inverse[axis][i] = ray.inverse[axis];
            }
        }
        let fold = |lanes: &Lanes, f: fn(f64, f64) -> f64| lanes.iter().copied().fold(lanes[0], f);
        let (near_origin, far_origin, inverse) =
            (&self.near_origin, &self.far_origin, &self.inverse);
        for axis in 0..3 {
            let lo = fold(&inverse[axis], min);
            let hi = fold(&inverse[axis], max);
            if !lo.is_finite() || !hi.is_finite() {
                return false;
            }
            (self.inverse_lo[axis], self.inverse_hi[axis]) = (lo, hi);
            // Positive direction: the largest near origin, the smallest far origin.
            let (near_lo, near_hi) = (fold(&near_origin[axis], min), fold(&near_origin[axis], max));
            let (far_lo, far_hi) = (fold(&far_origin[axis], min), fold(&far_origin[axis], max));
            (self.near_extreme[axis], self.far_extreme[axis]) = if negative[axis] {
                (near_lo, far_hi)
            } else {
                (near_hi, far_lo)
            };
        }
        true
    }

    /// The rays (bit `i` for ray `i`) whose own slab interval in lane `lane` of `node`, clipped to
    /// `[t_min, t_hi[i]]`, is not empty: lane by lane the operations of [`PreparedRay::slab`].
    #[inline(always)]
    fn entering(&self, node: &Node4, lane: usize, t_min: f64, t_hi: &Lanes) -> u32 {
        let mut near = [t_min; PACKET];
        let mut far = *t_hi;
        for axis in 0..3 {
            let (entry, exit) = if self.negative[axis] {
                (node.upper(axis)[lane], node.lower(axis)[lane])
            } else {
                (node.lower(axis)[lane], node.upper(axis)[lane])
            };
            for i in 0..PACKET {
                let t_entry = (entry - self.near_origin[axis][i]) * self.inverse[axis][i];
                let t_exit = (exit - self.far_origin[axis][i]) * self.inverse[axis][i];
                near[i] = if t_entry > near[i] { t_entry } else { near[i] };
                far[i] = if t_exit < far[i] { t_exit } else { far[i] };
            }
        }
        let mut mask = 0;
        for i in 0..PACKET {
            mask |= u32::from(near[i] <= far[i]) << i;
        }
        mask & (u32::MAX >> (32 - self.len))
    }

    /// Bounds on the parameter intervals of the packet's rays in a node's four child boxes,
    /// clipped to `[t_lo, t_hi]`: lanes with `near <= far` are entered.
    #[inline(always)]
    fn children(&self, node: &Node4, t_lo: f64, t_hi: f64) -> ([f64; 4], [f64; 4]) {
        let mut near = [t_lo; 4];
        let mut far = [t_hi; 4];
        for axis in 0..3 {
            let (entry, exit) = if self.negative[axis] {
                (node.upper(axis), node.lower(axis))
            } else {
                (node.lower(axis), node.upper(axis))
            };
            let (lo, hi) = (self.inverse_lo[axis], self.inverse_hi[axis]);
            for lane in 0..4 {
                let a = entry[lane] - self.near_extreme[axis];
                let b = exit[lane] - self.far_extreme[axis];
                let (a_lo, a_hi) = (a * lo, a * hi);
                let (b_lo, b_hi) = (b * lo, b * hi);
                let t_entry = if a_lo < a_hi { a_lo } else { a_hi };
                let t_exit = if b_lo > b_hi { b_lo } else { b_hi };
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
}

/// A stack entry of the packet traversal: a node (`count == 0`) or a leaf's first block and
/// triangle count, the packet's entry parameter, and (for a leaf) the rays that enter it.
#[derive(Clone, Copy)]
pub(crate) struct PacketEntry {
    child: u32,
    count: u32,
    rays: u32,
    near: f64,
}

/// The packet traversal's stack; batch queries reuse one per work item.
pub(crate) type PacketStack = Vec<PacketEntry>;

/// The one-ray test of `ray` against `block`, dispatched on the ray's dominant axis.
#[inline(always)]
fn intersect_block(
    ray: &PreparedRay,
    block: &TriangleBlock,
    found: impl FnMut(usize, f64, f64, f64) -> bool,
) -> bool {
    match ray.kz {
        0 => triangle::intersect_block::<0>(ray, block, found),
        1 => triangle::intersect_block::<1>(ray, block, found),
        _ => triangle::intersect_block::<2>(ray, block, found),
    }
}

impl Bvh {
    /// [`Bvh::closest_hit`] for each of `rays`, set up as `packet`, written to `out` in order.
    pub(crate) fn closest_packet(
        &self,
        rays: &[PreparedRay],
        packet: &Packet,
        t_min: f64,
        t_max: f64,
        stack: &mut PacketStack,
        out: &mut [Option<Hit>],
    ) {
        // Per ray, as in `closest`: a hit must have t < best_t, or t == best_t and a smaller index.
        let mut best_t = [t_max; PACKET];
        let mut best_id = [0_u32; PACKET];
        let mut best_uv: [Option<(f64, f64)>; PACKET] = [None; PACKET];
        // The largest best of the packet: no box beyond it can hold a hit that wins.
        let mut t_hi = t_max;
        stack.clear();
        if !self.nodes.is_empty() {
            stack.push(PacketEntry {
                child: 0,
                count: 0,
                rays: 0,
                near: t_min,
            });
        }
        while let Some(entry) = stack.pop() {
            if entry.near > t_hi {
                continue;
            }
            if entry.count > 0 {
                let blocks = self.leaf(entry.child, entry.count);
                let mut mask = entry.rays;
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    for block in blocks {
                        intersect_block(&rays[i], block, |k, t, u, v| {
                            let id = block.id[k];
                            if t_min < t && (t < best_t[i] || (t == best_t[i] && id < best_id[i])) {
                                best_t[i] = t;
                                best_id[i] = id;
                                best_uv[i] = Some((u, v));
                            }
                            false
                        });
                    }
                }
                t_hi = best_t[..rays.len()]
                    .iter()
                    .copied()
                    .fold(f64::NEG_INFINITY, max);
                continue;
            }
            let node = &self.nodes[entry.child as usize];
            let (near, far) = packet.children(node, t_min, t_hi);
            // Entered lanes, sorted by entry parameter, nearest last (popped first).
            let mut order = [(0.0, 0_usize, 0_u32); 4];
            let mut entered = 0;
            for lane in 0..4 {
                if near[lane] > far[lane] {
                    continue;
                }
                let rays_in = if node.count[lane] > 0 {
                    let mask = packet.entering(node, lane, t_min, &best_t);
                    if mask == 0 {
                        continue;
                    }
                    mask
                } else {
                    0
                };
                let mut k = entered;
                while k > 0 && order[k - 1].0 < near[lane] {
                    order[k] = order[k - 1];
                    k -= 1;
                }
                order[k] = (near[lane], lane, rays_in);
                entered += 1;
            }
            for &(near, lane, rays_in) in &order[..entered] {
                stack.push(PacketEntry {
                    child: node.child[lane],
                    count: node.count[lane],
                    rays: rays_in,
                    near,
                });
            }
        }
        for (i, out) in out.iter_mut().enumerate() {
            *out = best_uv[i].map(|(u, v)| Hit {
                t: best_t[i],
                triangle: best_id[i],
                u,
                v,
            });
        }
    }

    /// [`Bvh::occluded`] for each of `rays`, set up as `packet`, written to `out` in order.
    pub(crate) fn occluded_packet(
        &self,
        rays: &[PreparedRay],
        packet: &Packet,
        t_min: f64,
        t_max: f64,
        stack: &mut PacketStack,
        out: &mut [bool],
    ) {
        // The rays still looking for a hit.
        let mut open = u32::MAX >> (32 - rays.len());
        stack.clear();
        if !self.nodes.is_empty() {
            stack.push(PacketEntry {
                child: 0,
                count: 0,
                rays: 0,
                near: t_min,
            });
        }
        while open != 0
            && let Some(entry) = stack.pop()
        {
            if entry.count > 0 {
                let blocks = self.leaf(entry.child, entry.count);
                let mut mask = entry.rays & open;
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    for block in blocks {
                        if intersect_block(&rays[i], block, |_, t, _, _| t_min < t && t < t_max) {
                            open &= !(1 << i);
                            break;
                        }
                    }
                }
                continue;
            }
            let node = &self.nodes[entry.child as usize];
            let (near, far) = packet.children(node, t_min, t_max);
            for lane in 0..4 {
                if near[lane] > far[lane] {
                    continue;
                }
                let rays_in = if node.count[lane] > 0 {
                    let mask = packet.entering(node, lane, t_min, &[t_max; PACKET]) & open;
                    if mask == 0 {
                        continue;
                    }
                    mask
                } else {
                    0
                };
                stack.push(PacketEntry {
                    child: node.child[lane],
                    count: node.count[lane],
                    rays: rays_in,
                    near: near[lane],
                });
            }
        }
        for (i, out) in out.iter_mut().enumerate() {
            *out = open & (1 << i) == 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::{PACKET, Packet};
    use crate::build::{Aabb, Lanes, Node4};
    use crate::ray::{PreparedRay, Ray};
    use shadowlab_test_random::SplitMix;

    fn prepared(origin: DVec3, direction: DVec3) -> PreparedRay {
        PreparedRay::new(&Ray::new(origin, direction).expect("valid"), 4.0).expect("valid")
    }

    #[test]
    fn coherent_rays_form_a_packet_and_others_do_not() {
        let d = DVec3::new(-0.3, -1.0, -0.45);
        let rays: Vec<PreparedRay> = (0..PACKET)
            .map(|i| {
                prepared(
                    DVec3::new(f64::from(u8::try_from(i).expect("small")), 0.0, 2.0),
                    d,
                )
            })
            .collect();
        let mut packet = Packet::default();
        assert!(packet.set(&rays));
        assert!(packet.set(&rays[..3]));
        // A direction sign differs.
        let mut mixed = rays.clone();
        mixed[5] = prepared(DVec3::ZERO, DVec3::new(0.3, -1.0, -0.45));
        assert!(!packet.set(&mixed));
        // A zero component (of the same sign bit): an infinite inverse.
        mixed[5] = prepared(DVec3::ZERO, DVec3::new(-0.0, -1.0, -0.45));
        assert!(!packet.set(&mixed));
    }

    /// The packet's interval of a box contains the interval of each of its rays that enters it:
    /// random packets (directions jittered around one, origins spread) against random boxes.
    #[test]
    fn the_packet_interval_bounds_every_ray() {
        let mut rng = SplitMix(0x7ACE_0B02);
        let mut packet = Packet::default();
        let mut entered = 0;
        for _ in 0..2000 {
            let d = DVec3::new(-0.3, -1.0, -0.45);
            let spread = rng.range(0.0, 0.5);
            let rays: Vec<PreparedRay> = (0..PACKET)
                .map(|_| {
                    let jitter = d + rng.vector(0.2);
                    prepared(DVec3::new(0.0, 3.0, 1.0) + rng.vector(spread), jitter)
                })
                .collect();
            assert!(packet.set(&rays));
            let mut node = Node4::EMPTY;
            for lane in 0..4 {
                let (a, b) = (rng.vector(2.0), rng.vector(2.0));
                let (lo, hi) = (a.min(b), a.max(b));
                let bounds = Aabb {
                    lo: Lanes([lo.x, lo.y, lo.z, 0.0]),
                    hi: Lanes([hi.x, hi.y, hi.z, 0.0]),
                };
                node.set(lane, &bounds, 0, 1);
            }
            let (t_lo, t_hi) = (rng.range(-1.0, 1.0), rng.range(1.0, 9.0));
            let (near, far) = packet.children(&node, t_lo, t_hi);
            for lane in 0..4 {
                let lo = [0, 1, 2].map(|axis| node.lower(axis)[lane]);
                let hi = [0, 1, 2].map(|axis| node.upper(axis)[lane]);
                for ray in &rays {
                    let (ray_near, ray_far) = ray.slab(lo, hi, t_lo, t_hi);
                    if ray_near <= ray_far {
                        entered += 1;
                        assert!(near[lane] <= ray_near && ray_far <= far[lane]);
                    }
                }
                let mask = packet.entering(&node, lane, t_lo, &[t_hi; PACKET]);
                for (i, ray) in rays.iter().enumerate() {
                    let (ray_near, ray_far) = ray.slab(lo, hi, t_lo, t_hi);
                    assert_eq!(mask & (1 << i) != 0, ray_near <= ray_far);
                }
            }
        }
        assert!(entered > 1000, "{entered}");
    }
}
