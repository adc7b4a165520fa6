//! Rendering a planned shadow map.

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use shadowlab_raster::{
    DepthFormat, DepthPairTarget, DepthTarget, RasterError, RasterOptions, Rasterizer, Triangles,
};
use shadowlab_trace::{Bvh, Hit, RAY_CHUNK, Ray};
use wide::f64x4;

use crate::error::ShadowError;
use crate::lanes::{LANES, Vectors};
use crate::logarithmic_map::LogarithmicMap;
use crate::setup::{LightSetup, ShadowMapping};

/// Along a texel's ray (t from 0 to 1 across B's light-axis extent), hits closer than this to the
/// first count as the same surface when looking for the second.
const SAME_SURFACE: f64 = 1e-9;

/// What to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MapOptions {
    /// Side of the square map, in texels.
    pub resolution: u32,
    /// How depth is stored (an accuracy knob: see `shadowlab_raster::DepthFormat`).
    pub format: DepthFormat,
    /// Also keep the second-nearest depth (for the second-depth, midpoint and dual-depth biases).
    pub second_depth: bool,
}

/// A rendered shadow map: window depths (GL's `[0, 1]`, 1 where nothing is stored) of the nearest
/// and, if asked for, second-nearest surface per texel, row-major with row 0 at the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap {
    /// How it was planned.
    pub setup: LightSetup,
    /// Side in texels.
    pub resolution: u32,
    /// The depth format the values were stored in (and decoded from).
    pub format: DepthFormat,
    /// Nearest depth per texel.
    pub nearest: Vec<f64>,
    /// Second-nearest depth per texel, if rendered.
    pub second: Option<Vec<f64>>,
}

impl ShadowMap {
    /// Renders `setup`'s map of `mesh` with the rasterizer.
    ///
    /// # Errors
    /// [`ShadowError::NotDefined`] for the logarithmic and paraboloid maps, which are not
    /// projective and are cast instead ([`Self::cast`]); the rasterizer's errors (bad indices, sizes) as
    /// [`ShadowError::Raster`].
    pub fn render(
        setup: &LightSetup,
        mesh: Triangles<'_>,
        options: MapOptions,
    ) -> Result<Self, ShadowError> {
        if setup.mapping.is_cast() {
            return Err(ShadowError::NotDefined {
                technique: setup.technique.key(),
                reason: "the map is not projective: cast rays instead".into(),
            });
        }
        let clip_from_world = setup
            .mapping
            .clip_from_world()
            .expect("a projective mapping");
        let size = options.resolution;
        let mut raster = Rasterizer::new(RasterOptions::default());
        let (nearest, second) = if options.second_depth {
            let mut target = DepthPairTarget::new(size, size, options.format)?;
            raster.draw_depth_pair(&mut target, mesh, &clip_from_world)?;
            (target.nearest(), Some(target.second()))
        } else {
            let mut target = DepthTarget::new(size, size, options.format)?;
            raster.draw_depth(&mut target, mesh, &clip_from_world)?;
            (target.depths(), None)
        };
        Ok(Self {
            setup: setup.clone(),
            resolution: size,
            format: options.format,
            nearest,
            second,
        })
    }

    /// Makes a non-projective map exactly — the logarithmic map, a paraboloid hemisphere — one ray
    /// of light per texel centre, found through the inverse mapping
    /// ([`crate::logarithmic::LogarithmicMap::texel_row`], [`crate::paraboloid::ParaboloidMap::texel_ray`]), cast
    /// against `bvh`; the first hit's depth (and the second's, if asked for) through the forward
    /// mapping, stored in `options.format`. A texel with no ray (outside a paraboloid's disk) or
    /// whose ray meets nothing stores 1. The logarithmic map's nearest depths are cast as one grid
    /// ([`Bvh::closest_hits_grid`]: swept triangle by triangle where its rays are parallel, under
    /// a directional light); otherwise rows are cast in parallel, each row's rays in batches of at
    /// most [`RAY_CHUNK`] ([`Bvh::closest_hits`], which traces neighbouring texels' rays
    /// together). Either way each texel's value is its ray's brute-force first hit alone.
    ///
    /// # Errors
    /// [`ShadowError::NotDefined`] for a projective set-up (rasterize it with [`Self::render`]);
    /// [`ShadowError::Trace`] if a texel's ray is invalid (a degenerate map).
    pub fn cast(setup: &LightSetup, bvh: &Bvh, options: MapOptions) -> Result<Self, ShadowError> {
        let mapping = &setup.mapping;
        if !mapping.is_cast() {
            return Err(ShadowError::NotDefined {
                technique: setup.technique.key(),
                reason: "a projective map is rasterized, not cast".into(),
            });
        }
        let side = options.resolution as usize;
        // Texel k's centre in NDC, for columns and rows alike: found once per map, not per texel.
        #[expect(clippy::cast_precision_loss, reason = "texel indices are small")]
        let centres: Vec<f64> = (0..side)
            .map(|k| (k as f64 + 0.5) / side as f64 * 2.0 - 1.0)
            .collect();
        let centre = |k: usize| centres[k];
        let store = |ray: &Ray, t: f64| {
            let point = ray.at(t);
            let ndc = match mapping {
                ShadowMapping::Logarithmic(map) => map.ndc_depth(point),
                ShadowMapping::Paraboloid(map) => Some(map.ndc_depth(point)),
                ShadowMapping::Projective(_) => None,
            };
            stored(options.format, ndc)
        };
        // Row j's depths into `nearest` and, if asked for, `second`.
        let fill_row = |j: usize,
                        nearest: &mut [f64],
                        mut second: Option<&mut [f64]>|
         -> Result<(), ShadowError> {
            // 1 where a texel has no ray or its ray meets nothing.
            nearest.fill(1.0);
            if let Some(second) = second.as_deref_mut() {
                second.fill(1.0);
            }
            let y = centre(j);
            let row = match mapping {
                ShadowMapping::Logarithmic(map) => Some(map.texel_row(y)),
                _ => None,
            };
            // The row's rays in texel order, neighbours side by side, in batches of at most one
            // work item of the batch query (so that it runs on this thread, not split). Every
            // texel of the logarithmic map has a ray; a paraboloid's texels off its disk have none,
            // and only then is the list of the rays' texels kept.
            for first in (0..side).step_by(RAY_CHUNK) {
                let chunk = first..side.min(first + RAY_CHUNK);
                let mut rays = Vec::with_capacity(chunk.len());
                let mut texels = Vec::new();
                match (mapping, &row) {
                    (_, Some(row)) => {
                        for i in chunk {
                            let (from, to) = row.ray(centre(i));
                            rays.push(Ray::new(from, to - from)?);
                        }
                    }
                    (ShadowMapping::Paraboloid(map), None) => {
                        for i in chunk {
                            if let Some((from, to)) = map.texel_ray(centre(i), y) {
                                texels.push(i);
                                rays.push(Ray::new(from, to - from)?);
                            }
                        }
                    }
                    _ => {}
                }
                let texel = |k: usize| {
                    if texels.is_empty() {
                        first + k
                    } else {
                        texels[k]
                    }
                };
                let firsts = bvh.closest_hits(&rays, 0.0, 1.0);
                for (k, (ray, hit)) in rays.iter().zip(firsts).enumerate() {
                    let Some(hit) = hit else { continue };
                    let texel = texel(k);
                    nearest[texel] = store(ray, hit.t);
                    // The next surface: beyond the first by more than SAME_SURFACE, so that the
                    // first surface's neighbour across a shared edge (hit a few ulps further) is
                    // not taken for it.
                    if let Some(second) = second.as_deref_mut() {
                        second[texel] = bvh
                            .closest_hit(ray, hit.t + SAME_SURFACE, 1.0)
                            .map_or(1.0, |h| store(ray, h.t));
                    }
                }
            }
            Ok(())
        };
        // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers"); each row then
        // fills its own.
        let zeros = |n: usize| -> Vec<f64> { rayon::iter::repeat_n(0.0, n).collect() };
        let mut nearest = zeros(side * side);
        // The logarithmic map's first hits, as a grid of rays: swept, where they are parallel.
        if let (ShadowMapping::Logarithmic(map), false) = (mapping, options.second_depth) {
            let row = |j: usize, rays: &mut [Ray]| map.texel_row(centre(j)).rays(&centres, rays);
            bvh.closest_hits_grid(side, row, 0.0, 1.0, &mut nearest, |rays, hits, out| {
                logarithmic_depths(map, options.format, (rays, hits), out);
            })?;
            return Ok(Self {
                setup: setup.clone(),
                resolution: options.resolution,
                format: options.format,
                nearest,
                second: None,
            });
        }
        let mut second = zeros(if options.second_depth { side * side } else { 0 });
        let rows = nearest.par_chunks_mut(side).enumerate();
        if options.second_depth {
            rows.zip(second.par_chunks_mut(side))
                .try_for_each(|((j, nearest), second)| fill_row(j, nearest, Some(second)))?;
        } else {
            rows.try_for_each(|(j, nearest)| fill_row(j, nearest, None))?;
        }
        Ok(Self {
            setup: setup.clone(),
            resolution: options.resolution,
            format: options.format,
            nearest,
            second: options.second_depth.then_some(second),
        })
    }

    /// A map of `setup` whose depths are given rather than rendered — read back from another
    /// renderer, say: `nearest` (and `second`, for the biases that read it) are window depths,
    /// `resolution²` of them, row-major with row 0 at the bottom, each stored as `format` stores
    /// it (`format.decode(format.encode(z))`, which keeps a depth already in the format as it is).
    ///
    /// # Errors
    /// [`ShadowError::Raster`] with [`RasterError::ImageSize`] if a vector does not hold
    /// `resolution²` depths.
    pub fn from_depths(
        setup: LightSetup,
        resolution: u32,
        format: DepthFormat,
        nearest: Vec<f64>,
        second: Option<Vec<f64>>,
    ) -> Result<Self, ShadowError> {
        let texels = resolution as usize * resolution as usize;
        let stored = |depths: Vec<f64>| {
            if depths.len() != texels {
                return Err(ShadowError::Raster(RasterError::ImageSize {
                    width: resolution,
                    height: resolution,
                    values: depths.len(),
                }));
            }
            Ok(depths
                .into_iter()
                .map(|z| format.decode(format.encode(z)))
                .collect())
        };
        Ok(Self {
            setup,
            resolution,
            format,
            nearest: stored(nearest)?,
            second: second.map(stored).transpose()?,
        })
    }

    /// The texel `(i, j)` (column, row from the bottom) holding window point `(x, y)`, if it lies on
    /// the map: [`Self::texel_at`] of `(x, y)` in texels.
    #[must_use]
    pub fn texel_of(&self, window: DVec3) -> Option<(u32, u32)> {
        let side = f64::from(self.resolution);
        self.texel_at(DVec2::new(window.x * side, window.y * side))
    }

    /// The texel `(i, j)` holding texel-space point `at` (texels from the map's bottom-left
    /// corner: `(⌊at.x⌋, ⌊at.y⌋)`), if it lies on the map.
    #[must_use]
    pub fn texel_at(&self, at: DVec2) -> Option<(u32, u32)> {
        let side = f64::from(self.resolution);
        let (i, j) = (at.x.floor(), at.y.floor());
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "checked to lie in [0, resolution)"
        )]
        let texel = (i >= 0.0 && j >= 0.0 && i < side && j < side).then_some((i as u32, j as u32));
        texel
    }

    /// The stored nearest depth of texel `(i, j)`.
    #[must_use]
    pub fn depth(&self, i: u32, j: u32) -> f64 {
        self.nearest[self.index(i, j)]
    }

    /// The stored second-nearest depth of texel `(i, j)` (`None` if not rendered).
    #[must_use]
    pub fn second_depth(&self, i: u32, j: u32) -> Option<f64> {
        self.second.as_ref().map(|s| s[self.index(i, j)])
    }

    fn index(&self, i: u32, j: u32) -> usize {
        j as usize * self.resolution as usize + i as usize
    }
}

/// What a cast map stores of a hit point at NDC depth `ndc`: its window depth `(z + 1)/2` in
/// `format` (decoded back), 1 where the point has none.
fn stored(format: DepthFormat, ndc: Option<f64>) -> f64 {
    let depth = ndc.map_or(1.0, |z| 0.5 * (z + 1.0));
    format.decode(format.encode(depth))
}

/// The logarithmic map's stored depths of a work item's texel rays from their first hits, into
/// `out`: 1 where a ray meets nothing, else [`stored`] of [`LogarithmicMap::ndc_depth`] of the
/// hit point `ray.at(t)` — four rays at a time ([`LogarithmicMap::ndc_depth_lanes`]; the hit
/// point `origin + direction·t` lane by lane, as `Ray::at`), the same bits as one by one.
fn logarithmic_depths(
    map: &LogarithmicMap,
    format: DepthFormat,
    (rays, hits): (&[Ray], &[Option<Hit>]),
    out: &mut [f64],
) {
    let count = out.len();
    let mut blocks = out.chunks_exact_mut(LANES);
    for ((out, rays), hits) in (&mut blocks)
        .zip(rays.chunks_exact(LANES))
        .zip(hits.chunks_exact(LANES))
    {
        let t = f64x4::new(std::array::from_fn(|k| hits[k].map_or(0.0, |hit| hit.t)));
        let origin = Vectors::of(&std::array::from_fn(|k| rays[k].origin));
        let direction = Vectors::of(&std::array::from_fn(|k| rays[k].direction));
        let (ndc, undefined) = map.ndc_depth_lanes(origin.plus(direction.times(t)));
        let ndc = ndc.to_array();
        for (k, out) in out.iter_mut().enumerate() {
            *out = hits[k].map_or(1.0, |_| stored(format, (!undefined[k]).then_some(ndc[k])));
        }
    }
    let done = count - blocks.into_remainder().len();
    for ((out, ray), hit) in out[done..].iter_mut().zip(&rays[done..]).zip(&hits[done..]) {
        *out = hit.map_or(1.0, |hit| stored(format, map.ndc_depth(ray.at(hit.t))));
    }
}

#[cfg(test)]
mod tests {
    use shadowlab_raster::DepthFormat;
    use shadowlab_test_random::SplitMix;
    use shadowlab_trace::{Hit, Ray};

    use super::{logarithmic_depths, stored};
    use crate::logarithmic::tests::random_map;

    /// A work item's depths four rays at a time ([`logarithmic_depths`]) are each ray's alone to
    /// the bit — `stored` of the map's NDC depth at `ray.at(t)`, 1 for a miss — over spot and
    /// affine light spaces, hit points behind the light or short of the reference point among
    /// them, misses among hits, three formats, and work items of 0 to 11 rays.
    #[test]
    fn logarithmic_depths_four_at_a_time_are_each_rays_alone() {
        let mut random = SplitMix(0x5eed_0000_0000_de97);
        let formats = [
            DepthFormat::F32,
            DepthFormat::Unorm16,
            DepthFormat::ReversedF32,
        ];
        let (mut misses, mut without_depth, mut stored_depths) = (0, 0, 0);
        for round in 0..2000_usize {
            let map = random_map(&mut random, round);
            let format = formats[round % formats.len()];
            let count = round % 12;
            let rays: Vec<Ray> = (0..count)
                .map(|_| Ray {
                    origin: random.vector(20.0),
                    direction: random.vector(1.0),
                })
                .collect();
            let hits: Vec<Option<Hit>> = (0..count)
                .map(|k| {
                    (k % 3 != 1).then(|| Hit {
                        t: random.range(0.0, 1.0),
                        triangle: 0,
                        u: 0.0,
                        v: 0.0,
                    })
                })
                .collect();
            let mut out = vec![f64::NAN; count];
            logarithmic_depths(&map, format, (&rays, &hits), &mut out);
            for (k, (ray, hit)) in rays.iter().zip(&hits).enumerate() {
                let one = hit.map_or(1.0, |hit| {
                    let ndc = map.ndc_depth(ray.at(hit.t));
                    if ndc.is_some() {
                        stored_depths += 1;
                    } else {
                        without_depth += 1;
                    }
                    stored(format, ndc)
                });
                misses += usize::from(hit.is_none());
                assert_eq!(out[k].to_bits(), one.to_bits(), "round {round}, ray {k}");
            }
        }
        assert!(
            misses > 1000 && without_depth > 500 && stored_depths > 3000,
            "{misses} {without_depth} {stored_depths}"
        );
    }
}
