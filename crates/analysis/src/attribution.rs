//! Why a pixel is misclassified: every misclassified (light, pixel) pair of a combination given
//! one cause — acne, peter-panning, a partition seam (in a blend band or at a boundary), or
//! aliasing.
//!
//! # The causes, in precedence
//! A pair is misclassified as [`crate::classify`] counts it (visible, inside the light's cone, lit
//! fraction on the other side of [`LIT_THRESHOLD`] from the exact truth). It gets the first cause
//! whose rule holds, in this order; so the five counts are exclusive and sum to the misclassified
//! pairs ([`Causes::total`] equals `Misclassification::total`).
//!
//! 1. **Acne** ([`Cause::Acne`]) — *falsely shadowed*, and the map blocks the point with its own
//!    surface. The map is the one that serves the pixel ([`served`]; the nearer of two it blends).
//!    The texel is **the texel holding the point**, the one the nearest-texel lookup reads; for the
//!    filters that read several (PCF, the disk, VSM) it is their **centre texel**, the one under the
//!    point, and the others are not looked at. The rule holds when
//!    - that texel's stored depth lies **in front of the point's** window depth (it blocks the
//!      point without any bias: a texel holding the point's surface at or behind the point is no
//!      blocker, so a filtered lookup shadowed by its other taps is not acne), and
//!    - the surface stored there is the point's own: the texel centre's ray, cast from the light's
//!      side through the map's volume against the scene's triangles, first hits **the point's own
//!      triangle or a triangle of its mesh group** ([`shadowlab_scene::Mesh::groups`]: a scene
//!      file's entry, an OBJ group). The ray of a projective map runs from window `(x, y, 0)` to
//!      `(x, y, 1)`, both unprojected through the inverse of its `clip_from_world`; where that
//!      segment passes behind the projection centre (clip `w ≤ 0`, which the rasterizer never
//!      stores) only the part in front is cast, toward or from infinity, so the first hit is the
//!      stored surface's. The logarithmic map's ray is its `texel_ray`, the very ray it was cast
//!      with. A ray the caster rejects (a degenerate map) finds nothing: no acne.
//! 2. **Peter-panning** ([`Cause::PeterPanning`]) — *falsely lit*, the same maps looked up
//!    **with no bias at all** (`Bias::NONE`, the same filter, served, blended and faded as the
//!    technique's) say shadowed, and the texel under the point does **not** hold its own surface
//!    (the acne test of 1, negated): a true occluder within the bias's reach, which the bias lit.
//! 3. **Seam in a blend band** ([`Cause::SeamBand`]) — for a light with more than one partition,
//!    a pair not caused as above whose pixel lies **in a blend band** (served by two maps).
//! 4. **Seam at a boundary** ([`Cause::SeamBoundary`]) — likewise, outside any band, a pixel with
//!    a **4-neighbour** (a pixel that sees a surface) **served by another partition**: the hard
//!    boundary between cascades, a band's edge, or the seam between two faces of a point light's
//!    cube map or the two hemispheres of its dual-paraboloid map (each face is a partition).
//! 5. **Aliasing** ([`Cause::Aliasing`]) — the rest: too few texels where the pixel samples,
//!    wherever the shadow's edge is.
//!
//! # The choices, named
//! - *Own surface is the mesh group.* A mesh built without groups is one group, so there every
//!   blocking own-group texel counts as acne, including another object's; and two objects of one
//!   scene-file entry (the copies of a row) are one surface. The triangle alone would miss acne
//!   between a plane's two triangles.
//! - *The blocking test is unbiased.* "In front of the point" compares raw depths; the bias is
//!   what the technique added, and for the nearest texel a falsely shadowed point is behind the
//!   texel's depth anyway (any bias ≥ 0).
//! - *Peter-panning needs a true occluder in the texel:* one lookup more per falsely lit pair, and
//!   one ray where the unbiased lookup shadows. Without the ray, a falsely lit point at a shadow's
//!   edge whose texel holds its own surface — where the unbiased lookup would have acne — counted
//!   as peter-panning: on `outdoor` most of the falsely lit pixels of every technique. The bias
//!   did light it, but only out of its own acne; the error is the texel's, aliasing. VSM applies
//!   no bias, so it has no peter-panning: its light bleeding is aliasing.
//! - *Seams compare partition indices* of served pixels: a neighbour beyond the shadowed range
//!   (`Beyond::Lit`, served by none) is no other partition, and the fade is not a seam.
//! - *The 4-neighbourhood is the image's*, across surfaces: a pixel at a seam is one whose
//!   neighbour was looked up in another map, whatever it sees.
//! - Given depths (an evaluated set-up's images) are judged against the scene's triangles: the
//!   surface "stored" is the one the scene puts there.
//!
//! # Cost and determinism
//! At most one ray per falsely shadowed pair (none when the texel does not block it) and one lookup
//! per falsely lit pair; the seam rule reads the serving partition of four neighbours. Pixels are
//! attributed in parallel in fixed chunks of [`ATTRIBUTION_ROWS`] rows; each pair's cause depends
//! on that pair alone, so the result is the same on any thread count.
//!
//! # The picture
//! [`cause_image`] colours each pixel by the first cause (in the order above) of any light's
//! misclassified pair: [`ACNE`], [`PETER_PANNING`], [`SEAM_BAND`], [`SEAM_BOUNDARY`],
//! [`ALIASING`] — Okabe and Ito's reddish purple, orange, sky blue, yellow and bluish green, none of
//! them the difference image's two error colours — and correct pixels and the background as [`crate::classify::difference_image`]
//! does.

use std::fmt;
use std::ops::AddAssign;

use glam::{DMat4, DVec3, DVec4};
use rayon::prelude::*;
use shadowlab_raster::{EyeImage, NO_TRIANGLE};
use shadowlab_scene::Scene;
use shadowlab_shadow::{
    Bias, Eye, Filter, LightShadow, Lookup, ShadowMap, ShadowMapping, scene_eye, served,
};
use shadowlab_trace::{Bvh, Ray};

use crate::classify::{BACKGROUND, CORRECT_LIT, CORRECT_SHADOW};
use crate::error::AnalysisError;
use crate::tally;
use crate::truth::{LIT_THRESHOLD, Truth};

/// Rows of pixels attributed per parallel job; any size gives the same result.
pub const ATTRIBUTION_ROWS: usize = 8;

/// Why a (light, pixel) pair is misclassified (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cause {
    /// Falsely shadowed by its own surface's depth.
    Acne,
    /// Falsely lit because of the bias.
    PeterPanning,
    /// In the blend band of two partitions.
    SeamBand,
    /// At a hard boundary between two partitions: a 4-neighbour is served by another.
    SeamBoundary,
    /// The rest.
    Aliasing,
}

impl Cause {
    /// The five, in precedence order.
    pub const ALL: [Self; 5] = [
        Self::Acne,
        Self::PeterPanning,
        Self::SeamBand,
        Self::SeamBoundary,
        Self::Aliasing,
    ];

    /// The key in `results.json` and `results.csv`: `acne`, `peter_panning`, `seam_band`,
    /// `seam_boundary`, `aliasing`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Acne => "acne",
            Self::PeterPanning => "peter_panning",
            Self::SeamBand => "seam_band",
            Self::SeamBoundary => "seam_boundary",
            Self::Aliasing => "aliasing",
        }
    }

    /// The name in prose, legends and `report.html`'s classes: `acne`, `peter-panning`,
    /// `seam-band`, `seam-boundary`, `aliasing`.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Acne => "acne",
            Self::PeterPanning => "peter-panning",
            Self::SeamBand => "seam-band",
            Self::SeamBoundary => "seam-boundary",
            Self::Aliasing => "aliasing",
        }
    }

    /// What it means, as the causes picture's legend says it.
    #[must_use]
    pub fn meaning(self) -> &'static str {
        match self {
            Self::Acne => "acne (own surface's depth)",
            Self::PeterPanning => "peter-panning (lit by the bias)",
            Self::SeamBand => "seam: in a blend band",
            Self::SeamBoundary => "seam: at a partition boundary",
            Self::Aliasing => "aliasing (the rest)",
        }
    }

    /// Its colour in [`cause_image`].
    #[must_use]
    pub fn colour(self) -> [u8; 3] {
        match self {
            Self::Acne => ACNE,
            Self::PeterPanning => PETER_PANNING,
            Self::SeamBand => SEAM_BAND,
            Self::SeamBoundary => SEAM_BOUNDARY,
            Self::Aliasing => ALIASING,
        }
    }
}

/// A pixel whose first cause is acne: Okabe and Ito's reddish purple.
pub const ACNE: [u8; 3] = [204, 121, 167];
/// A pixel whose first cause is peter-panning: Okabe and Ito's orange.
pub const PETER_PANNING: [u8; 3] = [230, 159, 0];
/// A pixel whose first cause is a blend band's seam: Okabe and Ito's sky blue.
pub const SEAM_BAND: [u8; 3] = [86, 180, 233];
/// A pixel whose first cause is a partition boundary's seam: Okabe and Ito's yellow (their blue is
/// the difference image's falsely shadowed).
pub const SEAM_BOUNDARY: [u8; 3] = [240, 228, 66];
/// A pixel whose first cause is aliasing: Okabe and Ito's bluish green.
pub const ALIASING: [u8; 3] = [0, 158, 115];

/// Misclassified (light, pixel) pairs per cause, summed over lights.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Causes {
    /// [`Cause::Acne`].
    pub acne: u64,
    /// [`Cause::PeterPanning`].
    pub peter_panning: u64,
    /// [`Cause::SeamBand`].
    pub seam_band: u64,
    /// [`Cause::SeamBoundary`].
    pub seam_boundary: u64,
    /// [`Cause::Aliasing`].
    pub aliasing: u64,
}

impl Causes {
    /// The pairs of `cause`.
    #[must_use]
    pub fn of(&self, cause: Cause) -> u64 {
        match cause {
            Cause::Acne => self.acne,
            Cause::PeterPanning => self.peter_panning,
            Cause::SeamBand => self.seam_band,
            Cause::SeamBoundary => self.seam_boundary,
            Cause::Aliasing => self.aliasing,
        }
    }

    fn of_mut(&mut self, cause: Cause) -> &mut u64 {
        match cause {
            Cause::Acne => &mut self.acne,
            Cause::PeterPanning => &mut self.peter_panning,
            Cause::SeamBand => &mut self.seam_band,
            Cause::SeamBoundary => &mut self.seam_boundary,
            Cause::Aliasing => &mut self.aliasing,
        }
    }

    /// The seams of both kinds: the key `seam` of `results.json` and `results.csv`.
    #[must_use]
    pub fn seam(&self) -> u64 {
        self.seam_band + self.seam_boundary
    }

    /// The pairs of each cause in precedence order ([`Cause::ALL`]), joined by `separator`: a
    /// table's cells.
    #[must_use]
    pub fn joined(&self, separator: &str) -> String {
        Cause::ALL
            .map(|cause| self.of(cause).to_string())
            .join(separator)
    }

    /// Every cause's pairs: the misclassified pairs.
    #[must_use]
    pub fn total(&self) -> u64 {
        Cause::ALL.iter().map(|&cause| self.of(cause)).sum()
    }

    /// Counts one more pair of `cause`.
    pub fn count(&mut self, cause: Cause) {
        *self.of_mut(cause) += 1;
    }
}

/// `N acne, N peter-panning, N seam-band, N seam-boundary, N aliasing`.
impl fmt::Display for Causes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, cause) in Cause::ALL.into_iter().enumerate() {
            let separator = if k == 0 { "" } else { ", " };
            write!(f, "{separator}{} {}", self.of(cause), cause.label())?;
        }
        Ok(())
    }
}

impl AddAssign for Causes {
    fn add_assign(&mut self, other: Self) {
        for cause in Cause::ALL {
            *self.of_mut(cause) += other.of(cause);
        }
    }
}

/// A combination's misclassified pairs, each with its cause.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Attribution {
    /// Per light (the scene's order), per pixel (row-major, row 0 at the bottom): the cause of the
    /// pair's misclassification; `None` where it is correct or not judged.
    pub per_pixel: Vec<Vec<Option<Cause>>>,
    /// The pairs per cause, summed over lights.
    pub counts: Causes,
}

/// The lookup that tells what the bias did: no bias at all, the technique's filter. The one place
/// this module names a bias.
fn unbiased(filter: Filter) -> Lookup {
    Lookup::new(Bias::NONE, filter)
}

/// One light's maps as attribution reads them.
struct LightMaps<'a> {
    shadow: &'a LightShadow,
    /// Per partition, its map read with no bias.
    unbiased: Vec<Lookup>,
    /// Per partition, the inverse of its projective map's `clip_from_world`.
    inverse: Vec<Option<DMat4>>,
}

/// What attribution reads besides the light: the scene's view and surfaces, the eye pass and the
/// ray caster.
struct Context<'a> {
    view: Eye,
    groups: &'a [u32],
    eye: &'a EyeImage,
    bvh: &'a Bvh,
}

/// Gives every misclassified pair of the shadows `lights` (with lit fractions `lit`, as
/// `shadowlab_shadow::Shadows` holds them) of `scene`, seen in `eye` and judged against `truth`,
/// its cause (module docs). `filter(light, partition)` is the filter that partition's map was
/// looked up with; `bvh` is the scene's ray-casting hierarchy ([`crate::truth::scene_bvh`]).
///
/// # Errors
/// [`AnalysisError::BvhMismatch`] if `bvh` was built over another mesh than the scene's.
///
/// # Panics
/// If `lit`, `truth`, `lights` and `eye` differ in their numbers of lights or pixels.
pub fn attribute(
    scene: &Scene,
    eye: &EyeImage,
    truth: &Truth,
    (lights, lit): (&[LightShadow], &[Vec<f64>]),
    filter: impl Fn(usize, usize) -> Filter,
    bvh: &Bvh,
) -> Result<Attribution, AnalysisError> {
    if bvh.triangle_count() != scene.mesh.triangle_count() {
        return Err(AnalysisError::BvhMismatch {
            bvh: bvh.triangle_count(),
            mesh: scene.mesh.triangle_count(),
        });
    }
    let pixels = eye.triangle.len();
    assert!(
        lights.len() == truth.lit.len() && lit.len() == truth.lit.len(),
        "attribute: {} lights' maps and {} lights' lit fractions for a truth of {} lights",
        lights.len(),
        lit.len(),
        truth.lit.len()
    );
    assert_eq!(
        pixels,
        eye.width as usize * eye.height as usize,
        "attribute: the eye image's triangles do not fill width × height"
    );
    let context = Context {
        view: scene_eye(scene),
        groups: scene.mesh.groups(),
        eye,
        bvh,
    };
    let width = (eye.width as usize).max(1);
    let mut per_pixel = Vec::with_capacity(lights.len());
    let mut counts = Causes::default();
    for (index, shadow) in lights.iter().enumerate() {
        let (truth_lit, outside) = (&truth.lit[index], &truth.outside_cone[index]);
        let fractions = &lit[index];
        assert!(
            truth_lit.len() == pixels && outside.len() == pixels && fractions.len() == pixels,
            "attribute: light {index} has {} truth values and {} lit fractions for {pixels} pixels",
            truth_lit.len(),
            fractions.len()
        );
        let maps = LightMaps {
            shadow,
            unbiased: (0..shadow.maps.len())
                .map(|k| unbiased(filter(index, k)))
                .collect(),
            inverse: shadow
                .maps
                .iter()
                .map(|(_, map)| map.setup.mapping.clip_from_world().map(|m| m.inverse()))
                .collect(),
        };
        // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers"); each chunk
        // counts its own causes, and the counts are summed (`tally`).
        let mut causes: Vec<Option<Cause>> = rayon::iter::repeat_n(None, pixels).collect();
        counts += tally::total(
            causes
                .par_chunks_mut(width * ATTRIBUTION_ROWS)
                .enumerate()
                .map(|(chunk, out)| {
                    let first = chunk * width * ATTRIBUTION_ROWS;
                    let mut chunk_counts = Causes::default();
                    for (k, cause) in out.iter_mut().enumerate() {
                        let pixel = first + k;
                        let (Some(truly_lit), false) = (truth_lit[pixel], outside[pixel]) else {
                            continue;
                        };
                        if eye.triangle[pixel] == NO_TRIANGLE {
                            continue;
                        }
                        let classified_lit = fractions[pixel] >= LIT_THRESHOLD;
                        if classified_lit != truly_lit {
                            let found = cause_of(&context, &maps, pixel, classified_lit);
                            chunk_counts.count(found);
                            *cause = Some(found);
                        }
                    }
                    chunk_counts
                }),
        );
        per_pixel.push(causes);
    }
    Ok(Attribution { per_pixel, counts })
}

/// The cause of a misclassified pair: falsely lit if `classified_lit`, else falsely shadowed.
fn cause_of(
    context: &Context<'_>,
    maps: &LightMaps<'_>,
    pixel: usize,
    classified_lit: bool,
) -> Cause {
    let eye = context.eye;
    let (position, normal) = (eye.position[pixel], eye.normal[pixel]);
    let shadow = maps.shadow;
    let serving = served(
        &shadow.maps,
        |(p, _)| p,
        &shadow.selection,
        &context.view,
        position,
    );
    if let Some(serving) = serving {
        if classified_lit {
            let unbiased = serving
                .combine(|k| maps.unbiased[k].lit_fraction(&shadow.maps[k].1, position, normal));
            if unbiased < LIT_THRESHOLD && !self_blocked(context, maps, serving.index, pixel) {
                return Cause::PeterPanning;
            }
        } else if self_blocked(context, maps, serving.index, pixel) {
            return Cause::Acne;
        }
    }
    if shadow.maps.len() > 1 {
        let index = |p: usize| {
            served(
                &shadow.maps,
                |(partition, _)| partition,
                &shadow.selection,
                &context.view,
                eye.position[p],
            )
            .map(|s| s.index)
        };
        if serving.is_some_and(|s| s.blend.is_some()) {
            return Cause::SeamBand;
        }
        let own = serving.map(|s| s.index);
        if own.is_some_and(|own| {
            neighbours(eye, pixel)
                .into_iter()
                .flatten()
                .any(|n| index(n).is_some_and(|other| other != own))
        }) {
            return Cause::SeamBoundary;
        }
    }
    Cause::Aliasing
}

/// The 4-neighbours of `pixel` that see a surface.
fn neighbours(eye: &EyeImage, pixel: usize) -> [Option<usize>; 4] {
    let width = eye.width as usize;
    let (x, y) = (pixel % width, pixel / width);
    let height = eye.height as usize;
    let visible = |p: usize| (eye.triangle[p] != NO_TRIANGLE).then_some(p);
    [
        (x > 0).then(|| pixel - 1).and_then(visible),
        (x + 1 < width).then(|| pixel + 1).and_then(visible),
        (y > 0).then(|| pixel - width).and_then(visible),
        (y + 1 < height).then(|| pixel + width).and_then(visible),
    ]
}

/// Whether partition `index`'s map blocks `pixel`'s point with its own surface: the texel
/// holding the point stores a depth in front of it, and the texel centre's ray first hits the
/// point's triangle or its mesh group.
fn self_blocked(context: &Context<'_>, maps: &LightMaps<'_>, index: usize, pixel: usize) -> bool {
    let map = &maps.shadow.maps[index].1;
    let Some(window) = map.setup.mapping.window(context.eye.position[pixel]) else {
        return false;
    };
    // The texel the nearest lookup reads.
    let Some((i, j)) = map.texel_of(window) else {
        return false;
    };
    if map.depth(i, j) >= window.z {
        return false;
    }
    let Some(stored) = texel_surface(context.bvh, map, maps.inverse[index], (i, j)) else {
        return false;
    };
    let receiver = context.eye.triangle[pixel];
    let group = |t: u32| context.groups.get(t as usize).copied();
    stored == receiver || (group(stored).is_some() && group(stored) == group(receiver))
}

/// The triangle whose depth texel `(i, j)` of `map` stores: the first hit of the texel centre's
/// ray from the light's side (module docs); `inverse` is the inverse of a projective map's
/// `clip_from_world`.
fn texel_surface(
    bvh: &Bvh,
    map: &ShadowMap,
    inverse: Option<DMat4>,
    (i, j): (u32, u32),
) -> Option<u32> {
    let side = f64::from(map.resolution);
    // NDC of the texel centre, as the non-projective maps are cast (`ShadowMap::cast`).
    let centre = |k: u32| (f64::from(k) + 0.5) / side * 2.0 - 1.0;
    let (x, y) = (centre(i), centre(j));
    let (ray, t_max) = match (&map.setup.mapping, inverse) {
        (ShadowMapping::Logarithmic(log), _) => {
            let (from, to) = log.texel_ray(x, y);
            (Ray::new(from, to - from).ok()?, 1.0)
        }
        (ShadowMapping::Paraboloid(map), _) => {
            let (from, to) = map.texel_ray(x, y)?;
            (Ray::new(from, to - from).ok()?, 1.0)
        }
        (ShadowMapping::Projective(_), Some(inverse)) => projective_ray(bvh, inverse, x, y)?,
        (ShadowMapping::Projective(_), None) => return None,
    };
    bvh.closest_hit(&ray, 0.0, t_max).map(|hit| hit.triangle)
}

/// The ray through NDC `(x, y)` of a projective map whose clip → world matrix is `inverse`, from
/// the smallest window depth it stores to the largest, with its parameter's end: the points of
/// NDC depth −1 to 1 whose clip `w` is positive.
fn projective_ray(bvh: &Bvh, inverse: DMat4, x: f64, y: f64) -> Option<(Ray, f64)> {
    let near = inverse * DVec4::new(x, y, -1.0, 1.0);
    let far = inverse * DVec4::new(x, y, 1.0, 1.0);
    let point = |q: DVec4| q.truncate() / q.w;
    // Where w crosses zero the points run off to infinity along the homogeneous point's xyz
    // (approached with w > 0).
    let at_infinity = || {
        let s = near.w / (near.w - far.w);
        (near + (far - near) * s).truncate()
    };
    match (near.w > 0.0, far.w > 0.0) {
        (true, true) => {
            let from = point(near);
            Some((Ray::new(from, point(far) - from).ok()?, 1.0))
        }
        // From the near point out to infinity.
        (true, false) => Some((Ray::new(point(near), at_infinity()).ok()?, f64::INFINITY)),
        // In from infinity to the far point: cast back from beyond the scene.
        (false, true) => {
            let to = point(far);
            let direction = at_infinity().try_normalize()?;
            let (low, high) = bvh.bounds()?;
            let reach = (0..8)
                .map(|corner| {
                    let c = DVec3::new(
                        if corner & 1 == 0 { low.x } else { high.x },
                        if corner & 2 == 0 { low.y } else { high.y },
                        if corner & 4 == 0 { low.z } else { high.z },
                    );
                    (c - to).dot(direction)
                })
                .fold(f64::NEG_INFINITY, f64::max);
            if reach <= 0.0 {
                return None;
            }
            let from = to + direction * (2.0 * reach);
            Some((Ray::new(from, -direction).ok()?, 2.0 * reach))
        }
        (false, false) => None,
    }
}

/// The misclassified pixels coloured by cause (8-bit sRGB, row-major, row 0 at the bottom like
/// `eye`): the colour of the first cause (in precedence order) of any light's misclassified pair,
/// else [`CORRECT_LIT`] where at least one judged light lights the point, else [`CORRECT_SHADOW`];
/// [`BACKGROUND`] where nothing is visible — the difference image's greys and black.
///
/// # Panics
/// If `attribution`, `truth` and `eye` differ in their numbers of lights or pixels.
#[must_use]
pub fn cause_image(attribution: &Attribution, truth: &Truth, eye: &EyeImage) -> Vec<[u8; 3]> {
    assert_eq!(
        attribution.per_pixel.len(),
        truth.lit.len(),
        "cause_image: the attribution and the truth have different numbers of lights"
    );
    (0..eye.triangle.len())
        .into_par_iter()
        .map(|pixel| {
            if eye.triangle[pixel] == NO_TRIANGLE {
                return BACKGROUND;
            }
            let first = Cause::ALL.into_iter().find(|cause| {
                attribution
                    .per_pixel
                    .iter()
                    .any(|light| light[pixel] == Some(*cause))
            });
            if let Some(cause) = first {
                return cause.colour();
            }
            let lit_by_one = truth
                .lit
                .iter()
                .zip(&truth.outside_cone)
                .any(|(lit, outside)| lit[pixel] == Some(true) && !outside[pixel]);
            if lit_by_one {
                CORRECT_LIT
            } else {
                CORRECT_SHADOW
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use glam::DVec4;

    use super::*;

    /// A hierarchy of squares of half-side 10 across the z axis... placed across `direction` at
    /// the given distances from `origin`; triangle 2k and 2k + 1 make square k.
    fn squares(origin: DVec3, direction: DVec3, distances: &[f64]) -> Bvh {
        let axis = direction.normalize();
        let (a, b) = axis.any_orthonormal_pair();
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for (k, d) in distances.iter().enumerate() {
            let centre = origin + axis * *d;
            let base = u32::try_from(4 * k).unwrap();
            for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                positions.push(centre + (a * s + b * t) * 10.0);
            }
            triangles.push([base, base + 1, base + 2]);
            triangles.push([base, base + 2, base + 3]);
        }
        Bvh::new(&positions, &triangles).unwrap()
    }

    /// The square (index) the texel ray of `clip → world` matrix `inverse` through NDC `(x, y)`
    /// hits first.
    fn first_square(bvh: &Bvh, inverse: DMat4, (x, y): (f64, f64)) -> Option<u32> {
        let (ray, t_max) = projective_ray(bvh, inverse, x, y)?;
        bvh.closest_hit(&ray, 0.0, t_max)
            .map(|hit| hit.triangle / 2)
    }

    /// The NDC depth of `world` through `clip_from_world`, if it lies in front (w > 0).
    fn depth(clip_from_world: DMat4, world: DVec3) -> Option<f64> {
        let clip = clip_from_world * world.extend(1.0);
        (clip.w > 0.0).then(|| clip.z / clip.w)
    }

    /// Claim: the texel ray's first hit is the surface of least window depth among those in
    /// front of the projection centre, whether the segment of NDC depths −1 to 1 stays in front
    /// (w > 0 throughout), runs from the near end out to infinity, or comes in from infinity to
    /// the far end — and a segment wholly behind finds nothing.
    #[test]
    fn the_texel_ray_finds_the_nearest_stored_surface() {
        let (x, y) = (0.25, -0.5);
        let cases = [
            // w = 1: the segment from (x, y, −1) to (x, y, 1).
            (DMat4::IDENTITY, 1.0),
            // w = z + 0.5: in front for z > −0.5, from infinity in to the far end.
            (
                DMat4::from_cols(
                    DVec4::X,
                    DVec4::Y,
                    DVec4::new(0.0, 0.0, 1.0, 1.0),
                    DVec4::new(0.0, 0.0, 0.0, 0.5),
                ),
                1.0,
            ),
            // w = 0.5 − z: in front for z < 0.5, from the near end out to infinity.
            (
                DMat4::from_cols(
                    DVec4::X,
                    DVec4::Y,
                    DVec4::new(0.0, 0.0, 1.0, -1.0),
                    DVec4::new(0.0, 0.0, 0.0, 0.5),
                ),
                -1.0,
            ),
        ];
        for (k, (inverse, end)) in cases.into_iter().enumerate() {
            let clip_from_world = inverse.inverse();
            // The world line of the texel: the end point at NDC depth `end`, and where it heads.
            let q = inverse * DVec4::new(x, y, end, 1.0);
            let anchor = q.truncate() / q.w;
            let other = inverse * DVec4::new(x, y, 0.0, 1.0);
            let toward = other.truncate() / other.w - anchor;
            // Squares along the line, beyond and before the anchor; the stored one has the least
            // NDC depth in [−1, 1] and in front.
            let distances = [0.3, 0.6, 1.9, 40.0, -0.2, -5.0];
            let bvh = squares(anchor, toward, &distances);
            let stored = distances
                .iter()
                .enumerate()
                .filter_map(|(s, d)| {
                    let z = depth(clip_from_world, anchor + toward.normalize() * *d)?;
                    (-1.0..=1.0).contains(&z).then_some((s, z))
                })
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(s, _)| u32::try_from(s).unwrap());
            assert!(stored.is_some(), "case {k}: no square in the map's volume");
            assert_eq!(first_square(&bvh, inverse, (x, y)), stored, "case {k}");
        }
        // w = −1 throughout: nothing in front.
        let behind = DMat4::from_cols(
            DVec4::X,
            DVec4::Y,
            DVec4::Z,
            DVec4::new(0.0, 0.0, 0.0, -1.0),
        );
        let bvh = squares(DVec3::ZERO, DVec3::Z, &[0.5]);
        assert_eq!(first_square(&bvh, behind, (x, y)), None);
    }
}
