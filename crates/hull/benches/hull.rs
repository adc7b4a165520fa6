//! Criterion benchmarks of the per-frame geometry: the focus body B for a directional, a point and a
//! spot light (frustum + scene box + light), and the minimum-area rectangle of 10 000 points.
//!
//! Inputs are fixed (a SplitMix64 stream with a documented seed), so runs are comparable.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{DVec2, DVec3};
use shadowlab_hull::{
    Aabb, Frustum, Light, LightSpace, MinAreaRect, Perspective, Tolerances, ViewPose, focus_body,
};

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, seedable generator for benchmark inputs.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        #[expect(
            clippy::cast_precision_loss,
            reason = "53 random bits fit an f64 exactly"
        )]
        let unit = (z >> 11) as f64 / (1_u64 << 53) as f64;
        unit
    }
}

fn focus_bodies(c: &mut Criterion) {
    let tolerances = Tolerances::default();
    let pose = ViewPose::look_to(
        DVec3::new(0.0, 2.0, 10.0),
        DVec3::new(0.2, -0.25, -1.0),
        DVec3::Y,
    )
    .expect("valid pose");
    let view = Frustum::perspective(
        &pose,
        &Perspective::new(1.0, 16.0 / 9.0, 0.1, 100.0).expect("valid"),
    );
    let scene = Aabb::new(
        DVec3::new(-40.0, -1.0, -120.0),
        DVec3::new(40.0, 20.0, 20.0),
    )
    .expect("valid");
    let lights = [
        (
            "directional",
            Light::directional(DVec3::new(0.3, 1.0, 0.4)).expect("valid"),
        ),
        (
            "point",
            Light::point(DVec3::new(10.0, 30.0, -20.0)).expect("valid"),
        ),
        (
            "spot",
            Light::spot(
                &ViewPose::look_at(
                    DVec3::new(10.0, 30.0, 5.0),
                    DVec3::new(0.0, 0.0, -30.0),
                    DVec3::Y,
                )
                .expect("valid"),
                &Perspective::new(1.4, 1.0, 1.0, 200.0).expect("valid"),
            ),
        ),
    ];
    for (name, light) in &lights {
        c.bench_function(&format!("focus_body/{name}"), |b| {
            b.iter(|| {
                focus_body(
                    black_box(&view),
                    black_box(&scene),
                    black_box(light),
                    &tolerances,
                )
            })
        });
    }
    let sun = &lights[0].1;
    c.bench_function("focus_body/directional+light_space_bounds", |b| {
        b.iter(|| {
            let body = focus_body(black_box(&view), black_box(&scene), sun, &tolerances)
                .expect("valid")
                .expect("not empty");
            let ls = LightSpace::new(&pose, sun.to_light().expect("directional")).expect("valid");
            body.bounds_in(&ls.world_to_light(pose.eye()))
                .expect("in range")
        })
    });
}

fn min_area_rectangles(c: &mut Criterion) {
    // Seed 0x5EED_0010: 10 000 points in a rotated ellipse (a hull of a few dozen vertices), and
    // 10 000 points on a circle (every point a hull vertex: the calipers' worst case).
    let mut rng = SplitMix64(0x5EED_0010);
    let disk: Vec<DVec2> = (0..10_000)
        .map(|_| {
            let r = rng.next_unit().sqrt();
            let a = rng.next_unit() * std::f64::consts::TAU;
            DVec2::from_angle(0.4).rotate(DVec2::new(3.0 * r * a.cos(), r * a.sin()))
        })
        .collect();
    let circle: Vec<DVec2> = (0..10_000)
        .map(|_| DVec2::from_angle(rng.next_unit() * std::f64::consts::TAU) * 5.0)
        .collect();
    c.bench_function("min_area_rect/10k_in_ellipse", |b| {
        b.iter(|| MinAreaRect::of_points(black_box(&disk)))
    });
    c.bench_function("min_area_rect/10k_on_circle", |b| {
        b.iter(|| MinAreaRect::of_points(black_box(&circle)))
    });
}

criterion_group!(benches, focus_bodies, min_area_rectangles);
criterion_main!(benches);
