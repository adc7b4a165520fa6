//! Four neighbouring pixels looked up in one map at once — projective, logarithmic or a paraboloid
//! hemisphere — by the nearest filter, PCF or the jittered disk with a slope-scaled bias
//! (shadowlab's default lookup, and its filters).
//!
//! Such a lookup's arithmetic around its texel fetches — the receiver's window position, and the
//! receiver's depth slope (two more windows and a 2 × 2 inverse; for the nearest filter only where
//! the decision needs it) — is a chain of products, divisions and square roots per pixel with
//! nothing shared between pixels. Four pixels side by side in `wide::f64x4` lanes run each step as
//! one vector instruction: the divider and the square-root unit take four lanes per instruction,
//! and the four chains' latencies overlap.
//!
//! Each lane performs exactly the operations of the one-pixel functions — `ShadowMapping::window`
//! (`LaneMapping::windows`: glam's `DMat4 · DVec4` sums its columns from `x` to `w`; clip
//! coordinates divided as `lanes::point_of` divides, which gives the one-pixel function's bits;
//! the logarithmic warp's `ln_1p` is the C library's, lane by lane) and
//! `bias::depth_gradient` (glam's `DVec3::any_orthonormal_pair`, `DMat2::inverse`,
//! `DMat2 · DVec2`, term by term) — in the same order, and neither Rust nor `wide` contracts a
//! product and a sum into a fused multiply-add: every lane's decision is the one-pixel lookup's,
//! bit for bit (the tests compare them over random maps and receivers, degenerate lanes among
//! them). Lanes that fail a test (a point behind the map's centre, a plane seen edge-on) compute
//! meaningless numbers before being dropped, as no IEEE operation traps.

use glam::{DVec2, DVec3};
use wide::f64x4;

use super::{Filter, Lookup, disk_mean, pcf_mean};
use crate::bias::{DepthComparison, MAX_SLOPE, SLOPE_STEP, lit_whatever_the_slope};
use crate::lanes::{LANES, Vectors};
use crate::map::ShadowMap;
use crate::setup::LaneMapping;

/// `bias::depth_slope` of four receivers — points `world`, their windows `window`, normals
/// `normal` — through `mapping`, the mapping of `map` (module docs).
#[inline(always)]
fn depth_slopes(
    map: &ShadowMap,
    mapping: LaneMapping<'_>,
    (world, window): (Vectors, Vectors),
    normal: &[DVec3; LANES],
) -> [f64; LANES] {
    // `DVec3::any_orthonormal_pair` (Duff et al., "Building an Orthonormal Basis, Revisited").
    let n = Vectors::of(normal);
    let sign = f64x4::new(normal.map(|n| n.z.signum()));
    let a = -f64x4::ONE / (sign + n.z);
    let b = n.x * n.y * a;
    let t1 = Vectors {
        x: f64x4::ONE + sign * n.x * n.x * a,
        y: sign * b,
        z: -sign * n.x,
    };
    let t2 = Vectors {
        x: b,
        y: sign + n.y * n.y * a,
        z: -n.y,
    };
    let length = world.length().to_array();
    let step = f64x4::new(length.map(|l| SLOPE_STEP * l.max(1.0)));
    let side = f64x4::splat(f64::from(map.resolution));
    let (p1, behind1) = mapping.windows(world.plus(t1.times(step)));
    let (p2, behind2) = mapping.windows(world.plus(t2.times(step)));
    // In texels, less the receiver's own window position in texels.
    let (x0, y0) = (window.x * side, window.y * side);
    let (d1x, d1y, d1z) = (p1.x * side - x0, p1.y * side - y0, p1.z - window.z);
    let (d2x, d2y, d2z) = (p2.x * side - x0, p2.y * side - y0, p2.z - window.z);
    let determinant = d1x * d2y - d1y * d2x;
    let bound = f64x4::splat(f64::EPSILON)
        * (d1x * d1x + d1y * d1y).sqrt()
        * (d2x * d2x + d2y * d2y).sqrt();
    // (∂z/∂x, ∂z/∂y) = J⁻ᵀ·(dz1, dz2), glam's inverse: the adjugate times 1/det.
    let inverse = f64x4::ONE / determinant;
    let gx = (d2y * inverse) * d1z + (d1y * -inverse) * d2z;
    let gy = (d2x * -inverse) * d1z + (d1x * inverse) * d2z;
    let [determinant, bound, gx, gy] = [determinant, bound, gx, gy].map(f64x4::to_array);
    std::array::from_fn(|k| {
        if behind1[k] || behind2[k] || determinant[k].abs() <= bound[k] {
            MAX_SLOPE
        } else {
            gx[k].abs().max(gy[k].abs()).min(MAX_SLOPE)
        }
    })
}

impl Lookup {
    /// Whether [`Self::lit_fractions`] reads a map four points at a time: a nearest, PCF or disk
    /// lookup with a slope-scaled bias that reads the points themselves (no receiver offset), in any
    /// map (`ShadowMapping::in_lanes`).
    pub(crate) fn reads_together(&self) -> bool {
        matches!(
            (self.filter, self.bias.comparison),
            (
                Filter::Nearest | Filter::Pcf { .. } | Filter::Disk { .. },
                DepthComparison::SlopeScaled { .. }
            )
        ) && !self.bias.moves_receiver()
    }

    /// [`Lookup::lit_fraction`] of four points `world` with normals `normal` in `map`, if this
    /// lookup [reads them together](Self::reads_together); `None` otherwise. The windows and the
    /// slopes — PCF's and the disk's for every lane, as `Comparison::new` finds them; the nearest
    /// filter's only where a lane's decision needs one, as `Comparison::lit_only_tap` — are found
    /// four at a time (module docs); each lane's taps are then read as one pixel's.
    pub(crate) fn lit_fractions(
        &self,
        map: &ShadowMap,
        world: &[DVec3; LANES],
        normal: &[DVec3; LANES],
    ) -> Option<[f64; LANES]> {
        if !self.reads_together() {
            return None;
        }
        let DepthComparison::SlopeScaled { constant, slope } = self.bias.comparison else {
            return None;
        };
        if self.filter != Filter::Nearest {
            return Some(self.filtered_fractions(map, world, normal, (constant, slope)));
        }
        let mapping = map.setup.mapping.in_lanes();
        let points = Vectors::of(world);
        let (window, behind) = mapping.windows(points);
        let [x, y, z] = [window.x, window.y, window.z].map(f64x4::to_array);
        let side = f64::from(map.resolution);
        // The nearest tap (`Comparison::lit_only_tap`): each lane's texel and base, then the
        // slopes only if a lane's decision needs one.
        let undecided: [Option<f64>; LANES] = std::array::from_fn(|k| {
            if behind[k] {
                return None;
            }
            let (i, j) = map.texel_at(DVec2::new(x[k] * side, y[k] * side))?;
            let base = map.depth(i, j) + constant;
            (!lit_whatever_the_slope(base, slope, z[k])).then_some(base)
        });
        let mut lit = [1.0; LANES];
        if undecided.iter().any(Option::is_some) {
            let slopes = depth_slopes(map, mapping, (points, window), normal);
            for (k, base) in undecided.into_iter().enumerate() {
                if let Some(base) = base {
                    let lit_through = z[k] <= base + slope * slopes[k];
                    lit[k] = if lit_through { 1.0 } else { 0.0 };
                }
            }
        }
        Some(lit)
    }

    /// [`Self::lit_fractions`] through PCF or the jittered disk, whose taps all compare with the
    /// slope found up front (`Comparison::new`) with the slope-scaled bias
    /// `(constant, slope)`. Out of line: the nearest filter's path, the default lookup, is then
    /// compiled on its own with its slopes inlined (docs/benchmarks.md, "The lookup's slopes
    /// inlined").
    #[inline(never)]
    fn filtered_fractions(
        &self,
        map: &ShadowMap,
        world: &[DVec3; LANES],
        normal: &[DVec3; LANES],
        (constant, slope): (f64, f64),
    ) -> [f64; LANES] {
        let mapping = map.setup.mapping.in_lanes();
        let points = Vectors::of(world);
        let (window, behind) = mapping.windows(points);
        let [x, y, z] = [window.x, window.y, window.z].map(f64x4::to_array);
        let side = f64::from(map.resolution);
        let slopes = depth_slopes(map, mapping, (points, window), normal);
        std::array::from_fn(|k| {
            if behind[k] {
                return 1.0;
            }
            let centre = DVec2::new(x[k] * side, y[k] * side);
            let test = |offset: DVec2| match map.texel_at(centre + offset) {
                Some((i, j)) if z[k] <= map.depth(i, j) + constant + slope * slopes[k] => 1.0,
                Some(_) => 0.0,
                None => 1.0,
            };
            match self.filter {
                Filter::Pcf { size } => pcf_mean(size, test),
                _ => disk_mean(&self.taps, test),
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::{DMat4, DVec3, DVec4};
    use shadowlab_raster::DepthFormat;
    use shadowlab_test_random::SplitMix;
    use wide::f64x4;

    use super::{LANES, Vectors, depth_slopes};
    use crate::bias::{Bias, MAX_SLOPE, depth_slope};
    use crate::logarithmic_map::LogarithmicMap;
    use crate::lookup::{Filter, Lookup};
    use crate::map::ShadowMap;
    use crate::paraboloid_map::ParaboloidMap;
    use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
    use crate::technique::Technique;

    /// The projective mapping through `clip_from_world`.
    fn projective(clip_from_world: DMat4) -> ShadowMapping {
        ShadowMapping::Projective(ProjectiveMapping::new(DMat4::IDENTITY, clip_from_world))
    }

    /// A map through `mapping` holding `depths` (a square of them).
    fn map(mapping: ShadowMapping, depths: &[f64]) -> ShadowMap {
        let setup = LightSetup {
            technique: Technique::Uniform,
            mapping,
            gamma: 0.0,
            half_fov: 0.0,
            warp: None,
            psm: None,
            focus_body: Vec::new(),
        };
        let resolution = depths.len().isqrt();
        let resolution = u32::try_from(resolution).expect("a small map");
        ShadowMap::from_depths(setup, resolution, DepthFormat::F32, depths.to_vec(), None)
            .expect("a map")
    }

    /// Round `round`'s map (near 0.4·I, so that most receivers land on it; every third affine;
    /// every fourth the logarithmic map with that light space, κ from 0 to 100, and every fourth
    /// a paraboloid hemisphere under the receivers) holding one of `depths`, and four receivers:
    /// points on and off the map and behind its centre, normals random, zero, NaN and edge-on.
    fn case(
        random: &mut SplitMix,
        round: usize,
        depths: &[Vec<f64>],
    ) -> (ShadowMap, [DVec3; LANES], [DVec3; LANES]) {
        let perturbed = |random: &mut SplitMix, k: usize| {
            let mut c = DVec4::new(
                random.range(-0.1, 0.1),
                random.range(-0.1, 0.1),
                random.range(-0.1, 0.1),
                random.range(-0.1, 0.1),
            );
            c[k] += if k == 3 { 1.0 } else { 0.4 };
            c
        };
        let mut m = DMat4::from_cols(
            perturbed(random, 0),
            perturbed(random, 1),
            perturbed(random, 2),
            perturbed(random, 3),
        );
        if round.is_multiple_of(3) {
            (m.x_axis.w, m.y_axis.w, m.z_axis.w, m.w_axis.w) = (0.0, 0.0, 0.0, 1.0);
        }
        let mut world = [DVec3::ZERO; LANES];
        let mut normal = [DVec3::ZERO; LANES];
        for k in 0..LANES {
            world[k] = random.vector(1.2);
            normal[k] = random.vector(1.0).normalize_or(DVec3::Y);
            match (round + k) % 9 {
                0 => normal[k] = DVec3::ZERO,
                1 => normal[k].x = f64::NAN,
                2 => normal[k] = DVec3::Z,
                3 => normal[k] = DVec3::new(0.0, 0.0, -1.0),
                4 => world[k] *= 40.0,
                _ => {}
            }
        }
        let mapping = if round % 4 == 1 {
            let kappa = [0.0, 0.3, 5.0, 100.0][round / 4 % 4];
            ShadowMapping::Logarithmic(LogarithmicMap {
                world_to_light: m,
                light_to_world: m.inverse(),
                z_max: 0.6,
                depth: random.range(1.0, 1.4),
                kappa,
                log_range: f64::ln_1p(kappa),
                left: random.range(-0.7, -0.5),
                right: random.range(0.5, 0.7),
                y_min: random.range(-0.7, -0.5),
                y_max: random.range(0.5, 0.7),
            })
        } else if round % 4 == 3 {
            let light = DVec3::new(0.0, -2.0, 0.0) + random.vector(0.3);
            let axis = (DVec3::Y + random.vector(0.2)).normalize();
            ShadowMapping::Paraboloid(ParaboloidMap::new(
                light,
                axis,
                random.range(0.1, 0.5),
                random.range(4.0, 6.0),
            ))
        } else {
            projective(m)
        };
        (map(mapping, &depths[round % depths.len()]), world, normal)
    }

    /// Random depths for maps of 16², 100² and 300² texels.
    fn depths(random: &mut SplitMix) -> Vec<Vec<f64>> {
        [16, 100, 300]
            .map(|side: usize| (0..side * side).map(|_| random.range(0.0, 1.0)).collect())
            .into()
    }

    /// The windows and slopes of four receivers found together are each receiver's own, to the
    /// bit (`ShadowMapping::window`, `bias::depth_slope`), on the cases of [`case`].
    #[test]
    fn four_windows_and_slopes_are_each_receivers_own() {
        let mut random = SplitMix(0x5eed_0000_0000_100d);
        let depths = depths(&mut random);
        let mut sloped = 0;
        for round in 0..3000 {
            let (map, world, normal) = case(&mut random, round, &depths);
            let mapping = map.setup.mapping.in_lanes();
            let (window, behind) = mapping.windows(Vectors::of(&world));
            let slopes = depth_slopes(&map, mapping, (Vectors::of(&world), window), &normal);
            let [x, y, z] = [window.x, window.y, window.z].map(f64x4::to_array);
            for k in 0..LANES {
                let one = map.setup.mapping.window(world[k]);
                let block = (!behind[k]).then(|| DVec3::new(x[k], y[k], z[k]));
                assert_eq!(
                    block.map(|w| w.to_array().map(f64::to_bits)),
                    one.map(|w| w.to_array().map(f64::to_bits)),
                    "round {round}, lane {k}"
                );
                let Some(one) = one else { continue };
                let slope = depth_slope(&map, (world[k], one), normal[k]);
                assert_eq!(
                    slopes[k].to_bits(),
                    slope.to_bits(),
                    "round {round}, lane {k}"
                );
                sloped += usize::from(slope > 0.0 && slope < MAX_SLOPE);
            }
        }
        assert!(sloped > 3000, "{sloped}");
    }

    /// Puts the depth each receiver's texel holds within an ulp or two of the first bias's
    /// (`slope:2,1e-5`) limit, `z − (1e-5 + 2·slope)`, so that rounding decides the comparison.
    fn on_the_limit(
        map: &mut ShadowMap,
        world: &[DVec3; LANES],
        normal: &[DVec3; LANES],
        random: &mut SplitMix,
    ) {
        let side = f64::from(map.resolution);
        for k in 0..LANES {
            let Some(w) = map.setup.mapping.window(world[k]) else {
                continue;
            };
            let Some((i, j)) = map.texel_at(glam::DVec2::new(w.x * side, w.y * side)) else {
                continue;
            };
            let limit = w.z - (1e-5 + 2.0 * depth_slope(map, (world[k], w), normal[k]));
            let nudge = (random.unit() * 5.0).floor() - 2.0;
            #[expect(clippy::cast_possible_truncation, reason = "-2 to 2")]
            let bits = limit.to_bits().wrapping_add_signed(nudge as i64);
            map.nearest[j as usize * map.resolution as usize + i as usize] = f64::from_bits(bits);
        }
    }

    /// Four pixels looked up together give each pixel's own lookup, to the bit, on the cases of
    /// [`case`], nearest, PCF and disk under slope-scaled biases; other comparisons, and a bias
    /// that moves the receiver, are not read together. The slope decides some of the lookups.
    #[test]
    fn four_pixels_together_are_each_pixel_alone() {
        let mut random = SplitMix(0x5eed_0000_0000_100c);
        let biases = [
            "slope:2,1e-5",
            "slope:0.5,0.02",
            "slope:400,0",
            "constant:1e-3",
            "receiver-plane",
            "none",
        ]
        .map(|spec| Bias::parse(spec).expect("a bias"));
        let filters = [
            Filter::Nearest,
            Filter::Pcf { size: 3 },
            Filter::Pcf { size: 2 },
        ];
        let depths = depths(&mut random);
        let (mut decided_by_slope, mut shadowed, mut lit) = (0, 0, 0);
        for round in 0..600 {
            let (mut map, world, normal) = case(&mut random, round, &depths);
            if round % 2 == 1 {
                on_the_limit(&mut map, &world, &normal, &mut random);
            }
            for bias in &biases {
                for filter in filters {
                    let lookup = Lookup::new(*bias, filter);
                    let Some(block) = lookup.lit_fractions(&map, &world, &normal) else {
                        assert!(!lookup.reads_together(), "{bias}, {filter:?}");
                        continue;
                    };
                    assert!(lookup.reads_together());
                    for k in 0..LANES {
                        let one = lookup.lit_fraction(&map, world[k], normal[k]);
                        assert_eq!(
                            block[k].to_bits(),
                            one.to_bits(),
                            "round {round}, {bias}, {filter:?}, lane {k}"
                        );
                    }
                    if filter == Filter::Nearest && bias == &biases[0] {
                        let flat =
                            Lookup::new(Bias::parse("slope:0,1e-5").expect("a bias"), filter);
                        for k in 0..LANES {
                            let one = lookup.lit_fraction(&map, world[k], normal[k]);
                            decided_by_slope +=
                                usize::from(one != flat.lit_fraction(&map, world[k], normal[k]));
                            shadowed += usize::from(one == 0.0);
                            lit += usize::from(one == 1.0);
                        }
                    }
                }
            }
        }
        assert!(
            decided_by_slope > 20 && shadowed > 300 && lit > 300,
            "{decided_by_slope} {shadowed} {lit}"
        );
        let moved = Lookup::new(
            Bias::parse("slope:2,1e-5+normal:1").expect("a bias"),
            Filter::Nearest,
        );
        let map = map(projective(DMat4::IDENTITY), &depths[0]);
        assert!(
            moved
                .lit_fractions(&map, &[DVec3::ZERO; LANES], &[DVec3::Y; LANES])
                .is_none()
        );
    }
}
