//! Scenes built by hand, hand-built eye images, and the seeded proptest configuration.

use std::f64::consts::FRAC_PI_2;

use glam::{DAffine3, DVec3};
use proptest::test_runner::{Config, RngSeed};
use shadowlab_hull::{NdcDepth, Orthographic, Perspective, ViewPose};
use shadowlab_raster::EyeImage;
use shadowlab_scene::{Camera, Mesh, Scene, SceneLight, ShadowSettings, procedural};
use shadowlab_shadow::{LightSetup, ProjectiveMapping, ShadowMapping, Technique};

/// The seed of every property in this crate's tests.
pub(crate) const SEED: u64 = 0x5348_4144_4f57_414e; // "SHADOWAN"

pub(crate) fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        failure_persistence: None,
        ..Config::default()
    }
}

/// A camera at `eye` looking at `target` (+y up), vertical field of view `fov_degrees`, an image of
/// `width × height` pixels (aspect `width/height`), near 0.5, far 100.
pub(crate) fn camera(
    eye: DVec3,
    target: DVec3,
    fov_degrees: f64,
    width: u32,
    height: u32,
) -> Camera {
    Camera {
        pose: ViewPose::look_at(eye, target, DVec3::Y).expect("a valid pose"),
        projection: Perspective::new(
            fov_degrees.to_radians(),
            f64::from(width) / f64::from(height),
            0.5,
            100.0,
        )
        .expect("a valid projection"),
        width,
        height,
    }
}

/// A scene of `meshes` (merged in order) seen by `camera` and lit by `lights`.
pub(crate) fn scene(camera: Camera, lights: Vec<SceneLight>, meshes: &[Mesh]) -> Scene {
    Scene {
        name: "test".into(),
        camera,
        lights,
        mesh: Mesh::merged(meshes),
        shadow: ShadowSettings::default(),
    }
}

/// A directional light toward `to_light` (normalised here).
pub(crate) fn sun(to_light: DVec3) -> SceneLight {
    SceneLight::Directional {
        to_light: to_light.normalize(),
    }
}

/// A 16 × 16 ground at y = 0 (one quad, facing +y) and a closed box over its centre,
/// x, z ∈ [−2, 2], y ∈ [3, 5].
pub(crate) fn box_over_ground() -> [Mesh; 2] {
    let ground = procedural::plane(16.0, 16.0, 1).expect("a plane");
    let block = procedural::cuboid(DVec3::new(4.0, 2.0, 4.0))
        .expect("a box")
        .transformed(&DAffine3::from_translation(DVec3::new(0.0, 4.0, 0.0)));
    [ground, block]
}

/// The first triangle of `mesh` whose closed interior holds `point` (which must lie on it).
pub(crate) fn triangle_at(mesh: &Mesh, point: DVec3) -> u32 {
    let found = (0..mesh.triangle_count()).find(|&t| {
        let [a, b, c] = mesh.triangle_positions(t);
        let n = (b - a).cross(c - a);
        let on_plane = n.dot(point - a).abs() <= 1e-12 * n.length() * (1.0 + point.length());
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(p, q)| (q - p).cross(point - p).dot(n) >= 0.0);
        on_plane && inside
    });
    u32::try_from(found.expect("a triangle holds the point")).expect("a small mesh")
}

/// An eye image of one row holding `points` of `mesh` (each on some triangle), with the triangles'
/// vertex normals interpolated as the rasterizer would (here: the first vertex's normal, which is
/// the face's on the flat meshes used).
pub(crate) fn eye_image(mesh: &Mesh, points: &[DVec3]) -> EyeImage {
    let triangle: Vec<u32> = points.iter().map(|p| triangle_at(mesh, *p)).collect();
    let normal = triangle
        .iter()
        .map(|&t| mesh.normals()[mesh.triangles()[t as usize][0] as usize])
        .collect();
    EyeImage {
        width: u32::try_from(points.len()).expect("a few points"),
        height: 1,
        depth: vec![0.5; points.len()],
        triangle,
        position: points.to_vec(),
        normal,
    }
}

/// `f` run on a pool of `threads` threads.
pub(crate) fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}

/// Relative difference.
pub(crate) fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs())
}

/// A uniform (orthographic) map seen from `light` (its view along the light's rays, its right and
/// up the map's x and y): the square of half-width `half` around the light's axis, moved by `shift`
/// along both map axes, depths 1 to 40 from the light's position.
pub(crate) fn orthographic(light: &ViewPose, half: f64, shift: f64) -> LightSetup {
    let projection = Orthographic::new(
        -half + shift,
        half + shift,
        -half + shift,
        half + shift,
        1.0,
        40.0,
    )
    .expect("a valid box")
    .matrix(NdcDepth::NegativeOneToOne);
    LightSetup {
        technique: Technique::Uniform,
        mapping: ShadowMapping::Projective(ProjectiveMapping::new(light.view_matrix(), projection)),
        gamma: FRAC_PI_2,
        half_fov: 0.4,
        warp: None,
        psm: None,
        focus_body: Vec::new(),
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014) from `seed`: the tests' deterministic numbers.
pub(crate) fn split_mix64(seed: u64) -> impl FnMut() -> u64 {
    let mut state = seed;
    move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}
