//! How the tool fails: a usage or input error (exit code 2) or anything else (exit code 1).

use std::fmt;
use std::process::ExitCode;

use shadowlab_analysis::setup_file::SetupError;
use shadowlab_params::ParamError;
use shadowlab_scene::ReadError;

/// A failure of a subcommand.
#[derive(Debug)]
pub(crate) enum CliError {
    /// Bad input: the message names the flag or file. Exit code 2.
    Input(String),
    /// An I/O or internal failure. Exit code 1.
    Failure(anyhow::Error),
}

impl CliError {
    /// The exit code for this failure.
    pub(crate) fn exit_code(&self) -> ExitCode {
        match self {
            Self::Input(_) => ExitCode::from(2),
            Self::Failure(_) => ExitCode::from(1),
        }
    }

    /// An error of reading an input file (a scene file, an OBJ file), whose message names the
    /// file and the field or line: an input error (exit code 2), unless somewhere in its
    /// `source()` chain the operating system failed to read a file that is there (exit code 1).
    pub(crate) fn from_input_file(error: &(dyn std::error::Error + 'static)) -> Self {
        let mut cause = Some(error);
        while let Some(current) = cause {
            if current
                .downcast_ref::<ReadError>()
                .is_some_and(|read| !read.is_bad_input())
            {
                return Self::Failure(anyhow::anyhow!("{error}"));
            }
            cause = current.source();
        }
        Self::Input(error.to_string())
    }

    /// An input error from the params crate, naming the command-line flag that carried the bad
    /// value: the crate's parameter names are the flags' names.
    pub(crate) fn from_param(error: &ParamError) -> Self {
        Self::Input(format!(
            "invalid --{}: {error}",
            error.parameter().replace('_', "-")
        ))
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Input(message) => f.write_str(message),
            Self::Failure(error) => write!(f, "{error:#}"),
        }
    }
}

impl From<SetupError> for CliError {
    /// A set-up file's error: an input error naming the file and the field (exit 2), unless the
    /// operating system failed to read a file that is there (exit 1), as for scene files.
    fn from(error: SetupError) -> Self {
        Self::from_input_file(&error)
    }
}

impl From<anyhow::Error> for CliError {
    fn from(error: anyhow::Error) -> Self {
        Self::Failure(error)
    }
}
