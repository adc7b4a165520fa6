//! Golden frames: every built-in scene with every technique at a small size, hashed exactly.
//! `UPDATE_GOLDEN=1 cargo test -p shadowlab-shadow golden` rewrites `data/golden/shadow/frames.txt`
//! (review the diff: a change means every frame of that technique changed).
//!
//! The hash covers, per light, the lit fraction of every pixel quantised to 1/255 and the stored
//! f32 bits of every shadow-map texel: both are robust to a last-ulp difference in a libm function
//! (a quantised value flips only if it sits exactly on a boundary), so the hashes hold across the
//! machines CI runs on while any real change of a map or a lookup changes them.

use std::fmt::Write as _;
use std::path::PathBuf;

use shadowlab_raster::DepthFormat;
use shadowlab_scene::{BUILTIN_SCENES, builtin_scene};
use shadowlab_shadow::{
    Bias, Filter, FrameOptions, Lookup, PlanOptions, ShadowError, StepDirection, Technique,
    render_frame,
};

/// Eye image and shadow-map sizes of the golden frames.
const EYE: (u32, u32) = (160, 120);
const MAP: u32 = 256;

fn golden_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/golden/shadow/frames.txt")
}

/// FNV-1a, 64 bits.
fn fnv1a(bytes: impl IntoIterator<Item = u8>) -> u64 {
    bytes.into_iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

fn techniques() -> [Technique; 9] {
    [
        Technique::Uniform,
        Technique::UniformLimited,
        Technique::Psm,
        Technique::Lispsm(shadowlab_shadow::WarpChoice::PAPER),
        Technique::LOGARITHMIC,
        Technique::Logarithmic(shadowlab_shadow::LogarithmicChoice::Faces),
        Technique::Optimal(StepDirection::Paper),
        Technique::Cube,
        Technique::DualParaboloid,
    ]
}

/// One line per scene and technique: its hash, or why the technique is not defined there.
fn frames() -> String {
    let mut out = String::new();
    for name in BUILTIN_SCENES {
        let mut scene = builtin_scene(name).unwrap();
        (scene.camera.width, scene.camera.height) = EYE;
        for technique in techniques() {
            let options = FrameOptions {
                plan: PlanOptions::new(technique),
                resolution: MAP,
                format: DepthFormat::F32,
                lookup: Lookup::new(Bias::DEFAULT, Filter::Pcf { size: 3 }),
                snap_texels: 0,
            };
            let line = match render_frame(&scene, &options) {
                Ok(frame) => {
                    let mut bytes = Vec::new();
                    for (shadow, lit) in frame.lights.iter().zip(&frame.lit) {
                        #[expect(
                            clippy::cast_possible_truncation,
                            clippy::cast_sign_loss,
                            reason = "in [0, 255]"
                        )]
                        bytes.extend(lit.iter().map(|v| (v * 255.0).round() as u8));
                        for (_, map) in &shadow.maps {
                            #[expect(
                                clippy::cast_possible_truncation,
                                reason = "the f32 the map stores"
                            )]
                            bytes.extend(
                                map.nearest
                                    .iter()
                                    .flat_map(|d| (*d as f32).to_bits().to_le_bytes()),
                            );
                        }
                    }
                    format!("{:016x}", fnv1a(bytes))
                }
                Err(ShadowError::NotDefined { reason, .. }) => format!("not defined: {reason}"),
                Err(
                    e @ (ShadowError::UnservedLight { .. } | ShadowError::LightInsideFocusBody),
                ) => {
                    format!("not defined: {e}")
                }
                Err(e) => panic!("{name} with {technique}: {e}"),
            };
            let label = technique
                .parameter()
                .map_or(technique.key().to_string(), |p| {
                    format!("{}/{p}", technique.key())
                });
            writeln!(out, "{name} {label} {line}").unwrap();
        }
    }
    out
}

/// Claim: every built-in scene renders with every technique (or is refused with the documented
/// reason: not defined there, a light the technique cannot serve, the light inside PSM's body),
/// bit for bit as recorded.
#[test]
fn golden_frames_of_every_scene_and_technique() {
    let actual = frames();
    let path = golden_file();
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with UPDATE_GOLDEN=1)", path.display()));
    for (a, e) in actual.lines().zip(expected.lines()) {
        assert_eq!(a, e);
    }
    assert_eq!(actual.lines().count(), expected.lines().count());
}

/// Claim: a frame is the same on 1, 2 and 8 threads.
#[test]
fn frames_are_identical_on_any_thread_count() {
    let runs: Vec<String> = [1, 2, 8]
        .into_iter()
        .map(|threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(frames)
        })
        .collect();
    assert_eq!(runs[0], runs[1]);
    assert_eq!(runs[0], runs[2]);
}
