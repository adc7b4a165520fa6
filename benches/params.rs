//! The cost of the closed forms: one parameter evaluation per rule, and one 1000-point curve (the
//! error along the view axis, as `shadowlab curves` samples it). Inputs are fixed; there is no
//! randomness. Figures are recorded in docs/benchmarks.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use shadowlab_params::{
    DepthRange, FrustumModel, HalfFov, LightAngle, ParameterRule, WarpParameter, gmnpr, lispsm,
};

/// Points of the curve benchmark.
const CURVE_POINTS: u32 = 1000;

fn model() -> FrustumModel {
    FrustumModel::new(
        DepthRange::new(1.0, 100.0).expect("valid range"),
        HalfFov::from_full_fov_degrees(60.0).expect("valid fov"),
    )
}

fn parameter_evaluation(c: &mut Criterion) {
    let m = model();
    let gamma = LightAngle::from_degrees(45.0).expect("valid angle");
    let mut group = c.benchmark_group("parameter");
    for rule in ParameterRule::ALL {
        group.bench_function(rule.key(), |b| {
            b.iter(|| black_box(rule).warp(black_box(&m), black_box(gamma)));
        });
    }
    group.bench_function("lispsm_n_opt", |b| {
        b.iter(|| lispsm::n_opt(black_box(m.range())));
    });
    group.bench_function("minimax_with_max_error", |b| {
        b.iter(|| ParameterRule::Minimax.evaluate(black_box(&m), black_box(gamma)));
    });
    group.finish();
}

fn curve(c: &mut Criterion) {
    let m = model();
    let gamma = LightAngle::from_degrees(20.0).expect("valid angle");
    let warp = gmnpr::lambda_minimax(&m, gamma);
    let mut group = c.benchmark_group("curve_1000_points");
    group.bench_function("gmnpr_error_along_z", |b| {
        b.iter(|| {
            let range = black_box(m.range());
            let mut sum = 0.0;
            for i in 0..=CURVE_POINTS {
                let z = range.lerp(f64::from(i) / f64::from(CURVE_POINTS));
                sum += gmnpr::error(&m, gamma, black_box(warp), z).unwrap_or(f64::NAN);
            }
            sum
        });
    });
    group.bench_function("max_error_vs_angle_one_rule", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for i in 1..=CURVE_POINTS {
                let degrees = 90.0 * f64::from(i) / f64::from(CURVE_POINTS);
                let g = LightAngle::from_degrees(degrees).unwrap_or(LightAngle::PERPENDICULAR);
                let w = black_box(ParameterRule::Gmnpr)
                    .warp(&m, g)
                    .unwrap_or(WarpParameter::UNIFORM);
                sum += gmnpr::max_error(&m, g, w);
            }
            sum
        });
    });
    group.finish();
}

criterion_group!(benches, parameter_evaluation, curve);
criterion_main!(benches);
