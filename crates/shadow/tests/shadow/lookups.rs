//! Shadow maps rendered and looked up: the occluder's shadow falls where geometry says, the bias
//! family trades acne against light leaks as documented, filters give fractions only near edges.

use glam::DVec3;
use shadowlab_hull::{Aabb, Perspective, ViewPose};
use shadowlab_raster::{DepthFormat, Triangles};
use shadowlab_shadow::{
    Bias, DepthComparison, Eye, Filter, FocusPolicy, LightSource, Lookup, MapOptions, PlanInput,
    ShadowMap, Technique, WarpChoice, plan,
};

/// A 40 × 40 ground at y = 0 tilted by `tilt` (rise per unit x), and a closed box floating over
/// its centre (x, z ∈ [−2, 2], y ∈ [3, 5]).
struct World {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

fn world(tilt: f64) -> World {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let ground = |x: f64, z: f64| DVec3::new(x, tilt * x, z);
    positions.extend([
        ground(-20.0, -20.0),
        ground(20.0, -20.0),
        ground(20.0, 20.0),
        ground(-20.0, 20.0),
    ]);
    triangles.extend([[0, 2, 1], [0, 3, 2]]);
    let base = 4u32;
    for k in 0..8u32 {
        let (x, y, z) = (
            if k & 1 == 0 { -2.0 } else { 2.0 },
            if k & 2 == 0 { 3.0 } else { 5.0 },
            if k & 4 == 0 { -2.0 } else { 2.0 },
        );
        positions.push(DVec3::new(x, y, z));
    }
    // Outward, counter-clockwise faces of the box (vertex bit 0: x, bit 1: y, bit 2: z).
    for [a, b, c, d] in [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ] {
        triangles.push([base + a, base + b, base + c]);
        triangles.push([base + a, base + c, base + d]);
    }
    World {
        positions,
        triangles,
    }
}

fn input(sun: DVec3) -> PlanInput {
    let pose = ViewPose::look_at(DVec3::new(0.0, 12.0, 25.0), DVec3::ZERO, DVec3::Y).unwrap();
    let projection = Perspective::new(50f64.to_radians(), 4.0 / 3.0, 1.0, 80.0).unwrap();
    PlanInput {
        eye: Eye { pose, projection },
        light: LightSource::directional(sun).unwrap(),
        scene: Aabb::new(DVec3::new(-20.0, -1.0, -20.0), DVec3::new(20.0, 6.0, 20.0)).unwrap(),
        nearest_visible_depth: None,
        focus: FocusPolicy::Light,
    }
}

fn render(technique: Technique, sun: DVec3, tilt: f64, second_depth: bool) -> ShadowMap {
    let w = world(tilt);
    let setup = plan(&input(sun), technique).unwrap();
    let options = MapOptions {
        resolution: 512,
        format: DepthFormat::F32,
        second_depth,
    };
    ShadowMap::render(&setup, Triangles::new(&w.positions, &w.triangles), options).unwrap()
}

/// Claim: with the sun straight above, the ground under the box is shadowed and the ground beyond
/// it lit, for the uniform map, PSM and LiSPSM alike; the box's top is lit.
#[test]
fn the_box_shadows_the_ground_beneath_it() {
    let sun = DVec3::new(0.0, 1.0, 0.0);
    let lookup = Lookup::new(
        Bias::new(DepthComparison::SlopeScaled {
            constant: 1e-4,
            slope: 2.0,
        }),
        Filter::Nearest,
    );
    for technique in [
        Technique::Uniform,
        Technique::Psm,
        Technique::Lispsm(WarpChoice::PAPER),
    ] {
        let map = render(technique, sun, 0.0, false);
        let up = DVec3::Y;
        for (point, lit) in [
            (DVec3::new(0.0, 0.0, 0.0), 0.0),
            (DVec3::new(1.5, 0.0, -1.5), 0.0),
            (DVec3::new(3.0, 0.0, 0.0), 1.0),
            (DVec3::new(-8.0, 0.0, 6.0), 1.0),
            (DVec3::new(0.0, 5.0, 0.0), 1.0),
        ] {
            assert_eq!(
                lookup.lit_fraction(&map, point, up),
                lit,
                "{technique} at {point}"
            );
        }
    }
}

/// Claim: on a sloped, fully lit ground the unbiased test shadows some points (acne) while the
/// slope-scaled bias, the second-depth and midpoint biases light them all.
#[test]
fn biases_remove_acne_on_a_sloped_receiver() {
    let sun = DVec3::new(-0.3, 1.0, 0.2);
    let tilt = 0.35;
    let normal = DVec3::new(-tilt, 1.0, 0.0).normalize();
    let map = render(Technique::Uniform, sun, tilt, true);
    let points: Vec<DVec3> = (0..400)
        .map(|k| {
            let (x, z) = (
                -15.0 + 0.075 * f64::from(k % 20) * 20.0 / 1.5,
                8.0 + 0.0371 * f64::from(k / 20),
            );
            DVec3::new(x, tilt * x, z)
        })
        .collect();
    let lit_count = |bias| {
        let lookup = Lookup::new(bias, Filter::Nearest);
        points
            .iter()
            .filter(|p| lookup.lit_fraction(&map, **p, normal) == 1.0)
            .count()
    };
    let raw = lit_count(Bias::NONE);
    assert!(
        raw < points.len(),
        "no acne without bias: the test shows nothing"
    );
    for bias in [
        Bias::new(DepthComparison::SlopeScaled {
            constant: 1e-5,
            slope: 2.0,
        }),
        Bias::new(DepthComparison::SecondDepth),
        Bias::new(DepthComparison::Midpoint),
    ] {
        assert_eq!(lit_count(bias), points.len(), "{bias} leaves acne");
    }
}

/// Claim: filters give fractions strictly between 0 and 1 near the shadow's edge; deep inside the
/// shadow and far outside they agree with the nearest test (VSM within its Chebyshev bound: the
/// variance floor leaves a lit fraction of about `σ²_min/(t − μ)²` in the umbra).
#[test]
fn filters_soften_only_the_edge() {
    let sun = DVec3::new(0.0, 1.0, 0.0);
    let map = render(Technique::Uniform, sun, 0.0, false);
    let bias = Bias::new(DepthComparison::SlopeScaled {
        constant: 1e-4,
        slope: 2.0,
    });
    let up = DVec3::Y;
    for filter in [
        Filter::Pcf { size: 5 },
        Filter::Disk {
            taps: 16,
            radius: 2.5,
            seed: 7,
        },
        Filter::Vsm {
            size: 5,
            min_variance: 1e-6,
        },
    ] {
        let lookup = Lookup::new(bias, filter);
        let umbra = lookup.lit_fraction(&map, DVec3::new(0.0, 0.0, 0.0), up);
        assert!(umbra < 1e-4, "{filter:?} inside: {umbra}");
        assert_eq!(
            lookup.lit_fraction(&map, DVec3::new(8.0, 0.0, 8.0), up),
            1.0,
            "{filter:?} outside"
        );
        // Sample across the edge at x = 2: some point must be partly lit.
        let partial = (0..40).any(|k| {
            let f = lookup.lit_fraction(&map, DVec3::new(1.8 + 0.01 * f64::from(k), 0.0, 0.0), up);
            f > 0.0 && f < 1.0
        });
        assert!(partial, "{filter:?} gives no penumbra at the edge");
    }
}

/// Claim: the disk's taps depend only on its seed: the same seed gives the same lookups, another
/// seed different ones somewhere along the edge.
#[test]
fn the_disk_is_deterministic_per_seed() {
    let map = render(Technique::Uniform, DVec3::Y, 0.0, false);
    let bias = Bias::new(DepthComparison::Constant { offset: 1e-4 });
    let along = |seed| {
        let lookup = Lookup::new(
            bias,
            Filter::Disk {
                taps: 12,
                radius: 3.0,
                seed,
            },
        );
        (0..60)
            .map(|k| {
                lookup.lit_fraction(
                    &map,
                    DVec3::new(1.7 + 0.01 * f64::from(k), 0.0, 0.3),
                    DVec3::Y,
                )
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(along(1), along(1));
    assert_ne!(along(1), along(2));
}

/// Claim: the receiver-plane depth bias removes the acne of a tilted, fully lit plane where a
/// constant offset of the same size does not. Under PCF 3×3 (each tap's depth extrapolated to the
/// tap's position, as Isidoro does) the constant has only the half texel between a tap and the
/// centre of the texel it reads to cover, not the kernel's width; under the nearest filter the
/// depth is extrapolated to the texel's centre, so a constant of 1e-7 suffices. (The constant
/// leaves over 40 % of the points shadowed in both.)
#[test]
fn the_receiver_plane_bias_removes_acne_a_constant_leaves() {
    let sun = DVec3::new(-0.3, 1.0, 0.2);
    let tilt = 0.35;
    let normal = DVec3::new(-tilt, 1.0, 0.0).normalize();
    let map = render(Technique::Uniform, sun, tilt, false);
    let points: Vec<DVec3> = (0..400)
        .map(|k| {
            let (x, z) = (-15.0 + f64::from(k % 20), 8.0 + 0.0371 * f64::from(k / 20));
            DVec3::new(x, tilt * x, z)
        })
        .collect();
    let lit = |comparison, filter| {
        let lookup = Lookup::new(Bias::new(comparison), filter);
        points
            .iter()
            .filter(|p| lookup.lit_fraction(&map, **p, normal) == 1.0)
            .count()
    };
    for (filter, constant) in [(Filter::Pcf { size: 3 }, 5e-4), (Filter::Nearest, 1e-7)] {
        let plane = lit(DepthComparison::ReceiverPlane { constant }, filter);
        let offset = lit(DepthComparison::Constant { offset: constant }, filter);
        assert_eq!(
            plane,
            points.len(),
            "{filter:?}: receiver-plane:{constant} leaves acne"
        );
        assert!(
            offset * 5 < points.len() * 3,
            "{filter:?}: constant:{constant} lights {offset} of {}: the test shows nothing",
            points.len()
        );
    }
    // Without its constant the plane still acnes under PCF: the half texel is not extrapolated.
    let bare = lit(
        DepthComparison::ReceiverPlane { constant: 0.0 },
        Filter::Pcf { size: 3 },
    );
    assert!(bare < points.len(), "{bare}");
}
