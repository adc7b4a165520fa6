//! One hemisphere of a dual-paraboloid map, evaluated exactly (Brabec, Annen & Seidel, CGI 2002,
//! §3): the mapping a paraboloid set-up holds ([`crate::ShadowMapping::Paraboloid`]);
//! [`crate::paraboloid`] plans it.

use glam::{DVec2, DVec3};

/// One hemisphere's paraboloid map: the light, the hemisphere's frame and its depth range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParaboloidMap {
    light: DVec3,
    /// The frame's axes in world space: `x` and `y` across the map, `z` the hemisphere's axis.
    axes: [DVec3; 3],
    near: f64,
    far: f64,
}

impl ParaboloidMap {
    /// The map of the hemisphere around `axis` (unit) from `light`, depths from `near` to `far`.
    /// Its image's up is world +y projected across the axis, or −z where the axis lies along ±y.
    #[must_use]
    pub fn new(light: DVec3, axis: DVec3, near: f64, far: f64) -> Self {
        let hint = if axis.y.abs() >= axis.x.abs().max(axis.z.abs()) {
            DVec3::NEG_Z
        } else {
            DVec3::Y
        };
        let x = hint.cross(axis).normalize();
        let y = axis.cross(x);
        Self {
            light,
            axes: [x, y, axis],
            near,
            far,
        }
    }

    /// The light's position.
    #[must_use]
    pub fn light(&self) -> DVec3 {
        self.light
    }

    /// The hemisphere's axis.
    #[must_use]
    pub fn axis(&self) -> DVec3 {
        self.axes[2]
    }

    /// The near and far distances.
    #[must_use]
    pub fn depth_range(&self) -> (f64, f64) {
        (self.near, self.far)
    }

    /// Normalized device coordinates of `world`: the paraboloid's `(x, y)` and the distance's
    /// `2(r − near)/(far − near) − 1`; `None` at the light and at the opposite pole (`d_z = −1`),
    /// where the paraboloid has no image.
    #[inline]
    #[must_use]
    pub fn ndc(&self, world: DVec3) -> Option<DVec3> {
        let d = world - self.light;
        let r = d.length();
        let [x, y, z] = self.axes;
        let denominator = r + z.dot(d);
        if r == 0.0 || denominator <= 0.0 {
            return None;
        }
        Some(DVec3::new(
            x.dot(d) / denominator,
            y.dot(d) / denominator,
            self.ndc_of_distance(r),
        ))
    }

    /// The NDC depth of a point at distance `r` from the light.
    fn ndc_of_distance(&self, r: f64) -> f64 {
        2.0 * (r - self.near) / (self.far - self.near) - 1.0
    }

    /// The NDC depth of `world` (its distance from the light).
    #[must_use]
    pub fn ndc_depth(&self, world: DVec3) -> f64 {
        self.ndc_of_distance((world - self.light).length())
    }

    /// The ray of the texel centre at NDC `(x, y)`: from the near to the far distance along the
    /// direction the paraboloid maps there; `None` outside the unit disk, which no direction of
    /// the hemisphere reaches.
    #[must_use]
    pub fn texel_ray(&self, x: f64, y: f64) -> Option<(DVec3, DVec3)> {
        let s = x * x + y * y;
        if s > 1.0 {
            return None;
        }
        let [ax, ay, az] = self.axes;
        let direction = (ax * (2.0 * x) + ay * (2.0 * y) + az * (1.0 - s)) / (1.0 + s);
        Some((
            self.light + direction * self.near,
            self.light + direction * self.far,
        ))
    }

    /// The derivative of NDC `(x, y)` at `world` along `direction` (closed form: the unit
    /// direction `n = d/r` moves by `(δ − n(n·δ))/r`, and `x = n_x/(1 + n_z)`); `None` where
    /// [`Self::ndc`] is.
    #[must_use]
    pub fn ndc_derivative(&self, world: DVec3, direction: DVec3) -> Option<DVec2> {
        let d = world - self.light;
        let r = d.length();
        if r == 0.0 {
            return None;
        }
        let n = d / r;
        let dn = (direction - n * n.dot(direction)) / r;
        let [x, y, z] = self.axes;
        let (nz, dnz) = (z.dot(n), z.dot(dn));
        let denominator = 1.0 + nz;
        if denominator <= 0.0 {
            return None;
        }
        let along = |axis: DVec3| {
            (axis.dot(dn) * denominator - axis.dot(n) * dnz) / (denominator * denominator)
        };
        Some(DVec2::new(along(x), along(y)))
    }
}
