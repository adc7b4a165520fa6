//! Grids of parallel rays — a shadow map's texel rays under a directional light — answered
//! triangle by triangle instead of ray by ray.
//!
//! # The sweep
//! Seen along the rays' common axis, a grid of parallel rays is a grid of points on a plane and
//! each triangle a 2-D triangle (its *image*). Rather than each ray descending the tree, each
//! triangle finds, row by row, the rays whose points lie near its image — binary searches in the
//! row's points, which are sorted along it — and only those rays run the crate's ray–triangle test
//! ([`triangle::intersect`]) against it, keeping the nearest hit by the tree's rule (smaller `t`,
//! then smaller index). A rasterizer's loop, with the exact test where a rasterizer samples. Rows
//! are taken a few at a time ([`GRID_CHUNK`] rays, whole rows) in parallel; each work item finds
//! the triangles whose images reach its rows through a 1-D bucket index over the images' extents
//! across the rows.
//!
//! # Why each answer is the brute-force answer
//! A ray is given the hit of smallest `t` (then smallest index) among the triangles it is tested
//! against, by the same test as [`Bvh::intersect_triangle`]; so its answer is the brute-force one
//! if every triangle whose test reports a hit is among them. By the `bvh` module's argument (step
//! 1), a reported hit on a triangle `T` means a point `Q` of the exact `T` and a point `P` of the
//! exact ray's line with `|P − Q| ≤ √2·7u·R`, `u = ε/2`, `R = M + |o|∞` (`M` the mesh's
//! magnitude, `o` the ray's origin). Let `L` be the linear map onto the plane, `p ↦ (p·e₁, p·e₂)`
//! with the computed (unit within `2u`) axes across the rays, so `‖L‖ ≤ √2(1 + 2u)`. Then
//!
//! `|L(o) − L(Q)| ≤ |L(P) − L(Q)| + |L(P − o)| ≤ ‖L‖·√2·7u·R + |P − o|·σ·(1 + 2u)`,
//!
//! where `σ = |L(d)|/(d·a)` is the ray's slope against the common axis `a` (the component of
//! `P − o` along `a` is `t·(d·a)`, so `|t|·|L(d)| ≤ |P − o|·σ·|a|`), and `|P − o| ≤ |P| + |o| ≤
//! √3·(M + |o|∞) + |P − Q| < 2R`. The first term is below `21u·R`; the computed images of `o` and
//! of `T`'s vertices, and the clipping and searches below, each round by at most a few `u·R`
//! (every coordinate involved is below `2R`). So with `δ = SLACK·R + 4·R·σ_max` — `SLACK = 10⁻¹²`,
//! about 10⁴ times the roundings' sum — every ray whose test can report `T` has its computed point
//! within `δ` of `T`'s computed image. A row whose points lie across the rows between `b_lo` and
//! `b_hi` can only have such points where the image meets the band `[b_lo − δ, b_hi + δ]`, and
//! then at most `δ` beyond that part's extent along the row; the rays tested are those whose
//! points lie in that extent grown by `δ`. Larger than needed only costs tests: every answer is
//! the brute-force answer, to the bit, whatever the grid.
//!
//! # When the sweep does not apply
//! A grid of fewer than [`RAYS_PER_TRIANGLE`] rays per triangle, and a work item whose rays are
//! not parallel within [`MAX_SLOPE`] of the common axis (a spot light's texel rays, say) or whose
//! rows' points are not sorted along the row, are cast through the tree as [`Bvh::closest_hits`]
//! casts a batch, with the same answers.

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use wide::f64x4;

use crate::error::TraceError;
use crate::ray::{Hit, PreparedRay, PreparedRays, Ray};
use crate::triangle::{self, RAYS, TriangleVertices};

use super::{Bvh, check_range, vertices};

/// Rays per work item of [`Bvh::closest_hits_grid`]: whole rows, at least one. The split depends
/// on this constant only, and each answer on its ray alone: the output is identical for any
/// thread count.
pub const GRID_CHUNK: usize = 1024;

/// The search's slack per unit of `R = M + |o|∞` (module documentation): far above what the
/// roundings of the candidate search add up to, far below a texel.
const SLACK: f64 = 1e-12;

/// The largest slope `|L(d)|/(d·a)` of a ray against the grid's common axis for which a work
/// item is swept; beyond it the slack `4·R·σ` would reach across texels.
const MAX_SLOPE: f64 = 1e-6;

/// What a row's rays are before the caller writes them (an invalid ray, so that one left unset
/// is reported).
const UNSET: Ray = Ray {
    origin: DVec3::ZERO,
    direction: DVec3::ZERO,
};

/// The fewest rays per stored triangle for which a grid is swept; below it the tree's packets
/// are as fast or faster (docs/benchmarks.md: 2048² parallel rays take about as long either way
/// over the bunny's 69 451 triangles, sixty rays per triangle, and 1.4–1.7 times longer swept
/// over the dragon's 871 306, five per triangle; the default scene's logarithmic map, 90 to 630
/// per triangle, is 1.4 times faster swept).
const RAYS_PER_TRIANGLE: usize = 64;

/// The axes of a grid: `axis` along the rays, `along` and `across` its rows, all unit length.
struct Axes {
    axis: DVec3,
    along: DVec3,
    across: DVec3,
}

impl Axes {
    /// The axes of the rays `first` and `last` of the first row: along the first ray, and along
    /// the row as far as the row's spread allows (any perpendicular if it has none).
    fn of(first: &Ray, last: &Ray) -> Self {
        let axis = first.direction.normalize();
        let spread = last.origin - first.origin;
        let along = (spread - axis * spread.dot(axis)).try_normalize();
        let along = along.unwrap_or_else(|| axis.any_orthonormal_vector());
        let across = axis.cross(along).normalize();
        Self {
            axis,
            along,
            across,
        }
    }

    /// A point's coordinates on the plane: along the rows, across them.
    fn plane(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.along), p.dot(self.across))
    }
}

/// A triangle seen along the axis: its vertices' coordinates along (`a`) and across (`b`) the
/// rows, the extent `lo..=hi` of `b`; its index and stored vertices, for the test.
struct Image {
    a: [f64; 3],
    b: [f64; 3],
    lo: f64,
    hi: f64,
    id: u32,
    stored: TriangleVertices,
}

impl Image {
    /// The extent along the rows of the image's part in the band `lo <= b <= hi`: its vertices in
    /// the band and its edges' crossings of the band's lines. `None` if the image misses the
    /// band.
    fn extent(&self, lo: f64, hi: f64) -> Option<(f64, f64)> {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut take = |a: f64| {
            min = min.min(a);
            max = max.max(a);
        };
        for v in 0..3 {
            if lo <= self.b[v] && self.b[v] <= hi {
                take(self.a[v]);
            }
        }
        for (p, q) in [(0, 1), (1, 2), (2, 0)] {
            let (bp, bq) = (self.b[p], self.b[q]);
            for line in [lo, hi] {
                if (bp < line && line < bq) || (bq < line && line < bp) {
                    let f = ((line - bp) / (bq - bp)).clamp(0.0, 1.0);
                    take(self.a[p] + (self.a[q] - self.a[p]) * f);
                }
            }
        }
        (min <= max).then_some((min, max))
    }
}

/// An image's extent across the rows and its index, as a bucket lists it.
#[derive(Clone, Copy)]
struct Entry {
    lo: f64,
    hi: f64,
    image: u32,
}

/// The images in buckets of equal width across the rows: bucket `k` lists the images whose
/// extent `lo..=hi` meets it, in index order, with their extents (so that a scan reads one list).
struct Buckets {
    origin: f64,
    /// Buckets per unit across the rows.
    scale: f64,
    /// `start[k]..start[k + 1]` indexes `entries` for bucket `k`.
    start: Vec<usize>,
    entries: Vec<Entry>,
}

impl Buckets {
    /// `count` buckets (at least one) over the images' extents.
    fn new(images: &[Image], count: usize) -> Self {
        let count = count.max(1);
        let origin = images.iter().map(|i| i.lo).fold(f64::INFINITY, f64::min);
        let end = images
            .iter()
            .map(|i| i.hi)
            .fold(f64::NEG_INFINITY, f64::max);
        #[expect(clippy::cast_precision_loss, reason = "as many buckets as work items")]
        let scale = if end > origin {
            count as f64 / (end - origin)
        } else {
            0.0
        };
        let mut buckets = Self {
            origin,
            scale,
            start: vec![0; count + 1],
            entries: Vec::new(),
        };
        for image in images {
            for k in buckets.bucket(image.lo)..=buckets.bucket(image.hi) {
                buckets.start[k + 1] += 1;
            }
        }
        for k in 0..count {
            buckets.start[k + 1] += buckets.start[k];
        }
        let mut next = buckets.start.clone();
        let unset = Entry {
            lo: 0.0,
            hi: 0.0,
            image: 0,
        };
        buckets.entries = vec![unset; buckets.start[count]];
        for (index, image) in images.iter().enumerate() {
            let entry = Entry {
                lo: image.lo,
                hi: image.hi,
                image: u32::try_from(index).expect("fewer than 2^32 images"),
            };
            let (first, last) = (buckets.bucket(image.lo), buckets.bucket(image.hi));
            for next in &mut next[first..=last] {
                buckets.entries[*next] = entry;
                *next += 1;
            }
        }
        buckets
    }

    fn count(&self) -> usize {
        self.start.len() - 1
    }

    /// The bucket holding `b`, the first or last for values beyond them: monotone in `b`.
    fn bucket(&self, b: f64) -> usize {
        #[expect(clippy::cast_precision_loss, reason = "as many buckets as work items")]
        let last = (self.count() - 1) as f64;
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "clamped to 0..=last"
        )]
        let k = ((b - self.origin) * self.scale).floor().clamp(0.0, last) as usize;
        k
    }

    /// Each image whose extent meets `lo..=hi`, once, from the buckets that hold the band: an
    /// image spanning several of them is taken in the first.
    fn meeting<'a>(
        &'a self,
        images: &'a [Image],
        lo: f64,
        hi: f64,
    ) -> impl Iterator<Item = &'a Image> + 'a {
        let (first, last) = (self.bucket(lo), self.bucket(hi));
        (first..=last).flat_map(move |k| {
            self.entries[self.start[k]..self.start[k + 1]]
                .iter()
                .filter(move |entry| {
                    entry.lo <= hi && entry.hi >= lo && self.bucket(entry.lo).max(first) == k
                })
                .map(|entry| &images[entry.image as usize])
        })
    }
}

/// How many of `sorted` (ascending) lie below `value`, or at most at it with `or_equal`:
/// `partition_point`, started from a guess by linear interpolation between the ends — for a row
/// of evenly spaced points exact or next to it — and walked a few steps, bisecting only if the
/// walk does not end.
fn count_below(sorted: &[f64], value: f64, or_equal: bool) -> usize {
    /// Steps walked from the guess before bisecting.
    const WALK: usize = 4;
    let before = |a: f64| a < value || (or_equal && a == value);
    let n = sorted.len();
    if !before(sorted[0]) {
        return 0;
    }
    if before(sorted[n - 1]) {
        return n;
    }
    // Now the answer k lies in 1..n: before(sorted[k − 1]) and !before(sorted[k]).
    let (first, last) = (sorted[0], sorted[n - 1]);
    #[expect(clippy::cast_precision_loss, reason = "rows are far shorter than 2^52")]
    let guess = (value - first) / (last - first) * (n - 1) as f64;
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "clamped to 1..n − 1 (a NaN guess saturates to 0)"
    )]
    let mut k = (guess as usize).clamp(1, n - 1);
    for _ in 0..WALK {
        if before(sorted[k]) {
            k += 1;
        } else if !before(sorted[k - 1]) {
            k -= 1;
        } else {
            return k;
        }
    }
    sorted.partition_point(|&a| before(a))
}

/// One work item's rays — set up, seen on the plane, row by row — and their answers: buffers a
/// worker reuses from one work item to the next.
#[derive(Default)]
struct Rows {
    rays: Vec<Ray>,
    /// The rays set up, for the sweep.
    prepared: PreparedRays,
    /// The rays set up, for the tree where the sweep does not apply.
    descending: Vec<PreparedRay>,
    /// The points' coordinates along their row.
    along: Vec<f64>,
    /// The points' coordinates across the rows.
    across: Vec<f64>,
    /// Per row, the extent of its points across the rows.
    lo: Vec<f64>,
    hi: Vec<f64>,
    /// The rays' closest hits.
    hits: Vec<Option<Hit>>,
}

impl Bvh {
    /// [`Bvh::closest_hits`] for a grid of parallel rays, `row_len` rays per row, row `j` written
    /// by `row(j, rays)` (its rays, validated here, in order along the row); the answers of a work
    /// item's rays passed to `answer(rays, hits, out)` with the rays, in grid order, to be written
    /// to `out` (ray `(i, j)`'s to `out[j·row_len + i]`; `out` as long as `rays`). Every answer
    /// is [`Bvh::closest_hit`]'s, bit for bit, whatever the rays (the `grid` module); it comes
    /// faster where the rays are parallel, each row's origins lie along it in order and the rays
    /// far outnumber the triangles — a directional light's shadow-map texels over a scene of a
    /// few thousand triangles — by a sweep of the triangles over the rows instead of one descent
    /// of the tree per ray. Parallel (rayon, whole rows of about [`GRID_CHUNK`] rays per work
    /// item); identical for any thread count.
    ///
    /// # Errors
    /// The [`Ray::validate`] error of an invalid ray (of the first in its work item, of some work
    /// item).
    ///
    /// # Panics
    /// If `row_len` is zero or does not divide `out.len()`, or `t_min` or `t_max` is NaN.
    pub fn closest_hits_grid<T: Send>(
        &self,
        row_len: usize,
        row: impl Fn(usize, &mut [Ray]) + Sync,
        t_min: f64,
        t_max: f64,
        out: &mut [T],
        answer: impl Fn(&[Ray], &[Option<Hit>], &mut [T]) + Sync,
    ) -> Result<(), TraceError> {
        check_range(t_min, t_max);
        assert!(
            row_len > 0 && out.len().is_multiple_of(row_len),
            "a grid of {} rays in rows of {row_len}",
            out.len()
        );
        if out.is_empty() {
            return Ok(());
        }
        let mut first_row = vec![UNSET; row_len];
        row(0, &mut first_row);
        let (first, last) = (first_row[0], first_row[row_len - 1]);
        first.validate()?;
        last.validate()?;
        let axes = Axes::of(&first, &last);
        let rows_per_item = (GRID_CHUNK / row_len).max(1);
        let stored = self.triangles.len() - self.degenerate.len();
        let index = (out.len() >= RAYS_PER_TRIANGLE * stored).then(|| {
            let images = self.images(&axes);
            // As many buckets as work items: about one work item's band each, for an even grid.
            let buckets = Buckets::new(&images, (out.len() / row_len).div_ceil(rows_per_item));
            (images, buckets)
        });
        out.par_chunks_mut(rows_per_item * row_len)
            .enumerate()
            .try_for_each_init(Rows::default, |rows, (item, out)| {
                let first_row = item * rows_per_item;
                let count = out.len() / row_len;
                Self::load(rows, row_len, first_row, count, &row);
                // Set up field by field and seen on the plane only for a grid that may be swept.
                let swept = match index.as_ref() {
                    Some(index) => {
                        if !rows.prepared.set_up(&rows.rays, self.magnitude) {
                            Self::validate(&rows.rays)?;
                        }
                        self.slack(rows, &axes, row_len).map(|slack| (index, slack))
                    }
                    None => {
                        Self::validate(&rows.rays)?;
                        None
                    }
                };
                rows.hits.clear();
                rows.hits.resize(rows.rays.len(), None);
                match swept {
                    Some(((images, buckets), slack)) => {
                        self.sweep(rows, row_len, images, buckets, slack, t_min, t_max);
                    }
                    None => {
                        let Rows {
                            rays, descending, ..
                        } = rows;
                        descending.clear();
                        descending.extend(
                            rays.iter()
                                .map(|ray| PreparedRay::set_up(ray, self.magnitude)),
                        );
                        self.closest_item(descending, t_min, t_max, &mut rows.hits);
                    }
                }
                answer(&rows.rays, &rows.hits, out);
                Ok(())
            })
    }

    /// The stored triangles seen along the axes, ordered across the rows (by `lo`, then index),
    /// so that a work item reads the images it meets from one stretch of memory.
    fn images(&self, axes: &Axes) -> Vec<Image> {
        let stored: Vec<u32> = (0..u32::try_from(self.triangles.len()).expect("checked in new"))
            .filter(|id| self.degenerate.binary_search(id).is_err())
            .collect();
        let mut images: Vec<Image> = stored
            .par_iter()
            .map(|&id| {
                let corners = self.triangle(id);
                let p = corners.map(|v| axes.plane(v));
                let b = p.map(|q| q.y);
                Image {
                    a: p.map(|q| q.x),
                    b,
                    lo: b[0].min(b[1]).min(b[2]),
                    hi: b[0].max(b[1]).max(b[2]),
                    id,
                    stored: vertices(corners),
                }
            })
            .collect();
        images.par_sort_unstable_by(|p, q| p.lo.total_cmp(&q.lo).then(p.id.cmp(&q.id)));
        images
    }

    /// The [`Ray::validate`] error of the first invalid ray of `rays`, if any.
    fn validate(rays: &[Ray]) -> Result<(), TraceError> {
        rays.iter().try_for_each(Ray::validate)
    }

    /// Rows `first_row..first_row + count` of the grid into `rows`.
    fn load(
        rows: &mut Rows,
        row_len: usize,
        first_row: usize,
        count: usize,
        row: &(impl Fn(usize, &mut [Ray]) + Sync),
    ) {
        let rays = &mut rows.rays;
        rays.clear();
        rays.resize(row_len * count, UNSET);
        for (j, rays) in rays.chunks_mut(row_len).enumerate() {
            row(first_row + j, rays);
        }
    }

    /// The loaded rows seen on the plane (`along`, `lo`, `hi` of `rows`), and the slack δ of the
    /// module documentation; `None` if the rays are not parallel enough or a row is not sorted
    /// along itself. Read from the set-up rays' arrays four rays at a time (each lane the dot
    /// products of `Axes::plane` in their order; the extremes are exact in any order).
    fn slack(&self, rows: &mut Rows, axes: &Axes, row_len: usize) -> Option<f64> {
        let Rows {
            prepared,
            along,
            across,
            lo,
            hi,
            ..
        } = rows;
        let n = prepared.len();
        // Every entry is written below (as in `PreparedRays::set_up`, nothing is cleared first).
        along.resize(n, 0.0);
        across.resize(n, 0.0);
        let splat = |v: DVec3| [v.x, v.y, v.z].map(f64x4::splat);
        let (on_along, on_across, on_axis) =
            (splat(axes.along), splat(axes.across), splat(axes.axis));
        let dot = |v: &[f64x4; 3], w: &[f64x4; 3]| v[0] * w[0] + v[1] * w[1] + v[2] * w[2];
        // The slope's bound: the largest |L(d)|² over the smallest d·a (all positive).
        let (mut sideways, mut ahead, mut reach) =
            (f64x4::ZERO, f64x4::splat(f64::INFINITY), f64x4::ZERO);
        let fours = n / 4 * 4;
        for k in (0..fours).step_by(4) {
            let lanes = |field: &[Vec<f64>; 3]| field.each_ref().map(|v| PreparedRays::lanes(v, k));
            let (o, d) = (lanes(&prepared.origin), lanes(&prepared.direction));
            along[k..k + 4].copy_from_slice(&dot(&o, &on_along).to_array());
            across[k..k + 4].copy_from_slice(&dot(&o, &on_across).to_array());
            let (x, y) = (dot(&d, &on_along), dot(&d, &on_across));
            sideways = sideways.max(x * x + y * y);
            ahead = ahead.min(dot(&d, &on_axis));
            reach = reach.max(o[0].abs().max(o[1].abs().max(o[2].abs())));
        }
        let (mut sideways, mut ahead, mut reach) = (
            sideways.to_array().into_iter().fold(0.0_f64, f64::max),
            ahead.to_array().into_iter().fold(f64::INFINITY, f64::min),
            reach.to_array().into_iter().fold(0.0_f64, f64::max),
        );
        for k in fours..n {
            let at = |field: &[Vec<f64>; 3]| DVec3::new(field[0][k], field[1][k], field[2][k]);
            let (origin, direction) = (at(&prepared.origin), at(&prepared.direction));
            let point = axes.plane(origin);
            (along[k], across[k]) = (point.x, point.y);
            sideways = sideways.max(axes.plane(direction).length_squared());
            ahead = ahead.min(direction.dot(axes.axis));
            reach = reach.max(origin.abs().max_element());
        }
        lo.clear();
        hi.clear();
        let mut sorted = true;
        for (along, across) in along.chunks(row_len).zip(across.chunks(row_len)) {
            sorted &= along.windows(2).all(|pair| pair[1] >= pair[0]);
            lo.push(across.iter().copied().fold(f64::INFINITY, f64::min));
            hi.push(across.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        }
        let reach = self.magnitude + reach;
        // At least every ray's |L(d)|/(d·a); false for rays across or against the axis.
        let slope = sideways.sqrt() / ahead;
        let parallel = ahead > 0.0 && slope <= MAX_SLOPE;
        (sorted && parallel).then_some(SLACK * reach + 4.0 * reach * slope)
    }

    /// The closest hits of a work item's rays by the sweep (module documentation), into
    /// `rows.hits` (all `None` on entry).
    #[expect(clippy::too_many_arguments, reason = "one work item's whole context")]
    fn sweep(
        &self,
        rows: &mut Rows,
        row_len: usize,
        images: &[Image],
        buckets: &Buckets,
        slack: f64,
        t_min: f64,
        t_max: f64,
    ) {
        let band_lo = rows.lo.iter().copied().fold(f64::INFINITY, f64::min) - slack;
        let band_hi = rows.hi.iter().copied().fold(f64::NEG_INFINITY, f64::max) + slack;
        let prepared = &rows.prepared;
        for image in buckets.meeting(images, band_lo, band_hi) {
            let id = image.id;
            for (row, (&lo, &hi)) in rows.lo.iter().zip(&rows.hi).enumerate() {
                let (lo, hi) = (lo - slack, hi + slack);
                if image.lo > hi || image.hi < lo {
                    continue;
                }
                let Some((a_lo, a_hi)) = image.extent(lo, hi) else {
                    continue;
                };
                let first = row * row_len;
                let along = &rows.along[first..first + row_len];
                let (a_lo, a_hi) = (a_lo - slack, a_hi + slack);
                let start = count_below(along, a_lo, false);
                let end = count_below(along, a_hi, true);
                // Four rays at a time against the triangle where they share their dominant axis
                // (`triangle::intersect_rays`: each ray's own answer), one by one elsewhere.
                let (mut k, end) = (first + start, first + end);
                while k < end {
                    if k + RAYS <= end {
                        let kz = &prepared.kz[k..k + RAYS];
                        if kz.iter().all(|&axis| axis == kz[0]) {
                            let best = &mut rows.hits[k..k + RAYS];
                            let found = |lane: usize, found| {
                                keep(&mut best[lane], Some(found), id, (t_min, t_max));
                            };
                            let stored = &image.stored;
                            match kz[0] {
                                0 => triangle::intersect_rays::<0>(prepared, k, stored, found),
                                1 => triangle::intersect_rays::<1>(prepared, k, stored, found),
                                _ => triangle::intersect_rays::<2>(prepared, k, stored, found),
                            }
                            k += RAYS;
                            continue;
                        }
                    }
                    let ray = &prepared.ray(k);
                    let found = match ray.kz {
                        0 => triangle::intersect::<0>(ray, &image.stored),
                        1 => triangle::intersect::<1>(ray, &image.stored),
                        _ => triangle::intersect::<2>(ray, &image.stored),
                    };
                    keep(&mut rows.hits[k], found, id, (t_min, t_max));
                    k += 1;
                }
            }
        }
    }
}

/// Keeps `found`, a ray's hit of triangle `id`, in `best` if it wins by the tree's rule (as in
/// `closest`): `t` in `(t_min, t_max)`, and a smaller `t` than the best so far, or an equal `t` and
/// a smaller index.
#[inline(always)]
fn keep(
    best: &mut Option<Hit>,
    found: Option<(f64, f64, f64)>,
    id: u32,
    (t_min, t_max): (f64, f64),
) {
    let Some((t, u, v)) = found else { return };
    let wins = match best {
        None => t < t_max,
        Some(best) => t < best.t || (t == best.t && id < best.triangle),
    };
    if t_min < t && wins {
        *best = Some(Hit {
            t,
            triangle: id,
            u,
            v,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles of the unit square at z = 0.
    fn square() -> Bvh {
        let positions = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        Bvh::new(&positions, &[[0, 1, 2], [0, 2, 3]]).expect("a valid mesh")
    }

    /// A 4 × 3 grid of rays toward −z, from (x, y, 1), or toward `focus` if given.
    fn grid(focus: Option<DVec3>) -> Vec<Ray> {
        let mut rays = Vec::new();
        for j in 0..3 {
            for i in 0..4 {
                let origin = DVec3::new(0.3 * f64::from(i), 0.4 * f64::from(j), 1.0);
                let direction = focus.map_or(DVec3::NEG_Z, |focus| focus - origin);
                rays.push(Ray { origin, direction });
            }
        }
        rays
    }

    fn slack(bvh: &Bvh, rays: &[Ray]) -> Option<f64> {
        let axes = Axes::of(&rays[0], &rays[3]);
        let row = |j: usize, out: &mut [Ray]| out.copy_from_slice(&rays[4 * j..4 * j + 4]);
        let mut rows = Rows::default();
        Bvh::load(&mut rows, 4, 0, 3, &row);
        assert!(
            rows.prepared.set_up(&rows.rays, bvh.magnitude),
            "valid rays"
        );
        bvh.slack(&mut rows, &axes, 4)
    }

    /// Parallel rows in order are swept, with a slack of the order of `SLACK·R`; converging rays
    /// and a row out of order are not.
    #[test]
    fn parallel_sorted_rows_are_swept_and_others_are_not() {
        let bvh = square();
        let parallel = grid(None);
        let swept = slack(&bvh, &parallel).expect("swept");
        assert!(swept > 0.0 && swept < 10.0 * SLACK, "{swept}");
        assert_eq!(slack(&bvh, &grid(Some(DVec3::new(0.5, 0.5, -3.0)))), None);
        let mut unsorted = parallel;
        unsorted.swap(4, 5);
        assert_eq!(slack(&bvh, &unsorted), None);
    }

    /// The slack read four rays at a time is, to the bit, the slack and the rows' extents of the
    /// one-ray formulas (`Axes::plane` per origin and direction), on rows whose length leaves a
    /// tail of one to three rays, of parallel rays at random offsets.
    #[test]
    fn slack_in_lanes_is_each_rays_own() {
        let bvh = square();
        let mut random = shadowlab_test_random::SplitMix(0x5eed_0000_0000_51ac);
        for row_len in [1, 4, 5, 7] {
            let direction = DVec3::new(1e-9 * random.range(-1.0, 1.0), 0.0, -1.0);
            let rays: Vec<Ray> = (0..3 * row_len)
                .map(|k| {
                    let (i, j) = ((k % row_len) as f64, (k / row_len) as f64);
                    let jitter = random.range(0.0, 1e-3);
                    let origin = DVec3::new(0.3 * i + jitter, 0.4 * j + jitter, 1.0 + jitter);
                    Ray { origin, direction }
                })
                .collect();
            let axes = Axes::of(&rays[0], &rays[row_len - 1]);
            let row = |j: usize, out: &mut [Ray]| {
                out.copy_from_slice(&rays[row_len * j..row_len * (j + 1)]);
            };
            let mut rows = Rows::default();
            Bvh::load(&mut rows, row_len, 0, 3, &row);
            assert!(rows.prepared.set_up(&rows.rays, bvh.magnitude));
            let slack = bvh.slack(&mut rows, &axes, row_len);
            // The one-ray formulas.
            let (mut sideways, mut ahead, mut reach) = (0.0_f64, f64::INFINITY, 0.0_f64);
            let mut extents = Vec::new();
            for row in rays.chunks(row_len) {
                let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
                for ray in row {
                    let point = axes.plane(ray.origin);
                    low = low.min(point.y);
                    high = high.max(point.y);
                    sideways = sideways.max(axes.plane(ray.direction).length_squared());
                    ahead = ahead.min(ray.direction.dot(axes.axis));
                    reach = reach.max(ray.origin.abs().max_element());
                }
                extents.push((low, high));
            }
            let along: Vec<f64> = rays.iter().map(|r| axes.plane(r.origin).x).collect();
            let reach = bvh.magnitude + reach;
            let slope = sideways.sqrt() / ahead;
            let expected = SLACK * reach + 4.0 * reach * slope;
            assert_eq!(
                slack.map(f64::to_bits),
                Some(expected.to_bits()),
                "{row_len}"
            );
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&rows.along), bits(&along), "{row_len}");
            let (lo, hi): (Vec<f64>, Vec<f64>) = extents.into_iter().unzip();
            assert_eq!((bits(&rows.lo), bits(&rows.hi)), (bits(&lo), bits(&hi)));
        }
    }

    /// `count_below` is `partition_point`, on even rows (where the guess is right) and uneven
    /// ones (where it walks or bisects), for values at, between and beyond the points.
    #[test]
    fn count_below_is_partition_point() {
        let even: Vec<f64> = (0..50).map(|k| f64::from(k) * 0.5 - 3.0).collect();
        let uneven: Vec<f64> = (0..50).map(|k| f64::from(k).powi(3) * 1e-3).collect();
        let repeated = vec![1.0, 1.0, 1.0, 2.0, 2.0, 3.0];
        for sorted in [&even, &uneven, &repeated] {
            let (lo, hi) = (sorted[0] - 1.0, sorted[sorted.len() - 1] + 1.0);
            for k in 0..=400_u32 {
                let value = lo + (hi - lo) * f64::from(k) / 400.0;
                for value in [value, sorted[k as usize % sorted.len()]] {
                    assert_eq!(
                        count_below(sorted, value, false),
                        sorted.partition_point(|&a| a < value)
                    );
                    assert_eq!(
                        count_below(sorted, value, true),
                        sorted.partition_point(|&a| a <= value)
                    );
                }
            }
        }
    }

    /// The buckets give every image whose extent meets a band exactly once, and no other.
    #[test]
    fn buckets_give_each_image_meeting_a_band_once() {
        let images: Vec<Image> = (0..60_u32)
            .map(|id| {
                let lo = f64::from(id * 7 % 50) * 0.1;
                let hi = lo + f64::from(id % 9) * 0.37;
                Image {
                    a: [0.0; 3],
                    b: [lo, hi, lo],
                    lo,
                    hi,
                    id,
                    stored: [0.0; 9],
                }
            })
            .collect();
        for count in [1, 3, 16, 200] {
            let buckets = Buckets::new(&images, count);
            for (lo, hi) in [
                (-1.0, -0.5),
                (0.0, 0.05),
                (1.23, 1.24),
                (2.0, 4.5),
                (-9.0, 99.0),
            ] {
                let mut met: Vec<u32> = buckets.meeting(&images, lo, hi).map(|i| i.id).collect();
                met.sort_unstable();
                let expected: Vec<u32> = images
                    .iter()
                    .filter(|i| i.lo <= hi && i.hi >= lo)
                    .map(|i| i.id)
                    .collect();
                assert_eq!(met, expected, "{count} buckets, band {lo}..{hi}");
            }
        }
    }
}
