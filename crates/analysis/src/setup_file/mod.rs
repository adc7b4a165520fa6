//! Set-up files: a shadow set-up as an engine would dump it — per frame, per light, per
//! partition, the light's view and projection matrices, the eye depths the partition serves, the
//! map's size, depth format, bias and filter, and optionally the map's depths as an image — so that
//! an engine's own shadows can be judged against the exact truth ([`crate::evaluate`]).
//! `docs/setup-format.md` is the format's reference, with a worked example.
//!
//! * [`SetupFile`] and its parts are the JSON as written: plain data in the file's own
//!   conventions (row- or column-major numbers, NDC depth `[−1, 1]`, `[0, 1]` or reversed, NDC y
//!   up or down, a right- or left-handed world), versioned (`"format": "shadowlab-setup",
//!   "version": 1`), every object closed to unknown fields.
//! * [`load_setup`] / [`parse_setup`] read it into a [`Setup`], converting every matrix once into
//!   the library's convention (column vectors, GL clip space, the scene's right-handed world);
//!   every error names the file and the JSON path of the field ([`SetupError`]).
//! * [`setup_for`] writes the set-up shadowlab plans for any technique it can represent, so every
//!   built-in technique exercises the format. The logarithmic map (and its face partitioning) is
//!   refused: it is not a matrix per partition.

mod error;
mod file;
mod read;
mod write;

pub use error::SetupError;
pub use file::{
    CameraEntry, Conventions, FORMAT, FrameEntry, Handedness, LightEntry, MatrixOrder,
    NdcDepthRange, NdcY, PartitionEntry, SetupFile, VERSION,
};
pub use read::{
    CAMERA_TOLERANCE, DEPTH_IMAGE_SLACK_BYTES, DepthImage, FrameCamera, ImageKind,
    MAX_SETUP_FILE_BYTES, MAX_SETUP_FRAMES, MAX_SETUP_PARTITIONS, Setup, SetupFrame,
    SetupPartition, load_setup, parse_setup,
};
pub(crate) use shadowlab_scene::read_bounded;
pub use write::setup_for;
