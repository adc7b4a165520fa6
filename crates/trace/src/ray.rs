//! Rays, hits, and the per-ray set-up that every box and triangle test of one query shares.

use glam::DVec3;
use wide::f64x4;

use crate::error::TraceError;

/// The largest coordinate magnitude accepted for vertex positions and ray origins, and the largest
/// ray-direction component: 2²⁰⁰ ≈ 1.6·10⁶⁰.
///
/// Within it no intermediate of the ray–triangle test overflows: coordinates relative to the origin
/// stay below 2²⁰¹, sheared ones below 2²⁰², edge functions below 2⁴⁰⁵, scaled depths below 2⁴⁰¹
/// (with [`MIN_DIRECTION`]), and their weighted sum below 2⁸⁰⁸.
pub const MAX_COORDINATE: f64 = f64::from_bits((1023 + 200) << 52);

/// The smallest accepted magnitude of a ray direction's largest component: 2⁻²⁰⁰ ≈ 6.2·10⁻⁶¹.
/// It keeps `1/direction` along the dominant axis finite, and every hit parameter below 2⁴⁰¹.
pub const MIN_DIRECTION: f64 = f64::from_bits((1023 - 200) << 52);

/// The padding of every bounding box, per ray, in units of `f64::EPSILON × (M + |origin|∞)`, where
/// `M` is the largest absolute vertex coordinate of the mesh ([`crate::Bvh::magnitude`]). 8
/// suffices: the ray–triangle test acts as if vertices moved by less than `3.5·ε·(M + |origin|∞)`,
/// and the slab test rounds by about `1.5·ε·(M + |origin|∞)` more (the proof is in the source of
/// the `bvh` module).
pub const BOX_PADDING_ULPS: f64 = 8.0;

/// A ray `origin + t·direction`. The direction need not be of unit length: the parameter `t` of a
/// [`Hit`] is measured in units of `direction`, so a ray from `p` with `direction = q − p` passes
/// through `q` at `t = 1` (exactly when `q − p` is computed without rounding).
///
/// Queries accept only valid rays ([`Ray::validate`]): finite origin with coordinates of at most
/// [`MAX_COORDINATE`] in magnitude, and a finite direction whose largest component has a magnitude
/// in [[`MIN_DIRECTION`], [`MAX_COORDINATE`]].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts (`t = 0`).
    pub origin: DVec3,
    /// Where it goes, per unit of `t`.
    pub direction: DVec3,
}

impl Ray {
    /// A validated ray.
    ///
    /// # Errors
    /// See [`Ray::validate`].
    pub fn new(origin: DVec3, direction: DVec3) -> Result<Self, TraceError> {
        let ray = Self { origin, direction };
        ray.validate()?;
        Ok(ray)
    }

    /// Checks that every query accepts this ray.
    ///
    /// # Errors
    /// [`TraceError::NonFinite`] naming `origin` or `direction`; [`TraceError::OutOfRange`]
    /// naming `origin` for a coordinate beyond [`MAX_COORDINATE`];
    /// [`TraceError::DirectionOutOfRange`] for a zero direction or one whose largest component
    /// lies outside [[`MIN_DIRECTION`], [`MAX_COORDINATE`]].
    pub fn validate(&self) -> Result<(), TraceError> {
        if !self.origin.is_finite() {
            return Err(TraceError::NonFinite {
                parameter: "origin",
            });
        }
        if !self.direction.is_finite() {
            return Err(TraceError::NonFinite {
                parameter: "direction",
            });
        }
        let origin = self.origin.abs().max_element();
        if origin > MAX_COORDINATE {
            return Err(TraceError::OutOfRange {
                parameter: "origin",
                value: origin,
            });
        }
        let largest = self.direction.abs().max_element();
        if !(MIN_DIRECTION..=MAX_COORDINATE).contains(&largest) {
            return Err(TraceError::DirectionOutOfRange { largest });
        }
        Ok(())
    }

    /// The point `origin + t·direction` (rounded per coordinate).
    #[must_use]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }
}

/// Where a ray meets a triangle.
///
/// The hit point is `(1 − u − v)·p0 + u·p1 + v·p2` for the triangle's vertices `p0, p1, p2` (in
/// the order given to [`crate::Bvh::new`]); `u, v ≥ 0` and `u + v ≤ 1` up to rounding.
/// [`crate::Bvh::hit_point`] evaluates it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The ray parameter, in units of the ray's direction.
    pub t: f64,
    /// The triangle's index in the slice given to [`crate::Bvh::new`].
    pub triangle: u32,
    /// The barycentric coordinate of the triangle's second vertex (`p1`).
    pub u: f64,
    /// The barycentric coordinate of the triangle's third vertex (`p2`).
    pub v: f64,
}

/// One query's ray, set up once for all of its box and triangle tests.
///
/// * The **shear** of Woop, Benthin & Wald (JCGT 2013, §3): `kz` is the axis of the direction's
///   largest component (the first on ties), `kx = kz + 1`, `ky = kz + 2` (mod 3), and
///   `shear = (d[kx]/d[kz], d[ky]/d[kz], 1/d[kz])`. Vertices are transformed per query, never per
///   triangle, so a vertex shared by two triangles lands on the same sheared point in both.
/// * The **slab** set-up: `inverse = 1/d` per axis, and two shifted origins per axis so that one
///   subtraction and one multiplication give the entry and exit parameter of a box grown by the
///   padding `e = BOX_PADDING_ULPS·ε·(M + |origin|∞)`. The shifted origins are rounded outward
///   (`next_up`/`next_down`), so the box is grown by at least `e`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedRay {
    pub(crate) origin: [f64; 3],
    /// The dominant axis `kz` (0, 1 or 2).
    pub(crate) kz: usize,
    /// `(d[kx]/d[kz], d[ky]/d[kz], 1/d[kz])`.
    pub(crate) shear: [f64; 3],
    /// `1/d` per axis (±∞ for a zero component).
    pub(crate) inverse: [f64; 3],
    /// Whether `d` has a negative sign bit per axis: the entry plane is then the box's upper bound.
    pub(crate) negative: [bool; 3],
    /// The origin shifted so that `(entry plane − near_origin)·inverse` is the entry parameter of
    /// the padded box.
    pub(crate) near_origin: [f64; 3],
    /// The same for the exit plane.
    pub(crate) far_origin: [f64; 3],
}

impl PreparedRay {
    /// Sets `ray` up against a mesh whose largest absolute vertex coordinate is `magnitude`.
    ///
    /// Always inlined: out of line, the batch queries read each prepared ray back in a wider
    /// load than the stores that wrote it, a store-forwarding stall (docs/benchmarks.md, "f32 node
    /// boxes and an inlined ray set-up").
    ///
    /// # Errors
    /// As [`Ray::validate`].
    #[inline(always)]
    pub(crate) fn new(ray: &Ray, magnitude: f64) -> Result<Self, TraceError> {
        ray.validate()?;
        Ok(Self::set_up(ray, magnitude))
    }

    /// [`Self::new`] for a ray already validated ([`Ray::validate`]).
    #[inline(always)]
    pub(crate) fn set_up(ray: &Ray, magnitude: f64) -> Self {
        let o = ray.origin.to_array();
        let d = ray.direction.to_array();
        let abs = ray.direction.abs();
        let kz = if abs.x >= abs.y && abs.x >= abs.z {
            0
        } else if abs.y >= abs.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        // The six divisions as two vector divisions, lane by lane the same quotients.
        let [shear_x, shear_y, shear_z, _] =
            (f64x4::new([d[kx], d[ky], 1.0, 1.0]) / f64x4::splat(d[kz])).to_array();
        let shear = [shear_x, shear_y, shear_z];
        let [inverse_x, inverse_y, inverse_z, _] =
            (f64x4::ONE / f64x4::new([d[0], d[1], d[2], 1.0])).to_array();
        let inverse = [inverse_x, inverse_y, inverse_z];
        // The padding: multiplying by a power of two is exact.
        let reach = magnitude + ray.origin.abs().max_element();
        let padding = reach * (BOX_PADDING_ULPS * f64::EPSILON);
        let mut negative = [false; 3];
        let mut near_origin = [0.0; 3];
        let mut far_origin = [0.0; 3];
        for axis in 0..3 {
            negative[axis] = d[axis].is_sign_negative();
            let up = (o[axis] + padding).next_up();
            let down = (o[axis] - padding).next_down();
            // Entry plane lo − e (direction ≥ 0) or hi + e (direction < 0); exit plane the other.
            (near_origin[axis], far_origin[axis]) = if negative[axis] {
                (down, up)
            } else {
                (up, down)
            };
        }
        Self {
            origin: o,
            kz,
            shear,
            inverse,
            negative,
            near_origin,
            far_origin,
        }
    }

    /// The parameter interval `[near, far]` in which the ray lies in the padded box `lo..hi`,
    /// intersected with `[t_lo, t_hi]`; empty when `near > far`.
    ///
    /// Per axis: `(plane − shifted origin)·inverse`. A zero direction component makes `inverse`
    /// infinite: the product is −∞ or +∞ (the origin is inside or outside the slab), or NaN when
    /// the origin lies exactly on the padded plane. Comparisons ignore NaN (`x > near` is false),
    /// which treats the slab as unbounded: conservative. Every step is monotone in `lo` and `hi`,
    /// so a box inside another gets an interval inside the other's: a triangle's interval lies in
    /// each of its ancestors'.
    #[inline]
    pub(crate) fn slab(&self, lo: [f64; 3], hi: [f64; 3], t_lo: f64, t_hi: f64) -> (f64, f64) {
        let mut near = t_lo;
        let mut far = t_hi;
        for axis in 0..3 {
            let (entry, exit) = if self.negative[axis] {
                (hi[axis], lo[axis])
            } else {
                (lo[axis], hi[axis])
            };
            let t_entry = (entry - self.near_origin[axis]) * self.inverse[axis];
            let t_exit = (exit - self.far_origin[axis]) * self.inverse[axis];
            if t_entry > near {
                near = t_entry;
            }
            if t_exit < far {
                far = t_exit;
            }
        }
        (near, far)
    }
}
