//! `offset_origin`: points computed on a triangle in f64 and then offset lie strictly on the
//! intended side of the triangle's exact plane (checked with Shewchuk's exact `orient3d`), at
//! magnitudes from 10⁻³ to 10⁶, for small triangles far from the origin and for large ones around
//! it (a ground plane, whose points near the origin carry the rounding of its far vertices); and
//! rays cast from the offset points away from the surface do not hit their own triangle.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_trace::{Bvh, Hit, OFFSET_ULPS, Ray, offset_origin};

use crate::support::{Rng, config};

fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// A triangle at scale `scale`: small and far from the origin (`far`), or large around it.
fn triangle(rng: &mut Rng, scale: f64, far: bool) -> [DVec3; 3] {
    if far {
        let center = rng.direction() * scale;
        let size = scale * 10f64.powf(rng.range(-3.0, 0.0));
        [0, 1, 2].map(|_| center + rng.cube_point() * size)
    } else {
        [0, 1, 2].map(|_| rng.cube_point() * scale)
    }
}

/// Barycentric coordinates `(u, v)`: inside, on an edge, or at a vertex.
fn barycentrics(rng: &mut Rng) -> (f64, f64) {
    let (a, b) = (rng.unit(), rng.unit());
    match rng.int(0, 3) {
        0 => (a.min(b), (a.max(b) - a.min(b))),
        1 => (a, 1.0 - a),
        2 => (0.0, a),
        _ => [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][rng.index(3)],
    }
}

proptest! {
    // Seed 0x7ACE_0F01: 3 000 triangles at scales 10^-3..10^6, three points each.
    #![proptest_config(config(0x7ACE_0F01, 3000))]

    /// The offset point is strictly on the side `s·n` points to (s the sign of n·toward), at a
    /// distance between 64 and 300 ε·m (the proven bound is 100 ε·m; the f64 evaluation of the
    /// distance used here errs by a few ε·m).
    #[test]
    fn offset_points_lie_strictly_on_the_intended_side(
        seed in any::<u64>(),
        log_scale in -3.0..6.0_f64,
        far in any::<bool>(),
    ) {
        let mut rng = Rng::new(seed);
        let scale = 10f64.powf(log_scale);
        let p = triangle(&mut rng, scale, far);
        let bvh = Bvh::new(&p, &[[0, 1, 2]]).expect("valid");
        prop_assume!(bvh.degenerate_triangles().is_empty());
        let normal = bvh.geometric_normal(0);
        // The precondition on the normal: within 60° of the exact one (true unless nearly flat).
        prop_assume!(normal.length() > 1e-6 * (p[1] - p[0]).length() * (p[2] - p[0]).length());
        for _ in 0..3 {
            let (u, v) = barycentrics(&mut rng);
            let point = bvh.hit_point(&Hit { t: 0.0, triangle: 0, u, v });
            let toward = rng.direction();
            let side = if normal.dot(toward) < 0.0 { -1.0 } else { 1.0 };
            let origin = offset_origin(point, normal, toward, bvh.magnitude()).expect("valid");
            let orientation = robust::orient3d(coord(p[0]), coord(p[1]), coord(p[2]), coord(origin));
            // orient3d is negative on the side the normal (b − a) × (c − a) points to.
            prop_assert!(orientation * side < 0.0, "{origin} not on side {side} (orient3d {orientation})");
            let m = bvh.magnitude().max(point.abs().max_element());
            let distance = normal.normalize().dot(origin - p[0]) * side;
            prop_assert!(distance >= 64.0 * f64::EPSILON * m, "{distance} vs m = {m}");
            prop_assert!(distance <= (OFFSET_ULPS + 44.0) * f64::EPSILON * m, "{distance} vs m = {m}");
        }
    }

    /// Rays from offset points, leaving the surface at angles from 10⁻⁶ rad to 90°, do not hit
    /// their own triangle (t_min = 0).
    #[test]
    fn rays_leaving_an_offset_point_miss_their_own_triangle(
        seed in any::<u64>(),
        log_scale in -3.0..6.0_f64,
        far in any::<bool>(),
    ) {
        let mut rng = Rng::new(seed);
        let scale = 10f64.powf(log_scale);
        let p = triangle(&mut rng, scale, far);
        let bvh = Bvh::new(&p, &[[0, 1, 2]]).expect("valid");
        prop_assume!(bvh.degenerate_triangles().is_empty());
        let normal = bvh.geometric_normal(0);
        prop_assume!(normal.length() > 1e-6 * (p[1] - p[0]).length() * (p[2] - p[0]).length());
        let unit = normal.normalize();
        for _ in 0..4 {
            let (u, v) = barycentrics(&mut rng);
            let point = bvh.hit_point(&Hit { t: 0.0, triangle: 0, u, v });
            let side = if rng.unit() < 0.5 { -1.0 } else { 1.0 };
            let tangent = {
                let w = rng.direction();
                (w - unit * unit.dot(w)).normalize()
            };
            let angle = 10f64.powf(rng.range(-6.0, 0.2));
            let direction = unit * (side * angle.sin()) + tangent * angle.cos();
            let origin = offset_origin(point, normal, direction, bvh.magnitude()).expect("valid");
            let ray = Ray::new(origin, direction * scale).expect("valid");
            prop_assert_eq!(bvh.closest_hit(&ray, 0.0, f64::INFINITY), None, "angle {}", angle);
        }
    }
}

#[test]
fn a_point_near_the_origin_of_a_large_triangle_needs_the_triangles_magnitude() {
    // A triangle reaching 10⁶ around the origin in the plane z = 0.3x + 0.5y; its points near
    // the origin carry rounding of order ε·10⁶ across the plane, far more than ε·|point|.
    let p = [
        DVec3::new(-1e6, -1e6, -8e5),
        DVec3::new(1e6, -1e6, -2e5),
        DVec3::new(0.0, 1e6, 5e5),
    ];
    let bvh = Bvh::new(&p, &[[0, 1, 2]]).expect("valid");
    let normal = bvh.geometric_normal(0);
    let mut rng = Rng::new(0x7ACE_0F02);
    for _ in 0..2000 {
        // Barycentrics of points within ~1 of the origin.
        let (u, v) = (0.25 + rng.range(-1e-6, 1e-6), 0.5 + rng.range(-1e-6, 1e-6));
        let point = bvh.hit_point(&Hit {
            t: 0.0,
            triangle: 0,
            u,
            v,
        });
        for side in [-1.0, 1.0] {
            let origin =
                offset_origin(point, normal, normal * side, bvh.magnitude()).expect("valid");
            let orientation =
                robust::orient3d(coord(p[0]), coord(p[1]), coord(p[2]), coord(origin));
            assert!(orientation * side < 0.0, "{origin} on the wrong side");
        }
    }
}
