//! `shadowlab._native` maps and measurements: planning, shadow maps, the eye pass, the exact truth
//! and whole analyses, each the same computation (and the same bits) as the command-line tool's.

use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shadowlab_analysis::report::{filter_label, results_json, technique_label};
use shadowlab_analysis::study::{self, Setting, StudyOptions, default_techniques};
use shadowlab_analysis::truth::{exact_truth, scene_bvh};
use shadowlab_raster::{DepthFormat, EyeImage, NO_TRIANGLE};
use shadowlab_shadow::{
    Bias, Filter, FocusPolicy, FrameOptions, Lookup, Partition, PlanOptions, ShadowMapping, Splits,
    Technique, eye_pass as shadow_eye_pass, plan_frame, render_shadows,
};

use crate::arrays::{matrix, vectors};
use crate::scene::Scene;

/// A `ValueError` naming `what`.
fn bad(what: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{what}: {message}"))
}

/// The frame options of the keyword arguments shared by [`plan`] and [`render_map`].
fn frame_options(
    technique: &str,
    resolution: u32,
    partitions: usize,
    focus: &str,
    format: &str,
    bias: &str,
    filter: &str,
) -> PyResult<FrameOptions> {
    let technique = Technique::parse_spec(technique).map_err(|e| bad("technique", e))?;
    if !(1..=shadowlab_raster::MAX_TARGET_SIZE).contains(&resolution) {
        return Err(bad(
            "resolution",
            format!(
                "{resolution} must lie in 1..={}",
                shadowlab_raster::MAX_TARGET_SIZE
            ),
        ));
    }
    if partitions == 0 {
        return Err(bad("partitions", "must be at least 1"));
    }
    Ok(FrameOptions {
        plan: PlanOptions {
            partitions,
            focus: FocusPolicy::parse(focus).map_err(|e| bad("focus", e))?,
            ..PlanOptions::new(technique)
        },
        resolution,
        format: DepthFormat::parse(format).map_err(|e| bad("format", e))?,
        lookup: Lookup::new(
            Bias::parse(bias).map_err(|e| bad("bias", e))?,
            Filter::parse(filter).map_err(|e| bad("filter", e))?,
        ),
        snap_texels: 0,
    })
}

/// A planning or rendering error: a bad configuration for the scene is a `ValueError`.
fn shadow_error(error: &shadowlab_shadow::ShadowError) -> PyErr {
    PyValueError::new_err(error.to_string())
}

/// Per light, per partition, what the technique decided: the partition's eye depths and face,
/// γ and φ (radians), λ and n where it warps, PSM's decisions, the focus body's vertices (K × 3)
/// and the view and projection matrices (4 × 4, GL clip space; `None` for the non-projective
/// logarithmic and paraboloid maps).
#[pyfunction]
#[pyo3(signature = (scene, technique, resolution=1024, partitions=1, focus="light"))]
pub(crate) fn plan<'py>(
    py: Python<'py>,
    scene: &Scene,
    technique: &str,
    resolution: u32,
    partitions: usize,
    focus: &str,
) -> PyResult<Vec<Vec<Bound<'py, PyDict>>>> {
    let options = frame_options(
        technique,
        resolution,
        partitions,
        focus,
        "f32",
        "slope:2,1e-5",
        "nearest",
    )?;
    let scene = &scene.inner;
    let planned = py
        .detach(|| {
            let (eye, nearest) = shadow_eye_pass(scene)?;
            plan_frame(scene, &options, nearest, Some(&eye))
        })
        .map_err(|e| shadow_error(&e))?;
    planned
        .iter()
        .map(|light| light.iter().map(|p| partition_dict(py, p)).collect())
        .collect()
}

fn partition_dict<'py>(py: Python<'py>, partition: &Partition) -> PyResult<Bound<'py, PyDict>> {
    let setup = &partition.setup;
    let dict = PyDict::new(py);
    dict.set_item("near", partition.near)?;
    dict.set_item("far", partition.far)?;
    dict.set_item("face", partition.face.as_ref().map(|f| f.name()))?;
    dict.set_item("technique", setup.technique.to_string())?;
    dict.set_item("gamma", setup.gamma)?;
    dict.set_item("half_fov", setup.half_fov)?;
    dict.set_item("lam", setup.warp.as_ref().map(|w| w.lambda))?;
    dict.set_item("n", setup.warp.as_ref().map(|w| w.near_distance))?;
    dict.set_item(
        "psm",
        setup.psm.map(|p| {
            [
                ("shift", p.shift),
                ("near", p.near),
                ("inverted", f64::from(u8::from(p.inverted))),
                ("directional", f64::from(u8::from(p.directional))),
            ]
        }),
    )?;
    dict.set_item("focus_body", vectors(py, &setup.focus_body))?;
    let (view, projection) = match &setup.mapping {
        ShadowMapping::Projective(m) => (
            Some(matrix(py, &m.view())?),
            Some(matrix(py, &m.projection())?),
        ),
        ShadowMapping::Logarithmic(_) | ShadowMapping::Paraboloid(_) => (None, None),
    };
    dict.set_item("view", view)?;
    dict.set_item("projection", projection)?;
    Ok(dict)
}

/// The shadow map of partition `partition` of light `light`: window depths in [0, 1] (1 where
/// nothing is stored), `resolution × resolution`, row 0 at the bottom — rendered exactly as
/// `shadowlab render` renders it.
#[pyfunction]
#[pyo3(signature = (scene, technique, resolution=1024, light=0, partition=0, partitions=1, focus="light", format="f32"))]
#[expect(
    clippy::too_many_arguments,
    reason = "keyword arguments, each with its default"
)]
pub(crate) fn render_map<'py>(
    py: Python<'py>,
    scene: &Scene,
    technique: &str,
    resolution: u32,
    light: usize,
    partition: usize,
    partitions: usize,
    focus: &str,
    format: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let options = frame_options(
        technique,
        resolution,
        partitions,
        focus,
        format,
        "slope:2,1e-5",
        "nearest",
    )?;
    let scene = &scene.inner;
    if light >= scene.lights.len() {
        return Err(bad(
            "light",
            format!("the scene has {} light(s)", scene.lights.len()),
        ));
    }
    let shadows = py
        .detach(|| {
            let (eye, nearest) = shadow_eye_pass(scene)?;
            render_shadows(scene, &options, &eye, nearest, None)
        })
        .map_err(|e| shadow_error(&e))?;
    let maps = &shadows.lights[light].maps;
    let (_, map) = maps.get(partition).ok_or_else(|| {
        bad(
            "partition",
            format!("light {light} has {} map(s)", maps.len()),
        )
    })?;
    let side = map.resolution as usize;
    PyArray1::from_vec(py, map.nearest.clone()).reshape([side, side])
}

/// The eye pass of the scene's camera: `depth` (H × W window depth, 1 where nothing is seen),
/// `triangle` (H × W, −1 where nothing is seen), `position` and `normal` (H × W × 3, world space,
/// zero where nothing is seen); row 0 at the bottom, as every shadowlab image.
#[pyfunction]
pub(crate) fn eye_pass<'py>(py: Python<'py>, scene: &Scene) -> PyResult<Bound<'py, PyDict>> {
    let scene = &scene.inner;
    let (image, _) = py
        .detach(|| shadow_eye_pass(scene))
        .map_err(|e| shadow_error(&e))?;
    eye_dict(py, &image)
}

fn eye_dict<'py>(py: Python<'py>, image: &EyeImage) -> PyResult<Bound<'py, PyDict>> {
    let (w, h) = (image.width as usize, image.height as usize);
    let dict = PyDict::new(py);
    dict.set_item(
        "depth",
        PyArray1::from_slice(py, &image.depth).reshape([h, w])?,
    )?;
    dict.set_item(
        "triangle",
        PyArray1::from_iter(
            py,
            image
                .triangle
                .iter()
                .map(|&t| if t == NO_TRIANGLE { -1 } else { i64::from(t) }),
        )
        .reshape([h, w])?,
    )?;
    let three = |values: &[glam::DVec3]| -> PyResult<Bound<'py, PyArray3<f64>>> {
        let flat: Vec<f64> = values.iter().flat_map(|v| v.to_array()).collect();
        PyArray1::from_vec(py, flat).reshape([h, w, 3])
    };
    dict.set_item("position", three(&image.position)?)?;
    dict.set_item("normal", three(&image.normal)?)?;
    Ok(dict)
}

/// The truth's arrays: lit per light and pixel, and the visible pixels.
type TruthArrays<'py> = (Bound<'py, PyArray3<bool>>, Bound<'py, PyArray2<bool>>);

/// The exact truth: per light, whether each pixel's visible point is lit (one f64 shadow ray per
/// visible pixel), `lights × H × W` booleans (false where nothing is seen), and the `visible` mask
/// (H × W).
#[pyfunction]
pub(crate) fn truth<'py>(py: Python<'py>, scene: &Scene) -> PyResult<TruthArrays<'py>> {
    let scene = &scene.inner;
    let (image, truth) = py
        .detach(|| -> Result<_, String> {
            let (image, _) = shadow_eye_pass(scene).map_err(|e| e.to_string())?;
            let bvh = scene_bvh(scene).map_err(|e| e.to_string())?;
            let truth = exact_truth(scene, &image, &bvh).map_err(|e| e.to_string())?;
            Ok((image, truth))
        })
        .map_err(PyRuntimeError::new_err)?;
    let (w, h) = (image.width as usize, image.height as usize);
    let lit: Vec<bool> = truth
        .lit
        .iter()
        .flat_map(|light| light.iter().map(|l| l.unwrap_or(false)))
        .collect();
    let visible: Vec<bool> = image.triangle.iter().map(|&t| t != NO_TRIANGLE).collect();
    Ok((
        PyArray1::from_vec(py, lit).reshape([truth.lit.len(), h, w])?,
        PyArray1::from_vec(py, visible).reshape([h, w])?,
    ))
}

/// A whole analysis, as `shadowlab analyze` makes it (without pictures): every combination of
/// `techniques` (default: the command's, by the scene's lights), `resolutions`, `partitions` and
/// `filters`, against the exact truth; returns `results.json`'s text, which the Python package
/// parses (the same document the command writes).
#[pyfunction]
#[pyo3(signature = (scene, techniques=None, resolutions=None, partitions=None, filters=None, splits="practical:0.5", bias="slope:2,1e-5", focus="light", timing_runs=study::DEFAULT_TIMING_RUNS, pixels=false))]
#[expect(
    clippy::too_many_arguments,
    reason = "keyword arguments, each with its default"
)]
pub(crate) fn analyze<'py>(
    py: Python<'py>,
    scene: &Scene,
    techniques: Option<Vec<String>>,
    resolutions: Option<Vec<u32>>,
    partitions: Option<Vec<usize>>,
    filters: Option<Vec<String>>,
    splits: &str,
    bias: &str,
    focus: &str,
    timing_runs: usize,
    pixels: bool,
) -> PyResult<(String, Vec<PixelArrays<'py>>)> {
    let scene = &scene.inner;
    let techniques = match techniques {
        Some(specs) => specs
            .iter()
            .map(|s| Technique::parse_spec(s).map_err(|e| bad("techniques", e)))
            .collect::<PyResult<Vec<_>>>()?,
        None => default_techniques(scene, study::DEFAULT_TECHNIQUES),
    };
    let filters = filters
        .unwrap_or_else(|| vec!["nearest".to_owned()])
        .iter()
        .map(|s| Filter::parse(s).map_err(|e| bad("filters", e)))
        .collect::<PyResult<Vec<_>>>()?;
    if timing_runs == 0 {
        return Err(bad("timing_runs", "must be at least 1"));
    }
    let options = StudyOptions {
        techniques,
        resolutions: resolutions.unwrap_or_else(|| study::DEFAULT_RESOLUTIONS.to_vec()),
        partitions: partitions.unwrap_or_else(|| vec![1]),
        splits: Splits::parse(splits).map_err(|e| bad("splits", e))?,
        filters,
        bias: Bias::parse(bias).map_err(|e| bad("bias", e))?,
        format: DepthFormat::F32,
        map_truth: false,
        pictures_at: None,
        optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
        focus: FocusPolicy::parse(focus).map_err(|e| bad("focus", e))?,
        timing_runs,
    };
    // Per combination, when asked for: each light's lit fraction per pixel and the footprint per
    // pixel, kept as the study shows them (`study::run_observed`) before it lets them go.
    let mut kept: Vec<(Setting, Vec<Vec<f64>>, Vec<f64>)> = Vec::new();
    let study = py
        .detach(|| {
            study::run_observed(
                scene,
                &options,
                |_, _, _| {},
                |observed| -> Result<(), shadowlab_analysis::AnalysisError> {
                    if pixels {
                        let footprints = observed
                            .footprints
                            .each_pixel()
                            .map(|f| f.map_or(f64::NAN, |f| f.total))
                            .collect();
                        kept.push((
                            observed.setting.clone(),
                            observed.shadows.lit.clone(),
                            footprints,
                        ));
                    }
                    Ok(())
                },
            )
        })
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let (w, h) = (scene.camera.width as usize, scene.camera.height as usize);
    let arrays = kept
        .into_iter()
        .map(|(setting, lit, footprint)| {
            let lights = lit.len();
            Ok((
                technique_label(setting.technique),
                setting.resolution,
                setting.partitions,
                filter_label(&setting.filter),
                PyArray1::from_vec(py, lit.concat()).reshape([lights, h, w])?,
                PyArray1::from_vec(py, footprint).reshape([h, w])?,
            ))
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((
        serde_json::to_string(&results_json(&study)).expect("plain data"),
        arrays,
    ))
}

/// One combination's per-pixel results: its technique, side, partitions and filter (as
/// `results.json` labels them), each light's lit fraction per pixel (lights × H × W; 1 where
/// nothing is seen), and the texel footprint per pixel (H × W, pixels per texel; NaN where nothing
/// is seen or the map has no derivative there).
type PixelArrays<'py> = (
    String,
    u32,
    usize,
    String,
    Bound<'py, PyArray3<f64>>,
    Bound<'py, PyArray2<f64>>,
);
