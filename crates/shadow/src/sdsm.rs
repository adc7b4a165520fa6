//! Sample distribution shadow maps (SDSM): Lauritzen, Salvi and Lefohn, *Sample Distribution
//! Shadow Maps*, I3D 2011. z-partitions whose split depths and light-space windows are taken from
//! the samples the eye pass actually shows, not from the view frustum.
//!
//! A pure planner: from the eye, the light, the scene box S and the world positions of the visible
//! pixels ("samples") it plans the partitions — no scene, no rasterizer. [`plan`]:
//! 1. **Split depths.** Each sample's eye depth `(p − e)·v`. [`SdsmVariant::Log`] splits the tight
//!    visible range `[min, max]` logarithmically, `min·(max/min)^(i/k)`; [`SdsmVariant::Kmeans`]
//!    clusters the depths. A sample at depth `d` belongs to the last partition whose near is at most
//!    `d` ([`crate::served`]), so a sample on a split goes to the farther partition.
//! 2. **Windows.** Each partition's map is an orthographic projection in LiSPSM's light space (the
//!    light frame of `frame`: y toward the light; for a spot light, the spot's
//!    post-perspective space, where its rays are parallel): across the map (window x along the
//!    frame's x, window y along its z with 0 on the viewer's side) the tight axis-aligned box of
//!    exactly the samples the partition serves; in depth, from the farthest of them (away from the
//!    light) to the nearest point of S toward the light ([caster reach](#caster-reach)).
//!
//! # Sources
//! - The paper: "optimizing the placement and size of a fixed number of Z-partitions using the
//!   distribution of the light space samples required by the current frame" (its abstract). Its
//!   full text was not at hand here; the details follow its sample code.
//! - Intel's sample code for it (the "Sample Distribution Shadow Maps" DirectX 11 sample, Intel,
//!   2012, Intel Sample Source Code License;
//!   <https://www.intel.com/content/www/us/en/developer/articles/technical/sample-distribution-shadow-maps.html>),
//!   whose shaders fix the details the paper leaves open:
//!   - `LogPartitions.hlsl`: `ReduceZBoundsFromGBuffer` reduces the view-space z of every pixel
//!     inside the camera's near/far to `[min, max]`; `LogPartitionFromRange` puts split `i` of `k`
//!     at `minZ·pow(maxZ/minZ, i/k)`; `ComputeLogPartitionsFromZBounds` stretches the first
//!     interval to the camera's near plane and the last to its far plane. (The sample's other log
//!     path, `ComputeLogPartitionsFromHistogram`, rounds the range to histogram bins; this module
//!     follows the exact reduction.)
//!   - `CustomPartitions.hlsl`: `ReduceBoundsFromGBuffer` min/max-reduces each pixel's light-space
//!     coordinates into the partition whose interval holds its z; the partition index counts the
//!     splits with `z ≥ intervalEnd` (the farther partition takes a sample on a split).
//!   - `SDSMPartitions.hlsl`: `ComputePartitionDataFromBounds` turns the bounds into a scale and
//!     bias, after a light-space border (`mLightSpaceBorder`, for blur kernels) and a dilation
//!     (`mDilationFactor`, about ten texels), a cap on the scale (`mMaxScale`) and optional
//!     power-of-two quantisation; a partition with no samples is sent to "a tiny region that
//!     shouldn't be overlapped by any geometry", with the remark that skipping empty partitions on
//!     the CPU would be cleaner.
//!   - `KMeansPartitions.hlsl`: `ComputeKMeansPartitions` runs Lloyd's iterations on a depth
//!     histogram (`BINS` bins of the linear view-space z, `BinToZ`), starting from centroids at the
//!     equal-count quantiles `(i + 1)/(k + 1)` (`WeightUpperBound` on the histogram's prefix sums);
//!     each iteration assigns the bins between the midpoints of neighbouring centroids and moves
//!     each centroid to its cluster's mean z, keeping it where its cluster is empty; the splits are
//!     the midpoints.
//!
//! # Choices, named
//! Where shadowlab differs from the sample, or decides what neither source says:
//! - <a id="sample-range-ends"></a>**Sample range ends.** The first partition's near is the
//!   samples' smallest eye depth and the last one's far their largest — not the camera's near and
//!   far, which the sample stretches them to. [`crate::served`] already sends depths below the
//!   first near to the first partition and above the last near to the last, so what serves a pixel
//!   is the same; the reported depths say where the samples are.
//! - <a id="caster-reach"></a>**Caster reach.** A map's depth runs from its farthest sample (away
//!   from the light) to the nearest point of S toward the light, so that every caster between the
//!   light and the partition's receivers is inside the map's depth range (the sample's scale and
//!   bias fit depth to the samples' bounds as they fit x and y, widened by its border). For a
//!   spot light the reach stops at the spot's near plane, as the focus body B = conv(V ∪ l) ∩ S ∩ L
//!   of every other technique does (L, the spot's frustum, ends there): nearer the light,
//!   post-perspective depth grows without bound. A sample nearer the light than the reach (one
//!   outside S) moves it to the sample.
//! - <a id="cone-lit-samples"></a>**Cone-lit samples.** For a spot light, only the samples inside
//!   its cone (within half its `fov_y` of its axis: the test [`crate::view::shade`] lights by) bound
//!   the partitions and their windows; outside it the cone, not the map, darkens a point. A sample
//!   at the spot's own position has no place in its map: [`ShadowError::LightInsideFocusBody`].
//! - <a id="half-open-window"></a>**Half-open window, no border.** Nothing is added around the
//!   samples' box except what exactness needs: every served sample's window coordinates, computed
//!   as lookups compute them ([`ShadowMapping::window`]), lie in `[0, 1)` across the map (the texel
//!   lookup reads `[0, 1)`; a sample at exactly 1 would fall off the map) and in `[0, 1]` in
//!   depth. Where rounding puts one outside, that side is moved out by the overshoot and a few ulps,
//!   doubling each time, at most [`ROUNDING_PASSES`] times. The sample's border, dilation, scale
//!   cap and quantisation are left out: a filter's taps that reach past a window's edge read the
//!   map as lit there.
//! - <a id="flat-axes"></a>**Flat axes.** A box thinner on an axis than [`FLAT_FRACTION`] of its
//!   largest extent (all samples on one light-space line or plane, or one sample) is widened to that
//!   extent about its middle.
//! - <a id="merged-empty-partitions"></a>**Merged empty partitions.** A split interval that holds
//!   no sample is merged into its nearer neighbour (the first one, into its farther): its range is
//!   served by that neighbour, which holds the same samples as before. An empty partition would
//!   serve no sample of the frame it is planned from, and may have no depth extent at all (every
//!   sample at one depth). [`plan`] may therefore return fewer partitions than `count`.
//! - <a id="exact-k-means"></a>**Exact k-means.** [`SdsmVariant::Kmeans`] is the sample's Lloyd
//!   iteration on the samples' own eye depths (linear, as the sample's `BinToZ`), not on a
//!   histogram of them: the same quantile start, midpoint assignment (a sample on a midpoint goes
//!   to the farther cluster, as [`crate::served`] does), means and kept empty centres, repeated
//!   until the assignment stops changing or [`KMEANS_ITERATIONS`] times — the sample runs a count
//!   set in its UI. Sorted depths and sums in a fixed order make it deterministic and independent
//!   of the samples' order.

use std::borrow::Cow;

use glam::{DMat4, DVec3, DVec4};
use rayon::prelude::*;
use shadowlab_hull::HullError;
use shadowlab_params::{DepthRange, ParamError};

use crate::error::ShadowError;
use crate::frame::LightFrame;
use crate::gather::{gather, gather_groups};
use crate::homogeneous::point_of;
use crate::input::{LightSource, PlanInput};
use crate::lanes::{LANES, Vectors};
use crate::partition::Partition;
use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
pub use crate::technique::SdsmVariant;
use crate::technique::Technique;

/// The key errors and the light frame know this planner by.
const KEY: &str = "sdsm";

/// Below this fraction of a window's largest extent (of its largest coordinate magnitude, if the
/// window is a point), an axis counts as flat and is widened to this fraction about its middle
/// ([flat axes](#flat-axes)). 10⁻⁹ is far above the rounding of light-space coordinates (≈10⁻¹⁶ of
/// their magnitude) and far below any texel of a map up to 10⁸ texels wide.
pub const FLAT_FRACTION: f64 = 1e-9;

/// Samples per parallel work item of the window fit's bounds (see `bounds`): the split depends on
/// this constant only, never on the thread count.
const FIT_CHUNK: usize = 8192;
/// How many times a window's side may be moved out for rounding ([half-open
/// window](#half-open-window)); the extra move, `2^pass` ulps of the side's magnitude, doubles each
/// pass, so that 64 passes cover any rounding of a finite mapping.
pub const ROUNDING_PASSES: i32 = 64;

/// The most Lloyd iterations [`SdsmVariant::Kmeans`] runs ([exact k-means](#exact-k-means)). In
/// one dimension each iteration that changes the assignment lowers the clusters' summed squared
/// spread, so the iteration settles; the cap bounds the time on adversarial depths.
pub const KMEANS_ITERATIONS: usize = 100;

impl SdsmVariant {
    /// The `count + 1` split depths of `depths` (eye depths of samples, any order): non-decreasing,
    /// the first the smallest depth and the last the largest, exactly. Partition `i` is
    /// `[b_i, b_{i+1})`, the last one closed. Consecutive equal splits make empty partitions, which
    /// [`plan`] merges.
    ///
    /// # Errors
    /// [`ShadowError::Parameter`] for `count` 0 (or a range `shadowlab-params` rejects: a ratio
    /// `max/min` that overflows); [`ShadowError::NoSamples`] for no depths;
    /// [`ShadowError::Geometry`] for a depth that is not finite; [`ShadowError::NotDefined`] for a
    /// depth at or behind the eye (≤ 0).
    pub fn boundaries(self, depths: &[f64], count: usize) -> Result<Vec<f64>, ShadowError> {
        check_count(count)?;
        if depths.is_empty() {
            return Err(ShadowError::NoSamples);
        }
        if depths.par_iter().any(|d| !d.is_finite()) {
            return Err(HullError::NonFinite {
                parameter: "depths",
            }
            .into());
        }
        if depths.par_iter().any(|d| *d <= 0.0) {
            return Err(ShadowError::NotDefined {
                technique: KEY,
                reason: "a sample lies at or behind the eye's plane (eye depth ≤ 0), where the \
                         logarithmic split of the visible depths has no value"
                    .into(),
            });
        }
        Ok(match self {
            Self::Log => {
                // Positive finite depths: their least and greatest, whatever the order.
                let empty = (f64::INFINITY, f64::NEG_INFINITY);
                let (min, max) = depths
                    .par_iter()
                    .fold(|| empty, |(lo, hi), d| (lo.min(*d), hi.max(*d)))
                    .reduce(|| empty, |(lo, hi), (l, h)| (lo.min(l), hi.max(h)));
                logarithmic(min, max, count)?
            }
            Self::Kmeans => kmeans(depths, count),
        })
    }
}

/// The form [`SdsmVariant::parse`] reads.
/// `count` must be at least 1, as for every split scheme.
fn check_count(count: usize) -> Result<(), ShadowError> {
    if count == 0 {
        return Err(ParamError::OutOfDomain {
            name: "partitions",
            value: 0.0,
            requirement: "at least 1".into(),
        }
        .into());
    }
    Ok(())
}

/// `min·(max/min)^(i/k)`, exact at both ends ([`DepthRange::geometric_lerp`], the same split as
/// `shadowlab_params::splits::SplitScheme::Logarithmic`); every split at `min` if `min = max`.
fn logarithmic(min: f64, max: f64, count: usize) -> Result<Vec<f64>, ShadowError> {
    if min >= max {
        return Ok(vec![min; count + 1]);
    }
    let range = DepthRange::new(min, max)?;
    Ok((0..=count)
        .map(|i| range.geometric_lerp(i as f64 / count as f64))
        .collect())
}

/// Lloyd's iterations on the sorted depths ([exact k-means](#exact-k-means)); the splits between
/// the final centres, with the smallest and largest depth at the ends.
fn kmeans(depths: &[f64], count: usize) -> Vec<f64> {
    let mut sorted = depths.to_vec();
    // One order under `total_cmp`, so a parallel sort gives the same.
    sorted.par_sort_by(f64::total_cmp);
    let n = sorted.len();
    // The equal-count quantiles (i + 1)/(k + 1): the first sorted index whose inclusive count
    // exceeds that share of n, as the sample's WeightUpperBound finds it on its prefix sums.
    let mut centres: Vec<f64> = (0..count)
        .map(|i| sorted[((i + 1) * n / (count + 1)).min(n - 1)])
        .collect();
    // Cluster i is sorted[cuts[i − 1]..cuts[i]]: the depths from the midpoint before its centre
    // (inclusive) to the midpoint after it (exclusive).
    let cuts_of = |centres: &[f64]| -> Vec<usize> {
        let mut start = 0;
        midpoints(centres)
            .map(|b| {
                start = sorted.partition_point(|d| *d < b).max(start);
                start
            })
            .collect()
    };
    let mut cuts = cuts_of(&centres);
    for _ in 0..KMEANS_ITERATIONS {
        let mut start = 0;
        for (i, centre) in centres.iter_mut().enumerate() {
            let end = cuts.get(i).copied().unwrap_or(n);
            let cluster = &sorted[start..end];
            if !cluster.is_empty() {
                *centre = cluster.iter().sum::<f64>() / cluster.len() as f64;
            }
            start = end;
        }
        let next = cuts_of(&centres);
        if next == cuts {
            break;
        }
        cuts = next;
    }
    let mut boundaries = Vec::with_capacity(count + 1);
    boundaries.push(sorted[0]);
    for b in midpoints(&centres) {
        let last = boundaries[boundaries.len() - 1];
        boundaries.push(b.clamp(last, sorted[n - 1]));
    }
    boundaries.push(sorted[n - 1]);
    boundaries
}

/// The midpoints between neighbouring centres (the sample's `lerp(c_i, c_{i+1}, 0.5)`).
fn midpoints(centres: &[f64]) -> impl Iterator<Item = f64> + '_ {
    centres.windows(2).map(|c| c[0] + 0.5 * (c[1] - c[0]))
}

/// Plans the sample distribution shadow map of `input`'s light: `count` z-partitions (fewer where
/// a split interval holds no sample: [merged empty partitions](#merged-empty-partitions)) split by
/// `variant` from the eye depths of `samples` — the world positions of the visible pixels, as an
/// eye pass gives them — each with the orthographic map that fits exactly the samples it serves
/// ([`crate::served`]) in light space, from them to the [caster reach](#caster-reach). Nearest
/// first; the first near and the last far are the samples' smallest and largest eye depth.
/// `input`'s focus policy and nearest visible depth play no part: the samples are the focus.
///
/// # Errors
/// - [`ShadowError::Parameter`] for `count` 0;
/// - [`ShadowError::NoSamples`] if there are no samples (for a spot light, none inside its cone:
///   [cone-lit samples](#cone-lit-samples));
/// - [`ShadowError::Geometry`] for a sample that is not finite, or a light frame
///   `shadowlab-hull` rejects;
/// - [`ShadowError::NotDefined`] for a sample at or behind the eye's plane;
/// - [`ShadowError::LightInsideFocusBody`] for a sample at a spot light's position, or a spot's
///   near plane that its own transform cannot place;
/// - [`ShadowError::FlatFocusBody`] if a window has no extent and no magnitude to scale one from.
pub fn plan(
    input: &PlanInput,
    samples: &[DVec3],
    variant: SdsmVariant,
    count: usize,
) -> Result<Vec<Partition>, ShadowError> {
    check_count(count)?;
    if samples.par_iter().any(|p| !p.is_finite()) {
        return Err(HullError::NonFinite {
            parameter: "samples",
        }
        .into());
    }
    let frame = LightFrame::new(&input.eye, &input.light, KEY)?;
    let to_light = frame.world_to_light();
    let (e, v) = (input.eye.pose.eye(), input.eye.pose.forward());
    // Every pass over the samples is parallel, and keeps the samples' order (`gather`). Each
    // pass reads the positions alone, and a light-frame position is computed where it is used:
    // cheaper than reading it back. Samples the light reaches are read in place when that is all
    // of them (always a directional light's), not copied.
    let directional = matches!(input.light, LightSource::Directional { .. });
    let reached = |p: &DVec3| input.light.reaches(*p);
    let samples: Cow<'_, [DVec3]> = if directional || samples.par_iter().all(reached) {
        Cow::Borrowed(samples)
    } else {
        Cow::Owned(gather(samples, |_, p| reached(p)))
    };
    // A directional light's frame is affine (w = 1 for every finite sample): nothing to check.
    if !directional
        && samples
            .par_iter()
            .any(|&p| light_point(&to_light, p).is_none())
    {
        return Err(ShadowError::LightInsideFocusBody);
    }
    let depths: Vec<f64> = samples.par_iter().map(|&p| (p - e).dot(v)).collect();
    let boundaries = variant.boundaries(&depths, count)?;
    let nears = merged_nears(&boundaries, &depths);
    // Each partition's samples in the samples' order: all of them for one partition; for several,
    // grouped by partition into one vector, which the partitions' slices borrow.
    let grouped;
    let served: Vec<&[DVec3]> = if nears.len() == 1 {
        vec![&samples]
    } else {
        grouped = gather_groups(&samples, nears.len(), |i, _| {
            serving_index(&nears, depths[i])
        });
        grouped.slices()
    };
    let reach = caster_reach(input, &frame)?;
    let half_fov = input
        .eye
        .half_fov_toward(input.light.toward_from(input.eye.pose.eye()));
    let last_far = boundaries[boundaries.len() - 1];
    nears
        .iter()
        .zip(&served)
        .enumerate()
        .map(|(k, (&near, served))| {
            let far = nears.get(k + 1).copied().unwrap_or(last_far);
            let window = fit(&to_light, served, reach)?;
            Ok(partition(
                near,
                far,
                light_setup(Technique::Sdsm(variant), &frame, &window, half_fov),
            ))
        })
        .collect()
}

/// The one place a [`Partition`] is built: a z-partition of the whole view at these depths.
fn partition(near: f64, far: f64, setup: LightSetup) -> Partition {
    Partition {
        near,
        far,
        face: None,
        sphere: None,
        setup,
    }
}

/// The one place a set-up is built: the window's orthographic projection after the light frame,
/// labelled `technique`; its focus body is the window's box.
fn light_setup(
    technique: Technique,
    frame: &LightFrame,
    window: &Window,
    half_fov: f64,
) -> LightSetup {
    let view = frame.world_to_light();
    LightSetup {
        technique,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(view, window.projection())),
        gamma: frame.gamma(),
        half_fov,
        warp: None,
        psm: None,
        focus_body: window.world_corners(&view),
    }
}

/// `world` in light space through `to_light` (`None` where a spot's transform sends it behind the
/// light): [`LightFrame::light_point`] with the matrix made once.
fn light_point(to_light: &DMat4, world: DVec3) -> Option<DVec3> {
    let h: DVec4 = *to_light * world.extend(1.0);
    (h.w > 0.0).then(|| point_of(h))
}

/// [`light_point`] of four points in lanes: each lane's point (divided by `w` also where it is
/// exactly 1, which gives the same bits: `homogeneous` module) and whether it has none.
fn light_points(to_light: &DMat4, worlds: &[DVec3; LANES]) -> (Vectors, [bool; LANES]) {
    let [x, y, z, w] = Vectors::of(worlds).transformed(to_light, 1.0);
    let points = Vectors {
        x: x / w,
        y: y / w,
        z: z / w,
    };
    (points, w.to_array().map(|w| w.is_nan() || w <= 0.0))
}

/// The index of the partition, of those starting at `nears` (non-decreasing), that serves depth
/// `depth`: the last whose near is at most `depth`, the first if none is — [`crate::served`]'s
/// rule for z-partitions.
fn serving_index(nears: &[f64], depth: f64) -> usize {
    nears
        .partition_point(|near| *near <= depth)
        .saturating_sub(1)
}

/// The nears of the partitions that keep at least one of `depths` ([merged empty
/// partitions](#merged-empty-partitions)): the split intervals' nears, those that serve no depth
/// left out, the first one at the smallest depth.
fn merged_nears(boundaries: &[f64], depths: &[f64]) -> Vec<f64> {
    let nears = &boundaries[..boundaries.len() - 1];
    let none = || vec![false; nears.len()];
    let held = depths
        .par_iter()
        .fold(none, |mut held, depth| {
            held[serving_index(nears, *depth)] = true;
            held
        })
        .reduce(none, |mut held, other| {
            for (held, other) in held.iter_mut().zip(other) {
                *held |= other;
            }
            held
        });
    let mut merged: Vec<f64> = nears
        .iter()
        .zip(&held)
        .filter(|(_, held)| **held)
        .map(|(near, _)| *near)
        .collect();
    if let Some(first) = merged.first_mut() {
        *first = boundaries[0];
    }
    merged
}

/// The light-frame y of the nearest point toward the light that a map must reach: S's nearest
/// point; for a spot light no nearer than its near plane ([caster reach](#caster-reach)).
fn caster_reach(input: &PlanInput, frame: &LightFrame) -> Result<f64, ShadowError> {
    let corners = input.scene.corners();
    let highest = |points: &[DVec3]| points.iter().fold(f64::NEG_INFINITY, |y, p| y.max(p.y));
    match input.light {
        LightSource::Directional { .. } => {
            let points = frame
                .light_points(&corners)
                .ok_or(ShadowError::LightInsideFocusBody)?;
            Ok(highest(&points))
        }
        LightSource::Point { .. } => Err(Technique::unserved_point_light(KEY)),
        LightSource::Spot { pose, cone } => {
            // In the spot's space its near plane is perpendicular to the light's direction, the
            // frame's y: one point gives its height.
            let near_plane = frame
                .light_point(pose.eye() + pose.forward() * cone.near())
                .ok_or(ShadowError::LightInsideFocusBody)?
                .y;
            // A corner behind the light's plane: S reaches the light, whose neighbourhood the
            // spot's space sends to infinite depth.
            Ok(frame
                .light_points(&corners)
                .map_or(near_plane, |points| highest(&points).min(near_plane)))
        }
    }
}

/// The map axes: the light-frame axis each runs along, and whether it grows with that axis. Window
/// x along x; window y along −z (0 on the viewer's side, the largest z); depth along −y (0 nearest
/// the light, the largest y).
const MAP_AXES: [(usize, bool); 3] = [(0, true), (2, false), (1, false)];

/// A partition's window: a box in the light frame.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Window {
    lo: DVec3,
    hi: DVec3,
}

impl Window {
    /// The orthographic projection of the box onto GL clip space: x, z and y (in that order of
    /// map axes, [`MAP_AXES`]) from `[−1, 1]`.
    fn projection(&self) -> DMat4 {
        let (lo, hi) = (self.lo, self.hi);
        let size = hi - lo;
        let x_row = DVec4::new(2.0, 0.0, 0.0, -(lo.x + hi.x)) / size.x;
        let y_row = DVec4::new(0.0, 0.0, -2.0, lo.z + hi.z) / size.z;
        let z_row = DVec4::new(0.0, -2.0, 0.0, lo.y + hi.y) / size.y;
        DMat4::from_cols(x_row, y_row, z_row, DVec4::W).transpose()
    }

    /// The box's corners in world space (those the light frame can send back: all of them for a
    /// directional light, those in front of a spot light).
    fn world_corners(&self, view: &DMat4) -> Vec<DVec3> {
        let back = view.inverse();
        (0..8)
            .filter_map(|i| {
                let corner = DVec3::new(
                    if i & 1 == 0 { self.lo.x } else { self.hi.x },
                    if i & 2 == 0 { self.lo.y } else { self.hi.y },
                    if i & 4 == 0 { self.lo.z } else { self.hi.z },
                );
                let h = back * corner.extend(1.0);
                (h.w > 0.0).then(|| h.truncate() / h.w)
            })
            .collect()
    }

    /// Widens every axis thinner than [`FLAT_FRACTION`] of the largest extent (or, for a point, of
    /// the largest coordinate magnitude) to that extent about its middle.
    fn unflattened(mut self) -> Result<Self, ShadowError> {
        let extent = self.hi - self.lo;
        let largest = extent.max_element();
        let scale = if largest > 0.0 {
            largest
        } else {
            self.lo.abs().max(self.hi.abs()).max_element()
        };
        let minimum = FLAT_FRACTION * scale;
        if !(minimum > 0.0 && minimum.is_finite()) {
            return Err(ShadowError::FlatFocusBody {
                axis: "lateral axis",
            });
        }
        for axis in 0..3 {
            if extent[axis] < minimum {
                let middle = 0.5 * (self.lo[axis] + self.hi[axis]);
                self.lo[axis] = middle - 0.5 * minimum;
                self.hi[axis] = middle + 0.5 * minimum;
            }
        }
        Ok(self)
    }

    /// Moves out each side some window coordinate in `low` (the smallest, per map axis) or `high`
    /// (the largest) lies beyond: the overshoot in light units plus `2^pass` ulps of the side's
    /// magnitude. Across the map the window is half-open, `[0, 1)`; in depth closed, `[0, 1]`.
    /// Returns whether a side moved.
    fn widen(&mut self, low: DVec3, high: DVec3, pass: i32) -> bool {
        let mut moved = false;
        for (map_axis, (axis, grows)) in MAP_AXES.into_iter().enumerate() {
            let extent = self.hi[axis] - self.lo[axis];
            let slack = f64::EPSILON
                * 2f64.powi(pass)
                * self.lo[axis].abs().max(self.hi[axis].abs()).max(extent);
            let below = low[map_axis] < 0.0;
            let above = if map_axis < 2 {
                high[map_axis] >= 1.0
            } else {
                high[map_axis] > 1.0
            };
            // The side where the window coordinate is 0 is the low side of a growing axis.
            if below {
                let step = -low[map_axis] * extent + slack;
                if grows {
                    self.lo[axis] -= step;
                } else {
                    self.hi[axis] += step;
                }
            }
            if above {
                let step = (high[map_axis] - 1.0) * extent + slack;
                if grows {
                    self.hi[axis] += step;
                } else {
                    self.lo[axis] -= step;
                }
            }
            moved |= below || above;
        }
        moved
    }
}

/// The window of a partition's `samples`: their tight box in light space, up to `reach` toward the
/// light, flat axes widened, then moved out where rounding puts a sample outside
/// ([half-open window](#half-open-window)).
fn fit(to_light: &DMat4, samples: &[DVec3], reach: f64) -> Result<Window, ShadowError> {
    let (lo, mut hi) = bounds(
        samples,
        |&sample| light_point(to_light, sample),
        |four| light_points(to_light, four),
    )?;
    hi.y = hi.y.max(reach);
    let mut window = Window { lo, hi }.unflattened()?;
    for pass in 0..ROUNDING_PASSES {
        let mapping =
            ShadowMapping::Projective(ProjectiveMapping::new(*to_light, window.projection()));
        let (low, high) = bounds(
            samples,
            |&sample| mapping.window(sample),
            |four| mapping.in_lanes().windows(Vectors::of(four)),
        )?;
        if !window.widen(low, high, pass) {
            return Ok(window);
        }
    }
    Err(ShadowError::NotDefined {
        technique: KEY,
        reason: format!(
            "the window's rounding did not settle in {ROUNDING_PASSES} passes: the samples' \
             light-space coordinates are too large for their spread"
        ),
    })
}

/// The component-wise least and greatest of `point(sample)` over `samples`, in parallel over
/// fixed chunks of [`FIT_CHUNK`] whose bounds are combined in chunk order, so the result is the
/// same on any thread count; [`ShadowError::LightInsideFocusBody`] where `point` has none. The
/// points are mapped four at a time by `points` (each lane `point`'s bits, `None` where the lane's
/// flag is set: the `lanes` module), the last few of a chunk by `point`; the four lanes keep bounds
/// of their own, combined at the chunk's end. A NaN coordinate is passed over, as `f64::min` passes
/// it over, and a zero bound is +0 whatever zeros were taken (`f64::min(−0, +0)` may be either), so
/// the bounds do not depend on the order the points are taken in.
fn bounds(
    samples: &[DVec3],
    point: impl Fn(&DVec3) -> Option<DVec3> + Sync,
    points: impl Fn(&[DVec3; LANES]) -> (Vectors, [bool; LANES]) + Sync,
) -> Result<(DVec3, DVec3), ShadowError> {
    let empty = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let take = |(lo, hi): (DVec3, DVec3), (low, high): (DVec3, DVec3)| (lo.min(low), hi.max(high));
    let chunks: Vec<Option<(DVec3, DVec3)>> = samples
        .par_chunks(FIT_CHUNK)
        .map(|chunk| {
            let (fours, rest) = chunk.as_chunks::<LANES>();
            let lanes_empty = (Vectors::splat(empty.0), Vectors::splat(empty.1));
            let (lo, hi) = fours.iter().try_fold(lanes_empty, |(lo, hi), four| {
                let (p, undefined) = points(four);
                (!undefined.contains(&true)).then(|| (lo.min(p), hi.max(p)))
            })?;
            let (lo, hi) = (lo.vectors(), hi.vectors());
            let bounds = (0..LANES).fold(empty, |bounds, k| take(bounds, (lo[k], hi[k])));
            rest.iter().try_fold(bounds, |bounds, sample| {
                point(sample).map(|p| take(bounds, (p, p)))
            })
        })
        .collect();
    let (lo, hi) = chunks
        .into_iter()
        .try_fold(empty, |bounds, chunk| Some(take(bounds, chunk?)))
        .ok_or(ShadowError::LightInsideFocusBody)?;
    // −0 + +0 = +0; every other value stays as it is.
    Ok((lo + DVec3::ZERO, hi + DVec3::ZERO))
}

#[cfg(test)]
mod tests {
    use glam::{DMat4, DVec3, DVec4};
    use shadowlab_test_random::SplitMix;

    use super::{FIT_CHUNK, bounds, light_point, light_points};
    use crate::error::ShadowError;

    /// A zero bound is +0 whichever zeros were taken, in whatever order and lanes: the bounds are
    /// a function of the points' values alone. (A light-space −0 needs every term of its sum to be
    /// −0: here a translation of −0 and negative other coordinates.)
    #[test]
    fn a_zero_bound_is_positive_zero_in_any_order() {
        let to_light = DMat4::from_cols(
            DVec4::X,
            DVec4::Y,
            DVec4::Z,
            DVec4::new(-0.0, -0.0, -0.0, 1.0),
        );
        let point = |sample: &DVec3| light_point(&to_light, *sample);
        let at = |x: f64| DVec3::new(x, -1.0, -1.0);
        assert_eq!(
            point(&at(-0.0)).map(|p| p.x.to_bits()),
            Some((-0.0f64).to_bits())
        );
        let zeros = [-0.0, 0.0, -0.0, -0.0, 0.0, -0.0, 0.0];
        for count in [1, 2, 4, 5, 7] {
            for start in 0..zeros.len() {
                let samples: Vec<DVec3> = (0..count)
                    .map(|k| at(zeros[(start + k) % zeros.len()]))
                    .collect();
                let (lo, hi) =
                    bounds(&samples, point, |four| light_points(&to_light, four)).expect("bounds");
                assert_eq!(
                    [lo.x, hi.x].map(f64::to_bits),
                    [0, 0],
                    "{count} from {start}"
                );
            }
        }
    }

    /// The bounds of points mapped four at a time are those of the points mapped one by one and
    /// taken in order, to the bit — through an affine light space (`w` exactly 1) and a
    /// perspective one (`w` varying), for counts around the lanes and the chunks — and a point
    /// with no light-space position is the error wherever it lies.
    #[test]
    fn bounds_in_lanes_are_the_one_by_one_bounds() {
        let mut random = SplitMix(0x5eed_0000_0000_5d5e);
        // A rotation and a translation; and a projection whose `w = 20 − z` is positive for
        // every sample (coordinates within ±10) and not 1.
        let affine = DMat4::from_cols(
            DVec4::new(0.6, 0.8, 0.0, 0.0),
            DVec4::new(-0.8, 0.6, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(1.5, -2.0, 3.0, 1.0),
        );
        let perspective = DMat4::from_cols(
            DVec4::new(1.2, 0.0, 0.0, 0.0),
            DVec4::new(0.0, 1.2, 0.0, 0.0),
            DVec4::new(0.0, 0.0, -1.01, -1.0),
            DVec4::new(0.0, 0.0, -1.0, 20.0),
        );
        for to_light in [affine, perspective] {
            for count in [1, 3, 4, 5, 7, 8, 4095, FIT_CHUNK - 1, FIT_CHUNK + 6] {
                let samples: Vec<DVec3> = (0..count).map(|_| random.vector(10.0)).collect();
                let point = |sample: &DVec3| light_point(&to_light, *sample);
                let expected = samples
                    .iter()
                    .map(point)
                    .try_fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                        let p = p?;
                        Some((lo.min(p), hi.max(p)))
                    })
                    .expect("every sample in front of the centre");
                let found = bounds(&samples, point, |four| light_points(&to_light, four))
                    .expect("the same bounds");
                let bits = |(lo, hi): (DVec3, DVec3)| {
                    [lo.to_array(), hi.to_array()].map(|v| v.map(f64::to_bits))
                };
                assert_eq!(bits(found), bits(expected), "{count} samples");
                // A point on the projection's centre plane (`w = 0`) has no light-space position.
                if to_light == perspective {
                    // First, middle and last: in the first lanes, and among the last few.
                    for k in [0, count / 2, count - 1] {
                        let mut samples = samples.clone();
                        samples[k] = DVec3::new(0.0, 0.0, 20.0);
                        assert!(matches!(
                            bounds(&samples, point, |four| light_points(&to_light, four)),
                            Err(ShadowError::LightInsideFocusBody)
                        ));
                    }
                }
            }
        }
    }
}
