//! Every per-pixel result as files another program reads: the eye pass, the exact truth, each
//! combination's lookups and their classification, the texel footprints and every shadow map's raw
//! window depth — as NumPy arrays (`.npy`) and OpenEXR channels (`.exr`), each described in an
//! index ([`index`]) that names its quantity, type, shape and encoding.
//!
//! # Layout
//! Per-pixel arrays are the eye image's pixels: `.npy` files keep **row 0 at the bottom** (as the
//! eye image and `glReadPixels` have them; shape `(height, width)` or `(height, width, channels)`),
//! `.exr` files hold the same values **top row first**, as image viewers expect. Shadow maps are
//! `(side, side)` with texel row 0 at the bottom, the window's `y` (`ShadowMap::texel_of`).
//! Where an f64 quantity is exported, the `.npy` holds f64 and the `.exr` f32 (EXR has no f64).
//!
//! | file | what | type |
//! |---|---|---|
//! | `eye.exr` | channels `Z` (window depth), `P.X P.Y P.Z` (world position), `N.X N.Y N.Z` (unit normal), `triangle` (u32) | f32, u32 |
//! | `eye-depth.npy`, `eye-position.npy`, `eye-normal.npy` | the same, at full precision | f64 |
//! | `eye-triangle.npy` | the visible triangle; [`NO_TRIANGLE`] (2³²−1) where none | u32 |
//! | `truth-light{L}.npy` | the exact truth per light: [`SHADOWED`], [`LIT`], [`OUTSIDE_CONE`], [`NO_SURFACE`] | u8 |
//! | `{combination}/lit-light{L}.npy` | the lookup's lit fraction (NaN where no surface) | f32 |
//! | `{combination}/class-light{L}.npy` | [`CORRECT`], [`FALSELY_LIT`], [`FALSELY_SHADOWED`], [`NOT_JUDGED`] | u8 |
//! | `{combination}/footprint.npy`, `footprint.exr` | texel footprint: total, perspective, projection ([`crate::aliasing`]; first light; NaN where none) | f32 |
//! | `{combination}/map-light{L}-part{P}.npy`, `.exr` | the map's stored nearest window depth, decoded | f32 |
//!
//! A pixel counts as lit by a lookup when its fraction is at least [`LIT_THRESHOLD`], as
//! [`crate::classify`] counts it.

use serde_json::{Value, json};
use shadowlab_raster::image_out::{ExrLayer, NpyElement, array_npy, layers_exr};
use shadowlab_raster::{EyeImage, NO_TRIANGLE};
use shadowlab_shadow::LightShadow;

use crate::aliasing::{Footprint, FrameFootprints};
use crate::error::AnalysisError;
use crate::truth::LIT_THRESHOLD;
use crate::truth::Truth;

/// Truth code: the visible point is in shadow.
pub const SHADOWED: u8 = 0;
/// Truth code: the visible point is lit.
pub const LIT: u8 = 1;
/// Truth code: the visible point lies outside the spot light's cone (unlit by the cone; not
/// judged).
pub const OUTSIDE_CONE: u8 = 2;
/// Truth code: no surface is visible at the pixel.
pub const NO_SURFACE: u8 = 255;

/// Class code: the lookup agrees with the truth.
pub const CORRECT: u8 = 0;
/// Class code: lit by the lookup, in shadow in truth (a light leak).
pub const FALSELY_LIT: u8 = 1;
/// Class code: shadowed by the lookup, lit in truth (acne, over-shadowing).
pub const FALSELY_SHADOWED: u8 = 2;
/// Class code: not judged (no surface, or outside a spot light's cone).
pub const NOT_JUDGED: u8 = 255;

/// One exported file: its path in the output set, its bytes, and what the index says of it.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportFile {
    /// Path relative to the output set, `/`-separated.
    pub name: String,
    /// The file's contents.
    pub bytes: Vec<u8>,
    /// Its index entry: `what`, `type`, `shape`, and `codes` or `channels` where they apply.
    pub entry: Value,
}

/// The index of exported files: one entry per file, in order, with its name.
#[must_use]
pub fn index(files: &[ExportFile]) -> Value {
    Value::Array(
        files
            .iter()
            .map(|f| {
                let mut entry = f.entry.clone();
                entry["file"] = json!(f.name);
                entry
            })
            .collect(),
    )
}

/// A `.npy` file of per-pixel values with its index entry.
fn npy_file<T: NpyElement>(
    name: String,
    values: &[T],
    size: (u32, u32),
    channels: usize,
    entry: Value,
) -> Result<ExportFile, AnalysisError> {
    let (width, height) = size;
    let bytes = array_npy(values, width, height, channels)?;
    let mut entry = entry;
    entry["type"] = json!(T::DESCR);
    entry["shape"] = if channels == 1 {
        json!([height, width])
    } else {
        json!([height, width, channels])
    };
    entry["rows"] = json!("row 0 at the bottom");
    Ok(ExportFile { name, bytes, entry })
}

/// An `.exr` file of named channels with its index entry.
fn exr_file(
    name: String,
    layers: &[(&str, ExrLayer<'_>)],
    size: (u32, u32),
    what: &str,
) -> Result<ExportFile, AnalysisError> {
    let (width, height) = size;
    let bytes = layers_exr(layers, width, height)?;
    let channels: Vec<&str> = layers.iter().map(|(name, _)| *name).collect();
    Ok(ExportFile {
        name,
        bytes,
        entry: json!({
            "what": what,
            "channels": channels,
            "shape": [height, width],
            "rows": "top row first",
        }),
    })
}

/// `values` rounded to f32.
#[expect(clippy::cast_possible_truncation, reason = "the EXR channels are f32")]
fn to_f32(values: impl Iterator<Item = f64>) -> Vec<f32> {
    values.map(|v| v as f32).collect()
}

/// The eye pass: `eye.exr` and `eye-{depth,position,normal,triangle}.npy`.
///
/// # Errors
/// [`AnalysisError::Raster`] if the eye image's vectors do not fill its size.
pub fn eye_files(eye: &EyeImage) -> Result<Vec<ExportFile>, AnalysisError> {
    let size = (eye.width, eye.height);
    let axis = |v: &[glam::DVec3], k: usize| to_f32(v.iter().map(|p| p[k]));
    let depth = to_f32(eye.depth.iter().copied());
    let position = [0, 1, 2].map(|k| axis(&eye.position, k));
    let normal = [0, 1, 2].map(|k| axis(&eye.normal, k));
    let exr = exr_file(
        "eye.exr".into(),
        &[
            ("Z", ExrLayer::F32(&depth)),
            ("P.X", ExrLayer::F32(&position[0])),
            ("P.Y", ExrLayer::F32(&position[1])),
            ("P.Z", ExrLayer::F32(&position[2])),
            ("N.X", ExrLayer::F32(&normal[0])),
            ("N.Y", ExrLayer::F32(&normal[1])),
            ("N.Z", ExrLayer::F32(&normal[2])),
            ("triangle", ExrLayer::U32(&eye.triangle)),
        ],
        size,
        "the eye pass: window depth Z, world position P, unit world normal N, visible triangle",
    )?;
    let flat = |v: &[glam::DVec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
    Ok(vec![
        exr,
        npy_file(
            "eye-depth.npy".into(),
            &eye.depth,
            size,
            1,
            json!({"what": "the eye pass's window depth (1 where nothing is visible)"}),
        )?,
        npy_file(
            "eye-position.npy".into(),
            &flat(&eye.position),
            size,
            3,
            json!({
                "what": "world position of the visible point at the pixel centre (0 where none)"
            }),
        )?,
        npy_file(
            "eye-normal.npy".into(),
            &flat(&eye.normal),
            size,
            3,
            json!({"what": "unit world normal of the visible point (0 where none)"}),
        )?,
        npy_file(
            "eye-triangle.npy".into(),
            &eye.triangle,
            size,
            1,
            json!({
                "what": "the visible triangle's index in the scene's mesh",
                "codes": {"no surface": NO_TRIANGLE},
            }),
        )?,
    ])
}

/// The exact truth per light: `truth-light{L}.npy`.
///
/// # Errors
/// [`AnalysisError::Raster`] if the truth does not fill the eye image's size.
pub fn truth_files(truth: &Truth, eye: &EyeImage) -> Result<Vec<ExportFile>, AnalysisError> {
    let size = (eye.width, eye.height);
    truth
        .lit
        .iter()
        .zip(&truth.outside_cone)
        .enumerate()
        .map(|(light, (lit, outside))| {
            let codes: Vec<u8> = lit
                .iter()
                .zip(outside)
                .map(|(lit, outside)| match (lit, outside) {
                    (None, _) => NO_SURFACE,
                    (Some(_), true) => OUTSIDE_CONE,
                    (Some(true), false) => LIT,
                    (Some(false), false) => SHADOWED,
                })
                .collect();
            npy_file(
                format!("truth-light{light}.npy"),
                &codes,
                size,
                1,
                json!({
                    "what": format!("the exact truth for light {light} (one shadow ray per pixel)"),
                    "codes": {
                        "shadowed": SHADOWED,
                        "lit": LIT,
                        "outside the cone": OUTSIDE_CONE,
                        "no surface": NO_SURFACE,
                    },
                }),
            )
        })
        .collect()
}

/// The class of one judged pair.
fn class(truth: Option<bool>, outside_cone: bool, fraction: f64) -> u8 {
    match (truth, outside_cone) {
        (None, _) | (Some(_), true) => NOT_JUDGED,
        (Some(truly_lit), false) => match (fraction >= LIT_THRESHOLD, truly_lit) {
            (true, false) => FALSELY_LIT,
            (false, true) => FALSELY_SHADOWED,
            _ => CORRECT,
        },
    }
}

/// One combination's shadows under the directory `combination`: per light its lookups' lit
/// fractions and their classification against `truth`, the footprints (first light), and every
/// map's raw window depth.
///
/// # Errors
/// [`AnalysisError::Raster`] if a vector does not fill its image's size.
pub fn shadow_files(
    combination: &str,
    truth: &Truth,
    eye: &EyeImage,
    lights: &[LightShadow],
    lit: &[Vec<f64>],
    footprints: &FrameFootprints,
) -> Result<Vec<ExportFile>, AnalysisError> {
    let size = (eye.width, eye.height);
    let mut files = Vec::new();
    for (light, fractions) in lit.iter().enumerate() {
        let shown = to_f32(
            fractions.iter().zip(&eye.triangle).map(
                |(&f, &t)| {
                    if t == NO_TRIANGLE { f64::NAN } else { f }
                },
            ),
        );
        files.push(npy_file(
            format!("{combination}/lit-light{light}.npy"),
            &shown,
            size,
            1,
            json!({
                "what": format!(
                    "the lookup's lit fraction for light {light} (1 lit, 0 shadowed; NaN where \
                     no surface)"
                )
            }),
        )?);
        let classes: Vec<u8> = fractions
            .iter()
            .enumerate()
            .map(|(pixel, &f)| {
                let (truly, outside) = (
                    truth
                        .lit
                        .get(light)
                        .and_then(|t| t.get(pixel))
                        .copied()
                        .flatten(),
                    truth
                        .outside_cone
                        .get(light)
                        .and_then(|o| o.get(pixel))
                        .copied()
                        .unwrap_or(false),
                );
                class(truly, outside, f)
            })
            .collect();
        files.push(npy_file(
            format!("{combination}/class-light{light}.npy"),
            &classes,
            size,
            1,
            json!({
                "what": format!(
                    "the lookup against the exact truth for light {light}, lit where the \
                     fraction is at least {LIT_THRESHOLD}"
                ),
                "codes": {
                    "correct": CORRECT,
                    "falsely lit": FALSELY_LIT,
                    "falsely shadowed": FALSELY_SHADOWED,
                    "not judged": NOT_JUDGED,
                },
            }),
        )?);
    }
    let part = |f: fn(&Footprint) -> f64| {
        to_f32(
            footprints
                .each_pixel()
                .map(|p| p.as_ref().map_or(f64::NAN, f)),
        )
    };
    let [total, perspective, projection] = [
        part(|f| f.total),
        part(|f| f.perspective),
        part(|f| f.projection),
    ];
    files.push(exr_file(
        format!("{combination}/footprint.exr"),
        &[
            ("total", ExrLayer::F32(&total)),
            ("perspective", ExrLayer::F32(&perspective)),
            ("projection", ExrLayer::F32(&projection)),
        ],
        size,
        "texel footprint on screen, pixels per texel (first light): total = perspective × \
         projection; NaN where none",
    )?);
    let interleaved: Vec<f32> = (0..total.len())
        .flat_map(|p| [total[p], perspective[p], projection[p]])
        .collect();
    files.push(npy_file(
        format!("{combination}/footprint.npy"),
        &interleaved,
        size,
        3,
        json!({
            "what": "texel footprint (first light), channels total, perspective, projection; \
                     NaN where none"
        }),
    )?);
    for (light, shadow) in lights.iter().enumerate() {
        for (part, (_, map)) in shadow.maps.iter().enumerate() {
            let side = (map.resolution, map.resolution);
            let depth = to_f32(map.nearest.iter().copied());
            let what = format!(
                "light {light}, partition {part}: the map's nearest window depth as stored ({}), \
                 decoded; texel row 0 at the bottom",
                map.format.key_name()
            );
            files.push(exr_file(
                format!("{combination}/map-light{light}-part{part}.exr"),
                &[("Z", ExrLayer::F32(&depth))],
                side,
                &what,
            )?);
            files.push(npy_file(
                format!("{combination}/map-light{light}-part{part}.npy"),
                &depth,
                side,
                1,
                json!({"what": what}),
            )?);
        }
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pair_is_classified_as_the_counts_count_it() {
        assert_eq!(class(Some(true), false, 1.0), CORRECT);
        assert_eq!(class(Some(false), false, 0.0), CORRECT);
        assert_eq!(class(Some(false), false, LIT_THRESHOLD), FALSELY_LIT);
        assert_eq!(class(Some(true), false, 0.49), FALSELY_SHADOWED);
        assert_eq!(class(Some(true), true, 0.0), NOT_JUDGED);
        assert_eq!(class(None, false, 1.0), NOT_JUDGED);
    }
}
