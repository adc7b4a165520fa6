//! `--export` (render, analyze, evaluate): every per-pixel result beside the pictures, under `export/` in
//! the output set ([`shadowlab_analysis::export`] says what each file holds), with its index
//! `export/index.json`.

use serde_json::{Value, json};
use shadowlab_analysis::export::{ExportFile, eye_files, index, shadow_files, truth_files};
use shadowlab_analysis::report::{filter_label, technique_label};
use shadowlab_analysis::setup_file::{SetupError, setup_for};
use shadowlab_analysis::study::Setting;
use shadowlab_analysis::truth::Truth;
use shadowlab_analysis::{AnalysisError, aliasing::FrameFootprints};
use shadowlab_raster::EyeImage;
use shadowlab_scene::{Scene, export_glb, export_obj};
use shadowlab_shadow::{FrameOptions, LightShadow};

use crate::error::CliError;
use crate::output::{OutputSet, slug};

/// The directory of the exports inside an output set.
pub(crate) const EXPORT_DIR: &str = "export";

/// An upper bound of the bytes the exports of `combinations` combinations take, each with `maps`
/// maps of at most `largest_map`² texels, for the free-space check: per pixel the eye pass (EXR
/// f32 ×7 + u32, NPY f64 ×7 + u32), the truth (1 byte per light), per combination the lookups
/// (5 bytes per light) and footprints (12 bytes twice); per texel 4 bytes twice; plus headers.
pub(crate) fn bound(scene: &Scene, combinations: u64, maps: u64, largest_map: u32) -> u64 {
    let pixels = u64::from(scene.camera.width) * u64::from(scene.camera.height);
    let lights = scene.lights.len() as u64;
    let texels = u64::from(largest_map) * u64::from(largest_map);
    let eye = pixels * (7 * 4 + 4 + 7 * 8 + 4) + pixels * lights;
    let per_combination = pixels * (5 * lights + 24) + maps * lights * texels * 8;
    let headers = 4096 * (8 + combinations * (4 + 2 * maps * lights));
    eye.saturating_add(combinations.saturating_mul(per_combination))
        .saturating_add(headers)
}

/// The directory of one combination's exports: technique, resolution, partitions and filter.
pub(crate) fn combination_dir(setting: &Setting) -> String {
    slug(
        &format!(
            "{}-{}-{}p-{}",
            technique_label(setting.technique),
            setting.resolution,
            setting.partitions,
            filter_label(&setting.filter)
        ),
        "combination",
    )
}

/// Writes exports into a staged output set as they come, keeping their index.
pub(crate) struct Exporter {
    entries: Vec<ExportFile>,
}

impl Exporter {
    pub(crate) fn new() -> Self {
        Self {
            entries: Vec::new(),
        }
    }

    /// Adds `files` (named inside [`EXPORT_DIR`]) to `set`, keeping only their index entries.
    fn add(&mut self, set: &mut OutputSet<'_>, files: Vec<ExportFile>) -> Result<(), CliError> {
        for mut file in files {
            file.name = format!("{EXPORT_DIR}/{}", file.name);
            set.add(&file.name, &file.bytes)?;
            file.bytes = Vec::new();
            self.entries.push(file);
        }
        Ok(())
    }

    /// The eye pass and the exact truth, in `dir` (`""`, or a frame's directory ending in `/`).
    pub(crate) fn add_frame(
        &mut self,
        set: &mut OutputSet<'_>,
        dir: &str,
        eye: &EyeImage,
        truth: &Truth,
    ) -> Result<(), CliError> {
        let mut files = eye_files(eye).map_err(failure)?;
        files.extend(truth_files(truth, eye).map_err(failure)?);
        for file in &mut files {
            file.name.insert_str(0, dir);
        }
        self.add(set, files)
    }

    /// The assembled scene — world-space geometry, camera and lights — as `scene.glb` (f32, as
    /// glTF stores it) and `scene.obj` (every f64, camera and lights in its comment header), so
    /// another renderer reproduces the frame.
    pub(crate) fn add_scene(
        &mut self,
        set: &mut OutputSet<'_>,
        scene: &Scene,
    ) -> Result<(), CliError> {
        let glb = export_glb(scene)
            .map_err(|e| CliError::Input(format!("--export: {}: {e}", scene.name)))?;
        self.add(
            set,
            vec![
                ExportFile {
                    name: "scene.glb".into(),
                    bytes: glb,
                    entry: json!({"what": "the scene in world space with its camera and lights \
                        (KHR_lights_punctual), positions rounded to f32 as glTF stores them"}),
                },
                ExportFile {
                    name: "scene.obj".into(),
                    bytes: export_obj(scene).into_bytes(),
                    entry: json!({"what": "the scene's geometry in world space at full f64 \
                        precision; camera and lights in the comment header"}),
                },
            ],
        )
    }

    /// The set-up of one combination (`{combination}/setup.json`, docs/setup-format.md): its
    /// matrices per light and partition, which `evaluate --setup` reads; nothing for a technique
    /// that is not a matrix per partition (the logarithmic map).
    pub(crate) fn add_setup(
        &mut self,
        set: &mut OutputSet<'_>,
        combination: &str,
        scene: &Scene,
        options: &FrameOptions,
    ) -> Result<(), CliError> {
        match setup_for(scene, options) {
            Ok(setup) => self.add(
                set,
                vec![ExportFile {
                    name: format!("{combination}/setup.json"),
                    bytes: setup.to_json().into_bytes(),
                    entry: json!({"what": "the combination's shadow set-up: per light and \
                        partition its view and projection matrices, depth range, map size, \
                        format, bias and filter (docs/setup-format.md)"}),
                }],
            ),
            Err(SetupError::NotRepresentable { .. }) => Ok(()),
            Err(e) => Err(CliError::Failure(anyhow::anyhow!("--export: {e}"))),
        }
    }

    /// One combination's lookups, classes, footprints and maps under `combination`.
    pub(crate) fn add_shadows(
        &mut self,
        set: &mut OutputSet<'_>,
        combination: &str,
        (eye, truth): (&EyeImage, &Truth),
        (lights, lit): (&[LightShadow], &[Vec<f64>]),
        footprints: &FrameFootprints,
    ) -> Result<(), CliError> {
        let files =
            shadow_files(combination, truth, eye, lights, lit, footprints).map_err(failure)?;
        self.add(set, files)
    }

    /// The index of everything exported so far.
    pub(crate) fn index(&self) -> Value {
        index(&self.entries)
    }

    /// Writes `export/index.json`: the files with their quantities, types and shapes, and the
    /// conventions.
    pub(crate) fn finish(self, set: &mut OutputSet<'_>) -> Result<(), CliError> {
        let document = json!({
            "conventions": "npy: row 0 at the bottom (as the eye image and glReadPixels); exr: top \
                            row first; see shadowlab_analysis::export",
            "files": self.index(),
        });
        let bytes = serde_json::to_vec_pretty(&document).map_err(|e| {
            CliError::Failure(anyhow::anyhow!("cannot encode the export index: {e}"))
        })?;
        set.add(&format!("{EXPORT_DIR}/index.json"), &bytes)
    }
}

/// `results.json` with the exports' index added as `"exports"`.
pub(crate) fn with_exports(json: &str, index: serde_json::Value) -> Result<String, CliError> {
    let mut value: serde_json::Value = serde_json::from_str(json)
        .map_err(|e| CliError::Failure(anyhow::anyhow!("results.json: {e}")))?;
    value["exports"] = index;
    serde_json::to_string_pretty(&value)
        .map_err(|e| CliError::Failure(anyhow::anyhow!("results.json: {e}")))
}

/// An export that cannot be encoded is an internal failure (the sizes come from the library).
fn failure(error: AnalysisError) -> CliError {
    CliError::Failure(anyhow::anyhow!("cannot encode an export: {error}"))
}
