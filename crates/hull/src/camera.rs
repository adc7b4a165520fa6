//! Camera parameters: the pose (eye and axes), perspective and orthographic projections, and the NDC
//! depth convention of their matrices.
//!
//! # Conventions
//! World space is right-handed. Eye space follows OpenGL: the camera looks down **−z**, +y is up,
//! +x is right; a point at eye depth `t > 0` in front of the camera has eye `z = −t`. The projection
//! matrices here are column-vector matrices (`clip = P · view · world`), and their NDC depth range is
//! selected by [`NdcDepth`] (OpenGL's `[−1, 1]` by default).

use glam::{DMat4, DVec3, DVec4};

use crate::error::HullError;
use crate::finite::{finite, finite_vec, unit_vec};

/// The NDC depth range a projection matrix maps the near and far planes to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NdcDepth {
    /// OpenGL: near → −1, far → +1 (the default; formulas.md §0 and §3.2 use it).
    #[default]
    NegativeOneToOne,
    /// Direct3D / Vulkan / Metal: near → 0, far → 1.
    ZeroToOne,
    /// Reversed-Z on a `[0, 1]` range: near → 1, far → 0.
    ReversedZeroToOne,
}

impl NdcDepth {
    /// The NDC depths of the near and far planes, in that order.
    #[must_use]
    pub fn near_far(self) -> (f64, f64) {
        match self {
            Self::NegativeOneToOne => (-1.0, 1.0),
            Self::ZeroToOne => (0.0, 1.0),
            Self::ReversedZeroToOne => (1.0, 0.0),
        }
    }
}

/// Where a camera (or a spot light) is and where it looks.
///
/// # Guarantees
/// `forward`, `up` and `right = forward × up` are unit, mutually orthogonal and finite; `eye` is
/// finite. `(right, up, −forward)` is a right-handed frame: the eye-space x, y, z axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewPose {
    eye: DVec3,
    forward: DVec3,
    up: DVec3,
}

impl ViewPose {
    /// A camera at `eye` looking along `forward`, with `up_hint` giving the up direction (it is
    /// orthogonalised against `forward`; it need not be unit or orthogonal).
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `eye`, `forward` or `up_hint`; [`HullError::ZeroVector`] naming
    /// `forward` or `up_hint`; [`HullError::ParallelVectors`] naming `forward/up_hint` if they are
    /// parallel.
    pub fn look_to(eye: DVec3, forward: DVec3, up_hint: DVec3) -> Result<Self, HullError> {
        let eye = finite_vec(eye, "eye")?;
        let forward = unit_vec(forward, "forward")?;
        let up_hint = unit_vec(up_hint, "up_hint")?;
        let right = unit_vec(forward.cross(up_hint), "forward/up_hint").map_err(|_| {
            HullError::ParallelVectors {
                parameter: "forward/up_hint",
            }
        })?;
        Ok(Self {
            eye,
            forward,
            up: right.cross(forward),
        })
    }

    /// A camera at `eye` looking at `target`; see [`ViewPose::look_to`].
    ///
    /// # Errors
    /// As [`ViewPose::look_to`]; `forward` is reported as a zero vector if `target == eye`.
    pub fn look_at(eye: DVec3, target: DVec3, up_hint: DVec3) -> Result<Self, HullError> {
        let target = finite_vec(target, "target")?;
        let eye = finite_vec(eye, "eye")?;
        Self::look_to(eye, target - eye, up_hint)
    }

    /// The eye position.
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        self.eye
    }

    /// The unit view direction (eye-space −z).
    #[must_use]
    pub fn forward(&self) -> DVec3 {
        self.forward
    }

    /// The unit up direction (eye-space +y).
    #[must_use]
    pub fn up(&self) -> DVec3 {
        self.up
    }

    /// The unit right direction `forward × up` (eye-space +x).
    #[must_use]
    pub fn right(&self) -> DVec3 {
        self.forward.cross(self.up)
    }

    /// The view matrix (world → eye space).
    #[must_use]
    pub fn view_matrix(&self) -> DMat4 {
        let right = self.right();
        let back = -self.forward;
        rows(
            right.extend(-right.dot(self.eye)),
            self.up.extend(-self.up.dot(self.eye)),
            back.extend(-back.dot(self.eye)),
            DVec4::W,
        )
    }
}

/// A symmetric perspective projection (OpenGL's `gluPerspective`).
///
/// # Guarantees
/// All finite; `0 < fov_y < π`, `aspect > 0`, `0 < near < far`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    fov_y: f64,
    aspect: f64,
    near: f64,
    far: f64,
}

impl Perspective {
    /// A perspective projection with vertical field of view `fov_y` (radians), `aspect` = width /
    /// height, and near and far distances along the view direction.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming the parameter; [`HullError::FieldOfViewOutOfRange`] unless
    /// `0 < fov_y < π`; [`HullError::NotPositive`] naming `aspect` or `near`;
    /// [`HullError::EmptyRange`] naming `near/far` if `near >= far`.
    pub fn new(fov_y: f64, aspect: f64, near: f64, far: f64) -> Result<Self, HullError> {
        let fov_y = finite(fov_y, "fov_y")?;
        let aspect = finite(aspect, "aspect")?;
        let near = finite(near, "near")?;
        let far = finite(far, "far")?;
        if !(fov_y > 0.0 && fov_y < std::f64::consts::PI) {
            return Err(HullError::FieldOfViewOutOfRange { fov_y });
        }
        if aspect <= 0.0 {
            return Err(HullError::NotPositive {
                parameter: "aspect",
                value: aspect,
            });
        }
        if near <= 0.0 {
            return Err(HullError::NotPositive {
                parameter: "near",
                value: near,
            });
        }
        if near >= far {
            return Err(HullError::EmptyRange {
                parameter: "near/far",
                lo: near,
                hi: far,
            });
        }
        Ok(Self {
            fov_y,
            aspect,
            near,
            far,
        })
    }

    /// The vertical field of view in radians.
    #[must_use]
    pub fn fov_y(&self) -> f64 {
        self.fov_y
    }

    /// Width / height.
    #[must_use]
    pub fn aspect(&self) -> f64 {
        self.aspect
    }

    /// The near distance.
    #[must_use]
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The far distance.
    #[must_use]
    pub fn far(&self) -> f64 {
        self.far
    }

    /// `tan(fov_y/2)`: the half-height of the frustum at unit depth.
    #[must_use]
    pub fn tan_half_fov_y(&self) -> f64 {
        (0.5 * self.fov_y).tan()
    }

    /// The projection matrix (eye → clip space) for the given NDC depth range: formulas.md §3.2's `M`
    /// for [`NdcDepth::NegativeOneToOne`].
    #[must_use]
    pub fn matrix(&self, ndc: NdcDepth) -> DMat4 {
        let cy = 1.0 / self.tan_half_fov_y();
        let cx = cy / self.aspect;
        let (n, f) = (self.near, self.far);
        let (a, b) = match ndc {
            NdcDepth::NegativeOneToOne => ((f + n) / (n - f), 2.0 * f * n / (n - f)),
            NdcDepth::ZeroToOne => (f / (n - f), f * n / (n - f)),
            NdcDepth::ReversedZeroToOne => (n / (f - n), f * n / (f - n)),
        };
        rows(
            DVec4::new(cx, 0.0, 0.0, 0.0),
            DVec4::new(0.0, cy, 0.0, 0.0),
            DVec4::new(0.0, 0.0, a, b),
            DVec4::new(0.0, 0.0, -1.0, 0.0),
        )
    }
}

/// An orthographic projection (OpenGL's `glOrtho`): the box `[left, right] × [bottom, top]` in eye x
/// and y, from `near` to `far` along the view direction.
///
/// # Guarantees
/// All finite; `left < right`, `bottom < top`, `near < far` (near may be zero or negative).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orthographic {
    left: f64,
    right: f64,
    bottom: f64,
    top: f64,
    near: f64,
    far: f64,
}

impl Orthographic {
    /// An orthographic projection.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming the parameter; [`HullError::EmptyRange`] naming `left/right`,
    /// `bottom/top` or `near/far`.
    pub fn new(
        left: f64,
        right: f64,
        bottom: f64,
        top: f64,
        near: f64,
        far: f64,
    ) -> Result<Self, HullError> {
        let left = finite(left, "left")?;
        let right = finite(right, "right")?;
        let bottom = finite(bottom, "bottom")?;
        let top = finite(top, "top")?;
        let near = finite(near, "near")?;
        let far = finite(far, "far")?;
        for (parameter, lo, hi) in [
            ("left/right", left, right),
            ("bottom/top", bottom, top),
            ("near/far", near, far),
        ] {
            if lo >= hi {
                return Err(HullError::EmptyRange { parameter, lo, hi });
            }
        }
        Ok(Self {
            left,
            right,
            bottom,
            top,
            near,
            far,
        })
    }

    /// Eye-space x of the left side.
    #[must_use]
    pub fn left(&self) -> f64 {
        self.left
    }

    /// Eye-space x of the right side.
    #[must_use]
    pub fn right(&self) -> f64 {
        self.right
    }

    /// Eye-space y of the bottom side.
    #[must_use]
    pub fn bottom(&self) -> f64 {
        self.bottom
    }

    /// Eye-space y of the top side.
    #[must_use]
    pub fn top(&self) -> f64 {
        self.top
    }

    /// The near distance along the view direction.
    #[must_use]
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The far distance along the view direction.
    #[must_use]
    pub fn far(&self) -> f64 {
        self.far
    }

    /// The projection matrix (eye → clip space) for the given NDC depth range.
    #[must_use]
    pub fn matrix(&self, ndc: NdcDepth) -> DMat4 {
        let (l, r, b, t, n, f) = (
            self.left,
            self.right,
            self.bottom,
            self.top,
            self.near,
            self.far,
        );
        let (zz, zw) = match ndc {
            NdcDepth::NegativeOneToOne => (-2.0 / (f - n), -(f + n) / (f - n)),
            NdcDepth::ZeroToOne => (-1.0 / (f - n), -n / (f - n)),
            NdcDepth::ReversedZeroToOne => (1.0 / (f - n), f / (f - n)),
        };
        rows(
            DVec4::new(2.0 / (r - l), 0.0, 0.0, -(r + l) / (r - l)),
            DVec4::new(0.0, 2.0 / (t - b), 0.0, -(t + b) / (t - b)),
            DVec4::new(0.0, 0.0, zz, zw),
            DVec4::W,
        )
    }
}

/// A matrix given by its rows.
fn rows(r0: DVec4, r1: DVec4, r2: DVec4, r3: DVec4) -> DMat4 {
    DMat4::from_cols(r0, r1, r2, r3).transpose()
}
