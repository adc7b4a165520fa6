//! The perspective frustum P of LiSPSM §3.4–3.5, in a form that holds every warp strength from the
//! uniform map to PSM-like warps exactly.
//!
//! In light space (see [`crate::frame`]) the viewer looks down −z, y points toward the light. P's
//! near and far planes are perpendicular to z at the largest and smallest z of B, `z_max` and
//! `z_min`, `d = z_max − z_min` apart; its projection reference point p lies at distance
//! `n' = λ·d` beyond the near plane, `p = (x_eye, (y_min + y_max)/2, z_max + n')` (§3.4: x from the
//! viewpoint, y the middle of B's y range); its side planes are B's extents projected on the near
//! plane (§3.5).
//!
//! With `τ = (z_max − z)/d ∈ [0, 1]` a point's position through P's depth and `κ = 1/λ`, P's
//! homogeneous divisor is proportional to the distance from p, `w = 1 + κτ`, and the shadow map
//! is
//!
//! ```text
//! X = (2(x − p_x) − (l + r)·w)/(r − l)         lateral, [l, r] = extent of (x − p_x)/w over B
//! Y = (2 + κ)·τ − 1                            the warp axis: −1 at P's near plane, +1 at its far
//! Z = −(2(y − p_y) − (b + t)·w)/(t − b)        depth, growing away from the light
//! ```
//!
//! all divided by `w`. This is `glFrustum(l, r, b, t, n', n' + d)` seen from p with its axes
//! permuted (X lateral, Y along P's axis, depth along the light) and every row multiplied by
//! `1/n'` — which is what keeps it exact as `n' → ∞`: at `κ = 0` it is the focused uniform map
//! (an orthographic fit of B), with no infinities or cancellation on the way (formulas.md §9.1: the
//! warp's `Y(τ) = 2τ(λ + 1)/(λ + τ) − 1` is evaluated as `((2 + κ)τ − 1)/(1 + κτ)`).

use glam::{DMat4, DVec3, DVec4};

use crate::error::ShadowError;

/// Below this fraction of B's largest extent, B counts as flat along an axis.
const FLAT_FRACTION: f64 = 1e-12;

/// A fitted warp in light space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Warp {
    /// `d`, B's extent along light-space z: P's depth.
    pub(crate) depth: f64,
    /// Light space → GL clip space of the shadow map.
    pub(crate) matrix: DMat4,
}

/// The extents of a set of light-space points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Extents {
    pub(crate) min: DVec3,
    pub(crate) max: DVec3,
}

impl Extents {
    pub(crate) fn of(points: &[DVec3]) -> Self {
        points.iter().fold(
            Self {
                min: DVec3::splat(f64::INFINITY),
                max: DVec3::splat(f64::NEG_INFINITY),
            },
            |e, p| Self {
                min: e.min.min(*p),
                max: e.max.max(*p),
            },
        )
    }

    fn largest(&self) -> f64 {
        (self.max - self.min).max_element()
    }
}

/// Where P's projection reference point p sits across the warp axis, in light space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Reference {
    /// p's lateral coordinate.
    pub(crate) x: f64,
    /// p's coordinate along the light; `None`: the middle of B's range (LiSPSM §3.4).
    pub(crate) y: Option<f64>,
}

impl Reference {
    /// LiSPSM §3.4's p: x from the viewpoint (the light-space origin), y the middle of B.
    pub(crate) const EYE: Self = Self { x: 0.0, y: None };
}

/// Fits P with `κ = 1/λ` to the light-space points of B (LiSPSM §3.4–3.5), its projection
/// reference point placed across the warp axis as `reference` says.
///
/// # Errors
/// [`ShadowError::FlatFocusBody`] if B has no extent along an axis the map spans.
pub(crate) fn fit(points: &[DVec3], reference: Reference, kappa: f64) -> Result<Warp, ShadowError> {
    debug_assert!(kappa >= 0.0 && kappa.is_finite());
    let extents = Extents::of(points);
    let flat = FLAT_FRACTION * extents.largest();
    let depth = extents.max.z - extents.min.z;
    if depth <= flat {
        return Err(ShadowError::FlatFocusBody { axis: "warp axis" });
    }
    let z_max = extents.max.z;
    let eye_x = reference.x;
    let p_y = reference.y.unwrap_or(0.5 * (extents.min.y + extents.max.y));
    // w = 1 + κτ with τ = (z_max − z)/d: an affine function of the light-space point.
    let w_row = DVec4::new(0.0, 0.0, -kappa / depth, 1.0 + kappa * z_max / depth);
    let w = |p: DVec3| w_row.dot(p.extend(1.0));
    let (mut l, mut r, mut b, mut t) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in points {
        let w = w(*p);
        let (x, y) = ((p.x - eye_x) / w, (p.y - p_y) / w);
        (l, r, b, t) = (l.min(x), r.max(x), b.min(y), t.max(y));
    }
    if r - l <= flat {
        return Err(ShadowError::FlatFocusBody {
            axis: "lateral axis",
        });
    }
    if t - b <= flat {
        return Err(ShadowError::FlatFocusBody { axis: "light axis" });
    }
    // Rows of the matrix, acting on (x, y, z, 1).
    let x_row = (DVec4::new(2.0, 0.0, 0.0, -2.0 * eye_x) - (l + r) * w_row) / (r - l);
    let y_row = DVec4::new(
        0.0,
        0.0,
        -(2.0 + kappa) / depth,
        (2.0 + kappa) * z_max / depth - 1.0,
    );
    let z_row = -(DVec4::new(0.0, 2.0, 0.0, -2.0 * p_y) - (b + t) * w_row) / (t - b);
    Ok(Warp {
        depth,
        matrix: DMat4::from_cols(x_row, y_row, z_row, w_row).transpose(),
    })
}
