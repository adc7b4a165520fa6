//! What can go wrong when measuring: the errors of the crates the analysis calls, and inputs that
//! do not belong together.

use std::fmt;

use shadowlab_plot::PlotError;
use shadowlab_raster::RasterError;
use shadowlab_shadow::ShadowError;
use shadowlab_trace::TraceError;

/// Why a truth, a metric or a picture could not be made.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum AnalysisError {
    /// Planning or rendering a shadow map failed (`shadowlab-shadow`).
    Shadow(ShadowError),
    /// The ray caster rejected a mesh (`shadowlab-trace`).
    Trace(TraceError),
    /// The rasterizer rejected a draw or an image (`shadowlab-raster`).
    Raster(RasterError),
    /// A shadow ray could not be made for a pixel's visible point (a zero-area triangle has no
    /// normal to offset along; a point at a spot light's position has no direction to it).
    ShadowRay {
        /// Index of the light in the scene.
        light: usize,
        /// The pixel (row-major, row 0 at the bottom).
        pixel: usize,
        /// What the ray caster said.
        error: TraceError,
    },
    /// An eye image whose per-pixel vectors do not hold `width × height` values.
    EyeImageSize {
        /// Width of the image.
        width: u32,
        /// Height of the image.
        height: u32,
        /// The shortest per-pixel vector's length.
        values: usize,
    },
    /// An eye image naming a triangle the scene does not have: it was rendered from another mesh.
    TriangleOutOfRange {
        /// The pixel (row-major, row 0 at the bottom).
        pixel: usize,
        /// The triangle it names.
        triangle: u32,
        /// How many triangles the scene has.
        triangles: usize,
    },
    /// A ray-casting hierarchy built over a mesh other than the scene's.
    BvhMismatch {
        /// Triangles in the hierarchy.
        bvh: usize,
        /// Triangles in the scene's mesh.
        mesh: usize,
    },
    /// A bias sweep was asked of a technique that reads its maps with a bias of its own (an
    /// engine's preset).
    NotSwept {
        /// The technique's spec.
        technique: String,
    },
    /// A figure could not be drawn (`shadowlab-plot`).
    Plot(PlotError),
    /// A heat-map scale that is not `0 < low < high < ∞`.
    HeatScale {
        /// The lower end given.
        low: f64,
        /// The upper end given.
        high: f64,
    },
}

impl fmt::Display for AnalysisError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Shadow(e) => write!(f, "{e}"),
            Self::Trace(e) => write!(f, "{e}"),
            Self::Raster(e) => write!(f, "{e}"),
            Self::ShadowRay {
                light,
                pixel,
                error,
            } => write!(
                f,
                "the shadow ray of pixel {pixel} toward light {light}: {error}"
            ),
            Self::EyeImageSize {
                width,
                height,
                values,
            } => write!(
                f,
                "an eye image of {width} × {height} pixels holds only {values} values per pixel \
                 vector"
            ),
            Self::TriangleOutOfRange {
                pixel,
                triangle,
                triangles,
            } => write!(
                f,
                "pixel {pixel} sees triangle {triangle}, but the scene has {triangles} triangles: \
                 the eye image belongs to another mesh"
            ),
            Self::BvhMismatch { bvh, mesh } => write!(
                f,
                "the ray-casting hierarchy holds {bvh} triangles but the scene's mesh {mesh}: it \
                 was built over another mesh"
            ),
            Self::NotSwept { technique } => write!(
                f,
                "{technique} reads its maps with its engine's own bias, so a bias sweep does not \
                 apply to it; sweep the bias of a technique of the papers or SDSM"
            ),
            Self::Plot(e) => write!(f, "drawing a figure: {e}"),
            Self::HeatScale { low, high } => write!(
                f,
                "a heat-map scale needs 0 < low < high < ∞, got low = {low}, high = {high}"
            ),
        }
    }
}

impl std::error::Error for AnalysisError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Shadow(e) => Some(e),
            Self::Trace(e) | Self::ShadowRay { error: e, .. } => Some(e),
            Self::Raster(e) => Some(e),
            Self::Plot(e) => Some(e),
            Self::EyeImageSize { .. }
            | Self::TriangleOutOfRange { .. }
            | Self::BvhMismatch { .. }
            | Self::NotSwept { .. }
            | Self::HeatScale { .. } => None,
        }
    }
}

impl From<ShadowError> for AnalysisError {
    fn from(e: ShadowError) -> Self {
        Self::Shadow(e)
    }
}

impl From<TraceError> for AnalysisError {
    fn from(e: TraceError) -> Self {
        Self::Trace(e)
    }
}

impl From<RasterError> for AnalysisError {
    fn from(e: RasterError) -> Self {
        Self::Raster(e)
    }
}

impl From<PlotError> for AnalysisError {
    fn from(e: PlotError) -> Self {
        Self::Plot(e)
    }
}
