//! Depth against the exact plane: at every covered pixel centre, the depth the rasterizer gives
//! (before and after each storage format) is compared with an evaluation that shares nothing with
//! it — the pixel centre's ray intersected with the plane through the triangle's three clip-space
//! vertices, with no window coordinates and no snapping.

use glam::{DMat4, DVec3, DVec4};
use shadowlab_raster::{
    DepthFormat, EyeTarget, Fragment, NO_TRIANGLE, RasterOptions, Rasterizer, TargetSize, Triangles,
};

use crate::support::{Mesh, Rng};

/// The largest difference allowed between the f64 depth of a fragment and the exact depth:
/// rounding in the vertex stage, the plane's setup and the reference evaluation (measured: below
/// 6e-16), far below any stored format's quantum (f32's is 6e-8 near 1).
const INTERPOLATION_TOLERANCE: f64 = 1e-13;
/// The largest difference allowed between a stored f32 depth and the exact depth: half an f32 ulp
/// below 1 (2⁻²⁵ ≈ 3e-8) plus the interpolation error.
const F32_TOLERANCE: f64 = 1e-7;
/// The least fraction of covered pixels whose stored depth must be the exact depth correctly
/// rounded to the format. Only a pixel whose exact depth lies within the interpolation error of a
/// rounding boundary may miss.
const MIN_CORRECTLY_ROUNDED: f64 = 0.999;

/// The window depth of the plane through the clip-space triangle `clip` where the ray through NDC
/// point `(x, y)` meets it. The point of the triangle `Σ λₖ cₖ` projects to `(x, y)` when
/// `Σ λₖ (cₖ.x − x·cₖ.w) = 0` and `Σ λₖ (cₖ.y − y·cₖ.w) = 0`, so `λ` is the cross product of those
/// two rows, and the point's NDC depth is `Σ λₖ cₖ.z / Σ λₖ cₖ.w`.
fn exact_depth(clip: &[DVec4; 3], x: f64, y: f64) -> f64 {
    let row = |f: fn(&DVec4) -> f64, s: f64| {
        DVec3::new(
            f(&clip[0]) - s * clip[0].w,
            f(&clip[1]) - s * clip[1].w,
            f(&clip[2]) - s * clip[2].w,
        )
    };
    let lambda = row(|c| c.x, x).cross(row(|c| c.y, y));
    let z = lambda.dot(DVec3::new(clip[0].z, clip[1].z, clip[2].z));
    let w = lambda.dot(DVec3::new(clip[0].w, clip[1].w, clip[2].w));
    (z / w) * 0.5 + 0.5
}

/// The NDC coordinate of the centre of pixel `index` on a side of `size` pixels.
fn centre_ndc(index: u32, size: u32) -> f64 {
    (f64::from(index) + 0.5) / f64::from(size) * 2.0 - 1.0
}

/// The exact depth at the centre of pixel `(x, y)` of triangle `triangle` of `mesh` drawn with `m`.
fn exact_at(
    mesh: Triangles<'_>,
    m: &DMat4,
    size: TargetSize,
    triangle: u32,
    x: u32,
    y: u32,
) -> f64 {
    let corners = mesh.triangles()[triangle as usize];
    let clip = corners.map(|v| *m * mesh.positions()[v as usize].extend(1.0));
    exact_depth(
        &clip,
        centre_ndc(x, size.width()),
        centre_ndc(y, size.height()),
    )
    .clamp(0.0, 1.0)
}

/// How a draw's depths compare with the exact ones over its covered pixels.
#[derive(Clone, Copy, Debug, Default)]
struct Agreement {
    /// Covered pixels compared.
    pixels: u64,
    /// The largest |depth − exact|.
    max_error: f64,
    /// Pixels whose depth is the exact depth rounded to the format (for f64 fragments: equal to
    /// it).
    correctly_rounded: u64,
}

impl Agreement {
    fn add(&mut self, depth: f64, exact: f64, rounded: f64) {
        self.pixels += 1;
        self.max_error = self.max_error.max((depth - exact).abs());
        self.correctly_rounded += u64::from(depth == rounded);
    }

    fn merge(&mut self, other: Self) {
        self.pixels += other.pixels;
        self.max_error = self.max_error.max(other.max_error);
        self.correctly_rounded += other.correctly_rounded;
    }

    fn fraction(&self) -> f64 {
        self.correctly_rounded as f64 / self.pixels as f64
    }
}

/// The f64 depths of every fragment of `mesh` (from [`Rasterizer::for_each_fragment`]) against the
/// exact depths.
fn fragment_agreement(mesh: Triangles<'_>, m: &DMat4, size: TargetSize) -> Agreement {
    let mut agreement = Agreement::default();
    Rasterizer::new(RasterOptions::default())
        .for_each_fragment(size, mesh, m, |f: Fragment| {
            let exact = exact_at(mesh, m, size, f.triangle, f.x, f.y);
            agreement.add(f.depth, exact, exact);
        })
        .unwrap();
    agreement
}

/// The depths `mesh` leaves in an eye target of `format` (which knows each pixel's triangle)
/// against the exact depths and their correctly rounded values.
fn stored_agreement(
    mesh: Triangles<'_>,
    m: &DMat4,
    size: TargetSize,
    format: DepthFormat,
) -> Agreement {
    let mut target = EyeTarget::new(size.width(), size.height(), format).unwrap();
    Rasterizer::new(RasterOptions::default())
        .draw_eye(&mut target, mesh, m)
        .unwrap();
    let (depths, triangles) = (target.depths(), target.triangles());
    let mut agreement = Agreement::default();
    for y in 0..size.height() {
        for x in 0..size.width() {
            let p = (y * size.width() + x) as usize;
            if triangles[p] == NO_TRIANGLE {
                continue;
            }
            let exact = exact_at(mesh, m, size, triangles[p], x, y);
            agreement.add(depths[p], exact, format.decode(format.encode(exact)));
        }
    }
    agreement
}

/// The largest error a stored depth of `format` may have: half its quantum, plus the
/// interpolation error.
fn format_tolerance(format: DepthFormat) -> f64 {
    match format {
        DepthFormat::F32 | DepthFormat::ReversedF32 => F32_TOLERANCE,
        DepthFormat::Unorm24 => 0.5 / 16_777_215.0 + INTERPOLATION_TOLERANCE,
        DepthFormat::Unorm16 => 0.5 / 65_535.0 + INTERPOLATION_TOLERANCE,
    }
}

/// A quad over more than the viewport, its corners at random points off the 1/256-pixel grid and
/// at random depths (so each of its two triangles has its own random tilt), split along a random
/// diagonal, with random winding.
fn tilted_quad(rng: &mut Rng) -> Mesh {
    let mut mesh = Mesh::default();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| {
        let spread = |rng: &mut Rng, s: f64| s * (1.1 + 0.4 * rng.unit());
        let (x, y) = (spread(rng, x), spread(rng, y));
        mesh.vertex(DVec3::new(x, y, 1.8 * rng.unit() - 0.9))
    });
    let [a, b, c, d] = corners;
    let mut triangles = if rng.below(2) == 0 {
        [[a, b, c], [a, c, d]]
    } else {
        [[a, b, d], [b, c, d]]
    };
    for t in &mut triangles {
        if rng.below(2) == 0 {
            t.swap(1, 2);
        }
    }
    mesh.triangles = triangles.to_vec();
    mesh
}

/// Claim: on randomly tilted planes, every fragment's f64 depth is the exact depth to within
/// [`INTERPOLATION_TOLERANCE`], and every format stores it correctly rounded at all but a few
/// pixels, and within half its quantum everywhere.
#[test]
fn tilted_planes_follow_the_exact_plane_in_every_format() {
    let mut rng = Rng::new(0x0de9_7400);
    let size = TargetSize::new(200, 136).unwrap();
    let mut fragments = Agreement::default();
    let mut stored = [Agreement::default(); 4];
    for _ in 0..12 {
        let mesh = tilted_quad(&mut rng);
        fragments.merge(fragment_agreement(mesh.triangles(), &DMat4::IDENTITY, size));
        for (k, format) in DepthFormat::ALL.into_iter().enumerate() {
            let agreement = stored_agreement(mesh.triangles(), &DMat4::IDENTITY, size, format);
            stored[k].merge(agreement);
        }
    }
    assert_eq!(fragments.pixels, 12 * 200 * 136, "the quads cover the view");
    assert!(
        fragments.max_error <= INTERPOLATION_TOLERANCE,
        "{fragments:?}"
    );
    for (format, agreement) in DepthFormat::ALL.into_iter().zip(stored) {
        assert!(
            agreement.max_error <= format_tolerance(format),
            "{format:?}: {agreement:?}"
        );
        assert!(
            agreement.fraction() >= MIN_CORRECTLY_ROUNDED,
            "{format:?}: {agreement:?}"
        );
    }
}

/// A light's view of a ground plane: the quad `y = 0` over `[-extent, extent]²` (corners moved a
/// little off any grid) seen from `elevation` radians above the horizon at azimuth `azimuth`,
/// orthographic or perspective.
fn ground_view(rng: &mut Rng, elevation: f64, azimuth: f64, perspective: bool) -> (Mesh, DMat4) {
    let mut mesh = Mesh::default();
    let extent = 12.0;
    let [a, b, c, d] = [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)].map(|(x, z)| {
        let jitter = |rng: &mut Rng| 0.3 * (rng.unit() - 0.5);
        let (x, z) = (x * extent + jitter(rng), z * extent + jitter(rng));
        mesh.vertex(DVec3::new(x, 0.0, z))
    });
    mesh.triangles = vec![[a, b, c], [a, c, d]];
    let direction = DVec3::new(
        elevation.cos() * azimuth.cos(),
        elevation.sin(),
        elevation.cos() * azimuth.sin(),
    );
    let target = DVec3::new(0.37, 0.0, -0.21);
    let view = glam::dcamera::rh::view::look_at_mat4(target + direction * 10.0, target, DVec3::Y);
    let projection = if perspective {
        glam::dcamera::rh::proj::opengl::perspective(0.9, 1.0, 1.0, 40.0)
    } else {
        glam::dcamera::rh::proj::opengl::orthographic(-6.0, 6.0, -6.0, 6.0, 1.0, 30.0)
    };
    (mesh, projection * view)
}

/// Claim: a ground plane seen by a light at grazing to steep angles, orthographic or perspective,
/// is stored in 16 bits as the exact depth correctly rounded at all but a few texels (the shadow
/// map's use), and its fragments' f64 depths are exact to within [`INTERPOLATION_TOLERANCE`].
#[test]
fn ground_planes_are_stored_correctly_rounded_in_16_bits() {
    let mut rng = Rng::new(0x6e0d_91a5);
    let size = TargetSize::new(256, 256).unwrap();
    let mut cases = Vec::new();
    for perspective in [false, true] {
        for elevation_degrees in [12.0f64, 30.0, 55.0, 80.0] {
            let azimuth = rng.unit() * std::f64::consts::TAU;
            let (mesh, m) = ground_view(
                &mut rng,
                elevation_degrees.to_radians(),
                azimuth,
                perspective,
            );
            let fragments = fragment_agreement(mesh.triangles(), &m, size);
            let stored = stored_agreement(mesh.triangles(), &m, size, DepthFormat::Unorm16);
            let case = format!("perspective {perspective}, elevation {elevation_degrees}°");
            cases.push((case, fragments, stored));
        }
    }
    for (case, fragments, stored) in cases {
        assert!(fragments.pixels > 10_000, "{case}: {fragments:?}");
        assert!(
            fragments.max_error <= INTERPOLATION_TOLERANCE,
            "{case}: {fragments:?}"
        );
        assert!(
            stored.max_error <= format_tolerance(DepthFormat::Unorm16),
            "{case}: {stored:?}"
        );
        assert!(
            stored.fraction() >= MIN_CORRECTLY_ROUNDED,
            "{case}: {stored:?}"
        );
    }
}

/// Claim: a sliver that snapping turns over (its unsnapped vertices clockwise, its snapped ones
/// counter-clockwise), or leaves with a vanishing unsnapped area, still gets depths within its
/// vertices' depths at every centre it covers — by the tile pass (a long sliver) and by the
/// binning's early path (one of a pixel or two) alike — where the plane through its unsnapped
/// vertices would put them far outside (here below 0 or above 1).
#[test]
fn slivers_turned_over_by_snapping_keep_their_depths_in_range() {
    let size = TargetSize::new(64, 64).unwrap();
    // Grid units → NDC on a side of 64 pixels (256 grid units a pixel).
    let ndc = |grid: f64| grid / (256.0 * 32.0) - 1.0;
    // The centres of row 20 and column 5.
    let (row, column) = (20.0 * 256.0 + 128.0, 5.0 * 256.0 + 128.0);
    let depths = [0.2, 0.9, 0.3];
    // (x, y) offsets in grid units from (column, row). The vertices snap to (0, 0), (length/2, 0)
    // and (length, 1), counter-clockwise; unsnapped, the area is −0.025·length (turned over) or
    // +1e-6·length/2 (vanishing).
    let sliver = |start: f64, length: f64, last_y: f64| {
        [
            (start, 0.3),
            (start + length / 2.0, 0.45),
            (start + length, last_y),
        ]
    };
    let cases = [
        ("long, turned over", sliver(0.0, 5120.0, 0.55)),
        ("long, vanishing", sliver(0.0, 5120.0, 0.6 + 1e-6)),
        ("short, turned over", sliver(-100.0, 400.0, 0.55)),
        ("short, vanishing", sliver(-100.0, 400.0, 0.6 + 1e-6)),
    ];
    for (name, offsets) in cases {
        let mut mesh = Mesh::default();
        let corners: Vec<u32> = offsets
            .iter()
            .zip(depths)
            .map(|(&(x, y), z)| {
                mesh.vertex(DVec3::new(ndc(column + x), ndc(row + y), 2.0 * z - 1.0))
            })
            .collect();
        mesh.triangles = vec![[corners[0], corners[1], corners[2]]];
        let mut covered = 0;
        Rasterizer::new(RasterOptions::default())
            .for_each_fragment(size, mesh.triangles(), &DMat4::IDENTITY, |f: Fragment| {
                covered += 1;
                assert_eq!(f.y, 20, "{name}: row");
                assert!(
                    (0.2..=0.9).contains(&f.depth),
                    "{name}: depth {} at ({}, {})",
                    f.depth,
                    f.x,
                    f.y
                );
            })
            .unwrap();
        assert!(covered > 0, "{name} covers some centre");
    }
}
