//! The minimum-area enclosing rectangle of a 2-D point set, by rotating calipers (Freeman & Shapira
//! 1975: some side of the optimal rectangle lies on a hull edge; Toussaint 1983: the calipers visit
//! every edge in linear time). CG06 §4 fits its shadow map this way ("compute the minimum area
//! rectangle enclosing the convex hull … we need only loop over all convex hull edges").
//!
//! # Algorithm
//! For each hull edge `i` (direction `u`, inward normal `v = perp(u)`), three caliper indices track
//! the vertices extreme along `+u`, `+v` and `−u`. Each advances while the next hull edge still points
//! its way (sign of the edge's dot product with the direction), so all three move forward only, and
//! the whole loop is O(h) after the O(n log n) hull. The rectangle with the smallest area wins; ties
//! keep the earliest edge (the hull starts at its lexicographically smallest vertex), so the result is
//! deterministic.

use glam::DVec2;

use crate::error::{HullError, ValidationError};
use crate::hull2::{ConvexHull2, ConvexPolygon2, convex_hull_2d, validation_distance_2d};
use crate::tolerance::Tolerances;
use crate::tolerance::UNIT_LENGTH_TOLERANCE;

/// A rectangle given by its centre, two orthonormal axes and half-extents along them.
///
/// # Guarantees
/// Finite; `axes[1] = perp(axes[0])` (counter-clockwise), both unit; half-extents ≥ 0 (zero for a
/// point or a segment's width).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MinAreaRect {
    center: DVec2,
    axes: [DVec2; 2],
    half_extents: DVec2,
}

impl MinAreaRect {
    /// The minimum-area rectangle enclosing `points`.
    ///
    /// # Errors
    /// As [`convex_hull_2d`].
    pub fn of_points(points: &[DVec2]) -> Result<Self, HullError> {
        Ok(Self::of_hull(&convex_hull_2d(points)?))
    }

    /// The minimum-area rectangle enclosing a hull. A point gives a zero rectangle with the x and y
    /// axes; a segment a zero-width rectangle along it.
    #[must_use]
    pub fn of_hull(hull: &ConvexHull2) -> Self {
        match hull {
            ConvexHull2::Point(p) => Self {
                center: *p,
                axes: [DVec2::X, DVec2::Y],
                half_extents: DVec2::ZERO,
            },
            ConvexHull2::Segment(a, b) => {
                let u = (*b - *a).normalize();
                Self {
                    center: (*a + *b) * 0.5,
                    axes: [u, u.perp()],
                    half_extents: DVec2::new(0.5 * (*b - *a).length(), 0.0),
                }
            }
            ConvexHull2::Polygon(polygon) => rotating_calipers(polygon),
        }
    }

    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec2 {
        self.center
    }

    /// The two unit axes; the second is the first turned a quarter counter-clockwise.
    #[must_use]
    pub fn axes(&self) -> [DVec2; 2] {
        self.axes
    }

    /// The half-extents along the two axes.
    #[must_use]
    pub fn half_extents(&self) -> DVec2 {
        self.half_extents
    }

    /// The area.
    #[must_use]
    pub fn area(&self) -> f64 {
        4.0 * self.half_extents.x * self.half_extents.y
    }

    /// The corners, counter-clockwise, starting at `center − axes[0]·e₀ − axes[1]·e₁`.
    #[must_use]
    pub fn corners(&self) -> [DVec2; 4] {
        let [u, v] = self.axes;
        let (a, b) = (u * self.half_extents.x, v * self.half_extents.y);
        [
            self.center - a - b,
            self.center + a - b,
            self.center + a + b,
            self.center - a + b,
        ]
    }

    /// Whether `point` lies in the rectangle enlarged by `tolerance` on every side.
    #[must_use]
    pub fn contains(&self, point: DVec2, tolerance: f64) -> bool {
        let d = point - self.center;
        self.axes
            .iter()
            .zip([self.half_extents.x, self.half_extents.y])
            .all(|(axis, half)| axis.dot(d).abs() <= half + tolerance)
    }

    /// Checks the guarantees and that every point lies inside within the validation distance of
    /// `tolerances` (scaled to the points).
    ///
    /// # Errors
    /// [`ValidationError::NonFinite`], [`ValidationError::NotOrthonormal`],
    /// [`ValidationError::NegativeExtent`] or [`ValidationError::PointOutside`].
    pub fn validate(
        &self,
        points: &[DVec2],
        tolerances: &Tolerances,
    ) -> Result<(), ValidationError> {
        let [u, v] = self.axes;
        if !(self.center.is_finite()
            && u.is_finite()
            && v.is_finite()
            && self.half_extents.is_finite())
        {
            return Err(ValidationError::NonFinite);
        }
        if (u.length() - 1.0).abs() > UNIT_LENGTH_TOLERANCE
            || (v - u.perp()).length() > UNIT_LENGTH_TOLERANCE
        {
            return Err(ValidationError::NotOrthonormal);
        }
        if self.half_extents.min_element() < 0.0 {
            return Err(ValidationError::NegativeExtent);
        }
        let limit = validation_distance_2d(points, tolerances);
        for (point, p) in points.iter().enumerate() {
            if !self.contains(*p, limit) {
                let d = *p - self.center;
                let distance = (u.dot(d).abs() - self.half_extents.x)
                    .max(v.dot(d).abs() - self.half_extents.y);
                return Err(ValidationError::PointOutside { point, distance });
            }
        }
        Ok(())
    }
}

fn rotating_calipers(polygon: &ConvexPolygon2) -> MinAreaRect {
    let p = polygon.vertices();
    let n = p.len();
    let edge = |k: usize| p[(k + 1) % n] - p[k % n];
    // Advance `j` while the edge leaving it still goes along `direction` (sign > 0).
    let advance = |mut j: usize, direction: DVec2, sign: f64| {
        for _ in 0..n {
            if sign * edge(j).dot(direction) > 0.0 {
                j = (j + 1) % n;
            } else {
                break;
            }
        }
        j
    };
    let (mut far_u, mut far_v, mut near_u) = (0, 1, 1);
    let mut best: Option<(f64, MinAreaRect)> = None;
    for i in 0..n {
        let u = edge(i).normalize();
        let v = u.perp();
        if i == 0 {
            far_u = advance(0, u, 1.0);
            far_v = advance(far_u, v, 1.0);
            near_u = advance(far_v, u, -1.0);
        } else {
            far_u = advance(far_u, u, 1.0);
            far_v = advance(far_v, v, 1.0);
            near_u = advance(near_u, u, -1.0);
        }
        let origin = p[i];
        let u_max = (p[far_u] - origin).dot(u);
        let u_min = (p[near_u] - origin).dot(u);
        let v_max = (p[far_v] - origin).dot(v);
        let area = (u_max - u_min) * v_max;
        if best.as_ref().is_none_or(|(a, _)| area < *a) {
            let rect = MinAreaRect {
                center: origin + u * (0.5 * (u_min + u_max)) + v * (0.5 * v_max),
                axes: [u, v],
                half_extents: DVec2::new(0.5 * (u_max - u_min), 0.5 * v_max),
            };
            best = Some((area, rect));
        }
    }
    best.map(|(_, rect)| rect)
        .expect("a polygon has at least three edges")
}
