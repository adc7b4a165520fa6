//! Lloyd et al.'s face partitioning for the logarithmic map (*Warping and Partitioning for Low
//! Error Shadow Maps*, EGSR 2006 §5.2; *Logarithmic Perspective Shadow Maps*, ACM TOG 27(4), 2008).
//!
//! Seen from the light, the view frustum V is covered exactly once by the projections of its faces
//! that face away from the light (a convex body's back faces tile its shadow). Each such face gets a
//! map of its own, covering the part of B whose projection falls on the face's projection:
//!
//! - a **side face** lies in a plane through the eye, so its projection is a trapezoid whose two
//!   long edges meet at the eye's projection: the eye lies outside it, and the logarithm is
//!   measured from the eye along the bisector of those edges — the well-placed warp the partition
//!   exists for, at every light direction (the dueling frusta included, where the four side faces
//!   surround the eye's projection);
//! - the **near and far faces** get uniform maps (the depth over each is one value, so a warp along
//!   it buys nothing).
//!
//! A receiver is served by the face whose projection holds its own ([`FaceRegion`]); faces seen
//! edge-on (`|n·l| ≤ EDGE_ON`) have no area and no map. shadowlab's reading of the papers: the
//! back faces (Lloyd et al. do not say which of the two tilings they use; the back faces are the one
//! that gives the dueling frusta warped side faces), the side faces' warp axis along the bisector,
//! uniform end faces, and every face's map at the full resolution, as z-partitions have.

use glam::{DMat4, DVec2, DVec3, DVec4};
use shadowlab_hull::{
    ConvexHull2, ConvexPolyhedron, FACE_CORNERS, FAR, NEAR, Plane, Tolerances, convex_hull_2d,
};
use shadowlab_params::LightAngle;

use crate::error::ShadowError;
use crate::focus::{focus_polyhedron, view_model};
use crate::frame::LightFrame;
use crate::input::PlanInput;
use crate::logarithmic::{self, ReferenceRule};
use crate::setup::LightSetup;
use crate::technique::{LogarithmicChoice, Technique};

/// Faces whose unit normal has a component toward or away from the light of at most this are seen
/// edge-on: their projection has no area.
pub const EDGE_ON: f64 = 1e-9;

/// The part of the light's view a face partition serves: a convex polygon on the plane across the
/// light, in the (x, z) coordinates of the light space `world_to_light` maps to.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceRegion {
    /// Which face of V: 0 left, 1 right, 2 bottom, 3 top, 4 near, 5 far.
    pub face: usize,
    /// World → the light space the polygon lies in (projective for a spot light).
    pub world_to_light: DMat4,
    /// The face's projection, counter-clockwise in (x, z).
    pub polygon: Vec<DVec2>,
}

impl FaceRegion {
    /// The face's name: `left`, `right`, `bottom`, `top`, `near` or `far`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        ["left", "right", "bottom", "top", "near", "far"][self.face]
    }

    /// How far inside the region `world`'s projection lies: the least signed distance to its edges,
    /// positive inside, negative outside; −∞ if a spot light sends the point behind it.
    #[must_use]
    pub fn inside(&self, world: DVec3) -> f64 {
        let h = self.world_to_light * world.extend(1.0);
        if h.w <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let q = DVec2::new(h.x / h.w, h.z / h.w);
        let n = self.polygon.len();
        (0..n)
            .map(|k| {
                let (a, b) = (self.polygon[k], self.polygon[(k + 1) % n]);
                let edge = b - a;
                edge.perp_dot(q - a) / edge.length()
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// One face's plan: its region and its map's set-up.
pub(crate) struct FacePlan {
    pub(crate) region: FaceRegion,
    pub(crate) setup: LightSetup,
}

/// Plans the face partitions of `input` (one z-partition's view).
///
/// # Errors
/// [`ShadowError::EmptyFocusBody`] if no face's part of B has volume; as [`crate::plan`] otherwise.
pub(crate) fn plan(input: &PlanInput) -> Result<Vec<FacePlan>, ShadowError> {
    let technique = Technique::Logarithmic(LogarithmicChoice::Faces);
    let frame = LightFrame::new(&input.eye, &input.light, technique.key())?;
    let (model, half_fov) = view_model(input)?;
    let gamma = LightAngle::from_radians(frame.gamma())?;
    let body = focus_polyhedron(input)?;
    let frustum = input.eye.frustum();
    let corners = frame
        .light_points(frustum.corners())
        .ok_or(ShadowError::LightInsideFocusBody)?;
    let centre = corners.iter().copied().sum::<DVec3>() / 8.0;
    let world_to_light = frame.world_to_light();
    let tolerances = Tolerances::DEFAULT;
    let mut plans = Vec::new();
    for (face, indices) in FACE_CORNERS.iter().enumerate() {
        let [a, b, c, _] = indices.map(|i| corners[i]);
        let mut normal = (b - a).cross(c - a);
        if normal.dot(a - centre) < 0.0 {
            normal = -normal;
        }
        let length = normal.length();
        // Facing away from the light (+y in light space), not edge-on.
        if length == 0.0 || normal.y >= -EDGE_ON * length {
            continue;
        }
        let projected: Vec<DVec2> = indices
            .iter()
            .map(|&i| DVec2::new(corners[i].x, corners[i].z))
            .collect();
        let ConvexHull2::Polygon(hull) = convex_hull_2d(&projected)? else {
            continue;
        };
        let polygon = hull.vertices().to_vec();
        let Some(part) = clip_to_prism(&body, &polygon, &world_to_light, &tolerances)? else {
            continue;
        };
        let side = face != NEAR && face != FAR;
        let (face_frame, reference) = if side {
            // The warp axis along the bisector of the edges through the eye's projection, away
            // from it.
            let bisector = projected
                .iter()
                .map(|p| p.normalize_or_zero())
                .sum::<DVec2>()
                .normalize_or_zero();
            (frame.turned(bisector), ReferenceRule::Eye)
        } else {
            (frame, ReferenceRule::Uniform)
        };
        let setup = logarithmic::plan_in(
            technique,
            &face_frame,
            part.vertices().to_vec(),
            reference,
            &model,
            gamma,
            half_fov,
        )?;
        plans.push(FacePlan {
            region: FaceRegion {
                face,
                world_to_light,
                polygon,
            },
            setup,
        });
    }
    if plans.is_empty() {
        return Err(ShadowError::EmptyFocusBody);
    }
    Ok(plans)
}

/// `body` clipped to the prism along the light over `polygon` (counter-clockwise, light-space
/// (x, z)): each edge's plane `a·x + c·z + e ≤ 0` in light space taken back to world space through
/// `world_to_light` (a plane's coefficients times the matrix; the sign holds where w > 0).
fn clip_to_prism(
    body: &ConvexPolyhedron,
    polygon: &[DVec2],
    world_to_light: &DMat4,
    tolerances: &Tolerances,
) -> Result<Option<ConvexPolyhedron>, ShadowError> {
    let mut part = body.clone();
    let n = polygon.len();
    for k in 0..n {
        let (p, q) = (polygon[k], polygon[(k + 1) % n]);
        // Outside is to the right of the edge p → q: −perp_dot(q − p, x − p) ≥ 0.
        let edge = q - p;
        let (a, c) = (edge.y, -edge.x);
        let light_plane = DVec4::new(a, 0.0, c, -(a * p.x + c * p.y));
        let world = world_to_light.transpose() * light_plane;
        let normal = world.truncate();
        let length = normal.length();
        if !length.is_finite() || length <= 0.0 {
            return Err(ShadowError::FlatFocusBody {
                axis: "lateral axis",
            });
        }
        let plane = Plane::from_point_normal(-normal * (world.w / (length * length)), normal)?;
        match part.clip(&plane, tolerances) {
            Some(clipped) => part = clipped,
            None => return Ok(None),
        }
    }
    Ok(Some(part))
}
