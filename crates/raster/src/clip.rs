//! Homogeneous clipping of the triangles that cross the near or far plane or leave the guard band
//! (Sutherland–Hodgman in clip space, before the perspective divide).
//!
//! Every intersection is computed from the vertex inside the plane towards the one outside,
//! whichever way the polygon runs, and the planes are applied in one fixed order. So two triangles
//! sharing a clipped edge compute bit-identical new vertices, and stay watertight along it. The new
//! vertices keep their unsnapped window positions too: they lie on the triangle's plane (to
//! rounding), so the depth of every piece is the depth of the whole triangle, as if unclipped.

use glam::DVec4;

use crate::vertex::{MIN_W, Viewport, WindowVertex, code};

/// The largest polygon clipping a triangle by six planes can produce.
const MAX_POLYGON: usize = 9;

/// A clip-space vertex with a component of this magnitude or more (2¹⁰⁰⁰) is scaled by
/// [`HUGE_VERTEX_SCALE`] before clipping: a plane's distance multiplies w by a guard-band factor
/// (below 2¹⁵) and intersections subtract distances, which overflowed to ∞ − ∞ = NaN for w near
/// f64's largest (found by the raster fuzzer: w = 1.06·10³⁰⁸ gave NaN window positions).
const HUGE_VERTEX: f64 = f64::from_bits((1023 + 1000) << 52);
/// 2⁻¹²⁸: a positive power of two, so a scaled vertex is the same projective point (exactly, but
/// for components that become subnormal, far below its largest); the same vertex is scaled alike
/// in every triangle that shares it, so shared edges stay bit-identical.
const HUGE_VERTEX_SCALE: f64 = f64::from_bits((1023 - 128) << 52);

/// A clipped piece of a triangle, ready to rasterize.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ClippedTriangle {
    /// The piece's vertices in window space.
    pub(crate) vertices: [WindowVertex; 3],
    /// The index of the triangle it was cut from.
    pub(crate) triangle: u32,
}

/// A plane of the clip volume as the signed distance `d(c) ≥ 0` inside.
fn distance(plane: u8, c: DVec4, (gx, gy): (f64, f64)) -> f64 {
    match plane {
        code::LEFT => c.x + gx * c.w,
        code::RIGHT => gx * c.w - c.x,
        code::BOTTOM => c.y + gy * c.w,
        code::TOP => gy * c.w - c.y,
        code::NEAR => c.z + c.w,
        _ => c.w - c.z,
    }
}

/// `c`, an intersection with `plane`, with the plane's coordinate set from its equation (`z = ±w`,
/// `x = ±g_x·w`, `y = ±g_y·w`). Interpolated, that coordinate carries an error of ε times the
/// endpoints' magnitude: endpoints at y = 2·10²³⁶ and −2.7·10²⁸⁸ put the intersection with the
/// bottom guard plane at y = −2.8·10²¹⁹ instead of −497, far outside the guard band (found by the
/// raster fuzzer). Set from w, it lies on the plane; the other coordinates were clipped to the
/// planes before, so their error stays at ε of the guard band.
fn onto_plane(plane: u8, mut c: DVec4, (gx, gy): (f64, f64)) -> DVec4 {
    match plane {
        code::LEFT => c.x = -gx * c.w,
        code::RIGHT => c.x = gx * c.w,
        code::BOTTOM => c.y = -gy * c.w,
        code::TOP => c.y = gy * c.w,
        code::NEAR => c.z = -c.w,
        _ => c.z = c.w,
    }
    c
}

/// The planes in the order they are applied.
const PLANES: [u8; 6] = [
    code::NEAR,
    code::FAR,
    code::LEFT,
    code::RIGHT,
    code::BOTTOM,
    code::TOP,
];

/// Clips the triangle `clip` (clip-space vertices) against the planes in `outside` (the union of its
/// vertices' clip codes) and appends the pieces, fan-triangulated, to `out`. Pieces whose vertices
/// end with `w ≤ 0` (only possible for matrices that are not projections) are dropped.
pub(crate) fn clip_triangle(
    clip: [DVec4; 3],
    outside: u8,
    triangle: u32,
    viewport: &Viewport,
    out: &mut Vec<ClippedTriangle>,
) {
    let guard = viewport.guard();
    let clip = clip.map(|c| {
        if c.abs().max_element() >= HUGE_VERTEX {
            c * HUGE_VERTEX_SCALE
        } else {
            c
        }
    });
    let mut polygon = [DVec4::ZERO; MAX_POLYGON];
    let mut next = [DVec4::ZERO; MAX_POLYGON];
    polygon[..3].copy_from_slice(&clip);
    let mut count = 3;
    for plane in PLANES {
        if outside & plane == 0 {
            continue;
        }
        let mut kept = 0;
        for i in 0..count {
            let a = polygon[i];
            let b = polygon[(i + 1) % count];
            let (da, db) = (distance(plane, a, guard), distance(plane, b, guard));
            if da >= 0.0 {
                next[kept] = a;
                kept += 1;
            }
            if (da >= 0.0) != (db >= 0.0) {
                // From the inside vertex towards the outside one, whichever comes first.
                let (inside, outside_vertex, d_in, d_out) = if da >= 0.0 {
                    (a, b, da, db)
                } else {
                    (b, a, db, da)
                };
                let t = d_in / (d_in - d_out);
                next[kept] = onto_plane(plane, inside + (outside_vertex - inside) * t, guard);
                kept += 1;
            }
        }
        count = kept;
        if count < 3 {
            return;
        }
        polygon[..count].copy_from_slice(&next[..count]);
    }
    if polygon[..count].iter().any(|c| c.w.is_nan() || c.w < MIN_W) {
        return;
    }
    let window: Vec<WindowVertex> = polygon[..count]
        .iter()
        .map(|&c| viewport.window_vertex(c))
        .collect();
    for i in 1..count - 1 {
        out.push(ClippedTriangle {
            vertices: [window[0], window[i], window[i + 1]],
            triangle,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::SUBPIXELS_F64;

    /// The raster fuzzer's find: w near f64's largest overflowed the guard-band distances, and
    /// an intersection became NaN (debug builds panicked in the snap). Scaled first, its pieces are
    /// dropped (an intersection's w is lost to cancellation at this scale) or finite.
    #[test]
    fn vertices_near_the_largest_f64_clip_to_finite_pieces() {
        let viewport = Viewport::new(24, 40);
        let a = DVec4::new(11.75, 5.875, 6.0, -2.247_116_418_577_894_6e307);
        let b = DVec4::new(6.0, 6.0, 5.283_203_125, 1.063_869_179_420_472e308);
        let mut out = Vec::new();
        clip_triangle([a, b, b], 63, 0, &viewport, &mut out);
        for t in &out {
            for v in t.vertices {
                assert!(
                    v.unsnapped_x.is_finite()
                        && v.unsnapped_y.is_finite()
                        && (0.0..=1.0).contains(&v.z),
                    "{v:?}"
                );
            }
        }
    }

    /// The raster fuzzer's second find: interpolated between endpoints at y = 2·10²³⁶ and
    /// −2.7·10²⁸⁸, the bottom guard plane's intersection was 2.8·10²¹⁹ off the plane. Every
    /// piece's vertices now lie within the guard band and the depth range.
    #[test]
    fn intersections_of_huge_endpoints_lie_on_their_planes() {
        let viewport = Viewport::new(24, 24);
        let triangle = [
            DVec4::new(
                -0.125,
                2.034_916_513_940_519_4e236,
                1.738_212_971_1e-313,
                1.0,
            ),
            DVec4::new(0.0, -2.192_695_645_360_899e289, 0.125, 1.0),
            DVec4::new(0.0, 0.125, 1.125, 1.0),
        ];
        let outside = triangle
            .iter()
            .fold(0, |bits, &c| bits | viewport.clip_code(c));
        let mut out = Vec::new();
        clip_triangle(triangle, outside, 0, &viewport, &mut out);
        assert!(!out.is_empty());
        let (gx, gy) = viewport.guard();
        for t in &out {
            for v in t.vertices {
                let (x, y) = (v.unsnapped_x / SUBPIXELS_F64, v.unsnapped_y / SUBPIXELS_F64);
                assert!(
                    x.abs() <= 12.0 * (gx + 1.0) && y.abs() <= 12.0 * (gy + 1.0),
                    "{v:?}"
                );
                assert!((0.0..=1.0).contains(&v.z), "{v:?}");
            }
        }
    }

    /// A vertex is a projective point: scaled by a power of two large enough to be rescaled
    /// before clipping (2¹⁰⁰⁰ on every vertex), a triangle through the near plane and the guard
    /// band gives the same pieces, bit for bit (powers of two commute with the arithmetic).
    #[test]
    fn huge_vertices_clip_as_their_unscaled_points() {
        let viewport = Viewport::new(64, 64);
        let triangle = [
            DVec4::new(0.0, 0.0, -2.0, 1.0),
            DVec4::new(600.0, 0.25, 0.0, 1.0),
            DVec4::new(0.0, 0.5, 0.5, 2.0),
        ];
        let pieces = |triangle: [DVec4; 3]| {
            let mut out = Vec::new();
            clip_triangle(triangle, 63, 0, &viewport, &mut out);
            out
        };
        let unscaled = pieces(triangle);
        assert!(!unscaled.is_empty());
        let huge = f64::from_bits((1023 + 1000) << 52);
        assert_eq!(pieces(triangle.map(|c| c * huge)), unscaled);
    }

    #[test]
    fn a_triangle_through_the_near_plane_becomes_a_quad() {
        let viewport = Viewport::new(64, 64);
        let a = DVec4::new(0.0, 0.0, -2.0, 1.0); // in front of the near plane (z < −w)
        let b = DVec4::new(0.5, 0.0, 0.0, 1.0);
        let c = DVec4::new(0.0, 0.5, 0.0, 1.0);
        let mut out = Vec::new();
        clip_triangle([a, b, c], code::NEAR, 7, &viewport, &mut out);
        assert_eq!(out.len(), 2);
        assert!(out.iter().all(|t| t.triangle == 7));
        for t in &out {
            for v in t.vertices {
                assert!(v.z >= 0.0 && v.z <= 1.0);
            }
        }
    }

    #[test]
    fn shared_edges_are_cut_identically_in_either_direction() {
        let viewport = Viewport::new(64, 64);
        let a = DVec4::new(0.1, 0.2, -3.0, 1.0);
        let b = DVec4::new(0.3, -0.1, 0.7, 1.0);
        let c = DVec4::new(-0.4, 0.6, 0.2, 1.0);
        let d = DVec4::new(0.9, 0.9, 0.1, 1.0);
        let (mut one, mut two) = (Vec::new(), Vec::new());
        clip_triangle([a, b, c], code::NEAR, 0, &viewport, &mut one);
        clip_triangle([b, a, d], code::NEAR, 1, &viewport, &mut two);
        // Snapped and unsnapped positions: depth is interpolated from the latter.
        let new_vertices = |pieces: &[ClippedTriangle]| {
            let mut v: Vec<(i32, i32, u64, u64)> = pieces
                .iter()
                .flat_map(|t| {
                    t.vertices
                        .map(|v| (v.x, v.y, v.unsnapped_x.to_bits(), v.unsnapped_y.to_bits()))
                })
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let (p, q) = (new_vertices(&one), new_vertices(&two));
        let shared = p.iter().filter(|v| q.contains(v)).count();
        assert_eq!(shared, 2, "b and the cut point on a–b: {p:?} {q:?}");
    }
}
