//! What can go wrong in a sweep.

use std::fmt;

/// A sweep's errors. [`SweepError::Spec`], [`SweepError::Scene`] and [`SweepError::Shard`] are
/// the user's input; [`SweepError::Analysis`] a failure of the measurement itself.
#[derive(Debug)]
pub enum SweepError {
    /// The spec is malformed or a value is out of range; the message names the field.
    Spec(String),
    /// A scene of the spec cannot be loaded or posed; the message names it.
    Scene(String),
    /// A shard (`I/N`) is malformed, or results do not belong to the sweep.
    Shard(String),
    /// Measuring a cell failed (not a technique undefined for the frame: that is a result).
    Analysis(String),
    /// A table or figure could not be written.
    Output(String),
}

impl fmt::Display for SweepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Spec(m) => write!(f, "sweep spec: {m}"),
            Self::Scene(m) | Self::Shard(m) | Self::Analysis(m) | Self::Output(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for SweepError {}
