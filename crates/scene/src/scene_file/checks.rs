//! Checks of single fields, each naming the field by its path in the file.

use std::path::Path;

use glam::DVec3;

use shadowlab_hull::HullError;

use super::error::{SceneFileError, SceneFileProblem};
use super::{MAX_IMAGE_SIDE, MIN_ANGLE_DEGREES};
use crate::gltf_import::GltfError;
use crate::mesh::MeshError;
use crate::normals;
use crate::number::Shown;
use crate::obj::ObjError;
use crate::procedural::ShapeError;

/// The file being read, for naming it in errors.
#[derive(Clone, Copy)]
pub(super) struct Checker<'a> {
    path: &'a Path,
}

/// `prefix.name`, the path of a field of a table.
pub(super) fn field(prefix: &str, name: &str) -> String {
    format!("{prefix}.{name}")
}

/// The name of a field in an error: its path if the file gives it, `the default <path>` if its
/// value was derived.
pub(super) fn named(path: String, given: bool) -> String {
    if given {
        path
    } else {
        format!("the default {path}")
    }
}

impl<'a> Checker<'a> {
    pub(super) fn new(path: &'a Path) -> Self {
        Self { path }
    }

    /// [`SceneFileProblem::OutOfRange`] of `field`: its `value` and what it must be.
    fn out_of_range(
        &self,
        field: &str,
        value: f64,
        requirement: impl Into<String>,
    ) -> SceneFileError {
        self.error(
            field,
            SceneFileProblem::OutOfRange {
                value,
                requirement: requirement.into(),
            },
        )
    }

    /// A [`SceneFileError::Field`] for `field`.
    pub(super) fn error(
        &self,
        field: impl Into<String>,
        problem: SceneFileProblem,
    ) -> SceneFileError {
        SceneFileError::Field {
            path: self.path.to_owned(),
            field: field.into(),
            problem,
        }
    }

    /// A [`SceneFileError::Obj`] wrapping the OBJ loader's error about `field`.
    pub(super) fn obj_error(&self, field: impl Into<String>, source: ObjError) -> SceneFileError {
        SceneFileError::Obj {
            path: self.path.to_owned(),
            field: field.into(),
            source: Box::new(source),
        }
    }

    /// A [`SceneFileError::Gltf`] wrapping the glTF reader's error about `field`.
    pub(super) fn gltf_error(&self, field: impl Into<String>, source: GltfError) -> SceneFileError {
        SceneFileError::Gltf {
            path: self.path.to_owned(),
            field: Some(field.into()),
            source: Box::new(source),
        }
    }

    /// A [`SceneFileError::Shape`] wrapping the error of building the shape of `field`.
    pub(super) fn shape_error(
        &self,
        field: impl Into<String>,
        source: ShapeError,
    ) -> SceneFileError {
        SceneFileError::Shape {
            path: self.path.to_owned(),
            field: field.into(),
            source,
        }
    }

    /// A [`SceneFileError::Mesh`] wrapping the error of moving, copying or merging `field`.
    pub(super) fn mesh_error(&self, field: impl Into<String>, source: MeshError) -> SceneFileError {
        SceneFileError::Mesh {
            path: self.path.to_owned(),
            field: field.into(),
            source,
        }
    }

    /// A [`SceneFileError::Hull`] wrapping hull's error about `field`.
    pub(super) fn hull_error(&self, field: impl Into<String>, source: HullError) -> SceneFileError {
        SceneFileError::Hull {
            path: self.path.to_owned(),
            field: field.into(),
            source,
        }
    }

    /// `value` if it is finite.
    pub(super) fn finite(&self, field: &str, value: f64) -> Result<f64, SceneFileError> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.error(field, SceneFileProblem::NotFinite { value }))
        }
    }

    /// `value` if it is finite and > 0.
    pub(super) fn positive(&self, field: &str, value: f64) -> Result<f64, SceneFileError> {
        if self.finite(field, value)? > 0.0 {
            Ok(value)
        } else {
            Err(self.error(
                field,
                SceneFileProblem::OutOfRange {
                    value,
                    requirement: "> 0".into(),
                },
            ))
        }
    }

    /// `value` if it is at least `minimum`; `requirement` says so, e.g. `"at least 3"`.
    pub(super) fn at_least(
        &self,
        field: &str,
        value: u32,
        minimum: u32,
        requirement: &'static str,
    ) -> Result<u32, SceneFileError> {
        if value >= minimum {
            Ok(value)
        } else {
            Err(self.out_of_range(field, f64::from(value), requirement))
        }
    }

    /// A full angle in degrees (a field of view, a cone) in [[`MIN_ANGLE_DEGREES`], 180), in
    /// radians.
    pub(super) fn angle(&self, field: &str, degrees: f64) -> Result<f64, SceneFileError> {
        if self.finite(field, degrees)? >= MIN_ANGLE_DEGREES && degrees < 180.0 {
            Ok(degrees.to_radians())
        } else {
            Err(self.out_of_range(
                field,
                degrees,
                format!(
                    "in [{}, 180) degrees (MIN_ANGLE_DEGREES)",
                    Shown(MIN_ANGLE_DEGREES)
                ),
            ))
        }
    }

    /// An image side in pixels, in 1..=[`MAX_IMAGE_SIDE`].
    pub(super) fn image_side(&self, field: &str, value: u32) -> Result<u32, SceneFileError> {
        if (1..=MAX_IMAGE_SIDE).contains(&value) {
            Ok(value)
        } else {
            Err(self.out_of_range(
                field,
                f64::from(value),
                format!("in 1..={MAX_IMAGE_SIDE} pixels (MAX_IMAGE_SIDE)"),
            ))
        }
    }

    /// The vector `values` if every coordinate is finite; a bad one is named `field[i]`.
    pub(super) fn vector(&self, field: &str, values: [f64; 3]) -> Result<DVec3, SceneFileError> {
        for (index, &value) in values.iter().enumerate() {
            self.finite(&format!("{field}[{index}]"), value)?;
        }
        Ok(DVec3::from_array(values))
    }

    /// The vector `values` normalised, if it is finite and not zero.
    pub(super) fn direction(&self, field: &str, values: [f64; 3]) -> Result<DVec3, SceneFileError> {
        let value = self.vector(field, values)?;
        normals::unit(value)
            .ok_or_else(|| self.error(field, SceneFileProblem::ZeroVector { value }))
    }

    /// `value` if it is finite and ≥ 0.
    pub(super) fn non_negative(&self, field: &str, value: f64) -> Result<f64, SceneFileError> {
        if self.finite(field, value)? >= 0.0 {
            Ok(value)
        } else {
            Err(self.error(
                field,
                SceneFileProblem::OutOfRange {
                    value,
                    requirement: ">= 0".into(),
                },
            ))
        }
    }

    /// `value` if it is finite and not 0.
    pub(super) fn non_zero(&self, field: &str, value: f64) -> Result<f64, SceneFileError> {
        if self.finite(field, value)? == 0.0 {
            Err(self.error(
                field,
                SceneFileProblem::OutOfRange {
                    value,
                    requirement: "non-zero".into(),
                },
            ))
        } else {
            Ok(value)
        }
    }

    /// `Ok` unless both of two fields that exclude each other are given.
    pub(super) fn at_most_one(
        &self,
        first: (&str, bool),
        second: (&str, bool),
    ) -> Result<(), SceneFileError> {
        if first.1 && second.1 {
            Err(self.error(
                first.0,
                SceneFileProblem::Conflict {
                    other: second.0.to_owned(),
                },
            ))
        } else {
            Ok(())
        }
    }
}
