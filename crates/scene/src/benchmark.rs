//! The two views of the rasterizer benchmark (issue 4) and of the peer harness
//! `shared/tools/peers/gl_depth_bench.py`, built with the same formulas in the same order so that
//! both renderers see the same matrices.
//!
//! With `c` the centre of the mesh's bounding box and `R` half its diagonal:
//! * **light**: orthographic, looking at `c` from `c + 2R·normalize(0.3, 1, 0.5)`, up `(0, 0, −1)`,
//!   box `±R`, near `R`, far `3R`;
//! * **eye**: perspective, 45° vertical field of view, looking at `c` from
//!   `c + 2.2R·normalize(0.6, 0.35, 1)`, up `(0, 1, 0)`, near `0.05R`, far `4R`.
//!
//! Both map to GL clip space (column vectors, `clip = M·(p, 1)`, NDC depth in `[−1, 1]`).

use glam::{DMat4, DVec3, DVec4};

use crate::Bounds;

/// The light and eye matrices of the benchmark view of a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchmarkView {
    /// Light pass: world → clip, orthographic.
    pub light: DMat4,
    /// Eye pass: world → clip, perspective, for an `eye_width × eye_height` target.
    pub eye: DMat4,
}

impl BenchmarkView {
    /// The views of a mesh with these bounds, the eye's aspect ratio being `eye_width/eye_height`.
    #[must_use]
    pub fn new(bounds: &Bounds, eye_width: u32, eye_height: u32) -> Self {
        let c = (bounds.min + bounds.max) / 2.0;
        let r = (bounds.max - bounds.min).length() / 2.0;
        let to_light = DVec3::new(0.3, 1.0, 0.5).normalize();
        let light_view = look_at(c + to_light * 2.0 * r, c, DVec3::new(0.0, 0.0, -1.0));
        let light = orthographic(-r, r, -r, r, r, 3.0 * r) * light_view;
        let to_eye = DVec3::new(0.6, 0.35, 1.0).normalize();
        let aspect = f64::from(eye_width) / f64::from(eye_height);
        let eye = perspective(45.0, aspect, 0.05 * r, 4.0 * r)
            * look_at(c + to_eye * 2.2 * r, c, DVec3::Y);
        Self { light, eye }
    }
}

/// A right-handed view matrix: the camera at `eye` looks at `target`, `up` roughly up.
fn look_at(eye: DVec3, target: DVec3, up: DVec3) -> DMat4 {
    let f = (target - eye).normalize();
    let s = f.cross(up).normalize();
    let u = s.cross(f);
    DMat4::from_cols(
        DVec4::new(s.x, u.x, -f.x, 0.0),
        DVec4::new(s.y, u.y, -f.y, 0.0),
        DVec4::new(s.z, u.z, -f.z, 0.0),
        DVec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// OpenGL's `glOrtho`.
fn orthographic(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> DMat4 {
    DMat4::from_cols(
        DVec4::new(2.0 / (right - left), 0.0, 0.0, 0.0),
        DVec4::new(0.0, 2.0 / (top - bottom), 0.0, 0.0),
        DVec4::new(0.0, 0.0, -2.0 / (far - near), 0.0),
        DVec4::new(
            -(right + left) / (right - left),
            -(top + bottom) / (top - bottom),
            -(far + near) / (far - near),
            1.0,
        ),
    )
}

/// OpenGL's `gluPerspective`, the vertical field of view in degrees.
fn perspective(fov_y_degrees: f64, aspect: f64, near: f64, far: f64) -> DMat4 {
    let t = 1.0 / (fov_y_degrees.to_radians() / 2.0).tan();
    DMat4::from_cols(
        DVec4::new(t / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, t, 0.0, 0.0),
        DVec4::new(0.0, 0.0, (far + near) / (near - far), -1.0),
        DVec4::new(0.0, 0.0, 2.0 * far * near / (near - far), 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_views_frame_the_mesh() {
        let bounds = Bounds {
            min: DVec3::new(-1.0, 0.0, -2.0),
            max: DVec3::new(3.0, 2.0, 0.0),
        };
        let view = BenchmarkView::new(&bounds, 1024, 768);
        // Every corner of the box lands inside both clip volumes.
        for k in 0..8 {
            let p = DVec3::new(
                if k & 1 == 0 {
                    bounds.min.x
                } else {
                    bounds.max.x
                },
                if k & 2 == 0 {
                    bounds.min.y
                } else {
                    bounds.max.y
                },
                if k & 4 == 0 {
                    bounds.min.z
                } else {
                    bounds.max.z
                },
            );
            for m in [view.light, view.eye] {
                let c = m * p.extend(1.0);
                assert!(
                    c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w && c.z.abs() <= c.w,
                    "{p} {c}"
                );
            }
        }
        // The centre is on both view axes.
        let c = (bounds.min + bounds.max) / 2.0;
        for m in [view.light, view.eye] {
            let q = m * c.extend(1.0);
            assert!(q.x.abs() < 1e-12 && q.y.abs() < 1e-12);
        }
    }
}
