//! Biases: how a receiver's depth is compared with the stored depth (CAD Table 1, slope scaling,
//! receiver-plane depth bias).

use std::fmt;

use glam::{DMat2, DVec2, DVec3};
use shadowlab_params::bias::DepthBias;

use crate::lookup::spec_numbers;
use crate::map::ShadowMap;

/// A receiver's depth slope per texel is capped here: a surface seen edge-on by the light would
/// otherwise get an unbounded bias.
const MAX_SLOPE: f64 = 1.0;
/// Step along the surface for the slope, relative to the point's distance from the origin (or 1).
const SLOPE_STEP: f64 = 1e-5;

/// How a receiver's window depth is compared with the stored depth (it is lit when its depth is
/// at most the offset stored depth). Depths are GL window depths of the map, `[0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthComparison {
    /// No offset: the raw test, which acnes.
    None,
    /// Williams' constant offset, in window-depth units (CAD Table 1a).
    Constant {
        /// The offset.
        offset: f64,
    },
    /// A constant plus `slope` times the receiver's depth slope per texel (the larger of
    /// `|∂z/∂x|`, `|∂z/∂y|` over the map), as `glPolygonOffset(factor, units)` does.
    SlopeScaled {
        /// The constant part, in window-depth units.
        constant: f64,
        /// The factor on the slope.
        slope: f64,
    },
    /// The second-nearest depth (Wang & Molnar, CAD Table 1b); needs a map with second depths.
    SecondDepth,
    /// The midpoint of the two nearest depths (Woo, CAD Table 1c); needs second depths.
    Midpoint,
    /// The midpoint capped at `max_bias` (CAD Table 1d); needs second depths.
    DualDepth {
        /// The cap, in window-depth units.
        max_bias: f64,
    },
    /// Receiver plane depth bias (Isidoro, "Shadow Mapping: GPU-based Tips and Techniques", GDC
    /// 2006): the receiver's window depth is extrapolated on its own plane to each tap,
    /// `z_tap = z + (∂z/∂u)·du + (∂z/∂v)·dv`, with `(∂z/∂u, ∂z/∂v)` the receiver plane's
    /// window-depth gradient per texel (each component capped at ±1), and compared with the stored
    /// depth plus `constant`: lit when `z_tap ≤ z_stored + constant`. `(du, dv)` is the tap's offset
    /// from the point in texels: the kernel offset for PCF and the disk (Isidoro compares at the
    /// tap position), and for the nearest filter the offset from the point to the centre of the
    /// texel it reads (where the stored depth was sampled). A texel holding nothing (depth 1)
    /// lights the receiver; a surface seen edge-on by the light gets no extrapolation.
    ReceiverPlane {
        /// The constant added to the stored depth, in window-depth units.
        constant: f64,
    },
}

impl DepthComparison {
    /// Whether the map must hold second-nearest depths.
    #[must_use]
    pub fn needs_second_depth(&self) -> bool {
        matches!(
            self,
            Self::SecondDepth | Self::Midpoint | Self::DualDepth { .. }
        )
    }

    /// The term's name in a spec: `none`, `constant`, `slope`, `second-depth`, `midpoint`,
    /// `dual-depth`, `receiver-plane`.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Constant { .. } => "constant",
            Self::SlopeScaled { .. } => "slope",
            Self::SecondDepth => "second-depth",
            Self::Midpoint => "midpoint",
            Self::DualDepth { .. } => "dual-depth",
            Self::ReceiverPlane { .. } => "receiver-plane",
        }
    }
}

impl fmt::Display for DepthComparison {
    /// The term [`Bias::parse`] reads back: `none`, `constant:O`, `slope:F,C`, `second-depth`,
    /// `midpoint`, `dual-depth:MAX`, `receiver-plane:C`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Constant { offset } => write!(f, "constant:{offset:?}"),
            Self::SlopeScaled { constant, slope } => write!(f, "slope:{slope:?},{constant:?}"),
            Self::DualDepth { max_bias } => write!(f, "dual-depth:{max_bias:?}"),
            Self::ReceiverPlane { constant } => write!(f, "receiver-plane:{constant:?}"),
            Self::None | Self::SecondDepth | Self::Midpoint => f.write_str(self.key()),
        }
    }
}

/// A bias: for now the depth comparison alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bias {
    /// How the receiver's depth is compared with the stored one.
    pub comparison: DepthComparison,
}

impl From<DepthComparison> for Bias {
    fn from(comparison: DepthComparison) -> Self {
        Self::new(comparison)
    }
}

impl Bias {
    /// The default of `shadowlab render`: slope-scaled, factor 2 and constant 1e-5 (window depth).
    pub const DEFAULT: Self = Self::new(DepthComparison::SlopeScaled {
        constant: 1e-5,
        slope: 2.0,
    });

    /// The raw test: no comparison offset.
    pub const NONE: Self = Self::new(DepthComparison::None);

    /// A bias of `comparison`.
    #[must_use]
    pub const fn new(comparison: DepthComparison) -> Self {
        Self { comparison }
    }

    /// Whether the map must hold second-nearest depths.
    #[must_use]
    pub fn needs_second_depth(&self) -> bool {
        self.comparison.needs_second_depth()
    }
}

impl fmt::Display for Bias {
    /// The spec [`Bias::parse`] reads back, numbers in Rust's shortest round-trip form (so the
    /// parsed bias is the same bit for bit): the comparison's term.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.comparison.fmt(f)
    }
}

impl Bias {
    /// Parses `none`, `constant:OFFSET`, `slope:FACTOR[,CONSTANT]`, `second-depth`, `midpoint`,
    /// `dual-depth:MAX`, `receiver-plane[:CONSTANT]` (depths in window units).
    ///
    /// # Errors
    /// A message naming what is wrong and the accepted forms.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (name, n) = spec_numbers(spec, 2)?;
        let non_negative = |v: f64, what: &str| {
            if v >= 0.0 {
                Ok(v)
            } else {
                Err(format!("{what} in {spec:?} must be at least 0"))
            }
        };
        let comparison = match (name, n.as_slice()) {
            ("none", []) => DepthComparison::None,
            ("constant", [offset]) => DepthComparison::Constant { offset: *offset },
            ("slope", [slope]) => DepthComparison::SlopeScaled {
                constant: 0.0,
                slope: non_negative(*slope, "the factor")?,
            },
            ("slope", [slope, constant]) => DepthComparison::SlopeScaled {
                constant: *constant,
                slope: non_negative(*slope, "the factor")?,
            },
            ("second-depth", []) => DepthComparison::SecondDepth,
            ("midpoint", []) => DepthComparison::Midpoint,
            ("dual-depth", [max]) => DepthComparison::DualDepth {
                max_bias: non_negative(*max, "the cap")?,
            },
            ("receiver-plane", []) => DepthComparison::ReceiverPlane { constant: 0.0 },
            ("receiver-plane", [constant]) => DepthComparison::ReceiverPlane {
                constant: *constant,
            },
            _ => {
                return Err(format!(
                    "unknown bias {spec:?}; known: none, constant:OFFSET, slope:FACTOR[,CONSTANT], \
                     second-depth, midpoint, dual-depth:MAX, receiver-plane[:CONSTANT]"
                ));
            }
        };
        Ok(Self::new(comparison))
    }
}

/// A depth comparison ready for one lookup: the receiver's slope (or plane gradient) is found once
/// per lookup, not once per tap.
pub(crate) struct Comparison {
    comparison: DepthComparison,
    /// The capped slope, for [`DepthComparison::SlopeScaled`].
    slope: f64,
    /// The capped gradient per texel, for [`DepthComparison::ReceiverPlane`].
    gradient: DVec2,
}

impl Comparison {
    /// `comparison` for the receiver at `world` with `normal`.
    pub(crate) fn new(
        comparison: DepthComparison,
        map: &ShadowMap,
        world: DVec3,
        normal: DVec3,
    ) -> Self {
        let (slope, gradient) = match comparison {
            DepthComparison::SlopeScaled { .. } => (depth_slope(map, world, normal), DVec2::ZERO),
            DepthComparison::ReceiverPlane { .. } => {
                let gradient = depth_gradient(map, world, normal)
                    .filter(|g| g.is_finite())
                    .map_or(DVec2::ZERO, |g| {
                        g.clamp(DVec2::splat(-MAX_SLOPE), DVec2::splat(MAX_SLOPE))
                    });
                (0.0, gradient)
            }
            _ => (0.0, DVec2::ZERO),
        };
        Self {
            comparison,
            slope,
            gradient,
        }
    }

    /// Whether the receiver at window depth `receiver` is lit through texel `(i, j)`, read by a tap
    /// `offset` texels from the point.
    pub(crate) fn lit(
        &self,
        map: &ShadowMap,
        (i, j): (u32, u32),
        receiver: f64,
        offset: DVec2,
    ) -> bool {
        let z1 = map.depth(i, j);
        let second = || {
            let z2 = map.second_depth(i, j).unwrap_or(1.0);
            // A second depth at the far plane means no second surface.
            if z2 >= 1.0 { f64::INFINITY } else { z2.max(z1) }
        };
        let limit = match self.comparison {
            DepthComparison::None => z1,
            DepthComparison::Constant { offset } => z1 + offset,
            DepthComparison::SlopeScaled { constant, slope } => z1 + constant + slope * self.slope,
            DepthComparison::SecondDepth => table_1(DepthBias::SecondDepth, z1, second()),
            DepthComparison::Midpoint => table_1(DepthBias::Midpoint, z1, second()),
            DepthComparison::DualDepth { max_bias } => {
                table_1(DepthBias::DualDepth { max_bias }, z1, second())
            }
            DepthComparison::ReceiverPlane { constant } => {
                if z1 >= 1.0 {
                    return true;
                }
                let at_tap = receiver + self.gradient.x * offset.x + self.gradient.y * offset.y;
                return at_tap <= z1 + constant;
            }
        };
        receiver <= limit
    }

    /// Whether the taps' offsets matter (only the receiver plane reads them).
    pub(crate) fn reads_offsets(&self) -> bool {
        matches!(self.comparison, DepthComparison::ReceiverPlane { .. })
    }
}

/// CAD eq. 1 through `shadowlab-params`; an empty texel (z1 at the far plane) lights everything.
fn table_1(bias: DepthBias, z1: f64, z2: f64) -> f64 {
    bias.z_map(z1, z2).unwrap_or(f64::INFINITY)
}

/// The receiver's window-depth slope per texel: the larger of `|∂z/∂x|`, `|∂z/∂y|` of
/// [`depth_gradient`], capped at [`MAX_SLOPE`] (which is also the slope where the gradient is
/// undefined).
fn depth_slope(map: &ShadowMap, world: DVec3, normal: DVec3) -> f64 {
    depth_gradient(map, world, normal).map_or(MAX_SLOPE, |gradient| {
        gradient.x.abs().max(gradient.y.abs()).min(MAX_SLOPE)
    })
}

/// The window-depth gradient per texel `(∂z/∂x, ∂z/∂y)` of the surface plane through `world` with
/// `normal`, seen through the map: two steps along the plane, and the inverse of their Jacobian
/// in texels. `None` where the plane is seen edge-on (the Jacobian is singular) or a step lies
/// behind the map's projection centre.
fn depth_gradient(map: &ShadowMap, world: DVec3, normal: DVec3) -> Option<DVec2> {
    let (t1, t2) = normal.any_orthonormal_pair();
    let step = SLOPE_STEP * world.length().max(1.0);
    let side = f64::from(map.resolution);
    let at = |p: DVec3| {
        map.setup
            .mapping
            .window(p)
            .map(|w| DVec3::new(w.x * side, w.y * side, w.z))
    };
    let (p0, p1, p2) = (at(world)?, at(world + t1 * step)?, at(world + t2 * step)?);
    let (d1, d2) = (p1 - p0, p2 - p0);
    let jacobian = DMat2::from_cols(DVec2::new(d1.x, d1.y), DVec2::new(d2.x, d2.y));
    let determinant = jacobian.determinant();
    if determinant.abs() <= f64::EPSILON * d1.truncate().length() * d2.truncate().length() {
        return None;
    }
    // (∂z/∂x, ∂z/∂y) J = (dz1, dz2).
    Some(jacobian.transpose().inverse() * DVec2::new(d1.z, d2.z))
}
