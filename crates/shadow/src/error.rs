//! What can go wrong when planning a shadow map.

use std::fmt;

use shadowlab_hull::HullError;
use shadowlab_params::ParamError;
use shadowlab_raster::RasterError;
use shadowlab_trace::TraceError;

/// A light set-up that cannot be built, with the reason.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum ShadowError {
    /// A camera, light or body was rejected by `shadowlab-hull`.
    Geometry(HullError),
    /// A parameter was rejected by `shadowlab-params`.
    Parameter(ParamError),
    /// The rasterizer rejected a draw (bad indices, target size).
    Raster(RasterError),
    /// The ray caster rejected a mesh or a ray (`shadowlab-trace`).
    Trace(TraceError),
    /// The focus body B is empty: nothing in the scene bounds can cast a shadow into the view.
    EmptyFocusBody,
    /// The focus body is flat along an axis the shadow map must span (named), so no map fits it.
    FlatFocusBody {
        /// `"warp axis"`, `"lateral axis"` or `"light axis"`.
        axis: &'static str,
    },
    /// The technique has no set-up for this configuration (like GLPR for γ ≤ φ); the reason says why.
    NotDefined {
        /// The technique's key.
        technique: &'static str,
        /// Why, in words.
        reason: String,
    },
    /// The light lies inside the region the shadow map must cover, so no projection from it fits.
    LightInsideFocusBody,
    /// The technique cannot serve this kind of light (a light-space warp for a point light, whose
    /// light lights every direction; a cube map for a directional light).
    UnservedLight {
        /// The technique's key.
        technique: &'static str,
        /// The light's kind: `directional`, `spot` or `point`.
        light: &'static str,
        /// The techniques that serve such a light.
        serving: &'static str,
    },
    /// A map fitted to the eye pass's samples ([`crate::sdsm`]) has none to fit: nothing is
    /// visible, or nothing visible lies inside the spot light's cone.
    NoSamples,
}

impl fmt::Display for ShadowError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Geometry(e) => write!(f, "{e}"),
            Self::Parameter(e) => write!(f, "{e}"),
            Self::Raster(e) => write!(f, "{e}"),
            Self::Trace(e) => write!(f, "{e}"),
            Self::EmptyFocusBody => f.write_str(
                "the focus body is empty: nothing inside the scene bounds can cast a shadow into the view",
            ),
            Self::FlatFocusBody { axis } => {
                write!(f, "the focus body is flat along the shadow map's {axis}")
            }
            Self::NotDefined { technique, reason } => {
                write!(f, "{technique} is not defined here: {reason}")
            }
            Self::LightInsideFocusBody => {
                f.write_str("the light lies inside the region its shadow map must cover")
            }
            Self::UnservedLight {
                technique,
                light,
                serving,
            } => write!(
                f,
                "{technique} cannot serve a {light} light; techniques for {light} lights: {serving}"
            ),
            Self::NoSamples => f.write_str(
                "no visible sample to fit the shadow map to: nothing is visible, or nothing \
                 visible lies inside the spot light's cone",
            ),
        }
    }
}

impl ShadowError {
    /// Why the technique has no map for this configuration, where that is the error — the
    /// technique not defined here ([`Self::NotDefined`]: its reason), or the light inside the body
    /// its one map must cover ([`Self::LightInsideFocusBody`], PSM for a point light in the view's
    /// hull) — so that a study records it as that setting's outcome instead of stopping; `None`
    /// for every other error.
    #[must_use]
    pub fn undefined_reason(&self) -> Option<String> {
        match self {
            Self::NotDefined { reason, .. } => Some(reason.clone()),
            Self::LightInsideFocusBody => Some(self.to_string()),
            _ => None,
        }
    }
}

impl ShadowError {
    /// Why no map can be made for this frame, where that is the error: what
    /// [`Self::undefined_reason`] says, and also a frame whose focus body is empty or flat or that
    /// has no visible sample to fit to ([`Self::EmptyFocusBody`], [`Self::FlatFocusBody`],
    /// [`Self::NoSamples`]) — what a generated camera pose or light direction can come to — so
    /// that a sweep over generated frames records it as the cell's outcome; `None` for bad input
    /// and failures. shadowlab's choice for sweeps; `analyze` stops on these instead, since there
    /// they say the user's own scene is set up wrong.
    #[must_use]
    pub fn frame_reason(&self) -> Option<String> {
        match self {
            Self::EmptyFocusBody | Self::FlatFocusBody { .. } | Self::NoSamples => {
                Some(self.to_string())
            }
            _ => self.undefined_reason(),
        }
    }
}

impl std::error::Error for ShadowError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Geometry(e) => Some(e),
            Self::Parameter(e) => Some(e),
            Self::Raster(e) => Some(e),
            Self::Trace(e) => Some(e),
            Self::EmptyFocusBody
            | Self::FlatFocusBody { .. }
            | Self::NotDefined { .. }
            | Self::LightInsideFocusBody
            | Self::UnservedLight { .. }
            | Self::NoSamples => None,
        }
    }
}

impl From<TraceError> for ShadowError {
    fn from(e: TraceError) -> Self {
        Self::Trace(e)
    }
}

impl From<HullError> for ShadowError {
    fn from(e: HullError) -> Self {
        Self::Geometry(e)
    }
}

impl From<RasterError> for ShadowError {
    fn from(e: RasterError) -> Self {
        Self::Raster(e)
    }
}

impl From<ParamError> for ShadowError {
    fn from(e: ParamError) -> Self {
        Self::Parameter(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_without_a_map_has_a_reason_and_bad_input_none() {
        for frame in [
            ShadowError::EmptyFocusBody,
            ShadowError::FlatFocusBody { axis: "warp axis" },
            ShadowError::NoSamples,
        ] {
            assert_eq!(frame.frame_reason(), Some(frame.to_string()));
            assert_eq!(frame.undefined_reason(), None, "a study stops on {frame}");
        }
        let inside = ShadowError::LightInsideFocusBody;
        assert_eq!(inside.frame_reason(), inside.undefined_reason());
        let unserved = ShadowError::UnservedLight {
            technique: "cube",
            light: "directional",
            serving: "uniform",
        };
        assert_eq!(unserved.frame_reason(), None);
    }
}
