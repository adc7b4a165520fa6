//! Writing outputs: each file is written to a temporary file in its destination directory and
//! renamed into place, so a reader never sees half a file and a failure leaves the old one.

use std::io::Write;
use std::path::Path;

use anyhow::Context;

use crate::error::CliError;

/// Creates `dir` (and its parents) if needed; an existing non-directory is an input error naming
/// `flag`.
pub(crate) fn ensure_directory(dir: &Path, flag: &str) -> Result<(), CliError> {
    if dir.exists() && !dir.is_dir() {
        return Err(CliError::Input(format!(
            "invalid {flag}: {} exists and is not a directory",
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create directory {}", dir.display()))?;
    Ok(())
}

/// Writes `bytes` to `path` atomically (temporary file + rename in the same directory).
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or_else(|| Path::new("."));
    let mut builder = tempfile::Builder::new();
    builder.prefix(".shadowlab-");
    // Outputs are readable by everyone, as with `std::fs::write` under the usual umask; a
    // temporary file would otherwise keep its private 0600 mode through the rename.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut file = builder
        .tempfile_in(dir)
        .with_context(|| format!("cannot create a temporary file in {}", dir.display()))?;
    file.write_all(bytes)
        .and_then(|()| file.as_file().sync_all())
        .with_context(|| format!("cannot write {}", path.display()))?;
    file.persist(path)
        .with_context(|| format!("cannot move the finished file to {}", path.display()))?;
    Ok(())
}

/// Writes a line to standard output; a closed pipe (as with `| head`) is not an error.
pub(crate) fn print_line(line: &str) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{line}") {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(CliError::Failure(
            anyhow::Error::new(e).context("cannot write to standard output"),
        )),
        _ => Ok(()),
    }
}
