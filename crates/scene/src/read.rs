//! Reading input files with a bound: only regular files, and never more than a stated number of
//! bytes, so that a device (`/dev/zero`), a FIFO or a runaway file fails at once with a message
//! instead of filling memory or blocking.

use std::fmt;
use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::{Path, PathBuf};

/// The largest OBJ file read: 1 GiB, about 40 times the Stanford dragon's 871 414 triangles as
/// text (`data/meshes/fetch-dragon.sh`; its OBJ is some 60 MB).
pub const MAX_OBJ_BYTES: u64 = 1 << 30;

/// The largest scene file read: 4 MiB. Scene files describe meshes, they do not hold them (the
/// built-in ones are under 4 KiB); the bound only stops a wrong path early.
pub const MAX_SCENE_FILE_BYTES: u64 = 4 << 20;

/// Why an input file could not be read.
#[non_exhaustive]
#[derive(Debug)]
pub enum ReadError {
    /// The operating system could not open or read the file (missing, unreadable).
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
    /// The path names a directory, device, FIFO or socket: only regular files are read.
    NotRegularFile {
        /// The path.
        path: PathBuf,
        /// What it is, e.g. `"a character device"`.
        kind: &'static str,
    },
    /// The file is larger than the bound for its kind.
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What kind of file, e.g. `"an OBJ file"`.
        what: &'static str,
        /// The bound in bytes ([`MAX_OBJ_BYTES`], [`MAX_SCENE_FILE_BYTES`]).
        limit: u64,
        /// The bound's name, e.g. `"MAX_OBJ_BYTES"`.
        limit_name: &'static str,
    },
}

impl ReadError {
    /// The file.
    #[must_use]
    pub fn path(&self) -> &Path {
        match self {
            Self::Io { path, .. }
            | Self::NotRegularFile { path, .. }
            | Self::TooLarge { path, .. } => path,
        }
    }

    /// Whether the input itself is wrong (a missing file, a special file, a file too large): a
    /// usage error, as opposed to the operating system failing to read a file that is there.
    #[must_use]
    pub fn is_bad_input(&self) -> bool {
        match self {
            Self::Io { source, .. } => source.kind() == io::ErrorKind::NotFound,
            Self::NotRegularFile { .. } | Self::TooLarge { .. } => true,
        }
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::NotRegularFile { path, kind } => write!(
                f,
                "{}: is {kind}, not a regular file; only regular files are read as input",
                path.display()
            ),
            Self::TooLarge {
                path,
                what,
                limit,
                limit_name,
            } => write!(
                f,
                "{}: larger than {} ({limit_name}), the most read of {what}",
                path.display(),
                bytes(*limit)
            ),
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            Self::NotRegularFile { .. } | Self::TooLarge { .. } => None,
        }
    }
}

/// A byte count in the largest binary unit that divides it: `1 GiB`, `4 MiB`, `100 bytes`.
fn bytes(count: u64) -> String {
    const UNITS: [(u64, &str); 3] = [(1 << 30, "GiB"), (1 << 20, "MiB"), (1 << 10, "KiB")];
    UNITS
        .iter()
        .find(|(unit, _)| count >= *unit && count.is_multiple_of(*unit))
        .map_or_else(
            || format!("{count} bytes"),
            |(unit, name)| format!("{} {name}", count / unit),
        )
}

/// The contents of the regular file `path`, at most `limit` bytes; `what` and `limit_name` name
/// the kind of file and the bound in the error.
///
/// The path is checked with `stat` before it is opened (opening a FIFO would block until a writer
/// came), and the opened file again (it may have been replaced); at most `limit + 1` bytes are
/// read, so a file that grows while it is read is refused too. Every input file of shadowlab
/// (OBJ, scene, glTF and set-up files, depth images) is read with it.
///
/// # Errors
/// [`ReadError::Io`], [`ReadError::NotRegularFile`], [`ReadError::TooLarge`].
pub fn read_bounded(
    path: &Path,
    limit: u64,
    what: &'static str,
    limit_name: &'static str,
) -> Result<Vec<u8>, ReadError> {
    let io_error = |source| ReadError::Io {
        path: path.to_owned(),
        source,
    };
    let too_large = || ReadError::TooLarge {
        path: path.to_owned(),
        what,
        limit,
        limit_name,
    };
    regular(path, &std::fs::metadata(path).map_err(io_error)?)?;
    let file = File::open(path).map_err(io_error)?;
    let metadata = file.metadata().map_err(io_error)?;
    regular(path, &metadata)?;
    if metadata.len() > limit {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io_error)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// `Ok` if `metadata` is a regular file's, else [`ReadError::NotRegularFile`] naming its kind.
fn regular(path: &Path, metadata: &Metadata) -> Result<(), ReadError> {
    let kind = metadata.file_type();
    if kind.is_file() {
        return Ok(());
    }
    Err(ReadError::NotRegularFile {
        path: path.to_owned(),
        kind: kind_name(&kind),
    })
}

/// What a file that is not regular is, in words.
fn kind_name(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_fifo() {
            return "a FIFO";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
        read_bounded(path, limit, "a test file", "TEST_LIMIT")
    }

    #[test]
    fn a_file_at_the_limit_is_read_and_one_byte_more_is_refused() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let path = dir.path().join("file.txt");
        std::fs::write(&path, b"0123456789").expect("write");
        assert_eq!(read(&path, 10).expect("at the limit"), b"0123456789");
        let error = read(&path, 9).expect_err("over the limit");
        assert!(
            matches!(error, ReadError::TooLarge { limit: 9, .. }),
            "{error:?}"
        );
        let message = error.to_string();
        assert!(message.contains("file.txt") && message.contains("9 bytes (TEST_LIMIT)"));
        assert!(error.is_bad_input());
    }

    #[test]
    fn devices_and_directories_are_refused_by_kind() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let error = read(dir.path(), MAX_SCENE_FILE_BYTES).expect_err("a directory");
        assert!(
            error
                .to_string()
                .contains("is a directory, not a regular file")
        );
        #[cfg(unix)]
        {
            let error = read(Path::new("/dev/zero"), MAX_OBJ_BYTES).expect_err("a device");
            assert!(
                error
                    .to_string()
                    .contains("/dev/zero: is a character device"),
                "{error}"
            );
            assert!(error.is_bad_input());
        }
    }

    #[test]
    fn a_missing_file_is_bad_input_with_the_os_error_as_source() {
        let error = read(Path::new("/nonexistent/file.obj"), 10).expect_err("missing");
        assert!(error.is_bad_input());
        assert!(std::error::Error::source(&error).is_some());
        assert_eq!(error.path(), Path::new("/nonexistent/file.obj"));
    }

    #[test]
    fn sizes_are_named_in_binary_units() {
        assert_eq!(bytes(MAX_OBJ_BYTES), "1 GiB");
        assert_eq!(bytes(MAX_SCENE_FILE_BYTES), "4 MiB");
        assert_eq!(bytes(3 << 10), "3 KiB");
        assert_eq!(bytes(1536), "1536 bytes");
    }
}
