//! Shared test support: seeded proptest configuration, strategies, and membership by definition.

use glam::DVec3;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use shadowlab_hull::{
    Aabb, ConvexPolyhedron, Frustum, Light, Perspective, Scale, Tolerances, ViewPose,
};

/// The tolerances every test uses: the crate's documented defaults.
pub(crate) const TOL: Tolerances = Tolerances::DEFAULT;

/// A reproducible proptest configuration: a fixed seed (documented at each use), no persistence of
/// failures (a failing case is pasted into `extremes` as a regression test instead).
pub(crate) fn config(seed: u64, cases: u32) -> Config {
    Config {
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        cases,
        ..Config::default()
    }
}

/// A camera: pose plus perspective projection, kept together so tests can check membership from the
/// parameters.
#[derive(Clone, Debug)]
pub(crate) struct Camera {
    pub(crate) pose: ViewPose,
    pub(crate) projection: Perspective,
}

impl Camera {
    pub(crate) fn frustum(&self) -> Frustum {
        Frustum::perspective(&self.pose, &self.projection)
    }

    /// Eye-space coordinates `(x, y, depth)` of `p` (depth = distance along the view direction).
    pub(crate) fn eye_coordinates(&self, p: DVec3) -> (f64, f64, f64) {
        let e = p - self.pose.eye();
        (
            e.dot(self.pose.right()),
            e.dot(self.pose.up()),
            e.dot(self.pose.forward()),
        )
    }

    /// The six defining inequalities `c·(x, y, depth, 1) ≤ 0` of the frustum in eye coordinates.
    fn constraints(&self) -> [[f64; 4]; 6] {
        let ty = self.projection.tan_half_fov_y();
        let tx = ty * self.projection.aspect();
        [
            [0.0, 0.0, -1.0, self.projection.near()],
            [0.0, 0.0, 1.0, -self.projection.far()],
            [1.0, 0.0, -tx, 0.0],
            [-1.0, 0.0, -tx, 0.0],
            [0.0, 1.0, -ty, 0.0],
            [0.0, -1.0, -ty, 0.0],
        ]
    }

    /// Whether `p` is in the frustum by its definition, allowing `slack` (a distance).
    pub(crate) fn contains(&self, p: DVec3, slack: f64) -> bool {
        self.line_interval(p, DVec3::ZERO, slack).is_some()
    }

    /// The interval of `t` for which `p + t·direction` is in the frustum (by its definition, with
    /// `slack`), if not empty.
    pub(crate) fn line_interval(
        &self,
        p: DVec3,
        direction: DVec3,
        slack: f64,
    ) -> Option<(f64, f64)> {
        let (x0, y0, d0) = self.eye_coordinates(p);
        let (x1, y1, d1) = (
            direction.dot(self.pose.right()),
            direction.dot(self.pose.up()),
            direction.dot(self.pose.forward()),
        );
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for c in self.constraints() {
            let norm = DVec3::new(c[0], c[1], c[2]).length();
            let a = c[0] * x0 + c[1] * y0 + c[2] * d0 + c[3] - slack * norm;
            let b = c[0] * x1 + c[1] * y1 + c[2] * d1;
            if b == 0.0 {
                if a > 0.0 {
                    return None;
                }
            } else if b > 0.0 {
                hi = hi.min(-a / b);
            } else {
                lo = lo.max(-a / b);
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// A point of the frustum from three unit-interval fractions (depth, x, y).
    pub(crate) fn point(&self, fractions: [f64; 3]) -> DVec3 {
        let ty = self.projection.tan_half_fov_y();
        let tx = ty * self.projection.aspect();
        let (n, f) = (self.projection.near(), self.projection.far());
        let depth = n + (f - n) * fractions[0];
        self.pose.eye()
            + self.pose.forward() * depth
            + self.pose.right() * ((2.0 * fractions[1] - 1.0) * tx * depth)
            + self.pose.up() * ((2.0 * fractions[2] - 1.0) * ty * depth)
    }
}

/// A unit vector, uniform enough for testing (normalised Gaussian-free cube samples, rejecting the
/// tiny ones).
pub(crate) fn unit_vector() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0_f64, -1.0..1.0_f64, -1.0..1.0_f64)
        .prop_filter("not too short", |(x, y, z)| {
            DVec3::new(*x, *y, *z).length() > 0.1
        })
        .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
}

/// A point in the cube `[-extent, extent]³`.
pub(crate) fn point_in(extent: f64) -> impl Strategy<Value = DVec3> {
    (-extent..extent, -extent..extent, -extent..extent).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A random perspective camera looking at a point near the origin (where the scene boxes are), so
/// that most draws see part of the scene.
pub(crate) fn camera() -> impl Strategy<Value = Camera> {
    (
        point_in(40.0),
        point_in(15.0),
        unit_vector(),
        0.2..2.2_f64,
        0.5..2.0_f64,
        0.01..2.0_f64,
        2.0..500.0_f64,
    )
        .prop_filter_map(
            "eye at the target, or up parallel to forward",
            |(eye, target, up, fov, aspect, near, ratio)| {
                let forward = (target - eye).normalize();
                if !forward.is_finite() || forward.cross(up).length() < 0.05 {
                    return None;
                }
                Some(Camera {
                    pose: ViewPose::look_to(eye, forward, up).ok()?,
                    projection: Perspective::new(fov, aspect, near, near * ratio).ok()?,
                })
            },
        )
}

/// A random scene box around the origin.
pub(crate) fn scene_box() -> impl Strategy<Value = Aabb> {
    (
        point_in(30.0),
        (1.0..60.0_f64, 1.0..60.0_f64, 1.0..60.0_f64),
    )
        .prop_map(|(c, (x, y, z))| {
            let half = DVec3::new(x, y, z);
            Aabb::new(c - half, c + half).expect("positive size")
        })
}

/// The kind of light a test draws.
#[derive(Clone, Debug)]
pub(crate) enum LightCase {
    Directional(DVec3),
    Point(DVec3),
    Spot(Camera),
}

impl LightCase {
    pub(crate) fn light(&self) -> Light {
        match self {
            Self::Directional(u) => Light::directional(*u).expect("unit"),
            Self::Point(p) => Light::point(*p).expect("finite"),
            Self::Spot(c) => Light::spot(&c.pose, &c.projection),
        }
    }

    /// Whether `p` is in L (all space unless spot), by definition.
    pub(crate) fn in_light_frustum(&self, p: DVec3, slack: f64) -> bool {
        match self {
            Self::Spot(c) => c.contains(p, slack),
            Self::Directional(_) | Self::Point(_) => true,
        }
    }

    /// Whether `p` lies between the light and some point of V: moving away from the light from `p`
    /// hits V (by V's definition).
    pub(crate) fn reaches_view(&self, view: &Camera, p: DVec3, slack: f64) -> bool {
        match self {
            // q = p − t·u, t ≥ 0.
            Self::Directional(u) => view
                .line_interval(p, -*u, slack)
                .is_some_and(|(_, hi)| hi >= -slack),
            // q = l + t·(p − l), t ≥ 1 (p between l and q).
            Self::Point(l) => reaches_from(view, *l, p, slack),
            Self::Spot(c) => reaches_from(view, c.pose.eye(), p, slack),
        }
    }
}

fn reaches_from(view: &Camera, light: DVec3, p: DVec3, slack: f64) -> bool {
    let d = p - light;
    if d.length() <= slack {
        // p at the light: it lies between the light and every point of V.
        return true;
    }
    view.line_interval(light, d, slack)
        .is_some_and(|(_, hi)| hi >= 1.0 - slack / d.length())
}

/// A random light of any kind.
pub(crate) fn light_case() -> impl Strategy<Value = LightCase> {
    prop_oneof![
        unit_vector().prop_map(LightCase::Directional),
        point_in(80.0).prop_map(LightCase::Point),
        camera().prop_map(LightCase::Spot),
    ]
}

/// The validation distance for a scene made of these parts.
pub(crate) fn slack_for(parts: &[&[DVec3]]) -> f64 {
    let scale = parts.iter().map(|p| Scale::of_points(p.iter())).fold(
        Scale {
            extent: 0.0,
            magnitude: 0.0,
        },
        Scale::max,
    );
    TOL.validation_distance(scale)
}

/// Every vertex and `samples` convex combinations of vertices of `body`, from `weights` in [0, 1].
pub(crate) fn body_samples(body: &ConvexPolyhedron, weights: &[Vec<f64>]) -> Vec<DVec3> {
    let v = body.vertices();
    let mut points = v.to_vec();
    for w in weights.iter().filter(|w| !w.is_empty()) {
        let weight: Vec<f64> = (0..v.len()).map(|i| w[i % w.len()]).collect();
        let total: f64 = weight.iter().sum();
        if total > 0.0 {
            points.push(v.iter().zip(&weight).map(|(p, wi)| *p * (wi / total)).sum());
        }
    }
    points
}

/// Computes B and checks it against its definition on a grid of points of V (and their extensions
/// toward the light) and on its vertices; returns it.
pub(crate) fn checked_focus_body(
    view: &Camera,
    scene: &Aabb,
    light: &LightCase,
) -> Option<ConvexPolyhedron> {
    let frustum = view.frustum();
    let l = light.light();
    let b = shadowlab_hull::focus_body(&frustum, scene, &l, &TOL).expect("valid input");
    let slack = slack_for(&[
        frustum.corners(),
        &scene.corners(),
        &[l.position().unwrap_or(DVec3::ZERO)],
    ]);
    let steps = [0.0, 0.25, 0.5, 0.75, 1.0];
    let mut probes = Vec::new();
    for a in steps {
        for b in steps {
            for c in steps {
                let q = view.point([a, b, c]);
                probes.push(q);
                let reach = scene.size().length() + scene.center().distance(q);
                probes.push(match light {
                    LightCase::Directional(u) => q + *u * (reach * b),
                    LightCase::Point(p) => q + (*p - q) * b,
                    LightCase::Spot(s) => q + (s.pose.eye() - q) * b,
                });
            }
        }
    }
    let defined = |p: DVec3, s: f64| {
        scene.contains(p, s) && light.in_light_frustum(p, s) && light.reaches_view(view, p, s)
    };
    match &b {
        None => {
            for p in &probes {
                assert!(
                    !defined(*p, -slack),
                    "B is empty but {p} is in it by definition"
                );
            }
        }
        Some(body) => {
            assert_eq!(body.validate(&TOL), Ok(()));
            for p in &probes {
                if defined(*p, 0.0) {
                    assert!(
                        body.contains(*p, slack),
                        "{p} is in V∩S∩L (extended) but not in B"
                    );
                }
            }
            for p in body.vertices() {
                assert!(defined(*p, slack), "vertex {p} of B breaks the definition");
            }
        }
    }
    b
}

/// A camera from its parts.
pub(crate) fn make_camera(
    eye: DVec3,
    forward: DVec3,
    up: DVec3,
    fov: f64,
    aspect: f64,
    near: f64,
    far: f64,
) -> Camera {
    Camera {
        pose: ViewPose::look_to(eye, forward, up).expect("valid pose"),
        projection: Perspective::new(fov, aspect, near, far).expect("valid projection"),
    }
}
