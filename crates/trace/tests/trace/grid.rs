//! Grids of parallel rays answered by the sweep ([`Bvh::closest_hits_grid`]), each with enough
//! rays per triangle to be swept: every answer is brute force's, bit for bit — on the agreement
//! test's meshes at 10⁻³ to 10⁶, with zero-area triangles, for grids whose rays pass exactly
//! through vertices and along edges, for rays whose directions differ by their rounding (each
//! `to − from`, as a shadow map's texel rays are made), and for grids the sweep does not take
//! (converging rays, a row out of order).

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_trace::{Bvh, Hit, Ray};

use crate::agreement::mesh;
use crate::support::{Rng, brute_closest, config, tessellated_cube, with_threads};

/// The grid's answers by the sweep.
fn swept(bvh: &Bvh, row_len: usize, rays: &[Ray], t_min: f64, t_max: f64) -> Vec<Option<Hit>> {
    let mut out = vec![None; rays.len()];
    bvh.closest_hits_grid(
        row_len,
        |j, row| row.copy_from_slice(&rays[j * row_len..(j + 1) * row_len]),
        t_min,
        t_max,
        &mut out,
        |_, hits, out| out.copy_from_slice(hits),
    )
    .expect("valid rays");
    out
}

/// Each swept answer is the batch query's (which the other tests hold to brute force), and, for
/// every 16th ray, brute force's.
fn check(
    bvh: &Bvh,
    row_len: usize,
    rays: &[Ray],
    ranges: &[(f64, f64)],
) -> Result<(), TestCaseError> {
    for &(t_min, t_max) in ranges {
        let answers = swept(bvh, row_len, rays, t_min, t_max);
        let batch = bvh.closest_hits(rays, t_min, t_max);
        for (k, ray) in rays.iter().enumerate() {
            prop_assert_eq!(
                answers[k],
                batch[k],
                "ray {} {:?} in ({}, {})",
                k,
                ray,
                t_min,
                t_max
            );
            if k % 16 == 0 {
                prop_assert_eq!(
                    answers[k],
                    brute_closest(bvh, ray, t_min, t_max),
                    "ray {}",
                    k
                );
            }
        }
    }
    Ok(())
}

/// A `cols × rows` grid of parallel rays along `d` over the box `lo..hi`, row by row, each ray
/// from a point behind the box to one beyond it (`direction = to − from`, rounded per ray).
fn grid(lo: DVec3, hi: DVec3, d: DVec3, cols: usize, rows: usize) -> Vec<Ray> {
    let centre = (lo + hi) * 0.5;
    let radius = (hi - lo).length().max(f64::MIN_POSITIVE);
    let along = d.any_orthonormal_vector();
    let across = d.cross(along).normalize();
    let mut rays = Vec::with_capacity(cols * rows);
    #[expect(clippy::cast_precision_loss, reason = "small grids")]
    for j in 0..rows {
        for i in 0..cols {
            let x = (i as f64 + 0.5) / cols as f64 * 2.0 - 1.0;
            let y = (j as f64 + 0.5) / rows as f64 * 2.0 - 1.0;
            let point = centre + (along * x + across * y) * radius;
            let (from, to) = (point - d * (2.0 * radius), point + d * (2.0 * radius));
            rays.push(Ray::new(from, to - from).expect("valid"));
        }
    }
    rays
}

fn bounds(positions: &[DVec3]) -> (DVec3, DVec3) {
    positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        })
}

proptest! {
    // Seed 0x7ACE_0C01: 32 meshes of the agreement test's five kinds (at most 128 triangles),
    // with zero-area triangles over some of them, at scales 10^-3..10^6, some far from the
    // origin; a 128 × 64 grid each, enough rays per triangle to be swept.
    #![proptest_config(config(0x7ACE_0C01, 32))]

    /// Parallel grids over random meshes: the sweep's answers are brute force's.
    #[test]
    fn a_grid_of_parallel_rays_equals_brute_force(
        kind in 0u8..5,
        seed in any::<u64>(),
        log_scale in -3.0..6.0_f64,
        shift in prop_oneof![Just(0.0), 0.0..1e3_f64],
    ) {
        let scale = 10f64.powf(log_scale);
        let mut rng = Rng::new(seed ^ 0x6A1D);
        let mut mesh = mesh(kind, seed, scale, shift);
        let count = mesh.triangles.len();
        for _ in 0..count.min(8) {
            let [a, b, _] = mesh.triangles[rng.index(count)];
            mesh.triangles.push([a, a, b]);
        }
        let bvh = mesh.bvh();
        let (lo, hi) = bounds(&mesh.positions);
        let rays = grid(lo, hi, rng.direction(), 128, 64);
        let (a, b) = (rng.range(0.0, 1.0), rng.range(0.0, 1.0));
        check(&bvh, 128, &rays, &[(0.0, 1.0), (a.min(b), a.max(b))])?;
    }
}

/// A tessellated cube (48 triangles) under grids of rays along an axis (and a hair off it), on a
/// lattice of 1/32 that holds its vertices and its edges' midpoints exactly, some rays a hair
/// beside them: the tie rule and watertightness decided by the same test as the tree's. The
/// same answers on 1, 2 and 8 threads.
#[test]
fn rays_through_vertices_and_along_edges_equal_brute_force() {
    let mesh = tessellated_cube(2);
    let bvh = mesh.bvh();
    let step = 1.0 / 32.0;
    let count = 67_u32;
    for d in [
        DVec3::NEG_Z,
        DVec3::new(1e-17, 0.0, -1.0),
        DVec3::new(0.0, 0.0, -3.0),
    ] {
        let mut rays = Vec::new();
        for j in 0..count {
            for i in 0..count {
                let (x, y) = (
                    f64::from(i) * step - 33.0 * step,
                    f64::from(j) * step - 33.0 * step,
                );
                let hair = if (i + j) % 5 == 0 { f64::EPSILON } else { 0.0 };
                rays.push(Ray::new(DVec3::new(x + hair, y, 2.0), d).expect("valid"));
            }
        }
        let expected: Vec<Option<Hit>> = rays
            .iter()
            .map(|ray| brute_closest(&bvh, ray, 0.0, f64::INFINITY))
            .collect();
        assert!(expected.iter().flatten().count() > rays.len() / 2);
        let row_len = count as usize;
        for threads in [1, 2, 8] {
            let answers = with_threads(threads, || swept(&bvh, row_len, &rays, 0.0, f64::INFINITY));
            assert_eq!(answers, expected, "{threads} threads, direction {d}");
        }
    }
}

/// Grids the sweep does not take — rays from one point, a row out of order — are cast through
/// the tree, with brute force's answers.
#[test]
fn grids_that_are_not_swept_equal_brute_force() {
    let mesh = mesh(2, 7, 1.0, 0.0);
    let bvh = mesh.bvh();
    let (lo, hi) = bounds(&mesh.positions);
    let eye = DVec3::new(3.0, 2.5, 4.0);
    let converging: Vec<Ray> = grid(lo, hi, DVec3::new(-0.3, -0.5, -1.0).normalize(), 20, 20)
        .iter()
        .map(|ray| Ray::new(eye, ray.origin + ray.direction * 0.5 - eye).expect("valid"))
        .collect();
    let mut reversed = grid(lo, hi, DVec3::new(0.2, -1.0, 0.1).normalize(), 20, 20);
    reversed[20..40].reverse();
    for rays in [converging, reversed] {
        let answers = swept(&bvh, 20, &rays, 0.0, f64::INFINITY);
        for (k, ray) in rays.iter().enumerate() {
            assert_eq!(
                answers[k],
                brute_closest(&bvh, ray, 0.0, f64::INFINITY),
                "ray {k}"
            );
        }
    }
}
