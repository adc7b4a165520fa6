//! Scene-optimized shadow maps: Chong & Gortler, *Scene Optimized Shadow Mapping*, Harvard
//! TR-11-06, 2006 (CG06), Algorithm 1, with the equations as formulas.md §6 reconstructs them.
//!
//! P, the matrix from the paper's light space to the shadow map, is chosen to minimise the
//! screen-space footprint of the map's texels at the pixels that matter — those near shadow
//! boundaries — instead of being fitted to a body by a rule.
//!
//! # Coordinates (CG06 §2, formulas.md §6.1)
//! - **Light space** `X_l = (X¹, X², X³, 1)`. For a spot light it is the spot's eye space
//!   ([`shadowlab_hull::ViewPose::view_matrix`]): the light at the origin, and P, a camera at the
//!   light, sends the origin to `[0, 0, k, 0]`: P's **fourth** column is `(0, 0, k, 0)`. For a
//!   directional light it is LiSPSM's light space (`crate::frame`: y toward the light), translated
//!   to the centre of the samples' bounding box and scaled by `1/ρ`, ρ half the diagonal of their
//!   extent across the light (x and z). The light is the point at infinity `(0, 1, 0, 0)` and P's
//!   **second** column is `(0, 0, k, 0)`: light rays stay parallel to the map's depth axis. The
//!   scale gives the line search's angles the same meaning in a scene of any size: turning the
//!   orthographic `p̃_4 = (0, 0, 0, 1)` by θ puts P's projection centre `ρ·cot θ` from the centre.
//! - So rows 1, 2 and 4 of P have a zero at the light's entry; their other three entries are the
//!   free parameters (CG06 §2.1: nine, one lost to `|p̃_4| = 1`). [`Rows`] holds them as 3-vectors,
//!   and [`LightPoint::reduce`] drops the same entry from points and from the columns of `Q⁻¹`: every
//!   dot product of eq. 5 and of Appendix A is a dot product of these *reduced* vectors.
//! - **Screen** `x_s = (x1, x2, x3, 1)`: the eye's window coordinates in pixels of the full image
//!   (`camera.width × camera.height`, x right, y up, as `shadowlab_raster`), and x3 the window depth
//!   `(z_ndc + 1)/2`. `Q = viewport · projection · view_eye · (light space → world)`, so `w_q` is the
//!   eye depth; `q_j` are the columns of `Q⁻¹`. Eq. 4 eliminates x3, so h does not depend on that
//!   choice, and scaling x1 and x2 together scales h and leaves its minimiser alone.
//! - **Map** `u1, u2 ∈ [−1, 1]` across the map (GL's NDC), so h is in (pixels per half map)²;
//!   multiply by `(2/resolution)²` for pixels per texel, squared.
//! - **Depth slope** `∂x3/∂x_j` (eq. 4), from the plane `π` of the visible triangle: the points of
//!   the plane satisfy `π·(S⁻¹ x_s) = 0` with `S` world → screen, so `∂x3/∂x_j = −(π·s_j)/(π·s_3)`,
//!   `s_j` the columns of `S⁻¹`. CG06 takes it from the z-buffer and its neighbours (App. A); inside
//!   one triangle that measures the same plane, and at object boundaries this gives the true slope
//!   instead of the gap's.
//!
//! # Objective and gradient (eqs. 3–6, Appendix A; formulas.md §6.2–6.6)
//! `h(P) = Σ ‖J⁻¹‖²_F = Σ (1/det²J) Σ_{i,j=1,2} (du_i/dx_j)²` with `du_i/dx_j` the total derivative
//! on the visible surface (eq. 4) built from eq. 5. Writing `q̃_j = q_j + (∂x3/∂x_j) q_3` (the
//! surface's tangent per pixel step), `J_ij = w_q/a_4 · (p̃_i·q̃_j − a_i/a_4 · p̃_4·q̃_j)` with
//! `a_i = p̃_i·X_l`, and Appendix A gives `∇_{p̃_4} J_ij = w_q/a_4² · [(2 a_i (p̃_4·q̃_j)/a_4 −
//! p̃_i·q̃_j) X_l − a_i q̃_j]`; `∇h = Σ ∇S/det² − 2 S ∇det/det³` ([`Objective`]).
//!
//! # Samples (Algorithm 1 steps 1–3; CG06 §2.2, §3, §4)
//! 1. A low-resolution eye pass ([`Readback`], 70 × 70 by default, §4) with the scene's camera:
//!    visible point, its triangle and normal, and eye depth per pixel. Pixels outside the planned
//!    (sub-)frustum's `[near, far]` count as showing nothing.
//! 2. The shadow state of each pixel, looked up ([`Filter::Nearest`], [`Bias::DEFAULT`]) in the
//!    initial map: the paper's "normal shadow map with frustum limiting", here
//!    [`Technique::UniformLimited`] for the same (sub-)frustum, rendered at
//!    [`INITIAL_MAP_RESOLUTION`].
//! 3. A shadowed pixel is a sample if (a) one of its four neighbours is lit — "pixel center samples
//!    near shadow boundaries" (§2.1); (b) it lies on the border of the image — "shadowed points
//!    adjacent to the screen boundary" (§3); or (c) it is next to a depth discontinuity — "some
//!    shadowed points adjacent to geometry discontinuities" (§3): a neighbour shows nothing, or the
//!    acceleration in depth (§4: "thresholding the acceleration in z") along a row or column,
//!    `|ρ₋ − 2ρ + ρ₊|` of the reciprocal eye depth ρ (affine in screen space on a plane, like the
//!    window depth), exceeds [`DEPTH_ACCELERATION`] · ρ. Our lookups treat points outside the map as
//!    lit, so these rules apply to shadowed pixels, as §3 says for that case.
//!
//! Every sample bounds the map (the hull below). Samples whose triangle contains the ray to the
//! light within [`GRAZING_COS`] (`|n̂·l̂|` below it) are left out of h: there `det J = 0` for every P
//! with its projection centre at the light (formulas.md §9.9), and their `1/det²` would swamp h
//! without P being able to change it. The report counts them.
//!
//! # Iteration (Algorithm 1 step 4; CG06 §2.2, §4)
//! From the initial map's `p̃_4` (the spot's axis; `(0, 0, 0, 1)` for a directional light):
//! 1. **Affine part**: the samples are projected by the candidate P, the minimum-area rectangle of
//!    their convex hull is found ([`shadowlab_hull::MinAreaRect`], rotating calipers, §2.2 and
//!    Freeman & Shapira 1975), and rows 1 and 2 map it onto the middle `1 − 2·border` of the map on each axis
//!    ([`BORDER`], §4: "map the light's frustum into a bordered region of the shadow map …
//!    assuming the border is unusable"; the paper gives no width). The hull is computed once, on a
//!    fixed chart of the light's image plane, and each candidate maps its vertices: a projective map
//!    that keeps every point in front preserves convex hulls (§2.1's remark on the constraints).
//! 2. **Projective part**: `p̃_4`, kept unit, is turned against the tangential gradient
//!    `(I − p̃_4 p̃_4ᵀ)∇h` — about the axis `p̃_4 × (−∇h)` — by each angle of
//!    [`LINE_SEARCH_DEGREES`], each candidate gets its own affine part, and the one with the smallest
//!    h is kept if it is smaller than the current h; otherwise the search stops early.
//!    [`ITERATIONS`] (three, §4) iterations at most.
//! 3. **Constraints** (eq. 3): `0 ≤ u ≤ width` holds by construction (the rectangle); the near
//!    constraint `|near| < w_p` is enforced on the convex hull of the samples, which must be strictly
//!    in front (`p̃_4·X_l > 0`), and on the whole map: the ray through each corner of the map's window
//!    may be at most [`MAX_OFF_AXIS_DEGREES`] from the reference axis — `p̃_4` for a spot light (the
//!    map's field of view stays below 160°, so `w_p ≥ |X_l| cos 80°` on it), the chart's axis for a
//!    directional light (the window stays within `tan 80° ≈ 5.7` sample radii of the samples'
//!    centre, so it is bounded and in front). A candidate that breaks either is skipped.
//!
//! # Depth (row 3)
//! CG06 leaves row 3 free (§2.1). It is set so that the map's depth covers everything that can cast a
//! shadow into it: the focus body B of the [`crate::FocusPolicy`] (`conv(V ∪ l) ∩ S ∩ L`) clipped to
//! the map's window W (`|u1|, |u2| ≤ 1`, which implies `w_p ≥ 0`). The constraint above keeps
//! `w_p > 0` on B ∩ W (for a spot light B lies beyond the cone's near plane); the depth is
//! `u3 = A + B·ζ`, `ζ = (d·X_l)/(p̃_4·X_l)` with `d` the light's axis pointing away from it
//! (`−1` at the light's entry), which grows away from the light along every light ray, and A, B map
//! ζ's range over B ∩ W's vertices onto `[−1, 1]`. [`LightSetup::focus_body`] holds those vertices.
//!
//! # Deviations from the paper
//! - No affine skew (CG06 Fig. 2's heuristic, "minimal benefit in practice") and no aspect rule
//!   (shadowlab's maps are square).
//! - The shadow states come from this frame's uniform-limited map (what §3 does "every couple
//!   frames"), not from the previous frame's optimized map, and nothing is carried between frames
//!   (§4's anti-swimming start and its 80 % median rule): every frame is planned from scratch, so
//!   the result is a function of the frame alone.
//! - Samples at object boundaries stay in h (their slope is the triangle's, not the gap's); samples
//!   grazed by the light leave h (above).
//! - None in the step itself, but a measured property of it: Appendix A's gradient holds rows 1 and
//!   2 fixed, and the refit of the affine part then changes them, so the paper's direction need not
//!   descend the refitted objective. On a plane facing a light 10° off its optimal axis it points
//!   away, every candidate is worse and the search stops at the start (a test shows it). On the
//!   built-in scenes the first step lowers h by 1.4–13× and the search mostly stops after it,
//!   0.04–38 % above the best axis of a brute-force 2°×5° search. [`StepDirection::Refitted`]
//!   (technique `optimal:refit`) turns against the gradient of the refitted objective instead
//!   ([`REFIT_DIFFERENCE`]): it comes back on the facing plane and ends at most 8 % above the
//!   brute-force best (below it on `outdoor` and `dueling-frusta`, the grid being coarse), with
//!   0–28 % lower h than the paper's step. Measured on misclassified pixels
//!   (750²–2000²) that buys 7–12 % fewer on `dueling-frusta` (at 1000² and up) and `bunny`, nothing
//!   on `outdoor` and `cad-lattice`, and 1–3 % more on `chess-spot`: h is a proxy. The paper's step
//!   stays the default.
//! - With fewer than three samples off one line there is nothing to fit: the initial map is kept,
//!   and the report says so (`h` is `None`).
//!
//! Everything is deterministic: no randomness, sums in sample order, ties to the first candidate;
//! the same scene gives the same P bit for bit on any number of threads.

use glam::{DMat4, DVec2, DVec3, DVec4};
use shadowlab_hull::{
    ConvexHull2, ConvexPolyhedron, MinAreaRect, Plane, Tolerances, convex_hull_2d,
};
use shadowlab_raster::{
    DepthFormat, EyeImage, EyeTarget, NO_TRIANGLE, RasterOptions, Rasterizer, Triangles,
};
use shadowlab_scene::Scene;

use crate::bias::Bias;
use crate::error::ShadowError;
use crate::focus::focus_polyhedron;
use crate::frame::LightFrame;
use crate::input::{LightSource, PlanInput};
use crate::lookup::{Filter, Lookup};
use crate::map::{MapOptions, ShadowMap};
use crate::partition::Partition;
use crate::plan::{Splits, partition_inputs};
use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
use crate::technique::{StepDirection, Technique};
use crate::warp::Extents;

/// Side of the low-resolution eye pass of Algorithm 1 step 1, in pixels: CG06 §4, "for scenes
/// tested it was sufficient to read back only 70x70 buffers".
pub const READBACK_SIZE: (u32, u32) = (70, 70);

/// Side of the initial map the samples' shadow states are read from, in texels. CG06 read them
/// from the previous frame's map, at the map's own resolution; shadowlab plans each frame from
/// scratch. Measured over the built-in scenes at 1000² and 2000² (docs/benchmarks.md): against
/// 512², 1024² misclassifies 43 % fewer pixels on `outdoor` and 32 % fewer on `cad-lattice`, where
/// a coarser map misses thin poles and bars and so samples none of their shadows' boundaries, and
/// within 3 % elsewhere, for 3–8 ms more per light; 2048² gains nothing more for 30 ms.
pub const INITIAL_MAP_RESOLUTION: u32 = 1024;

/// The number of iterations of step 4: CG06 §4, "in all our tests, three iterations were
/// sufficient to reach convergence".
pub const ITERATIONS: usize = 3;

/// The rotations of `p̃_4` tried per iteration, degrees: CG06 §4, "for each iteration we tested 3,
/// 5, 8, 15, 23, 30, 40, and 50 degree rotations".
pub const LINE_SEARCH_DEGREES: [f64; 8] = [3.0, 5.0, 8.0, 15.0, 23.0, 30.0, 40.0, 50.0];

/// The border left around the samples, as a fraction of the map's side on each side: the samples'
/// rectangle fills the middle `1 − 2·BORDER` of each axis (7/8; 77 % of the texels). CG06 §4 maps
/// the samples "into a bordered region of the shadow map" because a hull of subsampled pixels is
/// "too aggressively small", and gives no width.
pub const BORDER: f64 = 0.0625;

/// The largest angle, degrees, between the ray through a corner of the map's window and the
/// reference axis (`p̃_4` for a spot light, the chart's axis for a directional one): the near
/// constraint of eq. 3, made scale-free.
pub const MAX_OFF_AXIS_DEGREES: f64 = 80.0;

/// The depth-discontinuity threshold: a pixel whose reciprocal eye depth ρ has a second difference
/// along a row or a column larger than this times ρ is next to a discontinuity (a jump of about 1 %
/// in depth between neighbours). Zero on any plane.
pub const DEPTH_ACCELERATION: f64 = 0.01;

/// Samples whose triangle's unit normal `n̂` and the unit vector toward the light `l̂` have
/// `|n̂·l̂|` below this (the light within 0.06° of the surface) are left out of h.
pub const GRAZING_COS: f64 = 1e-3;

/// How the scene-optimized map is planned. Defaults are the paper's where it gives one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OptimalOptions {
    /// Width and height of the low-resolution eye pass, pixels. Default: [`READBACK_SIZE`].
    pub readback: (u32, u32),
    /// Side of the initial (uniform-limited) map, texels. Default: [`INITIAL_MAP_RESOLUTION`].
    pub initial_resolution: u32,
    /// The most iterations of step 4. Default: [`ITERATIONS`].
    pub iterations: usize,
    /// The border around the samples, a fraction of the map's side in `[0, 0.5)`. Default:
    /// [`BORDER`].
    pub border: f64,
    /// Which way each step turns `p̃_4`. Default: the paper's ([`StepDirection::Paper`]).
    pub direction: StepDirection,
}

impl Default for OptimalOptions {
    fn default() -> Self {
        Self {
            readback: READBACK_SIZE,
            initial_resolution: INITIAL_MAP_RESOLUTION,
            iterations: ITERATIONS,
            border: BORDER,
            direction: StepDirection::Paper,
        }
    }
}

impl OptimalOptions {
    /// Checks the border (the sizes are checked by the rasterizer).
    fn validate(&self) -> Result<(), ShadowError> {
        if (0.0..0.5).contains(&self.border) {
            Ok(())
        } else {
            Err(not_defined(format!(
                "the border must lie in [0, 0.5), not {}",
                self.border
            )))
        }
    }
}

fn not_defined(reason: impl Into<String>) -> ShadowError {
    ShadowError::NotDefined {
        technique: Technique::Optimal(StepDirection::Paper).key(),
        reason: reason.into(),
    }
}

/// Where the light is in the paper's light space; it fixes one column of P (formulas.md §6.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightPoint {
    /// A spot light, at the origin `(0, 0, 0, 1)`: P's fourth column is `(0, 0, k, 0)`, and the
    /// reduced vectors are entries 1–3. Points the map sees have a negative third entry (in front
    /// of the spot, which looks down −z).
    Origin,
    /// A directional light, the point at infinity `(0, 1, 0, 0)`: P's second column is
    /// `(0, 0, k, 0)`, and the reduced vectors are entries 1, 3 and 4. Points have a third reduced
    /// entry of 1.
    Infinity,
}

impl LightPoint {
    /// The index of the light's homogeneous coordinate: the entry rows 1, 2 and 4 of P leave out.
    fn fixed(self) -> usize {
        match self {
            Self::Origin => 3,
            Self::Infinity => 1,
        }
    }

    /// The sign of the third reduced entry of every point the map can see.
    fn side(self) -> f64 {
        match self {
            Self::Origin => -1.0,
            Self::Infinity => 1.0,
        }
    }

    /// A light-space 4-vector without the light's entry.
    #[must_use]
    pub fn reduce(self, v: DVec4) -> DVec3 {
        match self {
            Self::Origin => v.truncate(),
            Self::Infinity => DVec3::new(v.x, v.z, v.w),
        }
    }

    /// A reduced row with a zero put back at the light's entry.
    #[must_use]
    pub fn expand(self, r: DVec3) -> DVec4 {
        match self {
            Self::Origin => r.extend(0.0),
            Self::Infinity => DVec4::new(r.x, 0.0, r.y, r.z),
        }
    }

    /// `d`: the light's axis, pointing away from the light (`−1` at the light's entry). `d·X_l` grows
    /// away from the light along a light ray.
    fn away(self) -> DVec4 {
        let mut d = DVec4::ZERO;
        d[self.fixed()] = -1.0;
        d
    }
}

/// One sample of the objective: a visible point near a shadow boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// `X̂`: the reduced light-space point (`X_l` without the light's entry).
    pub point: DVec3,
    /// `w_q`: the homogeneous coordinate of `Q·X_l`, the eye depth.
    pub w_q: f64,
    /// `(∂x3/∂x1, ∂x3/∂x2)`: the visible surface's window-depth slope per pixel (eq. 4).
    pub depth_slope: DVec2,
}

/// Rows 1, 2 and 4 of P, reduced (without their zero at the light's entry).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rows {
    /// `p̃_1`: the map's u1 (times `w_p`).
    pub p1: DVec3,
    /// `p̃_2`: the map's u2 (times `w_p`).
    pub p2: DVec3,
    /// `p̃_4`: `w_p`, the optical axis (unit after [`descend`]).
    pub p4: DVec3,
}

/// h of CG06 eq. 6 over a set of samples, given the first three columns of `Q⁻¹`, reduced.
#[derive(Clone, Debug, PartialEq)]
pub struct Objective {
    columns: [DVec3; 3],
    samples: Vec<Sample>,
}

/// One sample's `J` (eqs. 4–5) and what its gradient needs.
struct Jacobian {
    /// `J_ij = du_i/dx_j`.
    j: [[f64; 2]; 2],
    /// `a_i = p̃_i·X̂` for rows 1, 2, 4.
    a: [f64; 3],
    /// `t_ij = p̃_i·q̃_j` for rows 1, 2, 4 and the surface tangents `q̃_1`, `q̃_2`.
    t: [[f64; 2]; 3],
    det: f64,
}

impl Objective {
    /// The objective of `samples` with `columns` = `(q_1, q_2, q_3)`, the first three columns of
    /// `Q⁻¹` (reduced).
    #[must_use]
    pub fn new(columns: [DVec3; 3], samples: Vec<Sample>) -> Self {
        Self { columns, samples }
    }

    /// The samples.
    #[must_use]
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// `p̃_i·q_j` for rows 1, 2, 4 and columns 1–3.
    fn dots(&self, rows: &Rows) -> [[f64; 3]; 3] {
        [rows.p1, rows.p2, rows.p4].map(|r| self.columns.map(|q| r.dot(q)))
    }

    /// J of one sample (eqs. 4 and 5); `None` if the sample is not strictly in front of P
    /// (`p̃_4·X̂ ≤ 0`) or `det J` is zero or not finite.
    fn jacobian(sample: &Sample, rows: &Rows, dots: &[[f64; 3]; 3]) -> Option<Jacobian> {
        let x = sample.point;
        let a = [rows.p1.dot(x), rows.p2.dot(x), rows.p4.dot(x)];
        if a[2] <= 0.0 {
            return None;
        }
        let slope = [sample.depth_slope.x, sample.depth_slope.y];
        // p̃_i·q̃_j with q̃_j = q_j + (∂x3/∂x_j) q_3 (eq. 4 folded into eq. 5).
        let t: [[f64; 2]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| dots[i][j] + slope[j] * dots[i][2]));
        let scale = sample.w_q / a[2];
        let j: [[f64; 2]; 2] = std::array::from_fn(|i| {
            std::array::from_fn(|k| scale * (t[i][k] - a[i] / a[2] * t[2][k]))
        });
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        (det != 0.0 && det.is_finite()).then_some(Jacobian { j, a, t, det })
    }

    /// h(P) (eq. 6) for the reduced rows; `None` if a sample is not strictly in front of P or P
    /// maps its surface onto a line (`det J = 0`).
    #[must_use]
    pub fn value(&self, rows: &Rows) -> Option<f64> {
        let dots = self.dots(rows);
        let mut h = 0.0;
        for sample in &self.samples {
            let jac = Self::jacobian(sample, rows, &dots)?;
            let sum: f64 = jac.j.iter().flatten().map(|v| v * v).sum();
            h += sum / (jac.det * jac.det);
        }
        h.is_finite().then_some(h)
    }

    /// h(P) and its gradient `∂h/∂p̃_4` with rows 1 and 2 fixed (CG06 Appendix A; the assembly of
    /// formulas.md §6.6), reduced; `None` as for [`Self::value`].
    #[must_use]
    pub fn gradient(&self, rows: &Rows) -> Option<(f64, DVec3)> {
        let dots = self.dots(rows);
        let mut h = 0.0;
        // ∇h = Σ_s c_s X̂_s + Σ_j b_j q_j: the sample terms, and the columns' coefficients.
        let mut on_points = DVec3::ZERO;
        let mut on_columns = [0.0; 3];
        for sample in &self.samples {
            let Jacobian { j, a, t, det } = Self::jacobian(sample, rows, &dots)?;
            let sum: f64 = j.iter().flatten().map(|v| v * v).sum();
            let det2 = det * det;
            h += sum / det2;
            // κ_ij = ∂(S/det²)/∂J_ij = 2 J_ij/det² − 2 S/det³ · ∂det/∂J_ij.
            let d_det = [[j[1][1], -j[1][0]], [-j[0][1], j[0][0]]];
            let kappa: [[f64; 2]; 2] = std::array::from_fn(|i| {
                std::array::from_fn(|k| {
                    2.0 * j[i][k] / det2 - 2.0 * sum / (det2 * det) * d_det[i][k]
                })
            });
            // Appendix A with q̃_k: ∇J_ik = c (2 a_i t_4k/a_4 − t_ik) X̂ − c a_i q̃_k, c = w_q/a_4².
            let c = sample.w_q / (a[2] * a[2]);
            let mut on_point = 0.0;
            let mut on_tangent = [0.0; 2];
            for i in 0..2 {
                for k in 0..2 {
                    on_point += kappa[i][k] * c * (2.0 * a[i] * t[2][k] / a[2] - t[i][k]);
                    on_tangent[k] -= kappa[i][k] * c * a[i];
                }
            }
            on_points += sample.point * on_point;
            // q̃_k = q_k + (∂x3/∂x_k) q_3.
            on_columns[0] += on_tangent[0];
            on_columns[1] += on_tangent[1];
            on_columns[2] +=
                on_tangent[0] * sample.depth_slope.x + on_tangent[1] * sample.depth_slope.y;
        }
        let gradient = on_points
            + self.columns[0] * on_columns[0]
            + self.columns[1] * on_columns[1]
            + self.columns[2] * on_columns[2];
        (h.is_finite() && gradient.is_finite()).then_some((h, gradient))
    }
}

/// The result of step 4.
#[derive(Clone, Debug, PartialEq)]
pub struct Descent {
    /// The final rows; `p4` is unit.
    pub rows: Rows,
    /// h at the initial `p̃_4` with its affine part fitted to the samples: where the descent starts.
    pub initial_h: f64,
    /// h at the final rows.
    pub h: f64,
    /// The rotation accepted in each iteration, degrees (shorter than the iteration count if the
    /// search stopped early).
    pub steps_degrees: Vec<f64>,
}

/// The map's window fitted around the samples' hull on a chart of the light's image plane.
struct Window {
    light: LightPoint,
    /// The hull of the samples' chart points `(X̂₁, X̂₂)/|X̂₃|`, counter-clockwise.
    hull: Vec<DVec2>,
    /// `1 − 2·border`.
    scale: f64,
    /// `cos` of [`MAX_OFF_AXIS_DEGREES`].
    cos_limit: f64,
}

impl Window {
    fn new(light: LightPoint, hull: Vec<DVec2>, border: f64) -> Self {
        Self {
            light,
            hull,
            scale: 1.0 - 2.0 * border,
            cos_limit: MAX_OFF_AXIS_DEGREES.to_radians().cos(),
        }
    }

    /// Rows 1 and 2 for the unit axis `p4` (step 4b): the minimum-area rectangle around the hull's
    /// image, mapped onto the middle of the map; `None` if a hull vertex is not strictly in front,
    /// the image is flat, or a corner of the window breaks the off-axis bound.
    fn fit(&self, p4: DVec3) -> Option<Rows> {
        let side = self.light.side();
        // Image coordinates (e1·X̂, e2·X̂)/(p4·X̂) on the plane ⟂ p4.
        let (e1, e2) = p4.any_orthonormal_pair();
        let mut image = Vec::with_capacity(self.hull.len());
        for c in &self.hull {
            let lift = DVec3::new(c.x, c.y, side);
            let w = p4.dot(lift);
            if w <= 0.0 {
                return None;
            }
            image.push(DVec2::new(e1.dot(lift), e2.dot(lift)) / w);
        }
        let rect = MinAreaRect::of_points(&image).ok()?;
        let half = rect.half_extents();
        if half.min_element() <= 0.0 {
            return None;
        }
        let ([u, v], centre) = (rect.axes(), rect.center());
        // The whole window (the rectangle and its border): each corner's ray a·e1 + b·e2 + p4.
        let reference = match self.light {
            LightPoint::Origin => p4,
            LightPoint::Infinity => DVec3::Z,
        };
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let corner = centre + (u * (su * half.x) + v * (sv * half.y)) / self.scale;
            let ray = e1 * corner.x + e2 * corner.y + p4;
            if reference.dot(ray) < self.cos_limit * ray.length() {
                return None;
            }
        }
        let row = |axis: DVec2, half: f64| {
            (e1 * axis.x + e2 * axis.y - p4 * axis.dot(centre)) * (self.scale / half)
        };
        Some(Rows {
            p1: row(u, half.x),
            p2: row(v, half.y),
            p4,
        })
    }
}

/// The convex hull of the cover points on the chart `(X̂₁, X̂₂)/|X̂₃|`; `Ok(None)` if they have no
/// area there.
fn chart_hull(light: LightPoint, cover: &[DVec3]) -> Result<Option<Vec<DVec2>>, ShadowError> {
    let side = light.side();
    let chart = cover
        .iter()
        .map(|x| (x.z * side > 0.0).then(|| DVec2::new(x.x, x.y) / x.z.abs()))
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| not_defined("a sample lies behind the light's plane"))?;
    if chart.is_empty() {
        return Ok(None);
    }
    Ok(match convex_hull_2d(&chart)? {
        ConvexHull2::Polygon(polygon) => Some(polygon.vertices().to_vec()),
        ConvexHull2::Point(_) | ConvexHull2::Segment(..) => None,
    })
}

/// CG06 Algorithm 1 step 4 from the axis `p4` (normalised here): at most `options.iterations`
/// rotations of `p̃_4` against the tangential gradient, each chosen by the line search over
/// [`LINE_SEARCH_DEGREES`] with the affine part refitted around `cover` (the reduced points the map
/// must hold: every sample, also those left out of h).
///
/// # Errors
/// [`ShadowError::NotDefined`] if a cover point lies behind the light's plane, the cover points
/// have no area in the light's view (fewer than three off one line), `p4` is zero, or the start
/// breaks a constraint (a point not in front, a field of view over the bound) or gives no finite h.
pub fn descend(
    objective: &Objective,
    light: LightPoint,
    cover: &[DVec3],
    p4: DVec3,
    options: &OptimalOptions,
) -> Result<Descent, ShadowError> {
    options.validate()?;
    let hull = chart_hull(light, cover)?
        .ok_or_else(|| not_defined("the samples have no area in the light's view"))?;
    descend_from(
        objective,
        &Window::new(light, hull, options.border),
        p4,
        options,
    )
}

fn descend_from(
    objective: &Objective,
    window: &Window,
    p4: DVec3,
    options: &OptimalOptions,
) -> Result<Descent, ShadowError> {
    let p4 = p4
        .try_normalize()
        .ok_or_else(|| not_defined("the initial axis is zero"))?;
    let mut rows = window.fit(p4).ok_or_else(|| {
        not_defined(format!(
            "the initial map leaves a sample behind the light or needs a field of view over {}°",
            2.0 * MAX_OFF_AXIS_DEGREES
        ))
    })?;
    let mut h = objective
        .value(&rows)
        .ok_or_else(|| not_defined("the initial map maps a sample's surface onto a line"))?;
    let initial_h = h;
    let mut steps_degrees = Vec::new();
    for _ in 0..options.iterations {
        let tangential = match options.direction {
            StepDirection::Paper => {
                let Some((_, gradient)) = objective.gradient(&rows) else {
                    break;
                };
                // Rotating p̃_4 toward −(I − p̃_4 p̃_4ᵀ)∇h is rotating it about p̃_4 × (−∇h).
                gradient - rows.p4 * rows.p4.dot(gradient)
            }
            StepDirection::Refitted => {
                let Some(gradient) = refitted_gradient(objective, window, rows.p4) else {
                    break;
                };
                gradient
            }
        };
        let Some(toward) = (-tangential).try_normalize() else {
            break;
        };
        let mut best: Option<(f64, f64, Rows)> = None;
        for degrees in LINE_SEARCH_DEGREES {
            let (sin, cos) = degrees.to_radians().sin_cos();
            let Some(axis) = (rows.p4 * cos + toward * sin).try_normalize() else {
                continue;
            };
            let Some(candidate) = window.fit(axis) else {
                continue;
            };
            let Some(value) = objective.value(&candidate) else {
                continue;
            };
            if best.as_ref().is_none_or(|(b, ..)| value < *b) {
                best = Some((value, degrees, candidate));
            }
        }
        match best {
            Some((value, degrees, candidate)) if value < h => {
                (h, rows) = (value, candidate);
                steps_degrees.push(degrees);
            }
            _ => break,
        }
    }
    Ok(Descent {
        rows,
        initial_h,
        h,
        steps_degrees,
    })
}

/// The angle of the central differences of [`StepDirection::Refitted`], radians: far below the smallest
/// step of the line search (3°) and far above rounding — h is smooth in `p̃_4` wherever the fitted
/// rectangle keeps its orientation, and the differences are taken only where both sides fit.
pub const REFIT_DIFFERENCE: f64 = 1e-4;

/// The tangential gradient at the unit axis `p4` of `h*(p̃_4) = h(fit(p̃_4), p̃_4)`, the objective
/// with the affine rows refitted to each axis — what the line search compares — by central
/// differences along two orthonormal tangent directions ([`StepDirection::Refitted`]). `None`
/// where a difference point cannot be fitted or has no h.
fn refitted_gradient(objective: &Objective, window: &Window, p4: DVec3) -> Option<DVec3> {
    let value = |axis: DVec3| objective.value(&window.fit(axis.normalize())?);
    let (e1, e2) = p4.any_orthonormal_pair();
    let along = |e: DVec3| {
        let (plus, minus) = (
            value(p4 + e * REFIT_DIFFERENCE)?,
            value(p4 - e * REFIT_DIFFERENCE)?,
        );
        Some((plus - minus) / (2.0 * REFIT_DIFFERENCE))
    };
    let gradient = e1 * along(e1)? + e2 * along(e2)?;
    gradient.is_finite().then_some(gradient)
}

/// The low-resolution eye pass of Algorithm 1 steps 1–2 (the z-buffer read back, here resolved to
/// points): what every light's samples are picked from.
#[derive(Clone, Debug, PartialEq)]
pub struct Readback {
    /// The eye pass at the low resolution, with the scene's camera (so its pixels are not square
    /// unless the size has the camera's aspect).
    pub image: EyeImage,
    /// Eye depth `(p − e)·v` per pixel; `None` where nothing is visible.
    depths: Vec<Option<f64>>,
}

impl Readback {
    /// The eye pass of `scene`'s camera at `width × height` pixels.
    ///
    /// # Errors
    /// The rasterizer's (a zero size, bad indices).
    pub fn new(scene: &Scene, (width, height): (u32, u32)) -> Result<Self, ShadowError> {
        let camera = &scene.camera;
        let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
        let clip_from_world = camera.view_projection(shadowlab_hull::NdcDepth::NegativeOneToOne);
        let mut target = EyeTarget::new(width, height, DepthFormat::F32)?;
        Rasterizer::new(RasterOptions::default()).draw_eye(&mut target, mesh, &clip_from_world)?;
        let image = target.resolve(mesh, scene.mesh.normals(), &clip_from_world)?;
        let (e, v) = (camera.pose.eye(), camera.pose.forward());
        let depths = image
            .triangle
            .iter()
            .zip(&image.position)
            .map(|(t, p)| (*t != NO_TRIANGLE).then(|| (*p - e).dot(v)))
            .collect();
        Ok(Self { image, depths })
    }
}

/// A pixel of the readback as seen by one light's (sub-)frustum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    /// Nothing visible within the frustum's depth range.
    Empty,
    Lit,
    Shadowed,
}

/// How many samples each rule of step 3 contributed (a sample is counted under the first rule it
/// meets, in this order).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleCounts {
    /// Shadowed pixels with a lit neighbour.
    pub boundary: usize,
    /// Other shadowed pixels on the image's border.
    pub screen_border: usize,
    /// Other shadowed pixels next to a depth discontinuity or a pixel showing nothing.
    pub discontinuity: usize,
    /// Samples left out of h because the light grazes their triangle ([`GRAZING_COS`]), or the eye
    /// sees it edge-on (no finite depth slope).
    pub grazing: usize,
}

impl SampleCounts {
    /// All samples (each bounds the map).
    #[must_use]
    pub fn total(&self) -> usize {
        self.boundary + self.screen_border + self.discontinuity
    }
}

/// Picks the samples of step 3 from the classes and reciprocal eye depths of a `width`-wide image.
fn select(
    classes: &[Class],
    reciprocal: &[f64],
    width: usize,
    counts: &mut SampleCounts,
) -> Vec<usize> {
    let height = classes.len() / width;
    let mut picked = Vec::new();
    for row in 0..height {
        for column in 0..width {
            let k = row * width + column;
            if classes[k] != Class::Shadowed {
                continue;
            }
            let left = (column > 0).then(|| k - 1);
            let right = (column + 1 < width).then_some(k + 1);
            let below = (row > 0).then(|| k - width);
            let above = (row + 1 < height).then_some(k + width);
            let neighbours = [left, right, below, above];
            let has = |class: Class| neighbours.iter().flatten().any(|&n| classes[n] == class);
            // |ρ₋ − 2ρ + ρ₊| > DEPTH_ACCELERATION·ρ along a row or a column.
            let jump = |a: Option<usize>, b: Option<usize>| match (a, b) {
                (Some(a), Some(b)) => {
                    (reciprocal[a] - 2.0 * reciprocal[k] + reciprocal[b]).abs()
                        > DEPTH_ACCELERATION * reciprocal[k]
                }
                _ => false,
            };
            let border = neighbours.contains(&None);
            if has(Class::Lit) {
                counts.boundary += 1;
            } else if border {
                counts.screen_border += 1;
            } else if has(Class::Empty) || jump(left, right) || jump(below, above) {
                counts.discontinuity += 1;
            } else {
                continue;
            }
            picked.push(k);
        }
    }
    picked
}

/// World → homogeneous window coordinates of a `width × height` image (x, y in pixels, window
/// depth `(z_ndc + 1)/2`).
fn viewport(width: u32, height: u32) -> DMat4 {
    let (w, h) = (0.5 * f64::from(width), 0.5 * f64::from(height));
    DMat4::from_cols(
        DVec4::new(w, 0.0, 0.0, 0.0),
        DVec4::new(0.0, h, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 0.5, 0.0),
        DVec4::new(w, h, 0.5, 1.0),
    )
}

/// The samples of one light and (sub-)frustum, in the paper's coordinates, with what the map is
/// built from: Algorithm 1 steps 1–3 done, step 4 ([`Problem::solve`]) to do.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// The initial map (uniform with frustum limiting) the shadow states were read from.
    initial: LightSetup,
    /// World → the paper's light space.
    view: DMat4,
    light: LightPoint,
    objective: Objective,
    /// The reduced points of every sample: the map must hold them.
    cover: Vec<DVec3>,
    /// The initial map's rows, reduced and scaled so that `|p̃_4| = 1`.
    initial_rows: Rows,
    /// The focus body B, world space.
    body: ConvexPolyhedron,
    counts: SampleCounts,
}

/// What the optimizer found.
#[derive(Clone, Debug, PartialEq)]
pub struct OptimalReport {
    /// The samples, by rule.
    pub samples: SampleCounts,
    /// h of the initial (uniform-limited) map as it would be rendered, its window around the view
    /// frustum; `None` if there is no descent (below) or h is not finite for it.
    pub uniform_limited_h: Option<f64>,
    /// h at the initial map's `p̃_4` with the affine part fitted to the samples, where the descent
    /// starts; `None` if there was nothing to fit (fewer than three samples off one line, or a
    /// window so thin that the focus body has no volume in it): then the map is the initial one.
    pub initial_h: Option<f64>,
    /// h of the planned map; `None` as `initial_h`.
    pub h: Option<f64>,
    /// The rotation of `p̃_4` accepted in each iteration, degrees.
    pub steps_degrees: Vec<f64>,
}

/// A planned scene-optimized map and how it was found.
#[derive(Clone, Debug, PartialEq)]
pub struct Optimized {
    /// The set-up: [`Technique::Optimal`] with the options' step direction, a projective mapping from world to the paper's light space
    /// (`view`) and on by P (`projection`).
    pub setup: LightSetup,
    /// What was decided.
    pub report: OptimalReport,
}

impl Problem {
    /// Steps 1–3 for `input`'s light and (sub-)frustum of `scene`: the initial map planned and
    /// rendered, every pixel of `readback` in the frustum's depth range classified, the samples
    /// picked and put in the paper's coordinates. `input.eye` must have the scene camera's pose (its
    /// near and far may be a z-partition's).
    ///
    /// # Errors
    /// As [`crate::plan`] for [`Technique::UniformLimited`] (the initial map); the rasterizer's;
    /// [`ShadowError::NotDefined`] if `input.eye` is not the scene's camera or the options are
    /// invalid.
    pub fn new(
        scene: &Scene,
        input: &PlanInput,
        readback: &Readback,
        options: &OptimalOptions,
    ) -> Result<Self, ShadowError> {
        options.validate()?;
        if input.eye.pose != scene.camera.pose {
            return Err(not_defined(
                "the plan input's eye is not the scene's camera",
            ));
        }
        let initial = crate::plan::plan(input, Technique::UniformLimited)?;
        let mesh = Triangles::new(scene.mesh.positions(), scene.mesh.triangles());
        let map = ShadowMap::render(
            &initial,
            mesh,
            MapOptions {
                resolution: options.initial_resolution,
                format: DepthFormat::F32,
                second_depth: false,
            },
        )?;
        let lookup = Lookup::new(Bias::DEFAULT, Filter::Nearest);
        let image = &readback.image;
        let range = input.eye.projection.near()..=input.eye.projection.far();
        let classes: Vec<Class> = readback
            .depths
            .iter()
            .enumerate()
            .map(|(k, depth)| match depth {
                Some(d) if range.contains(d) => {
                    if lookup.lit_fraction(&map, image.position[k], image.normal[k]) < 1.0 {
                        Class::Shadowed
                    } else {
                        Class::Lit
                    }
                }
                _ => Class::Empty,
            })
            .collect();
        let reciprocal: Vec<f64> = readback
            .depths
            .iter()
            .map(|d| d.map_or(0.0, |d| 1.0 / d))
            .collect();
        let mut counts = SampleCounts::default();
        let picked = select(&classes, &reciprocal, image.width as usize, &mut counts);
        let world: Vec<DVec3> = picked.iter().map(|&k| image.position[k]).collect();
        let (view, light) = light_space(input, &world)?;

        // Q⁻¹ = view · S⁻¹, S = world → window coordinates of the full image.
        let screen =
            viewport(scene.camera.width, scene.camera.height) * input.eye.view_projection();
        let from_screen = screen.inverse();
        let inverse_q = view * from_screen;
        let columns = [0, 1, 2].map(|j| light.reduce(inverse_q.col(j)));
        let mut cover = Vec::with_capacity(picked.len());
        let mut samples = Vec::with_capacity(picked.len());
        for (&k, &p) in picked.iter().zip(&world) {
            let point = light.reduce(view * p.extend(1.0));
            cover.push(point);
            let [a, b, c] = scene.mesh.triangle_positions(image.triangle[k] as usize);
            let normal = (b - a).cross(c - a);
            let plane = normal.extend(-normal.dot(a));
            let [r1, r2, r3] = [0, 1, 2].map(|j| plane.dot(from_screen.col(j)));
            let depth_slope = DVec2::new(-r1 / r3, -r2 / r3);
            let facing = normal
                .normalize_or_zero()
                .dot(input.light.toward_from(p))
                .abs();
            if facing < GRAZING_COS || !depth_slope.is_finite() {
                counts.grazing += 1;
                continue;
            }
            samples.push(Sample {
                point,
                w_q: (screen * p.extend(1.0)).w,
                depth_slope,
            });
        }
        let initial_clip = initial
            .mapping
            .clip_from_world()
            .expect("the uniform-limited map is projective")
            * view.inverse();
        let [p1, p2, p4] = [0, 1, 3].map(|i| light.reduce(initial_clip.row(i)));
        let norm = p4.length();
        let initial_rows = Rows {
            p1: p1 / norm,
            p2: p2 / norm,
            p4: p4 / norm,
        };
        Ok(Self {
            initial,
            view,
            light,
            objective: Objective::new(columns, samples),
            cover,
            initial_rows,
            body: focus_polyhedron(input)?,
            counts,
        })
    }

    /// The objective over the samples that enter h.
    #[must_use]
    pub fn objective(&self) -> &Objective {
        &self.objective
    }

    /// The reduced points of every sample.
    #[must_use]
    pub fn cover(&self) -> &[DVec3] {
        &self.cover
    }

    /// Where the light is in the paper's light space.
    #[must_use]
    pub fn light(&self) -> LightPoint {
        self.light
    }

    /// World → the paper's light space.
    #[must_use]
    pub fn view(&self) -> DMat4 {
        self.view
    }

    /// The initial (uniform-limited) map's rows, reduced, with `|p̃_4| = 1`.
    #[must_use]
    pub fn initial_rows(&self) -> Rows {
        self.initial_rows
    }

    /// The samples, by rule.
    #[must_use]
    pub fn counts(&self) -> SampleCounts {
        self.counts
    }

    /// Step 4 and the depth row: samples → P.
    ///
    /// # Errors
    /// As [`descend`] (except that too few samples, or a window whose B ∩ W has no volume, keep the
    /// initial map); [`ShadowError::LightInsideFocusBody`] if B ∩ W reaches the light's plane.
    pub fn solve(&self, options: &OptimalOptions) -> Result<Optimized, ShadowError> {
        options.validate()?;
        let Some(hull) = chart_hull(self.light, &self.cover)? else {
            return Ok(self.keep_initial(options.direction));
        };
        let window = Window::new(self.light, hull, options.border);
        let descent = descend_from(&self.objective, &window, self.initial_rows.p4, options)?;
        let (projection, body) = match self.with_depth(&descent.rows) {
            Ok(fit) => fit,
            // A few samples nearly on one line fit a window so thin that B ∩ W has no volume
            // within the hull crate's tolerances (seen on `outdoor` with 4 samples): there is no
            // depth range to fit, and the initial map is kept.
            Err(ShadowError::EmptyFocusBody | ShadowError::FlatFocusBody { .. }) => {
                return Ok(self.keep_initial(options.direction));
            }
            Err(e) => return Err(e),
        };
        Ok(Optimized {
            setup: LightSetup {
                technique: Technique::Optimal(options.direction),
                mapping: ShadowMapping::Projective(ProjectiveMapping::new(self.view, projection)),
                gamma: self.initial.gamma,
                half_fov: self.initial.half_fov,
                warp: None,
                psm: None,
                focus_body: body,
            },
            report: OptimalReport {
                samples: self.counts,
                uniform_limited_h: self.objective.value(&self.initial_rows),
                initial_h: Some(descent.initial_h),
                h: Some(descent.h),
                steps_degrees: descent.steps_degrees,
            },
        })
    }

    /// The initial map, kept when there is nothing to optimize.
    fn keep_initial(&self, direction: StepDirection) -> Optimized {
        Optimized {
            setup: LightSetup {
                technique: Technique::Optimal(direction),
                ..self.initial.clone()
            },
            report: OptimalReport {
                samples: self.counts,
                uniform_limited_h: None,
                initial_h: None,
                h: None,
                steps_degrees: Vec::new(),
            },
        }
    }

    /// P with its depth row fitted to B ∩ W, and B ∩ W's vertices (world).
    fn with_depth(&self, rows: &Rows) -> Result<(DMat4, Vec<DVec3>), ShadowError> {
        let light = self.light;
        let [p1, p2, p4] = [rows.p1, rows.p2, rows.p4].map(|r| light.expand(r));
        // W: |u1| ≤ 1 and |u2| ≤ 1, i.e. (±p̃_i − p̃_4)·X_l ≤ 0, as world half-spaces.
        let planes = [p1 - p4, -p1 - p4, p2 - p4, -p2 - p4]
            .map(|row| {
                let plane = self.view.transpose() * row;
                let normal = plane.truncate();
                Plane::from_point_normal(-normal * (plane.w / normal.length_squared()), normal)
            })
            .into_iter()
            .collect::<Result<Vec<_>, _>>()?;
        let body = self
            .body
            .intersect_planes(&planes, &Tolerances::DEFAULT)
            .ok_or(ShadowError::EmptyFocusBody)?;
        let away = light.away();
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in body.vertices() {
            let x = self.view * v.extend(1.0);
            let w = p4.dot(x);
            if w <= 0.0 {
                return Err(ShadowError::LightInsideFocusBody);
            }
            let zeta = away.dot(x) / w;
            (low, high) = (low.min(zeta), high.max(zeta));
        }
        if high <= low {
            return Err(ShadowError::FlatFocusBody { axis: "light axis" });
        }
        // u3 = A + B·ζ from −1 at the lowest ζ to +1 at the highest.
        let slope = 2.0 / (high - low);
        let p3 = p4 * (-1.0 - slope * low) + away * slope;
        Ok((
            DMat4::from_cols(p1, p2, p3, p4).transpose(),
            body.vertices().to_vec(),
        ))
    }
}

/// World → the paper's light space, and where the light is in it, for the samples at `world`.
fn light_space(input: &PlanInput, world: &[DVec3]) -> Result<(DMat4, LightPoint), ShadowError> {
    match input.light {
        LightSource::Spot { pose, .. } => Ok((pose.view_matrix(), LightPoint::Origin)),
        LightSource::Point { .. } => Err(Technique::unserved_point_light("optimal")),
        LightSource::Directional { .. } => {
            let frame = LightFrame::new(
                &input.eye,
                &input.light,
                Technique::Optimal(StepDirection::Paper).key(),
            )?;
            let to_frame = frame.world_to_light();
            let points: Vec<DVec3> = world
                .iter()
                .map(|p| to_frame.transform_point3(*p))
                .collect();
            let (centre, radius) = if points.is_empty() {
                (DVec3::ZERO, 1.0)
            } else {
                let extents = Extents::of(&points);
                let size = extents.max - extents.min;
                let radius = 0.5 * size.x.hypot(size.z);
                (
                    0.5 * (extents.min + extents.max),
                    if radius > 0.0 { radius } else { 1.0 },
                )
            };
            let normalise =
                DMat4::from_scale(DVec3::splat(1.0 / radius)) * DMat4::from_translation(-centre);
            Ok((normalise * to_frame, LightPoint::Infinity))
        }
    }
}

/// Plans the scene-optimized map of `input`'s light and (sub-)frustum of `scene`: [`Problem::new`]
/// then [`Problem::solve`].
///
/// # Errors
/// As those two.
pub fn plan(
    scene: &Scene,
    input: &PlanInput,
    readback: &Readback,
    options: &OptimalOptions,
) -> Result<Optimized, ShadowError> {
    Problem::new(scene, input, readback, options)?.solve(options)
}

/// z-partitioning with scene-optimized maps: one readback of `scene` shared by the `count`
/// sub-frusta split by `splits` (as [`crate::plan_partitions`]), each optimized on its own samples
/// — the readback's pixels whose eye depth lies in its range.
///
/// # Errors
/// As [`Readback::new`], [`plan`] for any part, and the split scheme's.
pub fn plan_partitions(
    scene: &Scene,
    input: &PlanInput,
    splits: Splits,
    count: usize,
    options: &OptimalOptions,
) -> Result<Vec<(Partition, OptimalReport)>, ShadowError> {
    let readback = Readback::new(scene, options.readback)?;
    partition_inputs(input, splits, count)?
        .into_iter()
        .map(|(near, far, part)| {
            let optimized = plan(scene, &part, &readback, options)?;
            Ok((
                Partition {
                    near,
                    far,
                    face: None,
                    sphere: None,
                    setup: optimized.setup,
                },
                optimized.report,
            ))
        })
        .collect()
}
