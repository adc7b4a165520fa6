//! Axis-aligned bounds of a mesh.

use glam::DVec3;

/// The axis-aligned box `[min, max]` of a set of points.
///
/// # Guarantees
/// From [`crate::Mesh::bounds`]: finite, and `min ≤ max` on every axis (a box may be flat, e.g. the
/// bounds of a plane). The fields are public, so a hand-built value carries no guarantee.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The smallest coordinate on each axis.
    pub min: DVec3,
    /// The largest coordinate on each axis.
    pub max: DVec3,
}

impl Bounds {
    /// The bounds of finite points; `None` for no points.
    pub(crate) fn of_points(points: &[DVec3]) -> Option<Self> {
        let (first, rest) = points.split_first()?;
        let mut bounds = Self {
            min: *first,
            max: *first,
        };
        for &point in rest {
            bounds.min = bounds.min.min(point);
            bounds.max = bounds.max.max(point);
        }
        Some(bounds)
    }

    /// The centre, `(min + max)/2`, computed as `min/2 + max/2` so that it cannot overflow.
    #[must_use]
    pub fn centre(&self) -> DVec3 {
        self.min * 0.5 + self.max * 0.5
    }

    /// `max − min`: the extent on each axis.
    #[must_use]
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    /// The length of the diagonal, `|max − min|`.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        self.size().length()
    }

    /// The smallest box containing both.
    #[must_use]
    pub fn union(&self, other: &Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Whether `point` lies in the box (boundary included).
    #[must_use]
    pub fn contains(&self, point: DVec3) -> bool {
        point.cmpge(self.min).all() && point.cmple(self.max).all()
    }
}
