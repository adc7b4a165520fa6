//! Depth: monotone, exact at vertices, every storage format, the depth pair, the eye resolve.

use glam::{DMat4, DVec3};
use shadowlab_raster::{
    DepthCompare, DepthFormat, DepthPairTarget, DepthTarget, EyeTarget, NO_TRIANGLE, RasterOptions,
    Rasterizer,
};

use crate::support::{Mesh, ndc};

/// A quad over the whole viewport whose NDC depth runs from −0.75 at the left to 0.75 at the right.
fn slope() -> Mesh {
    let mut mesh = Mesh::default();
    let [a, b, c, d] = [
        (-1.0, -1.0, -0.75),
        (1.0, -1.0, 0.75),
        (1.0, 1.0, 0.75),
        (-1.0, 1.0, -0.75),
    ]
    .map(|(x, y, z)| mesh.vertex(DVec3::new(x, y, z)));
    mesh.triangles = vec![[a, b, c], [a, c, d]];
    mesh
}

#[test]
fn depth_is_monotone_and_follows_the_plane_in_every_format() {
    let size = 64u32;
    for format in DepthFormat::ALL {
        let mut target = DepthTarget::new(size, size, format).unwrap();
        Rasterizer::new(RasterOptions::default())
            .draw_depth(&mut target, slope().triangles(), &DMat4::IDENTITY)
            .unwrap();
        let depths = target.depths();
        let quantum = match format {
            DepthFormat::F32 | DepthFormat::ReversedF32 => 1e-7,
            DepthFormat::Unorm24 => 0.5 / 16_777_215.0 + 1e-12,
            DepthFormat::Unorm16 => 0.5 / 65_535.0 + 1e-12,
        };
        for j in 0..size as usize {
            for i in 0..size as usize {
                let z = depths[j * size as usize + i];
                // Window depth (z_ndc + 1)/2 with z_ndc linear in x.
                let expected = (0.75 * ndc(i as f64 + 0.5, size) + 1.0) / 2.0;
                assert!(
                    (z - expected).abs() <= quantum,
                    "{format:?} ({i}, {j}): {z} vs {expected}"
                );
                if i > 0 {
                    assert!(
                        z >= depths[j * size as usize + i - 1],
                        "{format:?}: not monotone at ({i}, {j})"
                    );
                }
            }
        }
    }
}

/// A vertex on a pixel centre, shared by a fan of triangles with different slopes: the one
/// triangle that covers that centre stores exactly the vertex's depth.
#[test]
fn depth_is_exact_at_vertices() {
    let size = 32u32;
    for (column, row) in [(10usize, 7usize), (3, 20), (25, 25)] {
        let (vx, vy) = (column as f64 + 0.5, row as f64 + 0.5);
        for z_window in [0.25, 0.5, 0.6875, 0.9990234375] {
            let mut mesh = Mesh::default();
            let z_ndc = z_window * 2.0 - 1.0;
            let centre = mesh.vertex(DVec3::new(ndc(vx, size), ndc(vy, size), z_ndc));
            let ring: Vec<u32> = [
                (-1.0, -1.0, 0.3),
                (1.0, -1.0, -0.9),
                (1.0, 1.0, 0.8),
                (-1.0, 1.0, -0.1),
            ]
            .iter()
            .map(|&(x, y, z)| mesh.vertex(DVec3::new(x, y, z)))
            .collect();
            for k in 0..4 {
                mesh.triangles.push([centre, ring[k], ring[(k + 1) % 4]]);
            }
            let mut target = DepthTarget::new(size, size, DepthFormat::F32).unwrap();
            let options = RasterOptions {
                compare: DepthCompare::Always,
                ..RasterOptions::default()
            };
            let stats = Rasterizer::new(options)
                .draw_depth(&mut target, mesh.triangles(), &DMat4::IDENTITY)
                .unwrap();
            assert_eq!(
                stats.fragments,
                u64::from(size * size),
                "the fan covers each pixel once"
            );
            let at = row * size as usize + column;
            assert_eq!(
                target.depths()[at],
                z_window,
                "vertex ({vx}, {vy}) at depth {z_window}"
            );
        }
    }
}

#[test]
fn the_depth_test_keeps_the_nearest_surface_and_compare_functions_work() {
    let size = 16u32;
    let mut mesh = Mesh::default();
    for z in [0.5, -0.5, 0.25] {
        let [a, b, c] =
            [(-1.0, -1.0), (3.0, -1.0), (-1.0, 3.0)].map(|(x, y)| mesh.vertex(DVec3::new(x, y, z)));
        mesh.triangles.push([a, b, c]);
    }
    let cases = [
        (DepthCompare::Less, 0.25),    // window depth of z_ndc −0.5
        (DepthCompare::Greater, 0.75), // cleared to 0 below, the farthest wins
        (DepthCompare::Always, 0.625), // the last triangle wins
        (DepthCompare::Never, 1.0),
    ];
    for (compare, expected) in cases {
        let mut target = DepthTarget::new(size, size, DepthFormat::F32).unwrap();
        if compare == DepthCompare::Greater {
            target.clear(0.0);
        }
        Rasterizer::new(RasterOptions {
            compare,
            ..RasterOptions::default()
        })
        .draw_depth(&mut target, mesh.triangles(), &DMat4::IDENTITY)
        .unwrap();
        assert!(
            target.depths().iter().all(|&z| z == expected),
            "{compare:?}: {}",
            target.depths()[0]
        );
    }
}

#[test]
fn the_depth_pair_keeps_the_two_nearest() {
    let size = 8u32;
    let mut mesh = Mesh::default();
    for z in [0.5, -0.5, 0.0, 0.75] {
        let [a, b, c] =
            [(-1.0, -1.0), (3.0, -1.0), (-1.0, 3.0)].map(|(x, y)| mesh.vertex(DVec3::new(x, y, z)));
        mesh.triangles.push([a, b, c]);
    }
    let mut target = DepthPairTarget::new(size, size, DepthFormat::F32).unwrap();
    Rasterizer::new(RasterOptions::default())
        .draw_depth_pair(&mut target, mesh.triangles(), &DMat4::IDENTITY)
        .unwrap();
    assert!(target.nearest().iter().all(|&z| z == 0.25));
    assert!(target.second().iter().all(|&z| z == 0.5));
    let mut single = DepthPairTarget::new(size, size, DepthFormat::Unorm16).unwrap();
    mesh.triangles.truncate(1);
    Rasterizer::new(RasterOptions::default())
        .draw_depth_pair(&mut single, mesh.triangles(), &DMat4::IDENTITY)
        .unwrap();
    assert!(
        single.second().iter().all(|&z| z == 1.0),
        "one surface: the second depth stays far"
    );
}

/// The resolve recovers world positions and normals perspective-correctly: a plane seen in
/// perspective, resolved at every pixel, lies on the plane at the point its pixel centre looks at.
#[test]
fn the_eye_resolve_is_perspective_correct() {
    let (w, h) = (48u32, 32u32);
    let view = glam::dcamera::rh::view::look_at_mat4(
        DVec3::new(0.3, 2.0, 3.0),
        DVec3::new(0.0, 0.0, -2.0),
        DVec3::Y,
    );
    let projection =
        glam::dcamera::rh::proj::opengl::perspective(1.0, f64::from(w) / f64::from(h), 0.5, 50.0);
    let m = projection * view;
    // The ground plane y = 0, a big quad, with normals tilted differently at each corner.
    let positions = vec![
        DVec3::new(-20.0, 0.0, 5.0),
        DVec3::new(20.0, 0.0, 5.0),
        DVec3::new(20.0, 0.0, -40.0),
        DVec3::new(-20.0, 0.0, -40.0),
    ];
    let normals = vec![DVec3::Y; 4];
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    let mesh = shadowlab_raster::Triangles::new(&positions, &triangles);
    let mut target = EyeTarget::new(w, h, DepthFormat::F32).unwrap();
    Rasterizer::new(RasterOptions::default())
        .draw_eye(&mut target, mesh, &m)
        .unwrap();
    let image = target.resolve(mesh, &normals, &m).unwrap();
    let inverse = m.inverse();
    // Where the centre of pixel (x, y) (in pixels, possibly fractional) sees the plane y = 0, and
    // that point's window depth.
    let on_plane = |x: f64, y: f64| {
        let (nx, ny) = (x / f64::from(w) * 2.0 - 1.0, y / f64::from(h) * 2.0 - 1.0);
        let near = inverse.project_point3(DVec3::new(nx, ny, -1.0));
        let far = inverse.project_point3(DVec3::new(nx, ny, 1.0));
        let hit = near + (far - near) * ((0.0 - near.y) / (far.y - near.y));
        let clip = m * hit.extend(1.0);
        (hit, (clip.z / clip.w + 1.0) / 2.0)
    };
    let mut seen = 0;
    for j in 0..h as usize {
        for i in 0..w as usize {
            let p = j * w as usize + i;
            if image.triangle[p] == NO_TRIANGLE {
                continue;
            }
            seen += 1;
            let q = image.position[p];
            assert!(q.y.abs() < 1e-9, "on the plane: {q}");
            assert!((image.normal[p] - DVec3::Y).length() < 1e-12);
            // The resolve is exact: the pixel centre's ray passes through q.
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            let (hit, z) = on_plane(x, y);
            assert!(
                (hit - q).length() < 1e-9 * (1.0 + hit.length()),
                "pixel ({i}, {j}): {q} vs {hit}"
            );
            // The stored depth is the plane's depth (through the unsnapped vertices) rounded to
            // f32: off by at most half an f32 ulp below 1, 2⁻²⁵, and the reference's rounding.
            assert!(
                (image.depth[p] - z).abs() <= f64::from(f32::EPSILON) / 2.0,
                "depth at ({i}, {j}): {} vs {z}",
                image.depth[p]
            );
        }
    }
    assert!(seen > 300, "the plane fills part of the view: {seen}");
    let bad = target.resolve(mesh, &normals[..3], &m);
    assert!(bad.is_err());
}

/// A small triangle at NDC depth 0 (window depth 0.5) over the lower-left part of the viewport.
fn small_triangle() -> Mesh {
    let mut mesh = Mesh::default();
    let [a, b, c] =
        [(-1.0, -1.0), (0.0, -1.0), (-1.0, 0.0)].map(|(x, y)| mesh.vertex(DVec3::new(x, y, 0.0)));
    mesh.triangles = vec![[a, b, c]];
    mesh
}

/// Claim: a target reads as its clear value before any draw, keeps it where nothing is drawn, and a
/// clear between draws forgets the first draw entirely — for all three targets.
#[test]
fn clears_hold_before_between_and_after_draws() {
    let size = 128u32;
    let pixels = (size * size) as usize;
    let mut raster = Rasterizer::new(RasterOptions::default());
    let (triangle, nothing) = (small_triangle(), Mesh::default());
    let covered = |depths: &[f64]| depths.iter().filter(|&&z| z == 0.5).count();

    let mut target = DepthTarget::new(size, size, DepthFormat::F32).unwrap();
    assert_eq!(target.depths(), vec![1.0; pixels]);
    target.clear(0.75);
    assert_eq!(target.depths(), vec![0.75; pixels]);
    let drawn = raster
        .draw_depth(&mut target, triangle.triangles(), &DMat4::IDENTITY)
        .unwrap()
        .fragments;
    let depths = target.depths();
    assert_eq!(covered(&depths) as u64, drawn);
    assert!(drawn > 0);
    assert!(depths.iter().all(|&z| z == 0.5 || z == 0.75));
    target.clear(0.25);
    raster
        .draw_depth(&mut target, nothing.triangles(), &DMat4::IDENTITY)
        .unwrap();
    assert_eq!(target.depths(), vec![0.25; pixels]);

    let mut pair = DepthPairTarget::new(size, size, DepthFormat::F32).unwrap();
    for _ in 0..2 {
        raster
            .draw_depth_pair(&mut pair, triangle.triangles(), &DMat4::IDENTITY)
            .unwrap();
    }
    // Drawn twice: the second draw's fragments are second-nearest (equal depth, not nearer).
    assert_eq!(covered(&pair.nearest()) as u64, drawn);
    assert_eq!(covered(&pair.second()) as u64, drawn);
    pair.clear();
    assert_eq!(pair.nearest(), vec![1.0; pixels]);
    assert_eq!(pair.second(), vec![1.0; pixels]);

    let mut eye = EyeTarget::new(size, size, DepthFormat::F32).unwrap();
    raster
        .draw_eye(&mut eye, triangle.triangles(), &DMat4::IDENTITY)
        .unwrap();
    assert_eq!(
        eye.triangles().iter().filter(|&&t| t == 0).count() as u64,
        drawn
    );
    eye.clear();
    assert_eq!(eye.triangles(), vec![NO_TRIANGLE; pixels]);
    raster
        .draw_eye(&mut eye, nothing.triangles(), &DMat4::IDENTITY)
        .unwrap();
    assert_eq!(eye.depths(), vec![1.0; pixels]);
    assert_eq!(eye.triangles(), vec![NO_TRIANGLE; pixels]);
}
