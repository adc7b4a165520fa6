//! The ray–triangle test against exact arithmetic.
//!
//! * On integer inputs, whenever the exact answer is not on an edge (all three scalar triple
//!   products non-zero), the decision is the exact one and `t`, `u`, `v` are accurate: the shear
//!   moves vertices by less than 10⁻¹² here, far less than an integer configuration can come to
//!   an edge without touching it.
//! * On edges and vertices (triple products zero), the exact line passes through a shared edge or
//!   vertex: at least one triangle around it must report the hit whenever the triangles there face
//!   the same way (exactly computed), i.e. whenever the surface does not fold over along the ray.
//! * On arbitrary f64 inputs the decision is exactly the 2-D point-in-triangle test of the sheared
//!   vertices (the documented shear, repeated here), checked with Shewchuk's exact `orient2d`.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_trace::{Bvh, Ray};

use crate::support::{Rng, config};

type I3 = [i128; 3];

fn sub(a: I3, b: I3) -> I3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The scalar triple product `a · (b × c)`, exactly.
fn det(a: I3, b: I3, c: I3) -> i128 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

fn to_f64(v: I3, scale: f64, shift: DVec3) -> DVec3 {
    DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64) * scale + shift
}

fn point(rng: &mut Rng, limit: i64) -> I3 {
    [0, 1, 2].map(|_| i128::from(rng.int(-limit, limit)))
}

proptest! {
    // Seed 0x7ACE_0C01: 4 000 integer triangles and rays.
    #![proptest_config(config(0x7ACE_0C01, 4000))]

    /// Integer configurations off every edge: the exact decision, and t, u, v within 10⁻¹²
    /// (relative to the ray's reach and to 1).
    #[test]
    fn integer_inputs_off_edges_are_decided_exactly(seed in any::<u64>()) {
        let mut rng = Rng::new(seed);
        let p = [point(&mut rng, 64), point(&mut rng, 64), point(&mut rng, 64)];
        let o = point(&mut rng, 64);
        // Half the rays aimed at a point inside the triangle's box, so that many hit.
        let d = if rng.unit() < 0.5 {
            point(&mut rng, 16)
        } else {
            let lo = [0, 1, 2].map(|k| p[0][k].min(p[1][k]).min(p[2][k]));
            let target = [0, 1, 2].map(|k| lo[k] + i128::from(rng.int(0, 8)));
            sub(target, o)
        };
        prop_assume!(d != [0, 0, 0]);
        let a = [sub(p[0], o), sub(p[1], o), sub(p[2], o)];
        // The weights of p0, p1, p2 (edges p1→p2, p2→p0, p0→p1), up to a common factor.
        let s = [det(d, a[1], a[2]), det(d, a[2], a[0]), det(d, a[0], a[1])];
        prop_assume!(s.iter().all(|&x| x != 0));
        let inside = s.iter().all(|&x| x > 0) || s.iter().all(|&x| x < 0);
        let positions = p.map(|q| to_f64(q, 1.0, DVec3::ZERO));
        let bvh = Bvh::new(&positions, &[[0, 1, 2]]).expect("valid");
        let ray = Ray::new(to_f64(o, 1.0, DVec3::ZERO), to_f64(d, 1.0, DVec3::ZERO)).expect("valid");
        let hit = bvh.intersect_triangle(&ray, 0, f64::NEG_INFINITY, f64::INFINITY);
        prop_assert_eq!(hit.is_some(), inside, "s = {:?}", s);
        if let Some(hit) = hit {
            let sum = s[0] + s[1] + s[2];
            let n = det(sub(p[1], p[0]), sub(p[2], p[0]), d);
            let t = det(sub(p[1], p[0]), sub(p[2], p[0]), a[0]) as f64 / n as f64;
            let reach = a.iter().flatten().map(|x| x.abs()).max().expect("3 vertices") as f64
                / d.iter().map(|x| x.abs()).max().expect("3 components") as f64;
            prop_assert!((hit.t - t).abs() <= 1e-12 * reach, "t = {} vs {t}", hit.t);
            let (u, v) = (s[1] as f64 / sum as f64, s[2] as f64 / sum as f64);
            prop_assert!((hit.u - u).abs() <= 1e-12 && (hit.v - v).abs() <= 1e-12,
                "(u, v) = ({}, {}) vs ({u}, {v})", hit.u, hit.v);
        }
    }

    /// A ray through the midpoint of an edge shared by two triangles that face the same way
    /// along it (exactly) hits at least one of them; at scales 2^-20..2^20 and offsets up to
    /// 2^20 of the scale (all exact).
    #[test]
    fn shared_edges_never_leak(seed in any::<u64>(), log_scale in -20i32..20, far in any::<bool>()) {
        let mut rng = Rng::new(seed);
        let even = |rng: &mut Rng| point(rng, 32).map(|x| 2 * x);
        let (a, b) = (even(&mut rng), even(&mut rng));
        prop_assume!(a != b);
        let mid = [0, 1, 2].map(|k| (a[k] + b[k]) / 2);
        // Triangles [a, b, c] and [b, a, e], consistently oriented; both must face the ray the
        // same way, and neither may contain the ray's line in its plane: draw until they do.
        let found = (0..64).find_map(|_| {
            let (c, e, o) = (point(&mut rng, 64), point(&mut rng, 64), point(&mut rng, 64));
            let d = sub(mid, o);
            let first = det(sub(b, a), sub(c, a), d);
            let second = det(sub(a, b), sub(e, b), d);
            (first != 0 && second != 0 && (first > 0) == (second > 0)).then_some((c, e, o))
        });
        prop_assume!(found.is_some());
        let (c, e, o) = found.expect("checked");
        let scale = 2f64.powi(log_scale);
        let shift = if far { DVec3::new(1.0, -1.0, 0.5) * 2f64.powi(20) * scale } else { DVec3::ZERO };
        let positions = [a, b, c, e].map(|q| to_f64(q, scale, shift));
        let bvh = Bvh::new(&positions, &[[0, 1, 2], [1, 0, 3]]).expect("valid");
        let origin = to_f64(o, scale, shift);
        let ray = Ray::new(origin, to_f64(mid, scale, shift) - origin).expect("valid");
        let hits = [0, 1].map(|i| bvh.intersect_triangle(&ray, i, f64::NEG_INFINITY, f64::INFINITY));
        prop_assert!(hits[0].is_some() || hits[1].is_some(), "the ray leaks through the edge");
        prop_assert!(bvh.closest_hit(&ray, f64::NEG_INFINITY, f64::INFINITY).is_some());
    }

    /// A ray exactly through the centre of a fan whose triangles all face it the same way
    /// (exactly) hits at least one of them.
    #[test]
    fn fan_centres_never_leak(seed in any::<u64>(), spokes in 3usize..10) {
        let mut rng = Rng::new(seed);
        let center = point(&mut rng, 64);
        // A ring around the centre in a random frame, with jitter off its plane.
        let (u, v) = (point(&mut rng, 8), point(&mut rng, 8));
        let ring: Vec<I3> = (0..spokes)
            .map(|k| {
                let angle = std::f64::consts::TAU * k as f64 / spokes as f64;
                #[expect(clippy::cast_possible_truncation, reason = "rounded values in [-4, 4]")]
                let (cu, cv) = ((4.0 * angle.cos()).round() as i128, (4.0 * angle.sin()).round() as i128);
                let jitter = point(&mut rng, 3);
                [0, 1, 2].map(|i| center[i] + cu * u[i] + cv * v[i] + jitter[i])
            })
            .collect();
        let o = point(&mut rng, 64);
        let d = sub(center, o);
        prop_assume!(d != [0, 0, 0]);
        let faces: Vec<i128> = (0..spokes)
            .map(|k| det(sub(ring[k], center), sub(ring[(k + 1) % spokes], center), d))
            .collect();
        prop_assume!(faces.iter().all(|&f| f > 0) || faces.iter().all(|&f| f < 0));
        let mut positions = vec![to_f64(center, 1.0, DVec3::ZERO)];
        positions.extend(ring.iter().map(|&q| to_f64(q, 1.0, DVec3::ZERO)));
        let n = u32::try_from(spokes).expect("small");
        let triangles: Vec<[u32; 3]> = (0..n)
            .map(|k| [0, 1 + k, 1 + (k + 1) % n])
            .collect();
        let bvh = Bvh::new(&positions, &triangles).expect("valid");
        let origin = to_f64(o, 1.0, DVec3::ZERO);
        let ray = Ray::new(origin, positions[0] - origin).expect("valid");
        let hit = bvh.closest_hit(&ray, f64::NEG_INFINITY, f64::INFINITY);
        prop_assert!(hit.is_some(), "the ray leaks through the fan's centre");
        prop_assert!((hit.expect("checked").t - 1.0).abs() < 1e-12);
    }
}

/// The signs of the three edge functions as the documentation defines them: sheared vertices,
/// exact 2-D orientation against the sheared origin (0, 0).
fn exact_sheared_decision(ray: &Ray, p: [DVec3; 3]) -> bool {
    let d = ray.direction.abs();
    let kz = if d.x >= d.y && d.x >= d.z {
        0
    } else if d.y >= d.z {
        1
    } else {
        2
    };
    let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
    let dir = ray.direction;
    let (sx, sy) = (dir[kx] / dir[kz], dir[ky] / dir[kz]);
    let sheared = p.map(|q| {
        let a = q - ray.origin;
        robust::Coord {
            x: a[kx] - sx * a[kz],
            y: a[ky] - sy * a[kz],
        }
    });
    let zero = robust::Coord { x: 0.0, y: 0.0 };
    let [a, b, c] = sheared;
    let s = [
        robust::orient2d(c, b, zero),
        robust::orient2d(a, c, zero),
        robust::orient2d(b, a, zero),
    ];
    (s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)) && s.iter().any(|&x| x != 0.0)
}

proptest! {
    // Seed 0x7ACE_0C02: 3 000 float triangles at scales 10^-3..10^6, rays aimed at points within
    // rounding of an edge or a vertex (where the edge functions round to zero or near it).
    #![proptest_config(config(0x7ACE_0C02, 3000))]

    /// The decision equals the exact point-in-triangle test of the sheared vertices: a non-zero
    /// edge function has the exact sign, a zero one is resolved exactly by the FMA fallback.
    #[test]
    fn decision_is_the_exact_test_of_the_sheared_vertices(
        seed in any::<u64>(),
        log_scale in -3.0..6.0_f64,
    ) {
        let mut rng = Rng::new(seed);
        let scale = 10f64.powf(log_scale);
        let center = rng.cube_point() * (4.0 * scale);
        let p = [0, 1, 2].map(|_| center + rng.cube_point() * scale);
        let bvh = Bvh::new(&p, &[[0, 1, 2]]).expect("valid");
        prop_assume!(bvh.degenerate_triangles().is_empty());
        let origin = center + rng.direction() * (3.0 * scale);
        let k = rng.index(3);
        let lambda = rng.unit();
        let target = match rng.int(0, 2) {
            0 => p[k],
            1 => p[k] + (p[(k + 1) % 3] - p[k]) * lambda,
            _ => p[k] * 0.5 + p[(k + 1) % 3] * 0.5,
        };
        let ray = Ray::new(origin, target - origin).expect("valid");
        let hit = bvh.intersect_triangle(&ray, 0, f64::NEG_INFINITY, f64::INFINITY);
        prop_assert_eq!(hit.is_some(), exact_sheared_decision(&ray, p));
    }
}
