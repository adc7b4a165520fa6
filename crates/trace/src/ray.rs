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

/// Rays set up as [`PreparedRay`] sets each up, held field by field (a structure of arrays), so
/// that the fields of any four consecutive rays load as vectors: a grid's rows, tested four rays
/// at a time against one triangle (`triangle::intersect_rays`). Set up four at a time
/// ([`PreparedRays::set_up`]), each lane the one-ray operations, so the same bits.
#[derive(Clone, Debug, Default)]
pub(crate) struct PreparedRays {
    /// [`PreparedRay::origin`], per axis.
    pub(crate) origin: [Vec<f64>; 3],
    /// The rays' directions, per axis.
    pub(crate) direction: [Vec<f64>; 3],
    /// [`PreparedRay::kz`].
    pub(crate) kz: Vec<u8>,
    /// [`PreparedRay::shear`], per component.
    pub(crate) shear: [Vec<f64>; 3],
    /// [`PreparedRay::inverse`], per axis; its sign is [`PreparedRay::negative`]'s (`1/d` keeps
    /// `d`'s sign, zeros included).
    inverse: [Vec<f64>; 3],
    /// [`PreparedRay::near_origin`], per axis.
    near_origin: [Vec<f64>; 3],
    /// [`PreparedRay::far_origin`], per axis.
    far_origin: [Vec<f64>; 3],
}

impl PreparedRays {
    /// `rays` set up against a mesh of magnitude `magnitude`, in place of the rays held: four at a
    /// time in `f64x4` lanes, the last few one by one. Whether every ray is valid
    /// ([`Ray::validate`]); an invalid ray's set-up holds no meaningful values.
    #[must_use]
    pub(crate) fn set_up(&mut self, rays: &[Ray], magnitude: f64) -> bool {
        let fields = self
            .origin
            .iter_mut()
            .chain(&mut self.direction)
            .chain(&mut self.shear)
            .chain(&mut self.inverse)
            .chain(&mut self.near_origin)
            .chain(&mut self.far_origin);
        // Every entry is written below: a work item as long as the last one resizes nothing
        // (clearing first would zero every array again: 4 % of the logarithmic map's pass in perf).
        for field in fields {
            field.resize(rays.len(), 0.0);
        }
        self.kz.resize(rays.len(), 0);
        let mut valid = true;
        let mut fours = rays.chunks_exact(4);
        for (k, four) in (&mut fours).enumerate() {
            valid &= self.set_four(4 * k, four, magnitude);
        }
        let done = rays.len() - fours.remainder().len();
        for (k, ray) in fours.remainder().iter().enumerate() {
            valid &= ray.validate().is_ok();
            self.set(done + k, ray, magnitude);
        }
        valid
    }

    /// Rays `first..first + 4`, `rays`, set up side by side: [`PreparedRay::set_up`] lane by lane —
    /// the dominant axis chosen per lane, the same IEEE quotients, sums and products, and the next
    /// doubles up and down taken on the bits as `f64::next_up` and `f64::next_down` take them.
    /// Whether all four are valid ([`Ray::validate`]'s conditions, lane by lane).
    #[inline(always)]
    fn set_four(&mut self, first: usize, rays: &[Ray], magnitude: f64) -> bool {
        let lanes = |f: fn(&Ray) -> f64| f64x4::new(std::array::from_fn(|k| f(&rays[k])));
        let o = [
            lanes(|r| r.origin.x),
            lanes(|r| r.origin.y),
            lanes(|r| r.origin.z),
        ];
        let d = [
            lanes(|r| r.direction.x),
            lanes(|r| r.direction.y),
            lanes(|r| r.direction.z),
        ];
        let abs = d.map(f64x4::abs);
        let [ax, ay, az] = abs.map(f64x4::to_array);
        let [dx, dy, dz] = d.map(f64x4::to_array);
        // Per lane, `d[kz]`, `d[kx]`, `d[ky]` for `PreparedRay::set_up`'s dominant axis `kz`.
        let mut kz = [0_u8; 4];
        let mut picked = [[0.0; 4]; 3];
        for k in 0..4 {
            let x_first = ax[k] >= ay[k] && ax[k] >= az[k];
            let y_over_z = ay[k] >= az[k];
            kz[k] = if x_first {
                0
            } else if y_over_z {
                1
            } else {
                2
            };
            let (z, x, y) = if x_first {
                (dx[k], dy[k], dz[k])
            } else if y_over_z {
                (dy[k], dz[k], dx[k])
            } else {
                (dz[k], dx[k], dy[k])
            };
            (picked[0][k], picked[1][k], picked[2][k]) = (z, x, y);
        }
        let [along_z, along_x, along_y] = picked.map(f64x4::new);
        let shear = [along_x / along_z, along_y / along_z, f64x4::ONE / along_z];
        let inverse = d.map(|d| f64x4::ONE / d);
        let farthest = o[0].abs().max(o[1].abs().max(o[2].abs()));
        let reach = f64x4::splat(magnitude) + farthest;
        let padding = reach * f64x4::splat(BOX_PADDING_ULPS * f64::EPSILON);
        // `Ray::validate`'s conditions as lane masks (where every coordinate is finite, the
        // maxima are those of the one-ray check), kept in registers: gathered per lane into an
        // array, they were read back across the stores that wrote them (a store-forwarding stall).
        let finite = [o[1], o[2], d[0], d[1], d[2]]
            .into_iter()
            .fold(o[0].is_finite(), |all, v| all & v.is_finite());
        let largest = abs[0].max(abs[1]).max(abs[2]);
        let (least, most) = (f64x4::splat(MIN_DIRECTION), f64x4::splat(MAX_COORDINATE));
        let valid =
            (finite & farthest.simd_le(most) & largest.simd_ge(least) & largest.simd_le(most))
                .all();
        let origins = o.map(f64x4::to_array);
        let range = first..first + 4;
        for axis in 0..3 {
            let up = next_double(o[axis] + padding, true);
            let down = next_double(o[axis] - padding, false);
            // Entry plane lo − e (direction ≥ 0) or hi + e (direction < 0); exit plane the other.
            let negative = [dx, dy, dz][axis].map(f64::is_sign_negative);
            let near: [f64; 4] = std::array::from_fn(|k| if negative[k] { down[k] } else { up[k] });
            let far: [f64; 4] = std::array::from_fn(|k| if negative[k] { up[k] } else { down[k] });
            self.origin[axis][range.clone()].copy_from_slice(&origins[axis]);
            self.direction[axis][range.clone()].copy_from_slice(&[dx, dy, dz][axis]);
            self.shear[axis][range.clone()].copy_from_slice(&shear[axis].to_array());
            self.inverse[axis][range.clone()].copy_from_slice(&inverse[axis].to_array());
            self.near_origin[axis][range.clone()].copy_from_slice(&near);
            self.far_origin[axis][range.clone()].copy_from_slice(&far);
        }
        self.kz[range].copy_from_slice(&kz);
        valid
    }

    /// Ray `k` set to `ray`, set up one by one ([`PreparedRay::set_up`]).
    fn set(&mut self, k: usize, ray: &Ray, magnitude: f64) {
        let prepared = PreparedRay::set_up(ray, magnitude);
        for axis in 0..3 {
            self.origin[axis][k] = prepared.origin[axis];
            self.direction[axis][k] = ray.direction[axis];
            self.shear[axis][k] = prepared.shear[axis];
            self.inverse[axis][k] = prepared.inverse[axis];
            self.near_origin[axis][k] = prepared.near_origin[axis];
            self.far_origin[axis][k] = prepared.far_origin[axis];
        }
        self.kz[k] = u8::try_from(prepared.kz).expect("an axis is 0, 1 or 2");
    }

    /// Ray `k`, as [`PreparedRay::set_up`] gives it.
    #[inline(always)]
    pub(crate) fn ray(&self, k: usize) -> PreparedRay {
        let at = |field: &[Vec<f64>; 3]| field.each_ref().map(|values| values[k]);
        let inverse = at(&self.inverse);
        PreparedRay {
            origin: at(&self.origin),
            kz: usize::from(self.kz[k]),
            shear: at(&self.shear),
            inverse,
            negative: inverse.map(f64::is_sign_negative),
            near_origin: at(&self.near_origin),
            far_origin: at(&self.far_origin),
        }
    }

    /// How many rays are held.
    pub(crate) fn len(&self) -> usize {
        self.kz.len()
    }

    /// Field `values` of the four rays from `first`.
    #[inline(always)]
    pub(crate) fn lanes(values: &[f64], first: usize) -> f64x4 {
        let four: [f64; 4] = values[first..first + 4].try_into().expect("four values");
        f64x4::new(four)
    }

    /// [`PreparedRay::slab`] of the four rays from `first` against the box `lo..hi`, from
    /// `(−∞, ∞)`: each lane the one-ray operations in their order (the entry and exit planes picked
    /// by the sign of `inverse`, the same differences and products, a bound replaced only where the
    /// new one is strictly tighter), so the same bits.
    #[inline(always)]
    pub(crate) fn slabs(&self, first: usize, lo: [f64; 3], hi: [f64; 3]) -> (f64x4, f64x4) {
        let mut near = f64x4::splat(f64::NEG_INFINITY);
        let mut far = f64x4::splat(f64::INFINITY);
        for axis in 0..3 {
            let inverse = Self::lanes(&self.inverse[axis], first);
            let negative = inverse.is_sign_negative();
            let (lo, hi) = (f64x4::splat(lo[axis]), f64x4::splat(hi[axis]));
            let (entry, exit) = (negative.bitselect(hi, lo), negative.bitselect(lo, hi));
            let t_entry = (entry - Self::lanes(&self.near_origin[axis], first)) * inverse;
            let t_exit = (exit - Self::lanes(&self.far_origin[axis], first)) * inverse;
            near = t_entry.simd_gt(near).bitselect(t_entry, near);
            far = t_exit.simd_lt(far).bitselect(t_exit, far);
        }
        (near, far)
    }
}

/// Of each lane of finite `x`, `f64::next_up` if `up`, else `f64::next_down`: on the bits, one
/// step away from zero or toward it by the lane's sign, and from either zero the least subnormal
/// of the direction's sign.
#[inline(always)]
fn next_double(x: f64x4, up: bool) -> [f64; 4] {
    x.to_array().map(|x| {
        let bits = x.to_bits();
        // +1 (away from zero) going up from a positive lane or down from a negative one, else −1.
        let away = (bits >> 63 == 0) == up;
        let next = if bits & !SIGN_BIT == 0 {
            if up { 1 } else { SIGN_BIT | 1 }
        } else {
            bits.wrapping_add(u64::from(away).wrapping_mul(2).wrapping_sub(1))
        };
        f64::from_bits(next)
    })
}

/// The sign bit of an f64.
const SIGN_BIT: u64 = 1 << 63;

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

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use shadowlab_test_random::SplitMix;

    use super::{MAX_COORDINATE, MIN_DIRECTION, PreparedRay, PreparedRays, Ray};

    /// A coordinate that is often a special case: either zero, a tie with another axis, or random.
    fn coordinate(random: &mut SplitMix, tie: f64) -> f64 {
        match random.next_u64() % 8 {
            0 => 0.0,
            1 => -0.0,
            2 => tie,
            3 => -tie,
            4 => f64::from_bits(1) * random.range(-3.0, 3.0).round(),
            _ => random.range(-50.0, 50.0),
        }
    }

    /// Claim: rays set up four at a time (`PreparedRays::set_up`) hold, ray by ray, every field of
    /// `PreparedRay::set_up` to the bit — over origins and directions with zeros of either sign,
    /// tied components (the dominant axis's first-on-ties rule), subnormals, and counts that leave
    /// one to three rays for the one-by-one path — one holder set up again and again, its counts
    /// growing and shrinking, holding nothing of the set-up before.
    #[test]
    fn rays_set_up_four_at_a_time_are_each_rays_set_up() {
        let mut random = SplitMix(0x5eed_0000_0000_5e70);
        let mut held = PreparedRays::default();
        for count in [1, 4, 7, 64, 1023, 7, 64, 5, 1] {
            let rays: Vec<Ray> = (0..count)
                .map(|_| {
                    loop {
                        let tie = random.range(-2.0, 2.0);
                        let mut axes = || coordinate(&mut random, tie);
                        let origin = DVec3::new(axes(), axes(), axes());
                        let direction = DVec3::new(axes(), axes(), axes());
                        if let Ok(ray) = Ray::new(origin, direction) {
                            break ray;
                        }
                    }
                })
                .collect();
            assert!(held.set_up(&rays, 8.0), "{count} valid rays");
            assert_eq!(held.len(), count);
            for (k, ray) in rays.iter().enumerate() {
                let (four, one) = (held.ray(k), PreparedRay::set_up(ray, 8.0));
                let bits = |p: &PreparedRay| {
                    let fields = [p.origin, p.shear, p.inverse, p.near_origin, p.far_origin];
                    (p.kz, p.negative, fields.map(|f| f.map(f64::to_bits)))
                };
                assert_eq!(bits(&four), bits(&one), "ray {k} of {count}: {ray:?}");
            }
        }
    }

    /// Claim: the set-up reports an invalid ray wherever it stands — in a lane or in the tail —
    /// for each of `Ray::validate`'s conditions, and only then.
    #[test]
    fn set_up_reports_what_validate_rejects() {
        let valid = Ray::new(DVec3::ONE, DVec3::NEG_Z).expect("valid");
        let invalid = [
            (DVec3::new(f64::NAN, 0.0, 0.0), DVec3::Z),
            (DVec3::ZERO, DVec3::new(0.0, f64::INFINITY, 0.0)),
            (DVec3::new(0.0, 0.0, 2.0 * MAX_COORDINATE), DVec3::Z),
            (DVec3::ZERO, DVec3::ZERO),
            (DVec3::ZERO, DVec3::new(0.0, 0.5 * MIN_DIRECTION, 0.0)),
            (DVec3::ZERO, DVec3::new(2.0 * MAX_COORDINATE, 1.0, 0.0)),
        ];
        let mut held = PreparedRays::default();
        for (origin, direction) in invalid {
            let bad = Ray { origin, direction };
            assert!(bad.validate().is_err());
            for at in [0, 3, 5, 9] {
                let mut rays = vec![valid; 10];
                rays[at] = bad;
                assert!(!held.set_up(&rays, 8.0), "{bad:?} at {at}");
            }
        }
        assert!(held.set_up(&[valid; 10], 8.0));
    }
}
