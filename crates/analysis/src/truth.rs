//! Shadow truth: for every eye pixel that sees a surface, whether the point it sees is lit by each
//! light — exactly, by casting one ray toward the light ([`exact_truth`]), or as Chong and Gortler
//! did (CG06 §5), from a very fine uniform shadow map ([`map_truth`]).
//!
//! # The exact truth, defined
//! * **The point.** The eye image's position (the perspective-correct point of the pixel centre on
//!   the visible triangle), carried onto its triangle: its barycentric coordinates are clamped to
//!   the triangle and re-evaluated by [`Bvh::hit_point`]. The position itself carries no bound on
//!   its distance from the triangle's plane (its weights come from clip-space cross products, and
//!   a pixel that a snapped edge lets in has weights slightly outside `[0, 1]`); `hit_point` with
//!   weights in the triangle lies within `4.4·ε·m` of the plane (trace's documentation), inside
//!   [`offset_origin`]'s precondition of `SURFACE_POINT_ULPS·ε·m = 16·ε·m`. Only points whose
//!   pixel centre a snapped edge let in move by more than rounding, and by about the snapping
//!   error (1/256 pixel).
//! * **The normal.** The visible triangle's geometric normal ([`Bvh::geometric_normal`] of
//!   `eye.triangle[pixel]`), which `offset_origin` requires — not the eye image's interpolated
//!   normal, which may lean more than 60° from the plane on a coarse smooth mesh.
//! * **The ray** starts at `offset_origin(point, normal, toward, bvh.magnitude())`, on the side of
//!   the triangle the light is on, and is occluded if it hits anything with `t > 0`:
//!   - *directional light*: along `to_light` with `t ∈ (0, ∞)` — the mesh is all there is, so
//!     this is the ray to the far side of the scene bounds;
//!   - *spot light*: the segment to the spot's position, `t ∈ (0, 1)`. Points outside the spot's
//!     cone — more than half its `fov_y` from its axis, the test `shadowlab_shadow::view::shade`
//!     lights by — are unlit (`Some(false)`) and marked in [`Truth::outside_cone`], with no ray.
//! * **Orientation does not shadow.** A point whose surface faces away from the light is lit when
//!   nothing blocks its ray: only occlusion counts, as in the papers' error model and as
//!   `shadowlab_shadow::Lookup` behaves (it compares depths and never looks at orientation). On a
//!   closed mesh the two agree anyway — the ray of a point facing away starts inside the solid
//!   and leaves through its lit side — and they differ only on open surfaces seen from behind.
//!
//! The rays are cast in parallel by [`Bvh::occluded_all`]; every answer depends on its ray
//! alone, so the truth is the same for any thread count.

use glam::DVec3;
use rayon::prelude::*;
use shadowlab_raster::{DepthFormat, EyeImage, NO_TRIANGLE, Triangles};
use shadowlab_scene::Scene;
use shadowlab_shadow::{
    Bias, DepthComparison, Filter, LightSource, Lookup, MapOptions, PlanOptions, ShadowMap,
    Technique, plan_light,
};
use shadowlab_trace::{Bvh, Hit, RAY_CHUNK, Ray, offset_origin};

use crate::error::AnalysisError;

/// A lit fraction at least this counts as lit: for a technique's lookups ([`crate::classify`]) and
/// for the map truth's ([`map_truth`]).
pub const LIT_THRESHOLD: f64 = 0.5;

/// Which visible points each light lights.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Truth {
    /// Per light (in the scene's order), per pixel (row-major, row 0 at the bottom): whether the
    /// visible point is lit; `None` where the pixel sees nothing.
    pub lit: Vec<Vec<Option<bool>>>,
    /// Per light, per pixel: whether the visible point lies outside the light's cone (spot lights
    /// only; such points are unlit, and the cone, not the shadow map, darkens them, so the metrics
    /// do not judge techniques there).
    pub outside_cone: Vec<Vec<bool>>,
}

/// The ray-casting hierarchy of `scene`'s mesh, to build once and pass to [`exact_truth`].
///
/// # Errors
/// [`AnalysisError::Trace`] if the mesh is not one the ray caster takes (coordinates beyond
/// `shadowlab_trace::MAX_COORDINATE`, more than `u32::MAX` triangles).
pub fn scene_bvh(scene: &Scene) -> Result<Bvh, AnalysisError> {
    Ok(Bvh::new(scene.mesh.positions(), scene.mesh.triangles())?)
}

/// The exact truth of `eye` (the eye pass of `scene`): one shadow ray per visible pixel and light
/// against `bvh` (built over `scene`'s mesh, e.g. by [`scene_bvh`]). See the module docs for the
/// definitions.
///
/// # Errors
/// [`AnalysisError::EyeImageSize`], [`AnalysisError::TriangleOutOfRange`] or
/// [`AnalysisError::BvhMismatch`] if the eye image or the hierarchy belongs to another mesh;
/// [`AnalysisError::ShadowRay`] if a visible triangle has zero area (no normal to offset along) or
/// a visible point lies at a spot light's position.
pub fn exact_truth(scene: &Scene, eye: &EyeImage, bvh: &Bvh) -> Result<Truth, AnalysisError> {
    check_eye(eye, scene.mesh.triangle_count())?;
    if bvh.triangle_count() != scene.mesh.triangle_count() {
        return Err(AnalysisError::BvhMismatch {
            bvh: bvh.triangle_count(),
            mesh: scene.mesh.triangle_count(),
        });
    }
    let surface: Vec<Option<(DVec3, DVec3)>> = eye
        .triangle
        .par_iter()
        .zip(&eye.position)
        .map(|(&triangle, &position)| {
            (triangle != NO_TRIANGLE).then(|| {
                (
                    on_triangle(bvh, triangle, position),
                    bvh.geometric_normal(triangle),
                )
            })
        })
        .collect();
    let mut truth = Truth {
        lit: Vec::with_capacity(scene.lights.len()),
        outside_cone: Vec::with_capacity(scene.lights.len()),
    };
    for (index, light) in scene.lights.iter().enumerate() {
        let (lit, outside_cone) = cast(bvh, &surface, &LightSource::from_scene(light), index)?;
        truth.lit.push(lit);
        truth.outside_cone.push(outside_cone);
    }
    Ok(truth)
}

/// One light's truth over the visible points `surface` (point and geometric normal per pixel):
/// runs of [`RAY_CHUNK`] pixels in parallel, each run's shadow rays made and cast together (one
/// work item of the batch query, so on that run's thread) and answered in place — no per-pixel
/// query or ray list of the whole image is kept. Each pixel's answer depends on its own ray alone,
/// so the result is the same for any run length and thread count.
fn cast(
    bvh: &Bvh,
    surface: &[Option<(DVec3, DVec3)>],
    light: &LightSource,
    index: usize,
) -> Result<(Vec<Option<bool>>, Vec<bool>), AnalysisError> {
    let magnitude = bvh.magnitude();
    // A ray toward a light at infinity, or along the segment to the light's position (t ≤ 1).
    let t_max = match light.position() {
        None => f64::INFINITY,
        Some(_) => 1.0,
    };
    let ray_from = |point: DVec3, normal: DVec3| match light.position() {
        None => {
            let to_light = light.toward_from(point);
            offset_origin(point, normal, to_light, magnitude)
                .and_then(|origin| Ray::new(origin, to_light))
        }
        Some(target) => offset_origin(point, normal, target - point, magnitude)
            .and_then(|origin| Ray::new(origin, target - origin)),
    };
    let mut lit = vec![None; surface.len()];
    let mut outside_cone = vec![false; surface.len()];
    lit.par_chunks_mut(RAY_CHUNK)
        .zip(outside_cone.par_chunks_mut(RAY_CHUNK))
        .zip(surface.par_chunks(RAY_CHUNK))
        .enumerate()
        .try_for_each(|(run, ((lit, outside_cone), surface))| {
            let mut rays = Vec::with_capacity(surface.len());
            let mut asked = Vec::with_capacity(surface.len());
            for (k, visible) in surface.iter().enumerate() {
                let Some((point, normal)) = *visible else {
                    continue;
                };
                if !light.reaches(point) {
                    // The cone or the range, not the map, darkens such points.
                    lit[k] = Some(false);
                    outside_cone[k] = true;
                    continue;
                }
                let ray = ray_from(point, normal).map_err(|error| AnalysisError::ShadowRay {
                    light: index,
                    pixel: run * RAY_CHUNK + k,
                    error,
                })?;
                rays.push(ray);
                asked.push(k);
            }
            for (k, occluded) in asked.into_iter().zip(bvh.occluded_all(&rays, 0.0, t_max)) {
                lit[k] = Some(!occluded);
            }
            Ok::<(), AnalysisError>(())
        })?;
    Ok((lit, outside_cone))
}

/// `position` carried onto triangle `triangle` of `bvh`: its barycentric coordinates, clamped to
/// the triangle, evaluated by [`Bvh::hit_point`] (see the module docs for why).
fn on_triangle(bvh: &Bvh, triangle: u32, position: DVec3) -> DVec3 {
    let [a, b, c] = bvh.triangle(triangle);
    let (e1, e2, d) = (b - a, c - a, position - a);
    let n = e1.cross(e2);
    let area2 = n.length_squared();
    let (mut u, mut v) = if area2 > 0.0 {
        (
            (d.cross(e2).dot(n) / area2).max(0.0),
            (e1.cross(d).dot(n) / area2).max(0.0),
        )
    } else {
        // No plane: the point is returned as the first vertex, and offset_origin then rejects the
        // zero normal.
        (0.0, 0.0)
    };
    let sum = u + v;
    if sum > 1.0 {
        (u, v) = (u / sum, v / sum);
    }
    bvh.hit_point(&Hit {
        t: 0.0,
        triangle,
        u,
        v,
    })
}

/// Checks that `eye`'s vectors hold `width × height` values and name only triangles below
/// `triangles`.
fn check_eye(eye: &EyeImage, triangles: usize) -> Result<(), AnalysisError> {
    let pixels = eye.width as usize * eye.height as usize;
    let shortest = eye
        .triangle
        .len()
        .min(eye.position.len())
        .min(eye.normal.len());
    let longest = eye
        .triangle
        .len()
        .max(eye.position.len())
        .max(eye.normal.len());
    if shortest != pixels || longest != pixels {
        return Err(AnalysisError::EyeImageSize {
            width: eye.width,
            height: eye.height,
            values: shortest,
        });
    }
    match eye
        .triangle
        .iter()
        .position(|&t| t != NO_TRIANGLE && t as usize >= triangles)
    {
        Some(pixel) => Err(AnalysisError::TriangleOutOfRange {
            pixel,
            triangle: eye.triangle[pixel],
            triangles,
        }),
        None => Ok(()),
    }
}

/// The constant part of [`map_truth`]'s bias, in window depth: 2⁻²⁰ ≈ 9.5·10⁻⁷, sixteen f32 ulps
/// at depth 1, so that a receiver is never shadowed by its own depth's rounding.
pub const MAP_TRUTH_CONSTANT_BIAS: f64 = 1.0 / 1_048_576.0;
/// The slope factor of [`map_truth`]'s bias: one texel's worth of the receiver's depth change,
/// which at the map's high resolution is a short distance.
pub const MAP_TRUTH_SLOPE_BIAS: f64 = 1.0;

/// The truth as Chong and Gortler measured it (CG06 §5, with a 3700² map): each light's uniform
/// shadow map (`Technique::Uniform`, focused on B, unpartitioned) of side `resolution` (f32
/// depths), looked up at each visible point with the nearest texel and a small slope-scaled bias
/// ([`MAP_TRUTH_SLOPE_BIAS`], [`MAP_TRUTH_CONSTANT_BIAS`]); lit when the lookup gives at least
/// [`LIT_THRESHOLD`]. Points outside a spot's cone are unlit and marked, as in [`exact_truth`].
///
/// It is an approximation that converges to the exact truth away from shadow edges as the
/// resolution grows; [`crate::classify::disagreement`] measures how far the two are apart. Memory grows with
/// `resolution²`: about 12.5 bytes per texel while rendering, 8 for the map kept during lookups.
///
/// # Errors
/// [`AnalysisError::EyeImageSize`] or [`AnalysisError::TriangleOutOfRange`] for an eye image of
/// another mesh; [`AnalysisError::Shadow`] if the uniform map cannot be planned or rendered (an
/// empty focus body, a resolution beyond the rasterizer's `MAX_TARGET_SIZE`).
pub fn map_truth(scene: &Scene, eye: &EyeImage, resolution: u32) -> Result<Truth, AnalysisError> {
    check_eye(eye, scene.mesh.triangle_count())?;
    let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
    let lookup = Lookup::new(
        Bias::new(DepthComparison::SlopeScaled {
            constant: MAP_TRUTH_CONSTANT_BIAS,
            slope: MAP_TRUTH_SLOPE_BIAS,
        }),
        Filter::Nearest,
    );
    let options = MapOptions {
        resolution,
        format: DepthFormat::F32,
        second_depth: false,
    };
    let mut truth = Truth {
        lit: Vec::with_capacity(scene.lights.len()),
        outside_cone: Vec::with_capacity(scene.lights.len()),
    };
    for light in &scene.lights {
        let partitions = plan_light(
            scene,
            light,
            &PlanOptions::new(Technique::Uniform),
            None,
            resolution,
            None,
        )?;
        let setup = &partitions
            .first()
            .expect("plan_light plans one partition when asked for one")
            .setup;
        let map = ShadowMap::render(setup, mesh, options)?;
        let source = LightSource::from_scene(light);
        let (lit, outside_cone): (Vec<Option<bool>>, Vec<bool>) = (0..eye.triangle.len())
            .into_par_iter()
            .map(|pixel| {
                if eye.triangle[pixel] == NO_TRIANGLE {
                    return (None, false);
                }
                let point = eye.position[pixel];
                if !source.reaches(point) {
                    return (Some(false), true);
                }
                let fraction = lookup.lit_fraction(&map, point, eye.normal[pixel]);
                (Some(fraction >= LIT_THRESHOLD), false)
            })
            .unzip();
        truth.lit.push(lit);
        truth.outside_cone.push(outside_cone);
    }
    Ok(truth)
}
