//! Rays and segments, and where they cross a plane.

use glam::DVec3;

use crate::error::HullError;
use crate::finite::{finite_vec, unit_vec};
use crate::plane::Plane;

/// A half-line `origin + t·direction`, `t ≥ 0`.
///
/// # Guarantees
/// Finite origin, unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    origin: DVec3,
    direction: DVec3,
}

impl Ray {
    /// The ray from `origin` along `direction` (normalised here).
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `origin` or `direction`; [`HullError::ZeroVector`] naming
    /// `direction`.
    pub fn new(origin: DVec3, direction: DVec3) -> Result<Self, HullError> {
        Ok(Self {
            origin: finite_vec(origin, "origin")?,
            direction: unit_vec(direction, "direction")?,
        })
    }

    /// The origin.
    #[must_use]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The unit direction.
    #[must_use]
    pub fn direction(&self) -> DVec3 {
        self.direction
    }

    /// `origin + t·direction`.
    #[must_use]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }

    /// The parameter `t ≥ 0` where the ray meets `plane`, if it does (a ray lying in the plane meets
    /// it at `t = 0`).
    #[must_use]
    pub fn intersect_plane(&self, plane: &Plane) -> Option<f64> {
        let start = plane.signed_distance(self.origin);
        let rate = plane.normal().dot(self.direction);
        if start == 0.0 {
            return Some(0.0);
        }
        let t = -start / rate;
        (t.is_finite() && t >= 0.0).then_some(t)
    }
}

/// A segment from `start` to `end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    start: DVec3,
    end: DVec3,
}

impl Segment {
    /// The segment between two finite points (which may coincide).
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `start` or `end`.
    pub fn new(start: DVec3, end: DVec3) -> Result<Self, HullError> {
        Ok(Self {
            start: finite_vec(start, "start")?,
            end: finite_vec(end, "end")?,
        })
    }

    /// The start point.
    #[must_use]
    pub fn start(&self) -> DVec3 {
        self.start
    }

    /// The end point.
    #[must_use]
    pub fn end(&self) -> DVec3 {
        self.end
    }

    /// The point at parameter `t ∈ [0, 1]` (`start` at 0, `end` at 1).
    #[must_use]
    pub fn at(&self, t: f64) -> DVec3 {
        self.start + (self.end - self.start) * t
    }

    /// The parameter in `[0, 1]` where the segment crosses `plane`, if its endpoints lie on opposite
    /// sides (or on it).
    #[must_use]
    pub fn intersect_plane(&self, plane: &Plane) -> Option<f64> {
        let a = plane.signed_distance(self.start);
        let b = plane.signed_distance(self.end);
        if a == 0.0 {
            return Some(0.0);
        }
        if b == 0.0 {
            return Some(1.0);
        }
        (a.signum() != b.signum()).then(|| a / (a - b))
    }
}
