//! Looking a point up in a shadow map: the filters (nearest, PCF, a jittered disk, VSM), each
//! reading the map with a bias ([`crate::bias`]).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};
use shadowlab_params::vsm::ShiftedMoments;

use crate::bias::{Bias, Comparison, spec_numbers};
use crate::map::ShadowMap;

/// How many texels a lookup reads, and how it combines them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    /// The one texel the point falls in.
    Nearest,
    /// Percentage-closer filtering over the `size × size` texels centred on the point (Reeves et
    /// al. 1987), each tested with the bias: the lit fraction.
    Pcf {
        /// Side of the kernel, in texels (≥ 1).
        size: u32,
    },
    /// PCF over `taps` points of a jittered disk of `radius` texels: tap `k` at radius
    /// `radius·√((k + u)/taps)` and angle `2π(k·φ_g + v)` (φ_g the golden ratio's fraction), with
    /// `u, v ∈ [0, 1)` drawn from SplitMix64 seeded by `seed` — the same taps for every lookup, so
    /// the result is deterministic.
    Disk {
        /// Number of taps (≥ 1).
        taps: u32,
        /// Disk radius in texels.
        radius: f64,
        /// The taps' seed.
        seed: u64,
    },
    /// Variance shadow maps (CAD eq. 2 on shifted moments, formulas.md §4.2, §9.4): the first two
    /// moments of the `size × size` texels' depths about the centre texel's depth, and the
    /// Chebyshev bound, with the variance raised to at least `min_variance`. The bias's depth
    /// comparison is not applied (the variance is VSM's bias); its receiver offsets are.
    Vsm {
        /// Side of the moment kernel, in texels (≥ 1).
        size: u32,
        /// The variance floor.
        min_variance: f64,
    },
}

/// 2⁶⁴/φ, SplitMix64's increment.
const SPLITMIX_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;
/// The fraction of the golden ratio, for the disk's angles.
const GOLDEN_FRACTION: f64 = 0.618_033_988_749_894_9;

/// A bias and a filter: one way of reading shadow maps.
#[derive(Clone, Debug, PartialEq)]
pub struct Lookup {
    /// The bias.
    pub bias: Bias,
    /// The filter.
    pub filter: Filter,
    /// The disk's taps in texels, precomputed from the seed.
    taps: Vec<DVec2>,
}

impl Lookup {
    /// A lookup with this bias and filter.
    #[must_use]
    pub fn new(bias: Bias, filter: Filter) -> Self {
        let taps = match filter {
            Filter::Disk { taps, radius, seed } => disk_taps(taps, radius, seed),
            _ => Vec::new(),
        };
        Self { bias, filter, taps }
    }

    /// How lit the surface point `world` with unit normal `normal` is by `map`'s light: 1 lit, 0 in
    /// shadow, fractions from filters. Points the map does not cover are lit. The bias's receiver
    /// offsets move the point first ([`Bias::receiver`]); the filters then read the moved point.
    #[must_use]
    pub fn lit_fraction(&self, map: &ShadowMap, world: DVec3, normal: DVec3) -> f64 {
        let world = self.bias.receiver(map, world, normal);
        let Some(window) = map.setup.mapping.window(world) else {
            return 1.0;
        };
        let side = f64::from(map.resolution);
        let centre = DVec2::new(window.x * side, window.y * side);
        let receiver = window.z;
        if let Filter::Vsm { size, min_variance } = self.filter {
            return vsm(map, centre, receiver, size, min_variance);
        }
        let comparison = Comparison::new(self.bias.comparison, map, (world, window), normal);
        let test = |offset: DVec2, nearest: bool| {
            let Some(texel) = texel(map, centre + offset) else {
                return 1.0;
            };
            // The nearest filter's tap is the centre of the texel it reads.
            let offset = if nearest && comparison.reads_offsets() {
                DVec2::new(f64::from(texel.0) + 0.5, f64::from(texel.1) + 0.5) - centre
            } else {
                offset
            };
            if comparison.lit(map, texel, receiver, offset) {
                1.0
            } else {
                0.0
            }
        };
        match self.filter {
            Filter::Nearest => test(DVec2::ZERO, true),
            Filter::Pcf { size } => {
                let half = 0.5 * f64::from(size.saturating_sub(1));
                let mut lit = 0.0;
                for b in 0..size {
                    for a in 0..size {
                        let offset = DVec2::new(f64::from(a) - half, f64::from(b) - half);
                        lit += test(offset, false);
                    }
                }
                lit / f64::from(size * size)
            }
            Filter::Disk { .. } => {
                let lit: f64 = self.taps.iter().map(|tap| test(*tap, false)).sum();
                lit / self.taps.len() as f64
            }
            Filter::Vsm { size, min_variance } => vsm(map, centre, receiver, size, min_variance),
        }
    }
}

/// The texel holding texel-space position `at` (`None` off the map).
fn texel(map: &ShadowMap, at: DVec2) -> Option<(u32, u32)> {
    let side = f64::from(map.resolution);
    map.texel_of(DVec3::new(at.x / side, at.y / side, 0.0))
}

/// VSM's lit fraction from the moments of the `size × size` texels around `centre`.
fn vsm(map: &ShadowMap, centre: DVec2, receiver: f64, size: u32, min_variance: f64) -> f64 {
    let Some((ci, cj)) = texel(map, centre) else {
        return 1.0;
    };
    let half = i64::from(size.saturating_sub(1) / 2);
    let side = i64::from(map.resolution);
    let mut depths = Vec::with_capacity((size * size) as usize);
    for dj in -half..=half {
        for di in -half..=half {
            let (i, j) = (i64::from(ci) + di, i64::from(cj) + dj);
            if (0..side).contains(&i) && (0..side).contains(&j) {
                #[expect(
                    clippy::cast_possible_truncation,
                    clippy::cast_sign_loss,
                    reason = "inside the map"
                )]
                depths.push(map.depth(i as u32, j as u32));
            }
        }
    }
    let reference = map.depth(ci, cj);
    ShiftedMoments::from_depths(reference, &depths)
        .and_then(|m| m.lit_fraction(receiver, min_variance))
        .unwrap_or(1.0)
}

/// The disk's taps (see [`Filter::Disk`]).
fn disk_taps(taps: u32, radius: f64, seed: u64) -> Vec<DVec2> {
    let mut state = seed;
    let mut unit = || {
        // SplitMix64 (Steele, Lea & Flood 2014), top 53 bits as a fraction.
        state = state.wrapping_add(SPLITMIX_GAMMA);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        #[expect(clippy::cast_precision_loss, reason = "53 bits, exact in f64")]
        let fraction = (z >> 11) as f64 / (1u64 << 53) as f64;
        fraction
    };
    (0..taps)
        .map(|k| {
            let (u, v) = (unit(), unit());
            let r = radius * ((f64::from(k) + u) / f64::from(taps)).sqrt();
            let angle = TAU * (f64::from(k) * GOLDEN_FRACTION + v);
            DVec2::new(r * angle.cos(), r * angle.sin())
        })
        .collect()
}

impl Filter {
    /// Parses `nearest`, `pcf:K`, `disk:TAPS,RADIUS[,SEED]`, `vsm:K[,MIN_VARIANCE]`.
    ///
    /// # Errors
    /// A message naming what is wrong and the accepted forms.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (name, n) = spec_numbers(spec, 3)?;
        let count = |v: f64, what: &str| {
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "checked to be a whole number in 1..=64"
            )]
            let whole = (v.fract() == 0.0 && (1.0..=64.0).contains(&v)).then_some(v as u32);
            whole.ok_or_else(|| format!("{what} in {spec:?} must be a whole number from 1 to 64"))
        };
        match (name, n.as_slice()) {
            ("nearest", []) => Ok(Self::Nearest),
            ("pcf", [k]) => Ok(Self::Pcf {
                size: count(*k, "the kernel size")?,
            }),
            ("disk", [taps, radius]) | ("disk", [taps, radius, _]) => {
                let seed = match n.get(2) {
                    #[expect(
                        clippy::cast_possible_truncation,
                        clippy::cast_sign_loss,
                        reason = "checked to be a whole non-negative number below 2^53"
                    )]
                    Some(s) if s.fract() == 0.0 && *s >= 0.0 && *s < 9_007_199_254_740_992.0 => {
                        *s as u64
                    }
                    Some(_) => {
                        return Err(format!(
                            "the seed in {spec:?} must be a whole number from 0 to 2^53"
                        ));
                    }
                    None => DEFAULT_DISK_SEED,
                };
                if *radius <= 0.0 {
                    return Err(format!("the radius in {spec:?} must be greater than 0"));
                }
                Ok(Self::Disk {
                    taps: count(*taps, "the number of taps")?,
                    radius: *radius,
                    seed,
                })
            }
            ("vsm", [k]) => Ok(Self::Vsm {
                size: count(*k, "the kernel size")?,
                min_variance: DEFAULT_MIN_VARIANCE,
            }),
            ("vsm", [k, floor]) if *floor >= 0.0 => Ok(Self::Vsm {
                size: count(*k, "the kernel size")?,
                min_variance: *floor,
            }),
            _ => Err(format!(
                "unknown filter {spec:?}; known: nearest, pcf:K, disk:TAPS,RADIUS[,SEED], vsm:K[,MIN_VARIANCE]"
            )),
        }
    }
}

/// The jittered disk's seed when none is given (documented in the README and `--help`).
pub const DEFAULT_DISK_SEED: u64 = 0x5348_4144_4f57;
/// VSM's variance floor when none is given: (1e-3 of the depth range)².
pub const DEFAULT_MIN_VARIANCE: f64 = 1e-6;
