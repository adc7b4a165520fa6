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

use crate::ray::PreparedRay;

/// A stored triangle: `p0.x, p0.y, p0.z, p1.x, …, p2.z`.
pub(crate) type TriangleVertices = [f64; 9];

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
    let (lo, hi) = bounds(triangle);
    let (near, far) = ray.slab(lo, hi, f64::NEG_INFINITY, f64::INFINITY);
    debug_assert!(
        near <= far,
        "a watertight hit outside its padded box: {near} > {far}"
    );
    if near > far {
        return None;
    }
    Some((t.max(near).min(far), u, v))
}
