//! 2-D convex hulls (Andrew's monotone chain with exact `orient2d`) and axis-aligned bounds.
//!
//! The hull is exact: its vertices are input points (bit for bit), every turn is decided by
//! `robust::orient2d` on the points rescaled by a power of two (exact), and collinear points on an edge
//! are not vertices. No tolerance is involved, so degenerate input gives an exact degenerate outcome:
//! [`ConvexHull2::Point`] or [`ConvexHull2::Segment`].

use glam::DVec2;
use robust::{Coord, orient2d};

use crate::error::{Degeneracy, HullError, ValidationError};
use crate::finite::{flush_tiny, rescale_for};
use crate::tolerance::{Scale, Tolerances};

/// The convex hull of a 2-D point set: a point, a segment, or a polygon with an interior.
#[derive(Clone, Debug, PartialEq)]
pub enum ConvexHull2 {
    /// All points coincide.
    Point(DVec2),
    /// All points are collinear (exactly); the two extreme points in lexicographic order.
    Segment(DVec2, DVec2),
    /// The points span an area.
    Polygon(ConvexPolygon2),
}

/// A strictly convex polygon, counter-clockwise.
///
/// # Guarantees
/// At least 3 finite vertices; every three consecutive vertices turn strictly left (exact
/// `orient2d > 0`); the first vertex is the lexicographically smallest (x, then y).
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexPolygon2 {
    vertices: Vec<DVec2>,
}

/// Exact orientation of `c` relative to the directed line `a → b` (positive = left), on the points
/// scaled by `factor` (a power of two) with coordinates below
/// [`crate::finite::ORIENTATION_FLOOR`] flushed to 0.
fn orient(a: DVec2, b: DVec2, c: DVec2, factor: f64) -> f64 {
    let coord = |p: DVec2| Coord {
        x: flush_tiny(p.x * factor),
        y: flush_tiny(p.y * factor),
    };
    orient2d(coord(a), coord(b), coord(c))
}

/// The power of two that brings the largest coordinate near 1.
fn rescale_factor(points: &[DVec2]) -> f64 {
    let largest = points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0_f64, f64::max);
    rescale_for(largest)
}

/// The convex hull of `points` by Andrew's monotone chain, exact: vertices are input points, turns
/// are decided by `robust::orient2d` on the points rescaled by a power of two, collinear boundary
/// points are not vertices, and no tolerance is involved.
///
/// # Errors
/// [`HullError::NonFinite`] naming `points`; [`HullError::DegeneratePoints`] with
/// [`Degeneracy::Empty`] for no points.
pub fn convex_hull_2d(points: &[DVec2]) -> Result<ConvexHull2, HullError> {
    if points.iter().any(|p| !p.is_finite()) {
        return Err(HullError::NonFinite {
            parameter: "points",
        });
    }
    let mut sorted = points.to_vec();
    sorted.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    sorted.dedup();
    let (Some(&first), Some(&last)) = (sorted.first(), sorted.last()) else {
        return Err(HullError::DegeneratePoints {
            degeneracy: Degeneracy::Empty,
        });
    };
    if sorted.len() == 1 {
        return Ok(ConvexHull2::Point(first));
    }
    let factor = rescale_factor(&sorted);
    let mut chain: Vec<DVec2> = Vec::with_capacity(sorted.len() + 1);
    let half_chain = |chain: &mut Vec<DVec2>, p: DVec2, floor: usize| {
        while chain.len() >= floor + 2
            && orient(chain[chain.len() - 2], chain[chain.len() - 1], p, factor) <= 0.0
        {
            chain.pop();
        }
        chain.push(p);
    };
    for &p in &sorted {
        half_chain(&mut chain, p, 0);
    }
    let lower_len = chain.len();
    for &p in sorted.iter().rev().skip(1) {
        half_chain(&mut chain, p, lower_len - 1);
    }
    chain.pop();
    if chain.len() < 3 {
        return Ok(ConvexHull2::Segment(first, last));
    }
    let polygon = ConvexPolygon2 { vertices: chain };
    debug_assert_eq!(polygon.validate(), Ok(()));
    Ok(ConvexHull2::Polygon(polygon))
}

impl ConvexPolygon2 {
    /// The vertices, counter-clockwise.
    #[must_use]
    pub fn vertices(&self) -> &[DVec2] {
        &self.vertices
    }

    /// The area (shoelace formula about the first vertex).
    #[must_use]
    pub fn area(&self) -> f64 {
        let o = self.vertices[0];
        self.vertices[1..]
            .windows(2)
            .map(|w| (w[0] - o).perp_dot(w[1] - o))
            .sum::<f64>()
            * 0.5
    }

    /// Whether `point` lies inside or within `tolerance` of the polygon.
    #[must_use]
    pub fn contains(&self, point: DVec2, tolerance: f64) -> bool {
        let n = self.vertices.len();
        (0..n).all(|k| {
            let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
            let edge = b - a;
            edge.perp_dot(point - a) >= -tolerance * edge.length()
        })
    }

    /// Checks the guarantees (exactly).
    ///
    /// # Errors
    /// [`ValidationError::TooFew`], [`ValidationError::NonFinite`] or
    /// [`ValidationError::WrongWinding`] (face = the vertex where the turn fails).
    pub fn validate(&self) -> Result<(), ValidationError> {
        let n = self.vertices.len();
        if n < 3 {
            return Err(ValidationError::TooFew {
                what: "vertices",
                count: n,
            });
        }
        if self.vertices.iter().any(|p| !p.is_finite()) {
            return Err(ValidationError::NonFinite);
        }
        let factor = rescale_factor(&self.vertices);
        for k in 0..n {
            let (a, b, c) = (
                self.vertices[k],
                self.vertices[(k + 1) % n],
                self.vertices[(k + 2) % n],
            );
            if orient(a, b, c, factor) <= 0.0 {
                return Err(ValidationError::WrongWinding { face: (k + 1) % n });
            }
        }
        Ok(())
    }

    /// Checks exactly that every point lies inside or on the polygon.
    ///
    /// # Errors
    /// [`ValidationError::PointOutside`] with the distance outside the violated edge.
    pub fn validate_contains(&self, points: &[DVec2]) -> Result<(), ValidationError> {
        let mut all = self.vertices.clone();
        all.extend_from_slice(points);
        let factor = rescale_factor(&all);
        let n = self.vertices.len();
        for (index, &p) in points.iter().enumerate() {
            for k in 0..n {
                let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
                if orient(a, b, p, factor) < 0.0 {
                    return Err(ValidationError::PointOutside {
                        point: index,
                        distance: -(b - a).perp_dot(p - a) / (b - a).length(),
                    });
                }
            }
        }
        Ok(())
    }
}

/// An axis-aligned 2-D rectangle `[min, max]` (may be flat), e.g. the bounds of B in a shadow map's
/// plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb2 {
    min: DVec2,
    max: DVec2,
}

impl Aabb2 {
    /// The bounds of `points`.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `points`; [`HullError::DegeneratePoints`] with
    /// [`Degeneracy::Empty`] for no points.
    pub fn from_points(points: &[DVec2]) -> Result<Self, HullError> {
        if points.iter().any(|p| !p.is_finite()) {
            return Err(HullError::NonFinite {
                parameter: "points",
            });
        }
        let (first, rest) = points.split_first().ok_or(HullError::DegeneratePoints {
            degeneracy: Degeneracy::Empty,
        })?;
        let mut bounds = Self {
            min: *first,
            max: *first,
        };
        for p in rest {
            bounds.min = bounds.min.min(*p);
            bounds.max = bounds.max.max(*p);
        }
        Ok(bounds)
    }

    /// The minimum corner.
    #[must_use]
    pub fn min(&self) -> DVec2 {
        self.min
    }

    /// The maximum corner.
    #[must_use]
    pub fn max(&self) -> DVec2 {
        self.max
    }

    /// `max − min`.
    #[must_use]
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// The area.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.size().x * self.size().y
    }
}

/// The scale of 2-D points (as 3-D points with z = 0), for tolerances.
pub(crate) fn scale_2d(points: &[DVec2]) -> Scale {
    Scale::of_points(
        points
            .iter()
            .map(|p| p.extend(0.0))
            .collect::<Vec<_>>()
            .iter(),
    )
}

/// The validation distance for 2-D points.
pub(crate) fn validation_distance_2d(points: &[DVec2], tolerances: &Tolerances) -> f64 {
    tolerances.validation_distance(scale_2d(points))
}
