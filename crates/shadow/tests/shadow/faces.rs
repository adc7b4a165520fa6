//! Lloyd et al.'s face partitioning of the logarithmic map: the back faces of V tile its
//! projection, each point of V is served by a face whose map covers it, side faces measure their
//! logarithm from the eye, and the overhead light reduces to the one map of the plain technique.

use std::f64::consts::PI;

use glam::DVec3;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::{
    Bias, FocusPolicy, FrameOptions, LogarithmicChoice, Lookup, Partition, PlanInput, PlanOptions,
    Selection, Splits, Technique, plan, plan_partitions, render_frame, served,
};

use crate::support::configuration;

const FACES: Technique = Technique::Logarithmic(LogarithmicChoice::Faces);

/// Every point of a grid filling V, as (point, eye depth).
fn points_of_view(input: &PlanInput) -> Vec<(DVec3, f64)> {
    let c = input.eye.frustum().corners().to_owned();
    let mut points = Vec::new();
    let steps = 7;
    for i in 0..=steps {
        for j in 0..=steps {
            for k in 0..=steps {
                let (u, v, w) = (
                    f64::from(i) / f64::from(steps),
                    f64::from(j) / f64::from(steps),
                    f64::from(k) / f64::from(steps),
                );
                // Trilinear in the corners (bit 0 right, bit 1 top, bit 2 far): inside V.
                let lerp = |a: DVec3, b: DVec3, t: f64| a + (b - a) * t;
                let near = lerp(lerp(c[0], c[1], u), lerp(c[2], c[3], u), v);
                let far = lerp(lerp(c[4], c[5], u), lerp(c[6], c[7], u), v);
                let p = lerp(near, far, 0.02 + 0.96 * w);
                let depth = (p - input.eye.pose.eye()).dot(input.eye.pose.forward());
                points.push((p, depth));
            }
        }
    }
    points
}

fn faces_of(input: &PlanInput) -> Vec<Partition> {
    plan_partitions(input, FACES, Splits::Uniform, 1).unwrap()
}

/// Claim: at every light direction (γ from 0 to 90°, in front and behind), each point of V lies in
/// the region of at least one back face (the regions tile V's projection, overlapping only on
/// edges), the face that serves it maps it inside its map's window, and side faces measure their
/// logarithm from the eye (λ = −z_max/d > 0).
#[test]
fn back_faces_tile_the_view_and_cover_what_they_serve() {
    for gamma_degrees in [0.0, 5.0, 18.0, 30.0, 45.0, 70.0, 89.0] {
        for facing in [true, false] {
            let input = configuration(
                DVec3::new(1.0, 2.0, 3.0),
                0.4,
                -0.3,
                60.0,
                1.0,
                100.0,
                f64::to_radians(gamma_degrees),
                true,
                facing,
                FocusPolicy::View,
            );
            let parts = faces_of(&input);
            assert!(
                !parts.is_empty() && parts.len() <= 5,
                "{} faces",
                parts.len()
            );
            for part in &parts {
                let face = part
                    .face
                    .as_ref()
                    .and_then(|f| f.view_face())
                    .expect("face partitions have view-face regions");
                let warp = part.setup.warp.as_ref().unwrap();
                if face.face < 4 {
                    let z_max = warp.inputs.iter().find(|(n, _)| *n == "z_max").unwrap().1;
                    assert!(
                        z_max < 0.0,
                        "γ = {gamma_degrees}: side face {} z_max {z_max}",
                        face.face
                    );
                    assert_eq!(warp.lambda, -z_max / warp.depth);
                } else {
                    assert!(warp.lambda.is_infinite(), "an end face is uniform");
                }
            }
            for (point, _) in points_of_view(&input) {
                let covering = parts
                    .iter()
                    .filter(|p| p.face.as_ref().unwrap().inside(point) >= -1e-9)
                    .count();
                assert!(covering >= 1, "γ = {gamma_degrees}: {point} in no face");
                let k = served(&parts, |p| p, &Selection::DEFAULT, &input.eye, point)
                    .expect("the last partition serves beyond")
                    .index;
                let window = parts[k].setup.mapping.window(point).expect("mapped");
                assert!(
                    window.min_element() >= -1e-9 && window.max_element() <= 1.0 + 1e-9,
                    "γ = {gamma_degrees}, facing {facing}: {point} at {window} of face {}",
                    parts[k].face.as_ref().unwrap().view_face().unwrap().face
                );
            }
        }
    }
}

/// Claim: with the light straight across the view (γ = 90°, in the camera's vertical plane) only
/// the bottom face faces away from the light, and its map is the plain logarithmic map.
#[test]
fn the_overhead_light_has_one_face_the_plain_logarithmic_map() {
    let input = configuration(
        DVec3::ZERO,
        0.0,
        0.0,
        60.0,
        1.0,
        100.0,
        PI / 2.0,
        true,
        true,
        FocusPolicy::View,
    );
    let parts = faces_of(&input);
    assert_eq!(parts.len(), 1);
    assert_eq!(
        parts[0].face.as_ref().unwrap().view_face().unwrap().face,
        shadowlab_hull::BOTTOM
    );
    let plain = plan(&input, Technique::LOGARITHMIC).unwrap();
    for (point, _) in points_of_view(&input) {
        let (a, b) = (
            parts[0].setup.mapping.window(point).unwrap(),
            plain.mapping.window(point).unwrap(),
        );
        assert!((a - b).length() < 1e-9, "{point}: {a} vs {b}");
    }
}

/// Claim: in the dueling frusta (the light straight ahead, γ = 0) the four side faces and the near
/// face face away from it, and each point is served by exactly the face around it.
#[test]
fn the_dueling_frusta_get_four_side_faces_and_the_near_face() {
    let input = configuration(
        DVec3::ZERO,
        0.2,
        0.1,
        60.0,
        1.0,
        100.0,
        0.0,
        true,
        true,
        FocusPolicy::View,
    );
    let mut faces: Vec<usize> = faces_of(&input)
        .iter()
        .map(|p| p.face.as_ref().unwrap().view_face().unwrap().face)
        .collect();
    faces.sort_unstable();
    assert_eq!(faces, [0, 1, 2, 3, 4]);
}

/// Claim: face partitioning renders the built-in dueling frusta, one map per face, and composes
/// with z-partitioning (each z-partition face-partitioned on its own); `plan` alone refuses it.
#[test]
fn face_partitions_render_and_compose_with_z_partitions() {
    let mut scene = builtin_scene("dueling-frusta").unwrap();
    (scene.camera.width, scene.camera.height) = (160, 120);
    for partitions in [1, 2] {
        let options = FrameOptions {
            plan: PlanOptions {
                partitions,
                splits: Splits::Logarithmic,
                ..PlanOptions::new(FACES)
            },
            resolution: 128,
            format: shadowlab_raster::DepthFormat::F32,
            lookup: Lookup::new(Bias::DEFAULT, shadowlab_shadow::Filter::Nearest),
            snap_texels: 0,
        };
        let frame = render_frame(&scene, &options).unwrap();
        let maps = &frame.lights[0].maps;
        assert!(maps.len() >= 2 * partitions, "{} maps", maps.len());
        let nears: std::collections::BTreeSet<u64> =
            maps.iter().map(|(p, _)| p.near.to_bits()).collect();
        assert_eq!(nears.len(), partitions);
        assert!(maps.iter().all(|(p, _)| p.face.is_some()));
    }
    let input =
        shadowlab_shadow::scene_input(&scene, &scene.lights[0], None, FocusPolicy::Light).unwrap();
    assert!(plan(&input, FACES).is_err());
}

/// A split scheme prints as the spec it is parsed from, so settings lines name it exactly.
#[test]
fn split_schemes_print_as_they_are_parsed() {
    for spec in [
        "uniform",
        "logarithmic",
        "practical:0.5",
        "practical:0.95",
        "adaptive:2",
        "adaptive:1.0000000000000002",
    ] {
        let splits = Splits::parse(spec).unwrap();
        assert_eq!(splits.to_string(), spec);
        assert_eq!(Splits::parse(&splits.to_string()), Ok(splits));
    }
}
