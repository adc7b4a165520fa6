//! Axis-aligned boxes: scene bounds S, and the bounds of a body in some frame.

use glam::{DAffine3, DVec3};

use crate::error::HullError;
use crate::finite::finite_vec;
use crate::plane::Plane;

/// An axis-aligned box `[min, max]`.
///
/// # Guarantees
/// Finite, and `min ≤ max` on every axis. A box may be flat (zero size on an axis) as a *value*, e.g.
/// the bounds of a polygon; where a box is used as a solid (scene bounds S,
/// [`crate::ConvexPolyhedron::from_aabb`]) a flat box is rejected with [`HullError::ZeroSizeBox`].
///
/// Corner `i` has x from `max` if bit 0 of `i` is set (else `min`), y from bit 1, z from bit 2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    min: DVec3,
    max: DVec3,
}

impl Aabb {
    /// The box with the given corners.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `min` or `max`; [`HullError::InvertedBox`] if `min > max` on an
    /// axis.
    pub fn new(min: DVec3, max: DVec3) -> Result<Self, HullError> {
        let min = finite_vec(min, "min")?;
        let max = finite_vec(max, "max")?;
        for axis in 0..3 {
            if min[axis] > max[axis] {
                return Err(HullError::InvertedBox { axis });
            }
        }
        Ok(Self { min, max })
    }

    /// The smallest box containing `points`.
    ///
    /// # Errors
    /// [`HullError::DegeneratePoints`] with [`crate::Degeneracy::Empty`] for no points;
    /// [`HullError::NonFinite`] naming `points` if a coordinate is not finite.
    pub fn from_points(points: &[DVec3]) -> Result<Self, HullError> {
        let (first, rest) = points.split_first().ok_or(HullError::DegeneratePoints {
            degeneracy: crate::Degeneracy::Empty,
        })?;
        let mut min = finite_vec(*first, "points")?;
        let mut max = min;
        for p in rest {
            let p = finite_vec(*p, "points")?;
            min = min.min(p);
            max = max.max(p);
        }
        Ok(Self { min, max })
    }

    /// Bounds of finite points known to be non-empty (internal).
    pub(crate) fn of_finite_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        let mut min = DVec3::splat(f64::INFINITY);
        let mut max = DVec3::splat(f64::NEG_INFINITY);
        for p in points {
            min = min.min(p);
            max = max.max(p);
        }
        debug_assert!(min.is_finite() && max.is_finite() && min.cmple(max).all());
        Self { min, max }
    }

    /// Bounds of points computed by `operation` from finite input, which may have overflowed.
    ///
    /// # Errors
    /// [`HullError::Overflow`] naming `operation` if a coordinate is not finite.
    pub(crate) fn of_computed_points(
        points: impl IntoIterator<Item = DVec3>,
        operation: &'static str,
    ) -> Result<Self, HullError> {
        let mut min = DVec3::splat(f64::INFINITY);
        let mut max = DVec3::splat(f64::NEG_INFINITY);
        for p in points {
            if !p.is_finite() {
                return Err(HullError::Overflow { operation });
            }
            min = min.min(p);
            max = max.max(p);
        }
        Ok(Self::of_finite_points([min, max]))
    }

    /// The minimum corner.
    #[must_use]
    pub fn min(&self) -> DVec3 {
        self.min
    }

    /// The maximum corner.
    #[must_use]
    pub fn max(&self) -> DVec3 {
        self.max
    }

    /// `max − min`.
    #[must_use]
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// The eight corners, indexed as described on [`Aabb`].
    #[must_use]
    pub fn corners(&self) -> [DVec3; 8] {
        std::array::from_fn(|i| {
            DVec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }

    /// The six outward face planes, in the order −x, +x, −y, +y, −z, +z.
    #[must_use]
    pub fn planes(&self) -> [Plane; 6] {
        std::array::from_fn(|i| {
            let axis = i / 2;
            let mut normal = DVec3::ZERO;
            if i % 2 == 0 {
                normal[axis] = -1.0;
                Plane::from_unit_normal_offset(normal, self.min[axis])
            } else {
                normal[axis] = 1.0;
                Plane::from_unit_normal_offset(normal, -self.max[axis])
            }
        })
    }

    /// Whether `point` lies in the box enlarged by `tolerance` on every side.
    #[must_use]
    pub fn contains(&self, point: DVec3, tolerance: f64) -> bool {
        (self.min - tolerance).cmple(point).all() && point.cmple(self.max + tolerance).all()
    }

    /// The bounds of this box's corners mapped by `transform` (in that frame).
    ///
    /// # Errors
    /// [`HullError::Overflow`] if a mapped corner lies beyond f64's range.
    pub fn transformed_bounds(&self, transform: &DAffine3) -> Result<Self, HullError> {
        Self::of_computed_points(
            self.corners().map(|c| transform.transform_point3(c)),
            "transformed_bounds",
        )
    }
}
