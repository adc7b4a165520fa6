//! Named tolerances, scaled to the size of the input.
//!
//! Every approximate decision in this crate (is a vertex on a clip plane? are two vertices the same?
//! is a point set flat?) compares a distance with one number, the **snap distance**, computed by
//! [`Tolerances::snap_distance`] from the [`Scale`] of the data at hand. Signs that decide hull
//! topology do not use a tolerance at all: they are exact (`robust::orient2d`/`orient3d`).
//!
//! The snap distance has two terms because f64 error has two sources:
//! - `relative × extent`: a fraction of the body's size (its bounding-box diagonal), so that the
//!   same scene at 10⁻⁷ or 10⁷ units gives the same decisions;
//! - `rounding_ulps × f64::EPSILON × magnitude`: the rounding of coordinates far from the origin
//!   (a unit-size frustum at 10⁷ cannot be resolved better than ~10⁻⁹ absolute).

use glam::DVec3;

/// How far from 1 the length of a stored unit normal may be. Normals are normalised in f64, so their
/// length is 1 within a few ulps; this bound is only a sanity check in `validate()`.
pub const UNIT_LENGTH_TOLERANCE: f64 = 1e-12;

/// The size of some data: what tolerances are scaled to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    /// The length of the bounding-box diagonal.
    pub extent: f64,
    /// The largest absolute coordinate.
    pub magnitude: f64,
}

impl Scale {
    /// The scale of a set of points (zero for an empty set).
    #[must_use]
    pub fn of_points<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> Self {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        let mut any = false;
        for p in points {
            lo = lo.min(*p);
            hi = hi.max(*p);
            any = true;
        }
        if !any {
            return Self {
                extent: 0.0,
                magnitude: 0.0,
            };
        }
        Self {
            extent: robust_length(hi - lo),
            magnitude: lo.abs().max(hi.abs()).max_element(),
        }
    }

    /// The larger of two scales, axis by axis (used when two bodies meet).
    #[must_use]
    pub fn max(self, other: Self) -> Self {
        Self {
            extent: self.extent.max(other.extent),
            magnitude: self.magnitude.max(other.magnitude),
        }
    }
}

/// The length of `v`, computed on `v` divided by its largest component so that it neither
/// overflows nor underflows for any finite `v` whose length is finite: the plain sum of squares
/// overflows from about 10¹⁵⁴ on (a body that large got an infinite snap distance) and underflows
/// below about 10⁻¹⁶² (two corners of a box 10⁻¹⁸⁰ wide were 0 apart, so "duplicates"). Both found
/// by the hull fuzzer.
pub(crate) fn robust_length(v: DVec3) -> f64 {
    let largest = v.abs().max_element();
    if largest == 0.0 || !largest.is_finite() {
        return largest;
    }
    largest * (v / largest).length()
}

/// The distance between `a` and `b` ([`robust_length`] of their difference): every comparison of
/// a distance with the snap distance uses it.
pub(crate) fn distance(a: DVec3, b: DVec3) -> f64 {
    robust_length(b - a)
}

/// Every tolerance of the crate, in one place.
///
/// # Default value
/// `relative = 1e-9`, `rounding_ulps = 64`, `validation_factor = 16` ([`Tolerances::DEFAULT`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Snap distance as a fraction of the data's extent (bounding-box diagonal). Vertices closer than
    /// the snap distance are merged; a vertex within it of a clip plane lies on the plane; a point set
    /// thinner than it is flat. Default value: `1e-9`.
    pub relative: f64,
    /// Snap distance added for coordinate rounding, in units of `f64::EPSILON × magnitude` (the
    /// largest absolute coordinate). Default value: `64`.
    pub rounding_ulps: f64,
    /// `validate()` accepts deviations (vertex off its face plane, vertex outside a face plane,
    /// point outside a body) up to `validation_factor × snap distance`; clipping leaves vertices up to
    /// one snap distance off a plane, so this must exceed 2. Default value: `16`.
    pub validation_factor: f64,
}

impl Tolerances {
    /// The documented defaults.
    pub const DEFAULT: Self = Self {
        relative: 1e-9,
        rounding_ulps: 64.0,
        validation_factor: 16.0,
    };

    /// The snap distance for data of the given scale:
    /// `relative × extent + rounding_ulps × f64::EPSILON × magnitude`. The first term makes decisions
    /// scale-invariant; the second covers the rounding of coordinates far from the origin.
    #[must_use]
    pub fn snap_distance(&self, scale: Scale) -> f64 {
        self.relative * scale.extent + self.rounding_ulps * f64::EPSILON * scale.magnitude
    }

    /// The distance `validate()` accepts for data of the given scale.
    #[must_use]
    pub fn validation_distance(&self, scale: Scale) -> f64 {
        self.validation_factor * self.snap_distance(scale)
    }
}

impl Default for Tolerances {
    fn default() -> Self {
        Self::DEFAULT
    }
}
