//! # shadowlab-hull: the bodies a shadow map is focused on
//!
//! Planes, boxes, rays, frusta, closed convex polyhedra, 3-D and 2-D convex hulls, the focus body
//! **B = conv(V ∪ l) ∩ S ∩ L** (PSM §4.1, Stamminger & Drettakis 2002; LiSPSM §3.3, Wimmer,
//! Scherzer & Purgathofer, EGSR 2004), LiSPSM light space (§3.4) and the minimum-area rectangle used
//! to fit a shadow map (Chong & Gortler 2006, CG06). Everything is f64; every result type has a
//! `validate()` that proves its invariants, which tests and debug builds call.
//!
//! ```
//! use glam::DVec3;
//! use shadowlab_hull::{Aabb, Frustum, Light, LightSpace, Perspective, Tolerances, ViewPose};
//!
//! let tolerances = Tolerances::default();
//! let pose = ViewPose::look_to(DVec3::new(0.0, 2.0, 10.0), DVec3::NEG_Z, DVec3::Y)?;
//! let view = Frustum::perspective(&pose, &Perspective::new(1.0, 1.5, 0.5, 50.0)?);
//! let scene = Aabb::new(DVec3::new(-20.0, 0.0, -40.0), DVec3::new(20.0, 10.0, 20.0))?;
//! let sun = Light::directional(DVec3::new(0.3, 1.0, 0.2))?;
//! let b = shadowlab_hull::focus_body(&view, &scene, &sun, &tolerances)?.expect("B is not empty");
//! b.validate(&tolerances)?;
//! let light_space = LightSpace::new(&pose, sun.to_light().expect("directional"))?;
//! let bounds = b.bounds_in(&light_space.world_to_light(pose.eye()))?;
//! assert!(bounds.size().min_element() > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Conventions
//! - **World space is right-handed.** Eye space is OpenGL's: the camera looks down **−z**, +y up, +x
//!   right ([`ViewPose`]). Matrices act on column vectors (`clip = P · view · world`).
//! - **NDC depth**: frusta are built from camera parameters directly (no NDC involved);
//!   [`Perspective::matrix`]/[`Orthographic::matrix`] and [`Frustum::from_view_projection`] take an
//!   [`NdcDepth`]: OpenGL's `[−1, 1]` (the default), D3D/Vulkan `[0, 1]`, or reversed-Z `[1, 0]`.
//! - **Planes** are `(n, d)` with unit `n`; `n·x + d ≤ 0` is inside: normals point **out** of the
//!   bodies they bound ([`Plane`]). Face loops are counter-clockwise seen from outside.
//! - **Frustum order**: corners indexed by bits (x: left/right, y: bottom/top, z: near/far); planes
//!   left, right, bottom, top, near, far ([`Frustum`]).
//! - **Lights**: a directional light is given by the unit vector **toward** the light
//!   ([`Light::directional`]); "moving away from the light" is along its negation.
//! - **γ** is the smallest angle between the light and view directions, in `[0, π/2]`; 0 = parallel
//!   or anti-parallel ([`light_view_angle`]).
//! - **Light space** (LiSPSM §3.4, right-handed): y toward the light, z ⟂ y in the light–view plane
//!   with the view vector having a negative z component, x = y × z; a documented continuous blend
//!   replaces the undefined axis when the light is (nearly) parallel to the view ([`LightSpace`]).
//! - **Tolerances** are named ([`Tolerances`]) and scaled to the data's extent and coordinate
//!   magnitude; signs that decide hull topology are exact (`robust::orient2d`/`orient3d`, on inputs
//!   rescaled by powers of two, which is exact).
//! - **Empty results** are `None` (`Option<ConvexPolyhedron>`); a degenerate point set is an `Err`
//!   naming its [`Degeneracy`]; there is no empty or flat polyhedron value.
//! - **2-D**: counter-clockwise polygons; rectangles as centre, orthonormal axes and half-extents.

#![deny(missing_docs)]

mod aabb;
mod area;
mod camera;
mod clip;
mod error;
mod extrude;
mod finite;
mod focus;
mod frustum;
mod hull2;
mod hull3;
mod light;
mod light_space;
mod mesh;
mod min_area_rect;
mod plane;
mod polyhedron;
mod ray;
mod tolerance;

pub use aabb::Aabb;
pub use camera::{NdcDepth, Orthographic, Perspective, ViewPose};
pub use error::{Degeneracy, HullError, ValidationError};
pub use focus::{eye_depth_range, focus_body, psm_near_body, visible_body};
pub use frustum::{BOTTOM, FACE_CORNERS, FAR, Frustum, LEFT, NEAR, RIGHT, TOP};
pub use hull2::{Aabb2, ConvexHull2, ConvexPolygon2, convex_hull_2d};
pub use light::Light;
pub use light_space::{LightSpace, SINGULAR_AXIS_LENGTH, light_view_angle};
pub use mesh::Face;
pub use min_area_rect::MinAreaRect;
pub use plane::Plane;
pub use polyhedron::ConvexPolyhedron;
pub use ray::{Ray, Segment};
pub use tolerance::{Scale, Tolerances, UNIT_LENGTH_TOLERANCE};
