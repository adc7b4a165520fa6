//! Looking a point up in a shadow map: the filters (nearest, PCF, a jittered disk, and the
//! filterable maps VSM, ESM, EVSM and MSM), each reading the map with a bias ([`crate::bias`]).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};
use shadowlab_params::ParamError;
use shadowlab_params::esm::ExponentialMoment;
use shadowlab_params::evsm::{Evsm2Moments, Evsm4Moments};
use shadowlab_params::filterable::FilterableMethod;
use shadowlab_params::msm::MsmMoments;
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
    /// A filterable map beyond VSM: the moments its method stores, of the `size × size` texels'
    /// depths (a box prefilter: every texel on the map weighted alike, as [`Filter::Vsm`] takes
    /// them), about the centre texel's depth where the method takes a reference, and the method's
    /// lit fraction at the receiver's depth. The bias's depth comparison is not applied (each
    /// method's parameter is its bias); its receiver offsets are. The moments are formed in f64
    /// from the stored depths: what a map that stores them at full precision and box-filters them
    /// reads.
    Moments {
        /// Side of the kernel, in texels (≥ 1).
        size: u32,
        /// The method and its parameters.
        method: MomentMethod,
    },
}

/// A filterable map's reconstruction with its parameters (`shadowlab_params::filterable`, where
/// each is derived and cited).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MomentMethod {
    /// Exponential shadow maps, Annen, Mertens, Seidel, Flerackers & Kautz, GI 2008
    /// (`shadowlab_params::esm`): `exp(−c·(t − d̄))` capped at 1, `d̄` the exponential mean depth.
    Esm {
        /// The exponent `c` (> 0).
        exponent: f64,
    },
    /// Exponential variance shadow maps with the positive warp `exp(c·d)`, Lauritzen & McCool,
    /// GI 2008 (`shadowlab_params::evsm::Evsm2Moments`): the Cantelli bound on the warped depths.
    Evsm2 {
        /// The exponent `c` (in `(0, 354]`).
        exponent: f64,
        /// The variance floor, in depth² (carried into the warp by its slope at the receiver).
        min_variance: f64,
    },
    /// EVSM with both warps, `exp(c₊·d)` and `−exp(−c₋·d)`: the smaller of their two bounds
    /// (`shadowlab_params::evsm::Evsm4Moments`).
    Evsm4 {
        /// The positive warp's exponent `c₊` (in `(0, 354]`).
        positive: f64,
        /// The negative warp's exponent `c₋` (in `(0, 354]`).
        negative: f64,
        /// The variance floor, in depth².
        min_variance: f64,
    },
    /// Moment shadow maps, Peters & Klein, I3D 2015, the Hamburger 4MSM reconstruction of four
    /// moments biased by `α` toward `(½, ½, ½, ½)` (`shadowlab_params::msm`).
    Msm {
        /// The bias `α` (in `[0, 1]`).
        alpha: f64,
    },
}

impl MomentMethod {
    /// Which method it is.
    #[must_use]
    pub const fn method(self) -> FilterableMethod {
        match self {
            Self::Esm { .. } => FilterableMethod::Esm,
            Self::Evsm2 { .. } => FilterableMethod::Evsm2,
            Self::Evsm4 { .. } => FilterableMethod::Evsm4,
            Self::Msm { .. } => FilterableMethod::Msm,
        }
    }

    /// The lit fraction of a receiver at window depth `receiver` behind texels of window depths
    /// `depths` (in `[0, 1]`, at least one), their moments taken about `reference` where the
    /// method takes one.
    ///
    /// # Errors
    /// The method's, naming the parameter out of its domain.
    pub fn lit_fraction(
        self,
        reference: f64,
        depths: &[f64],
        receiver: f64,
    ) -> Result<f64, ParamError> {
        match self {
            Self::Esm { exponent } => {
                ExponentialMoment::from_depths(exponent, depths)?.lit_fraction(receiver)
            }
            Self::Evsm2 {
                exponent,
                min_variance,
            } => Evsm2Moments::from_depths(exponent, reference, depths)?
                .lit_fraction(receiver, min_variance),
            Self::Evsm4 {
                positive,
                negative,
                min_variance,
            } => Evsm4Moments::from_depths(positive, negative, reference, depths)?
                .lit_fraction(receiver, min_variance),
            Self::Msm { alpha } => {
                MsmMoments::from_depths(reference, depths)?.lit_fraction(receiver, alpha)
            }
        }
    }
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
        match self.filter {
            Filter::Vsm { size, min_variance } => {
                return filtered(map, centre, size, |reference, depths| {
                    ShiftedMoments::from_depths(reference, depths)
                        .and_then(|m| m.lit_fraction(receiver, min_variance))
                });
            }
            Filter::Moments { size, method } => {
                return filtered(map, centre, size, |reference, depths| {
                    method.lit_fraction(reference, depths, receiver)
                });
            }
            Filter::Nearest | Filter::Pcf { .. } | Filter::Disk { .. } => {}
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
            Filter::Vsm { .. } | Filter::Moments { .. } => unreachable!("read above"),
        }
    }
}

/// The texel holding texel-space position `at` (`None` off the map).
fn texel(map: &ShadowMap, at: DVec2) -> Option<(u32, u32)> {
    let side = f64::from(map.resolution);
    map.texel_of(DVec3::new(at.x / side, at.y / side, 0.0))
}

/// A filterable map's lit fraction: `lit(reference, depths)` of the depths of the `size × size`
/// texels around `centre` that lie on the map — the texels holding `centre + (a − h, b − h)` for
/// `a, b < size`, `h = (size − 1)/2`, as PCF reads them: for an odd size the texels centred on the
/// point's own, for an even size the box whose middle is nearest the point — `reference` the depth of
/// the texel holding `centre`; 1 where that is off the map. The depths are a map's stored window
/// depths, in `[0, 1]`, and the methods' parameters are checked when the filter is parsed
/// ([`Filter::parse`]), so `lit` fails only on input no map holds; such a point reads as lit, as off
/// the map.
fn filtered(
    map: &ShadowMap,
    centre: DVec2,
    size: u32,
    lit: impl FnOnce(f64, &[f64]) -> Result<f64, ParamError>,
) -> f64 {
    let Some((ci, cj)) = texel(map, centre) else {
        return 1.0;
    };
    let half = 0.5 * f64::from(size.saturating_sub(1));
    let mut depths = Vec::with_capacity((size * size) as usize);
    for b in 0..size {
        for a in 0..size {
            let offset = DVec2::new(f64::from(a) - half, f64::from(b) - half);
            if let Some((i, j)) = texel(map, centre + offset) {
                depths.push(map.depth(i, j));
            }
        }
    }
    lit(map.depth(ci, cj), &depths).unwrap_or(1.0)
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
    /// Parses `nearest`, `pcf:K`, `disk:TAPS,RADIUS[,SEED]`, `vsm:K[,MIN_VARIANCE]`, `esm:K,C`,
    /// `evsm2:K,C[,MIN_VARIANCE]`, `evsm4:K,C+,C-[,MIN_VARIANCE]` and `msm:K,ALPHA` (`K` the
    /// prefilter's side in texels; the filterable maps' parameters as [`MomentMethod`] names them,
    /// checked here against their domains).
    ///
    /// # Errors
    /// A message naming what is wrong and the accepted forms.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (name, n) = spec_numbers(spec, 4)?;
        let count = |v: f64, what: &str| {
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "checked to be a whole number in 1..=64"
            )]
            let whole = (v.fract() == 0.0 && (1.0..=64.0).contains(&v)).then_some(v as u32);
            whole.ok_or_else(|| format!("{what} in {spec:?} must be a whole number from 1 to 64"))
        };
        // A filterable map, its parameters tried on one texel so that their domains are checked
        // here, where the spec can be named, and not at every lookup.
        let moments = |k: f64, method: MomentMethod| {
            let size = count(k, "the kernel size")?;
            method
                .lit_fraction(0.5, &[0.5], 0.5)
                .map_err(|e| format!("{spec:?}: {e}"))?;
            Ok(Self::Moments { size, method })
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
            ("esm", [k, c]) => moments(*k, MomentMethod::Esm { exponent: *c }),
            ("evsm2", [k, c]) | ("evsm2", [k, c, _]) => moments(
                *k,
                MomentMethod::Evsm2 {
                    exponent: *c,
                    min_variance: n.get(2).copied().unwrap_or(DEFAULT_MIN_VARIANCE),
                },
            ),
            ("evsm4", [k, positive, negative]) | ("evsm4", [k, positive, negative, _]) => moments(
                *k,
                MomentMethod::Evsm4 {
                    positive: *positive,
                    negative: *negative,
                    min_variance: n.get(3).copied().unwrap_or(DEFAULT_MIN_VARIANCE),
                },
            ),
            ("msm", [k, alpha]) => moments(*k, MomentMethod::Msm { alpha: *alpha }),
            _ => Err(format!(
                "unknown filter {spec:?}; known: nearest, pcf:K, disk:TAPS,RADIUS[,SEED], \
                 vsm:K[,MIN_VARIANCE], esm:K,C, evsm2:K,C[,MIN_VARIANCE], \
                 evsm4:K,C+,C-[,MIN_VARIANCE], msm:K,ALPHA"
            )),
        }
    }
}

/// The jittered disk's seed when none is given (documented in the README and `--help`).
pub const DEFAULT_DISK_SEED: u64 = 0x5348_4144_4f57;
/// VSM's variance floor when none is given: (1e-3 of the depth range)².
pub const DEFAULT_MIN_VARIANCE: f64 = 1e-6;
