//! Procedural shapes: closed and outward where they should be, of the analytic volume and area,
//! bounded as documented, with their groups; bad parameters are named.

use std::f64::consts::{PI, TAU};

use glam::DVec3;
use shadowlab_scene::procedural::{
    BAR_LATTICE_GROUPS, CHESS_DARK, CHESS_FRAME, CHESS_LIGHT, MAX_TRIANGLES, bar_lattice,
    chess_board, cuboid, cylinder, plane, sphere,
};
use shadowlab_scene::{Mesh, ShapeError};

use crate::support::{assert_close, assert_unit_normals, first_open_edge};

/// Checks a closed convex shape: watertight and consistently wound, positive volume, every
/// triangle's winding agreeing with its corners' normals, and normals pointing away from the
/// centre.
pub(crate) fn assert_closed_convex(mesh: &Mesh, what: &str) {
    assert_eq!(first_open_edge(mesh), None, "{what}: open edge");
    assert!(
        mesh.signed_volume() > 0.0,
        "{what}: volume {}",
        mesh.signed_volume()
    );
    assert_unit_normals(mesh);
    let centre = mesh.bounds().centre();
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.triangle_positions(t);
        let face = (b - a).cross(c - a);
        for &i in &mesh.triangles()[t] {
            let n = mesh.normals()[i as usize];
            let p = mesh.positions()[i as usize];
            assert!(
                face.dot(n) > 0.0,
                "{what}: triangle {t} winds against normal {i}"
            );
            assert!(
                (p - centre).dot(n) > 0.0,
                "{what}: normal {i} points inward"
            );
        }
    }
}

#[test]
fn cuboid_is_exact() {
    let size = DVec3::new(1.0, 2.5, 4.0);
    let mesh = cuboid(size).unwrap();
    assert_closed_convex(&mesh, "cuboid");
    assert_eq!((mesh.triangle_count(), mesh.vertex_count()), (12, 24));
    assert_eq!(mesh.signed_volume(), 10.0);
    assert_eq!(mesh.surface_area(), 2.0 * (2.5 + 4.0 + 10.0));
    assert_eq!(mesh.bounds().min, -0.5 * size);
    assert_eq!(mesh.bounds().max, 0.5 * size);
    assert_eq!(mesh.group_names(), ["cuboid"]);
    // Face normals: each vertex's normal is its face's.
    for t in 0..12 {
        let [a, b, c] = mesh.triangle_positions(t);
        let face = (b - a).cross(c - a).normalize();
        assert!(
            mesh.triangles()[t]
                .iter()
                .all(|&i| mesh.normals()[i as usize] == face)
        );
    }
}

#[test]
fn sphere_approaches_the_round_sphere() {
    for (segments, rings) in [(3, 2), (8, 4), (64, 32)] {
        let radius = 2.5;
        let mesh = sphere(radius, segments, rings).unwrap();
        let what = format!("sphere {segments}×{rings}");
        assert_closed_convex(&mesh, &what);
        assert_eq!(
            mesh.triangle_count(),
            2 * segments as usize * (rings as usize - 1)
        );
        assert_eq!(
            mesh.vertex_count(),
            segments as usize * (rings as usize - 1) + 2
        );
        for (p, n) in mesh.positions().iter().zip(mesh.normals()) {
            assert_close(p.length(), radius, 1e-15, "vertex on the sphere");
            assert!((*p / radius - *n).length() < 1e-15, "{what}: radial normal");
        }
        assert_eq!(mesh.bounds().max.y, radius);
        assert_eq!(mesh.bounds().min.y, -radius);
    }
    // An inscribed polyhedron: volume and area below the sphere's, within the chordal error. With
    // 64 × 32 the edges subtend at most π/32, so the deficit is at most ~3(1 − cos(π/32)) ≈ 1.4 %.
    let mesh = sphere(1.0, 64, 32).unwrap();
    let (volume, area) = (4.0 / 3.0 * PI, 4.0 * PI);
    assert!(mesh.signed_volume() < volume && mesh.surface_area() < area);
    assert_close(
        mesh.signed_volume(),
        volume,
        3.0 * (1.0 - (PI / 32.0).cos()),
        "volume",
    );
    assert_close(
        mesh.surface_area(),
        area,
        3.0 * (1.0 - (PI / 32.0).cos()),
        "area",
    );
}

#[test]
fn cylinder_has_the_prism_volume() {
    for segments in [3, 7, 100] {
        let (radius, height) = (1.5, 4.0);
        let mesh = cylinder(radius, height, segments).unwrap();
        let what = format!("cylinder {segments}");
        assert_closed_convex(&mesh, &what);
        assert_eq!(mesh.triangle_count(), 4 * segments as usize);
        let n = f64::from(segments);
        let polygon = n / 2.0 * radius * radius * (TAU / n).sin();
        assert_close(mesh.signed_volume(), polygon * height, 1e-13, &what);
        let side = n * 2.0 * radius * (PI / n).sin() * height;
        assert_close(mesh.surface_area(), 2.0 * polygon + side, 1e-13, &what);
        assert_eq!(mesh.bounds().max.y, 2.0);
        assert_eq!(mesh.bounds().min.y, -2.0);
        assert_eq!(mesh.bounds().max.x, radius);
    }
}

#[test]
fn plane_is_flat_and_faces_up() {
    let mesh = plane(4.0, 6.0, 3).unwrap();
    assert_eq!((mesh.triangle_count(), mesh.vertex_count()), (18, 16));
    assert!(mesh.normals().iter().all(|&n| n == DVec3::Y));
    assert_close(mesh.surface_area(), 24.0, 1e-15, "plane area");
    assert_eq!(mesh.bounds().min, DVec3::new(-2.0, 0.0, -3.0));
    assert_eq!(mesh.bounds().max, DVec3::new(2.0, 0.0, 3.0));
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.triangle_positions(t);
        assert!((b - a).cross(c - a).y > 0.0, "triangle {t} faces down");
    }
    // Open: its boundary edges are traversed once only.
    assert!(first_open_edge(&mesh).is_some());
}

#[test]
fn chess_board_squares_alternate() {
    let square = 0.5;
    for frame in [0.0, 0.25] {
        let mesh = chess_board(square, frame).unwrap();
        let framed = frame > 0.0;
        assert_eq!(mesh.triangle_count(), if framed { 200 } else { 128 });
        assert_eq!(mesh.vertex_count(), if framed { 121 } else { 81 });
        assert!(mesh.normals().iter().all(|&n| n == DVec3::Y));
        let half = 4.0 * square + frame;
        assert_eq!(mesh.bounds().min, DVec3::new(-half, 0.0, -half));
        assert_eq!(mesh.bounds().max, DVec3::new(half, 0.0, half));
        assert_close(mesh.surface_area(), 4.0 * half * half, 1e-15, "board area");
        let mut areas = [0.0; 3];
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle_positions(t);
            let face = (b - a).cross(c - a);
            assert!(face.y > 0.0, "triangle {t} faces down");
            areas[mesh.groups()[t] as usize] += 0.5 * face.length();
            // Every square's group follows the parity of its file i and rank j (a1 = (0, 0) dark).
            let centre = (a + b + c) / 3.0;
            if centre.x.abs() < 4.0 * square && centre.z.abs() < 4.0 * square {
                let i = ((centre.x + 4.0 * square) / square).floor();
                let j = ((4.0 * square - centre.z) / square).floor();
                let expected = if (i + j) % 2.0 == 0.0 {
                    CHESS_DARK
                } else {
                    CHESS_LIGHT
                };
                assert_eq!(mesh.groups()[t], expected, "square ({i}, {j})");
            } else {
                assert_eq!(mesh.groups()[t], CHESS_FRAME);
            }
        }
        assert_eq!(areas[0], 32.0 * square * square);
        assert_eq!(areas[1], 32.0 * square * square);
        let names: &[&str] = if framed {
            &["dark", "light", "frame"]
        } else {
            &["dark", "light"]
        };
        assert_eq!(mesh.group_names(), names);
    }
}

/// Checks that each bar of a lattice (12 consecutive triangles) is closed and outward on its own.
pub(crate) fn assert_bars_closed(lattice: &Mesh, what: &str) {
    assert_eq!(lattice.triangle_count() % 12, 0, "{what}");
    for (bar, triangles) in lattice.triangles().chunks(12).enumerate() {
        let start = u32::try_from(bar * 24).expect("small");
        let local = triangles.iter().map(|t| t.map(|i| i - start)).collect();
        let positions = lattice.positions()[bar * 24..(bar + 1) * 24].to_vec();
        let normals = lattice.normals()[bar * 24..(bar + 1) * 24].to_vec();
        let single = Mesh::with_normals(positions, normals, local).expect("a bar");
        assert_closed_convex(&single, &format!("{what}, bar {bar}"));
    }
}

#[test]
fn bar_lattice_is_a_set_of_closed_bars() {
    let (spacing, thickness) = (1.0, 0.05);
    for cells in [[2, 3, 1], [4, 0, 4], [1, 0, 0]] {
        let mesh = bar_lattice(cells, spacing, thickness).unwrap();
        let what = format!("lattice {cells:?}");
        let nodes = cells.map(|c| f64::from(c) + 1.0);
        let lengths = cells.map(|c| f64::from(c) * spacing + thickness);
        let mut bars = 0.0;
        let mut volume = 0.0;
        for a in 0..3 {
            if cells[a] > 0 {
                let count = nodes[(a + 1) % 3] * nodes[(a + 2) % 3];
                bars += count;
                volume += count * lengths[a] * thickness * thickness;
            }
        }
        assert_eq!(mesh.triangle_count() as f64, 12.0 * bars, "{what}");
        assert_bars_closed(&mesh, &what);
        assert_unit_normals(&mesh);
        // Overlaps at the nodes are counted once per bar: the sum of the bars' volumes.
        assert_close(mesh.signed_volume(), volume, 1e-12, &what);
        let half =
            (DVec3::from_array(cells.map(f64::from)) * spacing + DVec3::splat(thickness)) / 2.0;
        assert_eq!(mesh.bounds().max, half, "{what}");
        assert_eq!(mesh.bounds().min, -half, "{what}");
        assert_eq!(mesh.group_names(), BAR_LATTICE_GROUPS);
        for (t, &g) in mesh.groups().iter().enumerate() {
            // A bar along axis g is long along g.
            let [p, q, r] = mesh.triangle_positions(t);
            let extent = p.max(q).max(r) - p.min(q).min(r);
            assert!(
                extent
                    .to_array()
                    .iter()
                    .enumerate()
                    .all(|(a, &e)| a == g as usize || e <= thickness * (1.0 + 1e-9))
            );
        }
    }
}

#[test]
fn bad_parameters_are_named() {
    let parameter = |result: Result<Mesh, ShapeError>| match result {
        Err(ShapeError::InvalidParameter { parameter, .. }) => parameter,
        other => panic!("expected InvalidParameter, got {other:?}"),
    };
    assert_eq!(parameter(plane(0.0, 1.0, 1)), "size_x");
    assert_eq!(parameter(plane(1.0, f64::NAN, 1)), "size_z");
    assert_eq!(parameter(plane(1.0, 1.0, 0)), "segments");
    assert_eq!(parameter(cuboid(DVec3::new(1.0, -1.0, 1.0))), "size.y");
    assert_eq!(
        parameter(cuboid(DVec3::new(1.0, 1.0, f64::INFINITY))),
        "size.z"
    );
    assert_eq!(parameter(sphere(-1.0, 8, 4)), "radius");
    assert_eq!(parameter(sphere(1.0, 2, 4)), "segments");
    assert_eq!(parameter(sphere(1.0, 8, 1)), "rings");
    assert_eq!(parameter(cylinder(1.0, 0.0, 8)), "height");
    assert_eq!(parameter(cylinder(1.0, 1.0, 2)), "segments");
    assert_eq!(parameter(bar_lattice([1, 1, 1], 0.0, 0.1)), "spacing");
    assert_eq!(parameter(bar_lattice([1, 1, 1], 1.0, 1.0)), "thickness");
    assert_eq!(parameter(bar_lattice([1, 1, 1], 1.0, -0.1)), "thickness");
    assert_eq!(parameter(bar_lattice([0, 0, 0], 1.0, 0.1)), "cells");
    assert_eq!(parameter(chess_board(f64::NAN, 0.0)), "square_size");
    assert_eq!(parameter(chess_board(1.0, -0.5)), "frame_width");
    let message = sphere(1.0, 2, 4).unwrap_err().to_string();
    assert_eq!(message, "`segments` must be at least 3, got 2");
    // Too large: refused before anything is allocated.
    for (result, shape) in [
        (plane(1.0, 1.0, u32::MAX), "plane"),
        (sphere(1.0, u32::MAX, u32::MAX), "sphere"),
        (cylinder(1.0, 1.0, u32::MAX), "cylinder"),
        (bar_lattice([1000; 3], 1.0, 0.1), "bar_lattice"),
    ] {
        match result {
            Err(ShapeError::TooManyTriangles {
                shape: s,
                count,
                max,
            }) => {
                assert_eq!((s, max), (shape, MAX_TRIANGLES));
                assert!(count > u128::from(max));
            }
            other => panic!("{shape}: {other:?}"),
        }
    }
}
