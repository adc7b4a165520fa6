//! The tree against brute force: `closest_hit` and `occluded` (and their batch forms) return
//! exactly what a loop over all triangles returns, on random meshes at scales from 10⁻³ to 10⁶,
//! for random rays and for the hard ones: aimed exactly at vertices and edge midpoints, running
//! along shared edges (in the planes of both triangles), and lying in a flat grid's plane.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_trace::{Hit, Ray};

use crate::support::{
    Mesh, Rng, brute_closest, brute_occluded, config, jittered_grid, soup, uv_sphere,
};

/// Triangles with integer vertices in one plane through the origin, spanned by two random integer
/// vectors (not an axis plane): rays in that plane see them as slivers after the shear's rounding,
/// where the parameter of a hit is ill-conditioned.
fn coplanar(count: usize, rng: &mut Rng) -> (Mesh, [DVec3; 2]) {
    let vector = |rng: &mut Rng| {
        DVec3::new(
            rng.int(-9, 9) as f64,
            rng.int(-9, 9) as f64,
            rng.int(-9, 9) as f64,
        )
    };
    let (mut e1, mut e2) = (vector(rng), vector(rng));
    while e1.cross(e2) == DVec3::ZERO {
        (e1, e2) = (vector(rng), vector(rng));
    }
    let mut mesh = Mesh::default();
    for k in 0..3 * count {
        let p = e1 * rng.int(-20, 20) as f64 + e2 * rng.int(-20, 20) as f64;
        mesh.positions.push(p / 64.0);
        if k % 3 == 2 {
            let v = u32::try_from(k).expect("small");
            mesh.triangles.push([v - 2, v - 1, v]);
        }
    }
    (mesh, [e1, e2])
}

/// A test mesh of one of five kinds, scaled by `scale` and moved by `offset·scale·shift`.
pub(crate) fn mesh(kind: u8, seed: u64, scale: f64, shift: f64) -> Mesh {
    let mut rng = Rng::new(seed);
    let offset = rng.cube_point() * shift;
    let base = match kind {
        0 => soup(48, &mut rng),
        1 => jittered_grid(5, seed).map(|p| (p - DVec3::new(2.5, 2.5, 0.0)) * 0.4),
        2 => uv_sphere(6, 10, 1.0),
        3 => coplanar(40, &mut rng).0,
        // A flat grid: every ray in its plane runs along edges and through vertices.
        _ => jittered_grid(4, seed).map(|p| DVec3::new(p.x - 2.0, p.y - 2.0, 0.0) * 0.5),
    };
    base.map(|p| (p + offset) * scale)
}

/// Rays from lattice points of the plane of [`coplanar`] meshes to other lattice points: they lie
/// in the plane exactly (before scaling) and cross many of its triangles.
fn in_plane_rays(seed: u64, scale: f64, shift: f64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    let offset = rng.cube_point() * shift;
    let (_, [e1, e2]) = coplanar(40, &mut rng);
    let point = |rng: &mut Rng| {
        ((e1 * rng.int(-30, 30) as f64 + e2 * rng.int(-30, 30) as f64) / 64.0 + offset) * scale
    };
    (0..48)
        .filter_map(|_| {
            let origin = point(&mut rng);
            Ray::new(origin, point(&mut rng) - origin).ok()
        })
        .collect()
}

/// Rays of every hard kind for `mesh`, plus random ones.
fn rays(mesh: &Mesh, rng: &mut Rng, scale: f64) -> Vec<Ray> {
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let center = (lo + hi) * 0.5;
    let outside = |rng: &mut Rng| center + rng.direction() * (3.0 * scale);
    let mut rays = Vec::new();
    let mut push = |origin: DVec3, direction: DVec3| {
        if let Ok(ray) = Ray::new(origin, direction) {
            rays.push(ray);
        }
    };
    for _ in 0..24 {
        let origin = outside(rng);
        let target = lo + (hi - lo) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
        push(origin, target - origin);
    }
    for _ in 0..8 {
        let origin = center + rng.cube_point() * scale;
        push(origin, rng.direction());
    }
    for _ in 0..12 {
        let v = mesh.positions[rng.index(mesh.positions.len())];
        let origin = outside(rng);
        push(origin, v - origin);
    }
    let edges = mesh.shared_edges();
    if !edges.is_empty() {
        for _ in 0..12 {
            let [a, b] = edges[rng.index(edges.len())];
            let (a, b) = (mesh.positions[a as usize], mesh.positions[b as usize]);
            let origin = outside(rng);
            push(origin, (a + b) * 0.5 - origin);
            // Along the edge, starting before it: in the planes of both its triangles.
            push(a - (b - a), b - a);
            push(b + (b - a) * 0.5, a - b);
        }
    }
    // Along the axes (zero direction components: infinite slab parameters) exactly through
    // vertices, and through points sharing a coordinate with a vertex.
    for _ in 0..12 {
        let v = mesh.positions[rng.index(mesh.positions.len())];
        let axis = [DVec3::X, DVec3::Y, DVec3::Z][rng.index(3)];
        let sign = if rng.unit() < 0.5 { -1.0 } else { 1.0 };
        push(v - axis * (sign * 3.0 * scale), axis * sign);
        let w = mesh.positions[rng.index(mesh.positions.len())];
        let mixed = DVec3::new(v.x, w.y, center.z) - axis * (sign * 3.0 * scale);
        push(mixed, axis * sign);
    }
    // In the plane z = mean height (for the flat grid: its own plane).
    for _ in 0..6 {
        let origin = DVec3::new(center.x, center.y, center.z) + DVec3::new(3.0, 0.7, 0.0) * scale;
        let target = DVec3::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y), center.z);
        push(origin, target - origin);
    }
    rays
}

proptest! {
    // Seed 0x7ACE_0A01: 160 meshes (48-triangle soups, jittered height fields, coarse spheres,
    // coplanar triangles with rays in their plane, flat grids) at scales 10^-3..10^6, some far
    // from the origin, about 110 rays each.
    #![proptest_config(config(0x7ACE_0A01, 160))]

    /// `closest_hit` and `occluded` equal brute force, bit for bit, for t-ranges (0, ∞),
    /// (−∞, ∞) and a random sub-interval; the batch forms equal the single queries.
    #[test]
    fn tree_equals_brute_force(
        kind in 0u8..5,
        seed in any::<u64>(),
        log_scale in -3.0..6.0_f64,
        shift in prop_oneof![Just(0.0), 0.0..1e3_f64],
    ) {
        let scale = 10f64.powf(log_scale);
        let mesh = mesh(kind, seed, scale, shift);
        let bvh = mesh.bvh();
        let mut rng = Rng::new(seed ^ 0x5EED);
        let mut rays = rays(&mesh, &mut rng, scale);
        if kind == 3 {
            rays.extend(in_plane_rays(seed, scale, shift));
        }
        let (a, b) = (rng.range(0.0, 2.0), rng.range(0.0, 2.0));
        let ranges = [
            (0.0, f64::INFINITY),
            (f64::NEG_INFINITY, f64::INFINITY),
            (a.min(b), a.max(b)),
        ];
        for (t_min, t_max) in ranges {
            let mut any_hit = false;
            for ray in &rays {
                let expected = brute_closest(&bvh, ray, t_min, t_max);
                prop_assert_eq!(bvh.closest_hit(ray, t_min, t_max), expected, "ray {:?}", ray);
                let blocked = brute_occluded(&bvh, ray, t_min, t_max);
                prop_assert_eq!(bvh.occluded(ray, t_min, t_max), blocked);
                prop_assert_eq!(expected.is_some(), blocked);
                any_hit |= expected.is_some();
            }
            if t_min == 0.0 {
                prop_assert!(any_hit, "the rays aimed at vertices hit something");
            }
            let singles: Vec<_> = rays.iter().map(|r| bvh.closest_hit(r, t_min, t_max)).collect();
            prop_assert_eq!(bvh.closest_hits(&rays, t_min, t_max), singles);
            let singles: Vec<_> = rays.iter().map(|r| bvh.occluded(r, t_min, t_max)).collect();
            prop_assert_eq!(bvh.occluded_all(&rays, t_min, t_max), singles);
        }
    }
}

/// A larger mesh (a deep tree: 6 000 triangles, a hundred random rays): the same equality.
#[test]
fn deep_tree_equals_brute_force() {
    let mut rng = Rng::new(0x7ACE_0A02);
    let mut mesh = soup(3000, &mut rng);
    let sphere = uv_sphere(40, 40, 0.9);
    let base = u32::try_from(mesh.positions.len()).expect("small");
    mesh.positions.extend(&sphere.positions);
    mesh.triangles
        .extend(sphere.triangles.iter().map(|t| t.map(|v| v + base)));
    let bvh = mesh.bvh();
    assert!(bvh.stats().depth >= 4, "{:?}", bvh.stats());
    let mut hits = 0;
    for _ in 0..100 {
        let origin = rng.direction() * 3.0;
        let ray = Ray::new(origin, rng.cube_point() - origin).expect("valid");
        let expected = brute_closest(&bvh, &ray, 0.0, f64::INFINITY);
        assert_eq!(bvh.closest_hit(&ray, 0.0, f64::INFINITY), expected);
        assert_eq!(bvh.occluded(&ray, 0.0, f64::INFINITY), expected.is_some());
        hits += usize::from(expected.is_some());
    }
    assert!(hits > 50, "{hits} of 100 rays hit");
}

proptest! {
    // Seed 0x7ACE_0A03: 64 meshes and their rays, scaled by 2^k for k in -150..150.
    #![proptest_config(config(0x7ACE_0A03, 64))]

    /// Scaling the mesh and the rays' origins by a power of two changes no bit of any hit but
    /// nothing else: every operation of the test scales exactly (barring underflow and overflow,
    /// which these magnitudes stay clear of).
    #[test]
    fn power_of_two_scaling_changes_nothing(kind in 0u8..5, seed in any::<u64>(), k in -150i32..150) {
        let mesh = mesh(kind, seed, 1.0, 0.0);
        let mut rng = Rng::new(seed ^ 0x5CA1E);
        let rays = rays(&mesh, &mut rng, 1.0);
        let factor = 2f64.powi(k);
        let scaled = mesh.clone().map(|p| p * factor);
        let scaled_rays: Vec<Ray> = rays
            .iter()
            .map(|r| Ray::new(r.origin * factor, r.direction).expect("valid"))
            .collect();
        let (bvh, scaled_bvh) = (mesh.bvh(), scaled.bvh());
        prop_assert_eq!(scaled_bvh.magnitude(), bvh.magnitude() * factor);
        let hits = bvh.closest_hits(&rays, 0.0, f64::INFINITY);
        let scaled_hits = scaled_bvh.closest_hits(&scaled_rays, 0.0, f64::INFINITY);
        for (hit, scaled) in hits.iter().zip(&scaled_hits) {
            let expected = hit.map(|h| Hit { t: h.t * factor, ..h });
            prop_assert_eq!(*scaled, expected);
        }
    }
}
