//! Shadow maps rendered and looked up: the occluder's shadow falls where geometry says, the bias
//! family trades acne against light leaks as documented, filters give fractions only near edges.

use glam::DVec3;
use shadowlab_hull::{Aabb, Perspective, ViewPose};
use shadowlab_raster::{DepthFormat, Triangles};
use shadowlab_shadow::{
    Bias, DEFAULT_MIN_VARIANCE, DepthComparison, Eye, Filter, FocusPolicy, LightSetup, LightSource,
    Lookup, MapOptions, MomentMethod, PlanInput, ShadowMap, Technique, WarpChoice, plan,
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

/// The filterable maps beyond VSM as the command line names them, with their knobs.
fn moment_filters() -> [Filter; 4] {
    [
        Filter::parse("esm:5,80").unwrap(),
        Filter::parse("evsm2:5,11.08").unwrap(),
        Filter::parse("evsm4:5,11.08,11.08").unwrap(),
        Filter::parse("msm:5,6e-5").unwrap(),
    ]
}

/// Claim: each filterable map parses to its method with its parameters, the variance floor
/// defaulted; a parameter out of its domain is refused naming the spec and the parameter, and a
/// missing one is refused with the accepted forms.
#[test]
fn filterable_maps_parse_with_their_parameters() {
    assert_eq!(
        Filter::parse("evsm4:3,40,20").unwrap(),
        Filter::Moments {
            size: 3,
            method: MomentMethod::Evsm4 {
                positive: 40.0,
                negative: 20.0,
                min_variance: DEFAULT_MIN_VARIANCE,
            },
        }
    );
    assert_eq!(
        Filter::parse("evsm2:1,5,0").unwrap(),
        Filter::Moments {
            size: 1,
            method: MomentMethod::Evsm2 {
                exponent: 5.0,
                min_variance: 0.0,
            },
        }
    );
    for (spec, names) in [
        ("esm:3,0", "exponent"),
        ("evsm2:3,400", "exponent"),
        ("evsm4:3,10,-1", "exponent"),
        ("evsm2:3,10,-1e-6", "min_variance"),
        ("msm:3,1.5", "alpha"),
        ("esm:0,80", "kernel size"),
    ] {
        let error = Filter::parse(spec).unwrap_err();
        assert!(
            error.contains(spec) && error.contains(names),
            "{spec}: {error}"
        );
    }
    for spec in ["esm:3", "msm:3", "evsm4:3,10", "esm"] {
        let error = Filter::parse(spec).unwrap_err();
        assert!(
            error.contains("esm:K,C") && error.contains("msm:K,ALPHA"),
            "{spec}: {error}"
        );
    }
}

/// Claim: the filterable maps, like VSM, shadow the umbra to within their reconstruction's own
/// floor there — EVSM's variance floor σ²_min keeps the positive warp's bound at least
/// `1/(1 + (c·σ_min)⁻²)` (1.2e-4 at c = 11.08, σ_min = 1e-3), MSM's bias lights it by at least
/// α/2, ESM's exponential is below e⁻¹⁰ here — light the open ground (to within the receiver's
/// depth rounding against the stored depths, which no depth comparison offsets here), and give
/// fractions across the edge.
#[test]
fn filterable_maps_soften_only_the_edge() {
    let map = render(Technique::Uniform, DVec3::new(0.0, 1.0, 0.0), 0.0, false);
    let up = DVec3::Y;
    let evsm_floor = 1.0 / (1.0 + (11.08 * DEFAULT_MIN_VARIANCE.sqrt()).powi(-2));
    let floors = [1e-5, 1.01 * evsm_floor, 1.01 * evsm_floor, 1e-4];
    for (filter, floor) in moment_filters().into_iter().zip(floors) {
        let lookup = Lookup::new(Bias::NONE, filter);
        let umbra = lookup.lit_fraction(&map, DVec3::ZERO, up);
        assert!((0.0..floor).contains(&umbra), "{filter:?} inside: {umbra}");
        let open = lookup.lit_fraction(&map, DVec3::new(8.0, 0.0, 8.0), up);
        assert!(open > 0.999 && open <= 1.0, "{filter:?} outside: {open}");
        let partial = (0..40).any(|k| {
            let f = lookup.lit_fraction(&map, DVec3::new(1.8 + 0.01 * f64::from(k), 0.0, 0.0), up);
            f > 0.01 && f < 0.99
        });
        assert!(partial, "{filter:?} gives no penumbra at the edge");
    }
}

/// A map of side `side` over `setup`'s window, every texel at window depth `depth(i, j)` (as f32
/// stores it).
fn synthetic(setup: &LightSetup, side: u32, depth: impl Fn(u32, u32) -> f64) -> ShadowMap {
    let depths = (0..side)
        .flat_map(|j| (0..side).map(move |i| (i, j)))
        .map(|(i, j)| depth(i, j))
        .collect();
    ShadowMap::from_depths(setup.clone(), side, DepthFormat::F32, depths, None).unwrap()
}

/// The world point at the centre of texel `(i, j)` of `map` at window depth `z`.
fn at_window(map: &ShadowMap, (i, j): (u32, u32), z: f64) -> DVec3 {
    let side = f64::from(map.resolution);
    let ndc = DVec3::new(
        (f64::from(i) + 0.5) / side * 2.0 - 1.0,
        (f64::from(j) + 0.5) / side * 2.0 - 1.0,
        2.0 * z - 1.0,
    );
    let clip = map.setup.mapping.clip_from_world().unwrap().inverse() * ndc.extend(1.0);
    clip.truncate() / clip.w
}

/// Claim (issue 16: the known leak of VSM on a two-occluder stack): under a 3 × 3 kernel that sees
/// two occluders, a third of its texels at depth 0.2 and two thirds at 0.5, a receiver at 0.6 is
/// fully shadowed (the nearest and PCF tests say 0), VSM lights it by the Cantelli bound of that
/// two-point distribution, `σ²/(σ² + (t − μ)²)` with `μ = d₀ + pΔ`, `σ² = p(1 − p)Δ²` (p = ⅔ at the
/// back occluder, Δ between the two: here ⅓), and EVSM with both warps and MSM with a small bias
/// leak less; each filterable map reads what its method gives on the kernel's depths.
#[test]
fn vsm_leaks_on_a_two_occluder_stack_and_the_others_less() {
    let setup = plan(&input(DVec3::new(0.0, 1.0, 0.0)), Technique::Uniform).unwrap();
    let map = synthetic(&setup, 16, |i, _| if i % 2 == 0 { 0.2 } else { 0.5 });
    let receiver = 0.6;
    let point = at_window(&map, (8, 8), receiver);
    let up = DVec3::Y;
    let read = |filter| Lookup::new(Bias::NONE, filter).lit_fraction(&map, point, up);
    assert_eq!(read(Filter::Nearest), 0.0);
    assert_eq!(read(Filter::Pcf { size: 3 }), 0.0);
    let vsm = read(Filter::Vsm {
        size: 3,
        min_variance: 0.0,
    });
    let (front, back) = (map.depth(8, 8), map.depth(7, 8));
    let (p, gap) = (2.0 / 3.0, back - front);
    let (mean, variance) = (front + p * gap, p * (1.0 - p) * gap * gap);
    let closed = variance / (variance + (receiver - mean).powi(2));
    assert!((vsm - closed).abs() < 1e-12, "VSM {vsm} against {closed}");
    assert!(vsm > 0.3, "VSM's leak here is about a third: {vsm}");
    let depths: Vec<f64> = (0..3).flat_map(|_| [back, front, back]).collect();
    for filter in [
        Filter::parse("evsm4:3,40,40,0").unwrap(),
        Filter::parse("msm:3,1e-7").unwrap(),
    ] {
        let leak = read(filter);
        assert!(leak < vsm, "{filter:?} leaks {leak}, VSM {vsm}");
        let Filter::Moments { method, .. } = filter else {
            unreachable!("parsed as a filterable map")
        };
        // The receiver's depth as the lookup reads it (the point's round trip through the
        // mapping moves it by an ulp or so).
        let t = map.setup.mapping.window(point).unwrap().z;
        let direct = method.lit_fraction(front, &depths, t).unwrap();
        assert_eq!(
            leak, direct,
            "{filter:?} against its method on the kernel's depths"
        );
    }
}

/// Claim: an even prefilter reads a K × K box, as PCF's taps lie — VSM at K = 2 reads the 2 × 2
/// texels around the point (here two at 0.2 and two at 0.5, a quarter texel from the texel
/// centres so that no tap lies on a border) and gives their two-point distribution's bound.
#[test]
fn an_even_prefilter_reads_its_whole_box() {
    let setup = plan(&input(DVec3::new(0.0, 1.0, 0.0)), Technique::Uniform).unwrap();
    let map = synthetic(&setup, 16, |i, _| if i % 2 == 0 { 0.2 } else { 0.5 });
    let side = f64::from(map.resolution);
    let receiver = 0.6;
    // Texel space (8.75, 8.75): the taps at 8.25 and 9.25 read texels 8 and 9 along each axis.
    let ndc = DVec3::new(
        8.75 / side * 2.0 - 1.0,
        8.75 / side * 2.0 - 1.0,
        2.0 * receiver - 1.0,
    );
    let clip = setup.mapping.clip_from_world().unwrap().inverse() * ndc.extend(1.0);
    let point = clip.truncate() / clip.w;
    let t = map.setup.mapping.window(point).unwrap().z;
    let vsm = Lookup::new(
        Bias::NONE,
        Filter::Vsm {
            size: 2,
            min_variance: 0.0,
        },
    )
    .lit_fraction(&map, point, DVec3::Y);
    let (front, back) = (map.depth(8, 8), map.depth(9, 8));
    let (mean, variance) = (0.5 * (front + back), 0.25 * (back - front).powi(2));
    let closed = variance / (variance + (t - mean).powi(2));
    assert!((vsm - closed).abs() < 1e-12, "VSM {vsm} against {closed}");
    assert!(
        vsm > 0.1,
        "a 1 × 1 read would see one depth and give 0: {vsm}"
    );
}
