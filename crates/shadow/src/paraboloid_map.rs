//! One hemisphere of a dual-paraboloid map, evaluated exactly (Brabec, Annen & Seidel, CGI 2002,
//! §3): the mapping a paraboloid set-up holds ([`crate::ShadowMapping::Paraboloid`]);
//! [`crate::paraboloid`] plans it.

use glam::{DVec2, DVec3};
use wide::f64x4;

use crate::lanes::{LANES, Vectors};

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

    /// [`Self::ndc`] of four points (`lanes` module): each lane the one-point operations in order;
    /// and the lanes where `ndc` is `None` (their coordinates are meaningless numbers). A unit test
    /// holds the two together.
    #[inline(always)]
    #[must_use]
    pub fn ndc_lanes(&self, world: Vectors) -> (Vectors, [bool; LANES]) {
        let d = world.minus(Vectors::splat(self.light));
        let r = d.length();
        let [x, y, z] = self.axes.map(Vectors::splat);
        let denominator = r + z.dot(d);
        let depth = f64x4::splat(2.0) * (r - f64x4::splat(self.near))
            / f64x4::splat(self.far - self.near)
            - f64x4::ONE;
        let ndc = Vectors {
            x: x.dot(d) / denominator,
            y: y.dot(d) / denominator,
            z: depth,
        };
        let (r, denominator) = (r.to_array(), denominator.to_array());
        (
            ndc,
            std::array::from_fn(|k| r[k] == 0.0 || denominator[k] <= 0.0),
        )
    }

    /// [`Self::ndc_derivative`] at four points at once (`lanes` module): what the derivatives at
    /// a point share — `n`, `r`, `1 + n_z` — for the directions
    /// [`LanesAt::ndc_derivative`] takes.
    #[inline(always)]
    #[must_use]
    pub fn at_lanes(&self, world: Vectors) -> LanesAt<'_> {
        let d = world.minus(Vectors::splat(self.light));
        let r = d.length();
        let n = Vectors {
            x: d.x / r,
            y: d.y / r,
            z: d.z / r,
        };
        let denominator = f64x4::ONE + Vectors::splat(self.axes[2]).dot(n);
        let (r_lanes, denominator_lanes) = (r.to_array(), denominator.to_array());
        LanesAt {
            map: self,
            n,
            r,
            denominator,
            undefined: std::array::from_fn(|k| r_lanes[k] == 0.0 || denominator_lanes[k] <= 0.0),
        }
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

/// A paraboloid hemisphere at four points ([`ParaboloidMap::at_lanes`]): each lane's unit
/// direction `n` from the light, distance `r` and `1 + n_z`, as
/// [`ParaboloidMap::ndc_derivative`] computes them.
#[derive(Clone, Copy, Debug)]
pub struct LanesAt<'a> {
    map: &'a ParaboloidMap,
    n: Vectors,
    r: f64x4,
    denominator: f64x4,
    undefined: [bool; LANES],
}

impl LanesAt<'_> {
    /// The lanes where [`ParaboloidMap::ndc_derivative`] is `None` (at the light, or at the
    /// opposite pole): their derivatives are meaningless numbers.
    #[must_use]
    pub fn undefined(&self) -> [bool; LANES] {
        self.undefined
    }

    /// [`ParaboloidMap::ndc_derivative`] along `direction` (one per lane): `(ẋ, ẏ)` per lane, each
    /// lane the one-point function's operations in its order, so its bits wherever it is defined.
    #[inline(always)]
    #[must_use]
    pub fn ndc_derivative(&self, direction: Vectors) -> [f64x4; 2] {
        let (n, r, denominator) = (self.n, self.r, self.denominator);
        let towards = n.dot(direction);
        let dn = direction.minus(n.times(towards));
        let dn = Vectors {
            x: dn.x / r,
            y: dn.y / r,
            z: dn.z / r,
        };
        let [x, y, z] = self.map.axes.map(Vectors::splat);
        let dnz = z.dot(dn);
        let along = |axis: Vectors| {
            (axis.dot(dn) * denominator - axis.dot(n) * dnz) / (denominator * denominator)
        };
        [along(x), along(y)]
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use shadowlab_test_random::SplitMix;

    use super::ParaboloidMap;
    use crate::lanes::{LANES, Vectors, check};

    /// Four points side by side ([`ParaboloidMap::ndc_lanes`], [`ParaboloidMap::at_lanes`]) give
    /// each point's NDC and derivative to the bit, and are undefined exactly where they are
    /// `None`: random hemispheres, points around the light, at it and at the opposite pole among
    /// them.
    #[test]
    fn four_points_side_by_side_are_each_point_alone() {
        let mut random = SplitMix(0x5eed_0000_0000_9a2b);
        let (mut mapped, mut undefined, mut derivatives) = (0, 0, 0);
        for round in 0..3000_usize {
            let light = random.vector(3.0);
            let axis = random.vector(1.0).normalize_or(DVec3::Y);
            let near = random.range(0.01, 1.0);
            let map = ParaboloidMap::new(light, axis, near, near + random.range(1.0, 50.0));
            let points: [DVec3; LANES] = std::array::from_fn(|k| match (round + k) % 7 {
                0 => light,
                1 => light - axis * random.range(0.1, 5.0),
                _ => light + random.vector(10.0),
            });
            let found = check::ndc(
                &points,
                map.ndc_lanes(Vectors::of(&points)),
                |p| map.ndc(p),
                round,
            );
            mapped += found;
            undefined += LANES - found;
            let at = map.at_lanes(Vectors::of(&points));
            let direction: [DVec3; LANES] = std::array::from_fn(|_| random.vector(1.0));
            derivatives += check::derivatives(
                (&points, &direction),
                (at.ndc_derivative(Vectors::of(&direction)), at.undefined()),
                |p, d| map.ndc_derivative(p, d),
                round,
            );
        }
        assert!(
            mapped > 5000 && undefined > 1000 && derivatives > 5000,
            "{mapped} {undefined} {derivatives}"
        );
    }
}
