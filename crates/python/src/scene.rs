//! `shadowlab._native` scenes: a [`Scene`] built in, read from a file, or made of arrays, and its
//! parts as arrays.

use std::path::PathBuf;

use glam::DVec3;
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};

use crate::arrays::{matrix, vectors};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shadowlab_hull::{Perspective, ViewPose};
use shadowlab_scene::{
    BUILTIN_SCENES, Camera, Mesh, SceneLight, ShadowSettings, builtin_scene, load_scene,
    parse_scene,
};

/// A scene: its mesh, camera and lights (`shadowlab_scene::Scene`).
#[pyclass(module = "shadowlab._native", name = "Scene", frozen)]
pub(crate) struct Scene {
    pub(crate) inner: shadowlab_scene::Scene,
}

/// A `ValueError` with `message` about `what`.
fn bad(what: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{what}: {message}"))
}

/// A 3-vector from a Python sequence of three numbers.
fn vector(what: &str, value: &Bound<'_, PyAny>) -> PyResult<DVec3> {
    let [x, y, z]: [f64; 3] = value
        .extract()
        .map_err(|_| bad(what, "must be three numbers"))?;
    Ok(DVec3::new(x, y, z))
}

/// `dict[key]`, extracted, or `default` if absent.
fn field<'py, T: FromPyObjectOwned<'py>>(
    dict: &Bound<'py, PyDict>,
    what: &str,
    key: &str,
    default: Option<T>,
) -> PyResult<T> {
    match dict.get_item(key)? {
        Some(value) => value
            .extract()
            .map_err(|_| bad(&format!("{what}.{key}"), "has the wrong type")),
        None => default.ok_or_else(|| bad(&format!("{what}.{key}"), "is required")),
    }
}

#[pymethods]
impl Scene {
    /// The built-in scene `name` (`outdoor`, `dueling-frusta`, `cad-lattice`, `chess-spot`,
    /// `bunny`, `room-point`, `chess-point`).
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        builtin_scene(name)
            .map(|inner| Self { inner })
            .map_err(|e| bad("name", e))
    }

    /// The names of the built-in scenes.
    #[staticmethod]
    fn builtin_names() -> Vec<&'static str> {
        BUILTIN_SCENES.to_vec()
    }

    /// The scene of a TOML scene file, a glTF 2.0 file (`.gltf`, `.glb`) or an OBJ file (the
    /// mesh alone, with the scene files' default camera and sun, as a scene file naming only
    /// `[[mesh]] obj = PATH` has them).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let is_obj = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
        let scene = if is_obj {
            let quoted = toml::Value::String(path.to_string_lossy().into_owned());
            let text = format!("[[mesh]]\nobj = {quoted}\n");
            parse_scene(&text, &path)
        } else {
            load_scene(&path)
        };
        scene
            .map(|inner| Self { inner })
            .map_err(|e| bad("path", e))
    }

    /// A scene of arrays: `positions` (N × 3), `indices` (M × 3, counter-clockwise), a `camera`
    /// dict (`eye`, `target`, `near`, `far`; optional `up` = +y, `fov_degrees` = 60, `width` = 640,
    /// `height` = 480) and `lights`, a list of dicts: `{"kind": "directional", "direction": d}`
    /// (the direction light travels), `{"kind": "spot", "position", "target", "cone_degrees",
    /// "near", "far"}` or `{"kind": "point", "position", "range"}` (range optional).
    #[staticmethod]
    #[pyo3(signature = (positions, indices, camera, lights, name="arrays"))]
    fn from_arrays(
        positions: PyReadonlyArray2<'_, f64>,
        indices: PyReadonlyArray2<'_, i64>,
        camera: &Bound<'_, PyDict>,
        lights: Vec<Bound<'_, PyDict>>,
        name: &str,
    ) -> PyResult<Self> {
        let positions = rows::<f64>(&positions, "positions")?
            .into_iter()
            .map(|[x, y, z]| DVec3::new(x, y, z))
            .collect();
        let triangles = rows::<i64>(&indices, "indices")?
            .into_iter()
            .map(|t| {
                t.map(|k| {
                    u32::try_from(k).map_err(|_| bad("indices", format!("{k} is not an index")))
                })
            })
            .map(|[a, b, c]| Ok([a?, b?, c?]))
            .collect::<PyResult<Vec<[u32; 3]>>>()?;
        let mesh = Mesh::new(positions, triangles).map_err(|e| bad("positions/indices", e))?;
        let camera = camera_of(camera)?;
        if lights.is_empty() {
            return Err(bad("lights", "give at least one light"));
        }
        let lights = lights
            .iter()
            .enumerate()
            .map(|(k, light)| light_of(&format!("lights[{k}]"), light))
            .collect::<PyResult<Vec<SceneLight>>>()?;
        Ok(Self {
            inner: shadowlab_scene::Scene {
                name: name.to_owned(),
                camera,
                lights,
                mesh,
                shadow: ShadowSettings::default(),
            },
        })
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// Vertex positions, N × 3.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vectors(py, self.inner.mesh.positions())
    }

    /// Unit vertex normals, N × 3.
    #[getter]
    fn normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vectors(py, self.inner.mesh.normals())
    }

    /// Triangles as vertex indices, M × 3.
    #[getter]
    fn indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let rows: Vec<Vec<i64>> = self
            .inner
            .mesh
            .triangles()
            .iter()
            .map(|t| t.iter().map(|&k| i64::from(k)).collect())
            .collect();
        Ok(PyArray2::from_vec2(py, &rows)?)
    }

    /// Each triangle's group (the scene file's mesh entry), M.
    #[getter]
    fn groups<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        PyArray1::from_iter(py, self.inner.mesh.groups().iter().map(|&g| i64::from(g)))
    }

    /// The camera: `eye`, `forward`, `up`, `fov_degrees`, `aspect`, `near`, `far`, `width`,
    /// `height`, and its `view` and `projection` matrices (4 × 4, GL conventions).
    #[getter]
    fn camera<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let camera = &self.inner.camera;
        let dict = PyDict::new(py);
        dict.set_item("eye", camera.pose.eye().to_array())?;
        dict.set_item("forward", camera.pose.forward().to_array())?;
        dict.set_item("up", camera.pose.up().to_array())?;
        dict.set_item("fov_degrees", camera.projection.fov_y().to_degrees())?;
        dict.set_item("aspect", camera.projection.aspect())?;
        dict.set_item("near", camera.projection.near())?;
        dict.set_item("far", camera.projection.far())?;
        dict.set_item("width", camera.width)?;
        dict.set_item("height", camera.height)?;
        dict.set_item("view", matrix(py, &camera.pose.view_matrix())?)?;
        dict.set_item(
            "projection",
            matrix(
                py,
                &camera
                    .projection
                    .matrix(shadowlab_hull::NdcDepth::NegativeOneToOne),
            )?,
        )?;
        Ok(dict)
    }

    /// The lights, as dicts of the form [`Scene::from_arrays`] reads (a directional light by the
    /// direction it travels).
    #[getter]
    fn lights<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.inner
            .lights
            .iter()
            .map(|light| {
                let dict = PyDict::new(py);
                match light {
                    SceneLight::Directional { to_light } => {
                        dict.set_item("kind", "directional")?;
                        dict.set_item("direction", (-*to_light).to_array())?;
                    }
                    SceneLight::Spot { pose, cone } => {
                        dict.set_item("kind", "spot")?;
                        dict.set_item("position", pose.eye().to_array())?;
                        dict.set_item("direction", pose.forward().to_array())?;
                        dict.set_item("cone_degrees", cone.fov_y().to_degrees())?;
                        dict.set_item("near", cone.near())?;
                        dict.set_item("far", cone.far())?;
                    }
                    SceneLight::Point { position, range } => {
                        dict.set_item("kind", "point")?;
                        dict.set_item("position", position.to_array())?;
                        dict.set_item("range", *range)?;
                    }
                }
                Ok(dict)
            })
            .collect()
    }

    /// A copy with the eye image `width × height` pixels (the camera's aspect follows).
    fn with_image_size(&self, width: u32, height: u32) -> PyResult<Self> {
        let mut inner = self.inner.clone();
        let projection = inner.camera.projection;
        inner.camera.projection = Perspective::new(
            projection.fov_y(),
            f64::from(width) / f64::from(height.max(1)),
            projection.near(),
            projection.far(),
        )
        .map_err(|e| bad("width/height", e))?;
        if width == 0 || height == 0 {
            return Err(bad("width/height", "must be at least 1"));
        }
        (inner.camera.width, inner.camera.height) = (width, height);
        Ok(Self { inner })
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}: {} triangles, {} light(s), {}×{} eye image)",
            self.inner.name,
            self.inner.mesh.triangle_count(),
            self.inner.lights.len(),
            self.inner.camera.width,
            self.inner.camera.height
        )
    }
}

/// The rows of an N × 3 array.
fn rows<T: numpy::Element + Copy>(
    array: &PyReadonlyArray2<'_, T>,
    what: &str,
) -> PyResult<Vec<[T; 3]>> {
    let view = array.as_array();
    if view.ncols() != 3 {
        return Err(bad(
            what,
            format!("must be N × 3, not N × {}", view.ncols()),
        ));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

/// The camera of a `camera` dict.
fn camera_of(camera: &Bound<'_, PyDict>) -> PyResult<Camera> {
    let what = "camera";
    let eye = vector(
        "camera.eye",
        &field::<Bound<'_, PyAny>>(camera, what, "eye", None)?,
    )?;
    let target = vector(
        "camera.target",
        &field::<Bound<'_, PyAny>>(camera, what, "target", None)?,
    )?;
    let up = match camera.get_item("up")? {
        Some(up) => vector("camera.up", &up)?,
        None => DVec3::Y,
    };
    let fov: f64 = field(camera, what, "fov_degrees", Some(60.0))?;
    let near: f64 = field(camera, what, "near", None)?;
    let far: f64 = field(camera, what, "far", None)?;
    let width: u32 = field(camera, what, "width", Some(640))?;
    let height: u32 = field(camera, what, "height", Some(480))?;
    if width == 0 || height == 0 {
        return Err(bad("camera.width/height", "must be at least 1"));
    }
    let pose = ViewPose::look_at(eye, target, up).map_err(|e| bad(what, e))?;
    let projection = Perspective::new(
        fov.to_radians(),
        f64::from(width) / f64::from(height),
        near,
        far,
    )
    .map_err(|e| bad(what, e))?;
    Ok(Camera {
        pose,
        projection,
        width,
        height,
    })
}

/// The scene light of a `lights[k]` dict.
fn light_of(what: &str, light: &Bound<'_, PyDict>) -> PyResult<SceneLight> {
    let kind: String = field(light, what, "kind", Some("directional".to_owned()))?;
    let get = |key: &str| -> PyResult<DVec3> {
        vector(
            &format!("{what}.{key}"),
            &field::<Bound<'_, PyAny>>(light, what, key, None)?,
        )
    };
    match kind.as_str() {
        "directional" => {
            let direction = get("direction")?;
            let to_light = (-direction)
                .try_normalize()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    bad(
                        &format!("{what}.direction"),
                        "must be a non-zero finite vector",
                    )
                })?;
            Ok(SceneLight::Directional { to_light })
        }
        "spot" => {
            let position = get("position")?;
            let target = get("target")?;
            let cone: f64 = field(light, what, "cone_degrees", None)?;
            let near: f64 = field(light, what, "near", None)?;
            let far: f64 = field(light, what, "far", None)?;
            let forward = target - position;
            let hint = if forward.y.abs() >= forward.x.abs().max(forward.z.abs()) {
                DVec3::NEG_Z
            } else {
                DVec3::Y
            };
            let pose = ViewPose::look_at(position, target, hint).map_err(|e| bad(what, e))?;
            let cone =
                Perspective::new(cone.to_radians(), 1.0, near, far).map_err(|e| bad(what, e))?;
            Ok(SceneLight::Spot { pose, cone })
        }
        "point" => {
            let position = get("position")?;
            if !position.is_finite() {
                return Err(bad(&format!("{what}.position"), "must be finite"));
            }
            let range: Option<f64> = field(light, what, "range", Some(None))?;
            if let Some(r) = range.filter(|r| !(r.is_finite() && *r > 0.0)) {
                return Err(bad(
                    &format!("{what}.range"),
                    format!("{r} must be finite and > 0"),
                ));
            }
            Ok(SceneLight::Point { position, range })
        }
        other => Err(bad(
            &format!("{what}.kind"),
            format!("unknown {other:?}; known: directional, spot, point"),
        )),
    }
}
