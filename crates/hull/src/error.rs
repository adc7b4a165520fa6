//! Errors: what went wrong and which parameter was bad.
//!
//! [`HullError`] is returned by every constructor and operation that takes outside input; it names
//! the offending parameter. [`ValidationError`] is returned by the `validate()` methods and names the
//! broken invariant. Neither is ever produced for valid input by a correct implementation except the
//! documented outcomes ([`HullError::DegeneratePoints`] for flat point sets).

use std::fmt;

/// Why a point set has no 3-D (or 2-D) convex hull with an interior.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degeneracy {
    /// No points were given.
    Empty,
    /// All points coincide (within the snap distance of [`crate::Tolerances`]).
    Coincident,
    /// All points lie on one line (within the snap distance).
    Collinear,
    /// All points lie in one plane (within the snap distance); only reported for 3-D hulls.
    Coplanar,
}

impl fmt::Display for Degeneracy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Empty => "no points",
            Self::Coincident => "all points coincide",
            Self::Collinear => "all points are collinear",
            Self::Coplanar => "all points are coplanar",
        })
    }
}

/// An error from a constructor or an operation of this crate: bad input, named.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum HullError {
    /// A coordinate or scalar parameter is NaN or infinite.
    NonFinite {
        /// The parameter, e.g. `"eye"`, `"near"`, `"points[3]"`.
        parameter: &'static str,
    },
    /// A parameter that must be strictly positive is not.
    NotPositive {
        /// The parameter, e.g. `"near"`, `"aspect"`.
        parameter: &'static str,
        /// The value given.
        value: f64,
    },
    /// A range `lo..hi` that must be non-empty is empty or inverted (`lo >= hi`); `near >= far` is
    /// reported here.
    EmptyRange {
        /// The parameter pair, e.g. `"near/far"`, `"left/right"`.
        parameter: &'static str,
        /// The lower end given.
        lo: f64,
        /// The upper end given.
        hi: f64,
    },
    /// A vertical field of view outside the open interval (0°, 180°).
    FieldOfViewOutOfRange {
        /// The field of view given, in radians.
        fov_y: f64,
    },
    /// A scalar parameter outside its documented range `[min, max]`.
    OutOfRange {
        /// The parameter, e.g. `"parallel_sin"`.
        parameter: &'static str,
        /// The value given.
        value: f64,
        /// The smallest accepted value.
        min: f64,
        /// The largest accepted value.
        max: f64,
    },
    /// A box whose minimum corner exceeds its maximum corner on some axis.
    InvertedBox {
        /// The axis: 0 = x, 1 = y, 2 = z.
        axis: usize,
    },
    /// A box used as a solid (scene bounds) has zero size on some axis (within the snap distance).
    ZeroSizeBox {
        /// The axis: 0 = x, 1 = y, 2 = z.
        axis: usize,
    },
    /// A direction vector has zero length (or is too short to normalise).
    ZeroVector {
        /// The parameter, e.g. `"forward"`, `"to_light"`.
        parameter: &'static str,
    },
    /// Two vectors that must span a plane are parallel (e.g. the camera's up hint and its forward).
    ParallelVectors {
        /// The parameter pair, e.g. `"forward/up"`.
        parameter: &'static str,
    },
    /// A matrix that must be invertible is singular.
    SingularMatrix {
        /// The parameter, e.g. `"view_projection"`.
        parameter: &'static str,
    },
    /// A view-projection matrix whose frustum is not bounded and in front of its eye: a corner of the
    /// NDC cube unprojects to a point at infinity or behind the eye (`w <= 0`), e.g. an infinite far
    /// plane.
    UnboundedFrustum,
    /// A frustum whose corners (from the inverse matrix) lie off its planes (from the matrix's
    /// rows) by more than the validation distance: the view-projection matrix is too
    /// ill-conditioned for the two to agree in f64.
    InconsistentFrustum,
    /// An operation's result has coordinates beyond f64's range (finite input, e.g. a body near
    /// 10³⁰⁸ rotated or swept farther out).
    Overflow {
        /// The operation, e.g. `"bounds_in"`, `"sweep"`.
        operation: &'static str,
    },
    /// An operation failed for numerical reasons that the documented tolerances should rule out;
    /// this is a bug: please report it with the input.
    Internal {
        /// The operation, e.g. `"hull_with_point"`.
        operation: &'static str,
    },
    /// A point set without a hull with an interior; see [`Degeneracy`].
    DegeneratePoints {
        /// What kind of degeneracy.
        degeneracy: Degeneracy,
    },
}

impl fmt::Display for HullError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { parameter } => write!(f, "`{parameter}` is not finite"),
            Self::InconsistentFrustum => f.write_str(
                "the frustum's corners lie off its planes: the view-projection matrix is too \
                 ill-conditioned for f64",
            ),
            Self::Overflow { operation } => {
                write!(f, "the result of `{operation}` lies beyond f64's range")
            }
            Self::NotPositive { parameter, value } => {
                write!(f, "`{parameter}` must be positive, got {value}")
            }
            Self::EmptyRange { parameter, lo, hi } => {
                write!(f, "`{parameter}` must satisfy lo < hi, got {lo} and {hi}")
            }
            Self::FieldOfViewOutOfRange { fov_y } => write!(
                f,
                "`fov_y` must lie strictly between 0 and π radians (180°), got {fov_y}"
            ),
            Self::OutOfRange {
                parameter,
                value,
                min,
                max,
            } => write!(f, "`{parameter}` must lie in [{min}, {max}], got {value}"),
            Self::Internal { operation } => write!(
                f,
                "internal numerical failure in `{operation}`; please report this input"
            ),
            Self::InvertedBox { axis } => {
                write!(f, "box minimum exceeds its maximum on axis {axis}")
            }
            Self::ZeroSizeBox { axis } => write!(f, "box has zero size on axis {axis}"),
            Self::ZeroVector { parameter } => write!(f, "`{parameter}` has zero length"),
            Self::ParallelVectors { parameter } => {
                write!(f, "`{parameter}` are parallel; they must span a plane")
            }
            Self::SingularMatrix { parameter } => write!(f, "`{parameter}` is singular"),
            Self::UnboundedFrustum => f.write_str(
                "view-projection frustum is unbounded or reaches behind the eye (w <= 0 at a corner)",
            ),
            Self::DegeneratePoints { degeneracy } => {
                write!(f, "point set has no hull with an interior: {degeneracy}")
            }
        }
    }
}

impl std::error::Error for HullError {}

/// A broken invariant found by a `validate()` method. Indices refer to the validated value's own
/// vertex and face lists.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum ValidationError {
    /// A coordinate or plane coefficient is NaN or infinite.
    NonFinite,
    /// Fewer elements than the smallest valid value has (4 vertices and 4 faces for a polyhedron,
    /// 3 vertices for a polygon).
    TooFew {
        /// What is counted, e.g. `"vertices"`.
        what: &'static str,
        /// How many there are.
        count: usize,
    },
    /// A face with fewer than 3 vertices, a repeated vertex, or an index out of range.
    MalformedFace {
        /// The face index.
        face: usize,
    },
    /// A face plane whose normal is not of unit length.
    NonUnitNormal {
        /// The face index.
        face: usize,
    },
    /// A face vertex lies off its face's plane by more than the validation distance.
    NonPlanarFace {
        /// The face index.
        face: usize,
        /// The vertex index.
        vertex: usize,
        /// Its signed distance from the face plane.
        distance: f64,
    },
    /// A vertex lies outside a face plane by more than the validation distance: not convex, or a
    /// plane not oriented outward.
    NotConvex {
        /// The face index.
        face: usize,
        /// The vertex index.
        vertex: usize,
        /// Its signed distance from the face plane (positive = outside).
        distance: f64,
    },
    /// A face's vertex loop does not run counter-clockwise around its outward normal.
    WrongWinding {
        /// The face index.
        face: usize,
    },
    /// A directed edge without its opposite: the surface is not closed, or has a T-junction, or its
    /// faces are not consistently oriented.
    OpenEdge {
        /// Edge start vertex.
        from: usize,
        /// Edge end vertex.
        to: usize,
    },
    /// A directed edge used by two faces: the surface is not a 2-manifold, or is mis-oriented.
    RepeatedEdge {
        /// Edge start vertex.
        from: usize,
        /// Edge end vertex.
        to: usize,
    },
    /// The faces around a vertex do not form a single fan.
    NonManifoldVertex {
        /// The vertex index.
        vertex: usize,
    },
    /// A vertex used by no face.
    UnusedVertex {
        /// The vertex index.
        vertex: usize,
    },
    /// Two vertices closer than the snap distance.
    DuplicateVertex {
        /// One vertex index.
        first: usize,
        /// The other vertex index.
        second: usize,
    },
    /// V − E + F differs from 2.
    EulerCharacteristic {
        /// Vertex count.
        vertices: usize,
        /// Edge count.
        edges: usize,
        /// Face count.
        faces: usize,
    },
    /// The volume (or area) is not positive.
    NotSolid,
    /// A point that must be contained lies outside by more than the validation distance.
    PointOutside {
        /// The index of the point in the list given to the check.
        point: usize,
        /// How far outside it lies.
        distance: f64,
    },
    /// A frame or rectangle whose axes are not orthonormal (or not right-handed, for 3-D frames).
    NotOrthonormal,
    /// A negative extent.
    NegativeExtent,
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("a coordinate is not finite"),
            Self::TooFew { what, count } => write!(f, "too few {what}: {count}"),
            Self::MalformedFace { face } => write!(
                f,
                "face {face} has fewer than 3 vertices, a repeated vertex or a bad index"
            ),
            Self::NonUnitNormal { face } => write!(f, "face {face} has a non-unit normal"),
            Self::NonPlanarFace {
                face,
                vertex,
                distance,
            } => write!(
                f,
                "vertex {vertex} lies {distance} off the plane of face {face}"
            ),
            Self::NotConvex {
                face,
                vertex,
                distance,
            } => write!(
                f,
                "vertex {vertex} lies {distance} outside the plane of face {face}"
            ),
            Self::WrongWinding { face } => {
                write!(f, "face {face} is not counter-clockwise seen from outside")
            }
            Self::OpenEdge { from, to } => write!(f, "edge {from}→{to} has no opposite edge"),
            Self::RepeatedEdge { from, to } => write!(f, "edge {from}→{to} is used twice"),
            Self::NonManifoldVertex { vertex } => {
                write!(f, "the faces around vertex {vertex} do not form one fan")
            }
            Self::UnusedVertex { vertex } => write!(f, "vertex {vertex} is used by no face"),
            Self::DuplicateVertex { first, second } => {
                write!(f, "vertices {first} and {second} coincide")
            }
            Self::EulerCharacteristic {
                vertices,
                edges,
                faces,
            } => write!(
                f,
                "Euler characteristic V − E + F = {vertices} − {edges} + {faces} ≠ 2"
            ),
            Self::NotSolid => f.write_str("volume or area is not positive"),
            Self::PointOutside { point, distance } => {
                write!(f, "point {point} lies {distance} outside")
            }
            Self::NotOrthonormal => f.write_str("axes are not orthonormal and right-handed"),
            Self::NegativeExtent => f.write_str("an extent is negative"),
        }
    }
}

impl std::error::Error for ValidationError {}
