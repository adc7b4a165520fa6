//! Watertightness, the fill rule and translation.

use glam::{DMat4, DVec3};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use shadowlab_raster::TargetSize;

use crate::support::{Mesh, Rng, coverage, jittered_grid, ndc, owners};

/// The seed of every property in this file.
const SEED: u64 = 0x7261_7374_6572; // "raster"

/// The grid, in pixels, of the vertices of the translation property: 2⁻¹⁶, so that on its
/// 128-pixel target every window and NDC coordinate, and its translation by whole pixels, is exact
/// in f64.
const TRANSLATION_GRID: f64 = 1.0 / 65_536.0;

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// Claim: a mesh covering more than the viewport, with shared edges at every angle and through
    /// pixel centres, and triangles of both windings, covers every pixel exactly once. Target sizes
    /// cross tile boundaries (64) and include partial tiles; cells range from large ones to ones a
    /// few pixels wide, whose tiny triangles the binning rasterizes early.
    #[test]
    fn jittered_grids_cover_every_pixel_once(seed in any::<u64>(), cells in prop_oneof![2usize..14, 60usize..140], size_index in 0usize..3) {
        let (w, h) = [(64, 64), (128, 64), (256, 128)][size_index];
        let mut rng = Rng::new(seed);
        let mesh = jittered_grid(&mut rng, cells, 1.25, w.max(h));
        // Non-square targets stretch the square grid; the coverage claim is unchanged.
        let size = TargetSize::new(w, h).unwrap();
        let counts = coverage(size, &mesh, &DMat4::IDENTITY);
        let bad: Vec<usize> = (0..counts.len()).filter(|&p| counts[p] != 1).collect();
        prop_assert!(bad.is_empty(), "{} pixels not covered once, first at {:?}: {}", bad.len(), bad.first().map(|p| (p % w as usize, p / w as usize)), counts[bad[0]]);
    }

    /// Claim: a fan around a vertex on a pixel centre, with spokes through pixel centres at every
    /// angle, covers every pixel exactly once.
    #[test]
    fn fans_cover_every_pixel_once(seed in any::<u64>(), spokes in 3usize..40) {
        let size = 64u32;
        let mut rng = Rng::new(seed);
        let mut mesh = Mesh::default();
        let centre = mesh.vertex(DVec3::new(ndc(rng.below(64) as f64 + 0.5, size), ndc(rng.below(64) as f64 + 0.5, size), 0.0));
        // Boundary points on pixel centres of a square ring far outside the viewport (4000 pixels, inside
        // the guard band), in angular order.
        let mut angles: Vec<f64> = (0..spokes).map(|_| rng.unit() * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        let ring: Vec<u32> = angles
            .iter()
            .map(|a| {
                let (s, c) = a.sin_cos();
                let r = 4000.0 / c.abs().max(s.abs());
                let x = (32.0 + r * c).floor() + 0.5;
                let y = (32.0 + r * s).floor() + 0.5;
                mesh.vertex(DVec3::new(ndc(x, size), ndc(y, size), 0.0))
            })
            .collect();
        for k in 0..ring.len() {
            mesh.triangles.push([centre, ring[k], ring[(k + 1) % ring.len()]]);
        }
        // With no angular gap above 0.9π the ring's polygon keeps every edge at least 4000·cos(0.45π) ≈
        // 626 pixels from the ring's centre, so it contains the viewport and the fan covers it.
        let gaps = angles.windows(2).map(|w| w[1] - w[0]).chain([angles[0] + std::f64::consts::TAU - angles[angles.len() - 1]]);
        prop_assume!(gaps.fold(0.0, f64::max) < std::f64::consts::PI * 0.9);
        let counts = coverage(TargetSize::new(size, size).unwrap(), &mesh, &DMat4::IDENTITY);
        prop_assert!(counts.iter().all(|&c| c == 1), "{:?}", counts.iter().enumerate().find(|(_, c)| **c != 1));
    }

    /// Claim: translating a mesh by whole pixels shifts its image exactly: coverage, triangle and
    /// depth bits. Vertices are put on a dyadic grid of [`TRANSLATION_GRID`] pixel, finer than the
    /// 1/256-pixel snapping grid, so their window coordinates (snapped and unsnapped, the latter
    /// being what depth is interpolated from) and the translated ones are exact. With cells of
    /// one to two pixels, tiny triangles move between the binning's early path (box in one tile)
    /// and the tile pass (box across a tile border), so this also checks that both paths give the
    /// same pixels and the same depth bits.
    #[test]
    fn whole_pixel_translation_shifts_the_image_exactly(seed in any::<u64>(), cells in prop_oneof![Just(9usize), 50usize..90], dx in -20i32..20, dy in -20i32..20) {
        use shadowlab_raster::{DepthFormat, EyeTarget, RasterOptions, Rasterizer};
        let size = 128u32;
        let mut rng = Rng::new(seed);
        let mut mesh = jittered_grid(&mut rng, cells, 0.75, size);
        let on_grid = |ndc_coordinate: f64| {
            let window = (ndc_coordinate + 1.0) * f64::from(size) / 2.0;
            ndc((window / TRANSLATION_GRID).round() * TRANSLATION_GRID, size)
        };
        for p in &mut mesh.positions {
            (p.x, p.y) = (on_grid(p.x), on_grid(p.y));
        }
        let mut moved = mesh.clone();
        let offset = DVec3::new(2.0 * f64::from(dx) / f64::from(size), 2.0 * f64::from(dy) / f64::from(size), 0.0);
        for p in &mut moved.positions {
            *p += offset;
        }
        let render = |m: &Mesh| {
            let mut target = EyeTarget::new(size, size, DepthFormat::F32).unwrap();
            Rasterizer::new(RasterOptions::default()).draw_eye(&mut target, m.triangles(), &DMat4::IDENTITY).unwrap();
            (target.depths(), target.triangles())
        };
        let ((d0, t0), (d1, t1)) = (render(&mesh), render(&moved));
        let s = i64::from(size);
        for y in 0..s {
            for x in 0..s {
                let (mx, my) = (x + i64::from(dx), y + i64::from(dy));
                if (0..s).contains(&mx) && (0..s).contains(&my) {
                    let index = |x: i64, y: i64| usize::try_from(y * s + x).expect("inside the target");
                    let (p, q) = (index(x, y), index(mx, my));
                    prop_assert_eq!(t0[p], t1[q], "triangle at ({}, {})", x, y);
                    prop_assert_eq!(d0[p].to_bits(), d1[q].to_bits(), "depth at ({}, {})", x, y);
                }
            }
        }
    }
}

/// A square of two triangles split along the diagonal through pixel centres: each centre on the
/// diagonal belongs to exactly one of them — the one for which the diagonal is a left edge.
#[test]
fn the_shared_diagonal_goes_to_the_triangle_it_is_a_left_edge_of() {
    let size = TargetSize::new(8, 8).unwrap();
    let mut mesh = Mesh::default();
    let [a, b, c, d] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| mesh.vertex(DVec3::new(x, y, 0.0)));
    mesh.triangles = vec![[a, b, c], [a, c, d]]; // lower right (0), upper left (1)
    let owner = owners(size, &mesh, &DMat4::IDENTITY);
    for i in 0..8 {
        // Counter-clockwise, the diagonal runs c → a (down-left) in triangle 0: a left edge.
        assert_eq!(owner[i * 8 + i], 0, "diagonal pixel {i}");
    }
    assert!(owner.iter().all(|&o| o != u32::MAX));
}

/// A horizontal edge through a row of centres belongs to the triangle above it (for which it is a
/// bottom edge); a vertical one to the triangle on its right (a left edge).
#[test]
fn horizontal_and_vertical_edges_through_centres() {
    let size = TargetSize::new(8, 8).unwrap();
    // Row 4's centres are at y = 4.5 (NDC 0.125); column 3's at x = 3.5 (NDC −0.125).
    let (y, x) = (ndc(4.5, 8), ndc(3.5, 8));
    let mut mesh = Mesh::default();
    let v = |mesh: &mut Mesh, x: f64, y: f64| mesh.vertex(DVec3::new(x, y, 0.0));
    let (p0, p1, p2) = (
        v(&mut mesh, -1.0, y),
        v(&mut mesh, 1.0, y),
        v(&mut mesh, 0.0, 1.0),
    );
    let (q0, q1, q2) = (
        v(&mut mesh, -1.0, y),
        v(&mut mesh, 0.0, -1.0),
        v(&mut mesh, 1.0, y),
    );
    mesh.triangles = vec![[p0, p1, p2], [q0, q1, q2]]; // above (0), below (1)
    let owner = owners(size, &mesh, &DMat4::IDENTITY);
    for i in 2..6 {
        assert_eq!(
            owner[4 * 8 + i],
            0,
            "row 4, column {i} belongs to the triangle above"
        );
    }
    let mut mesh = Mesh::default();
    let (l0, l1, l2) = (
        v(&mut mesh, x, -1.0),
        v(&mut mesh, x, 1.0),
        v(&mut mesh, -1.0, 0.0),
    );
    let (r0, r1, r2) = (
        v(&mut mesh, x, -1.0),
        v(&mut mesh, 1.0, 0.0),
        v(&mut mesh, x, 1.0),
    );
    mesh.triangles = vec![[l0, l1, l2], [r0, r1, r2]]; // left (0), right (1)
    let owner = owners(size, &mesh, &DMat4::IDENTITY);
    for j in 2..6 {
        assert_eq!(
            owner[j * 8 + 3],
            1,
            "column 3, row {j} belongs to the triangle on the right"
        );
    }
}

/// A triangle whose three edges all pass exactly through pixel centres, on its own: the centres on
/// its left and bottom edges are drawn, those on its right edge are not.
#[test]
fn a_lone_triangle_keeps_its_left_and_bottom_edges() {
    let size = TargetSize::new(16, 16).unwrap();
    let mut mesh = Mesh::default();
    // Window (2.5, 2.5), (12.5, 2.5), (2.5, 12.5): bottom, left and a diagonal right edge, all
    // through centres.
    let [a, b, c] = [(2.5, 2.5), (12.5, 2.5), (2.5, 12.5)]
        .map(|(x, y)| mesh.vertex(DVec3::new(ndc(x, 16), ndc(y, 16), 0.0)));
    mesh.triangles = vec![[a, b, c]];
    let counts = coverage(size, &mesh, &DMat4::IDENTITY);
    for j in 0..16usize {
        for i in 0..16usize {
            let expected = i >= 2 && j >= 2 && i + j < 14; // on the diagonal i + j = 14: excluded
            assert_eq!(counts[j * 16 + i] == 1, expected, "pixel ({i}, {j})");
        }
    }
}
