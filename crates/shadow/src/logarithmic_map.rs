//! The logarithmic parameterisation evaluated exactly (LiSPSM §4, Lloyd et al. 2008): the mapping
//! a logarithmic set-up holds ([`crate::ShadowMapping::Logarithmic`]); [`crate::logarithmic`]
//! plans it.

use glam::{DMat4, DVec2, DVec3};
use shadowlab_trace::Ray;
use wide::f64x4;

use crate::homogeneous::{divided, point_of};
use crate::lanes::{self, LANES, Vectors};

/// The exact logarithmic mapping of one shadow map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogarithmicMap {
    /// World → light space (projective for a spot light).
    pub(crate) world_to_light: DMat4,
    /// Its inverse.
    pub(crate) light_to_world: DMat4,
    /// B's near plane (largest z) and its extent along the warp axis.
    pub(crate) z_max: f64,
    pub(crate) depth: f64,
    /// κ = 1/λ = d/n', 0 for the uniform limit.
    pub(crate) kappa: f64,
    /// `ln(1 + κ)` (`kappa.ln_1p()`, the same bits), the warp's range: kept so that a lookup
    /// takes one logarithm and a derivative none.
    pub(crate) log_range: f64,
    /// Lateral extents of x/w over B.
    pub(crate) left: f64,
    pub(crate) right: f64,
    /// B's extent along the light axis.
    pub(crate) y_min: f64,
    pub(crate) y_max: f64,
}

impl LogarithmicMap {
    /// GL NDC of a world point (`None` behind a spot light or on the eye's side of the logarithm's
    /// reference point).
    #[must_use]
    pub fn ndc(&self, world: DVec3) -> Option<DVec3> {
        let (q, tau, w) = self.light_point(world)?;
        let x = (2.0 * q.x / w - (self.left + self.right)) / (self.right - self.left);
        let y = 2.0 * self.warp(tau) - 1.0;
        Some(DVec3::new(x, y, self.depth_of(q)))
    }

    /// [`Self::ndc`]'s depth alone (the same bits), without the warp's logarithm: what a texel
    /// stores of the surface its ray hits.
    #[must_use]
    pub fn ndc_depth(&self, world: DVec3) -> Option<f64> {
        self.light_point(world).map(|(q, _, _)| self.depth_of(q))
    }

    /// A world point in light space `q`, the fraction τ of B's depth it lies through and
    /// `w = 1 + κτ`; `None` where [`Self::ndc`] is.
    fn light_point(&self, world: DVec3) -> Option<(DVec3, f64, f64)> {
        let h = self.world_to_light * world.extend(1.0);
        if h.w <= 0.0 {
            return None;
        }
        let q = point_of(h);
        let tau = (self.z_max - q.z) / self.depth;
        let w = 1.0 + self.kappa * tau;
        (w > 0.0).then_some((q, tau, w))
    }

    /// NDC depth of light-space `q`: across B along the light axis.
    fn depth_of(&self, q: DVec3) -> f64 {
        (self.y_max + self.y_min - 2.0 * q.y) / (self.y_max - self.y_min)
    }

    /// The derivative of [`Self::ndc`]'s `(X, Y)` at `world` along `direction` (per unit of
    /// `direction`), differentiated in closed form (the map in the module docs): with
    /// `h = M·(p, 1)`, `ḣ = M·(t, 0)`, `q = h/h_w`, `q̇ = (ḣ·h_w − h·ḣ_w)/h_w²`, `τ̇ = −q̇_z/d` and
    /// `ẇ = κ·τ̇`,
    ///
    /// `Ẋ = 2·(q̇_x·w − q_x·ẇ)/(w²·(r − l))`,  `Ẏ = 2·τ̇·κ/(w·ln(1 + κ))`,
    ///
    /// the last with `κ/ln(1 + κ)` taken as 1 at κ = 0 (the uniform limit). `None` where `ndc` is
    /// `None`. Inlined, so that a caller's derivatives at one point along several directions share
    /// the point's `h`, `q`, `τ` and `w` (docs/benchmarks.md).
    #[inline(always)]
    #[must_use]
    pub fn ndc_derivative(&self, world: DVec3, direction: DVec3) -> Option<DVec2> {
        let h = self.world_to_light * world.extend(1.0);
        if h.w <= 0.0 {
            return None;
        }
        let dh = self.world_to_light * direction.extend(0.0);
        let q = point_of(h);
        let dq = divided(dh.truncate() * h.w - h.truncate() * dh.w, h.w * h.w);
        let tau = (self.z_max - q.z) / self.depth;
        let w = 1.0 + self.kappa * tau;
        if w <= 0.0 {
            return None;
        }
        let dtau = -dq.z / self.depth;
        let dw = self.kappa * dtau;
        let dx = 2.0 * (dq.x * w - q.x * dw) / (w * w * (self.right - self.left));
        let dy = 2.0 * dtau * self.slope() / w;
        Some(DVec2::new(dx, dy))
    }

    /// Each lane's `h = M·(p, 1)`, `q = h/h_w`, `τ` and `w = 1 + κτ` of four points, as
    /// [`Self::light_point`] computes them one point at a time ([`lanes::point_of`]).
    #[inline(always)]
    fn light_lanes(&self, world: Vectors) -> ([f64x4; 4], Vectors, f64x4, f64x4) {
        let h = world.transformed(&self.world_to_light, 1.0);
        let q = lanes::point_of(h);
        let tau = (f64x4::splat(self.z_max) - q.z) / f64x4::splat(self.depth);
        let w = f64x4::ONE + f64x4::splat(self.kappa) * tau;
        (h, q, tau, w)
    }

    /// [`Self::ndc`] of four points (`lanes` module): each lane the one-point operations in
    /// order, the warp's `ln_1p` the C library's per lane; and the lanes where `ndc` is `None`
    /// (their coordinates are meaningless numbers). A unit test holds the two together.
    #[inline(always)]
    #[must_use]
    pub fn ndc_lanes(&self, world: Vectors) -> (Vectors, [bool; LANES]) {
        let (h, q, tau, w) = self.light_lanes(world);
        let two = f64x4::splat(2.0);
        let x = (two * q.x / w - f64x4::splat(self.left + self.right))
            / f64x4::splat(self.right - self.left);
        let warped = if self.kappa > 0.0 {
            let product = (f64x4::splat(self.kappa) * tau).to_array();
            f64x4::new(product.map(f64::ln_1p)) / f64x4::splat(self.log_range)
        } else {
            tau
        };
        let y = two * warped - f64x4::ONE;
        let (z, undefined) = self.depth_lanes(&h, q, w);
        (Vectors { x, y, z }, undefined)
    }

    /// [`Self::ndc_depth`] of four points (`lanes` module): each lane the one-point operations in
    /// order, without the warp's logarithm; and the lanes where it is `None` (their depths are
    /// meaningless numbers). A unit test holds the two together.
    #[inline(always)]
    #[must_use]
    pub fn ndc_depth_lanes(&self, world: Vectors) -> (f64x4, [bool; LANES]) {
        let (h, q, _, w) = self.light_lanes(world);
        self.depth_lanes(&h, q, w)
    }

    /// [`Self::depth_of`] of each lane's light-space `q`, and the lanes [`Self::light_point`]
    /// leaves undefined (`h_w ≤ 0`, or `w = 1 + κτ` not positive), from [`Self::light_lanes`].
    #[inline(always)]
    fn depth_lanes(&self, h: &[f64x4; 4], q: Vectors, w: f64x4) -> (f64x4, [bool; LANES]) {
        let depth = (f64x4::splat(self.y_max + self.y_min) - f64x4::splat(2.0) * q.y)
            / f64x4::splat(self.y_max - self.y_min);
        let (h_w, w) = (h[3].to_array(), w.to_array());
        let undefined = std::array::from_fn(|k| h_w[k] <= 0.0 || w[k].is_nan() || w[k] <= 0.0);
        (depth, undefined)
    }

    /// [`Self::ndc_derivative`] at four points at once (`lanes` module): what the derivatives at
    /// a point share — `h`, `q`, `w` — for the directions [`LanesAt::ndc_derivative`] takes.
    #[inline(always)]
    #[must_use]
    pub fn at_lanes(&self, world: Vectors) -> LanesAt<'_> {
        let (h, q, _, w) = self.light_lanes(world);
        let (h_w, w_lanes) = (h[3].to_array(), w.to_array());
        LanesAt {
            map: self,
            h,
            q,
            w,
            undefined: std::array::from_fn(|k| h_w[k] <= 0.0 || w_lanes[k] <= 0.0),
        }
    }

    /// The ray of light through the shadow-map point at NDC `(x, y)`: its origin on B's light side
    /// (NDC depth −1) and the point where it leaves B's far side (NDC depth +1), in world space.
    /// Casting it and mapping the first hit through [`Self::ndc`] gives the texel's depth.
    #[must_use]
    pub fn texel_ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        self.texel_row(y).ray(x)
    }

    /// The rays of the texels at NDC `y`: [`Self::texel_ray`] with what a row shares — the
    /// inverse warp — computed once (the same bits).
    #[must_use]
    pub fn texel_row(&self, y: f64) -> TexelRow<'_> {
        // Inverse of Y: τ = (exp(s·ln(1 + κ)) − 1)/κ, s = (Y + 1)/2, written with expm1 so that it
        // is exact near τ = 0 and for small κ; τ = s at κ = 0.
        let s = 0.5 * (y + 1.0);
        let tau = if self.kappa > 0.0 {
            (s * self.log_range).exp_m1() / self.kappa
        } else {
            s
        };
        TexelRow {
            map: self,
            w: 1.0 + self.kappa * tau,
            z: self.z_max - tau * self.depth,
        }
    }

    /// λ = n'/d, the reference point's distance beyond B's near plane in units of B's depth;
    /// infinite for the uniform limit.
    #[must_use]
    pub fn lambda(&self) -> f64 {
        1.0 / self.kappa
    }

    /// `dp/ds` along the view axis at eye depth `t`, for the map's own geometry (light space with
    /// the eye at the origin, the view axis at `z = −t·sin γ`, `sin_gamma` of the map's space): with
    /// `c = z_max + λ·d` the reference point's offset from the eye along the warp axis,
    ///
    /// `dp/ds = ln(1 + 1/λ)·(1 + c/(t·sin γ))`,
    ///
    /// the constant `ln(1 + 1/λ)` where the reference point is the eye (`c = 0`), and `d/(t·sin γ)`,
    /// the uniform map's, at κ = 0. Written as `ln(1 + κ)·(1 + z_max/(t sin γ)) + (ln(1 + κ)/κ)·d/(t
    /// sin γ)`, exact at κ = 0.
    #[must_use]
    pub fn view_axis_error(&self, sin_gamma: f64, t: f64) -> f64 {
        let axis = t * sin_gamma;
        self.log_range * (1.0 + self.z_max / axis) + self.depth / (self.slope() * axis)
    }

    /// The warp axis's map coordinate in `[0, 1]` of a point a fraction τ through B:
    /// `ln(1 + κτ)/ln(1 + κ)`, τ itself at κ = 0.
    fn warp(&self, tau: f64) -> f64 {
        if self.kappa > 0.0 {
            (self.kappa * tau).ln_1p() / self.log_range
        } else {
            tau
        }
    }

    /// `κ/ln(1 + κ)`, the warp's slope at τ = 0; 1 at κ = 0.
    fn slope(&self) -> f64 {
        if self.kappa > 0.0 {
            self.kappa / self.log_range
        } else {
            1.0
        }
    }
}

/// A logarithmic map at four points ([`LogarithmicMap::at_lanes`]): each lane's `h = M·(p, 1)`,
/// `q = h/h_w` and `w = 1 + κτ`, as [`LogarithmicMap::ndc_derivative`] computes them.
#[derive(Clone, Copy, Debug)]
pub struct LanesAt<'a> {
    map: &'a LogarithmicMap,
    h: [f64x4; 4],
    q: Vectors,
    w: f64x4,
    undefined: [bool; LANES],
}

impl LanesAt<'_> {
    /// The lanes where [`LogarithmicMap::ndc_derivative`] is `None` (behind a spot light, or on
    /// the eye's side of the reference point): their derivatives are meaningless numbers.
    #[must_use]
    pub fn undefined(&self) -> [bool; LANES] {
        self.undefined
    }

    /// [`LogarithmicMap::ndc_derivative`] along `direction` (one per lane): `(Ẋ, Ẏ)` per lane,
    /// each lane the one-point function's IEEE operations in its order, so its bits wherever it is
    /// defined (`lanes` module; a unit test holds the two together).
    #[inline(always)]
    #[must_use]
    pub fn ndc_derivative(&self, direction: Vectors) -> [f64x4; 2] {
        let map = self.map;
        let dh = direction.transformed(&map.world_to_light, 0.0);
        let (h, q, w) = (&self.h, self.q, self.w);
        // `divided(ḣ·h_w − h·ḣ_w, h_w²)`.
        let h_w2 = h[3] * h[3];
        let dq_x = lanes::quotient(dh[0] * h[3] - h[0] * dh[3], h_w2);
        let dq_z = lanes::quotient(dh[2] * h[3] - h[2] * dh[3], h_w2);
        let dtau = -dq_z / f64x4::splat(map.depth);
        let dw = f64x4::splat(map.kappa) * dtau;
        let two = f64x4::splat(2.0);
        let dx = two * (dq_x * w - q.x * dw) / (w * w * f64x4::splat(map.right - map.left));
        let dy = two * dtau * f64x4::splat(map.slope()) / w;
        [dx, dy]
    }
}

/// One row of a logarithmic map's texel rays ([`LogarithmicMap::texel_row`]).
#[derive(Clone, Copy, Debug)]
pub struct TexelRow<'a> {
    map: &'a LogarithmicMap,
    /// `w = 1 + κτ` of the row.
    w: f64,
    /// The row's light-space z.
    z: f64,
}

impl TexelRow<'_> {
    /// The ray of the texel at NDC `x` in this row ([`LogarithmicMap::texel_ray`]).
    #[must_use]
    pub fn ray(&self, x: f64) -> (DVec3, DVec3) {
        let map = self.map;
        let lateral = 0.5 * self.w * (x * (map.right - map.left) + map.left + map.right);
        let to_world = |light_y: f64| {
            point_of(map.light_to_world * DVec3::new(lateral, light_y, self.z).extend(1.0))
        };
        (to_world(map.y_max), to_world(map.y_min))
    }

    /// [`Self::ray`] of the texel at each NDC `xs[k]`, into `rays[k]` as the ray from its first
    /// point to its second (`Ray { origin: from, direction: to − from }`): four texels at a time
    /// (`lanes` module), each lane the one-texel operations in order, so the same bits (a unit test
    /// holds the two together). What the row's texels share is found once: the lateral scale, and
    /// the products of the light-space `y`, `z` and `w = 1` with their columns of the
    /// light-to-world matrix (each coordinate of glam's `DMat4 · DVec4` is
    /// `((x_axis·x + y_axis·y) + z_axis·z) + w_axis·w`, and a product rounds the same wherever it
    /// is then summed). The points are divided as [`lanes::point_of`] divides.
    ///
    /// # Panics
    /// If `xs` and `rays` differ in length.
    pub fn rays(&self, xs: &[f64], rays: &mut [Ray]) {
        assert_eq!(xs.len(), rays.len(), "one ray per texel");
        let map = self.map;
        let m = &map.light_to_world;
        let (scale, width) = (0.5 * self.w, map.right - map.left);
        // Per coordinate: the z and w terms (`w_axis · 1` is `w_axis`), and the y term at each end.
        let z_terms: [f64; 4] = std::array::from_fn(|i| m.z_axis[i] * self.z);
        let ends = [map.y_max, map.y_min].map(|light_y| {
            let y_terms: [f64; 4] = std::array::from_fn(|i| m.y_axis[i] * light_y);
            move |lateral: f64x4| {
                lanes::point_of(std::array::from_fn(|i| {
                    ((f64x4::splat(m.x_axis[i]) * lateral + f64x4::splat(y_terms[i]))
                        + f64x4::splat(z_terms[i]))
                        + f64x4::splat(m.w_axis[i])
                }))
            }
        });
        let mut blocks = rays.chunks_exact_mut(LANES);
        for (rays, xs) in (&mut blocks).zip(xs.chunks_exact(LANES)) {
            let x = f64x4::new(std::array::from_fn(|k| xs[k]));
            let lateral = f64x4::splat(scale)
                * ((x * f64x4::splat(width) + f64x4::splat(map.left)) + f64x4::splat(map.right));
            let (from, to) = (ends[0](lateral), ends[1](lateral));
            let direction = to.minus(from);
            let [ox, oy, oz, dx, dy, dz] = [
                from.x,
                from.y,
                from.z,
                direction.x,
                direction.y,
                direction.z,
            ]
            .map(f64x4::to_array);
            for (k, ray) in rays.iter_mut().enumerate() {
                *ray = Ray {
                    origin: DVec3::new(ox[k], oy[k], oz[k]),
                    direction: DVec3::new(dx[k], dy[k], dz[k]),
                };
            }
        }
        let done = xs.len() - blocks.into_remainder().len();
        for (ray, &x) in rays[done..].iter_mut().zip(&xs[done..]) {
            let (from, to) = self.ray(x);
            *ray = Ray {
                origin: from,
                direction: to - from,
            };
        }
    }
}
