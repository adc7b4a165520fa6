//! The scene file as TOML gives it: every field optional, unknown fields rejected
//! (`deny_unknown_fields` on every table). Values are checked and defaults filled in by the
//! sibling modules, which name each field by its path.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, IgnoredAny, SeqAccess, Visitor};

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) name: Option<String>,
    #[serde(default)]
    pub(super) camera: RawCamera,
    #[serde(default)]
    pub(super) light: Vec<RawLight>,
    #[serde(default)]
    pub(super) mesh: Vec<RawMesh>,
    #[serde(default)]
    pub(super) shadow: RawShadow,
}

/// `[camera]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCamera {
    pub(super) position: Option<[f64; 3]>,
    pub(super) target: Option<[f64; 3]>,
    pub(super) direction: Option<[f64; 3]>,
    pub(super) up: Option<[f64; 3]>,
    pub(super) fov: Option<f64>,
    pub(super) near: Option<f64>,
    pub(super) far: Option<f64>,
    pub(super) image: Option<[u32; 2]>,
}

/// The kinds of `[[light]]`.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightKind {
    #[default]
    Directional,
    Spot,
    Point,
}

/// One `[[light]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLight {
    pub(super) kind: Option<LightKind>,
    pub(super) direction: Option<[f64; 3]>,
    pub(super) position: Option<[f64; 3]>,
    pub(super) target: Option<[f64; 3]>,
    pub(super) up: Option<[f64; 3]>,
    pub(super) cone: Option<f64>,
    pub(super) near: Option<f64>,
    pub(super) far: Option<f64>,
    /// A point light's reach (`KHR_lights_punctual`'s `range`).
    pub(super) range: Option<f64>,
}

/// The procedural shapes a mesh entry can name.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum ShapeKind {
    Plane,
    #[serde(rename = "box")]
    Cuboid,
    Sphere,
    Cylinder,
    Lattice,
    Chessboard,
}

impl ShapeKind {
    /// The name as the file spells it, which is also the default group name.
    pub(super) fn name(self) -> &'static str {
        match self {
            Self::Plane => "plane",
            Self::Cuboid => "box",
            Self::Sphere => "sphere",
            Self::Cylinder => "cylinder",
            Self::Lattice => "lattice",
            Self::Chessboard => "chessboard",
        }
    }

    /// The shape parameters (fields of [`RawMesh::parameters`]) the shape takes.
    pub(super) fn parameters(self) -> &'static [&'static str] {
        match self {
            Self::Plane => &["size", "segments"],
            Self::Cuboid => &["size"],
            Self::Sphere => &["radius", "segments", "rings"],
            Self::Cylinder => &["radius", "height", "segments"],
            Self::Lattice => &["cells", "spacing", "thickness"],
            Self::Chessboard => &["square_size", "frame_width"],
        }
    }
}

/// One `[[mesh]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMesh {
    pub(super) obj: Option<String>,
    pub(super) gltf: Option<String>,
    pub(super) gltf_scene: Option<usize>,
    pub(super) shape: Option<ShapeKind>,
    pub(super) name: Option<String>,
    pub(super) translate: Option<[f64; 3]>,
    pub(super) rotate: Option<[f64; 3]>,
    pub(super) scale: Option<RawScale>,
    pub(super) copies: Option<u32>,
    pub(super) step: Option<[f64; 3]>,
    pub(super) size: Option<Vec<f64>>,
    pub(super) segments: Option<u32>,
    pub(super) rings: Option<u32>,
    pub(super) radius: Option<f64>,
    pub(super) height: Option<f64>,
    pub(super) cells: Option<[u32; 3]>,
    pub(super) spacing: Option<f64>,
    pub(super) thickness: Option<f64>,
    pub(super) square_size: Option<f64>,
    pub(super) frame_width: Option<f64>,
}

impl RawMesh {
    /// The names of the shape parameters this entry gives, in the order the format lists them.
    pub(super) fn parameters(&self) -> Vec<&'static str> {
        [
            ("size", self.size.is_some()),
            ("segments", self.segments.is_some()),
            ("rings", self.rings.is_some()),
            ("radius", self.radius.is_some()),
            ("height", self.height.is_some()),
            ("cells", self.cells.is_some()),
            ("spacing", self.spacing.is_some()),
            ("thickness", self.thickness.is_some()),
            ("square_size", self.square_size.is_some()),
            ("frame_width", self.frame_width.is_some()),
        ]
        .into_iter()
        .filter_map(|(name, given)| given.then_some(name))
        .collect()
    }
}

/// `scale`: one number for all axes, or one per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum RawScale {
    Uniform(f64),
    PerAxis([f64; 3]),
}

impl<'de> Deserialize<'de> for RawScale {
    fn deserialize<D: de::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ScaleVisitor)
    }
}

struct ScaleVisitor;

impl<'de> Visitor<'de> for ScaleVisitor {
    type Value = RawScale;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or an array of three numbers")
    }

    fn visit_f64<E: de::Error>(self, value: f64) -> Result<RawScale, E> {
        Ok(RawScale::Uniform(value))
    }

    #[expect(
        clippy::cast_precision_loss,
        reason = "a scale given as an integer is read as the nearest f64, as TOML floats are"
    )]
    fn visit_i64<E: de::Error>(self, value: i64) -> Result<RawScale, E> {
        Ok(RawScale::Uniform(value as f64))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RawScale, A::Error> {
        let mut values = [0.0; 3];
        for (index, value) in values.iter_mut().enumerate() {
            *value = seq
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(index, &self))?;
        }
        if seq.next_element::<IgnoredAny>()?.is_some() {
            let mut count = 4;
            while seq.next_element::<IgnoredAny>()?.is_some() {
                count += 1;
            }
            return Err(de::Error::invalid_length(count, &self));
        }
        Ok(RawScale::PerAxis(values))
    }
}

/// `[shadow]`: passed on as text and numbers, unvalidated.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShadow {
    pub(super) technique: Option<String>,
    pub(super) parameter: Option<String>,
    pub(super) resolution: Option<u32>,
    /// The number of z-partitions; `splits` is its former name, still read.
    #[serde(alias = "splits")]
    pub(super) partitions: Option<u32>,
    pub(super) split_scheme: Option<String>,
    pub(super) bias: Option<String>,
    pub(super) filter: Option<String>,
    pub(super) lambda: Option<f64>,
    pub(super) n: Option<f64>,
    pub(super) focus: Option<String>,
    pub(super) optimal_readback: Option<String>,
    pub(super) optimal_initial: Option<u32>,
    pub(super) optimal_iterations: Option<u32>,
    pub(super) optimal_border: Option<f64>,
}
