//! The documented semantics on hand-built cases: the open parameter interval, the tie rule, back
//! faces, rays in a triangle's plane, zero-area triangles, the empty mesh, hit points, bounds and
//! statistics, and the clamp that keeps every hit inside its triangle's padded box.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_trace::{BOX_PADDING_ULPS, Bvh, Hit, Ray};

use crate::support::{Rng, config, uv_sphere};

/// The triangle (−1, −1, 1), (1, −1, 1), (0, 1, 1): a ray from the origin along +z meets it at
/// t = 1 exactly, with u = 1/4 and v = 1/2 (every step of the test is exact on these inputs).
fn unit_triangle() -> Bvh {
    Bvh::new(
        &[
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(1.0, -1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ],
        &[[0, 1, 2]],
    )
    .expect("valid")
}

fn up() -> Ray {
    Ray::new(DVec3::ZERO, DVec3::Z).expect("valid")
}

#[test]
fn the_parameter_interval_is_open() {
    let bvh = unit_triangle();
    let ray = up();
    let hit = bvh.closest_hit(&ray, 0.0, 2.0).expect("hit");
    assert_eq!(
        hit,
        Hit {
            t: 1.0,
            triangle: 0,
            u: 0.25,
            v: 0.5
        }
    );
    for (t_min, t_max, expected) in [
        (0.0, 1.0, false),
        (0.0, 1.0_f64.next_up(), true),
        (1.0, 2.0, false),
        (1.0_f64.next_down(), 2.0, true),
        (1.0, 1.0, false),
        (2.0, 0.0, false),
        (f64::NEG_INFINITY, f64::INFINITY, true),
    ] {
        assert_eq!(
            bvh.closest_hit(&ray, t_min, t_max).is_some(),
            expected,
            "({t_min}, {t_max})"
        );
        assert_eq!(
            bvh.occluded(&ray, t_min, t_max),
            expected,
            "({t_min}, {t_max})"
        );
        assert_eq!(
            bvh.intersect_triangle(&ray, 0, t_min, t_max).is_some(),
            expected
        );
    }
    // Behind the origin: t = −1, found only when the interval reaches below it.
    let down = Ray::new(DVec3::ZERO, DVec3::NEG_Z).expect("valid");
    assert_eq!(bvh.closest_hit(&down, 0.0, f64::INFINITY), None);
    assert_eq!(
        bvh.closest_hit(&down, f64::NEG_INFINITY, 0.0).map(|h| h.t),
        Some(-1.0)
    );
    // t is in units of the direction.
    let slow = Ray::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 0.25)).expect("valid");
    assert_eq!(bvh.closest_hit(&slow, 0.0, 10.0).map(|h| h.t), Some(4.0));
}

#[test]
fn back_faces_hit() {
    let bvh = unit_triangle();
    let from_above = Ray::new(DVec3::new(0.0, 0.0, 3.0), DVec3::NEG_Z).expect("valid");
    assert_eq!(bvh.closest_hit(&up(), 0.0, 9.0).map(|h| h.t), Some(1.0));
    assert_eq!(
        bvh.closest_hit(&from_above, 0.0, 9.0).map(|h| h.t),
        Some(2.0)
    );
}

#[test]
fn equal_t_goes_to_the_smallest_index() {
    // Triangles 1 and 3 coincide (3 with reversed winding); 0 and 2 are elsewhere.
    let p = [
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(1.0, -1.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::new(5.0, 5.0, 5.0),
        DVec3::new(6.0, 5.0, 5.0),
        DVec3::new(5.0, 6.0, 5.0),
    ];
    let bvh = Bvh::new(&p, &[[3, 4, 5], [0, 1, 2], [4, 3, 5], [2, 1, 0]]).expect("valid");
    assert!(bvh.intersect_triangle(&up(), 3, 0.0, 9.0).is_some());
    assert_eq!(
        bvh.closest_hit(&up(), 0.0, 9.0).map(|h| h.triangle),
        Some(1)
    );
    let bvh = Bvh::new(&p, &[[3, 4, 5], [2, 1, 0], [4, 3, 5], [0, 1, 2]]).expect("valid");
    assert_eq!(
        bvh.closest_hit(&up(), 0.0, 9.0).map(|h| h.triangle),
        Some(1)
    );
}

#[test]
fn a_shared_edge_is_hit_by_both_triangles() {
    // The square [0, 1]² at z = 0 split along the diagonal x = y, in both orders; rays through
    // dyadic points of the diagonal.
    let p = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    ];
    for order in [[[0, 1, 2], [0, 2, 3]], [[0, 2, 3], [0, 1, 2]]] {
        let bvh = Bvh::new(&p, &order).expect("valid");
        for k in 1..8 {
            let on_diagonal = DVec3::new(f64::from(k) / 8.0, f64::from(k) / 8.0, 0.0);
            // Along an axis the shear is exact: the edge function is exactly zero, both report.
            let ray = Ray::new(on_diagonal + DVec3::Z, DVec3::NEG_Z).expect("valid");
            let both = [0, 1].map(|i| bvh.intersect_triangle(&ray, i, 0.0, 2.0));
            assert!(both[0].is_some() && both[1].is_some(), "{both:?}");
            assert_eq!(bvh.closest_hit(&ray, 0.0, 2.0).map(|h| h.triangle), Some(0));
            // Obliquely the sheared diagonal carries rounding: one or both report, never none,
            // and the closest is the nearest of them (the smaller index on equal t).
            for origin in [DVec3::new(0.3, -0.2, 2.0), DVec3::new(-1.0, 3.0, -1.5)] {
                let ray = Ray::new(origin, on_diagonal - origin).expect("valid");
                let hits = [0, 1].map(|i| bvh.intersect_triangle(&ray, i, 0.0, 2.0));
                let nearest = hits
                    .iter()
                    .flatten()
                    .min_by(|a, b| a.t.total_cmp(&b.t).then(a.triangle.cmp(&b.triangle)));
                assert!(nearest.is_some(), "never neither");
                assert_eq!(bvh.closest_hit(&ray, 0.0, 2.0).as_ref(), nearest);
            }
        }
    }
}

#[test]
fn a_shared_vertex_is_hit_by_every_triangle_around_it() {
    // Six triangles around the origin in the plane z = 0.
    let mut p = vec![DVec3::ZERO];
    for k in 0..6 {
        let a = std::f64::consts::TAU * f64::from(k) / 6.0;
        p.push(DVec3::new(a.cos(), a.sin(), 0.0));
    }
    let triangles: Vec<[u32; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
    let bvh = Bvh::new(&p, &triangles).expect("valid");
    let ray = Ray::new(DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.0, 0.0, -1.0)).expect("valid");
    for i in 0..6 {
        assert_eq!(
            bvh.intersect_triangle(&ray, i, 0.0, 9.0).map(|h| h.t),
            Some(2.0),
            "triangle {i}"
        );
    }
    assert_eq!(bvh.closest_hit(&ray, 0.0, 9.0).map(|h| h.triangle), Some(0));
}

#[test]
fn a_ray_in_a_triangles_plane_misses_it() {
    let bvh = unit_triangle();
    let along = Ray::new(DVec3::new(-3.0, 0.0, 1.0), DVec3::X).expect("valid");
    assert_eq!(
        bvh.closest_hit(&along, f64::NEG_INFINITY, f64::INFINITY),
        None
    );
}

#[test]
fn zero_area_triangles_are_listed_and_never_hit() {
    let p = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(2.0, 2.0, 2.0),
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(1.0, -1.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
        // Nearly collinear with 0 and 1, but not exactly: a valid (thin) triangle.
        DVec3::new(0.5, 0.5, 0.5 + f64::EPSILON),
    ];
    let triangles = [
        [0, 1, 2], // collinear
        [3, 4, 5], // the unit triangle
        [3, 3, 4], // repeated vertex
        [1, 1, 1], // a point
        [0, 1, 6], // thin, not degenerate
    ];
    let bvh = Bvh::new(&p, &triangles).expect("valid");
    assert_eq!(bvh.degenerate_triangles(), &[0, 2, 3]);
    assert_eq!(bvh.triangle_count(), 5);
    assert_eq!(bvh.stats().degenerate, 3);
    for (i, target) in [
        (0, DVec3::splat(1.5)),
        (2, DVec3::new(0.0, -1.0, 1.0)),
        (3, DVec3::ONE),
    ] {
        let origin = target + DVec3::new(0.3, -2.0, 0.7);
        let ray = Ray::new(origin, target - origin).expect("valid");
        assert_eq!(
            bvh.intersect_triangle(&ray, i, f64::NEG_INFINITY, f64::INFINITY),
            None
        );
        assert!(
            bvh.closest_hit(&ray, f64::NEG_INFINITY, f64::INFINITY)
                .is_none_or(|h| h.triangle != i)
        );
    }
    assert_eq!(
        bvh.closest_hit(&up(), 0.0, 9.0).map(|h| h.triangle),
        Some(1)
    );
    // A mesh of nothing but zero-area triangles has nothing to hit.
    let flat = Bvh::new(&p, &[[0, 1, 2]]).expect("valid");
    assert_eq!(flat.bounds(), None);
    assert_eq!(flat.magnitude(), 0.0);
    let ray = Ray::new(DVec3::new(1.0, 0.0, 0.0), DVec3::new(-1.0, 1.0, 0.0)).expect("valid");
    assert_eq!(
        flat.closest_hit(&ray, f64::NEG_INFINITY, f64::INFINITY),
        None
    );
}

#[test]
fn an_empty_mesh_has_nothing_to_hit() {
    let bvh = Bvh::new(&[], &[]).expect("valid");
    assert_eq!(bvh.closest_hit(&up(), 0.0, f64::INFINITY), None);
    assert!(!bvh.occluded(&up(), 0.0, f64::INFINITY));
    assert_eq!(bvh.closest_hits(&[up(), up()], 0.0, 1.0), vec![None, None]);
    assert_eq!(bvh.occluded_all(&[up()], 0.0, 1.0), vec![false]);
    assert_eq!(bvh.bounds(), None);
    assert_eq!(bvh.stats().nodes, 0);
    assert_eq!(bvh.triangle_count(), 0);
}

#[test]
fn hit_points_normals_bounds_and_stats() {
    let bvh = unit_triangle();
    let hit = bvh.closest_hit(&up(), 0.0, 9.0).expect("hit");
    assert_eq!(bvh.hit_point(&hit), DVec3::new(0.0, 0.0, 1.0));
    assert_eq!(bvh.geometric_normal(0), DVec3::new(0.0, 0.0, 4.0));
    assert_eq!(
        bvh.bounds(),
        Some((DVec3::new(-1.0, -1.0, 1.0), DVec3::new(1.0, 1.0, 1.0)))
    );
    assert_eq!(bvh.magnitude(), 1.0);

    let sphere = uv_sphere(32, 64, 2.0).map(|p| p + DVec3::new(10.0, 0.0, 0.0));
    let bvh = sphere.bvh();
    let stats = bvh.stats();
    assert_eq!(stats.triangles, 2 * 64 * 31);
    assert!(
        stats.max_leaf_size >= 1 && stats.max_leaf_size <= 8,
        "{stats:?}"
    );
    assert!(stats.leaves > stats.triangles / 8 && stats.nodes >= stats.leaves / 4);
    assert!(stats.depth >= 3, "{stats:?}");
    let (lo, hi) = bvh.bounds().expect("triangles");
    assert_eq!((lo.x, hi.x), (8.0, 12.0));
    assert_eq!(bvh.magnitude(), 12.0);
    // Hit points agree with the ray's own point for a head-on hit.
    let ray = Ray::new(DVec3::new(10.3, 0.2, -9.0), DVec3::new(0.0, 0.0, 1.0)).expect("valid");
    let hit = bvh.closest_hit(&ray, 0.0, f64::INFINITY).expect("hit");
    assert!((bvh.hit_point(&hit) - ray.at(hit.t)).length() < 1e-12);
    assert!(hit.u >= 0.0 && hit.v >= 0.0 && hit.u + hit.v <= 1.0 + 1e-15);
    assert!(
        bvh.geometric_normal(hit.triangle).z < 0.0,
        "outward, facing the ray"
    );
}

proptest! {
    // Seed 0x7ACE_0D01: 400 sets of 12 triangles in one lattice plane (not an axis plane), and
    // rays in that plane: the shear's rounding turns the triangles into slivers, the hit
    // parameter is ill-conditioned, and the clamp keeps it inside the triangle's padded box.
    #![proptest_config(config(0x7ACE_0D01, 400))]

    /// Every hit's point `ray.at(t)` lies in its triangle's bounding box grown by the padding
    /// (plus the rounding of `at`).
    #[test]
    fn grazing_hits_lie_in_the_padded_box(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let vector = |rng: &mut Rng| {
            DVec3::new(rng.int(-9, 9) as f64, rng.int(-9, 9) as f64, rng.int(-9, 9) as f64)
        };
        let (e1, e2) = (vector(&mut rng), vector(&mut rng));
        prop_assume!(e1.cross(e2) != DVec3::ZERO);
        let lattice = |rng: &mut Rng| e1 * rng.int(-20, 20) as f64 + e2 * rng.int(-20, 20) as f64;
        let positions: Vec<DVec3> = (0..36).map(|_| lattice(&mut rng)).collect();
        let triangles: Vec<[u32; 3]> = (0..12).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let bvh = Bvh::new(&positions, &triangles).expect("valid");
        for _ in 0..24 {
            let origin = lattice(&mut rng);
            let Ok(ray) = Ray::new(origin, lattice(&mut rng) - origin) else { continue };
            for i in 0..12 {
                let all = (f64::NEG_INFINITY, f64::INFINITY);
                let Some(hit) = bvh.intersect_triangle(&ray, i, all.0, all.1) else {
                    continue;
                };
                let [a, b, c] = bvh.triangle(i);
                let reach = bvh.magnitude() + origin.abs().max_element();
                let at = ray.at(hit.t);
                let travel = (ray.direction * hit.t).abs().max_element();
                let slack = 2.0 * BOX_PADDING_ULPS * f64::EPSILON * reach
                    + 4.0 * f64::EPSILON * (origin.abs().max_element() + travel);
                let (lo, hi) = (a.min(b).min(c) - slack, a.max(b).max(c) + slack);
                prop_assert!(at.cmpge(lo).all() && at.cmple(hi).all(), "{at} outside {lo}..{hi}");
            }
        }
    }
}
