//! A sweep's frames: each scene under each camera pose and light direction of the spec. A frame
//! is what one exact truth is computed for; its cells share it.

use std::f64::consts::PI;

use glam::{DQuat, DVec3};
use shadowlab_analysis::sweep::{light_at, swept_light};
use shadowlab_analysis::temporal::pose_at;
use shadowlab_hull::ViewPose;
use shadowlab_scene::{Scene, SceneLight};

use crate::error::SweepError;
use crate::spec::{Cameras, Lights, Side, gamma_angles};

/// A camera pose of the spec, before it meets a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraPose {
    /// The scene's own camera.
    Scene,
    /// Frame `k` of the camera walk.
    Walk(usize),
    /// A pose the spec gives.
    Given(ViewPose),
    /// The `k`-th random pose of the seed.
    Random {
        /// The generator's seed.
        seed: u64,
        /// Which pose.
        index: usize,
        /// Eye offset, scene radii.
        reach: f64,
        /// Largest yaw, radians.
        turn: f64,
    },
}

/// A light direction of the spec, before it meets a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightPlacement {
    /// The scene's own lights.
    Scene,
    /// At γ (radians) from the view, on a side.
    Gamma(f64, Side),
    /// Toward this world direction (unit, +y up).
    Direction(DVec3),
}

/// The camera poses a spec names, in order.
///
/// # Errors
/// [`SweepError::Spec`] if a given pose is degenerate (a checked spec's are not).
pub fn camera_poses(cameras: &Cameras) -> Result<Vec<CameraPose>, SweepError> {
    Ok(match cameras {
        Cameras::Scene => vec![CameraPose::Scene],
        Cameras::Path { poses } => poses
            .iter()
            .enumerate()
            .map(|(k, p)| {
                ViewPose::look_at(
                    DVec3::from_array(p.eye),
                    DVec3::from_array(p.target),
                    DVec3::from_array(p.up),
                )
                .map(CameraPose::Given)
                .map_err(|e| SweepError::Spec(format!("cameras.poses[{k}]: {e}")))
            })
            .collect::<Result<_, _>>()?,
        Cameras::Walk { frames, every } => {
            (0..*frames).map(|k| CameraPose::Walk(k * every)).collect()
        }
        &Cameras::Random {
            count,
            seed,
            reach,
            turn_degrees,
        } => (0..count)
            .map(|index| CameraPose::Random {
                seed,
                index,
                reach,
                turn: turn_degrees.to_radians(),
            })
            .collect(),
    })
}

/// The light placements a spec names, in order: a sphere grid elevation by elevation, azimuths
/// `2π·j/azimuths` from +x toward +z (one direction straight up).
#[must_use]
pub fn light_placements(lights: &Lights) -> Vec<LightPlacement> {
    match lights {
        Lights::Scene => vec![LightPlacement::Scene],
        Lights::Gamma {
            degrees,
            range,
            side,
        } => gamma_angles(degrees, range.as_ref())
            .iter()
            .map(|d| LightPlacement::Gamma(d.to_radians(), *side))
            .collect(),
        Lights::Sphere {
            elevations,
            azimuths,
        } => {
            let mut out = Vec::new();
            for e in elevations {
                let e = e.to_radians();
                let around = if (e - PI / 2.0).abs() < 1e-12 {
                    1
                } else {
                    *azimuths
                };
                for j in 0..around {
                    #[expect(clippy::cast_precision_loss, reason = "small counts")]
                    let a = 2.0 * PI * j as f64 / *azimuths as f64;
                    out.push(LightPlacement::Direction(DVec3::new(
                        e.cos() * a.cos(),
                        e.sin(),
                        e.cos() * a.sin(),
                    )));
                }
            }
            out
        }
    }
}

/// SplitMix64 (Steele, Lea and Flood 2014): the seeded generator of random poses; each pose
/// draws from its own stream, `seed + index·golden`, so a pose never depends on how many others
/// there are.
struct SplitMix64(u64);

impl SplitMix64 {
    const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(Self::GOLDEN);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[-1, 1)`, from the top 53 bits.
    fn symmetric(&mut self) -> f64 {
        #[expect(clippy::cast_precision_loss, reason = "53 bits are exact in an f64")]
        let unit = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        2.0 * unit - 1.0
    }
}

/// The random pose `index` of `seed` around the scene camera `pose`: the eye moved by a point
/// uniform in the ball of radius `reach`·`radius` (rejection from the cube), then the view turned
/// by a yaw uniform in `[-turn, turn]` about +y and a pitch uniform in `[-turn/2, turn/2]` about
/// the camera's right axis.
///
/// # Errors
/// If the turned view is degenerate (looking straight up or down).
pub fn random_pose(
    pose: &ViewPose,
    radius: f64,
    (seed, index): (u64, usize),
    (reach, turn): (f64, f64),
) -> Result<ViewPose, SweepError> {
    let mut rng = SplitMix64(seed.wrapping_add((index as u64).wrapping_mul(SplitMix64::GOLDEN)));
    let offset = loop {
        let p = DVec3::new(rng.symmetric(), rng.symmetric(), rng.symmetric());
        if p.length_squared() <= 1.0 {
            break p;
        }
    };
    let yaw = turn * rng.symmetric();
    let pitch = 0.5 * turn * rng.symmetric();
    let turned = DQuat::from_rotation_y(yaw) * DQuat::from_axis_angle(pose.right(), pitch);
    ViewPose::look_to(
        pose.eye() + offset * (reach * radius),
        turned * pose.forward(),
        turned * pose.up(),
    )
    .map_err(|e| SweepError::Scene(format!("random camera pose {index}: {e}")))
}

/// `scene` seen from `camera` and lit from `light`: the frame a truth is computed for.
///
/// # Errors
/// [`SweepError::Scene`] if a pose is degenerate.
pub fn posed(
    scene: &Scene,
    camera: CameraPose,
    light: LightPlacement,
) -> Result<Scene, SweepError> {
    let (pose, lights) = pose_and_lights(scene, camera, light)?;
    let mut posed = scene.clone();
    posed.camera.pose = pose;
    posed.lights = lights;
    Ok(posed)
}

/// The camera pose and lights of [`posed`], without copying the scene's mesh.
///
/// # Errors
/// As [`posed`].
pub fn pose_and_lights(
    scene: &Scene,
    camera: CameraPose,
    light: LightPlacement,
) -> Result<(ViewPose, Vec<SceneLight>), SweepError> {
    let bounds = scene.bounds();
    let radius = 0.5 * (bounds.max - bounds.min).length();
    let pose = match camera {
        CameraPose::Scene => scene.camera.pose,
        CameraPose::Given(pose) => pose,
        CameraPose::Walk(k) => pose_at(scene, k)
            .map_err(|e| SweepError::Scene(format!("{}: walk frame {k}: {e}", scene.name)))?,
        CameraPose::Random {
            seed,
            index,
            reach,
            turn,
        } => random_pose(&scene.camera.pose, radius, (seed, index), (reach, turn))?,
    };
    let to_light = match light {
        LightPlacement::Scene => return Ok((pose, scene.lights.clone())),
        LightPlacement::Gamma(gamma, side) => light_at(
            &pose,
            gamma,
            match side {
                Side::Front => shadowlab_analysis::sweep::Side::Front,
                Side::Behind => shadowlab_analysis::sweep::Side::Behind,
            },
        ),
        LightPlacement::Direction(d) => d,
    };
    Ok((
        pose,
        vec![swept_light(scene.lights.first(), pose.eye(), to_light)],
    ))
}

/// The unit vector from the eye toward the frame's first light, and γ — the angle between the
/// view direction and it, folded into `[0, π/2]` as the papers measure it (a light behind the
/// viewer at angle γ from the view axis has the same γ as one in front).
#[must_use]
pub fn light_direction(scene: &Scene) -> (DVec3, f64) {
    let eye = scene.camera.pose.eye();
    let toward = match scene.lights.first() {
        Some(SceneLight::Directional { to_light }) => *to_light,
        Some(SceneLight::Spot { pose, .. }) => (pose.eye() - eye).normalize_or(-pose.forward()),
        Some(SceneLight::Point { position, .. }) => {
            (*position - eye).normalize_or(scene.camera.pose.forward())
        }
        None => scene.camera.pose.forward(),
    };
    let cosine = scene.camera.pose.forward().dot(toward).abs().min(1.0);
    (toward, cosine.acos())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn random_poses_are_seeded_and_independent_of_their_count() {
        let scene = shadowlab_scene::builtin_scene("outdoor").unwrap();
        let pose =
            |seed, index| random_pose(&scene.camera.pose, 10.0, (seed, index), (0.1, 0.3)).unwrap();
        assert_eq!(pose(7, 3), pose(7, 3));
        assert_ne!(pose(7, 3).eye(), pose(8, 3).eye());
        assert_ne!(pose(7, 3).eye(), pose(7, 4).eye());
        // Within reach: 0.1 × 10.
        assert!((pose(7, 3).eye() - scene.camera.pose.eye()).length() <= 1.0 + 1e-12);
    }

    #[test]
    fn a_sphere_grid_has_one_direction_at_the_zenith() {
        let lights = Lights::Sphere {
            elevations: vec![30.0, 90.0],
            azimuths: 4,
        };
        let dirs = light_placements(&lights);
        assert_eq!(dirs.len(), 5);
        for d in dirs {
            let LightPlacement::Direction(d) = d else {
                panic!("a direction")
            };
            assert!((d.length() - 1.0).abs() < 1e-12 && d.y > 0.0);
        }
    }

    #[test]
    fn gamma_lights_have_their_gamma() {
        let scene = shadowlab_scene::builtin_scene("outdoor").unwrap();
        for degrees in [0.0, 10.0, 45.0, 90.0] {
            let placed = posed(
                &scene,
                CameraPose::Scene,
                LightPlacement::Gamma(f64::to_radians(degrees), Side::Behind),
            )
            .unwrap();
            let (_, gamma) = light_direction(&placed);
            assert!((gamma.to_degrees() - degrees).abs() < 1e-9, "{degrees}");
        }
    }
}
