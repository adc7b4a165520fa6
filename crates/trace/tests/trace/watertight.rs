//! Watertightness: rays never pass through a closed mesh, or through a height field seen from
//! steeper than its slopes, not even exactly through a vertex or an edge.
//!
//! Targets are chosen so that the rays pass *exactly* through them: the cube and the grid have
//! dyadic coordinates (multiples of 1/64 or 1/8 at small magnitudes), so `target − origin` and
//! edge midpoints `(a + b)/2` are computed without rounding; the sphere's rays start at its
//! centre, so the direction to a vertex is the vertex's offset itself (exact by Sterbenz's lemma
//! for the translated sphere).

use glam::DVec3;
use shadowlab_trace::{Bvh, Ray};

use crate::support::{Mesh, Rng, jittered_grid, tessellated_cube, uv_sphere};

/// How far past the target (in units of the ray's direction) the hit may come: the target is on
/// the surface at t = 1 exactly, the computed parameter is within rounding of it.
const PAST_TARGET: f64 = 1e-9;

/// Every ray from `origin` to each target hits the mesh no later than the target, by both
/// queries; returns how many rays were cast.
fn assert_all_hit(bvh: &Bvh, origin: DVec3, targets: &[DVec3], what: &str) -> usize {
    let rays: Vec<Ray> = targets
        .iter()
        .map(|&target| Ray::new(origin, target - origin).expect("valid ray"))
        .collect();
    let limit = 1.0 + PAST_TARGET;
    let hits = bvh.closest_hits(&rays, 0.0, limit);
    let blocked = bvh.occluded_all(&rays, 0.0, limit);
    for k in 0..rays.len() {
        assert!(
            hits[k].is_some() && blocked[k],
            "{what}: the ray from {origin} to {} escapes",
            targets[k]
        );
    }
    rays.len()
}

/// Targets: every vertex and the midpoint of every shared edge.
fn vertices_and_midpoints(mesh: &Mesh) -> Vec<DVec3> {
    let mut targets = mesh.positions.clone();
    for [a, b] in mesh.shared_edges() {
        targets.push((mesh.positions[a as usize] + mesh.positions[b as usize]) * 0.5);
    }
    targets
}

#[test]
fn no_ray_escapes_a_tessellated_sphere() {
    // 16 128 triangles; the sphere at the origin and far from it, at three sizes.
    for (center, radius) in [
        (DVec3::ZERO, 1.0),
        (DVec3::new(1e6, -2e6, 3e5), 1.0),
        (DVec3::new(-0.5, 0.25, 4.0), 1e-3),
    ] {
        let mesh = uv_sphere(64, 128, radius).map(|p| p + center);
        let bvh = mesh.bvh();
        let count = assert_all_hit(&bvh, center, &vertices_and_midpoints(&mesh), "sphere");
        assert!(count > 32_000);
        // Random directions from random interior points.
        let mut rng = Rng::new(0x7ACE_0B01);
        let rays: Vec<Ray> = (0..4000)
            .map(|_| {
                let origin = center + rng.cube_point() * (0.5 * radius);
                Ray::new(origin, rng.direction()).expect("valid")
            })
            .collect();
        for (k, hit) in bvh
            .closest_hits(&rays, 0.0, f64::INFINITY)
            .iter()
            .enumerate()
        {
            assert!(hit.is_some(), "ray {:?} escapes the sphere", rays[k]);
        }
        assert!(
            bvh.occluded_all(&rays, 0.0, f64::INFINITY)
                .iter()
                .all(|&b| b)
        );
    }
}

#[test]
fn no_ray_escapes_a_tessellated_cube() {
    // 3 072 triangles; rays from three interior points through every vertex (cube corners and
    // edges included) and every edge midpoint, at three scales and offsets (all dyadic).
    for (scale, shift) in [
        (1.0, DVec3::ZERO),
        (1024.0, DVec3::new(65536.0, -4096.0, 512.0)),
        (1.0 / 512.0, DVec3::new(0.125, 0.0, -0.25)),
    ] {
        let mesh = tessellated_cube(16).map(|p| p * scale + shift);
        let bvh = mesh.bvh();
        let targets = vertices_and_midpoints(&mesh);
        for origin in [
            DVec3::ZERO,
            DVec3::new(0.25, -0.5, 0.125),
            DVec3::new(0.875, 0.875, -0.9375),
        ] {
            assert_all_hit(&bvh, origin * scale + shift, &targets, "cube");
        }
    }
}

/// The steepest slope `|∇h|` of a height-field triangle.
fn slope(p: [DVec3; 3]) -> f64 {
    let n = (p[1] - p[0]).cross(p[2] - p[0]);
    n.truncate().length() / n.z.abs()
}

#[test]
fn no_ray_passes_through_a_jittered_grid() {
    // A 24 × 24 height field (1 152 triangles); rays from above and below, steeper than any of its
    // triangles (so the field covers every ray's footprint exactly once), through every interior
    // vertex and every shared edge's midpoint.
    let n = 24;
    let mesh = jittered_grid(n, 0x7ACE_0B02);
    let bvh = mesh.bvh();
    let steepest = mesh
        .triangles
        .iter()
        .map(|t| slope(t.map(|v| mesh.positions[v as usize])))
        .fold(0.0, f64::max);
    // Rays rise 20 over a lateral run of at most `reach`·√2, a quarter steeper than any triangle.
    let reach = (20.0 / (1.25 * steepest * std::f64::consts::SQRT_2) * 8.0).floor();
    assert!(
        reach >= 8.0,
        "the field is too steep for this test: {steepest}"
    );
    let interior = |p: &DVec3| p.x > 0.0 && p.x < f64::from(n) && p.y > 0.0 && p.y < f64::from(n);
    let targets: Vec<DVec3> = vertices_and_midpoints(&mesh)
        .into_iter()
        .filter(interior)
        .collect();
    assert!(targets.len() > 2000);
    let mut rng = Rng::new(0x7ACE_0B03);
    let mut cast = 0;
    #[expect(
        clippy::cast_possible_truncation,
        reason = "an integer between 8 and a few hundred"
    )]
    let reach = reach as i64;
    for &target in &targets {
        for side in [-1.0, 1.0] {
            // Dyadic offsets (multiples of 1/8), so target − origin is exact.
            let lateral = DVec3::new(
                rng.int(-reach, reach) as f64 / 8.0,
                rng.int(-reach, reach) as f64 / 8.0,
                0.0,
            );
            let origin = target + lateral + DVec3::new(0.0, 0.0, 20.0 * side);
            cast += assert_all_hit(&bvh, origin, &[target], "grid");
        }
    }
    assert_eq!(cast, 2 * targets.len());
}
