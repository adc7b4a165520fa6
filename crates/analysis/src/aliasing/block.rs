//! A pixel's footprint ([`footprint_of`](super::footprint_of) of [`local`](super::local)) through a
//! projective, the logarithmic or a paraboloid map, for four pixels at once.
//!
//! The footprint's arithmetic is a long chain of products, divisions and square roots per pixel
//! (three derivatives, each a division; a normalisation, two projections onto the plane, two
//! lengths and two cosines), with nothing shared between pixels. Four pixels side by side, one
//! coordinate of four vectors in one register, let each step run as one vector instruction for
//! all four, so that the divider and the square-root unit take four lanes per instruction and the
//! four chains' latencies overlap.
//!
//! Each lane performs exactly the operations of [`local`](super::local) on its pixel, in the same
//! order (the two `hypot`s correctly rounded, four lanes at once) — glam's `DVec3::dot` is
//! `(x·x′ + y·y′) + z·z′`, `DMat4 · DVec4` sums its columns from `x` to `w`, the homogeneous `w`
//! of a direction multiplies the last column by 0 and adds it — and neither Rust nor `wide`
//! contracts a product and a sum into a fused multiply-add, so every lane gives the same bits as
//! the one-pixel function (the tests compare them over random and degenerate input). The tests
//! the one-pixel function makes one at a time — a normal of zero length, a point behind the eye or
//! the map's centre, a plane through the eye, a result that is not finite — are made for all lanes
//! at the end; a lane that fails one computes meaningless numbers before being dropped, as no IEEE
//! operation traps.

use glam::{DMat4, DVec3};
use shadowlab_shadow::LaneMapping;
use shadowlab_shadow::lanes::{self, LANES, Vectors};
use shadowlab_shadow::{logarithmic, paraboloid};
use wide::f64x4;

use super::{Footprint, GRAZING_COS, Viewer};
use crate::hypot::hypot_lanes;

/// A [`LaneMapping`] at four points: `At` of the one-pixel function, lane by lane.
enum LanesAt<'a> {
    /// A projective map and the points' clip coordinates.
    Projective { m: &'a DMat4, clip: [f64x4; 4] },
    /// The logarithmic map at the points.
    Logarithmic(logarithmic::LanesAt<'a>),
    /// A paraboloid hemisphere at the points.
    Paraboloid(paraboloid::LanesAt<'a>),
}

impl LanesAt<'_> {
    fn new<'a>(mapping: LaneMapping<'a>, points: Vectors) -> LanesAt<'a> {
        match mapping {
            LaneMapping::Projective(m) => LanesAt::Projective {
                m,
                clip: points.transformed(m, 1.0),
            },
            LaneMapping::Logarithmic(map) => LanesAt::Logarithmic(map.at_lanes(points)),
            LaneMapping::Paraboloid(map) => LanesAt::Paraboloid(map.at_lanes(points)),
        }
    }

    /// The lanes the mapping does not differentiate at: behind a projective map's centre (clip
    /// `w <= 0`), where the logarithmic or paraboloid map's derivative is `None`.
    fn undefined(&self) -> [bool; LANES] {
        match self {
            Self::Projective { clip, .. } => {
                let w = clip[3].to_array();
                std::array::from_fn(|k| w[k] <= 0.0)
            }
            Self::Logarithmic(at) => at.undefined(),
            Self::Paraboloid(at) => at.undefined(),
        }
    }

    /// `At::derivative` in texels: the window coordinates' derivative along `direction`, times
    /// `texels`, a projective map's divided as `lanes::quotient` divides (as the one-pixel
    /// function's `quotient`). The logarithmic and paraboloid maps' NDC derivatives are halved into
    /// window units, as there.
    #[inline(always)]
    fn derivative(&self, direction: Vectors, texels: f64x4) -> [f64x4; 2] {
        let half = f64x4::splat(0.5);
        match self {
            Self::Projective { m, clip } => {
                let dp = direction.transformed(m, 0.0);
                let w = clip[3];
                let d = |i: usize| {
                    lanes::quotient(half * (dp[i] * w - clip[i] * dp[3]), w * w) * texels
                };
                [d(0), d(1)]
            }
            Self::Logarithmic(at) => at.ndc_derivative(direction).map(|d| d * half * texels),
            Self::Paraboloid(at) => at.ndc_derivative(direction).map(|d| d * half * texels),
        }
    }
}

/// [`footprint_of`](super::footprint_of)`(`[`local`](super::local)`)` through `mapping` at four
/// points with their normals, lane by lane (module docs).
pub(super) fn footprint_block(
    mapping: LaneMapping<'_>,
    resolution: u32,
    viewer: &Viewer,
    points: &[DVec3; LANES],
    normals: &[DVec3; LANES],
) -> [Option<Footprint>; LANES] {
    let normal = Vectors::of(normals);
    // `DVec3::try_normalize`: the normal times the reciprocal of its length.
    let reciprocal = f64x4::ONE / normal.length();
    let n = normal.times(reciprocal);
    let to_point = Vectors::of(points).minus(Vectors::splat(viewer.eye));
    let depth = to_point.dot(Vectors::splat(viewer.forward));
    let facing = to_point.dot(n);
    // One pixel's step of the eye ray at the point's depth, then onto the plane.
    let across = Vectors::splat(viewer.right).times(f64x4::splat(viewer.step_x) * depth);
    let up = Vectors::splat(viewer.up).times(f64x4::splat(viewer.step_y) * depth);
    let on_plane = |step: Vectors| step.minus(to_point.times(step.dot(n) / facing));
    let (t1, t2) = (on_plane(across), on_plane(up));
    let distance = to_point.length();
    let texels = f64x4::splat(f64::from(resolution));
    let at = LanesAt::new(mapping, Vectors::of(points));
    let [d1x, d1y] = at.derivative(t1, texels);
    let [d2x, d2y] = at.derivative(t2, texels);
    let [dnx, dny] = at.derivative(n, texels);
    // The light's ray: c·(t1, t2, n) with Du·(t1, t2, n)·c = 0, summed from the left.
    let c = Vectors {
        x: d1x,
        y: d2x,
        z: dnx,
    }
    .cross(Vectors {
        x: d1y,
        y: d2y,
        z: dny,
    });
    let ray = t1.times(c.x).plus(t2.times(c.y)).plus(n.times(c.z));
    let cos_alpha = facing.abs() / distance;
    let cos_beta = ray.dot(n).abs() / ray.length();
    // `footprint_of`: σ_max of J = [[a, b], [c, d]] over |det J|, and the projection factor.
    let (a, b, c, d) = (d1x, d2x, d1y, d2y);
    let sigma_max = f64x4::splat(0.5) * (hypot_lanes(a + d, c - b) + hypot_lanes(a - d, b + c));
    let total = sigma_max / (a * d - c * b).abs();
    let projection = cos_alpha / cos_beta;
    let perspective = total / projection;
    let undifferentiated = at.undefined();
    let [
        reciprocal,
        depth,
        facing,
        cos_beta,
        total,
        projection,
        perspective,
    ] = [
        reciprocal,
        depth,
        facing,
        cos_beta,
        total,
        projection,
        perspective,
    ]
    .map(f64x4::to_array);
    let jacobian = [d1x, d1y, d2x, d2y].map(f64x4::to_array);
    std::array::from_fn(|k| {
        let normalised = reciprocal[k].is_finite() && reciprocal[k] > 0.0;
        let seen = !(depth[k] <= 0.0 || facing[k] == 0.0 || !facing[k].is_finite());
        let finite = jacobian.iter().all(|v| v[k].is_finite()) && cos_beta[k].is_finite();
        let defined = normalised && seen && !undifferentiated[k] && finite;
        let grazed = cos_beta[k] < GRAZING_COS;
        let footprint =
            !grazed && total[k].is_finite() && projection[k].is_finite() && projection[k] > 0.0;
        (defined && footprint).then_some(Footprint {
            total: total[k],
            perspective: perspective[k],
            projection: projection[k],
        })
    })
}

#[cfg(test)]
mod tests {
    use glam::{DMat4, DVec3, DVec4};

    use super::{LANES, LaneMapping, footprint_block};
    use crate::aliasing::{Footprint, Prepared, Viewer, footprint_of, local};
    use shadowlab_test_random::SplitMix;

    /// The same bits, or both undefined.
    fn same(block: Option<Footprint>, one: Option<Footprint>) -> bool {
        match (block, one) {
            (None, None) => true,
            (Some(a), Some(b)) => [
                (a.total, b.total),
                (a.perspective, b.perspective),
                (a.projection, b.projection),
            ]
            .iter()
            .all(|(a, b)| a.to_bits() == b.to_bits()),
            _ => false,
        }
    }

    /// Four pixels side by side give each pixel's one-by-one footprint to the bit: random
    /// projective and affine maps, viewers, points and normals, with lanes made degenerate — a
    /// zero or NaN normal, a point at the eye or behind it, a point behind the map's centre, a
    /// normal edge-on to the light — among well-defined ones.
    #[test]
    fn four_pixels_side_by_side_are_each_pixel_alone() {
        let mut random = SplitMix(0x5eed_0000_0000_0b10);
        let (mut defined, mut undefined) = (0, 0);
        for round in 0..4000_u32 {
            let column = |random: &mut SplitMix| {
                DVec4::new(
                    random.range(-2.0, 2.0),
                    random.range(-2.0, 2.0),
                    random.range(-2.0, 2.0),
                    random.range(-2.0, 2.0),
                )
            };
            let mut m = DMat4::from_cols(
                column(&mut random),
                column(&mut random),
                column(&mut random),
                column(&mut random),
            );
            if round % 3 == 0 {
                // Affine: the last row (0, 0, 0, 1), so w = 1 exactly.
                (m.x_axis.w, m.y_axis.w, m.z_axis.w, m.w_axis.w) = (0.0, 0.0, 0.0, 1.0);
            }
            let viewer = Viewer {
                eye: random.vector(5.0),
                forward: random.vector(1.0),
                right: random.vector(1.0),
                up: random.vector(1.0),
                step_x: random.range(1e-4, 1e-2),
                step_y: random.range(1e-4, 1e-2),
            };
            let resolution = 750 + 250 * (round % 6);
            let mut points = [DVec3::ZERO; LANES];
            let mut normals = [DVec3::ZERO; LANES];
            for k in 0..LANES {
                points[k] =
                    viewer.eye + viewer.forward * random.range(1.0, 20.0) + random.vector(5.0);
                normals[k] = random.vector(1.0);
                match (round as usize + k) % 11 {
                    0 => normals[k] = DVec3::ZERO,
                    1 => normals[k].y = f64::NAN,
                    2 => points[k] = viewer.eye,
                    3 => points[k] = viewer.eye - viewer.forward * random.range(0.0, 3.0),
                    // On the plane w = 0 of the map, or just behind it.
                    4 => {
                        let w = DVec3::new(m.x_axis.w, m.y_axis.w, m.z_axis.w);
                        if w != DVec3::ZERO {
                            let shift = (m.w_axis.w + points[k].dot(w)) / w.length_squared();
                            points[k] -= w * (shift + random.range(0.0, 1e-9));
                        }
                    }
                    _ => {}
                }
            }
            let block = footprint_block(
                LaneMapping::Projective(&m),
                resolution,
                &viewer,
                &points,
                &normals,
            );
            let mapping = Prepared::Projective(m);
            for k in 0..LANES {
                let one = local(&mapping, resolution, &viewer, points[k], normals[k])
                    .as_ref()
                    .and_then(footprint_of);
                assert!(
                    same(block[k], one),
                    "round {round}, lane {k}: {:?} against {one:?}",
                    block[k]
                );
                if one.is_some() {
                    defined += 1;
                } else {
                    undefined += 1;
                }
            }
        }
        assert!(defined > 4000 && undefined > 4000, "{defined} {undefined}");
    }
}
