//! # shadowlab-trace: exact ray casting against triangle meshes
//!
//! The ground truth of shadowlab: whether a segment is blocked, and the nearest surface along a
//! ray, decided in f64 without leaks, the same on every run and thread count. `shadow` casts one
//! ray per texel to build shadow maps exactly in software; `analysis` casts one shadow ray per eye
//! pixel to know which pixels are truly lit.
//!
//! * **Watertight ray–triangle test** (Woop, Benthin & Wald, JCGT 2013): rays are sheared so that
//!   their dominant axis becomes z, and three 2-D edge functions decide the hit with an exact sign
//!   (an FMA-exact fallback when one rounds to zero). A ray through a shared edge or vertex hits
//!   a triangle there; it can only graze a silhouette, never slip between two triangles.
//! * **[`Bvh`]**: binned SAH (32 bins, leaves of at most 8 triangles), collapsed to 4 children per
//!   node; triangles stored leaf by leaf in blocks of four, coordinates side by side, which a ray
//!   tests four at a time. Boxes are padded per ray by an amount that provably covers the rounding
//!   of both the triangle test and the slab test (Ize's robust traversal, JCGT 2013, done in
//!   space), so the tree returns exactly what a loop over all triangles returns.
//! * **Queries**: [`Bvh::closest_hit`], [`Bvh::occluded`], and their parallel batch forms
//!   [`Bvh::closest_hits`] and [`Bvh::occluded_all`] (rayon), which trace runs of coherent rays
//!   in packets (Wald, Boulos & Shirley 2007: one box test per packet by interval arithmetic,
//!   bounding each ray's own rounded test), each ray with its own answer; and
//!   [`Bvh::closest_hits_grid`] for a grid of parallel rays (a directional light's shadow-map
//!   texels), swept triangle by triangle over the grid's rows, each ray tested only against the
//!   triangles whose image reaches it, with the same answers.
//! * **[`offset_origin`]**: moves a surface point off its triangle's plane by an amount proven to
//!   exceed its rounding error (after Wächter & Binder, Ray Tracing Gems ch. 6), for rays leaving
//!   the surface.
//!
//! ```
//! use glam::DVec3;
//! use shadowlab_trace::{Bvh, Ray, offset_origin};
//!
//! // A unit square at z = 0 (two triangles sharing the diagonal) and a ray through the diagonal.
//! let positions = [
//!     DVec3::new(0.0, 0.0, 0.0),
//!     DVec3::new(1.0, 0.0, 0.0),
//!     DVec3::new(1.0, 1.0, 0.0),
//!     DVec3::new(0.0, 1.0, 0.0),
//! ];
//! let bvh = Bvh::new(&positions, &[[0, 1, 2], [0, 2, 3]])?;
//! let ray = Ray::new(DVec3::new(0.25, 0.25, 2.0), DVec3::new(0.0, 0.0, -1.0))?;
//! let hit = bvh.closest_hit(&ray, 0.0, f64::INFINITY).expect("the diagonal is covered");
//! // Both triangles report it (the tie rule); the smaller index wins.
//! assert_eq!((hit.t, hit.triangle), (2.0, 0));
//!
//! // A shadow ray from the hit point toward a light: start it just off the surface.
//! let light = DVec3::new(3.0, 2.0, 5.0);
//! let point = bvh.hit_point(&hit);
//! let normal = bvh.geometric_normal(hit.triangle);
//! let origin = offset_origin(point, normal, light - point, bvh.magnitude())?;
//! assert!(origin.z > 0.0);
//! assert!(!bvh.occluded(&Ray::new(origin, light - origin)?, 0.0, 1.0));
//! # Ok::<(), shadowlab_trace::TraceError>(())
//! ```
//!
//! # Conventions
//! - **Rays** are `origin + t·direction`; `t` is in units of `direction` (which need not be unit
//!   length). Every query keeps hits with `t` in the **open** interval `(t_min, t_max)`; `t_max`
//!   may be `f64::INFINITY`, `t_min` negative.
//! - **Ties**: an edge function that is exactly zero counts as inside. A ray exactly through a
//!   shared edge (in the test's sheared coordinates) hits both triangles there, through a vertex
//!   every triangle around it that the ray crosses; never none. Among hits at equal `t` the
//!   smallest triangle index is the closest, so answers never depend on the tree.
//! - **Faces**: both sides are hit (no culling). A ray in a triangle's plane misses it.
//!   Zero-area triangles (exactly collinear vertices) are never hit and are listed by
//!   [`Bvh::degenerate_triangles`].
//! - **Barycentrics**: a [`Hit`]'s `u` and `v` weight the triangle's second and third vertex.
//! - **Range**: coordinates up to [`MAX_COORDINATE`] = 2²⁰⁰ in magnitude; the largest direction
//!   component between [`MIN_DIRECTION`] = 2⁻²⁰⁰ and 2²⁰⁰. Exactness assumes no intermediate
//!   product underflows (magnitudes below 2⁻⁹⁶⁹); in that range signs can only round to zero,
//!   which counts as a tie.
//! - **Threads**: batch queries and the build use rayon's current pool; every result is identical
//!   for any thread count.
//! - **Invalid rays** and NaN parameter bounds make queries panic with a message naming the bad
//!   parameter; [`Ray::new`] and [`Ray::validate`] check rays beforehand.

#![deny(missing_docs)]

mod build;
mod bvh;
mod error;
mod offset;
mod ray;
mod triangle;

pub use bvh::{Bvh, BvhStats, GRID_CHUNK, RAY_CHUNK};
pub use error::TraceError;
pub use offset::{MIN_MAGNITUDE, OFFSET_ULPS, SURFACE_POINT_ULPS, offset_origin};
pub use ray::{BOX_PADDING_ULPS, Hit, MAX_COORDINATE, MIN_DIRECTION, Ray};
