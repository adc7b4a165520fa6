//! Determinism: the same tree, and the same bits from every query, for 1, 2 and 8 threads and
//! across builds.

use glam::DVec3;
use shadowlab_trace::{Bvh, Ray};

use crate::support::{Mesh, Rng, soup, uv_sphere, with_threads};

/// 9 000 soup triangles around a 9 920-triangle sphere: large enough that the build splits its
/// upper nodes in parallel (from 1 024 triangles on).
fn scene() -> Mesh {
    let mut rng = Rng::new(0x7ACE_0E01);
    let mut mesh = soup(9000, &mut rng).map(|p| p * 3.0);
    let sphere = uv_sphere(40, 128, 1.0);
    let base = u32::try_from(mesh.positions.len()).expect("small");
    mesh.positions.extend(&sphere.positions);
    mesh.triangles
        .extend(sphere.triangles.iter().map(|t| t.map(|v| v + base)));
    mesh
}

/// 8 192 rays: from outside toward the scene, and from inside the sphere.
fn rays() -> Vec<Ray> {
    let mut rng = Rng::new(0x7ACE_0E02);
    (0..8192)
        .map(|k| {
            let origin = if k % 2 == 0 {
                rng.direction() * 8.0
            } else {
                rng.cube_point() * 0.5
            };
            let target = rng.cube_point() * 3.0;
            Ray::new(origin, target - origin).expect("valid")
        })
        .collect()
}

#[test]
fn identical_for_any_thread_count() {
    let mesh = scene();
    let rays = rays();
    let run = |threads: usize| {
        with_threads(threads, || {
            let bvh = Bvh::new(&mesh.positions, &mesh.triangles).expect("valid");
            let closest = bvh.closest_hits(&rays, 0.0, f64::INFINITY);
            let blocked = bvh.occluded_all(&rays, 0.0, 1.0);
            (bvh, closest, blocked)
        })
    };
    let (bvh, closest, blocked) = run(1);
    let hits = closest.iter().flatten().count();
    assert!(hits > 4096, "{hits} of {} rays hit", rays.len());
    assert!(blocked.iter().any(|&b| b) && !blocked.iter().all(|&b| b));
    for threads in [2, 8, 1] {
        let (other, other_closest, other_blocked) = run(threads);
        assert!(other == bvh, "the tree differs with {threads} threads");
        assert_eq!(other_closest, closest, "{threads} threads");
        assert_eq!(other_blocked, blocked, "{threads} threads");
    }
    // The batch results are the single queries' results.
    for (k, ray) in rays.iter().enumerate().step_by(97) {
        assert_eq!(bvh.closest_hit(ray, 0.0, f64::INFINITY), closest[k]);
        assert_eq!(bvh.occluded(ray, 0.0, 1.0), blocked[k]);
    }
    // A tree built from a translated copy differs, so the comparison above is not vacuous.
    let moved = mesh.clone().map(|p| p + DVec3::X);
    assert!(moved.bvh() != bvh);
}
