//! Why a set-up file could not be read, written or evaluated: every error names the file and the
//! JSON path of the field (`frames[0].lights[1].partitions[2].near`).

use std::fmt;
use std::path::PathBuf;

use shadowlab_raster::image_in::DepthImageError;
use shadowlab_scene::ReadError;
use shadowlab_shadow::Technique;

use crate::error::AnalysisError;

/// Why a set-up could not be read, written or evaluated.
#[non_exhaustive]
#[derive(Debug)]
pub enum SetupError {
    /// The set-up file could not be read: missing, not a regular file, or larger than
    /// [`super::MAX_SETUP_FILE_BYTES`].
    Read(ReadError),
    /// The file is not valid UTF-8 (JSON is UTF-8).
    NotUtf8 {
        /// The set-up file.
        path: PathBuf,
    },
    /// Not JSON, or JSON that does not fit the format: a syntax error, a missing or unknown
    /// field, a value of the wrong type or out of its type's range, a matrix without 16 numbers.
    Json {
        /// The set-up file.
        path: PathBuf,
        /// The JSON path of the field where the error was found (`frames[0].lights`), `.` for
        /// the top level.
        field: String,
        /// serde_json's message, with the line and column.
        message: String,
    },
    /// A field whose value is out of range, inconsistent with another, or with the scene.
    Field {
        /// The set-up file.
        path: PathBuf,
        /// The field's JSON path.
        field: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A partition's depth image could not be read (missing, not a regular file, too large).
    ImageRead {
        /// The set-up file.
        path: PathBuf,
        /// The field naming the image (`frames[0].lights[0].partitions[0].depth_image`).
        field: String,
        /// The read error, naming the image.
        source: ReadError,
    },
    /// A partition's depth image is not a depth image of its map: undecodable, another size,
    /// another content.
    Image {
        /// The set-up file.
        path: PathBuf,
        /// The field naming the image.
        field: String,
        /// The image.
        image: PathBuf,
        /// What the reader found (boxed: it is the largest error here).
        source: Box<DepthImageError>,
    },
    /// A technique whose maps the format cannot hold (the logarithmic map and its face
    /// partitioning), refused by the writer.
    NotRepresentable {
        /// The technique.
        technique: Technique,
        /// Why, in words.
        reason: String,
    },
    /// Planning, rendering or measuring failed.
    Analysis(AnalysisError),
}

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(e) => write!(f, "{e}"),
            Self::NotUtf8 { path } => write!(f, "{}: is not UTF-8 text", path.display()),
            Self::Json {
                path,
                field,
                message,
            } => write!(f, "{}: {field}: {message}", path.display()),
            Self::Field {
                path,
                field,
                problem,
            } => write!(f, "{}: {field}: {problem}", path.display()),
            Self::ImageRead {
                path,
                field,
                source,
            } => write!(f, "{}: {field}: {source}", path.display()),
            Self::Image {
                path,
                field,
                image,
                source,
            } => write!(
                f,
                "{}: {field}: {}: {source}",
                path.display(),
                image.display()
            ),
            Self::NotRepresentable { technique, reason } => write!(
                f,
                "{} cannot be written as a set-up file: {reason}",
                technique.spec()
            ),
            Self::Analysis(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SetupError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Read(e) | Self::ImageRead { source: e, .. } => Some(e),
            Self::Image { source, .. } => Some(source.as_ref()),
            Self::Analysis(e) => Some(e),
            Self::NotUtf8 { .. }
            | Self::Json { .. }
            | Self::Field { .. }
            | Self::NotRepresentable { .. } => None,
        }
    }
}

impl From<AnalysisError> for SetupError {
    fn from(e: AnalysisError) -> Self {
        Self::Analysis(e)
    }
}

impl From<shadowlab_shadow::ShadowError> for SetupError {
    fn from(e: shadowlab_shadow::ShadowError) -> Self {
        Self::Analysis(AnalysisError::Shadow(e))
    }
}
