//! The aliasing a shadow map shows on screen, measured per pixel: how many pixels one texel
//! covers, from the Jacobian of the screen → shadow-map mapping on the visible surface (CG06
//! eqs. 4–6; formulas.md §6.3–6.5), split into LiSPSM's perspective and projection parts (LiSPSM
//! eq. 1; formulas.md §1).
//!
//! # The Jacobian
//! Let `x = (x₁, x₂)` be window coordinates of the eye image in pixels (x right, y up), `X(x)` the
//! point where the eye ray through `x` meets the **surface plane** through the visible point `X₀`
//! with unit normal `n`, and `u(X) = res·(window_x, window_y)` the shadow map's texel coordinates
//! of `X` (`ShadowMapping::window`, `res` texels per side). The composite map's Jacobian is
//!
//! `J = ∂u/∂x = Du(X₀) · ∂X/∂x`   (texels per pixel; CG06 eq. 4 with `x₃` the depth of the plane)
//!
//! * `∂X/∂x_j = D_j − (X₀ − e)·(D_j·n)/((X₀ − e)·n)`, with `e` the eye and
//!   `D₁ = right·(2 tan φ_x/W)·z`, `D₂ = up·(2 tan φ_y/H)·z` one pixel's step of the eye ray at
//!   the point's eye depth `z`: the ray–plane intersection differentiated, exact. The plane is the
//!   one the eye image's normal gives (the facet's plane on a flat mesh, the smooth surface on a
//!   smooth one), so nothing is differenced across an edge, as neighbouring pixels would be.
//! * `Du·t` for a projective map (every technique but the logarithmic one) exactly: with
//!   `p = M·(X, 1)` and `ṗ = M·(t, 0)`, `d(p_k/p_w) = (ṗ_k p_w − p_k ṗ_w)/p_w²` — CG06 eq. 5; for the
//!   logarithmic map by its closed-form derivative
//!   (`shadowlab_shadow::logarithmic::LogarithmicMap::ndc_derivative`).
//!
//! # The footprint
//! `J⁻¹` maps a texel step to a pixel step; the image of one texel on screen is (to first order)
//! the parallelogram spanned by `J⁻¹`'s columns. The **total** footprint is the length of that
//! image along its longest direction, the largest singular value of `J⁻¹`:
//!
//! `total = σ_max(J⁻¹) = 1/σ_min(J) = σ_max(J)/|det J|`, with
//! `σ_max(J) = ½(√((a+d)² + (c−b)²) + √((a−d)² + (b+c)²))` for `J = [[a, b], [c, d]]`.
//!
//! It is rotation-invariant (it does not depend on how texels and pixels happen to be aligned),
//! it is the undersampling that shows as jagged edges (the worst direction, where CG06's L2
//! metric `‖J⁻¹‖_F² = ‖J‖_F²/det²J`, eq. 6, averages both), and in the papers' 1-D setting, where
//! `J` is diagonal in the map's and the screen's axes, it is their error along the worse axis.
//! Total > 1 is undersampling (a texel spans more than a pixel), < 1 oversampling.
//!
//! The **projection** part is `cos α / cos β` (LiSPSM's letters, CONVENTIONS.md): α between `n`
//! and the ray to the eye, β between `n` and the light's ray. The light's ray is read off the map
//! itself — the direction along which its `u` does not change, the kernel of `Du` (found from
//! `Du` on `∂X/∂x₁`, `∂X/∂x₂` and `n`) — so no light needs to be passed and PSM's post-perspective
//! light is handled like any other. The **perspective** part is `total / projection`.
//!
//! # Against the 1-D analysis
//! On the view axis at eye depth `z`, for a normal in the plane of the light and view directions
//! (so `J` is diagonal: the map's warp axis y against the screen's axis in that plane), the texel
//! covers along the warp axis
//!
//! `‖J⁻¹·e_y‖ = (dp/ds)·sin γ·(cos α/cos β)·res_c/(2 tan φ·res)`
//!
//! pixels, with `dp/ds = (1/z)·dz/ds` what `shadowlab_shadow::measure::view_axis_error` measures
//! and `res_c` the image's pixels across `2 tan φ` in that plane — CAD's `m_z` (eq. 6) times
//! `sin γ·cos α/cos β`. At γ = 90°, LiSPSM's configuration (§4.1, Fig. 4), with `cos α = cos β`
//! it is exactly `view_axis_error` in pixels per texel; the tests hold it to 1e-6. The `sin γ`
//! is not in the papers: a texel's shaft of light crosses the view axis over `dz` but is only
//! `dz·sin γ` wide, and it is the width that lands on the surface. This is why the 1-D error is
//! unbounded at γ = 0 while a surface facing both the eye and the light sees a finite texel.
//!
//! The factorisation `total = perspective × projection` is LiSPSM eq. 1 exactly in that 1-D
//! setting; in general the projection factor stretches one direction of the texel's image and
//! σ_max may pick another, so there the perspective part is a definition (the quotient), not a
//! separate measurement.

use glam::{DMat2, DMat4, DVec2, DVec3, DVec4};
use rayon::prelude::*;
use shadowlab_raster::{EyeImage, NO_TRIANGLE};
use shadowlab_scene::Camera;
use shadowlab_shadow::gather::gather_map;
use shadowlab_shadow::homogeneous::quotient;
use shadowlab_shadow::lanes::LANES;
use shadowlab_shadow::logarithmic::LogarithmicMap;
use shadowlab_shadow::paraboloid::ParaboloidMap;
use shadowlab_shadow::{LightSetup, ShadowMapping};

use crate::exact_sum::ExactSum;
use crate::hypot::hypot;
use block::footprint_block;

mod block;

/// Below this `cos β` (the surface within 0.057° of edge-on to the light's rays) a point has no
/// footprint: a texel's shaft of light meets the surface along a line, `det J → 0` for every map,
/// and rounding alone decides how large the quotient comes out (1e16 and more on the vertical
/// faces of `outdoor` under a light straight above). Such points are lit or shadowed by their
/// facing, not by the map's resolution, so the statistics leave them out — as CG06's optimizer
/// leaves grazed samples out of h (`shadowlab_shadow::optimal::GRAZING_COS`, the same value).
pub const GRAZING_COS: f64 = 1e-3;

/// How many pixels one shadow-map texel covers on screen, and its two factors (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Pixels per texel along the texel image's longest direction: `σ_max(J⁻¹)`.
    pub total: f64,
    /// `total / projection`.
    pub perspective: f64,
    /// `cos α / cos β`: α between the normal and the ray to the eye, β between the normal and the
    /// light's ray.
    pub projection: f64,
}

/// The local geometry of one visible point: `J`, `cos α`, `cos β`.
struct Local {
    jacobian: DMat2,
    cos_alpha: f64,
    cos_beta: f64,
}

/// A mapping prepared for many derivatives.
enum Prepared<'a> {
    /// World → GL clip space.
    Projective(DMat4),
    /// The logarithmic map, differentiated in closed form.
    Logarithmic(&'a LogarithmicMap),
    /// A paraboloid hemisphere, differentiated in closed form.
    Paraboloid(&'a ParaboloidMap),
}

impl<'a> Prepared<'a> {
    fn new(mapping: &'a ShadowMapping) -> Self {
        match mapping {
            ShadowMapping::Logarithmic(map) => Self::Logarithmic(map),
            ShadowMapping::Paraboloid(map) => Self::Paraboloid(map),
            ShadowMapping::Projective(mapping) => Self::Projective(mapping.clip_from_world()),
        }
    }

    /// The mapping at `point`, ready for derivatives there; `None` where it does not map the
    /// point (behind a projective map's centre).
    fn at(&self, point: DVec3) -> Option<At<'_>> {
        match self {
            Self::Projective(m) => {
                let clip = *m * point.extend(1.0);
                if clip.w <= 0.0 {
                    return None;
                }
                Some(At::Projective { m, clip })
            }
            Self::Logarithmic(map) => Some(At::Logarithmic { map, point }),
            Self::Paraboloid(map) => Some(At::Paraboloid { map, point }),
        }
    }
}

/// A mapping at one point: what its derivatives there share.
enum At<'a> {
    /// A projective map and the point's clip coordinates (`w` not `≤ 0`).
    Projective { m: &'a DMat4, clip: DVec4 },
    /// The logarithmic map and the point.
    Logarithmic {
        map: &'a LogarithmicMap,
        point: DVec3,
    },
    /// A paraboloid hemisphere and the point.
    Paraboloid {
        map: &'a ParaboloidMap,
        point: DVec3,
    },
}

impl At<'_> {
    /// The derivative of the window coordinates `(x, y)` along `direction` (per unit, window
    /// units); `None` where the logarithmic map has none. Inlined into [`local`], so that its
    /// three calls' chains of products and divisions overlap (docs/benchmarks.md).
    #[inline(always)]
    fn derivative(&self, direction: DVec3) -> Option<DVec2> {
        match self {
            Self::Projective { m, clip: p } => {
                let dp = **m * direction.extend(0.0);
                // Window = (ndc + 1)/2: half the derivative of p_k/p_w.
                let d = |k: usize| quotient(0.5 * (dp[k] * p.w - p[k] * dp.w), p.w * p.w);
                Some(DVec2::new(d(0), d(1)))
            }
            // Window = (ndc + 1)/2.
            Self::Logarithmic { map, point } => Some(map.ndc_derivative(*point, direction)? * 0.5),
            Self::Paraboloid { map, point } => Some(map.ndc_derivative(*point, direction)? * 0.5),
        }
    }
}

/// What [`local`] reads of a camera, taken once per image: its eye and axes, and one pixel's
/// step across and up per unit of depth.
struct Viewer {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    /// `2·tan(fov_x/2)/width`.
    step_x: f64,
    /// `2·tan(fov_y/2)/height`.
    step_y: f64,
}

impl Viewer {
    fn new(camera: &Camera) -> Self {
        let tan_y = camera.projection.tan_half_fov_y();
        let tan_x = tan_y * camera.projection.aspect();
        Self {
            eye: camera.pose.eye(),
            forward: camera.pose.forward(),
            right: camera.pose.right(),
            up: camera.pose.up(),
            step_x: 2.0 * tan_x / f64::from(camera.width),
            step_y: 2.0 * tan_y / f64::from(camera.height),
        }
    }
}

/// `J`, `cos α` and `cos β` at `point` with `normal` (module docs); `None` where undefined.
fn local(
    mapping: &Prepared<'_>,
    resolution: u32,
    viewer: &Viewer,
    point: DVec3,
    normal: DVec3,
) -> Option<Local> {
    let n = normal.try_normalize()?;
    let to_point = point - viewer.eye;
    let depth = to_point.dot(viewer.forward);
    let facing = to_point.dot(n);
    if depth <= 0.0 || facing == 0.0 || !facing.is_finite() {
        return None;
    }
    // One pixel's step of the eye ray at the point's depth, then onto the plane.
    let across = viewer.right * (viewer.step_x * depth);
    let up = viewer.up * (viewer.step_y * depth);
    let on_plane = |step: DVec3| step - to_point * (step.dot(n) / facing);
    let (t1, t2) = (on_plane(across), on_plane(up));
    let distance = to_point.length();
    let texels = f64::from(resolution);
    let at = mapping.at(point)?;
    let d1 = at.derivative(t1)? * texels;
    let d2 = at.derivative(t2)? * texels;
    let dn = at.derivative(n)? * texels;
    // The light's ray: c·(t1, t2, n) with Du·(t1, t2, n)·c = 0, c ⟂ both rows of Du there.
    let c = DVec3::new(d1.x, d2.x, dn.x).cross(DVec3::new(d1.y, d2.y, dn.y));
    let ray = t1 * c.x + t2 * c.y + n * c.z;
    let local = Local {
        jacobian: DMat2::from_cols(d1, d2),
        cos_alpha: facing.abs() / distance,
        cos_beta: ray.dot(n).abs() / ray.length(),
    };
    (local.jacobian.is_finite() && local.cos_beta.is_finite()).then_some(local)
}

/// The Jacobian `J = ∂u/∂x` (texels per pixel; columns `∂u/∂x₁`, `∂u/∂x₂`) of the map from the
/// window coordinates of `camera`'s image to the texel coordinates of `setup`'s map of side
/// `resolution`, at the visible point `point` on the surface plane with normal `normal` (module
/// docs). `None` where undefined: a zero normal, a point not in front of the eye, a plane seen
/// edge-on, a point the mapping does not map.
#[must_use]
pub fn texel_jacobian(
    setup: &LightSetup,
    resolution: u32,
    camera: &Camera,
    point: DVec3,
    normal: DVec3,
) -> Option<DMat2> {
    local(
        &Prepared::new(&setup.mapping),
        resolution,
        &Viewer::new(camera),
        point,
        normal,
    )
    .map(|l| l.jacobian)
}

/// The footprint of `setup`'s texels (map side `resolution`) at the visible point `point` with
/// surface normal `normal`, seen by `camera` (its pose, projection and image size). `None` where
/// [`texel_jacobian`] is undefined or the plane is edge-on to the light (`cos β` below
/// [`GRAZING_COS`], where the footprint is unbounded and the factors undefined).
#[must_use]
pub fn footprint(
    setup: &LightSetup,
    resolution: u32,
    camera: &Camera,
    point: DVec3,
    normal: DVec3,
) -> Option<Footprint> {
    let local = local(
        &Prepared::new(&setup.mapping),
        resolution,
        &Viewer::new(camera),
        point,
        normal,
    )?;
    footprint_of(&local)
}

/// The footprint from the local geometry.
fn footprint_of(local: &Local) -> Option<Footprint> {
    let j = local.jacobian;
    let (a, b, c, d) = (j.x_axis.x, j.y_axis.x, j.x_axis.y, j.y_axis.y);
    let sigma_max = 0.5 * (hypot(a + d, c - b) + hypot(a - d, b + c));
    let total = sigma_max / j.determinant().abs();
    if local.cos_beta < GRAZING_COS {
        return None;
    }
    let projection = local.cos_alpha / local.cos_beta;
    (total.is_finite() && projection.is_finite() && projection > 0.0).then(|| Footprint {
        total,
        perspective: total / projection,
        projection,
    })
}

/// [`footprint`] at every visible pixel of `eye` (the eye pass of `camera`, which gives the pixel
/// size) with its position and interpolated normal; parallel, and the same on any thread count.
#[must_use]
pub fn footprints(
    setup: &LightSetup,
    resolution: u32,
    eye: &EyeImage,
    camera: &Camera,
) -> FrameFootprints {
    footprints_served(&[(setup, resolution)], eye, camera, |_| Some(0))
}

/// [`footprints`] through one of several maps per pixel — `maps[k]` being a setup and its map
/// side, `serving(pixel)` the index of the map that serves pixel `pixel` (`None`: no footprint):
/// each pixel's footprint is computed once, through its own map, as a partitioned shadow looks it
/// up. Four visible pixels in a row of the visible pixels, served by one map, are measured side by
/// side (the `block` module: the same bits as one by one).
///
/// # Panics
/// If `eye` holds `2³²` pixels or more (a side is at most `MAX_IMAGE_SIDE`, 16384).
#[must_use]
pub fn footprints_served(
    maps: &[(&LightSetup, u32)],
    eye: &EyeImage,
    camera: &Camera,
    serving: impl Fn(usize) -> Option<usize> + Sync,
) -> FrameFootprints {
    let mappings: Vec<(Prepared<'_>, u32)> = maps
        .iter()
        .map(|&(setup, resolution)| (Prepared::new(&setup.mapping), resolution))
        .collect();
    let viewer = Viewer::new(camera);
    let visible: Vec<u32> = gather_map(&eye.triangle, 0, |pixel, &triangle| {
        (triangle != NO_TRIANGLE)
            .then(|| u32::try_from(pixel).expect("an eye image holds fewer than 2³² pixels"))
    });
    // The index of the map serving a visible pixel.
    let map_of = |pixel: usize| serving(pixel).filter(|&index| index < mappings.len());
    let one = |pixel: usize| {
        let (mapping, resolution) = &mappings[map_of(pixel)?];
        footprint_of(&local(
            mapping,
            *resolution,
            &viewer,
            eye.position[pixel],
            eye.normal[pixel],
        )?)
    };
    let block = |pixels: &[u32]| -> [Option<Footprint>; LANES] {
        let Ok(four) = <[u32; LANES]>::try_from(pixels) else {
            return std::array::from_fn(|k| pixels.get(k).and_then(|&p| one(p as usize)));
        };
        let four = four.map(|p| p as usize);
        let served = four.map(map_of);
        match served[0] {
            Some(index) if served.iter().all(|&s| s == Some(index)) => {
                let (setup, resolution) = maps[index];
                footprint_block(
                    setup.mapping.in_lanes(),
                    resolution,
                    &viewer,
                    &four.map(|p| eye.position[p]),
                    &four.map(|p| eye.normal[p]),
                )
            }
            _ => four.map(one),
        }
    };
    // Written once, by the workers: an indexed collect fills its vector in place.
    let blocks: Vec<[[f64; 3]; LANES]> = visible
        .par_chunks(LANES)
        .map(|pixels| {
            block(pixels).map(|footprint| {
                footprint.map_or([f64::NAN; 3], |f| [f.total, f.perspective, f.projection])
            })
        })
        .collect();
    let mut parts = blocks.into_flattened();
    parts.truncate(visible.len());
    FrameFootprints {
        pixels: eye.triangle.len(),
        visible,
        parts,
    }
}

/// The texel footprints of an eye image's pixels, held for its visible pixels alone — the total,
/// perspective and projection parts, all NaN where a visible pixel has no footprint (a
/// [`Footprint`]'s parts are never NaN) — in pixel order: 28 bytes a visible pixel with its
/// index, where one `Option<Footprint>` for every pixel takes 32 a pixel. A study writes and reads
/// one of these per combination, so its size is time (docs/benchmarks.md).
#[derive(Clone, Debug)]
pub struct FrameFootprints {
    /// The pixels of the image.
    pixels: usize,
    /// The visible pixels, ascending.
    visible: Vec<u32>,
    /// Per visible pixel, [`Footprint::total`], [`Footprint::perspective`] and
    /// [`Footprint::projection`]; NaN where it has none.
    parts: Vec<[f64; 3]>,
}

impl FrameFootprints {
    /// No footprint at any of `pixels` pixels.
    #[must_use]
    pub fn none(pixels: usize) -> Self {
        Self {
            pixels,
            visible: Vec::new(),
            parts: Vec::new(),
        }
    }

    /// Each pixel's footprint, in the image's order (row-major, row 0 at the bottom): `None` where
    /// nothing is visible or the footprint is undefined.
    pub fn each_pixel(&self) -> impl Iterator<Item = Option<Footprint>> + '_ {
        let mut visible = self.visible.iter().enumerate().peekable();
        (0..self.pixels).map(move |pixel| {
            let (k, _) = visible.next_if(|&(_, &p)| p as usize == pixel)?;
            let [total, perspective, projection] = self.parts[k];
            (!total.is_nan()).then_some(Footprint {
                total,
                perspective,
                projection,
            })
        })
    }

    /// The statistics of the total, perspective and projection parts, in that order ([`stats`]),
    /// from one read of the footprints.
    #[must_use]
    pub fn stats(&self) -> [AliasingStats; 3] {
        stats_of_each(&self.parts, |parts| parts.map(Some))
    }
}

/// Summary of a set of aliasing values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AliasingStats {
    /// The largest value.
    pub max: f64,
    /// The 99th percentile by nearest rank: the `⌈0.99·count⌉`-th smallest value.
    pub p99: f64,
    /// The arithmetic mean: the exact sum rounded once (a long fixed-point accumulator), divided
    /// by the count.
    pub mean: f64,
    /// How many values were summarised.
    pub count: u64,
}

/// Values per parallel work item of the statistics. Any size gives the same result: the sum is
/// exact, and the maximum, the counts and the selected percentile are integers or unique in the
/// total order.
const STATS_CHUNK: usize = 1 << 14;
/// Bits of the key by which one pass of the percentile's selection buckets the candidates.
const SELECT_DIGIT_BITS: u32 = 11;
/// Candidates few enough to be selected among directly, on one thread: each counting pass reads
/// every key again, and `select_nth_unstable` of this many costs less than such a pass
/// (docs/benchmarks.md, "Store-forwarding stalls": the footprint statistics at 2¹² and 2¹⁶).
const SELECT_DIRECT: usize = 1 << 16;
/// Counts per bucket in one counting pass of the selection, taken by its keys in turn (at most
/// [`STATS_CHUNK`] keys a chunk, so each fits in a `u32`).
const TALLIES: usize = 4;

/// The maximum, 99th percentile (nearest rank: the `⌈0.99·n⌉`-th smallest of `n` values, no
/// interpolation; values ordered by `f64::total_cmp`) and mean of `values`, NaNs left out (and not
/// counted). Deterministic: each statistic depends on the multiset of values only, not on their
/// order — the mean is their exact sum, rounded once, over their count. With no values, every
/// field is 0.
#[must_use]
pub fn stats(values: impl Iterator<Item = f64>) -> AliasingStats {
    let values: Vec<f64> = values.collect();
    stats_of(&values, |&value| Some(value))
}

/// The key of a value: an integer that orders as `f64::total_cmp` orders the values (negatives'
/// bits inverted, positives' sign bit set), undone by [`value_of_key`].
fn key_of(value: f64) -> u64 {
    let bits = value.to_bits();
    bits ^ ((bits >> 63).wrapping_neg() | (1 << 63))
}

/// The value whose key is `key` ([`key_of`]).
fn value_of_key(key: u64) -> f64 {
    f64::from_bits(key ^ ((key >> 63).wrapping_sub(1) | (1 << 63)))
}

/// [`stats`] of `value(item)` over `items` (`None` and NaN left out), in parallel and in place:
/// [`stats_of_each`] of the one value.
#[must_use]
pub fn stats_of<T: Sync>(items: &[T], value: impl Fn(&T) -> Option<f64> + Sync) -> AliasingStats {
    let [stats] = stats_of_each(items, |item| [value(item)]);
    stats
}

/// [`stats`] of each of the `N` values `values(item)` gives over `items` (`None` and NaN left
/// out), in parallel and in place, the items read once for all `N`: each chunk of `STATS_CHUNK`
/// items lists each value and takes their maximum (by their keys, integers that order as
/// `f64::total_cmp` orders the values) and exact sum; each percentile is then selected among the
/// chunks' values by a radix selection of their keys whose bucket counts are taken in parallel,
/// without gathering them into one list — no pass over all values runs on one thread.
#[must_use]
pub fn stats_of_each<T: Sync, const N: usize>(
    items: &[T],
    values: impl Fn(&T) -> [Option<f64>; N] + Sync,
) -> [AliasingStats; N] {
    let chunks: Vec<[ChunkStats; N]> = items
        .par_chunks(STATS_CHUNK)
        .map(|chunk| {
            // Room for every item: most have every value (a frame's footprints are held for its
            // visible pixels alone), and growing the vectors copied them again and again.
            let mut listed: [Vec<f64>; N] =
                std::array::from_fn(|_| Vec::with_capacity(chunk.len()));
            for item in chunk {
                for (listed, value) in listed.iter_mut().zip(values(item)) {
                    if let Some(value) = value.filter(|v| !v.is_nan()) {
                        listed.push(value);
                    }
                }
            }
            listed.map(|values| ChunkStats {
                max: values.iter().map(|&value| key_of(value)).max(),
                sum: ExactSum::of(&values),
                values,
            })
        })
        .collect();
    let mut parts: [Vec<ChunkStats>; N] = std::array::from_fn(|_| Vec::with_capacity(chunks.len()));
    for chunk in chunks {
        for (part, stats) in parts.iter_mut().zip(chunk) {
            part.push(stats);
        }
    }
    parts.map(summary)
}

/// The statistics of the values whose chunks are `chunks` ([`stats_of_each`]).
fn summary(chunks: Vec<ChunkStats>) -> AliasingStats {
    let Some(max) = chunks.iter().filter_map(|chunk| chunk.max).max() else {
        return AliasingStats {
            max: 0.0,
            p99: 0.0,
            mean: 0.0,
            count: 0,
        };
    };
    let n: usize = chunks.iter().map(|chunk| chunk.values.len()).sum();
    let rank = (99 * n).div_ceil(100);
    let values: Vec<&[f64]> = chunks.iter().map(|chunk| chunk.values.as_slice()).collect();
    let p99 = select(&values, n, rank - 1);
    let sum = chunks
        .into_iter()
        .fold(ExactSum::new(), |total, chunk| total.merged(chunk.sum));
    #[expect(
        clippy::cast_precision_loss,
        reason = "pixel counts are far below 2^53"
    )]
    let mean = sum.value() / n as f64;
    AliasingStats {
        max: value_of_key(max),
        p99: value_of_key(p99),
        mean,
        count: n as u64,
    }
}

/// What [`stats_of_each`] keeps of one chunk of one value.
struct ChunkStats {
    /// The values, in the chunk's order.
    values: Vec<f64>,
    /// The largest key.
    max: Option<u64>,
    /// The values' exact sum.
    sum: ExactSum,
}

/// The key of rank `rank` (0 the smallest) among the keys ([`key_of`]) of the `count` values of
/// `chunks`: a most-significant-digit radix selection. Each pass counts, in parallel, the
/// candidates — the keys that share the digits decided so far — by their next
/// [`SELECT_DIGIT_BITS`] bits, and keeps the bucket that holds the rank; once at most
/// [`SELECT_DIRECT`] candidates are left they are gathered and selected among directly. The counts
/// are integers, so the answer does not depend on the split.
fn select(chunks: &[&[f64]], count: usize, mut rank: usize) -> u64 {
    // The top `decided` bits of the answer are those of `prefix`; `candidates` keys share them.
    let (mut prefix, mut decided, mut candidates) = (0_u64, 0_u32, count);
    let shares = |key: u64, prefix: u64, decided: u32| {
        decided == 0 || key >> (64 - decided) == prefix >> (64 - decided)
    };
    while candidates > SELECT_DIRECT && decided < 64 {
        let bits = SELECT_DIGIT_BITS.min(64 - decided);
        let shift = 64 - decided - bits;
        let digit_mask = (1_u64 << bits) - 1;
        let digit_of = |key: u64| usize::try_from((key >> shift) & digit_mask).expect("11 bits");
        let buckets = chunks
            .par_iter()
            .map(|values| {
                // TALLIES counts per bucket, each key adding to the next in turn: a run of keys in
                // one bucket (neighbouring pixels' values are alike) would otherwise wait on its
                // own last increment, through memory, key after key.
                let mut tallies = vec![[0_u32; TALLIES]; 1 << bits];
                let mut tally = |lane: usize, value: f64| {
                    let key = key_of(value);
                    tallies[digit_of(key)][lane] += u32::from(shares(key, prefix, decided));
                };
                let mut groups = values.chunks_exact(TALLIES);
                for group in &mut groups {
                    for (lane, &value) in group.iter().enumerate() {
                        tally(lane, value);
                    }
                }
                for &value in groups.remainder() {
                    tally(0, value);
                }
                tallies
                    .into_iter()
                    .map(|counts| counts.into_iter().map(|c| c as usize).sum::<usize>())
                    .collect::<Vec<usize>>()
            })
            .reduce(
                || vec![0; 1 << bits],
                |mut total, part| {
                    total.iter_mut().zip(part).for_each(|(t, p)| *t += p);
                    total
                },
            );
        let mut digit = 0;
        while rank >= buckets[digit] {
            rank -= buckets[digit];
            digit += 1;
        }
        prefix |= (digit as u64) << shift;
        decided += bits;
        candidates = buckets[digit];
    }
    let mut left: Vec<u64> = chunks
        .par_iter()
        .flat_map_iter(|values| {
            values
                .iter()
                .map(|&value| key_of(value))
                .filter(move |&key| shares(key, prefix, decided))
        })
        .collect();
    *left.select_nth_unstable(rank).1
}
