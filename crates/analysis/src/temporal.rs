//! Temporal stability: the camera walks; a pixel *shimmers* when its shadow state flips from one
//! frame to the next while the truth there does not. Measured with and without texel snapping.
//!
//! Two counts, since the camera moves: **screen shimmer** compares the same pixel in consecutive
//! frames, which see different surface points as the camera moves — a map whose texel grid moves
//! with the camera keeps its jaggies still on screen and scores well; **surface shimmer** looks
//! each visible point of a frame up in the previous frame's maps and in its own, and counts the
//! points whose state flips — shadows crawling over static surfaces, which is what stabilisation
//! (texel snapping, rotation-invariant fits) is for. The truth at a point does not change (the
//! scene is static), so every surface flip is an error of one of the two frames.

use glam::{DQuat, DVec3};
use shadowlab_hull::ViewPose;
use shadowlab_raster::NO_TRIANGLE;
use shadowlab_scene::Scene;
use shadowlab_shadow::{
    Bias, Filter, FrameOptions, LightShadow, Lookup, PlanOptions, Technique, eye_pass, lit_at,
    render_shadows, scene_eye,
};
use shadowlab_trace::Bvh;

use crate::error::AnalysisError;
use crate::truth::LIT_THRESHOLD;
use crate::truth::exact_truth;

/// How far the camera walks per frame, as a fraction of the scene's bounding radius.
pub const STEP_FRACTION: f64 = 0.002;
/// How far it turns per frame (yaw about +y), radians.
pub const TURN_PER_FRAME: f64 = 0.1 * std::f64::consts::PI / 180.0;
/// Frames of the walk out before it turns back: the camera goes out over `WALK_OUT_FRAMES` steps
/// (half the scene's radius, 25°) and back the same way, and again, so a walk of any
/// length stays where the first `WALK_OUT_FRAMES` frames went (a straight walk of 600 frames left
/// the outdoor scene). Walks of at most this many frames are straight.
pub const WALK_OUT_FRAMES: usize = 250;

/// The walk's position at frame `k`, in steps: `k` up to [`WALK_OUT_FRAMES`], then back down to
/// 0 and out again (a triangle wave of period 2·[`WALK_OUT_FRAMES`]).
#[must_use]
pub fn walk_steps(k: usize) -> usize {
    let phase = k % (2 * WALK_OUT_FRAMES);
    if phase <= WALK_OUT_FRAMES {
        phase
    } else {
        2 * WALK_OUT_FRAMES - phase
    }
}

/// The camera pose of frame `k`: the scene's camera walked [`walk_steps`]`(k)` steps along its
/// horizontal view direction and turned as many times by [`TURN_PER_FRAME`].
///
/// # Errors
/// If the turned pose is degenerate (a camera looking straight up or down cannot walk
/// horizontally: it walks along its own view direction then).
pub fn pose_at(scene: &Scene, k: usize) -> Result<ViewPose, AnalysisError> {
    let pose = scene.camera.pose;
    let bounds = scene.bounds();
    let radius = 0.5 * (bounds.max - bounds.min).length();
    let v = pose.forward();
    let horizontal = DVec3::new(v.x, 0.0, v.z);
    let walk = if horizontal.length() > 1e-6 {
        horizontal.normalize()
    } else {
        v
    };
    #[expect(clippy::cast_precision_loss, reason = "a step count")]
    let k = walk_steps(k) as f64;
    let turn = DQuat::from_rotation_y(TURN_PER_FRAME * k);
    let eye = pose.eye() + walk * (STEP_FRACTION * radius * k);
    Ok(ViewPose::look_to(eye, turn * v, turn * pose.up())
        .map_err(shadowlab_shadow::ShadowError::from)?)
}

/// One technique's stability over the walk.
#[derive(Clone, Debug, PartialEq)]
pub struct Stability {
    /// The technique.
    pub technique: Technique,
    /// Texel snapping (0: off; otherwise the grid in texels).
    pub snap_texels: u32,
    /// Shimmering pixels between each pair of consecutive frames (or why the technique is not
    /// defined for some frame).
    pub shimmer: Result<Vec<u64>, String>,
    /// Surface shimmer between each pair of consecutive frames: the second frame's visible points
    /// whose state in the first frame's maps differs from their state in its own; `None` where it
    /// was not measured (given set-ups).
    pub surface_shimmer: Option<Vec<u64>>,
}

/// Walks the camera over `frames` frames and counts each technique's shimmering pixels, with
/// snapping off and on (1 texel), every map looked up with `filter`.
///
/// # Errors
/// Truth and rendering errors other than a technique not being defined.
pub fn temporal(
    scene: &Scene,
    techniques: &[Technique],
    frames: usize,
    resolution: u32,
    filter: Filter,
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<Stability>, AnalysisError> {
    let bvh = Bvh::new(scene.mesh.positions(), scene.mesh.triangles())?;
    let variants: Vec<(Technique, u32)> =
        techniques.iter().flat_map(|t| [(*t, 0), (*t, 1)]).collect();
    let mut states: Vec<Result<Vec<Vec<Option<bool>>>, String>> =
        vec![Ok(Vec::new()); variants.len()];
    // Per variant, the previous frame's first light and the surface flips so far.
    let mut previous: Vec<Option<LightShadow>> = vec![None; variants.len()];
    let mut surface: Vec<Vec<u64>> = vec![Vec::new(); variants.len()];
    let mut truths = Vec::with_capacity(frames);
    for k in 0..frames {
        let mut moved = scene.clone();
        moved.camera.pose = pose_at(scene, k)?;
        let (eye, nearest_visible) = eye_pass(&moved)?;
        truths.push(exact_truth(&moved, &eye, &bvh)?.lit[0].clone());
        let view = scene_eye(&moved);
        for (v, (state, (technique, snap))) in states.iter_mut().zip(&variants).enumerate() {
            let Ok(history) = state else { continue };
            let options = FrameOptions {
                plan: PlanOptions::new(*technique),
                resolution,
                format: shadowlab_raster::DepthFormat::F32,
                lookup: Lookup::new(Bias::DEFAULT, filter),
                snap_texels: *snap,
            };
            match render_shadows(&moved, &options, &eye, nearest_visible, Some(&bvh)) {
                Ok(mut shadows) => {
                    let lit = &shadows.lit[0];
                    if let Some(before) = &previous[v] {
                        let then = lit_at(before, &view, &eye);
                        let flips = eye
                            .triangle
                            .iter()
                            .zip(lit.iter().zip(&then))
                            .filter(|(t, (now, then))| {
                                **t != NO_TRIANGLE
                                    && (**now >= LIT_THRESHOLD) != (**then >= LIT_THRESHOLD)
                            })
                            .count();
                        surface[v].push(flips as u64);
                    }
                    history.push(
                        eye.triangle
                            .iter()
                            .zip(lit)
                            .map(|(t, l)| (*t != NO_TRIANGLE).then_some(*l >= LIT_THRESHOLD))
                            .collect(),
                    );
                    previous[v] = Some(shadows.lights.swap_remove(0));
                }
                Err(e) => match e.undefined_reason() {
                    Some(reason) => *state = Err(reason),
                    None => return Err(e.into()),
                },
            }
        }
        progress(k + 1, frames);
    }
    Ok(states
        .into_iter()
        .zip(variants)
        .zip(surface)
        .map(|((state, (technique, snap_texels)), surface)| Stability {
            technique,
            snap_texels,
            surface_shimmer: state.is_ok().then_some(surface),
            shimmer: state.map(|history| {
                (1..history.len())
                    .map(|k| shimmer(&history[k - 1], &history[k], &truths[k - 1], &truths[k]))
                    .collect()
            }),
        })
        .collect())
}

/// Pixels seen in both frames whose truth is the same in both but whose shadow state flips.
pub(crate) fn shimmer(
    before: &[Option<bool>],
    after: &[Option<bool>],
    truth_before: &[Option<bool>],
    truth_after: &[Option<bool>],
) -> u64 {
    let mut count = 0;
    for k in 0..before.len() {
        if let (Some(a), Some(b), Some(ta), Some(tb)) =
            (before[k], after[k], truth_before[k], truth_after[k])
            && ta == tb
            && a != b
        {
            count += 1;
        }
    }
    count
}

/// The walk written out: `temporal.csv` (shimmering pixels per frame pair) and `temporal.md` (mean
/// and largest per technique, snapping off and on, naming the lookups' `filter`).
#[must_use]
pub fn write(scene: &str, filter: &Filter, stability: &[Stability]) -> Vec<(String, Vec<u8>)> {
    use std::fmt::Write as _;
    let label = crate::report::technique_label;
    let scene_field = crate::report::csv_field(scene);
    let filter = crate::labels::filter_label(filter);
    let mut csv =
        String::from("scene,technique,snap_texels,frame,shimmering_pixels,surface_shimmer\n");
    let mut md = format!(
        "# Temporal stability: `{scene}`\n\nThe camera walks {STEP_FRACTION} of the scene's radius and turns 0.1° per frame, and walks back the same way after {WALK_OUT_FRAMES} frames. A pixel shimmers (screen) when its shadow state flips between consecutive frames while the exact truth there does not. A surface point shimmers when its state in the previous frame's maps differs from its state in its own frame's maps: shadows crawling over still surfaces, which texel snapping is for. Every map is looked up with `{filter}`.\n\n| technique | snapping | screen: mean shimmering pixels per frame | largest | surface: mean | largest |\n|---|---|---:|---:|---:|---:|\n"
    );
    for s in stability {
        let snapping = if s.snap_texels == 0 {
            "off".to_string()
        } else {
            format!("{} texel", s.snap_texels)
        };
        match &s.shimmer {
            Ok(counts) => {
                let surface = s.surface_shimmer.as_deref();
                for (k, c) in counts.iter().enumerate() {
                    let on_surface = surface
                        .and_then(|s| s.get(k))
                        .map_or(String::new(), ToString::to_string);
                    writeln!(
                        csv,
                        "{scene_field},{},{},{},{c},{on_surface}",
                        label(s.technique),
                        s.snap_texels,
                        k + 1
                    )
                    .expect("writing to a string");
                }
                let (mean, largest) = mean_and_largest(counts);
                let surface = surface.map_or("| |".into(), |s| {
                    let (mean, largest) = mean_and_largest(s);
                    format!("{mean:.1} | {largest}")
                });
                writeln!(
                    md,
                    "| {} | {snapping} | {mean:.1} | {largest} | {surface} |",
                    label(s.technique)
                )
                .expect("writing to a string");
            }
            Err(reason) => {
                writeln!(
                    md,
                    "| {} | {snapping} | not defined: {reason} | | | |",
                    label(s.technique)
                )
                .expect("writing to a string");
            }
        }
    }
    vec![
        ("temporal.csv".into(), csv.into_bytes()),
        ("temporal.md".into(), md.into_bytes()),
    ]
}

/// The mean and the largest of per-frame counts (0 for none).
fn mean_and_largest(counts: &[u64]) -> (f64, u64) {
    #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
    let mean = counts.iter().sum::<u64>() as f64 / counts.len().max(1) as f64;
    (mean, counts.iter().max().copied().unwrap_or(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_walk_turns_back_and_repeats() {
        assert_eq!(walk_steps(0), 0);
        assert_eq!(walk_steps(WALK_OUT_FRAMES), WALK_OUT_FRAMES);
        assert_eq!(walk_steps(WALK_OUT_FRAMES + 1), WALK_OUT_FRAMES - 1);
        assert_eq!(walk_steps(2 * WALK_OUT_FRAMES), 0);
        let scene = shadowlab_scene::builtin_scene("outdoor").unwrap();
        for k in [0, 1, 17, WALK_OUT_FRAMES] {
            let pose = pose_at(&scene, k).unwrap();
            let again = pose_at(&scene, k + 2 * WALK_OUT_FRAMES).unwrap();
            assert_eq!(pose.eye(), again.eye());
            assert_eq!(pose.forward(), again.forward());
        }
        let steps = (0..10_000).map(walk_steps).max();
        assert_eq!(steps, Some(WALK_OUT_FRAMES));
    }
}
