//! The watertight ray–triangle test (Woop, Benthin & Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1), 2013, <https://jcgt.org/published/0002/01/05/>), in f64 with an exact
//! sign for every edge function.
//!
//! # The test
//! With the shear of [`PreparedRay`] (dominant axis `kz`), each vertex `p` becomes the 2-D point
//! `(a[kx] − Sx·a[kz], a[ky] − Sy·a[kz])` with `a = p − origin`, and the ray becomes the 2-D
//! origin. The three edge functions are 2-D cross products of the sheared vertices `A, B, C`:
//! `U = C×B` (edge B→C, the weight of `p0`), `V = A×C` (weight of `p1`), `W = B×A` (weight of
//! `p2`). The ray hits when `U, V, W` are all ≥ 0 or all ≤ 0 and `det = U + V + W ≠ 0`; then
//! `t = (U·Az + V·Bz + W·Cz)/det` with `Az = Sz·a[kz]`, `u = V/det`, `v = W/det`. Back faces hit
//! (no culling).
//!
//! # Why it is watertight
//! * A vertex is sheared by the same operations in every triangle that uses it, so two triangles
//!   sharing an edge share that edge's sheared end points exactly.
//! * An edge's function is `X×Y` in one triangle and `Y×X` in a neighbour that runs the edge the
//!   other way; in floating point `fl(fl(a·b) − fl(c·d)) = −fl(fl(c·d) − fl(a·b))`, so the two
//!   values are exact negatives: the ray passes the edge on one side for both.
//! * The sign is exact: rounding is monotone, so a non-zero `fl(fl(a·b) − fl(c·d))` has the sign
//!   of `a·b − c·d`; when it is zero the products' rounding errors, exact by FMA
//!   (`fma(a, b, −fl(a·b))`), decide. This is the paper's double-precision fallback, one level up.
//!   (Exact unless a product is below 2⁻⁹⁶⁹ in magnitude, where the FMA error term is itself
//!   rounded; the sign is then still never wrong, at worst zero.)
//!
//! So the decision is the exact 2-D point-in-triangle test of the sheared (rounded) vertices: seen
//! along the ray, neighbouring triangles meet without gaps along their shared edges and vertices.
//! (Where the surface folds over along the ray, at a silhouette, both sides lie on the same side
//! of the shared edge, and a ray exactly through it may touch neither: it only grazes.)
//!
//! # Tie rule
//! A zero edge function counts as inside (`≥ 0`/`≤ 0`): a ray through a shared edge (exactly, in
//! the sheared coordinates) is reported by **both** triangles, a ray through a shared vertex by
//! every triangle around it whose other edge functions agree. Never by none. A ray lying in the
//! plane of a triangle (`U = V = W = 0`) misses it, as does a ray through a zero-area triangle,
//! which [`crate::Bvh`] does not store at all.
//!
//! # Four at a time
//! The tree stores triangles in blocks of four ([`TriangleBlock`], coordinates side by side) and
//! [`intersect_block`] tests one ray against the four with lane-by-lane code that compiles to AVX
//! instructions. Each lane performs exactly the operations of [`intersect`], in the same order
//! (Rust never contracts a multiply and an add into an FMA), so each lane's result is the same to
//! the bit as the one-triangle test's: only the exact-sign fallback and the clamp, rare, run per
//! lane.

use wide::f64x4;

use crate::ray::{PreparedRay, PreparedRays};

/// A stored triangle: `p0.x, p0.y, p0.z, p1.x, …, p2.z`.
pub(crate) type TriangleVertices = [f64; 9];

/// Triangles per [`TriangleBlock`].
pub(crate) const BLOCK: usize = 4;

/// Four triangles side by side: `p[c][k]` is coordinate `c` (`p0.x, p0.y, p0.z, p1.x, …, p2.z`) of
/// lane `k`'s triangle, and `id[k]` its index in the mesh. A leaf of fewer than four triangles
/// repeats its last one in the spare lanes (a repeated triangle changes no query's answer).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TriangleBlock {
    pub(crate) p: [[f64; BLOCK]; 9],
    pub(crate) id: [u32; BLOCK],
}

impl TriangleBlock {
    /// Lane `k`'s triangle.
    #[inline]
    pub(crate) fn triangle(&self, k: usize) -> TriangleVertices {
        std::array::from_fn(|c| self.p[c][k])
    }
}

/// `a×b = a.x·b.y − a.y·b.x` with the exact sign (see the module documentation); exactly
/// antisymmetric: `cross(b, a) = −cross(a, b)`.
#[inline]
fn cross(ax: f64, ay: f64, bx: f64, by: f64) -> f64 {
    let p = ax * by;
    let q = ay * bx;
    let d = p - q;
    if d != 0.0 {
        d
    } else {
        // p == q: the sign of a·b − c·d is that of the difference of the rounding errors, which
        // the FMA gives exactly (barring underflow).
        ax.mul_add(by, -p) - ay.mul_add(bx, -q)
    }
}

/// The watertight test: `Some((t, u, v))` if the ray's line meets the triangle (at any `t`, not
/// clamped), `None` otherwise. `KZ` is the ray's dominant axis
/// ([`PreparedRay::kz`]), a constant so that the coordinate permutation costs nothing.
#[inline(always)]
pub(crate) fn watertight<const KZ: usize>(
    ray: &PreparedRay,
    triangle: &TriangleVertices,
) -> Option<(f64, f64, f64)> {
    let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
    let o = &ray.origin;
    let [sx, sy, sz] = ray.shear;
    let sheared = |i: usize| {
        let x = triangle[3 * i + kx] - o[kx];
        let y = triangle[3 * i + ky] - o[ky];
        let z = triangle[3 * i + KZ] - o[KZ];
        (x - sx * z, y - sy * z, z)
    };
    let (ax, ay, az) = sheared(0);
    let (bx, by, bz) = sheared(1);
    let (cx, cy, cz) = sheared(2);
    let u = cross(cx, cy, bx, by);
    let v = cross(ax, ay, cx, cy);
    let w = cross(bx, by, ax, ay);
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let t = (u * (sz * az) + v * (sz * bz) + w * (sz * cz)) / det;
    Some((t, v / det, w / det))
}

/// [`cross`] lane by lane: the products and their difference for all lanes, the exact fallback
/// only for lanes where the difference is zero.
#[inline(always)]
fn cross4(ax: &Lanes, ay: &Lanes, bx: &Lanes, by: &Lanes) -> Lanes {
    let mut d: Lanes = std::array::from_fn(|k| ax[k] * by[k] - ay[k] * bx[k]);
    if d.contains(&0.0) {
        for k in 0..BLOCK {
            if d[k] == 0.0 {
                d[k] = cross(ax[k], ay[k], bx[k], by[k]);
            }
        }
    }
    d
}

/// One f64 per triangle of a block.
type Lanes = [f64; BLOCK];

/// Vertex `i` of the four triangles of `block`, sheared as in [`watertight`].
#[inline(always)]
fn sheared_block<const KZ: usize>(
    ray: &PreparedRay,
    block: &TriangleBlock,
    i: usize,
) -> (Lanes, Lanes, Lanes) {
    let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
    let o = &ray.origin;
    let [sx, sy, _] = ray.shear;
    let p = &block.p;
    let z: Lanes = std::array::from_fn(|k| p[3 * i + KZ][k] - o[KZ]);
    let x: Lanes = std::array::from_fn(|k| (p[3 * i + kx][k] - o[kx]) - sx * z[k]);
    let y: Lanes = std::array::from_fn(|k| (p[3 * i + ky][k] - o[ky]) - sy * z[k]);
    (x, y, z)
}

/// The watertight test against the four triangles of `block`: for each lane whose triangle the
/// ray's line meets (bit `k` of the returned mask), `(t, u, v)` exactly as [`watertight`]
/// computes them for that triangle; other lanes hold no meaningful values.
#[inline(always)]
pub(crate) fn watertight_block<const KZ: usize>(
    ray: &PreparedRay,
    block: &TriangleBlock,
) -> (u32, Lanes, Lanes, Lanes) {
    let (ax, ay, az) = sheared_block::<KZ>(ray, block, 0);
    let (bx, by, bz) = sheared_block::<KZ>(ray, block, 1);
    let (cx, cy, cz) = sheared_block::<KZ>(ray, block, 2);
    let u = cross4(&cx, &cy, &bx, &by);
    let v = cross4(&ax, &ay, &cx, &cy);
    let w = cross4(&bx, &by, &ax, &ay);
    let det: Lanes = std::array::from_fn(|k| u[k] + v[k] + w[k]);
    let mut mask = 0;
    for k in 0..BLOCK {
        let negative = u[k] < 0.0 || v[k] < 0.0 || w[k] < 0.0;
        let positive = u[k] > 0.0 || v[k] > 0.0 || w[k] > 0.0;
        mask |= u32::from(!(negative && positive) && det[k] != 0.0) << k;
    }
    if mask == 0 {
        return (0, [0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
    }
    let sz = ray.shear[2];
    let t: Lanes = std::array::from_fn(|k| {
        (u[k] * (sz * az[k]) + v[k] * (sz * bz[k]) + w[k] * (sz * cz[k])) / det[k]
    });
    let bu: Lanes = std::array::from_fn(|k| v[k] / det[k]);
    let bv: Lanes = std::array::from_fn(|k| w[k] / det[k]);
    (mask, t, bu, bv)
}

/// [`intersect`] against the four triangles of `block`: calls `found(lane, t, u, v)` for each lane
/// whose triangle the ray hits, in lane order, with the same `(t, u, v)` as [`intersect`] gives
/// for that triangle. Stops, returning `true`, when `found` returns `true`.
#[inline(always)]
pub(crate) fn intersect_block<const KZ: usize>(
    ray: &PreparedRay,
    block: &TriangleBlock,
    mut found: impl FnMut(usize, f64, f64, f64) -> bool,
) -> bool {
    let (mut mask, t, u, v) = watertight_block::<KZ>(ray, block);
    while mask != 0 {
        let k = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        if let Some(t) = clamp(ray, &block.triangle(k), t[k])
            && found(k, t, u[k], v[k])
        {
            return true;
        }
    }
    false
}

/// Rays per [`intersect_rays`] call.
pub(crate) const RAYS: usize = 4;

/// [`cross`] of four lanes: the products and their difference side by side, the exact fallback
/// only for lanes where the difference is zero.
#[inline(always)]
fn cross_lanes(ax: f64x4, ay: f64x4, bx: f64x4, by: f64x4) -> f64x4 {
    let (p, q) = (ax * by, ay * bx);
    let d = p - q;
    let lanes = d.to_array();
    if !lanes.contains(&0.0) {
        return d;
    }
    let [ax, ay, bx, by] = [ax, ay, bx, by].map(f64x4::to_array);
    f64x4::new(std::array::from_fn(|k| {
        if lanes[k] == 0.0 {
            cross(ax[k], ay[k], bx[k], by[k])
        } else {
            lanes[k]
        }
    }))
}

/// [`intersect`] of the four rays of `rays` from `first`, which share their dominant axis `KZ`,
/// against one triangle, the rays in lanes: each lane performs [`watertight`]'s operations in its
/// order (the sheared vertices, the three edge functions with their exact signs, the determinant,
/// `t`, `u` and `v`: the divisions of four rays in one instruction each) and [`intersect`]'s clamp
/// (the triangle's box once, each lane's slab: `PreparedRays::slabs`); `hit(k, (t, u, v))` for
/// each ray `first + k` that hits — the same `(t, u, v)` as [`intersect`] gives it, bit for bit.
///
/// The hits are handed over lane by lane rather than returned as an array of options: such an
/// array, written field by field, was read back across the stores that wrote it (a
/// store-forwarding stall; docs/benchmarks.md).
#[inline(always)]
pub(crate) fn intersect_rays<const KZ: usize>(
    rays: &PreparedRays,
    first: usize,
    triangle: &TriangleVertices,
    mut hit: impl FnMut(usize, (f64, f64, f64)),
) {
    let (kx, ky) = ((KZ + 1) % 3, (KZ + 2) % 3);
    let lanes = |values: &[f64]| PreparedRays::lanes(values, first);
    let (ox, oy, oz) = (
        lanes(&rays.origin[kx]),
        lanes(&rays.origin[ky]),
        lanes(&rays.origin[KZ]),
    );
    let (sx, sy, sz) = (
        lanes(&rays.shear[0]),
        lanes(&rays.shear[1]),
        lanes(&rays.shear[2]),
    );
    let sheared = |i: usize| {
        let x = f64x4::splat(triangle[3 * i + kx]) - ox;
        let y = f64x4::splat(triangle[3 * i + ky]) - oy;
        let z = f64x4::splat(triangle[3 * i + KZ]) - oz;
        (x - sx * z, y - sy * z, z)
    };
    let (ax, ay, az) = sheared(0);
    let (bx, by, bz) = sheared(1);
    let (cx, cy, cz) = sheared(2);
    let u = cross_lanes(cx, cy, bx, by);
    let v = cross_lanes(ax, ay, cx, cy);
    let w = cross_lanes(bx, by, ax, ay);
    let det = u + v + w;
    let t = (u * (sz * az) + v * (sz * bz) + w * (sz * cz)) / det;
    let (bu, bv) = (v / det, w / det);
    // `watertight`'s decision: an edge function of each sign, or a zero determinant, misses.
    let zero = f64x4::ZERO;
    let negative = u.simd_lt(zero) | v.simd_lt(zero) | w.simd_lt(zero);
    let positive = u.simd_gt(zero) | v.simd_gt(zero) | w.simd_gt(zero);
    let missed = ((negative & positive) | det.simd_eq(zero)).to_bitmask();
    if missed == (1 << RAYS) - 1 {
        return;
    }
    let (lo, hi) = bounds(triangle);
    let (near, far) = rays.slabs(first, lo, hi);
    let [t, near, far, bu, bv] = [t, near, far, bu, bv].map(f64x4::to_array);
    for k in 0..RAYS {
        if missed & (1 << k) != 0 {
            continue;
        }
        if let Some(t) = clamp_into(t[k], near[k], far[k]) {
            hit(k, (t, bu[k], bv[k]));
        }
    }
}

/// The smallest box holding the triangle: `(lo, hi)`.
#[inline]
pub(crate) fn bounds(triangle: &TriangleVertices) -> ([f64; 3], [f64; 3]) {
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for axis in 0..3 {
        let (a, b, c) = (triangle[axis], triangle[3 + axis], triangle[6 + axis]);
        lo[axis] = a.min(b).min(c);
        hi[axis] = a.max(b).max(c);
    }
    (lo, hi)
}

/// The crate's one ray–triangle test: the watertight decision, with `t` clamped into the
/// parameter interval of the triangle's padded bounding box. Returns `(t, u, v)`; callers keep the
/// hits with `t` in their open interval `(t_min, t_max)`.
///
/// The clamp changes `t` only for rays so close to the triangle's plane that the division above
/// has lost its accuracy. The padding guarantees that the interval is never empty for a watertight
/// hit (so the emptiness check below never fires for one; it keeps the definition total). Because
/// the interval of a triangle lies inside that of every box holding it, a traversal that enters
/// every box whose interval meets `[t_min, t_best]` finds exactly what a loop over all triangles
/// finds.
#[inline(always)]
pub(crate) fn intersect<const KZ: usize>(
    ray: &PreparedRay,
    triangle: &TriangleVertices,
) -> Option<(f64, f64, f64)> {
    let (t, u, v) = watertight::<KZ>(ray, triangle)?;
    Some((clamp(ray, triangle, t)?, u, v))
}

/// A watertight hit's `t` clamped into the parameter interval of the triangle's padded box (see
/// [`intersect`]).
#[inline]
fn clamp(ray: &PreparedRay, triangle: &TriangleVertices, t: f64) -> Option<f64> {
    let (lo, hi) = bounds(triangle);
    let (near, far) = ray.slab(lo, hi, f64::NEG_INFINITY, f64::INFINITY);
    clamp_into(t, near, far)
}

/// `t` clamped into the box's parameter interval `[near, far]`; `None` if it is empty, which
/// never happens for a watertight hit (see [`intersect`]).
#[inline(always)]
fn clamp_into(t: f64, near: f64, far: f64) -> Option<f64> {
    debug_assert!(
        near <= far,
        "a watertight hit outside its padded box: {near} > {far}"
    );
    (near <= far).then(|| t.max(near).min(far))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::{RAYS, TriangleVertices, intersect, intersect_rays};
    use crate::ray::{PreparedRay, PreparedRays, Ray};
    use shadowlab_test_random::SplitMix;

    /// A point with small integer coordinates: rays between such points meet edges and vertices
    /// exactly, where the edge functions are zero and their exact signs decide.
    fn lattice_point(random: &mut SplitMix) -> DVec3 {
        random.vector(3.0).round()
    }

    /// Four rays against one triangle, in lanes, give each ray's own [`intersect`], to the bit:
    /// random and lattice triangles, rays parallel (as a grid casts them) and nearly so, aimed at
    /// random points, at the vertices and at the edges' midpoints, and lying in the triangle's
    /// plane.
    #[test]
    fn four_rays_in_lanes_are_each_rays_own() {
        let mut random = SplitMix(0x5eed_0000_0000_07a1);
        let (mut hits, mut misses) = (0, 0);
        for round in 0..20_000_usize {
            let lattice = round % 2 == 0;
            let vertex = |random: &mut SplitMix| {
                if lattice {
                    lattice_point(random)
                } else {
                    random.vector(2.0)
                }
            };
            let p = [
                vertex(&mut random),
                vertex(&mut random),
                vertex(&mut random),
            ];
            let triangle: TriangleVertices = std::array::from_fn(|c| p[c / 3][c % 3]);
            let direction = if lattice {
                lattice_point(&mut random) + DVec3::new(0.0, 0.0, 4.0)
            } else {
                random.vector(1.0)
            };
            if direction == DVec3::ZERO {
                continue;
            }
            let held: Vec<Ray> = (0..RAYS)
                .map(|k| {
                    let target = match (round + k) % 6 {
                        0 => p[k % 3],
                        1 => (p[k % 3] + p[(k + 1) % 3]) * 0.5,
                        2 => p[0] + (p[1] - p[0]) * random.unit() + (p[2] - p[0]) * random.unit(),
                        _ => vertex(&mut random),
                    };
                    let d = match round % 5 {
                        0 => direction + random.vector(1e-9),
                        // In the triangle's plane.
                        1 if p[1] != p[0] => p[1] - p[0],
                        _ => direction,
                    };
                    Ray::new(target - d * random.range(1.0, 3.0).round(), d).expect("a valid ray")
                })
                .collect();
            let rays: Vec<PreparedRay> = held
                .iter()
                .map(|ray| PreparedRay::new(ray, 8.0).expect("a valid ray"))
                .collect();
            let kz = rays[0].kz;
            if rays.iter().any(|ray| ray.kz != kz) {
                continue;
            }
            // Held field by field, after a ray that is not among the four.
            let mut lanes = PreparedRays::default();
            let other = Ray::new(DVec3::ZERO, DVec3::X).expect("valid");
            assert!(lanes.set_up(&[&[other], held.as_slice()].concat(), 8.0));
            let mut together = [None; RAYS];
            let mut found = |k: usize, hit| together[k] = Some(hit);
            match kz {
                0 => intersect_rays::<0>(&lanes, 1, &triangle, &mut found),
                1 => intersect_rays::<1>(&lanes, 1, &triangle, &mut found),
                _ => intersect_rays::<2>(&lanes, 1, &triangle, &mut found),
            }
            for (k, ray) in rays.iter().enumerate() {
                let one = match kz {
                    0 => intersect::<0>(ray, &triangle),
                    1 => intersect::<1>(ray, &triangle),
                    _ => intersect::<2>(ray, &triangle),
                };
                let bits =
                    |hit: Option<(f64, f64, f64)>| hit.map(|(t, u, v)| [t, u, v].map(f64::to_bits));
                assert_eq!(bits(together[k]), bits(one), "round {round}, ray {k}");
                if one.is_some() {
                    hits += 1;
                } else {
                    misses += 1;
                }
            }
        }
        assert!(hits > 10_000 && misses > 10_000, "{hits} {misses}");
    }
}
