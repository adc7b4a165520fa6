//! 3-D convex hulls and clipping over random inputs.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_hull::{Aabb, ConvexPolyhedron, Plane, Scale};

use crate::support::{TOL, config, point_in, unit_vector};

/// A point cloud at a random scale (10⁻⁴ … 10⁴) and offset.
fn cloud() -> impl Strategy<Value = Vec<DVec3>> {
    (
        prop::collection::vec(point_in(1.0), 4..64),
        -4.0..4.0_f64,
        point_in(1.0),
    )
        .prop_map(|(points, log_scale, offset)| {
            let scale = 10f64.powf(log_scale);
            points
                .into_iter()
                .map(|p| (p + offset * 3.0) * scale)
                .collect()
        })
}

proptest! {
    // Seed 0x4A11_0003: 256 random clouds and planes.
    #![proptest_config(config(0x4A11_0003, 256))]

    /// The hull validates, contains all its points, and its vertices are input points (bit for bit).
    #[test]
    fn hull_contains_its_points_and_uses_them(points in cloud()) {
        let hull = ConvexPolyhedron::from_points(&points, &TOL).expect("random clouds are solid");
        prop_assert_eq!(hull.validate(&TOL), Ok(()));
        prop_assert_eq!(hull.validate_contains(&points, &TOL), Ok(()));
        for v in hull.vertices() {
            prop_assert!(points.contains(v), "{v} is not an input point");
        }
        // Every input point outside the hull by more than rounding would contradict exactness.
        let (lo, hi) = hull.extent_along(DVec3::X);
        let (plo, phi) = points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.x), b.max(p.x)));
        prop_assert_eq!((lo, hi), (plo, phi));
    }

    /// Clipping never grows the volume, keeps the result in the half-space, and the two sides of a
    /// plane add up to the whole.
    #[test]
    fn clipping_never_grows_and_stays_inside(
        points in cloud(),
        normal in unit_vector(),
        position in 0.0..1.0_f64,
    ) {
        let hull = ConvexPolyhedron::from_points(&points, &TOL).expect("solid");
        let (lo, hi) = hull.extent_along(normal);
        let through = normal * (lo + (hi - lo) * position);
        let plane = Plane::from_point_normal(through, normal).expect("valid");
        let slack = TOL.validation_distance(hull.scale());
        let volume = hull.volume();
        let kept = hull.clip(&plane, &TOL);
        let cut = hull.clip(&plane.flipped(), &TOL);
        let mut total = 0.0;
        for part in [&kept, &cut].into_iter().flatten() {
            prop_assert_eq!(part.validate(&TOL), Ok(()));
            prop_assert!(part.volume() <= volume * (1.0 + 1e-12) + slack * slack * slack);
            total += part.volume();
        }
        if let Some(part) = &kept {
            for v in part.vertices() {
                prop_assert!(plane.signed_distance(*v) <= slack);
                prop_assert!(hull.contains(*v, slack));
            }
        }
        // The two halves partition the body (up to slivers of the snap distance).
        let area_bound = hull.bounds().size().length().powi(2) * 3.0;
        prop_assert!((total - volume).abs() <= slack * area_bound, "{total} vs {volume}");
    }

    /// Intersecting with a box equals clipping by its six planes, and lies in both.
    #[test]
    fn box_intersection_lies_in_both(points in cloud(), corner in point_in(1.0), size in point_in(1.0)) {
        let hull = ConvexPolyhedron::from_points(&points, &TOL).expect("solid");
        let b = hull.bounds();
        let center = b.center() + corner * b.size() * 0.5;
        let half = (size.abs() + 0.05) * b.size() * 0.5;
        let aabb = Aabb::new(center - half, center + half).expect("valid");
        let slack = TOL.validation_distance(hull.scale().max(Scale::of_points(&aabb.corners())));
        let both = hull.intersect_aabb(&aabb, &TOL);
        let as_body = ConvexPolyhedron::from_aabb(&aabb, &TOL).expect("solid");
        let other_way = as_body.intersect(&hull, &TOL);
        prop_assert_eq!(both.is_some(), other_way.is_some());
        if let (Some(x), Some(y)) = (&both, &other_way) {
            prop_assert_eq!(x.validate(&TOL), Ok(()));
            for v in x.vertices() {
                prop_assert!(aabb.contains(*v, slack) && hull.contains(*v, slack));
            }
            prop_assert!((x.volume() - y.volume()).abs() <= slack * b.size().length().powi(2) * 6.0);
        }
    }
}

/// Grid clouds: many exactly coplanar and collinear points on the hull's boundary.
fn grid_cloud() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec((-3..=3_i32, -3..=3_i32, -3..=3_i32), 5..80).prop_map(|v| {
        v.into_iter()
            .map(|(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
            .collect()
    })
}

/// A plane that is hard to clip by: through three vertices of the body, or a face plane nudged by a
/// fraction of the snap distance (−2, −½, 0, ½, 2) and tilted by a tiny angle.
fn awkward_plane(
    body: &ConvexPolyhedron,
    pick: [usize; 3],
    nudge: usize,
    tilt: DVec3,
) -> Option<Plane> {
    let v = body.vertices();
    let snap = TOL.snap_distance(body.scale());
    if nudge == 5 {
        return Plane::from_points(
            v[pick[0] % v.len()],
            v[pick[1] % v.len()],
            v[pick[2] % v.len()],
        )
        .ok();
    }
    let face = &body.faces()[pick[0] % body.faces().len()];
    let offsets = [-2.0, -0.5, 0.0, 0.5, 2.0];
    let normal = (face.plane().normal() + tilt * 1e-10).normalize();
    let through = v[face.vertices()[0]] + normal * (offsets[nudge] * snap);
    Plane::from_point_normal(through, normal).ok()
}

proptest! {
    // Seed 0x4A11_0007: 256 grid clouds and awkward planes.
    #![proptest_config(config(0x4A11_0007, 256))]

    /// Exactly coplanar input merges into polygon faces with only extreme vertices; clipping by planes
    /// through vertices or within the snap distance of a face still gives valid bodies, in the
    /// half-space, no larger than the original.
    #[test]
    fn degenerate_hulls_and_clips(
        points in grid_cloud(),
        pick in (0..64_usize, 0..64_usize, 0..64_usize),
        nudge in 0..6_usize,
        tilt in unit_vector(),
    ) {
        let Ok(hull) = ConvexPolyhedron::from_points(&points, &TOL) else {
            return Ok(()); // flat draws are covered by `extremes`
        };
        prop_assert_eq!(hull.validate(&TOL), Ok(()));
        prop_assert_eq!(hull.validate_contains(&points, &TOL), Ok(()));
        // Exact merging: no two adjacent faces are coplanar, so every vertex has ≥ 3 faces.
        for (i, _) in hull.vertices().iter().enumerate() {
            let faces = hull.faces().iter().filter(|f| f.vertices().contains(&i)).count();
            prop_assert!(faces >= 3);
        }
        let Some(plane) = awkward_plane(&hull, [pick.0, pick.1, pick.2], nudge, tilt) else {
            return Ok(());
        };
        let slack = TOL.validation_distance(hull.scale());
        for side in [plane, plane.flipped()] {
            if let Some(part) = hull.clip(&side, &TOL) {
                prop_assert_eq!(part.validate(&TOL), Ok(()));
                prop_assert!(part.volume() <= hull.volume() * (1.0 + 1e-12));
                for v in part.vertices() {
                    prop_assert!(side.signed_distance(*v) <= slack);
                }
            }
        }
    }
}

proptest! {
    // Seed 0x4A11_0008: 256 slabs a few snap distances thick, each cut by 32 nearly parallel planes.
    // This is the hardest case for clipping (every vertex within a few snap distances of the plane,
    // cross-sections ill-conditioned in the plane); it exercises the exact-hull fallback of `clip`
    // (7 of these 8192 cuts at the time of writing).
    #![proptest_config(config(0x4A11_0008, 256))]

    #[test]
    fn thin_slabs_cut_by_nearly_parallel_planes(
        raw in prop::collection::vec((-0.5..0.5_f64, -0.5..0.5_f64, -0.5..0.5_f64), 12..200),
        snaps_thick in 2.0..12.0_f64,
        cuts in prop::collection::vec((unit_vector(), -12.0..-3.0_f64, -3.0..3.0_f64), 32),
    ) {
        let snap = TOL.snap_distance(Scale { extent: 2f64.sqrt(), magnitude: 0.5 });
        let thickness = snaps_thick * snap;
        let points: Vec<DVec3> = raw.iter().map(|&(x, y, z)| DVec3::new(x, y, z * thickness)).collect();
        let Ok(slab) = ConvexPolyhedron::from_points(&points, &TOL) else {
            return Ok(()); // within the snap distance of flat
        };
        let slack = TOL.validation_distance(slab.scale());
        for (tilt, log_tilt, offset) in cuts {
            let normal = (DVec3::Z + tilt * 10f64.powf(log_tilt)).normalize();
            let plane = Plane::from_point_normal(normal * (offset * snap), normal).expect("valid");
            if let Some(part) = slab.clip(&plane, &TOL) {
                prop_assert_eq!(part.validate(&TOL), Ok(()));
                prop_assert!(part.volume() <= slab.volume() * (1.0 + 1e-9));
                for v in part.vertices() {
                    prop_assert!(plane.signed_distance(*v) <= slack);
                    prop_assert!(slab.contains(*v, slack));
                }
            }
        }
    }
}
