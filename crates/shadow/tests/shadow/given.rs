//! Maps given rather than rendered, and lookups chosen per partition (`shadows_of`): a map's own
//! depths given back make the same map and the same lookups; given depths are stored in their
//! format; each partition is read with its own bias.

use glam::{DVec2, DVec3};
use shadowlab_raster::{DepthFormat, NO_TRIANGLE, RasterError};
use shadowlab_scene::{Scene, builtin_scene};
use shadowlab_shadow::{
    Bias, DepthComparison, Filter, FrameOptions, GivenDepths, LightMaps, LightSetup, LightSource,
    Lookup, MapSource, PartitionMap, PlanOptions, Selection, ShadowError, ShadowMap, Splits,
    Technique, eye_pass, plan_frame, render_shadows, scene_eye, served, shadows_of,
};

/// `outdoor` at a small eye image.
fn scene() -> Scene {
    let mut scene = builtin_scene("outdoor").unwrap();
    (scene.camera.width, scene.camera.height) = (128, 96);
    scene
}

fn options(partitions: usize) -> FrameOptions {
    FrameOptions {
        plan: PlanOptions {
            partitions,
            splits: Splits::Logarithmic,
            ..PlanOptions::new(Technique::Uniform)
        },
        resolution: 256,
        format: DepthFormat::F32,
        lookup: Lookup::new(Bias::DEFAULT, Filter::Nearest),
        snap_texels: 0,
    }
}

/// Claim: the depths of rendered maps, given back as they are, make the same maps and the same
/// lit fractions, bit for bit.
#[test]
fn a_maps_own_depths_given_back_change_nothing() {
    let scene = scene();
    let options = options(2);
    let (eye, nearest) = eye_pass(&scene).unwrap();
    let rendered = render_shadows(&scene, &options, &eye, nearest, None).unwrap();
    let lights = rendered
        .lights
        .iter()
        .map(|shadow| LightMaps {
            light: shadow.light,
            selection: shadow.selection,
            partitions: shadow
                .maps
                .iter()
                .map(|(partition, map)| PartitionMap {
                    partition: partition.clone(),
                    source: MapSource::Depths(GivenDepths {
                        resolution: map.resolution,
                        format: map.format,
                        nearest: map.nearest.clone(),
                        second: map.second.clone(),
                    }),
                    lookup: options.lookup.clone(),
                })
                .collect(),
        })
        .collect();
    let given = shadows_of(&scene, &eye, lights, None).unwrap();
    assert_eq!(given.lights, rendered.lights);
    assert_eq!(given.lit, rendered.lit);
    assert_eq!(given.timings.planning, std::time::Duration::ZERO);
}

/// The set-up of the scene's one map under `options(1)`.
fn one_map_setup() -> LightSetup {
    let scene = scene();
    let (eye, nearest) = eye_pass(&scene).unwrap();
    plan_frame(&scene, &options(1), nearest, Some(&eye)).unwrap()[0][0]
        .setup
        .clone()
}

/// Claim: given depths are stored as their format stores them, and must fill the map.
#[test]
fn given_depths_are_stored_in_their_format_and_fill_the_map() {
    let setup = one_map_setup();
    let depths = vec![0.3, 1.0, 0.0, 0.123_456_789];
    let map = ShadowMap::from_depths(
        setup.clone(),
        2,
        DepthFormat::Unorm16,
        depths.clone(),
        Some(depths.clone()),
    )
    .unwrap();
    let unorm16 = |z: f64| (z * 65535.0).round() / 65535.0;
    let expected: Vec<f64> = depths.iter().map(|z| unorm16(*z)).collect();
    assert_eq!(map.nearest, expected);
    assert_eq!(map.second, Some(expected));
    assert_ne!(map.nearest[0], 0.3);
    let short = ShadowMap::from_depths(setup, 3, DepthFormat::F32, depths, None);
    assert_eq!(
        short,
        Err(ShadowError::Raster(RasterError::ImageSize {
            width: 3,
            height: 3,
            values: 4
        }))
    );
}

/// Claim: each partition is read with its own lookup. With a bias past every depth on the near
/// partition and one below every depth on the far one, every pixel the near one serves is lit and
/// every pixel the far one serves is shadowed (both maps cover every visible point).
#[test]
fn each_partition_is_read_with_its_own_lookup() {
    let scene = scene();
    let options = options(2);
    let (eye, nearest) = eye_pass(&scene).unwrap();
    let planned = plan_frame(&scene, &options, nearest, Some(&eye)).unwrap();
    let offset = |offset: f64| {
        Lookup::new(
            Bias::new(DepthComparison::Constant { offset }),
            Filter::Nearest,
        )
    };
    let lights = scene
        .lights
        .iter()
        .zip(planned)
        .map(|(light, partitions)| LightMaps {
            light: LightSource::from_scene(light),
            selection: Selection::DEFAULT,
            partitions: partitions
                .into_iter()
                .enumerate()
                .map(|(k, partition)| PartitionMap {
                    partition,
                    source: MapSource::Render(shadowlab_shadow::MapOptions {
                        resolution: options.resolution,
                        format: options.format,
                        second_depth: false,
                    }),
                    lookup: offset(if k == 0 { 2.0 } else { -2.0 }),
                })
                .collect(),
        })
        .collect();
    let mixed = shadows_of(&scene, &eye, lights, None).unwrap();
    let view = scene_eye(&scene);
    let maps = &mixed.lights[0].maps;
    let mut counts = [0; 2];
    for pixel in (0..eye.triangle.len()).filter(|p| eye.triangle[*p] != NO_TRIANGLE) {
        let point: DVec3 = eye.position[pixel];
        let k = served(maps, |(p, _)| p, &Selection::DEFAULT, &view, point)
            .expect("the last partition serves beyond")
            .index;
        counts[k] += 1;
        let expected = if k == 0 { 1.0 } else { 0.0 };
        assert_eq!(
            mixed.lit[0][pixel], expected,
            "pixel {pixel}, partition {k}"
        );
    }
    assert!(counts[0] > 0 && counts[1] > 0, "{counts:?}");
}

/// Claim: the texel holding a texel-space point is its floor on each axis, on the map only (the
/// nearest lookup's and the filters' taps read it), and a window point's texel is that of the point
/// scaled to texels.
#[test]
fn a_texel_holds_the_points_it_floors_to() {
    let setup = one_map_setup();
    let map = ShadowMap::from_depths(setup, 4, DepthFormat::F32, vec![0.5; 16], None).unwrap();
    let below = |x: f64| f64::from_bits(x.to_bits() - 1);
    for (at, expected) in [
        ((0.0, 0.0), Some((0, 0))),
        ((-0.0, 3.999), Some((0, 3))),
        ((below(1.0), 1.0), Some((0, 1))),
        ((2.5, below(4.0)), Some((2, 3))),
        ((-1e-300, 1.0), None),
        ((1.0, 4.0), None),
        ((4.0, 0.0), None),
        ((f64::NAN, 1.0), None),
        ((1.0, f64::INFINITY), None),
    ] {
        assert_eq!(map.texel_at(DVec2::new(at.0, at.1)), expected, "{at:?}");
    }
    for window in [DVec3::new(0.3, 0.7, 0.2), DVec3::new(0.25, 0.999, 0.0)] {
        let side = 4.0;
        assert_eq!(
            map.texel_of(window),
            map.texel_at(DVec2::new(window.x * side, window.y * side))
        );
    }
}
