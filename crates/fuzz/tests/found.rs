//! What the fuzzers found, as reproducers: direct calls where the input reduces to a few values, and
//! fuzz inputs (`fuzz/found/<target>/`) replayed through their target where it takes a sequence of
//! operations. A fixed bug's test runs with the suite; an open bug's test is ignored, its reason
//! saying so (`cargo test -p shadowlab-fuzz --test found -- --ignored` runs them), until it is
//! fixed.

use std::path::Path;

use glam::{DMat4, DVec2, DVec3, DVec4};
use shadowlab_hull::{ConvexHull2, ConvexPolyhedron, Tolerances, convex_hull_2d};
use shadowlab_raster::{DepthFormat, DepthTarget, RasterOptions, Rasterizer, Triangles};

/// The 2-D hull of points whose coordinates span more than f64's exponent range once rescaled
/// (1.6e233 beside 8.3e-275) is not convex: debug builds panic at `convex_hull_2d`'s
/// `debug_assert` (`WrongWinding { face: 0 }`), release builds return a polygon that fails
/// `validate`. The rescaled tiny coordinates underflow, so the "exact" orientations are not.
#[test]
fn hull_2d_of_points_spanning_the_exponent_range_is_convex() {
    let points = [
        DVec2::new(1.752045279773521e133, -2.004348981630468e18),
        DVec2::new(1.6161560284831296e233, 8.314698343835115e-275),
        DVec2::new(0.875, 0.875),
        DVec2::new(-0.625, -4.2148483248543076e-228),
    ];
    let hull = convex_hull_2d(&points).expect("finite points have a hull");
    if let ConvexHull2::Polygon(polygon) = hull {
        assert_eq!(polygon.validate(), Ok(()));
        assert_eq!(polygon.validate_contains(&points), Ok(()));
    }
}

/// The 3-D hull of five points of magnitude at most 1 with coordinates down to 5e-324 panics in
/// debug builds: "a hull face has a positive area" (`newell_plane`: the face's area vector
/// underflows to zero and has no direction).
#[test]
fn hull_3d_of_points_with_tiny_coordinates_has_face_normals() {
    let points = [
        DVec3::new(8e-275, 1.0, 1e-300),
        DVec3::new(8e-275, -1.0, 8e-275),
        DVec3::new(1e-300, 0.0, 0.5),
        DVec3::new(0.0, 0.0, 5e-324),
        DVec3::new(0.5, 0.5, 0.5),
    ];
    let tolerances = Tolerances::default();
    if let Ok(body) = ConvexPolyhedron::from_points(&points, &tolerances) {
        assert_eq!(body.validate(&tolerances), Ok(()));
    }
}

/// Five ordinary points, one with a coordinate of 1e-50, panic in debug builds with the same
/// message: not an underflow, a face whose area vector comes out zero.
#[test]
fn hull_3d_of_five_points_has_face_normals() {
    let points = [
        DVec3::new(3.125, 3.125, 3.125),
        DVec3::new(3.125, 3.125, 15.5),
        DVec3::new(4.375, 3.125, 3.125),
        DVec3::new(4.375, 4.375, 4.375),
        DVec3::new(4.375, 0.0, 1.0419217143124348e-50),
    ];
    let tolerances = Tolerances {
        relative: 1e-6,
        ..Tolerances::DEFAULT
    };
    if let Ok(body) = ConvexPolyhedron::from_points(&points, &tolerances) {
        assert_eq!(body.validate(&tolerances), Ok(()));
    }
}

/// Replays `fuzz/found/<name>` through a target.
fn replay(name: &str, target: fn(&[u8])) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/found")
        .join(name);
    target(&std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())));
}

/// A pyramid 8 193 long (its apex at x = -8192.5, its base a unit square at x = 1), left by
/// extrusions and a sweep with face planes 1e-3 off its vertices (within the tolerances of its
/// scale, `relative = 1e-6`), clipped by a plane through three points with coordinates down to
/// 5e-324: the cut body is 2 long and its inherited planes are 30 times off its own tolerance
/// (`NonPlanarFace`). Fixed: a cut that does not validate at its own scale is rebuilt as the exact
/// hull of its vertices. The most frequent crash of the hull target: about one in 5 000 inputs.
#[test]
fn clip_keeps_faces_planar() {
    replay("hull/clip-invalid-body", shadowlab_fuzz::hull);
}

/// A body near z = 6145 swept toward `-(1, 1, 1)` by 2^31: the exact hull of the swept box's ten
/// corners came out `NotSolid`, because its volume, the sum of triple products about the vertex
/// mean (each ~ε·10²⁷ in error for a body 2·10⁹ long and 1 thick) was negative. Fixed: each fan
/// tetrahedron's determinant is `orient3d`, exact in sign.
#[test]
fn sweep_gives_a_solid() {
    let points = [
        DVec3::new(
            -1239850266.8564003,
            -1239850266.8564003,
            -1239844120.8876202,
        ),
        DVec3::new(-0.250470118790992, -0.250470118790992, 6148.343768596933),
        DVec3::new(-0.250470118790992, -1.5000228881835938, 6148.343768596933),
        DVec3::new(
            -1239850265.6068475,
            -1239850266.8564003,
            -1239844120.8876202,
        ),
        DVec3::new(-0.250470118790992, -0.250470118790992, 6144.468757152557),
        DVec3::new(-0.250470118790992, -1.5000228881835938, 6144.468757152557),
        DVec3::new(
            -1239850266.8564003,
            -1239850266.8564003,
            -1239844117.0126088,
        ),
        DVec3::new(
            -1239850265.6068475,
            -1239850266.8564003,
            -1239844117.0126088,
        ),
        DVec3::new(
            -1239850265.6068475,
            -1239850265.6068475,
            -1239844120.8876202,
        ),
        DVec3::new(-1.5000228881835933, -1.5000228881835938, 6148.343768596933),
    ];
    let tolerances = Tolerances {
        relative: 1e-13,
        rounding_ulps: 4.0,
        validation_factor: 4.0,
    };
    let body = ConvexPolyhedron::from_points(&points, &tolerances).expect("a solid hull");
    assert_eq!(body.validate(&tolerances), Ok(()));
    assert!(body.volume() > 0.0);
    replay("hull/sweep-not-solid", shadowlab_fuzz::hull);
}

/// A body's bounds in a light space whose transform carries a vertex beyond f64's range: debug
/// builds panicked at `Aabb::of_finite_points`'s `debug_assert`, release builds returned infinite
/// bounds. Found by the 15-minute hull run after the fixes above, 30 s in. Fixed: `bounds_in`,
/// `transformed_bounds` and `sweep` return `HullError::Overflow`. Writing this test found two more:
/// a box near 10³⁰⁰ had an infinite extent (its diagonal's squares overflowed: `ZeroSizeBox`), and
/// one near 10³⁰⁸ an infinite vertex mean (`NotSolid`); both are computed without overflow now.
#[test]
fn bounds_beyond_the_range_are_an_error() {
    let body = ConvexPolyhedron::from_aabb(
        &shadowlab_hull::Aabb::new(DVec3::splat(1e307), DVec3::splat(1e308)).expect("a box"),
        &Tolerances::default(),
    )
    .expect("a solid");
    assert_eq!(
        body.bounds_in(&glam::DAffine3::from_scale(DVec3::splat(2.0))),
        Err(shadowlab_hull::HullError::Overflow {
            operation: "bounds_in"
        })
    );
    assert!(matches!(
        body.sweep(DVec3::X, f64::MAX, &Tolerances::default()),
        Err(shadowlab_hull::HullError::Overflow { .. })
    ));
    replay("hull/bounds-overflow", shadowlab_fuzz::hull);
}

/// A frustum from an ill-conditioned matrix (corners from −3 to 3.6·10¹⁶): the corners its inverse
/// gives lie 3.4·10¹⁵ off the planes its rows give, so the polyhedron `from_frustum` built failed
/// validation (`NonPlanarFace`). Found by the second 15-minute hull run at once. Fixed: such a
/// frustum is `HullError::InconsistentFrustum`.
#[test]
fn an_ill_conditioned_frustum_is_refused() {
    replay("hull/frustum-inconsistent", shadowlab_fuzz::hull);
}

/// A box 3.6·10⁻¹⁸⁰ on a side: the distance of two corners, `sqrt(dx²)`, underflowed to 0, so
/// `validate` called them duplicates (`DuplicateVertex`). Found by the third 15-minute hull run.
/// Fixed: every distance compared with the snap distance is taken on the difference divided by its
/// largest component, and the hull's flatness tests run on the rescaled points.
#[test]
fn a_tiny_box_has_eight_distinct_corners() {
    let side = 3.568_571_534_544_457_6e-180;
    let tolerances = Tolerances {
        relative: 1e-6,
        ..Tolerances::DEFAULT
    };
    let aabb = shadowlab_hull::Aabb::new(DVec3::splat(-side), DVec3::ZERO).expect("a box");
    let body = ConvexPolyhedron::from_aabb(&aabb, &tolerances).expect("a solid");
    assert_eq!(body.validate(&tolerances), Ok(()));
    let corners: Vec<DVec3> = aabb.corners().to_vec();
    let hull = ConvexPolyhedron::from_points(&corners, &tolerances).expect("a solid hull");
    assert_eq!(hull.vertices().len(), 8);
    replay("hull/tiny-box-duplicates", shadowlab_fuzz::hull);
}

/// The exact hull that a clip falls back to had a sliver face (sides 1.05, 1.05 and 4·10⁻⁷) whose
/// f64 normal was 5·10⁻¹⁰ rad off, leaving a vertex 1.4·10⁻¹¹ off its plane, above the
/// validation distance of `relative = 1e-13` (`NonPlanarFace`). Found by the fourth 15-minute
/// hull run. Fixed: face normals come from the area vector in double-double arithmetic
/// (`area::loop_normal`).
#[test]
fn sliver_faces_of_a_hull_are_planar() {
    replay("hull/sliver-face-normal", shadowlab_fuzz::hull);
}

/// `DepthTarget::clear(NaN)` stores NaN in the reversed-f32 format, so `depths()` returns a depth
/// outside `[0, 1]` (f32 stores 1 and the unorm formats 0: the formats also disagree on it).
#[test]
fn clearing_to_nan_stores_a_depth_in_range() {
    for format in DepthFormat::ALL {
        let mut target = DepthTarget::new(1, 1, format).expect("a 1×1 target");
        target.clear(f64::NAN);
        let depths = target.depths();
        assert!(
            depths.iter().all(|z| (0.0..=1.0).contains(z)),
            "{format:?}: {depths:?}"
        );
    }
}

/// A vertex whose clip-space w is subnormal (1e-320) lies well inside the view (x/w = 0.1), but its
/// window position comes out infinite (the reciprocal of w overflows): debug builds panic at
/// `fixed::snapped`'s `debug_assert` ("inf outside the guard band"), release builds saturate the
/// cast. No triangle is needed: every vertex is transformed. Ten of the raster run's inputs, with
/// ±∞ or NaN window positions.
#[test]
fn a_vertex_with_subnormal_w_has_a_finite_window_position() {
    let clip_from_world = DMat4::from_cols(
        DVec4::X,
        DVec4::Y,
        DVec4::Z,
        DVec4::new(0.0, 0.0, 0.0, 1e-320),
    );
    let positions = [DVec3::new(1e-321, 0.0, 0.0)];
    let mut target = DepthTarget::new(1, 1, DepthFormat::F32).expect("a 1×1 target");
    let mut rasterizer = Rasterizer::new(RasterOptions::default());
    let stats = rasterizer
        .draw_depth(
            &mut target,
            Triangles::new(&positions, &[]),
            &clip_from_world,
        )
        .expect("finite input");
    assert_eq!(stats.triangles, 0);
}

/// A triangle with clip-space w of −2.2·10³⁰⁷ and 1.06·10³⁰⁸ crossing every plane: the
/// guard-band distances (`x + g·w`) overflowed, an intersection divided ∞ by ∞, and the NaN vertex
/// reached the snap (debug builds: "NaN outside the guard band" in `fixed::snapped`). Found by
/// this session's raster run after 190 s. Fixed: such vertices are scaled by 2⁻¹²⁸ before
/// clipping (`clip.rs`, `HUGE_VERTEX`), and a clipped vertex with a NaN w is dropped like one
/// with w below `MIN_W`.
#[test]
fn a_triangle_with_w_near_the_largest_f64_clips_to_finite_pieces() {
    replay("raster/clip-nan-window", shadowlab_fuzz::raster);
}

/// A triangle with y = 2·10²³⁶ and −2.2·10²⁸⁹ at two vertices crossing the far, bottom and top
/// planes: the intersection with the bottom guard plane, interpolated between endpoints of those
/// magnitudes, came out at y = −2.8·10²¹⁹ instead of on the plane (−497), and reached the snap
/// outside the guard band (debug builds: "… outside the guard band"). Found by this session's
/// second raster run after 9 minutes. Fixed: an intersection's coordinate across the plane is set
/// from the plane's equation (`clip.rs`, `onto_plane`).
#[test]
fn an_intersection_of_huge_endpoints_lies_on_its_plane() {
    replay("raster/guard-band-escape", shadowlab_fuzz::raster);
}
