//! Planes and the half-spaces they bound.

use glam::DVec3;

use crate::error::HullError;
use crate::finite::{finite_vec, unit_vec};

/// A plane `n·x + d = 0` with unit normal `n`, and the closed half-space `n·x + d ≤ 0` it bounds.
///
/// # Guarantees
/// `normal` has unit length (to rounding) and both `normal` and `offset` are finite. The normal
/// points **out of** the half-space: a body's face planes have outward normals, and
/// [`Plane::signed_distance`] is positive outside, negative inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    normal: DVec3,
    offset: f64,
}

impl Plane {
    /// The plane through `point` with outward normal along `normal` (normalised here).
    ///
    /// # Errors
    /// [`HullError::NonFinite`] or [`HullError::ZeroVector`] naming `point` or `normal`.
    pub fn from_point_normal(point: DVec3, normal: DVec3) -> Result<Self, HullError> {
        let point = finite_vec(point, "point")?;
        let normal = unit_vec(normal, "normal")?;
        Ok(Self::from_unit_normal_point(normal, point))
    }

    /// The plane through three points; the normal is `(b − a) × (c − a)`, so the half-space is on the
    /// side from which `a, b, c` appear clockwise.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `a`, `b` or `c`; [`HullError::ZeroVector`] naming `normal` if the
    /// points are collinear.
    pub fn from_points(a: DVec3, b: DVec3, c: DVec3) -> Result<Self, HullError> {
        let a = finite_vec(a, "a")?;
        let b = finite_vec(b, "b")?;
        let c = finite_vec(c, "c")?;
        let normal = unit_vec((b - a).cross(c - a), "normal")?;
        Ok(Self::from_unit_normal_point(normal, a))
    }

    /// Internal constructor: `normal` is already unit and finite, `point` finite.
    pub(crate) fn from_unit_normal_point(normal: DVec3, point: DVec3) -> Self {
        Self {
            normal,
            offset: -normal.dot(point),
        }
    }

    /// Internal constructor from coefficients already checked by the caller.
    pub(crate) fn from_unit_normal_offset(normal: DVec3, offset: f64) -> Self {
        Self { normal, offset }
    }

    /// The unit outward normal `n`.
    #[must_use]
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// The offset `d` in `n·x + d = 0`.
    #[must_use]
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// `n·x + d`: the signed distance of `point`, positive outside the half-space.
    #[must_use]
    pub fn signed_distance(&self, point: DVec3) -> f64 {
        self.normal.dot(point) + self.offset
    }

    /// Whether `point` lies in the closed half-space, allowing `tolerance` outside.
    #[must_use]
    pub fn contains(&self, point: DVec3, tolerance: f64) -> bool {
        self.signed_distance(point) <= tolerance
    }

    /// The same plane with the opposite half-space.
    #[must_use]
    pub fn flipped(&self) -> Self {
        Self {
            normal: -self.normal,
            offset: -self.offset,
        }
    }

    /// The orthogonal projection of `point` onto the plane.
    #[must_use]
    pub fn project(&self, point: DVec3) -> DVec3 {
        point - self.normal * self.signed_distance(point)
    }
}
