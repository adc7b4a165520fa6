//! What a filterable map (VSM, ESM, EVSM, MSM) gets wrong that the plain depth test of the same map
//! gets right (issue 16): its **light leaks** — pairs it lights where the point is in shadow and
//! the nearest-texel lookup of the same map, with the same bias, shadows it — and its
//! **over-darkening** — pairs it shadows where the point is lit and the nearest lookup lights it;
//! the leaks' **extent**, each leaking pixel's distance to the nearest edge of the true shadow; and
//! the **memory** the method stores per texel, at its storage's precision.
//!
//! A pair is judged as [`crate::classify`] judges it (visible, inside the light's cone; lit at a
//! fraction of at least [`LIT_THRESHOLD`]), so a leak here is also counted in the combination's
//! falsely lit pairs. What this adds is the attribution to the filter: a falsely lit pair the
//! nearest lookup gets wrong too is the map's (aliasing, bias), not the filter's.
//!
//! # The extent
//! An edge pixel of light `l`'s true shadow is a judged pixel with a 4-neighbour that is judged and
//! differs from it in truth. A leaking pixel's extent is the Euclidean distance, in pixels between
//! centres, to the nearest edge pixel of its light (exact: the squared distance transform of
//! Felzenszwalb & Huttenlocher, *Distance transforms of sampled functions*, Theory of Computing
//! 8(19), 2012, §2.1, one dimension at a time). A leak far from every edge is light through the
//! middle of a shadow, the failure filterable maps are known for (VSM's on stacked occluders); one
//! at the edge is the penumbra their prefilter is meant to give.

use rayon::prelude::*;
use shadowlab_params::FilterableMethod;
use shadowlab_shadow::{Filter, Storage};

use crate::aliasing::{AliasingStats, stats_of};
use crate::truth::{LIT_THRESHOLD, Truth};

/// A filterable method and where its map holds its moments: what a texel of it stores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StoredMethod {
    /// The method.
    pub method: FilterableMethod,
    /// The moments' storage ([`Storage::Exact`] is reported as 32-bit moments).
    pub storage: Storage,
}

impl StoredMethod {
    /// Bytes per texel: the method's moments times the storage's bytes per moment (2 for f16, 4 for
    /// f32 and for exact moments).
    #[must_use]
    pub fn bytes_per_texel(self) -> u32 {
        u32::try_from(self.method.moments_per_texel()).unwrap_or(u32::MAX)
            * self.storage.bytes_per_moment()
    }
}

/// A filterable map's errors against the nearest lookup of the same map (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterLeaks {
    /// The method.
    pub method: FilterableMethod,
    /// Where the method's moments are held.
    pub storage: Storage,
    /// Judged pairs the filter lights, the truth shadows and the nearest lookup shadows.
    pub leaks: u64,
    /// Judged pairs the filter shadows, the truth lights and the nearest lookup lights.
    pub over_darkening: u64,
    /// The leaking pixels' distances to the nearest true shadow edge of their light, in pixels
    /// (max, 99th percentile, mean; every leaking pair counts once).
    pub extent: AliasingStats,
    /// Bytes the method stores per texel ([`StoredMethod::bytes_per_texel`]).
    pub bytes_per_texel: u32,
}

/// The filterable method a filter reads with and the storage of its moments, if it is one.
#[must_use]
pub fn filterable_method(filter: &Filter) -> Option<StoredMethod> {
    match filter {
        Filter::Vsm { prefilter, .. } => Some(StoredMethod {
            method: FilterableMethod::Vsm,
            storage: prefilter.storage,
        }),
        Filter::Moments {
            method, prefilter, ..
        } => Some(StoredMethod {
            method: method.method(),
            storage: prefilter.storage,
        }),
        Filter::Nearest | Filter::Pcf { .. } | Filter::Disk { .. } => None,
    }
}

/// The leaks of `stored`'s lookups `filtered` against the `nearest` lookups of the same maps (each
/// per light, per pixel, as [`shadowlab_shadow::Shadows::lit`]) and `truth`, on an image `width`
/// pixels wide.
///
/// # Panics
/// If the lookups do not have the truth's lights and pixels.
#[must_use]
pub fn filter_leaks(
    truth: &Truth,
    width: usize,
    stored: StoredMethod,
    (filtered, nearest): (&[Vec<f64>], &[Vec<f64>]),
) -> FilterLeaks {
    assert!(
        filtered.len() == truth.lit.len() && nearest.len() == truth.lit.len(),
        "one lookup per light"
    );
    let mut leaks = 0;
    let mut over_darkening = 0;
    let mut extents = Vec::new();
    for (light, truly) in truth.lit.iter().enumerate() {
        let outside = &truth.outside_cone[light];
        let judged = |pixel: usize| truly[pixel].filter(|_| !outside[pixel]);
        let edges = edge_distances(width, truly.len() / width.max(1), &judged);
        let (light_leaks, light_over, light_extents) = (0..truly.len())
            .into_par_iter()
            .filter_map(|pixel| {
                let truly_lit = judged(pixel)?;
                let lit = filtered[light][pixel] >= LIT_THRESHOLD;
                let nearest_lit = nearest[light][pixel] >= LIT_THRESHOLD;
                match (truly_lit, lit, nearest_lit) {
                    (false, true, false) => Some((1, 0, Some(edges[pixel].sqrt()))),
                    (true, false, true) => Some((0, 1, None)),
                    _ => None,
                }
            })
            .fold(
                || (0u64, 0u64, Vec::new()),
                |(l, o, mut e), (dl, dov, extent)| {
                    e.extend(extent);
                    (l + dl, o + dov, e)
                },
            )
            .reduce(
                || (0, 0, Vec::new()),
                |(l1, o1, mut e1), (l2, o2, e2)| {
                    e1.extend(e2);
                    (l1 + l2, o1 + o2, e1)
                },
            );
        leaks += light_leaks;
        over_darkening += light_over;
        extents.extend(light_extents);
    }
    FilterLeaks {
        method: stored.method,
        storage: stored.storage,
        leaks,
        over_darkening,
        // The statistics depend on the multiset of distances only, whatever order they came in.
        extent: stats_of(&extents, |&extent| Some(extent)),
        bytes_per_texel: stored.bytes_per_texel(),
    }
}

/// The squared distance, in pixels, from each pixel of a `width × height` image to the nearest edge
/// of the true shadow that `judged` describes (module docs); infinite where there is no edge.
fn edge_distances(
    width: usize,
    height: usize,
    judged: &(impl Fn(usize) -> Option<bool> + Sync),
) -> Vec<f64> {
    let differs =
        |a: usize, b: usize| matches!((judged(a), judged(b)), (Some(x), Some(y)) if x != y);
    let mut squared: Vec<f64> = (0..width * height)
        .into_par_iter()
        .map(|pixel| {
            let (x, y) = (pixel % width, pixel / width);
            let edge = (x > 0 && differs(pixel, pixel - 1))
                || (x + 1 < width && differs(pixel, pixel + 1))
                || (y > 0 && differs(pixel, pixel - width))
                || (y + 1 < height && differs(pixel, pixel + width));
            if edge { 0.0 } else { f64::INFINITY }
        })
        .collect();
    // Rows, then columns (through a transpose): each line's transform depends on that line alone.
    squared.par_chunks_mut(width.max(1)).for_each(distance_1d);
    let mut columns = transpose(&squared, width, height);
    columns.par_chunks_mut(height.max(1)).for_each(distance_1d);
    transpose(&columns, height, width)
}

/// `image` (`width` values per row) with rows and columns exchanged.
fn transpose(image: &[f64], width: usize, height: usize) -> Vec<f64> {
    let mut out = vec![0.0; image.len()];
    out.par_chunks_mut(height.max(1))
        .enumerate()
        .for_each(|(x, column)| {
            for (y, value) in column.iter_mut().enumerate() {
                *value = image[y * width + x];
            }
        });
    out
}

/// The 1-D squared distance transform in place: `f(q) ← min_p (q − p)² + f(p)`, by the lower
/// envelope of the parabolas rooted at the finite samples (Felzenszwalb & Huttenlocher 2012,
/// Algorithm 1), exact for integer positions and the sums of squares of integers below 2⁵³ that
/// image sizes give.
fn distance_1d(f: &mut [f64]) {
    let n = f.len();
    let roots: Vec<usize> = (0..n).filter(|&q| f[q].is_finite()).collect();
    if roots.is_empty() {
        return;
    }
    #[expect(
        clippy::cast_precision_loss,
        reason = "positions are image coordinates"
    )]
    let at = |q: usize| q as f64;
    // The parabola rooted at p, evaluated where it meets the one rooted at r (p < r).
    let meet = |f: &[f64], p: usize, r: usize| {
        ((f[r] + at(r) * at(r)) - (f[p] + at(p) * at(p))) / (2.0 * (at(r) - at(p)))
    };
    let mut hull: Vec<usize> = Vec::with_capacity(roots.len());
    let mut bounds: Vec<f64> = Vec::with_capacity(roots.len() + 1);
    for &r in &roots {
        while let Some(&p) = hull.last() {
            if hull.len() > 1 && meet(f, p, r) <= bounds[hull.len() - 1] {
                hull.pop();
                bounds.pop();
            } else {
                break;
            }
        }
        if let Some(&p) = hull.last() {
            bounds.push(meet(f, p, r));
        } else {
            bounds.push(f64::NEG_INFINITY);
        }
        hull.push(r);
    }
    let values: Vec<f64> = hull.iter().map(|&p| f[p]).collect();
    let mut k = 0;
    for (q, value) in f.iter_mut().enumerate() {
        while k + 1 < hull.len() && bounds[k + 1] < at(q) {
            k += 1;
        }
        let d = at(q) - at(hull[k]);
        *value = d * d + values[k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: the least squared distance to a finite sample.
    fn brute(f: &[f64]) -> Vec<f64> {
        (0..f.len())
            .map(|q| {
                (0..f.len())
                    .filter(|&p| f[p].is_finite())
                    .map(|p| {
                        let d = q as f64 - p as f64;
                        d * d + f[p]
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    #[test]
    fn the_1d_transform_is_the_lower_envelope() {
        // Seeded patterns of seeds (value 0) and their absence, and finite non-zero values.
        let mut state = 0x4c45_414b_u64; // "LEAK"
        for _ in 0..200 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            let n = 1 + (state >> 58) as usize;
            let f: Vec<f64> = (0..n)
                .map(|k| match (state >> (k % 60)) & 3 {
                    0 => 0.0,
                    1 => ((state >> 20) % 7) as f64,
                    _ => f64::INFINITY,
                })
                .collect();
            let mut got = f.clone();
            distance_1d(&mut got);
            assert_eq!(got, brute(&f), "{f:?}");
        }
    }

    #[test]
    fn edge_distances_are_euclidean_to_the_shadows_border() {
        // A 7 × 5 image, lit left of x = 3, shadowed from x = 3 on; the pixel at (6, 4) unjudged.
        let (width, height) = (7, 5);
        let judged = |pixel: usize| {
            let (x, y) = (pixel % width, pixel / width);
            (x != 6 || y != 4).then_some(x < 3)
        };
        let squared = edge_distances(width, height, &judged);
        for (pixel, &got) in squared.iter().enumerate() {
            let x = pixel % width;
            let expected = if x < 3 { 2 - x } else { x - 3 } as f64;
            assert_eq!(got, expected * expected, "pixel {pixel}");
        }
    }

    #[test]
    fn leaks_are_the_filters_errors_the_nearest_lookup_gets_right() {
        // One light, four pixels in a row: shadowed, shadowed, lit, lit in truth.
        let truth = Truth {
            lit: vec![vec![Some(false), Some(false), Some(true), Some(true)]],
            outside_cone: vec![vec![false; 4]],
        };
        // The filter lights pixel 0 (nearest right: a leak) and 1 (nearest wrong too: the map's),
        // and shadows pixel 3 (nearest right: over-darkening).
        let filtered = [vec![0.9, 0.6, 1.0, 0.1]];
        let nearest = [vec![0.0, 1.0, 1.0, 1.0]];
        let msm = StoredMethod {
            method: FilterableMethod::Msm,
            storage: Storage::Exact,
        };
        let leaks = filter_leaks(&truth, 4, msm, (&filtered, &nearest));
        assert_eq!((leaks.leaks, leaks.over_darkening), (1, 1));
        // Pixel 0 is one pixel from the edge pixel 1 (whose neighbour 2 is lit).
        assert_eq!(leaks.extent.max, 1.0);
        assert_eq!(leaks.extent.count, 1);
        assert_eq!(leaks.bytes_per_texel, 16);
    }

    #[test]
    fn bytes_per_texel_follow_the_storage() {
        let bytes = |spec: &str| {
            filterable_method(&Filter::parse(spec).unwrap())
                .expect("a filterable map")
                .bytes_per_texel()
        };
        // Exact moments are reported as 32-bit ones, as before the storage knob.
        assert_eq!(bytes("vsm:5"), 8);
        assert_eq!(bytes("vsm:5@f32"), 8);
        assert_eq!(bytes("vsm:5@gauss@f16"), 4);
        assert_eq!(bytes("esm:3,80@f16"), 2);
        assert_eq!(bytes("evsm4:3,11.08,11.08"), 16);
        assert_eq!(bytes("evsm4:3,11.08,11.08@f16"), 8);
        assert_eq!(bytes("msm:3,6e-5@f16"), 8);
        assert_eq!(filterable_method(&Filter::parse("pcf:3").unwrap()), None);
    }
}
