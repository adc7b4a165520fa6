//! Running the binary and reading what it did.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `shadowlab` with `args` in `dir` (the current directory if `None`).
pub(crate) fn shadowlab(args: &[&str], dir: Option<&Path>) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_shadowlab"));
    command.args(args);
    if let Some(dir) = dir {
        command.current_dir(dir);
    }
    command.output().expect("the shadowlab binary runs")
}

/// Standard output as text.
pub(crate) fn stdout(output: &Output) -> String {
    String::from_utf8(output.stdout.clone()).expect("UTF-8 output")
}

/// Standard error as text.
pub(crate) fn stderr(output: &Output) -> String {
    String::from_utf8(output.stderr.clone()).expect("UTF-8 output")
}

/// Runs `shadowlab` with `args` and asserts that it refuses them as an input error: exit code 2
/// and a message on standard error that contains `expected`.
pub(crate) fn assert_refused<S: AsRef<str>>(args: &[S], expected: &str) {
    let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
    let output = shadowlab(&args, None);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{args:?}: {message}");
    assert!(message.contains(expected), "{args:?}: {message}");
}
