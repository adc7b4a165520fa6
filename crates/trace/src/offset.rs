//! Moving a surface point off its surface before casting a ray from it (the self-intersection
//! problem).
//!
//! Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems,
//! ch. 6, 2019 (<https://doi.org/10.1007/978-1-4842-4427-2_6>), offset a hit point along the
//! geometric normal by a fixed number of ulps of its coordinates (an absolute amount near the
//! origin), in f32. [`offset_origin`] does the same in f64, with the amount tied to a stated
//! error bound instead of a tuned constant:
//!
//! * **Scale.** The offset is `OFFSET_ULPS·ε·m` along the unit normal, `m` the larger of the
//!   caller's `magnitude` and the point's largest absolute coordinate (at least [`MIN_MAGNITUDE`]).
//!   The point's own coordinates are not enough: a point near the origin on a large triangle (a
//!   ground plane around the scene) carries the rounding error of the triangle's far vertices,
//!   which is why the caller passes the magnitude of the data the point was computed from — the
//!   triangle's, or [`crate::Bvh::magnitude`] for any point on the mesh.
//! * **Precondition.** The point lies within `SURFACE_POINT_ULPS·ε·m` (Euclidean) of the plane
//!   of its triangle, and `geometric_normal` is within 60° of that plane's normal (either
//!   orientation). [`crate::Bvh::hit_point`] meets the first (within `4.4·ε·m`); a normal computed
//!   as the cross product of two edges in f64 meets the second unless the triangle is within a few
//!   ulps of zero area (its angular error is about `3ε/sin α`, α the angle between the edges).
//! * **Guarantee.** The result lies strictly on the side of the plane into which
//!   `±geometric_normal` points, the sign being that of `geometric_normal·toward`, at a distance
//!   of at least `100·ε·m`.
//!
//! **Proof** (`u = ε/2`; `n̂` the computed unit normal, `N` the plane's unit normal oriented like
//! `n̂`, so `n̂·N ≥ (1 − 2u)·cos 60°`). The step is `D = p' − p` with
//! `D_c = fl(n̂_c·s·δ) + r_c`, `δ = 512u·m` (exact: a power-of-two multiple of `m`), `s = ±1`, and
//! `|r_c| ≤ u·(m + δ)` the rounding of the addition. Then
//! `D·sN ≥ δ·(n̂·N) − δ·u·|n̂|·|N| − √3·u·(m + δ) ≥ 512u·m·(0.5 − 2u) − 1.8u·m ≥ 254u·m`. The point
//! starts at most `32u·m` on the wrong side, so `p'` ends at least `222u·m = 111·ε·m` on the
//! intended side. ∎
//!
//! **What it buys a ray cast from `p'`** away from the surface (`direction·sN > 0`): the exact ray
//! stays farther than `222u·m` from the plane, while the watertight test perturbs the triangle's
//! vertices by less than `7u·L` with `L ≤ 2m + δ` here (see `bvh`'s documentation), so every hit
//! the test could report on the point's own triangle lies at a negative exact parameter. The
//! reported parameter is rounded; the tests check that no ray leaving at angles down to 10⁻⁶ rad
//! hits its own triangle with `t_min = 0`, but this last step is measured, not proven.

use glam::DVec3;

use crate::error::TraceError;
use crate::ray::MAX_COORDINATE;

/// The offset distance, in units of `f64::EPSILON × m` (see the module documentation); as Wächter
/// & Binder's 256 ulps, here of the magnitude `m` rather than of each coordinate.
pub const OFFSET_ULPS: f64 = 256.0;

/// How far from its plane a point given to [`offset_origin`] may lie, in units of
/// `f64::EPSILON × m`.
pub const SURFACE_POINT_ULPS: f64 = 16.0;

/// The smallest magnitude `m` used, 2⁻⁹⁰⁰ ≈ 1.2·10⁻²⁷¹, so that the offset is a normal number.
pub const MIN_MAGNITUDE: f64 = f64::from_bits((1023 - 900) << 52);

/// `v` finite, else [`TraceError::NonFinite`] naming `parameter`.
fn finite(v: DVec3, parameter: &'static str) -> Result<DVec3, TraceError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(TraceError::NonFinite { parameter })
    }
}

/// `v` scaled by a power of two (exactly) so that its largest component lies in [0.5, 2): products
/// and squares of it neither overflow nor underflow.
fn rescaled(v: DVec3) -> DVec3 {
    let largest = v.abs().max_element();
    if largest == 0.0 {
        return v;
    }
    let exponent = largest.log2().round().clamp(-1074.0, 1023.0);
    #[expect(
        clippy::cast_possible_truncation,
        reason = "an integer clamped to the exponent range"
    )]
    let exponent = exponent as i32;
    // 2^-exponent in two steps, each a normal power of two, so that no factor overflows.
    let half = exponent / 2;
    v * 2f64.powi(-half) * 2f64.powi(half - exponent)
}

/// `point` moved off its surface, by `OFFSET_ULPS·ε·m` along the unit geometric normal, to the
/// side `toward` points to: the origin for a ray leaving the surface (toward a light, a reflected
/// direction, …). `m = max(magnitude, |point|∞, MIN_MAGNITUDE)`.
///
/// # Guarantees
/// If `point` lies within `SURFACE_POINT_ULPS·ε·m` of the plane of its triangle and
/// `geometric_normal` within 60° of that plane's normal, the result lies strictly on the side of
/// the plane that `s·geometric_normal` points to, with `s` the sign of `geometric_normal·toward`
/// (+1 when that product is zero), at least `100·ε·m` from the plane. Proof and sources in the
/// module documentation.
///
/// # Errors
/// [`TraceError::NonFinite`] naming `point`, `geometric_normal`, `toward` or `magnitude`;
/// [`TraceError::OutOfRange`] naming `point` (a coordinate beyond [`MAX_COORDINATE`]) or
/// `magnitude` (negative, or beyond [`MAX_COORDINATE`]); [`TraceError::ZeroNormal`].
pub fn offset_origin(
    point: DVec3,
    geometric_normal: DVec3,
    toward: DVec3,
    magnitude: f64,
) -> Result<DVec3, TraceError> {
    let point = finite(point, "point")?;
    let normal = finite(geometric_normal, "geometric_normal")?;
    let toward = finite(toward, "toward")?;
    if !magnitude.is_finite() {
        return Err(TraceError::NonFinite {
            parameter: "magnitude",
        });
    }
    if !(0.0..=MAX_COORDINATE).contains(&magnitude) {
        return Err(TraceError::OutOfRange {
            parameter: "magnitude",
            value: magnitude,
        });
    }
    let largest = point.abs().max_element();
    if largest > MAX_COORDINATE {
        return Err(TraceError::OutOfRange {
            parameter: "point",
            value: largest,
        });
    }
    if normal == DVec3::ZERO {
        return Err(TraceError::ZeroNormal);
    }
    let unit = rescaled(normal).normalize();
    let side = if unit.dot(rescaled(toward)) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let m = magnitude.max(largest).max(MIN_MAGNITUDE);
    // A power-of-two multiple of m: exact.
    let distance = m * (OFFSET_ULPS * f64::EPSILON);
    Ok(point + unit * (side * distance))
}
