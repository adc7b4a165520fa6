//! Shadow maps rendered and looked up: the occluder's shadow falls where geometry says, the bias
//! family trades acne against light leaks as documented, filters give fractions only near edges.

use glam::{DVec2, DVec3};
use shadowlab_hull::{Aabb, Perspective, ViewPose};
use shadowlab_params::storage::MomentFormat;
use shadowlab_params::vsm::ShiftedMoments;
use shadowlab_raster::{DepthFormat, Triangles};
use shadowlab_shadow::{
    Bias, DEFAULT_MIN_VARIANCE, DepthComparison, Eye, Filter, FocusPolicy, GAUSSIAN_SIDE_PER_SIGMA,
    Kernel, LightSetup, LightSource, Lookup, MapOptions, MomentMethod, PlanInput, Prefilter,
    ShadowMap, Storage, Technique, WarpChoice, plan,
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

/// Claim: the nearest filter, which finds a slope-scaled receiver's slope only when its one tap's
/// decision depends on it, decides exactly as a one-tap PCF, which finds the slope up front — on a
/// sloped receiver (acne without bias) and across the box's shadow, for several factors
/// (negative included, which is never deferred).
#[test]
fn a_deferred_slope_decides_as_one_found_up_front() {
    let tilt = 0.35;
    let sloped = DVec3::new(-tilt, 1.0, 0.0).normalize();
    let scenes = [
        (
            render(Technique::Uniform, DVec3::new(-0.3, 1.0, 0.2), tilt, false),
            sloped,
        ),
        (
            render(Technique::Uniform, DVec3::new(0.0, 1.0, 0.0), 0.0, false),
            DVec3::Y,
        ),
    ];
    let mut decided = [0_usize; 2];
    for (constant, slope) in [(1e-5, 2.0), (0.0, 0.5), (1e-4, 0.0), (2e-3, -1.0)] {
        let bias = Bias::new(DepthComparison::SlopeScaled { constant, slope });
        let nearest = Lookup::new(bias, Filter::Nearest);
        let one_tap = Lookup::new(bias, Filter::Pcf { size: 1 });
        for (map, normal) in &scenes {
            for k in 0..900 {
                let (x, z) = (
                    -6.0 + 0.4 * f64::from(k % 30),
                    -6.0 + 0.4 * f64::from(k / 30),
                );
                let y = if *normal == DVec3::Y { 0.0 } else { tilt * x };
                let point = DVec3::new(x, y, z);
                let lit = nearest.lit_fraction(map, point, *normal);
                assert_eq!(
                    lit,
                    one_tap.lit_fraction(map, point, *normal),
                    "{bias} at {point}"
                );
                decided[usize::from(lit == 1.0)] += 1;
            }
        }
    }
    assert!(
        decided[0] > 100 && decided[1] > 100,
        "shadowed, lit: {decided:?}"
    );
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
            prefilter: Prefilter::default(),
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
            prefilter: Prefilter::default(),
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
            prefilter: Prefilter::default(),
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
        prefilter: Prefilter::default(),
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
            prefilter: Prefilter::default(),
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

/// Every filterable spec of the command line's tables, with its defaults left implicit.
const DEFAULT_SPECS: [&str; 6] = [
    "vsm:3",
    "vsm:5,0",
    "esm:5,80",
    "evsm2:3,11.08",
    "evsm4:5,11.08,11.08,0",
    "msm:3,6e-5",
];

/// The filterable lookup as it read before the prefilter knobs (kept here as the reference): the
/// depths of the `size × size` texels around the point that lie on the map, in row-major order, and
/// the method's moments of them about the depth of the point's own texel, box-weighted, in f64.
fn lit_before_knobs(map: &ShadowMap, filter: Filter, world: DVec3) -> f64 {
    let Some(window) = map.setup.mapping.window(world) else {
        return 1.0;
    };
    let side = f64::from(map.resolution);
    let centre = DVec2::new(window.x * side, window.y * side);
    let texel = |at: DVec2| map.texel_at(at);
    let Some((ci, cj)) = texel(centre) else {
        return 1.0;
    };
    let size = match filter {
        Filter::Vsm { size, .. } | Filter::Moments { size, .. } => size,
        _ => unreachable!("a filterable map"),
    };
    let half = 0.5 * f64::from(size - 1);
    let mut depths = Vec::new();
    for b in 0..size {
        for a in 0..size {
            let offset = DVec2::new(f64::from(a) - half, f64::from(b) - half);
            if let Some((i, j)) = texel(centre + offset) {
                depths.push(map.depth(i, j));
            }
        }
    }
    let reference = map.depth(ci, cj);
    match filter {
        Filter::Vsm { min_variance, .. } => ShiftedMoments::from_depths(reference, &depths)
            .and_then(|m| m.lit_fraction(window.z, min_variance)),
        Filter::Moments { method, .. } => method.lit_fraction(reference, &depths, window.z),
        _ => unreachable!("a filterable map"),
    }
    .unwrap_or(1.0)
}

/// Points across the box's shadow on the ground and on the box's top, in a grid.
fn across_the_shadow() -> Vec<DVec3> {
    (0..30)
        .flat_map(|k| {
            (0..6).map(move |m| {
                let x = -3.0 + 0.2 * f64::from(k);
                let z = -2.6 + 1.05 * f64::from(m);
                DVec3::new(x, if m == 5 { 5.0 } else { 0.0 }, z)
            })
        })
        .collect()
}

/// Claim: a spec without knobs reads every map exactly as the filterable lookups read before the
/// knobs existed (box weights, exact f64 moments about the centre texel): bit for bit, on rendered
/// maps of two techniques and on a synthetic two-occluder map.
#[test]
fn specs_without_knobs_read_as_before() {
    let setup = plan(&input(DVec3::new(0.0, 1.0, 0.0)), Technique::Uniform).unwrap();
    let maps = [
        render(Technique::Uniform, DVec3::new(0.0, 1.0, 0.0), 0.0, false),
        render(
            Technique::Lispsm(WarpChoice::PAPER),
            DVec3::new(-0.3, 1.0, 0.2),
            0.0,
            false,
        ),
        synthetic(&setup, 16, |i, j| if (i + j) % 3 == 0 { 0.2 } else { 0.5 }),
    ];
    for spec in DEFAULT_SPECS {
        let filter = Filter::parse(spec).unwrap();
        let lookup = Lookup::new(Bias::NONE, filter);
        for map in &maps {
            for point in across_the_shadow() {
                assert_eq!(
                    lookup.lit_fraction(map, point, DVec3::Y).to_bits(),
                    lit_before_knobs(map, filter, point).to_bits(),
                    "{spec} at {point}"
                );
            }
        }
    }
}

/// How far the Gaussian weights' sum, or a ratio of two of them, may be from its closed form: a
/// few roundings of the normalisation.
const WEIGHT_TOLERANCE: f64 = 1e-15;
/// A lookup against the closed form of the same bound, by another route in f64 (as the stack tests
/// above compare them).
const CLOSED_FORM_TOLERANCE: f64 = 1e-12;
/// The most an umbra may read lit, and the least below 1 the open ground may: far from the edge
/// every method's floor or bias leaves it within a hundredth of the exact 0 or 1 on this map.
const UMBRA_AND_OPEN_MARGIN: f64 = 0.01;

/// Claim: each kernel's weights along an axis sum to 1 and are symmetric about the middle; the
/// Gaussian's fall off from the middle with σ = (K + 1)/6 (Filament's rule) and are `[1]` at
/// K = 1, the box's.
#[test]
fn kernel_weights_are_normalised_and_symmetric() {
    for kernel in Kernel::ALL {
        for size in [1, 2, 3, 4, 5, 9, 64] {
            let w = kernel.weights(size);
            assert_eq!(w.len(), size as usize);
            let sum: f64 = w.iter().sum();
            assert!(
                (sum - 1.0).abs() <= WEIGHT_TOLERANCE,
                "{kernel:?} {size}: {sum}"
            );
            for a in 0..w.len() {
                assert_eq!(w[a], w[w.len() - 1 - a], "{kernel:?} {size} tap {a}");
            }
        }
        assert_eq!(kernel.weights(1), [1.0]);
    }
    let w = Kernel::Gaussian.weights(5);
    assert!(w[0] < w[1] && w[1] < w[2], "{w:?}");
    let sigma = 6.0 / GAUSSIAN_SIDE_PER_SIGMA;
    assert!((w[1] / w[2] - (-1.0 / (2.0 * sigma * sigma)).exp()).abs() <= WEIGHT_TOLERANCE);
    assert_eq!(Kernel::Box.weights(4), [0.25; 4]);
}

/// The two-occluder map of the stack tests: columns alternate between depths 0.2 and 0.5.
fn stack_map() -> ShadowMap {
    let setup = plan(&input(DVec3::new(0.0, 1.0, 0.0)), Technique::Uniform).unwrap();
    synthetic(&setup, 16, |i, _| if i % 2 == 0 { 0.2 } else { 0.5 })
}

/// Claim: the Gaussian prefilter reads the weighted moments of the box's texels: on the stack, a 3
/// × 3 Gaussian centred on a front column puts the share `2·w(1)/(w(0) + 2·w(1))` of the weight on
/// the back occluder (below the box's ⅔), and VSM's bound is that two-point distribution's; each
/// method reads what its weighted moments give.
#[test]
fn the_gaussian_prefilter_weighs_the_kernels_texels() {
    let map = stack_map();
    let receiver = 0.6;
    let point = at_window(&map, (8, 8), receiver);
    let t = map.setup.mapping.window(point).unwrap().z;
    let read = |spec: &str| {
        Lookup::new(Bias::NONE, Filter::parse(spec).unwrap()).lit_fraction(&map, point, DVec3::Y)
    };
    let w = Kernel::Gaussian.weights(3);
    let (front, back) = (map.depth(8, 8), map.depth(7, 8));
    let (p, gap) = (2.0 * w[0] / (w[1] + 2.0 * w[0]), back - front);
    assert!(p < 2.0 / 3.0);
    let (mean, variance) = (front + p * gap, p * (1.0 - p) * gap * gap);
    let closed = variance / (variance + (t - mean).powi(2));
    let vsm = read("vsm:3,0@gauss");
    assert!(
        (vsm - closed).abs() <= CLOSED_FORM_TOLERANCE,
        "VSM {vsm} against {closed}"
    );
    assert_ne!(vsm, read("vsm:3,0"));
    let depths: Vec<f64> = (0..3).flat_map(|_| [back, front, back]).collect();
    let weights: Vec<f64> = (0..3)
        .flat_map(|b| (0..3).map(move |a| (a, b)))
        .map(|(a, b)| w[a] * w[b])
        .collect();
    for spec in ["esm:3,80", "evsm2:3,11.08", "evsm4:3,40,40,0", "msm:3,1e-7"] {
        let Filter::Moments { method, .. } = Filter::parse(spec).unwrap() else {
            unreachable!("a filterable map")
        };
        let direct = method
            .weighted_lit_fraction(front, (&depths, &weights), t)
            .unwrap();
        assert_eq!(read(&format!("{spec}@gauss")), direct, "{spec}");
    }
}

/// Claim: at K = 1 the Gaussian is the box, whatever the storage: the same lit fraction bit for
/// bit, for every method.
#[test]
fn a_one_texel_gaussian_is_the_box() {
    let map = render(Technique::Uniform, DVec3::new(0.0, 1.0, 0.0), 0.0, false);
    for spec in [
        "vsm:1",
        "esm:1,80",
        "evsm2:1,11.08",
        "evsm4:1,11.08,11.08",
        "msm:1,6e-5",
    ] {
        for storage in ["", "@f32", "@f16"] {
            let read = |kernel: &str| {
                let filter = Filter::parse(&format!("{spec}{kernel}{storage}")).unwrap();
                let lookup = Lookup::new(Bias::NONE, filter);
                across_the_shadow()
                    .into_iter()
                    .map(|p| lookup.lit_fraction(&map, p, DVec3::Y).to_bits())
                    .collect::<Vec<_>>()
            };
            assert_eq!(read("@gauss"), read(""), "{spec}{storage}");
        }
    }
}

/// Claim: every method, kernel and storage gives lit fractions in `[0, 1]` (never NaN) across the
/// box's shadow; every one shadows the umbra but ESM with c = 80 in half floats, whose `exp(80·d)`
/// overflows binary16 for every depth above 0.139 and so reads lit (*overflow reads lit*); every one
/// lights the open ground but those without a variance floor in half floats, where the stored mean
/// of the ground's own depth can round to just in front of it (acne: what the floor is for).
#[test]
fn every_knob_gives_fractions_in_the_unit_interval() {
    let map = render(Technique::Uniform, DVec3::new(0.0, 1.0, 0.0), 0.0, false);
    for spec in DEFAULT_SPECS {
        for kernel in Kernel::ALL {
            for storage in Storage::ALL {
                let prefilter = Prefilter { kernel, storage };
                let filter = Filter::parse(&format!("{spec}{prefilter}")).unwrap();
                let lookup = Lookup::new(Bias::NONE, filter);
                for point in across_the_shadow() {
                    let lit = lookup.lit_fraction(&map, point, DVec3::Y);
                    assert!(
                        (0.0..=1.0).contains(&lit),
                        "{spec}{prefilter} at {point}: {lit}"
                    );
                }
                let umbra = lookup.lit_fraction(&map, DVec3::ZERO, DVec3::Y);
                let open = lookup.lit_fraction(&map, DVec3::new(8.0, 0.0, 8.0), DVec3::Y);
                let overflows =
                    spec.starts_with("esm") && storage == Storage::Texture(MomentFormat::F16);
                if overflows {
                    assert_eq!(umbra, 1.0, "{spec}{prefilter}: umbra");
                } else {
                    assert!(
                        umbra < UMBRA_AND_OPEN_MARGIN,
                        "{spec}{prefilter}: umbra {umbra}"
                    );
                }
                let acne = spec.ends_with(",0") && storage == Storage::Texture(MomentFormat::F16);
                assert!(
                    acne || open > 1.0 - UMBRA_AND_OPEN_MARGIN,
                    "{spec}{prefilter}: open ground {open}"
                );
            }
        }
    }
}

/// How far f32 storage moves a lookup from the exact moments' on the rendered box (measured: up to
/// 9·10⁻⁸ for VSM, ESM and EVSM, 3·10⁻⁶ for MSM, whose raw power moments lose most in the Hankel
/// determinants; `shadowlab_params::storage` bounds the methods on synthetic distributions).
const F32_LOOKUP_TOLERANCE: f64 = 1e-5;

/// Claim: f32 storage reads what the exact moments read, to within [`F32_LOOKUP_TOLERANCE`], for
/// every method and both kernels, across the box's shadow.
#[test]
fn f32_storage_reads_the_exact_moments() {
    let map = render(Technique::Uniform, DVec3::new(0.0, 1.0, 0.0), 0.0, false);
    for spec in [
        "vsm:3",
        "esm:5,80",
        "evsm2:3,11.08",
        "evsm4:5,11.08,11.08",
        "msm:3,6e-5",
    ] {
        for kernel in ["", "@gauss"] {
            let read = |storage: &str| {
                let filter = Filter::parse(&format!("{spec}{kernel}{storage}")).unwrap();
                let lookup = Lookup::new(Bias::NONE, filter);
                across_the_shadow()
                    .into_iter()
                    .map(|p| lookup.lit_fraction(&map, p, DVec3::Y))
                    .collect::<Vec<_>>()
            };
            for (exact, stored) in read("").into_iter().zip(read("@f32")) {
                assert!(
                    (exact - stored).abs() <= F32_LOOKUP_TOLERANCE,
                    "{spec}{kernel}: exact {exact}, f32 {stored}"
                );
            }
        }
    }
}

/// How far f32 storage moves VSM's bound on the thin distant stack below, relative: its variance
/// (3.4·10⁻⁶) is only some 60 times f32's rounding of `E[d²]` near 0.9 (1.8 % measured).
const F32_THIN_STACK_TOLERANCE: f64 = 0.05;
/// How far binary16 storage moves EVSM2 (c = 11.08) behind one occluder at 0.99: binary16 rounds
/// `w ≈ 228` and `w² ≈ 5.2·10⁴` so that the stored variance cancels to 0, and the variance floor
/// decides as for the exact single depth; the rounded mean moves the bound by 2·10⁻⁴.
const F16_EVSM_TOLERANCE: f64 = 1e-3;

/// Claim (the documented effects of half floats, end to end through the two blur passes): on a
/// distant stack — 4 of a 5 × 5 kernel's texels at 0.95, the rest at 0.955 — binary16 loses VSM's
/// variance and lights a receiver at 0.965 that f32 storage shadows as the exact moments do
/// (2.8 % lit); EVSM2 at c = 11.08 (Filament's 5.54 in its units) stays finite in binary16 and
/// shadows a receiver behind an occluder at 0.99 as the exact moments do, while at c = 12 (their 6)
/// the squares of the warp overflow and the texel reads lit; EVSM4 keeps its negative warp's bound
/// there.
#[test]
fn half_floats_cancel_the_variance_and_overflow() {
    let setup = plan(&input(DVec3::new(0.0, 1.0, 0.0)), Technique::Uniform).unwrap();
    let stack = synthetic(&setup, 16, |i, j| {
        if [7, 9].contains(&i) && [7, 9].contains(&j) {
            0.95
        } else {
            0.955
        }
    });
    let read = |map: &ShadowMap, spec: &str, receiver: f64| {
        let point = at_window(map, (8, 8), receiver);
        Lookup::new(Bias::NONE, Filter::parse(spec).unwrap()).lit_fraction(map, point, DVec3::Y)
    };
    let exact = read(&stack, "vsm:5", 0.965);
    let f32_lit = read(&stack, "vsm:5@f32", 0.965);
    let f16_lit = read(&stack, "vsm:5@f16", 0.965);
    assert!(exact < 0.03, "{exact}");
    assert!(
        (f32_lit - exact).abs() <= F32_THIN_STACK_TOLERANCE * exact,
        "f32 {f32_lit} against {exact}"
    );
    assert!(f16_lit > 0.7, "binary16 leaks: {f16_lit}");

    let occluder = synthetic(&setup, 16, |_, _| 0.99);
    for (c, overflows) in [(11.08, false), (12.0, true)] {
        let exact = read(&occluder, &format!("evsm2:3,{c}"), 0.995);
        let half = read(&occluder, &format!("evsm2:3,{c}@f16"), 0.995);
        assert!(exact < 0.05, "c = {c}: {exact}");
        if overflows {
            assert_eq!(half, 1.0, "c = {c}");
            let both = read(&occluder, &format!("evsm4:3,{c},{c}@f16"), 0.995);
            assert!(both < 0.5, "c = {c}: EVSM4 keeps its negative warp: {both}");
        } else {
            assert!(
                (half - exact).abs() <= F16_EVSM_TOLERANCE,
                "c = {c}: {half} against {exact}"
            );
        }
    }
}

/// Claim: the knobs parse after `@` in any order, each at most once, only on filterable maps; the
/// defaults are the plain spec's; a filter prints its knobs back as a spec writes them (defaults
/// left out), and the list form of `analyze --filters` (`;` between numbers) reads the same.
#[test]
fn prefilter_knobs_parse_and_print() {
    let knobs = |spec: &str| match Filter::parse(spec).unwrap() {
        Filter::Vsm { prefilter, .. } | Filter::Moments { prefilter, .. } => prefilter,
        other => panic!("{spec}: {other:?}"),
    };
    let half_gauss = Prefilter {
        kernel: Kernel::Gaussian,
        storage: Storage::Texture(MomentFormat::F16),
    };
    assert_eq!(knobs("evsm4:5,40,5@gauss@f16"), half_gauss);
    assert_eq!(knobs("evsm4:5,40,5@f16@gauss"), half_gauss);
    assert_eq!(
        knobs("evsm4:5;40;5@gauss@f16".replace(';', ",").as_str()),
        half_gauss
    );
    assert_eq!(knobs("vsm:5@box@exact"), Prefilter::default());
    assert_eq!(
        Filter::parse("msm:3,6e-5@box@exact").unwrap(),
        Filter::parse("msm:3,6e-5").unwrap()
    );
    assert_eq!(half_gauss.to_string(), "@gauss@f16");
    assert_eq!(Prefilter::default().to_string(), "");
    for kernel in Kernel::ALL {
        for storage in Storage::ALL {
            let prefilter = Prefilter { kernel, storage };
            assert_eq!(knobs(&format!("esm:3,80{prefilter}")), prefilter);
        }
    }
    for (spec, says) in [
        ("pcf:3@gauss", "filterable maps"),
        ("nearest@f16", "filterable maps"),
        ("vsm:5@gauss@box", "two kernels"),
        ("vsm:5@f16@f32", "two storages"),
        ("vsm:5@f64", "unknown knob"),
        ("vsm:5@", "unknown knob"),
        ("esm:3,0@f16", "exponent"),
    ] {
        let error = Filter::parse(spec).unwrap_err();
        assert!(
            error.contains(spec) && error.contains(says),
            "{spec}: {error}"
        );
    }
}
