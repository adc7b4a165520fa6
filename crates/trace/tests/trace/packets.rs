//! The batch queries trace runs of coherent rays together (rays sharing their direction signs,
//! in packets): their answers are each ray's single-query answer, and brute force's, bit for bit.
//! The batches here are built so that packets form — parallel rays, and rays from one point
//! outside the mesh — and aimed where the tests are hardest: exactly at vertices and edge
//! midpoints, along shared edges (grazing, in the planes of both triangles) and a hair beside
//! them, and through zero-area triangles added to the mesh.

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_trace::{Bvh, Ray};

use crate::agreement::mesh;
use crate::support::{Mesh, Rng, brute_closest, brute_occluded, config, uv_sphere};

/// Rays per group of one kind: several packets' worth, so that packets form inside each group.
const GROUP: usize = 40;

/// A direction with no component near zero (so that the rays of a group share their signs and
/// every inverse is finite), random otherwise.
fn generic_direction(rng: &mut Rng) -> DVec3 {
    loop {
        let d = rng.direction();
        if d.abs().min_element() > 0.1 {
            return d;
        }
    }
}

/// `mesh` with zero-area triangles added over some of its triangles (a repeated vertex, or an
/// edge's end points and one of them again), so that coherent rays cross them.
fn with_degenerate(mut mesh: Mesh, rng: &mut Rng) -> Mesh {
    let count = mesh.triangles.len();
    for _ in 0..count.min(12) {
        let [a, b, _] = mesh.triangles[rng.index(count)];
        mesh.triangles.push([a, a, b]);
        mesh.triangles.push([a, b, b]);
    }
    mesh
}

/// Coherent groups of rays for `mesh`: parallel rays at vertices, at edge midpoints and grazing
/// along shared edges (and beside them), rays from one point outside the mesh at vertices, and
/// parallel rays over the mesh's box.
fn coherent_rays(mesh: &Mesh, rng: &mut Rng, scale: f64) -> Vec<Ray> {
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let mut rays = Vec::new();
    let mut push = |origin: DVec3, direction: DVec3| {
        if let Ok(ray) = Ray::new(origin, direction) {
            rays.push(ray);
        }
    };
    let vertex = |rng: &mut Rng| mesh.positions[rng.index(mesh.positions.len())];
    let d = generic_direction(rng);
    for _ in 0..GROUP {
        let v = vertex(rng);
        push(v - d * (3.0 * scale), d);
    }
    let edges = mesh.shared_edges();
    if !edges.is_empty() {
        let edge = |rng: &mut Rng| {
            let [a, b] = edges[rng.index(edges.len())];
            (mesh.positions[a as usize], mesh.positions[b as usize])
        };
        for _ in 0..GROUP {
            let (a, b) = edge(rng);
            push((a + b) * 0.5 - d * (3.0 * scale), d);
        }
        // Along one shared edge, from several starts: every ray in both triangles' planes.
        let (a, b) = edge(rng);
        for k in 0..GROUP {
            push(
                a - (b - a) * (1.0 + f64::from(u32::try_from(k).expect("small"))),
                b - a,
            );
        }
        // Beside it, a few ulps of the scale away on either side.
        let side = (b - a).cross(d);
        for k in 0..GROUP {
            let offset = f64::from(i32::try_from(k).expect("small") - 20) * f64::EPSILON * scale;
            push(a - (b - a) + side * offset, b - a);
        }
    }
    // From one point beyond the mesh's box on every axis: all directions share their signs.
    let eye = hi + (hi - lo) * DVec3::new(0.7, 0.9, 1.1) + DVec3::splat(scale);
    for _ in 0..GROUP {
        let v = vertex(rng);
        push(eye, v - eye);
    }
    for _ in 0..GROUP {
        let target = lo + (hi - lo) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
        push(target - d * (3.0 * scale), d);
    }
    rays
}

/// The batch answers are the single answers, and brute force's, for three parameter ranges.
fn check(bvh: &Bvh, rays: &[Ray], ranges: &[(f64, f64)]) -> Result<(), TestCaseError> {
    for &(t_min, t_max) in ranges {
        let closest = bvh.closest_hits(rays, t_min, t_max);
        let occluded = bvh.occluded_all(rays, t_min, t_max);
        for (k, ray) in rays.iter().enumerate() {
            let single = bvh.closest_hit(ray, t_min, t_max);
            prop_assert_eq!(
                closest[k],
                single,
                "ray {} {:?} in ({}, {})",
                k,
                ray,
                t_min,
                t_max
            );
            prop_assert_eq!(single, brute_closest(bvh, ray, t_min, t_max));
            prop_assert_eq!(occluded[k], bvh.occluded(ray, t_min, t_max), "ray {}", k);
            prop_assert_eq!(occluded[k], brute_occluded(bvh, ray, t_min, t_max));
        }
    }
    Ok(())
}

proptest! {
    // Seed 0x7ACE_0B01: 96 meshes of the agreement test's five kinds, with zero-area triangles
    // added, at scales 10^-3..10^6, some far from the origin; about 280 coherent rays each.
    #![proptest_config(config(0x7ACE_0B01, 96))]

    /// Coherent batches: the packet answers equal the single answers and brute force's.
    #[test]
    fn packets_equal_single_rays(
        kind in 0u8..5,
        seed in any::<u64>(),
        log_scale in -3.0..6.0_f64,
        shift in prop_oneof![Just(0.0), 0.0..1e3_f64],
    ) {
        let scale = 10f64.powf(log_scale);
        let mut rng = Rng::new(seed ^ 0xC0E7);
        let mesh = with_degenerate(mesh(kind, seed, scale, shift), &mut rng);
        let bvh = mesh.bvh();
        let rays = coherent_rays(&mesh, &mut rng, scale);
        let (a, b) = (rng.range(0.0, 4.0), rng.range(0.0, 4.0));
        check(
            &bvh,
            &rays,
            &[(0.0, f64::INFINITY), (f64::NEG_INFINITY, f64::INFINITY), (a.min(b), a.max(b))],
        )?;
    }
}

/// A fine sphere (a deep tree) under a dense grid of parallel rays, a shadow map's rays: every
/// packet answer is the single answer, and the rays through the sphere's vertices hit (but at
/// its silhouette, where they only graze it).
#[test]
fn a_dense_grid_of_parallel_rays_equals_single_rays() {
    let mesh = uv_sphere(48, 96, 1.0);
    let bvh = mesh.bvh();
    let d = DVec3::new(-0.3, -1.0, -0.45);
    let (side, up) = (
        d.cross(DVec3::Z).normalize(),
        d.cross(DVec3::Z).cross(d).normalize(),
    );
    let mut rays = Vec::new();
    for j in 0..96 {
        for i in 0..96 {
            let (x, y) = (f64::from(i) / 48.0 - 1.0, f64::from(j) / 48.0 - 1.0);
            rays.push(Ray::new((side * x + up * y) * 1.1 - d * 3.0, d).expect("valid"));
        }
    }
    for &v in &mesh.positions {
        rays.push(Ray::new(v - d * 3.0, d).expect("valid"));
    }
    let closest = bvh.closest_hits(&rays, 0.0, f64::INFINITY);
    let occluded = bvh.occluded_all(&rays, 0.0, 2.0);
    for (k, ray) in rays.iter().enumerate() {
        assert_eq!(
            closest[k],
            bvh.closest_hit(ray, 0.0, f64::INFINITY),
            "ray {k}"
        );
        assert_eq!(occluded[k], bvh.occluded(ray, 0.0, 2.0), "ray {k}");
    }
    let through_vertices = &closest[96 * 96..];
    let hits = through_vertices.iter().flatten().count();
    assert!(
        hits * 10 > through_vertices.len() * 9,
        "{hits} of {}",
        through_vertices.len()
    );
}
