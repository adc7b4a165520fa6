//! Looking a point up in a shadow map: the filters (nearest, PCF, a jittered disk, and the
//! filterable maps VSM, ESM, EVSM and MSM), each reading the map with a bias ([`crate::bias`]).
//!
//! A filterable map takes two knobs, its [`Prefilter`]: the kernel its moments are filtered with
//! ([`Kernel`]: box or Gaussian) and where they are held ([`Storage`]: exactly, or in a 32- or
//! 16-bit float texture as an engine stores them).

use std::f64::consts::TAU;
use std::fmt;

use glam::{DVec2, DVec3};
use shadowlab_params::ParamError;
use shadowlab_params::esm::ExponentialMoment;
use shadowlab_params::evsm::{Evsm2Moments, Evsm4Moments, Warp, WarpedMoments};
use shadowlab_params::filterable::FilterableMethod;
use shadowlab_params::msm::MsmMoments;
use shadowlab_params::storage::MomentFormat;
use shadowlab_params::vsm::ShiftedMoments;

use crate::bias::{Bias, Comparison, spec_numbers};
use crate::map::ShadowMap;

mod block;

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
    /// moments of the `size × size` texels' depths, filtered and held as `prefilter` says (by
    /// default box-filtered and exact, about the centre texel's depth), and the Chebyshev bound,
    /// with the variance raised to at least `min_variance`. The bias's depth comparison is not
    /// applied (the variance is VSM's bias); its receiver offsets are.
    Vsm {
        /// Side of the moment kernel, in texels (≥ 1).
        size: u32,
        /// The variance floor.
        min_variance: f64,
        /// The kernel's weights and the moments' storage.
        prefilter: Prefilter,
    },
    /// A filterable map beyond VSM: the moments its method stores, of the `size × size` texels'
    /// depths, filtered and held as `prefilter` says — by default a box (every texel on the map
    /// weighted alike, as [`Filter::Vsm`] takes them) and exact (formed in f64 from the stored
    /// depths, about the centre texel's depth where the method takes a reference) — and the
    /// method's lit fraction at the receiver's depth. The bias's depth comparison is not applied
    /// (each method's parameter is its bias); its receiver offsets are.
    Moments {
        /// Side of the kernel, in texels (≥ 1).
        size: u32,
        /// The method and its parameters.
        method: MomentMethod,
        /// The kernel's weights and the moments' storage.
        prefilter: Prefilter,
    },
}

/// The weights a filterable map's kernel gives the `K × K` texels it reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// Every texel alike (the default).
    #[default]
    Box,
    /// Separable Gaussian weights `w(x)·w(y)`, `w(x) = exp(−x²/(2σ²))` at each tap's offset `x` in
    /// texels from the kernel's middle, with `σ = (K + 1)/6` ([`GAUSSIAN_SIDE_PER_SIGMA`]):
    /// Filament's VSM blur (google/filament, `filament/src/ShadowMapManager.cpp`:
    /// `sigma = (blurWidth + 1.0f) / 6.0f` for a blur `blurWidth` texels wide;
    /// `PostProcessManager::gaussianBlurPass`: the weights `exp(−x²/(2σ²))` divided by their sum,
    /// a horizontal pass, then a vertical one). Filament rounds its tap count up to `4n + 5` (pairs
    /// of taps read bilinearly); shadowlab keeps the `K` taps per axis the box reads, so that the
    /// two kernels read the same texels, and normalises the weights over the taps that lie on the
    /// map.
    Gaussian,
}

/// `K + 1` texels span this many σ of the Gaussian kernel ([`Kernel::Gaussian`]: `σ = (K + 1)/6`,
/// Filament's rule).
pub const GAUSSIAN_SIDE_PER_SIGMA: f64 = 6.0;

impl Kernel {
    /// Every kernel, the default first.
    pub const ALL: [Self; 2] = [Self::Box, Self::Gaussian];

    /// The kernel's name in a filter spec: `box`, `gauss`.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Self::Box => "box",
            Self::Gaussian => "gauss",
        }
    }

    /// The weights of the `size` taps along one axis, in order, summing to 1: `1/K` each for the
    /// box; `w(x) = exp(−x²/(2σ²))` at the offsets `x = a − (K − 1)/2`, divided by their sum, for
    /// the Gaussian (symmetric about the middle; `[1]` for `K = 1`, as the box).
    #[must_use]
    pub fn weights(self, size: u32) -> Vec<f64> {
        let half = 0.5 * f64::from(size.saturating_sub(1));
        let raw: Vec<f64> = match self {
            Self::Box => vec![1.0; size as usize],
            Self::Gaussian => {
                let sigma = (f64::from(size) + 1.0) / GAUSSIAN_SIDE_PER_SIGMA;
                (0..size)
                    .map(|a| {
                        let x = f64::from(a) - half;
                        (-x * x / (2.0 * sigma * sigma)).exp()
                    })
                    .collect()
            }
        };
        let total: f64 = raw.iter().sum();
        raw.into_iter().map(|w| w / total).collect()
    }
}

/// Where a filterable map's moments are held between its shadow pass, its blur and its lookup.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Storage {
    /// Not stored: the moments formed in f64 from the stored depths at each lookup, about the centre
    /// texel's depth where the method takes a reference (each method's shifted form) — the default,
    /// what a map that keeps its moments exactly reads. Its memory is reported as 32-bit moments.
    #[default]
    Exact,
    /// In a texture of this format, as an engine stores them (`shadowlab_params::storage`): each
    /// texel's raw moments rounded to the format, the kernel applied as two separable blur passes
    /// (rows, then columns) each accumulated in f32 and rounded to the format as it is written,
    /// and the method's reconstruction from the blurred raw moments. A warp whose moment overflowed
    /// the format reads lit (*overflow reads lit*).
    Texture(MomentFormat),
}

impl Storage {
    /// Every storage, the default first.
    pub const ALL: [Self; 3] = [
        Self::Exact,
        Self::Texture(MomentFormat::F32),
        Self::Texture(MomentFormat::F16),
    ];

    /// The storage's name in a filter spec: `exact`, `f32`, `f16`.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::Texture(format) => format.key(),
        }
    }

    /// Bytes per stored moment: the format's (4 for f32, 2 for f16), and 4 for [`Self::Exact`],
    /// reported as 32-bit moments.
    #[must_use]
    pub const fn bytes_per_moment(self) -> u32 {
        match self {
            Self::Exact => 4,
            Self::Texture(format) => format.bytes(),
        }
    }
}

/// A filterable map's prefilter knobs: the kernel's weights and the moments' storage. Written after
/// the filter's numbers, each after an `@`, in any order (`vsm:5@gauss@f16`); the defaults, a box
/// and exact moments, may be omitted and are not printed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Prefilter {
    /// The kernel's weights.
    pub kernel: Kernel,
    /// Where the moments are held.
    pub storage: Storage,
}

impl Prefilter {
    /// The knobs after a filterable map's numbers: `@`-separated keys of a [`Kernel`] and a
    /// [`Storage`], each at most once (`knobs` without its first `@`). Errors name `spec`.
    fn parse(knobs: &str, spec: &str) -> Result<Self, String> {
        let mut kernel = None;
        let mut storage = None;
        for knob in knobs.split('@') {
            if let Some(k) = Kernel::ALL.into_iter().find(|k| k.key() == knob) {
                if kernel.replace(k).is_some() {
                    return Err(format!("{spec:?} names two kernels"));
                }
            } else if let Some(s) = Storage::ALL.into_iter().find(|s| s.key() == knob) {
                if storage.replace(s).is_some() {
                    return Err(format!("{spec:?} names two storages"));
                }
            } else {
                return Err(format!(
                    "unknown knob {knob:?} in {spec:?}; known: @box, @gauss (the kernel), \
                     @exact, @f32, @f16 (the storage)"
                ));
            }
        }
        Ok(Self {
            kernel: kernel.unwrap_or_default(),
            storage: storage.unwrap_or_default(),
        })
    }
}

impl fmt::Display for Prefilter {
    /// The knobs as a spec writes them, the defaults left out: `@gauss@f16`, `@f32`, or nothing.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.kernel != Kernel::default() {
            write!(f, "@{}", self.kernel.key())?;
        }
        if self.storage != Storage::default() {
            write!(f, "@{}", self.storage.key())?;
        }
        Ok(())
    }
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

    /// As [`Self::lit_fraction`], with one weight per depth (the kernel's, as the methods'
    /// `from_weighted_depths` take them).
    ///
    /// # Errors
    /// The method's, naming the parameter out of its domain.
    pub fn weighted_lit_fraction(
        self,
        reference: f64,
        (depths, weights): (&[f64], &[f64]),
        receiver: f64,
    ) -> Result<f64, ParamError> {
        match self {
            Self::Esm { exponent } => {
                ExponentialMoment::from_weighted_depths(exponent, depths, weights)?
                    .lit_fraction(receiver)
            }
            Self::Evsm2 {
                exponent,
                min_variance,
            } => Evsm2Moments::from_weighted_depths(exponent, reference, depths, weights)?
                .lit_fraction(receiver, min_variance),
            Self::Evsm4 {
                positive,
                negative,
                min_variance,
            } => {
                Evsm4Moments::from_weighted_depths(positive, negative, reference, depths, weights)?
                    .lit_fraction(receiver, min_variance)
            }
            Self::Msm { alpha } => MsmMoments::from_weighted_depths(reference, depths, weights)?
                .lit_fraction(receiver, alpha),
        }
    }

    /// The lit fraction from the moments a texture of `format` holds after blurring the
    /// footprint's texels with the per-axis weights `axis` ([`Storage::Texture`]). A warp whose
    /// stored moments overflowed reads lit: ESM is then 1, EVSM4 its other warp's bound.
    fn stored_lit_fraction(
        self,
        footprint: &Footprint,
        (format, axis): (MomentFormat, &[f64]),
        receiver: f64,
    ) -> Result<f64, ParamError> {
        let warp = |warp: Warp, exponent: f64, min_variance: f64| {
            let raw = footprint.stored(format, axis, |d| {
                WarpedMoments::texel_moments(warp, exponent, d)
            })?;
            WarpedMoments::from_raw_moments(warp, exponent, raw)?
                .map_or(Ok(1.0), |m| m.lit_fraction(receiver, min_variance))
        };
        match self {
            Self::Esm { exponent } => {
                let raw = footprint.stored(format, axis, |d| {
                    ExponentialMoment::texel_moments(exponent, d)
                })?;
                ExponentialMoment::from_raw_moments(exponent, raw)?
                    .map_or(Ok(1.0), |m| m.lit_fraction(receiver))
            }
            Self::Evsm2 {
                exponent,
                min_variance,
            } => warp(Warp::Positive, exponent, min_variance),
            Self::Evsm4 {
                positive,
                negative,
                min_variance,
            } => Ok(warp(Warp::Positive, positive, min_variance)?.min(warp(
                Warp::Negative,
                negative,
                min_variance,
            )?)),
            Self::Msm { alpha } => {
                let raw = footprint.stored(format, axis, MsmMoments::texel_moments)?;
                MsmMoments::from_raw_moments(raw)?.lit_fraction(receiver, alpha)
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
            Filter::Vsm {
                size,
                min_variance,
                prefilter,
            } => {
                return filtered(map, centre, size, |footprint| {
                    let moments = match (prefilter.storage, prefilter.kernel) {
                        (Storage::Exact, Kernel::Box) => {
                            ShiftedMoments::from_depths(footprint.reference, &footprint.depths())?
                        }
                        (Storage::Exact, kernel) => ShiftedMoments::from_weighted_depths(
                            footprint.reference,
                            &footprint.depths(),
                            &footprint.weights(&kernel.weights(size)),
                        )?,
                        (Storage::Texture(format), kernel) => {
                            ShiftedMoments::from_raw_moments(footprint.stored(
                                format,
                                &kernel.weights(size),
                                ShiftedMoments::texel_moments,
                            )?)?
                        }
                    };
                    moments.lit_fraction(receiver, min_variance)
                });
            }
            Filter::Moments {
                size,
                method,
                prefilter,
            } => {
                return filtered(map, centre, size, |footprint| {
                    match (prefilter.storage, prefilter.kernel) {
                        (Storage::Exact, Kernel::Box) => {
                            method.lit_fraction(footprint.reference, &footprint.depths(), receiver)
                        }
                        (Storage::Exact, kernel) => method.weighted_lit_fraction(
                            footprint.reference,
                            (
                                &footprint.depths(),
                                &footprint.weights(&kernel.weights(size)),
                            ),
                            receiver,
                        ),
                        (Storage::Texture(format), kernel) => method.stored_lit_fraction(
                            footprint,
                            (format, &kernel.weights(size)),
                            receiver,
                        ),
                    }
                });
            }
            Filter::Nearest | Filter::Pcf { .. } | Filter::Disk { .. } => {}
        }
        let one_tap = matches!(self.filter, Filter::Nearest);
        let at = (world, window);
        let comparison = Comparison::new(self.bias.comparison, map, &at, &normal, one_tap);
        let test = |offset: DVec2, nearest: bool| {
            let Some(texel) = map.texel_at(centre + offset) else {
                return 1.0;
            };
            // The nearest filter's tap is the centre of the texel it reads.
            let offset = if nearest && comparison.reads_offsets() {
                DVec2::new(f64::from(texel.0) + 0.5, f64::from(texel.1) + 0.5) - centre
            } else {
                offset
            };
            let lit = if nearest {
                comparison.lit_only_tap(map, texel, receiver, offset)
            } else {
                comparison.lit(map, texel, receiver, offset)
            };
            if lit { 1.0 } else { 0.0 }
        };
        match self.filter {
            Filter::Nearest => test(DVec2::ZERO, true),
            Filter::Pcf { size } => pcf_mean(size, |offset| test(offset, false)),
            Filter::Disk { .. } => disk_mean(&self.taps, |tap| test(tap, false)),
            Filter::Vsm { .. } | Filter::Moments { .. } => unreachable!("read above"),
        }
    }
}

/// The mean of `test(offset)` over the `size × size` taps of PCF, at `offset = (a − h, b − h)`
/// texels from the point, `a, b < size`, `h = (size − 1)/2`, row by row.
#[inline(always)]
pub(crate) fn pcf_mean(size: u32, mut test: impl FnMut(DVec2) -> f64) -> f64 {
    let half = 0.5 * f64::from(size.saturating_sub(1));
    let mut lit = 0.0;
    for b in 0..size {
        for a in 0..size {
            lit += test(DVec2::new(f64::from(a) - half, f64::from(b) - half));
        }
    }
    lit / f64::from(size * size)
}

/// The mean of `test(tap)` over the jittered disk's `taps` (offsets in texels), in their order.
#[inline(always)]
pub(crate) fn disk_mean(taps: &[DVec2], mut test: impl FnMut(DVec2) -> f64) -> f64 {
    let lit: f64 = taps.iter().map(|&tap| test(tap)).sum();
    lit / taps.len() as f64
}

/// A filterable map's lit fraction: `lit` of the [`Footprint`] of the `size × size` texels around
/// `centre`; 1 where the texel holding `centre` is off the map. The depths are a map's stored window
/// depths, in `[0, 1]`, and the methods' parameters are checked when the filter is parsed
/// ([`Filter::parse`]), so `lit` fails only on input no map holds; such a point reads as lit, as off
/// the map.
fn filtered(
    map: &ShadowMap,
    centre: DVec2,
    size: u32,
    lit: impl FnOnce(&Footprint) -> Result<f64, ParamError>,
) -> f64 {
    let Some((ci, cj)) = map.texel_at(centre) else {
        return 1.0;
    };
    let half = 0.5 * f64::from(size.saturating_sub(1));
    let mut taps = Vec::with_capacity((size * size) as usize);
    for b in 0..size {
        for a in 0..size {
            let offset = DVec2::new(f64::from(a) - half, f64::from(b) - half);
            if let Some((i, j)) = map.texel_at(centre + offset) {
                taps.push(Tap {
                    column: a as usize,
                    row: b as usize,
                    depth: map.depth(i, j),
                });
            }
        }
    }
    let footprint = Footprint {
        reference: map.depth(ci, cj),
        taps,
    };
    lit(&footprint).unwrap_or(1.0)
}

/// The texels a filterable map's kernel reads around a point: those of the `size × size` texels
/// holding `centre + (a − h, b − h)`, `a, b < size`, `h = (size − 1)/2`, that lie on the map, as
/// PCF reads them (for an odd size the texels centred on the point's own, for an even size the box
/// whose middle is nearest the point), row by row.
struct Footprint {
    /// The depth of the texel holding the point: the reference of the exact moments.
    reference: f64,
    /// The texels on the map, in row-major order.
    taps: Vec<Tap>,
}

/// One texel of a [`Footprint`].
struct Tap {
    /// Its column `a` within the kernel.
    column: usize,
    /// Its row `b` within the kernel.
    row: usize,
    /// Its stored depth.
    depth: f64,
}

impl Footprint {
    /// The texels' depths, in row-major order.
    fn depths(&self) -> Vec<f64> {
        self.taps.iter().map(|t| t.depth).collect()
    }

    /// The texels' separable weights `axis[a]·axis[b]`, in the order of [`Self::depths`].
    fn weights(&self, axis: &[f64]) -> Vec<f64> {
        self.taps
            .iter()
            .map(|t| axis[t.column] * axis[t.row])
            .collect()
    }

    /// The blurred raw moments a texture of `format` holds at the footprint's middle
    /// ([`Storage::Texture`]): each texel's `texel(depth)` rounded to the format, a pass along each
    /// row of the footprint with the weights `axis[a]` of its texels, then a pass down the rows with
    /// the weights `axis[b]` (each pass normalised over the taps on the map, accumulated in f32 and
    /// rounded to the format: `MomentFormat::blur_pass`).
    fn stored<const N: usize>(
        &self,
        format: MomentFormat,
        axis: &[f64],
        texel: impl Fn(f64) -> [f64; N],
    ) -> Result<[f64; N], ParamError> {
        let mut rows: Vec<[f64; N]> = Vec::new();
        let mut row_weights = Vec::new();
        for row in self.taps.chunk_by(|a, b| a.row == b.row) {
            let texels: Vec<[f64; N]> = row
                .iter()
                .map(|t| texel(t.depth).map(|m| format.round(m)))
                .collect();
            let weights: Vec<f64> = row.iter().map(|t| axis[t.column]).collect();
            rows.push(blur(format, &texels, &weights)?);
            row_weights.push(axis[row[0].row]);
        }
        blur(format, &rows, &row_weights)
    }
}

/// One blur pass over `texels`, moment by moment.
fn blur<const N: usize>(
    format: MomentFormat,
    texels: &[[f64; N]],
    weights: &[f64],
) -> Result<[f64; N], ParamError> {
    let mut out = [0.0; N];
    for (k, mean) in out.iter_mut().enumerate() {
        let values: Vec<f64> = texels.iter().map(|t| t[k]).collect();
        *mean = format.blur_pass(&values, weights)?;
    }
    Ok(out)
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
    /// The filterable maps (`vsm`, `esm`, `evsm2`, `evsm4`, `msm`) take their [`Prefilter`] knobs
    /// after their numbers, each after an `@`, in any order, each at most once: the kernel `@box`
    /// (the default) or `@gauss` ([`Kernel`]), and the storage `@exact` (the default), `@f32` or
    /// `@f16` ([`Storage`]). So `evsm4:5,40,5@gauss@f16` is EVSM4 with a 5 × 5 Gaussian over
    /// moments stored in half floats, and every spec without `@` means what it always meant (a
    /// box, exact moments). In an `analyze --filters` list, where `,` separates filters and `;` a
    /// filter's numbers, the knobs are written the same way: `evsm4:5;40;5@gauss@f16`.
    ///
    /// # Errors
    /// A message naming what is wrong and the accepted forms.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (numbers, knobs) = match spec.split_once('@') {
            Some((numbers, knobs)) => (numbers, Some(knobs)),
            None => (spec, None),
        };
        let (name, n) = spec_numbers(numbers, 4)?;
        if knobs.is_some() && FilterableMethod::from_key(name).is_none() {
            return Err(format!(
                "{spec:?}: the @ knobs (kernel, storage) apply to the filterable maps vsm, esm, \
                 evsm2, evsm4 and msm only"
            ));
        }
        let prefilter = knobs
            .map(|knobs| Prefilter::parse(knobs, spec))
            .transpose()?
            .unwrap_or_default();
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
            Ok(Self::Moments {
                size,
                method,
                prefilter,
            })
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
                prefilter,
            }),
            ("vsm", [k, floor]) if *floor >= 0.0 => Ok(Self::Vsm {
                size: count(*k, "the kernel size")?,
                min_variance: *floor,
                prefilter,
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
                 evsm4:K,C+,C-[,MIN_VARIANCE], msm:K,ALPHA; the last five may end in \
                 @box or @gauss and @exact, @f32 or @f16"
            )),
        }
    }
}

/// The jittered disk's seed when none is given (documented in the README and `--help`).
pub const DEFAULT_DISK_SEED: u64 = 0x5348_4144_4f57;
/// VSM's variance floor when none is given: (1e-3 of the depth range)².
pub const DEFAULT_MIN_VARIANCE: f64 = 1e-6;
