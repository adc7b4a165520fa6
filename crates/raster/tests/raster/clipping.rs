//! Clipping against an exact per-pixel reference.
//!
//! Each case is built so that its clipped vertices land exactly on the 1/256-pixel grid (cut
//! parameters of 1/2 between dyadic points), so the exact clipped polygon is the one the rasterizer
//! draws. The reference tests every pixel centre against that polygon in i128 with the fill rule on
//! its boundary edges: covered if every edge function is > 0, or = 0 on a left or bottom edge.

use glam::{DMat4, DVec3, DVec4};
use shadowlab_raster::TargetSize;

use crate::support::{Mesh, owners};

/// The target side of every case.
const SIZE: u32 = 32;

/// GL clip-space polygon clipping against near (z ≥ −w) and far (z ≤ w) in exact rationals: points
/// are dyadic here, so f64 arithmetic on them is exact, which the function asserts.
fn clip_exact(polygon: &[DVec4]) -> Vec<DVec4> {
    let mut poly = polygon.to_vec();
    for plane in [|c: DVec4| c.z + c.w, |c: DVec4| c.w - c.z] {
        let mut out = Vec::new();
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (plane(a), plane(b));
            if da >= 0.0 {
                out.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                assert!(
                    t * 1024.0 == (t * 1024.0).round(),
                    "cut parameter {t} is not dyadic"
                );
                out.push(a + (b - a) * t);
            }
        }
        poly = out;
    }
    poly
}

/// Window coordinates of a clip point in units of 1/256 pixel, asserting they are on the grid.
fn grid(c: DVec4) -> (i128, i128) {
    let to = |v: f64| {
        let w = (v / c.w) * f64::from(SIZE) / 2.0 + f64::from(SIZE) / 2.0;
        let g = w * 256.0;
        assert_eq!(g, g.round(), "window coordinate {w} is not on the grid");
        #[expect(
            clippy::cast_possible_truncation,
            reason = "an integer below 2^24, asserted above"
        )]
        let exact = g as i128;
        exact
    };
    (to(c.x), to(c.y))
}

/// Exact coverage of the convex polygon (any winding) at every pixel centre.
fn reference(polygon: &[(i128, i128)]) -> Vec<bool> {
    let n = polygon.len();
    let area: i128 = (0..n)
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let ccw: Vec<(i128, i128)> = if area > 0 {
        polygon.to_vec()
    } else {
        polygon.iter().rev().copied().collect()
    };
    let size = SIZE as usize;
    let mut out = vec![false; size * size];
    for j in 0..size {
        for i in 0..size {
            let (px, py) = (i as i128 * 256 + 128, j as i128 * 256 + 128);
            out[j * size + i] = (0..n).all(|k| {
                let (a, b) = (ccw[k], ccw[(k + 1) % n]);
                let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                let e = dx * (py - a.1) - dy * (px - a.0);
                e > 0 || (e == 0 && (dy < 0 || (dy == 0 && dx > 0)))
            });
        }
    }
    out
}

/// Draws one clip-space triangle: its vertices are the unit points e_x, e_y, e_z and the matrix's
/// columns are the wanted clip points (the fourth column zero), so `M·(e_k, 1) = clip_k` exactly,
/// whatever the signs of w.
fn draw(clip: [DVec4; 3]) -> Vec<bool> {
    let basis = [DVec3::X, DVec3::Y, DVec3::Z];
    let m = DMat4::from_cols(clip[0], clip[1], clip[2], DVec4::ZERO);
    let mut mesh = Mesh::default();
    let v: Vec<u32> = basis.iter().map(|&p| mesh.vertex(p)).collect();
    mesh.triangles = vec![[v[0], v[1], v[2]]];
    let size = TargetSize::new(SIZE, SIZE).unwrap();
    owners(size, &mesh, &m)
        .into_iter()
        .map(|o| o != u32::MAX)
        .collect()
}

fn check(clip: [DVec4; 3]) {
    let polygon = clip_exact(&clip);
    let expected = if polygon.len() >= 3 {
        reference(&polygon.iter().map(|&c| grid(c)).collect::<Vec<_>>())
    } else {
        vec![false; (SIZE * SIZE) as usize]
    };
    let actual = draw(clip);
    let differ: Vec<(usize, usize)> = (0..expected.len())
        .filter(|&p| expected[p] != actual[p])
        .map(|p| (p % SIZE as usize, p / SIZE as usize))
        .collect();
    assert!(
        differ.is_empty(),
        "{} pixels differ from the reference, e.g. {:?}",
        differ.len(),
        &differ[..differ.len().min(8)]
    );
    assert!(expected.iter().any(|&c| c), "the case covers something");
}

#[test]
fn a_triangle_crossing_the_near_plane() {
    // A is in front of the near plane (z + w = −1), B and C behind it (z + w = 1): cuts at t = 1/2.
    check([
        DVec4::new(-0.5, -0.75, -2.0, 1.0),
        DVec4::new(0.75, -0.25, 0.0, 1.0),
        DVec4::new(-0.25, 0.875, 0.0, 1.0),
    ]);
}

#[test]
fn a_triangle_with_a_vertex_behind_the_eye() {
    // A has w = −1 (behind the eye), B and C w = 3, z chosen so that z + w is −2 and 2: cuts at
    // the midpoints, where w = 1.
    check([
        DVec4::new(0.5, -1.5, -1.0, -1.0),
        DVec4::new(-1.5, 0.75, -1.0, 3.0),
        DVec4::new(1.5, 2.25, -1.0, 3.0),
    ]);
}

#[test]
fn a_triangle_crossing_the_far_plane() {
    // w − z is −1 at A and 1 at B and C.
    check([
        DVec4::new(0.25, 0.5, 2.0, 1.0),
        DVec4::new(-0.75, -0.5, 0.0, 1.0),
        DVec4::new(0.625, -0.875, 0.0, 1.0),
    ]);
}

#[test]
fn an_enormous_triangle_covers_every_pixel_once() {
    // Vertices a million viewports away are clipped to the guard band; every pixel of the
    // viewport lies deep inside, so each is covered exactly once.
    let m = DMat4::IDENTITY;
    let mut mesh = Mesh::default();
    let a = mesh.vertex(DVec3::new(-1e6, -1e6, 0.0));
    let b = mesh.vertex(DVec3::new(1e6, -1e6, 0.5));
    let c = mesh.vertex(DVec3::new(0.0, 1e6, -0.5));
    mesh.triangles = vec![[a, b, c]];
    let size = TargetSize::new(SIZE, SIZE).unwrap();
    let counts = crate::support::coverage(size, &mesh, &m);
    assert!(counts.iter().all(|&c| c == 1));
}

#[test]
fn triangles_entirely_behind_or_beyond_are_not_drawn() {
    for clip in [
        [
            DVec4::new(0.0, 0.0, -2.0, 1.0),
            DVec4::new(0.5, 0.0, -3.0, 1.0),
            DVec4::new(0.0, 0.5, -1.5, 1.0),
        ],
        [
            DVec4::new(0.0, 0.0, 2.0, 1.0),
            DVec4::new(0.5, 0.0, 3.0, 1.0),
            DVec4::new(0.0, 0.5, 1.5, 1.0),
        ],
        [
            DVec4::new(0.0, 0.0, 0.5, -1.0),
            DVec4::new(0.5, 0.0, 0.5, -1.0),
            DVec4::new(0.0, 0.5, 0.5, -2.0),
        ],
    ] {
        assert!(draw(clip).iter().all(|&c| !c), "{clip:?}");
    }
}
