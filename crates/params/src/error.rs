//! The one error type of the crate: an input outside the domain of a formula.

use std::fmt;

/// An input that lies outside the domain of a formula.
///
/// Every variant names the offending parameter as the functions of this crate spell it (`near`,
/// `far`, `fov`, `gamma`, `z`, `n`, …), so a caller such as the command-line tool can point the user at
/// the flag or field that carries it. No function of this crate returns NaN for a bad input; it
/// returns one of these instead.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ParamError {
    /// The value is NaN or infinite where a finite number is required.
    NotFinite {
        /// The parameter's name.
        name: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// The value is finite but outside the parameter's domain.
    OutOfDomain {
        /// The parameter's name.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// The domain, in words, e.g. "greater than near (1)".
        requirement: String,
    },
    /// The depth range is too thin to be split into that many strictly increasing partitions in f64.
    TooManyPartitions {
        /// The number of partitions that was asked for.
        count: usize,
        /// The ratio far/near of the range.
        ratio: f64,
    },
}

impl ParamError {
    /// The name of the parameter the error is about (`"partitions"` for [`Self::TooManyPartitions`]).
    #[must_use]
    pub fn parameter(&self) -> &'static str {
        match self {
            Self::NotFinite { name, .. } | Self::OutOfDomain { name, .. } => name,
            Self::TooManyPartitions { .. } => "partitions",
        }
    }

    /// `Ok(value)` if `value` is finite, else [`Self::NotFinite`] naming `name`.
    pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, Self> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(Self::NotFinite { name, value })
        }
    }

    /// `Ok(value)` if `ok`, else [`Self::OutOfDomain`] with the given requirement.
    pub(crate) fn require(
        name: &'static str,
        value: f64,
        ok: bool,
        requirement: impl FnOnce() -> String,
    ) -> Result<f64, Self> {
        if value.is_nan() {
            Err(Self::NotFinite { name, value })
        } else if ok {
            Ok(value)
        } else {
            Err(Self::OutOfDomain {
                name,
                value,
                requirement: requirement(),
            })
        }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { name, value } => {
                write!(f, "{name} must be a finite number, got {value}")
            }
            Self::OutOfDomain {
                name,
                value,
                requirement,
            } => write!(f, "{name} must be {requirement}, got {value}"),
            Self::TooManyPartitions { count, ratio } => write!(
                f,
                "a depth range with far/near = {ratio} cannot be split into {count} strictly \
                 increasing partitions in double precision"
            ),
        }
    }
}

impl std::error::Error for ParamError {}
