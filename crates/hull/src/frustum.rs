//! View frusta V (and spot-light frusta L): eight corners and six outward planes.

use glam::{DMat4, DVec3, DVec4};

use crate::camera::{NdcDepth, Orthographic, Perspective, ViewPose};
use crate::error::{HullError, ValidationError};
use crate::plane::Plane;
use crate::tolerance::{Scale, Tolerances};

/// Index of the left plane in [`Frustum::planes`].
pub const LEFT: usize = 0;
/// Index of the right plane in [`Frustum::planes`].
pub const RIGHT: usize = 1;
/// Index of the bottom plane in [`Frustum::planes`].
pub const BOTTOM: usize = 2;
/// Index of the top plane in [`Frustum::planes`].
pub const TOP: usize = 3;
/// Index of the near plane in [`Frustum::planes`].
pub const NEAR: usize = 4;
/// Index of the far plane in [`Frustum::planes`].
pub const FAR: usize = 5;

/// For each plane (in [`Frustum::planes`] order), the four corners on it, counter-clockwise seen
/// from outside.
pub const FACE_CORNERS: [[usize; 4]; 6] = [
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

/// A frustum: the convex hexahedron seen by a perspective or orthographic camera.
///
/// Corner `i` is the left (bit 0 clear) or right (set), bottom (bit 1 clear) or top (set), near
/// (bit 2 clear) or far (set) corner; "near" is the NDC plane that [`NdcDepth::near_far`] names near.
/// Planes are stored in the order [`LEFT`], [`RIGHT`], [`BOTTOM`], [`TOP`], [`NEAR`], [`FAR`], with
/// unit normals pointing **out** of the frustum (see [`Plane`]).
///
/// # Guarantees
/// Finite corners and planes; corners lie in front of the eye (for matrices: `w > 0`). Planes are
/// computed analytically (from the camera parameters, or from the matrix rows by Gribb–Hartmann), not
/// fitted to corners, so they stay accurate when the near face is tiny.
#[derive(Clone, Debug, PartialEq)]
pub struct Frustum {
    corners: [DVec3; 8],
    planes: [Plane; 6],
}

impl Frustum {
    /// The frustum of a perspective camera. Built from the parameters directly; it equals
    /// `from_view_projection(projection.matrix(ndc) * pose.view_matrix(), ndc)` for any `ndc` up to
    /// rounding.
    #[must_use]
    pub fn perspective(pose: &ViewPose, projection: &Perspective) -> Self {
        let (eye, f, u, r) = (pose.eye(), pose.forward(), pose.up(), pose.right());
        let ty = projection.tan_half_fov_y();
        let tx = ty * projection.aspect();
        let corners = std::array::from_fn(|i| {
            let depth = if i & 4 == 0 {
                projection.near()
            } else {
                projection.far()
            };
            let sx = if i & 1 == 0 { -tx } else { tx };
            let sy = if i & 2 == 0 { -ty } else { ty };
            eye + f * depth + r * (sx * depth) + u * (sy * depth)
        });
        let side = |axis: DVec3, slope: f64| (axis - f * slope).normalize();
        let planes = [
            Plane::from_unit_normal_point(side(-r, tx), eye),
            Plane::from_unit_normal_point(side(r, tx), eye),
            Plane::from_unit_normal_point(side(-u, ty), eye),
            Plane::from_unit_normal_point(side(u, ty), eye),
            Plane::from_unit_normal_point(-f, eye + f * projection.near()),
            Plane::from_unit_normal_point(f, eye + f * projection.far()),
        ];
        Self { corners, planes }
    }

    /// The frustum (a box) of an orthographic camera.
    #[must_use]
    pub fn orthographic(pose: &ViewPose, projection: &Orthographic) -> Self {
        let (eye, f, u, r) = (pose.eye(), pose.forward(), pose.up(), pose.right());
        let corners = std::array::from_fn(|i| {
            let depth = if i & 4 == 0 {
                projection.near()
            } else {
                projection.far()
            };
            let x = if i & 1 == 0 {
                projection.left()
            } else {
                projection.right()
            };
            let y = if i & 2 == 0 {
                projection.bottom()
            } else {
                projection.top()
            };
            eye + f * depth + r * x + u * y
        });
        let planes = [
            Plane::from_unit_normal_point(-r, eye + r * projection.left()),
            Plane::from_unit_normal_point(r, eye + r * projection.right()),
            Plane::from_unit_normal_point(-u, eye + u * projection.bottom()),
            Plane::from_unit_normal_point(u, eye + u * projection.top()),
            Plane::from_unit_normal_point(-f, eye + f * projection.near()),
            Plane::from_unit_normal_point(f, eye + f * projection.far()),
        ];
        Self { corners, planes }
    }

    /// The frustum of any view-projection matrix `m` (world → clip, column vectors) whose NDC depth
    /// range is `ndc`: the points whose clip coordinates satisfy `−w ≤ x, y ≤ w` and the depth range,
    /// with `w > 0`. Planes come from the rows of `m` (Gribb & Hartmann), corners from `m⁻¹`.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `view_projection`; [`HullError::SingularMatrix`];
    /// [`HullError::UnboundedFrustum`] if a corner unprojects to infinity or behind the eye (e.g. an
    /// infinite far plane).
    pub fn from_view_projection(m: DMat4, ndc: NdcDepth) -> Result<Self, HullError> {
        if !m.is_finite() {
            return Err(HullError::NonFinite {
                parameter: "view_projection",
            });
        }
        let det = m.determinant();
        let inverse = m.inverse();
        if det == 0.0 || !det.is_finite() || !inverse.is_finite() {
            return Err(HullError::SingularMatrix {
                parameter: "view_projection",
            });
        }
        let (z_near, z_far) = ndc.near_far();
        let mut corners = [DVec3::ZERO; 8];
        for (i, corner) in corners.iter_mut().enumerate() {
            let x = if i & 1 == 0 { -1.0 } else { 1.0 };
            let y = if i & 2 == 0 { -1.0 } else { 1.0 };
            let z = if i & 4 == 0 { z_near } else { z_far };
            let h = inverse * DVec4::new(x, y, z, 1.0);
            let p = h.truncate() / h.w;
            if h.w <= 0.0 || !p.is_finite() {
                return Err(HullError::UnboundedFrustum);
            }
            *corner = p;
        }
        let (r0, r1, r2, r3) = (m.row(0), m.row(1), m.row(2), m.row(3));
        // Each clip inequality `c·(x, 1) ≥ 0` becomes the outward plane `−c`.
        let z_low = match ndc {
            NdcDepth::NegativeOneToOne => r3 + r2,
            NdcDepth::ZeroToOne | NdcDepth::ReversedZeroToOne => r2,
        };
        let z_high = r3 - r2;
        let (near, far) = match ndc {
            NdcDepth::ReversedZeroToOne => (z_high, z_low),
            NdcDepth::NegativeOneToOne | NdcDepth::ZeroToOne => (z_low, z_high),
        };
        let inside = [r3 + r0, r3 - r0, r3 + r1, r3 - r1, near, far];
        let mut planes = [Plane::from_unit_normal_offset(DVec3::X, 0.0); 6];
        for (plane, c) in planes.iter_mut().zip(inside) {
            let outward = -c;
            let length = outward.truncate().length();
            let normal = outward.truncate() / length;
            let offset = outward.w / length;
            if length <= 0.0 || !normal.is_finite() || !offset.is_finite() {
                return Err(HullError::UnboundedFrustum);
            }
            *plane = Plane::from_unit_normal_offset(normal, offset);
        }
        Ok(Self { corners, planes })
    }

    /// The eight corners (see [`Frustum`] for the order).
    #[must_use]
    pub fn corners(&self) -> &[DVec3; 8] {
        &self.corners
    }

    /// The six outward planes (see [`Frustum`] for the order).
    #[must_use]
    pub fn planes(&self) -> &[Plane; 6] {
        &self.planes
    }

    /// The unit direction from the near plane toward the far plane (the camera's view direction;
    /// for a reversed-Z matrix, see [`NdcDepth::ReversedZeroToOne`], still from near to far).
    #[must_use]
    pub fn view_direction(&self) -> DVec3 {
        -self.planes[NEAR].normal()
    }

    /// The scale of the corners, for tolerances.
    #[must_use]
    pub fn scale(&self) -> Scale {
        Scale::of_points(&self.corners)
    }

    /// Whether `point` lies inside all six planes, allowing `tolerance` outside.
    #[must_use]
    pub fn contains(&self, point: DVec3, tolerance: f64) -> bool {
        self.planes.iter().all(|p| p.contains(point, tolerance))
    }

    /// Checks that the planes have unit normals, that each corner lies on its three planes and inside
    /// the other three, within the validation distance of `tolerances`.
    ///
    /// # Errors
    /// The first broken invariant; face and vertex indices are plane and corner indices.
    pub fn validate(&self, tolerances: &Tolerances) -> Result<(), ValidationError> {
        if self.corners.iter().any(|c| !c.is_finite()) {
            return Err(ValidationError::NonFinite);
        }
        let limit = tolerances.validation_distance(self.scale());
        for (face, plane) in self.planes.iter().enumerate() {
            if !plane.normal().is_finite() || !plane.offset().is_finite() {
                return Err(ValidationError::NonFinite);
            }
            if (plane.normal().length() - 1.0).abs() > crate::tolerance::UNIT_LENGTH_TOLERANCE {
                return Err(ValidationError::NonUnitNormal { face });
            }
            for (vertex, corner) in self.corners.iter().enumerate() {
                let distance = plane.signed_distance(*corner);
                if FACE_CORNERS[face].contains(&vertex) {
                    if distance.abs() > limit {
                        return Err(ValidationError::NonPlanarFace {
                            face,
                            vertex,
                            distance,
                        });
                    }
                } else if distance > limit {
                    return Err(ValidationError::NotConvex {
                        face,
                        vertex,
                        distance,
                    });
                }
            }
        }
        Ok(())
    }
}
